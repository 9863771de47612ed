// The HTML report: one self-contained file with inline SVG.
#include <iterator>

#include "formats/report_markup.hpp"
#include "formats/report_model.hpp"
#include "protocols/profibus/health/health_render.hpp"

namespace dpscope::report {

namespace {

constexpr std::size_t kHtmlFindingRows = 2000;

constexpr std::string_view kHtmlStyle = R"(
body { font: 14px/1.45 system-ui, -apple-system, "Segoe UI", sans-serif; color: #1d2330;
       margin: 0 auto; max-width: 1100px; padding: 24px; background: #fafbfc; }
h1 { font-size: 24px; margin: 0 0 4px; }
h2 { font-size: 19px; margin: 32px 0 8px; border-bottom: 1px solid #d8dde6; padding-bottom: 4px; }
h3 { font-size: 15px; margin: 18px 0 6px; color: #394150; }
.meta { color: #5b6476; margin: 0 0 12px; }
.verdict { display: inline-block; padding: 6px 14px; border-radius: 6px; font-weight: 600; }
.verdict.pass { background: #e3f4e8; color: #1b6b34; border: 1px solid #9fd3ae; }
.verdict.fail { background: #fde8e8; color: #9b1c1c; border: 1px solid #f1a9a9; }
.cards { display: flex; flex-wrap: wrap; gap: 12px; margin: 12px 0; }
.card { background: #fff; border: 1px solid #d8dde6; border-radius: 8px; padding: 10px 16px;
        min-width: 110px; }
.card .n { font-size: 22px; font-weight: 600; }
.card .l { color: #5b6476; font-size: 12px; text-transform: uppercase; letter-spacing: .04em; }
table { border-collapse: collapse; background: #fff; margin: 6px 0 12px; }
th, td { border: 1px solid #d8dde6; padding: 4px 8px; text-align: left; vertical-align: top; }
th { background: #eef1f6; font-weight: 600; }
td.n, th.n { text-align: right; font-variant-numeric: tabular-nums; }
table.kv th { width: 190px; }
section.station, section.bus { background: #fff; border: 1px solid #d8dde6; border-radius: 8px;
                  padding: 4px 18px 14px; margin: 18px 0; }
td.error, .card.error, p.error { color: #b42318; }
td.warning, .card.warning { color: #a15c07; }
td.note, .card.note { color: #175cd3; }
tr.error td:first-child { border-left: 4px solid #d92d20; }
tr.warning td:first-child { border-left: 4px solid #f79009; }
tr.note td:first-child { border-left: 4px solid #2e90fa; }
svg { background: #fff; display: block; max-width: 100%; height: auto; }
.scroll { overflow-x: auto; max-width: 100%; }
table.findings td:last-child { overflow-wrap: anywhere; }
section.station h2, section.bus h2 { margin-top: 14px; }
svg text { font: 11px system-ui, sans-serif; fill: #394150; }
.legend span { display: inline-block; margin-right: 14px; font-size: 12px; }
.swatch { display: inline-block; width: 10px; height: 10px; margin-right: 4px; vertical-align: -1px; }
)";

}  // namespace

std::string_view html_style() { return kHtmlStyle; }

void write_html(const ReportContext& c, const ReportModel& m, Output& out) {
    TextBuffer& b = out.buffer();
    auto it = std::back_inserter(b);
    const TelegramTracker& tracker = *c.tracker;
    fmt::format_to(it,
                   "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                   "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
                   "<title>dpscope report: {}</title>\n<style>{}</style>\n</head>\n<body>\n",
                   xml(c.input.name), kHtmlStyle);
    append(b, "<h1>dpscope conformance report</h1>\n");
    if (report_of(c).checks_rc8_rule)
        fmt::format_to(it,
                       "<p class=\"meta\">{} ({}) &middot; dpscope {} &middot; {} "
                       "&middot; RC 8 rule {}</p>\n",
                       xml(c.input.name), xml(c.input.format), xml(c.version),
                       timeout_rule_text(c, m), tracker.strict() ? "strict" : "lenient");
    else
        fmt::format_to(it,
                       "<p class=\"meta\">{} ({}) &middot; dpscope {} &middot; {} &middot; {}"
                       "</p>\n",
                       xml(c.input.name), xml(c.input.format), xml(c.version), xml(bus_text(c)),
                       xml(checks_text(c, m)));
    if (!c.stations.empty() || !c.display_filter.empty())
        fmt::format_to(it,
                       "<p class=\"meta\">Filter: {} (telegram counts cover the whole "
                       "capture)</p>\n",
                       xml(filter_text(c)));
    fmt::format_to(it, "<p class=\"verdict {}\" id=\"verdict\">{}</p>\n", m.fails ? "fail" : "pass",
                   xml(verdict_text(c, m)));
    if (c.input.damaged)
        append(b,
               "<p class=\"error\">The input ended in damage; the report covers what was "
               "read.</p>\n");
    append(b, "<section id=\"summary\">\n<h2>Summary</h2>\n<div class=\"cards\">\n");
    auto card = [&](std::string_view label, std::uint64_t n, std::string_view cls) {
        fmt::format_to(it,
                       "<div class=\"card {}\"><div class=\"n\">{}</div><div class=\"l\">{}</div>"
                       "</div>\n",
                       cls, n, label);
    };
    card("telegrams", c.summary->telegrams(), "");
    card("bytes skipped", c.input.bytes_skipped, "");
    card(checksum_errors_label(c), m.fcs_errors, "");
    card("transactions", m.transactions, "");
    card(bus_wording(c).stations, m.slaves, "");
    card("errors", m.errors(), "error");
    card("warnings", m.warnings(), "warning");
    card("notes", m.notes(), "note");
    append(b, "</div>\n<div class=\"scroll\"><table class=\"slaves\">\n");
    append(b, bus_wording(c).html_table);
    for (const auto& section : m.stations)
        section->write_html_row(c, b);
    append(b, "</table></div>\n</section>\n");

    for (const auto& section : m.stations) {
        section->write_html(c, b);
        out.end_record();
    }
    if (m.has_bus_findings) {
        append(b,
               "<section class=\"bus\" id=\"bus\">\n<h2>Bus (telegrams no station can be "
               "named for)</h2>\n");
        html_findings_by_kind(b, bus_stats(c).findings, bus_stats(c).findings_by_severity);
        append(b, "</section>\n");
        out.end_record();
    }

    if (c.health) {
        append(b, "<section class=\"bus\" id=\"bus-health\">\n<h2>Bus health</h2>\n");
        health::html_segment(b, *c.health);
        health::html_tables(b, *c.health);
        append(b, "</section>\n");
        out.end_record();
    }

    fmt::format_to(it, "<section id=\"findings\">\n<h2>Findings ({})</h2>\n", m.shown);
    if (m.shown == 0) {
        append(b, "<p class=\"meta\">No findings.</p>\n");
    } else {
        append(b,
               "<div class=\"scroll\"><table class=\"findings\">\n<tr><th "
               "class=\"n\">frame</th><th class=\"n\">time "
               "(s)</th><th>severity</th><th>kind</th><th>master / slave</th><th "
               "class=\"n\">PNU</th><th>message</th></tr>\n");
        std::size_t rows = 0;
        c.findings->for_each([&](const Finding& f) {
            if (!shows(c, f) || rows++ >= kHtmlFindingRows) return;
            std::string_view severity = severity_name(f.severity);
            fmt::format_to(it,
                           "<tr class=\"{}\"><td class=\"n\">{}</td><td class=\"n\">{}</td><td "
                           "class=\"{}\">{}</td><td>{}</td><td>{}</td><td class=\"n\">{}</td><td>{}"
                           "</td></tr>\n",
                           severity, f.frame, relative_seconds(c, f.time_ns), severity, severity,
                           finding_kind_name(f.kind), xml(station_label(f)),
                           f.pnu ? fmt::format("{}", *f.pnu) : std::string("-"), xml(f.message));
            out.end_record();
        });
        append(b, "</table></div>\n");
        if (rows > kHtmlFindingRows)
            fmt::format_to(it,
                           "<p class=\"meta\">{} not listed here (at most {}; the JSON report "
                           "lists them all).</p>\n",
                           counted(rows - kHtmlFindingRows, "more finding", "more findings"),
                           kHtmlFindingRows);
    }
    if (const std::string lost = not_listed_text(c); !lost.empty())
        fmt::format_to(it, "<p class=\"meta\">{}</p>\n", xml(lost));
    append(b, "</section>\n</body>\n</html>\n");
    out.end_record();
}

}  // namespace dpscope::report
