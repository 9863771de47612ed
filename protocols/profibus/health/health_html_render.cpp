// The bus-health HTML: the capture as a key-value table, and the tables with the charts
// (protocols/profibus/health/health_charts_render.cpp) under <h3> headings, for the HTML report.
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
using detail::number;
using detail::slave_table;
using detail::Table;
using detail::threshold_value;
using report::escape_xml;
using report::xml;

namespace {

std::string_view verdict_colour(std::string_view verdict) {
    if (verdict == "bad") return "#b42318";
    if (verdict == "weak") return "#a15c07";
    return "#1b6b34";
}

void html_table(TextBuffer& b, const Table& t, std::string_view cls) {
    auto it = std::back_inserter(b);
    fmt::format_to(it, "<div class=\"scroll\"><table class=\"{}\">\n<tr>", cls);
    for (std::size_t i = 0; i < t.headers.size(); ++i) {
        append(b, t.numeric[i] ? "<th class=\"n\">" : "<th>");
        escape_xml(b, t.headers[i]);
        append(b, "</th>");
    }
    append(b, "</tr>\n");
    for (const auto& row : t.rows) {
        append(b, "<tr>");
        for (std::size_t i = 0; i < row.size(); ++i) {
            if (t.headers[i] == "verdict")
                fmt::format_to(it, "<td class=\"verdict-{}\" style=\"color:{};font-weight:600\">",
                               xml(row[i]), verdict_colour(row[i]));
            else
                append(b, t.numeric[i] ? "<td class=\"n\">" : "<td>");
            escape_xml(b, row[i]);
            append(b, "</td>");
        }
        append(b, "</tr>\n");
    }
    append(b, "</table></div>\n");
}

}  // namespace

void html_segment(TextBuffer& b, const BusHealth& h) {
    auto it = std::back_inserter(b);
    const SegmentHealth& s = h.segment;
    append(b, "<table class=\"kv segment\">\n");
    if (s.has_time()) {
        TextBuffer span;
        append_iso_time(span, s.first_ns);
        append(span, " to ");
        append_iso_time(span, s.end_ns);
        fmt::format_to(std::back_inserter(span), " ({:.6f} s)", s.duration_s());
        report::html_kv(b, "capture", fmt::to_string(span));
    } else {
        report::html_kv(b, "capture", "no timestamps (counts only, no rates)");
    }
    report::html_kv(b, "telegrams", number(s.telegrams));
    report::html_kv(b, "telegrams per second",
                    s.duration_s() > 0 ? fmt::format("{:.1f}", s.telegrams_per_second()) : "-");
    report::html_kv(b, "bytes", number(s.bytes));
    report::html_kv(
        b, "bus load",
        s.load_percent() >= 0
            ? fmt::format("{:.2f} % at {} baud", s.load_percent(), s.baud)
            : fmt::format("unknown ({})", s.duration_s() <= 0 ? "no timestamps" : "give --baud"));
    report::html_kv(b, "idle", s.idle_s() >= 0 ? fmt::format("{:.6f} s", s.idle_s()) : "unknown");
    report::html_kv(
        b, "damaged",
        fmt::format("{} ({} no station could be named for)", s.damaged, s.unattributed_damaged));
    const std::string_view verdict = verdict_name(s.judgement.verdict);
    if (!s.judged())
        append(b,
               "<tr><th>verdict</th><td class=\"verdict-none\" id=\"segment-verdict\">not "
               "judged (no telegrams)</td></tr>\n");
    else
        fmt::format_to(it,
                       "<tr><th>verdict</th><td class=\"verdict-{}\" id=\"segment-verdict\" "
                       "style=\"color:{};font-weight:600\">{}</td></tr>\n",
                       verdict, verdict_colour(verdict), verdict);
    if (!s.judgement.reasons.empty())
        report::html_kv(b, "reasons", reasons_text(s.judgement, h.thresholds));
    append(b, "</table>\n");
}

void html_tables(TextBuffer& b, const BusHealth& h) {
    auto it = std::back_inserter(b);
    fmt::format_to(it, "<h3>Live list ({})</h3>\n",
                   counted(h.stations.size(), "station", "stations"));
    if (h.stations.empty()) {
        append(b, "<p class=\"meta\">No stations.</p>\n");
    } else {
        html_table(b, live_list(h), "live");
        append(b, "<h3>State over the capture</h3>\n");
        svg_state_timeline(b, h);
    }
    append(b, "<h3>Slaves</h3>\n");
    const Table slaves = slave_table(h);
    if (slaves.rows.empty())
        append(b, "<p class=\"meta\">None.</p>\n");
    else
        html_table(b, slaves, "health-slaves");
    append(b, "<h3>Masters (times in ms)</h3>\n");
    if (h.masters.empty()) {
        append(b, "<p class=\"meta\">None.</p>\n");
    } else {
        html_table(b, master_table(h), "health-masters");
        for (const MasterHealth& m : h.masters) {
            fmt::format_to(it, "<h3>Master {}: cycle time and token rotation</h3>\n", m.address);
            svg_master_plot(b, h, m);
        }
    }
    append(b, "<h3>Verdicts</h3>\n");
    const std::vector<Judged> judged = not_good(h);
    if (!h.segment.judged()) {
        append(b, "<p class=\"meta\">Nothing judged: no telegrams.</p>\n");
    } else if (judged.empty()) {
        append(b, "<p class=\"meta\">Every station and master good.</p>\n");
    } else {
        append(b, "<ul class=\"verdicts\">\n");
        for (const Judged& j : judged) {
            const std::string_view verdict = verdict_name(j.judgement->verdict);
            fmt::format_to(it, "<li>{}: <strong style=\"color:{}\">{}</strong><ul>", xml(j.who),
                           verdict_colour(verdict), verdict);
            for (const VerdictReason& r : j.judgement->reasons) {
                append(b, "<li>");
                escape_xml(b, describe_reason(r, h.thresholds));
                append(b, "</li>");
            }
            append(b, "</ul></li>\n");
        }
        append(b, "</ul>\n");
    }
    append(b, "<h3>Thresholds</h3>\n");
    bool any = false;
    for (const HealthThresholdRow& row : health_threshold_catalogue()) {
        if (!differs_from_default(h.thresholds, row.kind)) continue;
        if (!any)
            append(b,
                   "<table class=\"thresholds\"><tr><th>threshold</th><th class=\"n\">value"
                   "</th><th class=\"n\">default</th></tr>\n");
        any = true;
        fmt::format_to(it, "<tr><td>{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td></tr>\n",
                       xml(row.name), threshold_value(h.thresholds.get(row.kind)),
                       threshold_value(row.default_value));
    }
    append(b, any ? "</table>\n" : "<p class=\"meta\">The defaults.</p>\n");
}

}  // namespace dpscope::health
