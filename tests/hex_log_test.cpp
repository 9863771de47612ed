// Hex text: log lines with timestamps, TX/RX prefixes, prompts and hexdump columns; strict hex
// arguments; timestamp tokens.
#include "capture/hex_log.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::hex;

constexpr std::int64_t kSecond = 1'000'000'000;
// 2024-01-02T00:00:00Z.
constexpr std::int64_t kJan2 = 1'704'153'600 * kSecond;
// 12:00:01.5 after midnight.
constexpr std::int64_t kNoonAndABit = (12 * 3600 + 1) * kSecond + 500'000'000;

const std::vector<std::uint8_t> kSd1 = hex("10 03 02 49 4E 16");
const std::vector<std::uint8_t> kSd2 = hex("68 07 07 68 83 82 7D 3E 3E F3 F1 E2 16");

struct Parsed {
    HexLogLine line;
    std::vector<std::uint8_t> bytes;
};

Parsed parse(std::string_view text) {
    Parsed parsed;
    parsed.line = parse_hex_log_line(text, parsed.bytes);
    return parsed;
}

// ---- parse_hex_log_line: bytes ---------------------------------------------------------------

TEST(HexLogTest, PlainBytes) {
    Parsed p = parse("10 03 02 49 4E 16");
    EXPECT_EQ(p.line.byte_count, 6u);
    EXPECT_EQ(p.bytes, kSd1);
    EXPECT_FALSE(p.line.time_ns.has_value());
}

TEST(HexLogTest, LowerCaseAndTabs) {
    Parsed p = parse("\t68 07 07 68\t83 82 7d 3e 3e f3 f1 e2 16\r");
    EXPECT_EQ(p.bytes, kSd2);
}

TEST(HexLogTest, AppendsToExistingBytes) {
    std::vector<std::uint8_t> bytes = {0xAA};
    HexLogLine line = parse_hex_log_line("E5", bytes);
    EXPECT_EQ(line.byte_count, 1u);
    EXPECT_EQ(bytes, hex("AA E5"));
}

TEST(HexLogTest, TxRxPrefixes) {
    for (std::string_view prefix : {"TX:", "RX:", "TX", "RX", "<TX>", "rx>"}) {
        Parsed p = parse(std::string(prefix) + " 10 03 02 49 4E 16");
        EXPECT_EQ(p.bytes, kSd1) << prefix;
        EXPECT_FALSE(p.line.time_ns.has_value()) << prefix;
    }
}

TEST(HexLogTest, Prompts) {
    for (std::string_view prompt : {">", "$", "dpscope>", "COM3>>", "#"}) {
        Parsed p = parse(std::string(prompt) + " 10 03 02 49 4E 16");
        EXPECT_EQ(p.bytes, kSd1) << prompt;
        EXPECT_FALSE(p.line.time_ns.has_value()) << prompt;
    }
}

TEST(HexLogTest, HexdumpCanonicalLine) {
    Parsed p = parse("00000000  68 07 07 68 83 82 7d 3e  3e f3 f1 e2 16           |h..h...>>....|");
    EXPECT_EQ(p.line.byte_count, 13u);
    EXPECT_EQ(p.bytes, kSd2);
    // The offset column is not a timestamp.
    EXPECT_FALSE(p.line.time_ns.has_value());
}

TEST(HexLogTest, HexdumpAsciiColumnThatLooksLikeHex) {
    // Bytes "AB CD E" print as the ASCII column |AB CD E|: its "tokens" must not count.
    Parsed p = parse("00000010  41 42 20 43 44 20 45                              |AB CD E|");
    EXPECT_EQ(p.bytes, hex("41 42 20 43 44 20 45"));
}

TEST(HexLogTest, HexdumpFinalOffsetLineHasNoBytes) {
    // hexdump -C ends its output with a line holding only the total length, e.g. after 13 bytes:
    // "0000000d". It is an offset, not four data bytes.
    Parsed p = parse("0000000d");
    EXPECT_EQ(p.line.byte_count, 0u);
    EXPECT_TRUE(p.bytes.empty());
}

TEST(HexLogTest, ZeroXPrefixedAndCommaSeparated) {
    EXPECT_EQ(parse("0x10 0x03 0x02 0x49 0x4E 0x16").bytes, kSd1);
    EXPECT_EQ(parse("0x10, 0x03, 0x02, 0x49, 0x4E, 0x16").bytes, kSd1);
    EXPECT_EQ(parse("10, 03, 02, 49, 4E, 16").bytes, kSd1);
    EXPECT_EQ(parse("0X10; 0X03; 0X02; 0X49; 0X4E; 0X16;").bytes, kSd1);
}

TEST(HexLogTest, CompactHexRun) {
    EXPECT_EQ(parse("6807076883827D3E3EF3F1E216").bytes, kSd2);
    EXPECT_EQ(parse("RX: 0x100302494E16").bytes, kSd1);
    Parsed timed = parse("12:00:01.5 TX 100302494E16");
    EXPECT_EQ(timed.bytes, kSd1);
    ASSERT_TRUE(timed.line.time_ns.has_value());
    EXPECT_EQ(*timed.line.time_ns, kNoonAndABit);
}

TEST(HexLogTest, CompactRunWithOddDigitCountIsNotBytesAndNamed) {
    // Truncated compact run: an odd number of digits.
    Parsed p = parse("RX: 100302494E1");
    EXPECT_EQ(p.line.byte_count, 0u);
    EXPECT_TRUE(p.bytes.empty());
    ASSERT_TRUE(p.line.error);
    EXPECT_EQ(p.line.error->column, 5u);
    EXPECT_EQ(p.line.error->token, "100302494E1");
    EXPECT_EQ(p.line.error->what, "is no run of hex bytes (an odd number of hex digits: 11)");
    EXPECT_EQ(p.line.breaks, std::vector<std::size_t>{0});
    // Corrupted: a non-hex digit inside.
    Parsed typo = parse("100302494G16");
    EXPECT_EQ(typo.line.byte_count, 0u);
    ASSERT_TRUE(typo.line.error);
    EXPECT_EQ(typo.line.error->what, "is no run of hex bytes ('G' is no hex digit)");
    // Words are no compact runs.
    EXPECT_FALSE(parse("12:00:01 capture started").line.error);
    EXPECT_FALSE(parse("decade5").line.error);  // two letters beyond hex
}

TEST(HexLogTest, LongestRunWinsAndLaterRunWinsATie) {
    Parsed longest = parse("AB CD status: 10 03 02 49 4E 16 ok FF");
    EXPECT_EQ(longest.bytes, kSd1);
    Parsed tie = parse("AB CD -- E5 16");
    EXPECT_EQ(tie.bytes, hex("E5 16"));
}

TEST(HexLogTest, LinesWithoutBytes) {
    for (std::string_view text : {"", "   ", "# dpscope sample: PROFIBUS tap on /dev/ttyUSB0",
                                  "hello world", "Frame 12: nothing", "ABC DEF"}) {
        Parsed p = parse(text);
        EXPECT_EQ(p.line.byte_count, 0u) << text;
        EXPECT_TRUE(p.bytes.empty()) << text;
    }
}

TEST(HexLogTest, CorruptedTokensAreNamedAndBreakTheBytes) {
    // Three-digit and one-digit tokens are not byte tokens: the bytes around them are kept, with
    // a break where each was, and the first is named by its column.
    Parsed p = parse("10 03 123 02 4 49 4E 16");
    EXPECT_EQ(p.bytes, hex("10 03 02 49 4E 16"));
    EXPECT_EQ(p.line.breaks, (std::vector<std::size_t>{2, 3}));
    EXPECT_EQ(p.line.bad_tokens, 2u);
    ASSERT_TRUE(p.line.error);
    EXPECT_EQ(p.line.error->column, 7u);
    EXPECT_EQ(p.line.error->token, "123");
    EXPECT_EQ(p.line.error->what, "is not a hex byte (an odd number of hex digits: 3)");
}

TEST(HexLogTest, TypoInsideOrAtTheEdgeOfTheBytes) {
    Parsed inside = parse("1704067200.5 RX: 68 07 07 68 83 0G 7D 3E 3E F3 F1 E2 16");
    EXPECT_EQ(inside.line.byte_count, 12u);
    EXPECT_EQ(inside.line.breaks, std::vector<std::size_t>{5});
    ASSERT_TRUE(inside.line.error);
    EXPECT_EQ(inside.line.error->column, 33u);
    EXPECT_EQ(inside.line.error->what, "is not a hex byte ('G' is no hex digit)");
    EXPECT_TRUE(inside.line.time_ns.has_value());  // the timestamp still counts
    // Before the bytes: a digit and a letter beyond hex; after them also a lone digit.
    Parsed first = parse("TX: 0G 03 02 49 4E 16");
    ASSERT_TRUE(first.line.error);
    EXPECT_EQ(first.line.error->column, 5u);
    EXPECT_EQ(first.line.breaks, std::vector<std::size_t>{0});
    Parsed last = parse("10 03 02 49 4E 6");
    ASSERT_TRUE(last.line.error);
    EXPECT_EQ(last.line.error->column, 16u);
    EXPECT_EQ(last.line.breaks, std::vector<std::size_t>{5});
    // After them, three hex digits are one too many; before them, a line number.
    Parsed long_last = parse("10 03 02 49 4E 160");
    ASSERT_TRUE(long_last.line.error);
    EXPECT_EQ(long_last.line.error->column, 16u);
    EXPECT_EQ(long_last.line.error->token, "160");
    Parsed numbered = parse("001 10 03 02 49 4E 16");
    EXPECT_FALSE(numbered.line.error);
    EXPECT_EQ(numbered.bytes, kSd1);
    // Labels around the bytes are no typos.
    for (std::string_view text :
         {"RX 10 03 02 49 4E 16 OK", "ID 10 03 02 49 4E 16", "CH 1 10 03 02 49 4E 16 done"}) {
        Parsed p = parse(text);
        EXPECT_FALSE(p.line.error) << text << ": " << p.line.error->token;
        EXPECT_EQ(p.bytes, kSd1) << text;
    }
}

// ---- xxd and hexdump -C ----------------------------------------------------------------------

TEST(HexLogTest, XxdLine) {
    Parsed p = parse("00000010: 6807 0768 8382 7d3e 3ef3 f1e2 16   h..h..}>>....");
    EXPECT_EQ(p.bytes, kSd2);
    ASSERT_TRUE(p.line.dump_offset);
    EXPECT_EQ(*p.line.dump_offset, 0x10u);
    EXPECT_FALSE(p.line.time_ns);
    // The ASCII column may hold anything, also what looks like hex.
    Parsed ascii = parse("00000000: 4142 2043 4420 45                             AB CD E");
    EXPECT_EQ(ascii.bytes, hex("41 42 20 43 44 20 45"));
    // xxd -g1 and -g4.
    EXPECT_EQ(parse("00000000: 10 03 02 49 4e 16                                ...IN.").bytes,
              kSd1);
    EXPECT_EQ(parse("00000000: 10030249 4e16                        ...IN.").bytes, kSd1);
}

TEST(HexLogTest, XxdLineWithTypoNamesTheColumn) {
    Parsed p = parse("00000000: 1003 0249 4g16 1002  ...IN...");
    EXPECT_EQ(p.bytes, hex("10 03 02 49 10 02"));
    ASSERT_TRUE(p.line.error);
    EXPECT_EQ(p.line.error->column, 21u);
    EXPECT_EQ(p.line.error->token, "4g16");
    EXPECT_EQ(p.line.error->what, "is not hex bytes ('g' is no hex digit)");
}

TEST(HexLogTest, RepeatMarker) {
    EXPECT_TRUE(parse("*").line.repeat_marker);
    EXPECT_TRUE(parse("*  ").line.repeat_marker);
    EXPECT_FALSE(parse("* 10 03").line.repeat_marker);
    Parsed end = parse("00000717");
    EXPECT_EQ(end.line.byte_count, 0u);
    ASSERT_TRUE(end.line.dump_offset);
    EXPECT_EQ(*end.line.dump_offset, 0x717u);
}

// ---- parse_hex_log_line: timestamps ----------------------------------------------------------

TEST(HexLogTest, EpochSecondsTimestamp) {
    Parsed p = parse("1700000000.000125 10 03 02 49 4E 16");
    EXPECT_EQ(p.bytes, kSd1);
    ASSERT_TRUE(p.line.time_ns.has_value());
    EXPECT_EQ(*p.line.time_ns, 1'700'000'000'000'125'000);
}

TEST(HexLogTest, EpochSecondsWithNanosecondsAndPrefix) {
    // As written by `dpscope simulate -F hex` and the sample terminal log.
    Parsed p = parse("1704067200.000066666 TX: 10 03 02 49 4E 16");
    EXPECT_EQ(p.bytes, kSd1);
    ASSERT_TRUE(p.line.time_ns.has_value());
    EXPECT_EQ(*p.line.time_ns, 1'704'067'200'000'066'666);
}

TEST(HexLogTest, CommaSeparatedAndGluedLabels) {
    for (const char* line :
         {"RX: 10,03,02,49,4E,16", "TX: 0x10,0x03,0x02,0x49,0x4E,0x16", "TX:100302494E16",
          "TX:0x10 0x03 0x02 0x49 0x4E 0x16", "COM3:10 03 02 49 4E 16", "rx;10;03;02;49;4E;16"}) {
        Parsed p = parse(line);
        EXPECT_EQ(p.bytes, kSd1) << line;
        EXPECT_FALSE(p.line.time_ns.has_value()) << line;
    }
    // A time with a glued label keeps its time; a label of hex letters only is data.
    Parsed timed = parse("12:00:01.5 RX:10 03 02 49 4E 16");
    EXPECT_EQ(timed.bytes, kSd1);
    ASSERT_TRUE(timed.line.time_ns.has_value());
    EXPECT_EQ(*timed.line.time_ns, kNoonAndABit);
    Parsed iso = parse("2024-01-02T12:00:01.5Z,10,03,02,49,4E,16");
    EXPECT_EQ(iso.bytes, kSd1);
    ASSERT_TRUE(iso.line.time_ns.has_value());
    EXPECT_EQ(*iso.line.time_ns, kJan2 + kNoonAndABit);
}

TEST(HexLogTest, TimeOfDayTimestamp) {
    Parsed p = parse("12:00:01.5 10 03 02 49 4E 16");
    EXPECT_EQ(p.bytes, kSd1);
    ASSERT_TRUE(p.line.time_ns.has_value());
    EXPECT_EQ(*p.line.time_ns, kNoonAndABit);
    Parsed whole = parse("23:59:59 E5");
    ASSERT_TRUE(whole.line.time_ns.has_value());
    EXPECT_EQ(*whole.line.time_ns, (23 * 3600 + 59 * 60 + 59) * kSecond);
}

TEST(HexLogTest, IsoDateTimeWithT) {
    Parsed p = parse("2024-01-02T12:00:01.5Z RX: 10 03 02 49 4E 16");
    EXPECT_EQ(p.bytes, kSd1);
    ASSERT_TRUE(p.line.time_ns.has_value());
    EXPECT_EQ(*p.line.time_ns, kJan2 + kNoonAndABit);
}

TEST(HexLogTest, IsoDateAndTimeAsTwoTokens) {
    Parsed p = parse("2024-01-02 12:00:01.5 10 03 02 49 4E 16");
    EXPECT_EQ(p.bytes, kSd1);
    ASSERT_TRUE(p.line.time_ns.has_value());
    EXPECT_EQ(*p.line.time_ns, kJan2 + kNoonAndABit);
}

TEST(HexLogTest, BracketedTimestamps) {
    Parsed time = parse("[12:00:01.5] TX 10 03 02 49 4E 16");
    ASSERT_TRUE(time.line.time_ns.has_value());
    EXPECT_EQ(*time.line.time_ns, kNoonAndABit);
    Parsed iso = parse("[2024-01-02 12:00:01.5] 10 03 02 49 4E 16");
    ASSERT_TRUE(iso.line.time_ns.has_value());
    EXPECT_EQ(*iso.line.time_ns, kJan2 + kNoonAndABit);
    Parsed iso_t = parse("[2024-01-02T12:00:01.5Z] 10 03 02 49 4E 16");
    ASSERT_TRUE(iso_t.line.time_ns.has_value());
    EXPECT_EQ(*iso_t.line.time_ns, kJan2 + kNoonAndABit);
    Parsed epoch = parse("[1700000000.000125] 10 03 02 49 4E 16");
    ASSERT_TRUE(epoch.line.time_ns.has_value());
    EXPECT_EQ(*epoch.line.time_ns, 1'700'000'000'000'125'000);
    EXPECT_EQ(epoch.bytes, kSd1);
}

TEST(HexLogTest, TimestampWithTrailingColon) {
    Parsed p = parse("12:00:01.5: 10 03 02 49 4E 16");
    ASSERT_TRUE(p.line.time_ns.has_value());
    EXPECT_EQ(*p.line.time_ns, kNoonAndABit);
    EXPECT_EQ(p.bytes, kSd1);
}

TEST(HexLogTest, CorruptedTimestampGivesNoTime) {
    Parsed hour = parse("25:00:00.0 10 03 02 49 4E 16");
    EXPECT_EQ(hour.bytes, kSd1);
    EXPECT_FALSE(hour.line.time_ns.has_value());
    Parsed month = parse("2024-13-02T12:00:01.5Z 10 03 02 49 4E 16");
    EXPECT_EQ(month.bytes, kSd1);
    EXPECT_FALSE(month.line.time_ns.has_value());
}

TEST(HexLogTest, TruncatedTimestampGivesNoTime) {
    Parsed p = parse("12:00 10 03 02 49 4E 16");
    EXPECT_EQ(p.bytes, kSd1);
    EXPECT_FALSE(p.line.time_ns.has_value());
    Parsed iso = parse("2024-01-02T12:0 10 03 02 49 4E 16");
    EXPECT_EQ(iso.bytes, kSd1);
    EXPECT_FALSE(iso.line.time_ns.has_value());
}

TEST(HexLogTest, TimestampOnlyAtTheStartOfTheLine) {
    // A time after the bytes is not the line's timestamp.
    Parsed p = parse("10 03 02 49 4E 16 12:00:01.5");
    EXPECT_EQ(p.bytes, kSd1);
    EXPECT_FALSE(p.line.time_ns.has_value());
}

// ---- parse_hex_bytes -------------------------------------------------------------------------

std::vector<std::uint8_t> strict(std::string_view text) {
    Result<std::vector<std::uint8_t>> bytes = parse_hex_bytes(text);
    EXPECT_TRUE(bytes) << bytes.error();
    EXPECT_TRUE(bytes.error().empty());
    return bytes ? std::move(bytes).value() : std::vector<std::uint8_t>{};
}

std::string strict_error(std::string_view text) {
    Result<std::vector<std::uint8_t>> bytes = parse_hex_bytes(text);
    EXPECT_FALSE(bytes) << text;
    return bytes.error();
}

TEST(HexLogTest, StrictAcceptsEveryDocumentedSpelling) {
    EXPECT_EQ(strict("68 07 07 68"), hex("68 07 07 68"));
    EXPECT_EQ(strict("0x68 0x07"), hex("68 07"));
    EXPECT_EQ(strict("0x68,0x07,0X07"), hex("68 07 07"));
    EXPECT_EQ(strict("680707"), hex("68 07 07"));
    EXPECT_EQ(strict("0x680707"), hex("68 07 07"));
    EXPECT_EQ(strict("68:07:07"), hex("68 07 07"));
    EXPECT_EQ(strict("68-07-07"), hex("68 07 07"));
    EXPECT_EQ(strict("10 0302\n49,4e:16"), kSd1);
    EXPECT_TRUE(strict("").empty());
    EXPECT_TRUE(strict("  \n ").empty());
}

TEST(HexLogTest, StrictGivesNoBytesWhenOneTokenIsBad) {
    Result<std::vector<std::uint8_t>> bytes = parse_hex_bytes("10 03 zz 02");
    EXPECT_FALSE(bytes);
    EXPECT_NE(bytes.error().find("'zz'"), std::string::npos) << bytes.error();
}

TEST(HexLogTest, StrictRejectsCorruptedTokenAndNamesIt) {
    std::string error = strict_error("68 zz 07");
    EXPECT_NE(error.find("'zz'"), std::string::npos) << error;
    EXPECT_NE(error.find("is not hex bytes"), std::string::npos) << error;
    EXPECT_EQ(error.find("'68'"), std::string::npos) << error;
    EXPECT_NE(strict_error("0xG1").find("'0xG1'"), std::string::npos);
    EXPECT_NE(strict_error("10 03 TX").find("'TX'"), std::string::npos);
}

TEST(HexLogTest, StrictRejectsTruncatedTokenAndNamesIt) {
    // An odd number of digits: half a byte.
    EXPECT_NE(strict_error("68 070").find("'070'"), std::string::npos);
    EXPECT_NE(strict_error("6").find("'6'"), std::string::npos);
    EXPECT_NE(strict_error("0x").find("'0x'"), std::string::npos);
    EXPECT_NE(strict_error("68:0").find("'68:0'"), std::string::npos);
}

// ---- parse_timestamp -------------------------------------------------------------------------

TEST(HexLogTest, ParseTimestampForms) {
    EXPECT_EQ(parse_timestamp("1700000000.000125"), 1'700'000'000'000'125'000);
    EXPECT_EQ(parse_timestamp("0.5"), 500'000'000);
    EXPECT_EQ(parse_timestamp("12:00:01"), (12 * 3600 + 1) * kSecond);
    EXPECT_EQ(parse_timestamp("12:00:01.123456789"), (12 * 3600 + 1) * kSecond + 123'456'789);
    EXPECT_EQ(parse_timestamp("00:00:00.000000001Z"), 1);
    EXPECT_EQ(parse_timestamp("1970-01-01T00:00:00Z"), 0);
    EXPECT_EQ(parse_timestamp("2024-01-02T12:00:01.5Z"), kJan2 + kNoonAndABit);
    EXPECT_EQ(parse_timestamp("2024-01-02t12:00:01.5z"), kJan2 + kNoonAndABit);
    EXPECT_EQ(parse_timestamp("2024-01-02", "12:00:01.5"), kJan2 + kNoonAndABit);
    EXPECT_EQ(parse_timestamp("[2024-01-02", "12:00:01.5]"), kJan2 + kNoonAndABit);
    EXPECT_EQ(parse_timestamp("[12:00:01.5]:"), kNoonAndABit);
    EXPECT_EQ(parse_timestamp("2024-01-02"), kJan2);
    // Leap day and a date before the Unix epoch.
    EXPECT_EQ(parse_timestamp("2024-02-29T00:00:00Z"), (1'704'067'200LL + 59 * 86'400) * kSecond);
    EXPECT_EQ(parse_timestamp("1969-12-31T00:00:00Z"), -86'400 * kSecond);
}

TEST(HexLogTest, ParseTimestampRejectsCorruptedTokens) {
    for (std::string_view text : {"", "abc", "TX:", "68", "1700000000", "1.2.3", ".5", "5.",
                                  "24:00:00", "12:60:00", "12:00:61", "1a:00:00", "2024-00-10",
                                  "2024-01-32", "2024-01-02T25:00:00Z", "2024/01/02"}) {
        EXPECT_FALSE(parse_timestamp(text).has_value()) << text;
    }
}

// Times that nanoseconds since the epoch in an int64 cannot hold (before 1677-09-21 or after
// 2262-04-11) are no timestamps, not a signed overflow. fuzz_hex_log found
// "17004067200.000136666" (a typo'd epoch time) overflowing seconds * 10^9.
TEST(HexLogTest, ParseTimestampRejectsTimesBeyondTheNanosecondRange) {
    for (std::string_view text :
         {"17004067200.000136666", "9223372036.854775807", "99999999999999999999.5",
          "9999-12-31T00:00:00Z", "0000-01-01T00:00:00Z", "1677-01-01T00:00:00Z",
          "2262-04-12T00:00:00Z", "2262-04-11T23:59:59.999999999Z"}) {
        EXPECT_FALSE(parse_timestamp(text).has_value()) << text;
    }
    EXPECT_FALSE(parse_timestamp("9999-12-31").has_value());
    EXPECT_FALSE(parse_timestamp("2262-04-11", "23:59:59").has_value());
    // The edges that still fit.
    EXPECT_EQ(parse_timestamp("9223372035.999999999"), 9'223'372'035'999'999'999);
    EXPECT_EQ(parse_timestamp("2262-04-10T00:00:00Z"), 106'750LL * 86'400 * kSecond);
    EXPECT_EQ(parse_timestamp("1677-09-22T00:00:00Z"), -106'751LL * 86'400 * kSecond);
    // In a line: the bytes are still read, the line has no time.
    Parsed p = parse("17004067200.000136666 RX: 10 03 02 49 4E 16");
    EXPECT_EQ(p.bytes, kSd1);
    EXPECT_FALSE(p.line.time_ns.has_value());
}

TEST(HexLogTest, ParseTimestampRejectsTruncatedTokens) {
    for (std::string_view text :
         {"12:00", "12:00:0", "2024-01-0", "2024-01-02T", "2024-01-02T12:00"})
        EXPECT_FALSE(parse_timestamp(text).has_value()) << text;
}

}  // namespace
}  // namespace dpscope
