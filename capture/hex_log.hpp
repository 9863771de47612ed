// Hex text: logs pasted from a terminal, and bytes typed on the command line.
//
// A log line carries its bytes as the longest run of two-digit hex tokens ("68", "0x68", "68,"),
// or, when it has none, as one compact hex string ("6807076805..."). Whatever else is on the line
// (a timestamp, "TX"/"RX", a prompt, a hexdump offset or ASCII column) is tolerated; a line of
// only 7 or 8 hex digits is taken for hexdump's closing offset line, not for data. A leading
// timestamp gives the line's time: epoch seconds ("1700000000.000125"), a time of day
// ("12:00:01.5"), or an ISO date and time ("2024-01-02T12:00:01.5Z" or "2024-01-02 12:00:01.5"),
// optionally in brackets; all UTC.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace dpscope {

struct HexLogLine {
    std::size_t byte_count = 0;  // bytes appended by this line
    std::optional<std::int64_t> time_ns;
};

// Appends the line's bytes to `bytes`.
HexLogLine parse_hex_log_line(std::string_view line, std::vector<std::uint8_t>& bytes);

// Strict: every token (separated by white space or commas) must be hex: "68", "0x68", "680707",
// "68:07:07". On failure returns false and names the offending token in `error`.
bool parse_hex_bytes(std::string_view text, std::vector<std::uint8_t>& bytes, std::string& error);

// A timestamp token as described above, in nanoseconds since the epoch (time of day: since
// midnight of 1970-01-01).
std::optional<std::int64_t> parse_timestamp(std::string_view date_or_time,
                                            std::string_view next_token = {});

}  // namespace dpscope
