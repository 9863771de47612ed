#include "protocols/fc/fc_framing_rules.hpp"

#include "core/stream_framer.hpp"

namespace dpscope {

namespace {
bool is_stx(std::uint8_t byte) { return byte == kFcStx; }
}  // namespace

FcFramingRules::FcFramingRules() noexcept : FramingRules(is_stx) {}

std::unique_ptr<FramerCore> FcFramingRules::make_framer_core() const {
    return std::make_unique<FramerFor<FcFramingRules>>(*this);
}

const FcFramingRules& fc_framing_rules() noexcept {
    static const FcFramingRules rules;
    return rules;
}

std::string_view FcFramingRules::reason_text(ProblemKind reason) const {
    switch (reason) {
        case ProblemKind::BadStartDelimiter: return "no STX";
        case ProblemKind::LgeInvalid: return "LGE is no block length (6, 14, 10..255)";
        case ProblemKind::AdrInvalid: return "address byte names no address";
        case ProblemKind::BccMismatch: return "BCC wrong and no telegram follows";
        default: return FramingRules::reason_text(reason);
    }
}

}  // namespace dpscope
