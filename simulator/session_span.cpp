// session_span_bound_ns (simulator/simulator.hpp): at least the time a session takes, from its
// options alone; the bus's record says (SimulatedBus::span_bound_ns), and PROFIBUS DP's is here,
// with the session that makes its traffic.
#include <algorithm>

#include "simulator/bus_model.hpp"
#include "simulator/session_defaults.hpp"
#include "simulator/simulator.hpp"

namespace dpscope {

using detail::slaves_or_default;

std::int64_t session_span_bound_ns(const SimulatorOptions& options) {
    return simulated_bus(options.bus).span_bound_ns(options);
}

std::int64_t detail::profibus_session_span_bound_ns(const SimulatorOptions& options) {
    const double slaves = static_cast<double>(slaves_or_default(options).size());
    const double baud = options.baud == 0 ? 1'500'000.0 : static_cast<double>(options.baud);
    // A telegram (or garbage record) is at most 64 bytes of 11 bits, after a gap of at most
    // 100 bits; a slot time that expires is 100 bits.
    constexpr double kTelegramBits = 64 * 11 + 100;
    // Start-up: twelve telegrams per slave, then Global_Control and the token.
    const double start_up_bits = (slaves * 12 + 2) * kTelegramBits;
    // A cycle: per slave garbage, request, response and their repeats and two slot times; then a
    // gap poll and its slot time, Global_Control and the token. At least --cycle-us.
    double cycle_bits = slaves * (5 * kTelegramBits + 200) + 3 * kTelegramBits + 100;
    // A DP-V1 slave adds a DP-V1 request and response per cycle, each at most 255 bytes.
    for (const SimulatedSlave& slave : slaves_or_default(options))
        if (slave.dpv1) cycle_bits += 2 * (255 * 11 + 100);
    // Bus-health faults: a slave parameterised anew (ten telegrams more) or a second repeat; a
    // token ring: per further master two tokens, a gap poll, its slot time and the hold.
    bool health_faults = false;
    for (const FaultSpec& spec : options.faults)
        health_faults = health_faults || spec.kind >= FaultKind::StationLost;
    if (health_faults) cycle_bits += slaves * 10 * kTelegramBits;
    const double ring = static_cast<double>(options.ring_masters.size());
    cycle_bits += ring * (3 * kTelegramBits + 100);
    double cycle_ns =
        std::max(static_cast<double>(options.cycle_us) * 1e3, cycle_bits * 1e9 / baud);
    cycle_ns += ring * std::max(static_cast<double>(options.token_hold_us) * 1e3, 40 * 1e9 / baud);
    // Every cycle writes one telegram at least (the token).
    const double cycles = session_cycles_bound(options);
    // After a time-out fault the session runs on until the master has given up, plus ten cycles.
    // A slave lost (station_lost) in the last cycle is silent, then parameterised anew, after it.
    const double tail_ns =
        static_cast<double>(options.master_give_up_ms) * 1e6 +
        static_cast<double>(options.cycle_us) * 1e4 + cycle_ns +
        (health_faults ? static_cast<double>(kStationLostCycles + 1) * cycle_ns : 0.0);
    const double span = start_up_bits * 1e9 / baud + cycles * cycle_ns + tail_ns;
    return span_bound_of(span);
}

}  // namespace dpscope
