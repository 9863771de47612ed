#include "core/telegram.hpp"

namespace dpscope {

std::string_view protocol_name(Protocol protocol) noexcept {
    switch (protocol) {
        case Protocol::ProfibusDp: return "profibus";
        case Protocol::Fc: return "fc";
        case Protocol::Vlt2000: return "vlt2000";
    }
    return "profibus";
}

std::optional<Protocol> protocol_from_name(std::string_view name) noexcept {
    if (name == "profibus") return Protocol::ProfibusDp;
    if (name == "fc") return Protocol::Fc;
    if (name == "vlt2000") return Protocol::Vlt2000;
    return std::nullopt;
}

}  // namespace dpscope
