// The bus-health JSON ("stats JSON" in docs/formats.md): the members write_json_members() writes.
#include <cmath>

#include "formats/json.hpp"
#include "protocols/profibus/health/health_render.hpp"
#include "protocols/profibus/health/health_tables_render.hpp"

namespace dpscope::health {

using detail::slave_columns;
using detail::SlaveColumn;
using detail::target_rotation_ns;

namespace {

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

}  // namespace

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

}  // namespace dpscope::health
