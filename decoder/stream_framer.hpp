// Splits a raw PROFIBUS byte stream (as recorded from a serial port) into telegrams. Input is fed
// in chunks of any size (feed), and finish() flushes what is left at the end. Bytes that do not
// form a telegram are skipped, and each run of skipped bytes is reported once: where it started,
// how many bytes, and which check failed first. Framing resumes at the next valid telegram.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "decoder/byte_reader.hpp"
#include "decoder/fdl.hpp"

namespace dpscope {

struct SkippedBytes {
    std::uint64_t offset = 0;  // stream offset of the first skipped byte
    std::uint64_t count = 0;
    ProblemKind reason = ProblemKind::BadStartDelimiter;  // the first check that failed
    std::uint16_t reason_offset = 0;  // byte of the candidate telegram where it failed
};

// "skipped 5 byte(s): no start delimiter"; the caller says where (offset, line).
std::string describe_skip(const SkippedBytes& skipped);

class StreamFramer {
  public:
    class Sink {
      public:
        virtual ~Sink() = default;
        // `telegram` is valid only during the call; `offset` is its stream offset.
        virtual void on_telegram(Bytes telegram, std::uint64_t offset) = 0;
        virtual void on_skipped(const SkippedBytes& skipped) = 0;
    };

    void feed(Bytes chunk, Sink& sink);
    // The line was idle: a telegram cannot continue across the gap, so whatever is pending is
    // decided now (a telegram if it is complete, skipped bytes otherwise).
    void mark_gap(Sink& sink);
    // End of input: pending bytes are decided as at a gap.
    void finish(Sink& sink);

    std::uint64_t bytes_fed() const noexcept { return bytes_fed_; }
    std::uint64_t bytes_skipped() const noexcept { return bytes_skipped_; }
    std::uint64_t telegrams() const noexcept { return telegrams_; }
    std::size_t pending() const noexcept { return buffer_.size() - start_; }

  private:
    void process(Sink& sink, bool input_ended);
    void skip(std::size_t count, ProblemKind reason, std::uint16_t reason_offset);
    void flush_skipped(Sink& sink);
    void compact();

    std::vector<std::uint8_t> buffer_;
    std::size_t start_ = 0;            // first unconsumed byte in buffer_
    std::uint64_t buffer_offset_ = 0;  // stream offset of buffer_[0]
    std::uint64_t bytes_fed_ = 0;
    std::uint64_t bytes_skipped_ = 0;
    std::uint64_t telegrams_ = 0;
    SkippedBytes run_{};  // the current run of skipped bytes (count 0: none)
};

}  // namespace dpscope
