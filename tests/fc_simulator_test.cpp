// The FC bus of the simulator (simulate --bus fc): the traffic decodes with FcDecoder without
// problems and with the right directions, it holds every kind of telegram the model promises, and
// each fault gives the telegram shape it stands for.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/protocol_descriptor.hpp"
#include "capture/telegram_source.hpp"
#include "protocols/fc/fc_codes.hpp"
#include "protocols/fc/fc_decoder.hpp"
#include "protocols/fc/fc_framing_rules.hpp"
#include "simulator/simulator.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

// A decoded FC telegram, copied out of the decoder's reused result.
struct Fc {
    std::vector<std::uint8_t> bytes;
    std::int64_t time_ns = 0;
    Direction direction = Direction::Request;
    std::uint64_t request_frame = 0;
    FcTelegram fc;  // its text view is not used (it points into the decoder's input)
    std::string text;
    std::vector<ProblemKind> problems;
};

SimulatorOptions fc_session(std::uint64_t seed, std::uint64_t cycles) {
    SimulatorOptions options;
    options.bus = Protocol::Fc;
    options.seed = seed;
    options.cycles = cycles;
    options.baud = 0;
    return options;
}

std::vector<Fc> decode_all(Simulator& simulator) {
    std::vector<Fc> out;
    FcDecoder decoder;
    std::vector<std::uint8_t> bytes;
    std::int64_t time_ns = 0;
    while (simulator.next(bytes, time_ns)) {
        Fc t;
        t.bytes = bytes;
        t.time_ns = time_ns;
        const DecodedTelegram& d = decoder.decode(Bytes(t.bytes), time_ns, out.size() + 1);
        t.direction = d.direction;
        t.request_frame = d.request_frame;
        t.fc = d.fc;
        t.text.assign(d.fc.text.begin(), d.fc.text.end());
        t.fc.text = {};
        for (const Problem& p : d.fc.problems)
            t.problems.push_back(p.kind);
        out.push_back(std::move(t));
    }
    return out;
}

std::vector<Fc> decode_all(const SimulatorOptions& options) {
    Simulator simulator(options);
    return decode_all(simulator);
}

// The time a telegram takes on the line at 9600 baud, 11 bits a character.
std::int64_t line_ns(const Fc& t) {
    return static_cast<std::int64_t>(t.bytes.size()) * 11 * 1'000'000'000 / 9600;
}

TEST(FcSimulatorTest, CleanSessionDecodesWithoutProblemsAndTheRightDirections) {
    std::vector<Fc> telegrams = decode_all(fc_session(3, 400));
    ASSERT_GT(telegrams.size(), 2000u);
    std::set<std::uint8_t> request_aks, response_aks, fault_codes, adrs;
    std::set<FcAddressFormat> formats;
    bool indexed = false, text_response = false, text_request = false, broadcast_short = false,
         broadcast_long = false;
    for (std::size_t i = 0; i < telegrams.size(); ++i) {
        const Fc& t = telegrams[i];
        SCOPED_TRACE("telegram " + std::to_string(i + 1));
        EXPECT_TRUE(t.problems.empty());
        ASSERT_TRUE(t.fc.complete);
        EXPECT_TRUE(t.fc.bcc_ok);
        ASSERT_TRUE(t.fc.has_pcd);
        // Telegrams are whole characters apart: the next starts after this one ends.
        if (i + 1 < telegrams.size()) {
            EXPECT_GE(telegrams[i + 1].time_ns - t.time_ns, line_ns(t) + 500'000);
        }
        if (t.fc.broadcast) {
            EXPECT_EQ(t.direction, Direction::Request);
            (t.fc.address_format == FcAddressFormat::Short ? broadcast_short : broadcast_long) =
                true;
            continue;
        }
        adrs.insert(t.fc.adr);
        formats.insert(t.fc.address_format);
        if (t.direction == Direction::Request) {
            // Every request to a drive is answered by the next telegram, with its ADR, within
            // the drive's response time.
            ASSERT_LT(i + 1, telegrams.size());
            const Fc& answer = telegrams[i + 1];
            EXPECT_EQ(answer.direction, Direction::Response);
            EXPECT_EQ(answer.request_frame, i + 1);
            EXPECT_EQ(answer.fc.adr, t.fc.adr);
            const std::int64_t response_ns = answer.time_ns - t.time_ns - line_ns(t);
            EXPECT_GE(response_ns, FcBusModel::kResponseMinNs);
            EXPECT_LE(response_ns, FcBusModel::kResponseMaxNs);
            EXPECT_LT(response_ns, 20'000'000);
            EXPECT_EQ(t.fc.pcd1, 0x047F);
            if (t.fc.has_pkw) {
                request_aks.insert(t.fc.pkw.rc);
                EXPECT_TRUE(answer.fc.has_pkw);
                if (t.fc.pkw.pnu == 1530) indexed = true;
                if (t.fc.pkw.rc == 15) {
                    text_request = true;
                    EXPECT_EQ(t.fc.ind_high, kFcTextRead);
                }
                if (answer.fc.has_pkw) {
                    EXPECT_EQ(answer.fc.pkw.pnu, t.fc.pkw.pnu);
                    EXPECT_EQ(answer.fc.pkw.ind, t.fc.pkw.ind);
                    const AnswerVerdict verdict = fc_judge_answer(t.fc.pkw.rc, answer.fc.pkw.rc);
                    EXPECT_TRUE(verdict == AnswerVerdict::Positive ||
                                verdict == AnswerVerdict::Negative)
                        << int(t.fc.pkw.rc) << " -> " << int(answer.fc.pkw.rc);
                }
            } else {
                EXPECT_EQ(answer.fc.block, FcBlock::Process);
            }
        } else {
            ASSERT_GT(i, 0u);
            EXPECT_EQ(telegrams[i - 1].direction, Direction::Request);
            if (t.fc.has_pkw) {
                response_aks.insert(t.fc.pkw.rc);
                if (t.fc.pkw.rc == 7) {
                    fault_codes.insert(static_cast<std::uint8_t>(t.fc.pkw.pva));
                    EXPECT_NE(fc_fault_text(t.fc.pkw.pva), "");
                }
                if (t.fc.block == FcBlock::Text) {
                    text_response = true;
                    EXPECT_EQ(t.fc.lge, kFcLgeTextBase + t.text.size());
                    EXPECT_TRUE(t.text == "FC-302" || t.text == "05.11" || t.text == "131B0002")
                        << t.text;
                }
            }
        }
    }
    EXPECT_EQ(request_aks, (std::set<std::uint8_t>{1, 2, 3, 13, 14, 15}));
    EXPECT_EQ(response_aks, (std::set<std::uint8_t>{1, 2, 7, 15}));
    EXPECT_EQ(fault_codes, (std::set<std::uint8_t>{1, 2}));  // read-only, out of range
    EXPECT_EQ(adrs, (std::set<std::uint8_t>{0x81, 0x82, 0x03}));
    EXPECT_EQ(formats.size(), 2u);
    EXPECT_TRUE(indexed);
    EXPECT_TRUE(text_request);
    EXPECT_TRUE(text_response);
    EXPECT_TRUE(broadcast_short);
    EXPECT_TRUE(broadcast_long);
}

TEST(FcSimulatorTest, SameSeedSameBytesAndTheDefaultBaudIs9600) {
    std::vector<Fc> a = decode_all(fc_session(8, 50));
    std::vector<Fc> b = decode_all(fc_session(8, 50));
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].bytes, b[i].bytes);
        EXPECT_EQ(a[i].time_ns, b[i].time_ns);
    }
    SimulatorOptions fast = fc_session(8, 50);
    fast.baud = 19200;
    std::vector<Fc> c = decode_all(fast);
    ASSERT_EQ(c.size(), a.size());
    EXPECT_LT(c.back().time_ns, a.back().time_ns);
}

TEST(FcSimulatorTest, DrivesAndTheirAddressFormats) {
    SimulatorOptions options = fc_session(4, 20);
    options.drives = {{31, FcAddressFormat::Short}, {126, FcAddressFormat::Long}};
    std::set<std::uint8_t> adrs;
    for (const Fc& t : decode_all(options))
        if (!t.fc.broadcast) adrs.insert(t.fc.adr);
    EXPECT_EQ(adrs, (std::set<std::uint8_t>{0x1F, 0xFE}));
}

TEST(FcSimulatorTest, CountLimitsTheTelegrams) {
    SimulatorOptions options = fc_session(4, 0);
    options.max_telegrams = 1234;
    EXPECT_EQ(decode_all(options).size(), 1234u);
}

// Runs a session with `kind` once on drive 2 from cycle 5 and returns the telegrams and the
// 0-based index of the telegram the injection names.
std::pair<std::vector<Fc>, std::size_t> with_fault(FaultKind kind, std::size_t drives = 3) {
    SimulatorOptions options = fc_session(21, 200);
    options.drives = {{1, FcAddressFormat::Long}, {2, FcAddressFormat::Short}, {9}};
    options.drives.resize(drives == 1 ? 2 : drives);
    if (drives == 1) options.drives.erase(options.drives.begin());
    options.faults = {FaultSpec{kind, 0, 5, 2}};
    Simulator simulator(options);
    std::vector<Fc> telegrams = decode_all(simulator);
    EXPECT_EQ(simulator.injections().size(), 1u);
    if (simulator.injections().empty()) return {telegrams, 0};
    const Injection& injection = simulator.injections()[0];
    EXPECT_EQ(injection.kind, kind);
    EXPECT_EQ(injection.slave, 2);
    EXPECT_GE(injection.cycle, 5u);
    EXPECT_GE(injection.telegram, 2u);
    EXPECT_LT(injection.telegram, telegrams.size());
    return {telegrams, static_cast<std::size_t>(injection.telegram - 1)};
}

TEST(FcSimulatorTest, StackedRequestIsASecondCommandBeforeTheAnswer) {
    auto [t, n] = with_fault(FaultKind::FcStackedRequest);
    ASSERT_GT(n, 0u);
    EXPECT_EQ(t[n - 1].direction, Direction::Request);
    EXPECT_EQ(t[n].direction, Direction::Request);
    EXPECT_EQ(t[n].fc.adr, t[n - 1].fc.adr);
    EXPECT_EQ(t[n].fc.pkw.rc, 14);
    EXPECT_TRUE(fc_command_only(t[n].fc.pkw.rc));
    // Sent before the drive's response time was up.
    EXPECT_LT(t[n].time_ns - t[n - 1].time_ns - line_ns(t[n - 1]), FcBusModel::kResponseMinNs);
    EXPECT_EQ(t[n + 1].direction, Direction::Response);
    EXPECT_EQ(t[n + 1].request_frame, n + 1);
    EXPECT_EQ(t[n + 1].fc.pkw.rc, 1);
    EXPECT_TRUE(t[n].problems.empty());
}

TEST(FcSimulatorTest, NoResponseLeavesTheRequestUnanswered) {
    for (std::size_t drives : {3u, 1u}) {
        SCOPED_TRACE(std::to_string(drives) + " drives");
        auto [t, n] = with_fault(FaultKind::FcNoResponse, drives);
        ASSERT_GT(n, 0u);
        EXPECT_EQ(t[n - 1].direction, Direction::Request);
        EXPECT_EQ(t[n - 1].fc.address, 2);
        // The master's next telegram goes to another drive, or is a broadcast.
        EXPECT_EQ(t[n].direction, Direction::Request);
        EXPECT_TRUE(t[n].fc.broadcast || t[n].fc.address != 2);
        EXPECT_GE(t[n].time_ns - t[n - 1].time_ns - line_ns(t[n - 1]),
                  FcBusModel::kMasterTimeoutNs);
    }
}

TEST(FcSimulatorTest, LateResponseComesAfterTheDocumentedResponseTime) {
    auto [t, n] = with_fault(FaultKind::FcLateResponse);
    ASSERT_GT(n, 0u);
    EXPECT_EQ(t[n].direction, Direction::Response);
    EXPECT_EQ(t[n].request_frame, n);
    EXPECT_EQ(t[n].fc.address, 2);
    // Late however the response time is measured: from the request's end or its start.
    EXPECT_GT(t[n].time_ns - t[n - 1].time_ns - line_ns(t[n - 1]), 40'000'000);
    EXPECT_TRUE(t[n].problems.empty());
}

TEST(FcSimulatorTest, MismatchedResponseCarriesAnotherPnuOrIndex) {
    auto [t, n] = with_fault(FaultKind::FcMismatchedResponse);
    ASSERT_GT(n, 0u);
    EXPECT_EQ(t[n].direction, Direction::Response);
    ASSERT_TRUE(t[n].fc.has_pkw);
    ASSERT_TRUE(t[n - 1].fc.has_pkw);
    EXPECT_TRUE(t[n].fc.pkw.pnu != t[n - 1].fc.pkw.pnu || t[n].fc.pkw.ind != t[n - 1].fc.pkw.ind);
    EXPECT_TRUE(t[n].problems.empty());
}

TEST(FcSimulatorTest, UnexpectedResponseTypeDoesNotAnswerTheCommand) {
    auto [t, n] = with_fault(FaultKind::FcUnexpectedResponseType);
    ASSERT_GT(n, 0u);
    EXPECT_EQ(t[n].direction, Direction::Response);
    ASSERT_TRUE(t[n].fc.has_pkw);
    EXPECT_EQ(fc_judge_answer(t[n - 1].fc.pkw.rc, t[n].fc.pkw.rc), AnswerVerdict::Invalid)
        << int(t[n - 1].fc.pkw.rc) << " -> " << int(t[n].fc.pkw.rc);
    EXPECT_TRUE(t[n].problems.empty());
}

TEST(FcSimulatorTest, CommandRejectedIsAk7WithAFaultCode) {
    auto [t, n] = with_fault(FaultKind::FcCommandRejected);
    ASSERT_GT(n, 0u);
    EXPECT_EQ(t[n].direction, Direction::Response);
    EXPECT_EQ(t[n].fc.pkw.rc, 7);
    EXPECT_EQ(t[n].fc.pkw.pva, 17u);
    EXPECT_EQ(fc_fault_text(t[n].fc.pkw.pva), "Not applicable while running");
    EXPECT_EQ(t[n].fc.pkw.pnu, t[n - 1].fc.pkw.pnu);
}

TEST(FcSimulatorTest, BccErrorDamagesOneResponse) {
    auto [t, n] = with_fault(FaultKind::FcBccError);
    ASSERT_GT(n, 0u);
    EXPECT_EQ(t[n].direction, Direction::Response);
    EXPECT_EQ(t[n].problems, (std::vector<ProblemKind>{ProblemKind::BccMismatch}));
    EXPECT_FALSE(t[n].fc.bcc_ok);
    for (std::size_t i = 0; i < t.size(); ++i)
        if (i != n) {
            EXPECT_TRUE(t[i].problems.empty()) << i;
        }
}

TEST(FcSimulatorTest, MalformedTelegramIsAResponseCutShort) {
    auto [t, n] = with_fault(FaultKind::MalformedTelegram);
    ASSERT_GT(n, 0u);
    EXPECT_EQ(t[n].direction, Direction::Response);
    EXPECT_EQ(t[n].problems, (std::vector<ProblemKind>{ProblemKind::Truncated}));
    EXPECT_FALSE(t[n].fc.complete);
    EXPECT_GE(t[n].bytes.size(), 3u);
}

TEST(FcSimulatorTest, GarbageHasNoStx) {
    auto [t, n] = with_fault(FaultKind::Garbage);
    EXPECT_EQ(t[n].problems, (std::vector<ProblemKind>{ProblemKind::BadStartDelimiter}));
    for (std::uint8_t b : t[n].bytes)
        EXPECT_NE(b, kFcStx);
    // The poll after it is whole.
    EXPECT_TRUE(t[n + 1].problems.empty());
    EXPECT_EQ(t[n + 1].direction, Direction::Request);
}

TEST(FcSimulatorTest, FaultRateOnEveryFcKindKeepsTheDecoderInStep) {
    SimulatorOptions options = fc_session(5, 300);
    for (std::size_t i = 0; i < kFaultKindCount; ++i) {
        const auto kind = static_cast<FaultKind>(i);
        if (fault_applies_to_fc(kind)) options.faults.push_back({kind, 0.01, {}, {}});
    }
    Simulator simulator(options);
    std::vector<Fc> telegrams = decode_all(simulator);
    EXPECT_GT(simulator.injection_count(), 20u);
    // Every response names the telegram before it (or the one before that after a stacked
    // request) as its request.
    for (std::size_t i = 0; i < telegrams.size(); ++i) {
        if (telegrams[i].direction != Direction::Response) continue;
        EXPECT_EQ(telegrams[i].request_frame, i) << i;
    }
}

TEST(FcSimulatorTest, FaultChecks) {
    SimulatorOptions options = fc_session(1, 100);
    options.faults = {FaultSpec{FaultKind::FcsError, 0, 3, std::nullopt}};
    EXPECT_EQ(check_simulator_faults(options).error(),
              "fault fcs_error@3: a PROFIBUS DP fault; an FC bus takes the fc_* faults, garbage "
              "and malformed_telegram");
    options.faults = {FaultSpec{FaultKind::FcBccError, 0, 3, 7}};
    EXPECT_EQ(check_simulator_faults(options).error(),
              "fault fc_bcc_error@3:7: drive 7 is not "
              "simulated");
    options.faults = {FaultSpec{FaultKind::FcBccError, 0, 300, 3}};
    EXPECT_EQ(check_simulator_faults(options).error(),
              "fault fc_bcc_error@300:3: cycle 300 is past the session's 100 cycles (0..99)");
    options.faults = {FaultSpec{FaultKind::Garbage, 0, 3, 3}};
    EXPECT_TRUE(check_simulator_faults(options));
    SimulatorOptions profibus;
    profibus.faults = {FaultSpec{FaultKind::FcNoResponse, 0, 3, std::nullopt}};
    EXPECT_EQ(check_simulator_faults(profibus).error(),
              "fault fc_no_response@3: an FC protocol fault; give --bus fc");
}

TEST(FcSimulatorTest, ParseDriveSpec) {
    Result<SimulatedDrive> plain = parse_drive_spec("7");
    ASSERT_TRUE(plain);
    EXPECT_EQ(plain->address, 7);
    EXPECT_EQ(plain->format, FcAddressFormat::Long);
    EXPECT_EQ(fc_adr_of(*plain), 0x87);
    Result<SimulatedDrive> short_format = parse_drive_spec("31:1-31");
    ASSERT_TRUE(short_format);
    EXPECT_EQ(short_format->format, FcAddressFormat::Short);
    EXPECT_EQ(fc_adr_of(*short_format), 0x1F);
    EXPECT_TRUE(parse_drive_spec("126:1-126"));
    EXPECT_EQ(parse_drive_spec("32:1-31").error(),
              "32:1-31: the address must be from 1 to 31 in the 1-31 format");
    EXPECT_EQ(parse_drive_spec("0").error(),
              "0: the address must be from 1 to 126 in the 1-126 format");
    EXPECT_EQ(parse_drive_spec("127").error(),
              "127: the address must be from 1 to 126 in the 1-126 format");
    EXPECT_EQ(parse_drive_spec("5:1-32").error(),
              "5:1-32: the address format must be 1-126 or 1-31");
    EXPECT_FALSE(parse_drive_spec("x"));
    EXPECT_FALSE(parse_drive_spec(""));
}

TEST(FcSimulatorTest, BuiltTelegramsHaveTheirBcc) {
    // The worked example of docs/protocol/fc-protocol.md: a process block to address 1.
    EXPECT_EQ(build_fc_telegram(0x81, {0x04, 0x7F, 0x20, 0x00}),
              (std::vector<std::uint8_t>{0x02, 0x06, 0x81, 0x04, 0x7F, 0x20, 0x00, 0xDE}));
    EXPECT_EQ(build_fc_telegram(0x81, {0x11, 0x9E, 0, 0, 0, 0, 0, 0, 0x04, 0x7F, 0x20, 0x00}),
              (std::vector<std::uint8_t>{0x02, 0x0E, 0x81, 0x11, 0x9E, 0, 0, 0, 0, 0, 0, 0x04, 0x7F,
                                         0x20, 0x00, 0x59}));
}

// The FC samples (scripts/make-samples): decoded as the simulator wrote them, the clean one without
// a problem, the faulty one with exactly the damage its faults make; both formats, every block.
TEST(FcSimulatorTest, SamplesDecode) {
    for (const char* name : {"fc-clean.pcap", "fc.pcap"}) {
        SCOPED_TRACE(name);
        OpenResult opened = open_source(test::source_dir() + "/samples/" + name, InputFormat::Auto,
                                        protocol_descriptor(Protocol::Fc));
        ASSERT_TRUE(opened) << opened.error();
        FcDecoder decoder;
        Record record;
        std::uint64_t frame = 0;
        std::map<ProblemKind, int> problems;
        std::set<FcAddressFormat> formats;
        std::set<FcBlock> blocks;
        std::set<std::uint8_t> aks;
        int broadcasts = 0, responses = 0;
        while (opened.value()->next(record)) {
            const DecodedTelegram& t = decoder.decode(record.bytes, record.time_ns, ++frame);
            for (const Problem& p : t.fc.problems)
                ++problems[p.kind];
            if (!t.has_roles) continue;
            formats.insert(t.fc.address_format);
            blocks.insert(t.fc.block);
            if (t.fc.has_pkw) aks.insert(t.fc.pkw.rc);
            broadcasts += t.fc.broadcast ? 1 : 0;
            responses += t.direction == Direction::Response ? 1 : 0;
        }
        EXPECT_GT(frame, 300u);
        EXPECT_EQ(formats.size(), 2u);
        EXPECT_EQ(blocks, (std::set<FcBlock>{FcBlock::Process, FcBlock::Parameter, FcBlock::Text}));
        EXPECT_EQ(aks, (std::set<std::uint8_t>{1, 2, 3, 7, 13, 14, 15}));
        EXPECT_GE(broadcasts, 1);
        if (std::string(name) == "fc-clean.pcap") {
            EXPECT_TRUE(problems.empty());
            EXPECT_EQ(responses * 2 + broadcasts, static_cast<int>(frame));
        } else {
            EXPECT_EQ(problems, (std::map<ProblemKind, int>{{ProblemKind::BccMismatch, 2},
                                                            {ProblemKind::Truncated, 2},
                                                            {ProblemKind::BadStartDelimiter, 2}}));
        }
    }
}

}  // namespace
}  // namespace dpscope
