// The hand-written field writers (formats/text_buffer.hpp) write the text fmt writes for the
// same value and format: the renderers' output must stay byte-identical (issue 31).
#include "formats/text_buffer.hpp"

#include <fmt/compile.h>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "formats/describe.hpp"
#include "formats/field_writers.hpp"
#include "formats/verbose_tree.hpp"
#include "protocols/profibus/pcd.hpp"

namespace dpscope {
namespace {

std::string text_of(const TextBuffer& b) { return std::string(b.data(), b.size()); }

// Values at every digit-count boundary, both sides, and the extremes.
std::vector<std::uint64_t> boundary_values() {
    std::vector<std::uint64_t> values = {0,
                                         1,
                                         9,
                                         10,
                                         11,
                                         99,
                                         100,
                                         101,
                                         255,
                                         256,
                                         65535,
                                         65536,
                                         std::numeric_limits<std::uint64_t>::max()};
    for (std::uint64_t p = 10; p < std::numeric_limits<std::uint64_t>::max() / 10; p *= 10) {
        values.push_back(p - 1);
        values.push_back(p);
        values.push_back(p + 1);
    }
    return values;
}

TEST(TextBufferTest, DecimalIsFmtsDecimal) {
    for (std::uint64_t v : boundary_values()) {
        TextBuffer b;
        append_decimal(b, v);
        EXPECT_EQ(text_of(b), fmt::format("{}", v));
    }
}

TEST(TextBufferTest, SignedIsFmtsSigned) {
    std::vector<std::int64_t> values = {0,
                                        -1,
                                        1,
                                        -9,
                                        -10,
                                        -99,
                                        -100,
                                        32767,
                                        -32768,
                                        std::numeric_limits<std::int64_t>::min(),
                                        std::numeric_limits<std::int64_t>::max()};
    for (std::int64_t v : values) {
        TextBuffer b;
        append_signed(b, v);
        EXPECT_EQ(text_of(b), fmt::format("{}", v));
    }
}

TEST(TextBufferTest, PaddedAndAlignedDecimalsAreFmts) {
    for (std::uint64_t v : boundary_values()) {
        for (int width : {0, 1, 3, 6, 9, 12}) {
            TextBuffer zero, right, left;
            append_decimal_padded(zero, v, width);
            append_decimal_right(right, v, width);
            append_decimal_left(left, v, width);
            EXPECT_EQ(text_of(zero), fmt::format("{:0{}}", v, width));
            EXPECT_EQ(text_of(right), fmt::format("{:>{}}", v, width));
            EXPECT_EQ(text_of(left), fmt::format("{:<{}}", v, width));
        }
    }
}

TEST(TextBufferTest, FixedHexIsFmtsHex) {
    for (std::uint64_t v : {0ULL, 1ULL, 0xAULL, 0xFFULL, 0x1234ULL, 0xBEEFULL, 0xFFFFULL}) {
        TextBuffer upper, lower;
        append_hex_fixed(upper, v, 4);
        append_hex_fixed(lower, v, 4, true);
        EXPECT_EQ(text_of(upper), fmt::format("{:04X}", v));
        EXPECT_EQ(text_of(lower), fmt::format("{:04x}", v));
    }
    TextBuffer byte, word;
    append_hex_byte(byte, 0x7D);
    put(word, "0x", hex(0x047F, 4));
    EXPECT_EQ(text_of(byte), "0x7D");
    EXPECT_EQ(text_of(word), "0x047F");
}

TEST(TextBufferTest, AlignedTextCountsCharactersNotBytes) {
    for (std::string_view text : {"", "SD2", "Data_Exchange", "Slave_Diag_long_name", "→", "ü→x"}) {
        for (std::size_t width : {0, 3, 14}) {
            TextBuffer left, right;
            append_left(left, text, width);
            append_right(right, text, width);
            EXPECT_EQ(text_of(left), fmt::format("{:<{}}", text, width)) << text;
            EXPECT_EQ(text_of(right), fmt::format("{:>{}}", text, width)) << text;
        }
    }
}

TEST(TextBufferTest, PutWritesEachPieceAsFmtWould) {
    TextBuffer b;
    const std::uint8_t ind = 7;
    const std::int16_t negative = -12;
    const char* guess = "?";
    put(b, "PNU ", std::uint16_t{918}, '[', ind, "] ", negative, ' ', hex(0x3E, 2), guess,
        std::string_view());
    EXPECT_EQ(text_of(b), "PNU 918[7] -12 3E?");
}

TEST(TextBufferTest, GrowsPastTheInlineStorage) {
    TextBuffer b;
    std::string expected;
    for (int i = 0; i < 10000; ++i) {
        put(b, i, ',');
        expected += fmt::format("{},", i);
    }
    EXPECT_EQ(text_of(b), expected);
}

// append_iso_time computes the civil date itself; gmtime_r and fmt are the reference.
std::string iso_time_by_gmtime(std::int64_t time_ns) {
    std::int64_t seconds = time_ns / 1'000'000'000, nanos = time_ns % 1'000'000'000;
    if (nanos < 0) {
        nanos += 1'000'000'000;
        --seconds;
    }
    std::time_t t = static_cast<std::time_t>(seconds);
    std::tm tm{};
    gmtime_r(&t, &tm);
    return fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}:{:02}.{:09}Z", tm.tm_year + 1900,
                       tm.tm_mon + 1, tm.tm_mday, tm.tm_hour, tm.tm_min, tm.tm_sec, nanos);
}

TEST(TextBufferTest, IsoTimeIsGmtimesDate) {
    // Nanoseconds since 1970 in an int64 reach from 1677 to 2262: both ends, and leap days.
    std::vector<std::int64_t> seconds = {
        0,          -1,         86399,      86400,      951782400,   951868800,   1704067200,
        1709164800, 4107542400, 4107628800, 9223372035, -9223372035, -86400 * 366};
    // Every day of 1969..2101 at a time that moves through the hours.
    for (std::int64_t day = -366; day < 48000; ++day)
        seconds.push_back(day * 86400 + (day * 3677) % 86400);
    for (std::int64_t s : seconds) {
        for (std::int64_t nanos : {0LL, 7LL, 123456789LL, 999999999LL}) {
            const std::int64_t time_ns = s * 1'000'000'000 + (s < 0 ? -nanos : nanos);
            TextBuffer b;
            append_iso_time(b, time_ns);
            ASSERT_EQ(text_of(b), iso_time_by_gmtime(time_ns)) << time_ns;
        }
    }
}

// The jsonl and csv "time": seconds, a point and nine digits, the sign in front ("-1.500000000").
TEST(TextBufferTest, EpochSecondsAreSignSecondsAndNineDigits) {
    std::vector<std::int64_t> times = {std::numeric_limits<std::int64_t>::min(),
                                       std::numeric_limits<std::int64_t>::max()};
    for (std::uint64_t v : boundary_values()) {
        if (v > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) continue;
        times.push_back(static_cast<std::int64_t>(v));
        times.push_back(-static_cast<std::int64_t>(v));
    }
    for (std::int64_t t : times) {
        const bool negative = t < 0;
        const std::uint64_t magnitude =
            negative ? 0 - static_cast<std::uint64_t>(t) : static_cast<std::uint64_t>(t);
        TextBuffer b;
        append_epoch_seconds(b, t);
        ASSERT_EQ(text_of(b), fmt::format("{}{}.{:09}", negative ? "-" : "",
                                          magnitude / 1'000'000'000, magnitude % 1'000'000'000))
            << t;
    }
}

// The whole seconds are kept from one time to the next (write_epoch_seconds()): a run in one
// second, a second forward and back, fewer and more digits, the sign, all in one thread's turn.
TEST(TextBufferTest, EpochSecondsStayRightWhenTheirSecondRepeatsOrChanges) {
    const std::vector<std::int64_t> times = {1'704'067'200'000'000'001,
                                             1'704'067'200'999'999'999,
                                             1'704'067'200'500'000'000,
                                             1'704'067'201'000'000'000,
                                             1'704'067'200'000'389'997,
                                             9'000'000'000,
                                             9'999'999'999,
                                             10'000'000'000,
                                             0,
                                             -1,
                                             -1'500'000'000,
                                             1'500'000'000,
                                             1'704'067'200'000'000'000,
                                             -1'704'067'200'000'000'000,
                                             std::numeric_limits<std::int64_t>::max(),
                                             1'704'067'200'000'000'002};
    for (int round = 0; round < 2; ++round)
        for (std::int64_t t : times) {
            const bool negative = t < 0;
            const std::uint64_t magnitude =
                negative ? 0 - static_cast<std::uint64_t>(t) : static_cast<std::uint64_t>(t);
            TextBuffer b;
            append(b, "x");
            append_epoch_seconds(b, t);
            append(b, "y");
            ASSERT_EQ(text_of(b), fmt::format("x{}{}.{:09}y", negative ? "-" : "",
                                              magnitude / 1'000'000'000, magnitude % 1'000'000'000))
                << t;
        }
}

// A control or status word's bit lines (the verbose tree): the indentation of the level, the
// bit's number right-aligned in two places, its state and its meaning, at any depth.
TEST(TextBufferTest, WordBitLinesAtEveryLevel) {
    WordBits bits{};
    for (std::size_t i = 0; i < bits.size(); ++i)
        bits[i] = WordBit{
            i % 3 == 0 ? std::string_view() : std::string_view("off"),
            i % 2 == 0 ? std::string_view("on, with a longer meaning") : std::string_view("on")};
    for (int level = 0; level <= 10; ++level)
        for (int value : {0x0000, 0xFFFF, 0x0E07, 0xA5A5}) {
            const auto word = static_cast<std::uint16_t>(value);
            std::string expected;
            for (int bit = 0; bit < 16; ++bit) {
                const bool set = (word >> bit) & 1;
                expected += fmt::format("{}bit {:2} = {}: {}\n", std::string(4 * level, ' '), bit,
                                        set ? 1 : 0, set ? bits[bit].when_1 : bits[bit].when_0);
            }
            TextBuffer b;
            append(b, "before\n");
            VerboseTree tree(b);
            tree.word_bit_fields(level, word, bits);
            ASSERT_EQ(text_of(b), "before\n" + expected) << level << " " << word;
        }
}

// A telegram's bytes in hex: two upper-case digits a byte, the separator between bytes.
TEST(TextBufferTest, HexIsTwoDigitsAByteWithTheSeparatorBetween) {
    std::vector<std::uint8_t> bytes(256);
    for (std::size_t i = 0; i < bytes.size(); ++i)
        bytes[i] = static_cast<std::uint8_t>(255 - i);
    for (std::string_view separator : {"", " ", ", "}) {
        for (std::size_t n : {0, 1, 2, 256}) {
            std::string expected;
            for (std::size_t i = 0; i < n; ++i)
                expected += fmt::format("{}{:02X}", i == 0 ? "" : separator, bytes[i]);
            TextBuffer b;
            append_hex(b, Bytes(bytes.data(), n), separator);
            ASSERT_EQ(text_of(b), expected) << n << " '" << separator << "'";
        }
    }
}

}  // namespace
}  // namespace dpscope

namespace dpscope {
namespace {

// RFC 4180: the field in quotes, a quote inside written twice.
TEST(TextBufferTest, CsvQuotedDoublesEveryQuote) {
    const std::pair<std::string_view, std::string_view> cases[] = {
        {"", "\"\""},
        {"plain", "\"plain\""},
        {"\"", "\"\"\"\""},
        {"say \"hi\"", "\"say \"\"hi\"\"\""},
        {"\"\"a\"", "\"\"\"\"\"a\"\"\""},
        {"a,b\nc", "\"a,b\nc\""},
    };
    for (const auto& [text, quoted] : cases) {
        TextBuffer b;
        csv_quoted(b, text);
        EXPECT_EQ(text_of(b), quoted) << text;
    }
}

}  // namespace
}  // namespace dpscope
