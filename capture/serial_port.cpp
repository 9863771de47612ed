// termios2 lives in <asm/termbits.h>, which clashes with <termios.h>: this file includes only
// the former.
#include "capture/serial_port.hpp"

#include <asm/termbits.h>
#include <fcntl.h>
#include <fmt/format.h>
#include <linux/serial.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <ctime>

namespace dpscope {

std::string_view serial_parity_name(SerialParity parity) {
    switch (parity) {
        case SerialParity::Even: return "even";
        case SerialParity::Odd: return "odd";
        case SerialParity::None: return "none";
    }
    return "even";
}

std::optional<SerialParity> serial_parity_from_name(std::string_view name) {
    for (SerialParity parity : {SerialParity::Even, SerialParity::Odd, SerialParity::None})
        if (serial_parity_name(parity) == name) return parity;
    return std::nullopt;
}

std::string serial_frame_name(SerialParity parity, unsigned stop_bits) {
    const char letter = parity == SerialParity::Even  ? 'E'
                        : parity == SerialParity::Odd ? 'O'
                                                      : 'N';
    return fmt::format("8{}{}", letter, stop_bits == 2 ? 2 : 1);
}

std::string SerialPort::frame() const {
    return serial_frame_name(settings_.parity, settings_.stop_bits);
}

namespace {

// What a configured port is to be put back to, kept where a signal handler can reach it without
// allocating or locking.
struct Slot {
    std::atomic<bool> used{false};
    std::atomic<int> fd{-1};  // set once `original` holds the settings found; -1: nothing to do
    struct termios2 original {};
    struct serial_struct original_serial {};
    std::atomic<bool> serial_changed{false};
    std::atomic<bool> lock_held{false};
    char lock_path[PATH_MAX] = {};
};

constexpr int kSlots = 8;
Slot g_slots[kSlots];

int take_slot() {
    for (int i = 0; i < kSlots; ++i) {
        bool expected = false;
        if (g_slots[i].used.compare_exchange_strong(expected, true)) return i;
    }
    return -1;
}

// Async-signal-safe: system calls only.
void restore_settings(Slot& slot, bool drain) noexcept {
    int fd = slot.fd.exchange(-1);
    if (fd < 0) return;
    if (drain) ioctl(fd, TCSBRK, 1);  // tcdrain: what was written goes out at the rate set
    ioctl(fd, TCSETS2, &slot.original);
    if (slot.serial_changed.exchange(false)) ioctl(fd, TIOCSSERIAL, &slot.original_serial);
    ioctl(fd, TIOCNXCL);
}

void release_lock_file(Slot& slot) noexcept {
    if (slot.lock_held.exchange(false)) unlink(slot.lock_path);
}

bool process_alive(pid_t pid) { return kill(pid, 0) == 0 || errno == EPERM; }

// What kind of file `mode` is, for a message: "a FIFO", "a folder".
std::string_view file_kind(mode_t mode) {
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISLNK(mode)) return "a symbolic link";
    if (S_ISDIR(mode)) return "a folder";
    if (S_ISSOCK(mode)) return "a socket";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    return "not a plain file";
}

// The process holding the UUCP lock file at `path`: its PID; 0 when the lock is stale (the
// process is gone, or the file is unreadable and older than a few seconds) or gone; -1 when the
// file is fresh but holds no PID yet (another program is writing it). The lock folder is writable
// by everyone: anything but a regular file there (a FIFO, whose opening would wait for a writer
// forever; a symbolic link; a folder) is no lock file and is refused, naming what it is. It is
// opened without following a link and without waiting, and checked again once open.
Result<pid_t> lock_owner(const std::string& path) {
    struct stat info {};
    if (::lstat(path.c_str(), &info) != 0) return 0;
    if (!S_ISREG(info.st_mode))
        return Error{fmt::format("is not a regular file ({})", file_kind(info.st_mode))};
    int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOFOLLOW | O_NOCTTY | O_CLOEXEC);
    if (fd < 0 && errno == ELOOP) return Error{"is not a regular file (a symbolic link)"};
    if (fd < 0) return 0;
    if (fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) {
        ::close(fd);
        return Error{fmt::format("is not a regular file ({})", file_kind(info.st_mode))};
    }
    char text[64] = {};
    ssize_t n = ::read(fd, text, sizeof text - 1);
    bool fresh = std::time(nullptr) - info.st_mtime < 5;
    ::close(fd);
    pid_t pid = 0;
    if (n == static_cast<ssize_t>(sizeof(int))) {  // the old binary format
        int binary = 0;
        std::memcpy(&binary, text, sizeof binary);
        pid = binary;
    } else if (n > 0) {
        // HDB format: the PID in ASCII, right-aligned in 10 characters, and a newline.
        char* end = nullptr;
        long value = std::strtol(text, &end, 10);
        if (end != text && value > 0 && value <= INT_MAX) pid = static_cast<pid_t>(value);
    }
    if (pid <= 0) return fresh ? -1 : 0;
    return process_alive(pid) ? pid : 0;
}

std::string process_name(pid_t pid) {
    int fd = ::open(fmt::format("/proc/{}/comm", pid).c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return {};
    char text[64] = {};
    ssize_t n = ::read(fd, text, sizeof text - 1);
    ::close(fd);
    std::string name(text, n > 0 ? static_cast<std::size_t>(n) : 0);
    while (!name.empty() && (name.back() == '\n' || name.back() == '\0'))
        name.pop_back();
    return name;
}

}  // namespace

Result<std::unique_ptr<SerialPort>> SerialPort::claim(const SerialSettings& settings) {
    char resolved[PATH_MAX] = {};
    struct stat info {};
    if (realpath(settings.device.c_str(), resolved) == nullptr || stat(resolved, &info) != 0) {
        return Error{fmt::format("{}: cannot open: {}", settings.device, std::strerror(errno))};
    }
    if (!S_ISCHR(info.st_mode)) {
        return Error{fmt::format("{}: not a serial port: not a character device", settings.device)};
    }
    std::unique_ptr<SerialPort> port(new SerialPort);
    port->settings_ = settings;
    port->device_ = settings.device;
    port->slot_ = take_slot();
    if (port->slot_ < 0) {
        return Error{fmt::format("{}: too many serial ports open", settings.device)};
    }
    const char* base = std::strrchr(resolved, '/');
    if (Result<void> locked = port->take_lock_file(base ? base + 1 : resolved); !locked)
        return Error{locked.error()};
    return port;
}

// The UUCP lock file (HDB format) that serial programs (minicom, picocom, cu, ModemManager)
// look for: `lock_dir`/LCK..NAME holding the owner's PID. A stale one (its process is gone) is
// removed. A lock directory that is missing or not writable is passed over.
Result<void> SerialPort::take_lock_file(const std::string& name) {
    const std::string& dir = settings_.lock_dir;
    if (dir.empty()) return {};
    std::string path = fmt::format("{}/LCK..{}", dir, name);
    Slot& slot = g_slots[slot_];
    if (path.size() >= sizeof slot.lock_path) return {};
    // Written whole under a temporary name, then linked into place: no one sees half a lock.
    // The name is made afresh (mkostemp: O_CREAT | O_EXCL), so nothing planted under a name
    // known in advance (LTMP.PID) is opened, followed or written through.
    std::string temp = fmt::format("{}/LTMP.XXXXXX", dir);
    int fd = ::mkostemp(temp.data(), O_CLOEXEC);
    if (fd < 0) return {};
    std::string content = fmt::format("{:>10}\n", getpid());
    bool written =
        ::fchmod(fd, 0644) == 0 &&  // others read the PID in it
        ::write(fd, content.data(), content.size()) == static_cast<ssize_t>(content.size());
    ::close(fd);
    for (int attempt = 0; written && attempt < 3; ++attempt) {
        if (link(temp.c_str(), path.c_str()) == 0) {
            unlink(temp.c_str());
            std::memcpy(slot.lock_path, path.c_str(), path.size() + 1);
            slot.lock_held = true;
            lock_file_ = path;
            return {};
        }
        if (errno != EEXIST) break;  // a file system without hard links: no lock file
        Result<pid_t> checked = lock_owner(path);
        if (!checked) {
            unlink(temp.c_str());
            return Error{fmt::format(
                "{}: lock file {} {}: not a lock file, and not removed; remove it if no program "
                "uses it",
                device_, path, checked.error())};
        }
        const pid_t owner = *checked;
        if (owner != 0) {
            unlink(temp.c_str());
            if (owner < 0)
                return Error{fmt::format("{} is in use: another program is taking the lock file {}",
                                         device_, path)};
            std::string owner_name = process_name(owner);
            return Error{fmt::format("{} is in use by process {}{}: lock file {}", device_, owner,
                                     owner_name.empty() ? "" : " (" + owner_name + ")", path)};
        }
        unlink(path.c_str());  // stale: its process is gone
    }
    unlink(temp.c_str());
    return {};
}

Result<void> SerialPort::configure() {
    const std::string& device = settings_.device;
    if (fd_ >= 0) {
        return Error{fmt::format("{}: already open", device)};
    }
    int fd = ::open(device.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        return Error{
            fmt::format("{}: cannot open: {}{}", device, std::strerror(errno),
                        errno == EBUSY ? " (another program has it open exclusively)" : "")};
    }
    fd_ = fd;
    // Programs that take no lock file (or a lock directory we cannot write) still meet here.
    if (flock(fd, LOCK_EX | LOCK_NB) != 0 && errno == EWOULDBLOCK) {
        return Error{
            fmt::format("{} is in use: another process holds a lock on the device", device)};
    }
    Slot& slot = g_slots[slot_];
    struct termios2 tio {};
    if (ioctl(fd, TCGETS2, &tio) != 0) {
        return Error{fmt::format("{}: not a serial port: {}", device, std::strerror(errno))};
    }
    slot.original = tio;
    slot.fd = fd;         // from here on the destructor (or a signal) puts the settings back
    ioctl(fd, TIOCEXCL);  // others (but root) cannot open it while we have it
    // Raw mode.
    tio.c_iflag &= ~static_cast<tcflag_t>(IGNBRK | BRKINT | ISTRIP | INLCR | IGNCR | ICRNL | IXON |
                                          IXOFF | IXANY | IGNPAR | PARMRK | INPCK);
    const bool parity = settings_.parity != SerialParity::None;
    if (!settings_.for_writing && parity) tio.c_iflag |= INPCK | PARMRK;  // mark parity errors
    tio.c_oflag &= ~static_cast<tcflag_t>(OPOST);
    tio.c_lflag &= ~static_cast<tcflag_t>(ECHO | ECHONL | ICANON | ISIG | IEXTEN);
    // 8E1 (or the parity and stop bits asked) at an arbitrary rate.
    tio.c_cflag &= ~static_cast<tcflag_t>(CSIZE | PARENB | PARODD | CBAUD | CSTOPB | CRTSCTS);
    tio.c_cflag |= CS8 | CREAD | CLOCAL | BOTHER;
    if (parity) tio.c_cflag |= PARENB;
    if (settings_.parity == SerialParity::Odd) tio.c_cflag |= PARODD;
    if (settings_.stop_bits == 2) tio.c_cflag |= CSTOPB;
    tio.c_cflag &= ~static_cast<tcflag_t>(CIBAUD);
    tio.c_ispeed = tio.c_ospeed = settings_.baud;
    tio.c_cc[VMIN] = 0;
    tio.c_cc[VTIME] = 0;
    if (ioctl(fd, TCSETS2, &tio) != 0) {
        return Error{fmt::format("{}: cannot set {} baud {}: {}", device, settings_.baud, frame(),
                                 std::strerror(errno))};
    }
    struct termios2 back {};
    if (ioctl(fd, TCGETS2, &back) != 0) {
        return Error{
            fmt::format("{}: cannot read the settings back: {}", device, std::strerror(errno))};
    }
    baud_ = back.c_ospeed;
    long long difference = static_cast<long long>(back.c_ospeed) - settings_.baud;
    if (std::llabs(difference) * 100 > settings_.baud) {
        return Error{fmt::format("{}: the port did not take {} baud: it is set to {} baud", device,
                                 settings_.baud, back.c_ospeed)};
    }
    if ((back.c_cflag & CSIZE) != CS8) {
        return Error{fmt::format("{}: the port did not take 8 data bits", device)};
    }
    // Pseudo-terminals have no parity (the kernel clears PARENB): capture still works, but
    // parity errors cannot be seen. Say so rather than refuse.
    const bool odd = settings_.parity == SerialParity::Odd;
    parity_checked_ = parity && (back.c_cflag & PARENB) && ((back.c_cflag & PARODD) != 0) == odd;
    parity_marked_ = parity && (back.c_iflag & PARMRK) != 0;
    if (parity && !parity_checked_)
        note_ = fmt::format(
            "{}: the port does not check {} parity (a pseudo-terminal?); "
            "parity errors will not be seen",
            device, serial_parity_name(settings_.parity));
    if (settings_.low_latency) {
        struct serial_struct serial {};
        if (ioctl(fd, TIOCGSERIAL, &serial) == 0 && !(serial.flags & ASYNC_LOW_LATENCY)) {
            slot.original_serial = serial;
            serial.flags |= ASYNC_LOW_LATENCY;
            low_latency_ = ioctl(fd, TIOCSSERIAL, &serial) == 0;
            slot.serial_changed = low_latency_;
        } else {
            low_latency_ = (serial.flags & ASYNC_LOW_LATENCY) != 0;
        }
    }
    ioctl(fd, TCFLSH, TCIFLUSH);  // what arrived before the settings held is not trusted
    return {};
}

Result<std::unique_ptr<SerialPort>> SerialPort::open(const SerialSettings& settings) {
    Result<std::unique_ptr<SerialPort>> port = claim(settings);
    if (!port) return port;
    if (Result<void> configured = (*port)->configure(); !configured)
        return Error{configured.error()};
    return port;
}

SerialPort::~SerialPort() {
    if (slot_ >= 0) restore_settings(g_slots[slot_], settings_.for_writing);
    if (fd_ >= 0) ::close(fd_);  // also releases flock()
    if (slot_ >= 0) {
        release_lock_file(g_slots[slot_]);
        g_slots[slot_].used = false;
    }
}

void SerialPort::restore_all_after_signal() noexcept {
    for (Slot& slot : g_slots) {
        restore_settings(slot, false);
        release_lock_file(slot);
    }
}

}  // namespace dpscope
