// The conformance report: one model, computed once, written in five formats.
//
// How it is put together:
// - render_report() (report.cpp) builds a ReportModel from the ReportContext once and hands it to
//   the writer of the format asked for, one file each: report_text.cpp, report_json.cpp,
//   report_markdown.cpp, report_html.cpp, report_junit.cpp. A writer lays out the document:
//   header and verdict, summary, one section per station, the bus section, then the findings in
//   capture order.
// - The per-station sections are StationSection objects, one class per channel kind: PcvSection
//   (protocols/profibus/pcv_report_section.cpp), the cyclic parameter channel (PCV) of a DP
//   slave, and Dpv1Section (protocols/profibus/dpv1/dpv1_report_section.cpp), its DP-V1
//   parameter access, which follows the PCV section of the same slave; FcSection
//   (protocols/fc/fc_report_section.cpp) and Vlt2000Section
//   (protocols/vlt2000/vlt2000_report_section.cpp),
//   a drive address of an FC or VLT 2000 capture. Each section covers the finding kinds of its
//   rules. Every format asks the section for its own part (write_text(), write_json(), ...).
// - What differs by bus (its sections, finding kinds, bus findings, checks and wording) is the
//   bus's BusReport, one per protocol in its report-section file (<name>_bus_report()), in a
//   table made from the registration list (formats/bus_reports.cpp); report_of() looks up the
//   capture's. So a new protocol is its StationSection class and its BusReport; a new channel
//   kind of a bus is one more StationSection class its BusReport's add_sections makes. The five
//   writers stay as they are.
// - Wording used by more than one writer lives here (verdict, filter, relative times, findings
//   by kind); escaping for Markdown, HTML and XML in report_markup.hpp.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "drives/parameter_naming.hpp"
#include "formats/describe.hpp"
#include "formats/json_writer.hpp"
#include "formats/report.hpp"

namespace dpscope::report {

using FindingCounts = std::array<std::uint64_t, kFindingKindCount>;

// The text and Markdown reports list at most this many findings of each kind.
inline constexpr std::uint64_t kListedPerKind = 1000;
inline constexpr std::string_view kNoTimestamps = "time-outs not judged (no timestamps)";

constexpr std::array<FindingKind, kFindingKindCount> all_finding_kinds() {
    std::array<FindingKind, kFindingKindCount> kinds{};
    for (std::size_t i = 0; i < kFindingKindCount; ++i)
        kinds[i] = static_cast<FindingKind>(i);
    return kinds;
}
inline constexpr auto kAllKinds = all_finding_kinds();

// One station's section of the report, for one channel kind. Each format asks it for its part;
// the writers never look inside a section.
class StationSection {
  public:
    virtual ~StationSection() = default;

    // The findings naming this master and slave belong to the section.
    virtual std::uint8_t master() const = 0;
    virtual std::uint8_t slave() const = 0;
    // Something was checked here; a report in which no section was checked says "nothing
    // checked".
    virtual bool checked() const = 0;
    // Transactions, counted in the summary.
    virtual std::uint64_t transactions() const = 0;
    // The station's findings by kind, of the kinds the section covers.
    virtual const FindingCounts& findings() const = 0;
    // Whether the section's rules find `kind` (its findings and its JUnit test cases).
    virtual bool covers(FindingKind kind) const = 0;

    // Text: the station's block, from its leading empty line.
    virtual void write_text(const ReportContext& c, TextBuffer& b) const = 0;
    // Markdown: the station's row in the "Slaves" table, and its "###" block.
    virtual void write_markdown_row(const ReportContext& c, TextBuffer& b) const = 0;
    virtual void write_markdown(const ReportContext& c, TextBuffer& b) const = 0;
    // JSON: the station's object in "stations" (schema in docs/formats.md).
    virtual void write_json(const ReportContext& c, JsonWriter& w) const = 0;
    // HTML: the station's row in the summary table, and its <section>.
    virtual void write_html_row(const ReportContext& c, TextBuffer& b) const = 0;
    virtual void write_html(const ReportContext& c, TextBuffer& b) const = 0;
    // JUnit: the test suite's name and class name, and a note for the test case of a rule ("" for
    // none), e.g. the dialect hint beside unknown_code.
    virtual std::string junit_suite_name() const = 0;
    virtual std::string junit_classname() const = 0;
    virtual std::string junit_note(FindingKind kind) const = 0;
    // JUnit: the suite's <properties> (name, value), e.g. a drive's commands by outcome; none by
    // default.
    virtual std::vector<std::pair<std::string, std::uint64_t>> junit_properties() const {
        return {};
    }
};

// DP-V1 parameter access of a DP slave (PROFIdrive over MSAC_C1/MSAC_C2), as the session
// tracker counted it (the PROFIBUS sections add it after the slave's cyclic section).
// `names`: what names the slave's PNUs (issue 29); a default one: numbers alone.
std::unique_ptr<StationSection> make_dpv1_section(const ChannelStats& stats,
                                                  StationNaming names = {});

// What the writers say differently per bus: its BusReport's row.
struct BusWording {
    // The header line naming the bus ("" for PROFIBUS DP, whose reports have always been
    // without it) and the JSON options.bus ("": not written).
    std::string_view name;
    std::string_view option;
    // The checksum findings the summary counts, as the summary and JSON name them.
    FindingKind checksum_kind;
    std::string_view checksum_label;  // "FCS errors"
    std::string_view checksum_key;    // "fcs_errors"
    // "slave" or "drive", "slaves" or "drives" (the HTML summary card).
    std::string_view station;
    std::string_view stations;
    // Markdown: the stations table's heading, header and alignment rows; HTML: the summary
    // table's header row.
    std::string_view markdown_table;
    std::string_view html_table;
    // JUnit: the name of the test case that says nothing was checked.
    std::string_view nothing_checked_case;
};

struct ReportModel {
    std::vector<std::unique_ptr<StationSection>> stations;  // the sections reported, in order
    std::uint64_t slaves = 0;                               // the slaves they are about
    std::array<std::uint64_t, 3> by_severity{};             // findings shown, by severity
    std::uint64_t fcs_errors = 0;  // the bus's checksum findings shown (BusWording::checksum_kind)
    std::uint64_t shown = 0;       // findings shown
    std::uint64_t transactions = 0;  // of every station reported
    bool fails = false;
    bool has_bus_findings = false;
    bool timed = false;            // the capture carries timestamps (or is empty)
    bool nothing_checked = false;  // no section checked anything

    std::uint64_t errors() const { return by_severity[static_cast<std::size_t>(Severity::Error)]; }
    std::uint64_t warnings() const {
        return by_severity[static_cast<std::size_t>(Severity::Warning)];
    }
    std::uint64_t notes() const { return by_severity[static_cast<std::size_t>(Severity::Note)]; }
};

ReportModel build_report_model(const ReportContext& c);

// The finding is shown: no station filter, a bus finding, or its slave is selected.
bool shows(const ReportContext& c, const Finding& f);
// The slave is reported: no station filter, or it is selected.
bool shows_slave(const ReportContext& c, std::uint8_t slave);

// What the report does and says differently per bus, one per protocol: <name>_bus_report() in
// the protocol's report-section file (protocols/<name>/*_report_section.cpp), listed in
// bus_report_table(). Shared code looks the bus up (report_of()) instead of switching on it.
struct BusReport {
    Protocol protocol;
    BusWording wording;
    // The context carries the bus's tracker. A report of a capture whose bus has none is of the
    // first protocol of the table (PROFIBUS DP, whose tracker is always there).
    bool (*tracked)(const ReportContext& c) noexcept = nullptr;
    // Adds the sections of the stations reported (shows_slave()) to the model, in report order,
    // and counts those stations in m.slaves.
    void (*add_sections)(const ReportContext& c, const ChannelTimelines& timelines,
                         ReportModel& m) = nullptr;
    // The kinds the bus suite and bus legend list: a report lists only its own bus's kinds.
    bool (*is_bus_kind)(FindingKind kind) noexcept = nullptr;
    // The findings no station can be named for, from the bus's tracker.
    const BusStats& (*bus_stats)(const ReportContext& c) = nullptr;
    // The checks the bus's tracker applies: "time-out 1000 ms, drive response time 20 ms".
    std::string (*checks_text)(const ReportContext& c, const ReportModel& m) = nullptr;
    // Why nothing was checked in a capture with telegrams: "no command to a drive".
    std::string_view (*nothing_checked_reason)(const ReportContext& c) = nullptr;
    // Writes the bus's own options into the JSON report's "options", after "timeout_ms"
    // ("fc_response_ms"); null: it has none there.
    void (*write_json_options)(const ReportContext& c, JsonWriter& w) = nullptr;
    // The bus's checks are the time-out and the RC 8 rule (an RC 8 answer to a read: unusual, or
    // with --strict an unexpected response), which each writer words itself from
    // timeout_rule_text() and --strict (the HTML one without naming the bus); otherwise the
    // writers say checks_text().
    bool checks_rc8_rule = false;
};

// Every bus's BusReport, in the order of the registration list (protocols/protocol_list.hpp);
// the first is the default bus.
std::span<const BusReport* const> bus_report_table() noexcept;
// The BusReport of a protocol.
const BusReport& bus_report(Protocol protocol) noexcept;
// The BusReport of the bus the report is about: the capture's protocol when its tracker is
// there, else the first of the table (PROFIBUS DP).
const BusReport& report_of(const ReportContext& c) noexcept;

// Each bus's BusReport, by the name its line in protocols/protocol_list.hpp gives it:
// profibus_bus_report(), fc_bus_report(), ... (defined in the protocol's report-section file).
#define DPSCOPE_BUS_REPORT(Enum, name, Payload, member) \
    const BusReport& name##_bus_report() noexcept;
DPSCOPE_PROTOCOLS(DPSCOPE_BUS_REPORT)
#undef DPSCOPE_BUS_REPORT

// The bus's wording: of a protocol (the command line names its stations with it), or of the bus
// the report is about.
const BusWording& bus_wording(Protocol bus);
const BusWording& bus_wording(const ReportContext& c);
// The kinds the capture's bus suite and bus legend list (BusReport::is_bus_kind).
bool is_bus_kind(const ReportContext& c, FindingKind kind);
// The findings no station can be named for, from the capture's tracker.
const BusStats& bus_stats(const ReportContext& c);
// "FCS errors", "BCC errors" or "checksum errors": the checksum findings the summary counts.
std::string_view checksum_errors_label(const ReportContext& c);
// The header line naming the bus of a capture other than PROFIBUS DP ("" for PROFIBUS DP, whose
// reports have always been without it).
std::string bus_text(const ReportContext& c);

// A section per drive address of a drive bus (FcStationStats, Vlt2000StationStats), in address
// order: `make(c, stats, timeline)` makes one.
template <typename Stats, typename Make>
void add_drive_sections(const ReportContext& c, const std::vector<const Stats*>& drives,
                        const ChannelTimelines& timelines, Make make, ReportModel& m) {
    for (const Stats* stats : drives) {
        if (!shows_slave(c, stats->address)) continue;
        m.stations.push_back(make(c, *stats, timelines.of(0, stats->address)));
        ++m.slaves;
    }
}

// The writers, one file each.
void write_text(const ReportContext& c, const ReportModel& m, Output& out);
void write_json(const ReportContext& c, const ReportModel& m, Output& out);
void write_markdown(const ReportContext& c, const ReportModel& m, Output& out);
void write_html(const ReportContext& c, const ReportModel& m, Output& out);
void write_junit(const ReportContext& c, const ReportModel& m, Output& out);

// ---- wording shared by the writers and the sections ---------------------------------------------

double to_ms(std::uint64_t ns);
// "1 error, 0 warnings, 2 notes".
std::string findings_text(const ReportModel& m);
// Why nothing was checked: "no telegrams", "no Data_Exchange telegram with a parameter channel".
std::string nothing_checked_reason(const ReportContext& c);
// The checks the bus's tracker applies (BusReport::checks_text): "time-out 1000 ms, drive
// response time 20 ms" for FC, "time-out 1000 ms, checksums checked" for VLT 2000 (for PROFIBUS
// DP the writers say it with timeout_rule_text and the RC 8 rule: BusReport::checks_rc8_rule).
std::string checks_text(const ReportContext& c, const ReportModel& m);
// "FAIL: 1 error, 0 warnings, 0 notes (fail on error)".
std::string verdict_text(const ReportContext& c, const ReportModel& m);
// "time-out 1000 ms", or kNoTimestamps without timestamps.
std::string timeout_rule_text(const ReportContext& c, const ReportModel& m);
// "" without a station filter or -Y, else "slaves 3, 5", "-Y EXPR: the findings of ...".
std::string filter_text(const ReportContext& c);
// Seconds since the capture's first telegram ("0.027865"), or "-".
std::string relative_seconds(const ReportContext& c, std::int64_t time_ns);
// "stacked_request 2, response_timeout 1", or "none".
std::string findings_by_kind_text(const FindingCounts& counts);
// "2 / 3", or "-" for a bus finding.
std::string station_label(const Finding& f);
// "1200 more stacked_request findings not listed: at most 1000 per kind, the JSON report lists
// them all", for the kinds the text and Markdown reports cut short.
std::string unlisted_text(FindingKind kind, const FindingCounts& listed);
// "4950 findings could not be listed: <why>" when the finding log could not keep them all (a
// full temporary folder), "" when it lists every finding. Final once the findings were listed.
std::string not_listed_text(const ReportContext& c);

}  // namespace dpscope::report
