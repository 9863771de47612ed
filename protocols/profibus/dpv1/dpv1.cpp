#include "protocols/profibus/dpv1/dpv1.hpp"

#include <algorithm>

#include "protocols/profibus/dp_payload.hpp"

namespace dpscope {

namespace {

std::string_view base_function_name(std::uint8_t function) {
    switch (function) {
        case dpv1_function::kIdle: return "Idle";
        case dpv1_function::kDataTransport: return "Data_Transport";
        case dpv1_function::kResourceManager: return "Resource_Manager";
        case dpv1_function::kInitiate: return "Initiate";
        case dpv1_function::kAbort: return "Abort";
        case dpv1_function::kAlarmAck: return "Alarm_Ack";
        case dpv1_function::kRead: return "Read";
        case dpv1_function::kWrite: return "Write";
        default: return "";
    }
}

std::string_view negative_function_name(std::uint8_t base) {
    switch (base) {
        case dpv1_function::kIdle: return "Idle negative";
        case dpv1_function::kDataTransport: return "Data_Transport negative";
        case dpv1_function::kResourceManager: return "Resource_Manager negative";
        case dpv1_function::kInitiate: return "Initiate negative";
        case dpv1_function::kAbort: return "Abort negative";
        case dpv1_function::kAlarmAck: return "Alarm_Ack negative";
        case dpv1_function::kRead: return "Read negative";
        case dpv1_function::kWrite: return "Write negative";
        default: return "";
    }
}

// True when the fixed part was there (the address parameters may still be missing).
bool read_initiate(ByteReader& reader, bool request, Dpv1Initiate& out, ProblemList& problems) {
    // Request: Function, 3 reserved, Send_Timeout (2), Features_Supported (2),
    // Profile_Features_Supported (2), Profile_Ident_Number (2), then the address parameters.
    // Response: Function, Max_Len_Data_Unit, Features_Supported (2),
    // Profile_Features_Supported (2), Profile_Ident_Number (2), then the same address parameters.
    constexpr std::size_t kRequestFixed = 11;  // after the function byte
    constexpr std::size_t kResponseFixed = 7;
    std::size_t fixed = request ? kRequestFixed : kResponseFixed;
    if (reader.remaining() < fixed) {
        report_service_data_short(reader, fixed, problems);
        return false;
    }
    if (request) {
        reader.skip(3);
        out.send_timeout = *reader.u16_be();
    } else {
        out.max_len_data_unit = *reader.u8();
    }
    out.features_supported = *reader.u16_be();
    out.profile_features_supported = *reader.u16_be();
    out.profile_ident_number = *reader.u16_be();
    if (reader.remaining() < 4) {
        report_service_data_short(reader, 4, problems);
        return true;
    }
    out.has_addresses = true;
    out.s_type = *reader.u8();
    out.s_len = *reader.u8();
    out.d_type = *reader.u8();
    out.d_len = *reader.u8();
    auto take = [&](std::uint8_t length, Bytes& into) {
        std::size_t n = std::min<std::size_t>(length, reader.remaining());
        into = *reader.bytes(n);
        if (n < length) report_service_data_short(reader, length - n, problems);
    };
    take(out.s_len, out.s_addr);
    take(out.d_len, out.d_addr);
    return true;
}

}  // namespace

std::string_view dpv1_function_name(std::uint8_t function) {
    if (function & dpv1_function::kNegative) return negative_function_name(function & 0x7F);
    return base_function_name(function);
}

std::string_view dpv1_error_decode_name(std::uint8_t error_decode) {
    switch (error_decode) {
        case 0x80: return "DP-V1";
        case 0x81: return "PNIO";
        case 0xFE: return "FMS";
        case 0xFF: return "HART";
        default: return "";
    }
}

std::string_view dpv1_error_class_name(std::uint8_t error_code_1) {
    switch (error_code_1 >> 4) {
        case 0xA: return "application";
        case 0xB: return "access";
        case 0xC: return "resource";
        case 0xD:
        case 0xE:
        case 0xF: return "user specific";
        default: return "";
    }
}

std::string_view dpv1_error_code_name(std::uint8_t error_code_1) {
    switch (error_code_1) {
        case 0xA0: return "read error";
        case 0xA1: return "write error";
        case 0xA2: return "module failure";
        case 0xA8: return "version conflict";
        case 0xA9: return "feature not supported";
        case 0xB0: return "invalid index";
        case 0xB1: return "write length error";
        case 0xB2: return "invalid slot";
        case 0xB3: return "type conflict";
        case 0xB4: return "invalid area";
        case 0xB5: return "state conflict";
        case 0xB6: return "access denied";
        case 0xB7: return "invalid range";
        case 0xB8: return "invalid parameter";
        case 0xB9: return "invalid type";
        case 0xC0: return "read constraint conflict";
        case 0xC1: return "write constraint conflict";
        case 0xC2: return "resource busy";
        case 0xC3: return "resource unavailable";
        default: break;
    }
    std::uint8_t error_class = error_code_1 >> 4;
    std::uint8_t code = error_code_1 & 0x0F;
    if (error_class >= 0xD) return "user specific";
    if (error_class == 0xA && code >= 0xA) return "user specific";
    if (error_class == 0xB && code >= 0xA) return "user specific";
    if (error_class == 0xC && code >= 0x8) return "user specific";
    return "reserved";
}

std::string_view dpv1_abort_instance_name(std::uint8_t instance_reason) {
    switch ((instance_reason >> 4) & 0x03) {
        case 0: return "FDL";
        case 1: return "MSAC_C2";
        case 2: return "user";
        default: return "reserved";
    }
}

std::string_view dpv1_abort_reason_name(std::uint8_t instance_reason) {
    std::uint8_t instance = (instance_reason >> 4) & 0x03;
    std::uint8_t reason = instance_reason & 0x0F;
    if (instance == 0) {  // FDL: the link layer's status of the failed service (dpscope's reading)
        switch (reason) {
            case 1: return "user error (UE)";
            case 2: return "no resource (RR)";
            case 3: return "service not activated (RS)";
            case 9: return "no response (NR)";
            case 10: return "data high (DH)";
            case 11: return "local resource error (LR)";
            case 12: return "no response data (RDL)";
            case 13: return "response data high (RDH)";
            case 14: return "not in the logical ring (DS)";
            case 15: return "no reaction (NA)";
            default: return "reserved";
        }
    }
    if (instance == 1) {  // MSAC_C2 (DDLM) (dpscope's reading of IEC 61158-6-3)
        switch (reason) {
            case 1: return "sequence error (ABT_SE)";
            case 2: return "invalid request PDU (ABT_FE)";
            case 3: return "connection timeout (ABT_TO)";
            case 4: return "invalid response PDU (ABT_RE)";
            case 5: return "invalid service from the user (ABT_IV)";
            case 6: return "Send_Timeout too small (ABT_STO)";
            case 7: return "invalid additional address information (ABT_IA)";
            case 8: return "waiting for FDL_DATA_REPLY.con (ABT_OC)";
            default: return "reserved";
        }
    }
    if (instance == 2) return "user specific";
    return "reserved";
}

void parse_dpv1_pdu(ByteReader reader, bool direction_is_request, Dpv1Pdu& out,
                    ProblemList& problems) noexcept {
    out = Dpv1Pdu{};
    auto function = reader.u8();
    if (!function) return;  // an empty data unit: a poll at the link layer, no PDU
    out.function = *function;
    if (out.negative()) {
        out.layout = Dpv1Pdu::Layout::Error;
        if (reader.remaining() < 3) {
            report_service_data_short(reader, 3, problems);
            out.error_decode = reader.u8().value_or(0);
            out.error_code_1 = reader.u8().value_or(0);
            return;
        }
        out.error_decode = *reader.u8();
        out.error_code_1 = *reader.u8();
        out.error_code_2 = *reader.u8();
        out.complete = true;
        return;
    }
    switch (out.function) {
        case dpv1_function::kRead:
        case dpv1_function::kWrite:
        case dpv1_function::kDataTransport:
        case dpv1_function::kAlarmAck: {
            out.layout = Dpv1Pdu::Layout::Addressed;
            // Alarm_Ack has slot, type and specifier only; the others slot, index and length.
            if (reader.remaining() < 3) {
                report_service_data_short(reader, 3, problems);
                out.slot = reader.u8().value_or(0);
                out.index = reader.u8().value_or(0);
                return;
            }
            out.slot = *reader.u8();
            out.index = *reader.u8();
            out.length = *reader.u8();
            out.complete = true;
            out.data_offset = static_cast<std::uint16_t>(reader.offset());
            out.data = reader.rest();
            return;
        }
        case dpv1_function::kInitiate:
            out.layout = Dpv1Pdu::Layout::Initiate;
            out.complete = read_initiate(reader, direction_is_request, out.initiate, problems);
            return;
        case dpv1_function::kAbort:
            out.layout = Dpv1Pdu::Layout::Abort;
            if (reader.remaining() < 2) {
                report_service_data_short(reader, 2, problems);
                out.abort.subnet = reader.u8().value_or(0);
                return;
            }
            out.abort.subnet = *reader.u8();
            out.abort.instance_reason = *reader.u8();
            out.complete = true;
            return;
        case dpv1_function::kIdle:
            out.layout = Dpv1Pdu::Layout::Idle;
            out.complete = true;
            return;
        default:
            out.layout = Dpv1Pdu::Layout::Unknown;
            out.complete = true;
            out.data_offset = static_cast<std::uint16_t>(reader.offset());
            out.data = reader.rest();
            return;
    }
}

}  // namespace dpscope
