#include "protocols/vlt2000/vlt2000_tracker.hpp"

#include <fmt/compile.h>
#include <fmt/format.h>

#include <algorithm>
#include <string>

#include "core/finding_list.hpp"
#include "protocols/vlt2000/vlt2000_codes.hpp"

namespace dpscope {

namespace {

constexpr FindingKind kVlt2000Kinds[] = {
    FindingKind::MalformedTelegram,         FindingKind::Vlt2000StackedRequest,
    FindingKind::Vlt2000NoResponse,         FindingKind::Vlt2000UnexpectedReply,
    FindingKind::Vlt2000MismatchedResponse, FindingKind::Vlt2000CommandFailed,
    FindingKind::Vlt2000ChecksumError,      FindingKind::Vlt2000ChecksumDisabled,
};

// The VLT 2000 channel: no SPM bit, the reply in the same exchange, every command new. The
// engine counts; the tracker words every finding itself (letters and parameters, not codes).
ParameterChannelPolicy vlt2000_policy(const Vlt2000TrackerOptions& options) {
    ParameterChannelPolicy policy;
    policy.has_spm_bit = false;
    policy.response_lags_one_cycle = false;
    policy.cyclic_requests = false;
    policy.timeout_ns = options.timeout_ns;
    policy.kinds = ParameterChannelKinds{std::nullopt, std::nullopt, std::nullopt, std::nullopt,
                                         std::nullopt, std::nullopt, std::nullopt, std::nullopt,
                                         std::nullopt, std::nullopt, std::nullopt};
    return policy;
}

constexpr std::uint8_t kMaster = 0;  // the master has no address

// "U (update) parameter 516", "C (control)".
std::string describe(Vlt2000Letter letter, std::uint8_t letter_char, std::uint16_t parameter) {
    if (letter == Vlt2000Letter::Control) return "C (control)";
    if (letter == Vlt2000Letter::Unknown)
        return fmt::format(FMT_COMPILE("letter 0x{:02X} parameter {}"), letter_char, parameter);
    return fmt::format(FMT_COMPILE("{} ({}) parameter {}"), vlt2000_letter_char(letter),
                       vlt2000_letter_name(letter), parameter);
}

// A telegram's or a pending command's letter and parameter, as findings name them. Written only
// for a finding, never for every telegram (issue 31).
template <typename Command>
std::string describe(const Command& c) {
    return describe(c.letter, c.letter_char, c.parameter);
}

// The letter's row in commands_by_letter (U, R, C, I).
std::size_t letter_row(Vlt2000Letter letter) { return static_cast<std::size_t>(letter); }

}  // namespace

std::span<const FindingKind> vlt2000_finding_kinds() noexcept { return kVlt2000Kinds; }

bool is_vlt2000_finding_kind(FindingKind kind) noexcept {
    return std::find(std::begin(kVlt2000Kinds), std::end(kVlt2000Kinds), kind) !=
           std::end(kVlt2000Kinds);
}

Vlt2000Tracker::Vlt2000Tracker(Vlt2000TrackerOptions options)
    : options_(options), engine_(vlt2000_policy(options)), index_(kStationCount, -1) {}

Vlt2000Tracker::~Vlt2000Tracker() = default;

Vlt2000StationStats& Vlt2000Tracker::station(std::uint8_t address) {
    const std::size_t key = address & 0x7Fu;
    if (index_[key] < 0) {
        index_[key] = static_cast<std::int32_t>(stations_.size());
        auto st = std::make_unique<Vlt2000StationStats>();
        st->address = static_cast<std::uint8_t>(key);
        engine_.add_channel(kMaster, st->address, st->channel);
        stations_.push_back(std::move(st));
    }
    return *stations_[static_cast<std::size_t>(index_[key])];
}

std::vector<const Vlt2000StationStats*> Vlt2000Tracker::stations() const {
    std::vector<const Vlt2000StationStats*> out;
    for (const auto& st : stations_)
        out.push_back(st.get());
    std::sort(out.begin(), out.end(),
              [](const Vlt2000StationStats* a, const Vlt2000StationStats* b) {
                  return a->address < b->address;
              });
    return out;
}

bool Vlt2000Tracker::has_station(std::uint8_t address) const {
    return std::any_of(stations_.begin(), stations_.end(),
                       [address](const auto& s) { return s->address == address; });
}

// Besides the early replies: most telegrams with a wrong checksum by the VLT 3000/3500 rule,
// perhaps because the drives compute it otherwise (docs/decisions.md); the option is named.
std::vector<std::string> Vlt2000Tracker::end_warnings(std::uint64_t telegrams) const {
    std::vector<std::string> warnings =
        early_response_warning(early_responses_, options_.line_baud, options_.character_bits);
    std::uint64_t wrong = 0;
    for (const auto& st : stations_)
        wrong += st->checksum_errors;
    if (wrong >= 4 && wrong * 2 >= telegrams)
        warnings.push_back(fmt::format(
            "{} of {} telegrams have a wrong checksum by the VLT 3000/3500 rule (the sum of the 18 "
            "characters after '<'); if the drives compute it otherwise, --vlt2000-checksum ignore "
            "decodes them without it",
            wrong, telegrams));
    return warnings;
}

std::uint64_t Vlt2000Tracker::transactions() const noexcept {
    std::uint64_t total = 0;
    for (const auto& st : stations_)
        total += st->answered;
    return total;
}

void Vlt2000Tracker::count() {
    for (const Finding& f : current_) {
        const auto kind = static_cast<std::size_t>(f.kind);
        const auto severity = static_cast<std::size_t>(f.severity);
        ++by_severity_[severity];
        if (f.has_stations) {
            Vlt2000StationStats& st = station(f.slave);
            ++st.findings[kind];
            ++st.findings_by_severity[kind][severity];
        } else {
            ++bus_.findings[kind];
            ++bus_.findings_by_severity[kind][severity];
        }
    }
}

bool Vlt2000Tracker::check_intact(const DecodedTelegram& t, bool answers_pending) {
    const ProblemList& problems = t.problems();
    for (const Problem& p : problems) {
        if (p.kind != ProblemKind::Vlt2000ChecksumMismatch) continue;
        add_finding(current_, FindingKind::Vlt2000ChecksumError, t.frame, t.time_ns,
                    answers_pending ? pending_.frame : 0, t.has_roles, kMaster, t.slave)
            .message = problem_message(p);
        if (t.has_roles) ++station(t.slave).checksum_errors;
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

void Vlt2000Tracker::close_pending() {
    if (pending_.active) engine_.abandon(kMaster, pending_.address);
    pending_.active = false;
}

bool Vlt2000Tracker::pending_judged() const noexcept {
    // The capture began with it: a tap clipped onto a running line may start with a drive's
    // reply, which nothing before it marks as one (docs/decisions.md, "VLT 2000").
    return pending_.frame != first_addressed_frame_;
}

void Vlt2000Tracker::check_deadline(std::int64_t now_ns, std::uint64_t frame) {
    if (!pending_.active || pending_.time_ns == kNoTime ||
        now_ns <= pending_.time_ns + options_.timeout_ns)
        return;
    if (!pending_judged()) {
        ++station(pending_.address).not_judged;
        close_pending();
        return;
    }
    Finding& f = add_finding(current_, FindingKind::Vlt2000NoResponse, frame, now_ns,
                             pending_.frame, true, kMaster, pending_.address);
    if (pending_.letter != Vlt2000Letter::Control) f.pnu = pending_.parameter;
    f.message = fmt::format("command {} to drive {:02} from frame {} got no reply within {} ms",
                            describe(pending_), pending_.address, pending_.frame,
                            options_.timeout_ns / 1'000'000);
    ++station(pending_.address).no_responses;
    close_pending();
}

ParameterChannelSample Vlt2000Tracker::sample_of(const DecodedTelegram& t,
                                                 std::uint64_t cycle) const {
    const Vlt2000Telegram& v = t.vlt2000;
    ParameterChannelSample s;
    s.frame = t.frame;
    s.time_ns = t.time_ns;
    s.direction = t.direction;
    s.master = kMaster;
    s.slave = t.slave;
    s.dialect = Dialect::Vlt2000;
    s.cycle = cycle;
    const bool reply = t.direction == Direction::Response;
    s.pcv.rc = reply && v.failed ? kVlt2000CodeFailed : vlt2000_code(v.letter);
    // A C telegram's parameter is ignored [S004]: not compared.
    s.pcv.pnu = v.letter == Vlt2000Letter::Control ? 0 : v.parameter;
    // A failed command's reason code (100: none given) is the engine's error number.
    s.pcv.pva = reply && v.failed ? (v.has_reason ? v.reason : 100u)
                                  : static_cast<std::uint32_t>(v.signed_digits());
    s.pcv.pca = static_cast<std::uint16_t>(s.pcv.rc << 12);
    return s;
}

std::span<const Finding> Vlt2000Tracker::track(const DecodedTelegram& t) {
    current_.clear();
    completed_.clear();
    last_frame_ = t.frame;
    const Vlt2000Telegram& v = t.vlt2000;
    subject_pnu_ = v.has_parameter && v.letter != Vlt2000Letter::Control ? v.parameter : -1;
    // The reply to the pending command (damaged or not) ends the wait for it before any deadline
    // is checked: a reply is never a missing one.
    const bool answers_pending = t.has_roles && t.direction == Direction::Response &&
                                 pending_.active && t.slave == pending_.address;
    if (t.has_time()) {
        now_ns_ = t.time_ns;
        if (!answers_pending) check_deadline(t.time_ns, t.frame);
    }
    if (!check_intact(t, answers_pending)) {
        // Counted by its direction, as decode -q counts it: a damaged command's outcome is
        // "damaged" (a reply to it is no finding of its own), a damaged reply answers nothing.
        if (t.has_roles) {
            Vlt2000StationStats& st = station(t.slave);
            if (t.direction == Direction::Request) {
                damaged_command_frame_ = t.frame;
                ++st.commands;
                ++st.damaged_commands;
                ++(v.broadcast ? st.broadcasts : st.damaged);
            } else {
                ++st.replies;
                ++st.damaged_replies;
            }
        }
        // A damaged reply from the drive the command went to ends the wait: "damaged".
        if (answers_pending) {
            ++station(pending_.address).damaged;
            close_pending();
        }
        count();
        return current_;
    }
    if (!t.has_roles) {
        count();
        return current_;
    }
    if (first_addressed_frame_ == 0) first_addressed_frame_ = t.frame;
    Vlt2000StationStats& st = station(t.slave);
    ++st.telegrams;
    if (t.has_time()) {
        if (st.first_time_ns == kNoTime) st.first_time_ns = t.time_ns;
        st.last_time_ns = t.time_ns;
    }
    if (v.checksum_disabled) {
        ++st.checksum_disabled;
        if (!checksum_disabled_said_[t.slave % 100]) {
            checksum_disabled_said_[t.slave % 100] = true;
            add_finding(current_, FindingKind::Vlt2000ChecksumDisabled, t.frame, t.time_ns, 0, true,
                        kMaster, t.slave)
                .message = fmt::format(
                "the {} in frame {} carries \"??\" for its checksum: the check is switched off "
                "for drive {:02} (said once per address)",
                t.direction == Direction::Response ? "reply" : "command", t.frame, t.slave);
        }
    }
    if (t.direction == Direction::Request)
        command(st, t);
    else
        reply(st, t);
    count();
    return current_;
}

void Vlt2000Tracker::command(Vlt2000StationStats& st, const DecodedTelegram& t) {
    const Vlt2000Telegram& v = t.vlt2000;
    // The master moved on: the command it sent before is left unanswered.
    if (pending_.active) {
        const std::optional<std::uint16_t> pnu =
            pending_.letter == Vlt2000Letter::Control
                ? std::nullopt
                : std::optional<std::uint16_t>(pending_.parameter);
        if (!pending_judged()) {
            // The capture's first telegram, perhaps a reply: neither unanswered nor stacked on.
            ++station(pending_.address).not_judged;
        } else if (!v.broadcast && t.slave == pending_.address) {
            ++st.abandoned;
            Finding& f = add_finding(current_, FindingKind::Vlt2000StackedRequest, t.frame,
                                     t.time_ns, pending_.frame, true, kMaster, t.slave);
            f.pnu = pnu;
            f.message = fmt::format(
                "new command {} to drive {:02} while the command {} from frame {} was unanswered",
                describe(v), t.slave, describe(pending_), pending_.frame);
        } else {
            Finding& f = add_finding(current_, FindingKind::Vlt2000NoResponse, t.frame, t.time_ns,
                                     pending_.frame, true, kMaster, pending_.address);
            f.pnu = pnu;
            f.message = fmt::format(
                "command {} to drive {:02} from frame {} got no reply before the master's next "
                "telegram",
                describe(pending_), pending_.address, pending_.frame);
            ++station(pending_.address).no_responses;
        }
        close_pending();
    }

    ++st.commands;
    if (!v.broadcast) commanded_.set(t.slave & 0x7F);
    if (v.letter != Vlt2000Letter::Unknown) ++st.commands_by_letter[letter_row(v.letter)];
    if (v.broadcast) ++st.broadcasts;
    if (v.has_parameter && v.letter != Vlt2000Letter::Control &&
        v.letter != Vlt2000Letter::Unknown) {
        const bool write = v.letter == Vlt2000Letter::Update;
        // One walk of the map: the row found is the row counted (a new one while there is room).
        auto it = st.parameters.lower_bound(v.parameter);
        if (it == st.parameters.end() || it->first != v.parameter) {
            if (st.parameters.size() >= Vlt2000StationStats::kMaxParameters) {
                ++st.parameters_not_counted;
                it = st.parameters.end();
            } else {
                it = st.parameters.emplace_hint(it, v.parameter, Vlt2000ParameterAccess{});
            }
        }
        if (it != st.parameters.end()) ++(write ? it->second.writes : it->second.reads);
    }
    if (v.broadcast) return;  // nobody replies to a broadcast
    pending_ = Pending{true, t.slave, t.frame, t.time_ns, v.letter_char, v.letter, v.parameter};
    engine_.track(sample_of(t, st.commands), current_);
}

void Vlt2000Tracker::reply(Vlt2000StationStats& st, const DecodedTelegram& t) {
    const Vlt2000Telegram& v = t.vlt2000;
    ++st.replies;
    if (v.failed) {
        ++st.failed;
        if (v.has_reason)
            ++st.failures_by_reason[v.reason];
        else
            ++st.failures_without_reason;
    }
    if (v.broadcast) {
        // The decoder took it for the reply to a broadcast: nobody should have sent it.
        Finding& f = add_finding(current_, FindingKind::Vlt2000UnexpectedReply, t.frame, t.time_ns,
                                 t.request_frame, true, kMaster, t.slave);
        if (v.letter != Vlt2000Letter::Control) f.pnu = v.parameter;
        f.message = t.request_frame != 0
                        ? fmt::format(
                              "reply {} to the broadcast from frame {}: nobody replies "
                              "to address 00",
                              describe(v), t.request_frame)
                        : fmt::format("reply {} with address 00: nobody replies to a broadcast",
                                      describe(v));
        return;
    }
    if (!pending_.active && t.request_frame != 0 && t.request_frame == damaged_command_frame_)
        return;  // the reply to a command with a wrong checksum, which was the finding
    if (!pending_.active || t.slave != pending_.address) {
        // Before the first command to the drive, its command may have come before the capture.
        if (!commanded_.test(t.slave & 0x7F)) return;
        Finding& f =
            add_finding(current_, FindingKind::Vlt2000MismatchedResponse, t.frame, t.time_ns,
                        pending_.active ? pending_.frame : 0, true, kMaster, t.slave);
        if (v.letter != Vlt2000Letter::Control) f.pnu = v.parameter;
        f.message = pending_.active
                        ? fmt::format(
                              "reply {} from drive {:02} while the command to drive {:02} from "
                              "frame {} was pending",
                              describe(v), t.slave, pending_.address, pending_.frame)
                        : fmt::format("reply {} from drive {:02} but no command was pending",
                                      describe(v), t.slave);
        return;  // the command pending (if any) still waits for its drive
    }

    const Pending command = pending_;
    const bool timed = t.has_time() && command.time_ns != kNoTime;
    if (timed) {
        // The drive's reply time: from the command's last character to the reply's first.
        const auto wire_ns =
            options_.line_baud == 0
                ? std::int64_t{0}
                : static_cast<std::int64_t>(static_cast<double>(kVlt2000TelegramSize) *
                                            options_.character_bits * 1e9 /
                                            static_cast<double>(options_.line_baud));
        if (t.time_ns - command.time_ns < wire_ns) ++early_responses_;
        const auto latency = static_cast<std::uint64_t>(
            std::max<std::int64_t>(0, t.time_ns - command.time_ns - wire_ns));
        st.latency_ns.add(latency);
        st.latency_sum_ns += latency;
    }
    ++st.answered;
    completed_.push_back(CompletedTransaction{kMaster, t.slave, t.frame, t.time_ns, timed});

    const std::optional<std::uint16_t> pnu = command.letter == Vlt2000Letter::Control
                                                 ? std::nullopt
                                                 : std::optional<std::uint16_t>(command.parameter);
    if (v.letter_char != command.letter_char ||
        (command.letter != Vlt2000Letter::Control && v.parameter != command.parameter)) {
        Finding& f = add_finding(current_, FindingKind::Vlt2000MismatchedResponse, t.frame,
                                 t.time_ns, command.frame, true, kMaster, t.slave);
        f.pnu = pnu;
        f.message = fmt::format(
            "reply {}{} answers the command {} from frame {}", describe(v),
            v.letter_char != command.letter_char ? " (another letter)" : " (another parameter)",
            describe(command), command.frame);
    } else if (v.failed) {
        Finding& f = add_finding(current_, FindingKind::Vlt2000CommandFailed, t.frame, t.time_ns,
                                 command.frame, true, kMaster, t.slave);
        f.pnu = pnu;
        f.message =
            v.has_reason
                ? fmt::format(FMT_COMPILE("drive {:02} could not carry out the command {} from "
                                          "frame {}: reason code {:02} ({})"),
                              t.slave, describe(command), command.frame, v.reason,
                              error_text_or_unknown(Dialect::Vlt2000, v.reason))
                : fmt::format(FMT_COMPILE("drive {:02} could not carry out the command {} from "
                                          "frame {} (decimal position 9: unknown parameter or "
                                          "command failed)"),
                              t.slave, describe(command), command.frame);
    }
    pending_.active = false;
    engine_.track(sample_of(t, st.commands), current_);
}

std::span<const Finding> Vlt2000Tracker::finish(std::int64_t end_ns) {
    current_.clear();
    completed_.clear();
    if (end_ns != kNoTime && (now_ns_ == kNoTime || end_ns > now_ns_)) now_ns_ = end_ns;
    if (now_ns_ != kNoTime) check_deadline(now_ns_, last_frame_);
    // Still waiting within its time-out when the capture ended: not judged (open). finish() may
    // come again with a later end, which may time it out.
    for (const auto& st : stations_)
        st->open = 0;
    if (pending_.active) station(pending_.address).open = 1;
    count();
    return current_;
}

}  // namespace dpscope
