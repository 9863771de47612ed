#include "formats/report_markup.hpp"

#include <algorithm>
#include <iterator>

#include "core/text_encoding.hpp"

namespace dpscope::report {

std::string md_escape(std::string_view text) {
    std::string out;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char ch = text[i];
        if (static_cast<unsigned char>(ch) >= 0x80) {
            // Valid UTF-8 as it is; a byte that starts no sequence becomes U+FFFD.
            const std::size_t length = utf8_sequence_length(text, i);
            if (length == 0) {
                out += kReplacementCharacter;
            } else {
                out.append(text.substr(i, length));
                i += length - 1;
            }
            continue;
        }
        if (ch == '\\' || ch == '|' || ch == '*' || ch == '_' || ch == '`' || ch == '<' ||
            ch == '>')
            out += '\\';
        out += ch;
    }
    return out;
}

void escape_xml(TextBuffer& b, std::string_view text) {
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char ch = text[i];
        const auto byte = static_cast<unsigned char>(ch);
        if (byte >= 0x80) {
            // XML and HTML here are UTF-8 (declared so): valid sequences as they are, a byte that
            // starts none becomes U+FFFD.
            const std::size_t length = utf8_sequence_length(text, i);
            if (length == 0) {
                append(b, kReplacementCharacter);
            } else {
                append(b, text.substr(i, length));
                i += length - 1;
            }
            continue;
        }
        // XML 1.0 allows no control character but tab, line feed and carriage return, not even
        // as a character reference.
        if ((byte < 0x20 && ch != '\t' && ch != '\n' && ch != '\r') || byte == 0x7F) {
            append(b, kReplacementCharacter);
            continue;
        }
        switch (ch) {
            case '&': append(b, "&amp;"); break;
            case '<': append(b, "&lt;"); break;
            case '>': append(b, "&gt;"); break;
            case '"': append(b, "&quot;"); break;
            case '\'': append(b, "&#39;"); break;
            default: b.push_back(ch);
        }
    }
}

std::string xml(std::string_view text) {
    TextBuffer b;
    escape_xml(b, text);
    return fmt::to_string(b);
}

void html_kv(TextBuffer& b, std::string_view key, std::string_view value) {
    append(b, "<tr><th>");
    escape_xml(b, key);
    append(b, "</th><td>");
    escape_xml(b, value);
    append(b, "</td></tr>\n");
}

std::array<std::uint64_t, 3> severity_totals(const FindingCounts& findings,
                                             const FindingSeverityCounts& by_severity) {
    std::array<std::uint64_t, 3> totals{};
    for (FindingKind kind : kAllKinds)
        if (findings[static_cast<std::size_t>(kind)])
            for (std::size_t level = 0; level < totals.size(); ++level)
                totals[level] += by_severity[static_cast<std::size_t>(kind)][level];
    return totals;
}

void html_findings_by_kind(TextBuffer& b, const FindingCounts& findings,
                           const FindingSeverityCounts& by_severity) {
    append(b, "<h3>Findings by kind</h3>\n");
    bool any = false;
    for (FindingKind kind : kAllKinds)
        any |= findings[static_cast<std::size_t>(kind)] > 0;
    if (!any) {
        append(b, "<p class=\"meta\">None.</p>\n");
        return;
    }
    append(b,
           "<table class=\"kinds\"><tr><th>kind</th><th>severity</th><th "
           "class=\"n\">count</th></tr>\n");
    for (FindingKind kind : kAllKinds) {
        if (!findings[static_cast<std::size_t>(kind)]) continue;
        for (Severity level : {Severity::Error, Severity::Warning, Severity::Note}) {
            std::uint64_t n =
                by_severity[static_cast<std::size_t>(kind)][static_cast<std::size_t>(level)];
            if (!n) continue;
            std::string_view severity = severity_name(level);
            fmt::format_to(std::back_inserter(b),
                           "<tr class=\"{}\"><td>{}</td><td class=\"{}\">{}</td><td "
                           "class=\"n\">{}</td></tr>\n",
                           severity, finding_kind_name(kind), severity, severity, n);
        }
    }
    append(b, "</table>\n");
}

void svg_latency_histogram(TextBuffer& b, const LogHistogram& h, bool answered,
                           std::string_view who) {
    auto it = std::back_inserter(b);
    if (h.count() == 0) {
        append(b, !answered
                      ? "<p class=\"meta\">No answered requests.</p>\n"
                      : "<p class=\"meta\">The capture carries no timestamps: latency in cycles "
                        "only (see above).</p>\n");
        return;
    }
    constexpr int kBars = 30, kWidth = 720, kHeight = 170, kLeft = 48, kBottom = 28, kTop = 10;
    const double max_ms = std::max(to_ms(h.max()), 0.001);
    std::array<std::uint64_t, kBars> bars{};
    h.for_each_bucket([&](std::uint64_t lower, std::uint64_t upper, std::uint64_t count) {
        double middle = to_ms(lower + (upper - lower) / 2);
        auto bar = static_cast<std::size_t>(std::min<double>(kBars - 1, middle / max_ms * kBars));
        bars[bar] += count;
    });
    std::uint64_t tallest = *std::max_element(bars.begin(), bars.end());
    const double bar_width = static_cast<double>(kWidth - kLeft - 10) / kBars;
    const int plot_height = kHeight - kBottom - kTop;
    fmt::format_to(it,
                   "<svg class=\"latency\" width=\"{}\" height=\"{}\" viewBox=\"0 0 {} {}\" "
                   "role=\"img\" aria-label=\"latency histogram of {}\">\n",
                   kWidth, kHeight, kWidth, kHeight, who);
    fmt::format_to(it, "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#8a93a6\"/>\n",
                   kLeft, kHeight - kBottom, kWidth - 10, kHeight - kBottom);
    for (int i = 0; i < kBars; ++i) {
        if (bars[static_cast<std::size_t>(i)] == 0) continue;
        double height = static_cast<double>(bars[static_cast<std::size_t>(i)]) /
                        static_cast<double>(tallest) * plot_height;
        double x = kLeft + i * bar_width;
        fmt::format_to(it,
                       "<rect class=\"bar\" x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" "
                       "height=\"{:.1f}\" fill=\"#4e79c5\"><title>{:.3f}-{:.3f} ms: {}"
                       "</title></rect>\n",
                       x + 1, kHeight - kBottom - height, bar_width - 2, height, max_ms * i / kBars,
                       max_ms * (i + 1) / kBars,
                       counted(bars[static_cast<std::size_t>(i)], "transaction", "transactions"));
    }
    fmt::format_to(it, "<text x=\"{}\" y=\"{}\">0 ms</text>\n", kLeft, kHeight - 10);
    fmt::format_to(it, "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{:.3f} ms</text>\n",
                   kWidth - 10, kHeight - 10, max_ms);
    fmt::format_to(it, "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text>\n", kLeft - 6,
                   kTop + 10, tallest);
    fmt::format_to(it, "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">0</text>\n", kLeft - 6,
                   kHeight - kBottom);
    append(b, "</svg>\n");
}

void svg_timeline(TextBuffer& b, const Timeline& timeline, std::string_view who,
                  const ReportContext& c) {
    auto it = std::back_inserter(b);
    if (timeline.empty()) {
        append(b, "<p class=\"meta\">No timed transactions or findings.</p>\n");
        return;
    }
    constexpr int kWidth = 720, kLeft = 84, kRight = 10;
    constexpr int kBarsTop = 64, kBarsHeight = 80, kHeight = 178;
    constexpr double kPlot = kWidth - kLeft - kRight;
    const auto& bins = timeline.bins();
    std::size_t used = 0;
    std::uint32_t tallest = 1;
    for (std::size_t i = 0; i < bins.size(); ++i) {
        const Timeline::Bin& bin = bins[i];
        if (bin.transactions || bin.errors || bin.warnings || bin.notes) used = i + 1;
        tallest = std::max(tallest, bin.transactions);
    }
    used = std::max<std::size_t>(used, 1);
    const std::int64_t width_ns = timeline.bin_width_ns();
    // The axis spans the capture, first telegram to last, whatever part of it this channel was
    // busy in: one finding is a tick at its time, not a bar across the page (issue 27). Without
    // the capture's times (never, when a timeline has events) the channel's own bins.
    std::int64_t axis_start = c.summary->first_time_ns();
    std::int64_t axis_end = c.summary->last_time_ns();
    if (axis_start == kNoTime || axis_end == kNoTime || axis_start > timeline.start_ns()) {
        axis_start = timeline.start_ns();
        axis_end = timeline.start_ns() + static_cast<std::int64_t>(used) * width_ns;
    }
    const double span_ns = static_cast<double>(std::max<std::int64_t>(axis_end - axis_start, 1));
    const auto x_of = [&](std::int64_t time_ns) {
        const double x = static_cast<double>(time_ns - axis_start) / span_ns * kPlot;
        return kLeft + std::clamp(x, 0.0, kPlot);
    };
    fmt::format_to(it,
                   "<svg class=\"timeline\" width=\"{}\" height=\"{}\" viewBox=\"0 0 {} {}\" "
                   "role=\"img\" aria-label=\"timeline of {}\">\n",
                   kWidth, kHeight, kWidth, kHeight, who);
    const char* rows[] = {"errors", "warnings", "notes"};
    const char* singular[] = {"error", "warning", "note"};
    const char* colours[] = {"#d92d20", "#f79009", "#2e90fa"};
    for (int row = 0; row < 3; ++row) {
        fmt::format_to(it, "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text>\n", kLeft - 6,
                       14 + row * 16, rows[row]);
        // Each row's axis: the capture, on which the events are ticks.
        fmt::format_to(it,
                       "<line class=\"axis\" x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" "
                       "stroke=\"#d0d5dd\"/>\n",
                       kLeft, 10 + row * 16, kWidth - kRight, 10 + row * 16);
    }
    fmt::format_to(it, "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">transactions</text>\n",
                   kLeft - 6, kBarsTop + kBarsHeight / 2);
    fmt::format_to(it, "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#8a93a6\"/>\n",
                   kLeft, kBarsTop + kBarsHeight, kWidth - kRight, kBarsTop + kBarsHeight);
    for (std::size_t i = 0; i < used; ++i) {
        const Timeline::Bin& bin = bins[i];
        const std::int64_t from = timeline.start_ns() + static_cast<std::int64_t>(i) * width_ns;
        const double x = x_of(from);
        const double x_end = x_of(from + width_ns);
        const std::string when = relative_seconds(c, from);
        if (bin.transactions) {
            double height = static_cast<double>(bin.transactions) / tallest * kBarsHeight;
            fmt::format_to(it,
                           "<rect class=\"tx\" x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" "
                           "height=\"{:.2f}\" fill=\"#4e79c5\"><title>from {} s: {}"
                           "</title></rect>\n",
                           x, kBarsTop + kBarsHeight - height, std::max(x_end - x - 0.5, 0.8),
                           height, when, counted(bin.transactions, "transaction", "transactions"));
        }
        // An event is a tick 2 units wide in the middle of its bin (its time within the bin is
        // not kept), however wide the bin is drawn.
        const double tick = std::min((x + x_end) / 2 - 1, static_cast<double>(kWidth - kRight) - 2);
        const std::uint32_t counts[] = {bin.errors, bin.warnings, bin.notes};
        for (int row = 0; row < 3; ++row) {
            if (!counts[row]) continue;
            fmt::format_to(it,
                           "<rect class=\"mark {}\" x=\"{:.2f}\" y=\"{}\" width=\"2\" "
                           "height=\"10\" fill=\"{}\"><title>from {} s: {}</title></rect>\n",
                           rows[row], std::max(tick, static_cast<double>(kLeft)), 5 + row * 16,
                           colours[row], when, counted(counts[row], singular[row], rows[row]));
        }
    }
    fmt::format_to(it, "<text x=\"{}\" y=\"{}\">{} s</text>\n", kLeft, kHeight - 8,
                   relative_seconds(c, axis_start));
    fmt::format_to(it, "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{} s</text>\n", kWidth - kRight,
                   kHeight - 8, relative_seconds(c, axis_end));
    append(b, "</svg>\n");
}

DriveLatency DriveLatency::of(const LogHistogram& ns, std::uint64_t mean_ns) {
    DriveLatency l;
    if (ns.count() == 0) return l;
    l.any = true;
    l.min_ms = to_ms(ns.min());
    l.mean_ms = to_ms(mean_ns);
    l.p95_ms = to_ms(ns.percentile(95));
    l.max_ms = to_ms(ns.max());
    return l;
}

std::string DriveLatency::text(bool broadcast, bool timed) const {
    if (broadcast) return "-";
    if (!timed) return "not measured (no timestamps)";
    if (!any) return "-";
    return fmt::format("min {:.3f}  mean {:.3f}  p95 {:.3f}  max {:.3f}", min_ms, mean_ms, p95_ms,
                       max_ms);
}

void html_drive_row(TextBuffer& b, std::string_view anchor, std::string_view label,
                    const DriveOutcomes& o, const DriveLatency& l,
                    const std::array<std::uint64_t, 3>& severities) {
    fmt::format_to(std::back_inserter(b),
                   "<tr><td class=\"n\"><a href=\"#{}\">{}</a></td><td class=\"n\">{}"
                   "</td><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td>"
                   "<td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td>"
                   "<td class=\"n\">{}</td><td class=\"n error\">{}</td><td class=\"n "
                   "warning\">{}</td><td class=\"n note\">{}</td></tr>\n",
                   anchor, label, o.commands, o.answered, o.unanswered, o.abandoned, o.damaged,
                   o.not_judged, l.any ? fmt::format("{:.3f}", l.mean_ms) : "-",
                   l.any ? fmt::format("{:.3f}", l.p95_ms) : "-", severities[2], severities[1],
                   severities[0]);
}

std::vector<std::pair<std::string, std::uint64_t>> drive_properties(const DriveOutcomes& o,
                                                                    std::string_view responses_name,
                                                                    std::uint64_t responses) {
    return {{"commands", o.commands},     {"broadcasts", o.broadcasts},
            {"transactions", o.answered}, {"no_responses", o.unanswered},
            {"abandoned", o.abandoned},   {"damaged", o.damaged},
            {"not_judged", o.not_judged}, {std::string(responses_name), responses}};
}

}  // namespace dpscope::report
