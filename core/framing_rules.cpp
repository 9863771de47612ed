#include "core/framing_rules.hpp"

#include <fmt/format.h>

#include "core/counted.hpp"
#include "core/stream_framer.hpp"

namespace dpscope {

FramingRules::FramingRules(bool (*can_start_telegram)(std::uint8_t),
                           std::uint8_t first_byte_number) noexcept
    : first_byte_number_(first_byte_number) {
    for (std::size_t byte = 0; byte < starts_.size(); ++byte)
        starts_[byte] = can_start_telegram(static_cast<std::uint8_t>(byte));
}

std::string_view FramingRules::reason_text(ProblemKind reason) const {
    switch (reason) {
        case ProblemKind::BadStartDelimiter: return "no start delimiter";
        case ProblemKind::Truncated: return "telegram cut off (gap or end of input)";
        default: return problem_kind_name(reason);
    }
}

std::string FramingRules::describe_skip(const SkippedBytes& skipped) const {
    const std::string_view what = reason_text(skipped.reason);
    const std::string bytes = counted(skipped.count, "byte", "bytes");
    // The framer's own reasons concern no particular byte of a candidate.
    if (skipped.reason == ProblemKind::BadStartDelimiter ||
        skipped.reason == ProblemKind::Truncated)
        return fmt::format("skipped {}: {}", bytes, what);
    return fmt::format("skipped {}: {} (byte {} of the candidate telegram)", bytes, what,
                       skipped.reason_offset + first_byte_number_);
}

std::unique_ptr<FramerCore> FramingRules::make_framer_core() const {
    return std::make_unique<FramerFor<FramingRules>>(*this);
}

}  // namespace dpscope
