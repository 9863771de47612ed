// A simulated PROFIBUS DP session with one master and PPO slaves: start-up (FDL_Status,
// Slave_Diag, Set_Prm, Chk_Cfg, Slave_Diag), then cyclic Data_Exchange with parameter requests
// and responses, token passing, gap polls and Global_Control, all timed at the bus baud rate.
// Seeded and reproducible: the same options give the same bytes on every platform.
//
// Faults can be injected: link-level (bad FCS, garbage bytes, a truncated telegram, a missing
// response, a retry) and every handshake fault the session tracker detects.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "decoder/code_tables.hpp"
#include "decoder/ppo.hpp"

namespace dpscope {

enum class FaultKind : std::uint8_t {
    FcsError,                   // one telegram's FCS is wrong
    Garbage,                    // junk bytes between telegrams
    MalformedTelegram,          // one telegram cut short
    StackedRequest,             // the master changes its request before the answer
    OrphanResponse,             // the slave answers although nothing was asked
    MismatchedResponse,         // the answer carries another PNU
    UnexpectedResponseType,     // the answer's code does not fit the request
    ResponseTimeout,            // the slave never answers; the master gives up later
    RequestRejected,            // RC 7 with an error number
    NoAuthority,                // RC 8 to a change request
    SpontaneousMessage,         // RC 9/10 with an SPM toggle, acknowledged by the master
    SpontaneousUnacknowledged,  // the same, acknowledged only after the time-out
    SpmViolation,               // the master toggles SPM with nothing pending
    ConfigMismatch,             // one Data_Exchange telegram longer than configured
    UnknownCode,                // one response with a code the dialect does not define
    FdlRetry,                   // a response lost and the request repeated with the same FCB
    FdlNoResponse,              // a response lost, no retry
    Count
};

std::string_view fault_kind_name(FaultKind kind);
std::optional<FaultKind> fault_kind_from_name(std::string_view name);

struct FaultSpec {
    FaultKind kind = FaultKind::FcsError;
    double rate = 0;                     // > 0: chance per cycle and slave, any number of times
    std::optional<std::uint64_t> cycle;  // once, at the first chance from this cycle on
    std::optional<std::uint8_t> slave;   // only this slave (default: one chosen by the seed)
};

// "KIND" (once, at a cycle chosen by the seed), "KIND@CYCLE", "KIND=RATE", each optionally
// followed by ":ADDR". KIND is one of the names of fault_kind_name ("bad_fcs" = "fcs_error").
std::optional<FaultSpec> parse_fault_spec(std::string_view text, std::string& error);

struct SimulatedSlave {
    std::uint8_t address = 0;
    std::uint8_t ppo_type = 1;
    Dialect dialect = Dialect::Vlt;
};

// Faults that act on the parameter channel need a slave with a PCV (PPO 1, 2 or 5).
bool fault_needs_parameter_channel(FaultKind kind) noexcept;

// "ADDR:PPO" or "ADDR:PPO:DIALECT", e.g. "5:2" or "7:1:profidrive".
std::optional<SimulatedSlave> parse_slave_spec(std::string_view text, std::string& error);

struct SimulatorOptions {
    std::uint64_t seed = 1;
    std::uint32_t baud = 1'500'000;
    std::uint8_t master = 2;
    std::vector<SimulatedSlave> slaves;  // empty: 3:PPO1, 4:PPO2, 5:PPO5
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
};

// What the simulator injected, for tests and for the user (`simulate -v`).
struct Injection {
    FaultKind kind;
    std::uint64_t cycle;
    std::uint8_t slave;
    std::uint64_t telegram;  // 1-based number of the telegram it affected (first of them)
};

// Why `options` cannot inject one of its faults (a slave that is not simulated, a parameter-
// channel fault on a slave without a PCV, a cycle past the end), or "" when each can be.
std::string check_simulator_faults(const SimulatorOptions& options);

// At least the time from the first telegram to the last of the session `options` describes
// (whatever the seed and faults), saturated at the largest int64: the CLI checks with it that the
// session's end fits the capture's timestamps.
std::int64_t session_span_bound_ns(const SimulatorOptions& options);

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
    struct Request {
        std::uint8_t rc = 0;
        std::uint16_t pnu = 0;
        std::uint8_t ind = 0;
        std::uint32_t pva = 0;
        bool operator==(const Request&) const = default;
    };

    struct Parameter {
        std::uint16_t pnu;
        bool dword;
        std::uint32_t value;
        bool array;
    };

    struct Slave {
        SimulatedSlave config;
        PpoLayout layout;
        std::uint16_t ident = 0;
        bool fcb = true;
        std::vector<Parameter> parameters;
        // Master side of the parameter channel.
        bool master_busy = false;  // a request is out and not answered yet
        Request master_request;
        Request last_request;
        Request next_request;
        bool has_next = false;
        std::int64_t request_time = 0;
        std::uint32_t idle_cycles = 0;
        bool master_spm = false;
        bool master_acked_slave_spm = false;  // the slave SPM of the last message acknowledged
        std::uint64_t request_cycle = 0;      // the cycle the current request was first sent
        bool master_saw_response = false;     // the master's view of the last response
        Request master_seen_answer;
        bool master_seen_spm = false;
        // Slave side: it sees the master's PCV one cycle late.
        bool seen_valid = false;
        Request seen;
        bool seen_spm = false;
        bool working = false;  // has a request it has not answered yet
        Request current;
        std::uint64_t ready_cycle = 0;
        Request answer;                  // what the slave's PCV says now
        bool answer_mismatched = false;  // `answer` is an injected wrong-PNU answer
        Request out;                     // what it sends this cycle
        bool slave_spm = false;
        bool spontaneous_active = false;
        bool spontaneous_late_ack = false;
        bool spontaneous_master_spm = false;  // the master's SPM when the message started
        std::int64_t spontaneous_time = 0;
        Request spontaneous;
        // Process data.
        std::uint16_t reference = 0x2000;
        std::uint16_t actual = 0;
    };

    std::uint64_t random(std::uint64_t bound);  // 0 <= r < bound
    bool chance(double p);
    std::int64_t bit_ns(std::uint64_t bits) const;

    void advance(std::int64_t ns);  // now_ += ns, stopping at the largest int64
    void emit(std::vector<std::uint8_t> bytes, std::uint64_t gap_bits);
    void generate_start_up();
    void generate_cycle();
    void exchange(std::size_t index);
    void arm_faults();
    bool take_fault(FaultKind kind, std::size_t slave);
    void record_injection(FaultKind kind, std::size_t slave);

    void master_step(Slave& slave);
    Request choose_request(Slave& slave);
    void slave_step(Slave& slave, std::size_t index);
    Request compute_answer(Slave& slave, std::size_t index);
    Parameter* find_parameter(Slave& slave, std::uint16_t pnu);

    SimulatorOptions options_;
    std::vector<Slave> slaves_;
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
};

}  // namespace dpscope
