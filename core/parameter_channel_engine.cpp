#include "core/parameter_channel_engine.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <string>

namespace dpscope {

namespace {

// "in the vlt dialect"; the FC protocol has one table, no dialect.
std::string where_defined(Dialect dialect) {
    if (dialect == Dialect::Fc) return "in the FC protocol";
    return fmt::format("in the {} dialect", dialect_name(dialect));
}

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
    return fmt::format("{} {} ({}) PNU {}{}", code_label(dialect), q.rc,
                       request_code(dialect, q.rc).meaning, q.pnu,
                       request_code(dialect, q.rc).is_array ? fmt::format(" IND {}", q.ind) : "");
}

// The finding as the carrier's kind, or nullptr when the carrier does not have the engine report
// it.
Finding* add(FindingList& out, std::optional<FindingKind> kind, const ParameterChannelSample& s,
             std::uint64_t request_frame) {
    if (!kind) return nullptr;
    return &add_finding(out, *kind, s.frame, s.time_ns, request_frame, true, s.master, s.slave);
}

}  // namespace

struct ParameterChannelEngine::Channel {
    std::uint8_t master = 0;
    std::uint8_t slave = 0;
    ParameterChannelStats* stats = nullptr;
    // Master side.
    bool master_valid = false;
    PcvKey master_key;
    bool master_spm_valid = false;
    bool master_spm = false;
    bool master_toggled = false;  // the master's SPM has changed since the capture began
    struct Pending {
        bool active = false;
        PcvKey key;
        Dialect dialect = Dialect::Vlt;
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
    // Slave side.
    bool slave_valid = false;
    PcvKey slave_key;
    std::uint64_t slave_change_cycle = 0;
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
        PcvKey key;  // without an SPM bit, a new message is a change of the slave's PCV
    } spontaneous;
};

ParameterChannelEngine::ParameterChannelEngine(ParameterChannelPolicy policy) : policy_(policy) {}

ParameterChannelEngine::~ParameterChannelEngine() = default;

void ParameterChannelEngine::add_channel(std::uint8_t master, std::uint8_t slave,
                                         ParameterChannelStats& stats) {
    if (index_.find(master, slave) != ChannelIndex::kNone) return;
    index_.set(master, slave, static_cast<std::int32_t>(channels_.size()));
    auto ch = std::make_unique<Channel>();
    ch->master = master & 0x7F;
    ch->slave = slave & 0x7F;
    ch->stats = &stats;
    channels_.push_back(std::move(ch));
}

std::optional<CompletedTransaction> ParameterChannelEngine::track(
    const ParameterChannelSample& sample, FindingList& out) {
    subject_pnu_ = sample.pcv.pnu;
    std::int32_t position = index_.find(sample.master, sample.slave);
    if (position < 0) return std::nullopt;
    Channel& ch = *channels_[static_cast<std::size_t>(position)];
    ++ch.stats->parameter_telegrams;
    if (sample.direction == Direction::Request) {
        master_pcv(ch, sample, out);
        return std::nullopt;
    }
    return slave_pcv(ch, sample, out);
}

void ParameterChannelEngine::master_pcv(Channel& ch, const ParameterChannelSample& s,
                                        FindingList& out) {
    const Pcv& p = s.pcv;
    if (policy_.has_spm_bit) {
        if (ch.master_spm_valid && p.spm != ch.master_spm) {
            ch.master_toggled = true;
            if (ch.spontaneous.pending) {
                ch.spontaneous.pending = false;  // acknowledged
            } else {
                if (Finding* f = add(out, policy_.kinds.spm_violation, s, 0))
                    f->message = fmt::format(
                        "master {} toggled SPM to {} with no spontaneous message pending", s.master,
                        p.spm ? 1 : 0);
            }
        }
        ch.master_spm = p.spm;
        ch.master_spm_valid = true;
    }

    PcvKey key = key_of(p);
    // The request stands (where requests are repeated cyclically).
    if (policy_.cyclic_requests && ch.master_valid && key == ch.master_key) return;
    ch.master_valid = true;
    ch.master_key = key;
    ParameterChannelStats& stats = *ch.stats;
    // The master moved on.
    if (ch.pending.active) {
        if (!ch.pending.timed_out) {
            if (p.rc == 0) ++stats.abandoned;
            if (p.rc != 0) {
                if (Finding* f = add(out, policy_.kinds.stacked_request, s, ch.pending.frame)) {
                    f->pnu = ch.pending.key.pnu;
                    f->message =
                        fmt::format("new request {} while {} from frame {} was still unanswered",
                                    describe_request(s.dialect, key),
                                    describe_request(s.dialect, ch.pending.key), ch.pending.frame);
                }
            }
        }
        ch.previous = Channel::Previous{true, ch.pending.key, false, true, s.cycle, false, 0};
        ch.pending.active = false;
    } else if (ch.previous.valid && !ch.previous.moved_on) {
        ch.previous.moved_on = true;
        ch.previous.moved_on_cycle = s.cycle;
    }
    if (p.rc == 0) return;
    const bool undefined = !request_code(s.dialect, p.rc).defined;
    if (undefined) {
        if (Finding* f = add(out, policy_.kinds.unknown_code, s, 0)) {
            f->pnu = p.pnu;
            f->message = fmt::format("request code {} {} is not defined {}", code_label(s.dialect),
                                     p.rc, where_defined(s.dialect));
        }
    }
    ch.pending =
        Channel::Pending{true, key, s.dialect, s.frame, s.time_ns, s.cycle, false, undefined};
    ch.orphan_valid = false;
    if (s.time_ns != kNoTime && policy_.kinds.response_timeout)
        next_deadline_ns_ = std::min(next_deadline_ns_, s.time_ns + policy_.timeout_ns);
    ++stats.requests;
    ++stats.pnu_requests[p.pnu];
}

void ParameterChannelEngine::spontaneous_message(Channel& ch, const ParameterChannelSample& s,
                                                 FindingList& out) {
    const Pcv& r = s.pcv;
    const ResponseCode& code = response_code(s.dialect, r.rc);
    Channel::Spontaneous& message = ch.spontaneous;
    const PcvKey key = key_of(r);
    if (!policy_.has_spm_bit) {
        // Nothing to toggle, nothing to acknowledge: a message is new when the PCV changes.
        if (message.seen && key == message.key) return;
        message = Channel::Spontaneous{};
        message.seen = true;
        message.frame = s.frame;
        message.time_ns = s.time_ns;
        message.pnu = r.pnu;
        message.cycle = s.cycle;
        message.key = key;
        ++ch.stats->spontaneous;
        if (Finding* f = add(out, policy_.kinds.spontaneous_message, s, 0)) {
            f->pnu = r.pnu;
            f->message = fmt::format("spontaneous message RC {} ({}) PNU {} value {}", r.rc,
                                     code.meaning, r.pnu, pcv_value(r, code.width));
        }
        return;
    }
    // A new message toggles SPM; the same SPM again is the message repeated.
    if (message.seen && r.spm == message.spm) {
        // Taken as acknowledged before the capture, yet still shown after the cycle the slave
        // lags: it was not acknowledged, it is pending since it was first seen.
        const std::uint64_t lag = policy_.response_lags_one_cycle ? 1 : 0;
        if (message.assumed_acknowledged && s.cycle > message.cycle + lag) {
            message.assumed_acknowledged = false;
            message.pending = true;
            if (message.time_ns != kNoTime)
                next_deadline_ns_ =
                    std::min(next_deadline_ns_, message.time_ns + policy_.timeout_ns);
        }
        return;
    }
    // A capture that begins after the master acknowledged: the first message seen already has
    // the master's SPM, and the master has not toggled since.
    const bool acknowledged =
        !message.seen && ch.master_spm_valid && !ch.master_toggled && ch.master_spm == r.spm;
    message = Channel::Spontaneous{true,  !acknowledged, r.spm,        s.frame, s.time_ns,
                                   r.pnu, false,         acknowledged, s.cycle, key};
    ++ch.stats->spontaneous;
    if (Finding* f = add(out, policy_.kinds.spontaneous_message, s, 0)) {
        f->pnu = r.pnu;
        f->message = fmt::format("spontaneous message RC {} ({}) PNU {} value {} with SPM {}{}",
                                 r.rc, code.meaning, r.pnu, pcv_value(r, code.width), r.spm ? 1 : 0,
                                 acknowledged ? " (already acknowledged)" : "");
    }
    if (acknowledged) return;
    if (s.time_ns != kNoTime)
        next_deadline_ns_ = std::min(next_deadline_ns_, s.time_ns + policy_.timeout_ns);
}

std::optional<CompletedTransaction> ParameterChannelEngine::slave_pcv(
    Channel& ch, const ParameterChannelSample& s, FindingList& out) {
    const Pcv& r = s.pcv;
    const Dialect dialect = s.dialect;
    const ResponseCode& code = response_code(dialect, r.rc);
    ParameterChannelStats& stats = *ch.stats;
    PcvKey key = key_of(r);
    // The cycles a response trails the request it answers.
    const std::uint64_t lag = policy_.response_lags_one_cycle ? 1 : 0;

    if (code.kind == ResponseKind::Spontaneous) {
        spontaneous_message(ch, s, out);
        return std::nullopt;
    }
    if (code.kind == ResponseKind::Undefined) {
        // Repeated in every cycle, it is reported once; without cyclic repetition each is new.
        if (policy_.cyclic_requests && ch.unknown_valid && key == ch.unknown_key)
            return std::nullopt;
        ch.unknown_valid = true;
        ch.unknown_key = key;
        if (Finding* f =
                add(out, policy_.kinds.unknown_code, s, ch.pending.active ? ch.pending.frame : 0)) {
            f->pnu = r.pnu;
            f->message = fmt::format("response code {} {} is not defined {}", code_label(dialect),
                                     r.rc, where_defined(dialect));
        }
        return std::nullopt;
    }
    ch.unknown_valid = false;

    // RC 7 and RC 8 may leave the PNU out (a Danfoss rejection reads PCA 70 00); with a PNU it
    // must be the request's.
    const bool negative =
        code.kind == ResponseKind::Rejected || code.kind == ResponseKind::NoAuthority;
    const bool no_echo = negative && r.pnu == 0;
    // Where the slave lags, the response in the cycle in which a request first appears shows
    // what the slave made of the master's data before it: it cannot answer that request.
    const bool before_pending = ch.pending.active && lag == 1 && s.cycle == ch.pending.cycle;
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
        if (judge_answer(dialect, q.rc, r.rc, policy_.strict) == AnswerVerdict::Invalid)
            return false;
        const RequestCode& request = request_code(dialect, q.rc);
        if (code.kind == ResponseKind::Value && request.is_change)
            return same_value(request.width, code.width, q.pva, r.pva);
        return true;
    };
    // Without cyclic repetition every response is an answer of its own.
    bool fresh = !policy_.cyclic_requests || !(ch.slave_valid && key == ch.slave_key);
    if (fresh) {
        ch.slave_valid = true;
        ch.slave_key = key;
        ch.slave_change_cycle = s.cycle;
        if (ch.orphan_valid && !same_parameter(ch.orphan_key, key)) ch.orphan_valid = false;
    } else {
        // A repeat is ignored, except when it answers a request issued after it first appeared
        // - a slave that does not clear its answer, a read-back returning the value just
        // written: the same bytes are then that request's answer. Where the slave lags, a
        // request in the same cycle counts (a response is made before its cycle's request
        // arrives). A rejection is taken again only for the same request asked again.
        const bool issued_after = ch.pending.cycle + lag > ch.slave_change_cycle;
        bool renewed = ch.pending.active && !before_pending && r.rc != 0 && issued_after &&
                       answers_pending() &&
                       (!negative || (ch.previous.valid && ch.previous.key == ch.pending.key));
        if (!renewed) return std::nullopt;
    }
    if (r.rc == 0) return std::nullopt;  // no response: idle, or still working

    // Answers to the request before the pending one are no orphans and no mismatches: repeats
    // with a refreshed value while the master still holds that request, the lagging one in the
    // cycle the master moved on, and the late answer to an abandoned request.
    auto belongs_to_previous = [&] {
        Channel::Previous& prev = ch.previous;
        // Without cyclic repetition nothing repeats an earlier answer.
        if (!policy_.cyclic_requests) return false;
        if (!prev.valid || !concerns(dialect, prev.key, r)) return false;
        if (!prev.answered) {
            if (prev.late_answer_seen) return false;
            prev.late_answer_seen = true;
            return true;
        }
        return r.rc == prev.answer_rc &&
               (!prev.moved_on || (lag == 1 && s.cycle == prev.moved_on_cycle));
    };

    if (!ch.pending.active || before_pending) {
        if (before_pending && !ch.previous.valid && ch.pending.cycle <= 1 && answers_pending()) {
            // The capture began while this request stood answered: it was issued before the
            // first captured cycle, so it is neither a transaction nor a time-out.
            auto requests = stats.pnu_requests.find(ch.pending.key.pnu);
            if (requests != stats.pnu_requests.end() && --requests->second == 0)
                stats.pnu_requests.erase(requests);
            --stats.requests;
            ch.previous = Channel::Previous{true, ch.pending.key, true, false, 0, false, r.rc};
            ch.pending.active = false;
            return std::nullopt;
        }
        if (belongs_to_previous()) return std::nullopt;
        // The capture's first cycle (the lagging slave's, or before the first request): the
        // request this answers was not captured.
        if (!ch.previous.valid && s.cycle <= lag) return std::nullopt;
        // A slave that keeps refreshing the same orphan answer is reported once.
        if (ch.orphan_valid) return std::nullopt;
        ch.orphan_valid = true;
        ch.orphan_key = key;
        if (Finding* f = add(out, policy_.kinds.orphan_response, s, 0)) {
            f->pnu = r.pnu;
            f->message =
                fmt::format("slave {} answered {} {} ({}) PNU {} but no request was pending",
                            s.slave, code_label(dialect), r.rc, code.meaning, r.pnu);
        }
        return std::nullopt;
    }

    const PcvKey& q = ch.pending.key;
    if (!no_echo && !concerns(dialect, q, r)) {
        if (belongs_to_previous()) return std::nullopt;
        if (Finding* f = add(out, policy_.kinds.mismatched_response, s, ch.pending.frame)) {
            f->pnu = q.pnu;
            f->message = fmt::format("answer {} {} for PNU {}{} to request {} from frame {}",
                                     code_label(dialect), r.rc, r.pnu,
                                     request_code(dialect, q.rc).is_array || code.is_array
                                         ? fmt::format(" IND {}", r.ind)
                                         : "",
                                     describe_request(dialect, q), ch.pending.frame);
        }
        ++stats.transactions.mismatched;
        return answered(ch, s);
    }

    // An undefined request code cannot be judged: any answer is taken for what it says.
    AnswerVerdict verdict = ch.pending.undefined
                                ? (negative ? AnswerVerdict::Negative : AnswerVerdict::Positive)
                                : judge_answer(dialect, q.rc, r.rc, policy_.strict);
    if (verdict == AnswerVerdict::Invalid) {
        if (Finding* f = add(out, policy_.kinds.unexpected_response_type, s, ch.pending.frame)) {
            f->pnu = q.pnu;
            f->message = fmt::format("{} {} ({}) is no valid answer to {} from frame {}",
                                     code_label(dialect), r.rc, code.meaning,
                                     describe_request(dialect, q), ch.pending.frame);
        }
        ++stats.transactions.unexpected;
    } else if (code.kind == ResponseKind::Rejected) {
        auto error = static_cast<std::uint16_t>(r.pva & 0xFFFF);
        if (Finding* f = add(out, policy_.kinds.request_rejected, s, ch.pending.frame)) {
            f->pnu = q.pnu;
            f->message =
                fmt::format("{} rejected with {} {} ({})", describe_request(dialect, q),
                            error_label(dialect), error, error_text_or_unknown(dialect, error));
        }
        ++stats.transactions.rejected;
        ++stats.rejection_errors[error];
        if (stats.rejections.size() < 1024 || stats.rejections.count({q.pnu, error}))
            ++stats.rejections[{q.pnu, error}];
    } else if (code.kind == ResponseKind::NoAuthority) {
        if (Finding* f = add(out, policy_.kinds.no_authority, s, ch.pending.frame)) {
            f->pnu = q.pnu;
            f->message =
                fmt::format("no operating authority for {}{}", describe_request(dialect, q),
                            verdict == AnswerVerdict::Unusual ? " (RC 8 after a read)" : "");
        }
        ++stats.transactions.no_authority;
    } else {
        ++stats.transactions.positive;
    }
    return answered(ch, s);
}

CompletedTransaction ParameterChannelEngine::answered(Channel& ch,
                                                      const ParameterChannelSample& s) {
    ParameterChannelStats& stats = *ch.stats;
    const bool timed = s.time_ns != kNoTime && ch.pending.time_ns != kNoTime;
    if (timed)
        stats.latency_ns.add(
            static_cast<std::uint64_t>(std::max<std::int64_t>(0, s.time_ns - ch.pending.time_ns)));
    stats.latency_cycles.add(s.cycle - ch.pending.cycle);
    ch.previous = Channel::Previous{true, ch.pending.key, true, false, 0, false, s.pcv.rc};
    ch.pending.active = false;
    return CompletedTransaction{ch.master, ch.slave, s.frame, s.time_ns, timed};
}

void ParameterChannelEngine::abandon(std::uint8_t master, std::uint8_t slave) {
    std::int32_t position = index_.find(master, slave);
    if (position < 0) return;
    Channel& ch = *channels_[static_cast<std::size_t>(position)];
    if (!ch.pending.active) return;
    if (!ch.pending.timed_out) ++ch.stats->abandoned;
    ch.previous = Channel::Previous{true, ch.pending.key, false, true, ch.pending.cycle, false, 0};
    ch.pending.active = false;
}

void ParameterChannelEngine::check_deadlines(std::int64_t now_ns, std::uint64_t frame,
                                             FindingList& out) {
    std::int64_t next = kNever;
    for (auto& owned : channels_) {
        Channel& ch = *owned;
        Channel::Pending& p = ch.pending;
        if (p.active && !p.timed_out && p.time_ns != kNoTime && policy_.kinds.response_timeout) {
            std::int64_t deadline = p.time_ns + policy_.timeout_ns;
            if (now_ns > deadline) {
                p.timed_out = true;
                ++ch.stats->timeouts;
                Finding& f = add_finding(out, *policy_.kinds.response_timeout, frame, now_ns,
                                         p.frame, true, ch.master, ch.slave);
                f.pnu = p.key.pnu;
                f.message = fmt::format("no answer to request {} from frame {} within {} ms",
                                        describe_request(p.dialect, p.key), p.frame,
                                        policy_.timeout_ns / 1'000'000);
            } else {
                next = std::min(next, deadline);
            }
        }
        Channel::Spontaneous& m = ch.spontaneous;
        if (m.pending && !m.reported_late && m.time_ns != kNoTime) {
            std::int64_t deadline = m.time_ns + policy_.timeout_ns;
            if (now_ns > deadline) {
                m.reported_late = true;
                if (policy_.kinds.spontaneous_unacknowledged) {
                    Finding& f = add_finding(out, *policy_.kinds.spontaneous_unacknowledged, frame,
                                             now_ns, m.frame, true, ch.master, ch.slave);
                    f.pnu = m.pnu;
                    f.message = fmt::format(
                        "spontaneous message from frame {} (PNU {}) not "
                        "acknowledged within {} ms",
                        m.frame, m.pnu, policy_.timeout_ns / 1'000'000);
                }
            } else {
                next = std::min(next, deadline);
            }
        }
    }
    next_deadline_ns_ = next;
}

}  // namespace dpscope
