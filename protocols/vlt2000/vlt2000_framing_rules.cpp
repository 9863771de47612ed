#include "protocols/vlt2000/vlt2000_framing_rules.hpp"

#include "core/stream_framer.hpp"

namespace dpscope {

namespace {
bool is_start(std::uint8_t byte) { return byte == kVlt2000Start; }
}  // namespace

Vlt2000FramingRules::Vlt2000FramingRules() noexcept
    : FramingRules(is_start, kVlt2000FirstByteNumber) {}

std::unique_ptr<FramerCore> Vlt2000FramingRules::make_framer_core() const {
    return std::make_unique<FramerFor<Vlt2000FramingRules>>(*this);
}

const Vlt2000FramingRules& vlt2000_framing_rules() noexcept {
    static const Vlt2000FramingRules rules;
    return rules;
}

std::string_view Vlt2000FramingRules::reason_text(ProblemKind reason) const {
    switch (reason) {
        case ProblemKind::BadStartDelimiter: return "no '<'";
        case ProblemKind::Vlt2000CharacterInvalid: return "a character that is not printable ASCII";
        case ProblemKind::BadEndDelimiter: return "no '>' at the telegram's end";
        case ProblemKind::Vlt2000ChecksumMismatch: return "checksum wrong and another '<' inside";
        default: return FramingRules::reason_text(reason);
    }
}

}  // namespace dpscope
