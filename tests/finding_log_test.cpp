// FindingLog (formats/finding_log.hpp): every finding in capture order, spilled to a file in the
// temporary folder beyond the first few thousand; its counts stay exact whatever happens to the
// spill, and it says what it cannot list.
#include "formats/finding_log.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdlib>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "tests/test_support.hpp"

namespace dpscope {
namespace {

// Finding number `i`: its fields vary with i, so that a round trip through the spill shows.
Finding finding(std::uint64_t i) {
    Finding f;
    f.kind = i % 3 == 0 ? FindingKind::FcsError : FindingKind::StackedRequest;
    f.severity = i % 3 == 0 ? Severity::Error : (i % 3 == 1 ? Severity::Warning : Severity::Note);
    f.frame = i + 1;
    f.request_frame = i;
    f.time_ns = static_cast<std::int64_t>(i) * 1000;
    f.has_stations = i % 5 != 0;
    f.master = f.has_stations ? 2 : 0;
    f.slave = f.has_stations ? static_cast<std::uint8_t>(3 + i % 4) : 0;
    if (i % 2 == 0) f.pnu = static_cast<std::uint16_t>(i % 2000);
    f.message = "finding " + std::to_string(i);
    // Now and then none, and now and then one longer than the log reads back at a time.
    if (i % 11 == 0) f.message.clear();
    if (i % 1000 == 7) f.message.append(70'000, static_cast<char>('a' + i % 26));
    return f;
}

void append(FindingLog& log, std::uint64_t count) {
    for (std::uint64_t i = 0; i < count; ++i) {
        const Finding f = finding(i);
        log.append(std::span<const Finding>(&f, 1));
    }
}

// The tallies of `log` summed by kind and severity, and in all.
struct Sums {
    std::uint64_t all = 0;
    std::uint64_t errors = 0;
    std::uint64_t without_stations = 0;
};

Sums sums_of(const FindingLog& log) {
    Sums sums;
    log.for_each_tally([&](const FindingTally& t) {
        sums.all += t.count;
        if (t.severity == Severity::Error) sums.errors += t.count;
        if (!t.has_stations) sums.without_stations += t.count;
    });
    return sums;
}

constexpr std::uint64_t kMany = 10'000;  // more than the log keeps in memory

// Every field of `f` is that of finding(`i`).
void expect_finding(const Finding& f, std::uint64_t i) {
    const Finding expected = finding(i);
    EXPECT_EQ(f.kind, expected.kind);
    EXPECT_EQ(f.severity, expected.severity);
    EXPECT_EQ(f.frame, expected.frame);
    EXPECT_EQ(f.request_frame, expected.request_frame);
    EXPECT_EQ(f.time_ns, expected.time_ns);
    EXPECT_EQ(f.has_stations, expected.has_stations);
    EXPECT_EQ(f.master, expected.master);
    EXPECT_EQ(f.slave, expected.slave);
    EXPECT_EQ(f.pnu, expected.pnu);
    EXPECT_EQ(f.message, expected.message);
}

TEST(FindingLogTest, SpillsIntoTheFolderGivenAndListsEveryFindingInOrder) {
    FindingLog log(test::temp_folder());
    append(log, kMany);
    EXPECT_EQ(log.size(), kMany);
    std::uint64_t next = 0;
    log.for_each([&](const Finding& f) { expect_finding(f, next++); });
    EXPECT_EQ(next, kMany);
    EXPECT_EQ(log.unlisted(), 0u);
    EXPECT_EQ(log.lost(), "");
    const Sums sums = sums_of(log);
    EXPECT_EQ(sums.all, kMany);
    EXPECT_EQ(sums.errors, (kMany + 2) / 3);
    EXPECT_EQ(sums.without_stations, kMany / 5);
}

// Fewer than it keeps in memory: no spill file, every finding given back as appended.
TEST(FindingLogTest, KeepsAFewFindingsInMemory) {
    FindingLog log(test::temp_folder() + "/no-such-folder");  // never needed
    append(log, 1500);
    std::uint64_t next = 0;
    log.for_each([&](const Finding& f) { expect_finding(f, next++); });
    EXPECT_EQ(next, 1500u);
    EXPECT_EQ(log.unlisted(), 0u);
    EXPECT_EQ(log.lost(), "");
}

TEST(FindingLogTest, CountsStayExactWhenTheSpillFolderCannotBeUsed) {
    const std::string missing = test::temp_folder() + "/no-such-folder";
    FindingLog log(missing);
    append(log, kMany);
    EXPECT_EQ(log.size(), kMany);
    // What it lists is the first findings, in order; the rest is counted and said to be lost.
    std::uint64_t next = 0;
    log.for_each([&](const Finding& f) { EXPECT_EQ(f.frame, finding(next++).frame); });
    EXPECT_EQ(next, 4096u);
    EXPECT_EQ(log.unlisted(), kMany - 4096);
    EXPECT_NE(log.lost().find("cannot make a temporary file in " + missing), std::string::npos)
        << log.lost();
    const Sums sums = sums_of(log);
    EXPECT_EQ(sums.all, kMany);
    EXPECT_EQ(sums.errors, (kMany + 2) / 3);
    EXPECT_EQ(sums.without_stations, kMany / 5);
}

// Each tally counts its kind, severity and stations exactly, whether findings come in runs of
// one key or alternate (the log tries the last finding's tally first).
TEST(FindingLogTest, TalliesCountEachKeyExactlyInRunsAndAlternating) {
    FindingLog log(test::temp_folder());
    std::map<std::tuple<FindingKind, Severity, bool, int, int>, std::uint64_t> expected;
    auto add = [&](FindingKind kind, Severity severity, bool has_stations, std::uint8_t slave,
                   int times) {
        for (int i = 0; i < times; ++i) {
            Finding f;
            f.kind = kind;
            f.severity = severity;
            f.has_stations = has_stations;
            f.master = has_stations ? 2 : 0;
            f.slave = has_stations ? slave : 0;
            log.append(std::span<const Finding>(&f, 1));
            ++expected[{kind, severity, has_stations, f.master, f.slave}];
        }
    };
    add(FindingKind::StackedRequest, Severity::Error, true, 5, 7);
    add(FindingKind::StackedRequest, Severity::Error, true, 6, 1);  // another slave
    add(FindingKind::StackedRequest, Severity::Error, true, 5, 3);  // back to the first
    add(FindingKind::StackedRequest, Severity::Warning, true, 5, 2);
    add(FindingKind::FcsError, Severity::Error, false, 0, 4);
    for (int round = 0; round < 50; ++round) {  // alternating keys
        add(FindingKind::FcsError, Severity::Error, false, 0, 1);
        add(FindingKind::StackedRequest, Severity::Error, true, 5, 1);
    }
    std::map<std::tuple<FindingKind, Severity, bool, int, int>, std::uint64_t> tallied;
    log.for_each_tally([&](const FindingTally& t) {
        tallied[{t.kind, t.severity, t.has_stations, t.master, t.slave}] += t.count;
    });
    EXPECT_EQ(tallied, expected);
    EXPECT_EQ(log.size(), 117u);
}

TEST(FindingLogTest, TheTemporaryFolderIsTmpdir) {
    const char* before = std::getenv("TMPDIR");
    const std::string saved = before ? before : "";
    const std::string missing = test::temp_folder() + "/not-there";
    ::setenv("TMPDIR", missing.c_str(), 1);
    EXPECT_EQ(default_spill_folder(), missing);
    ::setenv("TMPDIR", "", 1);
    EXPECT_EQ(default_spill_folder(), "/tmp");
    if (before)
        ::setenv("TMPDIR", saved.c_str(), 1);
    else
        ::unsetenv("TMPDIR");
}

}  // namespace
}  // namespace dpscope
