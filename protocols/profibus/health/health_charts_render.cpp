// The bus-health charts (SVG, in the HTML report): each station's state over the capture, and
// each master's cycle time and token rotation.
#include <algorithm>
#include <iterator>

#include "formats/report_markup.hpp"
#include "protocols/profibus/health/health_render.hpp"
#include "protocols/profibus/health/health_tables_render.hpp"

namespace dpscope::health {

using detail::target_rotation_ns;
using report::xml;

namespace {

std::string_view state_colour(StationState state) {
    switch (state) {
        case StationState::Active: return "#4e79c5";
        case StationState::Configuring: return "#9e77ed";
        case StationState::DataExchange: return "#32a852";
        case StationState::DiagnosisOnly: return "#f5b800";
        case StationState::Lost: return "#d92d20";
        case StationState::Unknown: break;
    }
    return "#b0b7c3";
}

constexpr StationState kAllStates[] = {StationState::Unknown,       StationState::Active,
                                       StationState::Configuring,   StationState::DataExchange,
                                       StationState::DiagnosisOnly, StationState::Lost};

// Seconds from the capture's start ("0.027865 s"), or "frame 12" without times.
std::string position_text(const BusHealth& h, std::int64_t time_ns, std::uint64_t frame) {
    if (time_ns == kNoTime || h.segment.first_ns == kNoTime) return fmt::format("frame {}", frame);
    return fmt::format("{} s (frame {})", relative_seconds_text(time_ns - h.segment.first_ns),
                       frame);
}

}  // namespace

void svg_state_timeline(TextBuffer& b, const BusHealth& h) {
    auto it = std::back_inserter(b);
    if (h.stations.empty()) {
        append(b, "<p class=\"meta\">No stations listed.</p>\n");
        return;
    }
    // The axis: the capture's times, or its frame numbers when it has none.
    const bool timed = h.segment.has_time();
    double start = 0, end = 0;
    if (timed) {
        start = static_cast<double>(h.segment.first_ns);
        end = static_cast<double>(h.segment.end_ns);
    } else {
        bool first = true;
        for (const StationHealth& s : h.stations) {
            double from = static_cast<double>(
                s.timeline.empty() ? s.first_frame : std::min(s.first_frame, s.timeline[0].frame));
            double to = static_cast<double>(s.last_frame) + 1;
            for (const StateChange& change : s.timeline)
                to = std::max(to, static_cast<double>(change.frame) + 1);
            start = first ? from : std::min(start, from);
            end = first ? to : std::max(end, to);
            first = false;
        }
    }
    if (end <= start) end = start + 1;
    constexpr int kWidth = 720, kLeft = 96, kRight = 10, kTop = 8, kLane = 18, kGap = 4;
    const int height = kTop + static_cast<int>(h.stations.size()) * (kLane + kGap) + 22;
    const double plot = kWidth - kLeft - kRight;
    auto x_of = [&](const StateChange& change) {
        double v = timed && change.time_ns != kNoTime ? static_cast<double>(change.time_ns)
                                                      : static_cast<double>(change.frame);
        if (timed && change.time_ns == kNoTime) v = start;
        return kLeft + std::clamp((v - start) / (end - start), 0.0, 1.0) * plot;
    };
    fmt::format_to(it,
                   "<svg class=\"states\" width=\"{}\" height=\"{}\" viewBox=\"0 0 {} {}\" "
                   "role=\"img\" aria-label=\"state of each station over the capture\">\n",
                   kWidth, height, kWidth, height);
    std::uint64_t dropped = 0;
    for (std::size_t lane = 0; lane < h.stations.size(); ++lane) {
        const StationHealth& s = h.stations[lane];
        const int y = kTop + static_cast<int>(lane) * (kLane + kGap);
        fmt::format_to(it, "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{} {}</text>\n", kLeft - 6,
                       y + kLane - 5, s.address, station_role_name(s.role));
        fmt::format_to(
            it, "<rect x=\"{}\" y=\"{}\" width=\"{:.0f}\" height=\"{}\" fill=\"#f2f4f7\"/>\n",
            kLeft, y, plot, kLane);
        dropped += s.state_changes > s.timeline.size() ? s.state_changes - s.timeline.size() : 0;
        for (std::size_t i = 0; i < s.timeline.size(); ++i) {
            const StateChange& change = s.timeline[i];
            const double x0 = x_of(change);
            const double x1 = i + 1 < s.timeline.size() ? x_of(s.timeline[i + 1]) : kLeft + plot;
            const std::string from = position_text(h, change.time_ns, change.frame);
            std::string to = "the end of the capture";
            if (i + 1 < s.timeline.size())
                to = position_text(h, s.timeline[i + 1].time_ns, s.timeline[i + 1].frame);
            fmt::format_to(it,
                           "<rect class=\"state {}\" x=\"{:.2f}\" y=\"{}\" width=\"{:.2f}\" "
                           "height=\"{}\" fill=\"{}\"><title>station {}: {}{} from {} to {}"
                           "</title></rect>\n",
                           station_state_id(change.state), x0, y, std::max(x1 - x0, 0.8), kLane,
                           state_colour(change.state), s.address, station_state_name(change.state),
                           change.returned ? " (returned)" : "", xml(from), xml(to));
        }
    }
    const int axis = height - 8;
    if (timed) {
        fmt::format_to(it, "<text x=\"{}\" y=\"{}\">0 s</text>\n", kLeft, axis);
        fmt::format_to(it, "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{} s</text>\n",
                       kWidth - kRight, axis,
                       relative_seconds_text(h.segment.end_ns - h.segment.first_ns));
    } else {
        fmt::format_to(it, "<text x=\"{}\" y=\"{}\">frame {:.0f}</text>\n", kLeft, axis, start);
        fmt::format_to(it, "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">frame {:.0f}</text>\n",
                       kWidth - kRight, axis, end - 1);
    }
    append(b, "</svg>\n<p class=\"legend\">");
    for (StationState state : kAllStates)
        fmt::format_to(it, "<span><span class=\"swatch\" style=\"background:{}\"></span>{}</span>",
                       state_colour(state), station_state_name(state));
    append(b, "</p>\n");
    if (dropped > 0)
        fmt::format_to(it,
                       "<p class=\"meta\">{} not drawn (at most {} kept per station; the last "
                       "state kept is drawn to the end).</p>\n",
                       counted(dropped, "later state change", "later state changes"),
                       BusHealthTracker::kMaxStateChanges);
}

void svg_master_plot(TextBuffer& b, const BusHealth& h, const MasterHealth& m) {
    auto it = std::back_inserter(b);
    struct Series {
        const TimeSeries* series;
        std::string_view name;
        std::string_view colour;
    };
    const Series all[] = {{&m.cycle_series, "cycle time", "#4e79c5"},
                          {&m.token_rotation_series, "token rotation", "#7a5af8"}};
    std::int64_t first = kNoTime, last = kNoTime;
    double top = 0;
    for (const Series& s : all)
        for (const TimeSeries::Point& p : s.series->points()) {
            if (p.first_ns == kNoTime || p.last_ns == kNoTime) continue;
            first = first == kNoTime ? p.first_ns : std::min(first, p.first_ns);
            last = last == kNoTime ? p.last_ns : std::max(last, p.last_ns);
            top = std::max(top, static_cast<double>(p.max_ns));
        }
    if (first == kNoTime) {
        fmt::format_to(it,
                       "<p class=\"meta\">Master {}: no cycle time or token rotation measured{}."
                       "</p>\n",
                       m.address, h.segment.has_time() ? "" : " (no timestamps)");
        return;
    }
    if (h.segment.has_time()) {
        first = std::min(first, h.segment.first_ns);
        last = std::max(last, h.segment.end_ns);
    }
    if (last <= first) last = first + 1;
    const double target = target_rotation_ns(h);
    top = std::max(top, target) * 1.05;
    if (top <= 0) top = 1;
    constexpr int kWidth = 720, kHeight = 200, kLeft = 72, kRight = 10, kTop = 10, kBottom = 26;
    const double plot_w = kWidth - kLeft - kRight, plot_h = kHeight - kTop - kBottom;
    auto x_of = [&](const TimeSeries::Point& p) {
        double mid = (static_cast<double>(p.first_ns) + static_cast<double>(p.last_ns)) / 2;
        return kLeft +
               (mid - static_cast<double>(first)) / static_cast<double>(last - first) * plot_w;
    };
    auto y_of = [&](double ns) { return kTop + plot_h - ns / top * plot_h; };
    fmt::format_to(it,
                   "<svg class=\"master-plot\" width=\"{}\" height=\"{}\" viewBox=\"0 0 {} {}\" "
                   "role=\"img\" aria-label=\"cycle time and token rotation of master {}\">\n",
                   kWidth, kHeight, kWidth, kHeight, m.address);
    // Axes with ms labels at 0, half and the top.
    fmt::format_to(it, "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#8a93a6\"/>\n",
                   kLeft, kTop, kLeft, kTop + plot_h);
    fmt::format_to(it, "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#8a93a6\"/>\n",
                   kLeft, kTop + plot_h, kWidth - kRight, kTop + plot_h);
    for (double fraction : {0.0, 0.5, 1.0})
        fmt::format_to(it, "<text x=\"{}\" y=\"{:.1f}\" text-anchor=\"end\">{} ms</text>\n",
                       kLeft - 6, y_of(top * fraction) + 4, ms(top * fraction));
    if (target > 0)
        fmt::format_to(it,
                       "<line class=\"target\" x1=\"{}\" y1=\"{:.2f}\" x2=\"{}\" y2=\"{:.2f}\" "
                       "stroke=\"#d92d20\" stroke-dasharray=\"4 3\"><title>target rotation {} ms"
                       "</title></line>\n",
                       kLeft, y_of(target), kWidth - kRight, y_of(target), ms(target));
    for (const Series& s : all) {
        auto points = s.series->points();
        if (points.empty()) continue;
        // The min-max band: along the maxima, back along the minima.
        fmt::format_to(it, "<polygon class=\"band\" fill=\"{}\" fill-opacity=\"0.18\" points=\"",
                       s.colour);
        for (const TimeSeries::Point& p : points)
            fmt::format_to(it, "{:.2f},{:.2f} ", x_of(p), y_of(static_cast<double>(p.max_ns)));
        for (auto p = points.rbegin(); p != points.rend(); ++p)
            fmt::format_to(it, "{:.2f},{:.2f} ", x_of(*p), y_of(static_cast<double>(p->min_ns)));
        fmt::format_to(it, "\"><title>{}: min to max</title></polygon>\n", s.name);
        fmt::format_to(it,
                       "<polyline class=\"mean\" fill=\"none\" stroke=\"{}\" stroke-width=\"1.5\" "
                       "points=\"",
                       s.colour);
        for (const TimeSeries::Point& p : points)
            fmt::format_to(it, "{:.2f},{:.2f} ", x_of(p), y_of(p.mean_ns()));
        append(b, "\"/>\n");
        for (const TimeSeries::Point& p : points)
            fmt::format_to(it,
                           "<circle class=\"point\" cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"2\" "
                           "fill=\"{}\"><title>{} from {} s: min {} mean {} max {} ms ({})</title>"
                           "</circle>\n",
                           x_of(p), y_of(p.mean_ns()), s.colour, s.name,
                           h.segment.first_ns == kNoTime
                               ? std::string("-")
                               : relative_seconds_text(p.first_ns - h.segment.first_ns),
                           ms(static_cast<double>(p.min_ns)), ms(p.mean_ns()),
                           ms(static_cast<double>(p.max_ns)),
                           counted(p.count, "sample", "samples"));
    }
    const std::int64_t origin = h.segment.first_ns == kNoTime ? first : h.segment.first_ns;
    fmt::format_to(it, "<text x=\"{}\" y=\"{}\">{} s</text>\n", kLeft, kHeight - 8,
                   relative_seconds_text(first - origin));
    fmt::format_to(it, "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{} s</text>\n", kWidth - kRight,
                   kHeight - 8, relative_seconds_text(last - origin));
    append(b, "</svg>\n<p class=\"legend\">");
    for (const Series& s : all)
        fmt::format_to(it,
                       "<span><span class=\"swatch\" style=\"background:{}\"></span>{} (mean; "
                       "band: min to max)</span>",
                       s.colour, s.name);
    if (target > 0)
        append(b,
               "<span><span class=\"swatch\" style=\"background:#d92d20\"></span>target "
               "rotation</span>");
    append(b, "</p>\n");
}

}  // namespace dpscope::health
