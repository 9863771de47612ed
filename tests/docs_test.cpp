// The README's reference tables list what the catalogues hold: every finding kind, every bus-health
// threshold with its default. A new kind or threshold without its README row fails here. And every
// relative link in the Markdown pages resolves.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

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

// Every relative link in README.md, CONTRIBUTING.md and docs/ names a file or folder that is
// there (issue 32: the reference moves into docs/, one link away from the README). Links into
// the web and to anchors of the same page are not checked; fenced code blocks are skipped.
TEST(DocsTest, EveryRelativeLinkResolves) {
    namespace fs = std::filesystem;
    const fs::path root = test::source_dir();
    std::vector<fs::path> pages = {root / "README.md", root / "CONTRIBUTING.md"};
    for (const auto& entry : fs::recursive_directory_iterator(root / "docs"))
        if (entry.is_regular_file() && entry.path().extension() == ".md")
            pages.push_back(entry.path());
    const std::regex link(R"(\]\(([^)\s]+)\))");
    std::size_t checked = 0;
    for (const fs::path& page : pages) {
        std::ifstream in(page);
        ASSERT_TRUE(in) << page;
        std::string line;
        bool fenced = false;
        for (int number = 1; std::getline(in, line); ++number) {
            if (line.rfind("```", 0) == 0) fenced = !fenced;
            if (fenced) continue;
            for (std::sregex_iterator it(line.begin(), line.end(), link), end; it != end; ++it) {
                std::string target = (*it)[1].str();
                if (target.rfind("http://", 0) == 0 || target.rfind("https://", 0) == 0 ||
                    target.rfind("mailto:", 0) == 0 || target.rfind('#', 0) == 0)
                    continue;
                target = target.substr(0, target.find('#'));
                ++checked;
                EXPECT_TRUE(fs::exists(page.parent_path() / target))
                    << page.lexically_relative(root).string() << ":" << number << ": " << target;
            }
        }
    }
    EXPECT_GT(checked, 10u);
}

}  // namespace
}  // namespace dpscope
