// Wording shared by the renderers: how a time, a frame control byte, a PPO layout, the PCV and
// the PCD words, and each service's content are written for a person.
#pragma once

#include <fmt/format.h>

#include <span>
#include <string>
#include <string_view>

#include "decoder/bus_decoder.hpp"
#include "decoder/counted.hpp"
#include "decoder/dp_payload.hpp"
#include "decoder/finding.hpp"

namespace dpscope {

using TextBuffer = fmt::memory_buffer;

inline void append(TextBuffer& out, std::string_view text) {
    out.append(text.data(), text.data() + text.size());
}

// 2024-01-01T00:00:00.000123000Z
void append_iso_time(TextBuffer& out, std::int64_t time_ns);
// Seconds with nanoseconds, e.g. 1704067200.000123000; "-" style handled by callers.
void append_epoch_seconds(TextBuffer& out, std::int64_t time_ns);
// Seconds with six decimals, cut (not rounded) to the microsecond, as tshark shows relative
// times: "0.027865", "-2.500000".
std::string relative_seconds_text(std::int64_t relative_ns);
// Names of the set bits, separated by spaces; `none` when no bit is set. True if any was named.
bool append_flags(TextBuffer& out, std::uint8_t value, std::span<const FlagBit> flags,
                  std::string_view none = "none", std::uint8_t ignore_mask = 0);
void append_hex(TextBuffer& out, Bytes bytes, std::string_view separator = " ");
// "request, FCB 1, FCV 1, SRD high" or "response, slave, DL (response data low)".
void append_frame_control(TextBuffer& out, FrameControl fc);
// "PPO1", "PPO1/4?" (from length, ambiguous), "PPO2?" (from length), "PCV+8w", "10w".
void append_ppo_short(TextBuffer& out, const PpoLayout& layout);
// "PPO 1 (PCV + 2 PCD words, 12 bytes each way) from Chk_Cfg"; "1 byte", "1 PCD word".
void append_ppo_long(TextBuffer& out, const PpoLayout& layout);
// A configuration module's length: "1 byte", "4 words".
std::string cfg_units(std::uint64_t units, bool words);
// A drive's commands by outcome (FC, VLT 2000): "119 answered, 0 unanswered, 1 abandoned, 1
// damaged", and ", 2 not judged" when there are such; with the broadcasts they add up to the
// commands (FcStationStats::commands_outcomes()).
std::string command_outcomes_text(std::uint64_t answered, std::uint64_t unanswered,
                                  std::uint64_t abandoned, std::uint64_t damaged,
                                  std::uint64_t not_judged);
// "RC=1 Request parameter value PNU=520 IND=0 PVA=0" (+ "SPM=1", error text).
void append_pcv_summary(TextBuffer& out, const DecodedTelegram& t);
// "CTW=0x047F MRV=50.00%".
void append_pcd_summary(TextBuffer& out, const DecodedTelegram& t);
// A DP-V1 telegram: "Write slot 0 idx 47 len 10 | PROFIdrive req ...", "Read negative DP-V1
// access: state conflict (0xB5)", "Abort subnet 0 MSAC_C2: ...", "no PDU (link-level poll)".
void append_dpv1_summary(TextBuffer& out, const DecodedTelegram& t);
// "PROFIdrive req ref 5 request parameter value axis 0, 1 param: PNU 12[4] value"; a response
// "... : PNU 12[4] = 3 (Word)" or "PNU 918: error 0x00 illegal or unknown parameter number".
void append_profidrive_summary(TextBuffer& out, const ProfidriveMessage& m, Dialect dialect);
// One value block: "3, 4 (Word)", "error 0x03 invalid subindex (subindex 5)", "done (Zero)".
void append_profidrive_block(TextBuffer& out, const ProfidriveValueBlock& block, Dialect dialect);
// The detail column of the text format for any service.
void append_service_detail(TextBuffer& out, const DecodedTelegram& t);
// "CTW"/"MRV" for requests, "STW"/"MAV" for responses, "" for further words.
std::string_view pcd_word_name(Direction direction, std::size_t index);
// Configuration identifiers of a Chk_Cfg / Get_Cfg data unit and the layout their modules make,
// e.g. "F3 F1 = PPO1".
void append_cfg_summary(TextBuffer& out, Bytes identifiers, std::span<const CfgModule> modules);

// ---- Danfoss FC protocol (docs/protocol/fc-protocol.md): wording from DecodedTelegram::fc ----

// FC-series parameter x-yy of a PNU: 414 -> "4-14", 1 -> "0-01".
std::string fc_parameter_name(std::uint16_t pnu);
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

// ---- VLT 2000 serial telegram (docs/protocol/vlt2000.md): wording from DecodedTelegram::vlt2000
// --

// Whether the record reaches the control letter (byte 4).
bool vlt2000_has_letter(const DecodedTelegram& t);
// The letter with its name: "U update", "I read index", "X unknown" ("0x07 unknown" for a
// character that is not printable; "none" when the record ends before it).
std::string vlt2000_letter_text(const DecodedTelegram& t);
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

// The text format's line after the frame and time columns: source → destination, frame type,
// service, req|rsp, the detail, then [problem kinds] and [severity finding-kind] for each finding.
// `dpscope decode` prints it; Wireshark's Info column shows it (wireshark/).
void append_telegram_columns(TextBuffer& out, const DecodedTelegram& t,
                             std::span<const Finding> findings);

}  // namespace dpscope
