// Private to the simulator (simulator/simulator.cpp, simulator/session_span.cpp and the PROFIBUS
// DP bus model): the slaves a PROFIBUS DP session takes when SimulatorOptions leaves them open,
// and the length of such a session. Not for other users: the simulator's interface is
// simulator/simulator.hpp. (The serial buses' defaults are in their bus models.)
#pragma once

#include <cstdint>
#include <vector>

#include "simulator/simulator.hpp"

namespace dpscope::detail {

inline std::vector<SimulatedSlave> slaves_or_default(const SimulatorOptions& options) {
    if (!options.slaves.empty()) return options.slaves;
    return {{3, 1, Dialect::Vlt}, {4, 2, Dialect::Vlt}, {5, 5, Dialect::Vlt}};
}

// session_span_bound_ns of a PROFIBUS DP session (simulator/session_span.cpp).
std::int64_t profibus_session_span_bound_ns(const SimulatorOptions& options);

}  // namespace dpscope::detail
