#include "core/finding.hpp"

#include <algorithm>
#include <iterator>

#include "core/catalogue.hpp"

namespace dpscope {

namespace {

using enum FindingComponent;

constexpr FindingKindInfo kCatalogue[] = {
    {FindingKind::StackedRequest, "stacked_request", Severity::Error, ParameterChannel,
     "the master waits for the answer before it sends a new request"},
    {FindingKind::OrphanResponse, "orphan_response", Severity::Warning, ParameterChannel,
     "every response answers a pending request"},
    {FindingKind::MismatchedResponse, "mismatched_response", Severity::Error, ParameterChannel,
     "the response carries the PNU (and IND for arrays) of the request"},
    {FindingKind::UnexpectedResponseType, "unexpected_response_type", Severity::Error,
     ParameterChannel, "the response code is a valid answer to the request code"},
    {FindingKind::ResponseTimeout, "response_timeout", Severity::Error, ParameterChannel,
     "every request is answered within the time-out"},
    {FindingKind::RequestRejected, "request_rejected", Severity::Note, ParameterChannel,
     "requests are executed (RC 7 rejections)"},
    {FindingKind::NoAuthority, "no_authority", Severity::Warning, ParameterChannel,
     "the master has operating authority (RC 8)"},
    {FindingKind::SpontaneousMessage, "spontaneous_message", Severity::Note, ParameterChannel,
     "spontaneous messages (RC 9-12 with SPM toggle)"},
    {FindingKind::SpontaneousUnacknowledged, "spontaneous_unacknowledged", Severity::Warning,
     ParameterChannel, "the master acknowledges spontaneous messages within the time-out"},
    {FindingKind::SpmViolation, "spm_violation", Severity::Warning, ParameterChannel,
     "the master toggles SPM only to acknowledge a spontaneous message"},
    {FindingKind::FcsError, "fcs_error", Severity::Error, ProfibusLink,
     "telegrams carry a correct FDL checksum"},
    {FindingKind::MalformedTelegram, "malformed_telegram", Severity::Error, ProfibusLink,
     "telegrams are well framed"},
    {FindingKind::ConfigMismatch, "config_mismatch", Severity::Error, DpConfiguration,
     "Data_Exchange lengths match the configuration sent in Chk_Cfg"},
    {FindingKind::UnknownCode, "unknown_code", Severity::Warning, ParameterChannel,
     "RC/AK values are defined by the dialect"},
    {FindingKind::FdlRetry, "fdl_retry", Severity::Note, ProfibusLink,
     "requests are not repeated with the same FCB"},
    {FindingKind::FdlNoResponse, "fdl_no_response", Severity::Warning, ProfibusLink,
     "SRD and SDA requests get a reply"},
    {FindingKind::Dpv1StackedRequest, "dpv1_stacked_request", Severity::Error, Dpv1ParameterAccess,
     "a new parameter request is written only after the previous response was read"},
    {FindingKind::Dpv1ReferenceMismatch, "dpv1_reference_mismatch", Severity::Error,
     Dpv1ParameterAccess, "the parameter response mirrors the request reference"},
    {FindingKind::Dpv1UnexpectedResponseId, "dpv1_unexpected_response_id", Severity::Error,
     Dpv1ParameterAccess, "the response ID answers the request ID"},
    {FindingKind::Dpv1ParameterCountMismatch, "dpv1_parameter_count_mismatch", Severity::Error,
     Dpv1ParameterAccess, "the response mirrors the axis and the number of parameters"},
    {FindingKind::Dpv1OrphanResponse, "dpv1_orphan_response", Severity::Warning,
     Dpv1ParameterAccess, "every parameter response answers a written request"},
    {FindingKind::Dpv1ResponseTimeout, "dpv1_response_timeout", Severity::Error,
     Dpv1ParameterAccess, "every parameter request is answered within the time-out"},
    {FindingKind::Dpv1NegativeResponse, "dpv1_negative_response", Severity::Note,
     Dpv1ParameterAccess, "parameter requests are executed (negative responses)"},
    {FindingKind::Dpv1LengthError, "dpv1_length_error", Severity::Error, Dpv1ParameterAccess,
     "requests are in range, and lengths and value blocks agree with the request"},
    {FindingKind::Dpv1ErrorPdu, "dpv1_error_pdu", Severity::Note, Dpv1ParameterAccess,
     "DP-V1 requests are accepted (error PDUs other than state conflict)"},
    {FindingKind::Dpv1UnknownCode, "dpv1_unknown_code", Severity::Warning, Dpv1ParameterAccess,
     "parameter requests use request IDs and attributes the dialect defines"},
    {FindingKind::FcStackedRequest, "fc_stacked_request", Severity::Error, FcProtocol,
     "the master waits for a drive's response before its next command to that drive"},
    {FindingKind::FcNoResponse, "fc_no_response", Severity::Error, FcProtocol,
     "every command to one drive is answered before the master's next telegram and within the "
     "time-out"},
    {FindingKind::FcLateResponse, "fc_late_response", Severity::Warning, FcProtocol,
     "drives answer within their documented response time (--fc-response-ms)"},
    {FindingKind::FcMismatchedResponse, "fc_mismatched_response", Severity::Error, FcProtocol,
     "a response carries the command's address, PNU and index"},
    {FindingKind::FcUnexpectedResponseType, "fc_unexpected_response_type", Severity::Error,
     FcProtocol, "the response's AK is a valid answer to the command's AK"},
    {FindingKind::FcCommandRejected, "fc_command_rejected", Severity::Note, FcProtocol,
     "commands are performed (AK 7 with a fault code)"},
    {FindingKind::FcBccError, "fc_bcc_error", Severity::Error, FcProtocol,
     "every telegram's BCC (XOR from STX) is right"},
    {FindingKind::Vlt2000StackedRequest, "vlt2000_stacked_request", Severity::Error,
     Vlt2000Protocol,
     "the master waits for a drive's reply before its next telegram to that drive"},
    {FindingKind::Vlt2000NoResponse, "vlt2000_no_response", Severity::Error, Vlt2000Protocol,
     "every command to one drive is answered before the master's next telegram and within the "
     "time-out"},
    {FindingKind::Vlt2000UnexpectedReply, "vlt2000_unexpected_reply", Severity::Error,
     Vlt2000Protocol, "nobody replies to a broadcast (address 00)"},
    {FindingKind::Vlt2000MismatchedResponse, "vlt2000_mismatched_response", Severity::Error,
     Vlt2000Protocol, "a reply carries the command's address, control letter and parameter"},
    {FindingKind::Vlt2000CommandFailed, "vlt2000_command_failed", Severity::Note, Vlt2000Protocol,
     "commands are carried out (a reply with decimal position 9, with its reason code)"},
    {FindingKind::Vlt2000ChecksumError, "vlt2000_checksum_error", Severity::Error, Vlt2000Protocol,
     "every telegram's checksum (sum of the 18 characters after '<', last two digits) is right"},
    {FindingKind::Vlt2000ChecksumDisabled, "vlt2000_checksum_disabled", Severity::Note,
     Vlt2000Protocol,
     "telegrams carry a checksum (\"??\" switches the check off; once per address)"},
    {FindingKind::GsdIdentMismatch, "gsd_ident_mismatch", Severity::Error, DeviceDescription,
     "Set_Prm and Slave_Diag carry the Ident_Number of the slave's GSD file"},
    {FindingKind::GsdUnknownModule, "gsd_unknown_module", Severity::Error, DeviceDescription,
     "every Chk_Cfg / Get_Cfg identifier belongs to a module of the slave's GSD file"},
    {FindingKind::GsdConfigLimit, "gsd_config_limit", Severity::Error, DeviceDescription,
     "a configuration keeps to the GSD's Max_Module, Max_Input_Len, Max_Output_Len and "
     "Max_Data_Len"},
    {FindingKind::GsdUserPrmLength, "gsd_user_prm_length", Severity::Error, DeviceDescription,
     "Set_Prm carries as many user parameter bytes as the GSD describes (User_Prm_Data_Len and "
     "the modules' parameters)"},
    {FindingKind::GsdUserPrmRange, "gsd_user_prm_range", Severity::Error, DeviceDescription,
     "each user parameter of Set_Prm is one of the values its ExtUserPrmData allows"},
    {FindingKind::GsdDiagTooLong, "gsd_diag_too_long", Severity::Warning, DeviceDescription,
     "a Slave_Diag answer is no longer than the GSD's Max_Diag_Data_Len"},
    {FindingKind::GsdLateResponse, "gsd_late_response", Severity::Warning, DeviceDescription,
     "a slave answers within the GSD's MaxTsdr at the line's baud rate (needs times and the "
     "baud rate; the first of a run reported)"},
    {FindingKind::GsdPollInterval, "gsd_poll_interval", Severity::Warning, DeviceDescription,
     "Data_Exchange requests to a slave are at least the GSD's Min_Slave_Intervall apart (the "
     "first of a run reported)"},
};

static_assert(catalogue::one_row_per_kind_in_order(std::span<const FindingKindInfo>(kCatalogue),
                                                   kFindingKindCount),
              "kCatalogue: one row per FindingKind, in enum order");
static_assert(catalogue::names_unique(std::span<const FindingKindInfo>(kCatalogue)),
              "kCatalogue: every finding kind needs a name of its own");

constexpr std::string_view kComponentNames[] = {
    "parameter channel", "PROFIBUS link", "DP configuration",       "DP-V1 parameter access",
    "FC protocol",       "VLT 2000",      "GSD device description",
};
static_assert(std::size(kComponentNames) == kFindingComponentCount);

}  // namespace

std::span<const FindingKindInfo> finding_catalogue() noexcept { return kCatalogue; }

std::size_t longest_finding_kind_name() noexcept {
    static const std::size_t longest = [] {
        std::size_t n = 0;
        for (const FindingKindInfo& row : kCatalogue)
            n = std::max(n, row.name.size());
        return n;
    }();
    return longest;
}

const FindingKindInfo& finding_kind_info(FindingKind kind) noexcept {
    return kCatalogue[static_cast<std::size_t>(kind)];
}

std::string_view finding_kind_name(FindingKind kind) { return finding_kind_info(kind).name; }

std::optional<FindingKind> finding_kind_from_name(std::string_view name) {
    for (const FindingKindInfo& row : kCatalogue)
        if (row.name == name) return row.kind;
    return std::nullopt;
}

Severity default_severity(FindingKind kind) { return finding_kind_info(kind).severity; }

std::string_view finding_rule_text(FindingKind kind) { return finding_kind_info(kind).rule; }

FindingComponent finding_component(FindingKind kind) { return finding_kind_info(kind).component; }

std::vector<FindingKind> finding_kinds_of(FindingComponent component) {
    return catalogue::kinds_of(std::span<const FindingKindInfo>(kCatalogue), component);
}

std::string_view finding_component_name(FindingComponent component) {
    return kComponentNames[static_cast<std::size_t>(component)];
}

}  // namespace dpscope
