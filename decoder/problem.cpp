#include "decoder/problem.hpp"

#include <fmt/format.h>

#include "decoder/counted.hpp"

namespace dpscope {

std::string_view severity_name(Severity severity) {
    switch (severity) {
        case Severity::Note: return "note";
        case Severity::Warning: return "warning";
        case Severity::Error: return "error";
    }
    return "error";
}

std::string_view problem_kind_name(ProblemKind kind) {
    switch (kind) {
        case ProblemKind::EmptyRecord: return "empty_record";
        case ProblemKind::BadStartDelimiter: return "bad_start_delimiter";
        case ProblemKind::Truncated: return "truncated";
        case ProblemKind::LengthMismatch: return "length_mismatch";
        case ProblemKind::LengthOutOfRange: return "length_out_of_range";
        case ProblemKind::StartDelimiterRepeat: return "start_delimiter_repeat";
        case ProblemKind::FcsMismatch: return "fcs_mismatch";
        case ProblemKind::BadEndDelimiter: return "bad_end_delimiter";
        case ProblemKind::TrailingBytes: return "trailing_bytes";
        case ProblemKind::InvalidAddress: return "invalid_address";
        case ProblemKind::AddressExtensionShort: return "address_extension_short";
        case ProblemKind::ServiceDataShort: return "service_data_short";
        case ProblemKind::CfgIdentifierTruncated: return "cfg_identifier_truncated";
        case ProblemKind::DiagBlockTruncated: return "diag_block_truncated";
        case ProblemKind::ReservedFrameControl: return "reserved_frame_control";
        case ProblemKind::Count: break;
    }
    return "unknown";
}

Severity problem_severity(ProblemKind kind) {
    return kind == ProblemKind::TrailingBytes ? Severity::Warning : Severity::Error;
}

std::string problem_message(const Problem& p) {
    switch (p.kind) {
        case ProblemKind::EmptyRecord: return "record holds no bytes";
        case ProblemKind::BadStartDelimiter:
            return fmt::format(
                "byte {}: 0x{:02X} is not a start delimiter (SD1 0x10, SD2 0x68, "
                "SD3 0xA2, SD4 0xDC, SC 0xE5)",
                p.offset, p.actual);
        case ProblemKind::Truncated:
            return fmt::format("telegram truncated: needs {} bytes, has {}", p.expected, p.actual);
        case ProblemKind::LengthMismatch:
            return fmt::format("byte {}: LEr {} differs from LE {}", p.offset, p.actual,
                               p.expected);
        case ProblemKind::LengthOutOfRange:
            return fmt::format("byte {}: LE {} outside 4..249", p.offset, p.actual);
        case ProblemKind::StartDelimiterRepeat:
            return fmt::format("byte {}: repeated start delimiter is 0x{:02X}, expected 0x68",
                               p.offset, p.actual);
        case ProblemKind::FcsMismatch:
            return fmt::format("byte {}: FCS 0x{:02X} wrong, checksum of the data is 0x{:02X}",
                               p.offset, p.actual, p.expected);
        case ProblemKind::BadEndDelimiter:
            return fmt::format("byte {}: end delimiter is 0x{:02X}, expected 0x16", p.offset,
                               p.actual);
        case ProblemKind::TrailingBytes:
            return fmt::format("byte {}: {} after the end of the telegram", p.offset,
                               counted(p.actual, "byte", "bytes"));
        case ProblemKind::InvalidAddress:
            return fmt::format("byte {}: address 0x{:02X} has bit 7 set, not allowed in a token",
                               p.offset, p.actual);
        case ProblemKind::AddressExtensionShort:
            return fmt::format("byte {}: address extension announced but the data unit ends",
                               p.offset);
        case ProblemKind::ServiceDataShort:
            return fmt::format("byte {}: service data has {} bytes, needs at least {}", p.offset,
                               p.actual, p.expected);
        case ProblemKind::CfgIdentifierTruncated:
            return fmt::format("byte {}: identifier announces {} more bytes, only {} present",
                               p.offset, p.expected, p.actual);
        case ProblemKind::DiagBlockTruncated:
            return fmt::format("byte {}: diagnosis block of {} bytes, only {} present", p.offset,
                               p.expected, p.actual);
        case ProblemKind::ReservedFrameControl:
            return fmt::format(
                "byte {}: frame control 0x{:02X} has the reserved bit 7 set (only the clock value "
                "request 0xC0 sets it)",
                p.offset, p.actual);
        case ProblemKind::Count: break;
    }
    return "unknown problem";
}

}  // namespace dpscope
