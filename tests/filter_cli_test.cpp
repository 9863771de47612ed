// The filter language on the command line (issue 30, docs/filter.md): -Y selects what decode and
// hex show and -q counts; --station and --pnu are its shorthands (the same lines); a bad
// expression is exit 2 naming its column; a health.* field turns the bus-health tracking on;
// `dpscope filter` lists the fields and checks an expression.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tests/json_parser.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::CommandResult;
using test::run_dpscope;

std::string sample(const std::string& name) { return test::source_dir() + "/samples/" + name; }

std::size_t lines(const std::string& text) {
    return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

TEST(FilterCliTest, DisplayFilterSelectsAsTheShorthandsDo) {
    const std::string faults = sample("faults.pcap");
    CommandResult station = run_dpscope({"decode", "--station", "3", faults});
    CommandResult y = run_dpscope({"decode", "-Y", "dpscope.station == 3", faults});
    ASSERT_EQ(station.exit_code, y.exit_code) << y.err;
    EXPECT_EQ(station.out, y.out);
    EXPECT_GT(lines(y.out), 10u);
    CommandResult pnu = run_dpscope({"decode", "--pnu", "516", faults});
    CommandResult ypnu =
        run_dpscope({"decode", "-Y", "dpscope.pnu == 516 || dpscope.finding.pnu == 516", faults});
    EXPECT_EQ(pnu.out, ypnu.out);
    // -Y and a shorthand together: both must hold.
    CommandResult both =
        run_dpscope({"decode", "--station", "3", "-Y", "dpscope.direction == request", faults});
    EXPECT_LT(lines(both.out), lines(station.out));
    EXPECT_GT(lines(both.out), 0u);
}

TEST(FilterCliTest, RejectedRequestsAndFindingsByName) {
    CommandResult r =
        run_dpscope({"decode", "-Y", "dpscope.pcv.rc == 7 && dpscope.direction == response",
                     sample("faults.pcap")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    ASSERT_GT(lines(r.out), 0u);
    std::size_t start = 0;
    while (start < r.out.size()) {
        const std::size_t end = r.out.find('\n', start);
        const std::string line = r.out.substr(start, end - start);
        EXPECT_NE(line.find("RC=7"), std::string::npos) << line;
        start = end + 1;
    }
    CommandResult stacked = run_dpscope(
        {"decode", "-Y", "dpscope.finding == \"stacked_request\"", sample("faults.pcap")});
    EXPECT_NE(stacked.out.find("[error stacked_request]"), std::string::npos) << stacked.out;
    CommandResult quiet =
        run_dpscope({"decode", "-q", "-Y", "dpscope.pcv.rc == 7", sample("faults.pcap")});
    EXPECT_NE(quiet.out.find("telegrams the -Y filter selects"), std::string::npos);
}

TEST(FilterCliTest, HealthEventsAreTrackedForTheFilter) {
    CommandResult lost = run_dpscope(
        {"decode", "-Y", "health.event == \"station_lost\"", sample("bus-health.pcap")});
    ASSERT_EQ(lost.exit_code, 0) << lost.err;
    EXPECT_EQ(lines(lost.out), 1u) << lost.out;
    // Verdicts are judged offline as sniff judges them live (every quarter second of capture
    // time): a verdict turning bad is an event at the telegram where it was judged.
    CommandResult bad =
        run_dpscope({"decode", "-Y", "health.event == \"verdict_bad\"", sample("bus-health.pcap")});
    ASSERT_EQ(bad.exit_code, 0) << bad.err;
    EXPECT_GE(lines(bad.out), 1u) << bad.out;
    CommandResult same =
        run_dpscope({"decode", "-Y", "health.verdict == \"bad\"", sample("bus-health.pcap")});
    EXPECT_EQ(same.out, bad.out);
    // stats -Y selecting every station lists them all, with the same figures.
    CommandResult stats = run_dpscope({"stats", "-T", "json", sample("bus-health.pcap")});
    CommandResult stats_all = run_dpscope(
        {"stats", "-T", "json", "-Y", "dpscope.station in {0..127}", sample("bus-health.pcap")});
    EXPECT_EQ(stats.out.substr(stats.out.find("\"segment\"")),
              stats_all.out.substr(stats_all.out.find("\"segment\"")));
}

TEST(FilterCliTest, ABadExpressionIsAUsageErrorNamingItsColumn) {
    CommandResult r = run_dpscope({"decode", "-Y", "dpscope.pcv.rc ==", sample("faults.pcap")});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err,
              "dpscope: error: -Y 'dpscope.pcv.rc ==': column 18: the expression ends where a "
              "value for dpscope.pcv.rc was expected\n");
    EXPECT_EQ(r.out, "");
    CommandResult unknown = run_dpscope({"hex", "-Y", "pcv.rc == 1", "10 03 02 49 4E 16"});
    EXPECT_EQ(unknown.exit_code, 2);
    EXPECT_NE(unknown.err.find("column 1: no field 'pcv.rc'"), std::string::npos) << unknown.err;
}

TEST(FilterCliTest, FilterListsFieldsAndChecksExpressions) {
    CommandResult fields = run_dpscope({"filter", "--fields"});
    ASSERT_EQ(fields.exit_code, 0) << fields.err;
    EXPECT_NE(fields.out.find("dpscope.pcv.rc"), std::string::npos);
    EXPECT_NE(fields.out.find("health.event"), std::string::npos);
    CommandResult json = run_dpscope({"filter", "--fields", "-T", "json"});
    EXPECT_EQ(json.out.rfind("[{\"name\":", 0), 0u) << json.out.substr(0, 80);
    CommandResult ok = run_dpscope({"filter", "dpscope.fc.ak in {1 2} || !dpscope.pcv"});
    EXPECT_EQ(ok.exit_code, 0);
    EXPECT_EQ(ok.out, "ok\n");
    CommandResult bad = run_dpscope({"filter", "dpscope.fc.ak in {1 2"});
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_NE(bad.err.find("column 18: '{' is not closed"), std::string::npos) << bad.err;
    CommandResult none = run_dpscope({"filter"});
    EXPECT_EQ(none.exit_code, 2);
}

// --trigger offline: decode cuts a capture into the windows around each event, in the folder -w
// names (made if missing), the triggering telegram commented; what is wrong is exit 2.
TEST(FilterCliTest, TriggersCutACaptureIntoItsWindows) {
    const std::string folder = test::temp_path("cuts");
    std::filesystem::remove_all(folder);
    CommandResult r =
        run_dpscope({"decode", "-q", "--trigger", "health.event == \"station_lost\"", "--pre",
                     "0.01", "--post", "0.01", "-w", folder, sample("bus-health.pcap")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("--trigger: 1 window written in " + folder + " (1 telegram fired)"),
              std::string::npos)
        << r.err;
    const std::string file = folder + "/trigger-20240101T000000Z-station_lost-4.pcapng";
    ASSERT_TRUE(std::filesystem::exists(file));
    CommandResult cut = run_dpscope({"decode", file});
    EXPECT_EQ(cut.exit_code, 0) << cut.err;
    EXPECT_GT(lines(cut.out), 10u);
    const std::vector<std::uint8_t> bytes = test::read_file(file);
    EXPECT_NE(std::string(bytes.begin(), bytes.end())
                  .find("dpscope trigger: health.event == \"station_lost\" (frame 213)"),
              std::string::npos);
    std::filesystem::remove_all(folder);

    CommandResult no_folder =
        run_dpscope({"decode", "--trigger", "dpscope.pcv.rc == 7", sample("faults.pcap")});
    EXPECT_EQ(no_folder.exit_code, 2);
    EXPECT_NE(no_folder.err.find("give -w FOLDER"), std::string::npos) << no_folder.err;
    const std::string a_file = test::temp_path("not-a-folder");
    test::write_text_file(a_file, "mine\n");
    CommandResult over_file = run_dpscope(
        {"decode", "--trigger", "dpscope.pcv.rc == 7", "-w", a_file, sample("faults.pcap")});
    EXPECT_EQ(over_file.exit_code, 2);
    EXPECT_NE(over_file.err.find("not a folder"), std::string::npos) << over_file.err;
    const std::vector<std::uint8_t> kept = test::read_file(a_file);
    EXPECT_EQ(std::string(kept.begin(), kept.end()), "mine\n");
    CommandResult bad = run_dpscope(
        {"decode", "--trigger", "dpscope.pcv.rc = 7", "-w", folder, sample("faults.pcap")});
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_NE(bad.err.find("--trigger 'dpscope.pcv.rc = 7': column 16"), std::string::npos)
        << bad.err;
    CommandResult range = run_dpscope({"decode", "--trigger", "dpscope.pcv", "--pre", "4000", "-w",
                                       folder, sample("faults.pcap")});
    EXPECT_EQ(range.exit_code, 2);
    EXPECT_FALSE(std::filesystem::exists(folder));
}

}  // namespace
}  // namespace dpscope

namespace dpscope {
namespace {

// report -Y: every telegram is tracked, the report lists the findings of the selected telegrams
// and judges --fail-on by them.
TEST(FilterCliTest, ReportListsTheFindingsOfTheSelectedTelegrams) {
    const std::string faults = sample("faults.pcap");
    CommandResult all = run_dpscope({"report", "-T", "json", faults});
    CommandResult stacked = run_dpscope(
        {"report", "-T", "json", "-Y", "dpscope.finding == \"stacked_request\"", faults});
    ASSERT_EQ(stacked.exit_code, 1) << stacked.err;  // the stacked request is an error
    EXPECT_NE(stacked.out.find("\"display_filter\":\"dpscope.finding == \\\"stacked_request\\\"\""),
              std::string::npos);
    EXPECT_NE(stacked.out.find("\"summary\":{\"telegrams\":458"), std::string::npos);
    EXPECT_NE(stacked.out.find("\"findings\":{\"error\":1,\"warning\":0,\"note\":0}"),
              std::string::npos)
        << stacked.out.substr(0, 800);
    EXPECT_EQ(all.out.find("display_filter"), std::string::npos);
    // Findings of no selected telegram: nothing listed, the report passes.
    CommandResult none =
        run_dpscope({"report", "-Y", "dpscope.finding == \"response_timeout\"", faults});
    EXPECT_EQ(none.exit_code, 0) << none.out;
    EXPECT_NE(none.out.find("Filter:  -Y dpscope.finding == \"response_timeout\": the findings "
                            "of the telegrams it selects (telegram counts cover the whole "
                            "capture)"),
              std::string::npos)
        << none.out;
    // A bad expression: exit 2, its column named.
    CommandResult bad = run_dpscope({"report", "-Y", "dpscope.station ==", faults});
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_NE(bad.err.find("column 19"), std::string::npos) << bad.err;
}

// stats -Y: the stations and masters of the selected telegrams, with their whole figures; the
// segment stays the capture's.
TEST(FilterCliTest, StatsListTheStationsOfTheSelectedTelegrams) {
    const std::string health = sample("bus-health.pcap");
    CommandResult all = run_dpscope({"stats", "-T", "csv", health});
    CommandResult five = run_dpscope({"stats", "-T", "csv", "-Y", "dpscope.station == 5", health});
    ASSERT_EQ(five.exit_code, all.exit_code) << five.err;
    // Station 5's row and its master's are the same as without the filter; no other station.
    const std::vector<std::string> rows = test::lines_of(five.out);
    std::vector<std::string> from_all;
    for (const std::string& row : test::lines_of(all.out))
        if (std::find(rows.begin(), rows.end(), row) != rows.end()) from_all.push_back(row);
    EXPECT_EQ(from_all.size(), rows.size()) << five.out;
    EXPECT_LT(rows.size(), test::lines_of(all.out).size());
    CommandResult text = run_dpscope({"stats", "-Y", "dpscope.station == 5", health});
    EXPECT_NE(text.out.find("stations of the telegrams the -Y filter selects"), std::string::npos);
    EXPECT_NE(text.out.find("Live list (2 stations)"), std::string::npos) << text.out;
    CommandResult bad = run_dpscope({"stats", "-Y", "no.such.field == 1", health});
    EXPECT_EQ(bad.exit_code, 2);
    // A filter on the verdicts that turn bad: judged every quarter second of capture time, as
    // decode judges them (report and stats judge them so only for -Y). The segment turns bad at
    // frame 659, a poll of station 3 by master 2.
    CommandResult turned_bad =
        run_dpscope({"stats", "-T", "csv", "-Y", "health.event == \"verdict_bad\"", health});
    ASSERT_EQ(turned_bad.exit_code, 1) << turned_bad.err;  // the segment is bad
    const std::vector<std::string> turned_rows = test::lines_of(turned_bad.out);
    ASSERT_EQ(turned_rows.size(), 3u) << turned_bad.out;
    EXPECT_EQ(turned_rows[1].substr(0, 2), "2,");
    EXPECT_EQ(turned_rows[2].substr(0, 2), "3,");
}

// report -Y on the verdicts that turn bad: report judges them every quarter second of capture
// time when a filter reads them, as decode does, and lists the findings of the telegram where
// one turned bad (in this simulated session, frame 2652: a slave silent and an SPM violation;
// without the judging, nothing would be selected).
TEST(FilterCliTest, ReportSelectsTheTelegramWhereAVerdictTurnedBad) {
    CommandResult session =
        run_dpscope({"simulate", "-c", "20000", "--seed", "3", "--fault", "station_lost", "--fault",
                     "request_rejected=0.3", "--fault", "unknown_code=0.3", "--fault",
                     "spm_violation=0.3", "-w", "-"});
    ASSERT_EQ(session.exit_code, 0) << session.err;
    const std::string filter = "health.event == \"verdict_bad\"";
    CommandResult decoded = run_dpscope({"decode", "-T", "csv", "-Y", filter, "-"}, session.out);
    ASSERT_EQ(decoded.exit_code, 0) << decoded.err;
    const std::vector<std::string> rows = test::lines_of(decoded.out);
    ASSERT_EQ(rows.size(), 2u) << decoded.out;  // the heading and the one telegram
    const long long frame = std::stoll(rows[1].substr(0, rows[1].find(',')));
    CommandResult report = run_dpscope({"report", "-T", "json", "-Y", filter, "-"}, session.out);
    const std::optional<test::Json> json = test::parse_json(report.out);
    ASSERT_TRUE(json) << report.out;
    const std::vector<test::Json>& findings = (*json)["findings"].items;
    ASSERT_EQ(findings.size(), 2u) << report.out;  // as decode shows them at that telegram
    for (const test::Json& finding : findings)
        EXPECT_EQ(finding["frame"].integer(), frame);
    EXPECT_EQ(findings[0]["kind"].string(), "fdl_no_response");
    EXPECT_EQ(findings[1]["kind"].string(), "spm_violation");
}

// stats without -Y leaves the parameter channel unjudged (it shows bus health only); with -Y a
// filter on findings still sees them: the response time-out is slave 3's, the spontaneous
// messages slave 4's, so each filter lists its slave and the master.
TEST(FilterCliTest, StatsSelectsByFindings) {
    const std::string timeouts = sample("timeouts.pcap");
    const auto addresses = [](const std::string& csv) {
        std::vector<std::string> first_column;
        for (const std::string& row : test::lines_of(csv))
            first_column.push_back(row.substr(0, row.find(',')));
        return first_column;
    };
    CommandResult timed_out = run_dpscope(
        {"stats", "-T", "csv", "-Y", "dpscope.finding == \"response_timeout\"", timeouts});
    ASSERT_EQ(timed_out.exit_code, 0) << timed_out.err;
    EXPECT_EQ(addresses(timed_out.out), (std::vector<std::string>{"address", "2", "3"}))
        << timed_out.out;
    CommandResult spontaneous = run_dpscope(
        {"stats", "-T", "csv", "-Y", "dpscope.finding contains \"spontaneous\"", timeouts});
    ASSERT_EQ(spontaneous.exit_code, 0) << spontaneous.err;
    EXPECT_EQ(addresses(spontaneous.out), (std::vector<std::string>{"address", "2", "4"}))
        << spontaneous.out;
}

}  // namespace
}  // namespace dpscope
