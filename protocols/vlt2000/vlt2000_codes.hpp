// The code tables of the VLT 2000 serial telegram (docs/protocol/vlt2000.md): the control letters,
// the bits of the control and status words, the reason codes of a failed command, and how the
// parameter-channel engine sees the letters (Dialect::Vlt2000 in core/code_tables.hpp).
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "core/code_tables.hpp"
#include "protocols/vlt2000/vlt2000_telegram.hpp"

namespace dpscope {

// The letter of a control character ('U', 'R', 'C', 'I'; anything else Unknown).
Vlt2000Letter vlt2000_letter_of(std::uint8_t c) noexcept;
// The character of a letter ('?' for Unknown).
char vlt2000_letter_char(Vlt2000Letter letter) noexcept;

// The code the parameter-channel engine knows a letter by (Dialect::Vlt2000): R 1, U 2, C 3, I 4;
// a reply with decimal position 9 (the command failed) is 7, the engine's rejection; Unknown 0.
inline constexpr std::uint8_t kVlt2000CodeRead = 1;
inline constexpr std::uint8_t kVlt2000CodeUpdate = 2;
inline constexpr std::uint8_t kVlt2000CodeControl = 3;
inline constexpr std::uint8_t kVlt2000CodeReadIndex = 4;
inline constexpr std::uint8_t kVlt2000CodeFailed = 7;
std::uint8_t vlt2000_code(Vlt2000Letter letter) noexcept;
// The letter of an engine code 1..4 (Unknown otherwise).
Vlt2000Letter vlt2000_letter_of_code(std::uint8_t code) noexcept;

// One bit of the control or status word: what 0 and what 1 mean, and whether its 0 is worth
// naming where only the bits that are 1 are listed (an OFF command, "ramp stop", "out of
// frequency range": the states a commissioning engineer looks for).
struct Vlt2000Bit {
    std::string_view when_0;
    std::string_view when_1;
    bool notable_0 = false;
};
// Control word (master -> drive) and status word (drive -> master), bits 0..15 (docs/protocol/
// vlt2000.md "Control and status word").
const Vlt2000Bit& vlt2000_control_bit(unsigned bit) noexcept;
const Vlt2000Bit& vlt2000_status_bit(unsigned bit) noexcept;

// The text of a failed command's reason code (VLT 3000 [P:VLT3000 p80] and VLT 3500 [P:VLT3500
// p92]: 00..08 and 99); "" for any other number.
std::string_view vlt2000_reason_text(std::uint32_t reason) noexcept;

// How a reply's code answers a command's code: the same letter is the answer, 7 (failed) answers
// every letter; anything else is no answer to it.
AnswerVerdict vlt2000_judge_answer(std::uint8_t command_code, std::uint8_t reply_code) noexcept;

// The request and response tables of Dialect::Vlt2000, by engine code.
const RequestCode& vlt2000_request_code(std::uint8_t code) noexcept;
const ResponseCode& vlt2000_response_code(std::uint8_t code) noexcept;

}  // namespace dpscope
