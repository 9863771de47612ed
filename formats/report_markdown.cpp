// The Markdown report.
#include <iterator>

#include "formats/report_markup.hpp"
#include "formats/report_model.hpp"
#include "protocols/profibus/health/health_render.hpp"

namespace dpscope::report {

void write_markdown(const ReportContext& c, const ReportModel& m, Output& out) {
    TextBuffer& b = out.buffer();
    auto it = std::back_inserter(b);
    const TelegramTracker& tracker = *c.tracker;
    fmt::format_to(it, "# dpscope conformance report\n\n");
    fmt::format_to(it, "**{}**\n\n", verdict_text(c, m));
    fmt::format_to(it, "- Input: `{}` ({}), {}{}\n", c.input.name, c.input.format,
                   counted(c.summary->telegrams(), "telegram", "telegrams"),
                   c.input.damaged ? " (ended in damage)" : "");
    if (const std::string bus = bus_text(c); !bus.empty()) fmt::format_to(it, "- Bus: {}\n", bus);
    if (report_of(c).checks_rc8_rule)
        fmt::format_to(it, "- Checks: {}; RC 8 after a read: {}\n", timeout_rule_text(c, m),
                       tracker.strict() ? "strict" : "lenient");
    else
        fmt::format_to(it, "- Checks: {}\n", checks_text(c, m));
    if (!c.stations.empty() || !c.display_filter.empty())
        fmt::format_to(it, "- Filter: {} (telegram counts cover the whole capture)\n",
                       filter_text(c));
    fmt::format_to(it, "- dpscope {}\n\n", c.version);
    fmt::format_to(it,
                   "## Summary\n\n| telegrams | bytes skipped | {} | transactions | errors | "
                   "warnings | notes |\n"
                   "|---:|---:|---:|---:|---:|---:|---:|\n",
                   checksum_errors_label(c));
    fmt::format_to(it, "| {} | {} | {} | {} | {} | {} | {} |\n\n", c.summary->telegrams(),
                   c.input.bytes_skipped, m.fcs_errors, m.transactions, m.errors(), m.warnings(),
                   m.notes());
    append(b, bus_wording(c).markdown_table);
    for (const auto& section : m.stations)
        section->write_markdown_row(c, b);
    for (const auto& section : m.stations)
        section->write_markdown(c, b);
    if (m.has_bus_findings)
        fmt::format_to(it, "\n### Bus (telegrams no station can be named for)\n\n- Findings: {}\n",
                       md_escape(findings_by_kind_text(bus_stats(c).findings)));
    if (c.health) {
        append(b, "\n## Bus health\n\n");
        health::markdown_segment(b, *c.health);
        health::markdown_tables(b, *c.health, "###");
        out.end_record();
    }
    fmt::format_to(it, "\n## Findings ({})\n\n", m.shown);
    if (m.shown > 0)
        append(b,
               "| frame | time (s) | severity | kind | master / slave | PNU | message |\n"
               "|---:|---:|---|---|---|---:|---|\n");
    FindingCounts listed{};
    c.findings->for_each([&](const Finding& f) {
        if (!shows(c, f) || listed[static_cast<std::size_t>(f.kind)]++ >= kListedPerKind) return;
        fmt::format_to(it, "| {} | {} | {} | {} | {} | {} | {} |\n", f.frame,
                       relative_seconds(c, f.time_ns), severity_name(f.severity),
                       md_escape(finding_kind_name(f.kind)), station_label(f),
                       f.pnu ? fmt::format("{}", *f.pnu) : std::string("-"), md_escape(f.message));
        out.end_record();
    });
    bool first_unlisted = true;
    for (FindingKind kind : kAllKinds)
        if (listed[static_cast<std::size_t>(kind)] > kListedPerKind) {
            fmt::format_to(it, "{}- {}\n", first_unlisted ? "\n" : "",
                           md_escape(unlisted_text(kind, listed)));
            first_unlisted = false;
        }
    if (const std::string lost = not_listed_text(c); !lost.empty())
        fmt::format_to(it, "\n{}\n", md_escape(lost));
    out.end_record();
}

}  // namespace dpscope::report
