// The framing rules of the Danfoss FC protocol (protocols/fc/fc_telegram.hpp) in a byte stream
// (docs/protocol/fc-protocol.md, "Splitting a byte stream"): a telegram starts with STX 0x02; its
// LGE must be a block length (6, 14, or 10 + n for a text block) and its address byte must name
// an address or the broadcast; the telegram is LGE + 2 bytes and ends with the BCC (XOR from STX).
// A candidate with a wrong BCC is taken as a damaged telegram only when the byte after it starts
// another telegram or nothing follows (the end of the input or an idle line); otherwise the framer
// resynchronises one byte further.
#pragma once

#include "core/framing_rules.hpp"
#include "protocols/fc/fc_telegram.hpp"

namespace dpscope {

// LGE values that start a telegram: 6, 14 and 10..255 (a text block of 0..245 characters).
constexpr bool fc_lge_valid(std::uint8_t lge) noexcept {
    return lge == kFcLgeProcess || lge >= kFcLgeTextBase;
}
// An address byte that names an address or the broadcast: 1..31 (bit 5 set: broadcast) in the
// short format, 1..126 or 0x80 (broadcast) in the long one.
constexpr bool fc_adr_valid(std::uint8_t adr) noexcept {
    if (adr & 0x80) return (adr & 0x7F) != 127;
    return (adr & 0x20) != 0 || (adr & 0x1F) != 0;
}
// XOR of `bytes`, starting from 0.
constexpr std::uint8_t fc_bcc_of(Bytes bytes) noexcept {
    std::uint8_t bcc = 0;
    for (std::uint8_t b : bytes)
        bcc ^= b;
    return bcc;
}

class FcFramingRules final : public FramingRules {
  public:
    FcFramingRules() noexcept;

    FramingVerdict judge(Bytes candidate, bool at_end) const noexcept override;
    std::string_view protocol_name() const noexcept override { return "FC protocol"; }
    std::unique_ptr<FramerCore> make_framer_core() const override;

  protected:
    std::string_view reason_text(ProblemKind reason) const override;
};

// The one instance every FC byte-stream source shares (the rules hold no state).
const FcFramingRules& fc_framing_rules() noexcept;

[[gnu::always_inline]] inline FramingVerdict FcFramingRules::judge(Bytes candidate,
                                                                   bool at_end) const noexcept {
    if (candidate.empty()) return FramingVerdict::need_more();
    if (candidate[0] != kFcStx) return FramingVerdict::invalid(ProblemKind::BadStartDelimiter, 0);
    if (candidate.size() < 2) return FramingVerdict::need_more();
    const std::uint8_t lge = candidate[1];
    if (!fc_lge_valid(lge)) return FramingVerdict::invalid(ProblemKind::LgeInvalid, 1);
    if (candidate.size() < 3) return FramingVerdict::need_more();
    if (!fc_adr_valid(candidate[2])) return FramingVerdict::invalid(ProblemKind::AdrInvalid, 2);
    const std::size_t size = std::size_t{lge} + 2;
    if (candidate.size() < size) return FramingVerdict::need_more();
    if (fc_bcc_of(candidate.first(size - 1)) == candidate[size - 1])
        return FramingVerdict::telegram(size);
    if (candidate.size() > size) {
        if (can_start(candidate[size])) return FramingVerdict::telegram(size);
        return FramingVerdict::invalid(ProblemKind::BccMismatch, size - 1);
    }
    return at_end ? FramingVerdict::telegram(size) : FramingVerdict::need_more();
}

}  // namespace dpscope
