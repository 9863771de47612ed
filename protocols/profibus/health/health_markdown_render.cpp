// The bus-health Markdown: the capture as a list and the tables, for the Markdown report.
#include <iterator>
#include <vector>

#include "formats/report_markup.hpp"
#include "protocols/profibus/health/health_render.hpp"
#include "protocols/profibus/health/health_tables_render.hpp"

namespace dpscope::health {

using detail::Judged;
using detail::live_list;
using detail::master_table;
using detail::not_good;
using detail::slave_table;
using detail::Table;
using detail::threshold_value;
using report::md_escape;

namespace {

void markdown_table(TextBuffer& b, const Table& t) {
    append(b, "|");
    for (std::string_view header : t.headers) {
        append(b, " ");
        append(b, md_escape(header));
        append(b, " |");
    }
    append(b, "\n|");
    for (bool numeric : t.numeric)
        append(b, numeric ? "---:|" : "---|");
    b.push_back('\n');
    for (const auto& row : t.rows) {
        append(b, "|");
        for (const std::string& cell : row) {
            append(b, " ");
            append(b, md_escape(cell));
            append(b, " |");
        }
        b.push_back('\n');
    }
}

}  // namespace

void markdown_segment(TextBuffer& b, const BusHealth& h) {
    auto it = std::back_inserter(b);
    const SegmentHealth& s = h.segment;
    if (s.has_time()) {
        append(b, "- Capture: ");
        append_iso_time(b, s.first_ns);
        append(b, " to ");
        append_iso_time(b, s.end_ns);
        fmt::format_to(it, " ({:.6f} s)\n", s.duration_s());
    } else {
        append(b, "- Capture: no timestamps (counts only, no rates)\n");
    }
    fmt::format_to(it, "- Telegrams: {}", s.telegrams);
    if (s.duration_s() > 0) fmt::format_to(it, ", {:.1f} per second", s.telegrams_per_second());
    fmt::format_to(it, ", {}\n", counted(s.bytes, "byte", "bytes"));
    if (s.load_percent() >= 0)
        fmt::format_to(it, "- Bus load: {:.2f} % at {} baud, idle {:.6f} s\n", s.load_percent(),
                       s.baud, s.idle_s());
    else
        fmt::format_to(it, "- Bus load: unknown ({})\n",
                       s.duration_s() <= 0 ? "no timestamps" : "give --baud");
    fmt::format_to(it, "- Damaged: {} ({} no station could be named for)\n", s.damaged,
                   s.unattributed_damaged);
    if (!s.judged())
        append(b, "- Segment: **not judged** (no telegrams)\n");
    else
        fmt::format_to(it, "- Segment: **{}**\n", verdict_name(s.judgement.verdict));
    for (const VerdictReason& r : s.judgement.reasons)
        fmt::format_to(it, "  - {}\n", md_escape(describe_reason(r, h.thresholds)));
}

void markdown_tables(TextBuffer& b, const BusHealth& h, std::string_view level) {
    auto it = std::back_inserter(b);
    fmt::format_to(it, "\n{} Live list ({})\n\n", level,
                   counted(h.stations.size(), "station", "stations"));
    if (h.stations.empty())
        append(b, "No stations.\n");
    else
        markdown_table(b, live_list(h));
    fmt::format_to(it, "\n{} Slaves\n\n", level);
    const Table slaves = slave_table(h);
    if (slaves.rows.empty())
        append(b, "None.\n");
    else
        markdown_table(b, slaves);
    fmt::format_to(it, "\n{} Masters (times in ms)\n\n", level);
    if (h.masters.empty())
        append(b, "None.\n");
    else
        markdown_table(b, master_table(h));
    fmt::format_to(it, "\n{} Verdicts\n\n", level);
    const std::vector<Judged> judged = not_good(h);
    if (!h.segment.judged())
        append(b, "Nothing judged: no telegrams.\n");
    else if (judged.empty())
        append(b, "Every station and master good.\n");
    for (const Judged& j : judged) {
        fmt::format_to(it, "- {}: **{}**\n", md_escape(j.who), verdict_name(j.judgement->verdict));
        for (const VerdictReason& r : j.judgement->reasons)
            fmt::format_to(it, "  - {}\n", md_escape(describe_reason(r, h.thresholds)));
    }
    fmt::format_to(it, "\n{} Thresholds\n\n", level);
    bool any = false;
    for (const HealthThresholdRow& row : health_threshold_catalogue()) {
        if (!differs_from_default(h.thresholds, row.kind)) continue;
        if (!any) append(b, "| threshold | value | default |\n|---|---:|---:|\n");
        any = true;
        fmt::format_to(it, "| {} | {} | {} |\n", md_escape(row.name),
                       threshold_value(h.thresholds.get(row.kind)),
                       threshold_value(row.default_value));
    }
    if (!any) append(b, "The defaults.\n");
}

}  // namespace dpscope::health
