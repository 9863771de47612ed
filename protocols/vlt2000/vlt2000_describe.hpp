// How a VLT 2000 telegram is worded for a person (protocols/vlt2000/vlt2000_describe.cpp); the
// renderers and the Wireshark tree use it.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "formats/describe.hpp"

namespace dpscope {

// Whether the record reaches the control letter (byte 4).
bool vlt2000_has_letter(const DecodedTelegram& t);
// The letter with its name: "U update", "I read index", "X unknown" ("0x07 unknown" for a
// character that is not printable; "none" when the record ends before it).
std::string vlt2000_letter_text(const DecodedTelegram& t);
void append_vlt2000_letter(TextBuffer& out, const DecodedTelegram& t);
// "control" (a command: the word goes to the drive) or "status" (a reply: from the drive).
std::string_view vlt2000_word_name(Direction direction);
// "CTW" or "STW", as the FC protocol's PCD 1.
std::string_view vlt2000_word_short_name(Direction direction);
// Whether bit 0..15 of the word was sent in a group kept as it is ('P').
bool vlt2000_bit_kept(const Vlt2000Telegram& v, unsigned bit);
// What bit 0..15 of the word says in the state it has: "data valid", "out of frequency range";
// "group kept (P)" for a bit of a kept group.
std::string_view vlt2000_bit_meaning(const Vlt2000Telegram& v, Direction direction, unsigned bit);
// The word in hex with the meanings of its bits that are 1 and the groups kept:
// "CTW=0x047F (ON1, ON2, ON3, coasting possible, ramp, start, data valid)",
// "CTW=0x0400 (bits 0-3 group kept (P); data valid)", "STW=0x0000 (no bit set)".
void append_vlt2000_word(TextBuffer& out, const Vlt2000Telegram& v, Direction direction);
// The value with its decimal point applied: "23.750" (+23750, 3 decimals), "80", "-0.5"; the
// digits as a whole number when the decimal position is 6..8 or not a digit (see the note).
std::string vlt2000_value_text(const Vlt2000Telegram& v);
void append_vlt2000_value(TextBuffer& out, const Vlt2000Telegram& v);
// Why the value is shown without a decimal point ("" when it has its point):
// "decimal position 7 is out of range (0-5): the digits as sent".
std::string vlt2000_value_note(const Vlt2000Telegram& v);
// The reason text of a failed reply: vlt2000_reason_text, "unknown reason code", or "no reason
// code given".
std::string_view vlt2000_reason_or_unknown(const Vlt2000Telegram& v);
// Whether the letter carries a value in bytes 13-19 (U and R, not C nor an I with its index).
bool vlt2000_carries_value(const Vlt2000Telegram& v);
// The index bytes of an I telegram as sent, escaped as append_fc_text does.
void append_vlt2000_index(TextBuffer& out, const Vlt2000Telegram& v);
// The checksum: "07 (correct)", "08 (wrong: computed 07)", "?? (not checked; computed 07)",
// "08 (wrong: computed 07; not judged, --vlt2000-checksum ignore)", "missing (telegram cut
// short)", "\"x7\" (not two digits; computed 07)".
void append_vlt2000_checksum(TextBuffer& out, const DecodedTelegram& t);
// Whether the checksum is wrong and was judged so (a vlt2000_checksum_mismatch problem).
bool vlt2000_checksum_judged_wrong(const DecodedTelegram& t);
// The detail column of the text format for a VLT 2000 telegram: the word, the parameter, the value
// or index or failure, and the checksum when it is not right:
// "CTW=0x047F (ON1, …) parameter 516 = 80", "STW=… parameter 999 failed: reason 0 (parameter
// does not exist)", "… checksum ?? (not checked; computed 07)".
void append_vlt2000_detail(TextBuffer& out, const DecodedTelegram& t);

}  // namespace dpscope
