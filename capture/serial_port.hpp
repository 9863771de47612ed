// A serial port (RS-485 adapter) set up for PROFIBUS: raw mode, 8 data bits, even parity, one
// stop bit, any baud rate the driver accepts (termios2 with BOTHER), parity errors marked in the
// data (PARMRK: an erroneous byte X arrives as FF 00 X, a real FF as FF FF), and the driver's
// low-latency flag where it offers one.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

namespace dpscope {

struct SerialSettings {
    std::string device;
    std::uint32_t baud = 1'500'000;
    bool low_latency = true;
    bool for_writing = false;  // the simulator plays onto the port: no parity marking needed
};

class SerialPort {
  public:
    // Opens and configures the port, then reads the settings back. Null with `error` naming the
    // device and the problem: cannot open, not a tty, or a baud rate the port did not take (the
    // message names the rate it got). A rate within 1 % of the request is taken: UARTs divide
    // their clock and tolerate that much.
    static std::unique_ptr<SerialPort> open(const SerialSettings& settings, std::string& error);
    ~SerialPort();
    SerialPort(const SerialPort&) = delete;
    SerialPort& operator=(const SerialPort&) = delete;

    int fd() const noexcept { return fd_; }
    const std::string& device() const noexcept { return device_; }
    std::uint32_t baud() const noexcept { return baud_; }       // as read back from the driver
    bool low_latency() const noexcept { return low_latency_; }  // the driver took the flag
    bool parity_checked() const noexcept { return parity_checked_; }  // even parity is on
    bool parity_marked() const noexcept { return parity_marked_; }    // PARMRK escaping is on
    // Something a user should know about the settings ("" when all is as asked).
    const std::string& note() const noexcept { return note_; }

  private:
    SerialPort() = default;
    int fd_ = -1;
    std::string device_;
    std::uint32_t baud_ = 0;
    bool low_latency_ = false;
    bool parity_checked_ = false;
    bool parity_marked_ = false;
    std::string note_;
};

// Nanoseconds one character takes on the wire: start bit, 8 data bits, parity, stop bit.
inline std::int64_t character_ns(std::uint32_t baud) {
    return baud == 0 ? 0 : static_cast<std::int64_t>(11'000'000'000ULL / baud);
}

}  // namespace dpscope
