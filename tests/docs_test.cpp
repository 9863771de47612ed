// The reference pages list what the catalogues hold: docs/findings.md every finding kind,
// docs/bus-health.md every bus-health threshold with its default. A new kind or threshold without
// its row fails here. The README stays a front door (issue 32): at most 250 lines, its Quick start
// the two commands it has always had. And every relative link in the Markdown pages resolves.
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

// The text of a Markdown page, by its path in the source tree ("docs/findings.md").
std::string page(const std::string& path) {
    std::ifstream in(test::source_dir() + "/" + path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

TEST(DocsTest, FindingsPageListsEveryFindingKind) {
    const std::string text = page("docs/findings.md");
    ASSERT_FALSE(text.empty());
    for (std::size_t i = 0; i < kFindingKindCount; ++i) {
        const std::string_view name = finding_kind_name(static_cast<FindingKind>(i));
        EXPECT_NE(text.find(fmt::format("| `{}` |", name)), std::string::npos) << name;
    }
}

TEST(DocsTest, BusHealthPageListsEveryHealthThresholdWithItsDefault) {
    const std::string text = page("docs/bus-health.md");
    ASSERT_FALSE(text.empty());
    for (const HealthThresholdRow& row : health_threshold_catalogue()) {
        const std::string unit = row.unit.empty() ? "" : fmt::format(" {}", row.unit);
        const std::string cell =
            fmt::format("| `{}` | {:g}{} |", row.name, row.default_value, unit);
        EXPECT_NE(text.find(cell), std::string::npos) << cell;
    }
}

// The README is the front door, the reference one link away (issue 32): at most 250 lines, and
// its "## Quick start" holds one fenced block of exactly the two commands it has always had (CI,
// .ci/run, runs the second).
TEST(DocsTest, ReadmeIsAFrontDoorWithItsTwoQuickStartCommands) {
    std::istringstream in(page("README.md"));
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);)
        lines.push_back(line);
    ASSERT_FALSE(lines.empty());
    EXPECT_LE(lines.size(), 250u) << "README.md has " << lines.size() << " lines";

    std::size_t section = 0;
    while (section < lines.size() && lines[section] != "## Quick start")
        ++section;
    ASSERT_LT(section, lines.size()) << "README.md has no \"## Quick start\"";
    std::vector<std::size_t> fences;
    std::vector<std::string> commands;
    for (std::size_t i = section + 1; i < lines.size() && lines[i].rfind("## ", 0) != 0; ++i) {
        if (lines[i].rfind("```", 0) == 0)
            fences.push_back(i);
        else if (fences.size() % 2 == 1)
            commands.push_back(lines[i]);
    }
    ASSERT_EQ(fences.size(), 2u) << "the Quick start must hold exactly one fenced block";
    EXPECT_EQ(lines[fences[0]], "```sh");
    EXPECT_EQ(commands, (std::vector<std::string>{
                            "scripts/install-deps && cmake --workflow --preset release && "
                            "build/release/dpscope decode samples/faults.pcap",
                            "scripts/install-deps && scripts/run-tests",
                        }));
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
