#include "simulator/fault_kind.hpp"

#include <iterator>

namespace dpscope {

namespace {

struct FaultInfo {
    FaultKind kind;
    std::optional<FindingKind> finding;  // the finding kind it is named after
    std::string_view own_name;           // set only for a fault no finding kind is named after
    bool needs_parameter_channel;
    bool needs_dpv1 = false;              // acts on DP-V1 parameter access: needs a DP-V1 slave
    Protocol bus = Protocol::ProfibusDp;  // the bus it acts on (simulate --bus)
};

constexpr FaultInfo kFaults[] = {
    {FaultKind::FcsError, FindingKind::FcsError, {}, false},
    {FaultKind::Garbage, std::nullopt, "garbage", false},
    {FaultKind::MalformedTelegram, FindingKind::MalformedTelegram, {}, false},
    {FaultKind::StackedRequest, FindingKind::StackedRequest, {}, true},
    {FaultKind::OrphanResponse, FindingKind::OrphanResponse, {}, true},
    {FaultKind::MismatchedResponse, FindingKind::MismatchedResponse, {}, true},
    {FaultKind::UnexpectedResponseType, FindingKind::UnexpectedResponseType, {}, true},
    {FaultKind::ResponseTimeout, FindingKind::ResponseTimeout, {}, true},
    {FaultKind::RequestRejected, FindingKind::RequestRejected, {}, true},
    {FaultKind::NoAuthority, FindingKind::NoAuthority, {}, true},
    {FaultKind::SpontaneousMessage, FindingKind::SpontaneousMessage, {}, true},
    {FaultKind::SpontaneousUnacknowledged, FindingKind::SpontaneousUnacknowledged, {}, true},
    {FaultKind::SpmViolation, FindingKind::SpmViolation, {}, true},
    {FaultKind::ConfigMismatch, FindingKind::ConfigMismatch, {}, false},
    {FaultKind::UnknownCode, FindingKind::UnknownCode, {}, true},
    {FaultKind::FdlRetry, FindingKind::FdlRetry, {}, false},
    {FaultKind::FdlNoResponse, FindingKind::FdlNoResponse, {}, false},
    {FaultKind::Dpv1StackedRequest, FindingKind::Dpv1StackedRequest, {}, false, true},
    {FaultKind::Dpv1ReferenceMismatch, FindingKind::Dpv1ReferenceMismatch, {}, false, true},
    {FaultKind::Dpv1UnexpectedResponseId, FindingKind::Dpv1UnexpectedResponseId, {}, false, true},
    {FaultKind::Dpv1ParameterCountMismatch,
     FindingKind::Dpv1ParameterCountMismatch,
     {},
     false,
     true},
    {FaultKind::Dpv1OrphanResponse, FindingKind::Dpv1OrphanResponse, {}, false, true},
    {FaultKind::Dpv1ResponseTimeout, FindingKind::Dpv1ResponseTimeout, {}, false, true},
    {FaultKind::Dpv1NegativeResponse, FindingKind::Dpv1NegativeResponse, {}, false, true},
    {FaultKind::Dpv1LengthError, FindingKind::Dpv1LengthError, {}, false, true},
    {FaultKind::Dpv1ErrorPdu, FindingKind::Dpv1ErrorPdu, {}, false, true},
    {FaultKind::Dpv1UnknownCode, FindingKind::Dpv1UnknownCode, {}, false, true},
    {FaultKind::FcStackedRequest, FindingKind::FcStackedRequest, {}, false, false, Protocol::Fc},
    {FaultKind::FcNoResponse, FindingKind::FcNoResponse, {}, false, false, Protocol::Fc},
    {FaultKind::FcLateResponse, FindingKind::FcLateResponse, {}, false, false, Protocol::Fc},
    {FaultKind::FcMismatchedResponse,
     FindingKind::FcMismatchedResponse,
     {},
     false,
     false,
     Protocol::Fc},
    {FaultKind::FcUnexpectedResponseType,
     FindingKind::FcUnexpectedResponseType,
     {},
     false,
     false,
     Protocol::Fc},
    {FaultKind::FcCommandRejected, FindingKind::FcCommandRejected, {}, false, false, Protocol::Fc},
    {FaultKind::FcBccError, FindingKind::FcBccError, {}, false, false, Protocol::Fc},
    {FaultKind::Vlt2000StackedRequest,
     FindingKind::Vlt2000StackedRequest,
     {},
     false,
     false,
     Protocol::Vlt2000},
    {FaultKind::Vlt2000NoResponse,
     FindingKind::Vlt2000NoResponse,
     {},
     false,
     false,
     Protocol::Vlt2000},
    {FaultKind::Vlt2000UnexpectedReply,
     FindingKind::Vlt2000UnexpectedReply,
     {},
     false,
     false,
     Protocol::Vlt2000},
    {FaultKind::Vlt2000MismatchedResponse,
     FindingKind::Vlt2000MismatchedResponse,
     {},
     false,
     false,
     Protocol::Vlt2000},
    {FaultKind::Vlt2000CommandFailed,
     FindingKind::Vlt2000CommandFailed,
     {},
     false,
     false,
     Protocol::Vlt2000},
    {FaultKind::Vlt2000ChecksumError,
     FindingKind::Vlt2000ChecksumError,
     {},
     false,
     false,
     Protocol::Vlt2000},
    {FaultKind::Vlt2000ChecksumDisabled,
     FindingKind::Vlt2000ChecksumDisabled,
     {},
     false,
     false,
     Protocol::Vlt2000},
    {FaultKind::GsdIdentMismatch, FindingKind::GsdIdentMismatch, {}, false},
    {FaultKind::GsdUnknownModule, FindingKind::GsdUnknownModule, {}, false},
    {FaultKind::GsdConfigLimit, FindingKind::GsdConfigLimit, {}, false},
    {FaultKind::GsdUserPrmLength, FindingKind::GsdUserPrmLength, {}, false},
    {FaultKind::GsdUserPrmRange, FindingKind::GsdUserPrmRange, {}, false},
    {FaultKind::GsdDiagTooLong, FindingKind::GsdDiagTooLong, {}, false},
    {FaultKind::GsdLateResponse, FindingKind::GsdLateResponse, {}, false},
    {FaultKind::GsdPollInterval, FindingKind::GsdPollInterval, {}, false},
    {FaultKind::StationLost, std::nullopt, "station_lost", false},
    {FaultKind::Resync, std::nullopt, "resync", false},
    {FaultKind::AnswerNotAsked, std::nullopt, "answer_not_asked", false},
    {FaultKind::AnswerWrongKind, std::nullopt, "answer_wrong_kind", false},
    {FaultKind::AnswerShortAck, std::nullopt, "answer_short_ack", false},
    {FaultKind::DiagFault, std::nullopt, "diag_fault", false},
    {FaultKind::Repeats, std::nullopt, "repeats", false},
    {FaultKind::Refusal, std::nullopt, "refusal", false},
};

// The bus-health faults' descriptions, in enum order from StationLost.
constexpr std::string_view kBusHealthDescriptions[] = {
    "a slave stops answering for 5 cycles (the master repeats each poll once, then polls "
    "Slave_Diag instead of Data_Exchange), then answers again and is parameterised anew "
    "(Slave_Diag, Set_Prm, Chk_Cfg, Slave_Diag): one lost event, one return, one resync",
    "a slave answers a Data_Exchange with DH (diagnosis), its Slave_Diag shows "
    "Station_Not_Ready and Prm_Req, and the master runs Set_Prm and Chk_Cfg again: one resync "
    "without being lost",
    "a slave sends its Data_Exchange response a second time when nothing waits for it: one "
    "illegal answer 'not asked'",
    "the master checks a slave with FDL_Status and it answers with data (SD2): one illegal "
    "answer 'wrong kind'",
    "a slave answers a Data_Exchange with a short acknowledge instead of its inputs: one "
    "illegal answer 'short acknowledge where data was due'",
    "a slave answers a Data_Exchange with DH, and the master's Slave_Diag that follows shows "
    "Ext_Diag with a device-related block: one diagnosis fault",
    "a response lost twice: the master repeats the request twice with the same FCB (retry limit "
    "2 or more) and the third try is answered: max repeats per cycle 2",
    "a slave refuses a Data_Exchange with RS (SD1, service not activated): one negative answer "
    "(refusal)",
};
static_assert(std::size(kBusHealthDescriptions) ==
              kFaultKindCount - static_cast<std::size_t>(FaultKind::StationLost));

// One entry per fault kind, in enum order; a name either from the finding catalogue or its own.
constexpr bool faults_in_enum_order() {
    if (std::size(kFaults) != kFaultKindCount) return false;
    for (std::size_t i = 0; i < std::size(kFaults); ++i) {
        if (static_cast<std::size_t>(kFaults[i].kind) != i) return false;
        if (kFaults[i].finding.has_value() == !kFaults[i].own_name.empty()) return false;
    }
    return true;
}

// Every finding kind is named by exactly one fault: a new finding kind needs a fault here (and a
// scenario in tests/session_tracker_test.cpp) before the simulator builds.
constexpr bool every_finding_kind_once() {
    for (std::size_t k = 0; k < kFindingKindCount; ++k) {
        int named = 0;
        for (const FaultInfo& fault : kFaults)
            if (fault.finding && static_cast<std::size_t>(*fault.finding) == k) ++named;
        if (named != 1) return false;
    }
    return true;
}

static_assert(faults_in_enum_order(), "kFaults: one entry per FaultKind, in enum order");
static_assert(every_finding_kind_once(), "kFaults: every FindingKind needs exactly one fault");

}  // namespace

std::optional<FindingKind> fault_finding_kind(FaultKind kind) {
    auto index = static_cast<std::size_t>(kind);
    return index < std::size(kFaults) ? kFaults[index].finding : std::nullopt;
}

std::string_view fault_kind_name(FaultKind kind) {
    auto index = static_cast<std::size_t>(kind);
    if (index >= std::size(kFaults)) return "unknown";
    const FaultInfo& fault = kFaults[index];
    return fault.finding ? finding_kind_name(*fault.finding) : fault.own_name;
}

std::optional<FaultKind> fault_kind_from_name(std::string_view name) {
    if (name == "bad_fcs") return FaultKind::FcsError;
    for (const FaultInfo& fault : kFaults)
        if (fault_kind_name(fault.kind) == name) return fault.kind;
    return std::nullopt;
}

bool fault_needs_parameter_channel(FaultKind kind) noexcept {
    auto index = static_cast<std::size_t>(kind);
    return index >= std::size(kFaults) || kFaults[index].needs_parameter_channel;
}

bool fault_needs_dpv1(FaultKind kind) noexcept {
    auto index = static_cast<std::size_t>(kind);
    return index < std::size(kFaults) && kFaults[index].needs_dpv1;
}

Protocol fault_bus(FaultKind kind) noexcept {
    auto index = static_cast<std::size_t>(kind);
    return index < std::size(kFaults) ? kFaults[index].bus : Protocol::ProfibusDp;
}

bool fault_is_fc(FaultKind kind) noexcept { return fault_bus(kind) == Protocol::Fc; }

bool fault_applies_to_bus(FaultKind kind, Protocol bus) noexcept {
    if (fault_bus(kind) == bus) return true;
    return bus != Protocol::ProfibusDp &&
           (kind == FaultKind::Garbage || kind == FaultKind::MalformedTelegram);
}

std::string fault_kind_names(Protocol bus, bool with_alias) {
    std::string names;
    for (std::size_t i = 0; i < kFaultKindCount; ++i) {
        const auto kind = static_cast<FaultKind>(i);
        if (!fault_applies_to_bus(kind, bus)) continue;
        if (!names.empty()) names += ", ";
        names += fault_kind_name(kind);
        if (with_alias && kind == FaultKind::FcsError) names += " (alias bad_fcs)";
    }
    return names;
}

std::string_view fault_kind_description(FaultKind kind) {
    const auto index = static_cast<std::size_t>(kind);
    const auto first = static_cast<std::size_t>(FaultKind::StationLost);
    if (index >= first && index < kFaultKindCount) return kBusHealthDescriptions[index - first];
    if (auto finding = fault_finding_kind(kind)) return finding_rule_text(*finding);
    if (kind == FaultKind::Garbage) return "junk bytes between telegrams";
    return {};
}

std::string bus_health_fault_help() {
    std::string help;
    for (auto i = static_cast<std::size_t>(FaultKind::StationLost); i < kFaultKindCount; ++i) {
        const auto kind = static_cast<FaultKind>(i);
        if (!help.empty()) help += "; ";
        help += fault_kind_name(kind);
        help += ": ";
        help += fault_kind_description(kind);
    }
    return help;
}

bool fault_needs_spontaneous_messages(FaultKind kind) noexcept {
    return kind == FaultKind::SpontaneousMessage || kind == FaultKind::SpontaneousUnacknowledged;
}

}  // namespace dpscope
