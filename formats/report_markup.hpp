// Escaping and small building blocks for the Markdown, HTML and JUnit (XML) reports.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "formats/report_model.hpp"

namespace dpscope::report {

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

// HTML: a station's latency histogram as inline SVG (`who`: "slave 3", in its label), or a line
// saying why there is none (`answered`: anything was answered).
void svg_latency_histogram(TextBuffer& b, const LogHistogram& h, bool answered,
                           std::string_view who);
// HTML: a station's timeline of transactions and findings as inline SVG.
void svg_timeline(TextBuffer& b, const Timeline& timeline, std::string_view who,
                  const ReportContext& c);

}  // namespace dpscope::report
