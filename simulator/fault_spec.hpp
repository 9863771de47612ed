// What the user asks the simulator for: the slaves on the bus (`--slave`) and the faults to inject
// (`--fault`), parsed and checked against each other; and, after the session, which of the faults
// given once were injected.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/code_tables.hpp"
#include "core/result.hpp"
#include "simulator/fault_kind.hpp"

namespace dpscope {

struct FaultSpec {
    FaultKind kind = FaultKind::FcsError;
    double rate = 0;                     // > 0: chance per cycle and slave, any number of times
    std::optional<std::uint64_t> cycle;  // once, at the first chance from this cycle on
    std::optional<std::uint8_t> slave;   // only this slave (default: one chosen by the seed)
};

// "KIND" (once, at a cycle chosen by the seed), "KIND@CYCLE", "KIND=RATE", each optionally
// followed by ":ADDR". KIND is one of the names of fault_kind_name ("bad_fcs" = "fcs_error").
// The error names the text and what is wrong with it; for an unknown kind, the kinds a session
// on `bus` takes (a kind of another bus is parsed: check_simulator_faults names its bus).
Result<FaultSpec> parse_fault_spec(std::string_view text, Protocol bus = Protocol::ProfibusDp);

// The spec written back as parse_fault_spec reads it ("fcs_error@4:3").
std::string describe_fault(const FaultSpec& spec);

struct SimulatedSlave {
    std::uint8_t address = 0;
    std::uint8_t ppo_type = 1;
    Dialect dialect = Dialect::Vlt;
    // DP-V1: Set_Prm enables it, and the master runs PROFIdrive parameter access (MSAC_C1,
    // slot 0, index 47) with the slave between the cyclic exchanges.
    bool dpv1 = false;
};

// "ADDR:PPO", "ADDR:PPO:DIALECT", each optionally followed by ":dpv1", e.g. "5:2",
// "7:1:profidrive", "8:3:dpv1" or "9:1:profidrive:dpv1".
Result<SimulatedSlave> parse_slave_spec(std::string_view text);

// PPO 1, 2 and 5 carry a PCV; PPO 3 and 4 do not.
bool has_parameter_channel(const SimulatedSlave& slave);

// An error when one of `faults` cannot be injected on `slaves` in a session of `cycles` cycles
// (0: no limit), saying why: a slave that is not simulated, a parameter-channel fault on a slave
// without a PCV, a DP-V1 fault on a slave without DP-V1, a cycle past the end.
Result<void> check_faults(const std::vector<FaultSpec>& faults,
                          const std::vector<SimulatedSlave>& slaves, std::uint64_t cycles);

// What the simulator injected, for tests and for the user (`simulate -v`).
struct Injection {
    FaultKind kind;
    std::uint64_t cycle;
    std::uint8_t slave;
    std::uint64_t telegram;  // 1-based number of the telegram it affected (first of them)
};

// Matches injections, as they happen, to the faults given once (no rate): each fault given once
// needs an injection of its own, of its kind, on its slave, from its cycle on. Keeps nothing per
// injection.
class OnceFaultCheck {
  public:
    explicit OnceFaultCheck(const std::vector<FaultSpec>& faults);
    void record(const Injection& injection);
    // The faults given once that no injection matched, described for the user.
    std::vector<std::string> missing() const;

  private:
    std::vector<FaultSpec> once_;
    std::vector<bool> found_;
};

}  // namespace dpscope
