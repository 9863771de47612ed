// The bus a capture carries: the tag dpscope writes into USER0 pcap and pcapng captures, read
// back, and the choice of the bus for a capture read without --bus (capture/bus_tag.hpp).
#include "capture/bus_tag.hpp"

#include <gtest/gtest.h>
#include <pcap/pcap.h>

#include <string>
#include <vector>

#include "capture/capture_writer.hpp"
#include "capture/telegram_source.hpp"
#include "protocols/fc/fc_framing_rules.hpp"
#include "protocols/vlt2000/vlt2000_framing_rules.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::run_dpscope;

// An FC telegram: STX, LGE, ADR, the data, BCC (XOR of everything before it).
std::vector<std::uint8_t> fc_telegram(std::uint8_t adr, const std::vector<std::uint8_t>& data) {
    std::vector<std::uint8_t> t{0x02, static_cast<std::uint8_t>(data.size() + 2), adr};
    for (std::uint8_t b : data)
        t.push_back(b);
    t.push_back(fc_bcc_of(Bytes(t.data(), t.size())));
    return t;
}

// A master request and a drive response with a parameter (PKW) and process block, `pairs` times.
std::vector<std::uint8_t> fc_stream(int pairs) {
    std::vector<std::uint8_t> stream;
    for (int i = 0; i < pairs; ++i) {
        for (const auto& t :
             {fc_telegram(0x81, {0x10, 0x02, 0, 0, 0, 0, 0, 0, 0x04, 0x7C, 0, 0}),
              fc_telegram(0x01, {0x10, 0x02, 0, 0, 0, 0, 0, 0x10, 0x06, 0x03, 0, 0})})
            for (std::uint8_t b : t)
                stream.push_back(b);
    }
    return stream;
}

// PROFIBUS: an SD2 Data_Exchange request and its short acknowledge, `pairs` times.
std::vector<std::uint8_t> profibus_stream(int pairs) {
    std::vector<std::uint8_t> stream;
    const std::vector<std::uint8_t> sd1 = test::hex("10 03 02 49 4E 16");
    for (int i = 0; i < pairs; ++i)
        for (std::uint8_t b : sd1)
            stream.push_back(b);
    return stream;
}

std::string hex_log_of(const std::vector<std::uint8_t>& bytes, std::size_t per_line) {
    std::string text;
    for (std::size_t i = 0; i < bytes.size(); ++i) {
        static const char digits[] = "0123456789ABCDEF";
        text += digits[bytes[i] >> 4];
        text += digits[bytes[i] & 15];
        text += (i + 1) % per_line == 0 ? '\n' : ' ';
    }
    return text + "\n";
}

// Writes `stream` (one telegram a record: FC telegrams of 16 bytes) as a capture.
std::string write_capture(CaptureFormat format, int link_type, Protocol bus,
                          const std::vector<std::uint8_t>& records, std::size_t record_size) {
    std::string path =
        test::temp_path(format == CaptureFormat::Pcap ? "tagged.pcap" : "tagged.pcapng");
    WriterResult opened = open_capture_writer(path, format, link_type, bus);
    EXPECT_TRUE(opened) << opened.error();
    for (std::size_t at = 0; at + record_size <= records.size(); at += record_size)
        EXPECT_TRUE((*opened)->write(Bytes(records.data() + at, record_size), 1'000'000'000));
    EXPECT_TRUE((*opened)->close());
    return path;
}

Bytes bytes_of(const std::vector<std::uint8_t>& v) { return Bytes(v.data(), v.size()); }

TEST(BusTagTest, PcapHeaderCarriesMagicAndBusNumberInReservedFields) {
    std::string path =
        write_capture(CaptureFormat::Pcap, kLinkTypeUser0, Protocol::Fc, fc_stream(2), 16);
    std::vector<std::uint8_t> file = test::read_file(path);
    ASSERT_GE(file.size(), 24u);
    EXPECT_EQ(std::string(file.begin() + 8, file.begin() + 12), "dpsc");
    CaptureLabel label = read_capture_label(bytes_of(file));
    EXPECT_EQ(label.link_type, kLinkTypeUser0);
    ASSERT_TRUE(label.tagged);
    EXPECT_EQ(*label.tagged, Protocol::Fc);
    ASSERT_TRUE(label.first_byte);
    EXPECT_EQ(*label.first_byte, 0x02);
    // libpcap ignores the fields and reads the file as before.
    char errbuf[PCAP_ERRBUF_SIZE] = {};
    pcap_t* handle = pcap_open_offline(path.c_str(), errbuf);
    ASSERT_NE(handle, nullptr) << errbuf;
    EXPECT_EQ(pcap_datalink(handle), kLinkTypeUser0);
    int records = 0;
    pcap_pkthdr* header = nullptr;
    const u_char* data = nullptr;
    while (pcap_next_ex(handle, &header, &data) == 1)
        ++records;
    pcap_close(handle);
    EXPECT_EQ(records, 4);
}

TEST(BusTagTest, ProfibusUser0IsTaggedAnd257IsLeftAsLibpcapWritesIt) {
    std::string user0 = write_capture(CaptureFormat::Pcap, kLinkTypeUser0, Protocol::ProfibusDp,
                                      profibus_stream(2), 6);
    CaptureLabel label = read_capture_label(bytes_of(test::read_file(user0)));
    ASSERT_TRUE(label.tagged);
    EXPECT_EQ(*label.tagged, Protocol::ProfibusDp);
    std::string dl = write_capture(CaptureFormat::Pcap, kLinkTypeProfibusDl, Protocol::ProfibusDp,
                                   profibus_stream(2), 6);
    std::vector<std::uint8_t> file = test::read_file(dl);
    EXPECT_EQ(std::vector<std::uint8_t>(file.begin() + 8, file.begin() + 16),
              std::vector<std::uint8_t>(8, 0));
    EXPECT_FALSE(read_capture_label(bytes_of(file)).tagged);
}

TEST(BusTagTest, PcapngInterfaceDescriptionNamesTheBus) {
    std::string path =
        write_capture(CaptureFormat::Pcapng, kLinkTypeUser0, Protocol::Fc, fc_stream(2), 16);
    std::vector<std::uint8_t> file = test::read_file(path);
    std::string text(file.begin(), file.end());
    EXPECT_NE(text.find("dpscope bus=fc"), std::string::npos);
    CaptureLabel label = read_capture_label(bytes_of(file));
    EXPECT_EQ(label.link_type, kLinkTypeUser0);
    ASSERT_TRUE(label.tagged);
    EXPECT_EQ(*label.tagged, Protocol::Fc);
    ASSERT_TRUE(label.first_byte);
    EXPECT_EQ(*label.first_byte, 0x02);
    // dpscope's pcapng reader still reads every record.
    OpenResult opened = open_source(path, InputFormat::Auto, fc_protocol());
    ASSERT_TRUE(opened) << opened.error();
    Record record;
    int records = 0;
    while ((*opened)->next(record))
        ++records;
    EXPECT_EQ(records, 4);
    EXPECT_EQ((*opened)->status(), InputStatus::Ok);
}

TEST(BusTagTest, TagIsWrittenIntoAPipeToo) {
    // A pipe cannot seek: the header is tagged on its way through.
    int fds[2];
    ASSERT_EQ(pipe(fds), 0);
    FILE* in = fdopen(fds[1], "wb");
    WriterResult opened =
        open_capture_writer(in, "<pipe>", CaptureFormat::Pcap, kLinkTypeUser0, Protocol::Fc);
    ASSERT_TRUE(opened) << opened.error();
    std::vector<std::uint8_t> stream = fc_stream(1);
    ASSERT_TRUE((*opened)->write(Bytes(stream.data(), 16), 5));
    ASSERT_TRUE((*opened)->close());
    std::vector<std::uint8_t> got(4096);
    std::size_t n = 0;
    for (ssize_t r; (r = read(fds[0], got.data() + n, got.size() - n)) > 0;)
        n += static_cast<std::size_t>(r);
    close(fds[0]);
    got.resize(n);
    ASSERT_EQ(got.size(), 24u + 16u + 16u);
    CaptureLabel label = read_capture_label(bytes_of(got));
    ASSERT_TRUE(label.tagged);
    EXPECT_EQ(*label.tagged, Protocol::Fc);
    EXPECT_EQ(got[40], 0x02);
}

// The line a capture was made on (sniff -w) is recorded beside the bus: in a pcap's tag (any
// link type once the line is known), in pcapng as if_speed and a comment naming the frame.
TEST(BusTagTest, CapturesRecordTheLineTheyWereMadeOn) {
    const LineSettings line{19200, SerialParity::Odd, 2};
    auto write_with_line = [&](CaptureFormat format, int link_type, Protocol bus,
                               const LineSettings& with) {
        const std::string path =
            test::temp_path(format == CaptureFormat::Pcap ? "line.pcap" : "line.pcapng");
        WriterResult opened = open_capture_writer(path, format, link_type, bus, with);
        EXPECT_TRUE(opened) << opened.error();
        const std::vector<std::uint8_t> stream = fc_stream(1);
        EXPECT_TRUE((*opened)->write(Bytes(stream.data(), 16), 1'000'000'000));
        EXPECT_TRUE((*opened)->close());
        return path;
    };
    for (CaptureFormat format : {CaptureFormat::Pcap, CaptureFormat::Pcapng}) {
        const std::string path = write_with_line(format, kLinkTypeUser0, Protocol::Fc, line);
        CaptureLabel label = read_capture_label(bytes_of(test::read_file(path)));
        ASSERT_TRUE(label.tagged);
        EXPECT_EQ(*label.tagged, Protocol::Fc);
        EXPECT_EQ(label.line, line) << capture_format_name(format);
        EXPECT_EQ(describe_line(label.line), "19200 baud 8O2");
        // libpcap (and so tcpdump and Wireshark) reads it as before.
        char errbuf[PCAP_ERRBUF_SIZE] = {};
        pcap_t* handle = pcap_open_offline(path.c_str(), errbuf);
        ASSERT_NE(handle, nullptr) << errbuf;
        pcap_pkthdr* header = nullptr;
        const u_char* data = nullptr;
        EXPECT_EQ(pcap_next_ex(handle, &header, &data), 1);
        pcap_close(handle);
    }
    // PROFIBUS (link type 257): tagged once the line is known, and a PROFIBUS tag whatever bus
    // the caller names.
    const std::string dl = write_with_line(CaptureFormat::Pcap, kLinkTypeProfibusDl, Protocol::Fc,
                                           {1'500'000, SerialParity::Even, 1});
    CaptureLabel label = read_capture_label(bytes_of(test::read_file(dl)));
    ASSERT_TRUE(label.tagged);
    EXPECT_EQ(*label.tagged, Protocol::ProfibusDp);
    EXPECT_EQ(label.line, (LineSettings{1'500'000, SerialParity::Even, 1}));
    // Only the baud rate known (decode --baud): the frame stays unknown.
    const std::string baud_only = write_with_line(CaptureFormat::Pcapng, kLinkTypeUser0,
                                                  Protocol::Fc, {38400, std::nullopt, 0});
    label = read_capture_label(bytes_of(test::read_file(baud_only)));
    EXPECT_EQ(label.line, (LineSettings{38400, std::nullopt, 0}));
    EXPECT_EQ(describe_line(label.line), "38400 baud");
}

TEST(BusTagTest, ThePcapTagWordHoldsBusAndLineInEitherByteOrder) {
    const LineSettings line{12'000'000, SerialParity::None, 1};
    EXPECT_EQ(pcap_tag_word(Protocol::Vlt2000, line), 3u | 1u << 4 | 1u << 6 | 12'000'000u << 8);
    for (bool big : {false, true}) {
        std::uint8_t header[24] = {};
        const std::uint8_t magic[4] = {0xA1, 0xB2, 0x3C, 0x4D};
        for (int i = 0; i < 4; ++i)
            header[i] = magic[big ? i : 3 - i];
        header[big ? 23 : 20] = 147;
        put_pcap_bus_tag(header, Protocol::Vlt2000, line);
        CaptureLabel label = read_capture_label(Bytes(header, sizeof header));
        ASSERT_TRUE(label.tagged) << big;
        EXPECT_EQ(*label.tagged, Protocol::Vlt2000);
        EXPECT_EQ(label.line, line) << big;
        // A tag as dpscope wrote it before the line was recorded: the bus alone.
        put_pcap_bus_tag(header, Protocol::Fc);
        label = read_capture_label(Bytes(header, sizeof header));
        ASSERT_TRUE(label.tagged);
        EXPECT_EQ(*label.tagged, Protocol::Fc);
        EXPECT_FALSE(label.line.known());
        EXPECT_FALSE(label.line.frame_known());
    }
}

TEST(BusTagTest, TheLineIsWrittenIntoAPipeToo) {
    int fds[2];
    ASSERT_EQ(pipe(fds), 0);
    FILE* in = fdopen(fds[1], "wb");
    const LineSettings line{9600, SerialParity::Even, 1};
    WriterResult opened =
        open_capture_writer(in, "<pipe>", CaptureFormat::Pcap, kLinkTypeUser0, Protocol::Fc, line);
    ASSERT_TRUE(opened) << opened.error();
    ASSERT_TRUE((*opened)->close());
    std::vector<std::uint8_t> got(4096);
    std::size_t n = 0;
    for (ssize_t r; (r = read(fds[0], got.data() + n, got.size() - n)) > 0;)
        n += static_cast<std::size_t>(r);
    close(fds[0]);
    got.resize(n);
    CaptureLabel label = read_capture_label(bytes_of(got));
    EXPECT_EQ(label.line, line);
}

// An FC capture made at 19200 baud 8E1: a 16-byte command takes 9.2 ms on the line, the drive
// answers 12 ms after it began (2.8 ms after its end). Read without --baud it is timed at the
// rate it records, as with --baud 19200; --baud 9600 wins, with a warning; decode -w keeps it.
TEST(BusTagTest, DecodeReportAndStatsReadTheLineACaptureRecords) {
    const std::string pcap = test::temp_path("fc-19200.pcap");
    {
        WriterResult opened = open_capture_writer(pcap, CaptureFormat::Pcap, kLinkTypeUser0,
                                                  Protocol::Fc, {19200, SerialParity::Even, 1});
        ASSERT_TRUE(opened) << opened.error();
        const std::vector<std::uint8_t> command = test::fc_parameter(1, 1, 414);
        const std::vector<std::uint8_t> response = test::fc_parameter(1, 1, 414, 0, 1500, 0x0607);
        ASSERT_EQ(command.size(), 16u);
        std::int64_t t = 1'700'000'000'000'000'000;
        for (int i = 0; i < 20; ++i, t += 100'000'000) {
            ASSERT_TRUE((*opened)->write(bytes_of(command), t));
            ASSERT_TRUE((*opened)->write(bytes_of(response), t + 12'000'000));
        }
        ASSERT_TRUE((*opened)->close());
    }
    test::CommandResult recorded = run_dpscope({"report", pcap});
    test::CommandResult given = run_dpscope({"report", "--baud", "19200", pcap});
    EXPECT_EQ(recorded.err, "");
    EXPECT_EQ(given.err, "");
    EXPECT_EQ(recorded.out, given.out);
    EXPECT_NE(recorded.out.find("mean 2.833"), std::string::npos) << recorded.out;
    test::CommandResult other = run_dpscope({"report", "--baud", "9600", pcap});
    EXPECT_NE(other.err.find(pcap + ": the capture records its line as 19200 baud 8E1, but --baud "
                                    "says 9600; timed at 9600 baud, as --baud says"),
              std::string::npos)
        << other.err;
    EXPECT_NE(other.out, recorded.out);
    // decode -w carries the line into the capture it writes, pcap and pcapng.
    for (const char* format : {"pcap", "pcapng"}) {
        const std::string out = test::temp_path(std::string("copy.") + format);
        test::CommandResult w = run_dpscope({"decode", pcap, "-w", out, "-F", format});
        ASSERT_EQ(w.exit_code, 0) << w.err;
        CaptureLabel label = read_capture_label(bytes_of(test::read_file(out)));
        EXPECT_EQ(label.line, (LineSettings{19200, SerialParity::Even, 1})) << format;
        const std::string copied = run_dpscope({"report", out}).out;
        EXPECT_EQ(copied.substr(copied.find("Checks:")),
                  recorded.out.substr(recorded.out.find("Checks:")))
            << format;
    }
    // PROFIBUS: stats gives the bus load at the rate recorded, not "unknown (give --baud)".
    const std::string dl = test::temp_path("profibus-line.pcap");
    {
        WriterResult opened =
            open_capture_writer(dl, CaptureFormat::Pcap, kLinkTypeProfibusDl, Protocol::ProfibusDp,
                                {19200, SerialParity::Even, 1});
        ASSERT_TRUE(opened) << opened.error();
        const std::vector<std::uint8_t> stream = profibus_stream(10);
        for (std::size_t at = 0; at < stream.size(); at += 6)
            ASSERT_TRUE((*opened)->write(
                Bytes(stream.data() + at, 6),
                1'700'000'000'000'000'000 + static_cast<std::int64_t>(at) * 1'000'000));
        ASSERT_TRUE((*opened)->close());
    }
    test::CommandResult stats = run_dpscope({"stats", dl});
    EXPECT_NE(stats.out.find("at 19200 baud"), std::string::npos) << stats.out << stats.err;
    EXPECT_EQ(stats.out.find("give --baud"), std::string::npos) << stats.out;
}

TEST(BusTagTest, UntaggedUser0IsChosenByItsFirstRecord) {
    // Untagged: as another tool writes USER0 (the reserved fields zero).
    for (auto [bus, records, size] :
         {std::tuple{Protocol::Fc, fc_stream(1), std::size_t{16}},
          std::tuple{Protocol::ProfibusDp, profibus_stream(1), std::size_t{6}}}) {
        std::string path = write_capture(CaptureFormat::Pcap, kLinkTypeUser0, bus, records, size);
        std::vector<std::uint8_t> file = test::read_file(path);
        std::fill(file.begin() + 8, file.begin() + 16, 0);
        BusChoice choice = choose_bus(bytes_of(file), InputFormat::Pcap, true);
        EXPECT_FALSE(choice.tagged);
        EXPECT_EQ(choice.protocol->protocol, bus);
        EXPECT_EQ(choice.say, bus == Protocol::Fc);  // PROFIBUS is today's reading
    }
}

// A live capture saved from Wireshark: dumpcap writes its own pcapng, whose interface description
// is the extcap interface's display text, not dpscope's tag. The first record still chooses.
TEST(BusTagTest, PcapngAsDumpcapWritesAnExtcapCaptureIsChosenByItsFirstRecord) {
    auto block = [](std::uint32_t type, std::vector<std::uint8_t> body) {
        while (body.size() % 4 != 0)
            body.push_back(0);
        const auto length = static_cast<std::uint32_t>(body.size() + 12);
        std::vector<std::uint8_t> out;
        for (std::uint32_t word : {type, length})
            for (int i = 0; i < 4; ++i)
                out.push_back(static_cast<std::uint8_t>(word >> (8 * i)));
        out.insert(out.end(), body.begin(), body.end());
        for (int i = 0; i < 4; ++i)
            out.push_back(static_cast<std::uint8_t>(length >> (8 * i)));
        return out;
    };
    const std::vector<std::uint8_t> shb =
        block(0x0A0D0D0A,
              {0x4D, 0x3C, 0x2B, 0x1A, 1, 0, 0, 0, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF});
    const std::string display = "dpscope: serial bus sniffer on /dev/ttyUSB0";
    std::vector<std::uint8_t> idb_body = {147, 0, 0, 0, 0xFF, 0xFF, 0, 0, 3, 0};
    idb_body.push_back(static_cast<std::uint8_t>(display.size()));
    idb_body.push_back(0);
    idb_body.insert(idb_body.end(), display.begin(), display.end());
    while (idb_body.size() % 4 != 0)
        idb_body.push_back(0);
    for (int i = 0; i < 4; ++i)
        idb_body.push_back(0);  // opt_endofopt
    for (auto [bus, record] :
         {std::pair{Protocol::Fc, fc_stream(1)},
          std::pair{Protocol::Vlt2000, std::vector<std::uint8_t>({'<', '0', '1', 'C'})},
          std::pair{Protocol::ProfibusDp, profibus_stream(1)}}) {
        std::vector<std::uint8_t> epb_body(20, 0);
        epb_body[12] = epb_body[16] = static_cast<std::uint8_t>(record.size());
        epb_body.insert(epb_body.end(), record.begin(), record.end());
        std::vector<std::uint8_t> file = shb;
        for (const std::vector<std::uint8_t>& b : {block(1, idb_body), block(6, epb_body)})
            file.insert(file.end(), b.begin(), b.end());
        BusChoice choice = choose_bus(bytes_of(file), InputFormat::Pcapng, true);
        EXPECT_FALSE(choice.tagged);
        EXPECT_EQ(choice.protocol->protocol, bus) << choice.reason;
    }
}

TEST(BusTagTest, Linktype257IsAlwaysProfibus) {
    std::vector<std::uint8_t> records = fc_stream(1);
    std::string path =
        write_capture(CaptureFormat::Pcap, kLinkTypeProfibusDl, Protocol::Fc, records, 16);
    BusChoice choice = choose_bus(bytes_of(test::read_file(path)), InputFormat::Pcap, true);
    EXPECT_EQ(choice.protocol->protocol, Protocol::ProfibusDp);
    EXPECT_FALSE(choice.say);
}

TEST(BusTagTest, RawAndHexStreamsAreChosenByTheFramingThatFramesMost) {
    std::vector<std::uint8_t> fc = fc_stream(20);
    BusChoice raw_fc = choose_bus(bytes_of(fc), InputFormat::Raw, true);
    EXPECT_EQ(raw_fc.protocol->protocol, Protocol::Fc);
    EXPECT_TRUE(raw_fc.say);
    EXPECT_NE(raw_fc.reason.find("40 telegrams framed in the first 640 bytes"), std::string::npos)
        << raw_fc.reason;
    std::vector<std::uint8_t> dp = profibus_stream(20);
    BusChoice raw_dp = choose_bus(bytes_of(dp), InputFormat::Raw, true);
    EXPECT_EQ(raw_dp.protocol->protocol, Protocol::ProfibusDp);
    EXPECT_TRUE(raw_dp.say) << "a byte stream names no bus: the choice is said";
    std::string log = hex_log_of(fc, 16);
    BusChoice hex_fc =
        choose_bus(Bytes(reinterpret_cast<const std::uint8_t*>(log.data()), log.size()),
                   InputFormat::Hex, true);
    EXPECT_EQ(hex_fc.protocol->protocol, Protocol::Fc);
    EXPECT_NE(hex_fc.reason.find("hex bytes"), std::string::npos) << hex_fc.reason;
}

TEST(BusTagTest, EmptyOrGarbageInputStaysProfibus) {
    BusChoice empty = choose_bus({}, InputFormat::Raw, true);
    EXPECT_EQ(empty.protocol->protocol, Protocol::ProfibusDp);
    EXPECT_FALSE(empty.say);
    std::vector<std::uint8_t> garbage;
    for (int i = 0; i < 1000; ++i)
        garbage.push_back(static_cast<std::uint8_t>(i * 37 + 11));
    BusChoice choice = choose_bus(bytes_of(garbage), InputFormat::Raw, true);
    EXPECT_EQ(choice.protocol->protocol, Protocol::ProfibusDp);
    // A truncated pcap header decides nothing and stays PROFIBUS.
    std::vector<std::uint8_t> cut = test::hex("D4 C3 B2 A1 02 00");
    EXPECT_EQ(choose_bus(bytes_of(cut), InputFormat::Pcap, true).protocol->protocol,
              Protocol::ProfibusDp);
}

TEST(BusTagTest, AStreamStillArrivingWaitsUntilItDecides) {
    std::vector<std::uint8_t> few = fc_stream(2);
    EXPECT_TRUE(choose_bus(bytes_of(few), InputFormat::Raw, false).need_more);
    std::vector<std::uint8_t> many = fc_stream(20);
    BusChoice decided = choose_bus(bytes_of(many), InputFormat::Raw, false);
    EXPECT_FALSE(decided.need_more);
    EXPECT_EQ(decided.protocol->protocol, Protocol::Fc);
}

TEST(BusTagTest, OpenSourceChoosesTheBusFromAFileAndFromStandardInput) {
    std::string raw = test::temp_path("fc.raw");
    test::write_file(raw, fc_stream(20));
    BusChoice choice;
    OpenResult opened = open_source(raw, InputFormat::Auto, nullptr, choice);
    ASSERT_TRUE(opened) << opened.error();
    EXPECT_EQ(choice.protocol->protocol, Protocol::Fc);
    Record record;
    int telegrams = 0;
    while ((*opened)->next(record))
        ++telegrams;
    EXPECT_EQ(telegrams, 40);
    // Standard input: the bytes looked at are not lost.
    std::vector<std::uint8_t> stream = fc_stream(20);
    test::CommandResult r =
        run_dpscope({"decode", "-T", "jsonl", "-"}, std::string(stream.begin(), stream.end()));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(test::lines_of(r.out).size(), 40u);
    EXPECT_EQ(r.err,
              "dpscope: note: <stdin>: read as the FC protocol (RS-485): 40 telegrams framed in "
              "the first 640 bytes, none by PROFIBUS framing; --bus chooses\n");
}

TEST(BusTagTest, DecodeWritesTaggedCapturesThatDecodeReadsWithoutBus) {
    std::string raw = test::temp_path("fc.raw");
    test::write_file(raw, fc_stream(3));
    for (const char* format : {"pcap", "pcapng"}) {
        std::string out = test::temp_path(std::string("fc.") + format);
        test::CommandResult w =
            run_dpscope({"decode", "--bus", "fc", raw, "-w", out, "-F", format});
        ASSERT_EQ(w.exit_code, 0) << w.err;
        EXPECT_EQ(w.err, "");
        CaptureLabel label = read_capture_label(bytes_of(test::read_file(out)));
        EXPECT_EQ(label.link_type, kLinkTypeUser0) << format;  // the FC default
        ASSERT_TRUE(label.tagged) << format;
        test::CommandResult r = run_dpscope({"decode", "-T", "jsonl", out});
        EXPECT_EQ(r.exit_code, 0) << r.err;
        EXPECT_EQ(r.err, "") << format;  // tagged: no note
        EXPECT_EQ(test::lines_of(r.out).size(), 6u);
        EXPECT_NE(r.out.find("\"fc_protocol\""), std::string::npos) << r.out.substr(0, 300);
        // --bus naming the other bus is obeyed, with a warning naming both.
        test::CommandResult other = run_dpscope({"decode", "--bus", "profibus", "-q", out});
        EXPECT_NE(other.err.find(out + ": the capture records its bus as the FC protocol "
                                       "(RS-485), but --bus profibus says PROFIBUS DP"),
                  std::string::npos)
            << other.err;
    }
    // Standard output: tagged as well.
    test::CommandResult piped = run_dpscope({"decode", "--bus", "fc", raw, "-w", "-"});
    ASSERT_EQ(piped.exit_code, 0) << piped.err;
    std::vector<std::uint8_t> file(piped.out.begin(), piped.out.end());
    CaptureLabel label = read_capture_label(bytes_of(file));
    ASSERT_TRUE(label.tagged);
    EXPECT_EQ(*label.tagged, Protocol::Fc);
}

TEST(BusTagTest, LinkType257IsRefusedForTheFcBus) {
    std::string raw = test::temp_path("fc.raw");
    test::write_file(raw, fc_stream(3));
    std::string out = test::temp_path("refused.pcap");
    test::CommandResult r =
        run_dpscope({"decode", "--bus", "fc", raw, "-w", out, "--linktype", "profibus"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--linktype profibus: link type 257 (PROFIBUS_DL) is PROFIBUS only"),
              std::string::npos)
        << r.err;
}

TEST(BusTagTest, ProfibusRawDumpsSayTheBusChosenAndGiveTheSameDecode) {
    std::string raw = test::temp_path("dp.raw");
    test::write_file(raw, profibus_stream(10));
    test::CommandResult r = run_dpscope({"decode", raw});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err.rfind("dpscope: note: " + raw + ": read as PROFIBUS DP: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("none by FC protocol framing; --bus chooses"), std::string::npos) << r.err;
    test::CommandResult given = run_dpscope({"decode", "--bus", "profibus", raw});
    EXPECT_EQ(given.err, "") << "with --bus nothing is said";
    EXPECT_EQ(given.out, r.out);
}

TEST(BusTagTest, NoTelegramErrorNamesTheBusTriedAndSuggestsBus) {
    std::string raw = test::temp_path("fc-cut.raw");
    // FC-looking bytes, all with a bad BCC and no telegram of either bus.
    test::write_file(raw, {0x02, 0x0E, 0x81, 0x10});
    test::CommandResult r = run_dpscope({"decode", "--bus", "fc", raw});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("no FC protocol telegram in its 4 bytes"), std::string::npos) << r.err;
    test::CommandResult chosen = run_dpscope({"decode", raw});
    EXPECT_NE(chosen.err.find("no PROFIBUS telegram in its 4 bytes read as a raw byte stream; is "
                              "it a capture? (read as PROFIBUS DP; --bus chooses the bus)"),
              std::string::npos)
        << chosen.err;
}

TEST(BusTagTest, HexArgumentsChooseTheBusToo) {
    std::vector<std::uint8_t> t = fc_stream(1);
    std::string text = hex_log_of(t, 100);
    test::CommandResult r = run_dpscope({"hex", "-T", "jsonl", text});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(test::lines_of(r.out).size(), 2u);
    EXPECT_NE(r.out.find("\"fc_protocol\""), std::string::npos) << r.out;
    // Typed telegrams only the FC protocol frames: a plain choice, not said (issue 27).
    EXPECT_EQ(r.err, "");
}

TEST(BusTagTest, DecodeAndReportSayTheChoiceForUntaggedUser0AndHexLogs) {
    // An untagged USER0 capture, as another tool writes it: chosen by its first record, and said.
    std::string path =
        write_capture(CaptureFormat::Pcap, kLinkTypeUser0, Protocol::Fc, fc_stream(2), 16);
    std::vector<std::uint8_t> file = test::read_file(path);
    std::fill(file.begin() + 8, file.begin() + 16, 0);
    test::write_file(path, file);
    for (const char* command : {"decode", "report"}) {
        test::CommandResult r = run_dpscope({command, path});
        EXPECT_NE(r.err.find("dpscope: note: " + path +
                             ": read as the FC protocol (RS-485): a USER0 capture without a bus "
                             "tag whose first record starts with STX (0x02); --bus chooses"),
                  std::string::npos)
            << command << ": " << r.err;
    }
    // A hex log of FC telegrams.
    std::string log = test::temp_path("fc.txt");
    test::write_text_file(log, hex_log_of(fc_stream(5), 16));
    test::CommandResult r = run_dpscope({"decode", "-T", "jsonl", log});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(test::lines_of(r.out).size(), 10u);
    EXPECT_NE(r.err.find("10 telegrams framed in the first 160 hex bytes"), std::string::npos)
        << r.err;
}

// VLT 2000: a command and its reply (the VLT 3000 manual's example; checksums computed), `pairs`
// times, as the ASCII characters go over the line.
std::vector<std::uint8_t> vlt2000_stream(int pairs) {
    std::vector<std::uint8_t> stream;
    for (int i = 0; i < pairs; ++i)
        for (std::string_view t : {"<01UOGD@0516+00080007>", "<01UGHK@0516+00080007>"})
            stream.insert(stream.end(), t.begin(), t.end());
    return stream;
}

TEST(BusTagTest, Vlt2000StreamExampleTelegramsHaveTheirChecksum) {
    std::vector<std::uint8_t> one = vlt2000_stream(1);
    EXPECT_TRUE(vlt2000_checksum_matches(Bytes(one.data(), 22)));
    EXPECT_TRUE(vlt2000_checksum_matches(Bytes(one.data() + 22, 22)));
}

TEST(BusTagTest, Vlt2000RawDumpsAreChosenByFramingAndAsciiDumpsAreTextLogs) {
    // Line noise before the telegrams: no text, a raw byte stream.
    std::vector<std::uint8_t> noisy{0xFF, 0x00, 0x83};
    for (std::uint8_t b : vlt2000_stream(20))
        noisy.push_back(b);
    EXPECT_EQ(detect_input_format(bytes_of(noisy)), InputFormat::Raw);
    BusChoice raw = choose_bus(bytes_of(noisy), InputFormat::Raw, true);
    EXPECT_EQ(raw.protocol->protocol, Protocol::Vlt2000);
    EXPECT_TRUE(raw.say);
    EXPECT_NE(raw.reason.find("40 telegrams framed in the first 883 bytes"), std::string::npos)
        << raw.reason;
    // Still arriving: decided once 32 telegrams are framed.
    EXPECT_FALSE(choose_bus(bytes_of(noisy), InputFormat::Raw, false).need_more);
    EXPECT_TRUE(choose_bus(Bytes(noisy.data(), 200), InputFormat::Raw, false).need_more);
    // Only the ASCII characters: a text log on one line, VLT 2000 by its kind.
    std::vector<std::uint8_t> ascii = vlt2000_stream(20);
    EXPECT_EQ(detect_input_format(bytes_of(ascii)), InputFormat::Text);
    BusChoice text = choose_bus(bytes_of(ascii), InputFormat::Text, false);
    EXPECT_EQ(text.protocol->protocol, Protocol::Vlt2000);
    EXPECT_FALSE(text.need_more);
    // Either way through decode, with the skipped noise named in VLT 2000 words.
    std::string path = test::temp_path("vlt.raw");
    test::write_file(path, noisy);
    test::CommandResult r = run_dpscope({"decode", "-T", "jsonl", path});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(test::lines_of(r.out).size(), 40u);
    EXPECT_NE(r.err.find("read as the VLT 2000 telegram: 40 telegrams framed"), std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find(path + ": byte offset 0: skipped 3 bytes: no '<'"), std::string::npos)
        << r.err;
}

TEST(BusTagTest, Vlt2000RawDumpResynchronisesAfterGarbageAndABrokenTelegram) {
    std::vector<std::uint8_t> stream = vlt2000_stream(2);
    const std::string cut = "<01UOGD@05";  // a telegram cut short, the next one right behind it
    stream.insert(stream.begin() + 22, cut.begin(), cut.end());
    stream.insert(stream.begin(), {0x00, 0x7F});
    std::string path = test::temp_path("vlt-broken.raw");
    test::write_file(path, stream);
    test::CommandResult r =
        run_dpscope({"decode", "--bus", "vlt2000", "--input-format", "raw", "-T", "jsonl", path});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(test::lines_of(r.out).size(), 4u) << r.out;
    EXPECT_NE(r.err.find(path + ": byte offset 0: skipped 2 bytes: no '<'"), std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find(path + ": byte offset 24: skipped 10 bytes: no '>' at the telegram's end"),
              std::string::npos)
        << r.err;
}

TEST(BusTagTest, Vlt2000CapturesAreWrittenTaggedAndReadBackWithoutBus) {
    std::string log = test::temp_path("vlt.log");
    std::vector<std::uint8_t> stream = vlt2000_stream(2);
    std::string text;
    for (std::size_t at = 0; at < stream.size(); at += 22)
        text += "TX: " +
                std::string(stream.begin() + static_cast<std::ptrdiff_t>(at),
                            stream.begin() + static_cast<std::ptrdiff_t>(at + 22)) +
                "\n";
    test::write_text_file(log, text);
    for (const char* format : {"pcap", "pcapng"}) {
        std::string out = test::temp_path(std::string("vlt.") + format);
        test::CommandResult w = run_dpscope({"decode", log, "-w", out, "-F", format});
        ASSERT_EQ(w.exit_code, 0) << w.err;
        CaptureLabel label = read_capture_label(bytes_of(test::read_file(out)));
        EXPECT_EQ(label.link_type, kLinkTypeUser0) << format;
        ASSERT_TRUE(label.tagged) << format;
        EXPECT_EQ(*label.tagged, Protocol::Vlt2000);
        test::CommandResult r = run_dpscope({"decode", "-T", "jsonl", out});
        EXPECT_EQ(r.exit_code, 0) << r.err;
        EXPECT_EQ(r.err, "") << format;  // tagged: no note
        EXPECT_EQ(test::lines_of(r.out).size(), 4u);
        EXPECT_NE(r.out.find("\"len\":22,"), std::string::npos) << r.out.substr(0, 300);
    }
    // The hex command's bytes are written tagged as well.
    std::string out = test::temp_path("vlt-hex.pcap");
    test::CommandResult h = run_dpscope({"hex", hex_log_of(vlt2000_stream(1), 100), "-w", out});
    ASSERT_EQ(h.exit_code, 0) << h.err;
    CaptureLabel label = read_capture_label(bytes_of(test::read_file(out)));
    ASSERT_TRUE(label.tagged);
    EXPECT_EQ(*label.tagged, Protocol::Vlt2000);
    // Untagged, as another tool writes USER0: the first record's '<' chooses, and that is said.
    std::string path = write_capture(CaptureFormat::Pcap, kLinkTypeUser0, Protocol::Vlt2000,
                                     vlt2000_stream(2), 22);
    std::vector<std::uint8_t> file = test::read_file(path);
    std::fill(file.begin() + 8, file.begin() + 16, 0);
    BusChoice choice = choose_bus(bytes_of(file), InputFormat::Pcap, true);
    EXPECT_FALSE(choice.tagged);
    EXPECT_EQ(choice.protocol->protocol, Protocol::Vlt2000);
    EXPECT_TRUE(choice.say);
    test::write_file(path, file);
    test::CommandResult r = run_dpscope({"decode", "-q", path});
    EXPECT_NE(r.err.find("read as the VLT 2000 telegram: a USER0 capture without a bus tag whose "
                         "first record starts with '<'; --bus chooses"),
              std::string::npos)
        << r.err;
}

TEST(BusTagTest, LinkType257IsRefusedForTheVlt2000Bus) {
    std::string raw = test::temp_path("vlt.raw");
    test::write_file(raw, vlt2000_stream(2));
    std::string out = test::temp_path("refused.pcap");
    test::CommandResult r = run_dpscope({"decode", raw, "-w", out, "--linktype", "profibus"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--linktype profibus: link type 257 (PROFIBUS_DL) is PROFIBUS only; a "
                         "capture of VLT 2000 is written as user0 (147)"),
              std::string::npos)
        << r.err;
}

}  // namespace
}  // namespace dpscope
