// The bus-health CSV: a row per station with every counter, and a master's figures.
#include <algorithm>
#include <iterator>
#include <string>

#include "protocols/profibus/health/health_render.hpp"
#include "protocols/profibus/health/health_tables_render.hpp"

namespace dpscope::health {

using detail::duration_cells;
using detail::slave_columns;
using detail::SlaveColumn;

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

}  // namespace dpscope::health
