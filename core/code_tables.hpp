// The parameter channel (PCV/PKW) of PPO types 1, 2 and 5, and its code tables per dialect.
//
//   bytes 1-2  PCA/PKE: RC/AK (bits 15..12), SPM (bit 11), PNU (bits 10..0)
//   byte 3     IND: array subindex (or description record subindex)
//   byte 4     IND low byte (unused on Danfoss PROFIBUS)
// That is the PKE layout of the PROFIBUS PPO (kPpoPkeLayout); other carriers of a parameter
// channel split the PKE and IND otherwise (the Danfoss FC protocol: a 12-bit PNU, no SPM bit, the
// index in IND's second byte; docs/protocol/fc-protocol.md), so read_pcv takes the layout.
//   bytes 5-8  PVA/PWE: word values in bytes 7-8, double words in bytes 5-8; for RC 7 the
//              error number in bytes 7-8
//
// Dialects:
//   vlt        Danfoss VLT 5000/6000/8000 (seed 000, MG.90.D1.02): RC 0..9 requests, 0..12
//              responses (9..12 spontaneous messages), error numbers 0..19 in seed 000's words.
//   ge         GE AF-600 FP / AF-650 GP (seed 002): the same requests and responses 0..8, but
//              RC 9..12 are "not used" (undefined, no spontaneous messages); fault numbers 0..19,
//              130 and 131 in seed 002's words.
//   profidrive PROFIdrive V2 PKW: AK 0..15 with the store-to-EEPROM variants 11..14 and text
//              access 15; error numbers 0..24 and the known manufacturer-specific numbers.
//   fc         the Danfoss FC protocol's parameter channel on RS-485 (seed 001): the AK commands,
//              responses and fault codes of protocols/fc/fc_codes.hpp, seen through these tables so
//              that the parameter-channel engine reads FC like any other carrier. Not a dialect of
//              a PROFIBUS slave: it is not in kDialects, so --dialect does not take it.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "core/byte_reader.hpp"

namespace dpscope {

enum class Dialect : std::uint8_t { Vlt, Profidrive, Ge, Fc, Vlt2000 };

// The dialects of a PROFIBUS slave's PCV (--dialect, the dialect hint). Dialect::Fc is the FC
// carrier's own and is left out.
inline constexpr Dialect kDialects[] = {Dialect::Vlt, Dialect::Ge, Dialect::Profidrive};
// The names as a list for help texts and error messages: "vlt, ge, profidrive".
inline constexpr std::string_view kDialectNameList = "vlt, ge, profidrive";

std::string_view dialect_name(Dialect dialect);  // "vlt", "ge", "profidrive", "fc"
// One of kDialects by name ("fc" is none of them).
std::optional<Dialect> dialect_from_name(std::string_view name);

// The dialect of a PROFIBUS ident number (Set_Prm, Slave_Diag) the sources name, and the drive
// it names: 0x0402, the Danfoss VLT 5000/6000 (vlt) [P:VLT5000-GSD]. The GE AF-600/AF-650's is
// in no source dpscope has (docs/protocol/ppo.md, "Ident numbers"). Others: nullopt.
std::optional<Dialect> dialect_of_ident(std::uint16_t ident) noexcept;
// "Danfoss VLT 5000/6000" for an ident dialect_of_ident() knows, else "".
std::string_view drive_of_ident(std::uint16_t ident) noexcept;

// A Danfoss-built drive: vlt, and ge (GE's AF-600/AF-650 use Danfoss's PCA tables [S002] and the
// Danfoss FC control word, docs/protocol/process-data.md). Everything but the PCV code tables
// (PCD profile, Danfoss bits 11..15, DP-V1 limits and error numbers) treats ge like vlt.
constexpr bool danfoss_family(Dialect dialect) noexcept { return dialect != Dialect::Profidrive; }
// Whether the dialect's RC 9..12 are spontaneous messages (ge: "not used"; fc: no such codes).
constexpr bool has_spontaneous_messages(Dialect dialect) noexcept {
    return dialect != Dialect::Ge && dialect != Dialect::Fc && dialect != Dialect::Vlt2000;
}
// What the dialect's sources call the code and the number of a rejection: "RC" and "error" for
// the PROFIBUS dialects, "AK" and "fault code" for fc.
// vlt2000: "code" (the engine's number for a control letter, protocols/vlt2000/vlt2000_codes.hpp)
// and "reason code".
constexpr std::string_view code_label(Dialect dialect) noexcept {
    return dialect == Dialect::Fc ? "AK" : dialect == Dialect::Vlt2000 ? "code" : "RC";
}
constexpr std::string_view error_label(Dialect dialect) noexcept {
    return dialect == Dialect::Fc        ? "fault code"
           : dialect == Dialect::Vlt2000 ? "reason code"
                                         : "error";
}

// Which of the two IND bytes holds the subindex: the first on the wire or the second.
enum class IndexByte : std::uint8_t { High, Low };

// How the PKE word and the IND bytes of a parameter channel are split. The code is always in
// bits 15..12; the PNU takes the `pnu_bits` below it.
struct PkeLayout {
    std::uint8_t pnu_bits = 11;
    std::optional<std::uint8_t> spm_bit;  // the toggle bit for spontaneous messages, if any
    IndexByte index_byte = IndexByte::High;
};

// The PROFIBUS PPO: PNU bits 10..0, SPM bit 11, the subindex in byte 3.
inline constexpr PkeLayout kPpoPkeLayout{11, 11, IndexByte::High};

struct Pcv {
    std::uint16_t pca = 0;     // the whole first word
    std::uint8_t rc = 0;       // request/response code (RC, AK)
    bool spm = false;          // toggle bit for spontaneous messages (false without one)
    std::uint16_t pnu = 0;     // parameter number, as wide as the layout says
    std::uint8_t ind = 0;      // the subindex: the IND byte the layout names (PPO: byte 3)
    std::uint8_t ind_low = 0;  // byte 4, IND's second byte
    std::uint32_t pva = 0;     // bytes 5-8, as a 32-bit big-endian value
};

// Reads the 8 PCV bytes into `pcv` as `layout` splits them; false (and `pcv` untouched) when
// fewer than 8 remain.
bool read_pcv(ByteReader& reader, const PkeLayout& layout, Pcv& pcv) noexcept;

enum class ValueWidth : std::uint8_t { None, Word, DoubleWord };

// The value a code carries: bytes 7-8 for a word, 5-8 for a double word, all four otherwise.
std::uint32_t pcv_value(const Pcv& pcv, ValueWidth width) noexcept;

enum class ResponseKind : std::uint8_t {
    None,         // RC 0: no response
    Value,        // a parameter value, description element or element count
    Rejected,     // RC 7 with an error number
    NoAuthority,  // RC 8
    Spontaneous,  // RC 9..12 in the vlt dialect, parameter change reports in profidrive (not ge)
    Text,         // profidrive AK 15
    Undefined,    // not in the dialect's table
};

struct RequestCode {
    std::string_view meaning;
    ValueWidth width = ValueWidth::None;
    bool defined = false;
    bool is_change = false;  // writes something (RC 8 "no authority" is a normal answer)
    bool is_array = false;   // IND selects an array element (checked in the answer)
};

struct ResponseCode {
    std::string_view meaning;
    ValueWidth width = ValueWidth::None;
    ResponseKind kind = ResponseKind::Undefined;
    bool is_array = false;
};

const RequestCode& request_code(Dialect dialect, std::uint8_t rc) noexcept;
const ResponseCode& response_code(Dialect dialect, std::uint8_t rc) noexcept;

// Whether a parameter channel's request (`request` true) or response with code `rc` carries a
// parameter's value, which a parameter database may scale (drives/): a change of a value, a
// value transmitted or reported spontaneously; not a description element (request 5, response
// 3), an element count (response 6), an error number or a text. The PKW numbering every dialect
// shares (PROFIdrive's, and the FC protocol's AK).
bool carries_parameter_value(Dialect dialect, bool request, std::uint8_t rc) noexcept;

// The text of an RC 7 error number, or "" when the dialect does not define it.
std::string_view error_text(Dialect dialect, std::uint16_t number) noexcept;

// What every output shows for an error number the dialect does not define.
inline constexpr std::string_view kUnknownErrorNumber = "unknown error number";
// The same for the FC protocol's fault codes (Dialect::Fc) and the VLT 2000 reason codes.
inline constexpr std::string_view kUnknownFaultCode = "unknown fault code";
inline constexpr std::string_view kUnknownReasonCode = "unknown reason code";
// error_text, or kUnknownErrorNumber (kUnknownFaultCode for Dialect::Fc) when the dialect does not
// define the number.
std::string_view error_text_or_unknown(Dialect dialect, std::uint16_t number) noexcept;

// How a response code answers a request code.
enum class AnswerVerdict : std::uint8_t {
    Positive,  // a listed positive answer
    Negative,  // RC 7 (or RC 8 after a change request)
    Unusual,   // RC 8 after a read: not listed, tolerated unless strict
    Invalid,   // not a valid answer to this request
};

// Pairing table (MICROMASTER 440 / ABB FPBA-01 / PROFIdrive), applied to every dialect:
// 1 -> 1|2, 2 -> 1, 3 -> 2, 4 -> 3, 5 -> 3, 6 -> 4|5, 7 -> 4, 8 -> 5, 9 -> 6; profidrive adds
// 11 -> 5, 12 -> 4, 13 -> 2, 14 -> 1, 15 -> 15. RC 7 answers any request 1..15 (RC 0 is no
// request: only RC 0 answers it); RC 8 answers change requests, and after a read it is Unusual
// (Invalid when strict).
AnswerVerdict judge_answer(Dialect dialect, std::uint8_t request_rc, std::uint8_t response_rc,
                           bool strict) noexcept;

}  // namespace dpscope
