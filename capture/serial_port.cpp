// termios2 lives in <asm/termbits.h>, which clashes with <termios.h>: this file includes only
// the former.
#include "capture/serial_port.hpp"

#include <asm/termbits.h>
#include <fcntl.h>
#include <fmt/format.h>
#include <linux/serial.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

namespace dpscope {

std::unique_ptr<SerialPort> SerialPort::open(const SerialSettings& settings, std::string& error) {
    int fd = ::open(settings.device.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        error = fmt::format("{}: cannot open: {}", settings.device, std::strerror(errno));
        return nullptr;
    }
    std::unique_ptr<SerialPort> port(new SerialPort);
    port->fd_ = fd;
    port->device_ = settings.device;
    struct termios2 tio {};
    if (ioctl(fd, TCGETS2, &tio) != 0) {
        error = fmt::format("{}: not a serial port: {}", settings.device, std::strerror(errno));
        return nullptr;
    }
    // Raw mode.
    tio.c_iflag &= ~static_cast<tcflag_t>(IGNBRK | BRKINT | ISTRIP | INLCR | IGNCR | ICRNL | IXON |
                                          IXOFF | IXANY | IGNPAR | PARMRK | INPCK);
    if (!settings.for_writing) tio.c_iflag |= INPCK | PARMRK;  // mark parity errors
    tio.c_oflag &= ~static_cast<tcflag_t>(OPOST);
    tio.c_lflag &= ~static_cast<tcflag_t>(ECHO | ECHONL | ICANON | ISIG | IEXTEN);
    // 8E1 at an arbitrary rate.
    tio.c_cflag &= ~static_cast<tcflag_t>(CSIZE | PARODD | CBAUD | CSTOPB | CRTSCTS);
    tio.c_cflag |= CS8 | PARENB | CREAD | CLOCAL | BOTHER;
    tio.c_cflag &= ~static_cast<tcflag_t>(CIBAUD);
    tio.c_ispeed = tio.c_ospeed = settings.baud;
    tio.c_cc[VMIN] = 0;
    tio.c_cc[VTIME] = 0;
    if (ioctl(fd, TCSETS2, &tio) != 0) {
        error = fmt::format("{}: cannot set {} baud 8E1: {}", settings.device, settings.baud,
                            std::strerror(errno));
        return nullptr;
    }
    struct termios2 back {};
    if (ioctl(fd, TCGETS2, &back) != 0) {
        error = fmt::format("{}: cannot read the settings back: {}", settings.device,
                            std::strerror(errno));
        return nullptr;
    }
    port->baud_ = back.c_ospeed;
    long long difference = static_cast<long long>(back.c_ospeed) - settings.baud;
    if (std::llabs(difference) * 100 > settings.baud) {
        error = fmt::format("{}: the port did not take {} baud: it is set to {} baud",
                            settings.device, settings.baud, back.c_ospeed);
        return nullptr;
    }
    if ((back.c_cflag & CSIZE) != CS8) {
        error = fmt::format("{}: the port did not take 8 data bits", settings.device);
        return nullptr;
    }
    // Pseudo-terminals have no parity (the kernel clears PARENB): capture still works, but
    // parity errors cannot be seen. Say so rather than refuse.
    port->parity_checked_ = (back.c_cflag & PARENB) && !(back.c_cflag & PARODD);
    port->parity_marked_ = (back.c_iflag & PARMRK) != 0;
    if (!port->parity_checked_)
        port->note_ = fmt::format(
            "{}: the port does not check even parity (a pseudo-terminal?); "
            "parity errors will not be seen",
            settings.device);
    if (settings.low_latency) {
        struct serial_struct serial {};
        if (ioctl(fd, TIOCGSERIAL, &serial) == 0) {
            serial.flags |= ASYNC_LOW_LATENCY;
            port->low_latency_ = ioctl(fd, TIOCSSERIAL, &serial) == 0;
        }
    }
    ioctl(fd, TCFLSH, TCIFLUSH);  // what arrived before the settings held is not trusted
    return port;
}

SerialPort::~SerialPort() {
    if (fd_ >= 0) ::close(fd_);
}

}  // namespace dpscope
