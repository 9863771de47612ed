// The table of the simulator's per-bus parts (SimulatedBus, simulator/bus_model.hpp), made from the
// registration list (protocols/protocol_list.hpp): nothing to edit here when a protocol is added.
#include <array>

#include "simulator/bus_model.hpp"

namespace dpscope {

namespace {

std::span<const SimulatedBus* const> simulated_bus_table() noexcept {
    static const std::array<const SimulatedBus*, kProtocolCount> table{
#define DPSCOPE_SIMULATED_BUS_ENTRY(Enum, name, Payload, member) &name##_simulated_bus(),
        DPSCOPE_PROTOCOLS(DPSCOPE_SIMULATED_BUS_ENTRY)
#undef DPSCOPE_SIMULATED_BUS_ENTRY
    };
    return table;
}

}  // namespace

const SimulatedBus& simulated_bus(Protocol protocol) noexcept {
    return protocol_record(simulated_bus_table(), protocol);
}

}  // namespace dpscope
