// The text report.
#include <algorithm>
#include <iterator>

#include "formats/report_model.hpp"
#include "protocols/profibus/health/health_render.hpp"

namespace dpscope::report {

void write_text(const ReportContext& c, const ReportModel& m, Output& out) {
    TextBuffer& b = out.buffer();
    auto it = std::back_inserter(b);
    const TelegramTracker& tracker = *c.tracker;
    fmt::format_to(it, "dpscope {} conformance report\n", c.version);
    fmt::format_to(it, "Input:   {} ({}), {}", c.input.name, c.input.format,
                   counted(c.summary->telegrams(), "telegram", "telegrams"));
    if (c.summary->first_time_ns() != kNoTime) {
        append(b, ", ");
        append_iso_time(b, c.summary->first_time_ns());
        append(b, " to ");
        append_iso_time(b, c.summary->last_time_ns());
    }
    b.push_back('\n');
    if (c.input.damaged)
        append(b, "         the input ended in damage; the report covers what was read\n");
    if (const std::string bus = bus_text(c); !bus.empty()) fmt::format_to(it, "Bus:     {}\n", bus);
    if (report_of(c).checks_rc8_rule)
        fmt::format_to(it, "Checks:  {}; RC 8 after a read is {}\n", timeout_rule_text(c, m),
                       tracker.strict() ? "an unexpected response (strict)" : "unusual, a warning");
    else
        fmt::format_to(it, "Checks:  {}\n", checks_text(c, m));
    if (!c.stations.empty() || !c.display_filter.empty())
        fmt::format_to(it, "Filter:  {} (telegram counts cover the whole capture)\n",
                       filter_text(c));
    fmt::format_to(it, "Result:  {}\n\n", verdict_text(c, m));
    append(b, "Summary\n");
    fmt::format_to(it, "  telegrams      {}\n", c.summary->telegrams());
    fmt::format_to(it, "  bytes skipped  {}\n", c.input.bytes_skipped);
    fmt::format_to(it, "  {:<14} {}\n", checksum_errors_label(c), m.fcs_errors);
    fmt::format_to(it, "  transactions   {}\n", m.transactions);
    fmt::format_to(it, "  findings       {}\n", findings_text(m));
    for (const auto& section : m.stations)
        section->write_text(c, b);
    if (m.has_bus_findings)
        fmt::format_to(it, "\nBus (telegrams no station can be named for)\n  findings       {}\n",
                       findings_by_kind_text(bus_stats(c).findings));
    if (c.health) {
        append(b, "\nBus health\n");
        health::text_segment(b, *c.health, "  ");
        health::text_tables(b, *c.health, "  ");
        out.end_record();
    }
    fmt::format_to(it, "\nFindings ({}, in capture order)\n", m.shown);
    // The kind column is as wide as the longest kind name.
    const std::size_t kind_width = longest_finding_kind_name();
    if (m.shown > 0)
        fmt::format_to(it, "  {:>8}  {:>12}  {:<8} {:<{}} {:<12} {:>5}  {}\n", "frame", "time (s)",
                       "severity", "kind", kind_width, "master/slave", "pnu", "message");
    FindingCounts listed{};
    c.findings->for_each([&](const Finding& f) {
        if (!shows(c, f) || listed[static_cast<std::size_t>(f.kind)]++ >= kListedPerKind) return;
        fmt::format_to(it, "  {:>8}  {:>12}  {:<8} {:<{}} {:<12} {:>5}  {}\n", f.frame,
                       relative_seconds(c, f.time_ns), severity_name(f.severity),
                       finding_kind_name(f.kind), kind_width, station_label(f),
                       f.pnu ? fmt::format("{}", *f.pnu) : std::string("-"), f.message);
        out.end_record();
    });
    for (FindingKind kind : kAllKinds)
        if (listed[static_cast<std::size_t>(kind)] > kListedPerKind)
            fmt::format_to(it, "  ({})\n", unlisted_text(kind, listed));
    if (const std::string lost = not_listed_text(c); !lost.empty())
        fmt::format_to(it, "  ({})\n", lost);
    out.end_record();
}

}  // namespace dpscope::report
