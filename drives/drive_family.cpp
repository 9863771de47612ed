#include "drives/drive_family.hpp"

#include "core/protocol_descriptor.hpp"
#include "core/text_encoding.hpp"

namespace dpscope {

std::string_view family_of_dialect(Dialect dialect) noexcept {
    switch (dialect) {
        case Dialect::Ge: return "af600";
        case Dialect::Profidrive: return kProfileFamily;
        case Dialect::Fc: return "fc";
        case Dialect::Vlt2000: return "vlt2000";
        case Dialect::Vlt: break;
    }
    return "vlt5000";
}

std::string_view drive_family(Protocol bus, Dialect dialect,
                              std::optional<std::string_view> hint) noexcept {
    if (hint && !hint->empty()) return *hint;
    const std::string_view own = protocol_descriptor(bus).drive_family;
    return own.empty() ? family_of_dialect(dialect) : own;
}

std::optional<std::string_view> family_of_device(std::string_view vendor,
                                                 std::string_view model) noexcept {
    if (contains_ignoring_case(vendor, "danfoss")) {
        if (contains_ignoring_case(model, "vlt 5") || contains_ignoring_case(model, "vlt5"))
            return "vlt5000";
        for (std::string_view fc : {"fc 1", "fc 2", "fc 3", "fc-1", "fc-2", "fc-3", "fc1", "fc2",
                                    "fc3", "automationdrive", "hvac drive", "aqua drive"})
            if (contains_ignoring_case(model, fc)) return "fc";
        return std::nullopt;
    }
    if (contains_ignoring_case(vendor, "ge ") || equal_ignoring_case(vendor, "ge") ||
        contains_ignoring_case(vendor, "general electric"))
        if (contains_ignoring_case(model, "af-6") || contains_ignoring_case(model, "af6"))
            return "af600";
    return std::nullopt;
}

std::optional<std::string_view> DriveHints::of(std::uint8_t address) const noexcept {
    const std::string& own = station[address & 0x7F];
    if (!own.empty()) return own;
    if (!all.empty()) return all;
    return std::nullopt;
}

}  // namespace dpscope
