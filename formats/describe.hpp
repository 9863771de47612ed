// Wording shared by the renderers: how a time, a frame control byte, a PPO layout, the PCV and
// the PCD words, and each service's content are written for a person.
#pragma once

#include <fmt/format.h>

#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "core/counted.hpp"
#include "core/finding.hpp"
#include "drives/parameter_naming.hpp"
#include "formats/text_buffer.hpp"
#include "protocols/profibus/bus_decoder.hpp"
#include "protocols/profibus/dp_payload.hpp"

namespace dpscope {

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
// What a slave's GSD file adds (issue 29): " (Vendor Model)" after an ident; " [GSD "A" + "B"]"
// after a configuration; "Name=text" for a user parameter ("(not allowed)" after one outside
// its values); "\"text\"" or "slot 2 \"module\"" for a diagnosis text.
void append_gsd_device(TextBuffer& out, const DecodedTelegram& t);
void append_gsd_modules(TextBuffer& out, std::span<const GsdModuleMatch> matches);
void append_gsd_value(TextBuffer& out, const GsdPrmValue& v);
void append_gsd_diag_text(TextBuffer& out, const GsdDiagText& d);
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
// With `t` (the telegram that carries it), each parameter's name and a value in its unit from
// the telegram's naming (issue 29): "PNU 1613[0] (16-13 Frequency) = 500 (50.0 Hz, Integer16)".
void append_profidrive_summary(TextBuffer& out, const ProfidriveMessage& m, Dialect dialect,
                               const DecodedTelegram* t = nullptr);
// Parameter `k` of a PROFIdrive message in its drive's database (issue 29), and the value its
// block carries in the parameter's unit: only for the value attribute and a block of one whole
// number (a description, a text, an array, a real value or an error is not scaled).
NamedParameter profidrive_parameter(const DecodedTelegram& t, const ProfidriveMessage& m,
                                    std::size_t k) noexcept;
std::optional<ScaledValue> profidrive_value_in_unit(const DecodedTelegram& t,
                                                    const ProfidriveMessage& m,
                                                    std::size_t k) noexcept;
// One value block: "3, 4 (Word)", "error 0x03 invalid subindex (subindex 5)", "done (Zero)".
void append_profidrive_block(TextBuffer& out, const ProfidriveValueBlock& block, Dialect dialect);
// The detail column of the text format for any service.
void append_service_detail(TextBuffer& out, const DecodedTelegram& t);
// "CTW"/"MRV" for requests, "STW"/"MAV" for responses, "" for further words.
std::string_view pcd_word_name(Direction direction, std::size_t index);
// Configuration identifiers of a Chk_Cfg / Get_Cfg data unit and the layout their modules make,
// e.g. "F3 F1 = PPO1".
void append_cfg_summary(TextBuffer& out, Bytes identifiers, std::span<const CfgModule> modules);

// The text format's line after the frame and time columns: source → destination, frame type,
// service, req|rsp, the detail, then [problem kinds] and [severity finding-kind] for each finding.
// `dpscope decode` prints it; Wireshark's Info column shows it (wireshark/).
void append_telegram_columns(TextBuffer& out, const DecodedTelegram& t,
                             std::span<const Finding> findings);

}  // namespace dpscope
