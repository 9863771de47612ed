#include "protocols/profibus/fdl_framing_rules.hpp"

#include "core/stream_framer.hpp"

namespace dpscope {

FdlFramingRules::FdlFramingRules() noexcept : FramingRules(is_start_delimiter) {}

std::unique_ptr<FramerCore> FdlFramingRules::make_framer_core() const {
    return std::make_unique<FramerFor<FdlFramingRules>>(*this);
}

const FdlFramingRules& fdl_framing_rules() noexcept {
    static const FdlFramingRules rules;
    return rules;
}

// Without a length field, a wrong FCS is only believed to be a damaged telegram when the next
// byte starts another telegram.
FramingVerdict FdlFramingRules::judge_fixed(Bytes candidate, std::size_t size,
                                            bool at_end) const noexcept {
    if (candidate.size() < size) return FramingVerdict::need_more();
    if (candidate[size - 1] != kEndDelimiter)
        return FramingVerdict::invalid(ProblemKind::BadEndDelimiter, size - 1);
    if (fcs_of(candidate.subspan(1, size - 3)) == candidate[size - 2])
        return FramingVerdict::telegram(size);
    if (candidate.size() > size) {
        if (can_start(candidate[size])) return FramingVerdict::telegram(size);
        return FramingVerdict::invalid(ProblemKind::FcsMismatch, size - 2);
    }
    return at_end ? FramingVerdict::telegram(size) : FramingVerdict::need_more();
}

std::string_view FdlFramingRules::reason_text(ProblemKind reason) const {
    switch (reason) {
        case ProblemKind::LengthOutOfRange: return "LE outside 3..249";
        case ProblemKind::LengthMismatch: return "LEr differs from LE";
        case ProblemKind::StartDelimiterRepeat: return "repeated start delimiter is not 0x68";
        case ProblemKind::BadEndDelimiter: return "no end delimiter where the length puts it";
        case ProblemKind::FcsMismatch: return "FCS wrong and no telegram follows";
        case ProblemKind::InvalidAddress: return "token address with bit 7 set";
        default: return FramingRules::reason_text(reason);
    }
}

}  // namespace dpscope
