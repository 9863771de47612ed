// The table of protocol descriptors, made from the registration list
// (protocols/protocol_list.hpp): nothing to edit here when a protocol is added.
#include <algorithm>
#include <array>

#include "core/protocol_descriptor.hpp"

namespace dpscope {

bool ProtocolDescriptor::carried_by(int link_type) const noexcept {
    return std::any_of(link_types.begin(), link_types.end(),
                       [link_type](const PcapLinkType& type) { return type.value == link_type; });
}

std::span<const ProtocolDescriptor* const> protocol_table() noexcept {
    static const std::array<const ProtocolDescriptor*, kProtocolCount> table{
#define DPSCOPE_PROTOCOL_ENTRY(Enum, name, Payload, member) &name##_protocol(),
        DPSCOPE_PROTOCOLS(DPSCOPE_PROTOCOL_ENTRY)
#undef DPSCOPE_PROTOCOL_ENTRY
    };
    return table;
}

const ProtocolDescriptor& protocol_descriptor(Protocol protocol) noexcept {
    return protocol_record(protocol_table(), protocol);
}

const ProtocolDescriptor* protocol_by_name(std::string_view name) noexcept {
    for (const ProtocolDescriptor* descriptor : protocol_table())
        if (descriptor->name == name) return descriptor;
    return nullptr;
}

const ProtocolDescriptor* only_protocol_of_link_type(int link_type) noexcept {
    const ProtocolDescriptor* owner = nullptr;
    for (const ProtocolDescriptor* descriptor : protocol_table()) {
        if (!descriptor->carried_by(link_type)) continue;
        if (owner) return nullptr;
        owner = descriptor;
    }
    return owner;
}

const ProtocolDescriptor* text_log_protocol() noexcept {
    for (const ProtocolDescriptor* descriptor : protocol_table())
        if (!descriptor->text_log_shape.empty()) return descriptor;
    return nullptr;
}

std::string_view protocol_name(Protocol protocol) noexcept {
    return protocol_descriptor(protocol).name;
}

std::optional<Protocol> protocol_from_name(std::string_view name) noexcept {
    const ProtocolDescriptor* descriptor = protocol_by_name(name);
    if (!descriptor) return std::nullopt;
    return descriptor->protocol;
}

}  // namespace dpscope
