// Findings: what the session tracker reports about the conversation between a master and a
// slave (handshake violations, time-outs, rejections, link-level trouble). Kind names and
// default severities are fixed; they are part of every output format.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "decoder/problem.hpp"

namespace dpscope {

enum class FindingKind : std::uint8_t {
    StackedRequest,
    OrphanResponse,
    MismatchedResponse,
    UnexpectedResponseType,
    ResponseTimeout,
    RequestRejected,
    NoAuthority,
    SpontaneousMessage,
    SpontaneousUnacknowledged,
    SpmViolation,
    FcsError,
    MalformedTelegram,
    ConfigMismatch,
    UnknownCode,
    FdlRetry,
    FdlNoResponse,
    Count
};

constexpr std::size_t kFindingKindCount = static_cast<std::size_t>(FindingKind::Count);

std::string_view finding_kind_name(FindingKind kind);  // "stacked_request", ...
std::optional<FindingKind> finding_kind_from_name(std::string_view name);
Severity default_severity(FindingKind kind);
// One sentence on what the rule checks (used for JUnit test case names and report legends).
std::string_view finding_rule_text(FindingKind kind);

struct Finding {
    FindingKind kind = FindingKind::StackedRequest;
    Severity severity = Severity::Error;
    std::uint64_t frame = 0;          // the telegram where it was found
    std::uint64_t request_frame = 0;  // the related request, 0 when there is none
    std::int64_t time_ns = 0;         // kNoTime (see bus_decoder.hpp) when unknown
    bool has_stations = false;        // false for a telegram nobody can be named for (garbage)
    std::uint8_t master = 0;
    std::uint8_t slave = 0;
    std::optional<std::uint16_t> pnu;
    std::string message;
};

}  // namespace dpscope
