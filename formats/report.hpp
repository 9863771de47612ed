// The protocol-conformance report: per slave the PPO layout, dialect (and a hint when the
// slave's codes fit another dialect), transactions, latency, parameters accessed, rejections and
// findings by kind; then the findings in capture order (text and Markdown: the first 1000 of each
// kind; HTML: the first 2000; JSON: all).
// Formats: text, json (schema in docs/formats.md, stable), markdown, html (one self-contained file
// with inline SVG) and junit (one test suite per slave, one test case per rule).
// How the report is built (the model, one writer per format, one section class per channel
// kind): formats/report_model.hpp.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/protocol_lane.hpp"
#include "drives/parameter_naming.hpp"
#include "formats/finding_log.hpp"
#include "formats/output.hpp"
#include "formats/report_timeline.hpp"
#include "formats/summary.hpp"
#include "protocols/profibus/health/bus_health.hpp"

namespace dpscope {

enum class ReportFormat { Text, Json, Markdown, Html, Junit };

std::string_view report_format_name(ReportFormat format);
std::optional<ReportFormat> report_format_from_name(std::string_view name);

// --fail-on: the lowest severity that makes the report (and the exit code) fail.
enum class FailOn { Error, Warning, Never };
std::string_view fail_on_name(FailOn fail_on);
std::optional<FailOn> fail_on_from_name(std::string_view name);
bool severity_fails(Severity severity, FailOn fail_on) noexcept;

struct ReportContext {
    InputSummary input;
    const Summary* summary = nullptr;
    // The capture's bus: its tracker's sections, bus findings and finding kinds are reported.
    Protocol protocol = Protocol::ProfibusDp;
    // The capture's decoder and tracker, of that bus (core/protocol_lane.hpp): each protocol's
    // report section reads its own (protocols/<name>/*_report_section.cpp). The tracker is
    // always set (its time-out is read).
    const TelegramDecoder* decoder = nullptr;
    const TelegramTracker* tracker = nullptr;
    // What names the capture's PNUs in the sections' parameter tables (issue 29,
    // drives/parameter_naming.hpp); null: numbers alone.
    const ParameterNaming* naming = nullptr;
    const ChannelTimelines* timelines = nullptr;      // the HTML report's (none: empty timelines)
    // PROFIBUS: the bus-health statistics (protocols/profibus/health/bus_health.hpp), reported in a
    // section of their own; null: no such section.
    const BusHealth* health = nullptr;
    const FindingLog* findings = nullptr;
    FailOn fail_on = FailOn::Error;
    // --allow-empty: a capture in which nothing could be checked (no Data_Exchange telegram with
    // a parameter channel from the slaves reported) passes; by default it fails.
    bool allow_empty = false;
    std::vector<std::uint8_t> stations;  // report only these slaves (empty: all)
    // -Y: the findings listed are those of the telegrams this filter selects ("": all).
    std::string display_filter;
    std::string version;                 // dpscope's version, named in the report
};

// Findings at or above --fail-on among those the report shows, or nothing checked without
// allow_empty.
bool report_fails(const ReportContext& context);

// Writes the report and returns its verdict (what report_fails() says), from the one model it
// builds: the finding log is read once.
bool render_report(ReportFormat format, const ReportContext& context, Output& out);

}  // namespace dpscope
