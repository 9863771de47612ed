// The report's section for one drive address of a toybus capture: its requests and responses,
// the transactions the parameter-channel engine paired, time-outs, latency and findings by kind,
// in every format; and what a toybus report does and says as its own (toybus_bus_report()).
#include <iterator>

#include "formats/report_markup.hpp"
#include "formats/report_model.hpp"
#include "protocols/toybus/toybus_tracker.hpp"

namespace dpscope::report {

namespace {

// The capture's tracker, a toybus one (toybus_tracked()).
const ToybusTracker& toybus_tracker(const ReportContext& c) noexcept {
    return static_cast<const ToybusTracker&>(*c.tracker);
}

constexpr std::string_view kToybusHtmlTable =
    "<tr><th class=\"n\">address</th><th class=\"n\">telegrams</th><th class=\"n\">requests</th>"
    "<th class=\"n\">transactions</th><th class=\"n\">time-outs</th><th class=\"n\">errors</th>"
    "<th class=\"n\">warnings</th><th class=\"n\">notes</th></tr>\n";

class ToybusSection final : public StationSection {
  public:
    explicit ToybusSection(const ToybusStationStats& stats) : s_(stats) {
        for (FindingKind kind : kAllKinds)
            if (covers(kind))
                findings_[static_cast<std::size_t>(kind)] =
                    stats.findings[static_cast<std::size_t>(kind)];
    }

    std::uint8_t master() const override { return 0; }
    std::uint8_t slave() const override { return s_.address; }
    bool checked() const override { return transactions() > 0; }
    std::uint64_t transactions() const override { return s_.channel.transactions.total(); }
    const FindingCounts& findings() const override { return findings_; }
    bool covers(FindingKind kind) const override { return is_toybus_finding_kind(kind); }

    void write_text(const ReportContext& /*c*/, TextBuffer& b) const override {
        auto it = std::back_inserter(b);
        fmt::format_to(it, "\nDrive {:02} (toybus)\n", s_.address);
        fmt::format_to(it, "  telegrams      {} intact, {} damaged\n", s_.telegrams, s_.damaged);
        fmt::format_to(it, "  requests       {}\n", requests_text());
        fmt::format_to(it, "  responses      {}\n", responses_text());
        fmt::format_to(it, "  transactions   {}\n", transactions_text());
        fmt::format_to(it, "  latency ms     {}\n", latency_text());
        fmt::format_to(it, "  findings       {}\n", findings_by_kind_text(findings_));
    }

    void write_markdown_row(const ReportContext& /*c*/, TextBuffer& b) const override {
        fmt::format_to(std::back_inserter(b), "| {:02} | {} | {} | {} | {} | {} |\n", s_.address,
                       s_.telegrams, s_.reads + s_.writes, transactions(), s_.channel.timeouts,
                       md_escape(findings_by_kind_text(findings_)));
    }

    void write_markdown(const ReportContext& /*c*/, TextBuffer& b) const override {
        auto it = std::back_inserter(b);
        fmt::format_to(it, "\n### Drive {:02} (toybus)\n\n", s_.address);
        fmt::format_to(it, "- Telegrams: {} intact, {} damaged\n", s_.telegrams, s_.damaged);
        fmt::format_to(it, "- Requests: {}\n", requests_text());
        fmt::format_to(it, "- Responses: {}\n", responses_text());
        fmt::format_to(it, "- Transactions: {}\n", transactions_text());
        fmt::format_to(it, "- Latency ms: {}\n", latency_text());
        fmt::format_to(it, "- Findings: {}\n", md_escape(findings_by_kind_text(findings_)));
    }

    void write_json(const ReportContext& /*c*/, JsonWriter& w) const override {
        auto count = [&w](std::string_view key, std::uint64_t n) {
            w.key(key).integer(static_cast<std::int64_t>(n));
        };
        const TransactionCounts& tx = s_.channel.transactions;
        w.begin_object();
        w.key("bus").string("toybus");
        w.key("address").integer(s_.address);
        count("telegrams", s_.telegrams);
        count("reads", s_.reads);
        count("writes", s_.writes);
        count("values", s_.values);
        count("errors", s_.errors);
        count("damaged", s_.damaged);
        count("transactions", tx.total());
        w.key("outcomes").begin_object();
        count("positive", tx.positive);
        count("rejected", tx.rejected);
        count("mismatched", tx.mismatched);
        count("unexpected", tx.unexpected);
        w.end_object();
        count("timeouts", s_.channel.timeouts);
        count("abandoned", s_.channel.abandoned);
        w.key("findings").begin_object();
        for (FindingKind kind : kAllKinds)
            if (covers(kind))
                count(finding_kind_name(kind), findings_[static_cast<std::size_t>(kind)]);
        w.end_object();
        w.end_object();
    }

    void write_html_row(const ReportContext& /*c*/, TextBuffer& b) const override {
        const auto severities = severity_totals(findings_, s_.findings_by_severity);
        fmt::format_to(std::back_inserter(b),
                       "<tr><td class=\"n\"><a href=\"#drive-{0:02}\">{0:02}</a></td><td "
                       "class=\"n\">{1}</td><td class=\"n\">{2}</td><td class=\"n\">{3}</td><td "
                       "class=\"n\">{4}</td><td class=\"n\">{5}</td><td class=\"n\">{6}</td><td "
                       "class=\"n\">{7}</td></tr>\n",
                       s_.address, s_.telegrams, s_.reads + s_.writes, transactions(),
                       s_.channel.timeouts, severities[2], severities[1], severities[0]);
    }

    void write_html(const ReportContext& /*c*/, TextBuffer& b) const override {
        fmt::format_to(std::back_inserter(b),
                       "<section class=\"station\" id=\"drive-{0:02}\">\n<h2>Drive {0:02} "
                       "(toybus)</h2>\n<table class=\"kv\">\n",
                       s_.address);
        html_kv(b, "Telegrams", fmt::format("{} intact, {} damaged", s_.telegrams, s_.damaged));
        html_kv(b, "Requests", requests_text());
        html_kv(b, "Responses", responses_text());
        html_kv(b, "Transactions", transactions_text());
        html_kv(b, "Latency (ms)", latency_text());
        append(b, "</table>\n");
        html_findings_by_kind(b, findings_, s_.findings_by_severity);
        append(b, "</section>\n");
    }

    std::string junit_suite_name() const override {
        return fmt::format("toybus drive {:02}", s_.address);
    }
    std::string junit_classname() const override {
        return fmt::format("dpscope.toybus.drive_{:02}", s_.address);
    }
    std::string junit_note(FindingKind /*kind*/) const override { return {}; }

  private:
    std::string requests_text() const {
        return fmt::format("{}: {} read, {} write", s_.reads + s_.writes, s_.reads, s_.writes);
    }
    std::string responses_text() const {
        return fmt::format("{}: {} value, {} error", s_.values + s_.errors, s_.values, s_.errors);
    }
    std::string transactions_text() const {
        const TransactionCounts& tx = s_.channel.transactions;
        return fmt::format("{} ({} positive, {} rejected, {} mismatched); {} timed out", tx.total(),
                           tx.positive, tx.rejected, tx.mismatched, s_.channel.timeouts);
    }
    std::string latency_text() const {
        const LogHistogram& h = s_.channel.latency_ns;
        if (h.count() == 0) return "-";
        return fmt::format("min {:.3f}  p95 {:.3f}  max {:.3f}", to_ms(h.min()),
                           to_ms(h.percentile(95)), to_ms(h.max()));
    }

    const ToybusStationStats& s_;
    FindingCounts findings_{};
};

void add_toybus_sections(const ReportContext& c, const ChannelTimelines& /*timelines*/,
                         ReportModel& m) {
    for (const ToybusStationStats* stats : toybus_tracker(c).stations()) {
        if (!shows_slave(c, stats->address)) continue;
        m.stations.push_back(std::make_unique<ToybusSection>(*stats));
        ++m.slaves;
    }
}

bool toybus_tracked(const ReportContext& c) noexcept {
    return dynamic_cast<const ToybusTracker*>(c.tracker) != nullptr;
}

const BusStats& toybus_bus_stats(const ReportContext& c) { return toybus_tracker(c).bus(); }

std::string toybus_checks_text(const ReportContext& c, const ReportModel& m) {
    return m.timed
               ? fmt::format("time-out {} ms", toybus_tracker(c).options().timeout_ns / 1'000'000)
               : std::string(kNoTimestamps);
}

std::string_view toybus_nothing_checked_reason(const ReportContext& c) {
    return c.stations.empty() ? "no request answered by a drive"
                              : "no request answered by the selected drives";
}

}  // namespace

const BusReport& toybus_bus_report() noexcept {
    static const BusReport report{
        .protocol = Protocol::Toybus,
        .wording =
            {
                .name = "toybus (a toy ASCII line protocol)",
                .option = "toybus",
                // No checksum: the summary counts the malformed telegrams in its place.
                .checksum_kind = FindingKind::MalformedTelegram,
                .checksum_label = "malformed telegrams",
                .checksum_key = "malformed_telegrams",
                .station = "drive",
                .stations = "drives",
                .markdown_table = "## Drives\n\n| address | telegrams | requests | transactions | "
                                  "time-outs | findings |\n|---|---:|---:|---:|---:|---|\n",
                .html_table = kToybusHtmlTable,
                .nothing_checked_case = "toybus: the capture holds requests answered by drives",
            },
        .tracked = toybus_tracked,
        .add_sections = add_toybus_sections,
        .is_bus_kind = is_toybus_finding_kind,
        .bus_stats = toybus_bus_stats,
        .checks_text = toybus_checks_text,
        .nothing_checked_reason = toybus_nothing_checked_reason,
        .write_json_options = nullptr,
        .checks_rc8_rule = false,
    };
    return report;
}

}  // namespace dpscope::report
