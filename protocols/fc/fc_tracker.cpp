#include "protocols/fc/fc_tracker.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <string>

#include "core/finding_list.hpp"
#include "protocols/fc/fc_codes.hpp"

namespace dpscope {

namespace {

constexpr FindingKind kFcKinds[] = {
    FindingKind::MalformedTelegram,
    FindingKind::UnknownCode,
    FindingKind::FcStackedRequest,
    FindingKind::FcNoResponse,
    FindingKind::FcLateResponse,
    FindingKind::FcMismatchedResponse,
    FindingKind::FcUnexpectedResponseType,
    FindingKind::FcCommandRejected,
    FindingKind::FcBccError,
};

// The FC parameter channel: no SPM bit, the response in the same exchange, every command new;
// the engine's findings as the FC kinds, or left to the tracker's link pairing (stacked, time-out,
// orphan: it pairs every block kind). FC has no "no authority" code and no spontaneous messages.
ParameterChannelPolicy fc_policy(const FcTrackerOptions& options) {
    ParameterChannelPolicy policy;
    policy.has_spm_bit = false;
    policy.response_lags_one_cycle = false;
    policy.cyclic_requests = false;
    policy.timeout_ns = options.timeout_ns;
    ParameterChannelKinds& kinds = policy.kinds;
    kinds.stacked_request = std::nullopt;
    kinds.orphan_response = std::nullopt;
    kinds.mismatched_response = FindingKind::FcMismatchedResponse;
    kinds.unexpected_response_type = FindingKind::FcUnexpectedResponseType;
    kinds.response_timeout = std::nullopt;
    kinds.request_rejected = FindingKind::FcCommandRejected;
    kinds.no_authority = std::nullopt;
    kinds.spontaneous_message = std::nullopt;
    kinds.spontaneous_unacknowledged = std::nullopt;
    kinds.spm_violation = std::nullopt;
    kinds.unknown_code = FindingKind::UnknownCode;
    return policy;
}

constexpr std::uint8_t kMaster = 0;  // the FC master has no address

std::string describe_command(const DecodedTelegram& t) {
    const FcTelegram& fc = t.fc;
    if (!fc.has_pkw) return fmt::format("{} block", fc_block_name(fc.block));
    return fmt::format("AK {} ({}) PNU {}", fc.pkw.rc, fc_command(fc.pkw.rc).meaning, fc.pkw.pnu);
}

std::string what_pending(bool pkw, std::uint8_t ak, std::uint16_t pnu) {
    if (!pkw) return "process block";
    return fmt::format("AK {} ({}) PNU {}", ak, fc_command(ak).meaning, pnu);
}

}  // namespace

std::span<const FindingKind> fc_finding_kinds() noexcept { return kFcKinds; }

bool is_fc_finding_kind(FindingKind kind) noexcept {
    return std::find(std::begin(kFcKinds), std::end(kFcKinds), kind) != std::end(kFcKinds);
}

FcTracker::FcTracker(FcTrackerOptions options)
    : options_(options), engine_(fc_policy(options)), index_(kStationCount, -1) {}

FcTracker::~FcTracker() = default;

FcStationStats& FcTracker::station(std::uint8_t address) {
    const std::size_t key = address & 0x7Fu;
    if (index_[key] < 0) {
        index_[key] = static_cast<std::int32_t>(stations_.size());
        auto st = std::make_unique<FcStationStats>();
        st->address = static_cast<std::uint8_t>(key);
        engine_.add_channel(kMaster, st->address, st->channel);
        stations_.push_back(std::move(st));
    }
    return *stations_[static_cast<std::size_t>(index_[key])];
}

std::vector<const FcStationStats*> FcTracker::stations() const {
    std::vector<const FcStationStats*> out;
    for (const auto& st : stations_)
        out.push_back(st.get());
    std::sort(out.begin(), out.end(), [](const FcStationStats* a, const FcStationStats* b) {
        return a->address < b->address;
    });
    return out;
}

bool FcTracker::has_station(std::uint8_t address) const {
    return std::any_of(stations_.begin(), stations_.end(),
                       [address](const auto& s) { return s->address == address; });
}

std::vector<std::string> FcTracker::end_warnings(std::uint64_t) const {
    return early_response_warning(early_responses_, options_.line_baud, options_.character_bits);
}

std::uint64_t FcTracker::transactions() const noexcept {
    std::uint64_t total = 0;
    for (const auto& st : stations_)
        total += st->answered;
    return total;
}

void FcTracker::count(std::size_t from) {
    for (std::size_t i = from; i < current_.size(); ++i) {
        const Finding& f = current_[i];
        const auto kind = static_cast<std::size_t>(f.kind);
        const auto severity = static_cast<std::size_t>(f.severity);
        ++by_severity_[severity];
        if (f.has_stations) {
            FcStationStats& st = station(f.slave);
            ++st.findings[kind];
            ++st.findings_by_severity[kind][severity];
        } else {
            ++bus_.findings[kind];
            ++bus_.findings_by_severity[kind][severity];
        }
    }
}

bool FcTracker::check_intact(const DecodedTelegram& t) {
    const ProblemList& problems = t.problems();
    if (problems.empty()) return true;
    for (const Problem& p : problems) {
        if (p.kind != ProblemKind::BccMismatch) continue;
        add_finding(current_, FindingKind::FcBccError, t.frame, t.time_ns, 0, t.has_roles, kMaster,
                    t.slave)
            .message = problem_message(p);
        return false;
    }
    for (const Problem& p : problems) {
        if (problem_severity(p.kind) != Severity::Error) continue;
        add_finding(current_, FindingKind::MalformedTelegram, t.frame, t.time_ns, 0, t.has_roles,
                    kMaster, t.slave)
            .message = fmt::format("{}: {}", problem_kind_name(p.kind), problem_message(p));
        return false;
    }
    return true;
}

void FcTracker::close_pending() {
    if (pending_.active && pending_.pkw) engine_.abandon(kMaster, pending_.address);
    pending_.active = false;
}

bool FcTracker::pending_judged() const noexcept {
    // The capture began with it: a tap clipped onto a running bus often starts with a drive's
    // response, which nothing before it marks as one (docs/decisions.md). It is not judged,
    // unless its AK says it is a command.
    return pending_.frame != first_addressed_frame_ || pending_.certain;
}

void FcTracker::check_deadline(std::int64_t now_ns, std::uint64_t frame) {
    if (!pending_.active || pending_.time_ns == kNoTime ||
        now_ns <= pending_.time_ns + pending_.wire_ns + options_.timeout_ns)
        return;
    if (!pending_judged()) {
        ++station(pending_.address).not_judged;
        close_pending();
        return;
    }
    Finding& f = add_finding(current_, FindingKind::FcNoResponse, frame, now_ns, pending_.frame,
                             true, kMaster, pending_.address);
    if (pending_.pkw) f.pnu = pending_.pnu;
    f.message = fmt::format("command {} to drive {} from frame {} got no response within {} ms",
                            what_pending(pending_.pkw, pending_.ak, pending_.pnu), pending_.address,
                            pending_.frame, options_.timeout_ns / 1'000'000);
    ++station(pending_.address).no_responses;
    close_pending();
}

std::span<const Finding> FcTracker::track(const DecodedTelegram& t) {
    current_.clear();
    completed_.clear();
    last_frame_ = t.frame;
    subject_pnu_ = t.fc.has_pkw ? t.fc.pkw.pnu : -1;
    // The answer to the pending command (damaged or not) ends the wait for it before any
    // deadline is checked: an answer is never a missing one.
    const bool answers_pending = t.has_roles && t.direction == Direction::Response &&
                                 pending_.active && t.slave == pending_.address;
    if (t.has_time()) {
        now_ns_ = t.time_ns;
        if (!answers_pending) check_deadline(t.time_ns, t.frame);
    }
    if (!check_intact(t)) {
        // Counted by its direction, as decode -q counts it: a damaged command is dropped by the
        // drive (its outcome: damaged), a damaged response answers nothing.
        if (t.has_roles) {
            FcStationStats& st = station(t.slave);
            if (t.direction == Direction::Request) {
                ++st.commands;
                ++st.damaged_commands;
                ++(t.fc.broadcast ? st.broadcasts : st.damaged);
            } else {
                ++st.responses;
                ++st.damaged_responses;
            }
        }
        // A damaged answer from the drive the command went to: it answered; the BCC error (or
        // malformed_telegram) is the finding, the command's outcome "damaged".
        if (answers_pending) {
            ++station(pending_.address).damaged;
            close_pending();
        }
        count(0);
        return current_;
    }
    if (!t.has_roles) {
        count(0);
        return current_;
    }
    if (first_addressed_frame_ == 0) first_addressed_frame_ = t.frame;
    FcStationStats& st = station(t.slave);
    ++st.telegrams;
    if (t.has_time()) {
        if (st.first_time_ns == kNoTime) st.first_time_ns = t.time_ns;
        st.last_time_ns = t.time_ns;
    }
    if (t.direction == Direction::Request)
        command(st, t);
    else
        response(st, t);
    count(0);
    return current_;
}

void FcTracker::command(FcStationStats& st, const DecodedTelegram& t) {
    const FcTelegram& fc = t.fc;
    // The master moved on: the command it sent before is left unanswered.
    if (pending_.active) {
        const std::string pending_text = what_pending(pending_.pkw, pending_.ak, pending_.pnu);
        if (!pending_judged()) {
            // The capture's first telegram, perhaps a response: neither unanswered nor stacked on.
            ++station(pending_.address).not_judged;
        } else if (!fc.broadcast && t.slave == pending_.address) {
            ++st.abandoned;
            Finding& f = add_finding(current_, FindingKind::FcStackedRequest, t.frame, t.time_ns,
                                     pending_.frame, true, kMaster, t.slave);
            if (pending_.pkw) f.pnu = pending_.pnu;
            f.message = fmt::format(
                "new command {} to drive {} while the command {} from frame {} was unanswered",
                describe_command(t), t.slave, pending_text, pending_.frame);
        } else {
            Finding& f = add_finding(current_, FindingKind::FcNoResponse, t.frame, t.time_ns,
                                     pending_.frame, true, kMaster, pending_.address);
            if (pending_.pkw) f.pnu = pending_.pnu;
            f.message = fmt::format(
                "command {} to drive {} from frame {} got no response before the master's next "
                "telegram",
                pending_text, pending_.address, pending_.frame);
            ++station(pending_.address).no_responses;
        }
        close_pending();
    }

    ++st.commands;
    if (!fc.broadcast) commanded_.set(t.slave & 0x7F);
    if (fc.broadcast) ++st.broadcasts;
    if (fc.block == FcBlock::Process) ++st.process_commands;
    if (fc.has_pkw) {
        const std::uint8_t ak = fc.pkw.rc & 0x0F;
        ++st.commands_by_ak[ak];
        const FcCommand& code = fc_command(ak);
        const bool write = code.is_change || (ak == 15 && fc.ind_high == kFcTextWrite);
        const bool read = !write && code.defined && ak != 0;
        if (read || write) {
            auto it = st.parameters.find(fc.pkw.pnu);
            if (it == st.parameters.end() && st.parameters.size() >= FcStationStats::kMaxParameters)
                ++st.parameters_not_counted;
            else
                ++(write ? st.parameters[fc.pkw.pnu].writes : st.parameters[fc.pkw.pnu].reads);
        }
    }
    if (fc.broadcast) return;  // nobody answers a broadcast
    const auto wire_ns = options_.line_baud == 0
                             ? std::int64_t{0}
                             : static_cast<std::int64_t>(static_cast<double>(t.bytes.size()) *
                                                         options_.character_bits * 1e9 /
                                                         static_cast<double>(options_.line_baud));
    pending_ =
        Pending{true, t.slave, t.frame, t.time_ns, wire_ns, fc.has_pkw, fc.pkw.rc, fc.pkw.pnu};
    // Only a command has AK 4, 13 or 14.
    pending_.certain = fc.has_pkw && fc_command_only(fc.pkw.rc);
    if (fc.has_pkw) {
        const ParameterChannelSample sample{t.frame, t.time_ns, Direction::Request, kMaster,
                                            t.slave, fc.pkw,    Dialect::Fc,        st.commands};
        engine_.track(sample, current_);
        subject_pnu_ = engine_.subject_pnu();
    }
}

void FcTracker::response(FcStationStats& st, const DecodedTelegram& t) {
    const FcTelegram& fc = t.fc;
    ++st.responses;
    if (!pending_.active || t.slave != pending_.address) {
        // Before the first command to the drive, its command may have come before the capture.
        if (!commanded_.test(t.slave & 0x7F)) return;
        Finding& f = add_finding(current_, FindingKind::FcMismatchedResponse, t.frame, t.time_ns,
                                 pending_.active ? pending_.frame : 0, true, kMaster, t.slave);
        if (fc.has_pkw) f.pnu = fc.pkw.pnu;
        const std::string what = fc.has_pkw ? fmt::format("response AK {} ({})", fc.pkw.rc,
                                                          fc_response(fc.pkw.rc).meaning)
                                            : std::string("process block response");
        f.message = pending_.active
                        ? fmt::format(
                              "{} from drive {} while the command to drive {} from frame {} was "
                              "pending",
                              what, t.slave, pending_.address, pending_.frame)
                        : fmt::format("{} from drive {} but no command was pending", what, t.slave);
        return;  // the command pending (if any) still waits for its drive
    }

    const Pending command = pending_;
    const bool timed = t.has_time() && command.time_ns != kNoTime;
    if (timed) {
        // The drive's response time: from the command's last byte to the response's first. A
        // response that began before the command could have ended says the line was faster than
        // line_baud: counted, so that the user is told.
        if (t.time_ns - command.time_ns < command.wire_ns) ++early_responses_;
        const auto latency = static_cast<std::uint64_t>(
            std::max<std::int64_t>(0, t.time_ns - command.time_ns - command.wire_ns));
        st.latency_ns.add(latency);
        st.latency_sum_ns += latency;
        if (latency > static_cast<std::uint64_t>(options_.response_ns)) {
            ++st.late;
            Finding& f = add_finding(current_, FindingKind::FcLateResponse, t.frame, t.time_ns,
                                     command.frame, true, kMaster, t.slave);
            if (command.pkw) f.pnu = command.pnu;
            f.message = fmt::format(
                "drive {} answered the command {} from frame {} after {:.3f} ms (more than {} ms)",
                t.slave, what_pending(command.pkw, command.ak, command.pnu), command.frame,
                static_cast<double>(latency) / 1e6, options_.response_ns / 1'000'000);
        }
    }
    ++st.answered;
    completed_.push_back(CompletedTransaction{kMaster, t.slave, t.frame, t.time_ns, timed});

    if (command.pkw != fc.has_pkw) {
        // The drive answered, with the other kind of block.
        Finding& f = add_finding(current_, FindingKind::FcMismatchedResponse, t.frame, t.time_ns,
                                 command.frame, true, kMaster, t.slave);
        if (command.pkw) f.pnu = command.pnu;
        f.message =
            fmt::format("a {} block answers the command {} from frame {}", fc_block_name(fc.block),
                        what_pending(command.pkw, command.ak, command.pnu), command.frame);
        close_pending();
        return;
    }
    pending_.active = false;
    if (!fc.has_pkw) return;
    const ParameterChannelSample sample{t.frame, t.time_ns, Direction::Response, kMaster,
                                        t.slave, fc.pkw,    Dialect::Fc,         st.commands};
    engine_.track(sample, current_);
    subject_pnu_ = engine_.subject_pnu();
}

std::span<const Finding> FcTracker::finish(std::int64_t end_ns) {
    current_.clear();
    completed_.clear();
    if (end_ns != kNoTime && (now_ns_ == kNoTime || end_ns > now_ns_)) now_ns_ = end_ns;
    if (now_ns_ != kNoTime) check_deadline(now_ns_, last_frame_);
    // Still waiting within its time-out when the capture ended: not judged (open). finish() may
    // come again with a later end, which may time it out.
    for (const auto& st : stations_)
        st->open = 0;
    if (pending_.active) station(pending_.address).open = 1;
    count(0);
    return current_;
}

}  // namespace dpscope
