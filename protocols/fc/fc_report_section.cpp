// The report's section for one drive address of a Danfoss FC protocol capture (address 0: the
// broadcasts): commands by kind and AK, responses, latency, parameters accessed, rejections with
// their fault texts and findings by kind, in every format, as the FC tracker counted them. And
// what an FC report does and says as its own (fc_bus_report()): a section per drive address,
// the protocol's kinds and options, its wording.
#include <algorithm>
#include <iterator>

#include "formats/json.hpp"
#include "formats/parameter_names.hpp"
#include "formats/report_markup.hpp"
#include "formats/report_model.hpp"
#include "protocols/fc/fc_codes.hpp"
#include "protocols/fc/fc_tracker.hpp"

namespace dpscope::report {

namespace {

// The capture's tracker, an FC one (fc_tracked(): the report is FC's only when it is).
const FcTracker& fc_tracker(const ReportContext& c) noexcept {
    return static_cast<const FcTracker&>(*c.tracker);
}

// "parameter AK 1 x3, AK 2 x1" or "none".
std::string commands_by_ak_text(const FcStationStats& s) {
    std::string text;
    for (std::size_t ak = 0; ak < s.commands_by_ak.size(); ++ak)
        if (s.commands_by_ak[ak])
            text += fmt::format("{}AK {} x{}", text.empty() ? "" : ", ", ak, s.commands_by_ak[ak]);
    return text.empty() ? "none" : text;
}

std::string parameters_text(const FcStationStats& s, StationNaming names) {
    std::string text;
    for (const auto& [pnu, access] : s.parameters)
        text += fmt::format("{}PNU {} ({} read{}, {} write{})", text.empty() ? "" : ", ",
                            pnu_label(names, pnu), access.reads, access.reads == 1 ? "" : "s",
                            access.writes, access.writes == 1 ? "" : "s");
    if (s.parameters_not_counted)
        text += fmt::format("{}{} more accesses to further parameters", text.empty() ? "" : "; ",
                            s.parameters_not_counted);
    return text.empty() ? "none" : text;
}

std::string_view fault_text(std::uint16_t code) { return error_text_or_unknown(Dialect::Fc, code); }

class FcSection final : public StationSection {
  public:
    FcSection(const ReportContext& c, const FcStationStats& stats, const Timeline& timeline)
        : s_(stats), timeline_(timeline), by_severity_(stats.findings_by_severity) {
        for (FindingKind kind : kAllKinds)
            if (covers(kind))
                findings_[static_cast<std::size_t>(kind)] =
                    stats.findings[static_cast<std::size_t>(kind)];
        response_ms_ = fc_tracker(c).options().response_ns / 1'000'000;
        latency_ = DriveLatency::of(stats.latency_ns, stats.mean_latency_ns());
        names_ = station_naming(c.naming, stats.address);
    }

    std::uint8_t master() const override { return 0; }
    std::uint8_t slave() const override { return s_.address; }
    bool checked() const override { return s_.commands > 0; }
    std::uint64_t transactions() const override { return s_.answered; }
    const FindingCounts& findings() const override { return findings_; }
    bool covers(FindingKind kind) const override { return is_fc_finding_kind(kind); }

    void write_text(const ReportContext& /*c*/, TextBuffer& b) const override {
        const FcStationStats& s = s_;
        auto it = std::back_inserter(b);
        fmt::format_to(it, "\n{} (FC protocol)\n", title());
        fmt::format_to(it, "  commands       {}\n", commands_text());
        if (!broadcast()) {
            fmt::format_to(it, "  outcome        {}\n", outcomes_text());
            fmt::format_to(it, "  responses      {}; {}\n", responses_text(), late_text());
        }
        fmt::format_to(it, "  latency ms     {}\n", latency_text());
        fmt::format_to(it, "  parameters     {}\n", parameters_text(s, names_));
        if (!s.channel.rejections.empty()) {
            append(b, "  rejections    ");
            const char* separator = " ";
            for (const auto& [key, count] : s.channel.rejections) {
                fmt::format_to(it, "{}PNU {} fault code {} ({}) {}x", separator,
                               pnu_label(names_, key.first), key.second, fault_text(key.second),
                               count);
                separator = "; ";
            }
            b.push_back('\n');
        }
        fmt::format_to(it, "  findings       {}\n", findings_by_kind_text(findings_));
    }

    void write_markdown_row(const ReportContext& /*c*/, TextBuffer& b) const override {
        const FcStationStats& s = s_;
        fmt::format_to(
            std::back_inserter(b), "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
            broadcast() ? std::string("broadcast") : fmt::format("{}", s.address), s.commands,
            s.answered, s.no_responses, s.abandoned, s.damaged, s.not_judged_total(), s.late,
            latency_text(), s.channel.transactions.rejected,
            md_escape(findings_by_kind_text(findings_)));
    }

    void write_markdown(const ReportContext& /*c*/, TextBuffer& b) const override {
        const FcStationStats& s = s_;
        auto it = std::back_inserter(b);
        fmt::format_to(it, "\n### {} (FC protocol)\n\n", title());
        fmt::format_to(it, "- Commands: {}\n", commands_text());
        if (!broadcast()) {
            fmt::format_to(it, "- Outcome: {}\n", outcomes_text());
            fmt::format_to(it, "- Responses: {}; {}\n", responses_text(), late_text());
        }
        fmt::format_to(it, "- Latency ms: {}\n", latency_text());
        fmt::format_to(it, "- Parameters: {}\n", parameters_text(s, names_));
        for (const auto& [key, count] : s.channel.rejections)
            fmt::format_to(it, "- Rejected: PNU {} fault code {} ({}), {}x\n",
                           pnu_label(names_, key.first), key.second,
                           md_escape(fault_text(key.second)), count);
        fmt::format_to(it, "- Findings: {}\n", md_escape(findings_by_kind_text(findings_)));
    }

    void write_json(const ReportContext& /*c*/, JsonWriter& w) const override {
        const FcStationStats& s = s_;
        const DriveLatency& l = latency_;
        auto count = [&w](std::string_view key, std::uint64_t n) {
            w.key(key).integer(static_cast<std::int64_t>(n));
        };
        auto ms = [&w](std::string_view key, double v) {
            char text[64];
            auto end = fmt::format_to_n(text, sizeof text, "{:.6f}", v).out;
            w.key(key).number_text(std::string_view(text, static_cast<std::size_t>(end - text)));
        };
        w.begin_object();
        w.key("bus").string("fc");
        w.key("address").integer(s.address);
        w.key("broadcast").boolean(broadcast());
        count("telegrams", s.telegrams);
        count("commands", s.commands);
        count("damaged_commands", s.damaged_commands);
        count("process_commands", s.process_commands);
        w.key("commands_by_ak").begin_object();
        for (std::size_t ak = 0; ak < s.commands_by_ak.size(); ++ak)
            if (s.commands_by_ak[ak]) count(fmt::format("{}", ak), s.commands_by_ak[ak]);
        w.end_object();
        count("broadcasts", s.broadcasts);
        count("responses", s.responses);
        count("damaged_responses", s.damaged_responses);
        count("transactions", s.answered);
        count("no_responses", s.no_responses);
        count("abandoned", s.abandoned);
        count("damaged", s.damaged);
        count("not_judged", s.not_judged_total());
        w.key("late").optional_integer(s.timed(), static_cast<std::int64_t>(s.late));
        w.key("latency_ms");
        if (l.any) {
            w.begin_object();
            ms("min", l.min_ms);
            ms("mean", l.mean_ms);
            ms("p95", l.p95_ms);
            ms("max", l.max_ms);
            w.end_object();
        } else {
            w.null();
        }
        w.key("outcomes").begin_object();
        count("positive", s.channel.transactions.positive);
        count("rejected", s.channel.transactions.rejected);
        count("mismatched", s.channel.transactions.mismatched);
        count("unexpected", s.channel.transactions.unexpected);
        w.end_object();
        w.key("parameters").begin_array();
        for (const auto& [pnu, access] : s.parameters) {
            w.begin_object();
            w.key("pnu").integer(pnu);
            pnu_name_key(w, names_, pnu);
            count("reads", access.reads);
            count("writes", access.writes);
            w.end_object();
        }
        w.end_array();
        count("parameters_not_counted", s.parameters_not_counted);
        w.key("rejections").begin_array();
        for (const auto& [key, n] : s.channel.rejections) {
            w.begin_object();
            w.key("pnu").integer(key.first);
            pnu_name_key(w, names_, key.first);
            w.key("fault_code").integer(key.second);
            w.key("fault_text").string(fault_text(key.second));
            count("count", n);
            w.end_object();
        }
        w.end_array();
        w.key("findings").begin_object();
        for (FindingKind kind : kAllKinds)
            if (covers(kind))
                count(finding_kind_name(kind), findings_[static_cast<std::size_t>(kind)]);
        w.end_object();
        w.end_object();
    }

    void write_html_row(const ReportContext& /*c*/, TextBuffer& b) const override {
        const FcStationStats& s = s_;
        html_drive_row(b, fmt::format("drive-{}", s.address),
                       broadcast() ? std::string("broadcast") : fmt::format("{}", s.address),
                       DriveOutcomes::of(s), latency_, severity_totals(findings_, by_severity_));
    }

    void write_html(const ReportContext& c, TextBuffer& b) const override {
        const FcStationStats& s = s_;
        auto it = std::back_inserter(b);
        fmt::format_to(it,
                       "<section class=\"station\" id=\"drive-{}\">\n<h2>{} (FC protocol)</h2>\n"
                       "<table class=\"kv\">\n",
                       s.address, title());
        html_kv(b, "Commands", commands_text());
        if (!broadcast()) {
            html_kv(b, "Outcome", outcomes_text());
            html_kv(b, "Responses", fmt::format("{}; {}", responses_text(), late_text()));
        }
        html_kv(b, "Latency (ms)", latency_text());
        append(b, "</table>\n");
        if (!broadcast()) {
            append(b, "<h3>Latency histogram</h3>\n");
            if (!s.timed())
                append(b, "<p class=\"meta\">The capture carries no timestamps.</p>\n");
            else
                svg_latency_histogram(b, s.latency_ns, s.answered > 0, title_lower());
        }
        append(b,
               "<h3>Timeline</h3>\n<div class=\"legend\"><span><i class=\"swatch\" "
               "style=\"background:#4e79c5\"></i>transactions</span><span><i class=\"swatch\" "
               "style=\"background:#d92d20\"></i>errors</span><span><i class=\"swatch\" "
               "style=\"background:#f79009\"></i>warnings</span><span><i class=\"swatch\" "
               "style=\"background:#2e90fa\"></i>notes</span></div>\n");
        svg_timeline(b, timeline_, title_lower(), c);
        append(b, "<h3>Parameters accessed</h3>\n");
        if (html_parameter_table(b, s.parameters, names_) && s.parameters_not_counted)
            fmt::format_to(it, "<p class=\"meta\">{} more accesses to further parameters.</p>\n",
                           s.parameters_not_counted);
        if (!s.channel.rejections.empty()) {
            append(b,
                   "<h3>Rejected commands</h3>\n<table class=\"rejections\"><tr><th "
                   "class=\"n\">PNU</th><th class=\"n\">fault code</th><th>meaning</th><th "
                   "class=\"n\">count</th></tr>\n");
            for (const auto& [key, count] : s.channel.rejections)
                fmt::format_to(it,
                               "<tr><td class=\"n\">{}</td><td class=\"n\">{}</td><td>{}</td>"
                               "<td class=\"n\">{}</td></tr>\n",
                               xml(pnu_label(names_, key.first)), key.second,
                               xml(fault_text(key.second)), count);
            append(b, "</table>\n");
        }
        html_findings_by_kind(b, findings_, by_severity_);
        append(b, "</section>\n");
    }

    std::string junit_suite_name() const override {
        return broadcast() ? std::string("FC broadcasts") : fmt::format("FC drive {}", s_.address);
    }
    std::string junit_classname() const override {
        return fmt::format("dpscope.fc.drive_{}", s_.address);
    }
    std::string junit_note(FindingKind /*kind*/) const override { return {}; }
    std::vector<std::pair<std::string, std::uint64_t>> junit_properties() const override {
        return drive_properties(DriveOutcomes::of(s_), "responses", s_.responses);
    }

  private:
    bool broadcast() const { return s_.address == 0; }
    // "121: 77 process, parameter/text AK 1 x18, AK 2 x4; 0 broadcasts" (", 1 damaged" after the
    // AKs when commands were damaged).
    std::string commands_text() const {
        const FcStationStats& s = s_;
        return fmt::format(
            "{}: {} process, parameter/text {}{}; {}", s.commands, s.process_commands,
            commands_by_ak_text(s),
            s.damaged_commands ? fmt::format(", {} damaged", s.damaged_commands) : std::string(),
            counted(s.broadcasts, "broadcast", "broadcasts"));
    }
    std::string outcomes_text() const {
        const FcStationStats& s = s_;
        return command_outcomes_text(s.answered, s.no_responses, s.abandoned, s.damaged,
                                     s.not_judged_total());
    }
    // "120 (1 damaged)", or "119".
    std::string responses_text() const {
        return s_.damaged_responses
                   ? fmt::format("{} ({} damaged)", s_.responses, s_.damaged_responses)
                   : fmt::format("{}", s_.responses);
    }
    std::string title() const {
        return broadcast() ? std::string("Broadcasts") : fmt::format("Drive {}", s_.address);
    }
    std::string title_lower() const {
        return broadcast() ? std::string("broadcasts") : fmt::format("drive {}", s_.address);
    }
    // "1 late (over 20 ms)", or not judged without timestamps.
    std::string late_text() const {
        return s_.timed() ? fmt::format("{} late (over {} ms)", s_.late, response_ms_)
                          : std::string("lateness not judged (no timestamps)");
    }
    std::string latency_text() const { return latency_.text(broadcast(), s_.timed()); }

    const FcStationStats& s_;
    StationNaming names_;  // what names its PNUs (issue 29)
    const Timeline& timeline_;
    FindingCounts findings_{};
    const FindingSeverityCounts& by_severity_;
    std::int64_t response_ms_ = 0;
    DriveLatency latency_;
};

// One drive address of an FC capture (address 0: the broadcasts), with its timeline.
std::unique_ptr<StationSection> make_fc_section(const ReportContext& c, const FcStationStats& stats,
                                                const Timeline& timeline) {
    return std::make_unique<FcSection>(c, stats, timeline);
}

void add_fc_sections(const ReportContext& c, const ChannelTimelines& timelines, ReportModel& m) {
    add_drive_sections(c, fc_tracker(c).stations(), timelines, make_fc_section, m);
}

bool fc_tracked(const ReportContext& c) noexcept {
    return dynamic_cast<const FcTracker*>(c.tracker) != nullptr;
}

const BusStats& fc_bus_stats(const ReportContext& c) { return fc_tracker(c).bus(); }

std::string fc_checks_text(const ReportContext& c, const ReportModel& m) {
    return m.timed ? fmt::format("time-out {} ms, drive response time {} ms",
                                 fc_tracker(c).options().timeout_ns / 1'000'000,
                                 fc_tracker(c).options().response_ns / 1'000'000)
                   : std::string("time-outs and response times not judged (no timestamps)");
}

std::string_view fc_nothing_checked_reason(const ReportContext& c) {
    return c.stations.empty() ? "no command to a drive" : "no command to the selected drives";
}

void fc_write_json_options(const ReportContext& c, JsonWriter& w) {
    w.key("fc_response_ms").integer(fc_tracker(c).options().response_ns / 1'000'000);
}

}  // namespace

const BusReport& fc_bus_report() noexcept {
    static const BusReport report{
        .protocol = Protocol::Fc,
        .wording =
            {
                .name = "Danfoss FC protocol (RS-485)",
                .option = "fc",
                .checksum_kind = FindingKind::FcBccError,
                .checksum_label = "BCC errors",
                .checksum_key = "bcc_errors",
                .station = "drive",
                .stations = "drives",
                .markdown_table =
                    "## Drives\n\n| address | commands | answered | unanswered | abandoned | "
                    "damaged | not judged | late | latency ms (min / mean / p95 / max) | "
                    "rejected | findings |\n"
                    "|---|---:|---:|---:|---:|---:|---:|---:|---|---:|---|\n",
                .html_table = kDriveHtmlTable,
                .nothing_checked_case = "FC protocol: the capture holds commands to drives",
            },
        .tracked = fc_tracked,
        .add_sections = add_fc_sections,
        .is_bus_kind = is_fc_finding_kind,
        .bus_stats = fc_bus_stats,
        .checks_text = fc_checks_text,
        .nothing_checked_reason = fc_nothing_checked_reason,
        .write_json_options = fc_write_json_options,
        .checks_rc8_rule = false,
    };
    return report;
}

}  // namespace dpscope::report
