// The toybus telegram in the dissector: its subtree (kind, drive, parameter, value or error, line
// end) and its record in the table of protocol trees. The items are text items under an existing
// subtree id: the toy registers no dpscope.toybus.* fields, which would be rows in the shared
// DPSCOPE_FIELDS table (wireshark/dissector_fields.hpp) and the field table of docs/wireshark.md.
#include <fmt/format.h>

#include <string>

#include "protocols/toybus/toybus_describe.hpp"
#include "wireshark/protocol_tree.hpp"

namespace dpscope::wireshark {
namespace {

void add_toybus(const Tree& top, const DecodedTelegram& t) {
    const ToybusTelegram& v = t.toybus;
    const std::size_t size = t.bytes.size();
    Tree tree = top.text(0, size, kEttParameter,
                         fmt::format("toybus telegram: {} {}", toybus_kind_text(v),
                                     t.direction == Direction::Request ? "request" : "response"));
    if (size == 0) return;
    tree.text(0, 1, kEttParameter, fmt::format("Kind: {}", toybus_kind_text(v)));
    if (v.has_address)
        tree.text(kToybusAddressAt, 2, kEttParameter, fmt::format("Drive: {:02}", v.address));
    if (v.has_parameter)
        tree.text(kToybusParameterAt, 4, kEttParameter,
                  fmt::format("Parameter: {:04}", v.parameter));
    if (v.has_value)
        tree.text(kToybusValueAt, 5, kEttParameter, fmt::format("Value: {:05}", v.value));
    if (v.has_error)
        tree.text(kToybusValueAt, 2, kEttParameter, fmt::format("Error: {:02}", v.error));
}

AddressColumns toybus_address_columns(const DecodedTelegram& t) {
    return drive_address_columns(t, false, fmt::format("{:02}", t.toybus.address));
}

}  // namespace

const ProtocolTree& toybus_tree() noexcept {
    static const ProtocolTree tree{
        .protocol = Protocol::Toybus,
        .column = "toybus",
        .bus_description = "toybus line protocol",
        .shows_master = false,
        .add_subtree = add_toybus,
        .address_columns = toybus_address_columns,
    };
    return tree;
}

}  // namespace dpscope::wireshark
