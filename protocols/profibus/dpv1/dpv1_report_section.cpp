// The report's section for DP-V1 parameter access of a DP slave (PROFIdrive over MSAC_C1 and
// MSAC_C2), beside its cyclic channel: transactions, latency, polls, parameters accessed,
// negative responses with their error texts and the DP-V1 findings by kind, in every format.
#include <iterator>

#include "formats/parameter_names.hpp"
#include "formats/report_markup.hpp"
#include "formats/report_model.hpp"

namespace dpscope::report {

namespace {

std::string plural_count(std::uint64_t n, std::string_view singular, std::string_view plural) {
    return counted(n, singular, plural);
}

// "12 (2 reads), 40 (1 read, 1 write)", or "none".
std::string parameters_text(const Dpv1Stats& s, StationNaming names) {
    std::string text;
    for (const auto& [pnu, use] : s.parameters) {
        std::string uses;
        if (use.reads) uses = plural_count(use.reads, "read", "reads");
        if (use.writes)
            uses += (uses.empty() ? "" : ", ") + plural_count(use.writes, "write", "writes");
        text += fmt::format("{}{} ({})", text.empty() ? "" : ", ", pnu_label(names, pnu), uses);
    }
    if (text.empty()) text = "none";
    if (s.parameters_not_counted)
        text += fmt::format("; {} to further PNUs not counted (at most {} PNUs)",
                            plural_count(s.parameters_not_counted, "access", "accesses"),
                            Dpv1Stats::kMaxParameters);
    return text;
}

// "5 started, 2 completed, 0 refused, 0 abandoned, 2 timed out (1 answered late), 1 open at end
// of capture": every transaction started is in exactly one of these (the late ones are among the
// timed out).
std::string transactions_text(const Dpv1Stats& s, bool timed) {
    std::string text = fmt::format(
        "{} started, {} completed, {} refused, {} abandoned, {}", s.started, s.completed, s.refused,
        s.abandoned, timed ? fmt::format("{} timed out", s.timeouts) : std::string(kNoTimestamps));
    if (s.late) fmt::format_to(std::back_inserter(text), " ({} answered late)", s.late);
    if (s.open) fmt::format_to(std::back_inserter(text), ", {} open at end of capture", s.open);
    return text;
}

// "; 3 with further error numbers not listed (at most 256 listed)", or "".
std::string errors_not_listed_text(const Dpv1Stats& s) {
    if (!s.negative_errors_not_listed) return {};
    return fmt::format("; {} with further error numbers not listed (at most {} listed)",
                       plural_count(s.negative_errors_not_listed, "block", "blocks"),
                       Dpv1Stats::kMaxNegativeErrors);
}

std::string polls_text(const Dpv1Stats& s) {
    return fmt::format("{}, at most {} in one transaction",
                       plural_count(s.polls, "state-conflict poll", "state-conflict polls"),
                       s.max_polls);
}

std::string error_text_of(const Dpv1Stats& s, std::uint16_t error) {
    return std::string(profidrive_error_text(error, s.dialect));
}

class Dpv1Section final : public StationSection {
  public:
    Dpv1Section(const ChannelStats& stats, StationNaming names)
        : c_(stats), s_(stats.dpv1), names_(names), by_severity_(stats.findings_by_severity) {
        for (FindingKind kind : kAllKinds)
            if (covers(kind))
                findings_[static_cast<std::size_t>(kind)] =
                    stats.findings[static_cast<std::size_t>(kind)];
        timed_ = s_.first_time_ns != kNoTime;
        const LogHistogram& h = s_.latency_ns;
        any_latency_ = h.count() > 0;
        if (any_latency_) {
            min_ms_ = to_ms(h.min());
            median_ms_ = to_ms(h.percentile(50));
            mean_ms_ = to_ms(s_.latency_mean_ns());
            p95_ms_ = to_ms(h.percentile(95));
            max_ms_ = to_ms(h.max());
        }
    }

    std::uint8_t master() const override { return c_.master; }
    std::uint8_t slave() const override { return c_.slave; }
    bool checked() const override { return s_.telegrams > 0; }
    std::uint64_t transactions() const override { return s_.completed; }
    const FindingCounts& findings() const override { return findings_; }
    bool covers(FindingKind kind) const override {
        return finding_component(kind) == FindingComponent::Dpv1ParameterAccess;
    }

    void write_text(const ReportContext& /*c*/, TextBuffer& b) const override {
        auto it = std::back_inserter(b);
        fmt::format_to(it, "\nSlave {} (master {}): DP-V1 parameter access\n", c_.slave, c_.master);
        fmt::format_to(it, "  DP-V1          {}\n",
                       plural_count(s_.telegrams, "telegram", "telegrams"));
        fmt::format_to(it, "  transactions   {}\n", transactions_text(s_, timed_));
        fmt::format_to(it, "  latency ms     {}\n", latency_text());
        fmt::format_to(it, "  polls          {}\n", polls_text(s_));
        fmt::format_to(it, "  parameters     {}\n", parameters_text(s_, names_));
        fmt::format_to(it, "  negative       {}", s_.negative_responses);
        const char* separator = ":";
        for (const auto& [error, n] : s_.negative_errors) {
            fmt::format_to(it, "{} error 0x{:02X} ({}) {}x", separator, error,
                           error_text_of(s_, error), n);
            separator = ";";
        }
        append(b, errors_not_listed_text(s_));
        b.push_back('\n');
        fmt::format_to(it, "  error PDUs     {}\n", s_.error_pdus);
        fmt::format_to(it, "  findings       {}\n", findings_by_kind_text(findings_));
    }

    void write_markdown_row(const ReportContext& /*c*/, TextBuffer& b) const override {
        std::string ms = !timed_        ? "no timestamps"
                         : any_latency_ ? fmt::format("{:.3f} / {:.3f} / {:.3f} / {:.3f}", min_ms_,
                                                      median_ms_, p95_ms_, max_ms_)
                                        : "-";
        fmt::format_to(std::back_inserter(b),
                       "| {} | {} | DP-V1 | {} | {} | {} | {} | {} | - | {} |\n", c_.slave,
                       c_.master, dialect_name(s_.dialect), s_.completed, s_.negative_responses,
                       timed_ ? fmt::format("{}", s_.timeouts) : "not judged", ms,
                       md_escape(findings_by_kind_text(findings_)));
    }

    void write_markdown(const ReportContext& /*c*/, TextBuffer& b) const override {
        auto it = std::back_inserter(b);
        fmt::format_to(it, "\n### Slave {} (master {}): DP-V1 parameter access\n\n", c_.slave,
                       c_.master);
        fmt::format_to(it, "- DP-V1: {}\n", plural_count(s_.telegrams, "telegram", "telegrams"));
        fmt::format_to(it, "- Transactions: {}\n", md_escape(transactions_text(s_, timed_)));
        fmt::format_to(it, "- Latency ms: {}\n", md_escape(latency_text()));
        fmt::format_to(it, "- Polls: {}\n", md_escape(polls_text(s_)));
        fmt::format_to(it, "- Parameters: {}\n", md_escape(parameters_text(s_, names_)));
        fmt::format_to(it, "- Negative responses: {}\n", s_.negative_responses);
        for (const auto& [error, n] : s_.negative_errors)
            fmt::format_to(it, "- Error 0x{:02X} ({}), {}x\n", error,
                           md_escape(error_text_of(s_, error)), n);
        if (s_.negative_errors_not_listed)
            fmt::format_to(it, "- Further error numbers not listed: {}\n",
                           plural_count(s_.negative_errors_not_listed, "block", "blocks"));
        fmt::format_to(it, "- Error PDUs: {}\n", s_.error_pdus);
        fmt::format_to(it, "- Findings: {}\n", md_escape(findings_by_kind_text(findings_)));
    }

    void write_json(const ReportContext& /*c*/, JsonWriter& w) const override {
        auto count = [&w](std::string_view key, std::uint64_t n) {
            w.key(key).integer(static_cast<std::int64_t>(n));
        };
        auto number = [&w](double v) {
            char text[64];
            auto end = fmt::format_to_n(text, sizeof text, "{:.6f}", v).out;
            w.number_text(std::string_view(text, static_cast<std::size_t>(end - text)));
        };
        w.begin_object();
        w.key("master").integer(c_.master);
        w.key("slave").integer(c_.slave);
        w.key("channel").string("dpv1");
        w.key("dialect").string(dialect_name(s_.dialect));
        count("telegrams", s_.telegrams);
        count("transactions", s_.completed);
        count("started", s_.started);
        count("completed", s_.completed);
        count("refused", s_.refused);
        count("abandoned", s_.abandoned);
        w.key("timeouts").optional_integer(timed_, static_cast<std::int64_t>(s_.timeouts));
        count("late", s_.late);
        count("open", s_.open);
        count("polls", s_.polls);
        count("max_polls", s_.max_polls);
        w.key("latency_ms");
        if (!any_latency_) {
            w.null();
        } else {
            w.begin_object();
            w.key("min");
            number(min_ms_);
            w.key("mean");
            number(mean_ms_);
            w.key("p95");
            number(p95_ms_);
            w.key("max");
            number(max_ms_);
            w.end_object();
        }
        w.key("parameters").begin_array();
        for (const auto& [pnu, use] : s_.parameters) {
            w.begin_object();
            w.key("pnu").integer(pnu);
            pnu_name_key(w, names_, pnu);
            count("reads", use.reads);
            count("writes", use.writes);
            w.end_object();
        }
        w.end_array();
        count("parameters_not_counted", s_.parameters_not_counted);
        count("negative_responses", s_.negative_responses);
        w.key("negative_errors").begin_array();
        for (const auto& [error, n] : s_.negative_errors) {
            w.begin_object();
            w.key("error").integer(error);
            w.key("error_text").string(error_text_of(s_, error));
            count("count", n);
            w.end_object();
        }
        w.end_array();
        count("negative_errors_not_listed", s_.negative_errors_not_listed);
        count("error_pdus", s_.error_pdus);
        w.key("findings").begin_object();
        for (FindingKind kind : kAllKinds)
            if (covers(kind))
                count(finding_kind_name(kind), findings_[static_cast<std::size_t>(kind)]);
        w.end_object();
        w.end_object();
    }

    void write_html_row(const ReportContext& /*c*/, TextBuffer& b) const override {
        const std::array<std::uint64_t, 3> severities = severity_totals(findings_, by_severity_);
        fmt::format_to(std::back_inserter(b),
                       "<tr><td class=\"n\"><a href=\"#slave-{}-{}-dpv1\">{}</a></td><td "
                       "class=\"n\">{}</td><td>DP-V1</td><td>{}</td><td class=\"n\">{}</td><td "
                       "class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n error\">{}</td>"
                       "<td class=\"n warning\">{}</td><td class=\"n note\">{}</td></tr>\n",
                       c_.slave, c_.master, c_.slave, c_.master, dialect_name(s_.dialect),
                       s_.completed, any_latency_ ? fmt::format("{:.3f}", median_ms_) : "-",
                       any_latency_ ? fmt::format("{:.3f}", p95_ms_) : "-", severities[2],
                       severities[1], severities[0]);
    }

    void write_html(const ReportContext& /*c*/, TextBuffer& b) const override {
        auto it = std::back_inserter(b);
        fmt::format_to(it,
                       "<section class=\"station\" id=\"slave-{}-{}-dpv1\">\n<h2>Slave {} (master "
                       "{}): DP-V1 parameter access</h2>\n<table class=\"kv\">\n",
                       c_.slave, c_.master, c_.slave, c_.master);
        html_kv(b, "DP-V1", plural_count(s_.telegrams, "telegram", "telegrams"));
        html_kv(b, "Transactions", transactions_text(s_, timed_));
        html_kv(b, "Latency (ms)", latency_text());
        html_kv(b, "Polls", polls_text(s_));
        html_kv(b, "Negative responses", fmt::format("{}", s_.negative_responses));
        html_kv(b, "Error PDUs", fmt::format("{}", s_.error_pdus));
        append(b, "</table>\n<h3>Parameters accessed</h3>\n");
        if (html_parameter_table(b, s_.parameters, names_) && s_.parameters_not_counted)
            fmt::format_to(it, "<p class=\"meta\">{} to further PNUs not counted.</p>\n",
                           plural_count(s_.parameters_not_counted, "access", "accesses"));
        if (!s_.negative_errors.empty()) {
            append(b,
                   "<h3>Negative responses</h3>\n<table class=\"rejections\"><tr><th "
                   "class=\"n\">error</th><th>meaning</th><th class=\"n\">count</th></tr>\n");
            for (const auto& [error, n] : s_.negative_errors)
                fmt::format_to(it,
                               "<tr><td class=\"n\">0x{:02X}</td><td>{}</td><td "
                               "class=\"n\">{}</td></tr>\n",
                               error, xml(error_text_of(s_, error)), n);
            append(b, "</table>\n");
            if (s_.negative_errors_not_listed)
                fmt::format_to(it,
                               "<p class=\"meta\">{} with further error numbers not listed.</p>\n",
                               plural_count(s_.negative_errors_not_listed, "block", "blocks"));
        }
        html_findings_by_kind(b, findings_, by_severity_);
        append(b, "</section>\n");
    }

    std::string junit_suite_name() const override {
        return fmt::format("slave {} (master {}) DP-V1", c_.slave, c_.master);
    }
    std::string junit_classname() const override {
        return fmt::format("dpscope.master_{}.slave_{}.dpv1", c_.master, c_.slave);
    }
    std::string junit_note(FindingKind /*kind*/) const override { return {}; }

  private:
    // "min 3.000  mean 4.000  p95 7.000  max 12.000", "-", or not measured.
    std::string latency_text() const {
        if (!timed_) return "not measured (no timestamps)";
        if (!any_latency_) return "-";
        return fmt::format("min {:.3f}  mean {:.3f}  p95 {:.3f}  max {:.3f}", min_ms_, mean_ms_,
                           p95_ms_, max_ms_);
    }

    const ChannelStats& c_;
    const Dpv1Stats& s_;
    StationNaming names_;  // what names its PNUs (issue 29); null: none
    FindingCounts findings_{};  // the DP-V1 kinds only
    const FindingSeverityCounts& by_severity_;
    bool timed_ = false;
    bool any_latency_ = false;
    double min_ms_ = 0, median_ms_ = 0, mean_ms_ = 0, p95_ms_ = 0, max_ms_ = 0;
};

}  // namespace

std::unique_ptr<StationSection> make_dpv1_section(const ChannelStats& stats,
                                                  StationNaming names) {
    return std::make_unique<Dpv1Section>(stats, names);
}

}  // namespace dpscope::report
