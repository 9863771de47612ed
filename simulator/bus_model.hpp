// What the simulated session (simulator/simulator.hpp) asks of each protocol's simulation, so that
// it picks a bus's model from a table instead of switching on the protocol. Each protocol fills in
// its record in its folder (`<name>_simulated_bus()` in protocols/<name>/*_bus_model.cpp); the
// table is made from the registration list (protocols/protocol_list.hpp;
// simulator/simulated_buses.cpp).
//
// PROFIBUS DP is the session's own traffic (start-up, Data_Exchange cycles, token ring: the
// Simulator with protocols/profibus/dp_bus_model.cpp); every other bus is a BusModel that the
// session runs cycle by cycle, handing it a BusEnvironment: its random numbers, faults and clock.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core/result.hpp"
#include "core/telegram.hpp"
#include "simulator/fault_kind.hpp"

namespace dpscope {

struct SimulatorOptions;  // simulator/simulator.hpp

// The bus as a bus model sees the session: random numbers, faults, the clock.
class BusEnvironment {
  public:
    virtual std::uint64_t random(std::uint64_t bound) = 0;  // 0 <= r < bound
    // Takes a fault of this kind armed for this drive (its index) and records its injection.
    virtual bool inject(FaultKind kind, std::size_t drive) = 0;
    // Leaves the line idle for gap_ns, then sends `bytes` (SimulatedBus::character_bits a
    // character at the baud rate).
    virtual void send(std::vector<std::uint8_t> bytes, std::int64_t gap_ns) = 0;
    virtual void wait(std::int64_t ns) = 0;  // the line stays idle

  protected:
    ~BusEnvironment() = default;
};

// A bus whose traffic a model makes in cycles: a master polling its drives.
class BusModel {
  public:
    virtual ~BusModel() = default;
    // One cycle of the bus: its number counts from 0.
    virtual void cycle(BusEnvironment& env, std::uint64_t number) = 0;
};

struct SimulatedBus {
    Protocol protocol;
    // Fills in what `options` leave open (the drives, the baud rate), makes the bus's model and
    // gives the addresses of its drives, in the order the model polls them (faults are armed per
    // drive). Null: the session makes the bus's traffic itself (PROFIBUS DP).
    std::unique_ptr<BusModel> (*make_model)(SimulatorOptions& options,
                                            std::vector<std::uint8_t>& drives) = nullptr;
    // An error when a fault of the options cannot be injected on this bus (a fault of another
    // bus, a station not simulated, a cycle past the end).
    Result<void> (*check_faults)(const SimulatorOptions& options) = nullptr;
    // At least the time a session of this bus takes, from its options alone.
    std::int64_t (*span_bound_ns)(const SimulatorOptions& options) = nullptr;
    // The faults its model injects (make_model's buses; the session judges PROFIBUS's itself).
    bool (*fault_applies)(FaultKind kind) noexcept = nullptr;
    // How long the session runs on after a fault of this kind was injected, so that what it
    // causes is in the capture (0: not at all); null: never.
    std::int64_t (*runs_on_ns)(FaultKind kind, const SimulatorOptions& options) = nullptr;
    // Bits a character takes on its line (start, data, parity, stop).
    std::uint64_t character_bits = 11;
};

// The record of a protocol.
const SimulatedBus& simulated_bus(Protocol protocol) noexcept;

// For the bounds of a session's length (SimulatedBus::span_bound_ns): the most cycles a session
// of `options` runs (--cycles, or fewer when -c stops it first: every cycle writes a telegram at
// least), and a length in nanoseconds as an int64, the largest one when it is beyond.
double session_cycles_bound(const SimulatorOptions& options) noexcept;
std::int64_t span_bound_of(double span_ns) noexcept;

// Each protocol's record, by the name its line in protocols/protocol_list.hpp gives it.
#define DPSCOPE_SIMULATED_BUS(Enum, name, Payload, member) \
    const SimulatedBus& name##_simulated_bus() noexcept;
DPSCOPE_PROTOCOLS(DPSCOPE_SIMULATED_BUS)
#undef DPSCOPE_SIMULATED_BUS

}  // namespace dpscope
