// Problems found while decoding one telegram, reported as values. A Problem is small and holds
// no heap memory, so the hot path can record one without allocating; the human message is built
// only when something asks for it.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace dpscope {

enum class Severity : std::uint8_t { Note, Warning, Error };

std::string_view severity_name(Severity severity);

enum class ProblemKind : std::uint8_t {
    EmptyRecord,
    BadStartDelimiter,
    Truncated,
    LengthMismatch,
    LengthOutOfRange,
    StartDelimiterRepeat,
    FcsMismatch,
    BadEndDelimiter,
    TrailingBytes,
    InvalidAddress,
    AddressExtensionShort,
    ServiceDataShort,
    CfgIdentifierTruncated,
    DiagBlockTruncated,
    ReservedFrameControl,
    LgeInvalid,
    BccMismatch,
    AdrInvalid,
    Vlt2000CharacterInvalid,
    Vlt2000FieldInvalid,
    Vlt2000LetterUnknown,
    Vlt2000ChecksumMismatch,
    Count
};

constexpr std::size_t kProblemKindCount = static_cast<std::size_t>(ProblemKind::Count);

// The layer of the decoder whose check a problem kind is.
enum class ProblemComponent : std::uint8_t {
    Framing,    // where the telegram starts and ends: delimiters, lengths, what is left over
    Fdl,        // the FDL telegram's own fields: checksum, addresses, frame control
    DpService,  // the data unit of a DP service
    Fc,         // the Danfoss FC protocol telegram's own fields: checksum, address byte
    Vlt2000,    // the VLT 2000 telegram's own fields: digits, control letter, checksum
    Count
};

constexpr std::size_t kProblemComponentCount = static_cast<std::size_t>(ProblemComponent::Count);

// One row of the problem catalogue (problem.cpp): everything fixed about a kind.
struct ProblemKindInfo {
    ProblemKind kind;
    std::string_view name;  // stable snake_case name used in jsonl, csv and the summary
    Severity severity;
    ProblemComponent component;
    std::string_view check;  // what was wrong, in a few words (for documentation)
};

// Every problem kind, one row each, in enum order (checked when problem.cpp compiles).
std::span<const ProblemKindInfo> problem_catalogue() noexcept;
const ProblemKindInfo& problem_kind_info(ProblemKind kind) noexcept;

// Stable snake_case name used in jsonl, csv and the summary.
std::string_view problem_kind_name(ProblemKind kind);
Severity problem_severity(ProblemKind kind);
ProblemComponent problem_component(ProblemKind kind);

// The kinds of one component, in enum order (for reports and documentation).
std::vector<ProblemKind> problem_kinds_of(ProblemComponent component);
// "framing", "FDL", "DP service".
std::string_view problem_component_name(ProblemComponent component);

struct Problem {
    ProblemKind kind = ProblemKind::Truncated;
    std::uint16_t offset = 0;    // byte offset in the telegram where the check failed (0-based)
    std::uint32_t expected = 0;  // what the check wanted (meaning depends on kind)
    std::uint32_t actual = 0;    // what the telegram had
    // The number the message gives the telegram's first byte: 0 (the offset itself: PROFIBUS, FC)
    // or 1, where the protocol's manual numbers the bytes from 1 (VLT 2000: bytes 1-22 [S004]).
    std::uint8_t first_byte = 0;

    // The byte number a message names: offset + first_byte.
    std::uint32_t byte_number() const noexcept { return std::uint32_t{offset} + first_byte; }
};

// One line a person understands, e.g. "byte 12: FCS 0x3B wrong, checksum of the data is 0x3A";
// the byte numbered as Problem::first_byte says.
std::string problem_message(const Problem& problem);

// A fixed-capacity list: a telegram rarely has more than two problems, and the decoder must not
// allocate per telegram. Problems past the capacity are counted in dropped().
class ProblemList {
  public:
    static constexpr std::size_t kCapacity = 6;

    constexpr ProblemList() noexcept = default;
    // `first_byte`: the Problem::first_byte of every problem added (1 for VLT 2000 telegrams).
    constexpr explicit ProblemList(std::uint8_t first_byte) noexcept : first_byte_(first_byte) {}

    void add(ProblemKind kind, std::size_t offset, std::uint32_t expected = 0,
             std::uint32_t actual = 0) noexcept {
        if (count_ < kCapacity) {
            items_[count_++] =
                Problem{kind, static_cast<std::uint16_t>(offset), expected, actual, first_byte_};
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
    std::array<Problem, kCapacity> items_{};  // only the first count_ are meaningful
    std::uint8_t count_ = 0;
    std::uint8_t dropped_ = 0;
    std::uint8_t first_byte_ = 0;
};
// No problem: what a telegram of no protocol has.
inline constexpr ProblemList kNoProblems{};


}  // namespace dpscope
