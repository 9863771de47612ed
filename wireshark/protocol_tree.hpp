// What the dissector shows differently by protocol, one record per protocol: the Protocol column,
// the bus preference's wording, the source and destination columns, the master field and the
// protocol's subtree. Each protocol fills in its record in its folder
// (protocols/<name>/<name>_tree.cpp, `<name>_tree()`); dissector.cpp looks the capture's protocol
// up here instead of switching on it. The table is made from the registration list
// (protocols/protocol_list.hpp): wireshark/protocol_trees.cpp.
#pragma once

#include <span>
#include <string>

#include "core/telegram.hpp"
#include "wireshark/tree.hpp"

namespace dpscope::wireshark {

// The Source and Destination columns of a telegram; both empty: the telegram names no station
// and the columns are left alone.
struct AddressColumns {
    std::string source;
    std::string destination;
};

struct ProtocolTree {
    Protocol protocol;
    // The Protocol column and the top item's title: "PROFIBUS". Wireshark keeps the pointer
    // (col_set_str), so it is a string literal.
    const char* column;
    // The bus preference's description of the protocol: "PROFIBUS DP". Wireshark keeps the
    // pointer (enum_val_t), so it is a string literal.
    const char* bus_description;
    // Whether the tree shows the master's station address (dpscope.master): only a bus whose
    // masters have addresses has one to show.
    bool shows_master;
    // Adds the protocol's subtree (or subtrees) to the top tree, after the request/response link.
    void (*add_subtree)(const Tree& top, const DecodedTelegram& t);
    // Source and destination as the text line has them.
    AddressColumns (*address_columns)(const DecodedTelegram& t);
};

// Every protocol's record, in the order of the registration list (the order of the bus
// preference's values).
std::span<const ProtocolTree* const> protocol_trees() noexcept;
// The record of a protocol.
const ProtocolTree& protocol_tree(Protocol protocol) noexcept;

// The columns of a bus whose master has no address (FC, VLT 2000): "M" for the master, the
// drive's address as `drive` writes it, "all" for a request to every drive (`broadcast`).
AddressColumns drive_address_columns(const DecodedTelegram& t, bool broadcast,
                                     const std::string& drive);

// Each protocol's record, by the name its line in protocols/protocol_list.hpp gives it:
// profibus_tree(), fc_tree(), ... (defined in protocols/<name>/<name>_tree.cpp).
#define DPSCOPE_PROTOCOL_TREE(Enum, name, Payload, member) \
    const ProtocolTree& name##_tree() noexcept;
DPSCOPE_PROTOCOLS(DPSCOPE_PROTOCOL_TREE)
#undef DPSCOPE_PROTOCOL_TREE

}  // namespace dpscope::wireshark
