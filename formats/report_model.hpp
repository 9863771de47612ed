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
//   rules. What differs by bus (sections, kinds, bus findings, wording) is chosen by report_bus():
//   a switch, or the bus's row of BusWording. Every format asks the section
//   for its own part (write_text(), write_json(), ...), so a new channel kind (DP-V1 acyclic, FC
//   protocol) is one new StationSection class plus the line in build_report_model() that makes its
//   sections; the five writers stay as they are.
// - Wording used by more than one writer lives here (verdict, filter, relative times, findings
//   by kind); escaping for Markdown, HTML and XML in report_markup.hpp.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

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
    // JSON: the station's object in "stations" (schema in README.md).
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

// The cyclic parameter channel (PCV) of a DP slave, as the session tracker counted it, with its
// timeline.
std::unique_ptr<StationSection> make_pcv_section(const ReportContext& c, const ChannelStats& stats,
                                                 const Timeline& timeline);

// DP-V1 parameter access of a DP slave (PROFIdrive over MSAC_C1/MSAC_C2), as the session
// tracker counted it.
std::unique_ptr<StationSection> make_dpv1_section(const ChannelStats& stats);

// One drive address of an FC capture (address 0: the broadcasts), as the FC tracker counted it.
std::unique_ptr<StationSection> make_fc_section(const ReportContext& c, const FcStationStats& stats,
                                                const Timeline& timeline);

// One drive address of a VLT 2000 capture (address 00: the broadcasts), as the VLT 2000 tracker
// counted it.
std::unique_ptr<StationSection> make_vlt2000_section(const ReportContext& c,
                                                     const Vlt2000StationStats& stats,
                                                     const Timeline& timeline);

// The PROFIBUS bus suite's and the cyclic channel's kinds: all but the DP-V1 parameter-access,
// the FC protocol and the VLT 2000 ones.
bool is_dp_kind(FindingKind kind);

// The bus the report is about: the capture's protocol when its tracker is there, else PROFIBUS DP.
// Everything that differs by bus switches on it, or reads the bus's BusWording.
Protocol report_bus(const ReportContext& c);

// What the writers say differently per bus: one row per bus (report_model.cpp).
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
const BusWording& bus_wording(Protocol bus);
const BusWording& bus_wording(const ReportContext& c);

// The kinds the capture's bus suite and bus legend list: the PROFIBUS ones (is_dp_kind), or the
// FC or VLT 2000 tracker's. A report lists only its own bus's kinds.
bool is_bus_kind(const ReportContext& c, FindingKind kind);
// The findings no station can be named for, from the capture's tracker.
const BusStats& bus_stats(const ReportContext& c);
// "FCS errors", "BCC errors" or "checksum errors": the checksum findings the summary counts.
std::string_view checksum_errors_label(const ReportContext& c);
// The header line naming the bus of a capture other than PROFIBUS DP ("" for PROFIBUS DP, whose
// reports have always been without it).
std::string bus_text(const ReportContext& c);

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
// The checks the protocol's tracker applies: "time-out 1000 ms, drive response time 20 ms" for
// FC, "time-out 1000 ms, checksums checked" for VLT 2000 (for PROFIBUS DP the writers say it with
// timeout_rule_text and the RC 8 rule).
std::string checks_text(const ReportContext& c, const ReportModel& m);
// "FAIL: 1 error, 0 warnings, 0 notes (fail on error)".
std::string verdict_text(const ReportContext& c, const ReportModel& m);
// "time-out 1000 ms", or kNoTimestamps without timestamps.
std::string timeout_rule_text(const ReportContext& c, const ReportModel& m);
// "" without a station filter, else "slaves 3, 5".
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
