// pcap and pcapng captures through open_source: link types 257 and 147, nanosecond times,
// record numbering, and every way a capture file can be unusable or damaged.
#include "capture/pcap_source.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <pcap/pcap.h>
#include <sys/stat.h>

#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "capture/capture_writer.hpp"
#include "capture/telegram_source.hpp"
#include "protocols/profibus/fdl_framing_rules.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::hex;

const std::vector<std::uint8_t> kSd1 = hex("10 03 02 49 4E 16");
const std::vector<std::uint8_t> kSd2 = hex("68 07 07 68 83 82 7D 3E 3E F3 F1 E2 16");
const std::vector<std::uint8_t> kToken = hex("DC 02 02");

constexpr std::int64_t kT0 = 1'704'067'200'000'000'000;  // 2024-01-01T00:00:00Z

struct Telegram {
    std::vector<std::uint8_t> bytes;
    std::int64_t time_ns;
};

const std::vector<Telegram> kTelegrams = {
    {kSd1, kT0 + 1},
    {kSd2, kT0 + 123'456'789},
    {kToken, kT0 + 2'000'000'007},
};

// Removes the file when the test ends.
struct TempFile {
    explicit TempFile(std::string_view name) : path(test::temp_path(name)) {}
    ~TempFile() { std::remove(path.c_str()); }
    std::string path;
};

void write_capture(const std::string& path, CaptureFormat format, int link_type,
                   const std::vector<Telegram>& telegrams = kTelegrams) {
    WriterResult opened = open_capture_writer(path, format, link_type);
    ASSERT_TRUE(opened) << opened.error();
    for (const Telegram& t : telegrams)
        ASSERT_TRUE(opened.value()->write(Bytes(t.bytes.data(), t.bytes.size()), t.time_ns));
    Result<void> closed = opened.value()->close();
    ASSERT_TRUE(closed) << closed.error();
}

struct ReadResult {
    std::vector<Record> records;  // bytes point into `data`
    std::vector<std::vector<std::uint8_t>> data;
    std::vector<InputIssue> issues;
    InputStatus status = InputStatus::Ok;
    InputFormat format = InputFormat::Auto;
    int link_type = -1;
};

ReadResult read_all(const std::string& path, InputFormat format = InputFormat::Auto) {
    ReadResult result;
    OpenResult opened = open_source(path, format, profibus_protocol());
    EXPECT_TRUE(opened) << opened.error();
    if (!opened) return result;
    EXPECT_TRUE(opened.error().empty()) << opened.error();
    opened.value()->on_issue([&](const InputIssue& issue) { result.issues.push_back(issue); });
    Record record;
    while (opened.value()->next(record)) {
        result.data.emplace_back(record.bytes.begin(), record.bytes.end());
        result.records.push_back(record);
    }
    result.status = opened.value()->status();
    result.format = opened.value()->format();
    result.link_type = opened.value()->link_type();
    return result;
}

std::string open_error(const std::string& path, InputFormat format = InputFormat::Auto) {
    OpenResult opened = open_source(path, format, profibus_protocol());
    EXPECT_FALSE(opened) << path;
    return opened.error();
}

// A classic pcap file built byte by byte.
class PcapBuilder {
  public:
    PcapBuilder(bool big_endian, bool nano, std::uint32_t link_type, std::uint32_t snaplen = 65535)
        : big_endian_(big_endian) {
        u32(nano ? 0xA1B23C4D : 0xA1B2C3D4);
        u16(2);
        u16(4);
        u32(0);
        u32(0);
        u32(snaplen);
        u32(link_type);
    }
    PcapBuilder& record(std::uint32_t seconds, std::uint32_t fraction,
                        const std::vector<std::uint8_t>& data, std::uint32_t length = 0,
                        std::uint32_t caplen = 0xFFFFFFFF) {
        u32(seconds);
        u32(fraction);
        u32(caplen == 0xFFFFFFFF ? static_cast<std::uint32_t>(data.size()) : caplen);
        u32(length ? length : static_cast<std::uint32_t>(data.size()));
        bytes_.insert(bytes_.end(), data.begin(), data.end());
        return *this;
    }
    const std::vector<std::uint8_t>& bytes() const { return bytes_; }

  private:
    void u16(std::uint16_t v) {
        if (big_endian_) {
            bytes_.push_back(static_cast<std::uint8_t>(v >> 8));
            bytes_.push_back(static_cast<std::uint8_t>(v));
        } else {
            bytes_.push_back(static_cast<std::uint8_t>(v));
            bytes_.push_back(static_cast<std::uint8_t>(v >> 8));
        }
    }
    void u32(std::uint32_t v) {
        if (big_endian_) {
            u16(static_cast<std::uint16_t>(v >> 16));
            u16(static_cast<std::uint16_t>(v));
        } else {
            u16(static_cast<std::uint16_t>(v));
            u16(static_cast<std::uint16_t>(v >> 16));
        }
    }
    bool big_endian_;
    std::vector<std::uint8_t> bytes_;
};

void expect_telegrams(const ReadResult& r, const std::vector<Telegram>& telegrams) {
    ASSERT_EQ(r.records.size(), telegrams.size());
    for (std::size_t i = 0; i < telegrams.size(); ++i) {
        SCOPED_TRACE(i);
        EXPECT_EQ(r.data[i], telegrams[i].bytes);
        EXPECT_EQ(r.records[i].time_ns, telegrams[i].time_ns);
        EXPECT_EQ(r.records[i].number, i + 1);
        EXPECT_EQ(r.records[i].original_length, telegrams[i].bytes.size());
    }
}

// ---- valid captures --------------------------------------------------------------------------

TEST(PcapSourceTest, ReadsPcapWithLinkTypeProfibusDl) {
    TempFile file("dl.pcap");
    write_capture(file.path, CaptureFormat::Pcap, kLinkTypeProfibusDl);
    ReadResult r = read_all(file.path);
    EXPECT_EQ(r.format, InputFormat::Pcap);
    EXPECT_EQ(r.link_type, 257);
    EXPECT_EQ(r.status, InputStatus::Ok);
    EXPECT_TRUE(r.issues.empty());
    expect_telegrams(r, kTelegrams);
    // Record offsets: after the 24-byte file header, each record has a 16-byte header.
    ASSERT_EQ(r.records.size(), 3u);
    EXPECT_EQ(r.records[0].offset, 24u);
    EXPECT_EQ(r.records[1].offset, 24u + 16 + 6);
    EXPECT_EQ(r.records[2].offset, 24u + 16 + 6 + 16 + 13);
}

TEST(PcapSourceTest, ReadsPcapWithLinkTypeUser0) {
    TempFile file("user0.pcap");
    write_capture(file.path, CaptureFormat::Pcap, kLinkTypeUser0);
    ReadResult r = read_all(file.path);
    EXPECT_EQ(r.format, InputFormat::Pcap);
    EXPECT_EQ(r.link_type, 147);
    EXPECT_EQ(r.status, InputStatus::Ok);
    expect_telegrams(r, kTelegrams);
}

TEST(PcapSourceTest, ReadsPcapng) {
    TempFile file("dl.pcapng");
    write_capture(file.path, CaptureFormat::Pcapng, kLinkTypeProfibusDl);
    ReadResult r = read_all(file.path);
    EXPECT_EQ(r.format, InputFormat::Pcapng);
    EXPECT_EQ(r.link_type, 257);
    EXPECT_EQ(r.status, InputStatus::Ok);
    EXPECT_TRUE(r.issues.empty());
    expect_telegrams(r, kTelegrams);
}

TEST(PcapSourceTest, ReadsPcapngWithLinkTypeUser0) {
    TempFile file("user0.pcapng");
    write_capture(file.path, CaptureFormat::Pcapng, kLinkTypeUser0);
    ReadResult r = read_all(file.path);
    EXPECT_EQ(r.link_type, 147);
    expect_telegrams(r, kTelegrams);
}

TEST(PcapSourceTest, PcapngRecordOffsetsAreBlockOffsets) {
    TempFile file("offsets.pcapng");
    write_capture(file.path, CaptureFormat::Pcapng, kLinkTypeProfibusDl);
    ReadResult r = read_all(file.path);
    ASSERT_EQ(r.records.size(), 3u);
    // Each record's offset is where its enhanced packet block starts: type 6, then its length.
    std::vector<std::uint8_t> bytes = test::read_file(file.path);
    std::uint64_t previous = 0;
    for (const Record& record : r.records) {
        ASSERT_LT(record.offset + 8, bytes.size());
        EXPECT_GT(record.offset, previous);
        EXPECT_EQ(bytes[record.offset], 6);
        EXPECT_EQ(bytes[record.offset + 1] | bytes[record.offset + 2] | bytes[record.offset + 3],
                  0);
        previous = record.offset;
    }
}

// ---- pcapng built block by block -------------------------------------------------------------

using test::PcapngBuilder;

constexpr std::uint64_t kT0Us = 1'704'067'200'000'000;  // kT0 in microseconds

TEST(PcapSourceTest, PcapngWithInterfacesOfBothLinkTypesAsMergecapMakesThem) {
    // libpcap refuses a second interface whose link type differs from the first one's.
    TempFile file("merged.pcapng");
    PcapngBuilder b;
    b.interface(257).interface(147);
    b.packet(0, kT0Us, kSd1).packet(1, kT0Us + 100, kSd2).packet(0, kT0Us + 200, kToken);
    test::write_file(file.path, b.bytes());
    ReadResult r = read_all(file.path);
    EXPECT_EQ(r.status, InputStatus::Ok);
    EXPECT_TRUE(r.issues.empty());
    EXPECT_EQ(r.format, InputFormat::Pcapng);
    EXPECT_EQ(r.link_type, 257);
    expect_telegrams(r, {{kSd1, kT0}, {kSd2, kT0 + 100'000}, {kToken, kT0 + 200'000}});
}

TEST(PcapSourceTest, PcapngSkipsPacketsOfAnInterfaceWithAnotherLinkTypeWithOneWarning) {
    TempFile file("ethernet-too.pcapng");
    PcapngBuilder b;
    b.interface(257).interface(1);
    std::vector<std::uint8_t> frame(60, 0xFF);
    b.packet(1, kT0Us, frame).packet(0, kT0Us + 1, kSd1).packet(1, kT0Us + 2, frame);
    b.packet(1, kT0Us + 3, frame).packet(0, kT0Us + 4, kToken);
    test::write_file(file.path, b.bytes());
    ReadResult r = read_all(file.path);
    EXPECT_EQ(r.status, InputStatus::Ok);
    ASSERT_EQ(r.records.size(), 2u);
    EXPECT_EQ(r.data[0], kSd1);
    EXPECT_EQ(r.data[1], kToken);
    // Frame numbers count every packet, as Wireshark does.
    EXPECT_EQ(r.records[0].number, 2u);
    EXPECT_EQ(r.records[1].number, 5u);
    ASSERT_EQ(r.issues.size(), 1u);
    const std::string& message = r.issues[0].message;
    EXPECT_EQ(r.issues[0].severity, Severity::Warning);
    EXPECT_NE(message.find(file.path + ": byte offset 52: interface 1 has link type 1 (EN10MB)"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("its packets are skipped"), std::string::npos) << message;
    EXPECT_EQ(message, file.path +
                           ": byte offset 52: interface 1 has link type 1 (EN10MB), which dpscope "
                           "does not decode (it reads 257 PROFIBUS_DL and 147 USER0); its packets "
                           "are skipped");
}

TEST(PcapSourceTest, PcapngWithVeryManyInterfacesIsReadInBoundedMemory) {
    // 200,000 interface descriptions (of a link type dpscope does not decode, each a warning
    // before the first packet), then a PROFIBUS interface and packets of interfaces past the
    // limit: the source keeps the first 4096 interfaces and 10 messages of each kind, whatever
    // the number of blocks (issue #27 point 2).
    TempFile file("many-interfaces.pcapng");
    PcapngBuilder b;
    b.interface(257);
    for (int i = 0; i < 200'000; ++i)
        b.interface(1);
    b.packet(0, kT0Us, kSd1).packet(150'000, kT0Us + 1, kSd2).packet(0, kT0Us + 2, kToken);
    test::write_file(file.path, b.bytes());
    OpenResult opened = open_source(file.path, InputFormat::Auto, profibus_protocol());
    ASSERT_TRUE(opened) << opened.error();
    TelegramSource& source = *opened.value();
    std::vector<InputIssue> issues;
    source.on_issue([&](const InputIssue& issue) { issues.push_back(issue); });
    std::size_t most = source.buffered_bytes();
    std::vector<std::vector<std::uint8_t>> data;
    Record record;
    while (source.next(record)) {
        data.emplace_back(record.bytes.begin(), record.bytes.end());
        most = std::max(most, source.buffered_bytes());
    }
    EXPECT_LE(most, std::size_t{1} << 20);
    EXPECT_EQ(source.status(), InputStatus::Ok);
    ASSERT_EQ(data.size(), 2u);
    EXPECT_EQ(data[0], kSd1);
    EXPECT_EQ(data[1], kToken);
    EXPECT_EQ(source.issue_count(IssueKind::Interface), 4095u + 1u);
    ASSERT_EQ(issues.size(), kMaxIssuesShown + 1);
    EXPECT_NE(issues.back().message.find("4086 more warnings about interfaces not shown"),
              std::string::npos)
        << issues.back().message;
}

TEST(PcapSourceTest, PcapngWithNoInterfaceDpscopeDecodesIsUnusable) {
    TempFile file("ethernet.pcapng");
    PcapngBuilder b;
    b.interface(1).packet(0, kT0Us, std::vector<std::uint8_t>(60, 0xFF));
    test::write_file(file.path, b.bytes());
    std::string error = open_error(file.path);
    EXPECT_EQ(error, file.path +
                         ": unsupported link type 1 (EN10MB); dpscope reads 257 (PROFIBUS_DL) and "
                         "147 (USER0)");
}

TEST(PcapSourceTest, PcapngWithoutInterfacesIsAnEmptyCapture) {
    TempFile file("no-interfaces.pcapng");
    test::write_file(file.path, PcapngBuilder().bytes());
    ReadResult r = read_all(file.path);
    EXPECT_EQ(r.status, InputStatus::Ok);
    EXPECT_TRUE(r.records.empty());
    EXPECT_TRUE(r.issues.empty());
}

TEST(PcapSourceTest, PcapngBigEndianWithResolutionAndOffset) {
    TempFile file("big-endian.pcapng");
    PcapngBuilder b(true);
    // Interface 0: nanoseconds; interface 1: 2^-10 s units, 100 s offset.
    b.interface(257, 9).interface(147, 0x80 | 10, 100);
    b.packet(0, 1'704'067'200'000'000'007ULL, kSd1);
    b.packet(1, (1'704'067'100ULL << 10) | 512, kSd2);  // + 100 s, + 0.5 s
    test::write_file(file.path, b.bytes());
    ReadResult r = read_all(file.path);
    EXPECT_EQ(r.status, InputStatus::Ok);
    EXPECT_TRUE(r.issues.empty());
    expect_telegrams(r, {{kSd1, kT0 + 7}, {kSd2, kT0 + 500'000'000}});
}

// if_tsoffset is any signed 64-bit number: one that puts the time past what nanoseconds since
// the epoch hold leaves the packet without a time, with a warning, and is no signed overflow
// (the offset was added to the seconds before the range check). A wrapped sum lands out of range
// too, so without the check this test fails only under UBSan (the asan preset), as
// fuzz_capture_file does on fuzz/corpus/fuzz_capture_file/regression-tsoffset-overflow.pcapng.
TEST(PcapSourceTest, PcapngTimestampOffsetBeyondTheRangeLeavesThePacketUntimed) {
    TempFile file("huge-offset.pcapng");
    PcapngBuilder b;
    b.interface(257, 0, std::numeric_limits<std::int64_t>::max())
        .interface(147, 0, std::numeric_limits<std::int64_t>::min())
        .interface(257, 0, -1'704'067'200)  // far back, but in range: 0 s after the epoch
        .packet(0, kT0Us, kSd1)
        .packet(1, kT0Us, kSd2)
        .packet(2, kT0Us + 5, kToken);
    test::write_file(file.path, b.bytes());
    ReadResult r = read_all(file.path);
    EXPECT_EQ(r.status, InputStatus::Ok);
    ASSERT_EQ(r.records.size(), 3u);
    EXPECT_EQ(r.records[0].time_ns, kNoTime);
    EXPECT_EQ(r.records[1].time_ns, kNoTime);
    EXPECT_EQ(r.records[2].time_ns, 5'000);
    ASSERT_EQ(r.issues.size(), 2u);
    for (const InputIssue& issue : r.issues) {
        EXPECT_EQ(issue.kind, IssueKind::BadTime);
        EXPECT_NE(issue.message.find("timestamp outside 1677-09-21 to 2262-04-11"),
                  std::string::npos)
            << issue.message;
    }
}

TEST(PcapSourceTest, PcapngSimplePacketsAndSecondSectionWithOtherInterfaces) {
    TempFile file("sections.pcapng");
    PcapngBuilder b;
    b.interface(1).interface(257).packet(1, kT0Us, kSd1);
    b.block(4, {0, 0, 0, 0});  // a name resolution block: passed over
    // A new section numbers its interfaces from 0 again.
    b.section().interface(147).simple_packet(kToken);
    test::write_file(file.path, b.bytes());
    ReadResult r = read_all(file.path);
    EXPECT_EQ(r.status, InputStatus::Ok);
    ASSERT_EQ(r.records.size(), 2u);
    EXPECT_EQ(r.data[0], kSd1);
    EXPECT_EQ(r.data[1], kToken);
    EXPECT_EQ(r.records[1].time_ns, kNoTime);  // simple packet blocks carry no time
    ASSERT_EQ(r.issues.size(), 1u);            // interface 0 of the first section
}

TEST(PcapSourceTest, PcapngBlockLengthsAreChecked) {
    PcapngBuilder good;
    good.interface(257).packet(0, kT0Us, kSd1).packet(0, kT0Us + 1, kSd2);
    const std::vector<std::uint8_t> whole = good.bytes();
    const std::size_t second = whole.size() - 48;  // the second packet block (48 bytes)
    struct Case {
        const char* what;
        std::size_t at;  // byte to change
        std::uint8_t value;
        const char* message;
    };
    for (const Case& c : std::vector<Case>{
             {"length not a multiple of 4", second + 4, 47, "gives its length as 47 bytes"},
             {"length below the minimum", second + 4, 8, "gives its length as 8 bytes"},
             {"length past the end", second + 4, 52, "cut off: the file ends after 48 of its"},
             {"trailing length differs", whole.size() - 4, 44, "at its start and 44 at its end"},
             {"captured length past the block", second + 20, 40, "captured length 40 runs past"},
         }) {
        SCOPED_TRACE(c.what);
        TempFile file("bad-length.pcapng");
        std::vector<std::uint8_t> bytes = whole;
        bytes[c.at] = c.value;
        test::write_file(file.path, bytes);
        ReadResult r = read_all(file.path);
        EXPECT_EQ(r.status, InputStatus::Damaged);
        ASSERT_EQ(r.records.size(), 1u);
        ASSERT_EQ(r.issues.size(), 1u);
        const std::string& message = r.issues[0].message;
        EXPECT_EQ(r.issues[0].severity, Severity::Error);
        EXPECT_NE(message.find(fmt::format("{}: record 2 (byte offset {}): ", file.path, second)),
                  std::string::npos)
            << message;
        EXPECT_NE(message.find(c.message), std::string::npos) << message;
        EXPECT_NE(message.find("decoding stopped after 1 record"), std::string::npos) << message;
    }
}

TEST(PcapSourceTest, PcapngCutInsideABlockHeaderOrWithBadByteOrderMagic) {
    PcapngBuilder good;
    good.interface(257).packet(0, kT0Us, kSd1);
    {
        TempFile file("cut-header.pcapng");
        std::vector<std::uint8_t> bytes = good.bytes();
        bytes.insert(bytes.end(), {6, 0, 0, 0, 32});
        test::write_file(file.path, bytes);
        ReadResult r = read_all(file.path);
        EXPECT_EQ(r.status, InputStatus::Damaged);
        EXPECT_EQ(r.records.size(), 1u);
        ASSERT_EQ(r.issues.size(), 1u);
        EXPECT_NE(r.issues[0].message.find("the file ends inside a block header (5 of 8 bytes)"),
                  std::string::npos)
            << r.issues[0].message;
    }
    {
        TempFile file("bad-magic.pcapng");
        std::vector<std::uint8_t> bytes = good.bytes();
        bytes[8] = 0x99;
        test::write_file(file.path, bytes);
        std::string error = open_error(file.path);
        EXPECT_NE(error.find("byte offset 0: section header block with byte-order magic"),
                  std::string::npos)
            << error;
    }
}

TEST(PcapSourceTest, MicrosecondLittleEndianPcapTimesInNanoseconds) {
    TempFile file("usec-le.pcap");
    PcapBuilder pcap(false, false, 257);
    pcap.record(1'704'067'200, 125, kSd1).record(1'704'067'201, 999'999, kToken);
    test::write_file(file.path, pcap.bytes());
    ReadResult r = read_all(file.path);
    EXPECT_EQ(r.format, InputFormat::Pcap);
    expect_telegrams(r, {{kSd1, kT0 + 125'000}, {kToken, kT0 + 1'999'999'000}});
}

TEST(PcapSourceTest, NanosecondBigEndianPcap) {
    TempFile file("nsec-be.pcap");
    PcapBuilder pcap(true, true, 147);
    pcap.record(1'704'067'200, 123'456'789, kSd2);
    test::write_file(file.path, pcap.bytes());
    ReadResult r = read_all(file.path);
    EXPECT_EQ(r.format, InputFormat::Pcap);
    EXPECT_EQ(r.link_type, 147);
    expect_telegrams(r, {{kSd2, kT0 + 123'456'789}});
}

TEST(PcapSourceTest, SnapshotLengthCutIsAWarning) {
    TempFile file("snap.pcap");
    PcapBuilder pcap(false, true, 257);
    pcap.record(1'704'067'200, 0, hex("68 07 07 68"), 13).record(1'704'067'200, 5, kSd1);
    test::write_file(file.path, pcap.bytes());
    ReadResult r = read_all(file.path);
    ASSERT_EQ(r.records.size(), 2u);
    EXPECT_EQ(r.data[0], hex("68 07 07 68"));
    EXPECT_EQ(r.records[0].original_length, 13u);
    EXPECT_EQ(r.status, InputStatus::Ok);
    ASSERT_EQ(r.issues.size(), 1u);
    EXPECT_EQ(r.issues[0].severity, Severity::Warning);
    EXPECT_NE(r.issues[0].message.find(file.path), std::string::npos) << r.issues[0].message;
    EXPECT_NE(r.issues[0].message.find("record 1 (byte offset 24): only 4 of 13 bytes captured"),
              std::string::npos)
        << r.issues[0].message;
    // The next record's offset counts the captured bytes only.
    EXPECT_EQ(r.records[1].offset, 24u + 16 + 4);
}

TEST(PcapSourceTest, LinkTypeNames) {
    EXPECT_EQ(link_type_name(257), "PROFIBUS_DL");
    EXPECT_EQ(link_type_name(147), "USER0");
    EXPECT_EQ(link_type_name(1), "EN10MB");
    EXPECT_EQ(link_type_name(-5), "unknown");
}

// ---- unusable inputs -------------------------------------------------------------------------

// A pcap file of link type EN10MB (Ethernet) holding one frame.
void write_ethernet_pcap(const std::string& path) {
    pcap_t* dead = pcap_open_dead(DLT_EN10MB, 65535);
    ASSERT_NE(dead, nullptr);
    pcap_dumper_t* dumper = pcap_dump_open(dead, path.c_str());
    ASSERT_NE(dumper, nullptr) << pcap_geterr(dead);
    std::vector<std::uint8_t> frame(60, 0xFF);
    pcap_pkthdr header{};
    header.ts.tv_sec = 1'704'067'200;
    header.caplen = header.len = static_cast<bpf_u_int32>(frame.size());
    pcap_dump(reinterpret_cast<u_char*>(dumper), &header, frame.data());
    pcap_dump_close(dumper);
    pcap_close(dead);
}

TEST(PcapSourceTest, UnsupportedLinkTypeNamesFileNumberAndName) {
    TempFile file("ethernet.pcap");
    write_ethernet_pcap(file.path);

    std::string error = open_error(file.path);
    EXPECT_NE(error.find(file.path), std::string::npos) << error;
    EXPECT_NE(error.find("unsupported link type 1 "), std::string::npos) << error;
    EXPECT_NE(error.find("(EN10MB)"), std::string::npos) << error;
    // Forcing the format changes nothing.
    EXPECT_NE(open_error(file.path, InputFormat::Pcap).find("unsupported link type 1 "),
              std::string::npos);
}

// A protocol carried by Ethernet frames, for the tests below: the readers take the link types
// from the protocol they are given, not from a list of their own.
const PcapLinkType kEthernetOnly[] = {{1, "EN10MB"}};
const ProtocolDescriptor kEthernetProtocol{.protocol = Protocol::ProfibusDp,
                                           .name = "ethernet-test",
                                           .title = "a test protocol on Ethernet",
                                           .capture_noun = "an Ethernet test",
                                           .framing = fdl_framing_rules(),
                                           .link_types = kEthernetOnly,
                                           .pcap_bus_number = 0,
                                           .lead_byte = std::nullopt,
                                           .lead_byte_text = {},
                                           .text_log_shape = {},
                                           .traffic_name = {},
                                           .has_bus_health = false,
                                           .timed_by_line = false,
                                           .masters_addressed = true};

TEST(PcapSourceTest, TheProtocolGivenChoosesTheLinkTypes) {
    TempFile file("ethernet-for-test-protocol.pcap");
    write_ethernet_pcap(file.path);
    OpenResult opened = open_source(file.path, InputFormat::Auto, kEthernetProtocol);
    ASSERT_TRUE(opened) << opened.error();
    Record record;
    ASSERT_TRUE(opened.value()->next(record));
    EXPECT_EQ(record.bytes.size(), 60u);
    EXPECT_EQ(opened.value()->link_type(), 1);

    TempFile profibus("profibus-for-test-protocol.pcap");
    write_capture(profibus.path, CaptureFormat::Pcap, kLinkTypeProfibusDl);
    OpenResult refused = open_source(profibus.path, InputFormat::Auto, kEthernetProtocol);
    ASSERT_FALSE(refused);
    EXPECT_EQ(
        refused.error(),
        profibus.path + ": unsupported link type 257 (PROFIBUS_DL); dpscope reads 1 (EN10MB)");
}

// A PROFIBUS capture (link type 257) read with another bus's protocol (--bus fc): the message
// names the real problem, the bus option, not an unsupported link type.
TEST(PcapSourceTest, AProfibusCaptureReadAsAnotherBusNamesTheBus) {
    for (CaptureFormat format : {CaptureFormat::Pcap, CaptureFormat::Pcapng}) {
        TempFile file(format == CaptureFormat::Pcap ? "profibus-as-fc.pcap"
                                                    : "profibus-as-fc.pcapng");
        write_capture(file.path, format, kLinkTypeProfibusDl);
        OpenResult refused = open_source(file.path, InputFormat::Auto, fc_protocol());
        ASSERT_FALSE(refused);
        EXPECT_EQ(refused.error(),
                  file.path +
                      ": link type 257 (PROFIBUS_DL) is a PROFIBUS capture, but --bus fc reads FC "
                      "protocol telegrams from captures of link type 147 (USER0) only; leave "
                      "--bus out (or give --bus profibus)");
        OpenResult vlt = open_source(file.path, InputFormat::Auto, vlt2000_protocol());
        ASSERT_FALSE(vlt);
        EXPECT_NE(vlt.error().find("is a PROFIBUS capture, but --bus vlt2000 reads VLT 2000 "
                                   "telegrams"),
                  std::string::npos)
            << vlt.error();
    }
}

TEST(PcapSourceTest, PcapngInterfacesAreJudgedByTheProtocolGiven) {
    TempFile file("profibus-and-ethernet-for-test-protocol.pcapng");
    PcapngBuilder b;
    b.interface(257).interface(1);
    b.packet(0, kT0Us, kSd1).packet(1, kT0Us + 1, std::vector<std::uint8_t>(60, 0xFF));
    test::write_file(file.path, b.bytes());
    OpenResult opened = open_source(file.path, InputFormat::Auto, kEthernetProtocol);
    ASSERT_TRUE(opened) << opened.error();
    std::vector<std::string> messages;
    opened.value()->on_issue([&](const InputIssue& issue) { messages.push_back(issue.message); });
    Record record;
    ASSERT_TRUE(opened.value()->next(record));
    EXPECT_EQ(record.number, 2u);
    EXPECT_FALSE(opened.value()->next(record));
    ASSERT_EQ(messages.size(), 1u);
    EXPECT_NE(messages[0].find("(it reads 1 EN10MB)"), std::string::npos) << messages[0];
}

TEST(PcapSourceTest, BadMagicWithPcapForcedIsAnError) {
    TempFile file("notpcap.bin");
    test::write_file(file.path, kSd2);
    std::string error = open_error(file.path, InputFormat::Pcap);
    EXPECT_NE(error.find(file.path), std::string::npos) << error;
    EXPECT_NE(error.find("not a readable pcap or pcapng file"), std::string::npos) << error;
    // The same with pcapng forced.
    EXPECT_NE(open_error(file.path, InputFormat::Pcapng).find(file.path), std::string::npos);
}

TEST(PcapSourceTest, TruncatedFileHeaderIsAnError) {
    TempFile file("short-header.pcap");
    std::vector<std::uint8_t> bytes = PcapBuilder(false, true, 257).bytes();
    bytes.resize(12);
    test::write_file(file.path, bytes);
    std::string error = open_error(file.path);
    EXPECT_NE(error.find(file.path), std::string::npos) << error;
    EXPECT_NE(error.find("not a readable pcap or pcapng file"), std::string::npos) << error;
}

TEST(PcapSourceTest, EmptyFileHasNoTelegrams) {
    TempFile file("empty.pcap");
    test::write_file(file.path, {});
    ReadResult r = read_all(file.path);
    EXPECT_TRUE(r.records.empty());
    EXPECT_TRUE(r.issues.empty());
    EXPECT_EQ(r.status, InputStatus::Ok);
    // As a pcap it is unusable.
    std::string error = open_error(file.path, InputFormat::Pcap);
    EXPECT_NE(error.find(file.path), std::string::npos) << error;
}

TEST(PcapSourceTest, DirectoryIsAnError) {
    std::string dir = test::temp_path("dir");
    ASSERT_EQ(mkdir(dir.c_str(), 0700), 0);
    std::string error = open_error(dir);
    rmdir(dir.c_str());
    EXPECT_EQ(error, dir + ": is a directory, not a capture file");
}

TEST(PcapSourceTest, MissingFileIsAnError) {
    std::string path = test::temp_path("missing.pcap");
    EXPECT_EQ(open_error(path), path + ": cannot open: No such file or directory");
}

// ---- damaged captures ------------------------------------------------------------------------

TEST(PcapSourceTest, TruncatedRecordDataStopsWithDamage) {
    TempFile file("cut.pcap");
    write_capture(file.path, CaptureFormat::Pcap, kLinkTypeProfibusDl);
    std::vector<std::uint8_t> bytes = test::read_file(file.path);
    ASSERT_EQ(bytes.size(), 24u + 16 + 6 + 16 + 13 + 16 + 3);
    bytes.resize(bytes.size() - 2);
    test::write_file(file.path, bytes);

    ReadResult r = read_all(file.path);
    expect_telegrams(r, {kTelegrams[0], kTelegrams[1]});
    EXPECT_EQ(r.status, InputStatus::Damaged);
    ASSERT_EQ(r.issues.size(), 1u);
    EXPECT_EQ(r.issues[0].severity, Severity::Error);
    const std::string& message = r.issues[0].message;
    EXPECT_EQ(message.rfind(file.path + ": record 3 (byte offset 75): ", 0), 0u) << message;
    EXPECT_NE(message.find("decoding stopped after 2 records"), std::string::npos) << message;
}

TEST(PcapSourceTest, TruncatedRecordHeaderStopsWithDamage) {
    TempFile file("cut-header.pcap");
    write_capture(file.path, CaptureFormat::Pcap, kLinkTypeProfibusDl);
    std::vector<std::uint8_t> bytes = test::read_file(file.path);
    bytes.resize(24 + 16 + 6 + 16 + 13 + 8);  // half of record 3's header
    test::write_file(file.path, bytes);

    ReadResult r = read_all(file.path);
    expect_telegrams(r, {kTelegrams[0], kTelegrams[1]});
    EXPECT_EQ(r.status, InputStatus::Damaged);
    ASSERT_EQ(r.issues.size(), 1u);
    EXPECT_NE(r.issues[0].message.find(file.path + ": record 3 (byte offset 75)"),
              std::string::npos)
        << r.issues[0].message;
}

TEST(PcapSourceTest, CorruptedRecordLengthStopsWithDamage) {
    TempFile file("bad-length.pcap");
    PcapBuilder pcap(false, true, 257);
    pcap.record(1'704'067'200, 1, kSd1).record(1'704'067'200, 2, kToken, 0x7FFFFFF0, 0x7FFFFFF0);
    test::write_file(file.path, pcap.bytes());

    ReadResult r = read_all(file.path);
    expect_telegrams(r, {{kSd1, kT0 + 1}});
    EXPECT_EQ(r.status, InputStatus::Damaged);
    ASSERT_EQ(r.issues.size(), 1u);
    EXPECT_NE(r.issues[0].message.find(file.path + ": record 2 (byte offset 46)"),
              std::string::npos)
        << r.issues[0].message;
}

// ---- Block reading: a regular classic pcap file's records are read a block of 256 KiB at a time
// by PcapSource itself; anything unusual goes to libpcap. Each test compares with libpcap's own
// reading of the same file.

struct LibpcapRecord {
    std::vector<std::uint8_t> bytes;
    std::int64_t time_ns;
    std::uint32_t length;
};

// Every record libpcap reads from `path` (nanosecond times, as PcapSource opens it), and whether
// it stopped on an error.
std::vector<LibpcapRecord> read_with_libpcap(const std::string& path, bool& error) {
    std::vector<LibpcapRecord> records;
    char errbuf[PCAP_ERRBUF_SIZE] = {};
    pcap_t* handle =
        pcap_open_offline_with_tstamp_precision(path.c_str(), PCAP_TSTAMP_PRECISION_NANO, errbuf);
    EXPECT_NE(handle, nullptr) << errbuf;
    error = false;
    if (!handle) return records;
    pcap_pkthdr* header = nullptr;
    const u_char* data = nullptr;
    int rc;
    while ((rc = pcap_next_ex(handle, &header, &data)) == 1)
        records.push_back(
            {std::vector<std::uint8_t>(data, data + header->caplen),
             static_cast<std::int64_t>(header->ts.tv_sec) * 1'000'000'000 + header->ts.tv_usec,
             header->len});
    error = rc != PCAP_ERROR_BREAK;
    pcap_close(handle);
    return records;
}

void expect_as_libpcap_reads(const std::string& path, std::size_t expected_records) {
    bool libpcap_error = false;
    const std::vector<LibpcapRecord> want = read_with_libpcap(path, libpcap_error);
    ReadResult r = read_all(path);
    ASSERT_EQ(want.size(), expected_records);
    ASSERT_EQ(r.records.size(), want.size());
    for (std::size_t i = 0; i < want.size(); ++i) {
        ASSERT_EQ(r.data[i], want[i].bytes) << "record " << i + 1;
        ASSERT_EQ(r.records[i].time_ns, want[i].time_ns == 0 ? kNoTime : want[i].time_ns)
            << "record " << i + 1;
        ASSERT_EQ(r.records[i].original_length, want[i].length) << "record " << i + 1;
        ASSERT_EQ(r.records[i].number, i + 1);
    }
    EXPECT_EQ(r.status == InputStatus::Damaged, libpcap_error);
}

// Records of 1 to 300 bytes, so that many cross a block's end, in each byte order and time
// precision.
TEST(PcapSourceTest, BlockReadingMatchesLibpcapAcrossManyBlocks) {
    for (bool big_endian : {false, true}) {
        for (bool nano : {false, true}) {
            TempFile file("blocks.pcap");
            PcapBuilder pcap(big_endian, nano, 257);
            std::vector<std::uint8_t> data;
            std::uint64_t offset = 24;
            std::vector<std::uint64_t> offsets;
            for (std::uint32_t i = 0; i < 8000; ++i) {
                data.assign(1 + (i * 37) % 300, static_cast<std::uint8_t>(i));
                offsets.push_back(offset);
                offset += 16 + data.size();
                pcap.record(1'704'067'200 + i / 1000,
                            (i * 7919) % (nano ? 1'000'000'000 : 1'000'000), data);
            }
            ASSERT_GT(pcap.bytes().size(), 4u * (1u << 18));
            test::write_file(file.path, pcap.bytes());
            expect_as_libpcap_reads(file.path, 8000);
            ReadResult r = read_all(file.path);
            for (std::size_t i = 0; i < r.records.size(); ++i)
                ASSERT_EQ(r.records[i].offset, offsets[i]) << "record " << i + 1;
        }
    }
}

// A record longer than the file's snapshot length, and the ones after it, are libpcap's.
TEST(PcapSourceTest, ARecordOverTheSnapshotLengthIsReadByLibpcap) {
    TempFile file("over-snaplen.pcap");
    PcapBuilder pcap(false, true, 257, 64);
    for (int i = 0; i < 100; ++i)
        pcap.record(1'704'067'200, static_cast<std::uint32_t>(i), kSd2);
    pcap.record(1'704'067'200, 100, std::vector<std::uint8_t>(100, 0x42));
    for (int i = 101; i < 200; ++i)
        pcap.record(1'704'067'200, static_cast<std::uint32_t>(i), kSd1);
    test::write_file(file.path, pcap.bytes());
    bool libpcap_error = false;
    const std::size_t records = read_with_libpcap(file.path, libpcap_error).size();
    expect_as_libpcap_reads(file.path, records);
}

// Cut inside a record far into the file: the message names that record and its byte offset,
// as libpcap's reading did.
TEST(PcapSourceTest, ACutFarIntoTheFileNamesTheRecordAndItsOffset) {
    TempFile file("cut-far.pcap");
    PcapBuilder pcap(false, true, 257);
    for (std::uint32_t i = 0; i < 30000; ++i)
        pcap.record(1'704'067'200, i, kSd2);
    std::vector<std::uint8_t> bytes = pcap.bytes();
    const std::size_t record_size = 16 + kSd2.size();
    bytes.resize(24 + 25000 * record_size + 20);  // into record 25,001's data
    test::write_file(file.path, bytes);
    ReadResult r = read_all(file.path);
    EXPECT_EQ(r.records.size(), 25000u);
    EXPECT_EQ(r.status, InputStatus::Damaged);
    ASSERT_EQ(r.issues.size(), 1u);
    const std::string where =
        fmt::format("{}: record 25001 (byte offset {}): ", file.path, 24 + 25000 * record_size);
    EXPECT_EQ(r.issues[0].message.rfind(where, 0), 0u) << r.issues[0].message;
    EXPECT_NE(r.issues[0].message.find("decoding stopped after 25000 records"), std::string::npos)
        << r.issues[0].message;
    expect_as_libpcap_reads(file.path, 25000);
}

TEST(PcapSourceTest, TruncatedPcapngNamesRecord) {
    TempFile file("cut.pcapng");
    write_capture(file.path, CaptureFormat::Pcapng, kLinkTypeProfibusDl);
    std::vector<std::uint8_t> bytes = test::read_file(file.path);
    bytes.resize(bytes.size() - 6);
    test::write_file(file.path, bytes);

    ReadResult r = read_all(file.path);
    expect_telegrams(r, {kTelegrams[0], kTelegrams[1]});
    EXPECT_EQ(r.status, InputStatus::Damaged);
    ASSERT_EQ(r.issues.size(), 1u);
    EXPECT_NE(r.issues[0].message.find(file.path + ": record 3 (byte offset "), std::string::npos)
        << r.issues[0].message;
}

TEST(PcapSourceTest, TruncatedSampleCapture) {
    std::string path = test::source_dir() + "/samples/truncated.pcap";
    ReadResult r = read_all(path);
    EXPECT_EQ(r.status, InputStatus::Damaged);
    EXPECT_EQ(r.records.size(), 101u);
    ASSERT_EQ(r.issues.size(), 1u);
    EXPECT_NE(r.issues[0].message.find("record 102 (byte offset 3098)"), std::string::npos)
        << r.issues[0].message;
}

}  // namespace
}  // namespace dpscope
