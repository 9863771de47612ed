// The bus-health tracker (protocols/profibus/health/bus_health.hpp) fed one telegram at a time: the
// segment's counts and times, the request waiting for its reply and the answer to it, frame counts
// and repeats, damaged telegrams, illegal and negative answers, diagnosis; and the end of the
// capture. The stations' states, the masters and the verdicts:
// protocols/profibus/health/bus_health_stations.cpp,
// protocols/profibus/health/bus_health_masters.cpp and
// protocols/profibus/health/bus_health_verdicts.cpp.
#include <algorithm>
#include <array>
#include <limits>
#include <memory>

#include "protocols/profibus/health/bus_health_state.hpp"

namespace dpscope {

namespace {

// A DP telegram's problems are its FDL layer's (payload_problems()), read here directly: the
// protocol is known.
bool is_damaged(const FdlTelegram& fdl) {
    if (fdl.fcs_ok && fdl.problems.empty()) return false;
    if (!fdl.fcs_ok) return true;
    for (const Problem& p : fdl.problems)
        if (problem_severity(p.kind) == Severity::Error) return true;
    return false;
}

// No time is the least time (the comparisons below lean on it: a later time is a greater one,
// and no time is never later).
static_assert(kNoTime == std::numeric_limits<std::int64_t>::min());

constexpr bool is_data_frame(FrameType type) {
    return type == FrameType::Sd2 || type == FrameType::Sd3;
}

constexpr bool status_is_refusal(std::uint8_t status) {
    return status == static_cast<std::uint8_t>(FdlStatus::UserError) ||
           status == static_cast<std::uint8_t>(FdlStatus::NoResource) ||
           status == static_cast<std::uint8_t>(FdlStatus::NoService);
}

// The SRD statuses that carry (or stand for) response data: DL, NR, DH, RDL, RDH.
constexpr bool status_is_srd_data(std::uint8_t status) {
    switch (static_cast<FdlStatus>(status)) {
        case FdlStatus::DataLow:
        case FdlStatus::NoResponseData:
        case FdlStatus::DataHigh:
        case FdlStatus::NotReceivedDataLow:
        case FdlStatus::NotReceivedDataHigh: return true;
        default: return false;
    }
}

constexpr int negative_index(std::uint8_t status) {
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

// The three above for each response status (the FC's low nibble), read once an answer.
struct StatusTraits {
    std::int8_t negative = -1;
    bool refusal = false;
    bool srd_data = false;
};
constexpr std::array<StatusTraits, 16> kStatusTraits = [] {
    std::array<StatusTraits, 16> rows{};
    for (std::uint8_t status = 0; status < rows.size(); ++status)
        rows[status] = {static_cast<std::int8_t>(negative_index(status)), status_is_refusal(status),
                        status_is_srd_data(status)};
    return rows;
}();

bool data_always_due(Service service) {
    return service == Service::SlaveDiag || service == Service::GetCfg ||
           service == Service::RdInp || service == Service::RdOutp;
}

}  // namespace

BusHealthTracker::BusHealthTracker(BusHealthOptions options)
    : options_(options), state_(std::make_unique<State>()) {
    health_.thresholds = options_.thresholds;
    health_.segment.baud = options_.baud;
    health_.segment.character_bits = options_.character_bits;
    state_->events.reserve(8);
    state_->steady_path = options_.steady_path;
    state_->lost_cycles =
        static_cast<std::uint64_t>(health_.thresholds.get(HealthThreshold::LostCycles));
    if (options_.baud != 0)
        state_->ns_per_byte =
            static_cast<double>(options_.character_bits) * 1e9 / static_cast<double>(options_.baud);
}

BusHealthTracker::~BusHealthTracker() = default;

std::uint64_t BusHealthTracker::steady_telegrams() const noexcept {
    return health_.segment.telegrams - state_->full_telegrams;
}

std::span<const HealthEvent> BusHealthTracker::observe(const DecodedTelegram& t) {
    using Impl = BusHealthTrackerImpl;
    if (t.protocol != Protocol::ProfibusDp) return {};
    State& s = *state_;
    SegmentHealth& seg = health_.segment;
    // The segment's counts and times. The usual telegram is later than the segment's end, on a
    // segment whose first time is known and whose line rate is not (s.plain_times): only the
    // times move. Another one (the first with a time, one without a time or not later than the
    // end, a line rate known) takes count_segment_times(), out of line.
    ++seg.telegrams;
    s.last_frame = t.frame;
    seg.bytes += t.bytes.size();  // apart from telegrams: two adds, not a vector add
    const std::int64_t time = t.time_ns;
    if (!(time > seg.end_ns && s.plain_times)) [[unlikely]]
        return Impl::observe_times(s, seg, t);
    s.last_time_ns = time;
    seg.end_ns = time;
    return Impl::choose_path(s, seg, t);
}

[[gnu::noinline]] std::span<const HealthEvent> BusHealthTrackerImpl::observe_times(
    State& s, SegmentHealth& seg, const DecodedTelegram& t) {
    count_segment_times(s, seg, t);
    return choose_path(s, seg, t);
}

[[gnu::always_inline]] inline std::span<const HealthEvent> BusHealthTrackerImpl::choose_path(
    State& s, SegmentHealth& seg, const DecodedTelegram& t) {
    // The steady path for an intact telegram, else the full rules (bus_health_state.hpp).
    const FdlTelegram& fdl = t.dp.fdl;
    if (fdl.fcs_ok && fdl.problems.empty() && s.steady_path) [[likely]]
        return s.pending.active != State::kNoRequest ? steady_answer(s, seg, t)
                                                     : steady_request(s, seg, t);
    return observe_rest(s, seg, t);
}

void BusHealthTrackerImpl::count_segment_times(State& s, SegmentHealth& seg,
                                               const DecodedTelegram& t) {
    const std::int64_t time = t.time_ns;
    if (time != kNoTime) {
        s.last_time_ns = time;
        if (seg.first_ns == kNoTime) [[unlikely]]
            seg.first_ns = time;
    }
    if (s.ns_per_byte != 0) {
        const double duration_ns = static_cast<double>(t.bytes.size()) * s.ns_per_byte;
        seg.busy_ns += duration_ns;
        if (time != kNoTime) {
            const std::int64_t end = time + static_cast<std::int64_t>(duration_ns + 0.5);
            if (end > seg.end_ns) seg.end_ns = end;
        }
    } else if (time > seg.end_ns) {
        seg.end_ns = time;
    }
    s.plain_times = s.ns_per_byte == 0 && seg.first_ns != kNoTime;
}

[[gnu::always_inline]] inline bool BusHealthTrackerImpl::count_frame(std::uint8_t& link, bool fcb) {
    // A repeat: the count valid and its FCB the same (both bits as they are now).
    const std::uint8_t now =
        static_cast<std::uint8_t>(State::kLinkFcbValid | (fcb ? State::kLinkFcb : 0));
    const bool repeat = (link & (State::kLinkFcbValid | State::kLinkFcb)) == now;
    link = static_cast<std::uint8_t>((link & State::kLinkAsked) | now);
    return repeat;
}

[[gnu::always_inline]] inline bool BusHealthTrackerImpl::count_request(State::Slot& slot,
                                                                       Service service, bool repeat,
                                                                       bool expects) {
    StationHealth& h = slot.health;
    ++h.requests;
    if (service == Service::SlaveDiag) ++h.diag_requests;
    if (expects) ++h.replies_due;
    if (repeat) {
        ++h.repeats;
        ++slot.cycle_repeats;
        h.max_repeats_per_cycle = std::max(h.max_repeats_per_cycle, slot.cycle_repeats);
    }
    return expects && !repeat;
}

[[gnu::always_inline]] inline void BusHealthTrackerImpl::count_answer(State::Slot& slot,
                                                                      const FdlTelegram& fdl,
                                                                      std::uint8_t function,
                                                                      Service service) {
    StationHealth& h = slot.health;
    const bool short_ack = fdl.type == FrameType::ShortAck;
    const std::uint8_t status = fdl.has_fc ? fdl.fc.function() : 0;
    const StatusTraits& traits = kStatusTraits[status];
    const bool data = is_data_frame(fdl.type);
    // (Without a frame control byte the status reads 0, no negative answer.)
    if (traits.negative >= 0) ++h.negative_answers[static_cast<std::size_t>(traits.negative)];
    // Illegal answers: wrong kind, then a short acknowledge where data was due.
    bool wrong_kind = false;
    if (function_is_srd(function)) {
        wrong_kind =
            fdl.type == FrameType::Sd1 && status == static_cast<std::uint8_t>(FdlStatus::Ok);
    } else if (function_is_sda(function)) {
        wrong_kind = data || (fdl.type == FrameType::Sd1 && traits.srd_data);
    } else if (function == static_cast<std::uint8_t>(FdlFunction::FdlStatus)) {
        wrong_kind = data;
    }
    const bool no_data = short_ack || (fdl.type == FrameType::Sd1 && !traits.refusal);
    if (wrong_kind) {
        ++h.illegal_answers[static_cast<std::size_t>(IllegalAnswer::WrongKind)];
    } else if (no_data && (data_always_due(service) ||
                           (service == Service::DataExchange && slot.exchange_data_seen))) {
        ++h.illegal_answers[static_cast<std::size_t>(IllegalAnswer::ShortAck)];
    }
}

// Out of line, as steady_answer() and observe_rest(): observe() only counts and chooses, and each
// path keeps its own registers (inlined into observe(), the steps cost every telegram the saving
// of the registers the request needs).
[[gnu::noinline]] std::span<const HealthEvent> BusHealthTrackerImpl::steady_request(
    State& s, SegmentHealth& seg, const DecodedTelegram& t) {
    const FdlTelegram& fdl = t.dp.fdl;
    // Read once: the stores below are of bytes, which the compiler must assume may change t.
    const FrameControl fc = fdl.fc;
    const std::uint8_t sa = fdl.sa;
    const std::uint8_t da = fdl.da;
    const Service service = t.dp.service;
    // SRD low or high with FCV set (FC bit 7 clear, bit 6 set: a request, bit 4 set, function
    // 0xC or 0xD); SD1 to SD3 carry a frame control byte and both addresses.
    if (!fdl.has_fc || (fc.raw & 0xDE) != 0x5C) [[unlikely]]
        return fdl.type == FrameType::Sd4 ? steady_token(s, seg, t) : observe_rest(s, seg, t);
    // Entries not made yet are the tables' blank ones (not listed, state Unknown): the tests
    // below fail for them, and nothing is written to them.
    State::Slot* sender = s.slots.peek(sa);
    State::Slot* slot = s.slots.peek(da);
    // Not to all; the token passed last is taken when its receiver sends (check_token_taken());
    // an active master (listed, and a master, as only master_sends() makes a station active)
    // asking a listed station whose poll cycle does not close unanswered (that counts toward
    // lost).
    if (da == kBroadcastAddress || (s.token_waiting && sa != s.token_holder) ||
        sender->health.state != StationState::Active || !slot->listed ||
        (slot->cycle_open && !slot->cycle_answered)) [[unlikely]]
        return observe_rest(s, seg, t);
    // Made by master_sends()'s callers before it made the master active: never blank here.
    State::Master* m = s.masters.peek(sa);
    if (s.masters.is_blank(m)) [[unlikely]]
        return observe_rest(s, seg, t);

    // First, so that fewer values stay live: what steady_answer() may then skip testing.
    s.pending = State::Pending{State::kSteadyRequest, sa, da, fc.function(), service, true, slot};
    s.token_waiting = false;
    heard_listed(*sender, t);
    master_sends(s, *sender, *m, t);
    ++m->health.requests;
    std::uint8_t link = s.links[sa][da] | State::kLinkAsked;
    const bool repeat = count_frame(link, fc.fcb());
    s.links[sa][da] = link;
    // The cycle this one closes was answered (tested above): nothing counts toward lost.
    if (count_request(*slot, service, repeat, true)) open_cycle(*slot);
    if (service == Service::DataExchange && !repeat) master_polls(*m, t, da);
    return {};
}

[[gnu::noinline]] std::span<const HealthEvent> BusHealthTrackerImpl::steady_token(
    State& s, SegmentHealth& seg, const DecodedTelegram& t) {
    const FdlTelegram& fdl = t.dp.fdl;
    const std::uint8_t sa = fdl.sa;
    // Passed by the master that holds it (taken, when it was just passed to it), an active one:
    // then token_passed() raises no event whoever receives it (only a master that becomes
    // active does; listing the receiver and making it a master raise none).
    if (!fdl.has_addresses || (s.token_waiting && sa != s.token_holder) ||
        s.slots.peek(sa)->health.state != StationState::Active)
        return observe_rest(s, seg, t);

    s.token_waiting = false;  // check_token_taken(): taken
    token_passed(s, t);
    return {};
}

[[gnu::noinline]] std::span<const HealthEvent> BusHealthTrackerImpl::steady_answer(
    State& s, SegmentHealth& seg, const DecodedTelegram& t) {
    const FdlTelegram& fdl = t.dp.fdl;
    // Read once (as in steady_request()).
    const State::Pending asked = s.pending;
    const FrameType type = fdl.type;
    // Asked through steady_request(), by the telegram before this one (the full rules end any
    // request waiting): the token is not waiting, the station asked is listed, the function is
    // SRD.
    if (asked.active != State::kSteadyRequest) [[unlikely]]
        return observe_rest(s, seg, t);
    // A short acknowledge, or a response (SD1 to SD3) from the station asked to its master.
    if (type != FrameType::ShortAck &&
        (!fdl.has_fc || fdl.fc.is_request() || fdl.da != asked.master || fdl.sa != asked.slave))
        return observe_rest(s, seg, t);
    State::Slot& slot = *asked.slot;
    const StationHealth& h = slot.health;
    // A slave that stays in its state (state_from_answer() changes nothing).
    if (slot.master || h.state == StationState::Lost) [[unlikely]]
        return observe_rest(s, seg, t);
    switch (asked.service) {
        case Service::SetPrm:
        case Service::ChkCfg:
        case Service::SlaveDiag: return observe_rest(s, seg, t);
        case Service::DataExchange:
            if (h.state != StationState::DataExchange) return observe_rest(s, seg, t);
            break;
        default: break;
    }

    s.pending.active = State::kNoRequest;
    heard_listed(slot, t);
    answered(slot);
    // SRD low or high (steady_request()): count_answer() reads only that it is SRD.
    count_answer(slot, fdl, static_cast<std::uint8_t>(FdlFunction::SrdLow), asked.service);
    if (asked.service == Service::DataExchange) exchanged(slot, is_data_frame(type));
    return {};
}

[[gnu::noinline]] std::span<const HealthEvent> BusHealthTrackerImpl::observe_rest(
    State& s, SegmentHealth& seg, const DecodedTelegram& t) {
    using Impl = BusHealthTrackerImpl;
    const FdlTelegram& fdl = t.dp.fdl;
    const std::uint64_t lost_cycles = s.lost_cycles;
    if (!s.events.empty()) s.events.clear();  // the last call's (the steady steps leave none)
    ++s.full_telegrams;

    const bool damaged = is_damaged(fdl);
    const bool addressed = fdl.has_addresses && fdl.type != FrameType::ShortAck;
    const bool is_request = fdl.type == FrameType::Sd4 || (fdl.has_fc && fdl.fc.is_request());

    // The token passed last: taken when this telegram is its receiver's own.
    if (s.token_waiting) Impl::check_token_taken(s, t, damaged, addressed, lost_cycles);

    // The request waiting for a reply: is this its answer, a damaged one in its place, or
    // something else (then the request went unanswered)?
    bool is_answer = false;
    State::Pending asked = s.pending;
    if (s.pending.active != State::kNoRequest) {
        s.pending.active = State::kNoRequest;
        if (damaged && !is_request) {
            // In the place of the answer: the station asked.
            ++seg.damaged;
            State::Slot& slot = *asked.slot;
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
        } else if (asked.counted) {
            ++asked.slot->health.no_answers;
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
            (void)Impl::count_frame(s.links[fdl.sa][fdl.da], fdl.fc.fcb());
        }
        return s.events;
    }

    if (fdl.type == FrameType::Invalid) return s.events;

    if (fdl.type == FrameType::Sd4) {
        Impl::token_passed(s, t);
        return s.events;
    }

    if (is_request) {
        if (!fdl.has_addresses || !fdl.has_fc) return s.events;
        State::Slot& sender = s.slots[fdl.sa];
        Impl::heard(s, sender, t);
        State::Master& m = s.masters[fdl.sa];
        Impl::master_sends(s, sender, m, t);
        ++m.health.requests;
        if (fdl.da == kBroadcastAddress) return s.events;
        std::uint8_t& link = s.links[fdl.sa][fdl.da];
        link |= State::kLinkAsked;
        const std::uint8_t function = fdl.fc.function();
        const bool fdl_status = function == static_cast<std::uint8_t>(FdlFunction::FdlStatus);
        State::Slot& slot = s.slots[fdl.da];
        if (!fdl_status) Impl::list(slot, t);

        // Frame count: the repeat rule of fdl_retry.
        bool repeat = false;
        if (fdl_status) {
            link = State::kLinkAsked;
        } else if (function_is_srd(function) || function_is_sda(function)) {
            if (!fdl.fc.fcv())
                link = State::kLinkAsked;
            else
                repeat = Impl::count_frame(link, fdl.fc.fcb());
        }
        const bool expects = function_expects_reply(function) && !fdl.fc.is_reserved();
        if (slot.listed && Impl::count_request(slot, t.dp.service, repeat, expects)) {
            Impl::close_cycle(s, slot, t, lost_cycles);
            Impl::open_cycle(slot);
        }
        if (expects)
            s.pending = State::Pending{State::kFullRequest, fdl.sa,      fdl.da, function,
                                       t.dp.service,        slot.listed, &slot};

        // The master's poll cycle.
        if (t.dp.service == Service::DataExchange && !repeat) Impl::master_polls(m, t, fdl.da);
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
        if (fdl.da != kBroadcastAddress && (s.links[fdl.da][fdl.sa] & State::kLinkAsked) != 0)
            ++sender.health.illegal_answers[static_cast<std::size_t>(IllegalAnswer::NotAsked)];
        return s.events;
    }

    State::Slot& slot = *asked.slot;
    StationHealth& h = slot.health;
    if (!slot.listed) {
        Impl::list(slot, t);
        ++h.requests;  // the FDL_Status request it answered, now that it is a station
        ++h.replies_due;
    }
    Impl::heard(s, slot, t);
    Impl::answered(slot);

    Impl::count_answer(slot, fdl, asked.function, asked.service);
    const bool data = is_data_frame(fdl.type);

    // FDL_Status answers name the station type.
    const bool fdl_status = asked.function == static_cast<std::uint8_t>(FdlFunction::FdlStatus);
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

    // The station's state, from its answer.
    Impl::state_from_answer(s, slot, asked.service, data, t, lost_cycles);
    return s.events;
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
            if (s.pending.active != State::kNoRequest && s.pending.slave == slot.health.address)
                continue;
            Impl::close_cycle(s, slot, end, lost_cycles);
        }
        if (end_ns != kNoTime && health_.segment.first_ns != kNoTime &&
            end_ns >= health_.segment.first_ns)
            health_.segment.end_ns = end_ns;
    }
    judge();
}

}  // namespace dpscope
