// A protocol's framing rules: how a byte stream (a serial dump, a hex log, a live port) splits
// into telegrams. The StreamFramer (core/stream_framer.hpp) does the buffering, the
// resynchronisation and the stream offsets for every protocol; it asks the rules only
//   - which byte may start a telegram (can_start: a table, so the framer's scan for the next
//     start byte makes no call per byte),
//   - what the candidate at the start of the unconsumed bytes is (judge: one call per candidate):
//     "need more bytes", "invalid, with the reason", or "a telegram of N bytes",
//   - and the words for a run of skipped bytes (describe_skip).
// FDL (PROFIBUS DP) is one implementation: protocols/profibus/fdl_framing_rules.hpp.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "core/byte_reader.hpp"
#include "core/problem.hpp"

namespace dpscope {

class FramerCore;  // core/stream_framer.hpp

enum class FramingStatus : std::uint8_t { Telegram, NeedMore, Invalid };

// What a candidate at the start of the bytes is.
struct FramingVerdict {
    FramingStatus status = FramingStatus::NeedMore;
    std::uint16_t length = 0;                             // Telegram: its size in bytes
    ProblemKind reason = ProblemKind::BadStartDelimiter;  // Invalid: the first check that failed
    std::uint16_t reason_offset = 0;                      // Invalid: at which byte of it

    static constexpr FramingVerdict need_more() noexcept { return FramingVerdict{}; }
    static constexpr FramingVerdict telegram(std::size_t size) noexcept {
        return FramingVerdict{FramingStatus::Telegram, static_cast<std::uint16_t>(size),
                              ProblemKind::BadStartDelimiter, 0};
    }
    static constexpr FramingVerdict invalid(ProblemKind why, std::size_t offset) noexcept {
        return FramingVerdict{FramingStatus::Invalid, 0, why, static_cast<std::uint16_t>(offset)};
    }
};

// A run of bytes the framer skipped because they form no telegram.
struct SkippedBytes {
    std::uint64_t offset = 0;  // stream offset of the first skipped byte
    std::uint64_t count = 0;
    ProblemKind reason = ProblemKind::BadStartDelimiter;  // the first check that failed
    std::uint16_t reason_offset = 0;  // byte of the candidate telegram where it failed
};

class FramingRules {
  public:
    virtual ~FramingRules() = default;
    FramingRules(const FramingRules&) = delete;
    FramingRules& operator=(const FramingRules&) = delete;

    // May `byte` start a telegram? The framer skips to the next byte that may, and judges only
    // candidates that begin with one (a byte that may not is skipped as BadStartDelimiter).
    bool can_start(std::uint8_t byte) const noexcept { return starts_[byte]; }

    // Judges the candidate telegram at the start of `candidate`: the undecided bytes received so
    // far, the first of them one that can_start() (never empty). `at_end`: nothing follows them
    // (the input ended, or the line was idle). The answer:
    //   need_more()                  the bytes so far may still become a telegram; at the end the
    //                                framer gives the candidate up as cut off (Truncated), one
    //                                byte at a time, so telegrams behind it are still found;
    //   invalid(reason, offset)      no telegram starts here: the first check that failed and at
    //                                which byte; the framer skips to the next start byte;
    //   telegram(n)                  the first n bytes (1 <= n <= candidate.size()) are one.
    // Called once per candidate, never per byte; must not allocate.
    virtual FramingVerdict judge(Bytes candidate, bool at_end) const noexcept = 0;

    // The protocol's name where an input is judged to be none of its streams ("not a PROFIBUS
    // byte stream").
    virtual std::string_view protocol_name() const noexcept = 0;

    // "skipped 5 bytes: no start delimiter"; "skipped 7 bytes: LEr differs from LE (byte 2 of
    // the candidate telegram)", the byte numbered as the protocol's messages number it (from 0,
    // or from 1 for VLT 2000). The caller says where (offset, line).
    std::string describe_skip(const SkippedBytes& skipped) const;

    // The engine of a StreamFramer over these rules. The default calls judge() through the vtable
    // (one virtual call per candidate); rules of a final class return
    // `std::make_unique<FramerFor<TheirClass>>(*this)` (core/stream_framer.hpp) so that the
    // framing loop calls their judge() directly.
    virtual std::unique_ptr<FramerCore> make_framer_core() const;

  protected:
    // `can_start_telegram` is asked once for every byte value, here. `first_byte_number`: the
    // number describe_skip gives a candidate's first byte (Problem::first_byte).
    explicit FramingRules(bool (*can_start_telegram)(std::uint8_t),
                          std::uint8_t first_byte_number = 0) noexcept;

    // The words for a reason judge() gives ("LE outside 3..249"). The framer's own reasons have
    // words here: BadStartDelimiter "no start delimiter" (a byte that may not start a telegram),
    // Truncated "telegram cut off (gap or end of input)"; others fall back to problem_kind_name.
    virtual std::string_view reason_text(ProblemKind reason) const;

  private:
    std::array<bool, 256> starts_{};
    std::uint8_t first_byte_number_ = 0;
};

}  // namespace dpscope
