// The framing rules of the VLT 2000 serial telegram (protocols/vlt2000/vlt2000_telegram.hpp) in a
// byte stream (docs/protocol/vlt2000.md, "Splitting a byte stream"): a telegram is exactly 22
// characters, '<' to '>'. A candidate whose 22nd character is not '>' is no telegram, and neither
// is one with a character outside printable ASCII; the framer resynchronises on the next '<'. A
// candidate with '>' in place whose checksum is wrong is taken as a damaged telegram (reported
// with a checksum error) unless it holds another '<', where a telegram may start that a broken one
// ran into: then it is skipped up to that '<'.
#pragma once

#include "core/framing_rules.hpp"
#include "protocols/vlt2000/vlt2000_telegram.hpp"

namespace dpscope {

// The characters a telegram may hold between '<' and '>': printable ASCII.
constexpr bool vlt2000_char_valid(std::uint8_t c) noexcept { return c >= 0x20 && c <= 0x7E; }

// Are the checksum characters (offsets 19, 20) right for the telegram, or "??"? `telegram` holds
// at least 21 bytes.
constexpr bool vlt2000_checksum_matches(Bytes telegram) noexcept {
    const std::uint8_t hi = telegram[kVlt2000ChecksumAt];
    const std::uint8_t lo = telegram[kVlt2000ChecksumAt + 1];
    if (hi == '?' && lo == '?') return true;
    if (hi < '0' || hi > '9' || lo < '0' || lo > '9') return false;
    return vlt2000_checksum_of(telegram) == (hi - '0') * 10 + (lo - '0');
}

class Vlt2000FramingRules final : public FramingRules {
  public:
    Vlt2000FramingRules() noexcept;

    FramingVerdict judge(Bytes candidate, bool at_end) const noexcept override;
    std::string_view protocol_name() const noexcept override { return "VLT 2000"; }
    std::unique_ptr<FramerCore> make_framer_core() const override;

  protected:
    std::string_view reason_text(ProblemKind reason) const override;
};

// The one instance every VLT 2000 byte-stream source shares (the rules hold no state).
const Vlt2000FramingRules& vlt2000_framing_rules() noexcept;

[[gnu::always_inline]] inline FramingVerdict Vlt2000FramingRules::judge(
    Bytes candidate, bool at_end) const noexcept {
    if (candidate.empty()) return FramingVerdict::need_more();
    if (candidate[0] != kVlt2000Start)
        return FramingVerdict::invalid(ProblemKind::BadStartDelimiter, 0);
    // Every character so far must be printable: a control character or a byte above 0x7E means
    // the line broke (or this is no VLT 2000 traffic), whatever follows.
    const std::size_t seen = std::min(candidate.size(), kVlt2000TelegramSize);
    for (std::size_t i = 1; i < seen; ++i)
        if (!vlt2000_char_valid(candidate[i]))
            return FramingVerdict::invalid(ProblemKind::Vlt2000CharacterInvalid, i);
    if (candidate.size() < kVlt2000TelegramSize) {
        (void)at_end;  // at the end the framer gives a cut-off candidate up itself
        return FramingVerdict::need_more();
    }
    if (candidate[kVlt2000StopAt] != kVlt2000Stop)
        return FramingVerdict::invalid(ProblemKind::BadEndDelimiter, kVlt2000StopAt);
    if (vlt2000_checksum_matches(candidate)) return FramingVerdict::telegram(kVlt2000TelegramSize);
    for (std::size_t i = 1; i < kVlt2000StopAt; ++i)
        if (candidate[i] == kVlt2000Start)
            return FramingVerdict::invalid(ProblemKind::Vlt2000ChecksumMismatch,
                                           kVlt2000ChecksumAt);
    return FramingVerdict::telegram(kVlt2000TelegramSize);
}

}  // namespace dpscope
