// The renderers' output buffer and the writers they call once or more for every field of every
// telegram: text, decimal and hexadecimal numbers appended straight into the buffer (issue 31).
//
// They do what fmt::format_to(fmt::appender(out), FMT_COMPILE("{}"), value) does, without its
// general path: each writer makes room once (an inline capacity check; the buffer grows only when
// full) and stores its characters there. A literal's length is a constant where the call is
// compiled, so appending one is a few stores. The text they write is the text fmt writes for
// "{}", "{:0N}", "{:>N}", "{:<N}", "{:0NX}" and "{:0Nx}" (tests/text_buffer_test.cpp compares
// the two).
#pragma once

#include <fmt/format.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string_view>
#include <type_traits>

namespace dpscope {

using TextBuffer = fmt::memory_buffer;

// `n` more characters at the end of `out`, uninitialised, for the caller to fill.
[[gnu::always_inline]] inline char* append_room(TextBuffer& out, std::size_t n) {
    const std::size_t at = out.size();
    // The buffer's size changes with every piece; in the largest writers the compiler keeps that
    // a call of its own. The JSON writer, whose pieces are many and small, writes through a
    // cursor instead and tells the buffer its size once a value is whole (json_writer.hpp).
    out.try_resize(at + n);
    return out.data() + at;
}

[[gnu::always_inline]] inline void append(TextBuffer& out, std::string_view text) {
    if (text.empty()) return;  // (an empty view may hold a null pointer: no memcpy from it)
    std::memcpy(append_room(out, text.size()), text.data(), text.size());
}

namespace text_detail {

// "00" "01" ... "99": two digits a step.
inline constexpr char kDigitPairs[] =
    "0001020304050607080910111213141516171819"
    "2021222324252627282930313233343536373839"
    "4041424344454647484950515253545556575859"
    "6061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

constexpr int decimal_digits(std::uint64_t value) noexcept {
    int digits = 1;
    for (;;) {
        if (value < 10) return digits;
        if (value < 100) return digits + 1;
        if (value < 1000) return digits + 2;
        if (value < 10000) return digits + 3;
        value /= 10000;
        digits += 4;
    }
}

// The decimal digits of `value`, ending just before `end`; returns where they begin.
inline char* write_decimal_backwards(char* end, std::uint64_t value) noexcept {
    while (value >= 100) {
        end -= 2;
        std::memcpy(end, kDigitPairs + (value % 100) * 2, 2);
        value /= 100;
    }
    if (value >= 10) {
        end -= 2;
        std::memcpy(end, kDigitPairs + value * 2, 2);
    } else {
        *--end = static_cast<char>('0' + value);
    }
    return end;
}

// Characters a terminal shows for UTF-8 text: bytes that do not continue a sequence.
constexpr std::size_t shown_width(std::string_view text) noexcept {
    std::size_t width = 0;
    for (char c : text)
        width += (static_cast<unsigned char>(c) & 0xC0) != 0x80;
    return width;
}

inline void append_spaces(TextBuffer& out, std::size_t count) {
    if (count != 0) std::memset(append_room(out, count), ' ', count);
}

}  // namespace text_detail

namespace text_detail {

// The most characters write_epoch_seconds() writes: a sign, 10 digits of seconds, the point and
// nine digits.
inline constexpr std::size_t kEpochSecondsMax = 21;

// The digits of the whole seconds write_epoch_seconds() wrote last (in this thread): a capture's
// telegrams share their second with thousands of others, whose lines copy them.
struct EpochSecondsDigits {
    std::uint64_t seconds = ~std::uint64_t{0};  // none yet
    int size = 0;
    char digits[16] = {};  // at most 10 (a 64-bit count of nanoseconds), copied 16 at a time
};
inline thread_local EpochSecondsDigits last_epoch_seconds;

// Seconds since 1970 with nine decimals ("1704067200.000389997", "-1.500000000": sign and
// magnitude) from `p` on, which has room for kEpochSecondsMax characters; returns the end. Every
// jsonl and csv line has one.
inline char* write_epoch_seconds(char* p, std::int64_t time_ns) noexcept {
    constexpr std::uint64_t kNanos = 1'000'000'000;
    const bool negative = time_ns < 0;
    const std::uint64_t magnitude =
        negative ? 0 - static_cast<std::uint64_t>(time_ns) : static_cast<std::uint64_t>(time_ns);
    const std::uint64_t seconds = magnitude / kNanos;
    auto nanos = static_cast<std::uint32_t>(magnitude % kNanos);
    if (negative) *p++ = '-';
    EpochSecondsDigits& last = last_epoch_seconds;
    if (seconds != last.seconds) [[unlikely]] {
        last.size = decimal_digits(seconds);
        write_decimal_backwards(last.digits + last.size, seconds);
        last.seconds = seconds;
    }
    // 16 bytes fit: the sign, 10 digits, the point and nine decimals are kEpochSecondsMax.
    static_assert(kEpochSecondsMax >= 1 + sizeof last.digits);
    std::memcpy(p, last.digits, sizeof last.digits);
    p += last.size;
    // The fraction's nine digits, zeros kept: four pairs and a digit.
    *p = '.';
    p[9] = static_cast<char>('0' + nanos % 10);
    nanos /= 10;
    for (int at = 7; at >= 1; at -= 2) {
        std::memcpy(p + at, kDigitPairs + (nanos % 100) * 2, 2);
        nanos /= 100;
    }
    return p + 10;
}

}  // namespace text_detail

// "{}" of an unsigned integer.
inline void append_decimal(TextBuffer& out, std::uint64_t value) {
    const int digits = text_detail::decimal_digits(value);
    text_detail::write_decimal_backwards(
        append_room(out, static_cast<std::size_t>(digits)) + digits, value);
}

// "{}" of a signed integer.
inline void append_signed(TextBuffer& out, std::int64_t value) {
    if (value >= 0) {
        append_decimal(out, static_cast<std::uint64_t>(value));
        return;
    }
    out.push_back('-');
    append_decimal(out, 0 - static_cast<std::uint64_t>(value));
}

// "{:.2f}" of hundredths / 100.0 ("-3.12" for -312), without a double: the caller has the value
// in whole hundredths already rounded (reference_percent_hundredths()).
inline void append_hundredths(TextBuffer& out, std::int64_t hundredths) {
    if (hundredths < 0) out.push_back('-');
    const std::uint64_t magnitude = hundredths < 0 ? 0 - static_cast<std::uint64_t>(hundredths)
                                                   : static_cast<std::uint64_t>(hundredths);
    append_decimal(out, magnitude / 100);
    char* p = append_room(out, 3);
    const std::size_t cents = static_cast<std::size_t>(magnitude % 100);
    p[0] = '.';
    p[1] = text_detail::kDigitPairs[2 * cents];
    p[2] = text_detail::kDigitPairs[2 * cents + 1];
}

namespace text_detail {

// The digits of `value` at the right of `width` characters, `fill` in front of them.
inline void append_decimal_filled(TextBuffer& out, std::uint64_t value, int width, char fill) {
    const int digits = decimal_digits(value);
    const int length = digits < width ? width : digits;
    char* at = append_room(out, static_cast<std::size_t>(length));
    std::memset(at, fill, static_cast<std::size_t>(length - digits));
    write_decimal_backwards(at + length, value);
}

}  // namespace text_detail

// "{:0<width>}" of an unsigned integer: zeros in front up to `width` digits.
inline void append_decimal_padded(TextBuffer& out, std::uint64_t value, int width) {
    text_detail::append_decimal_filled(out, value, width, '0');
}

// "{:0<digits>X}" (or "x" with `lower`) of a value that fits in `digits` hex digits: exactly
// `digits` characters (a wider value keeps only its low digits; callers pass a width that holds
// their type).
inline void append_hex_fixed(TextBuffer& out, std::uint64_t value, int digits, bool lower = false) {
    const char* set = lower ? "0123456789abcdef" : "0123456789ABCDEF";
    char* end = append_room(out, static_cast<std::size_t>(digits)) + digits;
    for (int i = 0; i < digits; ++i) {
        *--end = set[value & 0x0F];
        value >>= 4;
    }
}

// "{:>width}" of an unsigned integer: spaces in front up to `width` characters.
inline void append_decimal_right(TextBuffer& out, std::uint64_t value, int width) {
    text_detail::append_decimal_filled(out, value, width, ' ');
}

// "{:<width}" of an unsigned integer: spaces after it up to `width` characters.
inline void append_decimal_left(TextBuffer& out, std::uint64_t value, int width) {
    const int digits = text_detail::decimal_digits(value);
    const int length = digits < width ? width : digits;
    char* at = append_room(out, static_cast<std::size_t>(length));
    text_detail::write_decimal_backwards(at + digits, value);
    std::memset(at + digits, ' ', static_cast<std::size_t>(length - digits));
}

// "{:<width}" and "{:>width}" of text; the width counts characters, not bytes, as fmt does.
inline void append_left(TextBuffer& out, std::string_view text, std::size_t width) {
    append(out, text);
    const std::size_t shown = text_detail::shown_width(text);
    if (shown < width) text_detail::append_spaces(out, width - shown);
}
inline void append_right(TextBuffer& out, std::string_view text, std::size_t width) {
    const std::size_t shown = text_detail::shown_width(text);
    if (shown < width) text_detail::append_spaces(out, width - shown);
    append(out, text);
}

// "3 bytes", "1 byte": what counted() (core/counted.hpp) says, appended.
inline void append_counted(TextBuffer& out, std::uint64_t n, std::string_view singular,
                           std::string_view plural) {
    append_decimal(out, n);
    out.push_back(' ');
    append(out, n == 1 ? singular : plural);
}

// "0x{:02X}": a byte as the text columns show it.
inline void append_hex_byte(TextBuffer& out, std::uint8_t value) {
    append(out, "0x");
    append_hex_fixed(out, value, 2);
}

// One piece of text for put(): hex(v, 4) is "{:04X}", hex(v, 2, true) "{:02x}".
struct Hex {
    std::uint64_t value;
    int digits;
    bool lower = false;
};
constexpr Hex hex(std::uint64_t value, int digits, bool lower = false) noexcept {
    return {value, digits, lower};
}

namespace text_detail {

template <typename T>
[[gnu::always_inline]] inline void put_one(TextBuffer& out, const T& piece) {
    if constexpr (std::is_same_v<T, char>) {
        out.push_back(piece);
    } else if constexpr (std::is_same_v<T, bool>) {
        static_assert(!std::is_same_v<T, bool>, "put() writes no bool: name it");
    } else if constexpr (std::is_same_v<T, Hex>) {
        append_hex_fixed(out, piece.value, piece.digits, piece.lower);
    } else if constexpr (std::is_integral_v<T> && std::is_signed_v<T>) {
        append_signed(out, piece);
    } else if constexpr (std::is_integral_v<T>) {
        append_decimal(out, piece);
    } else {
        append(out, std::string_view(piece));
    }
}

}  // namespace text_detail

// The pieces one after the other, as fmt::format_to with "{}" for each would write them:
// text, a char, integers in decimal, hex(...) in hex. put(out, "PNU ", pnu, '[', index, ']').
template <typename... Pieces>
[[gnu::always_inline]] inline void put(TextBuffer& out, const Pieces&... pieces) {
    (text_detail::put_one(out, pieces), ...);
}

}  // namespace dpscope
