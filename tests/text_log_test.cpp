// Text logs of VLT 2000 telegrams (capture/text_log.hpp): telegrams found on lines among other
// text, leading time stamps, broken telegrams reported by line and column, one long line, and the
// detection of such a log next to hex logs (capture/input_format.hpp).
#include "capture/text_log.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "capture/bus_tag.hpp"
#include "capture/input_format.hpp"
#include "capture/telegram_source.hpp"
#include "protocols/vlt2000/vlt2000_telegram.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

// A telegram from its first 19 characters ('<' and bytes 2-19), with its checksum and '>'.
std::string vlt(std::string_view head) {
    std::string t(head);
    EXPECT_EQ(t.size(), 19u) << t;
    unsigned sum = 0;
    for (std::size_t i = 1; i < t.size(); ++i)
        sum += static_cast<unsigned char>(t[i]);
    t += static_cast<char>('0' + sum % 100 / 10);
    t += static_cast<char>('0' + sum % 10);
    return t + ">";
}

const std::string kRequest = vlt("<01UOGD@0516+000800");  // the VLT 3000 manual's example
const std::string kReply = vlt("<01UGHK@0516+000800");

Bytes bytes_of(const std::string& s) {
    return Bytes(reinterpret_cast<const std::uint8_t*>(s.data()), s.size());
}

struct ReadResult {
    std::vector<std::string> telegrams;
    std::vector<std::int64_t> times;
    std::vector<std::string> issues;
    InputFormat format = InputFormat::Auto;
    BusChoice choice;
    std::uint64_t skipped = 0;
    InputStatus status = InputStatus::Ok;
    std::string path;
};

ReadResult read_text(const std::string& text, InputFormat format = InputFormat::Auto) {
    const std::string path = test::temp_path("log.txt");
    test::write_text_file(path, text);
    ReadResult result;
    result.path = path;
    OpenResult opened = open_source(path, format, nullptr, result.choice);
    EXPECT_TRUE(opened) << opened.error();
    if (!opened) return result;
    TelegramSource& source = **opened;
    source.on_issue([&](const InputIssue& issue) { result.issues.push_back(issue.message); });
    Record record;
    while (source.next(record)) {
        result.telegrams.emplace_back(record.bytes.begin(), record.bytes.end());
        result.times.push_back(record.time_ns);
    }
    result.format = source.format();
    result.skipped = source.bytes_skipped();
    result.status = source.status();
    return result;
}

std::string joined(const std::vector<std::string>& lines) {
    std::string text;
    for (const std::string& line : lines)
        text += line + "\n";
    return text;
}

TEST(TextLogTest, TheExampleTelegramsChecksumIsTheManuals) {
    EXPECT_EQ(kRequest, "<01UOGD@0516+00080007>");
}

TEST(TextLogTest, TelegramsAmongOtherTextWithTimeStampsAndCrlf) {
    const std::string log = "12:00:00.000 TX: " + kRequest + "\r\n" +  //
                            "12:00:00.015 RX: " + kReply + "\r\n" +    //
                            "\r\n" +                                   //
                            "[12:00:01.5] TX " + kRequest + "  " + kRequest + "\r\n";
    ReadResult r = read_text(log);
    EXPECT_EQ(r.format, InputFormat::Text);
    EXPECT_EQ(r.choice.protocol->protocol, Protocol::Vlt2000);
    EXPECT_TRUE(r.choice.say);
    EXPECT_EQ(r.choice.reason, "a text log of ASCII telegrams ('<' ... '>')");
    ASSERT_EQ(r.telegrams.size(), 4u);
    EXPECT_EQ(r.telegrams[0], kRequest);
    EXPECT_EQ(r.telegrams[1], kReply);
    EXPECT_EQ(r.telegrams[3], kRequest);
    EXPECT_EQ(r.times[0], 12LL * 3600 * 1'000'000'000);
    EXPECT_EQ(r.times[1] - r.times[0], 15'000'000);
    // The line's time is its first telegram's; the second has none (the log does not say when).
    EXPECT_EQ(r.times[2], 12LL * 3600 * 1'000'000'000 + 1'500'000'000);
    EXPECT_EQ(r.times[3], kNoTime);
    EXPECT_TRUE(r.issues.empty()) << r.issues.front();
    EXPECT_EQ(r.skipped, 0u);
    // Dates, and epoch seconds.
    ReadResult dated =
        read_text("2024-01-02 12:00:01.5 " + kRequest + "\n1704067200.000125 RX " + kReply + "\n");
    ASSERT_EQ(dated.times.size(), 2u);
    const std::int64_t day = 19'724LL * 86'400 * 1'000'000'000;  // 2024-01-02
    EXPECT_EQ(dated.times[0], day + 12LL * 3600 * 1'000'000'000 + 1'500'000'000);
    EXPECT_EQ(dated.times[1], 1'704'067'200'000'125'000LL);
}

TEST(TextLogTest, ACarriageReturnEndsAnOpenTelegramLikeTheLineEnd) {
    ReadResult r = read_text("TX <01UOGD@05\r\n" + kReply + "\r\n");
    ASSERT_EQ(r.telegrams.size(), 1u);
    ASSERT_EQ(r.issues.size(), 1u);
    EXPECT_NE(r.issues[0].find("line 1, column 4: skipped 10 characters: '<01UOGD@05' is no VLT "
                               "2000 telegram: the line ends after 10 of its 22 characters"),
              std::string::npos)
        << r.issues[0];
}

TEST(TextLogTest, LinesWithoutATimeStampHaveNoTime) {
    ReadResult r = read_text("TX: " + kRequest + "\n" + kReply + "\n");
    ASSERT_EQ(r.telegrams.size(), 2u);
    EXPECT_EQ(r.times[0], kNoTime);
    EXPECT_EQ(r.times[1], kNoTime);
}

TEST(TextLogTest, ATruncatedTelegramIsReportedByLineAndColumnAndReadingGoesOn) {
    ReadResult r = read_text(joined({kRequest, "RX: <01UGHK@0516", kReply}));
    ASSERT_EQ(r.telegrams.size(), 2u);
    ASSERT_EQ(r.issues.size(), 1u);
    EXPECT_EQ(r.issues[0],
              r.path +
                  ": line 2, column 5: skipped 12 characters: '<01UGHK@0516' is no VLT 2000 "
                  "telegram: the line ends after 12 of its 22 characters");
    EXPECT_EQ(r.skipped, 12u);
}

TEST(TextLogTest, ABrokenTelegramRunningIntoAnotherIsResynchronisedOnTheNextStart) {
    // A telegram cut after 4 characters, the next one right behind it on the line.
    ReadResult r = read_text(joined({"<01U" + kRequest + " " + kReply}));
    ASSERT_EQ(r.telegrams.size(), 2u);
    EXPECT_EQ(r.telegrams[0], kRequest);
    EXPECT_EQ(r.telegrams[1], kReply);
    ASSERT_EQ(r.issues.size(), 1u);
    EXPECT_NE(r.issues[0].find(": line 1, column 1: skipped 4 characters: '<01U<01UOGD@0516+00080' "
                               "is no VLT 2000 telegram: its 22nd character is '0', not '>'; "
                               "another '<' at column 5"),
              std::string::npos)
        << r.issues[0];
}

TEST(TextLogTest, ControlCharactersAndAMissingStopAreNamed) {
    std::string tab = kRequest;
    tab[6] = '\t';
    std::string no_stop = kRequest;
    no_stop[21] = 'X';
    ReadResult r = read_text(joined({tab, no_stop, kReply}), InputFormat::Text);
    ASSERT_EQ(r.telegrams.size(), 1u);
    ASSERT_EQ(r.issues.size(), 2u);
    EXPECT_NE(r.issues[0].find("line 1, column 1: skipped 7 characters: '<01UOG\\x09' is no VLT "
                               "2000 telegram: character 7 is 0x09, not printable ASCII"),
              std::string::npos)
        << r.issues[0];
    EXPECT_NE(r.issues[1].find("line 2, column 1: skipped 22 characters: '<01UOGD@0516+00080007X' "
                               "is no VLT 2000 telegram: its 22nd character is 'X', not '>'"),
              std::string::npos)
        << r.issues[1];
}

TEST(TextLogTest, TheInputEndingInATelegramIsReported) {
    ReadResult r = read_text(kRequest + "\n<01UOG");
    ASSERT_EQ(r.telegrams.size(), 1u);
    ASSERT_EQ(r.issues.size(), 1u);
    EXPECT_NE(r.issues[0].find("line 2, column 1: skipped 6 characters: '<01UOG' is no VLT 2000 "
                               "telegram: the input ends after 6 of its 22 characters"),
              std::string::npos)
        << r.issues[0];
}

TEST(TextLogTest, AChecksumErrorIsLeftToTheDecoderAndAFramerSkipNamesTheColumn) {
    std::string bad_sum = kRequest;
    bad_sum[19] = '9';
    bad_sum[20] = '9';
    // '>' in place, wrong checksum and another '<' inside: the framer skips it to that '<'.
    std::string inner = "<01U<1UOGD@0516+00099>";
    ASSERT_EQ(inner.size(), 22u);
    ReadResult r = read_text(joined({bad_sum, "xx " + inner}));
    ASSERT_EQ(r.telegrams.size(), 1u);
    EXPECT_EQ(r.telegrams[0], bad_sum);
    ASSERT_FALSE(r.issues.empty());
    EXPECT_NE(r.issues[0].find(": line 2, column 4: skipped 22 bytes: checksum wrong and another "
                               "'<' inside"),
              std::string::npos)
        << r.issues[0];
}

TEST(TextLogTest, ARawDumpWithoutLineBreaksIsReadAsOneLongLine) {
    std::string dump;
    const int pairs = 6000;  // 264,000 characters on one line
    for (int i = 0; i < pairs; ++i) {
        dump += kRequest;
        if (i == pairs / 2) dump += "<01UOGD";  // a telegram cut in the middle
        dump += kReply;
    }
    ReadResult r = read_text(dump);
    EXPECT_EQ(r.format, InputFormat::Text);
    ASSERT_EQ(r.telegrams.size(), 2u * pairs);
    ASSERT_EQ(r.issues.size(), 1u);
    const std::size_t column = (pairs / 2 + 1) * kRequest.size() + pairs / 2 * kReply.size() + 1;
    EXPECT_NE(r.issues[0].find(fmt::format("line 1, column {}: skipped 7 characters", column)),
              std::string::npos)
        << r.issues[0];
}

TEST(TextLogTest, OneLongLineOfTelegramsOrBrokenStartsIsReadInBoundedMemory) {
    // 10 MB on one line, of telegrams or of '<' that start none (each a warning, most counted):
    // the source holds a read buffer and what one of them frames, whatever the line's length.
    for (const std::string& unit : {kRequest + kReply, std::string("<<<<<<<<")}) {
        std::string dump;
        while (dump.size() < 10'000'000)
            dump += unit;
        const std::string path = test::temp_path("long.txt");
        test::write_text_file(path, dump);
        OpenResult opened = open_source(path, InputFormat::Text, vlt2000_protocol());
        ASSERT_TRUE(opened) << opened.error();
        TelegramSource& source = **opened;
        std::size_t most = 0;
        source.on_issue([&](const InputIssue&) { most = std::max(most, source.buffered_bytes()); });
        Record record;
        while (source.next(record))
            most = std::max(most, source.buffered_bytes());
        EXPECT_LE(most, std::size_t{1} << 20) << unit;
    }
}

TEST(TextLogTest, AByteOrderMarkOrNonAsciiTextKeepsTheTimes) {
    // Issue #27 point 5: a BOM before the first time stamp, a header in UTF-8 or Latin-1: the log
    // is still detected as a text log, and every line keeps its time.
    for (const std::string& head : {std::string("\xEF\xBB\xBF"), std::string("Log \xC2\xB5s\n"),
                                    std::string("Log \xB5s, Latin-1\n")}) {
        SCOPED_TRACE(head);
        ReadResult r =
            read_text(head + "12:00:00.5 " + kRequest + "\n12:00:00.75 " + kReply + "\n");
        EXPECT_EQ(r.format, InputFormat::Text);
        ASSERT_EQ(r.telegrams.size(), 2u);
        EXPECT_EQ(r.times[0], 12 * 3600 * 1'000'000'000LL + 500'000'000);
        EXPECT_EQ(r.times[1], 12 * 3600 * 1'000'000'000LL + 750'000'000);
        EXPECT_TRUE(r.issues.empty());
    }
}

TEST(TextLogTest, AnEmptyOrTelegramLessTextHasNoTelegrams) {
    ReadResult empty = read_text("", InputFormat::Text);
    EXPECT_TRUE(empty.telegrams.empty());
    EXPECT_TRUE(empty.issues.empty());
    EXPECT_EQ(empty.status, InputStatus::Ok);
    ReadResult plain = read_text("no telegram here\n", InputFormat::Text);
    EXPECT_TRUE(plain.telegrams.empty());
    EXPECT_TRUE(plain.issues.empty());
    test::CommandResult cli = test::run_dpscope({"decode", "--input-format", "text", plain.path});
    EXPECT_EQ(cli.exit_code, 2);
    EXPECT_NE(cli.err.find("no VLT 2000 telegram ('<' ... '>') in the text"), std::string::npos)
        << cli.err;
}

TEST(TextLogTest, PiecesOfTelegramsInAnyOrderNeverLoseAWholeOne) {
    // Telegrams, their pieces, time stamps, line ends and stray bytes mixed at random: nothing
    // but 22-character telegrams comes out, and at least every whole telegram that follows no
    // open '<' is among them.
    std::mt19937 random(11);
    const std::vector<std::string> pieces = {kRequest,
                                             kReply,
                                             "<01U",
                                             "<",
                                             ">",
                                             "12:00:00.5 ",
                                             "TX: ",
                                             "\r\n",
                                             "\n",
                                             "x",
                                             std::string(1, '\x01')};
    for (int round = 0; round < 200; ++round) {
        std::string text;
        std::size_t whole = 0;
        bool clean_before = true;  // nothing open that a telegram could be taken into
        for (int i = 0; i < 40; ++i) {
            const std::string& piece = pieces[random() % pieces.size()];
            text += piece;
            const bool telegram = piece.size() == 22;
            if (telegram && clean_before) ++whole;
            clean_before = telegram || piece.find('<') == std::string::npos;
            if (piece == "<01U" || piece == "<") clean_before = false;
        }
        ReadResult r = read_text(text, InputFormat::Text);
        EXPECT_GE(r.telegrams.size(), whole) << text;
        for (const std::string& t : r.telegrams) {
            EXPECT_EQ(t.size(), 22u);
            EXPECT_EQ(t.front(), '<');
            EXPECT_EQ(t.back(), '>');
        }
        EXPECT_EQ(r.status, InputStatus::Ok);
    }
}

TEST(TextLogTest, DetectionTellsTextLogsFromHexLogs) {
    EXPECT_EQ(detect_input_format(bytes_of("12:00:00 TX " + kRequest + "\n")), InputFormat::Text);
    EXPECT_EQ(detect_input_format(bytes_of(kRequest + kReply)), InputFormat::Text);
    // A PROFIBUS hex log stays a hex log, and so does a hex log of VLT 2000 bytes.
    EXPECT_EQ(detect_input_format(bytes_of("12:00:00 10 03 02 49 4E 16\n")), InputFormat::Hex);
    std::string hex_of_vlt;
    for (char c : kRequest)
        hex_of_vlt += fmt::format("{:02X} ", static_cast<unsigned char>(c));
    EXPECT_EQ(detect_input_format(bytes_of(hex_of_vlt + "\n")), InputFormat::Hex);
    BusChoice choice = choose_bus(bytes_of(hex_of_vlt + "\n"), InputFormat::Hex, true);
    EXPECT_EQ(choice.protocol->protocol, Protocol::Vlt2000);
    // Not the shape: no address digits (markup), one character short, a line break inside, a
    // byte that is not text.
    EXPECT_EQ(detect_input_format(bytes_of("<!DOCTYPE html PUBLIC>\n<p>ab 12</p>\n")),
              InputFormat::Hex);
    EXPECT_EQ(detect_input_format(bytes_of("<0xUOGD@0516+00080007>")), InputFormat::Hex);
    EXPECT_EQ(detect_input_format(bytes_of("<01UOGD@0516+0008007>")), InputFormat::Hex);
    EXPECT_EQ(detect_input_format(bytes_of("<01UOGD@05\n16+00080007>")), InputFormat::Hex);
    std::string binary = kRequest;
    binary += '\x02';
    EXPECT_EQ(detect_input_format(bytes_of(binary)), InputFormat::Raw);
    // xxd and hexdump -C show 16 characters in their text column by default: no telegram shape.
    EXPECT_EQ(detect_input_format(bytes_of("00000000: 3c30 3155 4f47 4440 3035 3136 2b30 3030  "
                                           "<01UOGD@0516+000\n")),
              InputFormat::Hex);
    // With 32 a line (xxd -c 32, hexdump -C of wider lines) the column holds whole telegrams:
    // the offset column still makes them hex dumps.
    std::string xxd32 = "00000000:";
    for (std::size_t i = 0; i < 32; i += 2)
        xxd32 += fmt::format(" {:02x}{:02x}", static_cast<unsigned char>((kRequest + kReply)[i]),
                             static_cast<unsigned char>((kRequest + kReply)[i + 1]));
    xxd32 += "  " + (kRequest + kReply).substr(0, 32) + "\n";
    EXPECT_EQ(detect_input_format(bytes_of(xxd32)), InputFormat::Hex) << xxd32;
    EXPECT_EQ(detect_input_format(bytes_of("00000000  3c 30 31 55 4f 47 44 40  30 35 31 36 2b 30 "
                                           "30 30  |" +
                                           kRequest + "|\n")),
              InputFormat::Hex);
}

TEST(TextLogTest, CommandLineReadsATextLogAndRefusesAnotherBus) {
    const std::string path = test::temp_path("vlt.log");
    test::write_text_file(path, joined({"TX: " + kRequest, "RX: " + kReply}));
    test::CommandResult r = test::run_dpscope({"decode", "-T", "jsonl", path});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(test::lines_of(r.out).size(), 2u) << r.out;
    EXPECT_EQ(r.err, "dpscope: note: " + path +
                         ": read as the VLT 2000 telegram: a text log of ASCII telegrams ('<' ... "
                         "'>'); --bus chooses\n");
    test::CommandResult given = test::run_dpscope({"decode", "--bus", "vlt2000", path});
    EXPECT_EQ(given.exit_code, 0) << given.err;
    EXPECT_EQ(given.err, "");
    for (const char* bus : {"profibus", "fc"}) {
        for (const char* format : {"auto", "text"}) {
            test::CommandResult other =
                test::run_dpscope({"decode", "--bus", bus, "--input-format", format, path});
            EXPECT_EQ(other.exit_code, 2) << bus << " " << format;
            EXPECT_NE(other.err.find(path + ": a text log of telegrams ('<' ... '>'"),
                      std::string::npos)
                << other.err;
            EXPECT_NE(other.err.find(std::string("is VLT 2000 traffic; --bus ") + bus +
                                     " cannot read it"),
                      std::string::npos)
                << other.err;
        }
    }
    // Standard input too.
    test::CommandResult piped =
        test::run_dpscope({"decode", "-T", "jsonl", "-"}, joined({kRequest, kReply}));
    EXPECT_EQ(piped.exit_code, 0) << piped.err;
    EXPECT_EQ(test::lines_of(piped.out).size(), 2u);
    test::CommandResult report = test::run_dpscope({"report", "--input-format", "text", path});
    EXPECT_NE(report.exit_code, 2) << report.err;
}

}  // namespace
}  // namespace dpscope
