// The filter language (filter/display_filter.hpp, docs/filter.md): parsing (every construct,
// errors naming their column), evaluation on decoded telegrams (any-value semantics, !=, sets
// and ranges, contains, precedence), the shorthands of --station and --pnu, and the field names
// against the Wireshark plugin's and the docs.
#include "filter/display_filter.hpp"

#include <gtest/gtest.h>

#include <regex>
#include <set>
#include <string>
#include <vector>

#include "tests/test_support.hpp"

namespace dpscope {
namespace {

std::string error_of(std::string_view text) {
    Result<DisplayFilter> parsed = DisplayFilter::parse(text);
    return parsed ? "parsed" : parsed.error();
}

// A PROFIBUS Data_Exchange response from slave 5 to master 2 with a PCV.
DecodedTelegram pcv_response(std::uint8_t rc, std::uint16_t pnu, std::uint32_t pva = 0) {
    DecodedTelegram t;
    t.protocol = Protocol::ProfibusDp;
    t.frame = 42;
    t.direction = Direction::Response;
    t.has_roles = true;
    t.master = 2;
    t.slave = 5;
    t.dp.fdl.has_addresses = true;
    t.dp.fdl.sa = 5;
    t.dp.fdl.da = 2;
    t.dp.service = Service::DataExchange;
    t.dp.has_pcv = true;
    t.dp.pcv.rc = rc;
    t.dp.pcv.pnu = pnu;
    t.dp.pcv.pva = pva;
    return t;
}

bool matches(std::string_view text, const FilterInput& in) {
    Result<DisplayFilter> parsed = DisplayFilter::parse(text);
    EXPECT_TRUE(parsed) << text << ": " << parsed.error();
    return parsed && parsed->matches(in);
}

TEST(DisplayFilterTest, ComparesFieldsOfTheTelegram) {
    const DecodedTelegram t = pcv_response(7, 516, 2);
    const FilterInput in{t};
    EXPECT_TRUE(matches("dpscope.pcv.rc == 7", in));
    EXPECT_FALSE(matches("dpscope.pcv.rc == 1", in));
    EXPECT_TRUE(matches("dpscope.pcv.rc != 1", in));
    EXPECT_TRUE(matches("dpscope.pcv.pnu >= 516 && dpscope.pcv.pnu < 517", in));
    EXPECT_TRUE(matches("dpscope.pcv.pnu eq 0x204", in));
    EXPECT_TRUE(matches("dpscope.pcv.error == 2", in));
    EXPECT_TRUE(matches("dpscope.pcv", in));     // present
    EXPECT_FALSE(matches("dpscope.fc.ak", in));  // absent on PROFIBUS
    EXPECT_TRUE(matches("dpscope.bus == \"profibus\" and dpscope.direction == response", in));
    EXPECT_TRUE(matches("dpscope.dp.service == \"Data_Exchange\"", in));
    EXPECT_TRUE(matches("dpscope.dp.service contains \"Exch\"", in));
    EXPECT_TRUE(matches("frame.number == 42", in));
    EXPECT_TRUE(matches("dpscope.fdl.fcs_ok == true", in));
}

TEST(DisplayFilterTest, AnyValueSetsRangesAndNotEqual) {
    const DecodedTelegram t = pcv_response(1, 516);
    const FilterInput in{t};
    // dpscope.station has 2 and 5: == holds for either, != only when none equals.
    EXPECT_TRUE(matches("dpscope.station == 2", in));
    EXPECT_TRUE(matches("dpscope.station == 5", in));
    EXPECT_FALSE(matches("dpscope.station != 5", in));
    EXPECT_TRUE(matches("dpscope.station != 7", in));
    EXPECT_FALSE(matches("dpscope.fc.ak != 7", in));  // no value: != does not hold either
    EXPECT_TRUE(matches("!dpscope.fc.ak", in));
    EXPECT_TRUE(matches("dpscope.pcv.pnu in {515..520}", in));
    EXPECT_TRUE(matches("dpscope.pcv.pnu in {1, 2, 516}", in));
    EXPECT_TRUE(matches("dpscope.pcv.pnu in {1 2 516}", in));
    EXPECT_FALSE(matches("dpscope.pcv.pnu in {517..600 1}", in));
    EXPECT_TRUE(matches("dpscope.bus in {\"fc\" profibus}", in));
}

TEST(DisplayFilterTest, PrecedenceAndParentheses) {
    const DecodedTelegram t = pcv_response(1, 516);
    const FilterInput in{t};
    // && binds tighter than ||; ! tighter than both.
    EXPECT_TRUE(matches("dpscope.pcv.rc == 9 && dpscope.pcv.rc == 8 || dpscope.pcv.rc == 1", in));
    EXPECT_FALSE(
        matches("dpscope.pcv.rc == 9 && (dpscope.pcv.rc == 8 || dpscope.pcv.rc == 1)", in));
    EXPECT_TRUE(matches("!dpscope.pcv.rc == 9 && dpscope.pcv.rc == 1", in));
    EXPECT_FALSE(matches("not (dpscope.pcv.rc == 1 or dpscope.pcv.rc == 2)", in));
    EXPECT_TRUE(matches("((((dpscope.pcv.rc == 1))))", in));
}

TEST(DisplayFilterTest, FindingsProblemsAndHealthEvents) {
    const DecodedTelegram t = pcv_response(1, 516);
    Finding stacked;
    stacked.kind = FindingKind::StackedRequest;
    stacked.severity = Severity::Error;
    stacked.has_stations = true;
    stacked.master = 2;
    stacked.slave = 9;  // about another slave
    stacked.pnu = 1613;
    const Finding findings[] = {stacked};
    const FilterEvent events[] = {{"station_lost", "", 9}, {"verdict_bad", "bad", 255}};
    const FilterInput in{t, findings, -1, events};
    EXPECT_TRUE(matches("dpscope.finding == \"stacked_request\"", in));
    EXPECT_TRUE(matches("dpscope.finding == stacked_request", in));
    EXPECT_TRUE(matches("dpscope.finding.severity == \"error\"", in));
    EXPECT_TRUE(matches("dpscope.finding.pnu == 1613", in));
    EXPECT_TRUE(matches("dpscope.station == 9", in));  // a finding about station 9
    EXPECT_TRUE(matches("health.event == \"station_lost\" && health.station == 9", in));
    EXPECT_TRUE(matches("health.verdict == \"bad\"", in));
    EXPECT_FALSE(matches("dpscope.problem", in));
    const FilterInput bare{t};
    EXPECT_FALSE(matches("dpscope.finding", bare));
    EXPECT_FALSE(matches("dpscope.station == 9", bare));
}

// --station and --pnu as the filter language says them select what they always did (the
// golden cases with --station and --pnu run through these).
TEST(DisplayFilterTest, TheShorthandsOfStationAndPnu) {
    const std::uint8_t stations[] = {3, 5};
    EXPECT_EQ(station_filter_text(stations), "dpscope.station in {3 5}");
    const std::uint16_t pnus[] = {1613};
    EXPECT_EQ(pnu_filter_text(pnus), "dpscope.pnu in {1613} || dpscope.finding.pnu in {1613}");
    EXPECT_EQ(station_filter_text({}), "");
    DecodedTelegram t = pcv_response(7, 0);  // a rejection that leaves the PNU out
    const FilterInput paired{t, {}, 1613};   // the tracker pairs it with its request for 1613
    EXPECT_TRUE(matches(pnu_filter_text(pnus), paired));
    EXPECT_TRUE(matches(station_filter_text(stations), paired));
}

TEST(DisplayFilterTest, ErrorsNameTheirColumn) {
    EXPECT_EQ(error_of(""), "column 1: an empty filter: write a field and a comparison");
    EXPECT_EQ(error_of("dpscope.nope == 1"),
              "column 1: no field 'dpscope.nope' (dpscope filter --fields lists them)");
    EXPECT_EQ(error_of("dpscope.pcv.rc =="),
              "column 18: the expression ends where a value for dpscope.pcv.rc was expected");
    EXPECT_EQ(error_of("dpscope.pcv.rc == x"), "column 19: 'x' is no number for dpscope.pcv.rc");
    EXPECT_EQ(error_of("dpscope.pcv.rc == \"7\""),
              "column 19: dpscope.pcv.rc is a number, not text");
    EXPECT_EQ(error_of("(dpscope.pcv.rc == 7"), "column 1: '(' is not closed");
    EXPECT_EQ(error_of("dpscope.finding == \"abc"), "column 20: a string is not closed");
    EXPECT_EQ(error_of("dpscope.pcv.rc in {1 2"), "column 19: '{' is not closed");
    EXPECT_EQ(error_of("dpscope.pcv.rc in {}"), "column 19: an empty set");
    EXPECT_EQ(error_of("dpscope.pcv.rc in {5..2}"),
              "column 20: the range 5..2 ends before it starts");
    EXPECT_EQ(error_of("dpscope.pcv.rc contains 1"),
              "column 1: 'contains' compares text; dpscope.pcv.rc is a number");
    EXPECT_EQ(error_of("dpscope.pcv.rc == 1 dpscope.pcv.rc == 2"),
              "column 21: 'dpscope.pcv.rc' after a whole expression: join with && or ||");
    EXPECT_EQ(error_of("dpscope.pcv.rc == 1 &&"),
              "column 23: the expression ends where a field was expected");
    EXPECT_EQ(error_of("== 1"),
              "column 1: '==' where a field was expected (a name such as dpscope.pcv.rc)");
    EXPECT_EQ(error_of("dpscope.pcv.rc == 99999999999999999999"),
              "column 19: '99999999999999999999' is no number for dpscope.pcv.rc");
    EXPECT_EQ(error_of(std::string(70, '!') + "dpscope.pcv"),
              "column 65: nested too deep (at most 64 levels)");
}

// Every dpscope.* field is a field of the Wireshark plugin (wireshark/dissector_fields.hpp), so a
// filter written in Wireshark works here, except the few that select as --station and --pnu do.
TEST(DisplayFilterTest, FieldNamesAreTheWiresharkPlugins) {
    const std::string plugin = test::slurp(test::source_dir() + "/wireshark/dissector_fields.hpp");
    ASSERT_FALSE(plugin.empty());
    const std::set<std::string_view> filter_only = {"dpscope.station", "dpscope.pnu",
                                                    "dpscope.finding.pnu"};
    for (std::string_view name : filter_field_names()) {
        if (!name.starts_with("dpscope.") || filter_only.count(name)) continue;
        EXPECT_NE(plugin.find("\"" + std::string(name) + "\""), std::string::npos) << name;
    }
    for (std::string_view name : filter_only)
        EXPECT_EQ(plugin.find("\"" + std::string(name) + "\""), std::string::npos) << name;
}

// docs/filter.md names every field.
TEST(DisplayFilterTest, TheDocsNameEveryField) {
    const std::string docs = test::slurp(test::source_dir() + "/docs/filter.md");
    ASSERT_FALSE(docs.empty());
    for (std::string_view name : filter_field_names())
        EXPECT_NE(docs.find("`" + std::string(name) + "`"), std::string::npos) << name;
}

}  // namespace
}  // namespace dpscope
