#include "drives/drive_family.hpp"

#include "core/protocol_descriptor.hpp"

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

std::optional<std::string_view> DriveHints::of(std::uint8_t address) const noexcept {
    const std::string& own = station[address & 0x7F];
    if (!own.empty()) return own;
    if (!all.empty()) return all;
    return std::nullopt;
}

}  // namespace dpscope
