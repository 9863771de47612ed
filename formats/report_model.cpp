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

namespace {

// The cyclic and DP-V1 sections of the PROFIBUS DP slaves.
void add_dp_sections(const ReportContext& c, const ChannelTimelines& timelines, ReportModel& m) {
    for (const ChannelStats* stats : c.tracker->channels()) {
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
}

// A section per drive address (FcStationStats, Vlt2000StationStats), in address order.
template <typename Stats, typename Make>
void add_drive_sections(const ReportContext& c, const std::vector<const Stats*>& drives,
                        const ChannelTimelines& timelines, Make make, ReportModel& m) {
    for (const Stats* stats : drives) {
        if (!shows_slave(c, stats->address)) continue;
        m.stations.push_back(make(c, *stats, timelines.of(0, stats->address)));
        ++m.slaves;
    }
}

// The buses' rows of BusWording.
const BusWording kDpWording{
    "",
    "",
    FindingKind::FcsError,
    "FCS errors",
    "fcs_errors",
    "slave",
    "slaves",
    "## Slaves\n\n| slave | master | PPO | dialect | transactions | rejected | time-outs | latency "
    "ms (min / median / p95 / max) | latency cycles | findings |\n"
    "|---:|---:|---|---|---:|---:|---:|---|---|---|\n",
    "<tr><th class=\"n\">slave</th><th class=\"n\">master</th><th>PPO</th><th>dialect</th><th "
    "class=\"n\">transactions</th><th class=\"n\">median ms</th><th class=\"n\">p95 ms</th><th "
    "class=\"n\">errors</th><th class=\"n\">warnings</th><th class=\"n\">notes</th></tr>\n",
    "parameter channel: the capture holds Data_Exchange telegrams with a parameter channel",
};

// The drive buses' HTML summary table (the same columns for FC and VLT 2000).
constexpr std::string_view kDriveHtmlTable =
    "<tr><th class=\"n\">address</th><th class=\"n\">commands</th><th class=\"n\">answered"
    "</th><th class=\"n\">unanswered</th><th class=\"n\">abandoned</th><th class=\"n\">damaged"
    "</th><th class=\"n\">not judged</th><th class=\"n\">mean ms</th><th class=\"n\">p95 ms"
    "</th><th class=\"n\">errors</th><th class=\"n\">warnings</th><th class=\"n\">notes</th>"
    "</tr>\n";

const BusWording kFcWording{
    "Danfoss FC protocol (RS-485)",
    "fc",
    FindingKind::FcBccError,
    "BCC errors",
    "bcc_errors",
    "drive",
    "drives",
    "## Drives\n\n| address | commands | answered | unanswered | abandoned | damaged | not judged "
    "| late | latency ms (min / mean / p95 / max) | rejected | findings |\n"
    "|---|---:|---:|---:|---:|---:|---:|---:|---|---:|---|\n",
    kDriveHtmlTable,
    "FC protocol: the capture holds commands to drives",
};

const BusWording kVlt2000Wording{
    "Danfoss VLT 2000 serial telegram (ASCII)",
    "vlt2000",
    FindingKind::Vlt2000ChecksumError,
    "bad checksums",
    "checksum_errors",
    "drive",
    "drives",
    "## Drives\n\n| address | commands | answered | unanswered | abandoned | damaged | not judged "
    "| failed | latency ms (min / mean / p95 / max) | checksum errors | findings |\n"
    "|---|---:|---:|---:|---:|---:|---:|---:|---|---:|---|\n",
    kDriveHtmlTable,
    "VLT 2000: the capture holds commands answered by drives",
};

}  // namespace

ReportModel build_report_model(const ReportContext& c) {
    ReportModel m;
    // The sections, one per station and channel kind.
    static const ChannelTimelines kNoTimelines;
    const ChannelTimelines& timelines = c.timelines ? *c.timelines : kNoTimelines;
    switch (report_bus(c)) {
        case Protocol::Fc:
            add_drive_sections(c, c.fc_tracker->stations(), timelines, make_fc_section, m);
            break;
        case Protocol::Vlt2000:
            add_drive_sections(c, c.vlt2000_tracker->stations(), timelines, make_vlt2000_section,
                               m);
            break;
        case Protocol::ProfibusDp: add_dp_sections(c, timelines, m); break;
    }

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

bool is_dp_kind(FindingKind kind) {
    const FindingComponent component = finding_component(kind);
    return component != FindingComponent::Dpv1ParameterAccess &&
           component != FindingComponent::FcProtocol &&
           component != FindingComponent::Vlt2000Protocol;
}

Protocol report_bus(const ReportContext& c) {
    switch (c.protocol) {
        case Protocol::Fc: return c.fc_tracker ? Protocol::Fc : Protocol::ProfibusDp;
        case Protocol::Vlt2000: return c.vlt2000_tracker ? Protocol::Vlt2000 : Protocol::ProfibusDp;
        case Protocol::ProfibusDp: break;
    }
    return Protocol::ProfibusDp;
}

const BusWording& bus_wording(Protocol bus) {
    switch (bus) {
        case Protocol::Fc: return kFcWording;
        case Protocol::Vlt2000: return kVlt2000Wording;
        case Protocol::ProfibusDp: break;
    }
    return kDpWording;
}

const BusWording& bus_wording(const ReportContext& c) { return bus_wording(report_bus(c)); }

bool is_bus_kind(const ReportContext& c, FindingKind kind) {
    switch (report_bus(c)) {
        case Protocol::Fc: return is_fc_finding_kind(kind);
        case Protocol::Vlt2000: return is_vlt2000_finding_kind(kind);
        case Protocol::ProfibusDp: break;
    }
    return is_dp_kind(kind);
}

const BusStats& bus_stats(const ReportContext& c) {
    switch (report_bus(c)) {
        case Protocol::Fc: return c.fc_tracker->bus();
        case Protocol::Vlt2000: return c.vlt2000_tracker->bus();
        case Protocol::ProfibusDp: break;
    }
    return c.tracker->bus();
}

std::string_view checksum_errors_label(const ReportContext& c) {
    return bus_wording(c).checksum_label;
}

std::string bus_text(const ReportContext& c) { return std::string(bus_wording(c).name); }

std::string checks_text(const ReportContext& c, const ReportModel& m) {
    switch (report_bus(c)) {
        case Protocol::Fc:
            return m.timed ? fmt::format("time-out {} ms, drive response time {} ms",
                                         c.fc_tracker->options().timeout_ns / 1'000'000,
                                         c.fc_tracker->options().response_ns / 1'000'000)
                           : std::string("time-outs and response times not judged (no timestamps)");
        case Protocol::Vlt2000:
            return fmt::format(
                "{}, {}",
                m.timed ? fmt::format("time-out {} ms",
                                      c.vlt2000_tracker->options().timeout_ns / 1'000'000)
                        : std::string(kNoTimestamps),
                c.vlt2000_checksum ? "checksums checked"
                                   : "checksums not checked (--vlt2000-checksum ignore)");
        case Protocol::ProfibusDp: break;
    }
    return timeout_rule_text(c, m);
}

double to_ms(std::uint64_t ns) { return static_cast<double>(ns) / 1e6; }

std::string findings_text(const ReportModel& m) {
    return fmt::format("{}, {}, {}", counted(m.errors(), "error", "errors"),
                       counted(m.warnings(), "warning", "warnings"),
                       counted(m.notes(), "note", "notes"));
}

std::string nothing_checked_reason(const ReportContext& c) {
    if (c.summary->telegrams() == 0) return "no telegrams";
    const bool all = c.stations.empty();
    switch (report_bus(c)) {
        case Protocol::Fc:
            return all ? "no command to a drive" : "no command to the selected drives";
        case Protocol::Vlt2000:
            return all ? "no command answered by a drive"
                       : "no command answered by the selected drives";
        case Protocol::ProfibusDp: break;
    }
    return all ? "no Data_Exchange telegram with a parameter channel"
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
    // "slaves 3, 5" on PROFIBUS, "drives 7" on the FC protocol and VLT 2000 (as the sections).
    const std::string_view noun =
        c.stations.size() == 1 ? bus_wording(c).station : bus_wording(c).stations;
    for (std::uint8_t station : c.stations)
        text += text.empty() ? fmt::format("{} {}", noun, station) : fmt::format(", {}", station);
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
