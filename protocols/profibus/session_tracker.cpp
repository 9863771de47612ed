#include "protocols/profibus/session_tracker.hpp"

#include <algorithm>
#include <utility>

namespace dpscope {

// ---- DialectEvidence ---------------------------------------------------------------------------

void DialectEvidence::note_dialect(Dialect dialect) noexcept {
    if (decoded_ == dialect) return;
    // The dialect changed: the codes and error numbers counted start again (the ident stays).
    const bool has_ident = has_ident_;
    const std::uint16_t ident = ident_;
    const bool pcv_seen = pcv_seen_;
    *this = DialectEvidence{};
    decoded_ = dialect;
    has_ident_ = has_ident;
    ident_ = ident;
    pcv_seen_ = pcv_seen;
}

void DialectEvidence::add(const DecodedTelegram& t) noexcept {
    if (!t.dp.fdl.fcs_ok) return;
    if (t.dp.service != Service::DataExchange) {
        if (const SetPrm* prm = t.dp.service_data.set_prm(); prm && t.problems().empty()) {
            has_ident_ = true;
            ident_ = prm->ident;
        } else if (const SlaveDiag* diag = t.dp.service_data.slave_diag();
                   diag && t.direction == Direction::Response && t.problems().empty()) {
            has_ident_ = true;
            ident_ = diag->ident;
        }
        return;
    }
    if (!t.dp.has_pcv) return;
    note_dialect(t.dp.dialect);
    pcv_seen_ = true;
    const bool request = t.direction == Direction::Request;
    auto defines = [&](Dialect dialect) {
        return request ? request_code(dialect, t.dp.pcv.rc).defined
                       : response_code(dialect, t.dp.pcv.rc).kind != ResponseKind::Undefined;
    };
    if (!defines(t.dp.dialect)) {
        ++undefined_;
        for (Dialect other : kDialects)
            if (other != decoded_ && defines(other))
                ++other_defines_[static_cast<std::size_t>(other)];
        return;
    }
    // A rejection's error number (bytes 7-8).
    if (request || response_code(t.dp.dialect, t.dp.pcv.rc).kind != ResponseKind::Rejected) return;
    const auto error = static_cast<std::uint16_t>(t.dp.pcv.pva & 0xFFFF);
    if (!error_text(t.dp.dialect, error).empty()) return;
    ++undefined_errors_;
    const auto named = error_numbers_.begin() + static_cast<std::ptrdiff_t>(named_errors_);
    if (std::find(error_numbers_.begin(), named, error) == named) {
        if (named_errors_ < kNamedErrors)
            error_numbers_[named_errors_++] = error;
        else
            more_errors_ = true;
    }
    for (Dialect other : kDialects)
        if (other != decoded_ && response_code(other, t.dp.pcv.rc).kind == ResponseKind::Rejected &&
            !error_text(other, error).empty())
            ++other_defines_error_[static_cast<std::size_t>(other)];
}

std::pair<std::optional<Dialect>, DialectEvidence::Basis> DialectEvidence::judge() const noexcept {
    // The ident hints only for a slave with a parameter channel (whose dialect is named).
    if (has_ident_ && pcv_seen_)
        if (std::optional<Dialect> named = dialect_of_ident(ident_); named && *named != decoded_)
            return {named, Basis::Ident};
    // The first dialect in kDialects order that defines every one of them: vlt before ge (vlt
    // defines all ge does and RC 9..12 besides), then profidrive.
    if (undefined_ >= kMinimum)
        for (Dialect other : kDialects)
            if (other != decoded_ && other_defines_[static_cast<std::size_t>(other)] == undefined_)
                return {other, Basis::Codes};
    if (undefined_errors_ > 0)
        for (Dialect other : kDialects)
            if (other != decoded_ &&
                other_defines_error_[static_cast<std::size_t>(other)] == undefined_errors_)
                return {other, Basis::Errors};
    return {std::nullopt, Basis::None};
}

// ---- SessionTracker -----------------------------------------------------------------------------

namespace {

// Every problem of error severity is data cut short (service_data_short): the FDL telegram
// itself is whole.
bool only_cut_short(const DecodedTelegram& t) {
    for (const Problem& p : t.problems())
        if (problem_severity(p.kind) == Severity::Error && p.kind != ProblemKind::ServiceDataShort)
            return false;
    return true;
}

// The PROFIBUS DP parameter channel: the response lags one cycle, the PKE has an SPM bit.
ParameterChannelPolicy dp_policy(const TrackerOptions& options) {
    ParameterChannelPolicy policy;
    policy.has_spm_bit = true;
    policy.response_lags_one_cycle = true;
    policy.strict = options.strict;
    policy.timeout_ns = options.timeout_ns;
    return policy;
}

}  // namespace

SessionTracker::SessionTracker(TrackerOptions options)
    : options_(options),
      gsd_line_(gsd_line(options.line_baud)),
      engine_(dp_policy(options)),
      dpv1_(options.timeout_ns) {}

SessionTracker::~SessionTracker() = default;

SessionTracker::Channel& SessionTracker::channel(std::uint8_t master, std::uint8_t slave) {
    std::int32_t position = index_.find(master, slave);
    if (position == ChannelIndex::kNone) {
        position = static_cast<std::int32_t>(channels_.size());
        index_.set(master, slave, position);
        auto ch = std::make_unique<Channel>();
        ch->stats.master = master & 0x7F;
        ch->stats.slave = slave & 0x7F;
        // The engine checks time-outs channel by channel in the order they are made here.
        engine_.add_channel(ch->stats.master, ch->stats.slave, ch->stats);
        dpv1_.add_channel(ch->stats.master, ch->stats.slave, ch->stats.dpv1);
        channels_.push_back(std::move(ch));
    }
    return *channels_[static_cast<std::size_t>(position)];
}

bool SessionTracker::has_station(std::uint8_t address) const {
    const std::vector<const ChannelStats*> seen = channels();
    return std::any_of(seen.begin(), seen.end(),
                       [address](const ChannelStats* s) { return s->slave == address; });
}

std::vector<const ChannelStats*> SessionTracker::channels() const {
    std::vector<const ChannelStats*> out;
    for (const auto& ch : channels_)
        if (ch->stats.data_exchange > 0 || ch->stats.requests > 0 || ch->stats.dpv1.telegrams > 0 ||
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
        total += ch->stats.transactions.total() + ch->stats.dpv1.completed;
    return total;
}

void SessionTracker::count(std::size_t from, std::size_t to) {
    for (std::size_t i = from; i < to; ++i) {
        const Finding& f = current_[i];
        ++by_severity_[static_cast<std::size_t>(f.severity)];
        const auto kind = static_cast<std::size_t>(f.kind);
        const auto severity = static_cast<std::size_t>(f.severity);
        if (f.has_stations) {
            ChannelStats& stats = channel(f.master, f.slave).stats;
            ++stats.findings[kind];
            ++stats.findings_by_severity[kind][severity];
        } else {
            ++bus_.findings[kind];
            ++bus_.findings_by_severity[kind][severity];
        }
    }
}

std::span<const Finding> SessionTracker::track(const DecodedTelegram& t) {
    current_.clear();
    completed_.clear();
    last_frame_ = t.frame;
    subject_pnu_ = t.dp.has_pcv ? t.dp.pcv.pnu : -1;
    if (t.has_time()) {
        now_ns_ = t.time_ns;
        engine_.advance(now_ns_, t.frame, current_);
        dpv1_.advance(now_ns_, t.frame, current_);
    }
    check_reply_missing(t, current_);
    const std::size_t damage = current_.size();
    const bool intact = check_intact(t, current_);
    const bool dpv1 = t.dp.service_data.kind() == DpServiceData::Kind::Dpv1 && t.dp.fdl.fcs_ok;
    // A DP-V1 telegram with a correct FCS whose only defect is data cut short: its
    // malformed_telegram waits for the DP-V1 tracker, whose length rule may say the same.
    const bool held = !intact && dpv1 && t.has_roles && only_cut_short(t);
    // Counted before the telegram's own channel is made: channels are made in the order their
    // first finding or telegram came, the order the engine checks them for time-outs in (a held
    // finding is the telegram's own channel's).
    if (!current_.empty()) count(0, held ? damage : current_.size());
    if (!t.has_roles) return current_;
    const std::size_t counted = held ? damage : current_.size();
    Channel& ch = channel(t.master, t.slave);
    track_channel(ch, t, intact);
    const std::size_t dpv1_from = current_.size();
    if (dpv1) dpv1_.track(t, current_);
    // One defect, one finding: the DP-V1 one (docs/decisions.md, "DP-V1 data cut short").
    if (held && std::any_of(current_.begin() + static_cast<std::ptrdiff_t>(dpv1_from),
                            current_.end(), [&](const Finding& f) {
                                return f.kind == FindingKind::Dpv1LengthError && f.frame == t.frame;
                            }))
        current_.erase(current_.begin() + static_cast<std::ptrdiff_t>(damage));
    if (current_.size() > counted) count(counted, current_.size());
    return current_;
}

void SessionTracker::track_channel(Channel& ch, const DecodedTelegram& t, bool intact) {
    if (!intact) {
        // With a correct FCS the station received the telegram, whatever its data unit held:
        // its FCB counts, so a repeat of it is a retry and the next request no false one.
        if (t.dp.fdl.fcs_ok)
            check_frame_count(ch.frame_count, t, current_);
        else if (note_dropped_request(ch.frame_count, t))
            ch.damaged_request = true;
        return;
    }
    const bool retry = check_frame_count(ch.frame_count, t, current_);
    if (t.dp.device) {
        if (!ch.gsd) {
            ch.gsd = std::make_unique<GsdCheckState>();
            ch.stats.gsd = &ch.gsd->stats;
        }
        check_gsd(*ch.gsd, t, gsd_line_, retry, current_);
    }
    if (t.dp.service != Service::DataExchange) return;

    ChannelStats& stats = ch.stats;
    ++stats.data_exchange;
    stats.ppo = t.dp.ppo;
    stats.dialect = t.dp.dialect;
    if (t.has_time()) {
        if (stats.first_time_ns == kNoTime) stats.first_time_ns = t.time_ns;
        stats.last_time_ns = t.time_ns;
    }
    if (t.direction == Direction::Request) {
        if (!retry || ch.damaged_request) ++stats.cycles;
        ch.damaged_request = false;
    }
    check_config(ch.config, t, current_);
    if (!t.dp.has_pcv) return;
    const ParameterChannelSample sample{t.frame, t.time_ns, t.direction,  t.master,
                                        t.slave, t.dp.pcv,  t.dp.dialect, stats.cycles};
    if (auto transaction = engine_.track(sample, current_)) completed_.push_back(*transaction);
    subject_pnu_ = engine_.subject_pnu();
}

std::span<const Finding> SessionTracker::finish(std::int64_t end_ns) {
    current_.clear();
    completed_.clear();
    if (end_ns != kNoTime && (now_ns_ == kNoTime || end_ns > now_ns_)) now_ns_ = end_ns;
    if (now_ns_ != kNoTime) {
        engine_.advance(now_ns_, last_frame_, current_);
        dpv1_.advance(now_ns_, last_frame_, current_);
    }
    count(0, current_.size());
    return current_;
}

}  // namespace dpscope
