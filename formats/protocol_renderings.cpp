// The table of protocol renderings, made from the registration list
// (protocols/protocol_list.hpp): nothing to edit here when a protocol is added.
#include <array>

#include "formats/protocol_rendering.hpp"

namespace dpscope {

const ProtocolRendering& protocol_rendering(Protocol protocol) noexcept {
    static const std::array<const ProtocolRendering*, kProtocolCount> table{
#define DPSCOPE_PROTOCOL_RENDERING_ENTRY(Enum, name, Payload, member) &name##_rendering(),
        DPSCOPE_PROTOCOLS(DPSCOPE_PROTOCOL_RENDERING_ENTRY)
#undef DPSCOPE_PROTOCOL_RENDERING_ENTRY
    };
    const auto index = static_cast<std::size_t>(protocol);
    return *table[index < table.size() ? index : 0];
}

}  // namespace dpscope
