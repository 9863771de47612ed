// Byte-stream sources: raw serial dumps and hex text logs through open_source, and bytes in
// memory. Telegrams are framed from the stream; skipped bytes are reported with their place.
#include "capture/stream_source.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <future>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "capture/framed_source.hpp"
#include "capture/telegram_source.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::hex;

const std::vector<std::uint8_t> kSd1 = hex("10 03 02 49 4E 16");
const std::vector<std::uint8_t> kSd2 = hex("68 07 07 68 83 82 7D 3E 3E F3 F1 E2 16");
const std::vector<std::uint8_t> kToken = hex("DC 02 02");
const std::vector<std::uint8_t> kAck = hex("E5");

struct TempFile {
    explicit TempFile(std::string_view name) : path(test::temp_path(name)) {}
    ~TempFile() { std::remove(path.c_str()); }
    std::string path;
};

std::vector<std::uint8_t> concat(std::initializer_list<std::vector<std::uint8_t>> parts) {
    std::vector<std::uint8_t> out;
    for (const auto& part : parts)
        out.insert(out.end(), part.begin(), part.end());
    return out;
}

struct ReadResult {
    std::vector<Record> records;
    std::vector<std::vector<std::uint8_t>> data;
    std::vector<InputIssue> issues;
    InputStatus status = InputStatus::Ok;
    InputFormat format = InputFormat::Auto;
    int link_type = -1;
    std::uint64_t skipped = 0;
};

ReadResult drain(TelegramSource& source) {
    ReadResult result;
    source.on_issue([&](const InputIssue& issue) { result.issues.push_back(issue); });
    Record record;
    while (source.next(record)) {
        result.data.emplace_back(record.bytes.begin(), record.bytes.end());
        result.records.push_back(record);
    }
    result.status = source.status();
    result.format = source.format();
    result.link_type = source.link_type();
    result.skipped = source.bytes_skipped();
    return result;
}

ReadResult read_all(const std::string& path, InputFormat format) {
    OpenResult opened = open_source(path, format, profibus_protocol());
    EXPECT_TRUE(opened) << opened.error();
    if (!opened) return {};
    return drain(*opened.value());
}

std::vector<std::uint8_t> random_bytes(std::size_t n, std::uint32_t seed = 7) {
    std::mt19937 generator(seed);
    std::vector<std::uint8_t> bytes(n);
    for (std::uint8_t& b : bytes)
        b = static_cast<std::uint8_t>(generator());
    return bytes;
}

// ---- raw -------------------------------------------------------------------------------------

TEST(StreamSourceTest, RawTelegramsWithOffsets) {
    TempFile file("stream.raw");
    test::write_file(file.path, concat({kSd1, kSd2, kToken, kAck}));
    for (InputFormat format : {InputFormat::Raw, InputFormat::Auto}) {
        SCOPED_TRACE(input_format_name(format));
        ReadResult r = read_all(file.path, format);
        EXPECT_EQ(r.format, InputFormat::Raw);
        EXPECT_EQ(r.link_type, 0);
        EXPECT_EQ(r.status, InputStatus::Ok);
        EXPECT_TRUE(r.issues.empty());
        EXPECT_EQ(r.skipped, 0u);
        ASSERT_EQ(r.records.size(), 4u);
        EXPECT_EQ(r.data[0], kSd1);
        EXPECT_EQ(r.data[1], kSd2);
        EXPECT_EQ(r.data[2], kToken);
        EXPECT_EQ(r.data[3], kAck);
        const std::uint64_t offsets[] = {0, 6, 19, 22};
        for (std::size_t i = 0; i < 4; ++i) {
            EXPECT_EQ(r.records[i].number, i + 1);
            EXPECT_EQ(r.records[i].offset, offsets[i]);
            EXPECT_EQ(r.records[i].time_ns, kNoTime);
            EXPECT_EQ(r.records[i].original_length, r.data[i].size());
        }
    }
}

TEST(StreamSourceTest, RawSkippedBytesNameTheOffset) {
    TempFile file("garbage.raw");
    test::write_file(file.path, concat({kSd1, hex("01 02 03"), kToken}));
    ReadResult r = read_all(file.path, InputFormat::Raw);
    ASSERT_EQ(r.records.size(), 2u);
    EXPECT_EQ(r.data[1], kToken);
    EXPECT_EQ(r.records[1].offset, 9u);
    EXPECT_EQ(r.skipped, 3u);
    EXPECT_EQ(r.status, InputStatus::Ok);
    ASSERT_EQ(r.issues.size(), 1u);
    EXPECT_EQ(r.issues[0].severity, Severity::Warning);
    EXPECT_EQ(r.issues[0].message,
              file.path + ": byte offset 6: skipped 3 bytes: no start delimiter");
}

TEST(StreamSourceTest, RawTruncatedTelegramAtTheEnd) {
    TempFile file("cut.raw");
    std::vector<std::uint8_t> cut(kSd2.begin(), kSd2.end() - 3);
    test::write_file(file.path, concat({kSd1, cut}));
    ReadResult r = read_all(file.path, InputFormat::Raw);
    ASSERT_EQ(r.records.size(), 1u);
    EXPECT_EQ(r.data[0], kSd1);
    EXPECT_EQ(r.skipped, cut.size());
    EXPECT_EQ(r.status, InputStatus::Ok);
    ASSERT_EQ(r.issues.size(), 1u);
    EXPECT_EQ(r.issues[0].message,
              file.path +
                  ": byte offset 6: skipped 10 bytes: telegram cut off (gap or end of "
                  "input)");
}

TEST(StreamSourceTest, RawCorruptedTelegrams) {
    TempFile file("corrupt.raw");
    // An SD2 with a wrong FCS keeps its structure and is handed out (the decoder reports the
    // FCS); an SD2 whose LEr disagrees with LE is skipped.
    std::vector<std::uint8_t> bad_fcs = kSd2;
    bad_fcs[11] ^= 0x5A;
    std::vector<std::uint8_t> bad_length = kSd2;
    bad_length[2] = 0x08;
    test::write_file(file.path, concat({bad_fcs, bad_length, kSd1}));
    ReadResult r = read_all(file.path, InputFormat::Raw);
    ASSERT_EQ(r.records.size(), 2u);
    EXPECT_EQ(r.data[0], bad_fcs);
    EXPECT_EQ(r.data[1], kSd1);
    EXPECT_EQ(r.records[1].offset, 26u);
    EXPECT_EQ(r.skipped, 13u);
    ASSERT_EQ(r.issues.size(), 1u);
    EXPECT_EQ(r.issues[0].message,
              file.path +
                  ": byte offset 13: skipped 13 bytes: LEr differs from LE (byte 2 of "
                  "the candidate telegram)");
}

TEST(StreamSourceTest, RawTelegramsAcrossReadChunks) {
    TempFile file("big.raw");
    // 13-byte telegrams over several 64 KiB reads: some straddle a chunk boundary.
    constexpr std::size_t kCount = 12'000;
    std::vector<std::uint8_t> bytes;
    for (std::size_t i = 0; i < kCount; ++i)
        bytes.insert(bytes.end(), kSd2.begin(), kSd2.end());
    test::write_file(file.path, bytes);
    ReadResult r = read_all(file.path, InputFormat::Raw);
    ASSERT_EQ(r.records.size(), kCount);
    EXPECT_TRUE(r.issues.empty());
    for (std::size_t i = 0; i < kCount; ++i) {
        ASSERT_EQ(r.data[i], kSd2) << i;
        ASSERT_EQ(r.records[i].offset, i * 13) << i;
        ASSERT_EQ(r.records[i].number, i + 1) << i;
    }
}

TEST(StreamSourceTest, EmptyRawFile) {
    TempFile file("empty.raw");
    test::write_file(file.path, {});
    ReadResult r = read_all(file.path, InputFormat::Raw);
    EXPECT_TRUE(r.records.empty());
    EXPECT_TRUE(r.issues.empty());
    EXPECT_EQ(r.status, InputStatus::Ok);
}

// ---- hex -------------------------------------------------------------------------------------

TEST(StreamSourceTest, HexLinesWithTimestamps) {
    TempFile file("log.txt");
    test::write_text_file(file.path,
                          "# capture of the bus\n"
                          "1704067200.000000001 TX: 10 03 02 49 4E 16\n"
                          "1704067200.000500000 RX: 68 07 07 68 83 82 7D\n"
                          "        3E 3E F3 F1 E2 16\n"
                          "\n"
                          "1704067200.001000000 E5\r\n");
    for (InputFormat format : {InputFormat::Hex, InputFormat::Auto}) {
        SCOPED_TRACE(input_format_name(format));
        ReadResult r = read_all(file.path, format);
        EXPECT_EQ(r.format, InputFormat::Hex);
        EXPECT_EQ(r.status, InputStatus::Ok);
        EXPECT_TRUE(r.issues.empty());
        ASSERT_EQ(r.records.size(), 3u);
        EXPECT_EQ(r.data[0], kSd1);
        EXPECT_EQ(r.data[1], kSd2);  // split across two lines
        EXPECT_EQ(r.data[2], kAck);
        EXPECT_EQ(r.records[0].time_ns, 1'704'067'200'000'000'001);
        EXPECT_EQ(r.records[1].time_ns, 1'704'067'200'000'500'000);  // the line it starts on
        EXPECT_EQ(r.records[2].time_ns, 1'704'067'200'001'000'000);
        // Offsets count decoded bytes.
        EXPECT_EQ(r.records[0].offset, 0u);
        EXPECT_EQ(r.records[1].offset, 6u);
        EXPECT_EQ(r.records[2].offset, 19u);
        EXPECT_EQ(r.records[2].number, 3u);
    }
}

TEST(StreamSourceTest, HexTelegramStartingMidLineTakesThatLinesTime) {
    TempFile file("midline.txt");
    test::write_text_file(file.path,
                          "12:00:00.25 10 03 02 49 4E 16 68 07 07 68\n"
                          "12:00:00.75 83 82 7D 3E 3E F3 F1 E2 16 DC 02 02\n");
    ReadResult r = read_all(file.path, InputFormat::Hex);
    ASSERT_EQ(r.records.size(), 3u);
    const std::int64_t first = (12 * 3600) * 1'000'000'000LL + 250'000'000;
    const std::int64_t second = (12 * 3600) * 1'000'000'000LL + 750'000'000;
    EXPECT_EQ(r.data[1], kSd2);
    EXPECT_EQ(r.records[0].time_ns, first);
    EXPECT_EQ(r.records[1].time_ns, first);
    EXPECT_EQ(r.data[2], kToken);
    EXPECT_EQ(r.records[2].time_ns, second);
}

TEST(StreamSourceTest, HexWithoutTimestampsHasNoTime) {
    TempFile file("plain.txt");
    test::write_text_file(file.path, "10 03 02 49 4E 16\nTX: DC 02 02\n");
    ReadResult r = read_all(file.path, InputFormat::Auto);
    EXPECT_EQ(r.format, InputFormat::Hex);
    ASSERT_EQ(r.records.size(), 2u);
    EXPECT_EQ(r.records[0].time_ns, kNoTime);
    EXPECT_EQ(r.records[1].time_ns, kNoTime);
}

TEST(StreamSourceTest, HexSkippedBytesNameTheLine) {
    TempFile file("noise.txt");
    test::write_text_file(file.path,
                          "10 03 02 49 4E 16\n"
                          "# noise follows\n"
                          "01 02 03\n"
                          "DC 02 02\n");
    ReadResult r = read_all(file.path, InputFormat::Hex);
    ASSERT_EQ(r.records.size(), 2u);
    EXPECT_EQ(r.data[1], kToken);
    EXPECT_EQ(r.skipped, 3u);
    ASSERT_EQ(r.issues.size(), 1u);
    EXPECT_EQ(r.issues[0].severity, Severity::Warning);
    EXPECT_EQ(r.issues[0].message, file.path +
                                       ": line 3 (byte 6 of the decoded stream): skipped 3 "
                                       "bytes: no start delimiter");
}

TEST(StreamSourceTest, HexTruncatedTelegramAtTheEnd) {
    TempFile file("cut.txt");
    test::write_text_file(file.path, "10 03 02 49 4E 16\n68 07 07 68 83 82\n");
    ReadResult r = read_all(file.path, InputFormat::Hex);
    ASSERT_EQ(r.records.size(), 1u);
    EXPECT_EQ(r.status, InputStatus::Ok);
    ASSERT_EQ(r.issues.size(), 1u);
    EXPECT_EQ(r.issues[0].message, file.path +
                                       ": line 2 (byte 6 of the decoded stream): skipped 6 "
                                       "bytes: telegram cut off (gap or end of input)");
}

TEST(StreamSourceTest, HexCorruptedLinesAreIgnored) {
    TempFile file("corrupt.txt");
    // Lines whose tokens are not bytes contribute nothing, so the telegram still frames.
    test::write_text_file(file.path, "10 03 02\nzz yy xx\n49 4E 16\n");
    ReadResult r = read_all(file.path, InputFormat::Hex);
    ASSERT_EQ(r.records.size(), 1u);
    EXPECT_EQ(r.data[0], kSd1);
    EXPECT_TRUE(r.issues.empty());
}

TEST(StreamSourceTest, HexTypoIsNamedAndTheRestStillDecodes) {
    TempFile file("typo.txt");
    test::write_text_file(file.path,
                          "10 03 02 49 4E 16\n"
                          "68 07 07 68 83 0G 7D 3E 3E F3 F1 E2 16\n"
                          "DC 02 02\n");
    ReadResult r = read_all(file.path, InputFormat::Auto);
    ASSERT_EQ(r.records.size(), 2u);
    EXPECT_EQ(r.data[0], kSd1);
    EXPECT_EQ(r.data[1], kToken);
    ASSERT_GE(r.issues.size(), 1u);
    EXPECT_EQ(r.issues[0].kind, IssueKind::HexSyntax);
    EXPECT_EQ(r.issues[0].message,
              file.path +
                  ": line 2, column 16: '0G' is not a hex byte ('G' is no hex digit); "
                  "the bytes before and after it are framed apart");
    // Then the pieces of the telegram that could not be framed.
    for (std::size_t i = 1; i < r.issues.size(); ++i)
        EXPECT_EQ(r.issues[i].kind, IssueKind::SkippedBytes) << r.issues[i].message;
}

TEST(StreamSourceTest, HexBadLinesAreCapped) {
    TempFile file("typos.txt");
    std::string text;
    for (int i = 0; i < 25; ++i)
        text += "10 03 02 49 4E 16\n10 0G\n";
    test::write_text_file(file.path, text);
    ReadResult r = read_all(file.path, InputFormat::Hex);
    EXPECT_EQ(r.records.size(), 25u);
    std::size_t hex_syntax = 0;
    for (const InputIssue& issue : r.issues)
        if (issue.kind == IssueKind::HexSyntax) ++hex_syntax;
    EXPECT_EQ(hex_syntax, kMaxIssuesShown);
    bool summed_up = false;
    for (const InputIssue& issue : r.issues)
        if (issue.message == file.path +
                                 ": 15 more lines with tokens that are no hex bytes not "
                                 "shown")
            summed_up = true;
    EXPECT_TRUE(summed_up);
}

// The dumps of samples/serial.raw made with `xxd` and `hexdump -C` (samples/serial.xxd,
// samples/serial.hexdump) decode to the same telegrams as the raw file.
TEST(StreamSourceTest, XxdAndHexdumpOfTheSerialSampleEqualTheRawFile) {
    ReadResult raw = read_all(test::source_dir() + "/samples/serial.raw", InputFormat::Auto);
    ASSERT_GT(raw.records.size(), 10u);
    for (const char* dump : {"/samples/serial.xxd", "/samples/serial.hexdump"}) {
        SCOPED_TRACE(dump);
        ReadResult r = read_all(test::source_dir() + dump, InputFormat::Auto);
        EXPECT_EQ(r.format, InputFormat::Hex);
        EXPECT_EQ(r.status, InputStatus::Ok);
        EXPECT_EQ(r.data, raw.data);
        ASSERT_EQ(r.records.size(), raw.records.size());
        for (std::size_t i = 0; i < r.records.size(); ++i)
            EXPECT_EQ(r.records[i].offset, raw.records[i].offset);
        EXPECT_EQ(r.skipped, raw.skipped);
    }
}

TEST(StreamSourceTest, DumpRepeatMarkerStandsForTheLeftOutLines) {
    // hexdump -C of kSd1, 40 zero bytes, kSd1: the zero lines are shown once, then "*".
    std::vector<std::uint8_t> raw = concat({kSd1, std::vector<std::uint8_t>(42, 0), kSd1});
    TempFile file("repeat.hd");
    test::write_text_file(
        file.path,
        "00000000  10 03 02 49 4e 16 00 00  00 00 00 00 00 00 00 00  |...IN...........|\n"
        "00000010  00 00 00 00 00 00 00 00  00 00 00 00 00 00 00 00  |................|\n"
        "*\n"
        "00000030  10 03 02 49 4e 16                                 |...IN.|\n"
        "00000036\n");
    ReadResult r = read_all(file.path, InputFormat::Hex);
    ASSERT_EQ(r.records.size(), 2u);
    EXPECT_EQ(r.records[1].offset, 48u);
    EXPECT_EQ(r.skipped, 42u);
    // Without the "*", the offset jump is named.
    test::write_text_file(
        file.path,
        "00000000  10 03 02 49 4e 16 00 00  00 00 00 00 00 00 00 00  |...IN...........|\n"
        "00000030  10 03 02 49 4e 16                                 |...IN.|\n");
    r = read_all(file.path, InputFormat::Hex);
    ASSERT_EQ(r.records.size(), 2u);
    bool named = false;
    for (const InputIssue& issue : r.issues)
        named |= issue.message.find(
                     ": line 2: the dump's offset is 0x30, but 0x10 bytes came "
                     "before it; lines are missing") != std::string::npos;
    EXPECT_TRUE(named);
}

// Found by fuzz_capture_file (fuzz/corpus/fuzz_capture_file/regression-hexdump-star-1 and -2:
// 1 KiB dumps whose "*" lines stand for 60 MiB): a "*" was framed whole before its first telegram
// was handed out, so every telegram it stood for was held in memory at once (3.6 M telegrams,
// 1.5 GB). Now it is framed 64 KiB at a time: at most one chunk's telegrams wait.
TEST(StreamSourceTest, DumpRepeatIsFramedAChunkAtATime) {
    // Lines of two SD1 telegrams and four short acknowledgements; the "*" stands for 1 MiB.
    TempFile file("long-repeat.hd");
    const std::string line =
        "  10 03 02 49 4e 16 10 03  02 49 4e 16 e5 e5 e5 e5  |...IN...IN.....|\n";
    test::write_text_file(file.path, "00000000" + line + "*\n00100000" + line + "00100010\n");
    OpenResult opened = open_source(file.path, InputFormat::Hex, profibus_protocol());
    ASSERT_TRUE(opened) << opened.error();
    auto* source = dynamic_cast<FramedSource*>(opened.value().get());
    ASSERT_NE(source, nullptr);
    constexpr std::uint64_t kStarts[] = {0, 6, 12, 13, 14, 15};  // in each 16-byte line
    Record record;
    std::uint64_t n = 0;
    std::size_t most_waiting = 0;
    bool offsets_ok = true;
    while (source->next(record)) {
        offsets_ok &= record.offset == (n / 6) * 16 + kStarts[n % 6];
        most_waiting = std::max(most_waiting, source->telegrams_waiting());
        ++n;
    }
    EXPECT_TRUE(offsets_ok);
    EXPECT_EQ(n, 6u * (0x100000 / 16 + 1));
    EXPECT_EQ(source->bytes_skipped(), 0u);
    EXPECT_EQ(source->status(), InputStatus::Ok);
    EXPECT_LE(most_waiting, 6u * (64 * 1024 / 16));  // one chunk of lines
}

// What fuzz_capture_file took for a defect (fuzz/corpus/fuzz_capture_file/regression-hexdump-
// star-fc-1 and -2, FC telegrams): a telegram framed from a dump's "*" longer than the dump
// itself. That is right, the dumped file held it; the target's invariant was wrong and now allows
// it. Shown here with a PROFIBUS telegram of the longest kind.
TEST(StreamSourceTest, DumpRepeatMakesATelegramLongerThanTheDump) {
    // An SD2 telegram with LE 249 and zero data (FCS 0): 255 bytes from a dump of fewer.
    TempFile file("long-telegram.hd");
    const std::string dump =
        "00000000  68 f9 f9 68 00 00 00 00  00 00 00 00 00 00 00 00  |h..h............|\n"
        "00000010  00 00 00 00 00 00 00 00  00 00 00 00 00 00 00 00  |................|\n"
        "*\n"
        "000000f0  00 00 00 00 00 00 00 00  00 00 00 00 00 00 16     |...............|\n";
    test::write_text_file(file.path, dump);
    ReadResult r = read_all(file.path, InputFormat::Hex);
    ASSERT_EQ(r.records.size(), 1u);
    EXPECT_EQ(r.data[0].size(), 255u);
    EXPECT_GT(r.data[0].size(), dump.size());
    EXPECT_EQ(r.skipped, 0u);
    EXPECT_EQ(r.status, InputStatus::Ok);
}

TEST(StreamSourceTest, DumpRepeatLongerThanTheLimitIsNamed) {
    // The "*" stands for 0x20 bytes: the lines 0x10 and 0x20, each a telegram as the first.
    TempFile file("repeat-limit.hd");
    test::write_text_file(
        file.path,
        "00000000  10 03 02 49 4e 16 00 00  00 00 00 00 00 00 00 00  |...IN...........|\n"
        "*\n"
        "00000030  10 03 02 49 4e 16                                 |...IN.|\n");
    for (std::uint64_t limit : {std::uint64_t{0x20}, std::uint64_t{0x1f}}) {
        SCOPED_TRACE(limit);
        SourceOptions options;
        options.max_hex_repeat_bytes = limit;
        OpenResult opened =
            open_source(file.path, InputFormat::Hex, profibus_protocol(), options);
        ASSERT_TRUE(opened) << opened.error();
        ReadResult r = drain(*opened.value());
        bool named = false;
        for (const InputIssue& issue : r.issues)
            named |= issue.message == file.path +
                                          ": line 3: the dump's offset is 0x30, but 0x10 bytes "
                                          "came before it (counting the lines \"*\" stands "
                                          "for); lines are missing or out of order";
        if (limit == 0x20) {
            ASSERT_EQ(r.records.size(), 4u);
            EXPECT_EQ(r.records[3].offset, 0x30u);
            EXPECT_FALSE(named);
        } else {
            ASSERT_EQ(r.records.size(), 2u);
            EXPECT_EQ(r.records[1].offset, 0x10u);  // the repeats are left out
            EXPECT_TRUE(named);
        }
    }
}

TEST(StreamSourceTest, EmptyHexFile) {
    TempFile file("empty.txt");
    test::write_text_file(file.path, "# nothing captured\n");
    ReadResult r = read_all(file.path, InputFormat::Hex);
    EXPECT_TRUE(r.records.empty());
    EXPECT_TRUE(r.issues.empty());
    EXPECT_EQ(r.status, InputStatus::Ok);
}

TEST(StreamSourceTest, SampleTerminalLog) {
    ReadResult r = read_all(test::source_dir() + "/samples/terminal.log", InputFormat::Auto);
    EXPECT_EQ(r.format, InputFormat::Hex);
    EXPECT_TRUE(r.issues.empty());
    EXPECT_EQ(r.skipped, 0u);
    ASSERT_GT(r.records.size(), 30u);
    std::int64_t previous = 0;
    for (const Record& record : r.records) {
        ASSERT_NE(record.time_ns, kNoTime) << record.number;
        EXPECT_GT(record.time_ns, previous) << record.number;
        previous = record.time_ns;
    }
    EXPECT_EQ(r.records[0].time_ns / 1'000'000'000, 1'704'067'200);
}

TEST(StreamSourceTest, SampleSerialDump) {
    ReadResult r = read_all(test::source_dir() + "/samples/serial.raw", InputFormat::Auto);
    EXPECT_EQ(r.format, InputFormat::Raw);
    EXPECT_EQ(r.status, InputStatus::Ok);
    // Two garbage injections, each reported once with its offset.
    ASSERT_EQ(r.issues.size(), 2u);
    for (const InputIssue& issue : r.issues)
        EXPECT_NE(issue.message.find("serial.raw: byte offset "), std::string::npos)
            << issue.message;
    EXPECT_GT(r.skipped, 0u);
}

TEST(StreamSourceTest, HexFromStandardInputIsDecodedLineByLine) {
    // `dpscope hex` reads a hex log from standard input "one line at a time": a telegram typed
    // on a line must come out before the input ends. Standard input is a pipe kept open here.
    int fds[2];
    ASSERT_EQ(pipe(fds), 0);
    int saved = dup(STDIN_FILENO);
    ASSERT_GE(saved, 0);
    ASSERT_EQ(dup2(fds[0], STDIN_FILENO), STDIN_FILENO);
    close(fds[0]);
    clearerr(stdin);
    const std::string line = "12:00:00.5 TX: 10 03 02 49 4E 16\n";
    ASSERT_EQ(write(fds[1], line.data(), line.size()), static_cast<ssize_t>(line.size()));

    std::promise<std::vector<std::uint8_t>> first;
    std::future<std::vector<std::uint8_t>> first_telegram = first.get_future();
    std::thread reader([&first] {
        OpenResult opened = open_source("-", InputFormat::Hex, profibus_protocol());
        std::vector<std::uint8_t> bytes;
        Record record;
        if (opened && opened.value()->next(record))
            bytes.assign(record.bytes.begin(), record.bytes.end());
        first.set_value(bytes);
        while (opened && opened.value()->next(record)) {
        }
    });
    // Its line came long before the input ends (the patience only bounds a reader that would
    // wait for the end: then it is not ready).
    bool in_time = first_telegram.wait_for(std::chrono::duration<double>(test::kPatienceSeconds)) ==
                   std::future_status::ready;
    close(fds[1]);  // the end of the input releases the reader either way
    reader.join();
    dup2(saved, STDIN_FILENO);
    close(saved);
    clearerr(stdin);

    EXPECT_EQ(first_telegram.get(), kSd1);
    EXPECT_TRUE(in_time) << "a telegram on a line of standard input was handed out only when the "
                            "input ended";
}

// ---- memory ----------------------------------------------------------------------------------

TEST(StreamSourceTest, MemorySourceFramesBytes) {
    std::vector<std::uint8_t> bytes = concat({kSd1, hex("00 01"), kAck});
    auto source =
        memory_source("<command line>", Bytes(bytes.data(), bytes.size()), profibus_protocol());
    ASSERT_TRUE(source);
    EXPECT_EQ(source->name(), "<command line>");
    ReadResult r = drain(*source);
    ASSERT_EQ(r.records.size(), 2u);
    EXPECT_EQ(r.data[0], kSd1);
    EXPECT_EQ(r.data[1], kAck);
    EXPECT_EQ(r.records[1].offset, 8u);
    EXPECT_EQ(r.records[1].number, 2u);
    EXPECT_EQ(r.records[0].time_ns, kNoTime);
    ASSERT_EQ(r.issues.size(), 1u);
    EXPECT_EQ(r.issues[0].message, "<command line>: byte 6: skipped 2 bytes: no start delimiter");
}

TEST(StreamSourceTest, MemorySourceCopiesItsBytes) {
    std::vector<std::uint8_t> bytes = kSd1;
    auto source = memory_source("mem", Bytes(bytes.data(), bytes.size()), profibus_protocol());
    bytes.assign(bytes.size(), 0x00);
    ReadResult r = drain(*source);
    ASSERT_EQ(r.records.size(), 1u);
    EXPECT_EQ(r.data[0], kSd1);
}

TEST(StreamSourceTest, MemorySourceTruncatedAndEmpty) {
    std::vector<std::uint8_t> cut = hex("68 07 07 68 83");
    ReadResult r =
        drain(*memory_source("mem", Bytes(cut.data(), cut.size()), profibus_protocol()));
    EXPECT_TRUE(r.records.empty());
    EXPECT_EQ(r.skipped, 5u);
    ASSERT_EQ(r.issues.size(), 1u);
    EXPECT_EQ(r.issues[0].message,
              "mem: byte 0: skipped 5 bytes: telegram cut off (gap or end of input)");
    ReadResult empty = drain(*memory_source("mem", Bytes(), profibus_protocol()));
    EXPECT_TRUE(empty.records.empty());
    EXPECT_TRUE(empty.issues.empty());
}

// ---- judging detected inputs, capped warnings, stopping at a count, times --------------------

TEST(StreamSourceTest, RandomBytesDetectedAsRawAreNoProfibusStream) {
    TempFile file("random.bin");
    test::write_file(file.path, random_bytes(200'000));
    ReadResult r = read_all(file.path, InputFormat::Auto);
    EXPECT_EQ(r.format, InputFormat::Raw);
    EXPECT_EQ(r.status, InputStatus::Unusable);
    // Decided over the first 64 KiB, before anything is handed out or warned about.
    EXPECT_TRUE(r.records.empty());
    EXPECT_TRUE(r.issues.empty());
    OpenResult opened = open_source(file.path, InputFormat::Auto, profibus_protocol());
    ASSERT_TRUE(opened);
    Record record;
    EXPECT_FALSE(opened.value()->next(record));
    const std::string& reason = opened.value()->unusable_reason();
    EXPECT_NE(reason.find(file.path + ": not a PROFIBUS byte stream: "), std::string::npos)
        << reason;
    EXPECT_NE(reason.find("of its first 65536 bytes (9"), std::string::npos) << reason;
    EXPECT_NE(reason.find(" %) form no telegram; --input-format raw decodes it anyway"),
              std::string::npos)
        << reason;
}

TEST(StreamSourceTest, RandomBytesForcedRawAreDecodedWithCappedWarnings) {
    TempFile file("random.raw");
    test::write_file(file.path, random_bytes(200'000));
    ReadResult r = read_all(file.path, InputFormat::Raw);
    EXPECT_EQ(r.status, InputStatus::Ok);
    EXPECT_GT(r.records.size(), 100u);
    // The first kMaxIssuesShown runs of skipped bytes, then one message for the rest.
    ASSERT_EQ(r.issues.size(), kMaxIssuesShown + 1);
    std::uint64_t shown = 0;
    for (std::size_t i = 0; i < kMaxIssuesShown; ++i) {
        EXPECT_EQ(r.issues[i].kind, IssueKind::SkippedBytes);
        std::size_t at = r.issues[i].message.find("skipped ");
        ASSERT_NE(at, std::string::npos);
        shown += std::stoull(r.issues[i].message.substr(at + 8));
    }
    const std::string& last = r.issues.back().message;
    EXPECT_NE(last.find(file.path + ": "), std::string::npos) << last;
    EXPECT_NE(last.find(" more runs of skipped bytes not shown (" +
                        std::to_string(r.skipped - shown) + " bytes)"),
              std::string::npos)
        << last;
    EXPECT_GT(r.skipped, 190'000u);
}

TEST(StreamSourceTest, DumpWithSomeGarbageIsStillAProfibusStream) {
    // 40 % of the bytes are garbage between telegrams: decoded, with warnings.
    std::vector<std::uint8_t> bytes;
    std::vector<std::uint8_t> noise = random_bytes(100'000, 3);
    std::size_t used = 0;
    while (bytes.size() < 100'000) {
        bytes.insert(bytes.end(), kSd2.begin(), kSd2.end());
        bytes.insert(bytes.end(), kSd1.begin(), kSd1.end());
        for (int i = 0; i < 12; ++i, ++used)
            bytes.push_back(static_cast<std::uint8_t>(noise[used] & 0x0F));  // no start delimiter
    }
    TempFile file("noisy.raw");
    test::write_file(file.path, bytes);
    ReadResult r = read_all(file.path, InputFormat::Auto);
    EXPECT_EQ(r.status, InputStatus::Ok);
    EXPECT_GT(r.records.size(), 5000u);
}

TEST(StreamSourceTest, ShortInputIsJudgedWholeFromMinimumSize) {
    // 600 bytes, 2 telegrams: judged over all of it.
    std::vector<std::uint8_t> noise(600 - kSd1.size() - kSd2.size(), 0x01);
    TempFile file("short.raw");
    test::write_file(file.path, concat({kSd1, noise, kSd2}));
    OpenResult opened = open_source(file.path, InputFormat::Auto, profibus_protocol());
    ASSERT_TRUE(opened);
    ReadResult r = drain(*opened.value());
    EXPECT_EQ(r.status, InputStatus::Unusable);
    EXPECT_NE(opened.value()->unusable_reason().find("581 of its 600 bytes (96.8 %)"),
              std::string::npos)
        << opened.value()->unusable_reason();
    // Below kMinJudgedBytes there is no verdict.
    noise.resize(FramedSource::kMinJudgedBytes - 1 - kSd1.size() - kSd2.size());
    test::write_file(file.path, concat({kSd1, noise, kSd2}));
    r = read_all(file.path, InputFormat::Auto);
    EXPECT_EQ(r.status, InputStatus::Ok);
    EXPECT_EQ(r.records.size(), 2u);
}

TEST(StreamSourceTest, HexLogMostlySkippedIsNoProfibusLogUnlessForced) {
    std::string text;
    for (int i = 0; i < 200; ++i)
        text += "12 34 56 78 9A BC DE F0 11 22 33 44\n";
    text += "10 03 02 49 4E 16\n";
    TempFile file("numbers.txt");
    test::write_text_file(file.path, text);
    OpenResult opened = open_source(file.path, InputFormat::Auto, profibus_protocol());
    ASSERT_TRUE(opened);
    ReadResult r = drain(*opened.value());
    EXPECT_EQ(r.status, InputStatus::Unusable);
    EXPECT_NE(opened.value()->unusable_reason().find(": not a PROFIBUS hex log: "),
              std::string::npos);
    EXPECT_NE(opened.value()->unusable_reason().find("--input-format hex decodes it anyway"),
              std::string::npos);
    r = read_all(file.path, InputFormat::Hex);
    EXPECT_EQ(r.status, InputStatus::Ok);
    EXPECT_EQ(r.records.size(), 1u);
}

TEST(StreamSourceTest, StopAfterReportsNothingPastTheLastTelegram) {
    TempFile file("count.raw");
    test::write_file(file.path,
                     concat({kSd1, hex("01 02"), kSd2, hex("03 04 05"), kToken, hex("06"), kAck}));
    OpenResult opened = open_source(file.path, InputFormat::Raw, profibus_protocol());
    ASSERT_TRUE(opened);
    opened.value()->stop_after(2);
    ReadResult r = drain(*opened.value());
    ASSERT_EQ(r.records.size(), 2u);
    EXPECT_EQ(r.data[1], kSd2);
    ASSERT_EQ(r.issues.size(), 1u);  // the two bytes before the second telegram only
    EXPECT_NE(r.issues[0].message.find("byte offset 6: skipped 2 bytes"), std::string::npos)
        << r.issues[0].message;
    EXPECT_EQ(r.skipped, 2u);
    Record record;
    EXPECT_FALSE(opened.value()->next(record));  // and stays stopped
}

TEST(StreamSourceTest, HexLogWithAByteOrderMarkKeepsItsFirstTimestamp) {
    // Issue #27 point 5: the BOM was glued to the first line's timestamp, which was lost.
    TempFile file("bom.txt");
    test::write_text_file(file.path,
                          "\xEF\xBB\xBF"
                          "1704067200.000000001 10 03 02 49 4E 16\n"
                          "Log \xC2\xB5s \xB5 \xE2\x80\x94 1704067200.5 (comment)\n"
                          "1704067200.000500000 DC 02 02\n");
    for (InputFormat format : {InputFormat::Hex, InputFormat::Auto}) {
        SCOPED_TRACE(input_format_name(format));
        ReadResult r = read_all(file.path, format);
        EXPECT_EQ(r.format, InputFormat::Hex);
        EXPECT_TRUE(r.issues.empty());
        ASSERT_EQ(r.records.size(), 2u);
        EXPECT_EQ(r.data[0], kSd1);
        EXPECT_EQ(r.records[0].time_ns, 1'704'067'200'000'000'001);
        EXPECT_EQ(r.data[1], kToken);
        EXPECT_EQ(r.records[1].time_ns, 1'704'067'200'000'500'000);
    }
}

TEST(StreamSourceTest, TextReadAsARawStreamSaysWhichInputFormatToTry) {
    // A hex log with colour escapes is detected as a raw stream (ESC is a control byte) and
    // refused; the message says it looks like text and names the input formats for text.
    std::string text;
    for (int i = 0; i < 40; ++i)
        text += "\x1B[32m12:00:01.5 10 03 02 49 4E 16\x1B[0m\n";
    TempFile file("colour.log");
    test::write_text_file(file.path, text);
    OpenResult opened = open_source(file.path, InputFormat::Auto, profibus_protocol());
    ASSERT_TRUE(opened);
    ReadResult r = drain(*opened.value());
    EXPECT_EQ(r.status, InputStatus::Unusable);
    const std::string& reason = opened.value()->unusable_reason();
    EXPECT_NE(reason.find("not a PROFIBUS byte stream"), std::string::npos) << reason;
    EXPECT_NE(reason.find("it looks like text: --input-format hex reads a log of hex bytes, "
                          "--input-format text a log of VLT 2000 telegrams"),
              std::string::npos)
        << reason;
    // A short one is not judged; reading no telegram, the command line says the same.
    test::write_text_file(file.path, "\x1B[32mhello, this is no capture\x1B[0m\n");
    test::CommandResult cli = test::run_dpscope({"decode", file.path});
    EXPECT_EQ(cli.exit_code, 2);
    EXPECT_NE(cli.err.find("read as a raw byte stream; is it a capture? It looks like text: "
                           "--input-format hex reads a log of hex bytes, --input-format text a "
                           "log of VLT 2000 telegrams"),
              std::string::npos)
        << cli.err;
    // A real raw stream gets no such hint.
    test::write_file(file.path, random_bytes(300));
    cli = test::run_dpscope({"decode", "--input-format", "raw", file.path});
    EXPECT_EQ(cli.err.find("looks like text"), std::string::npos) << cli.err;
}

TEST(StreamSourceTest, ALongRunWithoutATelegramIsNotedAsItGrows) {
    // Issue #27 point 23: a forced raw (or hex) reading of zeros ran silently until stopped. A run
    // of skipped bytes still going on is noted at 1 MiB, 2, 4 ... MiB; the run itself is
    // reported where it ends, as always.
    TempFile file("zeros");
    test::write_file(file.path, concat({std::vector<std::uint8_t>((5u << 20) + 100, 0), kSd1}));
    ReadResult raw = read_all(file.path, InputFormat::Raw);
    ASSERT_EQ(raw.records.size(), 1u);
    ASSERT_EQ(raw.issues.size(), 4u);
    EXPECT_EQ(raw.issues[0].message, file.path +
                                         ": byte offset 0: 1 MiB read so far without a PROFIBUS "
                                         "telegram; still reading (the run of skipped bytes is "
                                         "reported where it ends)");
    EXPECT_NE(raw.issues[1].message.find("byte offset 0: 2 MiB read so far"), std::string::npos);
    EXPECT_NE(raw.issues[2].message.find("byte offset 0: 4 MiB read so far"), std::string::npos);
    EXPECT_EQ(raw.issues[3].message,
              file.path + ": byte offset 0: skipped 5242980 bytes: no start delimiter");
    // A hex reading of the same file: one line without a hex byte.
    ReadResult hex_read = read_all(file.path, InputFormat::Hex);
    ASSERT_EQ(hex_read.issues.size(), 3u);
    EXPECT_EQ(hex_read.issues[0].message,
              file.path + ": line 1: 1 MiB of text read so far without a hex byte; still reading");
    EXPECT_NE(hex_read.issues[2].message.find("line 1: 4 MiB of text"), std::string::npos);
}

TEST(StreamSourceTest, ALongRunIsNotedOnTheCommandLineAtDoublingSizes) {
    // Issue #27 point 23: `decode --input-format raw` on 20 MiB of zeros between two telegrams
    // notes the run at 1, 2, 4, 8 and 16 MiB, naming where it starts (byte 6, after the first
    // telegram), and reports the run where it ends.
    TempFile file("zeros20");
    const std::size_t run = 20u << 20;
    test::write_file(file.path, concat({kSd1, std::vector<std::uint8_t>(run, 0), kSd1}));
    test::CommandResult r =
        test::run_dpscope({"decode", "--input-format", "raw", "-T", "jsonl", file.path});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(test::lines_of(r.out).size(), 2u) << r.out;
    std::vector<std::string> expected;
    for (int mib : {1, 2, 4, 8, 16})
        expected.push_back(
            fmt::format("dpscope: warning: {}: byte offset 6: {} MiB read so far "
                        "without a PROFIBUS telegram; still reading (the run of "
                        "skipped bytes is reported where it ends)",
                        file.path, mib));
    expected.push_back(
        fmt::format("dpscope: warning: {}: byte offset 6: skipped {} bytes: no start delimiter",
                    file.path, run));
    EXPECT_EQ(test::lines_of(r.err), expected) << r.err;
    // With -c 1 the first telegram ends the reading: the run after it is never read, so never
    // noted. With -c 2 the whole run is read, and noted the same way.
    r = test::run_dpscope({"decode", "--input-format", "raw", "-c", "1", "-q", file.path});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err.find("read so far"), std::string::npos) << r.err;
    r = test::run_dpscope({"decode", "--input-format", "raw", "-c", "2", "-T", "jsonl", file.path});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(test::lines_of(r.err), expected) << r.err;
}

TEST(StreamSourceTest, ALongStretchOfTextWithoutATelegramIsNoted) {
    // Issue #27 point 23: a text (VLT 2000) log, or a forced text reading of a binary file, of
    // megabytes without a telegram was read in silence. Noted at 1, 2 ... MiB of characters
    // after the last telegram, naming the line reached and the line the stretch started on.
    TempFile file("stretch.log");
    std::string text = "<01UOGD@0516+00080007>\n";
    const std::string filler(63, 'x');
    for (int i = 0; i < 3 * 16384; ++i)  // 3 MiB of lines of 64 characters
        text += filler + "\n";
    text += "<01UGHK@0516+00080007>\n";
    test::write_text_file(file.path, text);
    OpenResult opened = open_source(file.path, InputFormat::Text, vlt2000_protocol());
    ASSERT_TRUE(opened) << opened.error();
    ReadResult read = drain(*opened.value());
    EXPECT_EQ(read.records.size(), 2u);
    std::vector<std::string> messages;
    for (const InputIssue& issue : read.issues)
        messages.push_back(issue.message);
    // The stretch counts the first line's end: its 1 MiB-th character is the last x of line
    // 16385, its 2 MiB-th the last x of line 32769.
    EXPECT_EQ(messages,
              (std::vector<std::string>{
                  file.path + ": line 16385: 1 MiB of text read since line 1 without a VLT 2000 "
                              "telegram; still reading",
                  file.path + ": line 32769: 2 MiB of text read since line 1 without a VLT 2000 "
                              "telegram; still reading"}));
}

// ---- bounded memory (issue #27 point 2) ----------------------------------------------------

// What a source may hold in memory at any time, whatever the input: a few read buffers and what
// one of them frames.
constexpr std::size_t kMostBufferedBytes = 1 << 20;

struct BufferedRead {
    std::size_t records = 0;
    std::size_t most_buffered = 0;
    std::vector<InputIssue> issues;
};

// Reads `path` to its end (or `limit` telegrams), noting the most memory the source held.
BufferedRead read_buffered(const std::string& path, InputFormat format,
                           const ProtocolDescriptor& protocol = profibus_protocol(),
                           std::size_t limit = 0) {
    BufferedRead result;
    OpenResult opened = open_source(path, format, protocol);
    EXPECT_TRUE(opened) << opened.error();
    if (!opened) return result;
    TelegramSource& source = *opened.value();
    source.on_issue([&](const InputIssue& issue) {
        result.issues.push_back(issue);
        result.most_buffered = std::max(result.most_buffered, source.buffered_bytes());
    });
    source.stop_after(limit);
    Record record;
    while (source.next(record)) {
        ++result.records;
        result.most_buffered = std::max(result.most_buffered, source.buffered_bytes());
    }
    result.most_buffered = std::max(result.most_buffered, source.buffered_bytes());
    return result;
}

constexpr std::size_t kTenMegabytes = 10'000'000;

TEST(StreamSourceTest, HexLogOfOneLongLineIsReadInBoundedMemory) {
    // A 10 MB hex log written as one line (a terminal program that logs without line breaks).
    const std::string telegram = "68 07 07 68 83 82 7D 3E 3E F3 F1 E2 16 ";
    std::string text = "12:00:00.5 ";
    std::size_t count = 0;
    while (text.size() < kTenMegabytes) {
        text += telegram;
        ++count;
    }
    text += "\n";
    TempFile file("one-line.txt");
    test::write_text_file(file.path, text);
    for (InputFormat format : {InputFormat::Hex, InputFormat::Auto}) {
        SCOPED_TRACE(input_format_name(format));
        BufferedRead r = read_buffered(file.path, format);
        EXPECT_EQ(r.records, count);
        EXPECT_TRUE(r.issues.empty());
        EXPECT_LE(r.most_buffered, kMostBufferedBytes);
    }
}

TEST(StreamSourceTest, CompactHexStringOfOneLongLineIsReadInBoundedMemory) {
    // The same as one compact hex string: a single token of 10 MB.
    std::string text;
    std::size_t count = 0;
    while (text.size() < kTenMegabytes) {
        text += "6807076883827D3E3EF3F1E216";
        ++count;
    }
    TempFile file("compact.txt");
    test::write_text_file(file.path, text + "\n");
    BufferedRead r = read_buffered(file.path, InputFormat::Hex);
    EXPECT_EQ(r.records, count);
    EXPECT_TRUE(r.issues.empty());
    EXPECT_LE(r.most_buffered, kMostBufferedBytes);
}

TEST(StreamSourceTest, ZerosReadAsHexAreReadInBoundedMemory) {
    // `decode --input-format hex /dev/zero`: one line without end that holds no hex byte.
    TempFile file("zeros.txt");
    test::write_file(file.path, std::vector<std::uint8_t>(kTenMegabytes, 0));
    BufferedRead r = read_buffered(file.path, InputFormat::Hex);
    EXPECT_EQ(r.records, 0u);
    EXPECT_LE(r.most_buffered, kMostBufferedBytes);
}

TEST(StreamSourceTest, RawZerosAreReadInBoundedMemory) {
    TempFile file("zeros.raw");
    test::write_file(file.path, std::vector<std::uint8_t>(kTenMegabytes, 0));
    BufferedRead r = read_buffered(file.path, InputFormat::Raw);
    EXPECT_EQ(r.records, 0u);
    EXPECT_LE(r.most_buffered, kMostBufferedBytes);
}

TEST(StreamSourceTest, HexLogOfManyBadLinesIsReadInBoundedMemory) {
    // Lines that each hold a bad compact string and no byte: nothing is framed, so a detected
    // log is judged only when enough lines are held back; they must not pile up unjudged.
    std::string text;
    while (text.size() < kTenMegabytes)
        text += "TX 68070G\n";
    TempFile file("bad-lines.txt");
    test::write_text_file(file.path, text);
    BufferedRead r = read_buffered(file.path, InputFormat::Auto);
    EXPECT_LE(r.most_buffered, kMostBufferedBytes);
}

TEST(StreamSourceTest, TimesGoingBackwardsOrJumpingAreReportedOncePerKind) {
    TempFile file("times.txt");
    test::write_text_file(file.path,
                          "1704067200.0 10 03 02 49 4E 16\n"
                          "1704067199.5 E5\n"    // 0.5 s back
                          "1704067199.0 E5\n"    // back again: counted
                          "1704067300.0 E5\n"    // 101 s forward
                          "1704067301.0 E5\n"    // 1 s: fine
                          "1704068000.0 E5\n");  // 699 s forward: counted
    ReadResult r = read_all(file.path, InputFormat::Hex);
    ASSERT_EQ(r.records.size(), 6u);
    ASSERT_EQ(r.issues.size(), 4u);
    EXPECT_EQ(r.issues[0].kind, IssueKind::TimeBackwards);
    EXPECT_NE(r.issues[0].message.find(file.path +
                                       ": frame 2: time goes backwards by 0.500 s from frame 1;"),
              std::string::npos)
        << r.issues[0].message;
    EXPECT_EQ(r.issues[1].kind, IssueKind::TimeJump);
    EXPECT_NE(r.issues[1].message.find(file.path +
                                       ": frame 4: time jumps forward by 101.000 s from frame 3"),
              std::string::npos)
        << r.issues[1].message;
    EXPECT_EQ(r.issues[2].message, file.path + ": time went backwards 1 more time");
    EXPECT_EQ(r.issues[3].message,
              file.path + ": time jumped forward by more than a minute 1 more time");
}

}  // namespace
}  // namespace dpscope
