// The table of protocol trees, made from the registration list (protocols/protocol_list.hpp):
// nothing to edit here when a protocol is added.
#include <array>

#include "wireshark/protocol_tree.hpp"

namespace dpscope::wireshark {

std::span<const ProtocolTree* const> protocol_trees() noexcept {
    static const std::array<const ProtocolTree*, kProtocolCount> table{
#define DPSCOPE_PROTOCOL_TREE_ENTRY(Enum, name, Payload, member) &name##_tree(),
        DPSCOPE_PROTOCOLS(DPSCOPE_PROTOCOL_TREE_ENTRY)
#undef DPSCOPE_PROTOCOL_TREE_ENTRY
    };
    return table;
}

const ProtocolTree& protocol_tree(Protocol protocol) noexcept {
    return protocol_record(protocol_trees(), protocol);
}

AddressColumns drive_address_columns(const DecodedTelegram& t, bool broadcast,
                                     const std::string& drive) {
    if (!t.has_roles) return {};
    const bool request = t.direction == Direction::Request;
    const std::string station = broadcast && request ? std::string("all") : drive;
    return request ? AddressColumns{"M", station} : AddressColumns{station, "M"};
}

}  // namespace dpscope::wireshark
