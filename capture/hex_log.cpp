#include "capture/hex_log.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <string>

namespace dpscope {

namespace {

bool is_hex(char c) {
    return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
}

bool is_digit(char c) { return c >= '0' && c <= '9'; }

std::uint8_t hex_value(char c) {
    if (c >= '0' && c <= '9') return static_cast<std::uint8_t>(c - '0');
    if (c >= 'a' && c <= 'f') return static_cast<std::uint8_t>(c - 'a' + 10);
    return static_cast<std::uint8_t>(c - 'A' + 10);
}

std::string_view strip_prefix_0x(std::string_view token) {
    if (token.size() > 2 && token[0] == '0' && (token[1] == 'x' || token[1] == 'X'))
        token.remove_prefix(2);
    return token;
}

std::string_view strip_punctuation(std::string_view token) {
    while (!token.empty() && (token.back() == ',' || token.back() == ';'))
        token.remove_suffix(1);
    return token;
}

bool all_hex(std::string_view text) {
    if (text.empty()) return false;
    for (char c : text)
        if (!is_hex(c)) return false;
    return true;
}

// "68" or "0x68": exactly one byte.
std::optional<std::uint8_t> byte_token(std::string_view token) {
    token = strip_prefix_0x(strip_punctuation(token));
    if (token.size() != 2 || !all_hex(token)) return std::nullopt;
    return static_cast<std::uint8_t>(hex_value(token[0]) << 4 | hex_value(token[1]));
}

void append_hex_run(std::string_view run, std::vector<std::uint8_t>& bytes) {
    for (std::size_t i = 0; i + 1 < run.size(); i += 2)
        bytes.push_back(static_cast<std::uint8_t>(hex_value(run[i]) << 4 | hex_value(run[i + 1])));
}

std::vector<std::string_view> split_whitespace(std::string_view line) {
    std::vector<std::string_view> tokens;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r'))
            ++i;
        std::size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r')
            ++i;
        if (i > start) tokens.push_back(line.substr(start, i - start));
    }
    return tokens;
}

// The tokens of a log line: separated by white space, commas and semicolons; a label glued to
// data ("TX:0x10", "RX:680707") is split off after its colon. A label starts with a letter, holds
// letters, digits and '_', and has a letter that is no hex digit, so times (12:00:01,
// 2024-01-02T12:00) and hex bytes stay whole.
std::vector<std::string_view> split_log_tokens(std::string_view line) {
    std::vector<std::string_view> tokens;
    auto separator = [](char c) {
        return c == ' ' || c == '\t' || c == '\r' || c == ',' || c == ';';
    };
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && separator(line[i]))
            ++i;
        std::size_t start = i;
        while (i < line.size() && !separator(line[i]))
            ++i;
        if (i == start) continue;
        std::string_view token = line.substr(start, i - start);
        std::size_t colon = token.find(':');
        if (colon != std::string_view::npos && colon + 1 < token.size()) {
            std::string_view label = token.substr(0, colon);
            auto letter = [](char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); };
            bool is_label = letter(label[0]);
            bool beyond_hex = false;
            for (char c : label) {
                if (!letter(c) && !is_digit(c) && c != '_') is_label = false;
                if (letter(c) && !is_hex(c)) beyond_hex = true;
            }
            if (is_label && beyond_hex) {
                tokens.push_back(token.substr(0, colon + 1));
                token.remove_prefix(colon + 1);
            }
        }
        tokens.push_back(token);
    }
    return tokens;
}

// The most seconds before or after the epoch that nanoseconds in an int64 hold, with room for
// the fraction (about 1677-09-21 to 2262-04-11).
constexpr std::int64_t kMaxSeconds = std::numeric_limits<std::int64_t>::max() / 1'000'000'000 - 1;

// Parses "[digits][.digits]" into nanoseconds; nullopt beyond kMaxSeconds.
std::optional<std::int64_t> seconds_with_fraction(std::string_view text) {
    std::int64_t seconds = 0;
    std::size_t i = 0;
    while (i < text.size() && is_digit(text[i])) {
        seconds = seconds * 10 + (text[i] - '0');
        if (seconds > kMaxSeconds) return std::nullopt;
        ++i;
    }
    if (i == 0) return std::nullopt;
    std::int64_t nanos = 0;
    if (i < text.size()) {
        if (text[i] != '.') return std::nullopt;
        ++i;
        std::int64_t scale = 100'000'000;
        std::size_t digits = 0;
        while (i < text.size() && is_digit(text[i])) {
            nanos += (text[i] - '0') * scale;
            scale /= 10;
            ++i;
            ++digits;
        }
        if (digits == 0 || i != text.size()) return std::nullopt;
    }
    return seconds * 1'000'000'000 + nanos;
}

// HH:MM:SS[.frac] -> nanoseconds since midnight.
std::optional<std::int64_t> time_of_day(std::string_view text) {
    if (!text.empty() && (text.back() == 'Z' || text.back() == 'z')) text.remove_suffix(1);
    if (text.size() < 8 || text[2] != ':' || text[5] != ':') return std::nullopt;
    for (std::size_t i : {0u, 1u, 3u, 4u})
        if (!is_digit(text[i])) return std::nullopt;
    int hours = (text[0] - '0') * 10 + (text[1] - '0');
    int minutes = (text[3] - '0') * 10 + (text[4] - '0');
    auto seconds = seconds_with_fraction(text.substr(6));
    if (!seconds || hours > 23 || minutes > 59 || *seconds >= 61'000'000'000LL) return std::nullopt;
    return (hours * 3600LL + minutes * 60LL) * 1'000'000'000LL + *seconds;
}

// Days since 1970-01-01 of a proleptic Gregorian date (Howard Hinnant's algorithm).
std::int64_t days_from_civil(int y, unsigned m, unsigned d) {
    y -= m <= 2;
    const int era = (y >= 0 ? y : y - 399) / 400;
    const unsigned yoe = static_cast<unsigned>(y - era * 400);
    const unsigned doy = (153 * (m > 2 ? m - 3 : m + 9) + 2) / 5 + d - 1;
    const unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    return era * 146097LL + static_cast<std::int64_t>(doe) - 719468;
}

std::optional<std::int64_t> date_nanos(std::string_view text) {
    if (text.size() != 10 || text[4] != '-' || text[7] != '-') return std::nullopt;
    for (std::size_t i : {0u, 1u, 2u, 3u, 5u, 6u, 8u, 9u})
        if (!is_digit(text[i])) return std::nullopt;
    int year =
        (text[0] - '0') * 1000 + (text[1] - '0') * 100 + (text[2] - '0') * 10 + (text[3] - '0');
    unsigned month = static_cast<unsigned>((text[5] - '0') * 10 + (text[6] - '0'));
    unsigned day = static_cast<unsigned>((text[8] - '0') * 10 + (text[9] - '0'));
    if (month < 1 || month > 12 || day < 1 || day > 31) return std::nullopt;
    const std::int64_t days = days_from_civil(year, month, day);
    if (days > kMaxSeconds / 86'400 || days < -kMaxSeconds / 86'400) return std::nullopt;
    return days * 86'400LL * 1'000'000'000LL;
}

// A date plus a time of day; nullopt when the sum leaves the int64 nanoseconds.
std::optional<std::int64_t> date_and_time(std::int64_t date, std::int64_t time) {
    std::int64_t sum = 0;
    if (__builtin_add_overflow(date, time, &sum)) return std::nullopt;
    return sum;
}

std::string_view unwrap(std::string_view token) {
    if (!token.empty() && token.front() == '[') token.remove_prefix(1);
    while (!token.empty() && (token.back() == ']' || token.back() == ':' || token.back() == ','))
        token.remove_suffix(1);
    return token;
}

}  // namespace

std::optional<std::int64_t> parse_timestamp(std::string_view first, std::string_view next) {
    first = unwrap(first);
    if (first.size() > 10 && (first[10] == 'T' || first[10] == 't')) {
        auto date = date_nanos(first.substr(0, 10));
        auto time = time_of_day(first.substr(11));
        if (date && time) return date_and_time(*date, *time);
        return std::nullopt;
    }
    if (auto date = date_nanos(first)) {
        if (auto time = time_of_day(unwrap(next))) return date_and_time(*date, *time);
        return *date;
    }
    if (auto time = time_of_day(first)) return time;
    if (first.find('.') != std::string_view::npos) return seconds_with_fraction(first);
    return std::nullopt;
}

std::string hex_capture_header(Protocol bus) {
    return fmt::format("{} bus={}, one record a line\n", kHexCaptureHeader, protocol_name(bus));
}

bool is_hex_capture_header(std::string_view line) { return line.starts_with(kHexCaptureHeader); }

std::optional<Protocol> hex_capture_bus(std::string_view line) {
    if (!is_hex_capture_header(line)) return std::nullopt;
    line.remove_prefix(kHexCaptureHeader.size());
    const std::size_t at = line.find("bus=");
    if (at == std::string_view::npos) return std::nullopt;
    line.remove_prefix(at + 4);
    std::size_t end = 0;
    while (end < line.size() &&
           ((line[end] >= 'a' && line[end] <= 'z') || (line[end] >= '0' && line[end] <= '9')))
        ++end;
    return protocol_from_name(line.substr(0, end));
}

std::optional<std::int64_t> parse_leading_timestamp(std::string_view text) {
    std::string_view tokens[2];
    std::size_t found = 0;
    std::size_t i = 0;
    while (found < 2 && i < text.size()) {
        while (i < text.size() && (text[i] == ' ' || text[i] == '\t' || text[i] == '\r'))
            ++i;
        const std::size_t start = i;
        while (i < text.size() && text[i] != ' ' && text[i] != '\t' && text[i] != '\r')
            ++i;
        if (i > start) tokens[found++] = text.substr(start, i - start);
    }
    if (found == 0) return std::nullopt;
    return parse_timestamp(tokens[0], tokens[1]);
}

namespace {

bool is_alnum(char c) { return is_digit(c) || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }

std::size_t column_of(std::string_view line, std::string_view token) {
    return static_cast<std::size_t>(token.data() - line.data()) + 1;
}

// Why `body` (a token without 0x and trailing punctuation) is no run of hex bytes; "" if it is.
std::string hex_run_problem(std::string_view body) {
    for (char c : body)
        if (!is_hex(c)) return fmt::format("'{}' is no hex digit", c);
    if (body.size() % 2 != 0) return fmt::format("an odd number of hex digits: {}", body.size());
    return {};
}

void add_error(HexLogLine& result, std::string_view line, std::string_view token, std::string what,
               std::size_t bytes_before) {
    if (result.breaks.empty() || result.breaks.back() != bytes_before)
        result.breaks.push_back(bytes_before);
    ++result.bad_tokens;
    if (!result.error)
        result.error = HexLogError{column_of(line, token), std::string(token), std::move(what)};
}

std::optional<std::uint64_t> hex_number(std::string_view text) {
    if (text.empty() || text.size() > 16 || !all_hex(text)) return std::nullopt;
    std::uint64_t value = 0;
    for (char c : text)
        value = value << 4 | hex_value(c);
    return value;
}

// The bytes of a dump's hex area: groups of hex digit pairs separated by spaces (xxd groups
// 2 bytes by default, hexdump -C shows single bytes).
void dump_bytes(std::string_view line, std::string_view area, HexLogLine& result,
                std::vector<std::uint8_t>& bytes, std::size_t before) {
    for (std::string_view group : split_whitespace(area)) {
        std::string problem = hex_run_problem(group);
        if (problem.empty())
            append_hex_run(group, bytes);
        else
            add_error(result, line, group, fmt::format("is not hex bytes ({})", problem),
                      bytes.size() - before);
    }
}

// xxd ("00000010: 8382 7d3c  ..}<") and hexdump -C ("00000010  83 82 7d 3c  |..}<|") lines.
bool parse_dump_line(std::string_view line, HexLogLine& result, std::vector<std::uint8_t>& bytes) {
    std::size_t digits = 0;
    while (digits < line.size() && is_hex(line[digits]))
        ++digits;
    if (digits < 7 || digits > 16) return false;
    std::optional<std::uint64_t> offset = hex_number(line.substr(0, digits));
    if (!offset) return false;
    const std::size_t before = bytes.size();
    std::string_view rest = line.substr(digits);
    std::string_view area;
    if (rest.size() >= 2 && rest[0] == ':' && rest[1] == ' ') {  // xxd
        area = rest.substr(2);
        std::size_t ascii = area.find("  ");
        if (ascii != std::string_view::npos) area = area.substr(0, ascii);
    } else if (rest.size() >= 3 && rest[0] == ' ' && rest[1] == ' ' && is_hex(rest[2])) {
        area = rest.substr(2);  // hexdump -C
        std::size_t ascii = area.find("  |");
        if (ascii != std::string_view::npos) area = area.substr(0, ascii);
    } else if (rest.empty() && (digits == 7 || digits == 8)) {
        // hexdump's closing line: the length of the input.
        result.dump_offset = offset;
        return true;
    } else {
        return false;
    }
    result.dump_offset = offset;
    dump_bytes(line, area, result, bytes, before);
    result.byte_count = bytes.size() - before;
    return true;
}

enum class TokenKind { Byte, Suspect, Other };

// A token meant as a hex byte that is none: letters and digits only, at most 4 of them, with a
// hex digit among them ("0G", "680", "7", "0x6").
bool suspect_token(std::string_view token) {
    std::string_view body = strip_prefix_0x(strip_punctuation(token));
    if (body.empty() || body.size() > 4) return false;
    bool hex_digit = false;
    for (char c : body) {
        if (!is_alnum(c)) return false;
        if (is_hex(c)) hex_digit = true;
    }
    return hex_digit;
}

// At the edges of the run only what is most likely a typo counts: two characters, a decimal digit
// and a letter that is no hex digit ("0G", "O7"), or (after the run) one hex digit too few or too
// many ("6", "160"). Before the run three digits are more likely a line number than a typo.
bool typo_token(std::string_view token, bool after_run) {
    std::string_view body = strip_prefix_0x(strip_punctuation(token));
    if (after_run && (body.size() == 1 || body.size() == 3) &&
        std::all_of(body.begin(), body.end(), [](char c) { return is_hex(c); }))
        return true;
    if (body.size() != 2) return false;
    bool digit = is_digit(body[0]) || is_digit(body[1]);
    bool beyond_hex =
        (is_alnum(body[0]) && !is_hex(body[0])) || (is_alnum(body[1]) && !is_hex(body[1]));
    return digit && beyond_hex && is_alnum(body[0]) && is_alnum(body[1]);
}

std::string token_problem(std::string_view token) {
    std::string problem = hex_run_problem(strip_prefix_0x(strip_punctuation(token)));
    return fmt::format("is not a hex byte ({})",
                       problem.empty() ? "one byte is two hex digits" : problem);
}

}  // namespace

HexLogLine parse_hex_log_line(std::string_view line, std::vector<std::uint8_t>& bytes,
                              LinePiece piece) {
    HexLogLine result;
    std::size_t first = 0;
    while (first < line.size() && (line[first] == ' ' || line[first] == '\t'))
        ++first;
    std::string_view trimmed = line.substr(first);
    while (!trimmed.empty() &&
           (trimmed.back() == ' ' || trimmed.back() == '\t' || trimmed.back() == '\r'))
        trimmed.remove_suffix(1);
    const bool whole = piece == LinePiece::Whole;
    if (whole && trimmed == "*") {
        result.repeat_marker = true;
        return result;
    }
    if (whole && first == 0 && parse_dump_line(line, result, bytes)) return result;
    std::vector<std::string_view> tokens = split_log_tokens(line);
    std::vector<TokenKind> kinds;
    kinds.reserve(tokens.size());
    for (std::string_view token : tokens)
        kinds.push_back(byte_token(token)      ? TokenKind::Byte
                        : suspect_token(token) ? TokenKind::Suspect
                                               : TokenKind::Other);
    // The longest span of byte tokens, across suspect tokens between them; the later one wins a
    // tie.
    std::size_t best_start = 0, best_end = 0, best_bytes = 0;
    for (std::size_t i = 0; i < tokens.size();) {
        if (kinds[i] != TokenKind::Byte) {
            ++i;
            continue;
        }
        std::size_t start = i, end = i, count = 0;
        while (i < tokens.size()) {
            if (kinds[i] == TokenKind::Byte) {
                ++count;
                end = ++i;
                continue;
            }
            std::size_t j = i;
            while (j < tokens.size() && kinds[j] == TokenKind::Suspect)
                ++j;
            if (j == i || j == tokens.size() || kinds[j] != TokenKind::Byte) break;
            i = j;
        }
        if (count >= best_bytes) {
            best_start = start;
            best_end = end;
            best_bytes = count;
        }
    }
    std::size_t before = bytes.size();
    std::size_t first_data_token = tokens.size();
    if (best_bytes > 0) {
        if (best_start > 0 && typo_token(tokens[best_start - 1], false)) --best_start;
        if (best_end < tokens.size() && kinds[best_end] == TokenKind::Suspect &&
            typo_token(tokens[best_end], true))
            ++best_end;
        for (std::size_t i = best_start; i < best_end; ++i) {
            if (kinds[i] == TokenKind::Byte)
                bytes.push_back(*byte_token(tokens[i]));
            else
                add_error(result, line, tokens[i], token_problem(tokens[i]), bytes.size() - before);
        }
        first_data_token = best_start;
    } else if (!tokens.empty()) {
        std::string_view run = strip_prefix_0x(strip_punctuation(tokens.back()));
        // A line holding nothing but 7 or 8 hex digits is the closing offset line of hexdump,
        // not data.
        bool hexdump_offset = whole && tokens.size() == 1 && (run.size() == 7 || run.size() == 8);
        std::size_t beyond_hex = 0;
        bool alnum = true;
        for (char c : run) {
            if (!is_hex(c)) ++beyond_hex;
            if (!is_alnum(c)) alnum = false;
        }
        if (!hexdump_offset && run.size() >= 2 && run.size() % 2 == 0 && beyond_hex == 0) {
            append_hex_run(run, bytes);
            first_data_token = tokens.size() - 1;
        } else if (!hexdump_offset && run.size() >= 6 && alnum && beyond_hex <= 1) {
            add_error(result, line, tokens.back(),
                      fmt::format("is no run of hex bytes ({})", hex_run_problem(run)), 0);
            first_data_token = tokens.size() - 1;
        }
    }
    result.byte_count = bytes.size() - before;
    if (piece != LinePiece::Later && first_data_token > 0 && first_data_token < tokens.size())
        result.time_ns = parse_timestamp(tokens[0], first_data_token > 1 ? tokens[1] : "");
    return result;
}

HexLogLine LongHexToken::part(std::string_view text, bool first, bool last,
                              std::vector<std::uint8_t>& bytes) {
    HexLogLine result;
    const std::size_t before = bytes.size();
    std::size_t start = 0;
    if (first) {
        nibble_ = 0;
        if (text.size() >= 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X')) start = 2;
    }
    const bool any_hex = std::any_of(text.begin() + static_cast<std::ptrdiff_t>(start), text.end(),
                                     [](char c) { return is_hex(c); });
    if (!any_hex) {
        // Text (or a run of zero bytes): nothing here; a digit waiting before it is left over.
        if (nibble_ != 0 && !text.empty())
            add_error(result, text, text.substr(0, 1),
                      "follows a hex string with an odd number of digits", 0);
        nibble_ = 0;
        return result;
    }
    for (std::size_t i = start; i < text.size();) {
        if (is_hex(text[i])) {
            if (nibble_ == 0) {
                nibble_ = text[i];
            } else {
                bytes.push_back(
                    static_cast<std::uint8_t>(hex_value(nibble_) << 4 | hex_value(text[i])));
                nibble_ = 0;
            }
            ++i;
            continue;
        }
        std::size_t end = i;
        while (end < text.size() && !is_hex(text[end]))
            ++end;
        add_error(result, text, text.substr(i, end - i),
                  nibble_ != 0 ? "is no hex digit (in a compact hex string, after an odd "
                                 "number of digits)"
                               : "is no hex digit (in a compact hex string)",
                  bytes.size() - before);
        nibble_ = 0;
        i = end;
    }
    if (last && nibble_ != 0) {
        add_error(result, text, text.substr(text.size() - 1),
                  "is left over: the compact hex string has an odd number of digits",
                  bytes.size() - before);
        nibble_ = 0;
    }
    result.byte_count = bytes.size() - before;
    return result;
}

std::string shown_token(std::string_view token) {
    constexpr std::size_t kShownChars = 24;
    std::string shown;
    for (std::size_t i = 0; i < token.size() && i < kShownChars; ++i) {
        const auto c = static_cast<unsigned char>(token[i]);
        if (c >= 0x20 && c < 0x7F && c != '\'' && c != '\\')
            shown.push_back(static_cast<char>(c));
        else
            shown += fmt::format("\\x{:02X}", c);
    }
    if (token.size() > kShownChars) shown += "...";
    return shown;
}

Result<std::vector<std::uint8_t>> parse_hex_bytes(std::string_view text) {
    std::vector<std::uint8_t> bytes;
    std::string cleaned(text);
    for (char& c : cleaned)
        if (c == ',' || c == '\n') c = ' ';
    for (std::string_view token : split_whitespace(cleaned)) {
        std::string_view body = strip_prefix_0x(token);
        std::string digits;
        for (char c : body)
            if (c != ':' && c != '-') digits.push_back(c);
        if (digits.empty() || digits.size() % 2 != 0 || !all_hex(digits)) {
            return Error{
                fmt::format("'{}' is not hex bytes (expected pairs of hex digits such as 68 or "
                            "0x68 or 680707)",
                            token)};
        }
        append_hex_run(digits, bytes);
    }
    return bytes;
}

}  // namespace dpscope
