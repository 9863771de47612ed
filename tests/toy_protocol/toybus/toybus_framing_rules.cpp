#include "protocols/toybus/toybus_framing_rules.hpp"

#include "core/stream_framer.hpp"

namespace dpscope {

namespace {
bool is_start(std::uint8_t byte) { return toybus_is_lead(byte); }
}  // namespace

ToybusFramingRules::ToybusFramingRules() noexcept : FramingRules(is_start) {}

std::unique_ptr<FramerCore> ToybusFramingRules::make_framer_core() const {
    return std::make_unique<FramerFor<ToybusFramingRules>>(*this);
}

const ToybusFramingRules& toybus_framing_rules() noexcept {
    static const ToybusFramingRules rules;
    return rules;
}

std::string_view ToybusFramingRules::reason_text(ProblemKind reason) const {
    switch (reason) {
        case ProblemKind::BadStartDelimiter: return "no '?', '!', '=' or '#'";
        case ProblemKind::BadEndDelimiter: return "no line end where the line should end";
        case ProblemKind::Vlt2000CharacterInvalid: return "a character that is not printable ASCII";
        default: return FramingRules::reason_text(reason);
    }
}

}  // namespace dpscope
