// Hex text: logs pasted from a terminal, and bytes typed on the command line.
//
// A log line carries its bytes as the longest run of two-digit hex tokens ("68", "0x68", "68,"),
// or, when it has none, as one compact hex string ("6807076805..."). Whatever else is on the line
// (a timestamp, "TX"/"RX", a prompt) is tolerated. Inside the run, a token that is meant as a
// byte but is none ("0G", "680", "7") is an error named by its column, and so is such a token
// right after the run (or a "0G"-like one right before it); the bytes on either side of it are
// kept but do not belong to one telegram (`breaks`). A compact string of 6 or more characters
// with an odd digit count or one non-hex character is an error too.
//
// Dumps: `xxd` lines ("00000010: 8382 7d3c ...  ..}<") and `hexdump -C` lines ("00000010  83 82
// ...  |..}<|") are read by their layout: the offset column and the ASCII column are not data; a
// line of only 7 or 8 hex digits is the closing offset line of hexdump; a "*" line stands for
// lines equal to the one before it, up to the next line's offset (`dump_offset`). A leading
// timestamp gives the line's time: epoch seconds ("1700000000.000125"), a time of day
// ("12:00:01.5"), or an ISO date and time ("2024-01-02T12:00:01.5Z" or "2024-01-02 12:00:01.5"),
// optionally in brackets; all UTC.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"
#include "core/telegram.hpp"

namespace dpscope {

// The first line of a hex capture that dpscope writes (-F hex): "# dpscope hex capture:
// bus=NAME, one record a line". A hex log that starts with it (after a byte order mark) is read
// one record a line, the line's bytes as they are, damaged or not, so that a capture written
// with -F hex reads back with the same records and frame numbers; any other hex log is a byte
// stream that the framer cuts into telegrams (docs/decisions.md, "Hex captures: one record a
// line").
inline constexpr std::string_view kHexCaptureHeader = "# dpscope hex capture:";
// The header line of a capture of `bus`, with its line end.
std::string hex_capture_header(Protocol bus);
// Is `line` such a header? (Its bus may be one this build does not know.)
bool is_hex_capture_header(std::string_view line);
// The bus a header line names, if any.
std::optional<Protocol> hex_capture_bus(std::string_view line);

// A token that should be a hex byte but is none.
struct HexLogError {
    std::size_t column = 0;  // 1-based, in the line as given
    std::string token;
    std::string what;  // "is not a hex byte", ...
};

struct HexLogLine {
    std::size_t byte_count = 0;  // bytes appended by this line
    std::optional<std::int64_t> time_ns;
    // Where bad tokens interrupt the line's bytes: counts of the line's bytes before each.
    std::vector<std::size_t> breaks;
    std::optional<HexLogError> error;  // the first bad token
    std::size_t bad_tokens = 0;
    std::optional<std::uint64_t> dump_offset;  // xxd or hexdump -C: the line's offset column
    bool repeat_marker = false;                // a "*" line of hexdump -C or xxd -a
};

// A line longer than kHexLogPieceChars is read a piece at a time (memory stays bounded whatever
// the length of a line): pieces of whole tokens, cut after a separator, each read like a line of
// its own (the longest run of byte tokens, or a compact string); only the first piece may give
// the line's time, and a long line is no dump line. A token longer than a piece is a compact hex
// string read in parts (LongHexToken).
inline constexpr std::size_t kHexLogPieceChars = 64 * 1024;

enum class LinePiece {
    Whole,  // a whole line
    First,  // the first piece of a long line
    Later,  // a later piece of a long line
};

// Appends the line's (or piece's) bytes to `bytes`; columns count from the piece's start.
HexLogLine parse_hex_log_line(std::string_view line, std::vector<std::uint8_t>& bytes,
                              LinePiece piece = LinePiece::Whole);

// A compact hex string longer than a piece, read in parts: pairs of hex digits are bytes; a
// character that is no hex digit is an error (one per run of them), and the bytes before and
// after it are framed apart; a digit left over at the end is an error. A part without any hex
// digit is text and holds nothing (a run of zero bytes read as a hex log).
class LongHexToken {
  public:
    // `first`: the token's first part ("0x" is stripped); `last`: the token ends after it.
    HexLogLine part(std::string_view text, bool first, bool last, std::vector<std::uint8_t>& bytes);

  private:
    char nibble_ = 0;  // a hex digit waiting for its pair (0: none)
};

// A token as a message shows it: at most 24 characters (then "..."), with every byte that is not
// printable ASCII, a quote or a backslash written as \xNN.
std::string shown_token(std::string_view token);

// Strict: every token (separated by white space or commas) must be hex: "68", "0x68", "680707",
// "68:07:07". On failure the error names the offending token.
Result<std::vector<std::uint8_t>> parse_hex_bytes(std::string_view text);

// The timestamp that starts `text` (its first one or two tokens), if any.
std::optional<std::int64_t> parse_leading_timestamp(std::string_view text);

// A timestamp token as described above, in nanoseconds since the epoch (time of day: since
// midnight of 1970-01-01).
std::optional<std::int64_t> parse_timestamp(std::string_view date_or_time,
                                            std::string_view next_token = {});

}  // namespace dpscope
