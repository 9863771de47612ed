// How an FC protocol telegram is worded for a person (protocols/fc/fc_describe.cpp); the renderers
// and the Wireshark tree use it.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "formats/describe.hpp"

namespace dpscope {

// FC-series parameter x-yy of a PNU: 414 -> "4-14", 1 -> "0-01".
std::string fc_parameter_name(std::uint16_t pnu);
void append_fc_parameter_name(TextBuffer& out, std::uint16_t pnu);
// The AK's meaning: fc_command for a request, fc_response for a response.
std::string_view fc_ak_meaning(const DecodedTelegram& t);
bool fc_ak_defined(const DecodedTelegram& t);
// The width of PWE the AK carries (word: PWE low, double word: all four bytes).
ValueWidth fc_ak_width(const DecodedTelegram& t);
// A response with AK 7 (command cannot be performed): PWE low holds the fault code.
bool fc_rejected(const DecodedTelegram& t);
std::uint16_t fc_fault_code(const FcTelegram& fc);
// fc_fault_text, or "unknown fault code" for a code the table does not define.
std::string_view fc_fault_text_or_unknown(std::uint32_t code);
// "read" (IND high 0x04), "write" (0x05), "" otherwise.
std::string_view fc_text_mode_name(std::uint8_t ind_high);
// The characters of a text block: printable ASCII as it is, '"' and '\\' escaped with a
// backslash, any other byte as \xNN.
void append_fc_text(TextBuffer& out, Bytes text);
// "ADR 0x81 (1-126)", "ADR 0xA0 (1-31, broadcast)".
void append_fc_address(TextBuffer& out, const FcTelegram& fc);
// The detail column of the text format for an FC telegram: address, the PKW part ("AK=1 Read
// parameter value PNU=414 (4-14) IND=0 PWE=0"), then " | CTW=0x047F MRV=50.00%".
void append_fc_detail(TextBuffer& out, const DecodedTelegram& t);

}  // namespace dpscope
