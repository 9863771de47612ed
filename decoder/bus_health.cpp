#include "decoder/bus_health.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bitset>
#include <cmath>
#include <memory>

#include "decoder/dp_service.hpp"

namespace dpscope {

std::string_view station_role_name(StationRole role) noexcept {
    switch (role) {
        case StationRole::Master: return "master";
        case StationRole::Slave: return "slave";
        case StationRole::Unknown: break;
    }
    return "unknown";
}

std::string_view station_state_name(StationState state) noexcept {
    switch (state) {
        case StationState::Active: return "active";
        case StationState::Configuring: return "configuring";
        case StationState::DataExchange: return "data exchange";
        case StationState::DiagnosisOnly: return "diagnosis only";
        case StationState::Lost: return "lost";
        case StationState::Unknown: break;
    }
    return "unknown";
}

std::string_view station_state_id(StationState state) noexcept {
    switch (state) {
        case StationState::Active: return "active";
        case StationState::Configuring: return "configuring";
        case StationState::DataExchange: return "data_exchange";
        case StationState::DiagnosisOnly: return "diagnosis_only";
        case StationState::Lost: return "lost";
        case StationState::Unknown: break;
    }
    return "unknown";
}

std::string_view illegal_answer_id(IllegalAnswer kind) noexcept {
    switch (kind) {
        case IllegalAnswer::NotAsked: return "not_asked";
        case IllegalAnswer::WrongKind: return "wrong_kind";
        case IllegalAnswer::ShortAck:
        case IllegalAnswer::Count: break;
    }
    return "short_ack";
}

std::string_view diag_fault_name(DiagFault fault) noexcept {
    switch (fault) {
        case DiagFault::StationNotReady: return "Station_Not_Ready";
        case DiagFault::CfgFault: return "Cfg_Fault";
        case DiagFault::ExtDiag: return "Ext_Diag";
        case DiagFault::PrmFault: return "Prm_Fault";
        case DiagFault::StatDiag:
        case DiagFault::Count: break;
    }
    return "Stat_Diag";
}

std::string_view negative_answer_name(NegativeAnswer kind) noexcept {
    switch (kind) {
        case NegativeAnswer::UE: return "UE";
        case NegativeAnswer::RR: return "RR";
        case NegativeAnswer::RS: return "RS";
        case NegativeAnswer::NR: return "NR";
        case NegativeAnswer::DH: return "DH";
        case NegativeAnswer::RDH:
        case NegativeAnswer::Count: break;
    }
    return "RDH";
}

std::string_view health_event_name(HealthEventKind kind) noexcept {
    switch (kind) {
        case HealthEventKind::StationLost: return "station_lost";
        case HealthEventKind::StationReturned: return "station_returned";
        case HealthEventKind::VerdictBad:
        case HealthEventKind::Count: break;
    }
    return "verdict_bad";
}

std::string describe_reason(const VerdictReason& reason, const HealthThresholds& thresholds) {
    const HealthThresholdRow& row = health_threshold_row(reason.threshold);
    const double limit = thresholds.get(reason.threshold);
    const std::string unit = row.unit.empty() ? "" : fmt::format(" {}", row.unit);
    const std::string_view what = row.name;
    const std::string_view comparison =
        row.comparison == ThresholdComparison::From ? "from" : "above";
    // Counts as whole numbers, rates to three significant digits (0.758 %, 2.99 %, 12.5 %).
    const auto figure = [](double value) {
        if (value == std::floor(value) && value < 1e15) return fmt::format("{:.0f}", value);
        return value >= 100 ? fmt::format("{:.1f}", value) : fmt::format("{:.3g}", value);
    };
    return fmt::format("{}: {}{} ({} {} {}{})", what, figure(reason.measured), unit,
                       verdict_name(reason.verdict), comparison, figure(limit), unit);
}

void TimeSeries::add(std::int64_t time_ns, std::int64_t value_ns) {
    if (!points_.empty() && points_.back().count < per_point_) {
        Point& p = points_.back();
        p.last_ns = time_ns;
        p.min_ns = std::min(p.min_ns, value_ns);
        p.max_ns = std::max(p.max_ns, value_ns);
        p.sum_ns += static_cast<double>(value_ns);
        ++p.count;
        return;
    }
    if (points_.size() == kMaxPoints) {
        // Merge neighbours pairwise: half the points, each spanning twice the samples.
        std::size_t out = 0;
        for (std::size_t i = 0; i + 1 < points_.size(); i += 2) {
            Point merged = points_[i];
            const Point& next = points_[i + 1];
            merged.last_ns = next.last_ns;
            merged.min_ns = std::min(merged.min_ns, next.min_ns);
            merged.max_ns = std::max(merged.max_ns, next.max_ns);
            merged.sum_ns += next.sum_ns;
            merged.count += next.count;
            points_[out++] = merged;
        }
        points_.resize(out);
        per_point_ *= 2;
        add(time_ns, value_ns);
        return;
    }
    if (points_.capacity() < kMaxPoints) points_.reserve(kMaxPoints);
    points_.push_back(
        Point{time_ns, time_ns, value_ns, value_ns, static_cast<double>(value_ns), 1});
}

namespace {

bool is_damaged(const DecodedTelegram& t) {
    if (t.dp.fdl.fcs_ok && t.problems().empty()) return false;
    if (!t.dp.fdl.fcs_ok) return true;
    for (const Problem& p : t.problems())
        if (problem_severity(p.kind) == Severity::Error) return true;
    return false;
}

bool is_data_frame(FrameType type) { return type == FrameType::Sd2 || type == FrameType::Sd3; }

bool status_is_refusal(std::uint8_t status) {
    return status == static_cast<std::uint8_t>(FdlStatus::UserError) ||
           status == static_cast<std::uint8_t>(FdlStatus::NoResource) ||
           status == static_cast<std::uint8_t>(FdlStatus::NoService);
}

// The SRD statuses that carry (or stand for) response data: DL, NR, DH, RDL, RDH.
bool status_is_srd_data(std::uint8_t status) {
    switch (static_cast<FdlStatus>(status)) {
        case FdlStatus::DataLow:
        case FdlStatus::NoResponseData:
        case FdlStatus::DataHigh:
        case FdlStatus::NotReceivedDataLow:
        case FdlStatus::NotReceivedDataHigh: return true;
        default: return false;
    }
}

int negative_index(std::uint8_t status) {
    switch (static_cast<FdlStatus>(status)) {
        case FdlStatus::UserError: return static_cast<int>(NegativeAnswer::UE);
        case FdlStatus::NoResource: return static_cast<int>(NegativeAnswer::RR);
        case FdlStatus::NoService: return static_cast<int>(NegativeAnswer::RS);
        case FdlStatus::NoResponseData: return static_cast<int>(NegativeAnswer::NR);
        case FdlStatus::DataHigh: return static_cast<int>(NegativeAnswer::DH);
        case FdlStatus::NotReceivedDataHigh: return static_cast<int>(NegativeAnswer::RDH);
        default: return -1;
    }
}

bool data_always_due(Service service) {
    return service == Service::SlaveDiag || service == Service::GetCfg ||
           service == Service::RdInp || service == Service::RdOutp;
}

// Judges a count against a "from" threshold (0: off).
void judge_from(std::vector<VerdictReason>& reasons, const HealthThresholds& limits,
                HealthThreshold kind, double measured) {
    const double limit = limits.get(kind);
    if (limit > 0 && measured >= limit)
        reasons.push_back({kind, measured, health_threshold_row(kind).verdict});
}

// Judges a rate against a weak and a bad "above" threshold (the worse one only).
void judge_rate(std::vector<VerdictReason>& reasons, const HealthThresholds& limits,
                HealthThreshold weak, HealthThreshold bad, double count, double base) {
    if (base <= 0) return;
    const double percent = count / base * 100.0;
    if (percent > limits.get(bad))
        reasons.push_back({bad, percent, Verdict::Bad});
    else if (percent > limits.get(weak))
        reasons.push_back({weak, percent, Verdict::Weak});
}

void conclude(Judgement& judgement) {
    std::stable_sort(
        judgement.reasons.begin(), judgement.reasons.end(),
        [](const VerdictReason& a, const VerdictReason& b) { return a.verdict > b.verdict; });
    judgement.verdict = Verdict::Good;
    for (const VerdictReason& r : judgement.reasons)
        judgement.verdict = worse(judgement.verdict, r.verdict);
}

// Per-address entries (a station's Slot, a master's Master), each made on first use with its
// address: a capture names a handful of the 128 addresses, and all 128 made up front (about
// 100 KB) cost more than tracking a short capture. Iterating visits the entries made so far, in
// address order.
template <class Entry>
class StationTable {
  public:
    Entry& operator[](std::size_t address) {
        std::unique_ptr<Entry>& entry = entries_[address];
        if (!entry) {
            entry = std::make_unique<Entry>();
            entry->health.address = static_cast<std::uint8_t>(address);
        }
        return *entry;
    }

    class iterator {
      public:
        using Slots = std::array<std::unique_ptr<Entry>, kStationCount>;
        iterator(Slots& entries, std::size_t at) : entries_(&entries), at_(at) { skip_empty(); }
        Entry& operator*() const { return *(*entries_)[at_]; }
        iterator& operator++() {
            ++at_;
            skip_empty();
            return *this;
        }
        bool operator==(const iterator& other) const { return at_ == other.at_; }

      private:
        void skip_empty() {
            while (at_ < kStationCount && !(*entries_)[at_])
                ++at_;
        }
        Slots* entries_;
        std::size_t at_;
    };
    iterator begin() { return iterator(entries_, 0); }
    iterator end() { return iterator(entries_, kStationCount); }

  private:
    std::array<std::unique_ptr<Entry>, kStationCount> entries_;
};

}  // namespace

// The tracker's state beyond what BusHealth holds.
struct BusHealthTracker::State {
    // A station's counters and what its rules remember.
    struct Slot {
        StationHealth health;
        bool listed = false;
        bool master = false;    // sent a token or request, got the token, or said so
        bool answered = false;  // answered a request
        // Poll cycles (slave side).
        bool cycle_open = false;
        bool cycle_answered = false;
        std::uint64_t cycle_repeats = 0;
        std::uint64_t unanswered_cycles = 0;
        std::uint64_t diag_streak = 0;  // Slave_Diag answers in a row while in data exchange
        bool exchange_data_seen = false;
        // Answered Set_Prm or Data_Exchange (since listed or since lost): its diagnosis from then
        // on can show a fault (before, Station_Not_Ready and Prm_Req are the start-up's).
        bool parameterised = false;
        // Answered Data_Exchange since it last answered Set_Prm or Chk_Cfg: the next of those
        // answered is a resync (whatever came between, e.g. being lost and diagnosis polls).
        bool exchanged_since_prm = false;
        Verdict last_verdict = Verdict::Good;
    };
    struct Master {
        MasterHealth health;
        std::uint64_t tokens_missed_in_row = 0;
        std::int64_t last_token_ns = kNoTime;
        std::int64_t cycle_start_ns = kNoTime;
        bool cycle_started = false;
        std::int64_t last_cycle_ns = -1;
        double jitter_sum = 0;
        std::uint64_t jitter_count = 0;
        std::bitset<kStationCount> polled_in_cycle;
        std::bitset<kStationCount> polled_ever;
        Verdict last_verdict = Verdict::Good;
    };
    // The request waiting for its reply.
    struct Pending {
        bool active = false;
        std::uint8_t master = 0;
        std::uint8_t slave = 0;
        std::uint8_t function = 0;
        Service service = Service::Unknown;
        bool counted = false;  // counted as a request of a listed station
    };

    StationTable<Slot> slots;
    StationTable<Master> masters;
    // Frame count per master -> slave link: bit 0 valid, bit 1 the last FCB.
    std::array<std::array<std::uint8_t, kStationCount>, kStationCount> link_fcb{};
    // The links (master -> slave) an intact request was seen on: before it, nothing the slave
    // sends that master is judged (a capture may begin with the answer to a request before it).
    std::array<std::bitset<kStationCount>, kStationCount> link_asked{};
    Pending pending;
    bool token_waiting = false;
    std::uint8_t token_holder = 0;
    std::vector<HealthEvent> events;
    std::vector<HealthEvent> verdict_events;
    std::int64_t last_time_ns = kNoTime;
    std::uint64_t last_frame = 0;
    Verdict segment_last_verdict = Verdict::Good;
    bool finished = false;
    double ns_per_byte = 0;  // a character's time on the line (0: baud not known)
    std::uint64_t lost_cycles = 3;
};

BusHealthTracker::BusHealthTracker(BusHealthOptions options)
    : options_(options), state_(std::make_unique<State>()) {
    health_.thresholds = options_.thresholds;
    health_.segment.baud = options_.baud;
    health_.segment.character_bits = options_.character_bits;
    state_->events.reserve(8);
    state_->lost_cycles =
        static_cast<std::uint64_t>(health_.thresholds.get(HealthThreshold::LostCycles));
    if (options_.baud != 0)
        state_->ns_per_byte =
            static_cast<double>(options_.character_bits) * 1e9 / static_cast<double>(options_.baud);
}

BusHealthTracker::~BusHealthTracker() = default;

// The work of observe(), out of the class to keep the header small.
class BusHealthTrackerImpl {
  public:
    using State = BusHealthTracker::State;

    static void list(State::Slot& slot, const DecodedTelegram& t) {
        if (slot.listed) return;
        slot.listed = true;
        slot.health.first_seen_ns = t.time_ns;
        slot.health.first_frame = t.frame;
        if (slot.health.last_seen_ns == kNoTime) {
            slot.health.last_seen_ns = t.time_ns;
            slot.health.last_frame = t.frame;
        }
    }

    static void set_state(State& s, State::Slot& slot, StationState next, const DecodedTelegram& t,
                          bool returned) {
        StationHealth& h = slot.health;
        if (h.state == next && !returned) return;
        h.state = next;
        ++h.state_changes;
        if (h.timeline.size() < BusHealthTracker::kMaxStateChanges)
            h.timeline.push_back(StateChange{t.time_ns, t.frame, next, returned});
        (void)s;
    }

    static StationRole role_of(const State::Slot& slot) {
        if (slot.master) return StationRole::Master;
        if (slot.answered) return StationRole::Slave;
        return StationRole::Unknown;
    }

    static void emit(State& s, HealthEventKind kind, const State::Slot& slot,
                     const DecodedTelegram& t) {
        s.events.push_back(
            HealthEvent{kind, slot.health.address, t.time_ns, t.frame, role_of(slot)});
    }

    static void go_lost(State& s, State::Slot& slot, const DecodedTelegram& t) {
        if (slot.health.state == StationState::Lost) return;
        slot.parameterised = false;
        ++slot.health.lost_events;
        set_state(s, slot, StationState::Lost, t, false);
        emit(s, HealthEventKind::StationLost, slot, t);
    }

    // A station that sent a telegram.
    static void heard(State& s, State::Slot& slot, const DecodedTelegram& t) {
        list(slot, t);
        ++slot.health.telegrams_sent;
        slot.health.last_seen_ns = t.time_ns;
        slot.health.last_frame = t.frame;
        (void)s;
    }

    static void make_master(State& s, State::Slot& slot, const DecodedTelegram& t) {
        slot.master = true;
        (void)s;
        (void)t;
    }

    // A master sent a telegram: it is active (back from lost when it was).
    static void master_sends(State& s, State::Slot& slot, const DecodedTelegram& t) {
        make_master(s, slot, t);
        s.masters[slot.health.address].tokens_missed_in_row = 0;
        const bool was_lost = slot.health.state == StationState::Lost;
        if (slot.health.state != StationState::Active || was_lost) {
            set_state(s, slot, StationState::Active, t, was_lost);
            if (was_lost) {
                ++slot.health.returns;
                emit(s, HealthEventKind::StationReturned, slot, t);
            }
        }
    }

    // Closes a slave's poll cycle: an unanswered one counts toward lost.
    static void close_cycle(State& s, State::Slot& slot, const DecodedTelegram& t,
                            std::uint64_t lost_cycles) {
        if (!slot.cycle_open) return;
        slot.cycle_open = false;
        if (slot.cycle_answered) return;
        ++slot.unanswered_cycles;
        if (!slot.master && slot.unanswered_cycles >= lost_cycles) go_lost(s, slot, t);
    }
};

std::span<const HealthEvent> BusHealthTracker::observe(const DecodedTelegram& t) {
    using Impl = BusHealthTrackerImpl;
    State& s = *state_;
    if (!s.events.empty()) s.events.clear();
    if (t.protocol != Protocol::ProfibusDp) return {};
    SegmentHealth& seg = health_.segment;
    const FdlTelegram& fdl = t.dp.fdl;
    const std::uint64_t lost_cycles = s.lost_cycles;

    ++seg.telegrams;
    seg.bytes += t.bytes.size();
    s.last_frame = t.frame;
    if (t.time_ns != kNoTime) {
        s.last_time_ns = t.time_ns;
        if (seg.first_ns == kNoTime) seg.first_ns = t.time_ns;
    }
    if (s.ns_per_byte != 0) {
        const double duration_ns = static_cast<double>(t.bytes.size()) * s.ns_per_byte;
        seg.busy_ns += duration_ns;
        if (t.time_ns != kNoTime) {
            const std::int64_t end = t.time_ns + static_cast<std::int64_t>(duration_ns + 0.5);
            if (seg.end_ns == kNoTime || end > seg.end_ns) seg.end_ns = end;
        }
    } else if (t.time_ns != kNoTime && (seg.end_ns == kNoTime || t.time_ns > seg.end_ns)) {
        seg.end_ns = t.time_ns;
    }

    const bool damaged = is_damaged(t);
    const bool addressed = fdl.has_addresses && fdl.type != FrameType::ShortAck;
    const bool is_request = fdl.type == FrameType::Sd4 || (fdl.has_fc && fdl.fc.is_request());

    // The token passed last: taken when this telegram is its receiver's own.
    if (s.token_waiting) {
        s.token_waiting = false;
        if (!damaged) {
            State::Master& m = s.masters[s.token_holder];
            if (!(addressed && fdl.sa == s.token_holder)) {
                ++m.health.tokens_not_taken;
                ++m.tokens_missed_in_row;
                if (m.tokens_missed_in_row >= lost_cycles)
                    Impl::go_lost(s, s.slots[s.token_holder], t);
            }
        }
    }

    // The request waiting for a reply: is this its answer, a damaged one in its place, or
    // something else (then the request went unanswered)?
    bool is_answer = false;
    State::Pending asked = s.pending;
    if (s.pending.active) {
        s.pending.active = false;
        if (damaged && !is_request) {
            // In the place of the answer: the station asked.
            ++seg.damaged;
            State::Slot& slot = s.slots[asked.slave];
            if (slot.listed)
                ++slot.health.fcs_errors;
            else
                ++seg.unattributed_damaged;
            return s.events;
        }
        if (!damaged && !is_request &&
            (fdl.type == FrameType::ShortAck ||
             (fdl.has_addresses && fdl.da == asked.master && fdl.sa == asked.slave))) {
            is_answer = true;
        } else {
            State::Slot& slot = s.slots[asked.slave];
            if (asked.counted) ++slot.health.no_answers;
        }
    }

    if (damaged) {
        ++seg.damaged;
        std::uint8_t address = kBroadcastAddress;
        if (fdl.has_addresses && fdl.type != FrameType::ShortAck)
            address = is_request ? fdl.da : fdl.sa;
        if (address != kBroadcastAddress && s.slots[address].listed) {
            ++s.slots[address].health.fcs_errors;
        } else {
            ++seg.unattributed_damaged;
        }
        // A damaged SRD/SDA request keeps its FCB for the link: the master repeats it.
        if (is_request && fdl.has_fc && fdl.has_addresses && fdl.da != kBroadcastAddress &&
            (function_is_srd(fdl.fc.function()) || function_is_sda(fdl.fc.function())) &&
            fdl.fc.fcv()) {
            s.link_fcb[fdl.sa][fdl.da] = static_cast<std::uint8_t>(1 | (fdl.fc.fcb() ? 2 : 0));
        }
        return s.events;
    }

    if (fdl.type == FrameType::Invalid) return s.events;

    if (fdl.type == FrameType::Sd4) {
        if (!fdl.has_addresses) return s.events;
        State::Slot& sender = s.slots[fdl.sa];
        Impl::heard(s, sender, t);
        Impl::master_sends(s, sender, t);
        ++s.masters[fdl.sa].health.tokens_passed;
        if (fdl.da != kBroadcastAddress) {
            State::Slot& receiver = s.slots[fdl.da];
            Impl::list(receiver, t);
            Impl::make_master(s, receiver, t);
            State::Master& m = s.masters[fdl.da];
            ++m.health.tokens_received;
            if (t.time_ns != kNoTime) {
                if (m.last_token_ns != kNoTime && t.time_ns >= m.last_token_ns) {
                    const std::int64_t rotation = t.time_ns - m.last_token_ns;
                    m.health.token_rotation.add(rotation);
                    m.health.token_rotation_series.add(t.time_ns, rotation);
                }
                m.last_token_ns = t.time_ns;
            }
            s.token_waiting = true;
            s.token_holder = fdl.da;
        }
        return s.events;
    }

    if (is_request) {
        if (!fdl.has_addresses || !fdl.has_fc) return s.events;
        State::Slot& sender = s.slots[fdl.sa];
        Impl::heard(s, sender, t);
        Impl::master_sends(s, sender, t);
        State::Master& m = s.masters[fdl.sa];
        ++m.health.requests;
        if (fdl.da == kBroadcastAddress) return s.events;
        s.link_asked[fdl.sa].set(fdl.da);
        const std::uint8_t function = fdl.fc.function();
        const bool fdl_status = function == static_cast<std::uint8_t>(FdlFunction::FdlStatus);
        State::Slot& slot = s.slots[fdl.da];
        if (!fdl_status) Impl::list(slot, t);

        // Frame count: the repeat rule of fdl_retry.
        bool repeat = false;
        std::uint8_t& link = s.link_fcb[fdl.sa][fdl.da];
        if (fdl_status) {
            link = 0;
        } else if (function_is_srd(function) || function_is_sda(function)) {
            if (!fdl.fc.fcv()) {
                link = 0;
            } else {
                const bool fcb = fdl.fc.fcb();
                repeat = (link & 1) != 0 && ((link & 2) != 0) == fcb;
                link = static_cast<std::uint8_t>(1 | (fcb ? 2 : 0));
            }
        }
        const bool expects = function_expects_reply(function) && !fdl.fc.is_reserved();
        if (slot.listed) {
            StationHealth& h = slot.health;
            ++h.requests;
            if (t.dp.service == Service::SlaveDiag) ++h.diag_requests;
            if (expects) ++h.replies_due;
            if (repeat) {
                ++h.repeats;
                ++slot.cycle_repeats;
                h.max_repeats_per_cycle = std::max(h.max_repeats_per_cycle, slot.cycle_repeats);
            } else if (expects) {
                Impl::close_cycle(s, slot, t, lost_cycles);
                slot.cycle_open = true;
                slot.cycle_answered = false;
                slot.cycle_repeats = 0;
            }
        }
        if (expects)
            s.pending = State::Pending{true, fdl.sa, fdl.da, function, t.dp.service, slot.listed};

        // The master's poll cycle.
        if (t.dp.service == Service::DataExchange && !repeat) {
            if (m.polled_in_cycle.test(fdl.da) || !m.cycle_started) {
                if (m.cycle_started && t.time_ns != kNoTime && m.cycle_start_ns != kNoTime &&
                    t.time_ns >= m.cycle_start_ns) {
                    const std::int64_t cycle = t.time_ns - m.cycle_start_ns;
                    m.health.cycle.add(cycle);
                    m.health.cycle_series.add(t.time_ns, cycle);
                    if (m.last_cycle_ns >= 0) {
                        m.jitter_sum += std::fabs(static_cast<double>(cycle - m.last_cycle_ns));
                        ++m.jitter_count;
                        m.health.cycle_jitter_ns =
                            m.jitter_sum / static_cast<double>(m.jitter_count);
                    }
                    m.last_cycle_ns = cycle;
                }
                m.cycle_started = true;
                m.cycle_start_ns = t.time_ns;
                m.polled_in_cycle.reset();
            }
            m.polled_in_cycle.set(fdl.da);
            if (!m.polled_ever.test(fdl.da)) {
                m.polled_ever.set(fdl.da);
                ++m.health.slaves_polled;
            }
        }
        return s.events;
    }

    // A response.
    if (!is_answer) {
        if (fdl.type == FrameType::ShortAck) ++seg.unasked_short_acks;
        if (!fdl.has_addresses || fdl.type == FrameType::ShortAck) return s.events;
        State::Slot& sender = s.slots[fdl.sa];
        Impl::heard(s, sender, t);
        // Before the first request from that master to it, the answer's request may have come
        // before the capture: not judged.
        if (fdl.da != kBroadcastAddress && s.link_asked[fdl.da].test(fdl.sa))
            ++sender.health.illegal_answers[static_cast<std::size_t>(IllegalAnswer::NotAsked)];
        return s.events;
    }

    State::Slot& slot = s.slots[asked.slave];
    StationHealth& h = slot.health;
    if (!slot.listed) {
        Impl::list(slot, t);
        ++h.requests;  // the FDL_Status request it answered, now that it is a station
        ++h.replies_due;
    }
    Impl::heard(s, slot, t);
    ++h.answers;
    slot.answered = true;
    slot.cycle_answered = true;
    slot.unanswered_cycles = 0;

    const bool short_ack = fdl.type == FrameType::ShortAck;
    const std::uint8_t status = fdl.has_fc ? fdl.fc.function() : 0;
    const bool data = is_data_frame(fdl.type);
    if (fdl.has_fc) {
        const int negative = negative_index(status);
        if (negative >= 0) ++h.negative_answers[static_cast<std::size_t>(negative)];
    }

    // Illegal answers: wrong kind, then a short acknowledge where data was due.
    const bool fdl_status = asked.function == static_cast<std::uint8_t>(FdlFunction::FdlStatus);
    bool wrong_kind = false;
    if (function_is_sda(asked.function)) {
        wrong_kind = data || (fdl.type == FrameType::Sd1 && status_is_srd_data(status));
    } else if (fdl_status) {
        wrong_kind = data;
    } else if (function_is_srd(asked.function)) {
        wrong_kind =
            fdl.type == FrameType::Sd1 && status == static_cast<std::uint8_t>(FdlStatus::Ok);
    }
    const bool no_data = short_ack || (fdl.type == FrameType::Sd1 && !status_is_refusal(status));
    if (wrong_kind) {
        ++h.illegal_answers[static_cast<std::size_t>(IllegalAnswer::WrongKind)];
    } else if (no_data && (data_always_due(asked.service) ||
                           (asked.service == Service::DataExchange && slot.exchange_data_seen))) {
        ++h.illegal_answers[static_cast<std::size_t>(IllegalAnswer::ShortAck)];
    }

    // FDL_Status answers name the station type.
    if (fdl_status && fdl.type == FrameType::Sd1 && fdl.has_fc && fdl.fc.station_type() != 0)
        Impl::make_master(s, slot, t);

    // Diagnosis.
    if (asked.service == Service::SlaveDiag) {
        if (const SlaveDiag* diag = t.dp.service_data.slave_diag(); diag != nullptr && data) {
            ++h.diag_answers;
            // Before Set_Prm a slave reports Station_Not_Ready / Prm_Fault by design: the
            // start-up's diagnosis shows no fault.
            if (slot.parameterised) {
                const std::uint8_t s1 = diag->station_status_1;
                const std::uint8_t s2 = diag->station_status_2;
                const bool bits[kDiagFaultCount] = {(s1 & 0x02) != 0, (s1 & 0x04) != 0,
                                                    (s1 & 0x08) != 0, (s1 & 0x40) != 0,
                                                    (s2 & 0x02) != 0};
                bool fault = false;
                for (std::size_t i = 0; i < kDiagFaultCount; ++i)
                    if (bits[i]) {
                        ++h.diag_fault_bits[i];
                        fault = true;
                    }
                if (fault) ++h.diag_faults;
            }
        }
    }

    // The slave's state, from its answer.
    if (slot.master) {
        if (h.state == StationState::Lost) Impl::master_sends(s, slot, t);
        return s.events;
    }
    const bool was_lost = h.state == StationState::Lost;
    StationState next = was_lost ? StationState::Unknown : h.state;
    switch (asked.service) {
        case Service::SetPrm:
        case Service::ChkCfg:
            if (asked.service == Service::SetPrm) slot.parameterised = true;
            if (slot.exchanged_since_prm) {
                ++h.resyncs;
                slot.exchanged_since_prm = false;
            }
            next = StationState::Configuring;
            slot.diag_streak = 0;
            break;
        case Service::DataExchange:
            next = StationState::DataExchange;
            slot.diag_streak = 0;
            slot.parameterised = true;
            slot.exchanged_since_prm = true;
            if (data) slot.exchange_data_seen = true;
            break;
        case Service::SlaveDiag:
            if (was_lost ||
                (h.state != StationState::DataExchange && h.state != StationState::Configuring)) {
                next = StationState::DiagnosisOnly;
            } else if (h.state == StationState::DataExchange && ++slot.diag_streak >= lost_cycles) {
                next = StationState::DiagnosisOnly;
            }
            break;
        default: break;
    }
    if (was_lost) {
        ++h.returns;
        Impl::set_state(s, slot, next, t, true);
        Impl::emit(s, HealthEventKind::StationReturned, slot, t);
    } else {
        Impl::set_state(s, slot, next, t, false);
    }
    return s.events;
}

std::span<const HealthEvent> BusHealthTracker::judge() {
    using Impl = BusHealthTrackerImpl;
    State& s = *state_;
    s.verdict_events.clear();
    const HealthThresholds& limits = health_.thresholds;
    using enum HealthThreshold;

    health_.stations.clear();
    health_.masters.clear();
    Verdict segment = Verdict::Good;
    auto turned_bad = [&](Verdict& last, Verdict now, std::uint8_t address, StationRole role) {
        if (now == Verdict::Bad && last != Verdict::Bad)
            s.verdict_events.push_back(HealthEvent{HealthEventKind::VerdictBad, address,
                                                   s.last_time_ns, s.last_frame, role});
        last = now;
    };

    for (State::Slot& slot : s.slots) {
        if (!slot.listed) continue;
        StationHealth& h = slot.health;
        h.role = Impl::role_of(slot);
        Judgement& j = h.judgement;
        j.reasons.clear();
        judge_from(j.reasons, limits, LostEventsBad, static_cast<double>(h.lost_events));
        judge_rate(j.reasons, limits, FcsErrorPercentWeak, FcsErrorPercentBad,
                   static_cast<double>(h.fcs_errors), static_cast<double>(h.link_telegrams()));
        judge_rate(j.reasons, limits, RepeatPercentWeak, RepeatPercentBad,
                   static_cast<double>(h.repeats), static_cast<double>(h.requests));
        judge_from(j.reasons, limits, RepeatsPerCycleWeak,
                   static_cast<double>(h.max_repeats_per_cycle));
        judge_rate(j.reasons, limits, NoAnswerPercentWeak, NoAnswerPercentBad,
                   static_cast<double>(h.no_answers), static_cast<double>(h.replies_due));
        // Illegal answers and resyncs: the worse of the two limits only.
        const double illegal = static_cast<double>(h.illegal_answers_total());
        const std::size_t before_illegal = j.reasons.size();
        judge_from(j.reasons, limits, IllegalAnswersBad, illegal);
        if (j.reasons.size() == before_illegal)
            judge_from(j.reasons, limits, IllegalAnswersWeak, illegal);
        const std::size_t before_resyncs = j.reasons.size();
        judge_from(j.reasons, limits, ResyncsBad, static_cast<double>(h.resyncs));
        if (j.reasons.size() == before_resyncs)
            judge_from(j.reasons, limits, ResyncsWeak, static_cast<double>(h.resyncs));
        judge_from(j.reasons, limits, DiagFaultsWeak, static_cast<double>(h.diag_faults));
        const double refusals =
            static_cast<double>(h.negative_answers[static_cast<std::size_t>(NegativeAnswer::UE)] +
                                h.negative_answers[static_cast<std::size_t>(NegativeAnswer::RR)] +
                                h.negative_answers[static_cast<std::size_t>(NegativeAnswer::RS)]);
        judge_from(j.reasons, limits, RefusalsWeak, refusals);
        conclude(j);
        turned_bad(slot.last_verdict, j.verdict, h.address, h.role);
        segment = worse(segment, j.verdict);
        health_.stations.push_back(h);

        if (!slot.master) continue;
        State::Master& m = s.masters[h.address];
        Judgement& mj = m.health.judgement;
        mj.reasons.clear();
        const double target_ms = limits.get(TargetRotationMs);
        if (target_ms > 0 && m.health.token_rotation.count() > 0) {
            const double p95_ms = static_cast<double>(m.health.token_rotation.p95()) / 1e6;
            const double max_ms = static_cast<double>(m.health.token_rotation.max()) / 1e6;
            if (max_ms > 1.5 * target_ms)
                mj.reasons.push_back({TargetRotationMs, max_ms, Verdict::Bad});
            else if (p95_ms > target_ms)
                mj.reasons.push_back({TargetRotationMs, p95_ms, Verdict::Weak});
        }
        const double jitter_limit = limits.get(CycleJitterPercentWeak);
        if (jitter_limit > 0 && m.jitter_count > 0 && m.health.cycle.mean() > 0) {
            const double percent = m.health.cycle_jitter_ns / m.health.cycle.mean() * 100.0;
            if (percent > jitter_limit)
                mj.reasons.push_back({CycleJitterPercentWeak, percent, Verdict::Weak});
        }
        conclude(mj);
        turned_bad(m.last_verdict, mj.verdict, h.address, StationRole::Master);
        segment = worse(segment, mj.verdict);
        health_.masters.push_back(m.health);
    }

    SegmentHealth& seg = health_.segment;
    Judgement& sj = seg.judgement;
    sj.reasons.clear();
    const double load = seg.load_percent();
    if (load >= 0) {
        if (load > limits.get(BusLoadPercentBad))
            sj.reasons.push_back({BusLoadPercentBad, load, Verdict::Bad});
        else if (load > limits.get(BusLoadPercentWeak))
            sj.reasons.push_back({BusLoadPercentWeak, load, Verdict::Weak});
    }
    // The segment's damaged telegrams, all of them, over all its telegrams (the rate its
    // "Damaged" line reads; those no station could be named for weigh here only).
    judge_rate(sj.reasons, limits, FcsErrorPercentWeak, FcsErrorPercentBad,
               static_cast<double>(seg.damaged), static_cast<double>(seg.telegrams));
    conclude(sj);
    sj.verdict = worse(sj.verdict, segment);
    turned_bad(s.segment_last_verdict, sj.verdict, kSegmentAddress, StationRole::Unknown);
    return s.verdict_events;
}

void BusHealthTracker::finish(std::int64_t end_ns) {
    using Impl = BusHealthTrackerImpl;
    State& s = *state_;
    if (!s.finished) {
        s.finished = true;
        const std::uint64_t lost_cycles =
            static_cast<std::uint64_t>(health_.thresholds.get(HealthThreshold::LostCycles));
        DecodedTelegram end;
        end.time_ns = end_ns != kNoTime ? end_ns : health_.segment.end_ns;
        end.frame = s.last_frame;
        for (State::Slot& slot : s.slots) {
            if (!slot.listed || !slot.cycle_open) continue;
            // A poll still waiting for its reply when the capture ended is not judged.
            if (s.pending.active && s.pending.slave == slot.health.address) continue;
            Impl::close_cycle(s, slot, end, lost_cycles);
        }
        if (end_ns != kNoTime && health_.segment.first_ns != kNoTime &&
            end_ns >= health_.segment.first_ns)
            health_.segment.end_ns = end_ns;
    }
    judge();
}

}  // namespace dpscope
