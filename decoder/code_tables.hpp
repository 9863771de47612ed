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
//   vlt        Danfoss VLT 5000/6000/8000 (MG.90.D1.02) and GE AF-600/AF-650 (the same RC tables;
//              the GE manual marks RC 9..12 unused). RC 0..9 requests, 0..12 responses, error
//              numbers 0..19 and 130/131.
//   profidrive PROFIdrive V2 PKW: AK 0..15 with the store-to-EEPROM variants 11..14 and text
//              access 15; error numbers 0..24 and the known manufacturer-specific numbers.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "decoder/byte_reader.hpp"

namespace dpscope {

enum class Dialect : std::uint8_t { Vlt, Profidrive };

std::string_view dialect_name(Dialect dialect);  // "vlt", "profidrive"
std::optional<Dialect> dialect_from_name(std::string_view name);

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
    Spontaneous,  // RC 9..12 in the vlt dialect, parameter change reports in profidrive
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

// The text of an RC 7 error number, or "" when the dialect does not define it.
std::string_view error_text(Dialect dialect, std::uint16_t number) noexcept;

// How a response code answers a request code.
enum class AnswerVerdict : std::uint8_t {
    Positive,  // a listed positive answer
    Negative,  // RC 7 (or RC 8 after a change request)
    Unusual,   // RC 8 after a read: not listed, tolerated unless strict
    Invalid,   // not a valid answer to this request
};

// Pairing table (MICROMASTER 440 / ABB FPBA-01 / PROFIdrive), applied to both dialects:
// 1 -> 1|2, 2 -> 1, 3 -> 2, 4 -> 3, 5 -> 3, 6 -> 4|5, 7 -> 4, 8 -> 5, 9 -> 6; profidrive adds
// 11 -> 5, 12 -> 4, 13 -> 2, 14 -> 1, 15 -> 15. RC 7 answers any request 1..15 (RC 0 is no
// request: only RC 0 answers it); RC 8 answers change requests, and after a read it is Unusual
// (Invalid when strict).
AnswerVerdict judge_answer(Dialect dialect, std::uint8_t request_rc, std::uint8_t response_rc,
                           bool strict) noexcept;

}  // namespace dpscope
