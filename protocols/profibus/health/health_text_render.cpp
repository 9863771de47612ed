// The bus-health text: the capture's lines and the tables, as `dpscope stats` and the text report
// show them.
#include <algorithm>
#include <iterator>
#include <vector>

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

namespace {

void text_table(TextBuffer& b, const Table& t) {
    std::vector<std::size_t> widths(t.headers.size());
    for (std::size_t i = 0; i < t.headers.size(); ++i)
        widths[i] = t.headers[i].size();
    for (const auto& row : t.rows)
        for (std::size_t i = 0; i < row.size(); ++i)
            widths[i] = std::max(widths[i], row[i].size());
    auto line = [&](auto cell_of) {
        std::string text = " ";
        for (std::size_t i = 0; i < t.headers.size(); ++i) {
            std::string_view cell = cell_of(i);
            std::string pad(widths[i] - cell.size(), ' ');
            text += ' ';
            text += t.numeric[i] ? pad + std::string(cell) : std::string(cell) + pad;
            text += ' ';
        }
        while (!text.empty() && text.back() == ' ')
            text.pop_back();
        append(b, text);
        b.push_back('\n');
    };
    line([&](std::size_t i) { return t.headers[i]; });
    for (const auto& row : t.rows)
        line([&](std::size_t i) { return std::string_view(row[i]); });
}

}  // namespace

void text_segment(TextBuffer& b, const BusHealth& h, std::string_view indent) {
    auto it = std::back_inserter(b);
    const SegmentHealth& s = h.segment;
    if (s.has_time()) {
        fmt::format_to(it, "{}Capture:   ", indent);
        append_iso_time(b, s.first_ns);
        append(b, " to ");
        append_iso_time(b, s.end_ns);
        fmt::format_to(it, " ({:.6f} s)\n", s.duration_s());
    } else {
        fmt::format_to(it, "{}Capture:   no timestamps: counts only, no rates\n", indent);
    }
    fmt::format_to(it, "{}Telegrams: {}", indent, s.telegrams);
    if (s.duration_s() > 0) fmt::format_to(it, ", {:.1f} per second", s.telegrams_per_second());
    fmt::format_to(it, ", {}\n", counted(s.bytes, "byte", "bytes"));
    if (s.load_percent() >= 0)
        fmt::format_to(it, "{}Bus load:  {:.2f} % at {} baud, idle {:.6f} s\n", indent,
                       s.load_percent(), s.baud, s.idle_s());
    else if (s.duration_s() <= 0)
        fmt::format_to(it, "{}Bus load:  unknown (no timestamps)\n", indent);
    else
        fmt::format_to(it, "{}Bus load:  unknown (give --baud)\n", indent);
    fmt::format_to(it, "{}Damaged:   {} ({} no station could be named for)\n", indent, s.damaged,
                   s.unattributed_damaged);
    const std::string cause = segment_cause(h);
    if (!s.judged())
        fmt::format_to(it, "{}Segment:   not judged (no telegrams)\n", indent);
    else
        fmt::format_to(it, "{}Segment:   {}{}\n", indent, verdict_name(s.judgement.verdict),
                       cause.empty() ? "" : fmt::format(" ({})", cause));
    for (const VerdictReason& r : s.judgement.reasons)
        fmt::format_to(it, "{}           - {}\n", indent, describe_reason(r, h.thresholds));
}

void text_tables(TextBuffer& out, const BusHealth& h, std::string_view indent) {
    TextBuffer b;
    auto it = std::back_inserter(b);
    if (h.stations.empty()) {
        append(b, "\nLive list: no stations\n");
    } else {
        fmt::format_to(it, "\nLive list ({})\n", counted(h.stations.size(), "station", "stations"));
        text_table(b, live_list(h));
    }
    const Table slaves = slave_table(h);
    if (slaves.rows.empty()) {
        append(b, "\nSlaves: none\n");
    } else {
        append(b, "\nSlaves (as asked: counts of requests to them and their answers)\n");
        text_table(b, slaves);
    }
    if (h.masters.empty()) {
        append(b, "\nMasters: none\n");
    } else {
        append(b, "\nMasters (times in ms)\n");
        text_table(b, master_table(h));
    }
    const std::vector<Judged> judged = not_good(h);
    append(b, "\nVerdicts\n");
    if (!h.segment.judged())
        append(b, "  nothing judged: no telegrams\n");
    else if (judged.empty())
        append(b, "  every station and master good\n");
    for (const Judged& j : judged) {
        fmt::format_to(it, "  {}: {}\n", j.who, verdict_name(j.judgement->verdict));
        for (const VerdictReason& r : j.judgement->reasons)
            fmt::format_to(it, "    - {}\n", describe_reason(r, h.thresholds));
    }
    bool any = false;
    for (const HealthThresholdRow& row : health_threshold_catalogue()) {
        if (!differs_from_default(h.thresholds, row.kind)) continue;
        if (!any) append(b, "\nThresholds (other than the defaults)\n");
        any = true;
        fmt::format_to(it, "  {} = {} (default {})\n", row.name,
                       threshold_value(h.thresholds.get(row.kind)),
                       threshold_value(row.default_value));
    }
    if (!any) append(b, "\nThresholds: the defaults\n");
    // Every line but the empty ones indented (the report nests the tables in its section).
    const std::string_view text(b.data(), b.size());
    std::size_t start = 0;
    while (start < text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string_view::npos) end = text.size() - 1;
        if (end > start) append(out, indent);
        append(out, text.substr(start, end - start + 1));
        start = end + 1;
    }
}

}  // namespace dpscope::health
