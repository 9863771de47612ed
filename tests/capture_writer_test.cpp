// Capture writers: pcap, pcapng, raw and hex files read back through open_source give the same
// bytes, nanosecond timestamps and link type; failures name the file.
#include "capture/capture_writer.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <string>
#include <vector>

#include "capture/pcap_source.hpp"
#include "capture/telegram_source.hpp"
#include "simulator/simulator.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::hex;

constexpr std::int64_t kT0 = 1'704'067'200'000'000'000;  // 2024-01-01T00:00:00Z

struct Telegram {
    std::vector<std::uint8_t> bytes;
    std::int64_t time_ns;
};

const std::vector<Telegram> kTelegrams = {
    {hex("10 03 02 49 4E 16"), kT0 + 1},
    {hex("68 07 07 68 83 82 7D 3E 3E F3 F1 E2 16"), kT0 + 123'456'789},
    {hex("E5"), kT0 + 999'999'999},
    {hex("E5"), kT0 + 30'000'000'000},  // no step of more than a minute (a capture problem)
    {hex("DC 02 02"), kT0 + 61'000'000'007},
};

struct TempFile {
    explicit TempFile(std::string_view name) : path(test::temp_path(name)) {}
    ~TempFile() { std::remove(path.c_str()); }
    std::string path;
};

void write_all(const std::string& path, CaptureFormat format, int link_type,
               const std::vector<Telegram>& telegrams) {
    WriterResult opened = open_capture_writer(path, format, link_type);
    ASSERT_TRUE(opened) << opened.error();
    EXPECT_TRUE(opened.error().empty());
    for (const Telegram& t : telegrams)
        ASSERT_TRUE(opened.value()->write(Bytes(t.bytes.data(), t.bytes.size()), t.time_ns));
    Result<void> flushed = opened.value()->flush();
    ASSERT_TRUE(flushed) << flushed.error();
    Result<void> closed = opened.value()->close();
    ASSERT_TRUE(closed) << closed.error();
    EXPECT_TRUE(closed.error().empty());
}

struct ReadBack {
    std::vector<Telegram> telegrams;
    InputFormat format = InputFormat::Auto;
    int link_type = -1;
    InputStatus status = InputStatus::Ok;
    std::size_t issues = 0;
};

ReadBack read_back(const std::string& path) {
    ReadBack result;
    OpenResult opened = open_source(path, InputFormat::Auto, profibus_protocol());
    EXPECT_TRUE(opened) << opened.error();
    if (!opened) return result;
    opened.value()->on_issue([&](const InputIssue&) { ++result.issues; });
    Record record;
    while (opened.value()->next(record))
        result.telegrams.push_back(
            {std::vector<std::uint8_t>(record.bytes.begin(), record.bytes.end()), record.time_ns});
    result.format = opened.value()->format();
    result.link_type = opened.value()->link_type();
    result.status = opened.value()->status();
    return result;
}

std::vector<std::string> lines_of_file(const std::string& path) {
    return test::lines_of(test::slurp(path));
}

void expect_same(const std::vector<Telegram>& got, const std::vector<Telegram>& want,
                 bool with_times) {
    ASSERT_EQ(got.size(), want.size());
    for (std::size_t i = 0; i < want.size(); ++i) {
        SCOPED_TRACE(i);
        EXPECT_EQ(got[i].bytes, want[i].bytes);
        EXPECT_EQ(got[i].time_ns, with_times ? want[i].time_ns : kNoTime);
    }
}

TEST(CaptureWriterTest, FormatNames) {
    EXPECT_EQ(capture_format_name(CaptureFormat::Pcap), "pcap");
    EXPECT_EQ(capture_format_name(CaptureFormat::Pcapng), "pcapng");
    EXPECT_EQ(capture_format_name(CaptureFormat::Raw), "raw");
    EXPECT_EQ(capture_format_name(CaptureFormat::Hex), "hex");
    for (CaptureFormat format :
         {CaptureFormat::Pcap, CaptureFormat::Pcapng, CaptureFormat::Raw, CaptureFormat::Hex})
        EXPECT_EQ(capture_format_from_name(capture_format_name(format)), format);
    EXPECT_FALSE(capture_format_from_name("auto").has_value());
    EXPECT_FALSE(capture_format_from_name("PCAP").has_value());
    EXPECT_FALSE(capture_format_from_name("").has_value());
}

TEST(CaptureWriterTest, PcapRoundTrip) {
    for (int link_type : {kLinkTypeProfibusDl, kLinkTypeUser0}) {
        SCOPED_TRACE(link_type);
        TempFile file("round.pcap");
        write_all(file.path, CaptureFormat::Pcap, link_type, kTelegrams);
        ReadBack r = read_back(file.path);
        EXPECT_EQ(r.format, InputFormat::Pcap);
        EXPECT_EQ(r.link_type, link_type);
        EXPECT_EQ(r.status, InputStatus::Ok);
        EXPECT_EQ(r.issues, 0u);
        expect_same(r.telegrams, kTelegrams, true);
    }
}

TEST(CaptureWriterTest, PcapUsesTheNanosecondMagic) {
    TempFile file("magic.pcap");
    write_all(file.path, CaptureFormat::Pcap, kLinkTypeProfibusDl, kTelegrams);
    std::vector<std::uint8_t> bytes = test::read_file(file.path);
    ASSERT_GE(bytes.size(), 24u);
    // Little-endian nanosecond magic 0xA1B23C4D, link type 257 in the last header word.
    EXPECT_EQ(std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + 4), hex("4D 3C B2 A1"));
    EXPECT_EQ(std::vector<std::uint8_t>(bytes.begin() + 20, bytes.begin() + 24),
              hex("01 01 00 00"));
    EXPECT_EQ(bytes.size(), 24u + 5 * 16 + 6 + 13 + 1 + 1 + 3);
}

TEST(CaptureWriterTest, PcapngRoundTrip) {
    for (int link_type : {kLinkTypeProfibusDl, kLinkTypeUser0}) {
        SCOPED_TRACE(link_type);
        TempFile file("round.pcapng");
        write_all(file.path, CaptureFormat::Pcapng, link_type, kTelegrams);
        ReadBack r = read_back(file.path);
        EXPECT_EQ(r.format, InputFormat::Pcapng);
        EXPECT_EQ(r.link_type, link_type);
        EXPECT_EQ(r.status, InputStatus::Ok);
        EXPECT_EQ(r.issues, 0u);
        expect_same(r.telegrams, kTelegrams, true);
    }
}

TEST(CaptureWriterTest, PcapngBlockLayout) {
    TempFile file("layout.pcapng");
    write_all(file.path, CaptureFormat::Pcapng, kLinkTypeProfibusDl, {kTelegrams[0]});
    std::vector<std::uint8_t> bytes = test::read_file(file.path);
    // Section header 28 + interface description 32 + one enhanced packet block 32 + 8.
    ASSERT_EQ(bytes.size(), 28u + 32 + 40);
    EXPECT_EQ(std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + 12),
              hex("0A 0D 0D 0A 1C 00 00 00 4D 3C 2B 1A"));
    EXPECT_EQ(std::vector<std::uint8_t>(bytes.begin() + 28, bytes.begin() + 36),
              hex("01 00 00 00 20 00 00 00"));
    EXPECT_EQ(bytes[36], 0x01);  // link type 257, little endian
    EXPECT_EQ(bytes[37], 0x01);
    EXPECT_EQ(std::vector<std::uint8_t>(bytes.begin() + 60, bytes.begin() + 68),
              hex("06 00 00 00 28 00 00 00"));
}

TEST(CaptureWriterTest, RawRoundTrip) {
    TempFile file("round.raw");
    write_all(file.path, CaptureFormat::Raw, kLinkTypeProfibusDl, kTelegrams);
    std::vector<std::uint8_t> expected;
    for (const Telegram& t : kTelegrams)
        expected.insert(expected.end(), t.bytes.begin(), t.bytes.end());
    EXPECT_EQ(test::read_file(file.path), expected);
    ReadBack r = read_back(file.path);
    EXPECT_EQ(r.format, InputFormat::Raw);
    EXPECT_EQ(r.link_type, 0);
    EXPECT_EQ(r.issues, 0u);
    expect_same(r.telegrams, kTelegrams, false);
}

TEST(CaptureWriterTest, HexRoundTrip) {
    TempFile file("round.txt");
    write_all(file.path, CaptureFormat::Hex, kLinkTypeProfibusDl, kTelegrams);
    ReadBack r = read_back(file.path);
    EXPECT_EQ(r.format, InputFormat::Hex);
    EXPECT_EQ(r.issues, 0u);
    expect_same(r.telegrams, kTelegrams, true);
}

TEST(CaptureWriterTest, HexLineFormat) {
    TempFile file("lines.txt");
    write_all(file.path, CaptureFormat::Hex, kLinkTypeProfibusDl,
              {kTelegrams[0], {hex("E5"), kNoTime}, {hex("DC 02 02"), kT0 + 61'000'000'007}});
    std::vector<std::uint8_t> bytes = test::read_file(file.path);
    EXPECT_EQ(std::string(bytes.begin(), bytes.end()),
              "# dpscope hex capture: bus=profibus, one record a line\n"
              "1704067200.000000001 10 03 02 49 4E 16\n"
              "E5\n"
              "1704067261.000000007 DC 02 02\n");
    ReadBack r = read_back(file.path);
    ASSERT_EQ(r.telegrams.size(), 3u);
    EXPECT_EQ(r.telegrams[1].time_ns, kNoTime);
    EXPECT_EQ(r.telegrams[2].time_ns, kT0 + 61'000'000'007);
}

TEST(CaptureWriterTest, HexCaptureIsReadBackOneRecordALineDamagedOrNot) {
    // Issue #27 point 4: a hex capture read back as a stream lost its damaged telegrams (the
    // framer skipped or split them) and renumbered every later frame. dpscope's hex capture is
    // read one record a line, whatever the bytes.
    const std::vector<Telegram> records = {
        {hex("10 03 02 49 4E 16"), kT0},
        {hex("68 07 08 68 83 82 7D 3E 3E F3 F1 E2 16"), kT0 + 1'000},  // LEr differs from LE
        {hex("01 02"), kNoTime},                                       // no telegram at all
        {hex("68 07 07 68 83 82 7D"), kT0 + 3'000},                    // cut short
        {hex("10 03 02 49 4E 16 DC 02 02"), kT0 + 4'000},              // two in one record
        {hex("DC 02 02"), kT0 + 5'000},
    };
    TempFile file("records.txt");
    write_all(file.path, CaptureFormat::Hex, kLinkTypeProfibusDl, records);
    ReadBack r = read_back(file.path);
    EXPECT_EQ(r.format, InputFormat::Hex);
    EXPECT_EQ(r.status, InputStatus::Ok);
    EXPECT_EQ(r.issues, 0u);
    expect_same(r.telegrams, records, true);
    // The same lines without the first line are a hand-made log: framed as a stream.
    std::string text = test::slurp(file.path);
    test::write_text_file(file.path, text.substr(text.find('\n') + 1));
    ReadBack stream = read_back(file.path);
    EXPECT_EQ(stream.telegrams.size(), 4u);  // the damaged ones are skipped, two are split
}

TEST(CaptureWriterTest, HexCaptureNamesItsBus) {
    TempFile file("fc.txt");
    WriterResult opened =
        open_capture_writer(file.path, CaptureFormat::Hex, kLinkTypeUser0, Protocol::Fc);
    ASSERT_TRUE(opened) << opened.error();
    const std::vector<std::uint8_t> telegram = test::fc_process(4);
    ASSERT_TRUE(opened.value()->write(Bytes(telegram.data(), telegram.size()), kT0));
    ASSERT_TRUE(opened.value()->close());
    EXPECT_EQ(lines_of_file(file.path).front(), "# dpscope hex capture: bus=fc, one record a line");
    BusChoice choice;
    OpenResult source = open_source(file.path, InputFormat::Auto, nullptr, choice);
    ASSERT_TRUE(source) << source.error();
    EXPECT_EQ(choice.protocol->protocol, Protocol::Fc);
    ASSERT_TRUE(choice.tagged.has_value());
    EXPECT_EQ(*choice.tagged, Protocol::Fc);
    EXPECT_FALSE(choice.say);  // the capture says it
}

TEST(CaptureWriterTest, UnknownTimeIsZeroInPcapAndReadsBackUnknown) {
    for (CaptureFormat format : {CaptureFormat::Pcap, CaptureFormat::Pcapng}) {
        SCOPED_TRACE(capture_format_name(format));
        TempFile file("notime.cap");
        write_all(file.path, format, kLinkTypeProfibusDl, {{hex("E5"), kNoTime}, {hex("E5"), kT0}});
        std::vector<std::uint8_t> bytes = test::read_file(file.path);
        if (format == CaptureFormat::Pcap) {
            // The first record header's seconds and fraction are 0.
            ASSERT_GE(bytes.size(), 32u);
            EXPECT_EQ(std::vector<std::uint8_t>(bytes.begin() + 24, bytes.begin() + 32),
                      std::vector<std::uint8_t>(8, 0));
        }
        ReadBack r = read_back(file.path);
        ASSERT_EQ(r.telegrams.size(), 2u);
        EXPECT_EQ(r.telegrams[0].time_ns, kNoTime);
        EXPECT_EQ(r.telegrams[1].time_ns, kT0);
    }
}

TEST(CaptureWriterTest, EmptyCapturesReadBackEmpty) {
    for (CaptureFormat format : {CaptureFormat::Pcap, CaptureFormat::Pcapng}) {
        SCOPED_TRACE(capture_format_name(format));
        TempFile file("empty.cap");
        write_all(file.path, format, kLinkTypeProfibusDl, {});
        ReadBack r = read_back(file.path);
        EXPECT_TRUE(r.telegrams.empty());
        EXPECT_EQ(r.status, InputStatus::Ok);
        EXPECT_EQ(r.link_type, kLinkTypeProfibusDl);
    }
}

TEST(CaptureWriterTest, SimulatedSessionRoundTripsInEveryFormat) {
    SimulatorOptions options;
    options.seed = 5;
    options.cycles = 40;
    options.faults = {FaultSpec{FaultKind::FcsError, 0, 10, std::nullopt}};
    Simulator simulator(options);
    std::vector<Telegram> telegrams;
    std::vector<std::uint8_t> bytes;
    std::int64_t time_ns = 0;
    while (simulator.next(bytes, time_ns))
        telegrams.push_back({bytes, time_ns});
    ASSERT_GT(telegrams.size(), 100u);
    for (CaptureFormat format :
         {CaptureFormat::Pcap, CaptureFormat::Pcapng, CaptureFormat::Raw, CaptureFormat::Hex}) {
        SCOPED_TRACE(capture_format_name(format));
        TempFile file("session.cap");
        write_all(file.path, format, kLinkTypeProfibusDl, telegrams);
        ReadBack r = read_back(file.path);
        EXPECT_EQ(r.issues, 0u);
        expect_same(r.telegrams, telegrams, format != CaptureFormat::Raw);
    }
}

TEST(CaptureWriterTest, PcapRefusesTimesItCannotHold) {
    // Regression: the record's 32-bit seconds field wrapped 5e9 s (2128) round to 1992. libpcap
    // (and so tcpdump and dpscope) reads the field as signed: 2^31 s reads back as 1901.
    for (std::int64_t time : {std::int64_t{5'000'000'000'000'000'000},
                              std::int64_t{2'147'483'648'000'000'000}, std::int64_t{-1}}) {
        SCOPED_TRACE(time);
        TempFile file("late.pcap");
        WriterResult opened =
            open_capture_writer(file.path, CaptureFormat::Pcap, kLinkTypeProfibusDl);
        ASSERT_TRUE(opened) << opened.error();
        const Telegram& first = kTelegrams[0];
        ASSERT_TRUE(opened.value()->write(Bytes(first.bytes.data(), first.bytes.size()), kT0));
        Result<void> written =
            opened.value()->write(Bytes(first.bytes.data(), first.bytes.size()), time);
        EXPECT_FALSE(written);
        EXPECT_NE(written.error().find(file.path + ": telegram time "), std::string::npos)
            << written.error();
        EXPECT_NE(written.error().find("outside what a pcap file holds (0 to 2147483647 s"),
                  std::string::npos)
            << written.error();
        // Closing fails with the same error: it stays.
        Result<void> closed = opened.value()->close();
        EXPECT_FALSE(closed);
        EXPECT_EQ(closed.error(), written.error());
        ReadBack r = read_back(file.path);  // what came before is kept
        expect_same(r.telegrams, {{first.bytes, kT0}}, true);
    }
    // The last second it holds is written (libpcap reads the field as signed: 2038).
    constexpr std::int64_t kLast = 2'147'483'647LL * 1'000'000'000 + 999'999'999;
    TempFile file("last.pcap");
    write_all(file.path, CaptureFormat::Pcap, kLinkTypeProfibusDl, {{hex("E5"), kLast}});
    expect_same(read_back(file.path).telegrams, {{hex("E5"), kLast}}, true);
}

TEST(CaptureWriterTest, LongPcapWritesAreFlushedEvery4096Records) {
    // Regression: without flushes, the writer kept every record's end (8 bytes a telegram) for
    // cutting the file back after a failed write. It now flushes every 4096 records (and
    // forgets them): then the file on disk ends with the last record before.
    TempFile file("long.pcap");
    WriterResult opened = open_capture_writer(file.path, CaptureFormat::Pcap, kLinkTypeProfibusDl);
    ASSERT_TRUE(opened) << opened.error();
    // 23 bytes a record: 4096 of them do not fill whole stdio buffers by chance.
    const std::vector<std::uint8_t> telegram = hex("10 03 02 49 4E 16 E5");
    const std::uint64_t record = kPcapRecordHeaderBytes + telegram.size();
    for (std::int64_t i = 0; i < 4097; ++i)
        ASSERT_TRUE(opened.value()->write(Bytes(telegram.data(), telegram.size()), kT0 + i));
    EXPECT_EQ(test::read_file(file.path).size(), kPcapFileHeaderBytes + 4096 * record);
    EXPECT_TRUE(opened.value()->close());
    EXPECT_EQ(read_back(file.path).telegrams.size(), 4097u);
}

TEST(CaptureWriterTest, UnwritablePathFailsNamingIt) {
    TempFile blocker("plain-file");
    test::write_file(blocker.path, {0x00});
    // A path below a regular file cannot be created, not even by root.
    const std::string path = blocker.path + "/capture.out";
    for (CaptureFormat format :
         {CaptureFormat::Pcap, CaptureFormat::Pcapng, CaptureFormat::Raw, CaptureFormat::Hex}) {
        SCOPED_TRACE(capture_format_name(format));
        WriterResult opened = open_capture_writer(path, format, kLinkTypeProfibusDl);
        EXPECT_FALSE(opened);
        EXPECT_EQ(opened.error().rfind(path + ": cannot open for writing: ", 0), 0u)
            << opened.error();
    }
}

TEST(CaptureWriterTest, WriteErrorIsReportedOnClose) {
    // /dev/full accepts the open and fails every write. A pcap file's header is written at once:
    // there the error comes at the open.
    WriterResult pcap = open_capture_writer("/dev/full", CaptureFormat::Pcap, kLinkTypeProfibusDl);
    EXPECT_FALSE(pcap);
    EXPECT_EQ(pcap.error(), "/dev/full: write failed: No space left on device");
    for (CaptureFormat format : {CaptureFormat::Pcapng, CaptureFormat::Raw, CaptureFormat::Hex}) {
        SCOPED_TRACE(capture_format_name(format));
        WriterResult opened = open_capture_writer("/dev/full", format, kLinkTypeProfibusDl);
        ASSERT_TRUE(opened) << opened.error();
        for (const Telegram& t : kTelegrams)
            (void)opened.value()->write(Bytes(t.bytes.data(), t.bytes.size()), t.time_ns);
        Result<void> closed = opened.value()->close();
        EXPECT_FALSE(closed);
        EXPECT_EQ(closed.error().rfind("/dev/full: write failed: ", 0), 0u) << closed.error();
    }
}

// ---- the ring (sniff --ring, --max-disk; issue 30) ----------------------------------------------

// 40 telegrams of 14 bytes (30 bytes a record in pcap) through a writer rotating at 100 bytes (the
// 24-byte header and two records a file): the ring of 3 keeps the last 3 files, removes the older
// ones only after the next is complete, and counts what it removed; what is kept is the session's
// end, whole and in order, in readable files.
TEST(CaptureWriterTest, TheRingKeepsTheLastFilesAndCountsWhatItRemoved) {
    const std::string path = test::temp_path("ring.pcap");
    RotationOptions rotation;
    rotation.max_bytes = 100;
    rotation.ring_files = 3;
    WriterResult opened = open_rotating_writer(path, CaptureFormat::Pcap, 257, rotation);
    ASSERT_TRUE(opened) << opened.error();
    CaptureWriter& writer = *opened.value();
    std::vector<std::vector<std::uint8_t>> sent;
    for (int i = 0; i < 40; ++i) {
        std::vector<std::uint8_t> bytes = hex("68 07 07 68 83 82 7D 3E 3E F3 F1 E2 16");
        bytes.push_back(static_cast<std::uint8_t>(i));
        sent.push_back(bytes);
        ASSERT_TRUE(writer.write(Bytes(sent.back().data(), sent.back().size()), kT0 + i * 1000));
        // Never more than 3 files on disk, the current one included.
        unsigned on_disk = 0;
        for (unsigned index = 1; index <= 30; ++index)
            on_disk += access(rotated_file_name(path, index).c_str(), F_OK) == 0 ? 1 : 0;
        EXPECT_LE(on_disk, 3u) << i;
    }
    ASSERT_TRUE(writer.close());
    const RotationStats* stats = writer.rotation_stats();
    ASSERT_NE(stats, nullptr);
    EXPECT_EQ(stats->files_written, 20u);  // two records a file
    EXPECT_EQ(stats->files_removed, 17u);
    EXPECT_EQ(stats->records_removed, 34u);
    EXPECT_EQ(stats->bytes_kept, 3u * (24 + 2 * 30));
    std::vector<Telegram> kept;
    for (unsigned index = 1; index <= 20; ++index) {
        const std::string name = rotated_file_name(path, index);
        if (index <= 17) {
            EXPECT_NE(access(name.c_str(), F_OK), 0) << name;  // removed
            continue;
        }
        ReadBack back = read_back(name);
        EXPECT_EQ(back.status, InputStatus::Ok) << name;
        kept.insert(kept.end(), back.telegrams.begin(), back.telegrams.end());
        std::remove(name.c_str());
    }
    ASSERT_EQ(kept.size(), 6u);
    for (std::size_t i = 0; i < kept.size(); ++i)
        EXPECT_EQ(kept[i].bytes, sent[34 + i]) << i;
}

// --max-disk: the oldest complete files go while the set is over the cap, never the current one.
TEST(CaptureWriterTest, TheDiskCapRemovesTheOldestCompleteFiles) {
    const std::string path = test::temp_path("capped.pcap");
    RotationOptions rotation;
    rotation.max_bytes = 100;
    rotation.max_disk = 250;  // two full files of 84 bytes and a part of the third
    WriterResult opened = open_rotating_writer(path, CaptureFormat::Pcap, 257, rotation);
    ASSERT_TRUE(opened) << opened.error();
    CaptureWriter& writer = *opened.value();
    const std::vector<std::uint8_t> bytes = hex("68 07 07 68 83 82 7D 3E 3E F3 F1 E2 16 00");
    for (int i = 0; i < 20; ++i) {
        ASSERT_TRUE(writer.write(Bytes(bytes.data(), bytes.size()), kT0 + i * 1000));
        EXPECT_LE(writer.rotation_stats()->bytes_kept, 250u) << i;
    }
    ASSERT_TRUE(writer.close());
    const RotationStats* stats = writer.rotation_stats();
    EXPECT_EQ(stats->files_written, 10u);
    EXPECT_EQ(stats->records_removed, 2u * stats->files_removed);
    unsigned kept = 0;
    std::uint64_t kept_bytes = 0;
    for (unsigned index = 1; index <= 10; ++index) {
        const std::string name = rotated_file_name(path, index);
        if (access(name.c_str(), F_OK) != 0) {
            EXPECT_LE(index, stats->files_removed) << name;  // the oldest went
            continue;
        }
        ++kept;
        kept_bytes += test::read_file(name).size();
        EXPECT_EQ(read_back(name).status, InputStatus::Ok) << name;
        std::remove(name.c_str());
    }
    EXPECT_EQ(kept + stats->files_removed, 10u);
    EXPECT_GE(kept, 2u);
    EXPECT_EQ(kept_bytes, stats->bytes_kept);
    EXPECT_LE(kept_bytes, 250u);
}

}  // namespace
}  // namespace dpscope
