// Problems found while decoding one telegram, reported as values. A Problem is small and holds
// no heap memory, so the hot path can record one without allocating; the human message is built
// only when something asks for it.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace dpscope {

enum class Severity : std::uint8_t { Note, Warning, Error };

std::string_view severity_name(Severity severity);

enum class ProblemKind : std::uint8_t {
    EmptyRecord,             // a capture record with no bytes at all
    BadStartDelimiter,       // first byte is none of SD1, SD2, SD3, SD4, SC
    Truncated,               // the telegram ends before its structure says it should
    LengthMismatch,          // SD2: LE differs from LEr
    LengthOutOfRange,        // SD2: LE outside 4..249
    StartDelimiterRepeat,    // SD2: the repeated start delimiter is not 0x68
    FcsMismatch,             // FDL checksum wrong
    BadEndDelimiter,         // end delimiter is not 0x16
    TrailingBytes,           // bytes after the end of the telegram in the same record
    InvalidAddress,          // SD4: an address with bit 7 set (tokens carry no extension)
    AddressExtensionShort,   // an address-extension bit announces a SAP byte that is not there
    ServiceDataShort,        // a DP service's data unit is shorter than the service requires
    CfgIdentifierTruncated,  // a special-format identifier announces bytes that are not there
    DiagBlockTruncated,      // an extended-diagnosis block runs past the end of the data
    ReservedFrameControl,    // FC bit 7 set in anything but the clock value request 0xC0
    Count
};

constexpr std::size_t kProblemKindCount = static_cast<std::size_t>(ProblemKind::Count);

// Stable snake_case name used in jsonl, csv and the summary.
std::string_view problem_kind_name(ProblemKind kind);
Severity problem_severity(ProblemKind kind);

struct Problem {
    ProblemKind kind = ProblemKind::Truncated;
    std::uint16_t offset = 0;    // byte offset in the telegram where the check failed
    std::uint32_t expected = 0;  // what the check wanted (meaning depends on kind)
    std::uint32_t actual = 0;    // what the telegram had
};

// One line a person understands, e.g. "FCS mismatch at byte 12: expected 0x3A, got 0x3B".
std::string problem_message(const Problem& problem);

// A fixed-capacity list: a telegram rarely has more than two problems, and the decoder must not
// allocate per telegram. Problems past the capacity are counted in dropped().
class ProblemList {
  public:
    static constexpr std::size_t kCapacity = 6;

    void add(ProblemKind kind, std::size_t offset, std::uint32_t expected = 0,
             std::uint32_t actual = 0) noexcept {
        if (count_ < kCapacity) {
            items_[count_++] = Problem{kind, static_cast<std::uint16_t>(offset), expected, actual};
        } else {
            ++dropped_;
        }
    }
    void clear() noexcept { count_ = 0, dropped_ = 0; }
    bool empty() const noexcept { return count_ == 0; }
    std::size_t size() const noexcept { return count_; }
    std::size_t dropped() const noexcept { return dropped_; }
    const Problem* begin() const noexcept { return items_.data(); }
    const Problem* end() const noexcept { return items_.data() + count_; }
    const Problem& operator[](std::size_t i) const noexcept { return items_[i]; }
    bool contains(ProblemKind kind) const noexcept {
        for (const Problem& p : *this)
            if (p.kind == kind) return true;
        return false;
    }

  private:
    std::array<Problem, kCapacity> items_;  // only the first count_ are meaningful
    std::uint8_t count_ = 0;
    std::uint8_t dropped_ = 0;
};

}  // namespace dpscope
