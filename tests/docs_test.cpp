// The README's reference tables list what the catalogues hold: every finding kind, every bus-health
// threshold with its default. A new kind or threshold without its README row fails here.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "core/finding.hpp"
#include "protocols/profibus/health/health_thresholds.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

std::string readme() {
    std::ifstream in(test::source_dir() + "/README.md");
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

TEST(DocsTest, ReadmeListsEveryFindingKind) {
    const std::string text = readme();
    ASSERT_FALSE(text.empty());
    for (std::size_t i = 0; i < kFindingKindCount; ++i) {
        const std::string_view name = finding_kind_name(static_cast<FindingKind>(i));
        EXPECT_NE(text.find(fmt::format("| `{}` |", name)), std::string::npos) << name;
    }
}

TEST(DocsTest, ReadmeListsEveryHealthThresholdWithItsDefault) {
    const std::string text = readme();
    ASSERT_FALSE(text.empty());
    for (const HealthThresholdRow& row : health_threshold_catalogue()) {
        const std::string unit = row.unit.empty() ? "" : fmt::format(" {}", row.unit);
        const std::string cell =
            fmt::format("| `{}` | {:g}{} |", row.name, row.default_value, unit);
        EXPECT_NE(text.find(cell), std::string::npos) << cell;
    }
}

}  // namespace
}  // namespace dpscope
