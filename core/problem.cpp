#include "core/problem.hpp"

#include <fmt/format.h>

#include <iterator>

#include "core/catalogue.hpp"
#include "core/counted.hpp"

namespace dpscope {

std::string_view severity_name(Severity severity) {
    switch (severity) {
        case Severity::Note: return "note";
        case Severity::Warning: return "warning";
        case Severity::Error: return "error";
    }
    return "error";
}

namespace {

using enum ProblemComponent;

constexpr ProblemKindInfo kCatalogue[] = {
    {ProblemKind::EmptyRecord, "empty_record", Severity::Error, Framing,
     "a capture record with no bytes at all"},
    {ProblemKind::BadStartDelimiter, "bad_start_delimiter", Severity::Error, Framing,
     "the first byte starts no telegram (PROFIBUS: none of SD1, SD2, SD3, SD4, SC; FC: not STX; "
     "VLT 2000: not '<')"},
    {ProblemKind::Truncated, "truncated", Severity::Error, Framing,
     "the telegram ends before its structure says it should"},
    {ProblemKind::LengthMismatch, "length_mismatch", Severity::Error, Framing,
     "SD2: LE differs from LEr"},
    {ProblemKind::LengthOutOfRange, "length_out_of_range", Severity::Error, Framing,
     "SD2: LE outside 4..249"},
    {ProblemKind::StartDelimiterRepeat, "start_delimiter_repeat", Severity::Error, Framing,
     "SD2: the repeated start delimiter is not 0x68"},
    {ProblemKind::FcsMismatch, "fcs_mismatch", Severity::Error, Fdl, "the FDL checksum is wrong"},
    {ProblemKind::BadEndDelimiter, "bad_end_delimiter", Severity::Error, Framing,
     "the end delimiter is not 0x16"},
    {ProblemKind::TrailingBytes, "trailing_bytes", Severity::Warning, Framing,
     "bytes after the end of the telegram in the same record"},
    {ProblemKind::InvalidAddress, "invalid_address", Severity::Error, Fdl,
     "SD4: an address with bit 7 set (tokens carry no extension)"},
    {ProblemKind::AddressExtensionShort, "address_extension_short", Severity::Error, Fdl,
     "an address-extension bit announces a SAP byte that is not there"},
    {ProblemKind::ServiceDataShort, "service_data_short", Severity::Error, DpService,
     "a DP service's data unit is shorter than the service requires"},
    {ProblemKind::CfgIdentifierTruncated, "cfg_identifier_truncated", Severity::Error, DpService,
     "a special-format identifier announces bytes that are not there"},
    {ProblemKind::DiagBlockTruncated, "diag_block_truncated", Severity::Error, DpService,
     "an extended-diagnosis block runs past the end of the data"},
    {ProblemKind::ReservedFrameControl, "reserved_frame_control", Severity::Error, Fdl,
     "FC bit 7 set in anything but the clock value request 0xC0"},
    {ProblemKind::LgeInvalid, "lge_invalid", Severity::Error, Framing,
     "FC protocol: LGE is none of 6 (process block), 14 (parameter block), 10..255 (text block)"},
    {ProblemKind::BccMismatch, "bcc_mismatch", Severity::Error, Fc,
     "FC protocol: the BCC (XOR of STX to the last data byte) is wrong"},
    {ProblemKind::AdrInvalid, "adr_invalid", Severity::Error, Fc,
     "FC protocol: the address byte names no address (0 in the 1-31 format, 127 in 1-126)"},
    {ProblemKind::Vlt2000CharacterInvalid, "vlt2000_character_invalid", Severity::Error, Framing,
     "VLT 2000: a character between '<' and '>' is not printable ASCII"},
    {ProblemKind::Vlt2000FieldInvalid, "vlt2000_field_invalid", Severity::Error, Vlt2000,
     "VLT 2000: a character that must be a digit (address, parameter, value, decimals, checksum) "
     "is not"},
    {ProblemKind::Vlt2000LetterUnknown, "vlt2000_letter_unknown", Severity::Error, Vlt2000,
     "VLT 2000: the control letter is none of U, R, C, I"},
    {ProblemKind::Vlt2000ChecksumMismatch, "vlt2000_checksum_mismatch", Severity::Error, Vlt2000,
     "VLT 2000: the checksum (sum of the 18 characters after '<', last two decimal digits) is "
     "wrong"},
};

static_assert(catalogue::one_row_per_kind_in_order(std::span<const ProblemKindInfo>(kCatalogue),
                                                   kProblemKindCount),
              "kCatalogue: one row per ProblemKind, in enum order");
static_assert(catalogue::names_unique(std::span<const ProblemKindInfo>(kCatalogue)),
              "kCatalogue: every problem kind needs a name of its own");

constexpr std::string_view kComponentNames[] = {"framing", "FDL", "DP service", "FC telegram",
                                                "VLT 2000 telegram"};
static_assert(std::size(kComponentNames) == kProblemComponentCount);

}  // namespace

std::span<const ProblemKindInfo> problem_catalogue() noexcept { return kCatalogue; }

const ProblemKindInfo& problem_kind_info(ProblemKind kind) noexcept {
    return kCatalogue[static_cast<std::size_t>(kind)];
}

std::string_view problem_kind_name(ProblemKind kind) {
    const auto index = static_cast<std::size_t>(kind);
    return index < kProblemKindCount ? kCatalogue[index].name : "unknown";
}

Severity problem_severity(ProblemKind kind) {
    const auto index = static_cast<std::size_t>(kind);
    return index < kProblemKindCount ? kCatalogue[index].severity : Severity::Error;
}

ProblemComponent problem_component(ProblemKind kind) { return problem_kind_info(kind).component; }

std::vector<ProblemKind> problem_kinds_of(ProblemComponent component) {
    return catalogue::kinds_of(std::span<const ProblemKindInfo>(kCatalogue), component);
}

std::string_view problem_component_name(ProblemComponent component) {
    return kComponentNames[static_cast<std::size_t>(component)];
}

namespace {

// 'A', or 0x07 for a character that does not print.
std::string quoted_char(std::uint32_t c) {
    if (c >= 0x20 && c <= 0x7E) return fmt::format("'{}'", static_cast<char>(c));
    return fmt::format("0x{:02X}", c);
}

// The VLT 2000 field a byte offset belongs to (protocols/vlt2000/vlt2000_telegram.hpp).
std::string_view vlt2000_field_at(std::uint32_t offset) {
    if (offset <= 2) return "address";
    if (offset <= 7) return "control/status word";
    if (offset <= 11) return "parameter number";
    if (offset <= 17) return "value";
    if (offset == 18) return "decimal position";
    return "checksum";
}

}  // namespace

std::string problem_message(const Problem& p) {
    switch (p.kind) {
        case ProblemKind::EmptyRecord: return "record holds no bytes";
        case ProblemKind::BadStartDelimiter:
            // The FC decoder names what it wanted (STX 0x02), the VLT 2000 decoder its '<'; FDL
            // has five start delimiters.
            if (p.expected == 0x02)
                return fmt::format("byte {}: 0x{:02X} is not STX 0x{:02X}", p.byte_number(),
                                   p.actual, p.expected);
            if (p.expected != 0)
                return fmt::format("byte {}: {} is not {} (0x{:02X})", p.byte_number(),
                                   quoted_char(p.actual), quoted_char(p.expected), p.expected);
            return fmt::format(
                "byte {}: 0x{:02X} is not a start delimiter (SD1 0x10, SD2 0x68, "
                "SD3 0xA2, SD4 0xDC, SC 0xE5)",
                p.byte_number(), p.actual);
        case ProblemKind::Truncated:
            return fmt::format("telegram truncated: needs {}, has {}",
                               counted(p.expected, "byte", "bytes"), p.actual);
        case ProblemKind::LengthMismatch:
            return fmt::format("byte {}: LEr {} differs from LE {}", p.byte_number(), p.actual,
                               p.expected);
        case ProblemKind::LengthOutOfRange:
            return fmt::format("byte {}: LE {} outside 4..249", p.byte_number(), p.actual);
        case ProblemKind::StartDelimiterRepeat:
            return fmt::format("byte {}: repeated start delimiter is 0x{:02X}, expected 0x68",
                               p.byte_number(), p.actual);
        case ProblemKind::FcsMismatch:
            return fmt::format("byte {}: FCS 0x{:02X} wrong, checksum of the data is 0x{:02X}",
                               p.byte_number(), p.actual, p.expected);
        case ProblemKind::BadEndDelimiter:
            // The VLT 2000 decoder names what it wanted ('>' 0x3E); FDL's is ED 0x16.
            if (p.expected != 0)
                return fmt::format("byte {}: end delimiter is {}, expected {} (0x{:02X})",
                                   p.byte_number(), quoted_char(p.actual), quoted_char(p.expected),
                                   p.expected);
            return fmt::format("byte {}: end delimiter is 0x{:02X}, expected 0x16", p.byte_number(),
                               p.actual);
        case ProblemKind::TrailingBytes:
            return fmt::format("byte {}: {} after the end of the telegram", p.byte_number(),
                               counted(p.actual, "byte", "bytes"));
        case ProblemKind::InvalidAddress:
            return fmt::format("byte {}: address 0x{:02X} has bit 7 set, not allowed in a token",
                               p.byte_number(), p.actual);
        case ProblemKind::AddressExtensionShort:
            return fmt::format("byte {}: address extension announced but the data unit ends",
                               p.byte_number());
        case ProblemKind::ServiceDataShort:
            return fmt::format("byte {}: service data has {}, needs at least {}", p.byte_number(),
                               counted(p.actual, "byte", "bytes"), p.expected);
        case ProblemKind::CfgIdentifierTruncated:
            return fmt::format("byte {}: identifier announces {} more, only {} present",
                               p.byte_number(), counted(p.expected, "byte", "bytes"), p.actual);
        case ProblemKind::DiagBlockTruncated:
            return fmt::format("byte {}: diagnosis block of {}, only {} present", p.byte_number(),
                               counted(p.expected, "byte", "bytes"), p.actual);
        case ProblemKind::ReservedFrameControl:
            return fmt::format(
                "byte {}: frame control 0x{:02X} has the reserved bit 7 set (only the clock value "
                "request 0xC0 sets it)",
                p.byte_number(), p.actual);
        case ProblemKind::LgeInvalid:
            return fmt::format(
                "byte {}: LGE {} is no FC block length (6 process, 14 parameter, 10..255 text)",
                p.byte_number(), p.actual);
        case ProblemKind::BccMismatch:
            return fmt::format("byte {}: BCC 0x{:02X} wrong, XOR of the telegram is 0x{:02X}",
                               p.byte_number(), p.actual, p.expected);
        case ProblemKind::AdrInvalid:
            return fmt::format("byte {}: address byte 0x{:02X} names no address", p.byte_number(),
                               p.actual);
        case ProblemKind::Vlt2000CharacterInvalid:
            return fmt::format("byte {}: 0x{:02X} is not printable ASCII", p.byte_number(),
                               p.actual);
        case ProblemKind::Vlt2000FieldInvalid:
            return fmt::format("byte {}: {} is not a digit ({})", p.byte_number(),
                               quoted_char(p.actual), vlt2000_field_at(p.offset));
        case ProblemKind::Vlt2000LetterUnknown:
            return fmt::format("byte {}: control letter {} is none of U, R, C, I", p.byte_number(),
                               quoted_char(p.actual));
        case ProblemKind::Vlt2000ChecksumMismatch:
            // The characters after '<' to the decimal position: offsets 1-18.
            return fmt::format(
                "byte {}: checksum {:02} wrong, the sum of bytes {}-{} ends in {:02}",
                p.byte_number(), p.actual, 1 + p.first_byte, 18 + p.first_byte, p.expected);
        case ProblemKind::Count: break;
    }
    return "unknown problem";
}

}  // namespace dpscope
