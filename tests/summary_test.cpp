// The decode summary: counts by frame type, service, problem kind and finding kind, per-slave
// Data_Exchange counts, and the text `decode -q` prints.
#include "formats/summary.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "protocols/fc/fc_bus_model.hpp"
#include "protocols/fc/fc_decoder.hpp"
#include "protocols/fc/fc_tracker.hpp"
#include "protocols/profibus/bus_decoder.hpp"
#include "protocols/profibus/telegram_builder.hpp"
#include "protocols/vlt2000/vlt2000_bus_model.hpp"
#include "protocols/vlt2000/vlt2000_decoder.hpp"
#include "protocols/vlt2000/vlt2000_tracker.hpp"
#include "simulator/simulator.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::hex;

constexpr std::int64_t kT0 = 1'704'067'200'000'000'000;  // 2024-01-01T00:00:00Z
constexpr std::int64_t kMs = 1'000'000;

struct Input {
    std::vector<std::uint8_t> bytes;
    std::int64_t time_ns;
};

std::vector<std::uint8_t> data_exchange(std::uint8_t da, std::uint8_t sa, bool request,
                                        std::vector<std::uint8_t> du) {
    std::uint8_t fc =
        request ? request_fc(FdlFunction::SrdHigh, true, true) : response_fc(FdlStatus::DataLow);
    return build_telegram({da, sa, fc, std::nullopt, std::nullopt, Bytes(du)});
}

// Slave 3 configured as PPO 1, slave 6 guessed from the length, then damage.
std::vector<Input> inputs() {
    std::vector<std::uint8_t> ppo1(12, 0);
    std::vector<std::uint8_t> ppo3 = {0x04, 0x7F, 0x20, 0x00};
    std::vector<std::uint8_t> bad_response = data_exchange(2, 6, false, ppo3);
    bad_response[bad_response.size() - 2] ^= 0x5A;
    std::vector<std::vector<std::uint8_t>> telegrams = {
        build_telegram({3, 2, request_fc(FdlFunction::SrdHigh, true, true), 61, 62,
                        Bytes(hex("88 0A 0A 0B 04 02 00"))}),  // 1 Set_Prm
        hex("E5"),                                             // 2
        build_telegram({3, 2, request_fc(FdlFunction::SrdHigh, false, true), 62, 62,
                        Bytes(hex("F3 F1"))}),  // 3 Chk_Cfg
        hex("E5"),                              // 4
        data_exchange(3, 2, true, ppo1),        // 5
        data_exchange(2, 3, false, ppo1),       // 6
        hex("DC 02 02"),                        // 7 token
        data_exchange(6, 2, true, ppo3),        // 8
        bad_response,                           // 9 bad FCS
        hex("2A 3F"),                           // 10 junk
    };
    std::vector<Input> out;
    for (std::size_t i = 0; i < telegrams.size(); ++i)
        out.push_back({telegrams[i], kT0 + static_cast<std::int64_t>(i) * kMs});
    out.push_back({hex("10 09 02 49"), kNoTime});  // 11: truncated FDL_Status, no time
    return out;
}

struct Counted {
    Summary summary;
    BusDecoder decoder;
};

void count(Counted& c, const std::vector<Input>& in) {
    for (std::size_t i = 0; i < in.size(); ++i) {
        const DecodedTelegram& t =
            c.decoder.decode(Bytes(in[i].bytes.data(), in[i].bytes.size()), in[i].time_ns, i + 1);
        c.summary.add(t);
    }
}

std::vector<Finding> findings() {
    Finding fcs;
    fcs.kind = FindingKind::FcsError;
    Finding stacked;
    stacked.kind = FindingKind::StackedRequest;
    Finding rejected;
    rejected.kind = FindingKind::RequestRejected;
    std::vector<Finding> out{fcs, stacked, fcs, rejected};
    for (Finding& f : out)
        f.severity = default_severity(f.kind);  // as the rules make them
    return out;
}

std::string render_text(const Counted& c, const InputSummary& input) {
    return test::output_text([&](Output& out) { c.summary.render_text(out, input, c.decoder); });
}

// The kind column holds the longest kind name: the counts stay in one column.
TEST(SummaryTest, LongestKindNamesKeepTheCountsAligned) {
    Counted c;
    std::vector<Finding> list(3);
    list[0].kind = FindingKind::Dpv1ParameterCountMismatch;
    list[1].kind = FindingKind::Dpv1UnexpectedResponseId;
    list[2].kind = FindingKind::FcsError;
    c.summary.add_findings(list);
    std::string text = render_text(c, InputSummary{"x.raw", "raw", 0, false});
    std::vector<std::size_t> ends;
    for (std::string_view name :
         {"dpv1_parameter_count_mismatch", "dpv1_unexpected_response_id", "fcs_error"}) {
        std::size_t at = text.find(std::string("    ") + std::string(name) + " ");
        ASSERT_NE(at, std::string::npos) << text;
        std::size_t end = text.find("  (", at);
        ASSERT_NE(end, std::string::npos);
        ends.push_back(end - at);
    }
    EXPECT_EQ(ends[0], ends[1]) << text;
    EXPECT_EQ(ends[0], ends[2]) << text;
    EXPECT_NE(text.find("    dpv1_parameter_count_mismatch       1  (error)\n"), std::string::npos)
        << text;
}

// A kind whose findings had several severities says how many had which.
TEST(SummaryTest, KindWithMixedSeveritiesCountsEach) {
    Counted c;
    std::vector<Finding> list(4);
    list[0].kind = FindingKind::Dpv1ErrorPdu;
    list[0].severity = Severity::Warning;
    list[1].kind = FindingKind::Dpv1ErrorPdu;
    list[1].severity = Severity::Note;
    list[2].kind = FindingKind::Dpv1ErrorPdu;
    list[2].severity = Severity::Note;
    list[3].kind = FindingKind::FcsError;
    list[3].severity = Severity::Error;
    c.summary.add_findings(list);
    std::string text = render_text(c, InputSummary{"x.raw", "raw", 0, false});
    EXPECT_NE(text.find("dpv1_error_pdu                      3  (1 warning, 2 notes)\n"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("fcs_error                           1  (error)\n"), std::string::npos)
        << text;
}

TEST(SummaryTest, EmptySummary) {
    Summary summary;
    EXPECT_EQ(summary.telegrams(), 0u);
    EXPECT_EQ(summary.with_problems(), 0u);
    EXPECT_EQ(summary.requests(Service::DataExchange), 0u);
    EXPECT_EQ(summary.findings(FindingKind::FcsError), 0u);
    Counted c;
    std::string text = render_text(c, InputSummary{"empty.raw", "raw", 0, false});
    EXPECT_EQ(text,
              "Summary of empty.raw (raw)\n"
              "  telegrams: 0\n"
              "  by frame type:\n"
              "  by service:\n"
              "  telegrams with problems: 0\n"
              "  findings: 0\n");
}

TEST(SummaryTest, CountsByServiceAndDirection) {
    Counted c;
    count(c, inputs());
    const Summary& s = c.summary;
    EXPECT_EQ(s.telegrams(), 11u);
    EXPECT_EQ(s.requests(Service::SetPrm), 1u);
    EXPECT_EQ(s.responses(Service::SetPrm), 1u);
    EXPECT_EQ(s.requests(Service::ChkCfg), 1u);
    EXPECT_EQ(s.responses(Service::ChkCfg), 1u);
    EXPECT_EQ(s.requests(Service::DataExchange), 2u);
    EXPECT_EQ(s.responses(Service::DataExchange), 2u);
    EXPECT_EQ(s.requests(Service::Token), 1u);
    EXPECT_EQ(s.requests(Service::Unknown), 1u);
    EXPECT_EQ(s.requests(Service::FdlStatus), 1u);
    EXPECT_EQ(s.responses(Service::FdlStatus), 0u);
    EXPECT_EQ(s.requests(Service::SlaveDiag), 0u);
    EXPECT_EQ(s.data_exchange(3), 2u);
    EXPECT_EQ(s.data_exchange(6), 2u);
    EXPECT_EQ(s.data_exchange(2), 0u);
}

TEST(SummaryTest, CountsProblemsAndFindingsByKind) {
    Counted c;
    count(c, inputs());
    c.summary.add_findings(findings());
    const Summary& s = c.summary;
    EXPECT_EQ(s.with_problems(), 3u);
    EXPECT_EQ(s.problems(ProblemKind::FcsMismatch), 1u);
    EXPECT_EQ(s.problems(ProblemKind::BadStartDelimiter), 1u);
    EXPECT_EQ(s.problems(ProblemKind::Truncated), 1u);
    EXPECT_EQ(s.problems(ProblemKind::LengthMismatch), 0u);
    EXPECT_EQ(s.findings(FindingKind::FcsError), 2u);
    EXPECT_EQ(s.findings(FindingKind::StackedRequest), 1u);
    EXPECT_EQ(s.findings(FindingKind::RequestRejected), 1u);
    EXPECT_EQ(s.findings(FindingKind::OrphanResponse), 0u);
}

TEST(SummaryTest, RenderText) {
    Counted c;
    count(c, inputs());
    c.summary.add_findings(findings());
    std::string text = render_text(c, InputSummary{"bus.pcap", "pcap", 0, false});
    EXPECT_EQ(text,
              "Summary of bus.pcap (pcap)\n"
              "  telegrams: 11, from 2024-01-01T00:00:00.000000000Z to "
              "2024-01-01T00:00:00.009000000Z (0.009000000 s)\n"
              "  by frame type: SD1 1 SD2 6 SD4 1 SC 2 invalid 1\n"
              "  by service:\n"
              "    Unknown                   1  (1 request, 0 responses)\n"
              "    FDL_Status                1  (1 request, 0 responses)\n"
              "    Set_Prm                   2  (1 request, 1 response)\n"
              "    Chk_Cfg                   2  (1 request, 1 response)\n"
              "    Data_Exchange             4  (2 requests, 2 responses)\n"
              "    Token                     1  (1 request, 0 responses)\n"
              "  telegrams with problems: 3\n"
              "    bad_start_delimiter                 1\n"
              "    truncated                           1\n"
              "    fcs_mismatch                        1\n"
              "  findings: 4\n"
              "    stacked_request                     1  (error)\n"
              "    request_rejected                    1  (note)\n"
              "    fcs_error                           2  (error)\n"
              "  slaves:\n"
              "      3: PPO 1 (PCV + 2 PCD words, 12 bytes each way) from Chk_Cfg; dialect vlt; "
              "ident 0x0402; 2 Data_Exchange telegrams\n"
              "      6: PPO guessed from each Data_Exchange length; no parameter channel; 2 "
              "Data_Exchange telegrams\n");
}

TEST(SummaryTest, RenderTextNotesDamageAndSkippedBytes) {
    Counted c;
    count(c, {{hex("E5"), kNoTime}});
    std::string text = render_text(c, InputSummary{"<stdin>", "raw", 17, true});
    EXPECT_EQ(text,
              "Summary of <stdin> (raw)\n"
              "  telegrams: 1\n"
              "  input: reading stopped early (see the message above)\n"
              "  bytes skipped between telegrams: 17\n"
              "  by frame type: SC 1\n"
              "  by service:\n"
              "    Short_Ack                 1  (0 requests, 1 response)\n"
              "  telegrams with problems: 0\n"
              "  findings: 0\n");
}

TEST(SummaryTest, RenderTextWithTimesGoingBackwards) {
    // A log whose clock steps back: the span from the first to the last telegram is negative.
    Counted c;
    count(c, {{hex("E5"), kT0 + 1'000'000'000}, {hex("E5"), kT0 + 500'000'000}});
    std::string text = render_text(c, InputSummary{"log.txt", "hex", 0, false});
    std::string expected_line =
        "  telegrams: 2, from 2024-01-01T00:00:01.000000000Z to 2024-01-01T00:00:00.500000000Z "
        "(-0.500000000 s)\n";
    EXPECT_NE(text.find(expected_line), std::string::npos) << text;
    EXPECT_EQ(text.find(".-"), std::string::npos) << text;
}

TEST(SummaryTest, SlaveLayoutGivenByOption) {
    DecoderOptions options;
    options.station_ppo[6] = 4;
    options.station_dialect[6] = Dialect::Profidrive;
    Counted c{Summary{}, BusDecoder(options)};
    count(c, {{data_exchange(6, 2, true, std::vector<std::uint8_t>(12, 0)), kT0}});
    std::string text = render_text(c, InputSummary{"x", "pcap", 0, false});
    EXPECT_NE(text.find("      6: PPO 4 (6 PCD words, 12 bytes each way) given by --ppo; no "
                        "parameter channel; 1 Data_Exchange telegram\n"),
              std::string::npos)
        << text;
}

// An I/O slave (ET200S and the like) configured with one byte each way: no parameter channel,
// so no dialect, and "1 byte".
TEST(SummaryTest, SlaveWithoutAParameterChannelHasNoDialect) {
    Counted c;
    count(c, {{build_telegram(
                   {4, 2, request_fc(FdlFunction::SrdHigh, true, true), 62, 62, Bytes(hex("30"))}),
               kT0},
              {hex("E5"), kT0 + kMs},
              {data_exchange(4, 2, true, {0x5A}), kT0 + 2 * kMs},
              {data_exchange(2, 4, false, {0xA5}), kT0 + 3 * kMs}});
    std::string text = render_text(c, InputSummary{"x", "pcap", 0, false});
    EXPECT_NE(text.find("      4: no standard PPO (0 PCD words, 1 byte each way) from Chk_Cfg; no "
                        "parameter channel; 2 Data_Exchange telegrams\n"),
              std::string::npos)
        << text;
    EXPECT_EQ(text.find("dialect"), std::string::npos) << text;
}

// Data_Exchange between master 2 and slave 3 (PPO 1 by option) with RC `rc` and PNU 207.
std::vector<std::uint8_t> pcv_telegram(bool request, std::uint8_t rc) {
    std::vector<std::uint8_t> du(12, 0);
    du[0] = static_cast<std::uint8_t>(rc << 4);
    du[1] = 207;
    return request ? data_exchange(3, 2, true, du) : data_exchange(2, 3, false, du);
}

TEST(SummaryTest, DialectHintAfterTenCodesAllDefinedByTheOtherDialect) {
    DecoderOptions options;
    options.station_ppo[3] = 1;
    Counted c{Summary{}, BusDecoder(options)};
    // AK 14 (change and store in EEPROM) is PROFIdrive; vlt leaves RC 14 unassigned.
    for (int i = 0; i < 9; ++i)
        count(c, {{pcv_telegram(true, 14), kT0 + i * kMs}});
    EXPECT_FALSE(c.summary.dialect_evidence(3).hint());
    EXPECT_EQ(render_text(c, InputSummary{"x", "pcap", 0, false}).find("hint"), std::string::npos);
    count(c, {{pcv_telegram(false, 15), kT0 + 9 * kMs}});  // AK 15: transfer text
    ASSERT_EQ(c.summary.dialect_evidence(3).hint(), Dialect::Profidrive);
    EXPECT_NE(render_text(c, InputSummary{"x", "pcap", 0, false})
                  .find("         hint: its parameter-channel codes fit the profidrive dialect (10 "
                        "telegrams carry codes vlt does not define); decode with --dialect "
                        "3=profidrive\n"),
              std::string::npos);
    // A code neither dialect defines (response 13) takes the hint back.
    count(c, {{pcv_telegram(false, 13), kT0 + 10 * kMs}});
    EXPECT_EQ(c.summary.dialect_evidence(3).undefined(), 11u);
    EXPECT_FALSE(c.summary.dialect_evidence(3).hint());
}

// A rejection (RC 7) of slave 3 with error number `error` in bytes 7-8.
std::vector<std::uint8_t> rejection(std::uint16_t error) {
    std::vector<std::uint8_t> du(12, 0);
    du[0] = 0x70;
    du[1] = 207;
    du[6] = static_cast<std::uint8_t>(error >> 8);
    du[7] = static_cast<std::uint8_t>(error & 0xFF);
    return data_exchange(2, 3, false, du);
}

// A GE AF-600/AF-650 decoded with the default dialect uses the vlt codes, so its codes never
// give it away; its fault numbers 130 and 131 do [S002]: vlt does not define them, ge does. One
// rejection is enough (a short capture), and the hint says what it rests on.
TEST(SummaryTest, DialectHintFromAnErrorNumberOnlyTheOtherDialectDefines) {
    DecoderOptions options;
    options.station_ppo[3] = 1;
    Counted c{Summary{}, BusDecoder(options)};
    count(c, {{rejection(2), kT0}});  // defined by vlt: nothing to hint
    EXPECT_FALSE(c.summary.dialect_evidence(3).hint());
    count(c, {{pcv_telegram(true, 1), kT0 + kMs}, {rejection(130), kT0 + 2 * kMs}});
    ASSERT_EQ(c.summary.dialect_evidence(3).hint(), Dialect::Ge);
    EXPECT_NE(render_text(c, InputSummary{"x", "pcap", 0, false})
                  .find("         hint: its error numbers fit the ge dialect (error 130, which vlt "
                        "does not define, in 1 rejection telegram); decode with --dialect 3=ge\n"),
              std::string::npos)
        << render_text(c, InputSummary{"x", "pcap", 0, false});
    // An error number no dialect defines takes the hint back.
    count(c, {{rejection(999), kT0 + 3 * kMs}});
    EXPECT_FALSE(c.summary.dialect_evidence(3).hint());
    // Decoded as ge, 130 is defined: nothing to hint.
    DecoderOptions ge = options;
    ge.station_dialect[3] = Dialect::Ge;
    Counted right{Summary{}, BusDecoder(ge)};
    count(right, {{rejection(130), kT0}, {rejection(131), kT0 + kMs}});
    EXPECT_FALSE(right.summary.dialect_evidence(3).hint());
}

// The ident number from Set_Prm (or a Slave_Diag answer) names the drive: a documented one hints
// its dialect at once, whatever the codes. 0x0402 is the Danfoss VLT 5000/6000's
// (docs/protocol/ppo.md); an ident the sources do not name hints nothing.
TEST(SummaryTest, DialectHintFromADocumentedIdentNumber) {
    DecoderOptions options;
    options.station_dialect[3] = Dialect::Profidrive;
    Counted c{Summary{}, BusDecoder(options)};
    const std::vector<Input> start = {
        {build_telegram({3, 2, request_fc(FdlFunction::SrdHigh, true, true), 61, 62,
                         Bytes(hex("88 0A 0A 0B 04 02 00"))}),
         kT0},
        {hex("E5"), kT0 + kMs},
        {build_telegram(
             {3, 2, request_fc(FdlFunction::SrdHigh, false, true), 62, 62, Bytes(hex("F3 F1"))}),
         kT0 + 2 * kMs},
        {hex("E5"), kT0 + 3 * kMs},
        {pcv_telegram(true, 1), kT0 + 4 * kMs}};
    count(c, start);
    ASSERT_EQ(c.summary.dialect_evidence(3).hint(), Dialect::Vlt);
    EXPECT_NE(
        render_text(c, InputSummary{"x", "pcap", 0, false})
            .find("         hint: its ident number 0x0402 is the Danfoss VLT 5000/6000's (the "
                  "vlt dialect); decode with --dialect 3=vlt\n"),
        std::string::npos)
        << render_text(c, InputSummary{"x", "pcap", 0, false});
    // Decoded as vlt: nothing to hint.
    Counted vlt;
    count(vlt, start);
    EXPECT_FALSE(vlt.summary.dialect_evidence(3).hint());
    // An ident no source names (dpscope's simulator gives its ge slaves 0x6002, made up).
    std::vector<Input> other = start;
    other[0].bytes = build_telegram({3, 2, request_fc(FdlFunction::SrdHigh, true, true), 61, 62,
                                     Bytes(hex("88 0A 0A 0B 60 02 00"))});
    Counted unknown{Summary{}, BusDecoder(options)};
    count(unknown, other);
    EXPECT_FALSE(unknown.summary.dialect_evidence(3).hint());
}

TEST(SummaryTest, NoDialectHintForDefinedCodesOrDamagedTelegrams) {
    DecoderOptions options;
    options.station_ppo[3] = 1;
    options.station_dialect[3] = Dialect::Profidrive;
    Counted c{Summary{}, BusDecoder(options)};
    // Decoded as profidrive, AK 14 is defined: nothing to hint.
    for (int i = 0; i < 20; ++i)
        count(c, {{pcv_telegram(true, 14), kT0 + i * kMs}});
    EXPECT_EQ(c.summary.dialect_evidence(3).undefined(), 0u);
    EXPECT_FALSE(c.summary.dialect_evidence(3).hint());
    // A telegram with a bad FCS says nothing about the dialect.
    DecoderOptions vlt;
    vlt.station_ppo[3] = 1;
    Counted damaged{Summary{}, BusDecoder(vlt)};
    for (int i = 0; i < 20; ++i) {
        std::vector<std::uint8_t> bytes = pcv_telegram(true, 14);
        bytes[bytes.size() - 2] ^= 0xFF;  // the FCS
        count(damaged, {{bytes, kT0 + i * kMs}});
    }
    EXPECT_EQ(damaged.summary.dialect_evidence(3).undefined(), 0u);
}

TEST(SummaryTest, SimulatedSessionTotalsAddUp) {
    SimulatorOptions options;
    options.seed = 11;
    options.cycles = 120;
    options.faults = {FaultSpec{FaultKind::FcsError, 0, 10, 3},
                      FaultSpec{FaultKind::Garbage, 0, 20, 4}};
    Simulator simulator(options);
    std::vector<Input> in;
    std::vector<std::uint8_t> bytes;
    std::int64_t time_ns = 0;
    while (simulator.next(bytes, time_ns))
        in.push_back({bytes, time_ns});
    Counted c;
    count(c, in);
    const Summary& s = c.summary;
    EXPECT_EQ(s.telegrams(), in.size());
    std::uint64_t by_service = 0;
    for (std::size_t i = 0; i < kServiceCount; ++i)
        by_service += s.requests(static_cast<Service>(i)) + s.responses(static_cast<Service>(i));
    EXPECT_EQ(by_service, in.size());
    EXPECT_EQ(s.with_problems(), 2u);
    EXPECT_EQ(s.problems(ProblemKind::FcsMismatch), 1u);
    EXPECT_EQ(s.problems(ProblemKind::BadStartDelimiter), 1u);
    EXPECT_EQ(s.requests(Service::Token), 121u);
    // 120 cycles, one request and one response each, plus the retry after the bad FCS.
    EXPECT_EQ(s.data_exchange(3), 242u);
    EXPECT_EQ(s.data_exchange(4), 240u);
    EXPECT_EQ(s.data_exchange(5), 240u);
    std::string text = render_text(c, InputSummary{"sim.pcap", "pcap", 0, false});
    EXPECT_NE(text.find("  telegrams: " + std::to_string(in.size()) + ", from "),
              std::string::npos);
    EXPECT_NE(text.find("    fcs_mismatch                        1\n"), std::string::npos);
    EXPECT_NE(text.find("      4: PPO 2 (PCV + 6 PCD words, 20 bytes each way) from Chk_Cfg; "
                        "dialect vlt; ident 0x0402; 240 Data_Exchange telegrams\n"),
              std::string::npos)
        << text;
}

// FC and VLT 2000 sessions with every fault of their bus: per drive, the tracker's commands add
// up to their outcomes, and decode -q's counts (the summary's, per telegram) equal the report's
// (the tracker's): commands = requests, responses and replies with the damaged ones (#27 point 12).
template <class Decoder, class Tracker, class Check>
void run_simulated_bus(Protocol bus, bool (*applies)(FaultKind), Check check) {
    SimulatorOptions options;
    options.bus = bus;
    options.seed = 7;
    options.cycles = 400;
    options.baud = 0;
    for (std::size_t i = 0; i < kFaultKindCount; ++i) {
        const auto kind = static_cast<FaultKind>(i);
        if (applies(kind)) options.faults.push_back({kind, 0.02, {}, {}});
    }
    Simulator simulator(options);
    Decoder decoder;
    Tracker tracker;
    Summary summary;
    std::vector<std::uint8_t> bytes;
    std::int64_t time_ns = 0;
    std::uint64_t frame = 0;
    while (simulator.next(bytes, time_ns)) {
        const DecodedTelegram& t = decoder.decode(Bytes(bytes), time_ns, ++frame);
        summary.add(t);
        summary.add_findings(tracker.track(t));
    }
    tracker.finish();
    ASSERT_GT(simulator.injection_count(), 20u);
    check(tracker, summary);
}

TEST(SummaryTest, FcDriveCountsAddUpAndAgreeWithTheReport) {
    run_simulated_bus<FcDecoder, FcTracker>(
        Protocol::Fc, fault_applies_to_fc, [](const FcTracker& tracker, const Summary& summary) {
            std::uint64_t damaged = 0;
            for (const FcStationStats* s : tracker.stations()) {
                SCOPED_TRACE(s->address);
                EXPECT_EQ(s->commands, s->commands_outcomes());
                damaged += s->damaged;
                if (s->address == 0) continue;  // the broadcasts: not a drive of the summary
                EXPECT_EQ(summary.fc_drive_requests(s->address), s->commands);
                EXPECT_EQ(summary.fc_drive_responses(s->address), s->responses);
            }
            EXPECT_GT(damaged, 0u);
        });
}

TEST(SummaryTest, Vlt2000DriveCountsAddUpAndAgreeWithTheReport) {
    run_simulated_bus<Vlt2000Decoder, Vlt2000Tracker>(
        Protocol::Vlt2000, fault_applies_to_vlt2000,
        [](const Vlt2000Tracker& tracker, const Summary& summary) {
            std::uint64_t damaged = 0;
            for (const Vlt2000StationStats* s : tracker.stations()) {
                SCOPED_TRACE(s->address);
                EXPECT_EQ(s->commands, s->commands_outcomes());
                damaged += s->damaged;
                EXPECT_EQ(summary.vlt2000_address(s->address).commands, s->commands);
                EXPECT_EQ(summary.vlt2000_address(s->address).replies, s->replies);
                EXPECT_EQ(summary.vlt2000_address(s->address).failed, s->failed);
            }
            EXPECT_GT(damaged, 0u);
        });
}

// decode -q names each drive's commands by outcome, as the report does, and its responses with
// the damaged ones (#27 point 12).
TEST(SummaryTest, FcDrivesShowTheirCommandsByOutcome) {
    FcDecoder decoder;
    FcTracker tracker;
    Summary summary;
    std::uint64_t frame = 0;
    auto feed = [&](std::vector<std::uint8_t> bytes, std::int64_t ms) {
        const DecodedTelegram& t = decoder.decode(Bytes(bytes), ms * kMs, ++frame);
        summary.add(t);
        summary.add_findings(tracker.track(t));
    };
    feed(test::fc_process(2), 0);
    feed(test::fc_process(2, 0x0607), 4);
    feed(test::fc_process(2), 10);  // unanswered
    feed(test::fc_parameter(1, 1, 414), 20);
    std::vector<std::uint8_t> answer = test::fc_parameter(1, 1, 414, 0, 5, 0x0607);
    answer.back() ^= 0x10;  // damaged
    feed(answer, 24);
    feed(test::fc_parameter(1, 1, 415), 30);  // the capture ends before its answer
    summary.add_findings(tracker.finish());
    BusDecoder dp;
    const std::string text = test::output_text([&](Output& out) {
        summary.render_text(out, InputSummary{"fc.pcap", "pcap", 0, false}, dp, &tracker);
    });
    EXPECT_NE(text.find("  drives:\n"
                        "      1: 2 commands (0 answered, 0 unanswered, 0 abandoned, 1 damaged, 1 "
                        "not judged), 1 response (1 damaged)\n"
                        "      2: 2 commands (1 answered, 1 unanswered, 0 abandoned, 0 damaged), 1 "
                        "response\n"),
              std::string::npos)
        << text;
    // Without the tracker (decode -q --pnu: the telegrams about a parameter), the counts alone.
    const std::string alone = test::output_text([&](Output& out) {
        summary.render_text(out, InputSummary{"fc.pcap", "pcap", 0, false}, dp);
    });
    EXPECT_NE(alone.find("      1: 2 commands, 1 response\n"), std::string::npos) << alone;
}

TEST(SummaryTest, Vlt2000AddressesShowTheirCommandsByOutcome) {
    Vlt2000Decoder decoder;
    Vlt2000Tracker tracker;
    Summary summary;
    std::uint64_t frame = 0;
    auto feed = [&](std::string_view text, std::int64_t ms) {
        std::vector<std::uint8_t> bytes(text.begin(), text.end());
        const DecodedTelegram& t = decoder.decode(Bytes(bytes), ms * kMs, ++frame);
        summary.add(t);
        summary.add_findings(tracker.track(t));
    };
    // The manual's example command (§7.5), the capture ending before its reply.
    feed("<01UOGD@0516+00080007>", 0);
    summary.add_findings(tracker.finish());
    BusDecoder dp;
    const std::string text = test::output_text([&](Output& out) {
        summary.render_text(out, InputSummary{"vlt.pcap", "pcap", 0, false}, dp, &tracker);
    });
    EXPECT_NE(text.find("    01: 1 command (0 answered, 0 unanswered, 0 abandoned, 0 damaged, 1 "
                        "not judged), 0 replies"),
              std::string::npos)
        << text;
}

}  // namespace
}  // namespace dpscope
