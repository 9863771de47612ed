#include "core/code_tables.hpp"

#include <array>

#include "protocols/fc/fc_codes.hpp"
#include "protocols/vlt2000/vlt2000_codes.hpp"

namespace dpscope {

std::string_view dialect_name(Dialect dialect) {
    switch (dialect) {
        case Dialect::Vlt: return "vlt";
        case Dialect::Ge: return "ge";
        case Dialect::Profidrive: return "profidrive";
        case Dialect::Fc: return "fc";
        case Dialect::Vlt2000: return "vlt2000";
    }
    return "vlt";
}

std::optional<Dialect> dialect_from_name(std::string_view name) {
    for (Dialect dialect : kDialects)
        if (name == dialect_name(dialect)) return dialect;
    return std::nullopt;
}

bool read_pcv(ByteReader& reader, const PkeLayout& layout, Pcv& pcv) noexcept {
    if (reader.remaining() < 8) return false;
    pcv.pca = *reader.u16_be();
    pcv.rc = static_cast<std::uint8_t>(pcv.pca >> 12);
    pcv.spm = layout.spm_bit && ((pcv.pca >> *layout.spm_bit) & 1u) != 0;
    pcv.pnu = static_cast<std::uint16_t>(pcv.pca & ((1u << layout.pnu_bits) - 1u));
    const std::uint8_t ind_high = *reader.u8();
    pcv.ind_low = *reader.u8();
    pcv.ind = layout.index_byte == IndexByte::High ? ind_high : pcv.ind_low;
    pcv.pva = *reader.u32_be();
    return true;
}

std::uint32_t pcv_value(const Pcv& pcv, ValueWidth width) noexcept {
    return width == ValueWidth::Word ? (pcv.pva & 0xFFFF) : pcv.pva;
}

bool carries_parameter_value(Dialect dialect, bool request, std::uint8_t rc) noexcept {
    if (request) {
        const RequestCode& code = request_code(dialect, rc);
        return code.defined && code.is_change && code.width != ValueWidth::None && rc != 5;
    }
    const ResponseCode& code = response_code(dialect, rc);
    if (code.width == ValueWidth::None) return false;
    return (code.kind == ResponseKind::Value && rc != 3 && rc != 6) ||
           code.kind == ResponseKind::Spontaneous;
}

namespace {

using W = ValueWidth;
using K = ResponseKind;

// Seed 000 (VLT 5000 MG.90.D1.02) request table.
constexpr std::array<RequestCode, 16> kVltRequests{{
    {"No request", W::None, true, false, false},
    {"Request parameter value", W::None, true, false, false},
    {"Change parameter value (word)", W::Word, true, true, false},
    {"Change parameter value (double word)", W::DoubleWord, true, true, false},
    {"Request description element", W::None, true, false, false},
    {"Change description element", W::DoubleWord, true, true, false},
    {"Request parameter value (array)", W::None, true, false, true},
    {"Change parameter value (array word)", W::Word, true, true, true},
    {"Change parameter value (array double word)", W::DoubleWord, true, true, true},
    {"Request number of array elements", W::None, true, false, false},
    {"Not assigned", W::None, false, false, false},
    {"Not assigned", W::None, false, false, false},
    {"Not assigned", W::None, false, false, false},
    {"Not assigned", W::None, false, false, false},
    {"Not assigned", W::None, false, false, false},
    {"Not assigned", W::None, false, false, false},
}};

// Seed 000 response table.
constexpr std::array<ResponseCode, 16> kVltResponses{{
    {"No response", W::None, K::None, false},
    {"Transmit parameter value (word)", W::Word, K::Value, false},
    {"Transmit parameter value (double word)", W::DoubleWord, K::Value, false},
    {"Transmit description element", W::DoubleWord, K::Value, false},
    {"Transmit parameter value (array word)", W::Word, K::Value, true},
    {"Transmit parameter value (array double word)", W::DoubleWord, K::Value, true},
    {"Transmit number of array elements", W::Word, K::Value, false},
    {"Request not executable", W::Word, K::Rejected, false},
    {"No operating authority for PCV interface", W::None, K::NoAuthority, false},
    {"Spontaneous message (word)", W::Word, K::Spontaneous, false},
    {"Spontaneous message (double word)", W::DoubleWord, K::Spontaneous, false},
    {"Spontaneous message (array word)", W::Word, K::Spontaneous, true},
    {"Spontaneous message (array double word)", W::DoubleWord, K::Spontaneous, true},
    {"Not assigned", W::None, K::Undefined, false},
    {"Not assigned", W::None, K::Undefined, false},
    {"Not assigned", W::None, K::Undefined, false},
}};

// Seed 002 (GE AF-600 FP / AF-650 GP) request table, in its words.
constexpr std::array<RequestCode, 16> kGeRequests{{
    {"No request", W::None, true, false, false},
    {"Request parameter value", W::None, true, false, false},
    {"Change parameter value (word)", W::Word, true, true, false},
    {"Change parameter value (long word)", W::DoubleWord, true, true, false},
    {"Request description element", W::None, true, false, false},
    {"Change description element", W::DoubleWord, true, true, false},
    {"Request parameter value (array)", W::None, true, false, true},
    {"Change parameter value (array word)", W::Word, true, true, true},
    {"Change parameter value (array long word)", W::DoubleWord, true, true, true},
    {"Request number of array elements", W::None, true, false, false},
    {"Not used", W::None, false, false, false},
    {"Not used", W::None, false, false, false},
    {"Not used", W::None, false, false, false},
    {"Not used", W::None, false, false, false},
    {"Not used", W::None, false, false, false},
    {"Not used", W::None, false, false, false},
}};

// Seed 002 response table: 9..12 "Not used" (no spontaneous messages), 13-15 "Not used".
constexpr std::array<ResponseCode, 16> kGeResponses{{
    {"No response", W::None, K::None, false},
    {"Transfer parameter value (word)", W::Word, K::Value, false},
    {"Transfer parameter value (long word)", W::DoubleWord, K::Value, false},
    {"Transfer description element", W::DoubleWord, K::Value, false},
    {"Transfer parameter value (array word)", W::Word, K::Value, true},
    {"Transfer parameter value (array long word)", W::DoubleWord, K::Value, true},
    {"Transfer number of array elements", W::Word, K::Value, false},
    {"Request rejected", W::Word, K::Rejected, false},
    {"Not serviceable by PCV interface", W::None, K::NoAuthority, false},
    {"Not used", W::None, K::Undefined, false},
    {"Not used", W::None, K::Undefined, false},
    {"Not used", W::None, K::Undefined, false},
    {"Not used", W::None, K::Undefined, false},
    {"Not used", W::None, K::Undefined, false},
    {"Not used", W::None, K::Undefined, false},
    {"Not used", W::None, K::Undefined, false},
}};

// PROFIdrive V2 task identifiers (MICROMASTER 440 table).
constexpr std::array<RequestCode, 16> kProfidriveRequests{{
    {"No task", W::None, true, false, false},
    {"Request parameter value", W::None, true, false, false},
    {"Change parameter value (word)", W::Word, true, true, false},
    {"Change parameter value (double word)", W::DoubleWord, true, true, false},
    {"Request descriptive element", W::None, true, false, false},
    {"Change descriptive element", W::DoubleWord, true, true, false},
    {"Request parameter value (array)", W::None, true, false, true},
    {"Change parameter value (array word)", W::Word, true, true, true},
    {"Change parameter value (array double word)", W::DoubleWord, true, true, true},
    {"Request number of array elements", W::None, true, false, false},
    {"Reserved", W::None, false, false, false},
    {"Change parameter value (array double word) and store in EEPROM", W::DoubleWord, true, true,
     true},
    {"Change parameter value (array word) and store in EEPROM", W::Word, true, true, true},
    {"Change parameter value (double word) and store in EEPROM", W::DoubleWord, true, true, false},
    {"Change parameter value (word) and store in EEPROM", W::Word, true, true, false},
    {"Read or change text", W::None, true, true, false},
}};

// PROFIdrive V2 reply identifiers.
constexpr std::array<ResponseCode, 16> kProfidriveResponses{{
    {"No reply", W::None, K::None, false},
    {"Transfer parameter value (word)", W::Word, K::Value, false},
    {"Transfer parameter value (double word)", W::DoubleWord, K::Value, false},
    {"Transfer descriptive element", W::DoubleWord, K::Value, false},
    {"Transfer parameter value (array word)", W::Word, K::Value, true},
    {"Transfer parameter value (array double word)", W::DoubleWord, K::Value, true},
    {"Transfer number of array elements", W::Word, K::Value, false},
    {"Request cannot be executed", W::Word, K::Rejected, false},
    {"No master authority for the PKW interface", W::None, K::NoAuthority, false},
    {"Parameter change report (word)", W::Word, K::Spontaneous, false},
    {"Parameter change report (double word)", W::DoubleWord, K::Spontaneous, false},
    {"Parameter change report (array word)", W::Word, K::Spontaneous, true},
    {"Parameter change report (array double word)", W::DoubleWord, K::Spontaneous, true},
    {"Reserved", W::None, K::Undefined, false},
    {"Reserved", W::None, K::Undefined, false},
    {"Transfer text", W::None, K::Text, false},
}};

struct ErrorEntry {
    std::uint16_t number;
    std::string_view text;
};

// Seed 000 (0..19), word for word.
constexpr ErrorEntry kVltErrors[] = {
    {0, "Improper PNU"},
    {1, "Parameter value not changeable"},
    {2, "Upper or lower value passed"},
    {3, "Faulty subindex"},
    {4, "No array"},
    {5, "Wrong data type"},
    {6, "Setting not permitted (resettable only)"},
    {7, "Description element not changeable"},
    {8, "No PPO-Write for IR"},
    {9, "Description data not available"},
    {10, "Access group"},
    {11, "No parameter operating authority"},
    {12, "Keyword missing"},
    {13, "Text not readable in cyclical traffic"},
    {14, "Name not readable in cyclical traffic"},
    {15, "Text array not available"},
    {16, "PPO-Write missing"},
    {17, "Request temporarily unexecutable"},
    {18, "Other error"},
    {19, "Data not readable in cyclical traffic"},
};

// Seed 002 (0..19, 130, 131), word for word.
constexpr ErrorEntry kGeErrors[] = {
    {0, "Illegal PNU"},
    {1, "Parameter value cannot be changed"},
    {2, "Upper or lower limit exceeded"},
    {3, "Subindex corrupted"},
    {4, "No array"},
    {5, "Data type false"},
    {6, "Cannot be set by user (reset only)"},
    {7, "Description element cannot be changed"},
    {8, "IR required PPO-write not available"},
    {9, "Description data not available"},
    {10, "Access group"},
    {11, "No parameter write access"},
    {12, "Key word missing"},
    {13, "Text in cyclical transmission not readable"},
    {14, "Name in cyclical transmission not readable"},
    {15, "Text array not available"},
    {16, "PPO-write missing"},
    {17, "Request temporarily rejected"},
    {18, "Other fault"},
    {19, "Data in cyclical transmission not readable"},
    {130, "There is no network access to the parameter called"},
    {131, "Data change is not possible because factory setup has been selected"},
};

// PROFIdrive V2 0..19, continuation 20..24 (MASTERDRIVES), and manufacturer numbers seen in
// PKW replies of Siemens drives (MASTERDRIVES, MICROMASTER, G120).
constexpr ErrorEntry kProfidriveErrors[] = {
    {0, "Illegal parameter number"},
    {1, "Parameter value cannot be changed"},
    {2, "Upper or lower limit exceeded"},
    {3, "Faulty subindex"},
    {4, "No array"},
    {5, "Wrong data type"},
    {6, "Setting not allowed (reset only)"},
    {7, "Descriptive element cannot be changed"},
    {8, "PPO-Write requested in IR not available"},
    {9, "Description data not available"},
    {10, "Access group wrong"},
    {11, "No operating (change) rights"},
    {12, "Keyword (password) missing"},
    {13, "Text not readable in cyclic transfer"},
    {14, "Name not readable in cyclic transfer"},
    {15, "Text array not available"},
    {16, "PPO-Write missing"},
    {17, "Request cannot be executed in the current operating state"},
    {18, "Other error"},
    {19, "Data not readable in cyclic transfer"},
    {20, "Illegal value"},
    {21, "Response too long"},
    {22, "Illegal parameter address"},
    {23, "Illegal format"},
    {24, "Number of values inconsistent"},
    {101, "Parameter number currently deactivated (manufacturer)"},
    {102, "Channel width too small (manufacturer)"},
    {103, "Incorrect number of PKWs (manufacturer)"},
    {104, "Parameter value not permitted (manufacturer)"},
    {105, "Parameter is indexed (manufacturer)"},
    {106, "Task not implemented (manufacturer)"},
    {107, "No write access while controller enabled (manufacturer)"},
    {200, "Modified minimum not reached (manufacturer)"},
    {201, "Modified maximum exceeded (manufacturer)"},
    {204, "Access level does not allow change (manufacturer)"},
};

template <std::size_t N>
std::string_view find_error(const ErrorEntry (&table)[N], std::uint16_t number) {
    for (const ErrorEntry& entry : table)
        if (entry.number == number) return entry.text;
    return {};
}

struct Pairing {
    std::uint16_t positive;  // bit n set: response RC n is a positive answer
};

constexpr std::uint16_t bit(int n) { return static_cast<std::uint16_t>(1u << n); }

constexpr std::array<Pairing, 16> kPairings{{
    {bit(0)},           // 0: no request -> no response
    {bit(1) | bit(2)},  // 1: read -> word or double word
    {bit(1)},           // 2
    {bit(2)},           // 3
    {bit(3)},           // 4
    {bit(3)},           // 5
    {bit(4) | bit(5)},  // 6
    {bit(4)},           // 7
    {bit(5)},           // 8
    {bit(6)},           // 9
    {0},                // 10: reserved
    {bit(5)},           // 11 (profidrive)
    {bit(4)},           // 12 (profidrive)
    {bit(2)},           // 13 (profidrive)
    {bit(1)},           // 14 (profidrive)
    {bit(15)},          // 15 (profidrive)
}};

// The fc dialect's tables, built once from the FC code tables (protocols/fc/fc_codes.hpp) so that
// the FC codes are written down in one place. There are no array commands: array elements are read
// and written with the ordinary ones and the index in IND [S001], so every command but AK 0 has
// its index checked in the answer (is_array).
struct FcTables {
    std::array<RequestCode, 16> requests{};
    std::array<ResponseCode, 16> responses{};
};

const FcTables& fc_tables() noexcept {
    static const FcTables tables = [] {
        FcTables t;
        for (std::uint8_t ak = 0; ak < 16; ++ak) {
            const FcCommand& command = fc_command(ak);
            t.requests[ak] = RequestCode{command.meaning, command.width, command.defined,
                                         command.is_change, command.defined && ak != 0};
            const FcResponse& response = fc_response(ak);
            t.responses[ak] = ResponseCode{response.meaning, response.width, response.kind, false};
        }
        return t;
    }();
    return tables;
}

}  // namespace

const RequestCode& request_code(Dialect dialect, std::uint8_t rc) noexcept {
    switch (dialect) {
        case Dialect::Ge: return kGeRequests[rc & 0x0F];
        case Dialect::Profidrive: return kProfidriveRequests[rc & 0x0F];
        case Dialect::Fc: return fc_tables().requests[rc & 0x0F];
        case Dialect::Vlt2000: return vlt2000_request_code(rc);
        case Dialect::Vlt: break;
    }
    return kVltRequests[rc & 0x0F];
}

const ResponseCode& response_code(Dialect dialect, std::uint8_t rc) noexcept {
    switch (dialect) {
        case Dialect::Ge: return kGeResponses[rc & 0x0F];
        case Dialect::Profidrive: return kProfidriveResponses[rc & 0x0F];
        case Dialect::Fc: return fc_tables().responses[rc & 0x0F];
        case Dialect::Vlt2000: return vlt2000_response_code(rc);
        case Dialect::Vlt: break;
    }
    return kVltResponses[rc & 0x0F];
}

namespace {

struct IdentEntry {
    std::uint16_t ident;
    Dialect dialect;
    std::string_view drive;
};

// The ident numbers the sources name (docs/protocol/ppo.md, "Ident numbers").
constexpr IdentEntry kIdents[] = {
    {0x0402, Dialect::Vlt, "Danfoss VLT 5000/6000"},  // [P:VLT5000-GSD]
};

}  // namespace

std::optional<Dialect> dialect_of_ident(std::uint16_t ident) noexcept {
    for (const IdentEntry& entry : kIdents)
        if (entry.ident == ident) return entry.dialect;
    return std::nullopt;
}

std::string_view drive_of_ident(std::uint16_t ident) noexcept {
    for (const IdentEntry& entry : kIdents)
        if (entry.ident == ident) return entry.drive;
    return {};
}

std::string_view error_text(Dialect dialect, std::uint16_t number) noexcept {
    switch (dialect) {
        case Dialect::Ge: return find_error(kGeErrors, number);
        case Dialect::Profidrive: return find_error(kProfidriveErrors, number);
        case Dialect::Fc: return fc_fault_text(number);
        case Dialect::Vlt2000: return vlt2000_reason_text(number);
        case Dialect::Vlt: break;
    }
    return find_error(kVltErrors, number);
}

std::string_view error_text_or_unknown(Dialect dialect, std::uint16_t number) noexcept {
    std::string_view text = error_text(dialect, number);
    if (!text.empty()) return text;
    if (dialect == Dialect::Vlt2000) return kUnknownReasonCode;
    return dialect == Dialect::Fc ? kUnknownFaultCode : kUnknownErrorNumber;
}

AnswerVerdict judge_answer(Dialect dialect, std::uint8_t request_rc, std::uint8_t response_rc,
                           bool strict) noexcept {
    if (dialect == Dialect::Fc) return fc_judge_answer(request_rc, response_rc);
    if (dialect == Dialect::Vlt2000) return vlt2000_judge_answer(request_rc, response_rc);
    const RequestCode& request = request_code(dialect, request_rc);
    const ResponseCode& response = response_code(dialect, response_rc);
    if (!request.defined || response.kind == ResponseKind::Undefined) return AnswerVerdict::Invalid;
    if (kPairings[request_rc & 0x0F].positive & bit(response_rc & 0x0F))
        return AnswerVerdict::Positive;
    if (request_rc == 0) return AnswerVerdict::Invalid;
    if (response.kind == ResponseKind::Rejected) return AnswerVerdict::Negative;
    if (response.kind == ResponseKind::NoAuthority) {
        if (request.is_change) return AnswerVerdict::Negative;
        return strict ? AnswerVerdict::Invalid : AnswerVerdict::Unusual;
    }
    return AnswerVerdict::Invalid;
}

}  // namespace dpscope
