#include "formats/report_model.hpp"

#include <algorithm>

namespace dpscope::report {

bool shows_slave(const ReportContext& c, std::uint8_t slave) {
    return c.stations.empty() ||
           std::find(c.stations.begin(), c.stations.end(), slave) != c.stations.end();
}

bool shows(const ReportContext& c, const Finding& f) {
    return !f.has_stations || shows_slave(c, f.slave);
}

ReportModel build_report_model(const ReportContext& c) {
    ReportModel m;
    // The sections, one per station and channel kind.
    static const ChannelTimelines kNoTimelines;
    const ChannelTimelines& timelines = c.timelines ? *c.timelines : kNoTimelines;
    if (is_fc(c)) {
        for (const FcStationStats* stats : c.fc_tracker->stations()) {
            if (!shows_slave(c, stats->address)) continue;
            m.stations.push_back(make_fc_section(c, *stats, timelines.of(0, stats->address)));
            ++m.slaves;
        }
    }
    for (const ChannelStats* stats :
         is_fc(c) ? std::vector<const ChannelStats*>{} : c.tracker->channels()) {
        if (!shows_slave(c, stats->slave)) continue;
        bool dp_findings = false, dpv1_findings = false;
        for (FindingKind kind : kAllKinds)
            if (stats->findings[static_cast<std::size_t>(kind)] > 0)
                (is_dp_kind(kind) ? dp_findings : dpv1_findings) = true;
        const bool dpv1 = stats->dpv1.telegrams > 0 || dpv1_findings;
        // The cyclic channel's section, unless the slave only talked DP-V1.
        if (!dpv1 || stats->data_exchange > 0 || stats->parameter_telegrams > 0 || dp_findings)
            m.stations.push_back(
                make_pcv_section(c, *stats, timelines.of(stats->master, stats->slave)));
        if (dpv1) m.stations.push_back(make_dpv1_section(*stats));
        ++m.slaves;
    }

    for (const auto& section : m.stations)
        m.transactions += section->transactions();
    m.timed = c.summary->first_time_ns() != kNoTime || c.summary->telegrams() == 0;
    m.nothing_checked = std::none_of(m.stations.begin(), m.stations.end(),
                                     [](const auto& section) { return section->checked(); });
    if (m.nothing_checked && !c.allow_empty) m.fails = true;
    c.findings->for_each([&](const Finding& f) {
        if (!shows(c, f)) return;
        ++m.shown;
        ++m.by_severity[static_cast<std::size_t>(f.severity)];
        if (f.kind == (is_fc(c) ? FindingKind::FcBccError : FindingKind::FcsError)) ++m.fcs_errors;
        if (severity_fails(f.severity, c.fail_on)) m.fails = true;
        if (!f.has_stations) m.has_bus_findings = true;
    });
    return m;
}

bool is_dp_kind(FindingKind kind) {
    const FindingComponent component = finding_component(kind);
    return component != FindingComponent::Dpv1ParameterAccess &&
           component != FindingComponent::FcProtocol &&
           component != FindingComponent::Vlt2000Protocol;
}

bool is_fc(const ReportContext& c) { return c.protocol == Protocol::Fc && c.fc_tracker; }

bool is_bus_kind(const ReportContext& c, FindingKind kind) {
    return is_fc(c) ? is_fc_finding_kind(kind) : is_dp_kind(kind);
}

const BusStats& bus_stats(const ReportContext& c) {
    return is_fc(c) ? c.fc_tracker->bus() : c.tracker->bus();
}

std::string_view checksum_errors_label(const ReportContext& c) {
    return is_fc(c) ? "BCC errors" : "FCS errors";
}

std::string bus_text(const ReportContext& c) {
    return is_fc(c) ? std::string("Danfoss FC protocol (RS-485)") : std::string();
}

std::string checks_text(const ReportContext& c, const ReportModel& m) {
    if (!is_fc(c)) return timeout_rule_text(c, m);
    return m.timed ? fmt::format("time-out {} ms, drive response time {} ms",
                                 c.fc_tracker->options().timeout_ns / 1'000'000,
                                 c.fc_tracker->options().response_ns / 1'000'000)
                   : std::string("time-outs and response times not judged (no timestamps)");
}

double to_ms(std::uint64_t ns) { return static_cast<double>(ns) / 1e6; }

std::string findings_text(const ReportModel& m) {
    return fmt::format("{}, {}, {}", counted(m.errors(), "error", "errors"),
                       counted(m.warnings(), "warning", "warnings"),
                       counted(m.notes(), "note", "notes"));
}

std::string nothing_checked_reason(const ReportContext& c) {
    if (c.summary->telegrams() == 0) return "no telegrams";
    if (is_fc(c))
        return c.stations.empty() ? "no command to a drive" : "no command to the selected drives";
    return c.stations.empty()
               ? "no Data_Exchange telegram with a parameter channel"
               : "no Data_Exchange telegram with a parameter channel from the selected slaves";
}

std::string verdict_text(const ReportContext& c, const ReportModel& m) {
    return fmt::format("{}: {}{} (fail on {}{})", m.fails ? "FAIL" : "PASS",
                       m.nothing_checked
                           ? fmt::format("nothing checked ({}); ", nothing_checked_reason(c))
                           : std::string(),
                       findings_text(m), fail_on_name(c.fail_on),
                       m.nothing_checked && c.allow_empty ? ", empty allowed" : "");
}

std::string timeout_rule_text(const ReportContext& c, const ReportModel& m) {
    return m.timed ? fmt::format("time-out {} ms", c.tracker->options().timeout_ns / 1'000'000)
                   : std::string(kNoTimestamps);
}

std::string filter_text(const ReportContext& c) {
    std::string text;
    for (std::uint8_t station : c.stations)
        text += fmt::format("{}{}", text.empty() ? "slaves " : ", ", station);
    return text;
}

std::string relative_seconds(const ReportContext& c, std::int64_t time_ns) {
    std::int64_t first = c.summary->first_time_ns();
    if (time_ns == kNoTime || first == kNoTime) return "-";
    return relative_seconds_text(time_ns - first);
}

std::string findings_by_kind_text(const FindingCounts& counts) {
    std::string text;
    for (FindingKind kind : kAllKinds)
        if (counts[static_cast<std::size_t>(kind)])
            text += fmt::format("{}{} {}", text.empty() ? "" : ", ", finding_kind_name(kind),
                                counts[static_cast<std::size_t>(kind)]);
    return text.empty() ? "none" : text;
}

std::string station_label(const Finding& f) {
    return f.has_stations ? fmt::format("{} / {}", f.master, f.slave) : std::string("-");
}

std::string unlisted_text(FindingKind kind, const FindingCounts& listed) {
    std::uint64_t more = listed[static_cast<std::size_t>(kind)] - kListedPerKind;
    return fmt::format(
        "{} more {} {} not listed: at most {} per kind, the JSON report lists them all", more,
        finding_kind_name(kind), more == 1 ? "finding" : "findings", kListedPerKind);
}

}  // namespace dpscope::report
