// `dpscope stats` renderers (protocols/profibus/health/stats_render.hpp,
// protocols/profibus/health/health_render.hpp) over a BusHealth built by hand with known numbers
// (tests/health_sample.hpp): every format's content, escaping of hostile text, the JSON schema
// through a strict parser, the HTML through an XML parser, the CSV through an RFC 4180 reader; an
// empty capture, one without times, one without a baud rate; the live table and its truncation.
#include "protocols/profibus/health/stats_render.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "protocols/profibus/health/health_render.hpp"
#include "tests/health_sample.hpp"
#include "tests/json_parser.hpp"
#include "tests/test_support.hpp"
#include "tests/xml_parser.hpp"

namespace dpscope {
namespace {

using test::health_sample;
using test::Json;
using test::parse_json;
using test::parse_xml;
using test::XmlNode;

constexpr std::string_view kHostile = "cap<script>alert('x')</script>&\"|*_,\n.pcap";

template <typename Write>
std::string capture(Write write) {
    return test::output_text(write);
}

std::string render(StatsFormat format, const BusHealth& h, std::string_view name = "bus.pcap") {
    StatsContext context;
    context.input = InputSummary{std::string(name), "pcap", 0, false};
    context.health = &h;
    context.version = "7.8.9-test";
    return capture([&](Output& out) { render_stats(format, context, out); });
}

std::string live(const BusHealth& h, unsigned width) {
    return capture([&](Output& out) { render_live_table(h, out, width); });
}

bool has(const std::string& text, std::string_view needle) {
    return text.find(needle) != std::string::npos;
}

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::size_t start = 0;
    while (start < text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        out.push_back(text.substr(start, end - start));
        start = end + 1;
    }
    return out;
}

// An RFC 4180 reader: records of fields, quotes undone.
std::vector<std::vector<std::string>> read_csv(std::string_view text) {
    std::vector<std::vector<std::string>> records;
    std::vector<std::string> record;
    std::string field;
    bool quoted = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        char c = text[i];
        if (quoted) {
            if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
                field += '"';
                ++i;
            } else if (c == '"') {
                quoted = false;
            } else {
                field += c;
            }
        } else if (c == '"') {
            EXPECT_TRUE(field.empty()) << "a quote inside an unquoted field";
            quoted = true;
        } else if (c == ',') {
            record.push_back(field);
            field.clear();
        } else if (c == '\n') {
            record.push_back(field);
            field.clear();
            records.push_back(record);
            record.clear();
        } else {
            field += c;
        }
    }
    EXPECT_FALSE(quoted) << "an unterminated quote";
    EXPECT_TRUE(field.empty() && record.empty()) << "the last record has no line end";
    return records;
}

TEST(StatsTest, FormatNamesRoundTrip) {
    for (StatsFormat f : {StatsFormat::Text, StatsFormat::Json, StatsFormat::Markdown,
                          StatsFormat::Html, StatsFormat::Csv})
        EXPECT_EQ(stats_format_from_name(stats_format_name(f)), f);
    EXPECT_FALSE(stats_format_from_name("xml"));
    EXPECT_EQ(stats_format_name(StatsFormat::Markdown), "markdown");
}

TEST(StatsTest, NothingWithoutHealth) {
    StatsContext context;
    EXPECT_EQ(capture([&](Output& out) { render_stats(StatsFormat::Text, context, out); }), "");
}

TEST(StatsTest, TextHeaderSegmentAndTables) {
    const BusHealth h = health_sample();
    const std::string text = render(StatsFormat::Text, h);
    EXPECT_TRUE(text.starts_with("dpscope 7.8.9-test bus health\nInput:     bus.pcap (pcap)\n"))
        << text;
    EXPECT_TRUE(has(text,
                    "Capture:   2024-01-01T00:00:00.000000000Z to 2024-01-01T00:00:02.000000000Z "
                    "(2.000000 s)\n"))
        << text;
    EXPECT_TRUE(has(text, "Telegrams: 1000, 500.0 per second, 12000 bytes\n"));
    EXPECT_TRUE(has(text, "Bus load:  25.00 % at 1500000 baud, idle 1.500000 s\n"));
    EXPECT_TRUE(has(text, "Damaged:   3 (1 no station could be named for)\n"));
    EXPECT_TRUE(has(text, "Segment:   bad\n           - lost_events_bad: 1 (bad from 1)\n"));
    // The live list: one row per station, times as the report writes them.
    EXPECT_TRUE(has(text, "Live list (3 stations)\n"));
    EXPECT_TRUE(has(text,
                    "        5  slave    data exchange  2024-01-01T00:00:00.100000000Z  "
                    "2024-01-01T00:00:01.998000000Z  bad"))
        << text;
    EXPECT_TRUE(has(text, "        7  unknown  unknown"));
    // The slave table: 5 and 7 (the master was asked nothing).
    const std::vector<std::string> all = lines(text);
    auto row_after = [&](std::string_view title, std::string_view first_cell) -> std::string {
        bool in = false;
        for (const std::string& line : all) {
            if (line.starts_with(title))
                in = true;
            else if (in && line.empty())
                break;
            else if (in && line.find_first_not_of(' ') != std::string::npos &&
                     line.substr(line.find_first_not_of(' ')).starts_with(first_cell))
                return line;
        }
        return {};
    };
    std::string slave5 = row_after("Slaves", "5 ");
    // The counts, then the illegal answers and the negative answers each in one cell.
    std::vector<std::string> cells;
    for (std::size_t at = 0; at < slave5.size();) {
        std::size_t start = slave5.find_first_not_of(' ', at);
        if (start == std::string::npos) break;
        std::size_t end = slave5.find("  ", start);
        if (end == std::string::npos) end = slave5.size();
        cells.push_back(slave5.substr(start, end - start));
        at = end;
    }
    EXPECT_EQ(cells,
              (std::vector<std::string>{"5", "400", "390", "10", "4", "2", "1", "1", "1", "6", "2",
                                        "2", "3 (not asked 1, short ack 2)", "RR 1, DH 3"}))
        << text;
    EXPECT_EQ(row_after("Slaves", "2 "), "");
    EXPECT_NE(row_after("Slaves", "7 "), "");
    EXPECT_TRUE(has(text, "diag faults  damaged  illegal                       negative answers\n"))
        << text;
    // The master table: tokens, rotation, the target (set), cycle, jitter, slaves polled.
    EXPECT_TRUE(has(text, "target"));
    std::string master2 = row_after("Masters", "2 ");
    EXPECT_TRUE(has(master2, "100  ")) << master2;
    EXPECT_TRUE(has(master2, "20.000")) << master2;
    EXPECT_TRUE(has(master2, "15.000")) << master2;
    EXPECT_TRUE(has(master2, "10.000")) << master2;
    EXPECT_TRUE(has(master2, "11.000")) << master2;
    EXPECT_TRUE(has(master2, "12.000")) << master2;
    EXPECT_TRUE(has(master2, "2.000")) << master2;
    // The verdicts, with describe_reason's words, and the thresholds set.
    EXPECT_TRUE(has(text,
                    "  station 5 (slave): bad\n    - lost_events_bad: 1 (bad from 1)\n"
                    "    - repeat_percent_weak: 1 % (weak above 0.1 %)\n"))
        << text;
    EXPECT_TRUE(has(text, "  master 2: weak\n"));
    EXPECT_FALSE(has(text, "station 2 (master): "));
    EXPECT_TRUE(has(text,
                    "Thresholds (other than the defaults)\n  target_rotation_ms = 15 "
                    "(default 0)\n"));
}

TEST(StatsTest, TextWithoutBaudSaysHowToGetTheLoad) {
    const BusHealth h = health_sample(true, 0);
    const std::string text = render(StatsFormat::Text, h);
    EXPECT_TRUE(has(text, "Bus load:  unknown (give --baud)\n")) << text;
    EXPECT_TRUE(has(text, "500.0 per second"));
}

TEST(StatsTest, TextWithoutTimesNamesFramesAndNoRates) {
    const BusHealth h = health_sample(false);
    const std::string text = render(StatsFormat::Text, h);
    EXPECT_TRUE(has(text, "Capture:   no timestamps: counts only, no rates\n")) << text;
    EXPECT_TRUE(has(text, "Telegrams: 1000, 12000 bytes\n"));
    EXPECT_TRUE(has(text, "Bus load:  unknown (no timestamps)\n"));
    EXPECT_TRUE(has(text, "  frame 10  ")) << text;
    EXPECT_TRUE(has(text, "  frame 998  ")) << text;
    EXPECT_FALSE(has(text, "2024-"));
    EXPECT_FALSE(has(text, "per second"));
}

TEST(StatsTest, TextOfAnEmptyCapture) {
    const BusHealth h;
    const std::string text = render(StatsFormat::Text, h);
    EXPECT_TRUE(has(text, "Telegrams: 0, 0 bytes\n")) << text;
    EXPECT_TRUE(has(text, "Live list: no stations\n"));
    EXPECT_TRUE(has(text, "Slaves: none\n"));
    EXPECT_TRUE(has(text, "Masters: none\n"));
    EXPECT_TRUE(has(text, "nothing judged: no telegrams\n"));
    EXPECT_TRUE(has(text, "Thresholds: the defaults\n"));
    // Nothing seen is nothing judged, not good (SegmentHealth::judged()).
    EXPECT_TRUE(has(text, "Segment:   not judged (no telegrams)\n"));
    EXPECT_FALSE(has(text, "good"));
}

TEST(StatsTest, JsonSchemaAndValues) {
    const BusHealth h = health_sample();
    const std::string text = render(StatsFormat::Json, h, kHostile);
    ASSERT_TRUE(text.ends_with("}\n"));
    EXPECT_EQ(lines(text).size(), 1u);
    auto json = parse_json(text);
    ASSERT_TRUE(json);
    EXPECT_EQ(json->keys(), (std::vector<std::string>{"dpscope", "input", "segment", "stations",
                                                      "masters", "thresholds"}));
    EXPECT_EQ((*json)["dpscope"].string(), "7.8.9-test");
    EXPECT_EQ((*json)["input"]["file"].string(), kHostile);
    const Json& seg = (*json)["segment"];
    EXPECT_EQ(seg.keys(),
              (std::vector<std::string>{"telegrams", "bytes", "damaged", "unattributed_damaged",
                                        "unasked_short_acks", "first_time", "end_time",
                                        "duration_s", "telegrams_per_s", "baud", "character_bits",
                                        "load_percent", "idle_s", "verdict", "reasons"}));
    EXPECT_EQ(seg["telegrams"].integer(), 1000);
    EXPECT_EQ(seg["first_time"].text, "1704067200.000000000");
    EXPECT_EQ(seg["duration_s"].text, "2.000000000");
    EXPECT_EQ(seg["telegrams_per_s"].text, "500.000");
    EXPECT_EQ(seg["baud"].integer(), 1'500'000);
    EXPECT_EQ(seg["load_percent"].text, "25.000");
    EXPECT_EQ(seg["idle_s"].text, "1.500000000");
    EXPECT_EQ(seg["verdict"].string(), "bad");
    ASSERT_EQ(seg["reasons"].items.size(), 1u);
    const Json& reason = seg["reasons"][0];
    EXPECT_EQ(reason.keys(),
              (std::vector<std::string>{"threshold", "measured", "limit", "verdict", "text"}));
    EXPECT_EQ(reason["threshold"].string(), "lost_events_bad");
    EXPECT_EQ(reason["measured"].text, "1");
    EXPECT_EQ(reason["limit"].text, "1");
    EXPECT_EQ(reason["text"].string(), "lost_events_bad: 1 (bad from 1)");

    const Json& stations = (*json)["stations"];
    ASSERT_EQ(stations.items.size(), 3u);
    const Json& s5 = stations[1];
    EXPECT_EQ(s5["address"].integer(), 5);
    EXPECT_EQ(s5["role"].string(), "slave");
    EXPECT_EQ(s5["state"].string(), "data_exchange");
    EXPECT_EQ(s5["verdict"].string(), "bad");
    EXPECT_EQ(s5["reasons"].items.size(), 2u);
    EXPECT_EQ(s5["first_seen"].text, "1704067200.100000000");
    for (auto [key, value] :
         std::vector<std::pair<std::string, long long>>{{"requests", 400},
                                                        {"answers", 390},
                                                        {"no_answers", 10},
                                                        {"repeats", 4},
                                                        {"max_repeats_per_cycle", 2},
                                                        {"lost_events", 1},
                                                        {"returns", 1},
                                                        {"resyncs", 1},
                                                        {"diag_requests", 6},
                                                        {"diag_answers", 6},
                                                        {"diag_faults", 2},
                                                        {"damaged", 2},
                                                        {"state_changes", 4},
                                                        {"telegrams_sent", 390},
                                                        {"replies_due", 400}})
        EXPECT_EQ(s5[key].integer(), value) << key;
    EXPECT_EQ(s5["illegal_answers"]["not_asked"].integer(), 1);
    EXPECT_EQ(s5["illegal_answers"]["short_ack"].integer(), 2);
    EXPECT_EQ(s5["negative_answers"]["DH"].integer(), 3);
    EXPECT_EQ(s5["negative_answers"]["RR"].integer(), 1);
    EXPECT_EQ(s5["diag_fault_bits"]["Station_Not_Ready"].integer(), 2);
    EXPECT_EQ(s5["diag_fault_bits"]["Ext_Diag"].integer(), 1);
    const Json& timeline = s5["timeline"];
    ASSERT_EQ(timeline.items.size(), 4u);
    EXPECT_EQ(timeline[2].keys(), (std::vector<std::string>{"time", "frame", "state", "returned"}));
    EXPECT_EQ(timeline[2]["state"].string(), "lost");
    EXPECT_EQ(timeline[2]["frame"].integer(), 500);
    EXPECT_EQ(timeline[2]["time"].text, "1704067201.000000000");
    EXPECT_FALSE(timeline[2]["returned"].boolean);
    EXPECT_TRUE(timeline[3]["returned"].boolean);

    const Json& master = (*json)["masters"][0];
    EXPECT_EQ(master["address"].integer(), 2);
    EXPECT_EQ(master["verdict"].string(), "weak");
    EXPECT_EQ(master["tokens_received"].integer(), 100);
    EXPECT_EQ(master["cycle"]["count"].integer(), 2);
    EXPECT_EQ(master["cycle"]["min_ms"].text, "10.000000");
    EXPECT_EQ(master["cycle"]["mean_ms"].text, "11.000000");
    EXPECT_EQ(master["cycle"]["max_ms"].text, "12.000000");
    EXPECT_EQ(master["cycle_jitter_ms"].text, "2.000000");
    EXPECT_EQ(master["token_rotation"]["max_ms"].text, "20.000000");
    EXPECT_EQ(master["target_rotation_ms"].text, "15");
    const Json& points = master["cycle_series"]["points"];
    ASSERT_EQ(points.items.size(), 2u);
    EXPECT_EQ(master["cycle_series"]["samples_per_point"].integer(), 1);
    EXPECT_EQ(points[1]["first_time"].text, "1704067201.500000000");
    EXPECT_EQ(points[1]["mean_ms"].text, "12.000000");

    const Json& thresholds = (*json)["thresholds"];
    EXPECT_EQ(thresholds.members.size(), kHealthThresholdCount);
    EXPECT_EQ(thresholds["target_rotation_ms"].text, "15");
    EXPECT_EQ(thresholds["lost_cycles"].text, "3");
    EXPECT_EQ(thresholds["repeat_percent_weak"].text, "0.1");
}

TEST(StatsTest, JsonWithoutTimesOrBaudHasNulls) {
    const BusHealth h = health_sample(false, 0);
    auto json = parse_json(render(StatsFormat::Json, h));
    ASSERT_TRUE(json);
    const Json& seg = (*json)["segment"];
    for (const char* key : {"first_time", "end_time", "duration_s", "telegrams_per_s", "baud",
                            "load_percent", "idle_s"})
        EXPECT_TRUE(seg[key].is_null()) << key;
    EXPECT_TRUE((*json)["stations"][1]["timeline"][0]["time"].is_null());
    EXPECT_EQ((*json)["stations"][1]["timeline"][0]["frame"].integer(), 10);
    const Json& master = (*json)["masters"][0];
    EXPECT_TRUE(master["cycle"].is_null());
    EXPECT_TRUE(master["token_rotation"].is_null());
    EXPECT_TRUE(master["cycle_jitter_ms"].is_null());
    EXPECT_TRUE(master["cycle_series"]["points"].items.empty());
}

TEST(StatsTest, JsonOfAnEmptyCapture) {
    const BusHealth h;
    auto json = parse_json(render(StatsFormat::Json, h));
    ASSERT_TRUE(json);
    EXPECT_TRUE((*json)["stations"].items.empty());
    EXPECT_TRUE((*json)["masters"].items.empty());
    EXPECT_TRUE((*json)["segment"]["verdict"].is_null());
    EXPECT_TRUE((*json)["segment"]["reasons"].items.empty());
    EXPECT_TRUE((*json)["masters"].type == Json::Type::Array);
}

TEST(StatsTest, MarkdownTablesAndEscaping) {
    const BusHealth h = health_sample();
    const std::string text = render(StatsFormat::Markdown, h, "a|b*c_.pcap");
    EXPECT_TRUE(text.starts_with("# dpscope bus health\n\n- Input: a\\|b\\*c\\_.pcap (pcap)\n"))
        << text;
    EXPECT_TRUE(has(text, "- Bus load: 25.00 % at 1500000 baud, idle 1.500000 s\n"));
    EXPECT_TRUE(has(text, "- Segment: **bad**\n  - lost\\_events\\_bad: 1 (bad from 1)\n")) << text;
    EXPECT_TRUE(has(text,
                    "## Live list (3 stations)\n\n| address | role | state | first seen | "
                    "last seen | verdict |\n|---:|---|---|---|---|---|\n"))
        << text;
    EXPECT_TRUE(has(text,
                    "| 5 | slave | data exchange | 2024-01-01T00:00:00.100000000Z | "
                    "2024-01-01T00:00:01.998000000Z | bad |\n"));
    EXPECT_TRUE(has(text,
                    "| 5 | 400 | 390 | 10 | 4 | 2 | 1 | 1 | 1 | 6 | 2 | 2 | 3 (not asked 1, short "
                    "ack 2) | RR 1, DH 3 |\n"))
        << text;
    EXPECT_TRUE(has(text, "## Masters (times in ms)\n"));
    EXPECT_TRUE(has(text, "| 2 | 100 | 20.000 | 20.000 |"));
    EXPECT_TRUE(has(text, "- station 5 (slave): **bad**\n"));
    EXPECT_TRUE(has(text, "| target\\_rotation\\_ms | 15 | 0 |\n"));
    // Every table row has as many cells as its header.
    std::size_t columns = 0;
    for (const std::string& line : lines(text)) {
        if (!line.starts_with("|")) {
            columns = 0;
            continue;
        }
        std::size_t bars = 0;
        for (std::size_t i = 0; i < line.size(); ++i)
            if (line[i] == '|' && (i == 0 || line[i - 1] != '\\')) ++bars;
        if (columns == 0) columns = bars;
        EXPECT_EQ(bars, columns) << line;
    }
}

TEST(StatsTest, HtmlIsWellFormedEscapedWithTablesAndCharts) {
    const BusHealth h = health_sample();
    const std::string text = render(StatsFormat::Html, h, kHostile);
    EXPECT_FALSE(has(text, "<script>")) << "the input name is escaped";
    EXPECT_TRUE(has(text, "cap&lt;script&gt;alert(&#39;x&#39;)&lt;/script&gt;&amp;&quot;"));
    auto root = parse_xml(text, true);
    ASSERT_TRUE(root);
    EXPECT_EQ(root->all("title")[0]->text,
              std::string("dpscope bus health: ") + std::string(kHostile));
    // The tables.
    ASSERT_EQ(root->all("table", "live").size(), 1u);
    EXPECT_EQ(root->all("table", "live")[0]->all("tr").size(), 4u);
    ASSERT_EQ(root->all("table", "health-slaves").size(), 1u);
    EXPECT_EQ(root->all("table", "health-slaves")[0]->all("tr").size(), 3u);
    ASSERT_EQ(root->all("table", "health-masters").size(), 1u);
    auto verdict = root->all("td", "verdict-bad");
    ASSERT_FALSE(verdict.empty());
    EXPECT_EQ(verdict[0]->text, "bad");
    // The state timeline: one lane per station, a segment per state, lost in red with a tooltip.
    auto states = root->all("svg", "states");
    ASSERT_EQ(states.size(), 1u);
    EXPECT_EQ(states[0]->all("rect", "state").size(), 6u);
    auto lost = states[0]->all("rect", "lost");
    ASSERT_EQ(lost.size(), 1u);
    EXPECT_EQ(lost[0]->attribute("fill"), "#d92d20");
    ASSERT_EQ(lost[0]->elements("title").size(), 1u);
    EXPECT_EQ(lost[0]->elements("title")[0]->text,
              "station 5: lost from 1.000000 s (frame 500) to 1.500000 s (frame 700)");
    auto returned = states[0]->all("rect", "data_exchange");
    ASSERT_EQ(returned.size(), 2u);
    EXPECT_TRUE(has(returned[1]->elements("title")[0]->text, "(returned)"));
    // The lost segment spans a quarter of the plot (1.0 s to 1.5 s of 2 s).
    const double width = std::stod(lost[0]->attribute("width"));
    EXPECT_NEAR(width, (720 - 96 - 10) / 4.0, 0.05);
    // The master's plot: a band and a mean line per series, ms labels, the target line.
    auto plots = root->all("svg", "master-plot");
    ASSERT_EQ(plots.size(), 1u);
    EXPECT_EQ(plots[0]->all("polygon", "band").size(), 2u);
    EXPECT_EQ(plots[0]->all("polyline", "mean").size(), 2u);
    EXPECT_EQ(plots[0]->all("circle", "point").size(), 3u);
    EXPECT_EQ(plots[0]->all("line", "target").size(), 1u);
    bool ms_label = false;
    for (const XmlNode* label : plots[0]->all("text"))
        ms_label |= label->text == "0.000 ms";
    EXPECT_TRUE(ms_label);
    EXPECT_TRUE(has(text, "lost_events_bad: 1 (bad from 1)"));
}

TEST(StatsTest, HtmlWithoutTimesDrawsStatesByFrameAndNoPlot) {
    const BusHealth h = health_sample(false, 0);
    const std::string text = render(StatsFormat::Html, h);
    auto root = parse_xml(text, true);
    ASSERT_TRUE(root);
    auto states = root->all("svg", "states");
    ASSERT_EQ(states.size(), 1u);
    auto lost = states[0]->all("rect", "lost");
    ASSERT_EQ(lost.size(), 1u);
    EXPECT_EQ(lost[0]->elements("title")[0]->text, "station 5: lost from frame 500 to frame 700");
    EXPECT_TRUE(root->all("svg", "master-plot").empty());
    EXPECT_TRUE(has(text, "Master 2: no cycle time or token rotation measured (no timestamps)."));
    EXPECT_TRUE(has(text, "unknown (no timestamps)"));
}

TEST(StatsTest, HtmlSaysWhenStateChangesWereNotKeptAndPlotsEveryPoint) {
    BusHealth h = health_sample();
    h.stations[1].state_changes = 4 + 10;  // 10 changes beyond the kept timeline
    MasterHealth& m = h.masters[0];
    m.cycle_series = TimeSeries{};
    for (std::int64_t i = 0; i < 2000; ++i)
        m.cycle_series.add(test::kHealthStart + i * test::kMs, (10 + i % 3) * test::kMs);
    const std::string text = render(StatsFormat::Html, h);
    auto root = parse_xml(text, true);
    ASSERT_TRUE(root);
    EXPECT_TRUE(has(text, "10 later state changes not drawn (at most 4096 kept per station"))
        << text;
    auto plots = root->all("svg", "master-plot");
    ASSERT_EQ(plots.size(), 1u);
    // The points of both series, each with its tooltip.
    const std::size_t points = m.cycle_series.points().size() + 1;
    EXPECT_LE(m.cycle_series.points().size(), TimeSeries::kMaxPoints);
    EXPECT_EQ(plots[0]->all("circle", "point").size(), points);
    EXPECT_TRUE(has(plots[0]->all("circle", "point")[0]->elements("title")[0]->text,
                    "cycle time from 0.000000 s: min 10.000 mean"));
    // The highest value (the 20 ms rotation, above the 15 ms target) sets the axis, 5 % above.
    bool top = false;
    for (const XmlNode* label : plots[0]->all("text"))
        top |= label->text == "21.000 ms";
    EXPECT_TRUE(top);
}

TEST(StatsTest, HtmlOfAnEmptyCapture) {
    const BusHealth h;
    auto root = parse_xml(render(StatsFormat::Html, h), true);
    ASSERT_TRUE(root);
    EXPECT_TRUE(root->all("svg").empty());
    EXPECT_TRUE(root->all("table", "live").empty());
}

TEST(StatsTest, CsvOneRowPerStationWithMasterColumns) {
    const BusHealth h = health_sample();
    const std::string text = render(StatsFormat::Csv, h);
    auto records = read_csv(text);
    ASSERT_EQ(records.size(), 4u);
    const std::vector<std::string>& header = records[0];
    for (const auto& record : records)
        EXPECT_EQ(record.size(), header.size());
    auto column = [&](std::string_view name) {
        for (std::size_t i = 0; i < header.size(); ++i)
            if (header[i] == name) return i;
        ADD_FAILURE() << "no column " << name;
        return std::size_t{0};
    };
    EXPECT_EQ(header[0], "address");
    EXPECT_EQ(records[2][column("address")], "5");
    EXPECT_EQ(records[2][column("state")], "data_exchange");
    EXPECT_EQ(records[2][column("verdict")], "bad");
    EXPECT_EQ(records[2][column("reasons")],
              "lost_events_bad: 1 (bad from 1); repeat_percent_weak: 1 % (weak above 0.1 %)");
    EXPECT_EQ(records[2][column("requests")], "400");
    EXPECT_EQ(records[2][column("replies_due")], "400");
    EXPECT_EQ(records[2][column("illegal_short_ack")], "2");
    EXPECT_EQ(records[2][column("negative_dh")], "3");
    EXPECT_EQ(records[2][column("damaged")], "2");
    EXPECT_EQ(records[2][column("diag_Station_Not_Ready")], "2");
    EXPECT_EQ(records[2][column("first_seen")], "2024-01-01T00:00:00.100000000Z");
    EXPECT_EQ(records[2][column("tokens_received")], "");
    EXPECT_EQ(records[2][column("cycle_mean_ms")], "");
    EXPECT_EQ(records[1][column("role")], "master");
    EXPECT_EQ(records[1][column("master_verdict")], "weak");
    EXPECT_EQ(records[1][column("tokens_received")], "100");
    EXPECT_EQ(records[1][column("cycle_mean_ms")], "11.000");
    EXPECT_EQ(records[1][column("rotation_max_ms")], "20.000");
    EXPECT_EQ(records[1][column("cycle_jitter_ms")], "2.000");
    EXPECT_EQ(records[3][column("role")], "unknown");
    EXPECT_EQ(records[3][column("no_answers")], "3");
}

TEST(StatsTest, CsvWithoutTimesLeavesTimesEmptyAndEmptyCaptureHasTheHeaderOnly) {
    const BusHealth h = health_sample(false);
    auto records = read_csv(render(StatsFormat::Csv, h));
    ASSERT_EQ(records.size(), 4u);
    EXPECT_EQ(records[2][5], "");
    EXPECT_EQ(records[1][records[0].size() - 1], "");
    const BusHealth empty;
    auto only = read_csv(render(StatsFormat::Csv, empty));
    ASSERT_EQ(only.size(), 1u);
    EXPECT_EQ(only[0].size(), records[0].size());
}

TEST(StatsTest, CsvFieldsAreQuotedAsRfc4180Says) {
    TextBuffer b;
    health::csv_field(b, "plain");
    b.push_back(',');
    health::csv_field(b, "a,b");
    b.push_back(',');
    health::csv_field(b, "say \"hi\"");
    b.push_back(',');
    health::csv_field(b, "two\nlines");
    b.push_back('\n');
    const std::string text = fmt::to_string(b);
    EXPECT_EQ(text, "plain,\"a,b\",\"say \"\"hi\"\"\",\"two\nlines\"\n");
    auto records = read_csv(text);
    ASSERT_EQ(records.size(), 1u);
    EXPECT_EQ(records[0], (std::vector<std::string>{"plain", "a,b", "say \"hi\"", "two\nlines"}));
}

TEST(StatsTest, LiveTableHasALinePerStationAndTheSegment) {
    const BusHealth h = health_sample();
    const std::vector<std::string> all = lines(live(h, 0));
    ASSERT_EQ(all.size(), 5u);
    EXPECT_TRUE(all[0].starts_with("addr role    state")) << all[0];
    EXPECT_TRUE(
        all[2].starts_with("   5 slave   data exchange        400       390      10       4"
                           "     1     3     2 bad"))
        << all[2];
    EXPECT_EQ(all[4], "segment: 1000 telegrams, 500.0 tel/s, load 25.0 %, 3 damaged, verdict bad");
}

TEST(StatsTest, LiveTableIsCutToTheWidth) {
    const BusHealth h = health_sample();
    const std::string full = live(h, 0);
    const std::vector<std::string> cut = lines(live(h, 20));
    const std::vector<std::string> whole = lines(full);
    ASSERT_EQ(cut.size(), whole.size());
    for (std::size_t i = 0; i < cut.size(); ++i) {
        EXPECT_LE(cut[i].size(), 20u);
        EXPECT_EQ(cut[i], whole[i].substr(0, 20));
    }
    EXPECT_GT(whole[2].size(), 20u);
    EXPECT_EQ(lines(live(h, 1000)), whole);
}

TEST(StatsTest, LiveTableWithoutTimesOrStations) {
    const BusHealth untimed = health_sample(false, 0);
    const std::vector<std::string> all = lines(live(untimed, 0));
    EXPECT_EQ(all.back(), "segment: 1000 telegrams, - tel/s, load unknown, 3 damaged, verdict bad");
    const BusHealth empty;
    EXPECT_EQ(lines(live(empty, 0)).size(), 2u);
}

}  // namespace
}  // namespace dpscope
