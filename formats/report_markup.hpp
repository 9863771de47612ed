// Escaping and small building blocks for the Markdown, HTML and JUnit (XML) reports.
#pragma once

#include <fmt/format.h>

#include <array>
#include <cstdint>
#include <iterator>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "formats/parameter_names.hpp"
#include "formats/report_model.hpp"

namespace dpscope::report {

// The report's stylesheet (report_html.cpp), also the `dpscope stats` page's.
std::string_view html_style();
// Markdown text with \ | * _ ` < > escaped.
std::string md_escape(std::string_view text);
// XML/HTML text with & < > " ' escaped.
void escape_xml(TextBuffer& b, std::string_view text);
std::string xml(std::string_view text);
// An HTML table row <tr><th>key</th><td>value</td></tr>, both escaped.
void html_kv(TextBuffer& b, std::string_view key, std::string_view value);
// HTML "Findings by kind": a table of the kinds found, or "None."
// The kinds `findings` counts, a row per kind and severity seen (`by_severity`).
void html_findings_by_kind(TextBuffer& b, const FindingCounts& findings,
                           const FindingSeverityCounts& by_severity);
// The findings of the kinds `findings` counts, by the severity each had (indexed by Severity):
// the error, warning and note columns of a station's HTML row.
std::array<std::uint64_t, 3> severity_totals(const FindingCounts& findings,
                                             const FindingSeverityCounts& by_severity);

// HTML "Parameters accessed": a table of PNUs with their reads and writes (`parameters` maps PNU ->
// anything with `reads` and `writes`), or "None." when it is empty. Returns whether a table was
// written (the caller then says what was not counted).
// With `family`, each PNU's name after it (issue 29).
template <typename ParameterMap>
bool html_parameter_table(TextBuffer& b, const ParameterMap& parameters,
                          StationNaming names = {}) {
    if (parameters.empty()) {
        fmt::format_to(std::back_inserter(b), "<p class=\"meta\">None.</p>\n");
        return false;
    }
    auto it = std::back_inserter(b);
    fmt::format_to(it,
                   "<table class=\"parameters\"><tr><th class=\"n\">PNU</th><th "
                   "class=\"n\">reads</th><th class=\"n\">writes</th></tr>\n");
    for (const auto& [pnu, access] : parameters)
        fmt::format_to(it,
                       "<tr><td class=\"n\">{}</td><td class=\"n\">{}</td><td "
                       "class=\"n\">{}</td></tr>\n",
                       xml(pnu_label(names, pnu)), access.reads, access.writes);
    fmt::format_to(it, "</table>\n");
    return true;
}

// A serial-bus drive's reply times in ms (FC and VLT 2000 sections), from its histogram and mean.
struct DriveLatency {
    bool any = false;
    double min_ms = 0, mean_ms = 0, p95_ms = 0, max_ms = 0;

    static DriveLatency of(const LogHistogram& ns, std::uint64_t mean_ns);
    // "min 2.014  mean 4.835  p95 7.635  max 7.988"; "-" for the broadcasts or nothing answered,
    // "not measured (no timestamps)" without times.
    std::string text(bool broadcast, bool timed) const;
};

// A drive's commands by outcome (FC, VLT 2000), read from its tracker's counts.
struct DriveOutcomes {
    std::uint64_t commands = 0;
    std::uint64_t broadcasts = 0;
    std::uint64_t answered = 0;
    std::uint64_t unanswered = 0;
    std::uint64_t abandoned = 0;
    std::uint64_t damaged = 0;
    std::uint64_t not_judged = 0;

    template <class Stats>
    static DriveOutcomes of(const Stats& s) {
        return {s.commands,  s.broadcasts, s.answered,          s.no_responses,
                s.abandoned, s.damaged,    s.not_judged_total()};
    }
};

// HTML: the header row of a serial bus's drives table (FC, VLT 2000: their BusWording's
// html_table), the columns of html_drive_row().
inline constexpr std::string_view kDriveHtmlTable =
    "<tr><th class=\"n\">address</th><th class=\"n\">commands</th><th class=\"n\">answered"
    "</th><th class=\"n\">unanswered</th><th class=\"n\">abandoned</th><th class=\"n\">damaged"
    "</th><th class=\"n\">not judged</th><th class=\"n\">mean ms</th><th class=\"n\">p95 ms"
    "</th><th class=\"n\">errors</th><th class=\"n\">warnings</th><th class=\"n\">notes</th>"
    "</tr>\n";

// HTML: one row of a serial bus's drives table (kDriveHtmlTable's columns): the address (linked
// to `anchor`, shown as `label`), commands, answered, unanswered, abandoned, damaged, not judged,
// mean and p95 reply time, findings by severity.
void html_drive_row(TextBuffer& b, std::string_view anchor, std::string_view label,
                    const DriveOutcomes& outcomes, const DriveLatency& latency,
                    const std::array<std::uint64_t, 3>& severities);

// JUnit: a drive suite's <properties>: its commands by outcome and its responses (or replies),
// named as in the JSON report.
std::vector<std::pair<std::string, std::uint64_t>> drive_properties(const DriveOutcomes& outcomes,
                                                                    std::string_view responses_name,
                                                                    std::uint64_t responses);

// HTML: a station's latency histogram as inline SVG (`who`: "slave 3", in its label), or a line
// saying why there is none (`answered`: anything was answered).
void svg_latency_histogram(TextBuffer& b, const LogHistogram& h, bool answered,
                           std::string_view who);
// HTML: a station's timeline of transactions and findings as inline SVG.
void svg_timeline(TextBuffer& b, const Timeline& timeline, std::string_view who,
                  const ReportContext& c);

}  // namespace dpscope::report
