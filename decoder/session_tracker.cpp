#include "decoder/session_tracker.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>

namespace dpscope {

namespace {

constexpr std::int64_t kNever = std::numeric_limits<std::int64_t>::max();

struct PcvKey {
    std::uint8_t rc = 0;
    std::uint16_t pnu = 0;
    std::uint8_t ind = 0;
    std::uint32_t pva = 0;
    bool operator==(const PcvKey&) const = default;
};

PcvKey key_of(const Pcv& pcv) { return PcvKey{pcv.rc, pcv.pnu, pcv.ind, pcv.pva}; }

// The same code for the same parameter, whatever the value.
bool same_parameter(const PcvKey& a, const PcvKey& b) {
    return a.rc == b.rc && a.pnu == b.pnu && a.ind == b.ind;
}

// Does response `r` concern the parameter of request `q`? PNU must match, and IND too when
// either code is an array code.
bool concerns(Dialect dialect, const PcvKey& q, const Pcv& r) {
    if (q.pnu != r.pnu) return false;
    bool array = request_code(dialect, q.rc).is_array || response_code(dialect, r.rc).is_array;
    return !array || q.ind == r.ind;
}

// Do two PVAs carry the same value? Compared in the narrower of the two codes' widths.
bool same_value(ValueWidth request_width, ValueWidth response_width, std::uint32_t request_pva,
                std::uint32_t response_pva) {
    const bool word = request_width == ValueWidth::Word || response_width == ValueWidth::Word;
    const std::uint32_t mask = word ? 0xFFFFu : 0xFFFF'FFFFu;
    return (request_pva & mask) == (response_pva & mask);
}

std::string describe_request(Dialect dialect, const PcvKey& q) {
    return fmt::format("RC {} ({}) PNU {}{}", q.rc, request_code(dialect, q.rc).meaning, q.pnu,
                       request_code(dialect, q.rc).is_array ? fmt::format(" IND {}", q.ind) : "");
}

bool is_link_problem(const Problem& p) { return problem_severity(p.kind) == Severity::Error; }

}  // namespace

// ---- Timeline -----------------------------------------------------------------------------------

Timeline::Bin& Timeline::bin(std::int64_t time_ns) {
    if (start_ns_ == kNoTime) start_ns_ = time_ns;
    std::int64_t offset = std::max<std::int64_t>(0, time_ns - start_ns_);
    while (offset / width_ns_ >= static_cast<std::int64_t>(kBins)) {
        // Halve the resolution: merge neighbouring bins.
        for (std::size_t i = 0; i < kBins / 2; ++i) {
            const Bin& a = bins_[2 * i];
            const Bin& b = bins_[2 * i + 1];
            bins_[i] = Bin{a.transactions + b.transactions, a.errors + b.errors,
                           a.warnings + b.warnings, a.notes + b.notes};
        }
        for (std::size_t i = kBins / 2; i < kBins; ++i)
            bins_[i] = Bin{};
        width_ns_ *= 2;
    }
    return bins_[static_cast<std::size_t>(offset / width_ns_)];
}

void Timeline::add_finding(std::int64_t time_ns, Severity severity) {
    Bin& b = bin(time_ns);
    switch (severity) {
        case Severity::Error: ++b.errors; break;
        case Severity::Warning: ++b.warnings; break;
        case Severity::Note: ++b.notes; break;
    }
}

// ---- DialectEvidence ---------------------------------------------------------------------------

void DialectEvidence::add(const DecodedTelegram& t) noexcept {
    if (t.dp.service != Service::DataExchange || !t.dp.has_pcv || !t.dp.fdl.fcs_ok) return;
    const bool request = t.direction == Direction::Request;
    auto defines = [&](Dialect dialect) {
        return request ? request_code(dialect, t.dp.pcv.rc).defined
                       : response_code(dialect, t.dp.pcv.rc).kind != ResponseKind::Undefined;
    };
    if (defines(t.dp.dialect)) return;
    if (decoded_ != t.dp.dialect) *this = DialectEvidence{};  // the dialect changed: start again
    decoded_ = t.dp.dialect;
    ++undefined_;
    const Dialect other = t.dp.dialect == Dialect::Vlt ? Dialect::Profidrive : Dialect::Vlt;
    if (defines(other)) ++other_defines_;
}

std::optional<Dialect> DialectEvidence::hint() const noexcept {
    if (undefined_ < kMinimum || other_defines_ != undefined_) return std::nullopt;
    return decoded_ == Dialect::Vlt ? Dialect::Profidrive : Dialect::Vlt;
}

// ---- Channel state ------------------------------------------------------------------------------

struct SessionTracker::Channel {
    ChannelStats stats;
    // FDL frame count bit of the last SRD/SDA request to this slave.
    bool fcb_valid = false;
    bool last_fcb = false;
    // Data_Exchange lengths that disagree with the configuration (length + 1; 0: they agree).
    std::size_t output_mismatch = 0;
    std::size_t input_mismatch = 0;
    // Master side of the parameter channel.
    bool master_valid = false;
    PcvKey master_key;
    bool master_spm_valid = false;
    bool master_spm = false;
    bool master_toggled = false;  // the master's SPM has changed since the capture began
    struct Pending {
        bool active = false;
        PcvKey key;
        std::uint64_t frame = 0;
        std::int64_t time_ns = kNoTime;
        std::uint64_t cycle = 0;
        bool timed_out = false;
        bool undefined = false;  // a code the dialect does not define: any answer closes it
    } pending;
    struct Previous {
        bool valid = false;
        PcvKey key;
        bool answered = false;
        bool moved_on = false;  // the master has moved on from it
        std::uint64_t moved_on_cycle = 0;
        bool late_answer_seen = false;  // an abandoned request's late answer was already seen
        std::uint8_t answer_rc = 0;     // the code it was answered with
    } previous;
    // A damaged request (bad FCS) was dropped by the slave: its retry is the cycle.
    bool damaged_request = false;
    // Slave side.
    bool slave_valid = false;
    PcvKey slave_key;
    std::uint64_t slave_change_cycle = 0;
    bool slave_spm_valid = false;
    bool slave_spm = false;
    bool unknown_valid = false;
    PcvKey unknown_key;
    bool orphan_valid = false;  // the last orphan reported, not repeated while only refreshed
    PcvKey orphan_key;
    struct Spontaneous {
        bool seen = false;
        bool pending = false;
        bool spm = false;
        std::uint64_t frame = 0;
        std::int64_t time_ns = kNoTime;
        std::uint16_t pnu = 0;
        bool reported_late = false;
        bool assumed_acknowledged = false;  // first seen with the master's SPM: see slave_pcv
        std::uint64_t cycle = 0;
    } spontaneous;
};

SessionTracker::SessionTracker(const BusDecoder& decoder, TrackerOptions options)
    : decoder_(decoder), options_(options), index_(kStationCount * kStationCount, -1) {}

SessionTracker::~SessionTracker() = default;

SessionTracker::Channel& SessionTracker::channel(std::uint8_t master, std::uint8_t slave) {
    std::size_t key = std::size_t{master & 0x7Fu} * kStationCount + (slave & 0x7Fu);
    if (index_[key] < 0) {
        index_[key] = static_cast<std::int32_t>(channels_.size());
        auto ch = std::make_unique<Channel>();
        ch->stats.master = master & 0x7F;
        ch->stats.slave = slave & 0x7F;
        channels_.push_back(std::move(ch));
    }
    return *channels_[static_cast<std::size_t>(index_[key])];
}

std::vector<const ChannelStats*> SessionTracker::channels() const {
    std::vector<const ChannelStats*> out;
    for (const auto& ch : channels_)
        if (ch->stats.data_exchange > 0 || ch->stats.requests > 0 ||
            std::any_of(ch->stats.findings.begin(), ch->stats.findings.end(),
                        [](std::uint64_t n) { return n > 0; }))
            out.push_back(&ch->stats);
    std::sort(out.begin(), out.end(), [](const ChannelStats* a, const ChannelStats* b) {
        return std::pair(a->slave, a->master) < std::pair(b->slave, b->master);
    });
    return out;
}

std::uint64_t SessionTracker::transactions() const noexcept {
    std::uint64_t total = 0;
    for (const auto& ch : channels_)
        total += ch->stats.transactions.total();
    return total;
}

Finding& SessionTracker::add_for(FindingKind kind, std::uint64_t frame, std::int64_t time_ns,
                                 std::uint64_t request_frame, bool has_stations,
                                 std::uint8_t master, std::uint8_t slave) {
    Finding& f = current_.emplace_back();
    f.kind = kind;
    f.severity = default_severity(kind);
    f.frame = frame;
    f.request_frame = request_frame;
    f.time_ns = time_ns;
    f.has_stations = has_stations;
    f.master = master;
    f.slave = slave;
    ++by_severity_[static_cast<std::size_t>(f.severity)];
    if (has_stations) {
        ChannelStats& stats = channel(master, slave).stats;
        ++stats.findings[static_cast<std::size_t>(kind)];
        if (time_ns != kNoTime) stats.timeline.add_finding(time_ns, f.severity);
    } else {
        ++bus_.findings[static_cast<std::size_t>(kind)];
    }
    return f;
}

Finding& SessionTracker::add(FindingKind kind, const DecodedTelegram& t,
                             std::uint64_t request_frame) {
    return add_for(kind, t.frame, t.time_ns, request_frame, t.has_roles, t.master, t.slave);
}

// ---- Feeding ------------------------------------------------------------------------------------

std::span<const Finding> SessionTracker::track(const DecodedTelegram& t) {
    current_.clear();
    last_frame_ = t.frame;
    subject_pnu_ = t.dp.has_pcv ? t.dp.pcv.pnu : -1;
    if (t.has_time()) {
        now_ns_ = t.time_ns;
        check_deadlines(&t, now_ns_);
    }
    // A request answered by nothing before the master's next telegram.
    if (t.dp.unanswered && (function_is_srd(t.dp.unanswered->function) ||
                            function_is_sda(t.dp.unanswered->function))) {
        const UnansweredRequest& u = *t.dp.unanswered;
        Finding& f = add_for(FindingKind::FdlNoResponse, t.frame, t.time_ns, u.frame, true,
                             u.master, u.slave);
        f.message = fmt::format(
            "{} request to station {} ({}) got no reply before the master's "
            "next telegram",
            request_function_name(u.function), u.slave, service_name(u.service));
    }
    bool usable = true;
    check_link(t, usable);
    if (!t.has_roles) return current_;
    if (!usable) {
        // The slave drops a damaged request, so the master repeats it: its FCB still counts.
        if (!t.dp.fdl.fcs_ok && t.direction == Direction::Request && t.dp.fdl.has_fc &&
            t.dp.fdl.fc.fcv() && t.dp.fdl.da != kBroadcastAddress &&
            (function_is_srd(t.dp.fdl.fc.function()) || function_is_sda(t.dp.fdl.fc.function()))) {
            Channel& ch = channel(t.master, t.slave);
            ch.last_fcb = t.dp.fdl.fc.fcb();
            ch.fcb_valid = true;
            ch.damaged_request = true;
        }
        return current_;
    }
    Channel& ch = channel(t.master, t.slave);
    bool retry = false;
    check_frame_count(ch, t, retry);
    if (t.dp.service != Service::DataExchange) return current_;

    ChannelStats& stats = ch.stats;
    ++stats.data_exchange;
    stats.ppo = t.dp.ppo;
    stats.dialect = t.dp.dialect;
    if (t.has_time()) {
        if (stats.first_time_ns == kNoTime) stats.first_time_ns = t.time_ns;
        stats.last_time_ns = t.time_ns;
    }
    const bool request = t.direction == Direction::Request;
    if (request) {
        if (!retry || ch.damaged_request) ++stats.cycles;
        ch.damaged_request = false;
    }
    check_config(ch, t);
    if (!t.dp.has_pcv) return current_;
    ++stats.parameter_telegrams;
    if (request)
        master_pcv(ch, t);
    else
        slave_pcv(ch, t);
    return current_;
}

std::span<const Finding> SessionTracker::finish(std::int64_t end_ns) {
    current_.clear();
    if (end_ns != kNoTime && (now_ns_ == kNoTime || end_ns > now_ns_)) now_ns_ = end_ns;
    if (now_ns_ != kNoTime) check_deadlines(nullptr, now_ns_);
    return current_;
}

void SessionTracker::check_link(const DecodedTelegram& t, bool& usable) {
    if (!t.dp.fdl.fcs_ok) {
        usable = false;
        Finding& f = add(FindingKind::FcsError, t, 0);
        for (const Problem& p : t.problems())
            if (p.kind == ProblemKind::FcsMismatch) f.message = problem_message(p);
        return;
    }
    for (const Problem& p : t.problems()) {
        if (!is_link_problem(p)) continue;
        usable = false;
        add(FindingKind::MalformedTelegram, t, 0).message =
            fmt::format("{}: {}", problem_kind_name(p.kind), problem_message(p));
        return;
    }
}

void SessionTracker::check_frame_count(Channel& ch, const DecodedTelegram& t, bool& retry) {
    if (t.direction != Direction::Request || !t.dp.fdl.has_fc || t.dp.fdl.da == kBroadcastAddress)
        return;
    std::uint8_t function = t.dp.fdl.fc.function();
    if (function == static_cast<std::uint8_t>(FdlFunction::FdlStatus)) {
        ch.fcb_valid = false;  // the frame count restarts after FDL_Status
        return;
    }
    if (!function_is_srd(function) && !function_is_sda(function)) return;
    if (!t.dp.fdl.fc.fcv()) {
        ch.fcb_valid = false;
        return;
    }
    bool fcb = t.dp.fdl.fc.fcb();
    if (ch.fcb_valid && ch.last_fcb == fcb) {
        retry = true;
        add(FindingKind::FdlRetry, t, 0).message =
            fmt::format("{} request to station {} repeated with the same FCB {}",
                        request_function_name(function), t.slave, fcb ? 1 : 0);
    }
    ch.last_fcb = fcb;
    ch.fcb_valid = true;
}

void SessionTracker::check_config(Channel& ch, const DecodedTelegram& t) {
    if (t.dp.ppo.source != PpoSource::ChkCfg && t.dp.ppo.source != PpoSource::GetCfg) return;
    const bool request = t.direction == Direction::Request;
    std::size_t actual = t.dp.fdl.du.size();
    // A response without data (SC, or a status such as RS after a restart) carries no inputs to
    // measure.
    if (!request && actual == 0) return;
    std::size_t expected = request ? t.dp.ppo.output_bytes : t.dp.ppo.input_bytes;
    std::size_t& state = request ? ch.output_mismatch : ch.input_mismatch;
    if (actual == expected) {
        state = 0;
        return;
    }
    if (state == actual + 1) return;  // already reported for this length
    state = actual + 1;
    const StationConfig& config = decoder_.station(t.slave);
    add(FindingKind::ConfigMismatch, t, 0).message =
        fmt::format("Data_Exchange {} carries {} bytes; the {} in frame {} announced {}",
                    request ? "request" : "response", actual,
                    t.dp.ppo.source == PpoSource::ChkCfg ? "Chk_Cfg" : "Get_Cfg response",
                    config.cfg_frame, expected);
}

void SessionTracker::master_pcv(Channel& ch, const DecodedTelegram& t) {
    const Pcv& p = t.dp.pcv;
    if (ch.master_spm_valid && p.spm != ch.master_spm) {
        ch.master_toggled = true;
        if (ch.spontaneous.pending) {
            ch.spontaneous.pending = false;  // acknowledged
        } else {
            add(FindingKind::SpmViolation, t, 0).message =
                fmt::format("master {} toggled SPM to {} with no spontaneous message pending",
                            t.master, p.spm ? 1 : 0);
        }
    }
    ch.master_spm = p.spm;
    ch.master_spm_valid = true;

    PcvKey key = key_of(p);
    if (ch.master_valid && key == ch.master_key) return;  // the request stands
    ch.master_valid = true;
    ch.master_key = key;
    // The master moved on.
    if (ch.pending.active) {
        if (!ch.pending.timed_out) {
            if (p.rc == 0) ++ch.stats.abandoned;
            if (p.rc != 0) {
                Finding& f = add(FindingKind::StackedRequest, t, ch.pending.frame);
                f.pnu = ch.pending.key.pnu;
                f.message =
                    fmt::format("new request {} while {} from frame {} was still unanswered",
                                describe_request(t.dp.dialect, key),
                                describe_request(t.dp.dialect, ch.pending.key), ch.pending.frame);
            }
        }
        ch.previous =
            Channel::Previous{true, ch.pending.key, false, true, ch.stats.cycles, false, 0};
        ch.pending.active = false;
    } else if (ch.previous.valid && !ch.previous.moved_on) {
        ch.previous.moved_on = true;
        ch.previous.moved_on_cycle = ch.stats.cycles;
    }
    if (p.rc == 0) return;
    const bool undefined = !request_code(t.dp.dialect, p.rc).defined;
    if (undefined) {
        Finding& f = add(FindingKind::UnknownCode, t, 0);
        f.pnu = p.pnu;
        f.message = fmt::format("request code RC {} is not defined in the {} dialect", p.rc,
                                dialect_name(t.dp.dialect));
    }
    ch.pending = Channel::Pending{true, key, t.frame, t.time_ns, ch.stats.cycles, false, undefined};
    ch.orphan_valid = false;
    if (t.has_time())
        next_deadline_ns_ = std::min(next_deadline_ns_, t.time_ns + options_.timeout_ns);
    ++ch.stats.requests;
    ++ch.stats.pnu_requests[p.pnu];
}

void SessionTracker::slave_pcv(Channel& ch, const DecodedTelegram& t) {
    const Pcv& r = t.dp.pcv;
    const Dialect dialect = t.dp.dialect;
    const ResponseCode& code = response_code(dialect, r.rc);
    ch.slave_spm = r.spm;
    ch.slave_spm_valid = true;
    PcvKey key = key_of(r);

    if (code.kind == ResponseKind::Spontaneous) {
        Channel::Spontaneous& message = ch.spontaneous;
        // A new message toggles SPM; the same SPM again is the message repeated.
        if (message.seen && r.spm == message.spm) {
            // Taken as acknowledged before the capture, yet still shown after the one cycle the
            // slave lags: it was not acknowledged, it is pending since it was first seen.
            if (message.assumed_acknowledged && ch.stats.cycles > message.cycle + 1) {
                message.assumed_acknowledged = false;
                message.pending = true;
                if (message.time_ns != kNoTime)
                    next_deadline_ns_ =
                        std::min(next_deadline_ns_, message.time_ns + options_.timeout_ns);
            }
            return;
        }
        // A capture that begins after the master acknowledged: the first message seen already
        // has the master's SPM, and the master has not toggled since.
        const bool acknowledged =
            !message.seen && ch.master_spm_valid && !ch.master_toggled && ch.master_spm == r.spm;
        message =
            Channel::Spontaneous{true,  !acknowledged, r.spm,        t.frame,        t.time_ns,
                                 r.pnu, false,         acknowledged, ch.stats.cycles};
        ++ch.stats.spontaneous;
        Finding& f = add(FindingKind::SpontaneousMessage, t, 0);
        f.pnu = r.pnu;
        f.message = fmt::format("spontaneous message RC {} ({}) PNU {} value {} with SPM {}{}",
                                r.rc, code.meaning, r.pnu, pcv_value(r, code.width), r.spm ? 1 : 0,
                                acknowledged ? " (already acknowledged)" : "");
        if (acknowledged) return;
        if (t.has_time())
            next_deadline_ns_ = std::min(next_deadline_ns_, t.time_ns + options_.timeout_ns);
        return;
    }
    if (code.kind == ResponseKind::Undefined) {
        if (ch.unknown_valid && key == ch.unknown_key) return;
        ch.unknown_valid = true;
        ch.unknown_key = key;
        Finding& f = add(FindingKind::UnknownCode, t, ch.pending.active ? ch.pending.frame : 0);
        f.pnu = r.pnu;
        f.message = fmt::format("response code RC {} is not defined in the {} dialect", r.rc,
                                dialect_name(dialect));
        return;
    }
    ch.unknown_valid = false;

    // RC 7 and RC 8 may leave the PNU out (a Danfoss rejection reads PCA 70 00); with a PNU it
    // must be the request's.
    const bool negative =
        code.kind == ResponseKind::Rejected || code.kind == ResponseKind::NoAuthority;
    const bool no_echo = negative && r.pnu == 0;
    // The response in the cycle in which a request first appears shows what the slave made of
    // the master's data before it (the slave lags one cycle): it cannot answer that request.
    const bool before_pending = ch.pending.active && ch.stats.cycles == ch.pending.cycle;
    // A rejection without its PNU is about the request it answers (or repeats the answer to).
    if (no_echo) {
        if (ch.pending.active && !before_pending)
            subject_pnu_ = ch.pending.key.pnu;
        else if (ch.previous.valid)
            subject_pnu_ = ch.previous.key.pnu;
    }
    // Could `r` be the slave's answer to the pending request? Its parameter, a valid code for
    // it, and for a change request answered positively, the value written.
    auto answers_pending = [&] {
        const PcvKey& q = ch.pending.key;
        if (!no_echo && !concerns(dialect, q, r)) return false;
        if (ch.pending.undefined) return true;
        if (judge_answer(dialect, q.rc, r.rc, options_.strict) == AnswerVerdict::Invalid)
            return false;
        const RequestCode& request = request_code(dialect, q.rc);
        if (code.kind == ResponseKind::Value && request.is_change)
            return same_value(request.width, code.width, q.pva, r.pva);
        return true;
    };
    bool fresh = !(ch.slave_valid && key == ch.slave_key);
    if (fresh) {
        ch.slave_valid = true;
        ch.slave_key = key;
        ch.slave_change_cycle = ch.stats.cycles;
        if (ch.orphan_valid && !same_parameter(ch.orphan_key, key)) ch.orphan_valid = false;
    } else {
        // A repeat is ignored, except when it answers a request issued after it first appeared
        // (in the same cycle counts: a response is made before its cycle's request arrives) -
        // a slave that does not clear its answer, a read-back returning the value just written:
        // the same bytes are then that request's answer, a cycle after it was sent. A rejection
        // is taken again only for the same request asked again.
        bool renewed = ch.pending.active && !before_pending && r.rc != 0 &&
                       ch.pending.cycle >= ch.slave_change_cycle && answers_pending() &&
                       (!negative || (ch.previous.valid && ch.previous.key == ch.pending.key));
        if (!renewed) return;
    }
    if (r.rc == 0) return;  // no response: idle, or still working

    // Answers to the request before the pending one are no orphans and no mismatches: repeats
    // with a refreshed value while the master still holds that request, the lagging one in the
    // cycle the master moved on, and the late answer to an abandoned request.
    auto belongs_to_previous = [&] {
        Channel::Previous& prev = ch.previous;
        if (!prev.valid || !concerns(dialect, prev.key, r)) return false;
        if (!prev.answered) {
            if (prev.late_answer_seen) return false;
            prev.late_answer_seen = true;
            return true;
        }
        return r.rc == prev.answer_rc && (!prev.moved_on || ch.stats.cycles == prev.moved_on_cycle);
    };

    if (!ch.pending.active || before_pending) {
        if (before_pending && !ch.previous.valid && ch.pending.cycle <= 1 && answers_pending()) {
            // The capture began while this request stood answered: it was issued before the
            // first captured cycle, so it is neither a transaction nor a time-out.
            auto requests = ch.stats.pnu_requests.find(ch.pending.key.pnu);
            if (requests != ch.stats.pnu_requests.end() && --requests->second == 0)
                ch.stats.pnu_requests.erase(requests);
            --ch.stats.requests;
            ch.previous = Channel::Previous{true, ch.pending.key, true, false, 0, false, r.rc};
            ch.pending.active = false;
            return;
        }
        if (belongs_to_previous()) return;
        // The first cycle of a capture: the request this answers was not captured.
        if (!ch.previous.valid && ch.stats.cycles <= 1) return;
        // A slave that keeps refreshing the same orphan answer is reported once.
        if (ch.orphan_valid) return;
        ch.orphan_valid = true;
        ch.orphan_key = key;
        Finding& f = add(FindingKind::OrphanResponse, t, 0);
        f.pnu = r.pnu;
        f.message = fmt::format("slave {} answered RC {} ({}) PNU {} but no request was pending",
                                t.slave, r.rc, code.meaning, r.pnu);
        return;
    }

    const PcvKey& q = ch.pending.key;
    if (!no_echo && !concerns(dialect, q, r)) {
        if (belongs_to_previous()) return;
        Finding& f = add(FindingKind::MismatchedResponse, t, ch.pending.frame);
        f.pnu = q.pnu;
        f.message = fmt::format(
            "answer RC {} for PNU {}{} to request {} from frame {}", r.rc, r.pnu,
            request_code(dialect, q.rc).is_array || code.is_array ? fmt::format(" IND {}", r.ind)
                                                                  : "",
            describe_request(dialect, q), ch.pending.frame);
        ++ch.stats.transactions.mismatched;
        answered(ch, t);
        return;
    }

    // An undefined request code cannot be judged: any answer is taken for what it says.
    AnswerVerdict verdict = ch.pending.undefined
                                ? (negative ? AnswerVerdict::Negative : AnswerVerdict::Positive)
                                : judge_answer(dialect, q.rc, r.rc, options_.strict);
    if (verdict == AnswerVerdict::Invalid) {
        Finding& f = add(FindingKind::UnexpectedResponseType, t, ch.pending.frame);
        f.pnu = q.pnu;
        f.message = fmt::format("RC {} ({}) is no valid answer to {} from frame {}", r.rc,
                                code.meaning, describe_request(dialect, q), ch.pending.frame);
        ++ch.stats.transactions.unexpected;
    } else if (code.kind == ResponseKind::Rejected) {
        auto error = static_cast<std::uint16_t>(r.pva & 0xFFFF);
        std::string_view text = error_text(dialect, error);
        Finding& f = add(FindingKind::RequestRejected, t, ch.pending.frame);
        f.pnu = q.pnu;
        f.message = fmt::format("{} rejected with error {} ({})", describe_request(dialect, q),
                                error, text.empty() ? "not known to the dialect" : text);
        ++ch.stats.transactions.rejected;
        ++ch.stats.rejection_errors[error];
        if (ch.stats.rejections.size() < 1024 || ch.stats.rejections.count({q.pnu, error}))
            ++ch.stats.rejections[{q.pnu, error}];
    } else if (code.kind == ResponseKind::NoAuthority) {
        Finding& f = add(FindingKind::NoAuthority, t, ch.pending.frame);
        f.pnu = q.pnu;
        f.message = fmt::format("no operating authority for {}{}", describe_request(dialect, q),
                                verdict == AnswerVerdict::Unusual ? " (RC 8 after a read)" : "");
        ++ch.stats.transactions.no_authority;
    } else {
        ++ch.stats.transactions.positive;
    }
    answered(ch, t);
}

void SessionTracker::answered(Channel& ch, const DecodedTelegram& t) {
    ChannelStats& stats = ch.stats;
    if (t.has_time() && ch.pending.time_ns != kNoTime) {
        stats.latency_ns.add(
            static_cast<std::uint64_t>(std::max<std::int64_t>(0, t.time_ns - ch.pending.time_ns)));
        stats.timeline.add_transaction(t.time_ns);
    }
    stats.latency_cycles.add(stats.cycles - ch.pending.cycle);
    ch.previous = Channel::Previous{true, ch.pending.key, true, false, 0, false, t.dp.pcv.rc};
    ch.pending.active = false;
}

void SessionTracker::check_deadlines(const DecodedTelegram* at, std::int64_t now_ns) {
    if (now_ns < next_deadline_ns_ && at != nullptr) return;
    std::int64_t next = kNever;
    const std::uint64_t frame = at ? at->frame : last_frame_;
    for (auto& owned : channels_) {
        Channel& ch = *owned;
        Channel::Pending& p = ch.pending;
        if (p.active && !p.timed_out && p.time_ns != kNoTime) {
            std::int64_t deadline = p.time_ns + options_.timeout_ns;
            if (now_ns > deadline) {
                p.timed_out = true;
                ++ch.stats.timeouts;
                Finding& f = add_for(FindingKind::ResponseTimeout, frame, now_ns, p.frame, true,
                                     ch.stats.master, ch.stats.slave);
                f.pnu = p.key.pnu;
                f.message = fmt::format(
                    "no answer to request {} from frame {} within {} ms",
                    describe_request(decoder_.options().dialect_of(ch.stats.slave), p.key), p.frame,
                    options_.timeout_ns / 1'000'000);
            } else {
                next = std::min(next, deadline);
            }
        }
        Channel::Spontaneous& s = ch.spontaneous;
        if (s.pending && !s.reported_late && s.time_ns != kNoTime) {
            std::int64_t deadline = s.time_ns + options_.timeout_ns;
            if (now_ns > deadline) {
                s.reported_late = true;
                Finding& f = add_for(FindingKind::SpontaneousUnacknowledged, frame, now_ns, s.frame,
                                     true, ch.stats.master, ch.stats.slave);
                f.pnu = s.pnu;
                f.message = fmt::format(
                    "spontaneous message from frame {} (PNU {}) not "
                    "acknowledged within {} ms",
                    s.frame, s.pnu, options_.timeout_ns / 1'000'000);
            } else {
                next = std::min(next, deadline);
            }
        }
    }
    next_deadline_ns_ = next;
}

}  // namespace dpscope
