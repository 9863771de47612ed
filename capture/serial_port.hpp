// A serial port (RS-485 adapter) set up for PROFIBUS: raw mode, 8 data bits, even parity, one
// stop bit, any baud rate the driver accepts (termios2 with BOTHER), parity errors marked in the
// data (PARMRK: an erroneous byte X arrives as FF 00 X, a real FF as FF FF), and the driver's
// low-latency flag where it offers one.
//
// The port is the user's: it is taken exclusively while dpscope uses it (a UUCP lock file
// LCK..NAME in the lock directory, flock() on the device, TIOCEXCL), and the settings found when
// it was opened (termios2 and the serial flags) are put back when it is closed, also from a
// signal handler that ends the process (restore_all_after_signal).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "core/result.hpp"

namespace dpscope {

// The character frame's parity bit (8 data bits always): PROFIBUS uses even, the FC protocol
// even by default (8E1) and whatever the drive's parameter 8-33 sets (odd, or none with one or
// two stop bits).
enum class SerialParity { Even, Odd, None };

// "even", "odd", "none", and back.
std::string_view serial_parity_name(SerialParity parity);
std::optional<SerialParity> serial_parity_from_name(std::string_view name);

// The character frame as serial programs write it: "8E1", "8O1", "8N2" (8 data bits always).
std::string serial_frame_name(SerialParity parity, unsigned stop_bits);

struct SerialSettings {
    std::string device;
    std::uint32_t baud = 1'500'000;
    bool low_latency = true;
    bool for_writing = false;  // the simulator plays onto the port: no parity marking needed
    // Where the UUCP lock file goes; "" takes none (flock and TIOCEXCL still apply). A directory
    // that does not exist or cannot be written is passed over, as other serial programs do.
    std::string lock_dir = "/run/lock";
    SerialParity parity = SerialParity::Even;
    unsigned stop_bits = 1;  // 1 or 2
};

class SerialPort {
  public:
    // Claims the device without opening it: resolves links, checks that it is a character
    // device and takes the lock file. The error names the device and the problem (cannot
    // open, not a serial port, in use by process N).
    static Result<std::unique_ptr<SerialPort>> claim(const SerialSettings& settings);
    // Opens and configures a claimed port, then reads the settings back. The error names the
    // device and the problem: cannot open, in use by another process, not a tty, or
    // a baud rate the port did not take (the message names the rate it got). A rate within 1 %
    // of the request is taken: UARTs divide their clock and tolerate that much.
    Result<void> configure();
    // claim() and configure() in one.
    static Result<std::unique_ptr<SerialPort>> open(const SerialSettings& settings);
    // Restores the settings found, releases the port and the lock file.
    ~SerialPort();
    SerialPort(const SerialPort&) = delete;
    SerialPort& operator=(const SerialPort&) = delete;

    // For a handler of a signal that ends the process: puts every port this process has
    // configured back as it was found and removes the lock files. Async-signal-safe.
    static void restore_all_after_signal() noexcept;

    int fd() const noexcept { return fd_; }
    const std::string& device() const noexcept { return device_; }
    const std::string& lock_file() const noexcept { return lock_file_; }  // "" when none taken
    std::uint32_t baud() const noexcept { return baud_; }       // as read back from the driver
    bool low_latency() const noexcept { return low_latency_; }  // the driver took the flag
    bool parity_checked() const noexcept { return parity_checked_; }  // the parity asked is on
    // The character frame asked for: "8E1", "8O1", "8N2".
    std::string frame() const;
    bool parity_marked() const noexcept { return parity_marked_; }  // PARMRK escaping is on
    // Something a user should know about the settings ("" when all is as asked).
    const std::string& note() const noexcept { return note_; }

  private:
    SerialPort() = default;
    Result<void> take_lock_file(const std::string& name);

    SerialSettings settings_;
    int slot_ = -1;  // where the settings to restore are kept (see serial_port.cpp)
    int fd_ = -1;
    std::string device_;
    std::string lock_file_;
    std::uint32_t baud_ = 0;
    bool low_latency_ = false;
    bool parity_checked_ = false;
    bool parity_marked_ = false;
    std::string note_;
};

// Bits of one character on the wire: start bit, 8 data bits, the parity bit if any, stop bits.
inline unsigned character_bits(SerialParity parity, unsigned stop_bits) {
    return 1 + 8 + (parity == SerialParity::None ? 0 : 1) + stop_bits;
}

// Nanoseconds one character takes on the wire: start bit, 8 data bits, parity, stop bit (11
// bits, as PROFIBUS and the FC protocol's 8E1 have them), or `bits`.
inline std::int64_t character_ns(std::uint32_t baud, unsigned bits = 11) {
    return baud == 0 ? 0 : static_cast<std::int64_t>(bits * 1'000'000'000ULL / baud);
}

}  // namespace dpscope
