// The thresholds of the bus-health verdict: one catalogue row per threshold (name, default,
// range, unit, what it judges), so that the settings file, the command line, --help and the
// table in docs/bus-health.md all read the same table. A verdict is good, weak or bad; the
// station's and the segment's verdict is the worst any threshold gives.
//
// Settings file (`--health-config FILE`): lines `name = value`, `#` or `;` starting a comment,
// an optional `[thresholds]` section header; both a TOML and an INI reader take it.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "core/result.hpp"

namespace dpscope {

enum class Verdict : std::uint8_t { Good, Weak, Bad };
// "good", "weak", "bad".
std::string_view verdict_name(Verdict verdict) noexcept;
inline Verdict worse(Verdict a, Verdict b) noexcept { return a < b ? b : a; }

enum class HealthThreshold : std::uint8_t {
    LostCycles,              // consecutive unanswered cycles that make a station lost
    LostEventsBad,           // lost events from which a station is bad
    FcsErrorPercentWeak,     // damaged telegrams on a link, % of its telegrams, above: weak
    FcsErrorPercentBad,      // ... above: bad
    RepeatPercentWeak,       // FDL retries, % of the requests to a slave, above: weak
    RepeatPercentBad,        // ... above: bad
    RepeatsPerCycleWeak,     // most repeats of one request, from: weak
    NoAnswerPercentWeak,     // requests without an answer, % of those expecting one, above: weak
    NoAnswerPercentBad,      // ... above: bad
    IllegalAnswersWeak,      // illegal answers from: weak
    IllegalAnswersBad,       // illegal answers from: bad
    ResyncsWeak,             // resyncs from: weak
    ResyncsBad,              // resyncs from: bad
    DiagFaultsWeak,          // diagnosis answers showing a fault from: weak
    RefusalsWeak,            // negative answers UE, RR, RS from: weak
    TargetRotationMs,        // the target token rotation time (0: none given)
    CycleJitterPercentWeak,  // cycle jitter, % of the mean cycle time, above: weak
    BusLoadPercentWeak,      // bus load above: weak (the segment)
    BusLoadPercentBad,       // bus load above: bad (the segment)
    Count
};
inline constexpr std::size_t kHealthThresholdCount =
    static_cast<std::size_t>(HealthThreshold::Count);

// How a threshold compares: from the limit on (a count reaching it), or above it (a rate
// exceeding it). A limit of 0 switches a "from" threshold off (see the catalogue's texts).
enum class ThresholdComparison : std::uint8_t { From, Above, Setting };

struct HealthThresholdRow {
    HealthThreshold kind;
    std::string_view name;  // as in the settings file and --threshold NAME=VALUE
    double default_value;
    double minimum;
    double maximum;
    bool whole;                     // a whole number
    std::string_view unit;          // "%", "ms", "" (a count)
    Verdict verdict;                // what crossing it gives (Good for settings)
    ThresholdComparison comparison;
    std::string_view description;  // one sentence for --help and docs
    std::string_view reasoning;    // why the default (docs/bus-health.md)
};

// The catalogue, in enum order.
std::span<const HealthThresholdRow> health_threshold_catalogue() noexcept;
const HealthThresholdRow& health_threshold_row(HealthThreshold kind) noexcept;
std::optional<HealthThreshold> health_threshold_from_name(std::string_view name) noexcept;

class HealthThresholds {
  public:
    HealthThresholds() noexcept;  // the defaults
    double get(HealthThreshold kind) const noexcept {
        return values_[static_cast<std::size_t>(kind)];
    }
    // Sets a value after checking its range and wholeness; the error names the threshold, the
    // value and the range.
    Result<void> set(HealthThreshold kind, double value);
    // "name=value" (the --threshold option); the error names what was wrong.
    Result<void> set_from_text(std::string_view assignment);
    // The settings file's text; `origin` names the file in errors, with the line number
    // ("health.toml:3: unknown threshold 'lost_cycle'; ...").
    Result<void> load(std::string_view text, std::string_view origin);

  private:
    std::array<double, kHealthThresholdCount> values_{};
};

}  // namespace dpscope
