// The VLT 2000 serial telegram payload of a decoded telegram (docs/protocol/vlt2000.md): 22 ASCII
// characters
//   <  AA  L  wwww  pppp  s  vvvvv  d  cc  >
//   0  1-2 3  4-7   8-11  12 13-17  18 19-20 21   (byte offsets; messages and labels count from
//                                                 1 as the manuals: offset + 1)
// start '<', address (two digits, 00 = broadcast), control letter (U, R, C, I), the control word
// (to the drive) or status word (from it) at 4 bits per character, parameter number, sign, value
// (five digits), digits after the decimal point (9: the command failed), checksum (two digits, or
// "??": not checked), stop '>'. The VLT 3000 and 3500 use the same telegram. Filled by
// Vlt2000Decoder (protocols/vlt2000/vlt2000_decoder.hpp).
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "core/byte_reader.hpp"
#include "core/problem.hpp"

namespace dpscope {

inline constexpr std::size_t kVlt2000TelegramSize = 22;
inline constexpr std::uint8_t kVlt2000Start = '<';
inline constexpr std::uint8_t kVlt2000Stop = '>';
// The number the manual gives the '<' [S004]: messages and labels name a byte by offset + 1
// ("byte 19" is the decimal position at offset 18).
inline constexpr std::uint8_t kVlt2000FirstByteNumber = 1;
// Byte offsets (0-based) of the fields.
inline constexpr std::size_t kVlt2000AddressAt = 1;
inline constexpr std::size_t kVlt2000LetterAt = 3;
inline constexpr std::size_t kVlt2000WordAt = 4;
inline constexpr std::size_t kVlt2000ParameterAt = 8;
inline constexpr std::size_t kVlt2000SignAt = 12;
inline constexpr std::size_t kVlt2000ValueAt = 13;
inline constexpr std::size_t kVlt2000ReasonAt = 16;  // bytes 17-18 of a failed command's reply
inline constexpr std::size_t kVlt2000DecimalsAt = 18;
inline constexpr std::size_t kVlt2000ChecksumAt = 19;
inline constexpr std::size_t kVlt2000StopAt = 21;
// Byte 19 (offset 18) of a reply to a command that could not be carried out.
inline constexpr std::uint8_t kVlt2000FailedDecimals = 9;

// The control letter (byte 4) [S004].
enum class Vlt2000Letter : std::uint8_t {
    Update,     // U: write the value into the parameter
    Read,       // R: read the parameter's value
    Control,    // C: only the control word; the drive replies with its status
    ReadIndex,  // I: read an indexed parameter, the index in bytes 13-18
    Unknown,    // any other character
};

// The fields a telegram decodes to; Vlt2000Telegram adds its problems (two parts for reset(), as
// FcTelegram).
struct Vlt2000TelegramFields {
    bool complete = false;  // all 22 characters are there
    std::uint8_t address = 0;
    bool broadcast = false;  // address 00: every unit acts, none replies
    std::uint8_t letter_char = 0;
    Vlt2000Letter letter = Vlt2000Letter::Unknown;
    // The control or status word: the low 4 bits of bytes 5-8 (byte 5 bits 3..0 ... byte 8 bits
    // 15..12). `word_keep` marks the groups sent as 'P' (VLT 3000: keep that group as it is).
    bool has_word = false;
    std::uint16_t word = 0;
    std::uint8_t word_keep = 0;  // bit g set: group g (bits 4g..4g+3) was 'P'
    bool has_parameter = false;
    std::uint16_t parameter = 0;  // 0..9999
    bool negative = false;        // byte 13 is '-' (anything else is '+')
    bool has_value = false;       // bytes 14-18 are five digits
    std::uint32_t digits = 0;     // 0..99999, the value without its sign and decimal point
    bool has_decimals = false;    // byte 19 is a digit
    std::uint8_t decimals = 0;    // 0..5 (or 6..8, out of range), 9: failed
    bool failed = false;          // decimals 9: unknown parameter or command failed
    bool has_reason = false;      // failed, and bytes 17-18 are two digits
    std::uint8_t reason = 0;      // the VLT 3000's reason code, 0..99
    Bytes index;                  // letter I: bytes 13-18 as sent (a view into the telegram)
    bool has_index_number = false;
    std::uint32_t index_number = 0;  // the index when bytes 13-18 are digits (a '+' first allowed)
    bool checksum_disabled = false;  // bytes 20-21 are "??"
    bool has_checksum = false;       // bytes 20-21 are two digits
    std::uint8_t checksum = 0;       // as sent, 0..99
    std::uint8_t checksum_computed = 0;
    bool checksum_ok = false;  // as sent and as computed agree (false when disabled)
};

struct Vlt2000Telegram : Vlt2000TelegramFields {
    // Messages number the bytes 1-22 as the manual does [S004]; offsets stay 0-based.
    ProblemList problems{kVlt2000FirstByteNumber};

    // The value as a signed whole number (digits with the sign).
    std::int64_t signed_digits() const noexcept {
        return negative ? -static_cast<std::int64_t>(digits) : static_cast<std::int64_t>(digits);
    }
    // The value with the decimal point applied (decimals 0..5); digits itself otherwise.
    double value() const noexcept;

    void reset() noexcept {
        // Copied from a constant: a temporary built on the stack first cost a stalled load.
        static constexpr Vlt2000TelegramFields kFresh{};
        static_cast<Vlt2000TelegramFields&>(*this) = kFresh;
        problems.clear();
    }
};

// Every problem found in a VLT 2000 telegram (DecodedTelegram::problems()).
inline const ProblemList& payload_problems(const Vlt2000Telegram& v) noexcept {
    return v.problems;
}

std::string_view vlt2000_letter_name(Vlt2000Letter letter) noexcept;

// The parameter a VLT 2000 telegram names (a C telegram's is ignored); none without one (--pnu,
// the filter's dpscope.pnu).
inline std::optional<std::uint16_t> vlt2000_named_pnu(const Vlt2000Telegram& t) noexcept {
    if (!t.has_parameter || t.letter == Vlt2000Letter::Control) return std::nullopt;
    return t.parameter;
}  // "update", ..., "unknown"

// The checksum of a telegram [P:VLT3500 p86]: the sum of the character codes of bytes 2..19
// (offsets 1..18), its last two decimal digits. `telegram` holds at least 19 bytes.
constexpr std::uint8_t vlt2000_checksum_of(Bytes telegram) noexcept {
    unsigned sum = 0;
    for (std::size_t i = kVlt2000AddressAt; i < kVlt2000ChecksumAt; ++i)
        sum += telegram[i];
    return static_cast<std::uint8_t>(sum % 100);
}

}  // namespace dpscope
