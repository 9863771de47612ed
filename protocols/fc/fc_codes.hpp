// The code tables of the Danfoss FC protocol's parameter channel [S001] (Danfoss CDS 803 design
// guide; docs/protocol/fc-protocol.md): the AK commands (master -> slave) and responses
// (slave -> master) in PKE bits 15..12, the fault codes of AK 7, and which response answers
// which command.
#pragma once

#include <cstdint>
#include <string_view>

#include "core/code_tables.hpp"

namespace dpscope {

struct FcCommand {
    std::string_view meaning;  // "Read parameter value"
    ValueWidth width = ValueWidth::None;
    bool defined = false;
    bool is_change = false;  // writes a value
};

struct FcResponse {
    std::string_view meaning;
    ValueWidth width = ValueWidth::None;
    ResponseKind kind = ResponseKind::Undefined;
};

// AK 0, 1, 2, 3, 13, 14, 15 [S001], and 4 (read description, early FC 300 firmware
// [P:FC300-DG-B6 p291]); the others are not defined.
const FcCommand& fc_command(std::uint8_t ak) noexcept;
// AK 0, 1, 2, 7, 15 [S001], and 3 (description element, the early FC 300 answer to AK 4).
const FcResponse& fc_response(std::uint8_t ak) noexcept;

// AK codes only a command can have (4, 13, 14) or only a response (7): the decoder tells
// requests from responses by them where order and address leave it open.
bool fc_command_only(std::uint8_t ak) noexcept;
bool fc_response_only(std::uint8_t ak) noexcept;

// The text of an AK 7 fault code [S001]: 0..7, 9, 11, 15, 17, 18, 130, 131, 132, 252..255 (6 and
// 7 "Not used" as the table says); "" for a code the table does not define.
std::string_view fc_fault_text(std::uint32_t code) noexcept;

// How a response AK answers a command AK (dpscope's reading of the two tables): 1 -> 1|2,
// 2 -> 1, 3 -> 2, 4 -> 3, 13 -> 2, 14 -> 1, 15 -> 15; AK 7 answers every command 1..15; AK 0
// answers only AK 0 (no command).
AnswerVerdict fc_judge_answer(std::uint8_t command_ak, std::uint8_t response_ak) noexcept;

}  // namespace dpscope
