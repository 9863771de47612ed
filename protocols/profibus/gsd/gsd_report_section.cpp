#include "protocols/profibus/gsd/gsd_report_section.hpp"

#include <fmt/format.h>

#include <iterator>

#include "formats/report_markup.hpp"

namespace dpscope::report {

namespace {

double to_us(std::uint64_t ns) { return static_cast<double>(ns) / 1e3; }

class GsdSection final : public StationSection {
  public:
    GsdSection(const ChannelStats& stats, std::vector<const GsdModule*> modules)
        : c_(stats),
          g_(*stats.gsd),
          modules_(std::move(modules)),
          by_severity_(stats.findings_by_severity) {
        for (FindingKind kind : kGsdKinds)
            if (covers(kind))
                findings_[static_cast<std::size_t>(kind)] =
                    stats.findings[static_cast<std::size_t>(kind)];
    }

    std::uint8_t master() const override { return c_.master; }
    std::uint8_t slave() const override { return c_.slave; }
    bool checked() const override {
        for (std::uint64_t n : g_.judged)
            if (n > 0) return true;
        return false;
    }
    std::uint64_t transactions() const override { return 0; }
    const FindingCounts& findings() const override { return findings_; }
    // The GSD checks that were run on the slave (a check not run is no passed test).
    bool covers(FindingKind kind) const override {
        if (finding_component(kind) != FindingComponent::DeviceDescription) return false;
        return g_.judged_by(kind) > 0 || c_.findings[static_cast<std::size_t>(kind)] > 0;
    }

    void write_text(const ReportContext& /*c*/, TextBuffer& b) const override {
        auto it = std::back_inserter(b);
        fmt::format_to(it, "\nSlave {} (master {}): GSD device description\n", c_.slave, c_.master);
        fmt::format_to(it, "  GSD            {}\n", device_text());
        fmt::format_to(it, "  modules        {}\n", modules_text());
        fmt::format_to(it, "  answer us      {}\n", answer_text());
        fmt::format_to(it, "  poll ms        {}\n", poll_text());
        fmt::format_to(it, "  checks         {}\n", checks_text());
        fmt::format_to(it, "  findings       {}\n", findings_by_kind_text(findings_));
    }

    void write_markdown_row(const ReportContext& /*c*/, TextBuffer& b) const override {
        fmt::format_to(std::back_inserter(b),
                       "| {} | {} | GSD | {} | - | - | - | answer µs: {} | - | {} |\n", c_.slave,
                       c_.master, md_escape(gsd_device_title(*g_.device)), md_escape(answer_text()),
                       md_escape(findings_by_kind_text(findings_)));
    }

    void write_markdown(const ReportContext& /*c*/, TextBuffer& b) const override {
        auto it = std::back_inserter(b);
        fmt::format_to(it, "\n### Slave {} (master {}): GSD device description\n\n", c_.slave,
                       c_.master);
        fmt::format_to(it, "- GSD: {}\n", md_escape(device_text()));
        fmt::format_to(it, "- Modules: {}\n", md_escape(modules_text()));
        fmt::format_to(it, "- Answer µs: {}\n", md_escape(answer_text()));
        fmt::format_to(it, "- Poll interval ms: {}\n", md_escape(poll_text()));
        fmt::format_to(it, "- Checks: {}\n", md_escape(checks_text()));
        fmt::format_to(it, "- Findings: {}\n", md_escape(findings_by_kind_text(findings_)));
    }

    void write_json(const ReportContext& /*c*/, JsonWriter& w) const override {
        const GsdDevice& d = *g_.device;
        auto number = [&w](double v) {
            char text[64];
            auto end = fmt::format_to_n(text, sizeof text, "{:.3f}", v).out;
            w.number_text(std::string_view(text, static_cast<std::size_t>(end - text)));
        };
        w.begin_object();
        w.key("master").integer(c_.master);
        w.key("slave").integer(c_.slave);
        w.key("channel").string("gsd");
        w.key("file").string(d.file);
        w.key("vendor").string(d.vendor);
        w.key("model").string(d.model);
        w.key("ident").optional_integer(d.ident_number.has_value(), d.ident_number.value_or(0));
        w.key("modules").begin_array();
        for (const GsdModule* m : modules_)
            if (m)
                w.string(m->name);
            else
                w.null();
        w.end_array();
        w.key("response_us");
        histogram_json(w, g_.response_ns, g_.response_sum_ns, 1e3, number);
        w.key("max_tsdr_us");
        if (g_.max_tsdr_ns)
            number(to_us(g_.max_tsdr_ns));
        else
            w.null();
        w.key("poll_interval_ms");
        histogram_json(w, g_.poll_interval_ns, 0, 1e6, number);
        w.key("min_slave_interval_ms");
        if (g_.min_slave_interval_ns)
            number(to_ms(g_.min_slave_interval_ns));
        else
            w.null();
        w.key("checks").begin_object();
        for (FindingKind kind : kGsdKinds) {
            w.key(finding_kind_name(kind)).begin_object();
            w.key("judged").integer(static_cast<std::int64_t>(g_.judged_by(kind)));
            w.key("broken").integer(static_cast<std::int64_t>(g_.broken_by(kind)));
            w.end_object();
        }
        w.end_object();
        w.key("findings").begin_object();
        for (FindingKind kind : kGsdKinds)
            w.key(finding_kind_name(kind))
                .integer(static_cast<std::int64_t>(findings_[static_cast<std::size_t>(kind)]));
        w.end_object();
        w.end_object();
    }

    void write_html_row(const ReportContext& /*c*/, TextBuffer& b) const override {
        const std::array<std::uint64_t, 3> severities = severity_totals(findings_, by_severity_);
        const LogHistogram& h = g_.response_ns;
        fmt::format_to(std::back_inserter(b),
                       "<tr><td class=\"n\"><a href=\"#slave-{}-{}-gsd\">{}</a></td><td "
                       "class=\"n\">{}</td><td>GSD</td><td>{}</td><td class=\"n\">-</td><td "
                       "class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n error\">{}</td>"
                       "<td class=\"n warning\">{}</td><td class=\"n note\">{}</td></tr>\n",
                       c_.slave, c_.master, c_.slave, c_.master, xml(gsd_device_title(*g_.device)),
                       h.count() ? fmt::format("{:.1f} µs", to_us(h.percentile(50))) : "-",
                       h.count() ? fmt::format("{:.1f} µs", to_us(h.percentile(95))) : "-",
                       severities[2], severities[1], severities[0]);
    }

    void write_html(const ReportContext& /*c*/, TextBuffer& b) const override {
        fmt::format_to(std::back_inserter(b),
                       "<section class=\"station\" id=\"slave-{}-{}-gsd\">\n<h2>Slave {} (master "
                       "{}): GSD device description</h2>\n<table class=\"kv\">\n",
                       c_.slave, c_.master, c_.slave, c_.master);
        html_kv(b, "GSD", device_text());
        html_kv(b, "Modules", modules_text());
        html_kv(b, "Answer (µs)", answer_text());
        html_kv(b, "Poll interval (ms)", poll_text());
        html_kv(b, "Checks", checks_text());
        append(b, "</table>\n");
        html_findings_by_kind(b, findings_, by_severity_);
        append(b, "</section>\n");
    }

    std::string junit_suite_name() const override {
        return fmt::format("slave {} (master {}) GSD", c_.slave, c_.master);
    }
    std::string junit_classname() const override {
        return fmt::format("dpscope.master_{}.slave_{}.gsd", c_.master, c_.slave);
    }
    std::string junit_note(FindingKind kind) const override {
        if (finding_component(kind) != FindingComponent::DeviceDescription) return {};
        return fmt::format("checked against {}", g_.device->file);
    }

  private:
    template <class Number>
    static void histogram_json(JsonWriter& w, const LogHistogram& h, std::uint64_t sum,
                               double scale, Number& number) {
        if (h.count() == 0) {
            w.null();
            return;
        }
        w.begin_object();
        w.key("min");
        number(static_cast<double>(h.min()) / scale);
        if (sum) {
            w.key("mean");
            number(static_cast<double>(sum) / static_cast<double>(h.count()) / scale);
        }
        w.key("p95");
        number(static_cast<double>(h.percentile(95)) / scale);
        w.key("max");
        number(static_cast<double>(h.max()) / scale);
        w.end_object();
    }

    std::string device_text() const {
        const GsdDevice& d = *g_.device;
        return fmt::format(
            "{}: {}{}", d.file, gsd_device_title(d),
            d.ident_number ? fmt::format(", ident 0x{:04X}", *d.ident_number) : std::string());
    }
    std::string modules_text() const {
        if (modules_.empty()) return "no configuration seen";
        std::string text;
        for (const GsdModule* m : modules_) {
            if (!text.empty()) text += " + ";
            text += m ? fmt::format("\"{}\"", m->name) : std::string("no module of the GSD");
        }
        return text;
    }
    std::string answer_text() const {
        const LogHistogram& h = g_.response_ns;
        if (h.count() == 0) return "not measured (needs timestamps and the baud rate)";
        std::string text = fmt::format("min {:.1f}  mean {:.1f}  p95 {:.1f}  max {:.1f}",
                                       to_us(h.min()), to_us(g_.response_sum_ns / h.count()),
                                       to_us(h.percentile(95)), to_us(h.max()));
        if (g_.max_tsdr_ns)
            text += fmt::format(" (MaxTsdr {:.1f})", to_us(g_.max_tsdr_ns));
        else
            text += " (the GSD gives no MaxTsdr at this rate)";
        return text;
    }
    std::string poll_text() const {
        const LogHistogram& h = g_.poll_interval_ns;
        if (h.count() == 0) return "not measured";
        return fmt::format("min {:.3f}  p95 {:.3f}  max {:.3f} (Min_Slave_Intervall {:.1f})",
                           to_ms(h.min()), to_ms(h.percentile(95)), to_ms(h.max()),
                           to_ms(g_.min_slave_interval_ns));
    }
    // "gsd_ident_mismatch 3 ok, gsd_late_response 1 of 200 broken, ..." for the checks run.
    std::string checks_text() const {
        std::string text;
        for (FindingKind kind : kGsdKinds) {
            const std::uint64_t judged = g_.judged_by(kind);
            if (judged == 0) continue;
            const std::uint64_t broken = g_.broken_by(kind);
            if (!text.empty()) text += ", ";
            text += broken
                        ? fmt::format("{} {} of {} broken", finding_kind_name(kind), broken, judged)
                        : fmt::format("{} {} passed", finding_kind_name(kind), judged);
        }
        return text.empty() ? std::string("none run") : text;
    }

    const ChannelStats& c_;
    const GsdCheckStats& g_;
    std::vector<const GsdModule*> modules_;
    FindingCounts findings_{};
    const FindingSeverityCounts& by_severity_;
};

}  // namespace

std::unique_ptr<StationSection> make_gsd_section(const ChannelStats& stats,
                                                 std::vector<const GsdModule*> modules) {
    return std::make_unique<GsdSection>(stats, std::move(modules));
}

}  // namespace dpscope::report
