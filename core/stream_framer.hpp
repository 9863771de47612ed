// Splits a byte stream (as recorded from a serial port) into telegrams by a protocol's framing
// rules (core/framing_rules.hpp). Input is fed in chunks of any size (feed), and finish()
// flushes what is left at the end. Bytes that do not form a telegram are skipped, and each run of
// skipped bytes is reported once: where it started, how many bytes, and which check failed first
// (the rules' describe_skip() words it). Framing resumes at the next valid telegram.
//
// StreamFramer is what callers hold; the rules pick its engine once (make_framer_core): for
// rules that return FramerFor<TheirType>, the framing loop calls their judge() directly, so it
// can be inlined, and a chunk costs one virtual call, a candidate none.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core/byte_reader.hpp"
#include "core/framing_rules.hpp"

namespace dpscope {

class FramingSink {
  public:
    virtual ~FramingSink() = default;
    // `telegram` is valid only during the call; `offset` is its stream offset.
    virtual void on_telegram(Bytes telegram, std::uint64_t offset) = 0;
    virtual void on_skipped(const SkippedBytes& skipped) = 0;
};

// The framer's state, the same for every protocol: the bytes not decided yet, stream offsets,
// counters and the current run of skipped bytes. FramerFor<Rules> adds the framing loop.
class FramerCore {
  public:
    explicit FramerCore(const FramingRules& rules) noexcept : rules_(&rules) {}
    virtual ~FramerCore() = default;
    FramerCore(const FramerCore&) = delete;
    FramerCore& operator=(const FramerCore&) = delete;

    const FramingRules& rules() const noexcept { return *rules_; }

    void feed(Bytes chunk, FramingSink& sink) {
        bytes_fed_ += chunk.size();
        buffer_.insert(buffer_.end(), chunk.begin(), chunk.end());
        process(sink, false);
        compact();
    }
    void mark_gap(FramingSink& sink) {
        process(sink, true);
        flush_skipped(sink);
        compact();
    }

    std::uint64_t bytes_fed() const noexcept { return bytes_fed_; }
    std::uint64_t bytes_skipped() const noexcept { return bytes_skipped_; }
    std::uint64_t telegrams() const noexcept { return telegrams_; }
    std::size_t pending() const noexcept { return buffer_.size() - start_; }
    // The memory of the undecided bytes' buffer.
    std::size_t buffer_capacity() const noexcept { return buffer_.capacity(); }
    // The run of skipped bytes not reported yet (count 0: none): it goes on until a telegram or
    // a gap ends it.
    const SkippedBytes& skipping() const noexcept { return run_; }

  protected:
    // Decides what it can of the undecided bytes; `at_end`: nothing follows them.
    virtual void process(FramingSink& sink, bool at_end) = 0;

    // The undecided bytes (empty when all are decided).
    Bytes undecided() const noexcept {
        return Bytes(buffer_.data() + start_, buffer_.size() - start_);
    }
    void take_telegram(FramingSink& sink, std::size_t length) {
        flush_skipped(sink);
        sink.on_telegram(undecided().first(length), buffer_offset_ + start_);
        ++telegrams_;
        start_ += length;
    }
    void skip(std::size_t count, ProblemKind reason, std::uint16_t reason_offset) noexcept {
        if (run_.count == 0) {
            run_.offset = buffer_offset_ + start_;
            run_.reason = reason;
            run_.reason_offset = reason_offset;
        }
        run_.count += count;
        bytes_skipped_ += count;
        start_ += count;
    }
    void flush_skipped(FramingSink& sink) {
        if (run_.count == 0) return;
        sink.on_skipped(run_);
        run_ = SkippedBytes{};
    }

  private:
    void compact();

    const FramingRules* rules_;
    std::vector<std::uint8_t> buffer_;
    std::size_t start_ = 0;            // first undecided byte in buffer_
    std::uint64_t buffer_offset_ = 0;  // stream offset of buffer_[0]
    std::uint64_t bytes_fed_ = 0;
    std::uint64_t bytes_skipped_ = 0;
    std::uint64_t telegrams_ = 0;
    SkippedBytes run_{};  // the current run of skipped bytes (count 0: none)
};

// The framing loop for the rules of type `Rules`: when Rules is a final class, judge() is called
// directly, and inlined when the rules' header defines it inline (as FdlFramingRules does);
// FramerFor<FramingRules> calls it through the vtable.
template <class Rules>
class FramerFor final : public FramerCore {
  public:
    explicit FramerFor(const Rules& rules) noexcept : FramerCore(rules), typed_rules_(rules) {}

  private:
    void process(FramingSink& sink, bool at_end) override {
        for (;;) {
            const Bytes rest = undecided();
            if (rest.empty()) return;
            FramingVerdict verdict =
                typed_rules_.can_start(rest[0])
                    ? typed_rules_.judge(rest, at_end)
                    : FramingVerdict::invalid(ProblemKind::BadStartDelimiter, 0);
            if (verdict.status == FramingStatus::NeedMore) {
                if (!at_end) return;
                // Nothing more will come: this candidate is cut off. Later bytes may still hold
                // whole telegrams, so only this one byte is given up.
                verdict = FramingVerdict::invalid(ProblemKind::Truncated, 0);
            }
            if (verdict.status == FramingStatus::Telegram) {
                take_telegram(sink, verdict.length);
                continue;
            }
            // Invalid: skip this byte and everything up to the next byte that may start one.
            std::size_t next = 1;
            while (next < rest.size() && !typed_rules_.can_start(rest[next]))
                ++next;
            skip(next, verdict.reason, verdict.reason_offset);
        }
    }

    const Rules& typed_rules_;
};

class StreamFramer {
  public:
    using Sink = FramingSink;

    // `rules` must outlive the framer.
    explicit StreamFramer(const FramingRules& rules) : core_(rules.make_framer_core()) {}

    const FramingRules& rules() const noexcept { return core_->rules(); }

    void feed(Bytes chunk, Sink& sink) { core_->feed(chunk, sink); }
    // The line was idle: a telegram cannot continue across the gap, so whatever is pending is
    // decided now (a telegram if it is complete, skipped bytes otherwise).
    void mark_gap(Sink& sink) { core_->mark_gap(sink); }
    // End of input: pending bytes are decided as at a gap.
    void finish(Sink& sink) { core_->mark_gap(sink); }

    std::uint64_t bytes_fed() const noexcept { return core_->bytes_fed(); }
    std::uint64_t bytes_skipped() const noexcept { return core_->bytes_skipped(); }
    std::uint64_t telegrams() const noexcept { return core_->telegrams(); }
    std::size_t pending() const noexcept { return core_->pending(); }
    std::size_t buffer_capacity() const noexcept { return core_->buffer_capacity(); }
    const SkippedBytes& skipping() const noexcept { return core_->skipping(); }

  private:
    std::unique_ptr<FramerCore> core_;
};

}  // namespace dpscope
