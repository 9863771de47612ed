// The building blocks of every bus-health rendering (protocols/profibus/health/bus_health.hpp),
// shared by `dpscope stats` (protocols/profibus/health/stats_render.cpp) and the bus-health section
// of the conformance report (formats/report_*.cpp): one function per piece, so that the tables, the
// JSON objects and the charts read the same in both. They only render: every figure and verdict
// comes from BusHealth.
//
// One file per format: protocols/profibus/health/health_json_render.cpp, health_text_render.cpp,
// health_markdown_render.cpp, health_csv_render.cpp, health_html_render.cpp and
// health_charts_render.cpp (the SVG charts), over the tables and
// cells they share (formats/health_tables.*, private to them); the shared words below are in
// protocols/profibus/health/health_render.cpp.
#pragma once

#include <string>
#include <string_view>

#include "formats/describe.hpp"
#include "formats/json_writer.hpp"
#include "protocols/profibus/health/bus_health.hpp"

namespace dpscope::health {

// "12.345 ms" figures: nanoseconds in milliseconds with three decimals.
std::string ms(double ns);
// "2024-01-01T00:00:00.000123000Z", or "frame 12" when the time is not known.
std::string when(std::int64_t time_ns, std::uint64_t frame);
// The reasons of a judgement as describe_reason() words them, joined by "; " ("" for none).
std::string reasons_text(const Judgement& judgement, const HealthThresholds& thresholds);
// The stations listed in the slave table: every station that is not a master, and a master
// that was asked something (it answers FDL_Status).
// Why the segment has its verdict when its own reasons do not say it: "from station 4 (slave),
// master 2 (token and cycle)" (those with the segment's verdict); "" otherwise.
std::string segment_cause(const BusHealth& h);
bool in_slave_table(const StationHealth& s);
// The thresholds whose value differs from the default.
bool differs_from_default(const HealthThresholds& thresholds, HealthThreshold kind);

// ---- JSON ("stats JSON" in docs/formats.md) -----------------------------------------------------

// The members "segment", "stations", "masters" and "thresholds" of the object the writer is in:
// the whole of `dpscope stats -T json` after "dpscope" and "input", and the report's
// "bus_health" object.
void write_json_members(JsonWriter& w, const BusHealth& h);

// ---- text
// ------------------------------------------------------------------------------------------

// The capture's lines: duration, telegrams, telegrams/s, bus load and idle time, damaged
// telegrams, the segment's verdict and its reasons. Each line starts with `indent`.
void text_segment(TextBuffer& b, const BusHealth& h, std::string_view indent);
// The live list, the slave table, the master table, the verdict reasons per station and the
// thresholds that differ from the defaults, each under a title line; every line that is not
// empty starts with `indent`.
void text_tables(TextBuffer& b, const BusHealth& h, std::string_view indent = "");

// ---- Markdown
// --------------------------------------------------------------------------------------

// The capture as a list, then the same tables as text_tables() under headings of `level`
// ("##" or "###").
void markdown_segment(TextBuffer& b, const BusHealth& h);
void markdown_tables(TextBuffer& b, const BusHealth& h, std::string_view level);

// ---- CSV
// -------------------------------------------------------------------------------------------

// A header row and one row per station: address, role, state, verdict, reasons, every counter,
// and for a master its token and cycle figures (empty for the others). RFC 4180 quoting.
void write_csv(TextBuffer& b, const BusHealth& h);
// A CSV field, quoted when it holds a comma, a quote or a line break (quotes doubled).
void csv_field(TextBuffer& b, std::string_view text);

// ---- HTML
// ------------------------------------------------------------------------------------------

// The capture as a key-value table with the segment's verdict and reasons.
void html_segment(TextBuffer& b, const BusHealth& h);
// The live list, the state timeline (SVG), the slave table, the master table with each
// master's plot of cycle time and token rotation (SVG), the verdict reasons and the thresholds,
// under <h3> headings.
void html_tables(TextBuffer& b, const BusHealth& h);
// The SVG pieces on their own (also for tests).
void svg_state_timeline(TextBuffer& b, const BusHealth& h);
void svg_master_plot(TextBuffer& b, const BusHealth& h, const MasterHealth& m);

}  // namespace dpscope::health
