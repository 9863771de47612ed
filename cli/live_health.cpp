#include "cli/live_health.hpp"

#include <fmt/format.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <string_view>
#include <vector>

#include "cli/common_options.hpp"
#include "protocols/profibus/health/stats_render.hpp"

namespace dpscope::cli {

namespace {

constexpr std::size_t kRecentEvents = 5;  // event lines kept under the table on a terminal

struct TerminalSize {
    unsigned columns = 80;
    unsigned rows = 24;
};

TerminalSize terminal_size(FILE* stream) {
    TerminalSize size;
    winsize ws{};
    if (::ioctl(fileno(stream), TIOCGWINSZ, &ws) == 0) {
        if (ws.ws_col > 0) size.columns = ws.ws_col;
        if (ws.ws_row > 0) size.rows = ws.ws_row;
    }
    return size;
}

// `text` cut to `width` columns (bytes: the table is ASCII; 0: no limit).
std::string_view cut(std::string_view text, unsigned width) {
    return width > 0 && text.size() > width ? text.substr(0, width) : text;
}

}  // namespace

LiveHealth::LiveHealth(BusHealthTracker& tracker, Output& out, FILE* stream, Show show,
                       std::string heading, AlarmRunner* alarms)
    : tracker_(tracker),
      out_(out),
      stream_(stream),
      show_(show),
      heading_(std::move(heading)),
      alarms_(alarms) {}

void LiveHealth::handle(const HealthEvent& event) {
    AlarmEvent described = describe_health_event(event, tracker_.health());
    std::string line = health_event_line(described);
    switch (show_) {
        case Show::Table:
            recent_.push_back(std::move(line));
            if (recent_.size() > kRecentEvents) recent_.erase(recent_.begin());
            break;
        case Show::Lines:
            out_.append(line);
            out_.put('\n');
            out_.end_record();
            break;
        case Show::StandardError: write_standard_error(line + "\n"); break;
        case Show::Nothing: break;
    }
    if (alarms_) alarms_->raise(described);
    if (listener_) listener_->on_health_event(described);
}

void LiveHealth::judged() {
    if (listener_) listener_->on_judged(tracker_.health());
}

void LiveHealth::on_events(std::span<const HealthEvent> events) {
    if (events.empty()) return;
    // A station lost or back changes verdicts: judged now (cheap, and events are rare), so the
    // event's line and alarm carry the verdict it leads to, and a verdict that turns bad by it
    // is said at once, with this telegram, not at the next redraw.
    const std::vector<HealthEvent> station_events(events.begin(), events.end());
    const std::span<const HealthEvent> verdicts = tracker_.judge();
    const std::vector<HealthEvent> turned_bad(verdicts.begin(), verdicts.end());
    for (const HealthEvent& event : station_events)
        handle(event);
    for (const HealthEvent& event : turned_bad)
        handle(event);
    judged();
}

void LiveHealth::tick(std::int64_t now_ns, std::uint64_t telegrams, double seconds) {
    if (alarms_) alarms_->reap();
    if (ticked_ && now_ns - last_tick_ns_ < kRedrawEveryNs) return;
    ticked_ = true;
    last_tick_ns_ = now_ns;
    for (const HealthEvent& event : tracker_.judge())
        handle(event);
    judged();
    if (show_ == Show::Table) redraw(telegrams, seconds, false);
}

void LiveHealth::before_finish() {
    for (const HealthEvent& event : tracker_.judge())
        handle(event);
    // The statistics end with the last telegram, not at the stop: `dpscope stats` of the -w
    // file gives the same figures (Pipeline::finish() later finds the tracker finished).
    tracker_.finish();
    judged();
}

void LiveHealth::after_finish(std::uint64_t telegrams, double seconds) {
    if (show_ == Show::Table) redraw(telegrams, seconds, true);
}

void LiveHealth::redraw(std::uint64_t telegrams, double seconds, bool final) {
    const TerminalSize size = terminal_size(stream_);
    // The table, rendered into a buffer of its own (never flushed: emptied before it goes).
    std::string table;
    {
        Output scratch(stream_);
        render_live_table(tracker_.health(), scratch, size.columns);
        table.assign(scratch.buffer().data(), scratch.buffer().size());
        scratch.buffer().clear();
    }

    std::vector<std::string_view> lines;
    const std::string heading =
        fmt::format("dpscope sniff --stats: {}: {} telegrams in {:.1f} s{}", heading_, telegrams,
                    seconds, final ? ", stopped" : "; Ctrl-C stops");
    lines.push_back(heading);
    for (std::size_t at = 0; at < table.size();) {
        std::size_t end = table.find('\n', at);
        if (end == std::string::npos) end = table.size();
        lines.push_back(std::string_view(table).substr(at, end - at));
        at = end + 1;
    }
    if (!recent_.empty()) {
        lines.push_back("recent events:");
        for (const std::string& line : recent_)
            lines.push_back(line);
    }
    // Keep the region within the screen (the cursor cannot move above its top); the last row
    // stays free for the cursor.
    const std::size_t room = size.rows > 1 ? size.rows - 1 : 1;
    std::string more;
    if (lines.size() > room) {
        more = fmt::format("... {} more lines: enlarge the terminal", lines.size() - room + 1);
        lines.resize(room - 1);
        lines.push_back(more);
    }
    // Back to the region's first line, clear from there to the end of the screen, draw.
    std::string frame =
        drawn_lines_ > 0 ? fmt::format("\r\x1b[{}A\x1b[J", drawn_lines_) : std::string("\r\x1b[J");
    for (std::string_view line : lines) {
        frame.append(cut(line, size.columns));
        frame.push_back('\n');
    }
    out_.append(frame);
    out_.flush();
    drawn_lines_ = static_cast<unsigned>(lines.size());
    ++redraws_;
}

}  // namespace dpscope::cli
