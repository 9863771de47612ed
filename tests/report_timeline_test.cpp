// The timelines of the HTML report, built from what the tracker reports at each telegram: its
// findings and the transactions it completed. (Timeline's bins: report_test.cpp.)
#include "formats/report_timeline.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace dpscope {
namespace {

constexpr std::int64_t kMs = 1'000'000;
constexpr std::int64_t kStart = 1'704'067'200'000'000'000;

Finding finding(Severity severity, std::int64_t time_ns, bool has_stations = true,
                std::uint8_t slave = 3) {
    Finding f;
    f.severity = severity;
    f.time_ns = time_ns;
    f.has_stations = has_stations;
    f.master = 2;
    f.slave = slave;
    return f;
}

TEST(ReportTimelineTest, FindingsAndTimedTransactionsGoToTheirChannel) {
    ChannelTimelines timelines;
    std::vector<Finding> at_first = {finding(Severity::Error, kStart),
                                     finding(Severity::Warning, kStart, true, 5)};
    std::vector<CompletedTransaction> answered = {{2, 3, 1, kStart, true}};
    timelines.add(at_first, answered);
    std::vector<CompletedTransaction> later = {{2, 3, 9, kStart + 25 * kMs, true}};
    timelines.add({}, later);

    const Timeline& three = timelines.of(2, 3);
    EXPECT_EQ(three.start_ns(), kStart);
    EXPECT_EQ(three.bins()[0].errors, 1u);
    EXPECT_EQ(three.bins()[0].transactions, 1u);
    EXPECT_EQ(three.bins()[2].transactions, 1u);
    const Timeline& five = timelines.of(2, 5);
    EXPECT_EQ(five.bins()[0].warnings, 1u);
    EXPECT_EQ(five.bins()[0].transactions, 0u);
}

TEST(ReportTimelineTest, UntimedEventsAndBusFindingsAreLeftOut) {
    ChannelTimelines timelines;
    std::vector<Finding> findings = {finding(Severity::Error, kNoTime),
                                     finding(Severity::Error, kStart, false)};
    std::vector<CompletedTransaction> untimed = {{2, 3, 4, kStart, false}};
    timelines.add(findings, untimed);
    EXPECT_TRUE(timelines.of(2, 3).empty());
    EXPECT_TRUE(timelines.of(0, 3).empty());
    EXPECT_TRUE(timelines.of(7, 9).empty());  // a channel never seen
}

}  // namespace
}  // namespace dpscope
