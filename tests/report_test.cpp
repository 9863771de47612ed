// The conformance report (formats/report.hpp) in all five formats, fed by the real pipeline
// (BusDecoder, SessionTracker, Summary, FindingLog) over the sample captures and simulated
// sessions; the FindingLog that holds the findings; the Timeline and LogHistogram behind the
// report's charts and latency figures. The JSON report is checked with a strict JSON parser and
// the JUnit and HTML reports with a small XML parser, both written here (the project has no JSON
// or XML library).
#include "formats/report.hpp"

#include <dirent.h>
#include <gtest/gtest.h>
#include <malloc.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "capture/input_format.hpp"
#include "capture/telegram_source.hpp"
#include "core/finding.hpp"
#include "core/log_histogram.hpp"
#include "formats/finding_log.hpp"
#include "formats/report_model.hpp"
#include "formats/report_timeline.hpp"
#include "formats/summary.hpp"
#include "protocols/fc/fc_decoder.hpp"
#include "protocols/fc/fc_tracker.hpp"
#include "protocols/profibus/bus_decoder.hpp"
#include "protocols/profibus/health/bus_health.hpp"
#include "protocols/profibus/health/stats_render.hpp"
#include "protocols/profibus/session_tracker.hpp"
#include "protocols/profibus/telegram_builder.hpp"
#include "protocols/vlt2000/vlt2000_decoder.hpp"
#include "protocols/vlt2000/vlt2000_tracker.hpp"
#include "simulator/simulator.hpp"
#include "tests/health_sample.hpp"
#include "tests/json_parser.hpp"
#include "tests/test_support.hpp"
#include "tests/xml_parser.hpp"

namespace dpscope {
namespace {

using test::Json;
using test::JsonParser;
using test::number_of;
using test::parse_json;

using test::parse_xml;
using test::XmlNode;
using test::XmlParser;

TEST(ReportTest, CheckersAcceptValidAndRejectBrokenDocuments) {
    std::string error;
    auto xml = XmlParser(
                   "<?xml version=\"1.0\"?>\n<a x=\"1 &amp; &quot;2&quot;\"><b/>t&lt;&#39;"
                   "<c y=\"\">u</c></a>\n",
                   false)
                   .parse(error);
    ASSERT_TRUE(xml) << error;
    EXPECT_EQ(xml->attribute("x"), "1 & \"2\"");
    EXPECT_EQ(xml->text, "t<'");
    EXPECT_EQ(xml->inner, "t<'u");
    EXPECT_EQ(xml->children.size(), 2u);
    for (std::string_view broken :
         {"", "<a>", "<a></b>", "<a><b></a></b>", "<a x=1/>", "<a x=\"1\" x=\"2\"/>",
          "<a>&foo;</a>", "<a>&amp</a>", "<a>x < y</a>", "<a/><b/>", "<a x=\"<\"/>", "text<a/>",
          "<a></a>tail", "<a x=\"1\"y=\"2\"/>", "<a>&#0;</a>"}) {
        std::string message;
        EXPECT_FALSE(XmlParser(broken, false).parse(message)) << broken;
    }
    EXPECT_TRUE(XmlParser("<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><style>a>b{}"
                          "</style></head><body>&middot;</body></html>",
                          true)
                    .parse(error))
        << error;
    EXPECT_FALSE(XmlParser("<!DOCTYPE html><html><p></html>", true).parse(error));
    EXPECT_FALSE(XmlParser("<html></html>", true).parse(error));

    EXPECT_TRUE(JsonParser(R"({"a":[1,-2.5e3,true,null,"x\"\u00e9"],"b":{}})").parse(error));
    for (std::string_view broken : {"", "{", R"({"a":1,})", "[1,]", "01", R"({"a":1,"a":2})"}) {
        std::string message;
        EXPECT_FALSE(JsonParser(broken).parse(message)) << broken;
    }
}

// ---- the pipeline ------------------------------------------------------------------------------

// What `dpscope report` builds before rendering (cli/report_command.cpp).
struct Analysis {
    explicit Analysis(TrackerOptions options = {}, DecoderOptions decoder_options = {})
        : decoder(decoder_options), tracker(options) {}

    void feed(Bytes bytes, std::int64_t time_ns, std::uint64_t number) {
        const DecodedTelegram& t = decoder.decode(bytes, time_ns, number);
        std::span<const Finding> found = tracker.track(t);
        summary.add(t);
        summary.add_findings(found);
        timelines.add(found, tracker.completed());
        if (!found.empty()) log.append(found);
    }
    void finish() {
        std::span<const Finding> found = tracker.finish();
        summary.add_findings(found);
        timelines.add(found, {});
        log.append(found);
    }
    const ChannelStats& station(std::uint8_t slave) const {
        for (const ChannelStats* stats : tracker.channels())
            if (stats->slave == slave) return *stats;
        ADD_FAILURE() << "no channel for slave " << int(slave);
        static const ChannelStats none;
        return none;
    }

    BusDecoder decoder;
    SessionTracker tracker;
    Summary summary;
    ChannelTimelines timelines;
    FindingLog log;
    InputSummary input;
};

// `relative` is a path under the source directory, e.g. "samples/faults.pcap".
std::unique_ptr<Analysis> analyse_file(const std::string& relative) {
    auto analysis = std::make_unique<Analysis>();
    OpenResult opened =
        open_source(test::source_dir() + "/" + relative, InputFormat::Auto, profibus_protocol());
    EXPECT_TRUE(opened) << opened.error();
    if (!opened) return analysis;
    TelegramSource& source = *opened.value();
    Record record;
    while (source.next(record))
        analysis->feed(record.bytes, record.time_ns, record.number);
    analysis->finish();
    analysis->input = InputSummary{relative, std::string(input_format_name(source.format())),
                                   source.bytes_skipped(), source.status() == InputStatus::Damaged};
    return analysis;
}

std::unique_ptr<Analysis> analyse_simulation(const SimulatorOptions& options,
                                             DecoderOptions decoder_options = {}) {
    auto analysis = std::make_unique<Analysis>(TrackerOptions{}, decoder_options);
    Simulator simulator(options);
    std::vector<std::uint8_t> bytes;
    std::int64_t time_ns = 0;
    std::uint64_t number = 0;
    while (simulator.next(bytes, time_ns))
        analysis->feed(Bytes(bytes.data(), bytes.size()), time_ns, ++number);
    analysis->finish();
    analysis->input = InputSummary{"simulated.pcap", "pcap", 0, false};
    return analysis;
}

SimulatorOptions one_slave(std::uint8_t address, std::uint8_t ppo, std::uint64_t cycles) {
    SimulatorOptions options;
    options.seed = 5;
    options.cycles = cycles;
    options.slaves = {SimulatedSlave{address, ppo, Dialect::Vlt}};
    return options;
}

ReportContext context_of(const Analysis& a, FailOn fail_on = FailOn::Error,
                         std::vector<std::uint8_t> stations = {}) {
    ReportContext context;
    context.input = a.input;
    context.summary = &a.summary;
    context.decoder = &a.decoder;
    context.tracker = &a.tracker;
    context.timelines = &a.timelines;
    context.findings = &a.log;
    context.fail_on = fail_on;
    context.stations = std::move(stations);
    context.version = "7.8.9-test";
    return context;
}

std::string render(ReportFormat format, const ReportContext& context) {
    return test::output_text([&](Output& out) { render_report(format, context, out); });
}

std::size_t count_of(std::string_view text, std::string_view needle) {
    std::size_t n = 0;
    for (std::size_t at = text.find(needle); at != std::string_view::npos;
         at = text.find(needle, at + needle.size()))
        ++n;
    return n;
}

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::size_t start = 0;
    while (start < text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        lines.push_back(text.substr(start, end - start));
        start = end + 1;
    }
    return lines;
}

bool starts_with(std::string_view text, std::string_view prefix) {
    return text.substr(0, prefix.size()) == prefix;
}

std::string fixed6(double value) {
    char text[64];
    std::snprintf(text, sizeof text, "%.6f", value);
    return text;
}

Finding make_finding(FindingKind kind, std::uint64_t frame, std::uint8_t slave,
                     std::string message) {
    Finding f;
    f.kind = kind;
    f.severity = default_severity(kind);
    f.frame = frame;
    f.time_ns = 1'704'067'200'000'000'000 + static_cast<std::int64_t>(frame) * 1000;
    f.has_stations = true;
    f.master = 2;
    f.slave = slave;
    f.message = std::move(message);
    return f;
}

// The findings of samples/faults.pcap in capture order (slave 0: none can be named).
struct ExpectedFinding {
    std::uint64_t frame;
    std::string_view kind;
    std::string_view severity;
    int slave;
};

const std::vector<ExpectedFinding> kFaultsFindings = {
    {62, "fcs_error", "error", 3},
    {63, "fdl_retry", "note", 3},
    {79, "malformed_telegram", "error", 0},
    {97, "malformed_telegram", "error", 5},
    {98, "fdl_retry", "note", 5},
    {122, "stacked_request", "error", 3},
    {146, "request_rejected", "note", 4},
    {162, "mismatched_response", "error", 5},
    {179, "unknown_code", "warning", 3},
    {180, "config_mismatch", "error", 4},
    {211, "orphan_response", "warning", 5},
    {221, "fdl_no_response", "warning", 3},
    {221, "fdl_retry", "note", 3},
    {275, "unexpected_response_type", "error", 5},
    {306, "spontaneous_message", "note", 3},
    {321, "spm_violation", "warning", 4},
    {336, "no_authority", "warning", 4},
    {352, "fdl_no_response", "warning", 5},
    {352, "fdl_retry", "note", 5},
    {353, "fdl_no_response", "warning", 5},
};

// The kinds of the cyclic channel's section and the bus: all but the DP-V1 and the FC ones.
std::vector<std::string> dp_kind_names() {
    std::vector<std::string> names;
    for (std::size_t i = 0; i < kFindingKindCount; ++i) {
        const FindingComponent component = finding_component(static_cast<FindingKind>(i));
        if (component != FindingComponent::Dpv1ParameterAccess &&
            component != FindingComponent::DeviceDescription &&
            component != FindingComponent::FcProtocol &&
            component != FindingComponent::Vlt2000Protocol)
            names.emplace_back(finding_kind_name(static_cast<FindingKind>(i)));
    }
    return names;
}

std::vector<std::string> dpv1_kind_names() {
    std::vector<std::string> names;
    for (FindingKind kind : finding_kinds_of(FindingComponent::Dpv1ParameterAccess))
        names.emplace_back(finding_kind_name(kind));
    return names;
}

constexpr std::int64_t kT0Sample = 1'704'067'200'000'000'000;  // 2024-01-01T00:00:00Z

const Analysis& faults() {
    static const std::unique_ptr<Analysis> analysis = analyse_file("samples/faults.pcap");
    return *analysis;
}

const Analysis& clean() {
    static const std::unique_ptr<Analysis> analysis = analyse_file("samples/ppo2.pcap");
    return *analysis;
}

// ---- json --------------------------------------------------------------------------------------

std::optional<Json> json_report(const ReportContext& context) {
    std::string text = render(ReportFormat::Json, context);
    EXPECT_FALSE(text.empty());
    EXPECT_TRUE(!text.empty() && text.back() == '\n');
    EXPECT_EQ(count_of(text, "\n"), 1u) << "one line";
    return parse_json(text);
}

const std::vector<std::string> kStationKeys = {
    "master",       "slave",          "ppo_type",      "ppo_source", "dialect",
    "dialect_hint", "ident",          "data_exchange", "cycles",     "requests",
    "transactions", "outcomes",       "timeouts",      "abandoned",  "spontaneous",
    "latency_ms",   "latency_cycles", "parameters",    "rejections", "findings"};

const std::vector<std::string> kFindingKeys = {
    "kind", "severity", "frame", "request_frame", "time", "master", "slave", "pnu", "message"};

TEST(ReportTest, JsonHasTheDocumentedTopLevelSummaryAndStationKeys) {
    auto report = json_report(context_of(faults()));
    ASSERT_TRUE(report);
    EXPECT_EQ(report->keys(),
              (std::vector<std::string>{"dpscope", "input", "options", "result", "nothing_checked",
                                        "summary", "stations", "bus", "findings",
                                        "findings_not_listed"}));
    EXPECT_TRUE((*report)["findings_not_listed"].is_null());
    EXPECT_EQ((*report)["dpscope"].string(), "7.8.9-test");
    EXPECT_EQ((*report)["input"].keys(),
              (std::vector<std::string>{"file", "format", "damaged", "bytes_skipped", "first_time",
                                        "last_time"}));
    EXPECT_EQ((*report)["input"]["file"].string(), "samples/faults.pcap");
    EXPECT_EQ((*report)["input"]["format"].string(), "pcap");
    EXPECT_EQ((*report)["input"]["first_time"].text, "1704067200.000066666");
    EXPECT_EQ((*report)["input"]["last_time"].text, "1704067200.123415968");
    EXPECT_EQ(
        (*report)["options"].keys(),
        (std::vector<std::string>{"timeout_ms", "strict", "fail_on", "allow_empty", "stations"}));
    EXPECT_EQ((*report)["options"]["timeout_ms"].integer(), 1000);
    EXPECT_EQ((*report)["options"]["fail_on"].string(), "error");
    const Json& summary = (*report)["summary"];
    EXPECT_EQ(summary.keys(),
              (std::vector<std::string>{"telegrams", "fcs_errors", "transactions", "findings"}));
    EXPECT_EQ(summary["findings"].keys(), (std::vector<std::string>{"error", "warning", "note"}));
    const Json& stations = (*report)["stations"];
    ASSERT_EQ(stations.type, Json::Type::Array);
    ASSERT_EQ(stations.items.size(), 3u);
    for (const Json& station : stations.items) {
        EXPECT_EQ(station.keys(), kStationKeys);
        EXPECT_EQ(station["findings"].keys(), dp_kind_names());
        EXPECT_EQ(station["latency_ms"].keys(),
                  (std::vector<std::string>{"min", "median", "p95", "max"}));
        EXPECT_EQ(station["latency_cycles"].keys(),
                  (std::vector<std::string>{"min", "median", "p95", "max"}));
    }
    EXPECT_EQ((*report)["bus"]["findings"].keys(), dp_kind_names());
    ASSERT_EQ((*report)["findings"].type, Json::Type::Array);
    for (const Json& finding : (*report)["findings"].items)
        EXPECT_EQ(finding.keys(), kFindingKeys);
}

TEST(ReportTest, JsonValuesOfTheFaultsSample) {
    auto report = json_report(context_of(faults()));
    ASSERT_TRUE(report);
    EXPECT_EQ((*report)["result"].string(), "fail");
    const Json& summary = (*report)["summary"];
    EXPECT_EQ(summary["telegrams"].integer(), 458);
    EXPECT_EQ(summary["fcs_errors"].integer(), 1);
    EXPECT_EQ(summary["transactions"].integer(), 35);
    EXPECT_EQ(summary["findings"]["error"].integer(), 7);
    EXPECT_EQ(summary["findings"]["warning"].integer(), 7);
    EXPECT_EQ(summary["findings"]["note"].integer(), 6);

    const Json& stations = (*report)["stations"];
    ASSERT_EQ(stations.items.size(), 3u);
    const int slaves[] = {3, 4, 5};
    const int ppo[] = {1, 2, 5};
    const int transactions[] = {11, 12, 12};
    for (std::size_t i = 0; i < 3; ++i) {
        const Json& station = stations[i];
        EXPECT_EQ(station["master"].integer(), 2);
        EXPECT_EQ(station["slave"].integer(), slaves[i]);
        EXPECT_EQ(station["ppo_type"].integer(), ppo[i]);
        EXPECT_EQ(station["ppo_source"].string(), "chk_cfg");
        EXPECT_EQ(station["dialect"].string(), "vlt");
        EXPECT_EQ(station["ident"].integer(), 0x0402);
        EXPECT_EQ(station["transactions"].integer(), transactions[i]);
        EXPECT_EQ(station["cycles"].integer(), 60);
    }
    EXPECT_EQ(stations[1]["outcomes"]["rejected"].integer(), 1);
    EXPECT_EQ(stations[1]["outcomes"]["no_authority"].integer(), 1);
    ASSERT_EQ(stations[1]["rejections"].items.size(), 1u);
    EXPECT_EQ(stations[1]["rejections"][0]["pnu"].integer(), 207);
    EXPECT_EQ(stations[1]["rejections"][0]["error"].integer(), 2);
    EXPECT_EQ(stations[1]["rejections"][0]["error_text"].string(), "Upper or lower value passed");
    EXPECT_EQ(stations[1]["rejections"][0]["count"].integer(), 1);
    EXPECT_EQ(stations[2]["outcomes"]["mismatched"].integer(), 1);
    EXPECT_EQ(stations[2]["outcomes"]["unexpected"].integer(), 1);
    EXPECT_EQ(stations[0]["abandoned"].integer(), 0);  // its unanswered request was stacked
    EXPECT_EQ(stations[0]["spontaneous"].integer(), 1);

    const Json& latency = stations[0]["latency_ms"];
    EXPECT_EQ(latency["min"].text, "2.181999");
    EXPECT_EQ(latency["median"].text, "4.227071");
    EXPECT_EQ(latency["p95"].text, "8.201999");
    EXPECT_EQ(latency["max"].text, "8.201999");
    const Json& cycles = stations[0]["latency_cycles"];
    EXPECT_EQ(cycles["min"].integer(), 1);
    EXPECT_EQ(cycles["median"].integer(), 2);
    EXPECT_EQ(cycles["p95"].integer(), 4);
    EXPECT_EQ(cycles["max"].integer(), 4);
    EXPECT_EQ(stations[0]["parameters"].items.size(), 5u);
    EXPECT_EQ(stations[0]["parameters"][0]["pnu"].integer(), 207);
    EXPECT_EQ(stations[0]["parameters"][0]["requests"].integer(), 3);

    const Json& findings = (*report)["findings"];
    ASSERT_EQ(findings.items.size(), kFaultsFindings.size());
    for (std::size_t i = 0; i < findings.items.size(); ++i) {
        const Json& f = findings[i];
        const ExpectedFinding& expected = kFaultsFindings[i];
        SCOPED_TRACE("finding " + std::to_string(i));
        EXPECT_EQ(f["frame"].integer(), static_cast<long long>(expected.frame));
        EXPECT_EQ(f["kind"].string(), expected.kind);
        EXPECT_EQ(f["severity"].string(), expected.severity);
        if (expected.slave == 0) {
            EXPECT_TRUE(f["master"].is_null());
            EXPECT_TRUE(f["slave"].is_null());
        } else {
            EXPECT_EQ(f["master"].integer(), 2);
            EXPECT_EQ(f["slave"].integer(), expected.slave);
        }
        EXPECT_FALSE(f["message"].string().empty());
        EXPECT_EQ(f["time"].type, Json::Type::Number);
    }
    EXPECT_EQ(findings[0]["message"].string(),
              "byte 19: FCS 0x7C wrong, checksum of the data is 0x26");
    EXPECT_TRUE(findings[0]["pnu"].is_null());
    EXPECT_TRUE(findings[0]["request_frame"].is_null());
    EXPECT_EQ(findings[0]["time"].text, "1704067200.011971978");
    EXPECT_EQ(findings[5]["pnu"].integer(), 207);
    EXPECT_EQ(findings[5]["request_frame"].integer(), 115);
    EXPECT_EQ((*report)["bus"]["findings"]["malformed_telegram"].integer(), 1);
}

TEST(ReportTest, JsonCountsAgreeWithTheListedFindings) {
    for (FailOn fail_on : {FailOn::Error, FailOn::Warning, FailOn::Never}) {
        for (std::vector<std::uint8_t> stations : {std::vector<std::uint8_t>{}, {3}, {4, 5}, {9}}) {
            auto report = json_report(context_of(faults(), fail_on, stations));
            ASSERT_TRUE(report);
            std::map<std::string, long long> by_severity;
            std::map<std::pair<long long, std::string>, long long> by_slave_kind;
            long long failing = 0;
            for (const Json& f : (*report)["findings"].items) {
                ++by_severity[f["severity"].string()];
                if (!f["slave"].is_null())
                    ++by_slave_kind[{f["slave"].integer(), f["kind"].string()}];
                Severity severity = f["severity"].string() == "error"     ? Severity::Error
                                    : f["severity"].string() == "warning" ? Severity::Warning
                                                                          : Severity::Note;
                failing += severity_fails(severity, fail_on) ? 1 : 0;
            }
            const Json& counts = (*report)["summary"]["findings"];
            for (const char* severity : {"error", "warning", "note"})
                EXPECT_EQ(counts[severity].integer(), by_severity[severity]) << severity;
            long long transactions = 0;
            for (const Json& station : (*report)["stations"].items) {
                transactions += station["transactions"].integer();
                for (const auto& [kind, count] : station["findings"].members)
                    EXPECT_EQ(count.integer(), (by_slave_kind[{station["slave"].integer(), kind}]))
                        << "slave " << station["slave"].integer() << " " << kind;
            }
            EXPECT_EQ((*report)["summary"]["transactions"].integer(), transactions);
            // Slave 9 is not in the capture: nothing checked, which fails too.
            const bool nothing_checked = stations == std::vector<std::uint8_t>{9};
            EXPECT_EQ((*report)["nothing_checked"].boolean, nothing_checked);
            EXPECT_EQ((*report)["result"].string(),
                      failing > 0 || nothing_checked ? "fail" : "pass");
            EXPECT_EQ((*report)["options"]["fail_on"].string(), fail_on_name(fail_on));
        }
    }
}

TEST(ReportTest, JsonCleanCapturePassesWithoutFindings) {
    auto report = json_report(context_of(clean()));
    ASSERT_TRUE(report);
    EXPECT_EQ((*report)["result"].string(), "pass");
    EXPECT_EQ((*report)["input"]["file"].string(), "samples/ppo2.pcap");
    EXPECT_EQ((*report)["summary"]["telegrams"].integer(), 102);
    EXPECT_EQ((*report)["summary"]["fcs_errors"].integer(), 0);
    EXPECT_EQ((*report)["summary"]["transactions"].integer(), 6);
    for (const char* severity : {"error", "warning", "note"})
        EXPECT_EQ((*report)["summary"]["findings"][severity].integer(), 0);
    EXPECT_TRUE((*report)["findings"].items.empty());
    ASSERT_EQ((*report)["stations"].items.size(), 1u);
    const Json& station = (*report)["stations"][0];
    EXPECT_EQ(station["slave"].integer(), 4);
    EXPECT_EQ(station["ppo_type"].integer(), 2);
    for (const auto& [kind, count] : station["findings"].members)
        EXPECT_EQ(count.integer(), 0);
    for (const auto& [kind, count] : (*report)["bus"]["findings"].members)
        EXPECT_EQ(count.integer(), 0);
    EXPECT_EQ(station["latency_ms"]["min"].text, "2.232000");
    EXPECT_EQ(station["latency_cycles"]["max"].integer(), 2);
}

TEST(ReportTest, JsonLatencyFollowsTheTrackersHistograms) {
    auto report = json_report(context_of(faults()));
    ASSERT_TRUE(report);
    for (const Json& station : (*report)["stations"].items) {
        const ChannelStats& stats =
            faults().station(static_cast<std::uint8_t>(station["slave"].integer()));
        const LogHistogram& ns = stats.latency_ns;
        ASSERT_GT(ns.count(), 0u);
        const Json& ms = station["latency_ms"];
        EXPECT_EQ(ms["min"].text, fixed6(static_cast<double>(ns.min()) / 1e6));
        EXPECT_EQ(ms["median"].text, fixed6(static_cast<double>(ns.percentile(50)) / 1e6));
        EXPECT_EQ(ms["p95"].text, fixed6(static_cast<double>(ns.percentile(95)) / 1e6));
        EXPECT_EQ(ms["max"].text, fixed6(static_cast<double>(ns.max()) / 1e6));
        EXPECT_LE(number_of(ms["min"]), number_of(ms["median"]));
        EXPECT_LE(number_of(ms["median"]), number_of(ms["p95"]));
        EXPECT_LE(number_of(ms["p95"]), number_of(ms["max"]));
        const LogHistogram& cycles = stats.latency_cycles;
        EXPECT_EQ(station["latency_cycles"]["min"].integer(), static_cast<long long>(cycles.min()));
        EXPECT_EQ(station["latency_cycles"]["max"].integer(), static_cast<long long>(cycles.max()));
        EXPECT_EQ(station["transactions"].integer(), static_cast<long long>(ns.count()));
    }
}

TEST(ReportTest, JsonLatencyIsNullForAStationWithoutTransactions) {
    auto analysis = analyse_simulation(one_slave(6, 3, 1));
    ASSERT_EQ(analysis->tracker.transactions(), 0u);
    auto report = json_report(context_of(*analysis));
    ASSERT_TRUE(report);
    ASSERT_EQ((*report)["stations"].items.size(), 1u);
    const Json& station = (*report)["stations"][0];
    EXPECT_EQ(station["slave"].integer(), 6);
    EXPECT_EQ(station["transactions"].integer(), 0);
    EXPECT_TRUE(station["latency_ms"].is_null());
    EXPECT_TRUE(station["latency_cycles"].is_null());
    // PPO 3 has no parameter channel: nothing checked, a failure unless empty is allowed.
    EXPECT_TRUE((*report)["nothing_checked"].boolean);
    EXPECT_EQ((*report)["result"].string(), "fail");
    ReportContext allowed = context_of(*analysis);
    allowed.allow_empty = true;
    auto passed = json_report(allowed);
    ASSERT_TRUE(passed);
    EXPECT_EQ((*passed)["result"].string(), "pass");
    EXPECT_TRUE((*passed)["options"]["allow_empty"].boolean);
}

TEST(ReportTest, JsonStationFilterKeepsTheSlaveAndTheBusFindings) {
    auto report = json_report(context_of(faults(), FailOn::Error, {4}));
    ASSERT_TRUE(report);
    ASSERT_EQ((*report)["stations"].items.size(), 1u);
    EXPECT_EQ((*report)["stations"][0]["slave"].integer(), 4);
    const Json& findings = (*report)["findings"];
    ASSERT_EQ(findings.items.size(), 5u);
    EXPECT_TRUE(findings[0]["slave"].is_null());  // frame 79: garbage, no station
    EXPECT_EQ(findings[0]["frame"].integer(), 79);
    for (std::size_t i = 1; i < findings.items.size(); ++i)
        EXPECT_EQ(findings[i]["slave"].integer(), 4);
    EXPECT_EQ((*report)["summary"]["transactions"].integer(), 12);
    EXPECT_EQ((*report)["summary"]["findings"]["error"].integer(), 2);
    EXPECT_EQ((*report)["summary"]["findings"]["warning"].integer(), 2);
    EXPECT_EQ((*report)["summary"]["findings"]["note"].integer(), 1);
    EXPECT_EQ((*report)["summary"]["telegrams"].integer(), 458);  // the capture, not the slave
}

TEST(ReportTest, JsonMessagesAreEscapedAndRoundTrip) {
    auto analysis = analyse_file("samples/ppo2.pcap");
    std::string message =
        "quote \" backslash \\ tab \t newline \n cr \r bell \x07 esc \x1b "
        "utf8 \xC3\xA9 <&>";
    Finding f = make_finding(FindingKind::OrphanResponse, 7, 4, message);
    f.pnu = 0;
    analysis->log.append(std::span<const Finding>(&f, 1));
    analysis->input.name = "we\"ird\\name.pcap";
    auto report = json_report(context_of(*analysis));
    ASSERT_TRUE(report);
    EXPECT_EQ((*report)["input"]["file"].string(), "we\"ird\\name.pcap");
    ASSERT_EQ((*report)["findings"].items.size(), 1u);
    const Json& finding = (*report)["findings"][0];
    EXPECT_EQ(finding["message"].string(), message);
    EXPECT_EQ(finding["pnu"].integer(), 0);
    EXPECT_EQ(finding["kind"].string(), "orphan_response");
    EXPECT_EQ(finding["severity"].string(), "warning");
    EXPECT_EQ(finding["time"].text, "1704067200.000007000");
    EXPECT_EQ((*report)["result"].string(), "pass");
    EXPECT_EQ((*report)["summary"]["findings"]["warning"].integer(), 1);
}

// ---- junit -------------------------------------------------------------------------------------

std::optional<XmlNode> junit_report(const ReportContext& context) {
    std::string text = render(ReportFormat::Junit, context);
    EXPECT_TRUE(starts_with(text, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"));
    auto root = parse_xml(text);
    EXPECT_TRUE(!root || root->name == "testsuites");
    return root;
}

std::size_t failing_cases(const XmlNode& suite) {
    std::size_t n = 0;
    for (const XmlNode* testcase : suite.elements("testcase"))
        n += testcase->elements("failure").empty() ? 0 : 1;
    return n;
}

TEST(ReportTest, JunitOneSuitePerSlavePlusBusWithSixteenCasesEach) {
    auto root = junit_report(context_of(faults()));
    ASSERT_TRUE(root);
    auto suites = root->elements("testsuite");
    ASSERT_EQ(suites.size(), 4u);
    EXPECT_EQ(suites[0]->attribute("name"), "slave 3 (master 2)");
    EXPECT_EQ(suites[1]->attribute("name"), "slave 4 (master 2)");
    EXPECT_EQ(suites[2]->attribute("name"), "slave 5 (master 2)");
    EXPECT_EQ(suites[3]->attribute("name"), "bus");
    EXPECT_EQ(root->attribute("name"), "dpscope samples/faults.pcap");
    EXPECT_EQ(root->attribute("tests"), "64");
    EXPECT_EQ(root->attribute("failures"), "7");
    EXPECT_EQ(root->attribute("errors"), "0");
    const std::vector<std::string> kinds = dp_kind_names();
    const char* classnames[] = {"dpscope.master_2.slave_3", "dpscope.master_2.slave_4",
                                "dpscope.master_2.slave_5", "dpscope.bus"};
    const char* failures[] = {"2", "1", "3", "1"};
    for (std::size_t s = 0; s < suites.size(); ++s) {
        const XmlNode& suite = *suites[s];
        SCOPED_TRACE(suite.attribute("name"));
        EXPECT_EQ(suite.attribute("tests"), "16");
        EXPECT_EQ(suite.attribute("failures"), failures[s]);
        EXPECT_EQ(suite.attribute("failures"), std::to_string(failing_cases(suite)));
        EXPECT_EQ(suite.attribute("errors"), "0");
        auto cases = suite.elements("testcase");
        ASSERT_EQ(cases.size(), 16u);  // the DP-V1 rules have a suite of their own
        for (std::size_t k = 0; k < cases.size(); ++k) {
            EXPECT_EQ(cases[k]->attribute("classname"), classnames[s]);
            EXPECT_EQ(
                cases[k]->attribute("name"),
                kinds[k] + ": " + std::string(finding_rule_text(static_cast<FindingKind>(k))));
        }
    }
}

TEST(ReportTest, JunitOneFailurePerErrorFinding) {
    auto root = junit_report(context_of(faults()));
    ASSERT_TRUE(root);
    auto failures = root->all("failure");
    std::vector<const ExpectedFinding*> errors;
    for (const ExpectedFinding& f : kFaultsFindings)
        if (f.severity == "error") errors.push_back(&f);
    ASSERT_EQ(failures.size(), errors.size());
    // Failures come per suite, then per kind; each error finding has exactly one.
    for (const ExpectedFinding* expected : errors) {
        std::string prefix = "frame " + std::to_string(expected->frame) + ": ";
        std::size_t matches = 0;
        for (const XmlNode* failure : failures)
            if (failure->attribute("type") == expected->kind &&
                starts_with(failure->attribute("message"), prefix))
                ++matches;
        EXPECT_EQ(matches, 1u) << expected->kind << " at frame " << expected->frame;
    }
    auto suites = root->elements("testsuite");
    ASSERT_EQ(suites.size(), 4u);
    auto slave3 = suites[0]->elements("testcase");
    const XmlNode& stacked = *slave3[static_cast<std::size_t>(FindingKind::StackedRequest)];
    ASSERT_EQ(stacked.elements("failure").size(), 1u);
    EXPECT_EQ(stacked.elements("failure")[0]->text,
              "error stacked_request frame 122 (request frame 115): new request RC 1 (Request "
              "parameter value) PNU 516 while RC 4 (Request description element) PNU 207 from "
              "frame 115 was still unanswered");
    // Findings below the threshold are mentioned, not failed.
    const XmlNode& retry = *slave3[static_cast<std::size_t>(FindingKind::FdlRetry)];
    EXPECT_TRUE(retry.elements("failure").empty());
    ASSERT_EQ(retry.elements("system-out").size(), 1u);
    EXPECT_EQ(retry.elements("system-out")[0]->text, "2 note findings below the failure threshold");
    const XmlNode& bus_malformed =
        *suites[3]->elements("testcase")[static_cast<std::size_t>(FindingKind::MalformedTelegram)];
    ASSERT_EQ(bus_malformed.elements("failure").size(), 1u);
    EXPECT_TRUE(starts_with(bus_malformed.elements("failure")[0]->attribute("message"),
                            "frame 79: bad_start_delimiter"));
}

TEST(ReportTest, JunitFailOnWarningAlsoFailsWarnings) {
    auto root = junit_report(context_of(faults(), FailOn::Warning));
    ASSERT_TRUE(root);
    std::size_t errors_and_warnings = 0;
    for (const ExpectedFinding& f : kFaultsFindings)
        errors_and_warnings += f.severity != "note" ? 1 : 0;
    EXPECT_EQ(root->all("failure").size(), errors_and_warnings);
    EXPECT_EQ(errors_and_warnings, 14u);
    auto suites = root->elements("testsuite");
    ASSERT_EQ(suites.size(), 4u);
    const std::size_t expected[] = {4, 3, 5, 1};
    std::size_t total = 0;
    for (std::size_t s = 0; s < suites.size(); ++s) {
        EXPECT_EQ(failing_cases(*suites[s]), expected[s]) << suites[s]->attribute("name");
        EXPECT_EQ(suites[s]->attribute("failures"), std::to_string(expected[s]));
        total += expected[s];
    }
    EXPECT_EQ(root->attribute("failures"), std::to_string(total));
    // Two fdl_no_response warnings of slave 5 fail one test case twice.
    const XmlNode& no_response =
        *suites[2]->elements("testcase")[static_cast<std::size_t>(FindingKind::FdlNoResponse)];
    EXPECT_EQ(no_response.elements("failure").size(), 2u);
    EXPECT_TRUE(no_response.elements("system-out").empty());
}

TEST(ReportTest, JunitErrorsStayFailuresWhenFailOnIsNever) {
    auto root = junit_report(context_of(faults(), FailOn::Never));
    ASSERT_TRUE(root);
    EXPECT_EQ(root->all("failure").size(), 7u);
    EXPECT_EQ(root->attribute("failures"), "7");
}

TEST(ReportTest, JunitCleanCaptureHasNoFailuresAndNoBusSuite) {
    auto root = junit_report(context_of(clean()));
    ASSERT_TRUE(root);
    auto suites = root->elements("testsuite");
    ASSERT_EQ(suites.size(), 1u);
    EXPECT_EQ(suites[0]->attribute("name"), "slave 4 (master 2)");
    EXPECT_EQ(suites[0]->attribute("failures"), "0");
    EXPECT_EQ(suites[0]->elements("testcase").size(), 16u);
    EXPECT_TRUE(root->all("failure").empty());
    EXPECT_TRUE(root->all("system-out").empty());
    EXPECT_EQ(root->attribute("tests"), "16");
    EXPECT_EQ(root->attribute("failures"), "0");
}

TEST(ReportTest, JunitStationFilterKeepsTheSlaveAndTheBus) {
    auto root = junit_report(context_of(faults(), FailOn::Error, {4}));
    ASSERT_TRUE(root);
    auto suites = root->elements("testsuite");
    ASSERT_EQ(suites.size(), 2u);
    EXPECT_EQ(suites[0]->attribute("name"), "slave 4 (master 2)");
    EXPECT_EQ(suites[1]->attribute("name"), "bus");
    EXPECT_EQ(root->all("failure").size(), 2u);  // config_mismatch and the garbage
    EXPECT_EQ(root->attribute("tests"), "32");
}

// ---- DP-V1 parameter access -------------------------------------------------------------------

// Master 1 and slave 5 talking DP-V1 only (SAP 51), 1 ms apart: a read with one state-conflict
// poll, a two-parameter read answered negatively for PNU 30, and a request written over by the
// next one (dpv1_stacked_request).
const Analysis& dpv1_session() {
    static const std::unique_ptr<Analysis> analysis = [] {
        auto a = std::make_unique<Analysis>();
        std::int64_t time = kT0Sample;
        std::uint64_t number = 0;
        bool fcb = true;
        auto send = [&](std::vector<std::uint8_t> du, bool request) {
            std::vector<std::uint8_t> bytes =
                request
                    ? build_telegram(
                          {5, 1, request_fc(FdlFunction::SrdHigh, fcb, true), 51, 51, Bytes(du)})
                    : build_telegram({1, 5, response_fc(FdlStatus::DataLow), 51, 51, Bytes(du)});
            if (request) fcb = !fcb;
            a->feed(Bytes(bytes.data(), bytes.size()), time, ++number);
            time += 1'000'000;
        };
        auto write = [&](std::vector<std::uint8_t> request) {
            std::vector<std::uint8_t> du{0x5F, 0, 47, static_cast<std::uint8_t>(request.size())};
            du.insert(du.end(), request.begin(), request.end());
            send(du, true);
            send({0x5F, 0, 47, static_cast<std::uint8_t>(request.size())}, false);
        };
        auto read = [&](std::vector<std::uint8_t> response) {
            send({0x5E, 0, 47, 240}, true);
            std::vector<std::uint8_t> du{0x5E, 0, 47, static_cast<std::uint8_t>(response.size())};
            du.insert(du.end(), response.begin(), response.end());
            send(du, false);
        };
        write({1, 0x01, 0, 1, 0x10, 0, 0, 12, 0, 0});
        send({0x5E, 0, 47, 240}, true);
        send({0xDE, 0x80, 0xB5, 0x00}, false);  // not ready: a poll
        read({1, 0x01, 0, 1, 0x42, 0x01, 0x00, 0x03});
        write({2, 0x01, 0, 2, 0x10, 0, 0, 20, 0, 0, 0x10, 0, 0, 30, 0, 0});
        read({2, 0x81, 0, 2, 0x06, 0x01, 0x00, 0x07, 0x44, 0x01, 0x00, 0x00});
        write({3, 0x01, 0, 1, 0x10, 0, 0, 40, 0, 0});
        write({4, 0x01, 0, 1, 0x10, 0, 0, 41, 0, 0});
        read({4, 0x01, 0, 1, 0x06, 0x01, 0x00, 0x09});
        a->finish();
        a->input = InputSummary{"dpv1.pcap", "pcap", 0, false};
        return a;
    }();
    return *analysis;
}

TEST(ReportTest, Dpv1SectionInText) {
    std::string text = render(ReportFormat::Text, context_of(dpv1_session()));
    EXPECT_NE(text.find("\nSlave 5 (master 1): DP-V1 parameter access\n"
                        "  DP-V1          16 telegrams\n"
                        "  transactions   4 started, 3 completed, 0 refused, 1 abandoned, 0 timed "
                        "out\n"
                        "  latency ms     min 3.000  mean "),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("  polls          1 state-conflict poll, at most 1 in one transaction\n"
                        "  parameters     12 (1 read), 20 (1 read), 30 (1 read), 40 (1 read), 41 "
                        "(1 read)\n"
                        "  negative       1: error 0x00 (illegal or unknown parameter number) 1x\n"
                        "  error PDUs     0\n"
                        "  findings       dpv1_stacked_request 1, dpv1_negative_response 1\n"),
              std::string::npos)
        << text;
    EXPECT_EQ(text.find("Slave 5 (master 1)\n"), std::string::npos) << "no cyclic section";
    EXPECT_NE(text.find("  transactions   3\n"), std::string::npos);
    EXPECT_NE(text.find("Result:  FAIL: 1 error, 0 warnings, 1 note"), std::string::npos) << text;
}

TEST(ReportTest, Dpv1SectionInJson) {
    auto report = json_report(context_of(dpv1_session()));
    ASSERT_TRUE(report);
    EXPECT_FALSE((*report)["nothing_checked"].boolean);
    EXPECT_EQ((*report)["summary"]["transactions"].integer(), 3);
    const Json& stations = (*report)["stations"];
    ASSERT_EQ(stations.items.size(), 1u);
    const Json& s = stations[0];
    EXPECT_EQ(s.keys(), (std::vector<std::string>{"master",
                                                  "slave",
                                                  "channel",
                                                  "dialect",
                                                  "telegrams",
                                                  "transactions",
                                                  "started",
                                                  "completed",
                                                  "refused",
                                                  "abandoned",
                                                  "timeouts",
                                                  "late",
                                                  "open",
                                                  "polls",
                                                  "max_polls",
                                                  "latency_ms",
                                                  "parameters",
                                                  "parameters_not_counted",
                                                  "negative_responses",
                                                  "negative_errors",
                                                  "negative_errors_not_listed",
                                                  "error_pdus",
                                                  "findings"}));
    EXPECT_EQ(s["channel"].string(), "dpv1");
    EXPECT_EQ(s["slave"].integer(), 5);
    EXPECT_EQ(s["started"].integer(), 4);
    EXPECT_EQ(s["abandoned"].integer(), 1);
    EXPECT_EQ(s["timeouts"].integer(), 0);
    EXPECT_EQ(s["polls"].integer(), 1);
    EXPECT_EQ(s["latency_ms"].keys(), (std::vector<std::string>{"min", "mean", "p95", "max"}));
    EXPECT_EQ(s["latency_ms"]["min"].text, "3.000000");
    EXPECT_EQ(s["latency_ms"]["max"].text, "5.000000");
    ASSERT_EQ(s["parameters"].items.size(), 5u);
    EXPECT_EQ(s["parameters"][0]["pnu"].integer(), 12);
    EXPECT_EQ(s["parameters"][0]["reads"].integer(), 1);
    EXPECT_EQ(s["parameters"][0]["writes"].integer(), 0);
    ASSERT_EQ(s["negative_errors"].items.size(), 1u);
    EXPECT_EQ(s["negative_errors"][0]["error_text"].string(),
              "illegal or unknown parameter number");
    EXPECT_EQ(s["findings"].keys(), dpv1_kind_names());
    EXPECT_EQ(s["findings"]["dpv1_stacked_request"].integer(), 1);
    EXPECT_EQ(s["findings"]["dpv1_negative_response"].integer(), 1);
}

// The findings table's kind column holds the longest kind name in the catalogue.
TEST(ReportTest, FindingsTableKindColumnHoldsTheLongestKindName) {
    EXPECT_EQ(longest_finding_kind_name(),
              std::string_view("dpv1_parameter_count_mismatch").size());
    std::string text = render(ReportFormat::Text, context_of(dpv1_session()));
    std::size_t header = text.find("severity kind ");
    ASSERT_NE(header, std::string::npos) << text;
    std::size_t kind = header + std::string_view("severity ").size();
    std::size_t station = text.find("master/slave", header);
    ASSERT_NE(station, std::string::npos);
    EXPECT_EQ(station - kind, longest_finding_kind_name() + 1) << text;
}

// The transactions line accounts for every one started: late answers among the time-outs, and
// those still open at the end of the capture; error numbers beyond the listed ones are counted.
TEST(ReportTest, Dpv1SectionNamesLateOpenAndUnlistedErrors) {
    ChannelStats stats;
    stats.master = 1;
    stats.slave = 5;
    Dpv1Stats& s = stats.dpv1;
    s.telegrams = 20;
    s.first_time_ns = kT0Sample;
    s.started = 6;
    s.completed = 2;
    s.refused = 1;
    s.timeouts = 2;
    s.late = 1;
    s.open = 1;
    s.negative_responses = 4;
    s.negative_errors = {{2, 3}};
    s.negative_errors_not_listed = 1;
    auto section = report::make_dpv1_section(stats);
    const ReportContext c = context_of(dpv1_session());
    TextBuffer text;
    section->write_text(c, text);
    std::string out = fmt::to_string(text);
    EXPECT_NE(out.find("  transactions   6 started, 2 completed, 1 refused, 0 abandoned, 2 timed "
                       "out (1 answered late), 1 open at end of capture\n"),
              std::string::npos)
        << out;
    EXPECT_NE(out.find("3x; 1 block with further error numbers not listed (at most 256 listed)\n"),
              std::string::npos)
        << out;
    TextBuffer markdown;
    section->write_markdown(c, markdown);
    EXPECT_NE(fmt::to_string(markdown).find("1 open at end of capture"), std::string::npos);
    TextBuffer html;
    section->write_html(c, html);
    EXPECT_NE(fmt::to_string(html).find("1 block with further error numbers not listed."),
              std::string::npos)
        << fmt::to_string(html);
}

TEST(ReportTest, Dpv1SectionInMarkdownAndHtml) {
    const ReportContext c = context_of(dpv1_session());
    std::string markdown = render(ReportFormat::Markdown, c);
    EXPECT_NE(markdown.find("| 5 | 1 | DP-V1 | vlt | 3 | 1 | 0 | 3.000 / "), std::string::npos)
        << markdown;
    EXPECT_NE(markdown.find("### Slave 5 (master 1): DP-V1 parameter access"), std::string::npos);
    EXPECT_NE(markdown.find("- Error 0x00 (illegal or unknown parameter number), 1x"),
              std::string::npos);
    std::string html = render(ReportFormat::Html, c);
    EXPECT_NE(html.find("<section class=\"station\" id=\"slave-5-1-dpv1\">"), std::string::npos);
    EXPECT_NE(html.find("<a href=\"#slave-5-1-dpv1\">5</a>"), std::string::npos);
    EXPECT_NE(html.find("<td>illegal or unknown parameter number</td>"), std::string::npos);
    EXPECT_NE(html.find("<div class=\"n\">1</div><div class=\"l\">slaves</div>"),
              std::string::npos);
}

TEST(ReportTest, HtmlCountsEachFindingWithTheSeverityItHad) {
    // Two error PDUs to Writes: an application-class one (a warning) and an access-class one
    // (a note). The kinds table and the slave's row show what each was, not the kind's default.
    Analysis a;
    std::int64_t time = kT0Sample;
    std::uint64_t number = 0;
    bool fcb = true;
    auto send = [&](std::vector<std::uint8_t> du, bool request) {
        std::vector<std::uint8_t> bytes =
            request ? build_telegram(
                          {5, 1, request_fc(FdlFunction::SrdHigh, fcb, true), 51, 51, Bytes(du)})
                    : build_telegram({1, 5, response_fc(FdlStatus::DataLow), 51, 51, Bytes(du)});
        if (request) fcb = !fcb;
        a.feed(Bytes(bytes.data(), bytes.size()), time, ++number);
        time += 1'000'000;
    };
    for (std::uint8_t code : {std::uint8_t{0xA1}, std::uint8_t{0xB0}}) {
        send({0x5F, 0, 47, 10, code, 0x01, 0, 1, 0x10, 0, 0, 12, 0, 0}, true);
        send({0xDF, 0x80, code, 0x00}, false);
    }
    a.finish();
    a.input = InputSummary{"dpv1.pcap", "pcap", 0, false};
    std::string html = render(ReportFormat::Html, context_of(a));
    EXPECT_NE(html.find("<tr class=\"warning\"><td>dpv1_error_pdu</td><td class=\"warning\">"
                        "warning</td><td class=\"n\">1</td></tr>"),
              std::string::npos)
        << html;
    EXPECT_NE(html.find("<tr class=\"note\"><td>dpv1_error_pdu</td><td class=\"note\">"
                        "note</td><td class=\"n\">1</td></tr>"),
              std::string::npos)
        << html;
    EXPECT_NE(html.find("<td class=\"n error\">0</td><td class=\"n warning\">1</td><td "
                        "class=\"n note\">1</td></tr>"),
              std::string::npos)
        << html;
}

TEST(ReportTest, JunitDpv1SuiteHasACasePerDpv1Rule) {
    auto root = junit_report(context_of(dpv1_session()));
    ASSERT_TRUE(root);
    auto suites = root->elements("testsuite");
    ASSERT_EQ(suites.size(), 1u);
    const XmlNode& suite = *suites[0];
    EXPECT_EQ(suite.attribute("name"), "slave 5 (master 1) DP-V1");
    EXPECT_EQ(suite.attribute("tests"), "10");
    EXPECT_EQ(suite.attribute("failures"), "1");
    EXPECT_EQ(root->attribute("tests"), "10");
    auto cases = suite.elements("testcase");
    const std::vector<std::string> kinds = dpv1_kind_names();
    ASSERT_EQ(cases.size(), kinds.size());
    for (std::size_t k = 0; k < cases.size(); ++k) {
        EXPECT_EQ(cases[k]->attribute("classname"), "dpscope.master_1.slave_5.dpv1");
        EXPECT_TRUE(starts_with(cases[k]->attribute("name"), kinds[k] + ": "));
    }
    ASSERT_EQ(cases[0]->elements("failure").size(), 1u);  // dpv1_stacked_request
    EXPECT_EQ(cases[0]->elements("failure")[0]->attribute("type"), "dpv1_stacked_request");
    // The negative response is a note: mentioned, not failed.
    ASSERT_EQ(cases[6]->elements("system-out").size(), 1u);
    EXPECT_EQ(cases[6]->elements("system-out")[0]->text,
              "1 note finding below the failure threshold");
}

TEST(ReportTest, JunitEscapesMarkupInMessagesAndNames) {
    auto analysis = analyse_file("samples/ppo2.pcap");
    const std::string message = "a<b>&\"c\" 'd' </failure>";
    Finding f = make_finding(FindingKind::StackedRequest, 7, 4, message);
    analysis->log.append(std::span<const Finding>(&f, 1));
    analysis->input.name = "x<&\">.pcap";
    std::string text = render(ReportFormat::Junit, context_of(*analysis));
    EXPECT_NE(text.find("a&lt;b&gt;&amp;&quot;c&quot;"), std::string::npos) << text;
    EXPECT_EQ(text.find("a<b>"), std::string::npos);
    EXPECT_EQ(text.find("x<&"), std::string::npos);
    auto root = parse_xml(text);
    ASSERT_TRUE(root);
    EXPECT_EQ(root->attribute("name"), "dpscope x<&\">.pcap");
    auto failures = root->all("failure");
    ASSERT_EQ(failures.size(), 1u);
    EXPECT_EQ(failures[0]->attribute("message"), "frame 7: " + message);
    EXPECT_EQ(failures[0]->text, "error stacked_request frame 7: " + message);
}

// ---- text and markdown -------------------------------------------------------------------------

// The lines after the first line starting with `heading`.
std::vector<std::string> lines_after(const std::vector<std::string>& lines,
                                     std::string_view heading) {
    for (std::size_t i = 0; i < lines.size(); ++i)
        if (starts_with(lines[i], heading))
            return std::vector<std::string>(lines.begin() + static_cast<std::ptrdiff_t>(i) + 1,
                                            lines.end());
    ADD_FAILURE() << "no line starting with " << heading;
    return {};
}

TEST(ReportTest, TextHasTheSectionsAndOneLinePerFinding) {
    std::string text = render(ReportFormat::Text, context_of(faults()));
    std::vector<std::string> lines = lines_of(text);
    ASSERT_GT(lines.size(), 10u);
    EXPECT_EQ(lines[0], "dpscope 7.8.9-test conformance report");
    EXPECT_EQ(lines[1],
              "Input:   samples/faults.pcap (pcap), 458 telegrams, "
              "2024-01-01T00:00:00.000066666Z to 2024-01-01T00:00:00.123415968Z");
    EXPECT_EQ(lines[2], "Checks:  time-out 1000 ms; RC 8 after a read is unusual, a warning");
    EXPECT_EQ(lines[3], "Result:  FAIL: 7 errors, 7 warnings, 6 notes (fail on error)");
    for (std::string_view line :
         {"Summary", "  telegrams      458", "  FCS errors     1", "  transactions   35",
          "  findings       7 errors, 7 warnings, 6 notes", "Slave 3 (master 2)",
          "Slave 4 (master 2)", "Slave 5 (master 2)",
          "  latency ms     min 2.182  median 4.227  p95 8.202  max 8.202",
          "  latency cycles min 1  median 2  p95 4  max 4",
          "  rejections     PNU 207 error 2 (Upper or lower value passed) 1x",
          "Bus (telegrams no station can be named for)", "  findings       malformed_telegram 1",
          "Findings (20, in capture order)"})
        EXPECT_EQ(std::count(lines.begin(), lines.end(), std::string(line)), 1) << line;
    std::vector<std::string> rows = lines_after(lines, "Findings (");
    ASSERT_EQ(rows.size(), kFaultsFindings.size() + 1);  // the column heads, then the findings
    EXPECT_EQ(rows[0],
              "     frame      time (s)  severity kind                          "
              "master/slave   pnu  message");
    for (std::size_t i = 0; i < kFaultsFindings.size(); ++i) {
        const ExpectedFinding& f = kFaultsFindings[i];
        char start[128];
        std::snprintf(start, sizeof start, "  %8llu  ", static_cast<unsigned long long>(f.frame));
        const std::string& row = rows[i + 1];
        EXPECT_TRUE(starts_with(row, start)) << row;
        EXPECT_NE(row.find(std::string(" ") + std::string(f.severity) + " "), std::string::npos)
            << row;
        EXPECT_NE(row.find(std::string(f.kind) + " "), std::string::npos) << row;
        std::string station = f.slave ? "2 / " + std::to_string(f.slave) : "-   ";
        EXPECT_NE(row.find(station), std::string::npos) << row;
    }
    EXPECT_EQ(rows[1],
              "        62      0.011905  error    fcs_error                     2 / 3      "
              "      -  byte 19: FCS 0x7C wrong, checksum of the data is 0x26");
}

TEST(ReportTest, TextCleanCapturePassesAndListsNoFindings) {
    std::string text = render(ReportFormat::Text, context_of(clean()));
    std::vector<std::string> lines = lines_of(text);
    EXPECT_NE(std::find(lines.begin(), lines.end(),
                        "Result:  PASS: 0 errors, 0 warnings, 0 notes (fail on error)"),
              lines.end());
    ASSERT_FALSE(lines.empty());
    EXPECT_EQ(lines.back(), "Findings (0, in capture order)");
    EXPECT_EQ(count_of(text, "Slave "), 1u);
    EXPECT_EQ(text.find("Bus ("), std::string::npos);
    EXPECT_NE(text.find("  findings       none\n"), std::string::npos);
}

TEST(ReportTest, TextStationFilterHidesOtherSlavesAndTheirFindings) {
    std::string text = render(ReportFormat::Text, context_of(faults(), FailOn::Warning, {4}));
    EXPECT_NE(text.find("Slave 4 (master 2)"), std::string::npos);
    EXPECT_EQ(text.find("Slave 3"), std::string::npos);
    EXPECT_EQ(text.find("Slave 5"), std::string::npos);
    EXPECT_EQ(text.find("2 / 3"), std::string::npos);
    EXPECT_EQ(text.find("2 / 5"), std::string::npos);
    EXPECT_NE(text.find("Result:  FAIL: 2 errors, 2 warnings, 1 note (fail on warning)\n"),
              std::string::npos);
    std::vector<std::string> rows = lines_after(lines_of(text), "Findings (5, in capture order)");
    ASSERT_EQ(rows.size(), 6u);
    EXPECT_EQ(count_of(text, "  2 / 4  "), 4u);
}

TEST(ReportTest, TextWithStationsNotInTheCaptureShowsOnlyBusFindings) {
    std::string text = render(ReportFormat::Text, context_of(faults(), FailOn::Error, {9}));
    EXPECT_EQ(text.find("Slave "), std::string::npos);
    EXPECT_NE(text.find("Findings (1, in capture order)"), std::string::npos);
    EXPECT_NE(text.find("Result:  FAIL: nothing checked (no Data_Exchange telegram with a "
                        "parameter channel from the selected slaves); 1 error, 0 warnings, 0 "
                        "notes (fail on error)"),
              std::string::npos);
}

// Cells of a markdown table row: split at '|' not preceded by a backslash.
std::vector<std::string> markdown_cells(const std::string& row) {
    std::vector<std::string> cells;
    std::string cell;
    bool first = true;
    for (std::size_t i = 0; i < row.size(); ++i) {
        if (row[i] == '\\' && i + 1 < row.size()) {
            cell += row[i];
            cell += row[++i];
            continue;
        }
        if (row[i] == '|') {
            if (!first) cells.push_back(cell);
            first = false;
            cell.clear();
            continue;
        }
        cell += row[i];
    }
    for (std::string& c : cells) {
        std::size_t from = c.find_first_not_of(' ');
        std::size_t to = c.find_last_not_of(' ');
        c = from == std::string::npos ? std::string() : c.substr(from, to - from + 1);
    }
    return cells;
}

std::vector<std::string> markdown_findings_rows(const std::string& text, std::size_t shown) {
    std::vector<std::string> rows =
        lines_after(lines_of(text), "## Findings (" + std::to_string(shown) + ")");
    // An empty line, the header, the alignment row, then the findings.
    if (rows.size() < 3) return {};
    EXPECT_EQ(rows[0], "");
    EXPECT_EQ(rows[1], "| frame | time (s) | severity | kind | master / slave | PNU | message |");
    EXPECT_EQ(rows[2], "|---:|---:|---|---|---|---:|---|");
    return std::vector<std::string>(rows.begin() + 3, rows.end());
}

TEST(ReportTest, MarkdownHasTheSectionsAndOneRowPerFinding) {
    std::string text = render(ReportFormat::Markdown, context_of(faults()));
    std::vector<std::string> lines = lines_of(text);
    ASSERT_FALSE(lines.empty());
    EXPECT_EQ(lines[0], "# dpscope conformance report");
    for (std::string_view line :
         {"**FAIL: 7 errors, 7 warnings, 6 notes (fail on error)**",
          "- Input: `samples/faults.pcap` (pcap), 458 telegrams", "## Summary",
          "| 458 | 0 | 1 | 35 | 7 | 7 | 6 |", "## Slaves", "### Slave 3 (master 2)",
          "### Slave 4 (master 2)", "### Slave 5 (master 2)", "## Findings (20)",
          "- Rejected: PNU 207 error 2 (Upper or lower value passed), 1x", "- dpscope 7.8.9-test"})
        EXPECT_EQ(std::count(lines.begin(), lines.end(), std::string(line)), 1) << line;
    // One row per slave in the slaves table, ten cells each.
    std::vector<std::string> slaves = lines_after(lines, "## Slaves");
    ASSERT_GE(slaves.size(), 6u);
    for (std::size_t i = 3; i < 6; ++i) {
        auto cells = markdown_cells(slaves[i]);
        ASSERT_EQ(cells.size(), 10u) << slaves[i];
        EXPECT_EQ(cells[0], std::to_string(3 + (i - 3)));
        EXPECT_EQ(cells[1], "2");
    }
    EXPECT_EQ(slaves[6], "");
    std::vector<std::string> rows = markdown_findings_rows(text, 20);
    ASSERT_EQ(rows.size(), kFaultsFindings.size());
    for (std::size_t i = 0; i < rows.size(); ++i) {
        auto cells = markdown_cells(rows[i]);
        ASSERT_EQ(cells.size(), 7u) << rows[i];
        const ExpectedFinding& f = kFaultsFindings[i];
        EXPECT_EQ(cells[0], std::to_string(f.frame));
        EXPECT_EQ(cells[2], f.severity);
        std::string kind;
        for (char c : f.kind) {
            if (c == '_') kind += '\\';
            kind += c;
        }
        EXPECT_EQ(cells[3], kind);
        EXPECT_EQ(cells[4], f.slave ? "2 / " + std::to_string(f.slave) : "-");
    }
    EXPECT_EQ(rows[0],
              "| 62 | 0.011905 | error | fcs\\_error | 2 / 3 | - | byte 19: FCS 0x7C "
              "wrong, checksum of the data is 0x26 |");
}

TEST(ReportTest, MarkdownCleanCaptureHasNoFindingsTable) {
    std::string text = render(ReportFormat::Markdown, context_of(clean()));
    EXPECT_NE(text.find("**PASS: 0 errors, 0 warnings, 0 notes (fail on error)**"),
              std::string::npos);
    EXPECT_TRUE(text.size() >= 18 && text.substr(text.size() - 18) == "\n## Findings (0)\n\n")
        << text;
    EXPECT_EQ(text.find("| frame |"), std::string::npos);
}

TEST(ReportTest, MarkdownStationFilterHidesOtherSlavesAndTheirFindings) {
    std::string text = render(ReportFormat::Markdown, context_of(faults(), FailOn::Error, {3, 5}));
    EXPECT_NE(text.find("### Slave 3 (master 2)"), std::string::npos);
    EXPECT_NE(text.find("### Slave 5 (master 2)"), std::string::npos);
    EXPECT_EQ(text.find("Slave 4"), std::string::npos);
    EXPECT_EQ(text.find("| 2 / 4 |"), std::string::npos);
    EXPECT_NE(text.find("| 2 / 5 |"), std::string::npos);
    std::size_t expected = 0;
    for (const ExpectedFinding& f : kFaultsFindings)
        expected += f.slave != 4 ? 1 : 0;
    EXPECT_EQ(expected, 16u);  // slaves 3 and 5 and the garbage
    EXPECT_EQ(markdown_findings_rows(text, expected).size(), expected);
}

TEST(ReportTest, MarkdownEscapesTableAndEmphasisCharactersInMessages) {
    auto analysis = analyse_file("samples/ppo2.pcap");
    Finding f = make_finding(FindingKind::UnknownCode, 7, 4, "a|b *c* _d_ `e` <f>");
    analysis->log.append(std::span<const Finding>(&f, 1));
    std::string text = render(ReportFormat::Markdown, context_of(*analysis));
    std::vector<std::string> rows = markdown_findings_rows(text, 1);
    ASSERT_EQ(rows.size(), 1u);
    auto cells = markdown_cells(rows[0]);
    ASSERT_EQ(cells.size(), 7u) << rows[0];
    EXPECT_EQ(cells[6], "a\\|b \\*c\\* \\_d\\_ \\`e\\` \\<f\\>");
}

TEST(ReportTest, MarkdownBackslashInAMessageDoesNotBreakTheRow) {
    auto analysis = analyse_file("samples/ppo2.pcap");
    Finding f = make_finding(FindingKind::UnknownCode, 7, 4, "C:\\dir\\ and a\\|b ends \\");
    analysis->log.append(std::span<const Finding>(&f, 1));
    std::string text = render(ReportFormat::Markdown, context_of(*analysis));
    std::vector<std::string> rows = markdown_findings_rows(text, 1);
    ASSERT_EQ(rows.size(), 1u);
    auto cells = markdown_cells(rows[0]);
    ASSERT_EQ(cells.size(), 7u) << rows[0];
    EXPECT_EQ(cells[6], "C:\\\\dir\\\\ and a\\\\\\|b ends \\\\");
}

// ---- fail-on -----------------------------------------------------------------------------------

TEST(ReportTest, SeverityFailsFollowsTheThreshold) {
    EXPECT_TRUE(severity_fails(Severity::Error, FailOn::Error));
    EXPECT_FALSE(severity_fails(Severity::Warning, FailOn::Error));
    EXPECT_FALSE(severity_fails(Severity::Note, FailOn::Error));
    EXPECT_TRUE(severity_fails(Severity::Error, FailOn::Warning));
    EXPECT_TRUE(severity_fails(Severity::Warning, FailOn::Warning));
    EXPECT_FALSE(severity_fails(Severity::Note, FailOn::Warning));
    EXPECT_FALSE(severity_fails(Severity::Error, FailOn::Never));
    EXPECT_FALSE(severity_fails(Severity::Warning, FailOn::Never));
    EXPECT_FALSE(severity_fails(Severity::Note, FailOn::Never));
}

TEST(ReportTest, FormatAndFailOnNamesRoundTrip) {
    for (ReportFormat format : {ReportFormat::Text, ReportFormat::Json, ReportFormat::Markdown,
                                ReportFormat::Html, ReportFormat::Junit})
        EXPECT_EQ(report_format_from_name(report_format_name(format)), format);
    EXPECT_EQ(report_format_name(ReportFormat::Markdown), "markdown");
    EXPECT_EQ(report_format_name(ReportFormat::Junit), "junit");
    EXPECT_FALSE(report_format_from_name("md"));
    EXPECT_FALSE(report_format_from_name("HTML"));
    EXPECT_EQ(fail_on_from_name("error"), FailOn::Error);
    EXPECT_EQ(fail_on_from_name("warning"), FailOn::Warning);
    EXPECT_EQ(fail_on_from_name("never"), FailOn::Never);
    EXPECT_FALSE(fail_on_from_name("note"));
    for (FailOn f : {FailOn::Error, FailOn::Warning, FailOn::Never})
        EXPECT_EQ(fail_on_from_name(fail_on_name(f)), f);
}

TEST(ReportTest, RenderReportReturnsTheVerdictOfReportFails) {
    for (FailOn f : {FailOn::Error, FailOn::Warning, FailOn::Never}) {
        for (ReportFormat format : {ReportFormat::Text, ReportFormat::Json, ReportFormat::Markdown,
                                    ReportFormat::Html, ReportFormat::Junit}) {
            SCOPED_TRACE(std::string(report_format_name(format)) + " " +
                         std::string(fail_on_name(f)));
            FILE* sink = std::fopen("/dev/null", "w");
            ASSERT_NE(sink, nullptr);
            {
                Output out(sink);
                const ReportContext failing = context_of(faults(), f);
                EXPECT_EQ(render_report(format, failing, out), report_fails(failing));
                const ReportContext passing = context_of(clean(), f);
                EXPECT_FALSE(render_report(format, passing, out));
            }
            std::fclose(sink);
        }
    }
}

TEST(ReportTest, ReportFailsOnFindingsAtOrAboveTheThreshold) {
    EXPECT_TRUE(report_fails(context_of(faults(), FailOn::Error)));
    EXPECT_TRUE(report_fails(context_of(faults(), FailOn::Warning)));
    EXPECT_FALSE(report_fails(context_of(faults(), FailOn::Never)));
    for (FailOn f : {FailOn::Error, FailOn::Warning, FailOn::Never})
        EXPECT_FALSE(report_fails(context_of(clean(), f)));

    auto warned = analyse_file("samples/ppo2.pcap");
    Finding warning = make_finding(FindingKind::SpmViolation, 7, 4, "warning");
    warned->log.append(std::span<const Finding>(&warning, 1));
    EXPECT_FALSE(report_fails(context_of(*warned, FailOn::Error)));
    EXPECT_TRUE(report_fails(context_of(*warned, FailOn::Warning)));
    EXPECT_FALSE(report_fails(context_of(*warned, FailOn::Never)));

    auto noted = analyse_file("samples/ppo2.pcap");
    Finding note = make_finding(FindingKind::FdlRetry, 7, 4, "note");
    noted->log.append(std::span<const Finding>(&note, 1));
    EXPECT_FALSE(report_fails(context_of(*noted, FailOn::Error)));
    EXPECT_FALSE(report_fails(context_of(*noted, FailOn::Warning)));
    EXPECT_NE(render(ReportFormat::Text, context_of(*noted, FailOn::Warning))
                  .find("\nResult:  PASS: 0 errors, 0 warnings, 1 note (fail on warning)\n"),
              std::string::npos);
}

TEST(ReportTest, ReportFailsCountsOnlyTheFindingsShown) {
    auto analysis = analyse_file("samples/ppo2.pcap");
    Finding hidden = make_finding(FindingKind::StackedRequest, 7, 9, "on another slave");
    analysis->log.append(std::span<const Finding>(&hidden, 1));
    EXPECT_TRUE(report_fails(context_of(*analysis)));
    EXPECT_FALSE(report_fails(context_of(*analysis, FailOn::Error, {4})));
    auto report = json_report(context_of(*analysis, FailOn::Error, {4}));
    ASSERT_TRUE(report);
    EXPECT_EQ((*report)["result"].string(), "pass");
    EXPECT_TRUE((*report)["findings"].items.empty());
    // The faults sample filtered to slave 4 still fails on the garbage no station can be named
    // for, and on slave 4's config_mismatch.
    EXPECT_TRUE(report_fails(context_of(faults(), FailOn::Error, {4})));
}

// ---- html --------------------------------------------------------------------------------------

// N from a chart element's "<title>...: N things</title>".
std::uint64_t title_count(const XmlNode& rect) {
    auto titles = rect.elements("title");
    if (titles.size() != 1) {
        ADD_FAILURE() << "a chart element without one <title>";
        return 0;
    }
    const std::string& text = titles[0]->text;
    std::size_t colon = text.rfind(": ");
    EXPECT_NE(colon, std::string::npos) << text;
    return colon == std::string::npos ? 0 : std::strtoull(text.c_str() + colon + 2, nullptr, 10);
}

const XmlNode* find_id(const XmlNode& root, std::string_view tag, std::string_view id) {
    for (const XmlNode* node : root.all(tag))
        if (node->attribute("id") == id) return node;
    return nullptr;
}

// Rows of the findings table (header row excluded).
std::vector<const XmlNode*> findings_rows(const XmlNode& html) {
    auto tables = html.all("table", "findings");
    if (tables.size() != 1) return {};
    auto rows = tables[0]->elements("tr");
    EXPECT_FALSE(rows.empty());
    EXPECT_TRUE(rows.empty() || !rows[0]->elements("th").empty()) << "a header row";
    return rows.empty() ? rows : std::vector<const XmlNode*>(rows.begin() + 1, rows.end());
}

TEST(ReportTest, HtmlIsWellFormedAndSelfContained) {
    std::string text = render(ReportFormat::Html, context_of(faults()));
    EXPECT_TRUE(starts_with(text, "<!DOCTYPE html>\n"));
    for (std::string_view reference : {"http://", "https://", "src=", "<link", "url(", "@import"})
        EXPECT_EQ(text.find(reference), std::string::npos) << reference;
    auto html = parse_xml(text, true);
    ASSERT_TRUE(html);
    EXPECT_EQ(html->name, "html");
    EXPECT_EQ(html->all("script").size(), 0u);
    EXPECT_EQ(html->all("title").size(), 1 + html->all("rect").size());  // a tip per bar
    EXPECT_EQ(html->elements("head")[0]->elements("title")[0]->text,
              "dpscope report: samples/faults.pcap");
    for (const XmlNode* anchor : html->all("a")) {
        std::string href = anchor->attribute("href");
        ASSERT_TRUE(starts_with(href, "#")) << href;
        EXPECT_TRUE(find_id(*html, "section", href.substr(1))) << href;
    }
}

TEST(ReportTest, HtmlOneSectionPerSlaveWithLatencyHistogramAndTimeline) {
    auto html = parse_xml(render(ReportFormat::Html, context_of(faults())), true);
    ASSERT_TRUE(html);
    auto sections = html->all("section", "station");
    ASSERT_EQ(sections.size(), 3u);
    const std::uint8_t slaves[] = {3, 4, 5};
    for (std::size_t i = 0; i < sections.size(); ++i) {
        const XmlNode& section = *sections[i];
        const ChannelStats& stats = faults().station(slaves[i]);
        SCOPED_TRACE("slave " + std::to_string(slaves[i]));
        EXPECT_EQ(section.attribute("id"), "slave-" + std::to_string(slaves[i]) + "-2");
        ASSERT_EQ(section.elements("h2").size(), 1u);
        EXPECT_EQ(section.elements("h2")[0]->text,
                  "Slave " + std::to_string(slaves[i]) + " (master 2)");

        auto latency = section.all("svg", "latency");
        ASSERT_EQ(latency.size(), 1u);
        EXPECT_EQ(latency[0]->attribute("width"), "720");
        auto bars = latency[0]->all("rect", "bar");
        EXPECT_GT(bars.size(), 0u);
        EXPECT_LE(bars.size(), 30u);
        std::uint64_t answered = 0;
        for (const XmlNode* bar : bars) {
            answered += title_count(*bar);
            EXPECT_GT(std::strtod(bar->attribute("height").c_str(), nullptr), 0.0);
        }
        EXPECT_EQ(answered, stats.latency_ns.count());
        EXPECT_EQ(answered, stats.transactions.total());

        auto timeline = section.all("svg", "timeline");
        ASSERT_EQ(timeline.size(), 1u);
        EXPECT_EQ(timeline[0]->attribute("width"), "720");
        std::uint64_t transactions = 0;
        for (const XmlNode* bar : timeline[0]->all("rect", "tx"))
            transactions += title_count(*bar);
        EXPECT_EQ(transactions, stats.transactions.total());
        std::array<std::uint64_t, 3> marks{}, findings{};  // by severity
        const char* rows[] = {"notes", "warnings", "errors"};
        for (std::size_t row = 0; row < 3; ++row)
            for (const XmlNode* mark : timeline[0]->all("rect", rows[row]))
                marks[row] += title_count(*mark);
        for (std::size_t k = 0; k < kFindingKindCount; ++k)
            findings[static_cast<std::size_t>(default_severity(static_cast<FindingKind>(k)))] +=
                stats.findings[k];
        EXPECT_EQ(marks, findings);
        EXPECT_GT(findings[2], 0u);
        std::size_t rows_marked = 0;
        for (std::size_t row = 0; row < 3; ++row)
            rows_marked += timeline[0]->all("rect", rows[row]).size();
        EXPECT_EQ(rows_marked, timeline[0]->all("rect", "mark").size());
    }
}

TEST(ReportTest, HtmlVerdictSummaryAndFindingsTable) {
    auto html = parse_xml(render(ReportFormat::Html, context_of(faults())), true);
    ASSERT_TRUE(html);
    const XmlNode* verdict = find_id(*html, "p", "verdict");
    ASSERT_TRUE(verdict);
    EXPECT_TRUE(verdict->has_class("fail"));
    EXPECT_EQ(verdict->text, "FAIL: 7 errors, 7 warnings, 6 notes (fail on error)");
    auto cards = html->all("div", "card");
    ASSERT_EQ(cards.size(), 8u);
    std::vector<std::string> numbers;
    for (const XmlNode* card : cards)
        numbers.push_back(card->all("div", "n")[0]->text);
    EXPECT_EQ(numbers, (std::vector<std::string>{"458", "0", "1", "35", "3", "7", "7", "6"}));
    auto slave_rows = html->all("table", "slaves")[0]->elements("tr");
    ASSERT_EQ(slave_rows.size(), 4u);
    auto cells = slave_rows[1]->elements("td");
    ASSERT_EQ(cells.size(), 10u);
    EXPECT_EQ(cells[0]->inner, "3");
    EXPECT_EQ(cells[2]->text, "PPO1");
    EXPECT_EQ(cells[7]->text, "2");  // errors of slave 3
    EXPECT_EQ(cells[8]->text, "2");  // warnings
    EXPECT_EQ(cells[9]->text, "3");  // notes

    auto rows = findings_rows(*html);
    ASSERT_EQ(rows.size(), kFaultsFindings.size());
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const ExpectedFinding& f = kFaultsFindings[i];
        EXPECT_TRUE(rows[i]->has_class(f.severity)) << i;
        auto tds = rows[i]->elements("td");
        ASSERT_EQ(tds.size(), 7u);
        EXPECT_EQ(tds[0]->text, std::to_string(f.frame));
        EXPECT_EQ(tds[2]->text, f.severity);
        EXPECT_EQ(tds[3]->text, f.kind);
        EXPECT_EQ(tds[4]->text, f.slave ? "2 / " + std::to_string(f.slave) : "-");
    }
    EXPECT_EQ(rows[0]->elements("td")[6]->text,
              "byte 19: FCS 0x7C wrong, checksum of the data is 0x26");
    EXPECT_EQ(find_id(*html, "section", "findings")->elements("h2")[0]->text, "Findings (20)");
}

TEST(ReportTest, HtmlCleanCapturePassesAndHasNoFindingsTable) {
    auto html = parse_xml(render(ReportFormat::Html, context_of(clean())), true);
    ASSERT_TRUE(html);
    const XmlNode* verdict = find_id(*html, "p", "verdict");
    ASSERT_TRUE(verdict);
    EXPECT_TRUE(verdict->has_class("pass"));
    EXPECT_EQ(verdict->text, "PASS: 0 errors, 0 warnings, 0 notes (fail on error)");
    EXPECT_EQ(html->all("section", "station").size(), 1u);
    EXPECT_TRUE(html->all("table", "findings").empty());
    const XmlNode* findings = find_id(*html, "section", "findings");
    ASSERT_TRUE(findings);
    EXPECT_EQ(findings->elements("p")[0]->text, "No findings.");
    EXPECT_TRUE(html->all("svg", "timeline")[0]->all("rect", "mark").empty());
}

TEST(ReportTest, HtmlStationWithoutTransactionsHasNoCharts) {
    auto analysis = analyse_simulation(one_slave(6, 3, 1));
    ASSERT_EQ(analysis->tracker.transactions(), 0u);
    std::string text = render(ReportFormat::Html, context_of(*analysis));
    auto html = parse_xml(text, true);
    ASSERT_TRUE(html);
    ASSERT_EQ(html->all("section", "station").size(), 1u);
    EXPECT_TRUE(html->all("svg").empty());
    EXPECT_NE(text.find("<p class=\"meta\">No answered requests.</p>"), std::string::npos);
    EXPECT_NE(text.find("<p class=\"meta\">No timed transactions or findings.</p>"),
              std::string::npos);
}

// The timeline's axis spans the capture, and an event is a tick on it: a slave whose only event
// is one finding halfway through gets a 2-unit mark in the middle, not a bar across the page.
TEST(ReportTest, HtmlTimelineDrawsASingleFindingAsATickOnTheCapture) {
    auto analysis = analyse_simulation(one_slave(6, 3, 200));  // PPO 3: no parameter channel
    ASSERT_EQ(analysis->tracker.transactions(), 0u);
    const std::int64_t first = analysis->summary.first_time_ns();
    const std::int64_t last = analysis->summary.last_time_ns();
    ASSERT_LT(first, last);
    Finding finding;
    finding.kind = FindingKind::FdlNoResponse;
    finding.severity = Severity::Error;
    finding.time_ns = first + (last - first) / 2;
    finding.has_stations = true;
    finding.master = 2;
    finding.slave = 6;
    analysis->timelines.add(std::span<const Finding>(&finding, 1), {});
    auto html = parse_xml(render(ReportFormat::Html, context_of(*analysis)), true);
    ASSERT_TRUE(html);
    auto timeline = html->all("svg", "timeline");
    ASSERT_EQ(timeline.size(), 1u);
    auto marks = timeline[0]->all("rect", "mark");
    ASSERT_EQ(marks.size(), 1u);
    EXPECT_TRUE(marks[0]->has_class("errors"));
    EXPECT_EQ(marks[0]->attribute("width"), "2");
    // The plot runs from x 84 to 710; the middle is 397 (the bin's middle, within a bin).
    const double x = std::strtod(marks[0]->attribute("x").c_str(), nullptr);
    EXPECT_NEAR(x, 396.0, 8.0);
    // The axis is labelled with the capture's start and end.
    auto labels = timeline[0]->all("text");
    ASSERT_FALSE(labels.empty());
    EXPECT_EQ(labels.back()->text, relative_seconds_text(last - first) + " s");
}

TEST(ReportTest, HtmlStationFilterHidesOtherSlavesAndTheirFindings) {
    auto html =
        parse_xml(render(ReportFormat::Html, context_of(faults(), FailOn::Error, {5})), true);
    ASSERT_TRUE(html);
    auto sections = html->all("section", "station");
    ASSERT_EQ(sections.size(), 1u);
    EXPECT_EQ(sections[0]->attribute("id"), "slave-5-2");
    EXPECT_EQ(html->all("table", "slaves")[0]->elements("tr").size(), 2u);
    auto rows = findings_rows(*html);
    ASSERT_EQ(rows.size(), 9u);  // eight of slave 5 and the garbage
    for (const XmlNode* row : rows) {
        std::string station = row->elements("td")[4]->text;
        EXPECT_TRUE(station == "2 / 5" || station == "-") << station;
    }
}

TEST(ReportTest, BusFindingsHaveTheirOwnSectionInEveryFormat) {
    std::string text = render(ReportFormat::Text, context_of(faults()));
    EXPECT_NE(text.find("\nBus (telegrams no station can be named for)\n  findings       "
                        "malformed_telegram 1\n"),
              std::string::npos)
        << text;
    std::string markdown = render(ReportFormat::Markdown, context_of(faults()));
    EXPECT_NE(markdown.find("\n### Bus (telegrams no station can be named for)\n\n- Findings: "
                            "malformed\\_telegram 1\n"),
              std::string::npos)
        << markdown;
    auto html = parse_xml(render(ReportFormat::Html, context_of(faults())), true);
    ASSERT_TRUE(html);
    const XmlNode* bus = find_id(*html, "section", "bus");
    ASSERT_NE(bus, nullptr);
    auto rows = bus->all("tr");
    ASSERT_EQ(rows.size(), 2u);  // header and malformed_telegram
    EXPECT_EQ(rows[1]->elements("td")[0]->text, "malformed_telegram");
    // A capture without bus findings has no such section.
    auto clean_html = parse_xml(render(ReportFormat::Html, context_of(clean())), true);
    ASSERT_TRUE(clean_html);
    EXPECT_EQ(find_id(*clean_html, "section", "bus"), nullptr);
    EXPECT_EQ(render(ReportFormat::Markdown, context_of(clean())).find("### Bus"),
              std::string::npos);
}

TEST(ReportTest, HtmlEscapesMessagesAndTheInputName) {
    auto analysis = analyse_file("samples/ppo2.pcap");
    const std::string message = "<script>alert(\"x\")</script> & 'q' <b>";
    Finding f = make_finding(FindingKind::StackedRequest, 7, 4, message);
    analysis->log.append(std::span<const Finding>(&f, 1));
    analysis->input.name = "<img src=x>&.pcap";
    std::string text = render(ReportFormat::Html, context_of(*analysis));
    EXPECT_EQ(text.find("<script"), std::string::npos);
    EXPECT_EQ(text.find("<img"), std::string::npos);
    EXPECT_NE(text.find("&lt;script&gt;alert(&quot;x&quot;)&lt;/script&gt; &amp; &#39;q&#39; "
                        "&lt;b&gt;"),
              std::string::npos);
    auto html = parse_xml(text, true);
    ASSERT_TRUE(html);
    EXPECT_TRUE(html->all("script").empty());
    EXPECT_TRUE(html->all("b").empty());
    auto rows = findings_rows(*html);
    ASSERT_EQ(rows.size(), 1u);
    EXPECT_EQ(rows[0]->elements("td")[6]->text, message);
    EXPECT_EQ(html->all("title")[0]->text, "dpscope report: <img src=x>&.pcap");
}

TEST(ReportTest, HtmlListsAtMostTwoThousandFindings) {
    auto analysis = analyse_file("samples/ppo2.pcap");
    std::vector<Finding> many;
    for (std::uint64_t i = 0; i < 2345; ++i)
        many.push_back(make_finding(FindingKind::FdlRetry, 1000 + i, 4, "retry"));
    analysis->log.append(many);
    std::string text = render(ReportFormat::Html, context_of(*analysis));
    auto html = parse_xml(text, true);
    ASSERT_TRUE(html);
    auto rows = findings_rows(*html);
    ASSERT_EQ(rows.size(), 2000u);
    EXPECT_EQ(rows.front()->elements("td")[0]->text, "1000");
    EXPECT_EQ(rows.back()->elements("td")[0]->text, "2999");
    EXPECT_NE(text.find("<p class=\"meta\">345 more findings not listed here (at most 2000; the "
                        "JSON report lists them all).</p>"),
              std::string::npos);
    EXPECT_EQ(find_id(*html, "section", "findings")->elements("h2")[0]->text, "Findings (2345)");
    // The other formats list them all.
    auto report = json_report(context_of(*analysis));
    ASSERT_TRUE(report);
    EXPECT_EQ((*report)["findings"].items.size(), 2345u);
}

// samples/ppo2.pcap with `stacked` stacked_request findings of slave 4 from frame 1000 on, then
// `retries` fdl_retry findings from frame `retry_frame` on.
std::unique_ptr<Analysis> ppo2_with_findings(std::uint64_t stacked, std::uint64_t retries,
                                             std::uint64_t retry_frame) {
    auto analysis = analyse_file("samples/ppo2.pcap");
    std::vector<Finding> many;
    for (std::uint64_t i = 0; i < stacked; ++i)
        many.push_back(make_finding(FindingKind::StackedRequest, 1000 + i, 4, "stacked"));
    for (std::uint64_t i = 0; i < retries; ++i)
        many.push_back(make_finding(FindingKind::FdlRetry, retry_frame + i, 4, "retry"));
    analysis->log.append(many);
    return analysis;
}

TEST(ReportTest, JunitListsAtMostTenThousandFailuresPerRuleAndCountsTheRest) {
    auto analysis = ppo2_with_findings(10'003, 2, 20'000);
    auto root = junit_report(context_of(*analysis));
    ASSERT_TRUE(root);
    const XmlNode* slave4 = nullptr;
    for (const XmlNode* suite : root->elements("testsuite"))
        if (suite->attribute("name") == "slave 4 (master 2)") slave4 = suite;
    ASSERT_NE(slave4, nullptr);
    auto cases = slave4->elements("testcase");
    const XmlNode& stacked = *cases[static_cast<std::size_t>(FindingKind::StackedRequest)];
    auto failures = stacked.elements("failure");
    ASSERT_EQ(failures.size(), 10'000u);
    EXPECT_TRUE(starts_with(failures.front()->attribute("message"), "frame 1000: "));
    EXPECT_TRUE(starts_with(failures.back()->attribute("message"), "frame 10999: "));
    ASSERT_EQ(stacked.elements("system-out").size(), 1u);
    EXPECT_EQ(stacked.elements("system-out")[0]->text,
              "3 more failing findings not listed here (at most 10000 per rule; the JSON report "
              "lists them all)");
    const XmlNode& retry = *cases[static_cast<std::size_t>(FindingKind::FdlRetry)];
    EXPECT_TRUE(retry.elements("failure").empty());
    EXPECT_EQ(retry.elements("system-out")[0]->text, "2 note findings below the failure threshold");
}

// ---- inputs without times, damaged inputs, several masters -------------------------------------

TEST(ReportTest, UntimedCaptureHasCycleLatencyButNoTimes) {
    auto analysis = analyse_file("samples/serial.raw");
    auto report = json_report(context_of(*analysis));
    ASSERT_TRUE(report);
    EXPECT_EQ((*report)["input"]["format"].string(), "raw");
    EXPECT_TRUE((*report)["input"]["first_time"].is_null());
    EXPECT_TRUE((*report)["input"]["last_time"].is_null());
    EXPECT_EQ((*report)["summary"]["transactions"].integer(), 6);
    for (const Json& station : (*report)["stations"].items) {
        EXPECT_EQ(station["transactions"].integer(), 3);
        EXPECT_TRUE(station["timeouts"].is_null()) << "not judged, not 0";
        EXPECT_TRUE(station["latency_ms"].is_null());
        EXPECT_FALSE(station["latency_cycles"].is_null());
    }
    for (const Json& finding : (*report)["findings"].items)
        EXPECT_TRUE(finding["time"].is_null());
    std::string text = render(ReportFormat::Text, context_of(*analysis));
    EXPECT_NE(text.find("Input:   samples/serial.raw (raw), 99 telegrams\n"), std::string::npos);
    EXPECT_NE(text.find("Checks:  time-outs not judged (no timestamps); "), std::string::npos);
    EXPECT_NE(text.find("  bytes skipped  6\n"), std::string::npos);
    EXPECT_NE(text.find("  unanswered     time-outs not judged (no timestamps), 0 abandoned by "
                        "the master\n"),
              std::string::npos);
    EXPECT_NE(text.find("  latency ms     not measured (no timestamps)\n"), std::string::npos);
    EXPECT_NE(text.find("  latency cycles min 1  median 2  p95 3  max 3\n"), std::string::npos);
    std::vector<std::string> rows = lines_after(lines_of(text), "Findings (2, in capture order)");
    ASSERT_EQ(rows.size(), 3u);
    EXPECT_NE(rows[1].find("         -  "), std::string::npos) << rows[1];
}

TEST(ReportTest, HtmlUntimedCaptureDoesNotClaimRequestsWentUnanswered) {
    auto analysis = analyse_file("samples/serial.raw");
    ASSERT_EQ(analysis->station(3).transactions.total(), 3u);
    ASSERT_EQ(analysis->station(3).latency_ns.count(), 0u);
    std::string text = render(ReportFormat::Html, context_of(*analysis));
    ASSERT_TRUE(parse_xml(text, true));
    EXPECT_EQ(text.find("No answered requests."), std::string::npos);
    EXPECT_NE(text.find("carries no timestamps"), std::string::npos);
    EXPECT_EQ(count_of(text, "<section class=\"station\""), 2u);
}

TEST(ReportTest, DamagedInputIsNamedInEveryFormat) {
    auto analysis = analyse_file("samples/truncated.pcap");
    ASSERT_TRUE(analysis->input.damaged);
    auto report = json_report(context_of(*analysis));
    ASSERT_TRUE(report);
    EXPECT_TRUE((*report)["input"]["damaged"].boolean);
    EXPECT_EQ((*report)["result"].string(), "pass");
    EXPECT_NE(render(ReportFormat::Text, context_of(*analysis))
                  .find("\n         the input ended in damage; the report covers what was read\n"),
              std::string::npos);
    EXPECT_NE(
        render(ReportFormat::Markdown, context_of(*analysis))
            .find("- Input: `samples/truncated.pcap` (pcap), 101 telegrams (ended in damage)\n"),
        std::string::npos);
    auto html = parse_xml(render(ReportFormat::Html, context_of(*analysis)), true);
    ASSERT_TRUE(html);
    auto notes = html->all("p", "error");
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_EQ(notes[0]->text, "The input ended in damage; the report covers what was read.");
    auto clean_html = parse_xml(render(ReportFormat::Html, context_of(clean())), true);
    ASSERT_TRUE(clean_html);
    EXPECT_TRUE(clean_html->all("p", "error").empty());
}

std::vector<std::uint8_t> exchange(std::uint8_t da, std::uint8_t sa, bool request, bool fcb,
                                   std::uint8_t rc, std::uint16_t pnu, std::uint32_t pva) {
    std::vector<std::uint8_t> du;
    append_pcv(du, rc, false, pnu, 0, pva);
    append_u16_be(du, request ? 0x047F : 0x0F07);
    append_u16_be(du, 0x2000);
    std::uint8_t fc =
        request ? request_fc(FdlFunction::SrdHigh, fcb, true) : response_fc(FdlStatus::DataLow);
    return build_telegram({da, sa, fc, std::nullopt, std::nullopt, Bytes(du)});
}

// Two masters exchange data with slave 3; the slave answers master 2 with nothing pending.
std::unique_ptr<Analysis> two_masters() {
    auto analysis = std::make_unique<Analysis>();
    std::vector<std::vector<std::uint8_t>> telegrams;
    for (int cycle = 0; cycle < 4; ++cycle) {
        bool fcb = cycle % 2 == 0;
        telegrams.push_back(exchange(3, 1, true, fcb, 0, 0, 0));
        telegrams.push_back(exchange(1, 3, false, fcb, 0, 0, 0));
        telegrams.push_back(exchange(3, 2, true, fcb, 0, 0, 0));
        bool orphan = cycle == 2;
        telegrams.push_back(exchange(2, 3, false, fcb, orphan ? 1 : 0, orphan ? 520 : 0, 5));
    }
    std::uint64_t number = 0;
    for (const auto& bytes : telegrams) {
        ++number;
        analysis->feed(Bytes(bytes.data(), bytes.size()),
                       kT0Sample + static_cast<std::int64_t>(number) * 500'000, number);
    }
    analysis->finish();
    analysis->input = InputSummary{"two-masters.pcap", "pcap", 0, false};
    return analysis;
}

TEST(ReportTest, JunitPutsAFindingInTheSuiteOfItsMasterAndSlave) {
    auto analysis = two_masters();
    auto channels = analysis->tracker.channels();
    ASSERT_EQ(channels.size(), 2u);
    EXPECT_EQ(channels[0]->master, 1);
    EXPECT_EQ(channels[1]->master, 2);
    ASSERT_EQ(analysis->log.size(), 1u);
    ASSERT_EQ(channels[1]->findings[static_cast<std::size_t>(FindingKind::OrphanResponse)], 1u);
    auto root = junit_report(context_of(*analysis, FailOn::Warning));
    ASSERT_TRUE(root);
    auto suites = root->elements("testsuite");
    ASSERT_EQ(suites.size(), 2u);
    EXPECT_EQ(suites[0]->attribute("name"), "slave 3 (master 1)");
    EXPECT_EQ(suites[1]->attribute("name"), "slave 3 (master 2)");
    EXPECT_TRUE(suites[0]->all("failure").empty());
    EXPECT_EQ(suites[1]->all("failure").size(), 1u);
    EXPECT_EQ(suites[1]->attribute("failures"), "1");
    EXPECT_EQ(suites[0]->attribute("failures"), "0");
}

// ---- FindingLog --------------------------------------------------------------------------------

bool same_finding(const Finding& a, const Finding& b) {
    return a.kind == b.kind && a.severity == b.severity && a.frame == b.frame &&
           a.request_frame == b.request_frame && a.time_ns == b.time_ns &&
           a.has_stations == b.has_stations && a.master == b.master && a.slave == b.slave &&
           a.pnu == b.pnu && a.message == b.message;
}

std::vector<Finding> random_findings(std::size_t n, std::uint64_t seed) {
    std::mt19937_64 random(seed);
    std::vector<Finding> out;
    for (std::size_t i = 0; i < n; ++i) {
        Finding f;
        f.kind = static_cast<FindingKind>(random() % kFindingKindCount);
        f.severity = static_cast<Severity>(random() % 3);
        f.frame = (std::uint64_t{1} << 40) + i;
        f.request_frame = random() % 4 == 0 ? 0 : random();
        f.time_ns =
            random() % 5 == 0 ? kNoTime : static_cast<std::int64_t>(random() >> 1) - (1LL << 62);
        f.has_stations = random() % 3 != 0;
        f.master = static_cast<std::uint8_t>(random());
        f.slave = static_cast<std::uint8_t>(random());
        switch (random() % 3) {
            case 0: break;
            case 1: f.pnu = 0; break;  // present and zero is not absent
            default: f.pnu = static_cast<std::uint16_t>(random());
        }
        std::size_t length = random() % 4 == 0 ? 0 : random() % 300;
        for (std::size_t c = 0; c < length; ++c)
            f.message.push_back(static_cast<char>(random()));
        if (i % 97 == 0) f.message = std::string("nul\0inside\xff\xfe", 12);
        out.push_back(std::move(f));
    }
    return out;
}

std::vector<Finding> read_back(const FindingLog& log) {
    std::vector<Finding> out;
    log.for_each([&](const Finding& f) { out.push_back(f); });
    EXPECT_EQ(log.lost(), "");
    return out;
}

void expect_same(const std::vector<Finding>& actual, const std::vector<Finding>& expected) {
    ASSERT_EQ(actual.size(), expected.size());
    for (std::size_t i = 0; i < actual.size(); ++i)
        ASSERT_TRUE(same_finding(actual[i], expected[i])) << "finding " << i;
}

std::size_t open_descriptors() {
    std::size_t n = 0;
    DIR* dir = opendir("/proc/self/fd");
    if (!dir) return 0;
    while (readdir(dir))
        ++n;
    closedir(dir);
    return n;
}

TEST(ReportTest, FindingLogEmptyListsNothing) {
    FindingLog log;
    EXPECT_EQ(log.size(), 0u);
    EXPECT_TRUE(read_back(log).empty());
    log.append({});
    EXPECT_EQ(log.size(), 0u);
    EXPECT_TRUE(log.lost().empty());
}

TEST(ReportTest, FindingLogKeepsAFewFindingsInMemory) {
    std::vector<Finding> findings = random_findings(4095, 1);
    std::size_t before = open_descriptors();
    FindingLog log;
    log.append(findings);
    EXPECT_EQ(open_descriptors(), before) << "no temporary file below 4096 findings";
    EXPECT_EQ(log.size(), 4095u);
    expect_same(read_back(log), findings);
}

TEST(ReportTest, FindingLogSpillsBeyond4096AndReadsBackInOrder) {
    std::vector<Finding> findings = random_findings(10'000, 2);
    std::size_t before = open_descriptors();
    {
        FindingLog log;
        // Chunks of different sizes, as the tracker hands them out, one larger than the limit.
        const std::size_t chunks[] = {1, 0, 7, 4095, 1, 4200, 3, 1693};
        std::size_t at = 0;
        for (std::size_t chunk : chunks) {
            log.append(std::span<const Finding>(findings.data() + at, chunk));
            at += chunk;
            EXPECT_EQ(log.size(), at);
        }
        ASSERT_EQ(at, findings.size());
        EXPECT_EQ(open_descriptors(), before + 1) << "one temporary file";
        EXPECT_TRUE(log.lost().empty()) << log.lost();
        expect_same(read_back(log), findings);
        // Reading does not consume: a second pass gives the same, and appending after a read
        // continues the sequence.
        expect_same(read_back(log), findings);
        std::vector<Finding> more = random_findings(5000, 3);
        log.append(std::span<const Finding>(more.data(), 10));
        log.append(std::span<const Finding>(more.data() + 10, more.size() - 10));
        findings.insert(findings.end(), more.begin(), more.end());
        EXPECT_EQ(log.size(), findings.size());
        expect_same(read_back(log), findings);
        EXPECT_TRUE(log.lost().empty()) << log.lost();
    }
    EXPECT_EQ(open_descriptors(), before) << "the temporary file is closed";
}

TEST(ReportTest, FindingLogOneByOneAcrossTheLimit) {
    std::vector<Finding> findings = random_findings(9000, 4);
    FindingLog log;
    for (const Finding& f : findings)
        log.append(std::span<const Finding>(&f, 1));
    EXPECT_EQ(log.size(), 9000u);
    expect_same(read_back(log), findings);
}

TEST(ReportTest, ReportOfASpilledLogListsEveryFindingInOrder) {
    auto analysis = analyse_file("samples/ppo2.pcap");
    std::vector<Finding> many;
    for (std::uint64_t i = 0; i < 5000; ++i)
        many.push_back(make_finding(i % 2 ? FindingKind::FdlRetry : FindingKind::UnknownCode,
                                    200 + i, 4, "m" + std::to_string(i)));
    analysis->log.append(many);
    auto report = json_report(context_of(*analysis));
    ASSERT_TRUE(report);
    const Json& findings = (*report)["findings"];
    ASSERT_EQ(findings.items.size(), 5000u);
    for (std::size_t i = 0; i < 5000; ++i) {
        ASSERT_EQ(findings[i]["frame"].integer(), static_cast<long long>(200 + i));
        ASSERT_EQ(findings[i]["message"].string(), "m" + std::to_string(i));
    }
    EXPECT_EQ((*report)["summary"]["findings"]["warning"].integer(), 2500);
    EXPECT_EQ((*report)["summary"]["findings"]["note"].integer(), 2500);
}

// ---- LogHistogram ------------------------------------------------------------------------------

// Nearest rank: the sample of rank ceil(p/100 * n) (1-based) in sorted order.
std::uint64_t exact_percentile(const std::vector<std::uint64_t>& sorted, int p) {
    std::size_t n = sorted.size();
    std::size_t rank = (static_cast<std::size_t>(p) * n + 99) / 100;
    rank = std::clamp<std::size_t>(rank, 1, n);
    return sorted[rank - 1];
}

void expect_percentiles_close(const std::vector<std::uint64_t>& samples) {
    LogHistogram h;
    for (std::uint64_t v : samples)
        h.add(v);
    std::vector<std::uint64_t> sorted = samples;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(h.count(), samples.size());
    EXPECT_EQ(h.min(), sorted.front());
    EXPECT_EQ(h.max(), sorted.back());
    for (int p : {0, 1, 5, 10, 25, 50, 75, 90, 95, 99, 100}) {
        std::uint64_t exact = exact_percentile(sorted, p);
        std::uint64_t estimate = h.percentile(p);
        double error = std::fabs(static_cast<double>(estimate) - static_cast<double>(exact));
        if (exact < 128)
            EXPECT_EQ(estimate, exact) << "p" << p;
        else
            EXPECT_LE(error, 0.016 * static_cast<double>(exact))
                << "p" << p << ": " << estimate << " for " << exact;
        EXPECT_GE(estimate, h.min());
        EXPECT_LE(estimate, h.max());
    }
}

TEST(ReportTest, LogHistogramPercentilesWithinOnePointSixPercent) {
    std::mt19937_64 random(42);
    std::vector<std::uint64_t> latencies;  // log-uniform 1 us .. 10 s in ns
    std::uniform_real_distribution<double> exponent(3.0, 10.0);
    for (int i = 0; i < 10'000; ++i)
        latencies.push_back(static_cast<std::uint64_t>(std::pow(10.0, exponent(random))));
    expect_percentiles_close(latencies);

    std::vector<std::uint64_t> cycles;  // small integers, partly below the exact limit of 128
    for (int i = 0; i < 10'000; ++i)
        cycles.push_back(random() % 300);
    expect_percentiles_close(cycles);

    std::vector<std::uint64_t> narrow;  // a tight cluster around 2 ms
    std::normal_distribution<double> around(2'000'000.0, 50'000.0);
    for (int i = 0; i < 10'000; ++i)
        narrow.push_back(static_cast<std::uint64_t>(around(random)));
    expect_percentiles_close(narrow);

    std::vector<std::uint64_t> huge = {std::uint64_t{1} << 62, ~std::uint64_t{0}, 12345678901234};
    expect_percentiles_close(huge);
}

TEST(ReportTest, LogHistogramSmallValuesAreExact) {
    LogHistogram h;
    EXPECT_EQ(h.count(), 0u);
    EXPECT_EQ(h.percentile(50), 0u);
    for (std::uint64_t v : {7, 3, 127, 0, 3})
        h.add(v);
    EXPECT_EQ(h.count(), 5u);
    EXPECT_EQ(h.min(), 0u);
    EXPECT_EQ(h.max(), 127u);
    EXPECT_EQ(h.percentile(20), 0u);
    EXPECT_EQ(h.percentile(40), 3u);
    EXPECT_EQ(h.percentile(50), 3u);
    EXPECT_EQ(h.percentile(80), 7u);
    EXPECT_EQ(h.percentile(100), 127u);
}

TEST(ReportTest, LogHistogramBucketsAreNarrowAndFew) {
    std::mt19937_64 random(7);
    for (int i = 0; i < 100'000; ++i) {
        std::uint64_t v = random() >> (random() % 64);
        std::size_t b = LogHistogram::bucket_of(v);
        ASSERT_LE(LogHistogram::lower_of(b), v);
        ASSERT_GE(LogHistogram::upper_of(b), v);
        if (v >= 128) {
            ASSERT_LE(
                static_cast<double>(LogHistogram::upper_of(b) - LogHistogram::lower_of(b) + 1),
                static_cast<double>(LogHistogram::lower_of(b)) / 64.0)
                << v;
        }
    }
    // A million samples over one decade occupy a few hundred buckets at most.
    LogHistogram h;
    for (int i = 0; i < 1'000'000; ++i)
        h.add(1'000'000 + random() % 9'000'000);
    std::size_t buckets = 0;
    std::uint64_t counted = 0;
    std::uint64_t previous_upper = 0;
    h.for_each_bucket([&](std::uint64_t lower, std::uint64_t upper, std::uint64_t count) {
        EXPECT_GT(lower, previous_upper);
        previous_upper = upper;
        ++buckets;
        counted += count;
    });
    EXPECT_LE(buckets, 4u * 64u);
    EXPECT_EQ(counted, 1'000'000u);
}

// ---- Timeline ----------------------------------------------------------------------------------

constexpr std::int64_t kStart = 1'704'067'200'000'000'000;
constexpr std::int64_t kMs = 1'000'000;

Timeline::Bin total_of(const Timeline& timeline) {
    Timeline::Bin total;
    for (const Timeline::Bin& bin : timeline.bins()) {
        total.transactions += bin.transactions;
        total.errors += bin.errors;
        total.warnings += bin.warnings;
        total.notes += bin.notes;
    }
    return total;
}

TEST(ReportTest, TimelineStartsEmptyWithTenMillisecondBins) {
    Timeline timeline;
    EXPECT_TRUE(timeline.empty());
    EXPECT_EQ(timeline.start_ns(), kNoTime);
    EXPECT_EQ(timeline.bin_width_ns(), 10 * kMs);
    EXPECT_EQ(timeline.bins().size(), Timeline::kBins);
    EXPECT_EQ(Timeline::kBins, 240u);
    timeline.add_finding(kStart, Severity::Warning);
    EXPECT_FALSE(timeline.empty());
    EXPECT_EQ(timeline.start_ns(), kStart);
    EXPECT_EQ(timeline.bins()[0].warnings, 1u);
}

TEST(ReportTest, TimelineBinsMergeWhenTimeGrows) {
    Timeline timeline;
    for (std::int64_t i = 0; i < 240; ++i)
        timeline.add_transaction(kStart + i * 10 * kMs);
    EXPECT_EQ(timeline.bin_width_ns(), 10 * kMs);
    for (const Timeline::Bin& bin : timeline.bins())
        EXPECT_EQ(bin.transactions, 1u);

    timeline.add_finding(kStart + 2400 * kMs, Severity::Error);  // just past the last bin
    EXPECT_EQ(timeline.bin_width_ns(), 20 * kMs);
    EXPECT_EQ(timeline.start_ns(), kStart);
    for (std::size_t i = 0; i < 120; ++i)
        EXPECT_EQ(timeline.bins()[i].transactions, 2u) << i;
    EXPECT_EQ(timeline.bins()[120].errors, 1u);
    for (std::size_t i = 121; i < 240; ++i) {
        const Timeline::Bin& bin = timeline.bins()[i];
        EXPECT_EQ(bin.transactions + bin.errors + bin.warnings + bin.notes, 0u) << i;
    }

    // An hour later: the width doubles until the hour fits, 10 ms * 2^11 = 20.48 s.
    timeline.add_finding(kStart + 3'600'000 * kMs, Severity::Note);
    timeline.add_transaction(kStart + 3'600'000 * kMs);
    EXPECT_EQ(timeline.bin_width_ns(), 20'480 * kMs);
    EXPECT_EQ(timeline.bins()[0].transactions, 240u);
    EXPECT_EQ(timeline.bins()[0].errors, 1u);
    EXPECT_EQ(timeline.bins()[175].notes, 1u);
    EXPECT_EQ(timeline.bins()[175].transactions, 1u);
    Timeline::Bin total = total_of(timeline);
    EXPECT_EQ(total.transactions, 241u);
    EXPECT_EQ(total.errors, 1u);
    EXPECT_EQ(total.notes, 1u);
    EXPECT_EQ(total.warnings, 0u);
}

TEST(ReportTest, TimelineMemoryStaysFlatOverADay) {
    Timeline timeline;
    const std::size_t size = sizeof(timeline);
    std::uint64_t added = 0;
    for (std::int64_t t = 0; t < 86'400'000; t += 997) {  // a day, an event every ~1 s
        timeline.add_transaction(kStart + t * kMs);
        ++added;
    }
    EXPECT_EQ(sizeof(timeline), size);
    EXPECT_EQ(timeline.bins().size(), 240u);
    EXPECT_EQ(total_of(timeline).transactions, added);
    // 86 400 s in 240 bins: 10 ms * 2^16 = 655.36 s per bin (2^15 = 327.68 s needs 264 bins).
    EXPECT_EQ(timeline.bin_width_ns(), 655'360 * kMs);
    std::size_t used = 0;
    for (std::size_t i = 0; i < 240; ++i)
        if (timeline.bins()[i].transactions) used = i + 1;
    EXPECT_EQ(used, 132u);  // the last event, at 86 399.023 s, is in bin 131
}

TEST(ReportTest, TimelineEventsBeforeTheStartGoToTheFirstBin) {
    Timeline timeline;
    timeline.add_transaction(kStart);
    timeline.add_finding(kStart - 5'000 * kMs, Severity::Error);
    EXPECT_EQ(timeline.start_ns(), kStart);
    EXPECT_EQ(timeline.bin_width_ns(), 10 * kMs);
    EXPECT_EQ(timeline.bins()[0].transactions, 1u);
    EXPECT_EQ(timeline.bins()[0].errors, 1u);
}

TEST(ReportTest, TrackerTimelineCoversALongSession) {
    SimulatorOptions options = one_slave(3, 1, 3000);  // about 6 s at 2 ms cycles
    auto analysis = analyse_simulation(options);
    const ChannelStats& stats = analysis->station(3);
    const Timeline& timeline = analysis->timelines.of(stats.master, 3);
    ASSERT_GT(stats.transactions.total(), 100u);
    EXPECT_GT(timeline.bin_width_ns(), 10 * kMs);
    EXPECT_EQ(total_of(timeline).transactions, stats.latency_ns.count());
    EXPECT_EQ(stats.latency_ns.count(), stats.transactions.total());
    const std::int64_t span = stats.last_time_ns - timeline.start_ns();
    EXPECT_GE(span / (timeline.bin_width_ns() / 2), 240 / 2);
}

// ---- long lists, nothing checked, dialect hints -------------------------------------------------

TEST(ReportTest, TextAndMarkdownListAtMostAThousandFindingsPerKind) {
    auto analysis = ppo2_with_findings(1'201, 5, 5000);
    const ReportContext context = context_of(*analysis);

    std::string text = render(ReportFormat::Text, context);
    std::vector<std::string> rows =
        lines_after(lines_of(text), "Findings (1206, in capture order)");
    EXPECT_EQ(std::count_if(rows.begin(), rows.end(),
                            [](const std::string& row) {
                                return row.find(" stacked_request ") != std::string::npos &&
                                       row.find("more") == std::string::npos;
                            }),
              1000);
    EXPECT_EQ(std::count_if(rows.begin(), rows.end(),
                            [](const std::string& row) {
                                return row.find(" fdl_retry ") != std::string::npos;
                            }),
              5);
    EXPECT_NE(text.find("  (201 more stacked_request findings not listed: at most 1000 per kind, "
                        "the JSON report lists them all)\n"),
              std::string::npos);
    EXPECT_EQ(text.find("more fdl_retry"), std::string::npos);
    // The first 1000 in capture order: frame 1999 is the last listed, 2000 is not.
    EXPECT_NE(text.find("      1999  "), std::string::npos);
    EXPECT_EQ(text.find("      2000  "), std::string::npos);

    std::string markdown = render(ReportFormat::Markdown, context);
    std::vector<std::string> lines = lines_of(markdown);
    EXPECT_EQ(std::count_if(lines.begin(), lines.end(),
                            [](const std::string& line) {
                                return line.find("| stacked\\_request |") != std::string::npos;
                            }),
              1000);
    EXPECT_EQ(std::count(lines.begin(), lines.end(),
                         "- 201 more stacked\\_request findings not listed: at most 1000 per kind, "
                         "the JSON report lists them all"),
              1);

    auto report = json_report(context);
    ASSERT_TRUE(report);
    EXPECT_EQ((*report)["findings"].items.size(), 1206u);
}

// fopencookie sink that records the most heap in use whenever the report writes.
struct HeapWatch {
    std::size_t peak = 0;
};

ssize_t heap_watch_write(void* cookie, const char*, std::size_t size) {
    auto* watch = static_cast<HeapWatch*>(cookie);
    watch->peak = std::max(watch->peak, mallinfo2().uordblks);
    return static_cast<ssize_t>(size);
}

TEST(ReportTest, JunitStreamsFailuresFromTheLogInsteadOfGatheringThem) {
#if defined(__SANITIZE_ADDRESS__)
    GTEST_SKIP()
        << "mallinfo2() does not see AddressSanitizer's allocator; the release tree runs this";
#endif
    auto analysis = analyse_file("samples/ppo2.pcap");
    const std::string message(200, 'm');
    std::vector<Finding> many;
    for (FindingKind kind : {FindingKind::StackedRequest, FindingKind::MismatchedResponse,
                             FindingKind::ResponseTimeout, FindingKind::FcsError})
        for (std::uint64_t i = 0; i < 10'000; ++i)
            many.push_back(make_finding(kind, 1000 + many.size(), 4, message));
    analysis->log.append(many);
    many.clear();
    many.shrink_to_fit();
    const ReportContext context = context_of(*analysis);

    HeapWatch watch;
    cookie_io_functions_t functions{nullptr, heap_watch_write, nullptr, nullptr};
    FILE* file = fopencookie(&watch, "w", functions);
    ASSERT_NE(file, nullptr);
    const std::size_t before = mallinfo2().uordblks;
    {
        Output out(file);
        render_report(ReportFormat::Junit, context, out);
        EXPECT_TRUE(out.flush());
    }
    std::fclose(file);
    // 40,000 failures of 200-byte messages are over 10 MB; what is written at once stays small.
    ASSERT_GT(watch.peak, 0u);
    EXPECT_LT(watch.peak - std::min(watch.peak, before), std::size_t{2} << 20)
        << "heap in use grew by " << (watch.peak - before) << " bytes";
    // And every failure is there, in capture order per test case.
    auto root = junit_report(context);
    ASSERT_TRUE(root);
    EXPECT_EQ(root->all("failure").size(), 40'000u);
}

std::unique_ptr<Analysis> empty_analysis() {
    auto analysis = std::make_unique<Analysis>();
    analysis->finish();
    analysis->input = InputSummary{"empty.pcap", "pcap", 0, false};
    return analysis;
}

TEST(ReportTest, EmptyCaptureIsNothingCheckedAndFailsInEveryFormat) {
    auto analysis = empty_analysis();
    const ReportContext context = context_of(*analysis);
    EXPECT_TRUE(report_fails(context));
    const std::string verdict =
        "FAIL: nothing checked (no telegrams); 0 errors, 0 warnings, 0 notes (fail on error)";
    EXPECT_NE(render(ReportFormat::Text, context).find("Result:  " + verdict + "\n"),
              std::string::npos);
    EXPECT_NE(render(ReportFormat::Markdown, context).find("**" + verdict + "**"),
              std::string::npos);
    auto html = parse_xml(render(ReportFormat::Html, context), true);
    ASSERT_TRUE(html);
    const XmlNode* shown = find_id(*html, "p", "verdict");
    ASSERT_TRUE(shown);
    EXPECT_TRUE(shown->has_class("fail"));
    EXPECT_EQ(shown->text, verdict);
    auto report = json_report(context);
    ASSERT_TRUE(report);
    EXPECT_EQ((*report)["result"].string(), "fail");
    EXPECT_TRUE((*report)["nothing_checked"].boolean);
    EXPECT_FALSE((*report)["options"]["allow_empty"].boolean);
    // JUnit: no passing suite; one test case that fails and says why.
    auto root = junit_report(context);
    ASSERT_TRUE(root);
    EXPECT_EQ(root->attribute("tests"), "1");
    EXPECT_EQ(root->attribute("failures"), "1");
    auto suites = root->elements("testsuite");
    ASSERT_EQ(suites.size(), 1u);
    EXPECT_EQ(suites[0]->attribute("name"), "capture");
    auto failures = suites[0]->all("failure");
    ASSERT_EQ(failures.size(), 1u);
    EXPECT_EQ(failures[0]->attribute("message"), "nothing checked: no telegrams");
}

TEST(ReportTest, AllowEmptyPassesAnEmptyCaptureButStillSaysNothingWasChecked) {
    auto analysis = empty_analysis();
    ReportContext context = context_of(*analysis);
    context.allow_empty = true;
    EXPECT_FALSE(report_fails(context));
    EXPECT_NE(render(ReportFormat::Text, context)
                  .find("Result:  PASS: nothing checked (no telegrams); 0 errors, 0 warnings, 0 "
                        "notes (fail on error, empty allowed)\n"),
              std::string::npos);
    auto report = json_report(context);
    ASSERT_TRUE(report);
    EXPECT_EQ((*report)["result"].string(), "pass");
    EXPECT_TRUE((*report)["nothing_checked"].boolean);
    auto root = junit_report(context);
    ASSERT_TRUE(root);
    EXPECT_EQ(root->attribute("failures"), "0");
    auto suites = root->elements("testsuite");
    ASSERT_EQ(suites.size(), 1u);
    EXPECT_EQ(suites[0]->attribute("skipped"), "1");
    EXPECT_TRUE(suites[0]->all("failure").empty());
    ASSERT_EQ(suites[0]->all("skipped").size(), 1u);
}

TEST(ReportTest, TelegramsWithoutAParameterChannelAreNothingChecked) {
    // A PPO 3 slave: Data_Exchange, but no PCV (docs/decisions.md, "Reports").
    auto analysis = analyse_simulation(one_slave(6, 3, 50));
    ASSERT_GT(analysis->summary.telegrams(), 100u);
    const ReportContext context = context_of(*analysis);
    EXPECT_TRUE(report_fails(context));
    EXPECT_NE(render(ReportFormat::Text, context)
                  .find("Result:  FAIL: nothing checked (no Data_Exchange telegram with a "
                        "parameter channel); 0 errors, 0 warnings, 0 notes (fail on error)\n"),
              std::string::npos);
    // A slave with a parameter channel is checked, even without a single request.
    auto ppo1 = analyse_simulation(one_slave(6, 1, 3));
    EXPECT_FALSE(report_fails(context_of(*ppo1)));
}

SimulatorOptions profidrive_slave(std::uint64_t cycles) {
    SimulatorOptions options;
    options.seed = 1;
    options.cycles = cycles;
    options.slaves = {SimulatedSlave{3, 1, Dialect::Profidrive}};
    return options;
}

// A PPO 3 slave (2 PCD words, no parameter channel) has no dialect in any format: the dialect
// names the parameter channel's code tables.
TEST(ReportTest, SlaveWithoutAParameterChannelHasNoDialectInEveryFormat) {
    auto analysis = analyse_simulation(one_slave(3, 3, 50));
    const ReportContext context = context_of(*analysis);
    std::string text = render(ReportFormat::Text, context);
    EXPECT_NE(text.find("  layout         PPO 3 (2 PCD words, 4 bytes each way) from Chk_Cfg; no "
                        "parameter channel; ident 0x"),
              std::string::npos)
        << text;
    EXPECT_EQ(text.find("dialect"), std::string::npos) << text;
    std::string markdown = render(ReportFormat::Markdown, context);
    EXPECT_NE(markdown.find("| 3 | 2 | PPO3 | - |"), std::string::npos) << markdown;
    std::string html = render(ReportFormat::Html, context);
    EXPECT_NE(html.find("<tr><th>Dialect</th><td>none (no parameter channel)</td></tr>"),
              std::string::npos);
    EXPECT_NE(html.find("<td>PPO3</td><td>-</td>"), std::string::npos);
    auto report = json_report(context);
    ASSERT_TRUE(report);
    EXPECT_TRUE((*report)["stations"][0]["dialect"].is_null());
    EXPECT_TRUE((*report)["stations"][0]["dialect_hint"].is_null());
}

TEST(ReportTest, ProfidriveSlaveDecodedAsVltGetsOneDialectHintInEveryFormat) {
    auto analysis = analyse_simulation(profidrive_slave(2000));  // decoded as vlt (the default)
    ASSERT_GT(analysis->station(3).findings[static_cast<std::size_t>(FindingKind::UnknownCode)],
              0u);
    const ReportContext context = context_of(*analysis);
    const std::string hint_start = "its parameter-channel codes fit the profidrive dialect (";
    const std::string option = "decode with --dialect 3=profidrive";

    std::string text = render(ReportFormat::Text, context);
    EXPECT_NE(text.find("  dialect hint   " + hint_start), std::string::npos) << text;
    EXPECT_EQ(count_of(text, option), 1u);
    std::string markdown = render(ReportFormat::Markdown, context);
    EXPECT_NE(markdown.find("- Dialect hint: " + hint_start), std::string::npos);
    EXPECT_EQ(count_of(markdown, option), 1u);
    std::string html = render(ReportFormat::Html, context);
    EXPECT_NE(html.find("<tr><th>Dialect hint</th><td>" + hint_start), std::string::npos);
    EXPECT_EQ(count_of(html, option), 1u);
    auto report = json_report(context);
    ASSERT_TRUE(report);
    EXPECT_EQ((*report)["stations"][0]["dialect"].string(), "vlt");
    EXPECT_EQ((*report)["stations"][0]["dialect_hint"].string(), "profidrive");
    auto root = junit_report(context);
    ASSERT_TRUE(root);
    auto cases = root->elements("testsuite")[0]->elements("testcase");
    const XmlNode& unknown = *cases[static_cast<std::size_t>(FindingKind::UnknownCode)];
    ASSERT_EQ(unknown.elements("system-out").size(), 1u);
    EXPECT_NE(unknown.elements("system-out")[0]->text.find("dialect hint: " + hint_start),
              std::string::npos);
    EXPECT_EQ(count_of(render(ReportFormat::Junit, context), option), 1u);
}

TEST(ReportTest, NoDialectHintForTheRightDialectOrForCodesNoDialectDefines) {
    // The same slave decoded as profidrive.
    DecoderOptions options;
    options.station_dialect[3] = Dialect::Profidrive;
    auto right = analyse_simulation(profidrive_slave(2000), options);
    auto report = json_report(context_of(*right));
    ASSERT_TRUE(report);
    EXPECT_EQ((*report)["stations"][0]["dialect"].string(), "profidrive");
    EXPECT_TRUE((*report)["stations"][0]["dialect_hint"].is_null());

    // A vlt slave answering with RC 13, which neither dialect defines: warnings, no hint.
    SimulatorOptions faulty = one_slave(3, 1, 2000);
    faulty.faults = {FaultSpec{FaultKind::UnknownCode, 0.05, std::nullopt, std::nullopt}};
    auto unknown = analyse_simulation(faulty);
    ASSERT_GE(unknown->station(3).findings[static_cast<std::size_t>(FindingKind::UnknownCode)],
              DialectEvidence::kMinimum);
    ASSERT_GE(unknown->summary.dialect_evidence(3).undefined(), DialectEvidence::kMinimum);
    const ReportContext context = context_of(*unknown);
    for (ReportFormat format :
         {ReportFormat::Text, ReportFormat::Markdown, ReportFormat::Html, ReportFormat::Junit})
        EXPECT_EQ(render(format, context).find("--dialect"), std::string::npos)
            << report_format_name(format);
    auto vlt = json_report(context);
    ASSERT_TRUE(vlt);
    EXPECT_TRUE((*vlt)["stations"][0]["dialect_hint"].is_null());
}

// ---- the FC protocol section
// ----------------------------------------------------------------------

// What `dpscope report --bus fc` builds: FcDecoder and FcTracker (cli/pipeline.hpp).
struct FcAnalysis {
    FcAnalysis() {
        using test::fc_parameter;
        using test::fc_process;
        const std::vector<std::pair<std::vector<std::uint8_t>, std::int64_t>> telegrams = {
            {fc_parameter(1, 1, 414), 0},
            {fc_parameter(1, 1, 414, 0, 1500, 0x0607), 4},
            {fc_process(2), 10},
            {fc_process(2, 0x0607), 40},  // late
            {fc_parameter(1, 14, 302, 0, 60000), 50},
            {fc_parameter(1, 7, 302, 0, 2, 0x0607), 54},  // rejected, fault code 2
            {fc_parameter(1, 1, 415), 60},
            {fc_process(2), 70},  // drive 1 did not answer
            {fc_process(2, 0x0607), 72},
            {fc_parameter(0, 2, 302, 0, 10), 80},  // broadcast
        };
        std::uint64_t frame = 0;
        for (const auto& [bytes, ms] : telegrams) {
            const DecodedTelegram& t = decoder.decode(bytes, ms * 1'000'000, ++frame);
            std::span<const Finding> found = tracker.track(t);
            summary.add(t);
            summary.add_findings(found);
            timelines.add(found, tracker.completed());
            if (!found.empty()) log.append(found);
        }
        std::span<const Finding> found = tracker.finish();
        summary.add_findings(found);
        log.append(found);
    }

    ReportContext context() const {
        ReportContext c;
        c.input = InputSummary{"fc.hex", "hex", 0, false};
        c.protocol = Protocol::Fc;
        c.summary = &summary;
        c.decoder = &decoder;
        c.tracker = &tracker;
        c.timelines = &timelines;
        c.findings = &log;
        c.version = "7.8.9-test";
        return c;
    }

    FcDecoder decoder;
    FcTracker tracker;
    Summary summary;
    ChannelTimelines timelines;
    FindingLog log;
};

std::vector<std::string> fc_kind_names() {
    std::vector<std::string> names;
    for (FindingKind kind : fc_finding_kinds())
        names.emplace_back(finding_kind_name(kind));
    return names;
}

TEST(ReportTest, FcSectionInText) {
    FcAnalysis a;
    std::string text = render(ReportFormat::Text, a.context());
    EXPECT_NE(text.find("Bus:     Danfoss FC protocol (RS-485)\n"), std::string::npos) << text;
    EXPECT_NE(text.find("Checks:  time-out 1000 ms, drive response time 20 ms\n"),
              std::string::npos);
    EXPECT_NE(text.find("  BCC errors     0\n"), std::string::npos);
    EXPECT_NE(text.find("\nDrive 1 (FC protocol)\n"), std::string::npos);
    EXPECT_NE(text.find("\nDrive 2 (FC protocol)\n"), std::string::npos);
    EXPECT_NE(text.find("\nBroadcasts (FC protocol)\n"), std::string::npos);
    EXPECT_NE(text.find("  commands       3: 0 process, parameter/text AK 1 x2, AK 14 x1; 0 "
                        "broadcasts\n"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("  outcome        2 answered, 1 unanswered, 0 abandoned, 0 damaged\n"
                        "  responses      2; 0 late (over 20 ms)\n"),
              std::string::npos)
        << text;
    EXPECT_NE(
        text.find(
            "  parameters     PNU 302 (0 reads, 1 write), PNU 414 (1 read, 0 writes), PNU 415 (1 "
            "read, 0 writes)\n"),
        std::string::npos);
    EXPECT_NE(text.find(" PNU 302 fault code 2 (Upper or lower limit is exceeded) 1x\n"),
              std::string::npos);
    EXPECT_NE(text.find("  findings       fc_no_response 1, fc_command_rejected 1\n"),
              std::string::npos);
    EXPECT_NE(text.find("  findings       fc_late_response 1\n"), std::string::npos);
    EXPECT_NE(text.find("  latency ms     min 2.000  mean 16.000  p95 "), std::string::npos)
        << text;
    EXPECT_EQ(text.find("PPO"), std::string::npos);
    EXPECT_NE(text.find("Result:  FAIL: 1 error, 1 warning, 1 note (fail on error)"),
              std::string::npos);
}

TEST(ReportTest, FcSectionInJson) {
    FcAnalysis a;
    auto root = json_report(a.context());
    ASSERT_TRUE(root);
    const Json& r = *root;
    EXPECT_EQ(r["options"]["bus"].string(), "fc");
    EXPECT_EQ(r["options"]["fc_response_ms"].integer(), 20);
    EXPECT_EQ(r["summary"]["bcc_errors"].integer(), 0);
    EXPECT_EQ(r["summary"]["transactions"].integer(), 4);
    EXPECT_EQ(r["bus"]["findings"].keys(), fc_kind_names());
    ASSERT_EQ(r["stations"].items.size(), 3u);
    const Json& broadcasts = r["stations"][0];
    EXPECT_EQ(broadcasts["address"].integer(), 0);
    EXPECT_TRUE(broadcasts["broadcast"].boolean);
    EXPECT_EQ(broadcasts["broadcasts"].integer(), 1);
    const Json& one = r["stations"][1];
    EXPECT_EQ(one["bus"].string(), "fc");
    EXPECT_EQ(one["address"].integer(), 1);
    EXPECT_EQ(one["commands"].integer(), 3);
    EXPECT_EQ(one["commands_by_ak"]["14"].integer(), 1);
    EXPECT_EQ(one["no_responses"].integer(), 1);
    // Every command has one outcome: commands = transactions + no_responses + abandoned +
    // damaged + not_judged (+ broadcasts).
    EXPECT_EQ(one["transactions"].integer(), 2);
    EXPECT_EQ(one["abandoned"].integer(), 0);
    EXPECT_EQ(one["damaged"].integer(), 0);
    EXPECT_EQ(one["not_judged"].integer(), 0);
    EXPECT_EQ(one["damaged_commands"].integer(), 0);
    EXPECT_EQ(one["damaged_responses"].integer(), 0);
    for (const Json& station : r["stations"].items)
        EXPECT_EQ(station["commands"].integer(),
                  station["broadcasts"].integer() + station["transactions"].integer() +
                      station["no_responses"].integer() + station["abandoned"].integer() +
                      station["damaged"].integer() + station["not_judged"].integer());
    EXPECT_EQ(one["late"].integer(), 0);
    EXPECT_EQ(one["findings"].keys(), fc_kind_names());
    EXPECT_EQ(one["findings"]["fc_command_rejected"].integer(), 1);
    ASSERT_EQ(one["rejections"].items.size(), 1u);
    EXPECT_EQ(one["rejections"][0]["pnu"].integer(), 302);
    EXPECT_EQ(one["rejections"][0]["fault_code"].integer(), 2);
    EXPECT_EQ(one["rejections"][0]["fault_text"].string(), "Upper or lower limit is exceeded");
    ASSERT_EQ(one["parameters"].items.size(), 3u);
    EXPECT_EQ(one["parameters"][0]["writes"].integer(), 1);
    const Json& two = r["stations"][2];
    EXPECT_EQ(two["late"].integer(), 1);
    EXPECT_EQ(number_of(two["latency_ms"]["max"]), 30.0);
    EXPECT_EQ(two["findings"]["fc_late_response"].integer(), 1);
}

TEST(ReportTest, FcSectionInMarkdownAndHtml) {
    FcAnalysis a;
    std::string md = render(ReportFormat::Markdown, a.context());
    EXPECT_NE(md.find("- Bus: Danfoss FC protocol (RS-485)\n"), std::string::npos) << md;
    EXPECT_NE(md.find("| telegrams | bytes skipped | BCC errors |"), std::string::npos);
    EXPECT_NE(md.find("## Drives\n"), std::string::npos);
    EXPECT_NE(md.find("\n### Drive 1 (FC protocol)\n"), std::string::npos);
    EXPECT_NE(md.find("| address | commands | answered | unanswered | abandoned | damaged | not "
                      "judged | late |"),
              std::string::npos)
        << md;
    EXPECT_NE(md.find("- Outcome: 2 answered, 1 unanswered, 0 abandoned, 0 damaged\n"),
              std::string::npos)
        << md;
    EXPECT_NE(md.find("- Rejected: PNU 302 fault code 2 (Upper or lower limit is exceeded), 1x\n"),
              std::string::npos);
    EXPECT_EQ(md.find("## Slaves"), std::string::npos);
    std::string html = render(ReportFormat::Html, a.context());
    auto doc = parse_xml(html, true);
    ASSERT_TRUE(doc) << html;
    EXPECT_NE(html.find("<h2>Drive 1 (FC protocol)</h2>"), std::string::npos);
    EXPECT_NE(html.find("<th class=\"n\">abandoned</th><th class=\"n\">damaged</th><th "
                        "class=\"n\">not judged</th>"),
              std::string::npos)
        << html;
    EXPECT_NE(html.find("<tr><td class=\"n\"><a href=\"#drive-1\">1</a></td><td class=\"n\">3</td>"
                        "<td class=\"n\">2</td><td class=\"n\">1</td><td class=\"n\">0</td>"
                        "<td class=\"n\">0</td><td class=\"n\">0</td>"),
              std::string::npos)
        << html;
    EXPECT_NE(html.find("<th>Outcome</th><td>2 answered, 1 unanswered, 0 abandoned, 0 "
                        "damaged</td>"),
              std::string::npos)
        << html;
    EXPECT_NE(html.find("<td class=\"n\">302</td><td class=\"n\">2</td><td>Upper or lower limit "
                        "is exceeded</td>"),
              std::string::npos);
    EXPECT_NE(html.find("Danfoss FC protocol (RS-485)"), std::string::npos);
    EXPECT_NE(html.find("<td>fc_late_response</td>"), std::string::npos);
    EXPECT_NE(html.find("aria-label=\"latency histogram of drive 2\""), std::string::npos);
    EXPECT_NE(html.find("aria-label=\"timeline of drive 1\""), std::string::npos);
}

TEST(ReportTest, JunitFcSuitePerAddressWithACasePerFcRule) {
    FcAnalysis a;
    auto root = junit_report(a.context());
    ASSERT_TRUE(root);
    auto suites = root->elements("testsuite");
    ASSERT_EQ(suites.size(), 3u);
    EXPECT_EQ(suites[0]->attribute("name"), "FC broadcasts");
    EXPECT_EQ(suites[1]->attribute("name"), "FC drive 1");
    EXPECT_EQ(suites[2]->attribute("name"), "FC drive 2");
    const std::vector<std::string> kinds = fc_kind_names();
    for (const XmlNode* suite : suites) {
        auto cases = suite->elements("testcase");
        ASSERT_EQ(cases.size(), kinds.size());
        for (std::size_t k = 0; k < cases.size(); ++k)
            EXPECT_EQ(cases[k]->attribute("name").substr(0, kinds[k].size() + 1), kinds[k] + ":");
    }
    EXPECT_EQ(suites[1]->attribute("failures"), "1");  // fc_no_response
    EXPECT_EQ(suites[1]->elements("testcase")[0]->attribute("classname"), "dpscope.fc.drive_1");
    EXPECT_EQ(suites[2]->attribute("failures"), "0");  // a late answer is a warning
    EXPECT_EQ(root->attribute("failures"), "1");
    // The drive's commands by outcome, as in the JSON report.
    ASSERT_EQ(suites[1]->elements("properties").size(), 1u);
    std::map<std::string, std::string> properties;
    for (const XmlNode* p : suites[1]->elements("properties")[0]->elements("property"))
        properties[p->attribute("name")] = p->attribute("value");
    EXPECT_EQ(properties, (std::map<std::string, std::string>{{"commands", "3"},
                                                              {"broadcasts", "0"},
                                                              {"transactions", "2"},
                                                              {"no_responses", "1"},
                                                              {"abandoned", "0"},
                                                              {"damaged", "0"},
                                                              {"not_judged", "0"},
                                                              {"responses", "2"}}));
}

TEST(ReportTest, ProfibusReportsListNoFcKinds) {
    auto root = json_report(context_of(faults()));
    ASSERT_TRUE(root);
    std::vector<std::string> dp = dp_kind_names();
    EXPECT_EQ((*root)["bus"]["findings"].keys(), dp);
    EXPECT_EQ((*root)["stations"][0]["findings"].keys(), dp);
    EXPECT_EQ((*root)["options"].find("bus"), nullptr);
    for (ReportFormat format : {ReportFormat::Text, ReportFormat::Markdown, ReportFormat::Html,
                                ReportFormat::Junit, ReportFormat::Json}) {
        std::string text = render(format, context_of(faults()));
        EXPECT_EQ(text.find("fc_"), std::string::npos) << report_format_name(format);
        EXPECT_EQ(text.find("FC protocol"), std::string::npos) << report_format_name(format);
        EXPECT_EQ(text.find("vlt2000"), std::string::npos) << report_format_name(format);
        EXPECT_EQ(text.find("VLT 2000"), std::string::npos) << report_format_name(format);
    }
}

// ---- the VLT 2000 section
// ----------------------------------------------------------------------

// A VLT 2000 telegram (22 characters) with its checksum: the sum of offsets 1..18 mod 100, or
// `checksum` as given ("??").
std::string vlt2000(int address, char letter, int parameter, long value = 0, int decimals = 0,
                    std::string_view word = "@@@@", std::string_view checksum = {}) {
    std::string t =
        fmt::format("<{:02}{}{}{:04}+{:05}{}", address, letter, word, parameter, value, decimals);
    unsigned sum = 0;
    for (std::size_t i = 1; i < t.size(); ++i)
        sum += static_cast<unsigned char>(t[i]);
    t += checksum.empty() ? fmt::format("{:02}", sum % 100) : std::string(checksum);
    return t + '>';
}

// A drive's reply: decimals 9 (failed), the reason code in bytes 17-18; none: "--" there.
std::string vlt2000_failed(int address, char letter, int parameter, int reason = -1) {
    std::string t = vlt2000(address, letter, parameter, reason < 0 ? 0 : reason, 9);
    if (reason >= 0) return t;
    t[16] = '-';
    t[17] = '-';
    unsigned sum = 0;
    for (std::size_t i = 1; i <= 18; ++i)
        sum += static_cast<unsigned char>(t[i]);
    t.replace(19, 2, fmt::format("{:02}", sum % 100));
    return t;
}

// What `dpscope report --bus vlt2000` builds: Vlt2000Decoder and Vlt2000Tracker
// (cli/pipeline.hpp), over `telegrams` (time in ms; < 0: none).
struct Vlt2000Analysis {
    using Telegrams = std::vector<std::pair<std::string, std::int64_t>>;

    // Drive 01: R answered, U failed (reason 04), R unanswered, R failed without a reason; drive
    // 02: C answered twice, a damaged C (nothing replies), an R with the checksum off; a broadcast
    // U.
    static Telegrams mixed() {
        std::string damaged = vlt2000(2, 'C', 0);
        damaged[20] = damaged[20] == '0' ? '1' : '0';
        return {
            {vlt2000(1, 'R', 102), 0},
            {vlt2000(1, 'R', 102, 1500, 1, "GH@@"), 3},
            {vlt2000(1, 'U', 516, 800), 10},
            {vlt2000_failed(1, 'U', 516, 4), 15},  // read only
            {vlt2000(2, 'C', 0, 0, 0, "OGD@"), 20},
            {vlt2000(2, 'C', 0, 0, 0, "GHK@"), 40},
            {vlt2000(1, 'R', 999), 50},
            {vlt2000(2, 'C', 0, 0, 0, "OGD@"), 60},  // drive 01 did not reply
            {vlt2000(2, 'C', 0, 0, 0, "GHK@"), 62},
            {vlt2000(0, 'U', 516, 100), 70},  // broadcast
            {damaged, 80},
            {vlt2000(2, 'R', 102, 0, 0, "@@@@", "??"), 90},
            {vlt2000(2, 'R', 102, 7, 0, "GH@@", "??"), 95},
            {vlt2000(1, 'R', 5), 100},
            {vlt2000_failed(1, 'R', 5), 101},
        };
    }

    explicit Vlt2000Analysis(const Telegrams& telegrams = mixed()) {
        std::uint64_t frame = 0;
        for (const auto& [text, ms] : telegrams) {
            bytes.assign(text.begin(), text.end());
            const DecodedTelegram& t =
                decoder.decode(bytes, ms < 0 ? kNoTime : ms * 1'000'000, ++frame);
            std::span<const Finding> found = tracker.track(t);
            summary.add(t);
            summary.add_findings(found);
            timelines.add(found, tracker.completed());
            if (!found.empty()) log.append(found);
        }
        std::span<const Finding> found = tracker.finish();
        summary.add_findings(found);
        log.append(found);
    }

    ReportContext context() const {
        ReportContext c;
        c.input = InputSummary{"vlt2000.pcap", "pcap", 0, false};
        c.protocol = Protocol::Vlt2000;
        c.summary = &summary;
        c.decoder = &decoder;
        c.tracker = &tracker;
        c.timelines = &timelines;
        c.findings = &log;
        c.version = "7.8.9-test";
        return c;
    }

    Vlt2000Decoder decoder;
    Vlt2000Tracker tracker;
    Summary summary;
    ChannelTimelines timelines;
    FindingLog log;
    std::vector<std::uint8_t> bytes;
};

std::vector<std::string> vlt2000_kind_names() {
    std::vector<std::string> names;
    for (FindingKind kind : vlt2000_finding_kinds())
        names.emplace_back(finding_kind_name(kind));
    return names;
}

TEST(ReportTest, Vlt2000SectionInText) {
    Vlt2000Analysis a;
    std::string text = render(ReportFormat::Text, a.context());
    EXPECT_NE(text.find("Bus:     Danfoss VLT 2000 serial telegram (ASCII)\n"), std::string::npos)
        << text;
    EXPECT_NE(text.find("Checks:  time-out 1000 ms, checksums checked\n"), std::string::npos);
    EXPECT_NE(text.find("Result:  FAIL: 2 errors, 0 warnings, 3 notes (fail on error)\n"),
              std::string::npos);
    EXPECT_NE(text.find("  bad checksums  1\n"), std::string::npos);
    EXPECT_NE(text.find("  transactions   6\n"), std::string::npos);
    EXPECT_NE(text.find("\nBroadcasts (VLT 2000)\n  commands       1: U 1; 1 broadcast\n"
                        "  replies        0 (nobody replies to a broadcast)\n"),
              std::string::npos);
    EXPECT_NE(text.find("\nDrive 01 (VLT 2000)\n"
                        "  commands       4: U 1, R 3; 0 broadcasts\n"
                        "  outcome        3 answered, 1 unanswered, 0 abandoned, 0 damaged\n"
                        "  replies        3\n"
                        "  failed         2: reason 04 (read only, e.g. factory set-up selected) "
                        "1x, no reason code 1x\n"
                        "  checksums      0 checksum errors, 0 telegrams with the check off "
                        "(\"??\")\n"
                        "  latency ms     min 1.000  mean 3.000  p95 "),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("  parameters     5 (1 read, 0 writes), 102 (1 read, 0 writes), 516 (0 "
                        "reads, 1 write), 999 (1 read, 0 writes)\n"
                        "  findings       vlt2000_no_response 1, vlt2000_command_failed 2\n"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("\nDrive 02 (VLT 2000)\n"
                        "  commands       4: R 1, C 2, 1 damaged; 0 broadcasts\n"
                        "  outcome        3 answered, 0 unanswered, 0 abandoned, 1 damaged\n"
                        "  replies        3\n"
                        "  failed         0: none\n"
                        "  checksums      1 checksum error, 2 telegrams with the check off "
                        "(\"??\")\n"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("  findings       vlt2000_checksum_error 1, vlt2000_checksum_disabled 1\n"),
              std::string::npos);
    // In address order: the broadcasts first.
    EXPECT_LT(text.find("Broadcasts (VLT 2000)"), text.find("Drive 01 (VLT 2000)"));
    EXPECT_LT(text.find("Drive 01 (VLT 2000)"), text.find("Drive 02 (VLT 2000)"));
    for (std::string_view other : {"PPO", "fc_", "FC protocol", "FCS errors", "RC 8"})
        EXPECT_EQ(text.find(other), std::string::npos) << other;
}

const std::vector<std::string> kVlt2000StationKeys = {"bus",
                                                      "address",
                                                      "broadcast",
                                                      "telegrams",
                                                      "commands",
                                                      "damaged_commands",
                                                      "commands_by_letter",
                                                      "broadcasts",
                                                      "replies",
                                                      "damaged_replies",
                                                      "transactions",
                                                      "no_responses",
                                                      "abandoned",
                                                      "damaged",
                                                      "not_judged",
                                                      "failed",
                                                      "failures",
                                                      "failures_without_reason",
                                                      "checksum_errors",
                                                      "checksum_disabled",
                                                      "latency_ms",
                                                      "outcomes",
                                                      "parameters",
                                                      "parameters_not_counted",
                                                      "findings"};

TEST(ReportTest, Vlt2000SectionInJson) {
    Vlt2000Analysis a;
    auto root = json_report(a.context());
    ASSERT_TRUE(root);
    const Json& r = *root;
    EXPECT_EQ(r["options"].keys(),
              (std::vector<std::string>{"bus", "timeout_ms", "vlt2000_checksum", "strict",
                                        "fail_on", "allow_empty", "stations"}));
    EXPECT_EQ(r["options"]["bus"].string(), "vlt2000");
    EXPECT_EQ(r["options"]["vlt2000_checksum"].string(), "check");
    EXPECT_EQ(r["summary"].keys(), (std::vector<std::string>{"telegrams", "checksum_errors",
                                                             "transactions", "findings"}));
    EXPECT_EQ(r["summary"]["telegrams"].integer(), 15);
    EXPECT_EQ(r["summary"]["checksum_errors"].integer(), 1);
    EXPECT_EQ(r["summary"]["transactions"].integer(), 6);
    EXPECT_EQ(r["summary"]["findings"]["error"].integer(), 2);
    EXPECT_EQ(r["summary"]["findings"]["note"].integer(), 3);
    EXPECT_EQ(r["result"].string(), "fail");
    EXPECT_FALSE(r["nothing_checked"].boolean);
    EXPECT_EQ(r["bus"]["findings"].keys(), vlt2000_kind_names());
    ASSERT_EQ(r["stations"].items.size(), 3u);
    for (const Json& station : r["stations"].items) {
        EXPECT_EQ(station.keys(), kVlt2000StationKeys);
        EXPECT_EQ(station["bus"].string(), "vlt2000");
        EXPECT_EQ(station["findings"].keys(), vlt2000_kind_names());
        EXPECT_EQ(station["commands_by_letter"].keys(),
                  (std::vector<std::string>{"U", "R", "C", "I"}));
        EXPECT_EQ(station["outcomes"].keys(),
                  (std::vector<std::string>{"positive", "failed", "mismatched", "unexpected"}));
    }
    const Json& broadcasts = r["stations"][0];
    EXPECT_EQ(broadcasts["address"].integer(), 0);
    EXPECT_TRUE(broadcasts["broadcast"].boolean);
    EXPECT_EQ(broadcasts["broadcasts"].integer(), 1);
    EXPECT_TRUE(broadcasts["latency_ms"].is_null());
    const Json& one = r["stations"][1];
    EXPECT_EQ(one["address"].integer(), 1);
    EXPECT_FALSE(one["broadcast"].boolean);
    EXPECT_EQ(one["commands"].integer(), 4);
    EXPECT_EQ(one["commands_by_letter"]["R"].integer(), 3);
    EXPECT_EQ(one["commands_by_letter"]["U"].integer(), 1);
    EXPECT_EQ(one["commands_by_letter"]["I"].integer(), 0);
    EXPECT_EQ(one["replies"].integer(), 3);
    EXPECT_EQ(one["transactions"].integer(), 3);
    EXPECT_EQ(one["no_responses"].integer(), 1);
    EXPECT_EQ(one["failed"].integer(), 2);
    ASSERT_EQ(one["failures"].items.size(), 1u);
    EXPECT_EQ(one["failures"][0].keys(),
              (std::vector<std::string>{"reason", "reason_text", "count"}));
    EXPECT_EQ(one["failures"][0]["reason"].integer(), 4);
    EXPECT_EQ(one["failures"][0]["reason_text"].string(),
              "read only, e.g. factory set-up selected");
    EXPECT_EQ(one["failures_without_reason"].integer(), 1);
    EXPECT_EQ(number_of(one["latency_ms"]["min"]), 1.0);
    EXPECT_EQ(number_of(one["latency_ms"]["mean"]), 3.0);
    EXPECT_EQ(number_of(one["latency_ms"]["max"]), 5.0);
    EXPECT_EQ(one["outcomes"]["positive"].integer(), 1);
    EXPECT_EQ(one["outcomes"]["failed"].integer(), 2);
    ASSERT_EQ(one["parameters"].items.size(), 4u);
    EXPECT_EQ(one["parameters"][2]["pnu"].integer(), 516);
    EXPECT_EQ(one["parameters"][2]["writes"].integer(), 1);
    EXPECT_EQ(one["findings"]["vlt2000_command_failed"].integer(), 2);
    EXPECT_EQ(one["findings"]["vlt2000_no_response"].integer(), 1);
    const Json& two = r["stations"][2];
    // Every command has one outcome: the damaged C is counted, its outcome "damaged".
    EXPECT_EQ(two["commands"].integer(), 4);
    EXPECT_EQ(two["damaged_commands"].integer(), 1);
    EXPECT_EQ(two["transactions"].integer(), 3);
    EXPECT_EQ(two["no_responses"].integer(), 0);
    EXPECT_EQ(two["abandoned"].integer(), 0);
    EXPECT_EQ(two["damaged"].integer(), 1);
    EXPECT_EQ(two["not_judged"].integer(), 0);
    EXPECT_EQ(two["replies"].integer(), 3);
    EXPECT_EQ(two["damaged_replies"].integer(), 0);
    EXPECT_EQ(two["checksum_errors"].integer(), 1);
    EXPECT_EQ(two["checksum_disabled"].integer(), 2);
    EXPECT_EQ(number_of(two["latency_ms"]["max"]), 20.0);
    EXPECT_EQ(two["findings"]["vlt2000_checksum_error"].integer(), 1);
    EXPECT_EQ(two["findings"]["vlt2000_checksum_disabled"].integer(), 1);
    // Every finding listed, with its station.
    ASSERT_EQ(r["findings"].items.size(), 5u);
    EXPECT_EQ(r["findings"][0]["kind"].string(), "vlt2000_command_failed");
    EXPECT_EQ(r["findings"][0]["slave"].integer(), 1);
    EXPECT_EQ(r["findings"][0]["pnu"].integer(), 516);
}

TEST(ReportTest, Vlt2000SectionInMarkdownAndHtml) {
    Vlt2000Analysis a;
    std::string md = render(ReportFormat::Markdown, a.context());
    EXPECT_NE(md.find("- Bus: Danfoss VLT 2000 serial telegram (ASCII)\n"), std::string::npos)
        << md;
    EXPECT_NE(md.find("- Checks: time-out 1000 ms, checksums checked\n"), std::string::npos);
    EXPECT_NE(md.find("| telegrams | bytes skipped | bad checksums |"), std::string::npos);
    EXPECT_NE(md.find("## Drives\n\n| address | commands | answered | unanswered | abandoned | "
                      "damaged | not judged | failed |"),
              std::string::npos);
    EXPECT_NE(md.find("| 01 | 4 | 3 | 1 | 0 | 0 | 0 | 2 | min 1.000  mean 3.000  p95 "),
              std::string::npos)
        << md;
    EXPECT_NE(md.find("| 02 | 4 | 3 | 0 | 0 | 1 | 0 | 0 | "), std::string::npos) << md;
    EXPECT_NE(md.find("| broadcast | 1 | 0 | 0 | 0 | 0 | 0 | 0 | - | 0 | none |\n"),
              std::string::npos)
        << md;
    EXPECT_NE(md.find("\n### Drive 01 (VLT 2000)\n\n- Commands: 4: U 1, R 3; 0 broadcasts\n"
                      "- Outcome: 3 answered, 1 unanswered, 0 abandoned, 0 damaged\n"
                      "- Replies: 3\n"),
              std::string::npos)
        << md;
    EXPECT_NE(md.find("- Failed: reason code 04 (read only, e.g. factory set-up selected), 1x\n"
                      "- Failed: no reason code, 1x\n"),
              std::string::npos);
    EXPECT_NE(
        md.find("- Findings: vlt2000\\_checksum\\_error 1, vlt2000\\_checksum\\_disabled 1\n"),
        std::string::npos);
    EXPECT_EQ(md.find("## Slaves"), std::string::npos);

    std::string html = render(ReportFormat::Html, a.context());
    auto doc = parse_xml(html, true);
    ASSERT_TRUE(doc) << html;
    EXPECT_NE(html.find("Danfoss VLT 2000 serial telegram (ASCII) &middot; time-out 1000 ms, "
                        "checksums checked"),
              std::string::npos);
    EXPECT_NE(html.find("<div class=\"n\">3</div><div class=\"l\">drives</div>"),
              std::string::npos);
    EXPECT_NE(html.find("<div class=\"l\">bad checksums</div>"), std::string::npos);
    EXPECT_NE(html.find("<h2>Drive 01 (VLT 2000)</h2>"), std::string::npos);
    EXPECT_NE(html.find("<h2>Broadcasts (VLT 2000)</h2>"), std::string::npos);
    EXPECT_NE(html.find("<a href=\"#drive-01\">01</a>"), std::string::npos);
    EXPECT_NE(html.find("id=\"drive-01\""), std::string::npos);
    EXPECT_NE(html.find("<tr><td class=\"n\">04</td><td>read only, e.g. factory set-up "
                        "selected</td><td class=\"n\">1</td></tr>"),
              std::string::npos);
    EXPECT_NE(html.find("<tr><td class=\"n\">-</td><td>no reason code</td><td class=\"n\">1</td>"),
              std::string::npos);
    EXPECT_NE(html.find("<tr><td class=\"n\">516</td><td class=\"n\">0</td><td "
                        "class=\"n\">1</td></tr>"),
              std::string::npos);
    EXPECT_NE(html.find("<td>vlt2000_checksum_error</td>"), std::string::npos);
    EXPECT_NE(html.find("aria-label=\"latency histogram of drive 02\""), std::string::npos);
    EXPECT_NE(html.find("aria-label=\"timeline of drive 01\""), std::string::npos);
    // The sections' anchors are unique.
    std::vector<std::string> ids;
    for (const XmlNode* section : doc->all("section", "station"))
        ids.push_back(section->attribute("id"));
    EXPECT_EQ(ids, (std::vector<std::string>{"drive-00", "drive-01", "drive-02"}));
}

TEST(ReportTest, JunitVlt2000SuitePerAddressWithACasePerRule) {
    Vlt2000Analysis a;
    auto root = junit_report(a.context());
    ASSERT_TRUE(root);
    auto suites = root->elements("testsuite");
    ASSERT_EQ(suites.size(), 3u);
    EXPECT_EQ(suites[0]->attribute("name"), "VLT 2000 broadcasts");
    EXPECT_EQ(suites[1]->attribute("name"), "VLT 2000 drive 01");
    EXPECT_EQ(suites[2]->attribute("name"), "VLT 2000 drive 02");
    const std::vector<std::string> kinds = vlt2000_kind_names();
    for (const XmlNode* suite : suites) {
        auto cases = suite->elements("testcase");
        ASSERT_EQ(cases.size(), kinds.size());
        for (std::size_t k = 0; k < cases.size(); ++k)
            EXPECT_EQ(cases[k]->attribute("name").substr(0, kinds[k].size() + 1), kinds[k] + ":");
    }
    EXPECT_EQ(suites[1]->elements("testcase")[0]->attribute("classname"),
              "dpscope.vlt2000.drive_01");
    EXPECT_EQ(suites[1]->attribute("failures"), "1");  // vlt2000_no_response
    EXPECT_EQ(suites[2]->attribute("failures"), "1");  // vlt2000_checksum_error
    EXPECT_EQ(suites[0]->attribute("failures"), "0");
    EXPECT_EQ(root->attribute("failures"), "2");
    // Drive 02's commands by outcome, as in the JSON report: its damaged C is "damaged".
    ASSERT_EQ(suites[2]->elements("properties").size(), 1u);
    std::map<std::string, std::string> properties;
    for (const XmlNode* p : suites[2]->elements("properties")[0]->elements("property"))
        properties[p->attribute("name")] = p->attribute("value");
    EXPECT_EQ(properties, (std::map<std::string, std::string>{{"commands", "4"},
                                                              {"broadcasts", "0"},
                                                              {"transactions", "3"},
                                                              {"no_responses", "0"},
                                                              {"abandoned", "0"},
                                                              {"damaged", "1"},
                                                              {"not_judged", "0"},
                                                              {"replies", "3"}}));
    EXPECT_EQ(root->attribute("tests"), std::to_string(3 * kinds.size()));
    // The notes are below the failure threshold, said in the case.
    const XmlNode& failed = *suites[1]->elements("testcase")[static_cast<std::size_t>(
        std::find(kinds.begin(), kinds.end(), "vlt2000_command_failed") - kinds.begin())];
    ASSERT_EQ(failed.elements("system-out").size(), 1u);
    EXPECT_EQ(failed.elements("system-out")[0]->text,
              "2 note findings below the failure threshold");
}

TEST(ReportTest, Vlt2000ReportWithoutTimestampsAndWithoutChecksums) {
    Vlt2000Analysis::Telegrams untimed = Vlt2000Analysis::mixed();
    for (auto& telegram : untimed)
        telegram.second = -1;
    Vlt2000Analysis a(untimed);
    ReportContext c = a.context();
    Vlt2000DecoderOptions unchecked;  // --vlt2000-checksum ignore, as the report reads it
    unchecked.check_checksum = false;
    const Vlt2000Decoder decoder(unchecked);
    c.decoder = &decoder;
    std::string text = render(ReportFormat::Text, c);
    EXPECT_NE(text.find("Checks:  time-outs not judged (no timestamps), checksums not checked "
                        "(--vlt2000-checksum ignore)\n"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("  latency ms     not measured (no timestamps)\n"), std::string::npos);
    auto root = json_report(c);
    ASSERT_TRUE(root);
    EXPECT_EQ((*root)["options"]["vlt2000_checksum"].string(), "ignore");
    EXPECT_TRUE((*root)["stations"][1]["latency_ms"].is_null());
    std::string html = render(ReportFormat::Html, c);
    EXPECT_TRUE(parse_xml(html, true));
    EXPECT_NE(html.find("The capture carries no timestamps."), std::string::npos);
}

TEST(ReportTest, Vlt2000NothingCheckedWhenNoCommandWasAnswered) {
    // Broadcasts and a command nobody answered: nothing was paired.
    Vlt2000Analysis a({{vlt2000(0, 'U', 516, 100), 0},
                       {vlt2000(0, 'C', 0, 0, 0, "OGD@"), 10},
                       {vlt2000(3, 'R', 102), 20}});
    ReportContext c = a.context();
    std::string text = render(ReportFormat::Text, c);
    EXPECT_NE(text.find("Result:  FAIL: nothing checked (no command answered by a drive); 0 "
                        "errors, 0 warnings, 0 notes (fail on error)\n"),
              std::string::npos)
        << text;
    auto junit = junit_report(c);
    ASSERT_TRUE(junit);
    auto suites = junit->elements("testsuite");
    ASSERT_GE(suites.size(), 1u);
    EXPECT_EQ(suites[0]->attribute("name"), "capture");
    EXPECT_EQ(suites[0]->elements("testcase")[0]->attribute("name"),
              "VLT 2000: the capture holds commands answered by drives");
    c.allow_empty = true;
    EXPECT_FALSE(report_fails(c));
    EXPECT_NE(render(ReportFormat::Markdown, c)
                  .find("**PASS: nothing checked (no command answered "
                        "by a drive); 0 errors, 0 warnings, 0 notes "
                        "(fail on error, empty allowed)**"),
              std::string::npos);
    // A station filter naming a drive that answered nothing.
    Vlt2000Analysis b;
    ReportContext filtered = b.context();
    filtered.stations = {0};
    EXPECT_NE(render(ReportFormat::Text, filtered)
                  .find("nothing checked (no command answered by the selected drives)"),
              std::string::npos);
}

TEST(ReportTest, Vlt2000StationFilterKeepsTheDrivesChosen) {
    Vlt2000Analysis a;
    ReportContext c = a.context();
    c.stations = {2};
    auto root = json_report(c);
    ASSERT_TRUE(root);
    ASSERT_EQ((*root)["stations"].items.size(), 1u);
    EXPECT_EQ((*root)["stations"][0]["address"].integer(), 2);
    EXPECT_EQ((*root)["summary"]["transactions"].integer(), 3);
    EXPECT_EQ((*root)["summary"]["checksum_errors"].integer(), 1);
    ASSERT_EQ((*root)["findings"].items.size(), 2u);
    EXPECT_EQ((*root)["result"].string(), "fail");
    std::string text = render(ReportFormat::Text, c);
    EXPECT_EQ(text.find("Drive 01"), std::string::npos);
    EXPECT_NE(text.find("Drive 02 (VLT 2000)"), std::string::npos);
}

TEST(ReportTest, Vlt2000ReportsListOnlyTheirBussKinds) {
    // A finding no station is named for: the bus section, with the VLT 2000 kinds.
    std::string no_address = vlt2000(1, 'R', 102);
    no_address[1] = 'x';
    Vlt2000Analysis::Telegrams telegrams = Vlt2000Analysis::mixed();
    telegrams.emplace_back(no_address, 200);
    Vlt2000Analysis b(telegrams);
    auto root = json_report(b.context());
    ASSERT_TRUE(root);
    EXPECT_EQ((*root)["bus"]["findings"].keys(), vlt2000_kind_names());
    EXPECT_EQ((*root)["bus"]["findings"]["vlt2000_checksum_error"].integer(), 1);
    for (ReportFormat format : {ReportFormat::Text, ReportFormat::Markdown, ReportFormat::Html,
                                ReportFormat::Junit, ReportFormat::Json}) {
        std::string text = render(format, b.context());
        EXPECT_EQ(text.find("fc_"), std::string::npos) << report_format_name(format);
        EXPECT_EQ(text.find("FC protocol"), std::string::npos) << report_format_name(format);
        EXPECT_EQ(text.find("dpv1_"), std::string::npos) << report_format_name(format);
        EXPECT_EQ(text.find("\"response_timeout\""), std::string::npos)
            << report_format_name(format);
        EXPECT_NE(text.find(format == ReportFormat::Markdown ? "vlt2000\\_checksum\\_error"
                                                             : "vlt2000_checksum_error"),
                  std::string::npos)
            << report_format_name(format);
    }
    auto junit = junit_report(b.context());
    ASSERT_TRUE(junit);
    const XmlNode* bus = junit->elements("testsuite").back();
    EXPECT_EQ(bus->attribute("name"), "bus");
    EXPECT_EQ(bus->elements("testcase").size(), vlt2000_kind_names().size());
    // An FC report names no VLT 2000 kind.
    FcAnalysis fc;
    for (ReportFormat format : {ReportFormat::Text, ReportFormat::Markdown, ReportFormat::Html,
                                ReportFormat::Junit, ReportFormat::Json}) {
        std::string text = render(format, fc.context());
        EXPECT_EQ(text.find("vlt2000"), std::string::npos) << report_format_name(format);
        EXPECT_EQ(text.find("VLT 2000"), std::string::npos) << report_format_name(format);
    }
}

// ---- the bus-health section -----------------------------------------------------------------

ReportContext with_health(const BusHealth& h) {
    ReportContext context = context_of(clean());
    context.health = &h;
    return context;
}

TEST(ReportTest, NoBusHealthSectionWithoutHealth) {
    const ReportContext context = context_of(clean());
    EXPECT_EQ(render(ReportFormat::Text, context).find("Bus health"), std::string::npos);
    EXPECT_EQ(render(ReportFormat::Markdown, context).find("Bus health"), std::string::npos);
    EXPECT_EQ(render(ReportFormat::Html, context).find("bus-health"), std::string::npos);
    EXPECT_EQ(render(ReportFormat::Json, context).find("bus_health"), std::string::npos);
    EXPECT_EQ(render(ReportFormat::Junit, context).find("bus health"), std::string::npos);
}

TEST(ReportTest, BusHealthSectionInText) {
    const BusHealth h = test::health_sample();
    const std::string text = render(ReportFormat::Text, with_health(h));
    const std::size_t section = text.find("\nBus health\n  Capture:   2024-01-01T00:00:00");
    ASSERT_NE(section, std::string::npos) << text;
    const std::size_t findings = text.find("\nFindings (");
    EXPECT_LT(section, findings);
    EXPECT_NE(text.find("  Bus load:  25.00 % at 1500000 baud, idle 1.500000 s\n", section),
              std::string::npos);
    EXPECT_NE(
        text.find("  Segment:   bad\n             - lost_events_bad: 1 (bad from 1)\n", section),
        std::string::npos)
        << text;
    for (std::string_view title :
         {"\n  Live list (3 stations)\n", "\n  Slaves (as asked", "\n  Masters (times in ms)\n",
          "\n  Verdicts\n", "\n  Thresholds (other than the defaults)\n"}) {
        const std::size_t at = text.find(title, section);
        EXPECT_TRUE(at != std::string::npos && at < findings) << title;
    }
    // The result stays the findings' (the verdicts are the section's own).
    EXPECT_NE(text.find("Result:  PASS"), std::string::npos);
}

TEST(ReportTest, BusHealthSectionInJsonIsTheStatsJson) {
    const BusHealth h = test::health_sample();
    const ReportContext context = with_health(h);
    auto report = json_report(context);
    ASSERT_TRUE(report);
    const Json& health = (*report)["bus_health"];
    EXPECT_EQ(health.keys(),
              (std::vector<std::string>{"segment", "stations", "masters", "thresholds"}));
    EXPECT_EQ(health["stations"].items.size(), 3u);
    EXPECT_EQ(health["segment"]["verdict"].string(), "bad");
    std::vector<std::string> keys = report->keys();
    auto at = std::find(keys.begin(), keys.end(), "bus_health");
    ASSERT_NE(at, keys.end());
    EXPECT_EQ(*(at - 1), "bus");
    EXPECT_EQ(*(at + 1), "findings");
    // The very same text as `dpscope stats -T json` writes after "dpscope" and "input".
    StatsContext stats;
    stats.input = context.input;
    stats.health = &h;
    stats.version = context.version;
    const std::string stats_text =
        test::output_text([&](Output& out) { render_stats(StatsFormat::Json, stats, out); });
    const std::size_t members = stats_text.find(",\"segment\":");
    ASSERT_NE(members, std::string::npos);
    ASSERT_TRUE(stats_text.ends_with("}\n"));
    const std::string body = stats_text.substr(members + 1, stats_text.size() - members - 3);
    EXPECT_NE(render(ReportFormat::Json, context).find("\"bus_health\":{" + body + "}"),
              std::string::npos);
}

TEST(ReportTest, BusHealthSectionInMarkdownAndHtml) {
    const BusHealth h = test::health_sample();
    const std::string markdown = render(ReportFormat::Markdown, with_health(h));
    const std::size_t section = markdown.find("\n## Bus health\n\n- Capture: ");
    ASSERT_NE(section, std::string::npos) << markdown;
    EXPECT_LT(section, markdown.find("\n## Findings ("));
    EXPECT_NE(markdown.find("\n### Live list (3 stations)\n", section), std::string::npos);
    EXPECT_NE(markdown.find("\n### Masters (times in ms)\n", section), std::string::npos);
    EXPECT_NE(markdown.find("| 5 | 400 | 390 | 10 |", section), std::string::npos);

    auto html = parse_xml(render(ReportFormat::Html, with_health(h)), true);
    ASSERT_TRUE(html);
    const XmlNode* health = find_id(*html, "section", "bus-health");
    ASSERT_TRUE(health);
    EXPECT_EQ(health->elements("h2")[0]->text, "Bus health");
    EXPECT_EQ(health->all("svg", "states").size(), 1u);
    EXPECT_EQ(health->all("svg", "master-plot").size(), 1u);
    EXPECT_EQ(health->all("table", "live").size(), 1u);
    EXPECT_EQ(health->all("table", "health-slaves").size(), 1u);
    EXPECT_EQ(health->all("table", "health-masters").size(), 1u);
    EXPECT_TRUE(find_id(*html, "section", "findings"));
}

TEST(ReportTest, BusHealthSuiteInJunitFailsOnBadVerdicts) {
    const BusHealth h = test::health_sample();
    auto root = junit_report(with_health(h));
    ASSERT_TRUE(root);
    const XmlNode* suite = nullptr;
    std::size_t tests = 0, failures = 0;
    for (const XmlNode* s : root->elements("testsuite")) {
        if (s->attribute("name") == "bus health") suite = s;
        tests += std::stoul(s->attribute("tests"));
        failures += std::stoul(s->attribute("failures"));
    }
    ASSERT_TRUE(suite);
    EXPECT_EQ(root->attribute("tests"), std::to_string(tests));
    EXPECT_EQ(root->attribute("failures"), std::to_string(failures));
    EXPECT_EQ(suite->attribute("tests"), "5");
    EXPECT_EQ(suite->attribute("failures"), "2");
    auto cases = suite->elements("testcase");
    ASSERT_EQ(cases.size(), 5u);
    std::vector<std::string> names;
    for (const XmlNode* c : cases) {
        names.push_back(c->attribute("name"));
        EXPECT_EQ(c->attribute("classname"), "dpscope.bus_health");
    }
    EXPECT_EQ(names,
              (std::vector<std::string>{"segment", "station 2 (master)", "station 5 (slave)",
                                        "station 7 (unknown)", "master 2 (token and cycle)"}));
    // The segment's own reason says why it is bad: no station named besides (samples/expected/
    // report.bus-health.junit.xml has a segment bad by its station, which it names).
    ASSERT_EQ(cases[0]->elements("failure").size(), 1u);
    EXPECT_EQ(cases[0]->elements("failure")[0]->attribute("message"),
              "lost_events_bad: 1 (bad from 1)");
    ASSERT_EQ(cases[2]->elements("failure").size(), 1u);
    EXPECT_EQ(cases[2]->elements("failure")[0]->attribute("message"),
              "lost_events_bad: 1 (bad from 1); repeat_percent_weak: 1 % (weak above 0.1 %)");
    EXPECT_EQ(failing_cases(*suite), 2u);
    EXPECT_TRUE(cases[1]->children.empty());
    EXPECT_TRUE(cases[4]->elements("failure").empty());
    ASSERT_EQ(cases[4]->elements("system-out").size(), 1u);
    EXPECT_EQ(cases[4]->elements("system-out")[0]->text,
              "verdict weak: target_rotation_ms: 20 ms (weak above 15 ms)");
}

TEST(ReportTest, BusHealthSectionOfASimulatedSession) {
    // The real tracker over a clean simulated session: every format carries its figures.
    Analysis a;
    BusDecoder decoder;
    BusHealthTracker tracker;
    Simulator simulator(one_slave(3, 1, 60));
    std::vector<std::uint8_t> bytes;
    std::int64_t time_ns = 0;
    std::uint64_t number = 0;
    while (simulator.next(bytes, time_ns)) {
        ++number;
        a.feed(Bytes(bytes.data(), bytes.size()), time_ns, number);
        tracker.observe(decoder.decode(Bytes(bytes.data(), bytes.size()), time_ns, number));
    }
    a.finish();
    tracker.finish();
    a.input = InputSummary{"simulated.pcap", "pcap", 0, false};
    ReportContext context = context_of(a);
    context.health = &tracker.health();

    auto report = json_report(context);
    ASSERT_TRUE(report);
    const Json& health = (*report)["bus_health"];
    EXPECT_EQ(health["segment"]["telegrams"].integer(),
              static_cast<long long>(a.summary.telegrams()));
    const Json* slave = nullptr;
    for (const Json& station : health["stations"].items)
        if (station["address"].integer() == 3) slave = &station;
    ASSERT_TRUE(slave);
    EXPECT_EQ((*slave)["role"].string(), "slave");
    EXPECT_EQ((*slave)["state"].string(), "data_exchange");
    EXPECT_GT((*slave)["requests"].integer(), 60);
    EXPECT_FALSE((*slave)["timeline"].items.empty());
    EXPECT_FALSE(health["masters"].items.empty());

    auto root = junit_report(context);
    ASSERT_TRUE(root);
    const XmlNode* suite = nullptr;
    for (const XmlNode* s : root->elements("testsuite"))
        if (s->attribute("name") == "bus health") suite = s;
    ASSERT_TRUE(suite);
    EXPECT_EQ(suite->elements("testcase").size(),
              1 + tracker.health().stations.size() + tracker.health().masters.size());
    EXPECT_EQ(suite->attribute("failures"), "0") << render(ReportFormat::Text, context);

    auto html = parse_xml(render(ReportFormat::Html, context), true);
    ASSERT_TRUE(html);
    const XmlNode* section = find_id(*html, "section", "bus-health");
    ASSERT_TRUE(section);
    EXPECT_EQ(section->all("svg", "states").size(), 1u);
    EXPECT_FALSE(section->all("rect", "data_exchange").empty());
    const std::string text = render(ReportFormat::Text, context);
    EXPECT_NE(text.find("\nBus health\n"), std::string::npos);
    EXPECT_NE(render(ReportFormat::Markdown, context).find("\n## Bus health\n"), std::string::npos);
}

}  // namespace
}  // namespace dpscope
