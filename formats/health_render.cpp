#include "formats/health_render.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <iterator>
#include <vector>

#include "formats/json.hpp"
#include "formats/report_markup.hpp"

namespace dpscope::health {

using report::escape_xml;
using report::md_escape;
using report::xml;

std::string ms(double ns) { return fmt::format("{:.3f}", ns / 1e6); }

std::string when(std::int64_t time_ns, std::uint64_t frame) {
    if (time_ns == kNoTime) return fmt::format("frame {}", frame);
    TextBuffer b;
    append_iso_time(b, time_ns);
    return fmt::to_string(b);
}

std::string reasons_text(const Judgement& judgement, const HealthThresholds& thresholds) {
    std::string text;
    for (const VerdictReason& reason : judgement.reasons) {
        if (!text.empty()) text += "; ";
        text += describe_reason(reason, thresholds);
    }
    return text;
}

std::string segment_cause(const BusHealth& h) {
    const Verdict verdict = h.segment.judgement.verdict;
    for (const VerdictReason& reason : h.segment.judgement.reasons)
        if (reason.verdict == verdict) return "";  // its own reasons say it
    std::string text;
    auto add = [&](std::string_view who) {
        text += text.empty() ? "from " : ", ";
        text += who;
    };
    for (const StationHealth& s : h.stations)
        if (verdict != Verdict::Good && s.judgement.verdict == verdict)
            add(fmt::format("station {} ({})", s.address, station_role_name(s.role)));
    for (const MasterHealth& m : h.masters)
        if (verdict != Verdict::Good && m.judgement.verdict == verdict)
            add(fmt::format("master {} (token and cycle)", m.address));
    return text;
}

bool in_slave_table(const StationHealth& s) {
    return s.role != StationRole::Master || s.requests > 0 || s.answers > 0;
}

bool differs_from_default(const HealthThresholds& thresholds, HealthThreshold kind) {
    static const HealthThresholds defaults;
    return thresholds.get(kind) != defaults.get(kind);
}

namespace {

// ---- tables shared by text, Markdown and HTML ------------------------------------------------

struct Table {
    std::vector<std::string_view> headers;
    std::vector<bool> numeric;  // right-aligned
    std::vector<std::vector<std::string>> rows;
};

std::string number(std::uint64_t n) { return fmt::format("{}", n); }

// A station's own state at the end, its verdict and when it was seen.
Table live_list(const BusHealth& h) {
    Table t{{"address", "role", "state", "first seen", "last seen", "verdict"},
            {true, false, false, false, false, false},
            {}};
    for (const StationHealth& s : h.stations)
        t.rows.push_back({number(s.address), std::string(station_role_name(s.role)),
                          std::string(station_state_name(s.state)),
                          when(s.first_seen_ns, s.first_frame), when(s.last_seen_ns, s.last_frame),
                          std::string(verdict_name(s.judgement.verdict))});
    return t;
}

// The illegal answers' short names (by IllegalAnswer): the slave table's cell and the columns'
// headers.
constexpr std::string_view kIllegalShort[] = {"not asked", "wrong kind", "short ack"};
static_assert(std::size(kIllegalShort) == kIllegalAnswerCount);

struct SlaveColumn {
    std::string_view header;  // text, Markdown and HTML
    std::string_view id;      // CSV
    std::function<std::uint64_t(const StationHealth&)> value;
    // In the slave table of text, Markdown and HTML; the illegal and negative answers by kind are
    // CSV columns only: the table shows them in one cell each (illegal_cell, negative_cell).
    bool in_table = true;
};

const std::vector<SlaveColumn>& slave_columns() {
    static const std::vector<SlaveColumn> columns = [] {
        std::vector<SlaveColumn> c = {
            {"requests", "requests", [](const StationHealth& s) { return s.requests; }},
            {"answers", "answers", [](const StationHealth& s) { return s.answers; }},
            {"no answer", "no_answers", [](const StationHealth& s) { return s.no_answers; }},
            {"repeats", "repeats", [](const StationHealth& s) { return s.repeats; }},
            {"max/cycle", "max_repeats_per_cycle",
             [](const StationHealth& s) { return s.max_repeats_per_cycle; }},
            {"lost", "lost_events", [](const StationHealth& s) { return s.lost_events; }},
            {"returns", "returns", [](const StationHealth& s) { return s.returns; }},
            {"resyncs", "resyncs", [](const StationHealth& s) { return s.resyncs; }},
            {"diag req", "diag_requests", [](const StationHealth& s) { return s.diag_requests; }},
            {"diag faults", "diag_faults", [](const StationHealth& s) { return s.diag_faults; }},
        };
        static constexpr std::string_view kIllegalIds[] = {
            "illegal_not_asked", "illegal_wrong_kind", "illegal_short_ack"};
        for (std::size_t i = 0; i < kIllegalAnswerCount; ++i)
            c.push_back({kIllegalShort[i], kIllegalIds[i],
                         [i](const StationHealth& s) { return s.illegal_answers[i]; }, false});
        static constexpr std::string_view kNegativeIds[] = {"negative_ue", "negative_rr",
                                                            "negative_rs", "negative_nr",
                                                            "negative_dh", "negative_rdh"};
        for (std::size_t i = 0; i < kNegativeAnswerCount; ++i)
            c.push_back({negative_answer_name(static_cast<NegativeAnswer>(i)), kNegativeIds[i],
                         [i](const StationHealth& s) { return s.negative_answers[i]; }, false});
        c.push_back({"damaged", "damaged", [](const StationHealth& s) { return s.fcs_errors; }});
        return c;
    }();
    return columns;
}

// "0", or the total and the kinds that occurred: "2 (not asked 1, short ack 1)".
std::string illegal_cell(const StationHealth& s) {
    std::string cell = number(s.illegal_answers_total());
    std::string kinds;
    for (std::size_t i = 0; i < kIllegalAnswerCount; ++i) {
        if (s.illegal_answers[i] == 0) continue;
        kinds += fmt::format("{}{} {}", kinds.empty() ? "" : ", ", kIllegalShort[i],
                             s.illegal_answers[i]);
    }
    return kinds.empty() ? cell : fmt::format("{} ({})", cell, kinds);
}

// "-", or the kinds that occurred with their counts: "RS 1, DH 3".
std::string negative_cell(const StationHealth& s) {
    std::string cell;
    for (std::size_t i = 0; i < kNegativeAnswerCount; ++i) {
        if (s.negative_answers[i] == 0) continue;
        cell += fmt::format("{}{} {}", cell.empty() ? "" : ", ",
                            negative_answer_name(static_cast<NegativeAnswer>(i)),
                            s.negative_answers[i]);
    }
    return cell.empty() ? std::string("-") : cell;
}

Table slave_table(const BusHealth& h) {
    Table t;
    t.headers.push_back("address");
    for (const SlaveColumn& column : slave_columns())
        if (column.in_table) t.headers.push_back(column.header);
    t.numeric.assign(t.headers.size(), true);
    t.headers.push_back("illegal");
    t.headers.push_back("negative answers");
    t.numeric.push_back(false);
    t.numeric.push_back(false);
    for (const StationHealth& s : h.stations) {
        if (!in_slave_table(s)) continue;
        std::vector<std::string> row{number(s.address)};
        for (const SlaveColumn& column : slave_columns())
            if (column.in_table) row.push_back(number(column.value(s)));
        row.push_back(illegal_cell(s));
        row.push_back(negative_cell(s));
        t.rows.push_back(std::move(row));
    }
    return t;
}

double target_rotation_ns(const BusHealth& h) {
    return h.thresholds.get(HealthThreshold::TargetRotationMs) * 1e6;
}

// min, mean, p95, max in ms; "-" each when nothing was measured.
std::array<std::string, 4> duration_cells(const DurationStats& d) {
    if (d.count() == 0) return {"-", "-", "-", "-"};
    return {ms(static_cast<double>(d.min())), ms(d.mean()), ms(static_cast<double>(d.p95())),
            ms(static_cast<double>(d.max()))};
}

std::string jitter_cell(const MasterHealth& m) {
    return m.cycle.count() < 2 ? std::string("-") : ms(m.cycle_jitter_ns);
}

Table master_table(const BusHealth& h) {
    const bool target = target_rotation_ns(h) > 0;
    Table t;
    t.headers = {"address",       "tokens",       "rotation min",
                 "rotation mean", "rotation p95", "rotation max"};
    if (target) t.headers.push_back("target");
    for (std::string_view header :
         {"cycle min", "cycle mean", "cycle p95", "cycle max", "jitter", "slaves polled"})
        t.headers.push_back(header);
    t.numeric.assign(t.headers.size(), true);
    for (const MasterHealth& m : h.masters) {
        std::vector<std::string> row{number(m.address), number(m.tokens_received)};
        for (std::string& cell : duration_cells(m.token_rotation))
            row.push_back(std::move(cell));
        if (target) row.push_back(ms(target_rotation_ns(h)));
        for (std::string& cell : duration_cells(m.cycle))
            row.push_back(std::move(cell));
        row.push_back(jitter_cell(m));
        row.push_back(number(m.slaves_polled));
        t.rows.push_back(std::move(row));
    }
    return t;
}

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

// The stations and masters whose verdict is not good, with their reasons.
struct Judged {
    std::string who;
    const Judgement* judgement;
};

std::vector<Judged> not_good(const BusHealth& h) {
    std::vector<Judged> out;
    for (const StationHealth& s : h.stations)
        if (s.judgement.verdict != Verdict::Good)
            out.push_back({fmt::format("station {} ({})", s.address, station_role_name(s.role)),
                           &s.judgement});
    for (const MasterHealth& m : h.masters)
        if (m.judgement.verdict != Verdict::Good)
            out.push_back({fmt::format("master {}", m.address), &m.judgement});
    return out;
}

std::string threshold_value(double value) { return fmt::format("{}", value); }

// ---- JSON ------------------------------------------------------------------------------------

void fixed(JsonWriter& w, double value, int decimals = 6) {
    if (!std::isfinite(value)) {
        w.null();
        return;
    }
    w.number_text(fmt::format("{:.{}f}", value, decimals));
}

void shortest(JsonWriter& w, double value) {
    if (!std::isfinite(value)) {
        w.null();
        return;
    }
    w.number_text(fmt::format("{}", value));
}

void count(JsonWriter& w, std::string_view key, std::uint64_t n) {
    w.key(key).integer(static_cast<std::int64_t>(n));
}

void json_judgement(JsonWriter& w, const Judgement& j, const HealthThresholds& thresholds,
                    bool judged = true) {
    w.key("verdict");
    if (judged)
        w.string(verdict_name(j.verdict));
    else
        w.null();
    w.key("reasons").begin_array();
    for (const VerdictReason& r : j.reasons) {
        w.begin_object();
        w.key("threshold").string(health_threshold_row(r.threshold).name);
        w.key("measured");
        shortest(w, r.measured);
        w.key("limit");
        shortest(w, thresholds.get(r.threshold));
        w.key("verdict").string(verdict_name(r.verdict));
        w.key("text").string(describe_reason(r, thresholds));
        w.end_object();
    }
    w.end_array();
}

void json_durations(JsonWriter& w, std::string_view key, const DurationStats& d) {
    w.key(key);
    if (d.count() == 0) {
        w.null();
        return;
    }
    w.begin_object();
    count(w, "count", d.count());
    w.key("min_ms");
    fixed(w, static_cast<double>(d.min()) / 1e6);
    w.key("mean_ms");
    fixed(w, d.mean() / 1e6);
    w.key("p95_ms");
    fixed(w, static_cast<double>(d.p95()) / 1e6);
    w.key("max_ms");
    fixed(w, static_cast<double>(d.max()) / 1e6);
    w.end_object();
}

void json_series(JsonWriter& w, std::string_view key, const TimeSeries& series) {
    w.key(key).begin_object();
    count(w, "samples_per_point", series.samples_per_point());
    w.key("points").begin_array();
    for (const TimeSeries::Point& p : series.points()) {
        w.begin_object();
        w.key("first_time");
        json::time(w, p.first_ns);
        w.key("last_time");
        json::time(w, p.last_ns);
        count(w, "count", p.count);
        w.key("min_ms");
        fixed(w, static_cast<double>(p.min_ns) / 1e6);
        w.key("mean_ms");
        fixed(w, p.mean_ns() / 1e6);
        w.key("max_ms");
        fixed(w, static_cast<double>(p.max_ns) / 1e6);
        w.end_object();
    }
    w.end_array();
    w.end_object();
}

void json_segment(JsonWriter& w, const BusHealth& h) {
    const SegmentHealth& s = h.segment;
    w.key("segment").begin_object();
    count(w, "telegrams", s.telegrams);
    count(w, "bytes", s.bytes);
    count(w, "damaged", s.damaged);
    count(w, "unattributed_damaged", s.unattributed_damaged);
    count(w, "unasked_short_acks", s.unasked_short_acks);
    w.key("first_time");
    json::time(w, s.first_ns);
    w.key("end_time");
    json::time(w, s.end_ns);
    w.key("duration_s");
    if (s.has_time())
        fixed(w, s.duration_s(), 9);
    else
        w.null();
    w.key("telegrams_per_s");
    if (s.duration_s() > 0)
        fixed(w, s.telegrams_per_second(), 3);
    else
        w.null();
    w.key("baud").optional_integer(s.baud != 0, s.baud);
    count(w, "character_bits", s.character_bits);
    w.key("load_percent");
    if (s.load_percent() >= 0)
        fixed(w, s.load_percent(), 3);
    else
        w.null();
    w.key("idle_s");
    if (s.idle_s() >= 0)
        fixed(w, s.idle_s(), 9);
    else
        w.null();
    json_judgement(w, s.judgement, h.thresholds, s.judged());
    w.end_object();
}

void json_station(JsonWriter& w, const BusHealth& h, const StationHealth& s) {
    w.begin_object();
    count(w, "address", s.address);
    w.key("role").string(station_role_name(s.role));
    w.key("state").string(station_state_id(s.state));
    json_judgement(w, s.judgement, h.thresholds);
    w.key("first_seen");
    json::time(w, s.first_seen_ns);
    w.key("last_seen");
    json::time(w, s.last_seen_ns);
    count(w, "first_frame", s.first_frame);
    count(w, "last_frame", s.last_frame);
    count(w, "telegrams_sent", s.telegrams_sent);
    for (const SlaveColumn& column : slave_columns()) {
        // The arrays are objects of their own below.
        if (column.id.starts_with("illegal_") || column.id.starts_with("negative_")) continue;
        count(w, column.id, column.value(s));
    }
    count(w, "diag_answers", s.diag_answers);
    count(w, "replies_due", s.replies_due);
    w.key("diag_fault_bits").begin_object();
    for (std::size_t i = 0; i < kDiagFaultCount; ++i)
        count(w, diag_fault_name(static_cast<DiagFault>(i)), s.diag_fault_bits[i]);
    w.end_object();
    w.key("illegal_answers").begin_object();
    for (std::size_t i = 0; i < kIllegalAnswerCount; ++i)
        count(w, illegal_answer_id(static_cast<IllegalAnswer>(i)), s.illegal_answers[i]);
    w.end_object();
    w.key("negative_answers").begin_object();
    for (std::size_t i = 0; i < kNegativeAnswerCount; ++i)
        count(w, negative_answer_name(static_cast<NegativeAnswer>(i)), s.negative_answers[i]);
    w.end_object();
    count(w, "state_changes", s.state_changes);
    w.key("timeline").begin_array();
    for (const StateChange& change : s.timeline) {
        w.begin_object();
        w.key("time");
        json::time(w, change.time_ns);
        count(w, "frame", change.frame);
        w.key("state").string(station_state_id(change.state));
        w.key("returned").boolean(change.returned);
        w.end_object();
    }
    w.end_array();
    w.end_object();
}

void json_master(JsonWriter& w, const BusHealth& h, const MasterHealth& m) {
    w.begin_object();
    count(w, "address", m.address);
    json_judgement(w, m.judgement, h.thresholds);
    count(w, "tokens_received", m.tokens_received);
    count(w, "tokens_passed", m.tokens_passed);
    count(w, "tokens_not_taken", m.tokens_not_taken);
    count(w, "requests", m.requests);
    count(w, "slaves_polled", m.slaves_polled);
    json_durations(w, "token_rotation", m.token_rotation);
    w.key("target_rotation_ms");
    if (target_rotation_ns(h) > 0)
        shortest(w, h.thresholds.get(HealthThreshold::TargetRotationMs));
    else
        w.null();
    json_durations(w, "cycle", m.cycle);
    w.key("cycle_jitter_ms");
    if (m.cycle.count() >= 2)
        fixed(w, m.cycle_jitter_ns / 1e6);
    else
        w.null();
    json_series(w, "token_rotation_series", m.token_rotation_series);
    json_series(w, "cycle_series", m.cycle_series);
    w.end_object();
}

// ---- SVG ---------------------------------------------------------------------------------------

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

// ---- JSON ------------------------------------------------------------------------------------

void write_json_members(JsonWriter& w, const BusHealth& h) {
    json_segment(w, h);
    w.key("stations").begin_array();
    for (const StationHealth& s : h.stations)
        json_station(w, h, s);
    w.end_array();
    w.key("masters").begin_array();
    for (const MasterHealth& m : h.masters)
        json_master(w, h, m);
    w.end_array();
    w.key("thresholds").begin_object();
    for (const HealthThresholdRow& row : health_threshold_catalogue()) {
        w.key(row.name);
        shortest(w, h.thresholds.get(row.kind));
    }
    w.end_object();
}

// ---- text --------------------------------------------------------------------------------------

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

// ---- Markdown ----------------------------------------------------------------------------------

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

// ---- CSV ---------------------------------------------------------------------------------------

void csv_field(TextBuffer& b, std::string_view text) {
    if (text.find_first_of(",\"\r\n") == std::string_view::npos) {
        append(b, text);
        return;
    }
    b.push_back('"');
    for (char c : text) {
        if (c == '"') b.push_back('"');
        b.push_back(c);
    }
    b.push_back('"');
}

void write_csv(TextBuffer& b, const BusHealth& h) {
    auto it = std::back_inserter(b);
    append(b,
           "address,role,state,verdict,reasons,first_seen,last_seen,first_frame,last_frame,"
           "telegrams_sent");
    for (const SlaveColumn& column : slave_columns())
        fmt::format_to(it, ",{}", column.id);
    append(b, ",diag_answers,replies_due");
    for (std::size_t i = 0; i < kDiagFaultCount; ++i)
        fmt::format_to(it, ",diag_{}", diag_fault_name(static_cast<DiagFault>(i)));
    append(b,
           ",state_changes,master_verdict,master_reasons,tokens_received,tokens_passed,"
           "tokens_not_taken,master_requests,slaves_polled,rotation_min_ms,rotation_mean_ms,"
           "rotation_p95_ms,rotation_max_ms,cycle_min_ms,cycle_mean_ms,cycle_p95_ms,"
           "cycle_max_ms,cycle_jitter_ms\n");
    auto time_cell = [&](std::int64_t ns) {
        b.push_back(',');
        if (ns != kNoTime) append_iso_time(b, ns);
    };
    auto durations = [&](const DurationStats& d) {
        for (std::string& cell : duration_cells(d)) {
            b.push_back(',');
            if (cell != "-") append(b, cell);
        }
    };
    // The master columns: verdict, reasons, 5 counts, 8 durations, jitter.
    constexpr std::size_t kMasterColumns = 16;
    for (const StationHealth& s : h.stations) {
        fmt::format_to(it, "{},{},{},{},", s.address, station_role_name(s.role),
                       station_state_id(s.state), verdict_name(s.judgement.verdict));
        csv_field(b, reasons_text(s.judgement, h.thresholds));
        time_cell(s.first_seen_ns);
        time_cell(s.last_seen_ns);
        fmt::format_to(it, ",{},{},{}", s.first_frame, s.last_frame, s.telegrams_sent);
        for (const SlaveColumn& column : slave_columns())
            fmt::format_to(it, ",{}", column.value(s));
        fmt::format_to(it, ",{},{}", s.diag_answers, s.replies_due);
        for (std::uint64_t n : s.diag_fault_bits)
            fmt::format_to(it, ",{}", n);
        fmt::format_to(it, ",{}", s.state_changes);
        auto m = std::find_if(h.masters.begin(), h.masters.end(), [&](const MasterHealth& master) {
            return master.address == s.address;
        });
        if (m == h.masters.end()) {
            append(b, std::string(kMasterColumns, ','));
            b.push_back('\n');
            continue;
        }
        fmt::format_to(it, ",{},", verdict_name(m->judgement.verdict));
        csv_field(b, reasons_text(m->judgement, h.thresholds));
        fmt::format_to(it, ",{},{},{},{},{}", m->tokens_received, m->tokens_passed,
                       m->tokens_not_taken, m->requests, m->slaves_polled);
        durations(m->token_rotation);
        durations(m->cycle);
        fmt::format_to(it, ",{}\n", m->cycle.count() < 2 ? std::string() : ms(m->cycle_jitter_ns));
    }
}

// ---- HTML --------------------------------------------------------------------------------------

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
