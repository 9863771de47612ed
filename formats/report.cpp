#include "formats/report.hpp"

#include <algorithm>
#include <iterator>

#include "formats/describe.hpp"
#include "formats/json.hpp"

namespace dpscope {

std::string_view report_format_name(ReportFormat format) {
    switch (format) {
        case ReportFormat::Text: return "text";
        case ReportFormat::Json: return "json";
        case ReportFormat::Markdown: return "markdown";
        case ReportFormat::Html: return "html";
        case ReportFormat::Junit: return "junit";
    }
    return "text";
}

std::optional<ReportFormat> report_format_from_name(std::string_view name) {
    for (ReportFormat format : {ReportFormat::Text, ReportFormat::Json, ReportFormat::Markdown,
                                ReportFormat::Html, ReportFormat::Junit})
        if (report_format_name(format) == name) return format;
    return std::nullopt;
}

std::string_view fail_on_name(FailOn fail_on) {
    switch (fail_on) {
        case FailOn::Error: return "error";
        case FailOn::Warning: return "warning";
        case FailOn::Never: return "never";
    }
    return "error";
}

std::optional<FailOn> fail_on_from_name(std::string_view name) {
    for (FailOn f : {FailOn::Error, FailOn::Warning, FailOn::Never})
        if (fail_on_name(f) == name) return f;
    return std::nullopt;
}

bool severity_fails(Severity severity, FailOn fail_on) noexcept {
    switch (fail_on) {
        case FailOn::Error: return severity == Severity::Error;
        case FailOn::Warning: return severity != Severity::Note;
        case FailOn::Never: return false;
    }
    return false;
}

namespace {

constexpr std::size_t kHtmlFindingRows = 2000;
// The text and Markdown reports list at most this many findings of each kind.
constexpr std::uint64_t kListedPerKind = 1000;
// A JUnit test case lists at most this many failures; the rest are counted in <system-out>.
constexpr std::size_t kJunitFailuresPerCase = 10'000;
constexpr std::array<FindingKind, kFindingKindCount> all_kinds() {
    std::array<FindingKind, kFindingKindCount> kinds{};
    for (std::size_t i = 0; i < kFindingKindCount; ++i)
        kinds[i] = static_cast<FindingKind>(i);
    return kinds;
}
constexpr auto kAllKinds = all_kinds();

struct Latency {
    bool any = false;
    double min_ms = 0, median_ms = 0, p95_ms = 0, max_ms = 0;
    std::uint64_t min_cycles = 0, median_cycles = 0, p95_cycles = 0, max_cycles = 0;
    bool any_cycles = false;
};

struct StationView {
    const ChannelStats* stats = nullptr;
    bool has_ident = false;
    std::uint16_t ident = 0;
    bool timed = false;        // its telegrams carry timestamps: time-outs and ms latency judged
    std::string dialect_hint;  // "" or the hint that its codes fit another dialect
    Latency latency;
};

struct Model {
    std::vector<StationView> stations;
    std::array<std::uint64_t, 3> by_severity{};
    std::uint64_t fcs_errors = 0;  // fcs_error findings shown (every bad FCS is one)
    std::uint64_t shown = 0;
    bool fails = false;
    bool has_bus_findings = false;
    bool timed = false;            // the capture carries timestamps (or is empty)
    bool nothing_checked = false;  // no Data_Exchange telegram with a parameter channel shown
};

bool shows(const ReportContext& c, const Finding& f) {
    if (c.stations.empty() || !f.has_stations) return true;
    return std::find(c.stations.begin(), c.stations.end(), f.slave) != c.stations.end();
}

double to_ms(std::uint64_t ns) { return static_cast<double>(ns) / 1e6; }

Model build_model(const ReportContext& c) {
    Model m;
    for (const ChannelStats* stats : c.tracker->channels()) {
        if (!c.stations.empty() &&
            std::find(c.stations.begin(), c.stations.end(), stats->slave) == c.stations.end())
            continue;
        StationView view;
        view.stats = stats;
        const StationConfig& config = c.decoder->station(stats->slave);
        view.has_ident = config.has_ident;
        view.ident = config.ident;
        view.timed = stats->first_time_ns != kNoTime;
        view.dialect_hint = dialect_hint_text(stats->slave, stats->dialect,
                                              c.summary->dialect_evidence(stats->slave));
        const LogHistogram& ns = stats->latency_ns;
        if (ns.count() > 0) {
            view.latency.any = true;
            view.latency.min_ms = to_ms(ns.min());
            view.latency.median_ms = to_ms(ns.percentile(50));
            view.latency.p95_ms = to_ms(ns.percentile(95));
            view.latency.max_ms = to_ms(ns.max());
        }
        const LogHistogram& cycles = stats->latency_cycles;
        if (cycles.count() > 0) {
            view.latency.any_cycles = true;
            view.latency.min_cycles = cycles.min();
            view.latency.median_cycles = cycles.percentile(50);
            view.latency.p95_cycles = cycles.percentile(95);
            view.latency.max_cycles = cycles.max();
        }
        m.stations.push_back(view);
    }
    m.timed = c.summary->first_time_ns() != kNoTime || c.summary->telegrams() == 0;
    m.nothing_checked =
        std::none_of(m.stations.begin(), m.stations.end(),
                     [](const StationView& v) { return v.stats->parameter_telegrams > 0; });
    if (m.nothing_checked && !c.allow_empty) m.fails = true;
    c.findings->for_each([&](const Finding& f) {
        if (!shows(c, f)) return;
        ++m.shown;
        ++m.by_severity[static_cast<std::size_t>(f.severity)];
        if (f.kind == FindingKind::FcsError) ++m.fcs_errors;
        if (severity_fails(f.severity, c.fail_on)) m.fails = true;
        if (!f.has_stations) m.has_bus_findings = true;
    });
    return m;
}

std::uint64_t errors(const Model& m) {
    return m.by_severity[static_cast<std::size_t>(Severity::Error)];
}
std::uint64_t warnings(const Model& m) {
    return m.by_severity[static_cast<std::size_t>(Severity::Warning)];
}
std::uint64_t notes(const Model& m) {
    return m.by_severity[static_cast<std::size_t>(Severity::Note)];
}

std::string findings_text(const Model& m) {
    return fmt::format("{}, {}, {}", counted(errors(m), "error", "errors"),
                       counted(warnings(m), "warning", "warnings"),
                       counted(notes(m), "note", "notes"));
}

// Why nothing was checked: "no telegrams", "no Data_Exchange telegram with a parameter channel".
std::string nothing_checked_reason(const ReportContext& c) {
    if (c.summary->telegrams() == 0) return "no telegrams";
    return c.stations.empty()
               ? "no Data_Exchange telegram with a parameter channel"
               : "no Data_Exchange telegram with a parameter channel from the selected slaves";
}

std::string verdict_text(const ReportContext& c, const Model& m) {
    return fmt::format("{}: {}{} (fail on {}{})", m.fails ? "FAIL" : "PASS",
                       m.nothing_checked
                           ? fmt::format("nothing checked ({}); ", nothing_checked_reason(c))
                           : std::string(),
                       findings_text(m), fail_on_name(c.fail_on),
                       m.nothing_checked && c.allow_empty ? ", empty allowed" : "");
}

constexpr std::string_view kNoTimestamps = "time-outs not judged (no timestamps)";

// "2 timed out" or "time-outs not judged (no timestamps)".
std::string timeouts_text(const StationView& v) {
    return v.timed ? fmt::format("{} timed out", v.stats->timeouts) : std::string(kNoTimestamps);
}

// "" without a station filter, else "slaves 3, 5".
std::string filter_text(const ReportContext& c) {
    std::string text;
    for (std::uint8_t station : c.stations)
        text += fmt::format("{}{}", text.empty() ? "slaves " : ", ", station);
    return text;
}

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

std::string relative_seconds(const ReportContext& c, std::int64_t time_ns) {
    std::int64_t first = c.summary->first_time_ns();
    if (time_ns == kNoTime || first == kNoTime) return "-";
    return relative_seconds_text(time_ns - first);
}

std::string outcomes_text(const TransactionCounts& t) {
    return fmt::format("{} positive, {} rejected, {} no authority, {} mismatched, {} unexpected",
                       t.positive, t.rejected, t.no_authority, t.mismatched, t.unexpected);
}

std::string parameters_text(const ChannelStats& s) {
    std::string text;
    for (const auto& [pnu, count] : s.pnu_requests)
        text += fmt::format("{}{} ({}x)", text.empty() ? "" : ", ", pnu, count);
    return text.empty() ? "none" : text;
}

std::string findings_by_kind_text(const std::array<std::uint64_t, kFindingKindCount>& counts) {
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

// "1200 more stacked_request findings not listed: at most 1000 per kind, the JSON report lists
// them all", for the kinds the text and Markdown reports cut short.
std::string unlisted_text(FindingKind kind,
                          const std::array<std::uint64_t, kFindingKindCount>& listed) {
    std::uint64_t more = listed[static_cast<std::size_t>(kind)] - kListedPerKind;
    return fmt::format(
        "{} more {} {} not listed: at most {} per kind, the JSON report lists them all", more,
        finding_kind_name(kind), more == 1 ? "finding" : "findings", kListedPerKind);
}

// ---- text ---------------------------------------------------------------------------------------

void render_text(const ReportContext& c, const Model& m, Output& out) {
    TextBuffer& b = out.buffer();
    auto it = std::back_inserter(b);
    const TrackerOptions& options = c.tracker->options();
    fmt::format_to(it, "dpscope {} conformance report\n", c.version);
    fmt::format_to(it, "Input:   {} ({}), {}", c.input.name, c.input.format,
                   counted(c.summary->telegrams(), "telegram", "telegrams"));
    if (c.summary->first_time_ns() != kNoTime) {
        append(b, ", ");
        append_iso_time(b, c.summary->first_time_ns());
        append(b, " to ");
        append_iso_time(b, c.summary->last_time_ns());
    }
    b.push_back('\n');
    if (c.input.damaged)
        append(b, "         the input ended in damage; the report covers what was read\n");
    fmt::format_to(it, "Checks:  {}; RC 8 after a read is {}\n",
                   m.timed ? fmt::format("time-out {} ms", options.timeout_ns / 1'000'000)
                           : std::string(kNoTimestamps),
                   options.strict ? "an unexpected response (strict)" : "unusual, a warning");
    if (!c.stations.empty())
        fmt::format_to(it, "Filter:  {} (telegram counts cover the whole capture)\n",
                       filter_text(c));
    fmt::format_to(it, "Result:  {}\n\n", verdict_text(c, m));
    append(b, "Summary\n");
    fmt::format_to(it, "  telegrams      {}\n", c.summary->telegrams());
    fmt::format_to(it, "  bytes skipped  {}\n", c.input.bytes_skipped);
    fmt::format_to(it, "  FCS errors     {}\n", m.fcs_errors);
    std::uint64_t transactions = 0;
    for (const StationView& v : m.stations)
        transactions += v.stats->transactions.total();
    fmt::format_to(it, "  transactions   {}\n", transactions);
    fmt::format_to(it, "  findings       {}\n", findings_text(m));
    for (const StationView& v : m.stations) {
        const ChannelStats& s = *v.stats;
        fmt::format_to(it, "\nSlave {} (master {})\n", s.slave, s.master);
        fmt::format_to(it, "  layout         {}; dialect {}", ppo_text(s), dialect_name(s.dialect));
        if (v.has_ident) fmt::format_to(it, "; ident 0x{:04X}", v.ident);
        b.push_back('\n');
        if (!v.dialect_hint.empty()) fmt::format_to(it, "  dialect hint   {}\n", v.dialect_hint);
        fmt::format_to(it, "  Data_Exchange  {}, {}\n",
                       counted(s.data_exchange, "telegram", "telegrams"),
                       counted(s.cycles, "cycle", "cycles"));
        fmt::format_to(it, "  requests       {}\n", s.requests);
        fmt::format_to(it, "  transactions   {}: {}\n", s.transactions.total(),
                       outcomes_text(s.transactions));
        fmt::format_to(it, "  unanswered     {}, {} abandoned by the master\n", timeouts_text(v),
                       s.abandoned);
        fmt::format_to(it, "  spontaneous    {}\n", counted(s.spontaneous, "message", "messages"));
        if (!v.timed)
            append(b, "  latency ms     not measured (no timestamps)\n");
        else if (v.latency.any)
            fmt::format_to(
                it, "  latency ms     min {:.3f}  median {:.3f}  p95 {:.3f}  max {:.3f}\n",
                v.latency.min_ms, v.latency.median_ms, v.latency.p95_ms, v.latency.max_ms);
        if (v.latency.any_cycles)
            fmt::format_to(it, "  latency cycles min {}  median {}  p95 {}  max {}\n",
                           v.latency.min_cycles, v.latency.median_cycles, v.latency.p95_cycles,
                           v.latency.max_cycles);
        fmt::format_to(it, "  parameters     {}\n", parameters_text(s));
        if (!s.rejections.empty()) {
            append(b, "  rejections    ");
            for (const auto& [key, count] : s.rejections) {
                std::string_view text = error_text(s.dialect, key.second);
                fmt::format_to(it, " PNU {} error {} ({}) {}x;", key.first, key.second,
                               text.empty() ? "unknown" : text, count);
            }
            b.push_back('\n');
        }
        fmt::format_to(it, "  findings       {}\n", findings_by_kind_text(s.findings));
    }
    if (m.has_bus_findings)
        fmt::format_to(it, "\nBus (telegrams no station can be named for)\n  findings       {}\n",
                       findings_by_kind_text(c.tracker->bus().findings));
    fmt::format_to(it, "\nFindings ({}, in capture order)\n", m.shown);
    if (m.shown > 0)
        fmt::format_to(it, "  {:>8}  {:>12}  {:<8} {:<27} {:<9} {:>5}  {}\n", "frame", "time (s)",
                       "severity", "kind", "master/slave", "pnu", "message");
    std::array<std::uint64_t, kFindingKindCount> listed{};
    c.findings->for_each([&](const Finding& f) {
        if (!shows(c, f) || listed[static_cast<std::size_t>(f.kind)]++ >= kListedPerKind) return;
        fmt::format_to(it, "  {:>8}  {:>12}  {:<8} {:<27} {:<12} {:>5}  {}\n", f.frame,
                       relative_seconds(c, f.time_ns), severity_name(f.severity),
                       finding_kind_name(f.kind), station_label(f),
                       f.pnu ? fmt::format("{}", *f.pnu) : std::string("-"), f.message);
        out.end_record();
    });
    for (FindingKind kind : kAllKinds)
        if (listed[static_cast<std::size_t>(kind)] > kListedPerKind)
            fmt::format_to(it, "  ({})\n", unlisted_text(kind, listed));
    if (!c.findings->error().empty())
        fmt::format_to(it, "  (some findings could not be listed: {})\n", c.findings->error());
    out.end_record();
}

// ---- markdown -----------------------------------------------------------------------------------

std::string md_escape(std::string_view text) {
    std::string out;
    for (char ch : text) {
        if (ch == '\\' || ch == '|' || ch == '*' || ch == '_' || ch == '`' || ch == '<' ||
            ch == '>')
            out += '\\';
        out += ch;
    }
    return out;
}

void render_markdown(const ReportContext& c, const Model& m, Output& out) {
    TextBuffer& b = out.buffer();
    auto it = std::back_inserter(b);
    const TrackerOptions& options = c.tracker->options();
    fmt::format_to(it, "# dpscope conformance report\n\n");
    fmt::format_to(it, "**{}**\n\n", verdict_text(c, m));
    fmt::format_to(it, "- Input: `{}` ({}), {}{}\n", c.input.name, c.input.format,
                   counted(c.summary->telegrams(), "telegram", "telegrams"),
                   c.input.damaged ? " (ended in damage)" : "");
    fmt::format_to(it, "- Checks: {}; RC 8 after a read: {}\n",
                   m.timed ? fmt::format("time-out {} ms", options.timeout_ns / 1'000'000)
                           : std::string(kNoTimestamps),
                   options.strict ? "strict" : "lenient");
    if (!c.stations.empty())
        fmt::format_to(it, "- Filter: {} (telegram counts cover the whole capture)\n",
                       filter_text(c));
    fmt::format_to(it, "- dpscope {}\n\n", c.version);
    std::uint64_t transactions = 0;
    for (const StationView& v : m.stations)
        transactions += v.stats->transactions.total();
    append(b,
           "## Summary\n\n| telegrams | bytes skipped | FCS errors | transactions | errors | "
           "warnings | notes |\n"
           "|---:|---:|---:|---:|---:|---:|---:|\n");
    fmt::format_to(it, "| {} | {} | {} | {} | {} | {} | {} |\n\n", c.summary->telegrams(),
                   c.input.bytes_skipped, m.fcs_errors, transactions, errors(m), warnings(m),
                   notes(m));
    append(b,
           "## Slaves\n\n| slave | master | PPO | dialect | transactions | rejected | "
           "time-outs | latency ms (min / median / p95 / max) | latency cycles | findings |\n"
           "|---:|---:|---|---|---:|---:|---:|---|---|---|\n");
    for (const StationView& v : m.stations) {
        const ChannelStats& s = *v.stats;
        std::string ms = !v.timed ? "no timestamps"
                         : v.latency.any
                             ? fmt::format("{:.3f} / {:.3f} / {:.3f} / {:.3f}", v.latency.min_ms,
                                           v.latency.median_ms, v.latency.p95_ms, v.latency.max_ms)
                             : "-";
        std::string cycles =
            v.latency.any_cycles
                ? fmt::format("{} / {} / {} / {}", v.latency.min_cycles, v.latency.median_cycles,
                              v.latency.p95_cycles, v.latency.max_cycles)
                : "-";
        fmt::format_to(it, "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", s.slave,
                       s.master, md_escape(ppo_type_label(s.ppo)), dialect_name(s.dialect),
                       s.transactions.total(), s.transactions.rejected,
                       v.timed ? fmt::format("{}", s.timeouts) : "not judged", ms, cycles,
                       md_escape(findings_by_kind_text(s.findings)));
    }
    for (const StationView& v : m.stations) {
        const ChannelStats& s = *v.stats;
        fmt::format_to(it, "\n### Slave {} (master {})\n\n", s.slave, s.master);
        fmt::format_to(it, "- Layout: {}\n", md_escape(ppo_text(s)));
        if (v.has_ident) fmt::format_to(it, "- Ident number: 0x{:04X}\n", v.ident);
        if (!v.dialect_hint.empty())
            fmt::format_to(it, "- Dialect hint: {}\n", md_escape(v.dialect_hint));
        fmt::format_to(
            it, "- Data_Exchange: {}, {}; {}\n", counted(s.data_exchange, "telegram", "telegrams"),
            counted(s.cycles, "cycle", "cycles"), counted(s.requests, "request", "requests"));
        fmt::format_to(it, "- Transactions: {} ({})\n", s.transactions.total(),
                       outcomes_text(s.transactions));
        fmt::format_to(it, "- Unanswered: {}, {} abandoned; spontaneous messages: {}\n",
                       timeouts_text(v), s.abandoned, s.spontaneous);
        fmt::format_to(it, "- Parameters: {}\n", parameters_text(s));
        for (const auto& [key, count] : s.rejections) {
            std::string_view text = error_text(s.dialect, key.second);
            fmt::format_to(it, "- Rejected: PNU {} error {} ({}), {}x\n", key.first, key.second,
                           md_escape(text.empty() ? "unknown" : text), count);
        }
        fmt::format_to(it, "- Findings: {}\n", md_escape(findings_by_kind_text(s.findings)));
    }
    if (m.has_bus_findings)
        fmt::format_to(it, "\n### Bus (telegrams no station can be named for)\n\n- Findings: {}\n",
                       md_escape(findings_by_kind_text(c.tracker->bus().findings)));
    fmt::format_to(it, "\n## Findings ({})\n\n", m.shown);
    if (m.shown > 0)
        append(b,
               "| frame | time (s) | severity | kind | master / slave | PNU | message |\n"
               "|---:|---:|---|---|---|---:|---|\n");
    std::array<std::uint64_t, kFindingKindCount> listed{};
    c.findings->for_each([&](const Finding& f) {
        if (!shows(c, f) || listed[static_cast<std::size_t>(f.kind)]++ >= kListedPerKind) return;
        fmt::format_to(it, "| {} | {} | {} | {} | {} | {} | {} |\n", f.frame,
                       relative_seconds(c, f.time_ns), severity_name(f.severity),
                       md_escape(finding_kind_name(f.kind)), station_label(f),
                       f.pnu ? fmt::format("{}", *f.pnu) : std::string("-"), md_escape(f.message));
        out.end_record();
    });
    bool first_unlisted = true;
    for (FindingKind kind : kAllKinds)
        if (listed[static_cast<std::size_t>(kind)] > kListedPerKind) {
            fmt::format_to(it, "{}- {}\n", first_unlisted ? "\n" : "",
                           md_escape(unlisted_text(kind, listed)));
            first_unlisted = false;
        }
    if (!c.findings->error().empty())
        fmt::format_to(it, "\nSome findings could not be listed: {}\n",
                       md_escape(c.findings->error()));
    out.end_record();
}

// ---- json ---------------------------------------------------------------------------------------

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

void json_kind_counts(JsonWriter& w, const std::array<std::uint64_t, kFindingKindCount>& counts) {
    w.begin_object();
    for (std::size_t i = 0; i < kFindingKindCount; ++i)
        w.key(finding_kind_name(static_cast<FindingKind>(i)))
            .integer(static_cast<std::int64_t>(counts[i]));
    w.end_object();
}

void render_json(const ReportContext& c, const Model& m, Output& out) {
    JsonWriter w(out.buffer());
    auto count = [&w](std::string_view key, std::uint64_t n) {
        w.key(key).integer(static_cast<std::int64_t>(n));
    };
    const TrackerOptions& options = c.tracker->options();
    w.begin_object();
    w.key("dpscope").string(c.version);
    w.key("input").begin_object();
    w.key("file").string(c.input.name);
    w.key("format").string(c.input.format);
    w.key("damaged").boolean(c.input.damaged);
    count("bytes_skipped", c.input.bytes_skipped);
    w.key("first_time");
    json::time(w, c.summary->first_time_ns());
    w.key("last_time");
    json::time(w, c.summary->last_time_ns());
    w.end_object();
    w.key("options").begin_object();
    w.key("timeout_ms").integer(options.timeout_ns / 1'000'000);
    w.key("strict").boolean(options.strict);
    w.key("fail_on").string(fail_on_name(c.fail_on));
    w.key("allow_empty").boolean(c.allow_empty);
    w.key("stations");
    if (c.stations.empty()) {
        w.null();
    } else {
        w.begin_array();
        for (std::uint8_t station : c.stations)
            w.integer(station);
        w.end_array();
    }
    w.end_object();
    w.key("result").string(m.fails ? "fail" : "pass");
    w.key("nothing_checked").boolean(m.nothing_checked);
    std::uint64_t transactions = 0;
    for (const StationView& v : m.stations)
        transactions += v.stats->transactions.total();
    w.key("summary").begin_object();
    count("telegrams", c.summary->telegrams());
    count("fcs_errors", m.fcs_errors);
    count("transactions", transactions);
    w.key("findings").begin_object();
    count("error", errors(m));
    count("warning", warnings(m));
    count("note", notes(m));
    w.end_object();
    w.end_object();
    w.key("stations").begin_array();
    for (const StationView& v : m.stations) {
        const ChannelStats& s = *v.stats;
        w.begin_object();
        w.key("master").integer(s.master);
        w.key("slave").integer(s.slave);
        w.key("ppo_type").optional_integer(s.ppo.known() && s.ppo.type != 0, s.ppo.type);
        w.key("ppo_source").string(ppo_source_name(s.ppo.source));
        w.key("dialect").string(dialect_name(s.dialect));
        w.key("dialect_hint");
        if (std::optional<Dialect> hint = c.summary->dialect_evidence(s.slave).hint())
            w.string(dialect_name(*hint));
        else
            w.null();
        w.key("ident").optional_integer(v.has_ident, v.ident);
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
        w.key("timeouts").optional_integer(v.timed, static_cast<std::int64_t>(s.timeouts));
        count("abandoned", s.abandoned);
        count("spontaneous", s.spontaneous);
        w.key("latency_ms");
        json_latency(w, v.latency.any, v.latency.min_ms, v.latency.median_ms, v.latency.p95_ms,
                     v.latency.max_ms, false);
        w.key("latency_cycles");
        json_latency(w, v.latency.any_cycles, static_cast<double>(v.latency.min_cycles),
                     static_cast<double>(v.latency.median_cycles),
                     static_cast<double>(v.latency.p95_cycles),
                     static_cast<double>(v.latency.max_cycles), true);
        w.key("parameters").begin_array();
        for (const auto& [pnu, n] : s.pnu_requests) {
            w.begin_object();
            w.key("pnu").integer(pnu);
            count("requests", n);
            w.end_object();
        }
        w.end_array();
        w.key("rejections").begin_array();
        for (const auto& [key, n] : s.rejections) {
            w.begin_object();
            w.key("pnu").integer(key.first);
            w.key("error").integer(key.second);
            w.key("error_text");
            std::string_view text = error_text(s.dialect, key.second);
            if (text.empty())
                w.null();
            else
                w.string(text);
            count("count", n);
            w.end_object();
        }
        w.end_array();
        w.key("findings");
        json_kind_counts(w, s.findings);
        w.end_object();
        out.end_record();
    }
    w.end_array();
    w.key("bus").begin_object();
    w.key("findings");
    json_kind_counts(w, c.tracker->bus().findings);
    w.end_object();
    w.key("findings").begin_array();
    c.findings->for_each([&](const Finding& f) {
        if (!shows(c, f)) return;
        json::finding(w, f);
        out.end_record();
    });
    w.end_array();
    w.end_object();
    out.put('\n');
    out.end_record();
}

// ---- html ---------------------------------------------------------------------------------------

void escape_xml(TextBuffer& b, std::string_view text) {
    for (char ch : text) {
        switch (ch) {
            case '&': append(b, "&amp;"); break;
            case '<': append(b, "&lt;"); break;
            case '>': append(b, "&gt;"); break;
            case '"': append(b, "&quot;"); break;
            case '\'': append(b, "&#39;"); break;
            default: b.push_back(ch);
        }
    }
}

std::string xml(std::string_view text) {
    TextBuffer b;
    escape_xml(b, text);
    return fmt::to_string(b);
}

constexpr std::string_view kHtmlStyle = R"(
body { font: 14px/1.45 system-ui, -apple-system, "Segoe UI", sans-serif; color: #1d2330;
       margin: 0 auto; max-width: 1100px; padding: 24px; background: #fafbfc; }
h1 { font-size: 24px; margin: 0 0 4px; }
h2 { font-size: 19px; margin: 32px 0 8px; border-bottom: 1px solid #d8dde6; padding-bottom: 4px; }
h3 { font-size: 15px; margin: 18px 0 6px; color: #394150; }
.meta { color: #5b6476; margin: 0 0 12px; }
.verdict { display: inline-block; padding: 6px 14px; border-radius: 6px; font-weight: 600; }
.verdict.pass { background: #e3f4e8; color: #1b6b34; border: 1px solid #9fd3ae; }
.verdict.fail { background: #fde8e8; color: #9b1c1c; border: 1px solid #f1a9a9; }
.cards { display: flex; flex-wrap: wrap; gap: 12px; margin: 12px 0; }
.card { background: #fff; border: 1px solid #d8dde6; border-radius: 8px; padding: 10px 16px;
        min-width: 110px; }
.card .n { font-size: 22px; font-weight: 600; }
.card .l { color: #5b6476; font-size: 12px; text-transform: uppercase; letter-spacing: .04em; }
table { border-collapse: collapse; background: #fff; margin: 6px 0 12px; }
th, td { border: 1px solid #d8dde6; padding: 4px 8px; text-align: left; vertical-align: top; }
th { background: #eef1f6; font-weight: 600; }
td.n, th.n { text-align: right; font-variant-numeric: tabular-nums; }
table.kv th { width: 190px; }
section.station, section.bus { background: #fff; border: 1px solid #d8dde6; border-radius: 8px;
                  padding: 4px 18px 14px; margin: 18px 0; }
td.error, .card.error, p.error { color: #b42318; }
td.warning, .card.warning { color: #a15c07; }
td.note, .card.note { color: #175cd3; }
tr.error td:first-child { border-left: 4px solid #d92d20; }
tr.warning td:first-child { border-left: 4px solid #f79009; }
tr.note td:first-child { border-left: 4px solid #2e90fa; }
svg { background: #fff; display: block; max-width: 100%; height: auto; }
.scroll { overflow-x: auto; max-width: 100%; }
table.findings td:last-child { overflow-wrap: anywhere; }
section.station h2, section.bus h2 { margin-top: 14px; }
svg text { font: 11px system-ui, sans-serif; fill: #394150; }
.legend span { display: inline-block; margin-right: 14px; font-size: 12px; }
.swatch { display: inline-block; width: 10px; height: 10px; margin-right: 4px; vertical-align: -1px; }
)";

void svg_latency_histogram(TextBuffer& b, const ChannelStats& s) {
    const LogHistogram& h = s.latency_ns;
    auto it = std::back_inserter(b);
    if (h.count() == 0) {
        append(b, s.transactions.total() == 0
                      ? "<p class=\"meta\">No answered requests.</p>\n"
                      : "<p class=\"meta\">The capture carries no timestamps: latency in cycles "
                        "only (see above).</p>\n");
        return;
    }
    constexpr int kBars = 30, kWidth = 720, kHeight = 170, kLeft = 48, kBottom = 28, kTop = 10;
    const double max_ms = std::max(to_ms(h.max()), 0.001);
    std::array<std::uint64_t, kBars> bars{};
    h.for_each_bucket([&](std::uint64_t lower, std::uint64_t upper, std::uint64_t count) {
        double middle = to_ms(lower + (upper - lower) / 2);
        auto bar = static_cast<std::size_t>(std::min<double>(kBars - 1, middle / max_ms * kBars));
        bars[bar] += count;
    });
    std::uint64_t tallest = *std::max_element(bars.begin(), bars.end());
    const double bar_width = static_cast<double>(kWidth - kLeft - 10) / kBars;
    const int plot_height = kHeight - kBottom - kTop;
    fmt::format_to(it,
                   "<svg class=\"latency\" width=\"{}\" height=\"{}\" viewBox=\"0 0 {} {}\" "
                   "role=\"img\" aria-label=\"latency histogram of slave {}\">\n",
                   kWidth, kHeight, kWidth, kHeight, s.slave);
    fmt::format_to(it, "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#8a93a6\"/>\n",
                   kLeft, kHeight - kBottom, kWidth - 10, kHeight - kBottom);
    for (int i = 0; i < kBars; ++i) {
        if (bars[static_cast<std::size_t>(i)] == 0) continue;
        double height = static_cast<double>(bars[static_cast<std::size_t>(i)]) /
                        static_cast<double>(tallest) * plot_height;
        double x = kLeft + i * bar_width;
        fmt::format_to(it,
                       "<rect class=\"bar\" x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" "
                       "height=\"{:.1f}\" fill=\"#4e79c5\"><title>{:.3f}-{:.3f} ms: {}"
                       "</title></rect>\n",
                       x + 1, kHeight - kBottom - height, bar_width - 2, height, max_ms * i / kBars,
                       max_ms * (i + 1) / kBars,
                       counted(bars[static_cast<std::size_t>(i)], "transaction", "transactions"));
    }
    fmt::format_to(it, "<text x=\"{}\" y=\"{}\">0 ms</text>\n", kLeft, kHeight - 10);
    fmt::format_to(it, "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{:.3f} ms</text>\n",
                   kWidth - 10, kHeight - 10, max_ms);
    fmt::format_to(it, "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text>\n", kLeft - 6,
                   kTop + 10, tallest);
    fmt::format_to(it, "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">0</text>\n", kLeft - 6,
                   kHeight - kBottom);
    append(b, "</svg>\n");
}

void svg_timeline(TextBuffer& b, const ChannelStats& s, const ReportContext& c) {
    const Timeline& timeline = s.timeline;
    auto it = std::back_inserter(b);
    if (timeline.empty()) {
        append(b, "<p class=\"meta\">No timed transactions or findings.</p>\n");
        return;
    }
    constexpr int kWidth = 720, kLeft = 84, kRight = 10;
    constexpr int kBarsTop = 64, kBarsHeight = 80, kHeight = 178;
    const auto& bins = timeline.bins();
    std::size_t used = 0;
    std::uint32_t tallest = 1;
    for (std::size_t i = 0; i < bins.size(); ++i) {
        const Timeline::Bin& bin = bins[i];
        if (bin.transactions || bin.errors || bin.warnings || bin.notes) used = i + 1;
        tallest = std::max(tallest, bin.transactions);
    }
    used = std::max<std::size_t>(used, 1);
    const double step = static_cast<double>(kWidth - kLeft - kRight) / static_cast<double>(used);
    fmt::format_to(it,
                   "<svg class=\"timeline\" width=\"{}\" height=\"{}\" viewBox=\"0 0 {} {}\" "
                   "role=\"img\" aria-label=\"timeline of slave {}\">\n",
                   kWidth, kHeight, kWidth, kHeight, s.slave);
    const char* rows[] = {"errors", "warnings", "notes"};
    const char* singular[] = {"error", "warning", "note"};
    const char* colours[] = {"#d92d20", "#f79009", "#2e90fa"};
    for (int row = 0; row < 3; ++row)
        fmt::format_to(it, "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text>\n", kLeft - 6,
                       14 + row * 16, rows[row]);
    fmt::format_to(it, "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">transactions</text>\n",
                   kLeft - 6, kBarsTop + kBarsHeight / 2);
    fmt::format_to(it, "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#8a93a6\"/>\n",
                   kLeft, kBarsTop + kBarsHeight, kWidth - kRight, kBarsTop + kBarsHeight);
    const std::int64_t width_ns = timeline.bin_width_ns();
    for (std::size_t i = 0; i < used; ++i) {
        const Timeline::Bin& bin = bins[i];
        const double x = kLeft + static_cast<double>(i) * step;
        std::int64_t from = timeline.start_ns() + static_cast<std::int64_t>(i) * width_ns;
        std::string when = relative_seconds(c, from);
        if (bin.transactions) {
            double height = static_cast<double>(bin.transactions) / tallest * kBarsHeight;
            fmt::format_to(it,
                           "<rect class=\"tx\" x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" "
                           "height=\"{:.2f}\" fill=\"#4e79c5\"><title>from {} s: {}"
                           "</title></rect>\n",
                           x, kBarsTop + kBarsHeight - height, std::max(step - 0.5, 0.8), height,
                           when, counted(bin.transactions, "transaction", "transactions"));
        }
        const std::uint32_t counts[] = {bin.errors, bin.warnings, bin.notes};
        for (int row = 0; row < 3; ++row) {
            if (!counts[row]) continue;
            fmt::format_to(it,
                           "<rect class=\"mark {}\" x=\"{:.2f}\" y=\"{}\" width=\"{:.2f}\" "
                           "height=\"10\" fill=\"{}\"><title>from {} s: {}</title></rect>\n",
                           rows[row], x, 5 + row * 16, std::max(step, 3.0), colours[row], when,
                           counted(counts[row], singular[row], rows[row]));
        }
    }
    std::int64_t end_ns = timeline.start_ns() + static_cast<std::int64_t>(used) * width_ns;
    fmt::format_to(it, "<text x=\"{}\" y=\"{}\">{} s</text>\n", kLeft, kHeight - 8,
                   relative_seconds(c, timeline.start_ns()));
    fmt::format_to(it, "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{} s</text>\n", kWidth - kRight,
                   kHeight - 8, relative_seconds(c, end_ns));
    append(b, "</svg>\n");
}

void html_kv(TextBuffer& b, std::string_view key, std::string_view value) {
    append(b, "<tr><th>");
    escape_xml(b, key);
    append(b, "</th><td>");
    escape_xml(b, value);
    append(b, "</td></tr>\n");
}

// "Findings by kind": a table of the kinds found, or "None."
void html_findings_by_kind(TextBuffer& b,
                           const std::array<std::uint64_t, kFindingKindCount>& findings) {
    append(b, "<h3>Findings by kind</h3>\n");
    bool any = false;
    for (FindingKind kind : kAllKinds)
        any |= findings[static_cast<std::size_t>(kind)] > 0;
    if (!any) {
        append(b, "<p class=\"meta\">None.</p>\n");
        return;
    }
    append(b,
           "<table class=\"kinds\"><tr><th>kind</th><th>severity</th><th "
           "class=\"n\">count</th></tr>\n");
    for (FindingKind kind : kAllKinds) {
        std::uint64_t n = findings[static_cast<std::size_t>(kind)];
        if (!n) continue;
        std::string_view severity = severity_name(default_severity(kind));
        fmt::format_to(std::back_inserter(b),
                       "<tr class=\"{}\"><td>{}</td><td class=\"{}\">{}</td><td "
                       "class=\"n\">{}</td></tr>\n",
                       severity, finding_kind_name(kind), severity, severity, n);
    }
    append(b, "</table>\n");
}

void render_html(const ReportContext& c, const Model& m, Output& out) {
    TextBuffer& b = out.buffer();
    auto it = std::back_inserter(b);
    const TrackerOptions& options = c.tracker->options();
    std::uint64_t transactions = 0;
    for (const StationView& v : m.stations)
        transactions += v.stats->transactions.total();
    fmt::format_to(it,
                   "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                   "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
                   "<title>dpscope report: {}</title>\n<style>{}</style>\n</head>\n<body>\n",
                   xml(c.input.name), kHtmlStyle);
    append(b, "<h1>dpscope conformance report</h1>\n");
    fmt::format_to(it,
                   "<p class=\"meta\">{} ({}) &middot; dpscope {} &middot; {} "
                   "&middot; RC 8 rule {}</p>\n",
                   xml(c.input.name), xml(c.input.format), xml(c.version),
                   m.timed ? fmt::format("time-out {} ms", options.timeout_ns / 1'000'000)
                           : std::string(kNoTimestamps),
                   options.strict ? "strict" : "lenient");
    if (!c.stations.empty())
        fmt::format_to(it,
                       "<p class=\"meta\">Filter: {} (telegram counts cover the whole "
                       "capture)</p>\n",
                       xml(filter_text(c)));
    fmt::format_to(it, "<p class=\"verdict {}\" id=\"verdict\">{}</p>\n", m.fails ? "fail" : "pass",
                   xml(verdict_text(c, m)));
    if (c.input.damaged)
        append(b,
               "<p class=\"error\">The input ended in damage; the report covers what was "
               "read.</p>\n");
    append(b, "<section id=\"summary\">\n<h2>Summary</h2>\n<div class=\"cards\">\n");
    auto card = [&](std::string_view label, std::uint64_t n, std::string_view cls) {
        fmt::format_to(it,
                       "<div class=\"card {}\"><div class=\"n\">{}</div><div class=\"l\">{}</div>"
                       "</div>\n",
                       cls, n, label);
    };
    card("telegrams", c.summary->telegrams(), "");
    card("bytes skipped", c.input.bytes_skipped, "");
    card("FCS errors", m.fcs_errors, "");
    card("transactions", transactions, "");
    card("slaves", m.stations.size(), "");
    card("errors", errors(m), "error");
    card("warnings", warnings(m), "warning");
    card("notes", notes(m), "note");
    append(b,
           "</div>\n<div class=\"scroll\"><table class=\"slaves\">\n<tr><th "
           "class=\"n\">slave</th><th class=\"n\">"
           "master</th><th>PPO</th><th>dialect</th><th class=\"n\">transactions</th><th "
           "class=\"n\">median ms</th><th class=\"n\">p95 ms</th><th class=\"n\">errors</th><th "
           "class=\"n\">warnings</th><th class=\"n\">notes</th></tr>\n");
    for (const StationView& v : m.stations) {
        const ChannelStats& s = *v.stats;
        std::array<std::uint64_t, 3> severities{};
        for (FindingKind kind : kAllKinds)
            severities[static_cast<std::size_t>(default_severity(kind))] +=
                s.findings[static_cast<std::size_t>(kind)];
        fmt::format_to(it,
                       "<tr><td class=\"n\"><a href=\"#slave-{}-{}\">{}</a></td><td class=\"n\">{}"
                       "</td><td>{}</td><td>{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td>"
                       "<td class=\"n\">{}</td><td class=\"n error\">{}</td><td class=\"n "
                       "warning\">{}</td><td class=\"n note\">{}</td></tr>\n",
                       s.slave, s.master, s.slave, s.master, xml(ppo_type_label(s.ppo)),
                       dialect_name(s.dialect), s.transactions.total(),
                       v.latency.any ? fmt::format("{:.3f}", v.latency.median_ms) : "-",
                       v.latency.any ? fmt::format("{:.3f}", v.latency.p95_ms) : "-", severities[2],
                       severities[1], severities[0]);
    }
    append(b, "</table></div>\n</section>\n");

    for (const StationView& v : m.stations) {
        const ChannelStats& s = *v.stats;
        fmt::format_to(it,
                       "<section class=\"station\" id=\"slave-{}-{}\">\n<h2>Slave {} (master {})"
                       "</h2>\n<table class=\"kv\">\n",
                       s.slave, s.master, s.slave, s.master);
        html_kv(b, "Layout", ppo_text(s));
        html_kv(b, "Dialect", dialect_name(s.dialect));
        if (!v.dialect_hint.empty()) html_kv(b, "Dialect hint", v.dialect_hint);
        if (v.has_ident) html_kv(b, "Ident number", fmt::format("0x{:04X}", v.ident));
        html_kv(b, "Data_Exchange",
                fmt::format("{}, {}", counted(s.data_exchange, "telegram", "telegrams"),
                            counted(s.cycles, "cycle", "cycles")));
        html_kv(b, "Parameter requests", fmt::format("{}", s.requests));
        html_kv(b, "Transactions",
                fmt::format("{}: {}", s.transactions.total(), outcomes_text(s.transactions)));
        html_kv(b, "Unanswered",
                fmt::format("{}, {} abandoned by the master", timeouts_text(v), s.abandoned));
        html_kv(b, "Spontaneous messages", fmt::format("{}", s.spontaneous));
        html_kv(b, "Latency (ms)",
                !v.timed        ? std::string("not measured (no timestamps)")
                : v.latency.any ? fmt::format("min {:.3f}, median {:.3f}, p95 {:.3f}, max {:.3f}",
                                              v.latency.min_ms, v.latency.median_ms,
                                              v.latency.p95_ms, v.latency.max_ms)
                                : "-");
        html_kv(b, "Latency (cycles)",
                v.latency.any_cycles ? fmt::format("min {}, median {}, p95 {}, max {}",
                                                   v.latency.min_cycles, v.latency.median_cycles,
                                                   v.latency.p95_cycles, v.latency.max_cycles)
                                     : "-");
        append(b, "</table>\n<h3>Latency histogram</h3>\n");
        svg_latency_histogram(b, s);
        append(b,
               "<h3>Timeline</h3>\n<div class=\"legend\"><span><i class=\"swatch\" "
               "style=\"background:#4e79c5\"></i>transactions</span><span><i class=\"swatch\" "
               "style=\"background:#d92d20\"></i>errors</span><span><i class=\"swatch\" "
               "style=\"background:#f79009\"></i>warnings</span><span><i class=\"swatch\" "
               "style=\"background:#2e90fa\"></i>notes</span></div>\n");
        svg_timeline(b, s, c);
        append(b, "<h3>Parameters accessed</h3>\n");
        if (s.pnu_requests.empty()) {
            append(b, "<p class=\"meta\">None.</p>\n");
        } else {
            append(b,
                   "<table class=\"parameters\"><tr><th class=\"n\">PNU</th><th "
                   "class=\"n\">requests</th></tr>\n");
            for (const auto& [pnu, count] : s.pnu_requests)
                fmt::format_to(it, "<tr><td class=\"n\">{}</td><td class=\"n\">{}</td></tr>\n", pnu,
                               count);
            append(b, "</table>\n");
        }
        if (!s.rejections.empty()) {
            append(b,
                   "<h3>Rejected requests</h3>\n<table class=\"rejections\"><tr><th "
                   "class=\"n\">PNU</th><th class=\"n\">error</th><th>meaning</th><th "
                   "class=\"n\">count</th></tr>\n");
            for (const auto& [key, count] : s.rejections) {
                std::string_view text = error_text(s.dialect, key.second);
                fmt::format_to(it,
                               "<tr><td class=\"n\">{}</td><td class=\"n\">{}</td><td>{}</td>"
                               "<td class=\"n\">{}</td></tr>\n",
                               key.first, key.second, xml(text.empty() ? "unknown" : text), count);
            }
            append(b, "</table>\n");
        }
        html_findings_by_kind(b, s.findings);
        append(b, "</section>\n");
        out.end_record();
    }
    if (m.has_bus_findings) {
        append(b,
               "<section class=\"bus\" id=\"bus\">\n<h2>Bus (telegrams no station can be "
               "named for)</h2>\n");
        html_findings_by_kind(b, c.tracker->bus().findings);
        append(b, "</section>\n");
        out.end_record();
    }

    fmt::format_to(it, "<section id=\"findings\">\n<h2>Findings ({})</h2>\n", m.shown);
    if (m.shown == 0) {
        append(b, "<p class=\"meta\">No findings.</p>\n");
    } else {
        append(b,
               "<div class=\"scroll\"><table class=\"findings\">\n<tr><th "
               "class=\"n\">frame</th><th class=\"n\">time "
               "(s)</th><th>severity</th><th>kind</th><th>master / slave</th><th "
               "class=\"n\">PNU</th><th>message</th></tr>\n");
        std::size_t rows = 0;
        c.findings->for_each([&](const Finding& f) {
            if (!shows(c, f) || rows++ >= kHtmlFindingRows) return;
            std::string_view severity = severity_name(f.severity);
            fmt::format_to(it,
                           "<tr class=\"{}\"><td class=\"n\">{}</td><td class=\"n\">{}</td><td "
                           "class=\"{}\">{}</td><td>{}</td><td>{}</td><td class=\"n\">{}</td><td>{}"
                           "</td></tr>\n",
                           severity, f.frame, relative_seconds(c, f.time_ns), severity, severity,
                           finding_kind_name(f.kind), xml(station_label(f)),
                           f.pnu ? fmt::format("{}", *f.pnu) : std::string("-"), xml(f.message));
            out.end_record();
        });
        append(b, "</table></div>\n");
        if (rows > kHtmlFindingRows)
            fmt::format_to(it,
                           "<p class=\"meta\">{} not listed here (at most {}; the JSON report "
                           "lists them all).</p>\n",
                           counted(rows - kHtmlFindingRows, "more finding", "more findings"),
                           kHtmlFindingRows);
    }
    append(b, "</section>\n</body>\n</html>\n");
    out.end_record();
}

// ---- junit --------------------------------------------------------------------------------------

void render_junit(const ReportContext& c, const Model& m, Output& out) {
    TextBuffer& b = out.buffer();
    auto it = std::back_inserter(b);
    struct Suite {
        std::string name;
        std::string classname;
        bool has_stations;
        std::uint8_t master;
        std::uint8_t slave;
        std::string dialect_hint;
        std::array<std::uint64_t, kFindingKindCount> failing{};  // at or above the threshold
        std::array<std::uint64_t, kFindingKindCount> others{};   // below the threshold
        std::array<Severity, kFindingKindCount> other_severity{};
    };
    // Findings at or above --fail-on (errors at least) become failures. They are counted here
    // and written from the finding log one test case at a time, so memory stays flat however
    // many there are.
    std::vector<Suite> suites;
    for (const StationView& v : m.stations)
        suites.push_back(
            Suite{fmt::format("slave {} (master {})", v.stats->slave, v.stats->master),
                  fmt::format("dpscope.master_{}.slave_{}", v.stats->master, v.stats->slave),
                  true,
                  v.stats->master,
                  v.stats->slave,
                  v.dialect_hint,
                  {},
                  {},
                  {}});
    if (m.has_bus_findings)
        suites.push_back(Suite{"bus", "dpscope.bus", false, 0, 0, {}, {}, {}, {}});
    auto in_suite = [](const Suite& s, const Finding& f) {
        return s.has_stations == f.has_stations &&
               (!f.has_stations || (s.master == f.master && s.slave == f.slave));
    };
    auto fails = [&](const Finding& f) {
        return f.severity == Severity::Error || severity_fails(f.severity, c.fail_on);
    };
    c.findings->for_each([&](const Finding& f) {
        if (!shows(c, f)) return;
        auto s = std::find_if(suites.begin(), suites.end(),
                              [&](const Suite& suite) { return in_suite(suite, f); });
        if (s == suites.end()) return;
        auto kind = static_cast<std::size_t>(f.kind);
        if (fails(f)) {
            ++s->failing[kind];
        } else {
            ++s->others[kind];
            s->other_severity[kind] = f.severity;
        }
    });
    auto failed_cases = [](const Suite& s) {
        return static_cast<std::size_t>(
            std::count_if(s.failing.begin(), s.failing.end(), [](std::uint64_t n) { return n; }));
    };
    std::size_t total_tests = suites.size() * kFindingKindCount;
    std::size_t total_failed = 0;
    for (const Suite& s : suites)
        total_failed += failed_cases(s);
    // Nothing checked is no pass: one test case says so, a failure unless --allow-empty.
    if (m.nothing_checked) {
        ++total_tests;
        if (!c.allow_empty) ++total_failed;
    }
    fmt::format_to(it,
                   "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                   "<testsuites name=\"dpscope {}\" tests=\"{}\" failures=\"{}\" errors=\"0\">\n",
                   xml(c.input.name), total_tests, total_failed);
    if (m.nothing_checked) {
        std::string reason = "nothing checked: " + nothing_checked_reason(c);
        fmt::format_to(it,
                       "  <testsuite name=\"capture\" tests=\"1\" failures=\"{}\" errors=\"0\" "
                       "skipped=\"{}\">\n"
                       "    <testcase classname=\"dpscope.capture\" name=\"parameter channel: the "
                       "capture holds Data_Exchange telegrams with a parameter channel\">\n",
                       c.allow_empty ? 0 : 1, c.allow_empty ? 1 : 0);
        if (c.allow_empty)
            fmt::format_to(it, "      <skipped message=\"{} (--allow-empty)\"/>\n", xml(reason));
        else
            fmt::format_to(it,
                           "      <failure type=\"nothing_checked\" message=\"{}\">{}</failure>\n",
                           xml(reason), xml(reason));
        append(b, "    </testcase>\n  </testsuite>\n");
        out.end_record();
    }
    // Without timestamps the time-out rules cannot be judged: those cases are skipped.
    auto judged = [&](FindingKind kind) {
        return m.timed || (kind != FindingKind::ResponseTimeout &&
                           kind != FindingKind::SpontaneousUnacknowledged);
    };
    for (const Suite& s : suites) {
        fmt::format_to(it,
                       "  <testsuite name=\"{}\" tests=\"{}\" failures=\"{}\" errors=\"0\" "
                       "skipped=\"{}\">\n",
                       xml(s.name), kFindingKindCount, failed_cases(s), m.timed ? 0 : 2);
        for (FindingKind kind : kAllKinds) {
            auto k = static_cast<std::size_t>(kind);
            const bool hint = kind == FindingKind::UnknownCode && !s.dialect_hint.empty();
            fmt::format_to(it, "    <testcase classname=\"{}\" name=\"{}: {}\"", s.classname,
                           finding_kind_name(kind), xml(finding_rule_text(kind)));
            if (!judged(kind)) {
                append(b,
                       ">\n      <skipped message=\"not judged: the capture carries no "
                       "timestamps\"/>\n    </testcase>\n");
                continue;
            }
            if (s.failing[k] == 0 && s.others[k] == 0 && !hint) {
                append(b, "/>\n");
                continue;
            }
            append(b, ">\n");
            if (s.failing[k] > 0) {
                std::uint64_t listed = 0;
                c.findings->for_each([&](const Finding& f) {
                    if (f.kind != kind || listed >= kJunitFailuresPerCase || !shows(c, f) ||
                        !in_suite(s, f) || !fails(f))
                        return;
                    ++listed;
                    fmt::format_to(
                        it,
                        "      <failure type=\"{}\" message=\"frame {}: {}\">{} {} frame "
                        "{}{}: {}</failure>\n",
                        finding_kind_name(kind), f.frame, xml(f.message), severity_name(f.severity),
                        finding_kind_name(kind), f.frame,
                        f.request_frame ? fmt::format(" (request frame {})", f.request_frame)
                                        : std::string(),
                        xml(f.message));
                    out.end_record();
                });
            }
            const std::uint64_t unlisted =
                s.failing[k] > kJunitFailuresPerCase ? s.failing[k] - kJunitFailuresPerCase : 0;
            if (unlisted > 0 || s.others[k] > 0 || hint) {
                std::vector<std::string> notes;
                if (unlisted > 0)
                    notes.push_back(fmt::format(
                        "{} not listed here (at most {} per rule; the JSON report lists them all)",
                        counted(unlisted, "more failing finding", "more failing findings"),
                        kJunitFailuresPerCase));
                if (s.others[k] > 0)
                    notes.push_back(fmt::format("{} {} {} below the failure threshold", s.others[k],
                                                severity_name(s.other_severity[k]),
                                                s.others[k] == 1 ? "finding" : "findings"));
                if (hint) notes.push_back("dialect hint: " + s.dialect_hint);
                append(b, "      <system-out>");
                for (std::size_t i = 0; i < notes.size(); ++i) {
                    if (i) append(b, "; ");
                    escape_xml(b, notes[i]);
                }
                append(b, "</system-out>\n");
            }
            append(b, "    </testcase>\n");
        }
        append(b, "  </testsuite>\n");
        out.end_record();
    }
    append(b, "</testsuites>\n");
    out.end_record();
}

}  // namespace

bool report_fails(const ReportContext& context) { return build_model(context).fails; }

void render_report(ReportFormat format, const ReportContext& context, Output& out) {
    Model model = build_model(context);
    switch (format) {
        case ReportFormat::Text: render_text(context, model, out); break;
        case ReportFormat::Json: render_json(context, model, out); break;
        case ReportFormat::Markdown: render_markdown(context, model, out); break;
        case ReportFormat::Html: render_html(context, model, out); break;
        case ReportFormat::Junit: render_junit(context, model, out); break;
    }
}

}  // namespace dpscope
