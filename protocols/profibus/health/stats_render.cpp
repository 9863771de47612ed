// `dpscope stats` in its five formats, and the live table of `sniff --stats`. The tables, JSON
// objects and charts are those of protocols/profibus/health/health_render.hpp, shared with the
// report's bus-health section.
#include "protocols/profibus/health/stats_render.hpp"

#include <iterator>

#include "formats/report_markup.hpp"
#include "protocols/profibus/health/health_render.hpp"

namespace dpscope {

std::string_view stats_format_name(StatsFormat format) {
    switch (format) {
        case StatsFormat::Json: return "json";
        case StatsFormat::Markdown: return "markdown";
        case StatsFormat::Html: return "html";
        case StatsFormat::Csv: return "csv";
        case StatsFormat::Text: break;
    }
    return "text";
}

std::optional<StatsFormat> stats_format_from_name(std::string_view name) {
    for (StatsFormat f : {StatsFormat::Text, StatsFormat::Json, StatsFormat::Markdown,
                          StatsFormat::Html, StatsFormat::Csv})
        if (stats_format_name(f) == name) return f;
    return std::nullopt;
}

namespace {

void stats_text(const StatsContext& c, TextBuffer& b) {
    auto it = std::back_inserter(b);
    fmt::format_to(it, "dpscope {} bus health\n", c.version);
    fmt::format_to(it, "Input:     {} ({})\n", c.input.name, c.input.format);
    if (c.input.damaged)
        append(b, "           the input ended in damage; the statistics cover what was read\n");
    health::text_segment(b, *c.health, "");
    health::text_tables(b, *c.health);
}

void stats_json(const StatsContext& c, TextBuffer& b) {
    JsonWriter w(b);
    w.begin_object();
    w.key("dpscope").string(c.version);
    w.key("input").begin_object();
    w.key("file").string(c.input.name);
    w.key("format").string(c.input.format);
    w.key("damaged").boolean(c.input.damaged);
    w.key("bytes_skipped").integer(static_cast<std::int64_t>(c.input.bytes_skipped));
    w.end_object();
    health::write_json_members(w, *c.health);
    w.end_object();
    b.push_back('\n');
}

void stats_markdown(const StatsContext& c, TextBuffer& b) {
    auto it = std::back_inserter(b);
    append(b, "# dpscope bus health\n\n");
    fmt::format_to(it, "- Input: {} ({}){}\n", report::md_escape(c.input.name),
                   report::md_escape(c.input.format), c.input.damaged ? " (ended in damage)" : "");
    health::markdown_segment(b, *c.health);
    fmt::format_to(it, "- dpscope {}\n", report::md_escape(c.version));
    health::markdown_tables(b, *c.health, "##");
}

void stats_html(const StatsContext& c, TextBuffer& b) {
    auto it = std::back_inserter(b);
    using report::xml;
    fmt::format_to(it,
                   "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                   "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
                   "<title>dpscope bus health: {}</title>\n<style>{}</style>\n</head>\n<body>\n",
                   xml(c.input.name), report::html_style());
    append(b, "<h1>dpscope bus health</h1>\n");
    fmt::format_to(it, "<p class=\"meta\">{} ({}) &middot; dpscope {}</p>\n", xml(c.input.name),
                   xml(c.input.format), xml(c.version));
    if (c.input.damaged)
        append(b,
               "<p class=\"error\">The input ended in damage; the statistics cover what was "
               "read.</p>\n");
    append(b, "<section class=\"bus\" id=\"bus-health\">\n<h2>Segment</h2>\n");
    health::html_segment(b, *c.health);
    health::html_tables(b, *c.health);
    append(b, "</section>\n</body>\n</html>\n");
}

}  // namespace

void render_stats(StatsFormat format, const StatsContext& context, Output& out) {
    if (context.health == nullptr) return;
    TextBuffer& b = out.buffer();
    switch (format) {
        case StatsFormat::Text: stats_text(context, b); break;
        case StatsFormat::Json: stats_json(context, b); break;
        case StatsFormat::Markdown: stats_markdown(context, b); break;
        case StatsFormat::Html: stats_html(context, b); break;
        case StatsFormat::Csv: health::write_csv(b, *context.health); break;
    }
    out.end_record();
}

void render_live_table(const BusHealth& health, Output& out, unsigned width) {
    TextBuffer& b = out.buffer();
    auto line = [&](const std::string& text) {
        std::string_view shown = text;
        if (width > 0 && shown.size() > width) shown = shown.substr(0, width);
        append(b, shown);
        b.push_back('\n');
    };
    constexpr std::string_view kRow =
        "{:>4} {:<7} {:<14} {:>9} {:>9} {:>7} {:>7} {:>5} {:>5} {:>5} {}";
    line(fmt::format(fmt::runtime(kRow), "addr", "role", "state", "requests", "answers", "no ans",
                     "repeats", "lost", "illeg", "dmg", "verdict"));
    for (const StationHealth& s : health.stations)
        line(fmt::format(fmt::runtime(kRow), s.address, station_role_name(s.role),
                         station_state_name(s.state), s.requests, s.answers, s.no_answers,
                         s.repeats, s.lost_events, s.illegal_answers_total(), s.fcs_errors,
                         verdict_name(s.judgement.verdict)));
    const SegmentHealth& seg = health.segment;
    std::string segment = fmt::format("segment: {} telegrams", seg.telegrams);
    segment += seg.duration_s() > 0 ? fmt::format(", {:.1f} tel/s", seg.telegrams_per_second())
                                    : std::string(", - tel/s");
    segment += seg.load_percent() >= 0 ? fmt::format(", load {:.1f} %", seg.load_percent())
                                       : std::string(", load unknown");
    segment += fmt::format(", {} damaged, verdict {}", seg.damaged,
                           seg.judged() ? verdict_name(seg.judgement.verdict) : "-");
    line(segment);
    out.end_record();
}

}  // namespace dpscope
