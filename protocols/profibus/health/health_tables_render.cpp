// The tables and cells the bus-health formats share
// (protocols/profibus/health/health_tables_render.hpp): the live list, the slave table with its
// columns, the master table, the verdicts that are not good.
#include "protocols/profibus/health/health_tables_render.hpp"

#include <fmt/format.h>

#include <iterator>

#include "protocols/profibus/health/health_render.hpp"

namespace dpscope::health::detail {

namespace {

// The illegal answers' short names (by IllegalAnswer): the slave table's cell and the columns'
// headers.
constexpr std::string_view kIllegalShort[] = {"not asked", "wrong kind", "short ack"};
static_assert(std::size(kIllegalShort) == kIllegalAnswerCount);

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

std::string jitter_cell(const MasterHealth& m) {
    return m.cycle.count() < 2 ? std::string("-") : ms(m.cycle_jitter_ns);
}

}  // namespace

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

}  // namespace dpscope::health::detail
