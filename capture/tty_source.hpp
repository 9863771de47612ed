// Telegrams read live from a serial port (or any tty, such as one end of a pseudo-terminal),
// framed by the stream framer with the protocol's framing rules.
//
// Times: a read returns the bytes that arrived since the last one; the last of them arrived
// about when read() returned, each earlier byte one character time (11 bits at the configured
// baud) before it. A telegram gets the time of its first byte, but never earlier than the previous
// telegram's time plus the time the bytes between their starts (that telegram and any skipped
// bytes) took on the wire: telegrams get distinct times spaced at least by their length on the
// wire, within one read and across reads, whenever read() returns and whatever the clock does.
//
// Line idle time: telegram characters follow each other without a pause, so when no byte comes
// for `idle_gap_ns` while a telegram is incomplete, it is cut off (reported as skipped bytes) and
// framing starts afresh. USB adapters deliver data in bursts (docs/cli.md, `sniff`), so the gap
// must be longer than their latency timer.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "capture/framed_source.hpp"
#include "capture/serial_port.hpp"

namespace dpscope {

// Wall-clock time in nanoseconds since the epoch (CLOCK_REALTIME).
std::int64_t wall_clock_ns();

struct TtySourceOptions {
    std::uint32_t baud = 1'500'000;  // for character times
    // Bits of one character on the wire (8E1: 11), for the time a byte took to arrive.
    unsigned character_bits = 11;
    std::int64_t idle_gap_ns = 50'000'000;  // 0: do not use line idle time
    int poll_ms = 20;                       // how long poll() waits before reporting Idle
    bool parity_marked = true;              // the port marks parity errors (PARMRK)
    // When a read returned (tests give their own).
    std::int64_t (*clock)() = wall_clock_ns;
};

class TtySource final : public FramedSource {
  public:
    // `port` may be null when `fd` is an already configured descriptor the caller keeps open.
    // `rules` (the protocol's framing, e.g. fdl_framing_rules()) must outlive the source.
    TtySource(std::unique_ptr<SerialPort> port, int fd, std::string name, TtySourceOptions options,
              const FramingRules& rules);

    InputFormat format() const override { return InputFormat::Serial; }

    // End the capture: what the driver has buffered is still read, then pending bytes are decided
    // as at the end of input, and poll() reports End once every telegram is handed out.
    void request_stop() noexcept { stop_requested_ = true; }

    // Bytes received on the line: the PARMRK escapes the driver adds are not counted (FF FF is
    // one byte, FF 00 X one byte).
    std::uint64_t bytes_read() const noexcept { return stream_offset_; }
    std::uint64_t reads() const noexcept { return reads_; }
    std::uint64_t parity_errors() const noexcept { return parity_errors_; }
    std::uint64_t idle_gaps() const noexcept { return idle_gaps_; }

  protected:
    Fill fill() override;
    std::int64_t time_at(std::uint64_t offset) override;
    std::string where(std::uint64_t offset) const override;

  private:
    struct Chunk {
        std::uint64_t start;  // stream offset of its first byte
        std::uint64_t length;
        std::int64_t arrival_ns;
    };

    bool read_available(bool& hangup);
    void unescape_and_feed(const std::uint8_t* data, std::size_t size, std::int64_t arrival_ns);
    void drop_old_chunks();

    std::unique_ptr<SerialPort> port_;
    int fd_;
    TtySourceOptions options_;
    std::int64_t character_ns_;
    std::vector<std::uint8_t> raw_;
    std::vector<std::uint8_t> clean_;
    std::deque<Chunk> chunks_;
    std::uint64_t stream_offset_ = 0;      // bytes fed to the framer so far
    std::int64_t last_time_ns_ = kNoTime;  // the previous telegram's time
    std::uint64_t last_offset_ = 0;        // and stream offset
    std::int64_t last_data_ns_ = 0;
    bool gap_marked_ = true;
    bool stop_requested_ = false;
    enum class Escape { None, SawFF, SawFF00 } escape_ = Escape::None;
    std::uint64_t reads_ = 0;
    std::uint64_t parity_errors_ = 0;
    std::uint64_t idle_gaps_ = 0;
};

}  // namespace dpscope
