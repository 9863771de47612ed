// The bus-health model: its names, the wording of a verdict's reason, and the time series.
// The tracker that fills it: protocols/profibus/health/bus_health_tracker.cpp (one telegram at a
// time), protocols/profibus/health/bus_health_stations.cpp (the live list and each station's
// state), protocols/profibus/health/bus_health_masters.cpp (token and poll cycle) and
// protocols/profibus/health/bus_health_verdicts.cpp (the verdicts), sharing
// protocols/profibus/health/bus_health_state.hpp.
#include "protocols/profibus/health/bus_health.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace dpscope {

std::string_view station_role_name(StationRole role) noexcept {
    switch (role) {
        case StationRole::Master: return "master";
        case StationRole::Slave: return "slave";
        case StationRole::Unknown: break;
    }
    return "unknown";
}

std::string_view station_state_name(StationState state) noexcept {
    switch (state) {
        case StationState::Active: return "active";
        case StationState::Configuring: return "configuring";
        case StationState::DataExchange: return "data exchange";
        case StationState::DiagnosisOnly: return "diagnosis only";
        case StationState::Lost: return "lost";
        case StationState::Unknown: break;
    }
    return "unknown";
}

std::string_view station_state_id(StationState state) noexcept {
    switch (state) {
        case StationState::Active: return "active";
        case StationState::Configuring: return "configuring";
        case StationState::DataExchange: return "data_exchange";
        case StationState::DiagnosisOnly: return "diagnosis_only";
        case StationState::Lost: return "lost";
        case StationState::Unknown: break;
    }
    return "unknown";
}

std::string_view illegal_answer_id(IllegalAnswer kind) noexcept {
    switch (kind) {
        case IllegalAnswer::NotAsked: return "not_asked";
        case IllegalAnswer::WrongKind: return "wrong_kind";
        case IllegalAnswer::ShortAck:
        case IllegalAnswer::Count: break;
    }
    return "short_ack";
}

std::string_view diag_fault_name(DiagFault fault) noexcept {
    switch (fault) {
        case DiagFault::StationNotReady: return "Station_Not_Ready";
        case DiagFault::CfgFault: return "Cfg_Fault";
        case DiagFault::ExtDiag: return "Ext_Diag";
        case DiagFault::PrmFault: return "Prm_Fault";
        case DiagFault::StatDiag:
        case DiagFault::Count: break;
    }
    return "Stat_Diag";
}

std::string_view negative_answer_name(NegativeAnswer kind) noexcept {
    switch (kind) {
        case NegativeAnswer::UE: return "UE";
        case NegativeAnswer::RR: return "RR";
        case NegativeAnswer::RS: return "RS";
        case NegativeAnswer::NR: return "NR";
        case NegativeAnswer::DH: return "DH";
        case NegativeAnswer::RDH:
        case NegativeAnswer::Count: break;
    }
    return "RDH";
}

std::string_view health_event_name(HealthEventKind kind) noexcept {
    switch (kind) {
        case HealthEventKind::StationLost: return "station_lost";
        case HealthEventKind::StationReturned: return "station_returned";
        case HealthEventKind::VerdictBad:
        case HealthEventKind::Count: break;
    }
    return "verdict_bad";
}

std::string describe_reason(const VerdictReason& reason, const HealthThresholds& thresholds) {
    const HealthThresholdRow& row = health_threshold_row(reason.threshold);
    const double limit = thresholds.get(reason.threshold);
    const std::string unit = row.unit.empty() ? "" : fmt::format(" {}", row.unit);
    const std::string_view what = row.name;
    const std::string_view comparison =
        row.comparison == ThresholdComparison::From ? "from" : "above";
    // Counts as whole numbers, rates to three significant digits (0.758 %, 2.99 %, 12.5 %).
    const auto figure = [](double value) {
        if (value == std::floor(value) && value < 1e15) return fmt::format("{:.0f}", value);
        return value >= 100 ? fmt::format("{:.1f}", value) : fmt::format("{:.3g}", value);
    };
    return fmt::format("{}: {}{} ({} {} {}{})", what, figure(reason.measured), unit,
                       verdict_name(reason.verdict), comparison, figure(limit), unit);
}

void TimeSeries::add_point(std::int64_t time_ns, std::int64_t value_ns) {
    if (points_.size() == kMaxPoints) {
        // Merge neighbours pairwise: half the points, each spanning twice the samples.
        std::size_t out = 0;
        for (std::size_t i = 0; i + 1 < points_.size(); i += 2) {
            Point merged = points_[i];
            const Point& next = points_[i + 1];
            merged.last_ns = next.last_ns;
            merged.min_ns = std::min(merged.min_ns, next.min_ns);
            merged.max_ns = std::max(merged.max_ns, next.max_ns);
            merged.sum_ns += next.sum_ns;
            merged.count += next.count;
            points_[out++] = merged;
        }
        points_.resize(out);
        per_point_ *= 2;
        add(time_ns, value_ns);
        return;
    }
    if (points_.capacity() < kMaxPoints) points_.reserve(kMaxPoints);
    points_.push_back(
        Point{time_ns, time_ns, value_ns, value_ns, static_cast<double>(value_ns), 1});
}

}  // namespace dpscope
