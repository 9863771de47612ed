#include "decoder/finding.hpp"

namespace dpscope {

namespace {

struct KindInfo {
    std::string_view name;
    Severity severity;
    std::string_view rule;
};

constexpr KindInfo kKinds[] = {
    {"stacked_request", Severity::Error,
     "the master waits for the answer before it sends a new request"},
    {"orphan_response", Severity::Warning, "every response answers a pending request"},
    {"mismatched_response", Severity::Error,
     "the response carries the PNU (and IND for arrays) of the request"},
    {"unexpected_response_type", Severity::Error,
     "the response code is a valid answer to the request code"},
    {"response_timeout", Severity::Error, "every request is answered within the time-out"},
    {"request_rejected", Severity::Note, "requests are executed (RC 7 rejections)"},
    {"no_authority", Severity::Warning, "the master has operating authority (RC 8)"},
    {"spontaneous_message", Severity::Note, "spontaneous messages (RC 9-12 with SPM toggle)"},
    {"spontaneous_unacknowledged", Severity::Warning,
     "the master acknowledges spontaneous messages within the time-out"},
    {"spm_violation", Severity::Warning,
     "the master toggles SPM only to acknowledge a spontaneous message"},
    {"fcs_error", Severity::Error, "telegrams carry a correct FDL checksum"},
    {"malformed_telegram", Severity::Error, "telegrams are well framed"},
    {"config_mismatch", Severity::Error,
     "Data_Exchange lengths match the configuration sent in Chk_Cfg"},
    {"unknown_code", Severity::Warning, "RC/AK values are defined by the dialect"},
    {"fdl_retry", Severity::Note, "requests are not repeated with the same FCB"},
    {"fdl_no_response", Severity::Warning, "SRD and SDA requests get a reply"},
};
static_assert(std::size(kKinds) == kFindingKindCount);

}  // namespace

std::string_view finding_kind_name(FindingKind kind) {
    return kKinds[static_cast<std::size_t>(kind)].name;
}

std::optional<FindingKind> finding_kind_from_name(std::string_view name) {
    for (std::size_t i = 0; i < kFindingKindCount; ++i)
        if (kKinds[i].name == name) return static_cast<FindingKind>(i);
    return std::nullopt;
}

Severity default_severity(FindingKind kind) {
    return kKinds[static_cast<std::size_t>(kind)].severity;
}

std::string_view finding_rule_text(FindingKind kind) {
    return kKinds[static_cast<std::size_t>(kind)].rule;
}

}  // namespace dpscope
