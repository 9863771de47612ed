// The report's section for one drive address of a VLT 2000 capture (address 00: the broadcasts):
// commands by control letter, replies, answered and unanswered commands, failed commands by reason
// code with its text, checksum errors and telegrams with the check switched off, latency,
// parameters accessed and findings by kind, in every format, as the VLT 2000 tracker counted them.
// And what a VLT 2000 report does and says as its own (vlt2000_bus_report()): a section per drive
// address, the protocol's kinds and options, its wording.
#include <algorithm>
#include <iterator>

#include "core/code_tables.hpp"
#include "formats/json.hpp"
#include "formats/parameter_names.hpp"
#include "formats/report_markup.hpp"
#include "formats/report_model.hpp"
#include "protocols/vlt2000/vlt2000_codes.hpp"
#include "protocols/vlt2000/vlt2000_decoder.hpp"
#include "protocols/vlt2000/vlt2000_tracker.hpp"

namespace dpscope::report {

namespace {

// The capture's tracker, a VLT 2000 one (vlt2000_tracked(): the report is VLT 2000's only when it
// is).
const Vlt2000Tracker& vlt2000_tracker(const ReportContext& c) noexcept {
    return static_cast<const Vlt2000Tracker&>(*c.tracker);
}

// --vlt2000-checksum check (the default): a wrong checksum is a finding; the report's checks say
// whether it was judged.
bool checksums_checked(const ReportContext& c) noexcept {
    const auto* decoder = dynamic_cast<const Vlt2000Decoder*>(c.decoder);
    return decoder == nullptr || decoder->options().check_checksum;
}

constexpr Vlt2000Letter kLetters[] = {Vlt2000Letter::Update, Vlt2000Letter::Read,
                                      Vlt2000Letter::Control, Vlt2000Letter::ReadIndex};

std::uint64_t commands_of(const Vlt2000StationStats& s, Vlt2000Letter letter) {
    return s.commands_by_letter[static_cast<std::size_t>(letter)];
}

// "U 1, R 3, C 1" (the letters sent), or "none".
std::string commands_by_letter_text(const Vlt2000StationStats& s) {
    std::string text;
    for (Vlt2000Letter letter : kLetters)
        if (commands_of(s, letter))
            text +=
                fmt::format("{}{} {}", text.empty() ? "" : ", ",
                            static_cast<char>(vlt2000_letter_char(letter)), commands_of(s, letter));
    return text.empty() ? "none" : text;
}

std::string_view reason_text(std::uint8_t reason) {
    return error_text_or_unknown(Dialect::Vlt2000, reason);
}

// "reason 00 (parameter does not exist) 1x, no reason code 2x", or "none".
std::string failures_text(const Vlt2000StationStats& s) {
    std::string text;
    for (const auto& [reason, count] : s.failures_by_reason)
        text += fmt::format("{}reason {:02} ({}) {}x", text.empty() ? "" : ", ", reason,
                            reason_text(reason), count);
    if (s.failures_without_reason)
        text += fmt::format("{}no reason code {}x", text.empty() ? "" : ", ",
                            s.failures_without_reason);
    return text.empty() ? "none" : text;
}

// "1 checksum error, 2 telegrams with the check off (\"??\")".
std::string checksums_text(const Vlt2000StationStats& s) {
    return fmt::format("{}, {} with the check off (\"??\")",
                       counted(s.checksum_errors, "checksum error", "checksum errors"),
                       counted(s.checksum_disabled, "telegram", "telegrams"));
}

std::string parameters_text(const Vlt2000StationStats& s, StationNaming names) {
    std::string text;
    for (const auto& [parameter, access] : s.parameters)
        text +=
            fmt::format("{}{} ({} read{}, {} write{})", text.empty() ? "" : ", ",
                        pnu_label(names, parameter), access.reads, access.reads == 1 ? "" : "s",
                        access.writes, access.writes == 1 ? "" : "s");
    if (s.parameters_not_counted)
        text += fmt::format("{}{} more accesses to further parameters", text.empty() ? "" : "; ",
                            s.parameters_not_counted);
    return text.empty() ? "none" : text;
}

class Vlt2000Section final : public StationSection {
  public:
    Vlt2000Section(const ReportContext& c, const Vlt2000StationStats& stats,
                   const Timeline& timeline)
        : s_(stats), timeline_(timeline), by_severity_(stats.findings_by_severity) {
        for (FindingKind kind : kAllKinds)
            if (covers(kind))
                findings_[static_cast<std::size_t>(kind)] =
                    stats.findings[static_cast<std::size_t>(kind)];
        latency_ = DriveLatency::of(stats.latency_ns, stats.mean_latency_ns());
        names_ = station_naming(c.naming, stats.address);
    }

    std::uint8_t master() const override { return 0; }
    std::uint8_t slave() const override { return s_.address; }
    // Checked: a command was paired with its reply.
    bool checked() const override { return s_.answered > 0; }
    std::uint64_t transactions() const override { return s_.answered; }
    const FindingCounts& findings() const override { return findings_; }
    bool covers(FindingKind kind) const override { return is_vlt2000_finding_kind(kind); }

    void write_text(const ReportContext& /*c*/, TextBuffer& b) const override {
        const Vlt2000StationStats& s = s_;
        auto it = std::back_inserter(b);
        fmt::format_to(it, "\n{} (VLT 2000)\n", title());
        fmt::format_to(it, "  commands       {}\n", commands_text());
        if (!broadcast()) fmt::format_to(it, "  outcome        {}\n", outcomes_text());
        fmt::format_to(it, "  replies        {}\n", replies_text());
        fmt::format_to(it, "  failed         {}: {}\n", s.failed, failures_text(s));
        fmt::format_to(it, "  checksums      {}\n", checksums_text(s));
        fmt::format_to(it, "  latency ms     {}\n", latency_text());
        fmt::format_to(it, "  parameters     {}\n", parameters_text(s, names_));
        fmt::format_to(it, "  findings       {}\n", findings_by_kind_text(findings_));
    }

    void write_markdown_row(const ReportContext& /*c*/, TextBuffer& b) const override {
        const Vlt2000StationStats& s = s_;
        fmt::format_to(
            std::back_inserter(b), "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
            broadcast() ? std::string("broadcast") : fmt::format("{:02}", s.address), s.commands,
            s.answered, s.no_responses, s.abandoned, s.damaged, s.not_judged_total(), s.failed,
            latency_text(), s.checksum_errors, md_escape(findings_by_kind_text(findings_)));
    }

    void write_markdown(const ReportContext& /*c*/, TextBuffer& b) const override {
        const Vlt2000StationStats& s = s_;
        auto it = std::back_inserter(b);
        fmt::format_to(it, "\n### {} (VLT 2000)\n\n", title());
        fmt::format_to(it, "- Commands: {}\n", commands_text());
        if (!broadcast()) fmt::format_to(it, "- Outcome: {}\n", outcomes_text());
        fmt::format_to(it, "- Replies: {}\n", replies_text());
        fmt::format_to(it, "- Failed: {}\n", s.failed);
        for (const auto& [reason, count] : s.failures_by_reason)
            fmt::format_to(it, "- Failed: reason code {:02} ({}), {}x\n", reason,
                           md_escape(reason_text(reason)), count);
        if (s.failures_without_reason)
            fmt::format_to(it, "- Failed: no reason code, {}x\n", s.failures_without_reason);
        fmt::format_to(it, "- Checksums: {}\n", md_escape(checksums_text(s)));
        fmt::format_to(it, "- Latency ms: {}\n", latency_text());
        fmt::format_to(it, "- Parameters: {}\n", parameters_text(s, names_));
        fmt::format_to(it, "- Findings: {}\n", md_escape(findings_by_kind_text(findings_)));
    }

    void write_json(const ReportContext& /*c*/, JsonWriter& w) const override {
        const Vlt2000StationStats& s = s_;
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
        w.key("bus").string("vlt2000");
        w.key("address").integer(s.address);
        w.key("broadcast").boolean(broadcast());
        count("telegrams", s.telegrams);
        count("commands", s.commands);
        count("damaged_commands", s.damaged_commands);
        w.key("commands_by_letter").begin_object();
        for (Vlt2000Letter letter : kLetters) {
            const char name[] = {static_cast<char>(vlt2000_letter_char(letter)), '\0'};
            count(name, commands_of(s, letter));
        }
        w.end_object();
        count("broadcasts", s.broadcasts);
        count("replies", s.replies);
        count("damaged_replies", s.damaged_replies);
        count("transactions", s.answered);
        count("no_responses", s.no_responses);
        count("abandoned", s.abandoned);
        count("damaged", s.damaged);
        count("not_judged", s.not_judged_total());
        count("failed", s.failed);
        w.key("failures").begin_array();
        for (const auto& [reason, n] : s.failures_by_reason) {
            w.begin_object();
            w.key("reason").integer(reason);
            w.key("reason_text").string(reason_text(reason));
            count("count", n);
            w.end_object();
        }
        w.end_array();
        count("failures_without_reason", s.failures_without_reason);
        count("checksum_errors", s.checksum_errors);
        count("checksum_disabled", s.checksum_disabled);
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
        count("failed", s.channel.transactions.rejected);
        count("mismatched", s.channel.transactions.mismatched);
        count("unexpected", s.channel.transactions.unexpected);
        w.end_object();
        w.key("parameters").begin_array();
        for (const auto& [parameter, access] : s.parameters) {
            w.begin_object();
            w.key("pnu").integer(parameter);
            pnu_name_key(w, names_, parameter);
            count("reads", access.reads);
            count("writes", access.writes);
            w.end_object();
        }
        w.end_array();
        count("parameters_not_counted", s.parameters_not_counted);
        w.key("findings").begin_object();
        for (FindingKind kind : kAllKinds)
            if (covers(kind))
                count(finding_kind_name(kind), findings_[static_cast<std::size_t>(kind)]);
        w.end_object();
        w.end_object();
    }

    void write_html_row(const ReportContext& /*c*/, TextBuffer& b) const override {
        const Vlt2000StationStats& s = s_;
        html_drive_row(b, fmt::format("drive-{:02}", s.address),
                       broadcast() ? std::string("broadcast") : fmt::format("{:02}", s.address),
                       DriveOutcomes::of(s), latency_, severity_totals(findings_, by_severity_));
    }

    void write_html(const ReportContext& c, TextBuffer& b) const override {
        const Vlt2000StationStats& s = s_;
        auto it = std::back_inserter(b);
        fmt::format_to(it,
                       "<section class=\"station\" id=\"drive-{:02}\">\n<h2>{} (VLT 2000)</h2>\n"
                       "<table class=\"kv\">\n",
                       s.address, title());
        html_kv(b, "Commands", commands_text());
        if (!broadcast()) html_kv(b, "Outcome", outcomes_text());
        html_kv(b, "Replies", replies_text());
        html_kv(b, "Failed", fmt::format("{}", s.failed));
        html_kv(b, "Checksums", checksums_text(s));
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
        if (s.failed > 0) {
            append(b,
                   "<h3>Failed commands</h3>\n<table class=\"failures\"><tr><th "
                   "class=\"n\">reason code</th><th>meaning</th><th class=\"n\">count</th></tr>\n");
            for (const auto& [reason, count] : s.failures_by_reason)
                fmt::format_to(it,
                               "<tr><td class=\"n\">{:02}</td><td>{}</td><td class=\"n\">{}</td>"
                               "</tr>\n",
                               reason, xml(reason_text(reason)), count);
            if (s.failures_without_reason)
                fmt::format_to(it,
                               "<tr><td class=\"n\">-</td><td>no reason code</td><td "
                               "class=\"n\">{}</td></tr>\n",
                               s.failures_without_reason);
            append(b, "</table>\n");
        }
        html_findings_by_kind(b, findings_, by_severity_);
        append(b, "</section>\n");
    }

    std::string junit_suite_name() const override {
        return broadcast() ? std::string("VLT 2000 broadcasts")
                           : fmt::format("VLT 2000 drive {:02}", s_.address);
    }
    std::string junit_classname() const override {
        return fmt::format("dpscope.vlt2000.drive_{:02}", s_.address);
    }
    std::string junit_note(FindingKind /*kind*/) const override { return {}; }
    std::vector<std::pair<std::string, std::uint64_t>> junit_properties() const override {
        return drive_properties(DriveOutcomes::of(s_), "replies", s_.replies);
    }

  private:
    bool broadcast() const { return s_.address == 0; }
    // "81: U 11, R 25, C 33, I 12; 0 broadcasts" (", 1 damaged" after the letters when commands
    // were damaged).
    std::string commands_text() const {
        const Vlt2000StationStats& s = s_;
        return fmt::format(
            "{}: {}{}; {}", s.commands, commands_by_letter_text(s),
            s.damaged_commands ? fmt::format(", {} damaged", s.damaged_commands) : std::string(),
            counted(s.broadcasts, "broadcast", "broadcasts"));
    }
    std::string outcomes_text() const {
        const Vlt2000StationStats& s = s_;
        return command_outcomes_text(s.answered, s.no_responses, s.abandoned, s.damaged,
                                     s.not_judged_total());
    }
    std::string title() const {
        return broadcast() ? std::string("Broadcasts") : fmt::format("Drive {:02}", s_.address);
    }
    std::string title_lower() const {
        return broadcast() ? std::string("broadcasts") : fmt::format("drive {:02}", s_.address);
    }
    // "80 (1 damaged)", "79"; for the broadcasts, which nobody answers, "1 (nobody replies to a
    // broadcast)".
    std::string replies_text() const {
        const std::string damaged =
            s_.damaged_replies ? fmt::format(", {} damaged", s_.damaged_replies) : std::string();
        if (broadcast())
            return fmt::format("{} (nobody replies to a broadcast{})", s_.replies, damaged);
        return s_.damaged_replies ? fmt::format("{} ({} damaged)", s_.replies, s_.damaged_replies)
                                  : fmt::format("{}", s_.replies);
    }
    std::string latency_text() const { return latency_.text(broadcast(), s_.timed()); }

    const Vlt2000StationStats& s_;
    StationNaming names_;  // what names its parameters (issue 29)
    const Timeline& timeline_;
    FindingCounts findings_{};
    const FindingSeverityCounts& by_severity_;
    DriveLatency latency_;
};

// One drive address of a VLT 2000 capture (address 00: the broadcasts), with its timeline.
std::unique_ptr<StationSection> make_vlt2000_section(const ReportContext& c,
                                                     const Vlt2000StationStats& stats,
                                                     const Timeline& timeline) {
    return std::make_unique<Vlt2000Section>(c, stats, timeline);
}

void add_vlt2000_sections(const ReportContext& c, const ChannelTimelines& timelines,
                          ReportModel& m) {
    add_drive_sections(c, vlt2000_tracker(c).stations(), timelines, make_vlt2000_section, m);
}

bool vlt2000_tracked(const ReportContext& c) noexcept {
    return dynamic_cast<const Vlt2000Tracker*>(c.tracker) != nullptr;
}

const BusStats& vlt2000_bus_stats(const ReportContext& c) { return vlt2000_tracker(c).bus(); }

std::string vlt2000_checks_text(const ReportContext& c, const ReportModel& m) {
    return fmt::format(
        "{}, {}",
        m.timed ? fmt::format("time-out {} ms", vlt2000_tracker(c).options().timeout_ns / 1'000'000)
                : std::string(kNoTimestamps),
        checksums_checked(c) ? "checksums checked"
                             : "checksums not checked (--vlt2000-checksum ignore)");
}

std::string_view vlt2000_nothing_checked_reason(const ReportContext& c) {
    return c.stations.empty() ? "no command answered by a drive"
                              : "no command answered by the selected drives";
}

void vlt2000_write_json_options(const ReportContext& c, JsonWriter& w) {
    w.key("vlt2000_checksum").string(checksums_checked(c) ? "check" : "ignore");
}

}  // namespace

const BusReport& vlt2000_bus_report() noexcept {
    static const BusReport report{
        .protocol = Protocol::Vlt2000,
        .wording =
            {
                .name = "Danfoss VLT 2000 serial telegram (ASCII)",
                .option = "vlt2000",
                .checksum_kind = FindingKind::Vlt2000ChecksumError,
                .checksum_label = "bad checksums",
                .checksum_key = "checksum_errors",
                .station = "drive",
                .stations = "drives",
                .markdown_table =
                    "## Drives\n\n| address | commands | answered | unanswered | abandoned | "
                    "damaged | not judged | failed | latency ms (min / mean / p95 / max) | "
                    "checksum errors | findings |\n"
                    "|---|---:|---:|---:|---:|---:|---:|---:|---|---:|---|\n",
                .html_table = kDriveHtmlTable,
                .nothing_checked_case = "VLT 2000: the capture holds commands answered by drives",
            },
        .tracked = vlt2000_tracked,
        .add_sections = add_vlt2000_sections,
        .is_bus_kind = is_vlt2000_finding_kind,
        .bus_stats = vlt2000_bus_stats,
        .checks_text = vlt2000_checks_text,
        .nothing_checked_reason = vlt2000_nothing_checked_reason,
        .write_json_options = vlt2000_write_json_options,
        .checks_rc8_rule = false,
    };
    return report;
}

}  // namespace dpscope::report
