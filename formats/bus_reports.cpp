// The table of the report's per-bus parts (BusReport, formats/report_model.hpp), made from the
// registration list (protocols/protocol_list.hpp): nothing to edit here when a protocol is added.
#include <array>

#include "formats/report_model.hpp"

namespace dpscope::report {

std::span<const BusReport* const> bus_report_table() noexcept {
    static const std::array<const BusReport*, kProtocolCount> table{
#define DPSCOPE_BUS_REPORT_ENTRY(Enum, name, Payload, member) &name##_bus_report(),
        DPSCOPE_PROTOCOLS(DPSCOPE_BUS_REPORT_ENTRY)
#undef DPSCOPE_BUS_REPORT_ENTRY
    };
    return table;
}

const BusReport& bus_report(Protocol protocol) noexcept {
    return protocol_record(bus_report_table(), protocol);
}

}  // namespace dpscope::report
