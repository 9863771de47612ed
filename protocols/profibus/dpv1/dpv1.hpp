// DP-V1 acyclic services (MSAC_C1 on SAP 51, MSAC_C2 on SAPs 49/50 and the connection SAPs):
// the PDU every such telegram carries in its data unit. Facts and sources:
// docs/protocol/dpv1-parameter-access.md. Pure decoding; the PROFIdrive parameter request and
// response carried by index 47 are in protocols/profibus/dpv1/profidrive.hpp.
#pragma once

#include <cstdint>
#include <string_view>

#include "core/byte_reader.hpp"
#include "core/problem.hpp"
#include "protocols/profibus/fdl.hpp"

namespace dpscope {

// Function numbers (byte 0 of every DP-V1 PDU). Bit 7 set marks the negative response.
namespace dpv1_function {
inline constexpr std::uint8_t kIdle = 0x48;
inline constexpr std::uint8_t kDataTransport = 0x51;
inline constexpr std::uint8_t kResourceManager = 0x56;
inline constexpr std::uint8_t kInitiate = 0x57;
inline constexpr std::uint8_t kAbort = 0x58;
inline constexpr std::uint8_t kAlarmAck = 0x5C;
inline constexpr std::uint8_t kRead = 0x5E;
inline constexpr std::uint8_t kWrite = 0x5F;
inline constexpr std::uint8_t kNegative = 0x80;
}  // namespace dpv1_function

// The PROFIdrive parameter channel's index, and the Error_Code_1 of "state conflict" (the
// response is not ready yet: read again), which the tracker counts as a poll.
inline constexpr std::uint8_t kProfidriveIndex = 47;
inline constexpr std::uint8_t kDpv1ErrorDecodeDpv1 = 0x80;
inline constexpr std::uint8_t kDpv1StateConflict = 0xB5;

// "Read", "Write", "Idle", "Data_Transport", "Resource_Manager", "Initiate", "Abort",
// "Alarm_Ack"; with bit 7 set the same name with " negative" ("Read negative"); "" for a
// number DP-V1 does not define.
std::string_view dpv1_function_name(std::uint8_t function);
// Error_Decode: "DP-V1", "FMS", "HART", "PNIO"; "" otherwise.
std::string_view dpv1_error_decode_name(std::uint8_t error_decode);
// Error_Code_1 bits 7-4, the class: "application", "access", "resource", "user specific";
// "" for classes 0-9 (reserved).
std::string_view dpv1_error_class_name(std::uint8_t error_code_1);
// Error_Code_1 whole, the code within its class: "read error", "state conflict", ...;
// "user specific" or "reserved" where DP-V1 names none.
std::string_view dpv1_error_code_name(std::uint8_t error_code_1);
// Abort's Instance_Reason_Code bits 5-4: "FDL", "MSAC_C2", "user", "reserved".
std::string_view dpv1_abort_instance_name(std::uint8_t instance_reason);
// Abort's reason code (bits 3-0) in the context of its instance: e.g. "user abort" ...
std::string_view dpv1_abort_reason_name(std::uint8_t instance_reason);

// MSAC_C2 Initiate, request and response. The address parameters (S_Type, S_Len, D_Type,
// D_Len and the addresses) are the same in both.
struct Dpv1Initiate {
    // Request: Send_Timeout in units of 10 ms. Response: Max_Len_Data_Unit.
    std::uint16_t send_timeout = 0;
    std::uint8_t max_len_data_unit = 0;
    std::uint16_t features_supported = 0;  // bytes 1-2 as sent, big-endian
    std::uint16_t profile_features_supported = 0;
    std::uint16_t profile_ident_number = 0;
    bool has_addresses = false;  // the four address-parameter bytes were there
    std::uint8_t s_type = 0;
    std::uint8_t s_len = 0;
    std::uint8_t d_type = 0;
    std::uint8_t d_len = 0;
    Bytes s_addr{};  // as many bytes as S_Len says and the PDU holds
    Bytes d_addr{};
};

// MSAC_C2 Abort.
struct Dpv1Abort {
    std::uint8_t subnet = 0;  // 0 no, 1 subnet-local, 2 subnet-remote
    std::uint8_t instance_reason = 0;
    std::uint8_t instance() const noexcept { return (instance_reason >> 4) & 0x03; }
    std::uint8_t reason() const noexcept { return instance_reason & 0x0F; }
};

// One DP-V1 PDU as read from a data unit. `layout` says which fields are valid.
struct Dpv1Pdu {
    enum class Layout : std::uint8_t {
        None,       // no PDU: an empty data unit (a link-level poll) or an unread one
        Addressed,  // Read, Write, Data_Transport (and Alarm_Ack's slot/type/specifier)
        Error,      // a negative response: Error_Decode, Error_Code_1, Error_Code_2
        Initiate,   // MSAC_C2 Initiate request or positive response
        Abort,      // MSAC_C2 Abort
        Idle,       // MSAC_C2 Idle, function byte only
        Unknown,    // Resource_Manager, or a number DP-V1 does not define: `data` is the rest
    };

    Layout layout = Layout::None;
    // The fixed part of the layout was all there (a ServiceDataShort problem says where it broke
    // off otherwise). Initiate: up to Profile_Ident_Number; the address parameters may be missing.
    bool complete = false;
    std::uint8_t function = 0;  // as sent, bit 7 included
    // Addressed: slot, index and length as sent; data are the bytes after the 4-byte header
    // (`data_offset` is their offset in the telegram). For Alarm_Ack, index holds the
    // Alarm_Type and length the Specifier. A read request carries no data: `length` is the
    // most the master accepts.
    std::uint8_t slot = 0;
    std::uint8_t index = 0;
    std::uint8_t length = 0;
    Bytes data{};
    std::uint16_t data_offset = 0;
    // Error: the three bytes after the function.
    std::uint8_t error_decode = 0;
    std::uint8_t error_code_1 = 0;
    std::uint8_t error_code_2 = 0;
    Dpv1Initiate initiate;
    Dpv1Abort abort;

    bool negative() const noexcept { return (function & dpv1_function::kNegative) != 0; }
    std::uint8_t base_function() const noexcept { return function & 0x7F; }
    bool is_read() const noexcept { return base_function() == dpv1_function::kRead; }
    bool is_write() const noexcept { return base_function() == dpv1_function::kWrite; }
    // Read answered "state conflict": the response is not ready, the master reads again.
    bool is_state_conflict() const noexcept {
        return layout == Layout::Error && error_code_1 == kDpv1StateConflict;
    }
    // A PDU on the PROFIdrive parameter channel (index 47) of Read or Write.
    bool on_parameter_channel() const noexcept {
        return layout == Layout::Addressed && index == kProfidriveIndex &&
               (is_read() || is_write());
    }
};

// Reads the PDU at the reader's position (the FDL data unit). `direction_is_request` tells the
// request layout of Initiate from the response's. Bytes missing from the fixed part are a
// ServiceDataShort problem at their offset; the fields read before the break stay valid and
// `layout` names the PDU. Never throws.
void parse_dpv1_pdu(ByteReader reader, bool direction_is_request, Dpv1Pdu& out,
                    ProblemList& problems) noexcept;

}  // namespace dpscope
