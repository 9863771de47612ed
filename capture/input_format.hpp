// Input kinds and their detection from a file's first bytes.
#pragma once

#include <optional>
#include <string_view>

#include "core/byte_reader.hpp"

namespace dpscope {

// Serial: a live serial port (dpscope sniff); never detected from a file's content.
// Text: a text log of ASCII telegrams (the VLT 2000's "<...>", capture/text_log.hpp).
enum class InputFormat { Auto, Pcap, Pcapng, Raw, Hex, Serial, Text };

// "auto", "pcap", "pcapng", "raw", "hex", "serial", "text".
std::string_view input_format_name(InputFormat format);
std::optional<InputFormat> input_format_from_name(std::string_view name);

// The byte order mark some editors write at the start of a UTF-8 text file.
inline constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF";

// `text` without a UTF-8 byte order mark at its start.
Bytes without_bom(Bytes text);

// pcap (any byte order, microsecond or nanosecond magic), pcapng (section header block), a text
// log of VLT 2000 telegrams (text holding a telegram's shape on one line: '<', two digits, 18
// printable characters, '>'), hex text (text with at least one hex digit pair), raw bytes
// otherwise. Text: printable ASCII, tabs and line ends, and beyond ASCII UTF-8 (a byte order mark
// at the start is skipped) with at most one byte in 32 that is no UTF-8 (a Latin-1 'µ' in a
// header, a character cut off by the end of `head`); no other control byte (raw telegrams are
// full of them).
InputFormat detect_input_format(Bytes head);

// Does `head` look like text to a person: at most one byte in 10 a control byte or no UTF-8?
// Looser than detection (a log with colour escapes looks like text), so that an input read as a
// raw stream can be named as the text it probably is (text_input_hint).
bool looks_like_text(Bytes head);

// What an input that looks like text but was read as a raw stream is told: "it looks like text:
// --input-format hex reads a log of hex bytes, --input-format text a log of VLT 2000 telegrams
// ('<' ... '>')".
std::string_view text_input_hint();

// Does `text` hold a VLT 2000 telegram's shape: '<', two digits (the address), 18 printable ASCII
// characters, '>'? (The digits keep markup such as "<!DOCTYPE html PUBLIC>" out.)
bool has_vlt2000_telegram_shape(Bytes text);

}  // namespace dpscope
