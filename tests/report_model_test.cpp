// The report's model and its per-station seam (formats/report_model.hpp): a section of a new
// channel kind is asked for its part by every format, with nothing in the writers changed.
#include "formats/report_model.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "formats/finding_log.hpp"
#include "formats/summary.hpp"
#include "protocols/profibus/bus_decoder.hpp"
#include "protocols/profibus/session_tracker.hpp"
#include "tests/json_parser.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using report::ReportModel;
using report::StationSection;

// A channel kind the writers have never heard of: each part says which format asked for it.
class FakeSection final : public StationSection {
  public:
    std::uint8_t master() const override { return 1; }
    std::uint8_t slave() const override { return 9; }
    bool checked() const override { return true; }
    std::uint64_t transactions() const override { return 42; }
    const report::FindingCounts& findings() const override { return findings_; }
    bool covers(FindingKind) const override { return true; }
    void write_text(const ReportContext&, TextBuffer& b) const override {
        append(b, "\nFAKE text\n");
    }
    void write_markdown_row(const ReportContext&, TextBuffer& b) const override {
        append(b, "| FAKE row |\n");
    }
    void write_markdown(const ReportContext&, TextBuffer& b) const override {
        append(b, "\n### FAKE block\n");
    }
    void write_json(const ReportContext&, JsonWriter& w) const override {
        w.begin_object().key("fake").boolean(true).end_object();
    }
    void write_html_row(const ReportContext&, TextBuffer& b) const override {
        append(b, "<tr><td>FAKE row</td></tr>\n");
    }
    void write_html(const ReportContext&, TextBuffer& b) const override {
        append(b, "<section>FAKE section</section>\n");
    }
    std::string junit_suite_name() const override { return "FAKE suite"; }
    std::string junit_classname() const override { return "dpscope.fake"; }
    std::string junit_note(FindingKind kind) const override {
        return kind == FindingKind::UnknownCode ? "FAKE note" : "";
    }

  private:
    report::FindingCounts findings_{};
};

// An empty capture: a decoder, tracker, summary and finding log that saw nothing.
struct EmptyCapture {
    BusDecoder decoder;
    SessionTracker tracker;
    Summary summary;
    FindingLog log;

    ReportContext context() const {
        ReportContext c;
        c.input = InputSummary{"empty.pcap", "pcap", 0, false};
        c.summary = &summary;
        c.decoder = &decoder;
        c.tracker = &tracker;
        c.findings = &log;
        c.version = "7.8.9-test";
        return c;
    }
};

template <typename Write>
std::string written(Write write) {
    return test::output_text(write);
}

TEST(ReportModelTest, AnEmptyCaptureChecksNothingAndFailsUnlessAllowed) {
    EmptyCapture capture;
    ReportContext c = capture.context();
    ReportModel m = report::build_report_model(c);
    EXPECT_TRUE(m.stations.empty());
    EXPECT_TRUE(m.nothing_checked);
    EXPECT_TRUE(m.fails);
    EXPECT_EQ(m.shown, 0u);
    c.allow_empty = true;
    EXPECT_FALSE(report::build_report_model(c).fails);
}

TEST(ReportModelTest, EveryFormatAsksANewChannelKindForItsPart) {
    EmptyCapture capture;
    const ReportContext c = capture.context();
    ReportModel m = report::build_report_model(c);
    m.stations.push_back(std::make_unique<FakeSection>());
    m.transactions = 42;
    m.nothing_checked = false;
    m.fails = false;

    std::string text = written([&](Output& out) { report::write_text(c, m, out); });
    EXPECT_NE(text.find("\nFAKE text\n"), std::string::npos) << text;
    EXPECT_NE(text.find("transactions   42"), std::string::npos) << text;

    std::string markdown = written([&](Output& out) { report::write_markdown(c, m, out); });
    EXPECT_NE(markdown.find("| FAKE row |"), std::string::npos) << markdown;
    EXPECT_NE(markdown.find("### FAKE block"), std::string::npos) << markdown;

    std::string html = written([&](Output& out) { report::write_html(c, m, out); });
    EXPECT_NE(html.find("<td>FAKE row</td>"), std::string::npos);
    EXPECT_NE(html.find("FAKE section"), std::string::npos);

    std::string json = written([&](Output& out) { report::write_json(c, m, out); });
    std::optional<test::Json> parsed = test::parse_json(json);
    ASSERT_TRUE(parsed) << json;
    ASSERT_EQ((*parsed)["stations"].items.size(), 1u);
    EXPECT_TRUE((*parsed)["stations"][0]["fake"].boolean);
    EXPECT_EQ((*parsed)["summary"]["transactions"].integer(), 42);

    std::string junit = written([&](Output& out) { report::write_junit(c, m, out); });
    EXPECT_NE(junit.find("<testsuite name=\"FAKE suite\""), std::string::npos) << junit;
    EXPECT_NE(junit.find("classname=\"dpscope.fake\""), std::string::npos);
    EXPECT_NE(junit.find("<system-out>FAKE note</system-out>"), std::string::npos);
}

}  // namespace
}  // namespace dpscope
