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
    report_of(c).add_sections(c, timelines, m);

    for (const auto& section : m.stations)
        m.transactions += section->transactions();
    m.timed = c.summary->first_time_ns() != kNoTime || c.summary->telegrams() == 0;
    m.nothing_checked = std::none_of(m.stations.begin(), m.stations.end(),
                                     [](const auto& section) { return section->checked(); });
    if (m.nothing_checked && !c.allow_empty) m.fails = true;
    const FindingKind checksum_kind = bus_wording(c).checksum_kind;
    // Counted from the log's tallies, exact also when it cannot list every finding.
    c.findings->for_each_tally([&](const FindingTally& t) {
        if (t.has_stations && !shows_slave(c, t.slave)) return;
        m.shown += t.count;
        m.by_severity[static_cast<std::size_t>(t.severity)] += t.count;
        if (t.kind == checksum_kind) m.fcs_errors += t.count;
        if (severity_fails(t.severity, c.fail_on)) m.fails = true;
        if (!t.has_stations) m.has_bus_findings = true;
    });
    return m;
}

const BusReport& report_of(const ReportContext& c) noexcept {
    const BusReport& bus = bus_report(c.protocol);
    return bus.tracked(c) ? bus : *bus_report_table().front();
}

const BusWording& bus_wording(Protocol bus) { return bus_report(bus).wording; }

const BusWording& bus_wording(const ReportContext& c) { return report_of(c).wording; }

bool is_bus_kind(const ReportContext& c, FindingKind kind) {
    return report_of(c).is_bus_kind(kind);
}

const BusStats& bus_stats(const ReportContext& c) { return report_of(c).bus_stats(c); }

std::string_view checksum_errors_label(const ReportContext& c) {
    return bus_wording(c).checksum_label;
}

std::string bus_text(const ReportContext& c) { return std::string(bus_wording(c).name); }

std::string checks_text(const ReportContext& c, const ReportModel& m) {
    return report_of(c).checks_text(c, m);
}

double to_ms(std::uint64_t ns) { return static_cast<double>(ns) / 1e6; }

std::string findings_text(const ReportModel& m) {
    return fmt::format("{}, {}, {}", counted(m.errors(), "error", "errors"),
                       counted(m.warnings(), "warning", "warnings"),
                       counted(m.notes(), "note", "notes"));
}

std::string nothing_checked_reason(const ReportContext& c) {
    if (c.summary->telegrams() == 0) return "no telegrams";
    return std::string(report_of(c).nothing_checked_reason(c));
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
    return m.timed ? fmt::format("time-out {} ms", c.tracker->timeout_ns() / 1'000'000)
                   : std::string(kNoTimestamps);
}

std::string filter_text(const ReportContext& c) {
    std::string text;
    // "slaves 3, 5" on PROFIBUS, "drives 7" on the FC protocol and VLT 2000 (as the sections).
    const std::string_view noun =
        c.stations.size() == 1 ? bus_wording(c).station : bus_wording(c).stations;
    for (std::uint8_t station : c.stations)
        text += text.empty() ? fmt::format("{} {}", noun, station) : fmt::format(", {}", station);
    if (!c.display_filter.empty())
        text += fmt::format("{}-Y {}: the findings of the telegrams it selects",
                            text.empty() ? "" : "; ", c.display_filter);
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

std::string not_listed_text(const ReportContext& c) {
    if (c.findings->unlisted() == 0 && c.findings->lost().empty()) return "";
    return fmt::format("{} not be listed: {}",
                       counted(c.findings->unlisted(), "finding could", "findings could"),
                       c.findings->lost());
}

std::string unlisted_text(FindingKind kind, const FindingCounts& listed) {
    std::uint64_t more = listed[static_cast<std::size_t>(kind)] - kListedPerKind;
    return fmt::format(
        "{} more {} {} not listed: at most {} per kind, the JSON report lists them all", more,
        finding_kind_name(kind), more == 1 ? "finding" : "findings", kListedPerKind);
}

}  // namespace dpscope::report
