// The JUnit report: one test suite per station section (and one for the bus), one test case per
// rule the section covers: the cyclic channel's suite has the parameter-channel, link and
// configuration rules, the DP-V1 suite the DP-V1 parameter-access rules.
#include <algorithm>
#include <iterator>

#include "formats/report_markup.hpp"
#include "formats/report_model.hpp"
#include "protocols/profibus/health/health_render.hpp"

namespace dpscope::report {

namespace {

// A test case lists at most this many failures; the rest are counted in <system-out>.
constexpr std::size_t kJunitFailuresPerCase = 10'000;

// The bus-health suite's test cases: the segment, each station, each master; a bad verdict is a
// failure with the reasons as its message.
struct HealthCase {
    std::string name;
    const Judgement* judgement;
};

std::vector<HealthCase> health_cases(const BusHealth& h) {
    // A segment without telegrams is not judged (SegmentHealth::judged()): no case, as a station
    // never seen has none; the report's own result says that nothing was checked.
    std::vector<HealthCase> cases;
    if (h.segment.judged()) cases.push_back({"segment", &h.segment.judgement});
    for (const StationHealth& s : h.stations)
        cases.push_back(
            {fmt::format("station {} ({})", s.address, station_role_name(s.role)), &s.judgement});
    for (const MasterHealth& master : h.masters)
        cases.push_back(
            {fmt::format("master {} (token and cycle)", master.address), &master.judgement});
    return cases;
}

void write_health_suite(const BusHealth& h, const std::vector<HealthCase>& cases, TextBuffer& b) {
    auto it = std::back_inserter(b);
    const auto failures = std::count_if(cases.begin(), cases.end(), [](const HealthCase& c) {
        return c.judgement->verdict == Verdict::Bad;
    });
    fmt::format_to(it,
                   "  <testsuite name=\"bus health\" tests=\"{}\" failures=\"{}\" errors=\"0\" "
                   "skipped=\"0\">\n",
                   cases.size(), failures);
    for (const HealthCase& c : cases) {
        const Verdict verdict = c.judgement->verdict;
        fmt::format_to(it, "    <testcase classname=\"dpscope.bus_health\" name=\"{}\"",
                       xml(c.name));
        if (verdict == Verdict::Good) {
            append(b, "/>\n");
            continue;
        }
        std::string reasons = health::reasons_text(*c.judgement, h.thresholds);
        if (c.judgement == &h.segment.judgement) {
            const std::string cause = health::segment_cause(h);
            if (!cause.empty()) reasons += (reasons.empty() ? "" : "; ") + cause;
        }
        if (verdict == Verdict::Bad)
            fmt::format_to(it,
                           ">\n      <failure type=\"bus_health\" message=\"{}\">verdict bad: {}"
                           "</failure>\n    </testcase>\n",
                           xml(reasons), xml(reasons));
        else
            fmt::format_to(it,
                           ">\n      <system-out>verdict weak: {}</system-out>\n    </testcase>\n",
                           xml(reasons));
    }
    append(b, "  </testsuite>\n");
}

}  // namespace

void write_junit(const ReportContext& c, const ReportModel& m, Output& out) {
    TextBuffer& b = out.buffer();
    auto it = std::back_inserter(b);
    struct Suite {
        std::string name;
        std::string classname;
        bool has_stations;
        std::uint8_t master;
        std::uint8_t slave;
        const StationSection* section;                           // null for the bus
        std::array<std::uint64_t, kFindingKindCount> failing{};  // at or above the threshold
        std::array<std::uint64_t, kFindingKindCount> others{};   // below the threshold
        std::array<Severity, kFindingKindCount> other_severity{};
    };
    // Findings at or above --fail-on (errors at least) become failures. They are counted here
    // and written from the finding log one test case at a time, so memory stays flat however
    // many there are.
    std::vector<Suite> suites;
    for (const auto& section : m.stations)
        suites.push_back(Suite{section->junit_suite_name(),
                               section->junit_classname(),
                               true,
                               section->master(),
                               section->slave(),
                               section.get(),
                               {},
                               {},
                               {}});
    if (m.has_bus_findings)
        suites.push_back(Suite{"bus", "dpscope.bus", false, 0, 0, nullptr, {}, {}, {}});
    auto covers = [&c](const Suite& s, FindingKind kind) {
        return s.section ? s.section->covers(kind) : is_bus_kind(c, kind);
    };
    auto in_suite = [&](const Suite& s, const Finding& f) {
        return s.has_stations == f.has_stations && covers(s, f.kind) &&
               (!f.has_stations || (s.master == f.master && s.slave == f.slave));
    };
    auto fails = [&](const Finding& f) {
        return f.severity == Severity::Error || severity_fails(f.severity, c.fail_on);
    };
    // Counted from the log's tallies, exact also when it cannot list every finding.
    c.findings->for_each_tally([&](const FindingTally& t) {
        Finding f;
        f.kind = t.kind;
        f.severity = t.severity;
        f.has_stations = t.has_stations;
        f.master = t.master;
        f.slave = t.slave;
        if (!shows(c, f)) return;
        auto s = std::find_if(suites.begin(), suites.end(),
                              [&](const Suite& suite) { return in_suite(suite, f); });
        if (s == suites.end()) return;
        auto kind = static_cast<std::size_t>(f.kind);
        if (fails(f)) {
            s->failing[kind] += t.count;
        } else {
            s->others[kind] += t.count;
            s->other_severity[kind] = f.severity;
        }
    });
    auto failed_cases = [](const Suite& s) {
        return static_cast<std::size_t>(
            std::count_if(s.failing.begin(), s.failing.end(), [](std::uint64_t n) { return n; }));
    };
    // Without timestamps the time-out rules cannot be judged: those cases are skipped.
    auto judged = [&](FindingKind kind) {
        return m.timed ||
               (kind != FindingKind::ResponseTimeout &&
                kind != FindingKind::SpontaneousUnacknowledged &&
                kind != FindingKind::Dpv1ResponseTimeout && kind != FindingKind::FcLateResponse);
    };
    auto cases = [&](const Suite& s, bool only_skipped) {
        return static_cast<std::size_t>(std::count_if(
            kAllKinds.begin(), kAllKinds.end(),
            [&](FindingKind kind) { return covers(s, kind) && (!only_skipped || !judged(kind)); }));
    };
    std::size_t total_tests = 0;
    for (const Suite& s : suites)
        total_tests += cases(s, false);
    std::size_t total_failed = 0;
    for (const Suite& s : suites)
        total_failed += failed_cases(s);
    // Nothing checked is no pass: one test case says so, a failure unless --allow-empty.
    if (m.nothing_checked) {
        ++total_tests;
        if (!c.allow_empty) ++total_failed;
    }
    const std::vector<HealthCase> health =
        c.health ? health_cases(*c.health) : std::vector<HealthCase>{};
    total_tests += health.size();
    total_failed += static_cast<std::size_t>(
        std::count_if(health.begin(), health.end(),
                      [](const HealthCase& h) { return h.judgement->verdict == Verdict::Bad; }));
    // Findings the log could not keep (a full temporary folder): an error of the report itself.
    const std::string lost = not_listed_text(c);
    if (!lost.empty()) ++total_tests;
    fmt::format_to(it,
                   "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                   "<testsuites name=\"dpscope {}\" tests=\"{}\" failures=\"{}\" errors=\"{}\">\n",
                   xml(c.input.name), total_tests, total_failed, lost.empty() ? 0 : 1);
    if (!lost.empty()) {
        fmt::format_to(it,
                       "  <testsuite name=\"report\" tests=\"1\" failures=\"0\" errors=\"1\" "
                       "skipped=\"0\">\n"
                       "    <testcase classname=\"dpscope.report\" name=\"findings_listed: every "
                       "finding of the capture is listed\">\n"
                       "      <error type=\"findings_not_listed\" message=\"{}\"/>\n"
                       "    </testcase>\n  </testsuite>\n",
                       xml(lost));
        out.end_record();
    }
    if (m.nothing_checked) {
        std::string reason = "nothing checked: " + nothing_checked_reason(c);
        fmt::format_to(it,
                       "  <testsuite name=\"capture\" tests=\"1\" failures=\"{}\" errors=\"0\" "
                       "skipped=\"{}\">\n"
                       "    <testcase classname=\"dpscope.capture\" name=\"{}\">\n",
                       c.allow_empty ? 0 : 1, c.allow_empty ? 1 : 0,
                       bus_wording(c).nothing_checked_case);
        if (c.allow_empty)
            fmt::format_to(it, "      <skipped message=\"{} (--allow-empty)\"/>\n", xml(reason));
        else
            fmt::format_to(it,
                           "      <failure type=\"nothing_checked\" message=\"{}\">{}</failure>\n",
                           xml(reason), xml(reason));
        append(b, "    </testcase>\n  </testsuite>\n");
        out.end_record();
    }
    for (const Suite& s : suites) {
        fmt::format_to(it,
                       "  <testsuite name=\"{}\" tests=\"{}\" failures=\"{}\" errors=\"0\" "
                       "skipped=\"{}\">\n",
                       xml(s.name), cases(s, false), failed_cases(s), cases(s, true));
        if (s.section) {
            const auto properties = s.section->junit_properties();
            if (!properties.empty()) {
                append(b, "    <properties>\n");
                for (const auto& [name, value] : properties)
                    fmt::format_to(it, "      <property name=\"{}\" value=\"{}\"/>\n", xml(name),
                                   value);
                append(b, "    </properties>\n");
            }
        }
        for (FindingKind kind : kAllKinds) {
            if (!covers(s, kind)) continue;
            auto k = static_cast<std::size_t>(kind);
            const std::string note = s.section ? s.section->junit_note(kind) : std::string();
            fmt::format_to(it, "    <testcase classname=\"{}\" name=\"{}: {}\"", s.classname,
                           finding_kind_name(kind), xml(finding_rule_text(kind)));
            if (!judged(kind)) {
                append(b,
                       ">\n      <skipped message=\"not judged: the capture carries no "
                       "timestamps\"/>\n    </testcase>\n");
                continue;
            }
            if (s.failing[k] == 0 && s.others[k] == 0 && note.empty()) {
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
            if (unlisted > 0 || s.others[k] > 0 || !note.empty()) {
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
                if (!note.empty()) notes.push_back(note);
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
    if (c.health) {
        write_health_suite(*c.health, health, b);
        out.end_record();
    }
    append(b, "</testsuites>\n");
    out.end_record();
}

}  // namespace dpscope::report
