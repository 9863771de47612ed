// A simulated PROFIBUS DP session with one master and PPO slaves: start-up (FDL_Status,
// Slave_Diag, Set_Prm, Chk_Cfg, Slave_Diag), then cyclic Data_Exchange with parameter requests
// and responses, token passing, gap polls and Global_Control, all timed at the bus baud rate.
// Seeded and reproducible: the same options give the same bytes on every platform.
//
// A slave given as DP-V1 also gets PROFIdrive parameter access over MSAC_C1 after the cyclic
// exchanges of each cycle (protocols/profibus/dpv1/dpv1_parameter_model.hpp).
//
// Faults can be injected: link-level (bad FCS, garbage bytes, a truncated telegram, a missing
// response, a retry) and every handshake fault the session tracker detects.
//
// The parts: simulator/fault_kind.hpp (the fault catalogue), simulator/fault_spec.hpp (what the
// user asks for: `--slave`, `--fault`), protocols/profibus/parameter_channel_model.hpp (the PCV of
// each slave, both ends), and here the DP bus model that runs them: timing at the baud rate, FDL
// telegrams, start-up, the cycle, token and gap polls, process data, and the link faults
// (simulator/simulator.cpp: the session, its clock, cycles and faults armed;
// protocols/profibus/dp_bus_model.cpp: the DP telegrams; simulator/session_span.cpp: its length).
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/telegram.hpp"
#include "protocols/fc/fc_bus_model.hpp"
#include "protocols/profibus/dpv1/dpv1_parameter_model.hpp"
#include "protocols/profibus/parameter_channel_model.hpp"
#include "protocols/profibus/ppo.hpp"
#include "protocols/vlt2000/vlt2000_bus_model.hpp"
#include "simulator/bus_model.hpp"
#include "simulator/fault_spec.hpp"

namespace dpscope {

struct SimulatorOptions {
    // The bus: PROFIBUS DP (slaves, start-up, Data_Exchange), the Danfoss FC protocol (drives
    // polled by a master, protocols/fc/fc_bus_model.hpp; no start-up, no token) or the VLT 2000
    // serial telegram (protocols/vlt2000/vlt2000_bus_model.hpp, likewise).
    Protocol bus = Protocol::ProfibusDp;
    std::uint64_t seed = 1;
    std::uint32_t baud = 1'500'000;  // 0: 1500000 on PROFIBUS, 9600 on an FC or VLT 2000 bus
    std::uint8_t master = 2;
    std::vector<SimulatedSlave> slaves;  // empty: 3:PPO1, 4:PPO2, 5:PPO5
    std::vector<SimulatedDrive> drives;  // FC bus; empty: default_drives()
    // VLT 2000 bus: the drives' addresses 1..99; empty: default_vlt2000_drives().
    std::vector<std::uint8_t> vlt2000_drives;
    // Data_Exchange cycles after start-up; 0: until max_telegrams (with neither, the session is
    // the start-up alone: it always ends).
    std::uint64_t cycles = 1000;
    std::uint64_t max_telegrams = 0;  // stop after this many telegrams (0: no limit)
    // Time of the first telegram. Before 1970 counts as 1970 (no capture format holds it);
    // times stop at the largest int64 (2262) rather than wrap: session_span_bound_ns tells
    // whether a session fits.
    std::int64_t start_time_ns = 1'704'067'200'000'000'000;  // 2024-01-01T00:00:00Z
    std::uint32_t cycle_us = 2000;                           // target bus cycle time
    std::uint32_t master_give_up_ms = 1500;  // the master abandons an unanswered request
    bool record_start_up = true;             // false: the capture begins with the first cycle
    std::vector<FaultSpec> faults;
    // A token ring: further active masters (not the DP master). The DP master passes the token
    // at the end of its cycle to the first, each holds it for token_hold_us (and now and then
    // gap-polls a free address) and passes it on; the last passes it back to the DP master. Every
    // master's token rotation is then max(cycle_us, the cycle's work). Empty: the DP master passes
    // the token to itself (the bytes of a session without a ring are unchanged).
    std::vector<std::uint8_t> ring_masters;
    std::uint32_t token_hold_us = 100;
};

// An error when `options` cannot inject one of its faults, saying why (a slave that is not
// simulated, a parameter-channel fault on a slave without a PCV, a cycle past the end).
Result<void> check_simulator_faults(const SimulatorOptions& options);

// At least the time from the first telegram to the last of the session `options` describes
// (whatever the seed and faults), saturated at the largest int64: the CLI checks with it that the
// session's end fits the capture's timestamps.
std::int64_t session_span_bound_ns(const SimulatorOptions& options);

// The faults given once (no rate) that were not injected, described for the user.
std::vector<std::string> faults_not_injected(const SimulatorOptions& options,
                                             const std::vector<Injection>& injections);

class Simulator {
  public:
    explicit Simulator(SimulatorOptions options);

    // The next telegram (or garbage record) and its time; false when the session is over.
    bool next(std::vector<std::uint8_t>& bytes, std::int64_t& time_ns);

    // The first kKeptInjections injections (all of them in a session of ordinary length), so
    // that memory stays flat however long the session; on_injection sees every one as it
    // happens, injection_count counts them all.
    static constexpr std::size_t kKeptInjections = 10'000;
    const std::vector<Injection>& injections() const noexcept { return injections_; }
    std::uint64_t injection_count() const noexcept { return injection_count_; }
    void on_injection(std::function<void(const Injection&)> callback) {
        on_injection_ = std::move(callback);
    }
    // The faults given once (no rate) that were not injected (so far), described for the user.
    std::vector<std::string> faults_not_injected() const { return once_faults_.missing(); }
    const std::vector<SimulatedSlave>& slaves() const noexcept { return options_.slaves; }
    std::uint64_t telegrams() const noexcept { return emitted_; }

  private:
    struct Slave {
        SimulatedSlave config;
        PpoLayout layout;
        std::uint16_t ident = 0;
        bool fcb = true;
        std::optional<ParameterChannelModel> channel;  // PPO 1, 2 and 5 (those with a PCV)
        std::optional<Dpv1ParameterModel> dpv1;        // a DP-V1 slave's parameter access
        // Process data.
        std::uint16_t reference = 0x2000;
        std::uint16_t actual = 0;
        // station_lost: cycles it stays silent still; then re-parameterised in the next cycle.
        std::uint64_t silent = 0;
        bool reparameterise = false;
    };
    class SlaveEnvironment;  // a slave's ChannelEnvironment: the session's random numbers etc.

    std::uint64_t random(std::uint64_t bound);  // 0 <= r < bound
    bool chance(double p);
    std::int64_t bit_ns(std::uint64_t bits) const;

    void advance(std::int64_t ns);  // now_ += ns, stopping at the largest int64
    void emit(std::vector<std::uint8_t> bytes, std::uint64_t gap_bits);
    void emit_after(std::vector<std::uint8_t> bytes, std::int64_t gap_ns);
    class ModelEnvironment;  // a bus model's view of the session
    void generate_start_up();
    void generate_cycle();
    void exchange(std::size_t index);
    void parameter_access(std::size_t index);  // one DP-V1 request and response, if any
    void arm_faults();
    // Bus-health faults: a slave that is silent (station_lost) or is parameterised anew.
    void silent_poll(std::size_t index);
    // What a GSD fault changes in the parameterisation (GsdIdentMismatch ... GsdUserPrmRange).
    enum class Reparameterisation : std::uint8_t {
        AsBefore,
        WrongIdent,
        FreePlaceAdded,
        ModulesTwice,
        UserByteAdded,
        UserByteOutOfRange
    };
    void parameterise_again(std::size_t index,
                            Reparameterisation change = Reparameterisation::AsBefore);
    void request_srd(Slave& slave, std::optional<std::uint8_t> dsap, std::vector<std::uint8_t> du);
    void answer_sd2(Slave& slave, std::optional<std::uint8_t> ssap, std::vector<std::uint8_t> du,
                    FdlStatus status = FdlStatus::DataLow);
    void answer_short_ack(Slave& slave);
    // The token ring after the DP master's cycle (options_.ring_masters not empty).
    void pass_token_ring();
    bool address_in_use(std::uint8_t address) const;
    // Takes a fault of this kind armed for this slave and records its injection; false when
    // none is armed. Asked for several kinds in every exchange and almost always false: the
    // test is inline, the taking is not.
    bool inject(FaultKind kind, std::size_t slave) {
        std::uint64_t& armed = armed_[static_cast<std::size_t>(kind) * slaves_.size() + slave];
        if (armed == 0) return false;
        take(kind, slave, armed);
        return true;
    }
    void take(FaultKind kind, std::size_t slave, std::uint64_t& armed);

    SimulatorOptions options_;
    // On an FC or VLT 2000 bus, one entry per drive with its address only (faults are armed per
    // entry).
    std::vector<Slave> slaves_;
    const SimulatedBus* bus_;            // the bus's record (simulator/bus_model.hpp)
    std::unique_ptr<BusModel> model_;    // a bus of drives: its model; null: PROFIBUS DP
    std::uint64_t character_bits_ = 11;  // the bus's: 8E1 (PROFIBUS, FC); 8N1 (VLT 2000): 10
    std::deque<std::pair<std::vector<std::uint8_t>, std::int64_t>> queue_;
    // Faults armed and not taken yet, per kind and slave: armed_[kind * slaves + slave].
    std::vector<std::uint64_t> armed_;
    std::vector<bool> scheduled_done_;
    // A time-out fault was injected: the session runs on past its cycles until then, so the
    // master's give-up (and the time-out a tracker judges) is in the capture. No faults are armed
    // in that tail, so it ends.
    std::int64_t hold_open_until_ = std::numeric_limits<std::int64_t>::min();
    std::vector<Injection> injections_;
    std::uint64_t injection_count_ = 0;
    std::function<void(const Injection&)> on_injection_;
    OnceFaultCheck once_faults_;
    std::uint64_t rng_state_;
    std::int64_t now_;
    std::uint64_t cycle_ = 0;
    std::uint64_t emitted_ = 0;
    std::uint64_t queued_ = 0;
    bool started_ = false;
    bool recording_ = true;
    std::uint8_t gap_address_;
    std::vector<std::uint8_t> ring_gap_addresses_;  // each further master's next gap address
    std::uint64_t recovering_ = 0;  // slaves silent or waiting to be parameterised anew
};

}  // namespace dpscope
