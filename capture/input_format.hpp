// Input kinds and their detection from a file's first bytes.
#pragma once

#include <optional>
#include <string_view>

#include "decoder/byte_reader.hpp"

namespace dpscope {

// Serial: a live serial port (dpscope sniff); never detected from a file's content.
// Text: a text log of ASCII telegrams (the VLT 2000's "<...>", capture/text_log.hpp).
enum class InputFormat { Auto, Pcap, Pcapng, Raw, Hex, Serial, Text };

// "auto", "pcap", "pcapng", "raw", "hex", "serial", "text".
std::string_view input_format_name(InputFormat format);
std::optional<InputFormat> input_format_from_name(std::string_view name);

// pcap (any byte order, microsecond or nanosecond magic), pcapng (section header block), a text
// log of VLT 2000 telegrams (only printable ASCII and white space, holding a telegram's shape on
// one line: '<', two digits, 18 printable characters, '>'), hex text (only printable ASCII and
// white space, with at least one hex digit pair), raw bytes otherwise.
InputFormat detect_input_format(Bytes head);

// Does `text` hold a VLT 2000 telegram's shape: '<', two digits (the address), 18 printable ASCII
// characters, '>'? (The digits keep markup such as "<!DOCTYPE html PUBLIC>" out.)
bool has_vlt2000_telegram_shape(Bytes text);

}  // namespace dpscope
