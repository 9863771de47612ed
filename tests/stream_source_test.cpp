// Byte-stream sources: raw serial dumps and hex text logs through open_source, and bytes in
// memory. Telegrams are framed from the stream; skipped bytes are reported with their place.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <future>
#include <string>
#include <thread>
#include <vector>

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
    OpenResult opened = open_source(path, format);
    EXPECT_TRUE(opened.source) << opened.error;
    if (!opened.source) return {};
    return drain(*opened.source);
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
              file.path + ": byte offset 6: skipped 3 byte(s): no start delimiter");
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
                  ": byte offset 6: skipped 10 byte(s): telegram cut off (gap or end of "
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
                  ": byte offset 13: skipped 13 byte(s): LEr differs from LE (byte 2 of "
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
                                       "byte(s): no start delimiter");
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
                                       "byte(s): telegram cut off (gap or end of input)");
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
        OpenResult opened = open_source("-", InputFormat::Hex);
        std::vector<std::uint8_t> bytes;
        Record record;
        if (opened.source && opened.source->next(record))
            bytes.assign(record.bytes.begin(), record.bytes.end());
        first.set_value(bytes);
        while (opened.source && opened.source->next(record)) {
        }
    });
    bool in_time = first_telegram.wait_for(std::chrono::seconds(2)) == std::future_status::ready;
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
    auto source = memory_source("<command line>", Bytes(bytes.data(), bytes.size()));
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
    EXPECT_EQ(r.issues[0].message, "<command line>: byte 6: skipped 2 byte(s): no start delimiter");
}

TEST(StreamSourceTest, MemorySourceCopiesItsBytes) {
    std::vector<std::uint8_t> bytes = kSd1;
    auto source = memory_source("mem", Bytes(bytes.data(), bytes.size()));
    bytes.assign(bytes.size(), 0x00);
    ReadResult r = drain(*source);
    ASSERT_EQ(r.records.size(), 1u);
    EXPECT_EQ(r.data[0], kSd1);
}

TEST(StreamSourceTest, MemorySourceTruncatedAndEmpty) {
    std::vector<std::uint8_t> cut = hex("68 07 07 68 83");
    ReadResult r = drain(*memory_source("mem", Bytes(cut.data(), cut.size())));
    EXPECT_TRUE(r.records.empty());
    EXPECT_EQ(r.skipped, 5u);
    ASSERT_EQ(r.issues.size(), 1u);
    EXPECT_EQ(r.issues[0].message,
              "mem: byte 0: skipped 5 byte(s): telegram cut off (gap or end of input)");
    ReadResult empty = drain(*memory_source("mem", Bytes()));
    EXPECT_TRUE(empty.records.empty());
    EXPECT_TRUE(empty.issues.empty());
}

}  // namespace
}  // namespace dpscope
