// The table of the simulator's per-bus parts (SimulatedBus, simulator/bus_model.hpp), made from the
// registration list (protocols/protocol_list.hpp): nothing to edit here when a protocol is added.
#include <array>
#include <cmath>
#include <limits>

#include "simulator/bus_model.hpp"
#include "simulator/simulator.hpp"

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

double session_cycles_bound(const SimulatorOptions& options) noexcept {
    if (options.max_telegrams != 0 &&
        (options.cycles == 0 || options.max_telegrams < options.cycles))
        return static_cast<double>(options.max_telegrams);
    return static_cast<double>(options.cycles);
}

std::int64_t span_bound_of(double span_ns) noexcept {
    constexpr double kLargest = 9.2e18;  // below the largest int64 (9.22e18)
    return span_ns >= kLargest ? std::numeric_limits<std::int64_t>::max()
                               : static_cast<std::int64_t>(std::ceil(span_ns));
}

}  // namespace dpscope
