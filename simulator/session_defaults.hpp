// Private to the simulator (simulator/simulator.cpp, simulator/session_span.cpp): what a session
// takes when SimulatorOptions leaves it open, the slaves, the drives and the baud rates of the FC
// and VLT 2000 buses. Not for other users: the simulator's interface is simulator/simulator.hpp.
#pragma once

#include <cstdint>
#include <vector>

#include "simulator/simulator.hpp"

namespace dpscope::detail {

inline std::vector<SimulatedSlave> slaves_or_default(const SimulatorOptions& options) {
    if (!options.slaves.empty()) return options.slaves;
    return {{3, 1, Dialect::Vlt}, {4, 2, Dialect::Vlt}, {5, 5, Dialect::Vlt}};
}

inline std::vector<SimulatedDrive> drives_or_default(const SimulatorOptions& options) {
    return options.drives.empty() ? default_drives() : options.drives;
}

inline constexpr std::uint32_t kFcDefaultBaud = 9600;
inline constexpr std::uint32_t kVlt2000DefaultBaud = 9600;

inline std::vector<std::uint8_t> vlt2000_drives_or_default(const SimulatorOptions& options) {
    return options.vlt2000_drives.empty() ? default_vlt2000_drives() : options.vlt2000_drives;
}

}  // namespace dpscope::detail
