// The bus-health threshold catalogue: defaults, ranges, the --threshold text and the settings
// file reader (comments, sections, errors naming file:line).
#include "protocols/profibus/health/health_thresholds.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>

namespace dpscope {
namespace {

using enum HealthThreshold;

TEST(HealthThresholdsTest, CatalogueInEnumOrderWithDefaults) {
    const auto catalogue = health_threshold_catalogue();
    ASSERT_EQ(catalogue.size(), kHealthThresholdCount);
    std::set<std::string_view> names;
    for (std::size_t i = 0; i < catalogue.size(); ++i) {
        const HealthThresholdRow& row = catalogue[i];
        EXPECT_EQ(static_cast<std::size_t>(row.kind), i);
        EXPECT_TRUE(names.insert(row.name).second) << row.name;
        EXPECT_GE(row.default_value, row.minimum) << row.name;
        EXPECT_LE(row.default_value, row.maximum) << row.name;
        EXPECT_FALSE(row.description.empty()) << row.name;
        EXPECT_FALSE(row.reasoning.empty()) << row.name;
        EXPECT_EQ(health_threshold_from_name(row.name), row.kind);
        EXPECT_EQ(&health_threshold_row(row.kind), &row);
    }
    const HealthThresholds defaults;
    EXPECT_EQ(defaults.get(LostCycles), 3);
    EXPECT_EQ(defaults.get(LostEventsBad), 1);
    EXPECT_EQ(defaults.get(FcsErrorPercentWeak), 0);
    EXPECT_EQ(defaults.get(FcsErrorPercentBad), 0.1);
    EXPECT_EQ(defaults.get(RepeatPercentWeak), 0.1);
    EXPECT_EQ(defaults.get(RepeatPercentBad), 5);
    EXPECT_EQ(defaults.get(RepeatsPerCycleWeak), 2);
    EXPECT_EQ(defaults.get(NoAnswerPercentWeak), 0.1);
    EXPECT_EQ(defaults.get(NoAnswerPercentBad), 5);
    EXPECT_EQ(defaults.get(IllegalAnswersWeak), 1);
    EXPECT_EQ(defaults.get(IllegalAnswersBad), 10);
    EXPECT_EQ(defaults.get(ResyncsWeak), 1);
    EXPECT_EQ(defaults.get(ResyncsBad), 3);
    EXPECT_EQ(defaults.get(DiagFaultsWeak), 1);
    EXPECT_EQ(defaults.get(RefusalsWeak), 1);
    EXPECT_EQ(defaults.get(TargetRotationMs), 0);
    EXPECT_EQ(defaults.get(CycleJitterPercentWeak), 10);
    EXPECT_EQ(defaults.get(BusLoadPercentWeak), 90);
    EXPECT_EQ(defaults.get(BusLoadPercentBad), 100);
    EXPECT_FALSE(health_threshold_from_name("lost_cycle").has_value());
    EXPECT_EQ(verdict_name(Verdict::Weak), "weak");
    EXPECT_EQ(worse(Verdict::Weak, Verdict::Bad), Verdict::Bad);
    EXPECT_EQ(worse(Verdict::Weak, Verdict::Good), Verdict::Weak);
}

TEST(HealthThresholdsTest, SetChecksRangeAndWholeness) {
    HealthThresholds t;
    EXPECT_TRUE(t.set(LostCycles, 5).has_value());
    EXPECT_EQ(t.get(LostCycles), 5);
    EXPECT_TRUE(t.set(LostCycles, 1).has_value());
    EXPECT_TRUE(t.set(LostCycles, 1000).has_value());
    Result<void> low = t.set(LostCycles, 0);
    ASSERT_FALSE(low.has_value());
    EXPECT_EQ(low.error(), "threshold lost_cycles: 0 is out of range; give 1 to 1000");
    EXPECT_FALSE(t.set(LostCycles, 1001).has_value());
    Result<void> fraction = t.set(LostCycles, 2.5);
    ASSERT_FALSE(fraction.has_value());
    EXPECT_EQ(fraction.error(), "threshold lost_cycles: 2.5 is not a whole number");
    EXPECT_EQ(t.get(LostCycles), 1000);  // unchanged by the failures
    EXPECT_TRUE(t.set(RepeatPercentWeak, 0.25).has_value());
    Result<void> percent = t.set(RepeatPercentWeak, 100.5);
    ASSERT_FALSE(percent.has_value());
    EXPECT_EQ(percent.error(),
              "threshold repeat_percent_weak: 100.5 is out of range; give 0 to 100 %");
    EXPECT_FALSE(t.set(TargetRotationMs, std::numeric_limits<double>::quiet_NaN()).has_value());
    EXPECT_FALSE(t.set(TargetRotationMs, std::numeric_limits<double>::infinity()).has_value());
    EXPECT_FALSE(t.set(TargetRotationMs, -1).has_value());
}

TEST(HealthThresholdsTest, SetFromText) {
    HealthThresholds t;
    EXPECT_TRUE(t.set_from_text("lost_cycles=5").has_value());
    EXPECT_EQ(t.get(LostCycles), 5);
    EXPECT_TRUE(t.set_from_text(" target_rotation_ms = 12.5 ").has_value());
    EXPECT_EQ(t.get(TargetRotationMs), 12.5);

    Result<void> no_equals = t.set_from_text("lost_cycles");
    ASSERT_FALSE(no_equals.has_value());
    EXPECT_NE(no_equals.error().find("'lost_cycles' is no threshold setting"), std::string::npos);
    Result<void> unknown = t.set_from_text("lost_cycle=3");
    ASSERT_FALSE(unknown.has_value());
    EXPECT_NE(unknown.error().find("unknown threshold 'lost_cycle'"), std::string::npos);
    EXPECT_NE(unknown.error().find("bus_load_percent_bad"), std::string::npos);
    Result<void> not_number = t.set_from_text("lost_cycles=three");
    ASSERT_FALSE(not_number.has_value());
    EXPECT_EQ(not_number.error(), "threshold lost_cycles: 'three' is not a number");
    EXPECT_FALSE(t.set_from_text("lost_cycles=").has_value());
    EXPECT_FALSE(t.set_from_text("lost_cycles=5x").has_value());
    Result<void> range = t.set_from_text("resyncs_bad=-1");
    ASSERT_FALSE(range.has_value());
    EXPECT_NE(range.error().find("out of range"), std::string::npos);
    EXPECT_EQ(t.get(LostCycles), 5);
}

TEST(HealthThresholdsTest, LoadWithCommentsAndSection) {
    HealthThresholds t;
    const char* text =
        "# dpscope bus health\n"
        "; an INI comment\n"
        "\n"
        "lost_cycles = 4   # after four cycles\n"
        "[thresholds]\r\n"
        "\trepeat_percent_weak=0.5 ; a comment\n"
        "target_rotation_ms = 20";
    Result<void> loaded = t.load(text, "health.toml");
    ASSERT_TRUE(loaded.has_value()) << loaded.error();
    EXPECT_EQ(t.get(LostCycles), 4);
    EXPECT_EQ(t.get(RepeatPercentWeak), 0.5);
    EXPECT_EQ(t.get(TargetRotationMs), 20);
    EXPECT_EQ(t.get(ResyncsBad), 3);  // untouched
    EXPECT_TRUE(t.load("", "empty.ini").has_value());
}

TEST(HealthThresholdsTest, LoadErrorsNameFileAndLine) {
    HealthThresholds t;
    Result<void> unknown = t.load("lost_cycles = 4\n\nlost_cycle = 3\n", "health.toml");
    ASSERT_FALSE(unknown.has_value());
    EXPECT_EQ(unknown.error().rfind("health.toml:3: unknown threshold 'lost_cycle'", 0), 0u)
        << unknown.error();
    EXPECT_EQ(t.get(LostCycles), 3);  // nothing applied from a file with an error

    Result<void> section = t.load("[bus]\nlost_cycles = 4\n", "a.ini");
    ASSERT_FALSE(section.has_value());
    EXPECT_EQ(section.error().rfind("a.ini:1: unknown section '[bus]'", 0), 0u);

    Result<void> range = t.load("# x\nlost_cycles = 0\n", "b.ini");
    ASSERT_FALSE(range.has_value());
    EXPECT_EQ(range.error(), "b.ini:2: threshold lost_cycles: 0 is out of range; give 1 to 1000");

    Result<void> garbage = t.load("\x01\x02\xff\n", "c.ini");
    ASSERT_FALSE(garbage.has_value());
    EXPECT_EQ(garbage.error().rfind("c.ini:1: ", 0), 0u);
    Result<void> value = t.load("lost_cycles = = 3", "d.ini");
    ASSERT_FALSE(value.has_value());
    EXPECT_EQ(value.error().rfind("d.ini:1: threshold lost_cycles: '= 3' is not a number", 0), 0u);
}

TEST(HealthThresholdsTest, LoadSkipsAUtf8ByteOrderMark) {
    HealthThresholds t;
    // Notepad writes one before the first line.
    ASSERT_TRUE(t.load("\xEF\xBB\xBFlost_cycles = 4\r\n", "bom.toml").has_value());
    EXPECT_EQ(t.get(HealthThreshold::LostCycles), 4);
}

}  // namespace
}  // namespace dpscope
