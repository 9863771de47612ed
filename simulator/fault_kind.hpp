// The simulator's fault catalogue: every fault `dpscope simulate --fault` can inject. A fault that
// provokes one finding kind is named after it (finding_kind_name): the finding catalogue is the one
// list of those names, and the catalogue here fails to compile when a finding kind has no fault.
// The simulator's own faults (garbage between telegrams) have names of their own.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "core/finding.hpp"
#include "core/telegram.hpp"

namespace dpscope {

// In the order the names are listed to the user (parse_fault_spec's error message).
enum class FaultKind : std::uint8_t {
    FcsError,                    // one telegram's FCS is wrong
    Garbage,                     // junk bytes between telegrams
    MalformedTelegram,           // one telegram cut short
    StackedRequest,              // the master changes its request before the answer
    OrphanResponse,              // the slave answers although nothing was asked
    MismatchedResponse,          // the answer carries another PNU
    UnexpectedResponseType,      // the answer's code does not fit the request
    ResponseTimeout,             // the slave never answers; the master gives up later
    RequestRejected,             // RC 7 with an error number
    NoAuthority,                 // RC 8 to a change request
    SpontaneousMessage,          // RC 9/10 with an SPM toggle, acknowledged by the master
    SpontaneousUnacknowledged,   // the same, acknowledged only after the time-out
    SpmViolation,                // the master toggles SPM with nothing pending
    ConfigMismatch,              // one Data_Exchange telegram longer than configured
    UnknownCode,                 // one response with a code the dialect does not define
    FdlRetry,                    // a response lost and the request repeated with the same FCB
    FdlNoResponse,               // a response lost, no retry
    Dpv1StackedRequest,          // the master writes a new request before reading the answer
    Dpv1ReferenceMismatch,       // the response carries another request reference
    Dpv1UnexpectedResponseId,    // a change request answered as a read
    Dpv1ParameterCountMismatch,  // the response has another number of parameters
    Dpv1OrphanResponse,          // a parameter response nobody asked for
    Dpv1ResponseTimeout,         // the drive never answers; the master reads in vain
    Dpv1NegativeResponse,        // a negative parameter response with an error number
    Dpv1LengthError,             // a response whose value blocks do not fit the request
    Dpv1ErrorPdu,                // a DP-V1 error PDU (access, invalid index)
    Dpv1UnknownCode,             // a request with an attribute no dialect defines, refused
    FcStackedRequest,            // FC: a second command to a drive before its response
    FcNoResponse,                // FC: a drive does not answer
    FcLateResponse,              // FC: a drive answers after its documented response time
    FcMismatchedResponse,        // FC: the answer carries another PNU or index
    FcUnexpectedResponseType,    // FC: the answer's AK does not fit the command
    FcCommandRejected,           // FC: AK 7 with a fault code
    FcBccError,                  // FC: one telegram's BCC is wrong
    Vlt2000StackedRequest,       // VLT 2000: a second command to a drive before its reply
    Vlt2000NoResponse,           // VLT 2000: a drive does not reply
    Vlt2000UnexpectedReply,      // VLT 2000: a drive replies to a broadcast
    Vlt2000MismatchedResponse,   // VLT 2000: the reply carries another parameter
    Vlt2000CommandFailed,        // VLT 2000: a reply with decimal position 9 and a reason code
    Vlt2000ChecksumError,        // VLT 2000: one telegram's checksum is wrong
    Vlt2000ChecksumDisabled,     // VLT 2000: a drive's telegrams carry "??" as checksum
    // GSD faults (PROFIBUS DP: a slave against its GSD file; docs/gsd.md). Each but the last
    // three makes the slave leave data exchange and the master parameterise it again, with:
    GsdIdentMismatch,  // a Set_Prm with another ident (0x0100 flipped)
    GsdUnknownModule,  // a Chk_Cfg with a free place (0x00) after the PPO's identifiers
    GsdConfigLimit,    // a Chk_Cfg with the PPO's identifiers twice (two modules)
    GsdUserPrmLength,  // a Set_Prm with one user parameter byte more
    GsdUserPrmRange,   // a Set_Prm whose second user byte (DPV1_Status_2) is 0x01
    GsdDiagTooLong,    // a Data_Exchange answered DH, the Slave_Diag with 14 ext diag bytes
    GsdLateResponse,   // a Data_Exchange answered after 400 bit times
    GsdPollInterval,   // a slave polled twice in a row (two Data_Exchange cycles back to back)
    // Bus-health faults (PROFIBUS DP link layer; docs/bus-health.md):
    StationLost,      // a slave silent for kStationLostCycles cycles, then re-parameterised
    Resync,           // a slave leaves data exchange (DH, Prm_Req) and is parameterised again
    AnswerNotAsked,   // a slave sends its Data_Exchange response twice: the second is not asked
    AnswerWrongKind,  // the master's FDL_Status answered with data (SD2)
    AnswerShortAck,   // a Data_Exchange answered with a short acknowledge instead of data
    DiagFault,        // a Data_Exchange answered DH, the master's Slave_Diag shows Ext_Diag
    Repeats,          // a response lost twice: the request repeated twice with the same FCB
    Refusal,          // a Data_Exchange refused with RS (SD1, service not activated)
    Count
};

constexpr std::size_t kFaultKindCount = static_cast<std::size_t>(FaultKind::Count);

// The finding kind this fault is named after, or nothing for the simulator's own faults.
std::optional<FindingKind> fault_finding_kind(FaultKind kind);
// finding_kind_name of fault_finding_kind, or the fault's own name ("garbage").
std::string_view fault_kind_name(FaultKind kind);
// Also takes "bad_fcs" for "fcs_error".
std::optional<FaultKind> fault_kind_from_name(std::string_view name);

// Faults that act on the parameter channel need a slave with a PCV (PPO 1, 2 or 5).
bool fault_needs_parameter_channel(FaultKind kind) noexcept;
// Faults that act on DP-V1 parameter access need a DP-V1 slave (`--slave ADDR:PPO:dpv1`).
bool fault_needs_dpv1(FaultKind kind) noexcept;
// The bus a fault acts on (`simulate --bus`): PROFIBUS DP, the FC protocol or VLT 2000.
Protocol fault_bus(FaultKind kind) noexcept;
// fault_bus(kind) is the FC protocol.
bool fault_is_fc(FaultKind kind) noexcept;
// A session on `bus` can inject it: the faults of that bus; the FC and VLT 2000 buses also take
// the shared garbage and malformed_telegram.
bool fault_applies_to_bus(FaultKind kind, Protocol bus) noexcept;
// The names of the faults a session on `bus` can inject, in catalogue order, ", " between them
// ("bad_fcs" as "fcs_error (alias bad_fcs)" when `with_alias`).
std::string fault_kind_names(Protocol bus, bool with_alias = false);
// The cycles a slave stays silent with the station_lost fault (lost under the default
// lost_cycles 3); it answers again in the cycle after and is parameterised anew.
inline constexpr std::uint64_t kStationLostCycles = 5;
// What a fault does, one line for --help ("a slave silent for 5 cycles, ...").
std::string_view fault_kind_description(FaultKind kind);
// The bus-health faults (station_lost .. refusal): their names and descriptions for --help.
std::string bus_health_fault_help();

// Faults that make a slave send spontaneous messages need a dialect that has them (not ge).
bool fault_needs_spontaneous_messages(FaultKind kind) noexcept;

}  // namespace dpscope
