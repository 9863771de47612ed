// The report's section for the cyclic parameter channel (PCV) of a DP slave: PPO layout,
// dialect, transactions, latency, parameters accessed, rejections and findings by kind, in
// every format. And what a PROFIBUS DP report does and says as its own (profibus_bus_report()):
// a slave's cyclic and DP-V1 sections, the bus's kinds and wording.
#include <algorithm>
#include <iterator>

#include "formats/json.hpp"
#include "formats/parameter_names.hpp"
#include "formats/report_markup.hpp"
#include "formats/report_model.hpp"
#include "protocols/profibus/bus_decoder.hpp"
#include "protocols/profibus/gsd/gsd_report_section.hpp"
#include "protocols/profibus/session_tracker.hpp"

namespace dpscope::report {

namespace {

// The capture's tracker, a PROFIBUS one (profibus_tracked(): the report is PROFIBUS's only when
// it is).
const SessionTracker& profibus_tracker(const ReportContext& c) noexcept {
    return static_cast<const SessionTracker&>(*c.tracker);
}

// What the decoder knows of a slave's configuration (none without a PROFIBUS decoder).
const StationConfig& profibus_station(const ReportContext& c, std::uint8_t slave) noexcept {
    static const StationConfig kUnknown{};
    const auto* decoder = dynamic_cast<const BusDecoder*>(c.decoder);
    return decoder ? decoder->station(slave) : kUnknown;
}

// The PROFIBUS bus suite's and the cyclic channel's kinds: all but the DP-V1 parameter-access,
// the GSD, the FC protocol and the VLT 2000 ones.
bool is_dp_kind(FindingKind kind) noexcept {
    const FindingComponent component = finding_component(kind);
    return component != FindingComponent::Dpv1ParameterAccess &&
           component != FindingComponent::DeviceDescription &&
           component != FindingComponent::FcProtocol &&
           component != FindingComponent::Vlt2000Protocol;
}

struct Latency {
    bool any = false;
    double min_ms = 0, median_ms = 0, p95_ms = 0, max_ms = 0;
    std::uint64_t min_cycles = 0, median_cycles = 0, p95_cycles = 0, max_cycles = 0;
    bool any_cycles = false;
};

std::string ppo_text(const ChannelStats& s) {
    TextBuffer b;
    if (s.ppo.known())
        append_ppo_long(b, s.ppo);
    else
        append(b, "PPO unknown");
    return fmt::to_string(b);
}

std::string ppo_type_label(const PpoLayout& layout) {
    if (!layout.known()) return "unknown";
    TextBuffer b;
    append_ppo_short(b, layout);
    return fmt::to_string(b);
}

std::string outcomes_text(const TransactionCounts& t) {
    return fmt::format("{} positive, {} rejected, {} no authority, {} mismatched, {} unexpected",
                       t.positive, t.rejected, t.no_authority, t.mismatched, t.unexpected);
}

std::string parameters_text(const ChannelStats& s, StationNaming names) {
    std::string text;
    for (const auto& [pnu, count] : s.pnu_requests)
        text += fmt::format("{}{} ({}x)", text.empty() ? "" : ", ", pnu_label(names, pnu), count);
    return text.empty() ? "none" : text;
}

// {"min":..,"median":..,"p95":..,"max":..} with six decimals (or integers), or null.
void json_latency(JsonWriter& w, bool any, double min, double median, double p95, double max,
                  bool integers) {
    if (!any) {
        w.null();
        return;
    }
    auto value = [&](double v) {
        if (integers) {
            w.integer(static_cast<std::int64_t>(v));
        } else {
            char text[64];
            auto end = fmt::format_to_n(text, sizeof text, "{:.6f}", v).out;
            w.number_text(std::string_view(text, static_cast<std::size_t>(end - text)));
        }
    };
    w.begin_object();
    w.key("min");
    value(min);
    w.key("median");
    value(median);
    w.key("p95");
    value(p95);
    w.key("max");
    value(max);
    w.end_object();
}

class PcvSection final : public StationSection {
  public:
    PcvSection(const ReportContext& c, const ChannelStats& stats, const Timeline& timeline)
        : s_(stats), timeline_(timeline), by_severity_(stats.findings_by_severity) {
        for (FindingKind kind : kAllKinds)
            if (covers(kind))
                findings_[static_cast<std::size_t>(kind)] =
                    stats.findings[static_cast<std::size_t>(kind)];
        names_ = station_naming(c.naming, stats.slave);
        const StationConfig& config = profibus_station(c, stats.slave);
        has_ident_ = config.has_ident;
        ident_ = config.ident;
        timed_ = stats.first_time_ns != kNoTime;
        channel_ = stats.ppo.has_pcv || stats.parameter_telegrams > 0;
        dialect_hint_ =
            dialect_hint_text(stats.slave, stats.dialect, c.summary->dialect_evidence(stats.slave));
        const LogHistogram& ns = stats.latency_ns;
        if (ns.count() > 0) {
            latency_.any = true;
            latency_.min_ms = to_ms(ns.min());
            latency_.median_ms = to_ms(ns.percentile(50));
            latency_.p95_ms = to_ms(ns.percentile(95));
            latency_.max_ms = to_ms(ns.max());
        }
        const LogHistogram& cycles = stats.latency_cycles;
        if (cycles.count() > 0) {
            latency_.any_cycles = true;
            latency_.min_cycles = cycles.min();
            latency_.median_cycles = cycles.percentile(50);
            latency_.p95_cycles = cycles.percentile(95);
            latency_.max_cycles = cycles.max();
        }
    }

    std::uint8_t master() const override { return s_.master; }
    std::uint8_t slave() const override { return s_.slave; }
    bool checked() const override { return s_.parameter_telegrams > 0; }
    std::uint64_t transactions() const override { return s_.transactions.total(); }
    const FindingCounts& findings() const override { return findings_; }
    bool covers(FindingKind kind) const override { return is_dp_kind(kind); }

    void write_text(const ReportContext& /*c*/, TextBuffer& b) const override {
        const ChannelStats& s = s_;
        const Latency& l = latency_;
        auto it = std::back_inserter(b);
        fmt::format_to(it, "\nSlave {} (master {})\n", s.slave, s.master);
        fmt::format_to(it, "  layout         {}; {}", ppo_text(s),
                       channel_ ? fmt::format("dialect {}", dialect_name(s.dialect))
                                : std::string("no parameter channel"));
        if (has_ident_) fmt::format_to(it, "; ident 0x{:04X}", ident_);
        b.push_back('\n');
        if (!dialect_hint_.empty()) fmt::format_to(it, "  dialect hint   {}\n", dialect_hint_);
        fmt::format_to(it, "  Data_Exchange  {}, {}\n",
                       counted(s.data_exchange, "telegram", "telegrams"),
                       counted(s.cycles, "cycle", "cycles"));
        fmt::format_to(it, "  requests       {}\n", s.requests);
        fmt::format_to(it, "  transactions   {}: {}\n", s.transactions.total(),
                       outcomes_text(s.transactions));
        fmt::format_to(it, "  unanswered     {}, {} abandoned by the master\n", timeouts_text(),
                       s.abandoned);
        fmt::format_to(it, "  spontaneous    {}\n", counted(s.spontaneous, "message", "messages"));
        if (!timed_)
            append(b, "  latency ms     not measured (no timestamps)\n");
        else if (l.any)
            fmt::format_to(it,
                           "  latency ms     min {:.3f}  median {:.3f}  p95 {:.3f}  max {:.3f}\n",
                           l.min_ms, l.median_ms, l.p95_ms, l.max_ms);
        if (l.any_cycles)
            fmt::format_to(it, "  latency cycles min {}  median {}  p95 {}  max {}\n", l.min_cycles,
                           l.median_cycles, l.p95_cycles, l.max_cycles);
        fmt::format_to(it, "  parameters     {}\n", parameters_text(s, names_));
        if (!s.rejections.empty()) {
            append(b, "  rejections    ");
            const char* separator = " ";
            for (const auto& [key, count] : s.rejections) {
                fmt::format_to(it, "{}PNU {} error {} ({}) {}x", separator,
                               pnu_label(names_, key.first), key.second,
                               error_text_or_unknown(s.dialect, key.second), count);
                separator = "; ";
            }
            b.push_back('\n');
        }
        fmt::format_to(it, "  findings       {}\n", findings_by_kind_text(findings_));
    }

    void write_markdown_row(const ReportContext& /*c*/, TextBuffer& b) const override {
        const ChannelStats& s = s_;
        const Latency& l = latency_;
        std::string ms = !timed_ ? "no timestamps"
                         : l.any ? fmt::format("{:.3f} / {:.3f} / {:.3f} / {:.3f}", l.min_ms,
                                               l.median_ms, l.p95_ms, l.max_ms)
                                 : "-";
        std::string cycles = l.any_cycles ? fmt::format("{} / {} / {} / {}", l.min_cycles,
                                                        l.median_cycles, l.p95_cycles, l.max_cycles)
                                          : "-";
        fmt::format_to(std::back_inserter(b),
                       "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", s.slave, s.master,
                       md_escape(ppo_type_label(s.ppo)), channel_ ? dialect_name(s.dialect) : "-",
                       s.transactions.total(), s.transactions.rejected,
                       timed_ ? fmt::format("{}", s.timeouts) : "not judged", ms, cycles,
                       md_escape(findings_by_kind_text(findings_)));
    }

    void write_markdown(const ReportContext& /*c*/, TextBuffer& b) const override {
        const ChannelStats& s = s_;
        auto it = std::back_inserter(b);
        fmt::format_to(it, "\n### Slave {} (master {})\n\n", s.slave, s.master);
        fmt::format_to(it, "- Layout: {}\n", md_escape(ppo_text(s)));
        if (has_ident_) fmt::format_to(it, "- Ident number: 0x{:04X}\n", ident_);
        if (!dialect_hint_.empty())
            fmt::format_to(it, "- Dialect hint: {}\n", md_escape(dialect_hint_));
        fmt::format_to(
            it, "- Data_Exchange: {}, {}; {}\n", counted(s.data_exchange, "telegram", "telegrams"),
            counted(s.cycles, "cycle", "cycles"), counted(s.requests, "request", "requests"));
        fmt::format_to(it, "- Transactions: {} ({})\n", s.transactions.total(),
                       outcomes_text(s.transactions));
        fmt::format_to(it, "- Unanswered: {}, {} abandoned; spontaneous messages: {}\n",
                       timeouts_text(), s.abandoned, s.spontaneous);
        fmt::format_to(it, "- Parameters: {}\n", parameters_text(s, names_));
        for (const auto& [key, count] : s.rejections) {
            fmt::format_to(it, "- Rejected: PNU {} error {} ({}), {}x\n",
                           pnu_label(names_, key.first), key.second,
                           md_escape(error_text_or_unknown(s.dialect, key.second)), count);
        }
        fmt::format_to(it, "- Findings: {}\n", md_escape(findings_by_kind_text(findings_)));
    }

    void write_json(const ReportContext& c, JsonWriter& w) const override {
        const ChannelStats& s = s_;
        const Latency& l = latency_;
        auto count = [&w](std::string_view key, std::uint64_t n) {
            w.key(key).integer(static_cast<std::int64_t>(n));
        };
        w.begin_object();
        w.key("master").integer(s.master);
        w.key("slave").integer(s.slave);
        w.key("ppo_type").optional_integer(s.ppo.known() && s.ppo.type != 0, s.ppo.type);
        w.key("ppo_source").string(ppo_source_name(s.ppo.source));
        w.key("dialect");
        if (channel_)
            w.string(dialect_name(s.dialect));
        else
            w.null();
        w.key("dialect_hint");
        if (std::optional<Dialect> hint = c.summary->dialect_evidence(s.slave).hint())
            w.string(dialect_name(*hint));
        else
            w.null();
        w.key("ident").optional_integer(has_ident_, ident_);
        count("data_exchange", s.data_exchange);
        count("cycles", s.cycles);
        count("requests", s.requests);
        count("transactions", s.transactions.total());
        w.key("outcomes").begin_object();
        count("positive", s.transactions.positive);
        count("rejected", s.transactions.rejected);
        count("no_authority", s.transactions.no_authority);
        count("mismatched", s.transactions.mismatched);
        count("unexpected", s.transactions.unexpected);
        w.end_object();
        w.key("timeouts").optional_integer(timed_, static_cast<std::int64_t>(s.timeouts));
        count("abandoned", s.abandoned);
        count("spontaneous", s.spontaneous);
        w.key("latency_ms");
        json_latency(w, l.any, l.min_ms, l.median_ms, l.p95_ms, l.max_ms, false);
        w.key("latency_cycles");
        json_latency(w, l.any_cycles, static_cast<double>(l.min_cycles),
                     static_cast<double>(l.median_cycles), static_cast<double>(l.p95_cycles),
                     static_cast<double>(l.max_cycles), true);
        w.key("parameters").begin_array();
        for (const auto& [pnu, n] : s.pnu_requests) {
            w.begin_object();
            w.key("pnu").integer(pnu);
            pnu_name_key(w, names_, pnu);
            count("requests", n);
            w.end_object();
        }
        w.end_array();
        w.key("rejections").begin_array();
        for (const auto& [key, n] : s.rejections) {
            w.begin_object();
            w.key("pnu").integer(key.first);
            pnu_name_key(w, names_, key.first);
            w.key("error").integer(key.second);
            w.key("error_text").string(error_text_or_unknown(s.dialect, key.second));
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
        const ChannelStats& s = s_;
        const Latency& l = latency_;
        const std::array<std::uint64_t, 3> severities = severity_totals(findings_, by_severity_);
        fmt::format_to(std::back_inserter(b),
                       "<tr><td class=\"n\"><a href=\"#slave-{}-{}\">{}</a></td><td class=\"n\">{}"
                       "</td><td>{}</td><td>{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td>"
                       "<td class=\"n\">{}</td><td class=\"n error\">{}</td><td class=\"n "
                       "warning\">{}</td><td class=\"n note\">{}</td></tr>\n",
                       s.slave, s.master, s.slave, s.master, xml(ppo_type_label(s.ppo)),
                       channel_ ? dialect_name(s.dialect) : "-", s.transactions.total(),
                       l.any ? fmt::format("{:.3f}", l.median_ms) : "-",
                       l.any ? fmt::format("{:.3f}", l.p95_ms) : "-", severities[2], severities[1],
                       severities[0]);
    }

    void write_html(const ReportContext& c, TextBuffer& b) const override {
        const ChannelStats& s = s_;
        const Latency& l = latency_;
        auto it = std::back_inserter(b);
        fmt::format_to(it,
                       "<section class=\"station\" id=\"slave-{}-{}\">\n<h2>Slave {} (master {})"
                       "</h2>\n<table class=\"kv\">\n",
                       s.slave, s.master, s.slave, s.master);
        html_kv(b, "Layout", ppo_text(s));
        html_kv(b, "Dialect", channel_ ? dialect_name(s.dialect) : "none (no parameter channel)");
        if (!dialect_hint_.empty()) html_kv(b, "Dialect hint", dialect_hint_);
        if (has_ident_) html_kv(b, "Ident number", fmt::format("0x{:04X}", ident_));
        html_kv(b, "Data_Exchange",
                fmt::format("{}, {}", counted(s.data_exchange, "telegram", "telegrams"),
                            counted(s.cycles, "cycle", "cycles")));
        html_kv(b, "Parameter requests", fmt::format("{}", s.requests));
        html_kv(b, "Transactions",
                fmt::format("{}: {}", s.transactions.total(), outcomes_text(s.transactions)));
        html_kv(b, "Unanswered",
                fmt::format("{}, {} abandoned by the master", timeouts_text(), s.abandoned));
        html_kv(b, "Spontaneous messages", fmt::format("{}", s.spontaneous));
        html_kv(b, "Latency (ms)",
                !timed_ ? std::string("not measured (no timestamps)")
                : l.any ? fmt::format("min {:.3f}, median {:.3f}, p95 {:.3f}, max {:.3f}", l.min_ms,
                                      l.median_ms, l.p95_ms, l.max_ms)
                        : "-");
        html_kv(b, "Latency (cycles)",
                l.any_cycles ? fmt::format("min {}, median {}, p95 {}, max {}", l.min_cycles,
                                           l.median_cycles, l.p95_cycles, l.max_cycles)
                             : "-");
        append(b, "</table>\n<h3>Latency histogram</h3>\n");
        svg_latency_histogram(b, s.latency_ns, s.transactions.total() > 0,
                              fmt::format("slave {}", s.slave));
        append(b,
               "<h3>Timeline</h3>\n<div class=\"legend\"><span><i class=\"swatch\" "
               "style=\"background:#4e79c5\"></i>transactions</span><span><i class=\"swatch\" "
               "style=\"background:#d92d20\"></i>errors</span><span><i class=\"swatch\" "
               "style=\"background:#f79009\"></i>warnings</span><span><i class=\"swatch\" "
               "style=\"background:#2e90fa\"></i>notes</span></div>\n");
        svg_timeline(b, timeline_, fmt::format("slave {}", s.slave), c);
        append(b, "<h3>Parameters accessed</h3>\n");
        if (s.pnu_requests.empty()) {
            append(b, "<p class=\"meta\">None.</p>\n");
        } else {
            append(b,
                   "<table class=\"parameters\"><tr><th class=\"n\">PNU</th><th "
                   "class=\"n\">requests</th></tr>\n");
            for (const auto& [pnu, count] : s.pnu_requests)
                fmt::format_to(it, "<tr><td class=\"n\">{}</td><td class=\"n\">{}</td></tr>\n",
                               xml(pnu_label(names_, pnu)), count);
            append(b, "</table>\n");
        }
        if (!s.rejections.empty()) {
            append(b,
                   "<h3>Rejected requests</h3>\n<table class=\"rejections\"><tr><th "
                   "class=\"n\">PNU</th><th class=\"n\">error</th><th>meaning</th><th "
                   "class=\"n\">count</th></tr>\n");
            for (const auto& [key, count] : s.rejections) {
                std::string_view text = error_text_or_unknown(s.dialect, key.second);
                fmt::format_to(it,
                               "<tr><td class=\"n\">{}</td><td class=\"n\">{}</td><td>{}</td>"
                               "<td class=\"n\">{}</td></tr>\n",
                               xml(pnu_label(names_, key.first)), key.second, xml(text), count);
            }
            append(b, "</table>\n");
        }
        html_findings_by_kind(b, findings_, by_severity_);
        append(b, "</section>\n");
    }

    std::string junit_suite_name() const override {
        return fmt::format("slave {} (master {})", s_.slave, s_.master);
    }
    std::string junit_classname() const override {
        return fmt::format("dpscope.master_{}.slave_{}", s_.master, s_.slave);
    }
    std::string junit_note(FindingKind kind) const override {
        if (kind != FindingKind::UnknownCode || dialect_hint_.empty()) return {};
        return "dialect hint: " + dialect_hint_;
    }

  private:
    // "2 timed out" or "time-outs not judged (no timestamps)".
    std::string timeouts_text() const {
        return timed_ ? fmt::format("{} timed out", s_.timeouts) : std::string(kNoTimestamps);
    }

    const ChannelStats& s_;
    StationNaming names_;  // what names its PNUs (issue 29)
    const Timeline& timeline_;
    FindingCounts findings_{};  // the kinds the section covers
    const FindingSeverityCounts& by_severity_;
    bool has_ident_ = false;
    std::uint16_t ident_ = 0;
    bool timed_ = false;  // its telegrams carry timestamps: time-outs and ms latency judged
    // Its layout has a parameter channel (or a telegram carried one): only then is there a
    // dialect (the channel's code tables) to name.
    bool channel_ = false;
    std::string dialect_hint_;  // "" or the hint that its codes fit another dialect
    Latency latency_;
};

// The cyclic and DP-V1 sections of the PROFIBUS DP slaves.
void add_profibus_sections(const ReportContext& c, const ChannelTimelines& timelines,
                           ReportModel& m) {
    for (const ChannelStats* stats : profibus_tracker(c).channels()) {
        if (!shows_slave(c, stats->slave)) continue;
        bool dp_findings = false, dpv1_findings = false;
        for (FindingKind kind : kAllKinds)
            if (stats->findings[static_cast<std::size_t>(kind)] > 0) {
                if (is_dp_kind(kind))
                    dp_findings = true;
                else if (finding_component(kind) == FindingComponent::Dpv1ParameterAccess)
                    dpv1_findings = true;
            }
        const bool dpv1 = stats->dpv1.telegrams > 0 || dpv1_findings;
        // The cyclic channel's section, unless the slave only talked DP-V1.
        if (!dpv1 || stats->data_exchange > 0 || stats->parameter_telegrams > 0 || dp_findings)
            m.stations.push_back(
                std::make_unique<PcvSection>(c, *stats, timelines.of(stats->master, stats->slave)));
        if (dpv1)
            m.stations.push_back(
                make_dpv1_section(*stats, station_naming(c.naming, stats->slave)));
        // The slave against its GSD file, when it has one (--gsd).
        if (stats->gsd && stats->gsd->device)
            m.stations.push_back(
                make_gsd_section(*stats, profibus_station(c, stats->slave).gsd_modules));
        ++m.slaves;
    }
}

bool profibus_tracked(const ReportContext& c) noexcept {
    return dynamic_cast<const SessionTracker*>(c.tracker) != nullptr;
}

const BusStats& profibus_bus_stats(const ReportContext& c) { return profibus_tracker(c).bus(); }

// The writers word PROFIBUS DP's checks themselves (checks_rc8_rule); this is their time-out.
std::string profibus_checks_text(const ReportContext& c, const ReportModel& m) {
    return timeout_rule_text(c, m);
}

std::string_view profibus_nothing_checked_reason(const ReportContext& c) {
    return c.stations.empty()
               ? "no Data_Exchange telegram with a parameter channel"
               : "no Data_Exchange telegram with a parameter channel from the selected slaves";
}

}  // namespace

const BusReport& profibus_bus_report() noexcept {
    static const BusReport report{
        .protocol = Protocol::ProfibusDp,
        .wording =
            {
                .name = "",
                .option = "",
                .checksum_kind = FindingKind::FcsError,
                .checksum_label = "FCS errors",
                .checksum_key = "fcs_errors",
                .station = "slave",
                .stations = "slaves",
                .markdown_table =
                    "## Slaves\n\n| slave | master | PPO | dialect | transactions | rejected | "
                    "time-outs | latency ms (min / median / p95 / max) | latency cycles | "
                    "findings |\n"
                    "|---:|---:|---|---|---:|---:|---:|---|---|---|\n",
                .html_table =
                    "<tr><th class=\"n\">slave</th><th class=\"n\">master</th><th>PPO</th>"
                    "<th>dialect</th><th class=\"n\">transactions</th><th class=\"n\">median "
                    "ms</th><th class=\"n\">p95 ms</th><th class=\"n\">errors</th><th "
                    "class=\"n\">warnings</th><th class=\"n\">notes</th></tr>\n",
                .nothing_checked_case =
                    "parameter channel: the capture holds Data_Exchange telegrams with a "
                    "parameter channel",
            },
        .tracked = profibus_tracked,
        .add_sections = add_profibus_sections,
        .is_bus_kind = is_dp_kind,
        .bus_stats = profibus_bus_stats,
        .checks_text = profibus_checks_text,
        .nothing_checked_reason = profibus_nothing_checked_reason,
        .write_json_options = nullptr,
        .checks_rc8_rule = true,
    };
    return report;
}

}  // namespace dpscope::report
