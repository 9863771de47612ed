// Findings: what the session tracker reports about the conversation between a master and a
// slave (handshake violations, time-outs, rejections, link-level trouble). Kind names and
// default severities are fixed; they are part of every output format. The finding catalogue
// (finding.cpp) holds one row per kind: name, default severity, the component whose rule finds
// it, and the rule in one sentence; a new kind is one enumerator and one row.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/problem.hpp"

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
    Dpv1StackedRequest,
    Dpv1ReferenceMismatch,
    Dpv1UnexpectedResponseId,
    Dpv1ParameterCountMismatch,
    Dpv1OrphanResponse,
    Dpv1ResponseTimeout,
    Dpv1NegativeResponse,
    Dpv1LengthError,
    Dpv1ErrorPdu,
    Dpv1UnknownCode,
    FcStackedRequest,
    FcNoResponse,
    FcLateResponse,
    FcMismatchedResponse,
    FcUnexpectedResponseType,
    FcCommandRejected,
    FcBccError,
    Vlt2000StackedRequest,
    Vlt2000NoResponse,
    Vlt2000UnexpectedReply,
    Vlt2000MismatchedResponse,
    Vlt2000CommandFailed,
    Vlt2000ChecksumError,
    Vlt2000ChecksumDisabled,
    GsdIdentMismatch,
    GsdUnknownModule,
    GsdConfigLimit,
    GsdUserPrmLength,
    GsdUserPrmRange,
    GsdDiagTooLong,
    GsdLateResponse,
    GsdPollInterval,
    Count
};

constexpr std::size_t kFindingKindCount = static_cast<std::size_t>(FindingKind::Count);

// The rule set a finding kind belongs to. Each is a component of its own in the tracker, so a
// protocol brings its components and their kinds; the parameter channel is the same whatever
// carries it (the cyclic PCV of PROFIBUS DP today).
enum class FindingComponent : std::uint8_t {
    ParameterChannel,  // request/response pairing, rejections, spontaneous messages (any carrier)
    ProfibusLink,      // PROFIBUS FDL: checksum, framing, FCB repeats, requests left unanswered
    DpConfiguration,   // PROFIBUS DP: Data_Exchange lengths against the Chk_Cfg configuration
    Dpv1ParameterAccess,  // PROFIdrive parameter access over DP-V1: Write, Read polls, response
    FcProtocol,  // the Danfoss FC protocol on RS-485: command -> response per drive address, BCC
    Vlt2000Protocol,    // the VLT 2000 serial telegram: command -> reply per address, checksum
    DeviceDescription,  // PROFIBUS DP: a slave against its GSD file (--gsd): ident, modules,
                        // parameters
    Count
};

constexpr std::size_t kFindingComponentCount = static_cast<std::size_t>(FindingComponent::Count);

// One row of the finding catalogue (finding.cpp): everything fixed about a kind.
struct FindingKindInfo {
    FindingKind kind;
    std::string_view name;  // in every output format: "stacked_request"
    Severity severity;      // the default
    FindingComponent component;
    std::string_view rule;  // one sentence on what the rule checks (JUnit names, report legends)
};

// Every finding kind, one row each, in enum order (checked when finding.cpp compiles).
std::span<const FindingKindInfo> finding_catalogue() noexcept;
const FindingKindInfo& finding_kind_info(FindingKind kind) noexcept;
// The length of the longest kind name: the width of a column of kind names.
std::size_t longest_finding_kind_name() noexcept;

std::string_view finding_kind_name(FindingKind kind);  // "stacked_request", ...
std::optional<FindingKind> finding_kind_from_name(std::string_view name);
Severity default_severity(FindingKind kind);
// One sentence on what the rule checks (used for JUnit test case names and report legends).
std::string_view finding_rule_text(FindingKind kind);
FindingComponent finding_component(FindingKind kind);

// The kinds of one component, in enum order (for reports and documentation).
std::vector<FindingKind> finding_kinds_of(FindingComponent component);
// "parameter channel", "PROFIBUS link", "DP configuration", "DP-V1 parameter access".
std::string_view finding_component_name(FindingComponent component);

// Findings counted per kind and, within it, per severity (indexed by Severity).
using FindingSeverityCounts = std::array<std::array<std::uint64_t, 3>, kFindingKindCount>;

// Counts for what no channel can be named for (garbage on the bus), kept by each bus's tracker.
struct BusStats {
    std::array<std::uint64_t, kFindingKindCount> findings{};
    FindingSeverityCounts findings_by_severity{};
};

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
