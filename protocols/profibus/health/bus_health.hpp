// Bus health of a PROFIBUS segment (FDL/DP link-layer statistics): the live list of stations,
// per-slave and per-master counters, capture-wide rates, and a verdict (good / weak / bad) per
// station and for the segment from documented thresholds
// (protocols/profibus/health/health_thresholds.hpp).
//
// One component, fed every PROFIBUS telegram in capture order (intact or damaged), beside the
// session tracker and independent of it: it keeps its own view of the request waiting for its
// reply and of each link's frame count bit. No I/O; memory is bounded (128 stations, at most
// kMaxStateChanges state changes per station, fixed-size histograms and time series).
// The rules, in full: docs/bus-health.md.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/log_histogram.hpp"
#include "core/telegram.hpp"
#include "core/time.hpp"
#include "protocols/profibus/health/health_thresholds.hpp"

namespace dpscope {

// What a station is on the bus.
enum class StationRole : std::uint8_t {
    Unknown,  // addressed by a master but never heard, and nothing says which it is
    Master,   // sends tokens or requests, receives the token, or says so in an FDL_Status answer
    Slave,    // answers requests and sends none
};
// "unknown", "master", "slave".
std::string_view station_role_name(StationRole role) noexcept;

// A station's state at a moment of the capture.
enum class StationState : std::uint8_t {
    Unknown,       // listed (addressed, or heard only answering FDL_Status) with nothing more known
    Active,        // a master using the token
    Configuring,   // a slave answering Set_Prm / Chk_Cfg: being parameterised and configured
    DataExchange,  // a slave answering Data_Exchange
    DiagnosisOnly,  // a slave answering only Slave_Diag (not, or no longer, in data exchange)
    Lost,           // no answer for `lost_cycles` consecutive cycles (a master: token not taken)
};
// "unknown", "active", "configuring", "data exchange", "diagnosis only", "lost".
std::string_view station_state_name(StationState state) noexcept;
// The same as identifiers for JSON and CSV: "unknown", "active", "configuring",
// "data_exchange", "diagnosis_only", "lost".
std::string_view station_state_id(StationState state) noexcept;

// One change of a station's state. `returned`: the station came back from Lost with it.
struct StateChange {
    std::int64_t time_ns = kNoTime;
    std::uint64_t frame = 0;
    StationState state = StationState::Unknown;
    bool returned = false;
};

// Durations in nanoseconds: exact count, minimum, maximum and mean; p95 from a LogHistogram
// (within 1.6 %).
class DurationStats {
  public:
    void add(std::int64_t ns) {
        if (ns < 0) return;
        histogram_.add(static_cast<std::uint64_t>(ns));
        sum_ += static_cast<double>(ns);
    }
    std::uint64_t count() const noexcept { return histogram_.count(); }
    std::int64_t min() const noexcept { return static_cast<std::int64_t>(histogram_.min()); }
    std::int64_t max() const noexcept { return static_cast<std::int64_t>(histogram_.max()); }
    double mean() const noexcept {
        return count() == 0 ? 0.0 : sum_ / static_cast<double>(count());
    }
    std::int64_t p95() const { return static_cast<std::int64_t>(histogram_.percentile(95)); }

  private:
    LogHistogram histogram_;
    double sum_ = 0;
};

// A duration over the capture, for plotting: at most kMaxPoints points, each summarising the
// samples of a time span (minimum, mean, maximum). When full, neighbouring points are merged
// pairwise and every point then spans twice the time: memory stays fixed, the whole capture
// stays covered.
class TimeSeries {
  public:
    static constexpr std::size_t kMaxPoints = 512;
    struct Point {
        std::int64_t first_ns = kNoTime;  // time of the first sample in the span
        std::int64_t last_ns = kNoTime;   // time of the last
        std::int64_t min_ns = 0;
        std::int64_t max_ns = 0;
        double sum_ns = 0;
        std::uint64_t count = 0;
        double mean_ns() const noexcept {
            return count == 0 ? 0.0 : sum_ns / static_cast<double>(count);
        }
    };
    // A sample `value_ns` taken at `time_ns` (samples come in time order). Inline: most samples
    // join the last point; a new point is made out of line.
    void add(std::int64_t time_ns, std::int64_t value_ns) {
        if (!points_.empty() && points_.back().count < per_point_) [[likely]] {
            Point& p = points_.back();
            p.last_ns = time_ns;
            p.min_ns = std::min(p.min_ns, value_ns);
            p.max_ns = std::max(p.max_ns, value_ns);
            p.sum_ns += static_cast<double>(value_ns);
            ++p.count;
            return;
        }
        add_point(time_ns, value_ns);
    }
    std::span<const Point> points() const noexcept { return points_; }
    // Samples each point gathers before the next one starts (doubles at each merge).
    std::uint64_t samples_per_point() const noexcept { return per_point_; }

  private:
    // add() when the last point is full (or there is none): a new one, after merging the points
    // pairwise when kMaxPoints are there.
    void add_point(std::int64_t time_ns, std::int64_t value_ns);

    std::vector<Point> points_;
    std::uint64_t per_point_ = 1;
};

// Kinds of illegal answer.
enum class IllegalAnswer : std::uint8_t {
    NotAsked,   // a response from (or to) a station that was not asked: no request waiting for
                // a reply, or the waiting request was for another station
    WrongKind,  // a response of the wrong kind: data to an SDA request, an SDA acknowledgement
                // (status OK, no data) to an SRD request, a data response to FDL_Status
    ShortAck,   // a short acknowledge (SC) or SD1 without data where data was due: to Slave_Diag,
                // Get_Cfg, Rd_Inp, Rd_Outp, or to Data_Exchange from a slave that answers it with
                // data otherwise
    Count
};
inline constexpr std::size_t kIllegalAnswerCount = static_cast<std::size_t>(IllegalAnswer::Count);
// "not_asked", "wrong_kind", "short_ack".
std::string_view illegal_answer_id(IllegalAnswer kind) noexcept;

// The Slave_Diag bits that say a slave has a fault; a diagnosis answer with any of them counts
// as one that showed a fault (and each bit is counted).
enum class DiagFault : std::uint8_t {
    StationNotReady,  // station status 1 bit 1
    CfgFault,         // station status 1 bit 2
    ExtDiag,          // station status 1 bit 3
    PrmFault,         // station status 1 bit 6
    StatDiag,         // station status 2 bit 1
    Count
};
inline constexpr std::size_t kDiagFaultCount = static_cast<std::size_t>(DiagFault::Count);
// "Station_Not_Ready", "Cfg_Fault", "Ext_Diag", "Prm_Fault", "Stat_Diag" (the standard's names).
std::string_view diag_fault_name(DiagFault fault) noexcept;

// The negative FDL answers counted per slave, by response status (FC low nibble).
enum class NegativeAnswer : std::uint8_t {
    UE,   // 0x1 user error
    RR,   // 0x2 no resources
    RS,   // 0x3 no service (SAP not activated)
    NR,   // 0x9 no response data
    DH,   // 0xA data high (diagnosis pending)
    RDH,  // 0xD not received, data high
    Count
};
inline constexpr std::size_t kNegativeAnswerCount = static_cast<std::size_t>(NegativeAnswer::Count);
// "UE", "RR", "RS", "NR", "DH", "RDH".
std::string_view negative_answer_name(NegativeAnswer kind) noexcept;

// Why a verdict is weak or bad: a threshold, the value measured, and the verdict it gave.
struct VerdictReason {
    HealthThreshold threshold = HealthThreshold::LostCycles;
    double measured = 0;
    Verdict verdict = Verdict::Good;
};
// "2 lost events (bad from 1)", "0.25 % repeats (weak above 0.1 %)": the measured value, what
// it is, and the limit it crossed, in the threshold's unit.
std::string describe_reason(const VerdictReason& reason, const HealthThresholds& thresholds);

struct Judgement {
    Verdict verdict = Verdict::Good;
    std::vector<VerdictReason> reasons;  // the worst first; empty for good
};

// One station of the live list with its counters. Slave counters are those of the station as
// the one asked (requests addressed to it, answers it gave); a master's own figures are in
// MasterHealth.
struct StationHealth {
    std::uint8_t address = 0;
    StationRole role = StationRole::Unknown;
    StationState state = StationState::Unknown;
    std::int64_t first_seen_ns = kNoTime;  // first telegram from or (listing) to it
    std::int64_t last_seen_ns = kNoTime;   // last telegram it sent (first_seen_ns if none)
    std::uint64_t first_frame = 0;
    std::uint64_t last_frame = 0;
    std::uint64_t telegrams_sent = 0;  // telegrams it sent, short acknowledges included

    // As the station asked:
    std::uint64_t requests = 0;     // requests addressed to it (repeats included, tokens not)
    std::uint64_t answers = 0;      // responses it gave (short acknowledges included)
    std::uint64_t no_answers = 0;   // requests that expected a reply and got none
    std::uint64_t replies_due = 0;  // requests that expected a reply (the no-answer rate's base)
    std::uint64_t repeats = 0;      // FDL retries: a request repeated with the same FCB
    std::uint64_t max_repeats_per_cycle = 0;  // most repeats of one request
    std::uint64_t lost_events = 0;            // times it became Lost
    std::uint64_t returns = 0;                // times it came back from Lost
    std::uint64_t resyncs = 0;        // left data exchange and went through Set_Prm/Chk_Cfg again
    std::uint64_t diag_requests = 0;  // Slave_Diag requests
    std::uint64_t diag_answers = 0;   // Slave_Diag answers with the diagnosis data
    std::uint64_t diag_faults = 0;    // of those, the ones with a fault bit (DiagFault)
    std::array<std::uint64_t, kDiagFaultCount> diag_fault_bits{};
    std::array<std::uint64_t, kIllegalAnswerCount> illegal_answers{};
    std::array<std::uint64_t, kNegativeAnswerCount> negative_answers{};
    // Damaged telegrams (bad FCS, malformed) on its link: its own, requests to it, and damaged
    // telegrams in the place of its answer.
    std::uint64_t fcs_errors = 0;

    std::vector<StateChange> timeline;  // the first kMaxStateChanges changes of state
    std::uint64_t state_changes = 0;    // all of them (timeline.size() when none was dropped)

    Judgement judgement;

    std::uint64_t illegal_answers_total() const noexcept {
        std::uint64_t n = 0;
        for (std::uint64_t c : illegal_answers)
            n += c;
        return n;
    }
    std::uint64_t negative_answers_total() const noexcept {
        std::uint64_t n = 0;
        for (std::uint64_t c : negative_answers)
            n += c;
        return n;
    }
    // Telegrams on its link: requests to it and its answers (the base of the FCS error rate).
    std::uint64_t link_telegrams() const noexcept { return requests + answers; }
};

// A master's figures.
struct MasterHealth {
    std::uint8_t address = 0;
    std::uint64_t tokens_received = 0;   // SD4 addressed to it
    std::uint64_t tokens_passed = 0;     // SD4 it sent
    std::uint64_t tokens_not_taken = 0;  // tokens passed to it after which it sent nothing
    std::uint64_t requests = 0;          // requests it sent (tokens not counted)
    std::uint64_t slaves_polled = 0;     // distinct stations it sent Data_Exchange requests to
    // Token rotation: the time between two tokens addressed to it.
    DurationStats token_rotation;
    TimeSeries token_rotation_series;
    // Bus cycle of its Data_Exchange polling: the time between two starts of its poll cycle (a
    // cycle starts when it polls a slave it already polled in the current cycle; retries are not
    // polls).
    DurationStats cycle;
    TimeSeries cycle_series;
    // Cycle-to-cycle jitter: the mean absolute difference between consecutive cycle times.
    double cycle_jitter_ns = 0;

    Judgement judgement;
};

// The capture as a whole.
struct SegmentHealth {
    std::uint64_t telegrams = 0;
    std::uint64_t bytes = 0;                 // bytes in telegrams
    std::uint64_t damaged = 0;               // bad FCS or malformed
    std::uint64_t unattributed_damaged = 0;  // of those, no station could be named
    std::uint64_t unasked_short_acks = 0;    // short acknowledges with no request waiting
    std::int64_t first_ns = kNoTime;         // first telegram's start
    std::int64_t end_ns = kNoTime;           // last telegram's end (its start when no baud)
    std::uint32_t baud = 0;                  // the line rate (0: not known)
    std::uint32_t character_bits = 11;       // UART character on PROFIBUS: 8E1 = 11 bits
    double busy_ns = 0;                      // time the line carried telegrams (needs baud)

    // A segment with no telegram is not judged: its verdict stays good, but nothing was seen to
    // judge, and every format says "not judged (no telegrams)" instead (docs/decisions.md, "An
    // empty capture").
    bool judged() const noexcept { return telegrams > 0; }
    bool has_time() const noexcept { return first_ns != kNoTime && end_ns != kNoTime; }
    double duration_s() const noexcept {
        return has_time() ? static_cast<double>(end_ns - first_ns) / 1e9 : 0.0;
    }
    // 0 when the capture has no times or lasts no time.
    double telegrams_per_second() const noexcept {
        double d = duration_s();
        return d > 0 ? static_cast<double>(telegrams) / d : 0.0;
    }
    // Bus load in % of the line rate; negative when the baud rate or the times are not known.
    double load_percent() const noexcept {
        double d = duration_s();
        if (baud == 0 || d <= 0) return -1.0;
        double load = busy_ns / (d * 1e9) * 100.0;
        return load > 100.0 ? 100.0 : load;
    }
    // Idle time in seconds; negative when not known.
    double idle_s() const noexcept {
        double d = duration_s();
        if (baud == 0 || d <= 0) return -1.0;
        double idle = d - busy_ns / 1e9;
        return idle < 0 ? 0.0 : idle;
    }

    Judgement judgement;
};

// What the statistics say: what renderers read.
struct BusHealth {
    HealthThresholds thresholds;
    SegmentHealth segment;
    std::vector<StationHealth> stations;  // the live list, by address
    std::vector<MasterHealth> masters;    // by address
};

// A change worth an alarm or a live line: a station lost or returned, a verdict turning bad.
enum class HealthEventKind : std::uint8_t { StationLost, StationReturned, VerdictBad, Count };
// "station_lost", "station_returned", "verdict_bad".
std::string_view health_event_name(HealthEventKind kind) noexcept;

struct HealthEvent {
    HealthEventKind kind = HealthEventKind::StationLost;
    std::uint8_t address = 0;  // VerdictBad for the segment: kSegmentAddress
    std::int64_t time_ns = kNoTime;
    std::uint64_t frame = 0;
    StationRole role = StationRole::Unknown;
};
inline constexpr std::uint8_t kSegmentAddress = 0xFF;

class BusHealthTrackerImpl;

struct BusHealthOptions {
    HealthThresholds thresholds;
    std::uint32_t baud = 0;  // line rate for bus load and idle time (0: unknown)
    std::uint32_t character_bits = 11;
    // The steady poll's short path (protocols/profibus/health/bus_health_state.hpp); false takes
    // every telegram through the full rules. The figures are the same either way: the tests
    // compare the two.
    bool steady_path = true;
};

class BusHealthTracker {
  public:
    static constexpr std::size_t kMaxStateChanges = 4096;

    explicit BusHealthTracker(BusHealthOptions options = {});
    ~BusHealthTracker();
    BusHealthTracker(const BusHealthTracker&) = delete;
    BusHealthTracker& operator=(const BusHealthTracker&) = delete;

    // Feeds the next PROFIBUS telegram in capture order (telegrams of another protocol are
    // ignored). Returns the events it caused (lost, returned); valid until the next call.
    std::span<const HealthEvent> observe(const DecodedTelegram& t);
    // Judges every station, every master and the segment now (cheap: call it at will, e.g. for a
    // live table). Returns the verdicts that turned bad since the last judge(); valid until the
    // next call to observe() or judge().
    std::span<const HealthEvent> judge() { return judge(true); }
    // The same verdicts without copying the stations' and masters' figures out: health()'s
    // stations and masters stay as of the last judge() or finish() (its segment is live as
    // always, its judgement this one's). For judging often (offline, every quarter second of
    // capture time) when only the verdicts that turned bad are wanted.
    std::span<const HealthEvent> judge_verdicts() { return judge(false); }
    // The end of the capture at `end_ns` (a live capture's stop; default: the last telegram's
    // end): the open cycles are closed and everything judged.
    void finish(std::int64_t end_ns = kNoTime);

    // The statistics so far (judged as of the last judge() or finish()).
    const BusHealth& health() const noexcept { return health_; }
    const BusHealthOptions& options() const noexcept { return options_; }
    // Telegrams taken by the steady path (BusHealthOptions::steady_path; for its tests and
    // profiles: the figures do not depend on it).
    std::uint64_t steady_telegrams() const noexcept;

  private:
    friend class BusHealthTrackerImpl;
    struct State;
    // `publish`: copy each station's and master's figures into health_.
    std::span<const HealthEvent> judge(bool publish);
    BusHealthOptions options_;
    BusHealth health_;
    std::unique_ptr<State> state_;
};

}  // namespace dpscope
