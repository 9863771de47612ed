#include "protocols/profibus/health/health_thresholds.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

#include "core/catalogue.hpp"
#include "core/text_encoding.hpp"

namespace dpscope {

namespace {

using enum HealthThreshold;
using C = ThresholdComparison;

constexpr HealthThresholdRow kRows[] = {
    {LostCycles, "lost_cycles", 3, 1, 1000, true, "", Verdict::Good, C::Setting,
     "consecutive poll cycles without an answer after which a station counts as lost (a master: "
     "tokens passed to it and not taken)",
     "a DP master repeats a request up to its retry limit (typically 1 to 3) before it moves on; "
     "three whole cycles in silence is no longer a disturbance but a station gone"},
    {LostEventsBad, "lost_events_bad", 1, 0, 1e9, true, "", Verdict::Bad, C::From,
     "lost events from which a station is bad (0: never)",
     "a station dropping off the bus stops the machine part it serves: any lost event is bad"},
    {FcsErrorPercentWeak, "fcs_error_percent_weak", 0, 0, 100, false, "%", Verdict::Weak, C::Above,
     "damaged telegrams (bad FCS, malformed) on a station's link, in % of its telegrams, above "
     "which it is weak",
     "a healthy segment has no damaged telegrams at all: any one points to a cable, terminator "
     "or earthing fault worth looking at"},
    {FcsErrorPercentBad, "fcs_error_percent_bad", 0.1, 0, 100, false, "%", Verdict::Bad, C::Above,
     "damaged telegrams on a station's link, in % of its telegrams, above which it is bad",
     "one damaged telegram in a thousand means repeats on every few cycles and lost stations "
     "soon after"},
    {RepeatPercentWeak, "repeat_percent_weak", 0.1, 0, 100, false, "%", Verdict::Weak, C::Above,
     "FDL repeats (retries), in % of the requests to a slave, above which it is weak",
     "repeats are the first sign of a physical problem; a few per ten thousand requests are "
     "tolerable bursts of noise, more deserve a look"},
    {RepeatPercentBad, "repeat_percent_bad", 5, 0, 100, false, "%", Verdict::Bad, C::Above,
     "FDL repeats, in % of the requests to a slave, above which it is bad",
     "one request in twenty repeated stretches the bus cycle noticeably and is a short step from "
     "the retry limit"},
    {RepeatsPerCycleWeak, "repeats_per_cycle_weak", 2, 0, 1000, true, "", Verdict::Weak, C::From,
     "repeats of one request from which a slave is weak (0: never)",
     "a request that needed two repeats came close to the usual retry limit of the master"},
    {NoAnswerPercentWeak, "no_answer_percent_weak", 0.1, 0, 100, false, "%", Verdict::Weak,
     C::Above,
     "requests without an answer, in % of those that expected one, above which a station "
     "is weak",
     "a slave in data exchange answers every request; silence beyond noise level is a warning"},
    {NoAnswerPercentBad, "no_answer_percent_bad", 5, 0, 100, false, "%", Verdict::Bad, C::Above,
     "requests without an answer, in % of those that expected one, above which a station is bad",
     "one request in twenty unanswered is a station barely hanging on"},
    {IllegalAnswersWeak, "illegal_answers_weak", 1, 0, 1e9, true, "", Verdict::Weak, C::From,
     "illegal answers (not asked, wrong kind, short acknowledge where data was due) from which a "
     "station is weak (0: never)",
     "an illegal answer is a protocol violation or two stations with one address: always worth "
     "seeing"},
    {IllegalAnswersBad, "illegal_answers_bad", 10, 0, 1e9, true, "", Verdict::Bad, C::From,
     "illegal answers from which a station is bad (0: never)",
     "repeated illegal answers are no glitch: a duplicate address or a broken stack"},
    {ResyncsWeak, "resyncs_weak", 1, 0, 1e9, true, "", Verdict::Weak, C::From,
     "resyncs (leaving data exchange and being parameterised again) from which a slave is weak "
     "(0: never)",
     "a slave that leaves data exchange lost its outputs for a while: worth seeing once"},
    {ResyncsBad, "resyncs_bad", 3, 0, 1e9, true, "", Verdict::Bad, C::From,
     "resyncs from which a slave is bad (0: never)",
     "a slave that keeps dropping out of data exchange (watchdog, power, EMC) is not reliable"},
    {DiagFaultsWeak, "diag_faults_weak", 1, 0, 1e9, true, "", Verdict::Weak, C::From,
     "diagnosis answers showing a fault (Station_Not_Ready, Cfg_Fault, Ext_Diag, Prm_Fault, "
     "Stat_Diag) from which a slave is weak (0: never)",
     "a slave reporting a fault needs attention even when the bus itself is fine"},
    {RefusalsWeak, "refusals_weak", 1, 0, 1e9, true, "", Verdict::Weak, C::From,
     "negative FDL answers UE, RR and RS from which a slave is weak (0: never)",
     "a refused service (user error, no resources, SAP not active) is a configuration or "
     "overload problem; NR, DH and RDH are normal answers and only counted"},
    {TargetRotationMs, "target_rotation_ms", 0, 0, 1e6, false, "ms", Verdict::Weak, C::Above,
     "the target token rotation time (TTR) in ms; a master whose rotation exceeds it at the 95th "
     "percentile is weak, at the maximum by half again is bad (0: no target)",
     "TTR is a bus parameter set in the master, not sent on the bus (Set_Prm carries no TTR): "
     "give it from the configuration to have rotations judged"},
    {CycleJitterPercentWeak, "cycle_jitter_percent_weak", 10, 0, 1000, false, "%", Verdict::Weak,
     C::Above,
     "cycle-to-cycle jitter of a master's poll cycle, in % of its mean cycle time, above which the "
     "master is weak (0: never)",
     "a DP cycle varies by the odd repeat and acyclic service; a tenth of the cycle from one to "
     "the next is more than that"},
    {BusLoadPercentWeak, "bus_load_percent_weak", 90, 0, 100, false, "%", Verdict::Weak, C::Above,
     "bus load in % of the line rate above which the segment is weak (needs the baud rate; 100: "
     "never)",
     "a DP master polls back to back, so load is high by design; above 90 % there is no room "
     "left for repeats or acyclic services"},
    {BusLoadPercentBad, "bus_load_percent_bad", 100, 0, 100, false, "%", Verdict::Bad, C::Above,
     "bus load in % above which the segment is bad (100: never)",
     "off by default: a saturated line is a capacity question, the stations' figures say whether "
     "it hurts"},
};

static_assert(catalogue::one_row_per_kind_in_order(std::span<const HealthThresholdRow>(kRows),
                                                   kHealthThresholdCount),
              "one health threshold row per HealthThreshold, in enum order");
static_assert(catalogue::names_unique(std::span<const HealthThresholdRow>(kRows)),
              "health threshold names are unique and not empty");

std::string_view trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t'))
        s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
        s.remove_suffix(1);
    return s;
}

std::string known_names() {
    std::string names;
    for (const HealthThresholdRow& row : kRows) {
        if (!names.empty()) names += ", ";
        names += row.name;
    }
    return names;
}

std::string format_limit(double value) { return fmt::format("{:g}", value); }

}  // namespace

std::string_view verdict_name(Verdict verdict) noexcept {
    switch (verdict) {
        case Verdict::Good: return "good";
        case Verdict::Weak: return "weak";
        case Verdict::Bad: return "bad";
    }
    return "good";
}

std::span<const HealthThresholdRow> health_threshold_catalogue() noexcept { return kRows; }

const HealthThresholdRow& health_threshold_row(HealthThreshold kind) noexcept {
    return kRows[static_cast<std::size_t>(kind)];
}

std::optional<HealthThreshold> health_threshold_from_name(std::string_view name) noexcept {
    for (const HealthThresholdRow& row : kRows)
        if (row.name == name) return row.kind;
    return std::nullopt;
}

HealthThresholds::HealthThresholds() noexcept {
    for (const HealthThresholdRow& row : kRows)
        values_[static_cast<std::size_t>(row.kind)] = row.default_value;
}

Result<void> HealthThresholds::set(HealthThreshold kind, double value) {
    const HealthThresholdRow& row = health_threshold_row(kind);
    const std::string unit = row.unit.empty() ? "" : fmt::format(" {}", row.unit);
    if (!std::isfinite(value) || value < row.minimum || value > row.maximum)
        return Error{fmt::format("threshold {}: {} is out of range; give {} to {}{}", row.name,
                                 format_limit(value), format_limit(row.minimum),
                                 format_limit(row.maximum), unit)};
    if (row.whole && value != std::floor(value))
        return Error{
            fmt::format("threshold {}: {} is not a whole number", row.name, format_limit(value))};
    values_[static_cast<std::size_t>(kind)] = value;
    return {};
}

Result<void> HealthThresholds::set_from_text(std::string_view assignment) {
    const std::size_t equals = assignment.find('=');
    if (equals == std::string_view::npos)
        return Error{
            fmt::format("'{}' is no threshold setting; write NAME=VALUE, e.g. "
                        "lost_cycles=5 (thresholds: {})",
                        quoted_excerpt(assignment), known_names())};
    const std::string_view name = trim(assignment.substr(0, equals));
    const std::string_view text = trim(assignment.substr(equals + 1));
    const std::optional<HealthThreshold> kind = health_threshold_from_name(name);
    if (!kind)
        return Error{fmt::format("unknown threshold '{}'; the thresholds are: {}",
                                 quoted_excerpt(name), known_names())};
    double value = 0;
    const char* end = text.data() + text.size();
    auto [stop, error] = std::from_chars(text.data(), end, value);
    if (text.empty() || error != std::errc{} || stop != end)
        return Error{fmt::format("threshold {}: '{}' is not a number", name, quoted_excerpt(text))};
    return set(*kind, value);
}

Result<void> HealthThresholds::load(std::string_view text, std::string_view origin) {
    HealthThresholds loaded = *this;
    // A UTF-8 byte order mark (as Notepad writes one) is no part of the first name.
    if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);
    std::size_t line_number = 0;
    while (!text.empty()) {
        ++line_number;
        const std::size_t newline = text.find('\n');
        std::string_view line = text.substr(0, newline);
        text = newline == std::string_view::npos ? std::string_view{} : text.substr(newline + 1);
        if (const std::size_t comment = line.find_first_of("#;"); comment != std::string_view::npos)
            line = line.substr(0, comment);
        line = trim(line);
        if (line.empty()) continue;
        if (line.front() == '[') {
            if (line != "[thresholds]")
                return Error{
                    fmt::format("{}:{}: unknown section '{}'; the settings go in "
                                "[thresholds] or before any section",
                                origin, line_number, quoted_excerpt(line))};
            continue;
        }
        if (Result<void> set = loaded.set_from_text(line); !set)
            return Error{fmt::format("{}:{}: {}", origin, line_number, set.error())};
    }
    *this = loaded;
    return {};
}

}  // namespace dpscope
