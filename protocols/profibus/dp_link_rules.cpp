#include "protocols/profibus/dp_link_rules.hpp"

#include <fmt/format.h>

namespace dpscope {

namespace {

// A problem of error severity at any layer makes the telegram unusable for the rules.
bool is_error_problem(const Problem& p) { return problem_severity(p.kind) == Severity::Error; }

Finding& add(FindingList& out, FindingKind kind, const DecodedTelegram& t) {
    return add_finding(out, kind, t.frame, t.time_ns, 0, t.has_roles, t.master, t.slave);
}

// A request that counts frames: SRD or SDA to one station.
bool counts_frames(const DecodedTelegram& t) {
    if (t.direction != Direction::Request || !t.dp.fdl.has_fc || t.dp.fdl.da == kBroadcastAddress)
        return false;
    const std::uint8_t function = t.dp.fdl.fc.function();
    return function_is_srd(function) || function_is_sda(function);
}

}  // namespace

void report_reply_missing(const DecodedTelegram& t, FindingList& out) {
    if (!t.dp.unanswered ||
        !(function_is_srd(t.dp.unanswered->function) || function_is_sda(t.dp.unanswered->function)))
        return;
    const UnansweredRequest& u = *t.dp.unanswered;
    add_finding(out, FindingKind::FdlNoResponse, t.frame, t.time_ns, u.frame, true, u.master,
                u.slave)
        .message = fmt::format(
        "{} request to station {} ({}) got no reply before the master's "
        "next telegram",
        request_function_name(u.function), u.slave, service_name(u.service));
}

bool report_damage(const DecodedTelegram& t, FindingList& out) {
    if (!t.dp.fdl.fcs_ok) {
        Finding& f = add(out, FindingKind::FcsError, t);
        for (const Problem& p : t.problems())
            if (p.kind == ProblemKind::FcsMismatch) f.message = problem_message(p);
        return false;
    }
    for (const Problem& p : t.problems()) {
        if (!is_error_problem(p)) continue;
        add(out, FindingKind::MalformedTelegram, t).message =
            fmt::format("{}: {}", problem_kind_name(p.kind), problem_message(p));
        return false;
    }
    return true;
}

bool check_frame_count(FrameCountState& state, const DecodedTelegram& t, FindingList& out) {
    if (t.direction != Direction::Request || !t.dp.fdl.has_fc || t.dp.fdl.da == kBroadcastAddress)
        return false;
    const std::uint8_t function = t.dp.fdl.fc.function();
    if (function == static_cast<std::uint8_t>(FdlFunction::FdlStatus)) {
        state.valid = false;  // the frame count restarts after FDL_Status
        return false;
    }
    if (!counts_frames(t)) return false;
    if (!t.dp.fdl.fc.fcv()) {
        state.valid = false;
        return false;
    }
    const bool fcb = t.dp.fdl.fc.fcb();
    const bool retry = state.valid && state.last_fcb == fcb;
    if (retry)
        add(out, FindingKind::FdlRetry, t).message =
            fmt::format("{} request to station {} repeated with the same FCB {}",
                        request_function_name(function), t.slave, fcb ? 1 : 0);
    state.last_fcb = fcb;
    state.valid = true;
    return retry;
}

bool note_dropped_request(FrameCountState& state, const DecodedTelegram& t) {
    if (t.dp.fdl.fcs_ok || !counts_frames(t) || !t.dp.fdl.fc.fcv()) return false;
    state.last_fcb = t.dp.fdl.fc.fcb();
    state.valid = true;
    return true;
}

}  // namespace dpscope
