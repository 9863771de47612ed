// The framing rules of toybus (protocols/toybus/toybus_telegram.hpp) in a byte stream: a
// telegram starts with one of '?', '!', '=', '#' and ends at the next '\n'. A candidate is no
// telegram when a byte before the '\n' is neither printable ASCII nor the '\r' of the line end
// (the line broke), when another lead character comes first (a line cut short ran into the
// next: the framer resynchronises there), or when the longest telegram's 16 bytes hold no '\n'.
// The fields are checked by the decoder, not here.
#pragma once

#include <algorithm>

#include "core/framing_rules.hpp"
#include "protocols/toybus/toybus_telegram.hpp"

namespace dpscope {

class ToybusFramingRules final : public FramingRules {
  public:
    ToybusFramingRules() noexcept;

    FramingVerdict judge(Bytes candidate, bool at_end) const noexcept override;
    std::string_view protocol_name() const noexcept override { return "toybus"; }
    std::unique_ptr<FramerCore> make_framer_core() const override;

  protected:
    std::string_view reason_text(ProblemKind reason) const override;
};

// The one instance every toybus byte-stream source shares (the rules hold no state).
const ToybusFramingRules& toybus_framing_rules() noexcept;

[[gnu::always_inline]] inline FramingVerdict ToybusFramingRules::judge(
    Bytes candidate, bool /*at_end*/) const noexcept {
    if (candidate.empty()) return FramingVerdict::need_more();
    if (!toybus_is_lead(candidate[0]))
        return FramingVerdict::invalid(ProblemKind::BadStartDelimiter, 0);
    const std::size_t seen = std::min(candidate.size(), kToybusMaxTelegram);
    for (std::size_t i = 1; i < seen; ++i) {
        const std::uint8_t c = candidate[i];
        if (c == '\n') return FramingVerdict::telegram(i + 1);
        if (c == '\r') {
            // Only as the line end: the next byte, where there is one, is the '\n'.
            if (i + 1 < candidate.size() && candidate[i + 1] != '\n')
                return FramingVerdict::invalid(ProblemKind::BadEndDelimiter, i + 1);
            continue;
        }
        if (toybus_is_lead(c)) return FramingVerdict::invalid(ProblemKind::BadEndDelimiter, i);
        if (c < 0x20 || c > 0x7E)
            return FramingVerdict::invalid(ProblemKind::Vlt2000CharacterInvalid, i);
    }
    if (candidate.size() >= kToybusMaxTelegram)
        return FramingVerdict::invalid(ProblemKind::BadEndDelimiter, kToybusMaxTelegram - 1);
    return FramingVerdict::need_more();  // at the end the framer gives it up as cut off
}

}  // namespace dpscope
