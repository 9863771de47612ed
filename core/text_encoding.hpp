// Text that came from outside the program (file names, lines of a settings file) made safe to
// put into an output: valid UTF-8, with no control characters. Every output format is UTF-8
// (JSON must be, XML declares it), and a file name on Linux is any bytes but '/' and NUL.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace dpscope {

// U+FFFD REPLACEMENT CHARACTER in UTF-8: what a byte that is no valid UTF-8 becomes.
inline constexpr std::string_view kReplacementCharacter = "\xEF\xBF\xBD";

// The length (2 to 4) of the valid multi-byte UTF-8 sequence at text[at], whose first byte is
// 0x80 or above; 0 when the bytes there are no valid UTF-8 (a stray continuation byte, an overlong
// form, a surrogate, a code point beyond U+10FFFF, or a sequence cut short by the end).
std::size_t utf8_sequence_length(std::string_view text, std::size_t at) noexcept;

// Whether `text` is valid UTF-8 throughout.
bool is_valid_utf8(std::string_view text) noexcept;

// `text` for display: each byte that starts no valid UTF-8 sequence, and each C0 control
// character (tab included) and DEL, becomes U+FFFD. Text that is valid and has no control
// characters comes back unchanged.
std::string display_text(std::string_view text);

// `text` for a message that quotes it: display_text() of at most `max_bytes` of it (cut at a
// character boundary), followed by "..." when it was cut.
std::string quoted_excerpt(std::string_view text, std::size_t max_bytes = 80);

// ASCII letters without regard to case (keywords of GSD files, names in parameter databases,
// file name extensions); other bytes compare as they are, whatever the locale.
constexpr char ascii_lower(char c) noexcept {
    return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c;
}
bool equal_ignoring_case(std::string_view a, std::string_view b) noexcept;
bool contains_ignoring_case(std::string_view text, std::string_view part) noexcept;

}  // namespace dpscope
