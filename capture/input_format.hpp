// Input kinds and their detection from a file's first bytes.
#pragma once

#include <optional>
#include <string_view>

#include "decoder/byte_reader.hpp"

namespace dpscope {

// Serial: a live serial port (dpscope sniff); never detected from a file's content.
enum class InputFormat { Auto, Pcap, Pcapng, Raw, Hex, Serial };

// "auto", "pcap", "pcapng", "raw", "hex", "serial".
std::string_view input_format_name(InputFormat format);
std::optional<InputFormat> input_format_from_name(std::string_view name);

// pcap (any byte order, microsecond or nanosecond magic), pcapng (section header block), hex text
// (only printable ASCII and white space, with at least one hex digit pair), raw bytes otherwise.
InputFormat detect_input_format(Bytes head);

}  // namespace dpscope
