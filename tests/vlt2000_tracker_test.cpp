// The VLT 2000 tracker (protocols/vlt2000/vlt2000_tracker.hpp) on hand-made 22-character telegrams
// decoded by Vlt2000Decoder: clean exchanges with their latency and per-address counts, broadcasts,
// each rule with its frames, parameter and message, time-outs by the next telegram, by --timeout-ms
// and at the end, the capture's first telegram, damaged telegrams, bounded memory.
#include "protocols/vlt2000/vlt2000_tracker.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <array>
#include <map>
#include <string>
#include <vector>

#include "protocols/vlt2000/vlt2000_decoder.hpp"

namespace dpscope {
namespace {

constexpr std::int64_t kMs = 1'000'000;

// A VLT 2000 telegram: '<', address (2 digits), letter, word (4 characters), parameter (4
// digits), sign, value (5 digits), decimals (1 digit), checksum, '>'. The checksum is the sum of
// the characters at offsets 1..18, mod 100, as two digits, unless `checksum` is given ("??", or
// a wrong one).
std::string vlt(int address, char letter, int parameter, long value = 0, int decimals = 0,
                std::string_view checksum = {}, std::string_view word = "@@@@") {
    std::string t = fmt::format("<{:02}{}{}{:04}{}{:05}{}", address, letter, word, parameter,
                                value < 0 ? '-' : '+', value < 0 ? -value : value, decimals);
    unsigned sum = 0;
    for (std::size_t i = 1; i < t.size(); ++i)
        sum += static_cast<unsigned char>(t[i]);
    t += checksum.empty() ? fmt::format("{:02}", sum % 100) : std::string(checksum);
    t += '>';
    return t;
}

// `t` with its checksum computed again (after a change).
std::string with_checksum(std::string t) {
    unsigned sum = 0;
    for (std::size_t i = 1; i <= 18; ++i)
        sum += static_cast<unsigned char>(t[i]);
    t.replace(19, 2, fmt::format("{:02}", sum % 100));
    return t;
}

// A drive's reply saying the command could not be carried out: decimals 9, the reason code in
// bytes 17-18 (none: "--" there).
std::string failed(int address, char letter, int parameter, int reason = -1) {
    if (reason >= 0) return vlt(address, letter, parameter, reason, 9);
    std::string t = vlt(address, letter, parameter, 0, 9);
    t[16] = '-';
    t[17] = '-';
    return with_checksum(t);
}

// The telegram with a wrong checksum.
std::string damaged(std::string t) {
    t[20] = t[20] == '0' ? '1' : '0';
    return t;
}

std::size_t at(FindingKind kind) { return static_cast<std::size_t>(kind); }

// Feeds telegrams through a decoder and a tracker, keeping every finding.
struct Vlt2000Run {
    explicit Vlt2000Run(Vlt2000TrackerOptions options = {})
        : decoder(Vlt2000DecoderOptions{options.timeout_ns, true}), tracker(options) {}

    // `time_ms` < 0: no timestamp.
    std::vector<Finding> feed(const std::string& text, std::int64_t time_ms = -1) {
        bytes.assign(text.begin(), text.end());
        const DecodedTelegram& t =
            decoder.decode(bytes, time_ms < 0 ? kNoTime : time_ms * kMs, ++frame);
        std::span<const Finding> found = tracker.track(t);
        completed += tracker.completed().size();
        return keep(std::vector<Finding>(found.begin(), found.end()));
    }
    std::vector<Finding> finish(std::int64_t end_ms = -1) {
        std::span<const Finding> found = tracker.finish(end_ms < 0 ? kNoTime : end_ms * kMs);
        return keep(std::vector<Finding>(found.begin(), found.end()));
    }
    std::vector<Finding> keep(std::vector<Finding> found) {
        for (const Finding& f : found)
            all.push_back(f);
        return found;
    }
    const Vlt2000StationStats* station(std::uint8_t address) const {
        for (const Vlt2000StationStats* s : tracker.stations())
            if (s->address == address) return s;
        return nullptr;
    }
    // An exchange with drive 99 first: the capture's first telegram is not judged.
    void warm_up() {
        feed(vlt(99, 'C', 0));
        feed(vlt(99, 'C', 0, 0, 0, {}, "GH@@"));
    }

    Vlt2000Decoder decoder;
    Vlt2000Tracker tracker;
    std::vector<std::uint8_t> bytes;
    std::uint64_t frame = 0;
    std::uint64_t completed = 0;
    std::vector<Finding> all;
};

TEST(Vlt2000TrackerTest, TheHelperBuildsTheManualsExample) {
    // [P:VLT3000 p79]: <01UOGD@0516+00080007>.
    EXPECT_EQ(vlt(1, 'U', 516, 80, 0, {}, "OGD@"), "<01UOGD@0516+00080007>");
    Vlt2000Decoder decoder;
    const std::string text = failed(4, 'R', 999);
    std::vector<std::uint8_t> bytes(text.begin(), text.end());
    const DecodedTelegram& t = decoder.decode(bytes, kNoTime, 1);
    EXPECT_TRUE(t.vlt2000.problems.empty());
    EXPECT_TRUE(t.vlt2000.failed);
    EXPECT_FALSE(t.vlt2000.has_reason);
}

TEST(Vlt2000TrackerTest, CleanExchangesHaveNoFindingsAndCountLatencyPerAddress) {
    Vlt2000Run run;
    run.feed(vlt(1, 'R', 102), 0);
    run.feed(vlt(1, 'R', 102, 1500, 1, {}, "GH@@"), 3);
    run.feed(vlt(1, 'U', 516, 800), 10);
    run.feed(vlt(1, 'U', 516, 800, 0, {}, "GH@@"), 15);
    run.feed(vlt(1, 'C', 0, 0, 0, {}, "OGD@"), 20);
    run.feed(vlt(1, 'C', 0, 0, 0, {}, "GHK@"), 24);
    run.feed(vlt(1, 'I', 601, 3), 30);
    run.feed(vlt(1, 'I', 601, 1234, 0, {}, "GH@@"), 37);
    run.feed(vlt(2, 'R', 102), 40);
    run.feed(vlt(2, 'R', 102, 20, 0, {}, "GH@@"), 42);
    run.feed(vlt(2, 'R', 102), 50);
    run.feed(vlt(2, 'R', 102, 20, 0, {}, "GH@@"), 52);
    run.finish(5000);
    EXPECT_TRUE(run.all.empty()) << run.all[0].message;
    EXPECT_EQ(run.tracker.transactions(), 6u);
    EXPECT_EQ(run.completed, 6u);
    EXPECT_EQ(run.tracker.findings(Severity::Error), 0u);

    const Vlt2000StationStats* one = run.station(1);
    ASSERT_NE(one, nullptr);
    EXPECT_EQ(one->telegrams, 8u);
    EXPECT_EQ(one->commands, 4u);
    EXPECT_EQ(one->commands_by_letter, (std::array<std::uint64_t, 4>{1, 1, 1, 1}));
    EXPECT_EQ(one->broadcasts, 0u);
    EXPECT_EQ(one->replies, 4u);
    EXPECT_EQ(one->answered, 4u);
    EXPECT_EQ(one->no_responses, 0u);
    EXPECT_EQ(one->latency_ns.count(), 4u);
    EXPECT_EQ(one->latency_ns.min(), 3u * kMs);
    EXPECT_EQ(one->latency_ns.max(), 7u * kMs);
    EXPECT_EQ(one->mean_latency_ns(), (3u + 5 + 4 + 7) * kMs / 4);
    // R and I read, U writes, C has no parameter.
    ASSERT_EQ(one->parameters.size(), 3u);
    EXPECT_EQ(one->parameters.at(102).reads, 1u);
    EXPECT_EQ(one->parameters.at(516).writes, 1u);
    EXPECT_EQ(one->parameters.at(516).reads, 0u);
    EXPECT_EQ(one->parameters.at(601).reads, 1u);
    EXPECT_EQ(one->parameters.count(0), 0u);
    EXPECT_EQ(one->channel.transactions.positive, 4u);
    EXPECT_EQ(one->first_time_ns, 0);
    EXPECT_EQ(one->last_time_ns, 37 * kMs);

    const Vlt2000StationStats* two = run.station(2);
    ASSERT_NE(two, nullptr);
    EXPECT_EQ(two->commands_by_letter[static_cast<std::size_t>(Vlt2000Letter::Read)], 2u);
    EXPECT_EQ(two->answered, 2u);
    EXPECT_EQ(two->parameters.at(102).reads, 2u);
    // The same answer twice is two transactions: every command is new.
    EXPECT_EQ(two->channel.transactions.positive, 2u);
    EXPECT_EQ(two->latency_ns.min(), 2u * kMs);
    EXPECT_EQ(run.tracker.stations().size(), 2u);
}

TEST(Vlt2000TrackerTest, TheSubjectIsTheParameterExceptForAControlTelegram) {
    Vlt2000Run run;
    run.feed(vlt(1, 'R', 102));
    EXPECT_EQ(run.tracker.subject_pnu(), 102);
    run.feed(vlt(1, 'R', 102, 5, 0, {}, "GH@@"));
    EXPECT_EQ(run.tracker.subject_pnu(), 102);
    run.feed(vlt(1, 'C', 516));
    EXPECT_EQ(run.tracker.subject_pnu(), -1);
}

TEST(Vlt2000TrackerTest, BroadcastsExpectNoReply) {
    Vlt2000Run run;
    run.feed(vlt(0, 'U', 516, 800), 0);
    run.feed(vlt(0, 'C', 0, 0, 0, {}, "OGD@"), 10);
    run.feed(vlt(1, 'R', 102), 20);
    run.feed(vlt(1, 'R', 102, 5, 0, {}, "GH@@"), 25);
    run.finish(9000);
    EXPECT_TRUE(run.all.empty()) << run.all[0].message;
    const Vlt2000StationStats* broadcasts = run.station(0);
    ASSERT_NE(broadcasts, nullptr);
    EXPECT_EQ(broadcasts->broadcasts, 2u);
    EXPECT_EQ(broadcasts->commands, 2u);
    EXPECT_EQ(broadcasts->commands_by_letter[static_cast<std::size_t>(Vlt2000Letter::Update)], 1u);
    EXPECT_EQ(broadcasts->commands_by_letter[static_cast<std::size_t>(Vlt2000Letter::Control)], 1u);
    EXPECT_EQ(broadcasts->answered, 0u);
    EXPECT_EQ(broadcasts->parameters.at(516).writes, 1u);
    EXPECT_EQ(run.tracker.transactions(), 1u);
}

TEST(Vlt2000TrackerTest, AReplyToABroadcastIsUnexpected) {
    Vlt2000Run run;
    run.feed(vlt(0, 'R', 102), 0);
    std::vector<Finding> found = run.feed(vlt(0, 'R', 102, 7, 0, {}, "GH@@"), 5);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::Vlt2000UnexpectedReply);
    EXPECT_EQ(found[0].severity, Severity::Error);
    EXPECT_EQ(found[0].frame, 2u);
    EXPECT_EQ(found[0].request_frame, 1u);
    EXPECT_EQ(found[0].slave, 0);
    EXPECT_EQ(found[0].pnu, 102);
    EXPECT_NE(found[0].message.find("broadcast from frame 1"), std::string::npos)
        << found[0].message;
    EXPECT_EQ(run.station(0)->replies, 1u);
    EXPECT_EQ(run.station(0)->answered, 0u);
    // A failed reply with address 00 and no broadcast before it: still nobody's to send.
    found = run.feed(failed(0, 'U', 516, 1), 10);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::Vlt2000UnexpectedReply);
    EXPECT_EQ(found[0].request_frame, 0u);
    EXPECT_NE(found[0].message.find("nobody replies to a broadcast"), std::string::npos)
        << found[0].message;
    EXPECT_EQ(run.station(0)->failed, 1u);
}

TEST(Vlt2000TrackerTest, StackedCommandNamesTheFirst) {
    Vlt2000Run run;
    run.warm_up();
    run.feed(vlt(3, 'R', 102), 0);
    std::vector<Finding> found = run.feed(vlt(3, 'U', 516, 800), 5);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::Vlt2000StackedRequest);
    EXPECT_EQ(found[0].frame, 4u);
    EXPECT_EQ(found[0].request_frame, 3u);
    EXPECT_EQ(found[0].slave, 3);
    EXPECT_EQ(found[0].pnu, 102);
    EXPECT_NE(found[0].message.find("new command U (update) parameter 516 to drive 03 while the "
                                    "command R (read) parameter 102 from frame 3 was unanswered"),
              std::string::npos)
        << found[0].message;
    // The reply to the second command is its reply, not a mismatch for the first.
    EXPECT_TRUE(run.feed(vlt(3, 'U', 516, 800, 0, {}, "GH@@"), 8).empty());
    EXPECT_EQ(run.station(3)->answered, 1u);
    EXPECT_EQ(run.station(3)->no_responses, 0u);
    EXPECT_EQ(run.station(3)->channel.abandoned, 1u);

    // The same command sent again (the same characters) is stacked too.
    run.feed(vlt(3, 'C', 0, 0, 0, {}, "OGD@"), 20);
    found = run.feed(vlt(3, 'C', 0, 0, 0, {}, "OGD@"), 25);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::Vlt2000StackedRequest);
    EXPECT_FALSE(found[0].pnu.has_value());  // a C command's parameter is none
    EXPECT_NE(found[0].message.find("C (control)"), std::string::npos) << found[0].message;
}

TEST(Vlt2000TrackerTest, NoResponseWhenTheMasterMovesOn) {
    Vlt2000Run run;
    run.warm_up();
    run.feed(vlt(1, 'R', 102));
    std::vector<Finding> found = run.feed(vlt(2, 'C', 0));
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::Vlt2000NoResponse);
    EXPECT_EQ(found[0].frame, 4u);
    EXPECT_EQ(found[0].request_frame, 3u);
    EXPECT_EQ(found[0].slave, 1);
    EXPECT_EQ(found[0].pnu, 102);
    EXPECT_NE(found[0].message.find("command R (read) parameter 102 to drive 01 from frame 3 got "
                                    "no reply before the master's next telegram"),
              std::string::npos)
        << found[0].message;
    EXPECT_EQ(run.station(1)->no_responses, 1u);
    EXPECT_EQ(run.station(1)->findings[at(FindingKind::Vlt2000NoResponse)], 1u);
    EXPECT_EQ(run.station(2)->findings[at(FindingKind::Vlt2000NoResponse)], 0u);
    // A broadcast is the master moving on too; nothing waits after it.
    found = run.feed(vlt(0, 'C', 0));
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].slave, 2);
    EXPECT_FALSE(found[0].pnu.has_value());
    EXPECT_TRUE(run.finish().empty());
    EXPECT_EQ(run.station(2)->no_responses, 1u);
}

TEST(Vlt2000TrackerTest, NoResponseWhenTheTimeOutPasses) {
    Vlt2000Run run(Vlt2000TrackerOptions{200 * kMs});
    run.warm_up();
    run.feed(vlt(1, 'R', 102), 0);
    // Before the time-out the master may wait; after it the command is unanswered, said at the
    // next telegram, even one to the same drive (no stacked command then: the first was given up).
    std::vector<Finding> found = run.feed(vlt(1, 'U', 516, 1), 250);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::Vlt2000NoResponse);
    EXPECT_EQ(found[0].frame, 4u);
    EXPECT_EQ(found[0].request_frame, 3u);
    EXPECT_EQ(found[0].time_ns, 250 * kMs);
    EXPECT_NE(found[0].message.find("got no reply within 200 ms"), std::string::npos)
        << found[0].message;
    EXPECT_TRUE(run.feed(vlt(1, 'U', 516, 1, 0, {}, "GH@@"), 300).empty());
    EXPECT_EQ(run.station(1)->answered, 1u);
    EXPECT_EQ(run.station(1)->no_responses, 1u);
    // A reply just within the time-out is no missing one.
    run.feed(vlt(1, 'R', 102), 400);
    EXPECT_TRUE(run.feed(vlt(1, 'R', 102, 3, 0, {}, "GH@@"), 600).empty());
}

TEST(Vlt2000TrackerTest, NoResponseAtTheEndOfTheCapture) {
    Vlt2000Run run;
    run.warm_up();
    run.feed(vlt(1, 'R', 102), 0);
    EXPECT_TRUE(run.finish(500).empty());
    std::vector<Finding> found = run.finish(1100);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::Vlt2000NoResponse);
    EXPECT_EQ(found[0].frame, 3u);  // the last telegram
    EXPECT_EQ(found[0].request_frame, 3u);
    EXPECT_EQ(found[0].time_ns, 1100 * kMs);
    EXPECT_TRUE(run.finish(3000).empty()) << "reported once";
    EXPECT_EQ(run.station(1)->no_responses, 1u);
}

TEST(Vlt2000TrackerTest, UntimedCaptureJudgesOnlyTheOrderOfTelegrams) {
    Vlt2000Run run;
    run.warm_up();
    run.feed(vlt(1, 'R', 102));
    EXPECT_TRUE(run.finish().empty());
    EXPECT_EQ(run.station(1)->latency_ns.count(), 0u);
    EXPECT_FALSE(run.station(1)->timed());
}

TEST(Vlt2000TrackerTest, ACaptureStartingWithAReplyIsNotStackedOnOrTimedOut) {
    // A single drive: its reply first, then the master's next command to it with another letter.
    Vlt2000Run run;
    run.feed(vlt(1, 'R', 102, 5, 0, {}, "GH@@"), 0);
    EXPECT_TRUE(run.feed(vlt(1, 'C', 0, 0, 0, {}, "OGD@"), 5).empty());
    EXPECT_TRUE(run.feed(vlt(1, 'C', 0, 0, 0, {}, "GHK@"), 8).empty());
    EXPECT_EQ(run.station(1)->answered, 1u);
    // Nor after the time-out, at the next telegram or at the end.
    Vlt2000Run slow;
    slow.feed(vlt(1, 'R', 102, 5, 0, {}, "GH@@"), 0);
    EXPECT_TRUE(slow.feed(vlt(1, 'C', 0), 1500).empty());
    EXPECT_TRUE(slow.feed(vlt(1, 'C', 0, 0, 0, {}, "GHK@"), 1503).empty());
    Vlt2000Run alone;
    alone.feed(vlt(1, 'R', 102, 5, 0, {}, "GH@@"), 0);
    EXPECT_TRUE(alone.finish(5000).empty());
    EXPECT_EQ(alone.station(1)->no_responses, 0u);
}

TEST(Vlt2000TrackerTest, ACaptureStartingWithAReplyIsNotJudgedForIt) {
    // A tap clipped onto a running line: the first telegram is drive 1's reply, taken for a
    // command; the master's next command goes to drive 2.
    Vlt2000Run run;
    run.feed(vlt(1, 'R', 102, 5, 0, {}, "GH@@"));
    EXPECT_TRUE(run.feed(vlt(2, 'R', 102)).empty());
    EXPECT_TRUE(run.feed(vlt(2, 'R', 102, 5, 0, {}, "GH@@")).empty());
    // Later commands are judged.
    run.feed(vlt(3, 'R', 102));
    std::vector<Finding> found = run.feed(vlt(2, 'C', 0));
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::Vlt2000NoResponse);
    EXPECT_EQ(found[0].slave, 3);
    EXPECT_EQ(run.station(1)->no_responses, 0u);
}

TEST(Vlt2000TrackerTest, AFailedReplyFromAnotherDriveIsMismatched) {
    Vlt2000Run run;
    // Drives 2 and 5 have been commanded before (nothing before that is judged, see
    // AReplyBeforeTheFirstCommandToItsDriveIsNotJudged).
    for (int drive : {2, 5}) {
        run.feed(vlt(drive, 'C', 0));
        run.feed(vlt(drive, 'C', 0, 0, 0, {}, "GH@@"));
    }
    run.feed(vlt(1, 'R', 102), 0);
    std::vector<Finding> found = run.feed(failed(2, 'R', 102, 0), 2);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::Vlt2000MismatchedResponse);
    EXPECT_EQ(found[0].frame, 6u);
    EXPECT_EQ(found[0].request_frame, 5u);
    EXPECT_EQ(found[0].slave, 2);
    EXPECT_EQ(found[0].pnu, 102);
    EXPECT_NE(found[0].message.find("reply R (read) parameter 102 from drive 02 while the command "
                                    "to drive 01 from frame 5 was pending"),
              std::string::npos)
        << found[0].message;
    EXPECT_EQ(run.station(2)->replies, 2u);
    EXPECT_EQ(run.station(2)->failed, 1u);
    EXPECT_EQ(run.station(2)->answered, 1u);
    // The command still waits for drive 1.
    EXPECT_TRUE(run.feed(vlt(1, 'R', 102, 5, 0, {}, "GH@@"), 4).empty());
    EXPECT_EQ(run.station(1)->answered, 1u);
    EXPECT_EQ(run.station(1)->latency_ns.max(), 4u * kMs);

    // With nothing pending.
    found = run.feed(failed(5, 'U', 516, 4), 10);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::Vlt2000MismatchedResponse);
    EXPECT_EQ(found[0].request_frame, 0u);
    EXPECT_NE(found[0].message.find("from drive 05 but no command was pending"), std::string::npos)
        << found[0].message;
}

// A failed reply (decimal position 9 marks one wherever it comes) from a drive the capture has
// not yet seen a command to: its command may have come before the capture began. Nothing before
// the first command to a drive is judged; after it, the same reply is a mismatched one.
TEST(Vlt2000TrackerTest, AReplyBeforeTheFirstCommandToItsDriveIsNotJudged) {
    Vlt2000Run run;
    run.feed(failed(5, 'U', 516, 4), 0);  // nothing pending
    run.feed(vlt(1, 'R', 102), 10);
    run.feed(failed(2, 'R', 102, 0), 12);  // while drive 1 is asked
    run.feed(vlt(1, 'R', 102, 5, 0, {}, "GH@@"), 14);
    run.finish(5000);
    EXPECT_TRUE(run.all.empty()) << run.all[0].message;
    EXPECT_EQ(run.station(5)->replies, 1u);
    EXPECT_EQ(run.station(2)->replies, 1u);
    run.feed(vlt(5, 'C', 0), 6000);
    run.feed(vlt(5, 'C', 0, 0, 0, {}, "GH@@"), 6004);
    std::vector<Finding> found = run.feed(failed(5, 'U', 516, 4), 6010);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::Vlt2000MismatchedResponse);
}

TEST(Vlt2000TrackerTest, AReplyWithAnotherLetterOrParameterIsMismatched) {
    Vlt2000Run run;
    // Another letter: only a failed reply is taken for a reply then.
    run.feed(vlt(1, 'R', 102), 0);
    std::vector<Finding> found = run.feed(failed(1, 'U', 102, 0), 3);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::Vlt2000MismatchedResponse);
    EXPECT_EQ(found[0].request_frame, 1u);
    EXPECT_EQ(found[0].pnu, 102);
    EXPECT_NE(found[0].message.find("reply U (update) parameter 102 (another letter) answers the "
                                    "command R (read) parameter 102 from frame 1"),
              std::string::npos)
        << found[0].message;
    EXPECT_EQ(run.station(1)->answered, 1u);  // it answered, wrongly
    EXPECT_EQ(run.station(1)->failed, 1u);
    EXPECT_EQ(run.station(1)->findings[at(FindingKind::Vlt2000CommandFailed)], 0u);

    // Another parameter.
    run.feed(vlt(1, 'R', 102), 10);
    found = run.feed(vlt(1, 'R', 103, 5, 0, {}, "GH@@"), 12);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::Vlt2000MismatchedResponse);
    EXPECT_EQ(found[0].frame, 4u);
    EXPECT_EQ(found[0].request_frame, 3u);
    EXPECT_EQ(found[0].pnu, 102);
    EXPECT_NE(found[0].message.find("reply R (read) parameter 103 (another parameter) answers the "
                                    "command R (read) parameter 102 from frame 3"),
              std::string::npos)
        << found[0].message;
    EXPECT_EQ(run.station(1)->answered, 2u);
    EXPECT_EQ(run.station(1)->latency_ns.count(), 2u);
    EXPECT_EQ(run.station(1)->channel.transactions.mismatched, 1u);
    EXPECT_EQ(run.station(1)->findings[at(FindingKind::Vlt2000MismatchedResponse)], 2u);

    // A C reply's parameter is ignored [S004].
    run.feed(vlt(1, 'C', 0, 0, 0, {}, "OGD@"), 20);
    EXPECT_TRUE(run.feed(vlt(1, 'C', 516, 123, 0, {}, "GHK@"), 22).empty());
    EXPECT_EQ(run.station(1)->answered, 3u);
}

TEST(Vlt2000TrackerTest, AFailedCommandIsANoteWithItsReasonCode) {
    Vlt2000Run run;
    run.feed(vlt(1, 'R', 999), 0);
    std::vector<Finding> found = run.feed(failed(1, 'R', 999, 0), 3);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::Vlt2000CommandFailed);
    EXPECT_EQ(found[0].severity, Severity::Note);
    EXPECT_EQ(found[0].frame, 2u);
    EXPECT_EQ(found[0].request_frame, 1u);
    EXPECT_EQ(found[0].pnu, 999);
    EXPECT_NE(found[0].message.find("drive 01 could not carry out the command R (read) parameter "
                                    "999 from frame 1: reason code 00 (parameter does not exist)"),
              std::string::npos)
        << found[0].message;
    // An update refused as read-only, a reason no text is known for, and none at all.
    run.feed(vlt(1, 'U', 1, 3), 10);
    found = run.feed(failed(1, 'U', 1, 4), 12);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_NE(found[0].message.find("reason code 04 (read only"), std::string::npos)
        << found[0].message;
    run.feed(vlt(1, 'U', 1, 3), 20);
    found = run.feed(failed(1, 'U', 1, 42), 22);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_NE(found[0].message.find("reason code 42 (unknown reason code)"), std::string::npos)
        << found[0].message;
    run.feed(vlt(1, 'R', 998), 30);
    found = run.feed(failed(1, 'R', 998), 31);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::Vlt2000CommandFailed);
    EXPECT_NE(found[0].message.find("from frame 7 (decimal position 9: unknown parameter or "
                                    "command failed)"),
              std::string::npos)
        << found[0].message;

    const Vlt2000StationStats* one = run.station(1);
    EXPECT_EQ(one->failed, 4u);
    EXPECT_EQ(one->failures_by_reason,
              (std::map<std::uint8_t, std::uint64_t>{{0, 1}, {4, 1}, {42, 1}}));
    EXPECT_EQ(one->failures_without_reason, 1u);
    EXPECT_EQ(one->answered, 4u);
    EXPECT_EQ(one->findings[at(FindingKind::Vlt2000CommandFailed)], 4u);
    EXPECT_EQ(one->findings_by_severity[at(FindingKind::Vlt2000CommandFailed)]
                                       [static_cast<std::size_t>(Severity::Note)],
              4u);
    // The engine counts them rejected, by reason (100: none given).
    EXPECT_EQ(one->channel.transactions.rejected, 4u);
    EXPECT_EQ(one->channel.rejection_errors.at(4), 1u);
    EXPECT_EQ(one->channel.rejection_errors.at(100), 1u);
    EXPECT_EQ(run.tracker.findings(Severity::Note), 4u);
}

TEST(Vlt2000TrackerTest, ChecksumErrorsAreReportedAndTheTelegramIgnored) {
    Vlt2000Run run;
    run.warm_up();
    // A damaged command: reported, counted as a damaged command (its outcome), nothing waits for
    // it.
    std::vector<Finding> found = run.feed(damaged(vlt(1, 'R', 102)));
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::Vlt2000ChecksumError);
    EXPECT_EQ(found[0].frame, 3u);
    EXPECT_EQ(found[0].request_frame, 0u);
    EXPECT_EQ(found[0].slave, 1);
    EXPECT_TRUE(found[0].has_stations);
    EXPECT_NE(found[0].message.find("byte 20: checksum"), std::string::npos) << found[0].message;
    EXPECT_EQ(run.station(1)->checksum_errors, 1u);
    EXPECT_EQ(run.station(1)->commands, 1u);
    EXPECT_EQ(run.station(1)->damaged_commands, 1u);
    EXPECT_EQ(run.station(1)->damaged, 1u);
    EXPECT_EQ(run.station(1)->telegrams, 0u);
    EXPECT_TRUE(run.feed(vlt(2, 'R', 102)).empty());

    // A damaged reply from the drive the command went to ends the wait for it.
    found = run.feed(damaged(vlt(2, 'R', 102, 5, 0, {}, "GH@@")));
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::Vlt2000ChecksumError);
    EXPECT_EQ(found[0].request_frame, 4u);
    EXPECT_TRUE(run.feed(vlt(3, 'C', 0)).empty()) << "no vlt2000_no_response for drive 2";
    EXPECT_EQ(run.station(2)->no_responses, 0u);
    EXPECT_EQ(run.station(2)->answered, 0u);
    EXPECT_EQ(run.station(2)->damaged, 1u);
    EXPECT_EQ(run.station(2)->replies, 1u);
    EXPECT_EQ(run.station(2)->damaged_replies, 1u);
    EXPECT_EQ(run.station(2)->checksum_errors, 1u);
    EXPECT_EQ(run.station(2)->findings[at(FindingKind::Vlt2000ChecksumError)], 1u);
}

TEST(Vlt2000TrackerTest, TheReplyToACommandWithAWrongChecksumIsNoFindingOfItsOwn) {
    // The checksum error may be the tap's alone: the drive got the command and replies. The
    // reply is paired with it (no phantom command, no vlt2000_no_response later).
    Vlt2000Run run;
    run.warm_up();
    std::vector<Finding> found = run.feed(damaged(vlt(4, 'R', 102)));
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::Vlt2000ChecksumError);
    EXPECT_TRUE(run.feed(vlt(4, 'R', 102, 5, 0, {}, "GH@@")).empty());
    EXPECT_TRUE(run.feed(vlt(1, 'C', 0)).empty());
    EXPECT_TRUE(run.feed(vlt(1, 'C', 0, 0, 0, {}, "GH@@")).empty());
    EXPECT_TRUE(run.finish(100'000).empty());
    EXPECT_EQ(run.station(4)->commands, 1u);
    EXPECT_EQ(run.station(4)->damaged, 1u);  // its outcome: the command was damaged
    EXPECT_EQ(run.station(4)->answered, 0u);
    EXPECT_EQ(run.station(4)->replies, 1u);
    EXPECT_EQ(run.station(4)->no_responses, 0u);
}

TEST(Vlt2000TrackerTest, ADamagedReplyAfterTheTimeOutStillEndsTheWait) {
    Vlt2000Run run(Vlt2000TrackerOptions{100 * kMs});
    run.warm_up();
    run.feed(vlt(2, 'R', 102), 0);
    std::vector<Finding> found = run.feed(damaged(vlt(2, 'R', 102, 5, 0, {}, "GH@@")), 50);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::Vlt2000ChecksumError);
    EXPECT_TRUE(run.finish(5000).empty());
}

TEST(Vlt2000TrackerTest, ChecksumDisabledIsANoteOncePerAddress) {
    Vlt2000Run run;
    std::vector<Finding> found = run.feed(vlt(1, 'R', 102, 0, 0, "??"));
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::Vlt2000ChecksumDisabled);
    EXPECT_EQ(found[0].severity, Severity::Note);
    EXPECT_EQ(found[0].slave, 1);
    EXPECT_NE(found[0].message.find("the command in frame 1 carries \"??\""), std::string::npos)
        << found[0].message;
    EXPECT_TRUE(run.feed(vlt(1, 'R', 102, 5, 0, "??", "GH@@")).empty());
    EXPECT_TRUE(run.feed(vlt(1, 'R', 102, 0, 0, "??")).empty());
    EXPECT_TRUE(run.feed(vlt(1, 'R', 102, 5, 0, "??", "GH@@")).empty());
    // Drive 2's reply is the first with "??" there.
    run.feed(vlt(2, 'R', 102));
    found = run.feed(vlt(2, 'R', 102, 5, 0, "??", "GH@@"));
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::Vlt2000ChecksumDisabled);
    EXPECT_EQ(found[0].slave, 2);
    EXPECT_NE(found[0].message.find("the reply in frame 6"), std::string::npos) << found[0].message;
    // The telegrams count as usual.
    EXPECT_EQ(run.station(1)->checksum_disabled, 4u);
    EXPECT_EQ(run.station(1)->answered, 2u);
    EXPECT_EQ(run.station(1)->findings[at(FindingKind::Vlt2000ChecksumDisabled)], 1u);
    EXPECT_EQ(run.station(2)->checksum_disabled, 1u);
    EXPECT_EQ(run.station(2)->answered, 1u);
}

TEST(Vlt2000TrackerTest, MalformedTelegramsAreReportedAndOtherwiseIgnored) {
    Vlt2000Run run;
    run.warm_up();
    // Cut short.
    std::vector<Finding> found = run.feed(vlt(1, 'R', 102).substr(0, 15));
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::MalformedTelegram);
    EXPECT_EQ(found[0].slave, 1);
    EXPECT_TRUE(found[0].has_stations);
    EXPECT_NE(found[0].message.find("truncated"), std::string::npos) << found[0].message;
    // An unknown letter.
    found = run.feed(vlt(1, 'X', 102));
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::MalformedTelegram);
    EXPECT_NE(found[0].message.find("vlt2000_letter_unknown"), std::string::npos)
        << found[0].message;
    // A parameter that is no number (the checksum right).
    std::string bad = vlt(1, 'R', 102);
    bad[9] = 'A';
    found = run.feed(with_checksum(bad));
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::MalformedTelegram);
    EXPECT_NE(found[0].message.find("vlt2000_field_invalid: byte 10"), std::string::npos)
        << found[0].message;
    // No address: no station to name, a bus finding.
    std::string no_address = vlt(1, 'R', 102);
    no_address[1] = 'x';
    found = run.feed(with_checksum(no_address));
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].kind, FindingKind::MalformedTelegram);
    EXPECT_FALSE(found[0].has_stations);
    EXPECT_EQ(run.tracker.bus().findings[at(FindingKind::MalformedTelegram)], 1u);
    EXPECT_EQ(run.station(1)->telegrams, 0u);
    EXPECT_EQ(run.station(1)->commands, 3u);  // the three with its address, damaged
    EXPECT_EQ(run.station(1)->damaged, 3u);
    EXPECT_EQ(run.station(1)->findings[at(FindingKind::MalformedTelegram)], 3u);
    // The exchange after them is clean.
    EXPECT_TRUE(run.feed(vlt(1, 'R', 102)).empty());
    EXPECT_TRUE(run.feed(vlt(1, 'R', 102, 5, 0, {}, "GH@@")).empty());
    EXPECT_EQ(run.station(1)->answered, 1u);
}

TEST(Vlt2000TrackerTest, ParametersPerAddressAreBounded) {
    Vlt2000Run run;
    for (int p = 0; p < 300; ++p) {
        run.feed(vlt(1, 'R', 1000 + p));
        run.feed(vlt(1, 'R', 1000 + p, 1, 0, {}, "GH@@"));
    }
    EXPECT_TRUE(run.all.empty()) << run.all[0].message;
    const Vlt2000StationStats* one = run.station(1);
    EXPECT_EQ(one->parameters.size(), Vlt2000StationStats::kMaxParameters);
    EXPECT_EQ(one->parameters_not_counted, 300u - Vlt2000StationStats::kMaxParameters);
    EXPECT_EQ(one->answered, 300u);
}

TEST(Vlt2000TrackerTest, FindingsAreCountedPerAddressKindAndSeverity) {
    Vlt2000Run run;
    run.warm_up();
    run.feed(vlt(1, 'R', 102));
    run.feed(vlt(1, 'U', 102, 1));               // stacked (drive 1)
    run.feed(vlt(2, 'C', 0));                    // no response (drive 1)
    run.feed(vlt(2, 'C', 0, 0, 0, {}, "GH@@"));  // answered
    run.feed(vlt(3, 'R', 5));                    // to drive 3
    run.feed(failed(3, 'R', 5, 2));              // failed (drive 3)
    run.feed(vlt(1, 'x', 0).substr(0, 10));      // malformed (drive 1)
    run.finish();
    const Vlt2000StationStats* one = run.station(1);
    EXPECT_EQ(one->findings[at(FindingKind::Vlt2000StackedRequest)], 1u);
    EXPECT_EQ(one->findings[at(FindingKind::Vlt2000NoResponse)], 1u);
    EXPECT_EQ(one->findings[at(FindingKind::MalformedTelegram)], 1u);
    EXPECT_EQ(run.station(2)->findings, (std::array<std::uint64_t, kFindingKindCount>{}));
    EXPECT_EQ(run.station(3)->findings[at(FindingKind::Vlt2000CommandFailed)], 1u);
    std::uint64_t errors = 0;
    for (const Finding& f : run.all)
        errors += f.severity == Severity::Error;
    EXPECT_EQ(run.tracker.findings(Severity::Error), errors);
    EXPECT_EQ(run.tracker.findings(Severity::Note), 1u);
    EXPECT_EQ(run.tracker.findings(Severity::Error) + run.tracker.findings(Severity::Warning) +
                  run.tracker.findings(Severity::Note),
              run.all.size());
}

TEST(Vlt2000TrackerTest, KindsAreTheVlt2000ComponentsAndMalformedTelegram) {
    std::span<const FindingKind> kinds = vlt2000_finding_kinds();
    ASSERT_EQ(kinds.size(), finding_kinds_of(FindingComponent::Vlt2000Protocol).size() + 1);
    EXPECT_EQ(kinds[0], FindingKind::MalformedTelegram);
    for (std::size_t i = 1; i < kinds.size(); ++i) {
        EXPECT_EQ(finding_component(kinds[i]), FindingComponent::Vlt2000Protocol);
        EXPECT_LT(kinds[i - 1], kinds[i]) << "in enum order";
    }
    for (std::size_t i = 0; i < kFindingKindCount; ++i) {
        const auto kind = static_cast<FindingKind>(i);
        EXPECT_EQ(is_vlt2000_finding_kind(kind),
                  kind == FindingKind::MalformedTelegram ||
                      finding_component(kind) == FindingComponent::Vlt2000Protocol)
            << finding_kind_name(kind);
    }
}

}  // namespace
}  // namespace dpscope

namespace dpscope {
namespace {

// Every command to a drive has one outcome, so the counts add up (#27 point 12): commands =
// broadcasts + answered + unanswered + abandoned + damaged + not judged. Damaged telegrams count
// among the commands and replies (as decode -q counts them), and are the outcome "damaged".
void feed_every_outcome(Vlt2000Run& run) {
    run.feed(vlt(1, 'R', 102, 5, 0, {}, "GH@@"), 0);  // 1: drive 1's reply begins the capture
    run.feed(vlt(2, 'R', 102), 10);                   // 2: answered by 3
    run.feed(vlt(2, 'R', 102, 5, 0, {}, "GH@@"), 14);
    run.feed(vlt(2, 'C', 0), 20);       // 4: unanswered: the master moves on to drive 1
    run.feed(vlt(1, 'R', 103), 30);     // 5: abandoned: a new command to drive 1 before its reply
    run.feed(vlt(1, 'U', 103, 7), 40);  // 6: its reply (7) is damaged
    run.feed(damaged(vlt(1, 'U', 103, 7, 0, {}, "GH@@")), 44);
    run.feed(damaged(vlt(2, 'C', 0)), 50);  // 8: a damaged command
    run.feed(vlt(0, 'C', 0), 60);           // 9: a broadcast
    run.feed(vlt(2, 'R', 104), 70);         // 10: still waiting for its reply when the capture ends
}

void expect_outcomes_add_up(const Vlt2000Run& run) {
    for (const Vlt2000StationStats* s : run.tracker.stations()) {
        SCOPED_TRACE(s->address);
        EXPECT_EQ(s->commands, s->broadcasts + s->answered + s->no_responses + s->abandoned +
                                   s->damaged + s->not_judged + s->open);
        EXPECT_EQ(s->commands, s->commands_outcomes());
    }
}

TEST(Vlt2000TrackerTest, EveryCommandHasOneOutcomeAndTheCountsAddUp) {
    Vlt2000Run run;
    feed_every_outcome(run);
    run.finish();
    expect_outcomes_add_up(run);
    const Vlt2000StationStats* one = run.station(1);
    ASSERT_NE(one, nullptr);
    EXPECT_EQ(one->commands, 3u);
    EXPECT_EQ(one->abandoned, 1u);
    EXPECT_EQ(one->damaged, 1u);
    EXPECT_EQ(one->not_judged, 1u);
    EXPECT_EQ(one->open, 0u);
    EXPECT_EQ(one->answered, 0u);
    EXPECT_EQ(one->replies, 1u);
    EXPECT_EQ(one->damaged_replies, 1u);
    const Vlt2000StationStats* two = run.station(2);
    ASSERT_NE(two, nullptr);
    EXPECT_EQ(two->commands, 4u);
    EXPECT_EQ(two->answered, 1u);
    EXPECT_EQ(two->no_responses, 1u);
    EXPECT_EQ(two->damaged, 1u);
    EXPECT_EQ(two->damaged_commands, 1u);
    EXPECT_EQ(two->not_judged, 0u);
    EXPECT_EQ(two->open, 1u);
    EXPECT_EQ(two->replies, 1u);
    EXPECT_EQ(run.station(0)->commands, 1u);
    EXPECT_EQ(run.station(0)->broadcasts, 1u);

    Vlt2000Run late;
    feed_every_outcome(late);
    late.finish(5000);
    expect_outcomes_add_up(late);
    EXPECT_EQ(late.station(2)->no_responses, 2u);
    EXPECT_EQ(late.station(2)->not_judged, 0u);
    EXPECT_EQ(late.station(2)->open, 0u);
}

}  // namespace
}  // namespace dpscope
