// The FC tracker (protocols/fc/fc_tracker.hpp) on hand-made FC telegrams decoded by FcDecoder:
// clean exchanges with no findings, latency and the per-address counts, broadcasts, each rule with
// its frames and message, time-outs at the end, bounded memory. (One scenario per FC fault, exactly
// its findings: SessionTrackerTest.FcScenariosGiveExactlyTheExpectedFindings.)
#include "protocols/fc/fc_tracker.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "protocols/fc/fc_decoder.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::fc_parameter;
using test::fc_process;

constexpr std::int64_t kMs = 1'000'000;

// Feeds telegrams through a decoder and a tracker, keeping every finding.
struct FcRun {
    explicit FcRun(FcTrackerOptions options = {}) : tracker(options) {}

    // `time_ms` < 0: no timestamp.
    std::vector<Finding> feed(const std::vector<std::uint8_t>& bytes, std::int64_t time_ms) {
        const DecodedTelegram& t =
            decoder.decode(bytes, time_ms < 0 ? kNoTime : time_ms * kMs, ++frame);
        std::span<const Finding> found = tracker.track(t);
        return keep(std::vector<Finding>(found.begin(), found.end()));
    }
    std::vector<Finding> finish(std::int64_t end_ms = -1) {
        std::span<const Finding> found = tracker.finish(end_ms < 0 ? kNoTime : end_ms * kMs);
        return keep(std::vector<Finding>(found.begin(), found.end()));
    }
    std::vector<Finding> keep(std::vector<Finding> found) {
        all.insert(all.end(), found.begin(), found.end());
        return found;
    }
    const FcStationStats* station(std::uint8_t address) const {
        for (const FcStationStats* s : tracker.stations())
            if (s->address == address) return s;
        return nullptr;
    }

    FcDecoder decoder;
    FcTracker tracker;
    std::uint64_t frame = 0;
    std::vector<Finding> all;
};

TEST(FcTrackerTest, CleanExchangesHaveNoFindingsAndCountLatencyPerAddress) {
    FcRun run;
    for (int i = 0; i < 4; ++i) {
        const std::int64_t t = 20 * i;
        run.feed(fc_parameter(1, 1, 414), t);
        run.feed(fc_parameter(1, 1, 414, 0, 1500, 0x0607), t + 4 + i);  // 4..7 ms
        run.feed(fc_process(2), t + 10);
        run.feed(fc_process(2, 0x0607), t + 12);
    }
    run.feed(fc_parameter(1, 14, 415, 0, 33), 100);
    run.feed(fc_parameter(1, 1, 415, 0, 33, 0x0607), 103);
    run.finish(5000);
    EXPECT_TRUE(run.all.empty()) << run.all[0].message;
    EXPECT_EQ(run.tracker.transactions(), 9u);

    const FcStationStats* one = run.station(1);
    ASSERT_NE(one, nullptr);
    EXPECT_EQ(one->commands, 5u);
    EXPECT_EQ(one->commands_by_ak[1], 4u);
    EXPECT_EQ(one->commands_by_ak[14], 1u);
    EXPECT_EQ(one->process_commands, 0u);
    EXPECT_EQ(one->responses, 5u);
    EXPECT_EQ(one->answered, 5u);
    EXPECT_EQ(one->latency_ns.count(), 5u);
    EXPECT_EQ(one->latency_ns.min(), 3u * kMs);
    EXPECT_EQ(one->latency_ns.max(), 7u * kMs);
    EXPECT_EQ(one->mean_latency_ns(), (4u + 5 + 6 + 7 + 3) * kMs / 5);
    ASSERT_EQ(one->parameters.size(), 2u);
    EXPECT_EQ(one->parameters.at(414).reads, 4u);
    EXPECT_EQ(one->parameters.at(414).writes, 0u);
    EXPECT_EQ(one->parameters.at(415).writes, 1u);
    EXPECT_EQ(one->channel.transactions.positive, 5u);

    const FcStationStats* two = run.station(2);
    ASSERT_NE(two, nullptr);
    EXPECT_EQ(two->commands, 4u);
    EXPECT_EQ(two->process_commands, 4u);
    EXPECT_EQ(two->answered, 4u);
    EXPECT_EQ(two->latency_ns.min(), 2u * kMs);
    EXPECT_TRUE(two->parameters.empty());
    EXPECT_EQ(two->channel.parameter_telegrams, 0u);  // process blocks skip the engine
}

TEST(FcTrackerTest, BroadcastsExpectNoAnswer) {
    FcRun run;
    run.feed(fc_parameter(0, 2, 302, 0, 10), 0);  // broadcast write, ADR 0x80
    run.feed(fc_process(0), 10);
    run.feed(fc_parameter(1, 1, 414), 20);
    run.feed(fc_parameter(1, 1, 414, 0, 5, 0x0607), 25);
    run.finish(9000);
    EXPECT_TRUE(run.all.empty());
    const FcStationStats* broadcasts = run.station(0);
    ASSERT_NE(broadcasts, nullptr);
    EXPECT_EQ(broadcasts->broadcasts, 2u);
    EXPECT_EQ(broadcasts->commands, 2u);
    EXPECT_EQ(broadcasts->answered, 0u);
    EXPECT_EQ(broadcasts->parameters.at(302).writes, 1u);
    EXPECT_EQ(run.tracker.transactions(), 1u);
}

TEST(FcTrackerTest, StackedCommandNamesTheFirst) {
    FcRun run;
    // An exchange first (the capture's first telegram is not judged, see
    // ACaptureStartingWithAResponseIsNotJudgedForIt).
    run.feed(fc_process(3), -1);
    run.feed(fc_process(3, 0x0607), -1);
    run.feed(fc_parameter(3, 1, 414), 0);
    std::vector<Finding> found = run.feed(fc_parameter(3, 14, 415, 0, 7), 5);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::FcStackedRequest);
    EXPECT_EQ(found[0].frame, 4u);
    EXPECT_EQ(found[0].request_frame, 3u);
    EXPECT_EQ(found[0].slave, 3);
    EXPECT_EQ(found[0].pnu, 414);
    EXPECT_NE(found[0].message.find("AK 14"), std::string::npos) << found[0].message;
    // The answer to the second command is its answer, not a mismatch for the first.
    EXPECT_TRUE(run.feed(fc_parameter(3, 1, 415, 0, 7, 0x0607), 8).empty());
    EXPECT_EQ(run.station(3)->answered, 2u);
}

TEST(FcTrackerTest, NoResponseWhenTheMasterMovesOnOrTheTimeOutPasses) {
    FcRun run;
    // An exchange with drive 9 first (the capture's first telegram is not judged, see
    // ACaptureStartingWithAResponseIsNotJudgedForIt).
    run.feed(fc_process(9), -1);
    run.feed(fc_process(9, 0x0607), -1);
    run.feed(fc_parameter(1, 1, 414), 0);
    std::vector<Finding> found = run.feed(fc_process(2), 40);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::FcNoResponse);
    EXPECT_EQ(found[0].slave, 1);
    EXPECT_EQ(found[0].request_frame, 3u);
    EXPECT_NE(found[0].message.find("master's next telegram"), std::string::npos);
    EXPECT_EQ(run.station(1)->no_responses, 1u);
    // Drive 2 never answers: found at the end, past the 1000 ms time-out.
    EXPECT_TRUE(run.finish(500).empty());
    found = run.finish(1100);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::FcNoResponse);
    EXPECT_EQ(found[0].slave, 2);
    EXPECT_NE(found[0].message.find("within 1000 ms"), std::string::npos) << found[0].message;
    EXPECT_TRUE(run.finish(3000).empty()) << "reported once";
}

TEST(FcTrackerTest, UntimedCaptureJudgesOnlyTheOrderOfTelegrams) {
    FcRun run;
    run.feed(fc_parameter(1, 1, 414), -1);
    run.feed(fc_parameter(1, 1, 414, 0, 5, 0x0607), -1);
    run.feed(fc_parameter(2, 1, 414), -1);
    EXPECT_TRUE(run.finish().empty());
    EXPECT_TRUE(run.all.empty());
    EXPECT_EQ(run.station(1)->latency_ns.count(), 0u);
    EXPECT_EQ(run.station(1)->answered, 1u);
}

TEST(FcTrackerTest, LateResponseFollowsTheOption) {
    FcTrackerOptions options;
    options.response_ns = 50 * kMs;  // the VLT 2800's documented time
    FcRun run(options);
    run.feed(fc_parameter(1, 1, 414), 0);
    EXPECT_TRUE(run.feed(fc_parameter(1, 1, 414, 0, 5, 0x0607), 50).empty());
    run.feed(fc_parameter(1, 1, 414), 100);
    std::vector<Finding> found = run.feed(fc_parameter(1, 1, 414, 0, 5, 0x0607), 151);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::FcLateResponse);
    EXPECT_EQ(found[0].severity, Severity::Warning);
    EXPECT_EQ(found[0].request_frame, 3u);
    EXPECT_NE(found[0].message.find("51.000 ms (more than 50 ms)"), std::string::npos)
        << found[0].message;
    EXPECT_EQ(run.station(1)->late, 1u);
    EXPECT_EQ(run.station(1)->answered, 2u);
}

TEST(FcTrackerTest, ResponseFromAnotherDriveIsMismatched) {
    FcRun run;
    // Drives 2 and 4 have been commanded before (nothing before that is judged, see
    // ResponseBeforeTheFirstCommandToItsDriveIsNotJudged).
    for (std::uint8_t drive : {std::uint8_t{2}, std::uint8_t{4}}) {
        run.feed(fc_process(drive), -1);
        run.feed(fc_process(drive, 0x0607), -1);
    }
    run.feed(fc_parameter(1, 1, 414), 0);
    // AK 7 is only a response: from drive 2 while drive 1 is asked.
    std::vector<Finding> found = run.feed(fc_parameter(2, 7, 414, 0, 0, 0x0607), 3);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::FcMismatchedResponse);
    EXPECT_EQ(found[0].slave, 2);
    EXPECT_EQ(found[0].request_frame, 5u);
    // Drive 1 still answers its command.
    EXPECT_TRUE(run.feed(fc_parameter(1, 1, 414, 0, 5, 0x0607), 6).empty());
    // An AK 7 with no command pending at all.
    found = run.feed(fc_parameter(4, 7, 414, 0, 0, 0x0607), 9);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::FcMismatchedResponse);
    EXPECT_EQ(found[0].request_frame, 0u);
    EXPECT_NE(found[0].message.find("no command was pending"), std::string::npos);
}

TEST(FcTrackerTest, IndexIsCheckedInTheAnswer) {
    FcRun run;
    run.feed(fc_parameter(1, 1, 1530, 2), 0);  // 15-30 alarm log, index 2
    std::vector<Finding> found = run.feed(fc_parameter(1, 1, 1530, 3, 9, 0x0607), 4);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::FcMismatchedResponse);
    EXPECT_NE(found[0].message.find("IND 3"), std::string::npos) << found[0].message;
    EXPECT_EQ(run.station(1)->channel.transactions.mismatched, 1u);
}

TEST(FcTrackerTest, RejectionNamesTheFaultCodeAndCountsIt) {
    FcRun run;
    run.feed(fc_parameter(1, 14, 414, 0, 60000), 0);
    std::vector<Finding> found = run.feed(fc_parameter(1, 7, 414, 0, 2, 0x0607), 4);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::FcCommandRejected);
    EXPECT_EQ(found[0].severity, Severity::Note);
    EXPECT_EQ(found[0].message,
              "AK 14 (Write parameter value in RAM and EEPROM (word)) PNU 414 IND 0 rejected with "
              "fault code 2 (Upper or lower limit is exceeded)");
    const FcStationStats* one = run.station(1);
    EXPECT_EQ(one->channel.transactions.rejected, 1u);
    EXPECT_EQ(one->channel.rejection_errors.at(2), 1u);
    EXPECT_EQ(one->channel.rejections.at({414, 2}), 1u);
    // A fault code the table does not define.
    run.feed(fc_parameter(1, 1, 415), 10);
    found = run.feed(fc_parameter(1, 7, 415, 0, 100, 0x0607), 14);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_NE(found[0].message.find("fault code 100 (unknown fault code)"), std::string::npos)
        << found[0].message;
}

TEST(FcTrackerTest, UnexpectedAkAndUndefinedCodes) {
    FcRun run;
    run.feed(fc_parameter(1, 3, 414, 0, 70000), 0);  // write double word
    std::vector<Finding> found = run.feed(fc_parameter(1, 1, 414, 0, 70000, 0x0607), 4);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::FcUnexpectedResponseType);
    // AK 5 is no FC command: unknown_code; the answer then closes it whatever it is.
    run.feed(fc_parameter(1, 5, 414), 10);
    EXPECT_EQ(run.all.back().kind, FindingKind::UnknownCode);
    EXPECT_NE(run.all.back().message.find("request code AK 5 is not defined in the FC protocol"),
              std::string::npos)
        << run.all.back().message;
    // An undefined response AK, twice the same: each is a response of its own, each reported.
    // (Drive 2: a read to drive 1 now would look like the answer to its AK 5 command.)
    for (std::int64_t t : {20, 30}) {
        run.feed(fc_parameter(2, 1, 414), t);
        found = run.feed(fc_parameter(2, 5, 414, 0, 0, 0x0607), t + 4);
        ASSERT_EQ(found.size(), 1u) << t;
        EXPECT_EQ(found[0].kind, FindingKind::UnknownCode);
        EXPECT_NE(found[0].message.find("response code AK 5"), std::string::npos);
    }
}

TEST(FcTrackerTest, DamagedTelegramsAreReportedAndOtherwiseIgnored) {
    FcRun run;
    std::vector<std::uint8_t> command = fc_parameter(1, 1, 414);
    command.back() ^= 0xFF;
    std::vector<Finding> found = run.feed(command, 0);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::FcBccError);
    EXPECT_FALSE(found[0].message.empty());
    // The drive ignored the damaged command; the master's next one is no stacked command.
    run.feed(fc_parameter(1, 1, 414), 20);
    std::vector<std::uint8_t> answer = fc_parameter(1, 1, 414, 0, 5, 0x0607);
    answer.back() ^= 0x10;
    found = run.feed(answer, 24);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::FcBccError);
    // The damaged answer ended the wait: no fc_no_response at the next command.
    EXPECT_TRUE(run.feed(fc_parameter(2, 1, 414), 40).empty());
    // A truncated telegram is malformed.
    std::vector<std::uint8_t> cut = fc_parameter(2, 1, 414, 0, 5, 0x0607);
    cut.resize(9);
    found = run.feed(cut, 44);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::MalformedTelegram);
    EXPECT_NE(found[0].message.find("truncated"), std::string::npos) << found[0].message;
    // Garbage names no station.
    found = run.feed({0x55, 0x55}, 50);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_FALSE(found[0].has_stations);
    EXPECT_EQ(run.tracker.bus().findings[static_cast<std::size_t>(FindingKind::MalformedTelegram)],
              1u);
}

TEST(FcTrackerTest, ParametersPerAddressAreBounded) {
    FcRun run;
    for (std::uint16_t pnu = 0; pnu < 300; ++pnu) {
        run.feed(fc_parameter(1, 1, pnu), pnu * 10);
        run.feed(fc_parameter(1, 1, pnu, 0, 5, 0x0607), pnu * 10 + 2);
    }
    const FcStationStats* one = run.station(1);
    EXPECT_EQ(one->parameters.size(), FcStationStats::kMaxParameters);
    EXPECT_EQ(one->parameters_not_counted, 300u - FcStationStats::kMaxParameters);
    EXPECT_TRUE(run.all.empty());
}

TEST(FcTrackerTest, FindingsAreCountedPerAddressKindAndSeverity) {
    FcRun run;
    run.feed(fc_parameter(1, 1, 414), 0);
    run.feed(fc_parameter(1, 1, 414, 0, 5, 0x0607), 30);  // late
    run.feed(fc_parameter(1, 1, 414), 40);
    run.feed(fc_process(2), 50);  // no response from 1
    const FcStationStats* one = run.station(1);
    const auto late = static_cast<std::size_t>(FindingKind::FcLateResponse);
    const auto none = static_cast<std::size_t>(FindingKind::FcNoResponse);
    EXPECT_EQ(one->findings[late], 1u);
    EXPECT_EQ(one->findings_by_severity[late][static_cast<std::size_t>(Severity::Warning)], 1u);
    EXPECT_EQ(one->findings[none], 1u);
    EXPECT_EQ(run.tracker.findings(Severity::Error), 1u);
    EXPECT_EQ(run.tracker.findings(Severity::Warning), 1u);
}

TEST(FcTrackerTest, KindsAreTheFcComponentsAndTheSharedOnes) {
    for (FindingKind kind : finding_kinds_of(FindingComponent::FcProtocol))
        EXPECT_TRUE(is_fc_finding_kind(kind)) << finding_kind_name(kind);
    EXPECT_TRUE(is_fc_finding_kind(FindingKind::MalformedTelegram));
    EXPECT_TRUE(is_fc_finding_kind(FindingKind::UnknownCode));
    EXPECT_FALSE(is_fc_finding_kind(FindingKind::StackedRequest));
    EXPECT_FALSE(is_fc_finding_kind(FindingKind::FcsError));
    EXPECT_EQ(fc_finding_kinds().size(), finding_kinds_of(FindingComponent::FcProtocol).size() + 2);
    EXPECT_TRUE(std::is_sorted(fc_finding_kinds().begin(), fc_finding_kinds().end()));
}

TEST(FcTrackerTest, ResponseTimeRunsFromTheCommandsLastByteAtTheLineRate) {
    // 16 bytes at 9600 baud, 11 bits a byte: the command is on the line for 18.333 ms, so an
    // answer starting 23.333 ms after the command started came 5 ms after its last byte.
    FcTrackerOptions options;
    options.line_baud = 9600;
    FcRun run(options);
    const std::int64_t wire_ns = 16 * 11 * 1'000'000'000LL / 9600;
    FcDecoder& decoder = run.decoder;
    FcTracker& tracker = run.tracker;
    const auto command = fc_parameter(1, 1, 414);
    const auto answer = fc_parameter(1, 1, 414, 0, 10, 0x0607);
    (void)tracker.track(decoder.decode(command, 0, 1));
    (void)tracker.track(decoder.decode(answer, wire_ns + 5 * kMs, 2));
    // A second answer 30 ms after the last byte is late (20 ms by default).
    (void)tracker.track(decoder.decode(command, 100 * kMs, 3));
    std::span<const Finding> late =
        tracker.track(decoder.decode(answer, 100 * kMs + wire_ns + 30 * kMs, 4));
    const FcStationStats* one = run.station(1);
    ASSERT_NE(one, nullptr);
    EXPECT_EQ(one->latency_ns.min(), 5u * kMs);
    ASSERT_EQ(late.size(), 1u);
    EXPECT_EQ(late[0].kind, FindingKind::FcLateResponse);
    EXPECT_NE(late[0].message.find("after 30.000 ms"), std::string::npos) << late[0].message;
}

TEST(FcTrackerTest, ACaptureStartingWithAResponseIsNotJudgedForIt) {
    // A tap clipped onto a running bus: the first telegram is drive 1's answer, taken for a
    // command (nothing marks it); the master then polls drive 2. No fc_no_response for it.
    FcRun run;
    run.feed(fc_process(1, 0x0607), 0);
    run.feed(fc_process(2), 10);
    run.feed(fc_process(2, 0x0607), 15);
    run.feed(fc_process(1), 30);
    run.feed(fc_process(1, 0x0607), 35);
    EXPECT_TRUE(run.all.empty()) << run.all[0].message;
    // Later in the capture the same pattern is a missing answer.
    run.feed(fc_process(1), 200);
    std::vector<Finding> found = run.feed(fc_process(2), 210);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::FcNoResponse);
    // Nor is it a stacked command when the master's next command goes to the same drive, nor
    // unanswered when the time-out passes.
    FcRun same;
    same.feed(fc_process(1, 0x0607), 0);
    same.feed(fc_parameter(1, 1, 414), 10);
    same.feed(fc_parameter(1, 1, 414, 0, 5, 0x0607), 15);
    same.finish(5000);
    EXPECT_TRUE(same.all.empty()) << same.all[0].message;
    FcRun alone;
    alone.feed(fc_process(1, 0x0607), 0);
    alone.finish(5000);
    EXPECT_TRUE(alone.all.empty()) << alone.all[0].message;
    // A first command whose AK only a command has is judged from the start.
    FcRun certain;
    certain.feed(fc_parameter(1, 14, 202, 0, 5), 0);
    found = certain.feed(fc_process(2), 10);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::FcNoResponse);
}

// A response (AK 7 marks one wherever it comes) from a drive the capture has not yet seen a
// command to: its command may have come before the capture began. Nothing before the first
// command to a drive is judged; after it, the same response is a mismatched one.
TEST(FcTrackerTest, ResponseBeforeTheFirstCommandToItsDriveIsNotJudged) {
    FcRun run;
    run.feed(fc_parameter(4, 7, 414, 0, 0, 0x0607), 0);  // no command pending
    run.feed(fc_parameter(1, 1, 414), 10);
    run.feed(fc_parameter(2, 7, 414, 0, 0, 0x0607), 13);  // while drive 1 is asked
    run.feed(fc_parameter(1, 1, 414, 0, 5, 0x0607), 16);
    run.finish(5000);
    EXPECT_TRUE(run.all.empty()) << run.all[0].message;
    EXPECT_EQ(run.station(4)->responses, 1u);
    EXPECT_EQ(run.station(2)->responses, 1u);
    run.feed(fc_process(4), 6000);
    run.feed(fc_process(4, 0x0607), 6004);
    std::vector<Finding> found = run.feed(fc_parameter(4, 7, 414, 0, 0, 0x0607), 6010);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::FcMismatchedResponse);
}

}  // namespace
}  // namespace dpscope

namespace dpscope {
namespace {

// A process-data command answered with a parameter block (AK 7 is a response in any case, so
// the decoder calls it one): the answer is a mismatched response naming the block and the
// command, and the command is closed (no time-out follows).
TEST(FcTrackerTest, AnswerWithTheOtherBlockTypeIsAMismatchedResponse) {
    FcRun run;
    run.feed(fc_process(1), 0);
    std::vector<Finding> found = run.feed(fc_parameter(1, 7, 414, 0, 0, 0x0607), 4);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::FcMismatchedResponse);
    EXPECT_EQ(found[0].frame, 2u);
    EXPECT_EQ(found[0].request_frame, 1u);
    EXPECT_NE(found[0].message.find("block answers the command"), std::string::npos)
        << found[0].message;
    EXPECT_TRUE(run.finish(5000).empty());
}

// A byte after the BCC is a problem of warning severity only (trailing_bytes): the telegram is
// still intact, so no malformed_telegram is reported and the exchange is tracked as usual.
TEST(FcTrackerTest, TrailingBytesAloneLeaveTheTelegramIntact) {
    std::vector<std::uint8_t> command = fc_parameter(1, 1, 414);
    command.push_back(0x00);
    std::vector<std::uint8_t> answer = fc_parameter(1, 1, 414, 0, 5, 0x0607);
    answer.push_back(0x00);
    {
        FcDecoder decoder;
        const DecodedTelegram& t = decoder.decode(command, 0, 1);
        ASSERT_EQ(t.problems().size(), 1u);
        EXPECT_EQ(t.problems()[0].kind, ProblemKind::TrailingBytes);
        EXPECT_EQ(problem_severity(t.problems()[0].kind), Severity::Warning);
    }
    FcRun run;
    EXPECT_TRUE(run.feed(command, 0).empty());
    EXPECT_TRUE(run.feed(answer, 4).empty());
    EXPECT_TRUE(run.finish(5000).empty());
    const FcStationStats* one = run.station(1);
    ASSERT_NE(one, nullptr);
    EXPECT_EQ(one->telegrams, 2u);
    EXPECT_EQ(one->commands, 1u);
    EXPECT_EQ(one->responses, 1u);
    EXPECT_EQ(one->answered, 1u);
    EXPECT_EQ(one->latency_ns.min(), 4u * kMs);
    EXPECT_EQ(run.tracker.transactions(), 1u);
}

}  // namespace
}  // namespace dpscope

namespace dpscope {
namespace {

// Every command to a drive has one outcome, so the counts add up (#27 point 12): commands =
// broadcasts + answered + unanswered + abandoned + damaged + not judged. Damaged telegrams count
// among the commands and responses (as decode -q counts them), and are the outcome "damaged".
void feed_every_outcome(FcRun& run) {
    run.feed(fc_process(1, 0x0607), 0);  // 1: the capture begins with drive 1's answer: not judged
    run.feed(fc_process(2), 10);         // 2: answered by 3
    run.feed(fc_process(2, 0x0607), 14);
    run.feed(fc_process(2), 20);  // 4: unanswered: the master moves on to drive 1
    run.feed(fc_parameter(1, 1, 414),
             30);  // 5: abandoned: a new command to drive 1 before its answer
    run.feed(fc_parameter(1, 14, 415, 0, 7), 40);  // 6: its answer (7) is damaged
    std::vector<std::uint8_t> answer = fc_parameter(1, 1, 415, 0, 7, 0x0607);
    answer.back() ^= 0x10;
    run.feed(answer, 44);
    std::vector<std::uint8_t> command = fc_process(2);  // 8: a damaged command (the drive drops it)
    command.back() ^= 0x10;
    run.feed(command, 50);
    run.feed(fc_process(0), 60);  // 9: a broadcast
    run.feed(fc_process(2), 70);  // 10: still waiting for its answer when the capture ends
}

void expect_outcomes_add_up(const FcRun& run) {
    for (const FcStationStats* s : run.tracker.stations()) {
        SCOPED_TRACE(s->address);
        EXPECT_EQ(s->commands, s->broadcasts + s->answered + s->no_responses + s->abandoned +
                                   s->damaged + s->not_judged + s->open);
        EXPECT_EQ(s->commands, s->commands_outcomes());
    }
}

TEST(FcTrackerTest, EveryCommandHasOneOutcomeAndTheCountsAddUp) {
    FcRun run;
    feed_every_outcome(run);
    run.finish();  // at the last telegram: command 10 is within its time-out
    expect_outcomes_add_up(run);
    const FcStationStats* one = run.station(1);
    ASSERT_NE(one, nullptr);
    EXPECT_EQ(one->commands, 3u);
    EXPECT_EQ(one->answered, 0u);
    EXPECT_EQ(one->no_responses, 0u);
    EXPECT_EQ(one->abandoned, 1u);
    EXPECT_EQ(one->damaged, 1u);
    EXPECT_EQ(one->not_judged, 1u);
    EXPECT_EQ(one->open, 0u);
    EXPECT_EQ(one->responses, 1u);
    EXPECT_EQ(one->damaged_responses, 1u);
    EXPECT_EQ(one->damaged_commands, 0u);
    const FcStationStats* two = run.station(2);
    ASSERT_NE(two, nullptr);
    EXPECT_EQ(two->commands, 4u);
    EXPECT_EQ(two->answered, 1u);
    EXPECT_EQ(two->no_responses, 1u);
    EXPECT_EQ(two->abandoned, 0u);
    EXPECT_EQ(two->damaged, 1u);
    EXPECT_EQ(two->not_judged, 0u);
    EXPECT_EQ(two->open, 1u);
    EXPECT_EQ(two->damaged_commands, 1u);
    EXPECT_EQ(two->responses, 1u);
    const FcStationStats* broadcasts = run.station(0);
    ASSERT_NE(broadcasts, nullptr);
    EXPECT_EQ(broadcasts->commands, 1u);
    EXPECT_EQ(broadcasts->broadcasts, 1u);

    // Past the time-out at the end, the last command is unanswered instead.
    FcRun late;
    feed_every_outcome(late);
    late.finish(5000);
    expect_outcomes_add_up(late);
    EXPECT_EQ(late.station(2)->no_responses, 2u);
    EXPECT_EQ(late.station(2)->not_judged, 0u);
    EXPECT_EQ(late.station(2)->open, 0u);
}

}  // namespace
}  // namespace dpscope
