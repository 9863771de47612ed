// The problem catalogue: one row per kind, names fixed (they are in jsonl, csv and the summary),
// every kind in exactly one component.
#include "core/problem.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

namespace dpscope {
namespace {

TEST(ProblemTest, EveryKindHasExactlyOneRowInEnumOrder) {
    auto catalogue = problem_catalogue();
    ASSERT_EQ(catalogue.size(), kProblemKindCount);
    for (std::size_t i = 0; i < kProblemKindCount; ++i) {
        const auto kind = static_cast<ProblemKind>(i);
        EXPECT_EQ(catalogue[i].kind, kind) << i;
        EXPECT_EQ(&problem_kind_info(kind), &catalogue[i]) << i;
        EXPECT_FALSE(catalogue[i].check.empty()) << catalogue[i].name;
    }
}

TEST(ProblemTest, NamesAndSeveritiesAreTheDocumentedOnes) {
    const std::vector<std::string> expected = {
        "empty_record",
        "bad_start_delimiter",
        "truncated",
        "length_mismatch",
        "length_out_of_range",
        "start_delimiter_repeat",
        "fcs_mismatch",
        "bad_end_delimiter",
        "trailing_bytes",
        "invalid_address",
        "address_extension_short",
        "service_data_short",
        "cfg_identifier_truncated",
        "diag_block_truncated",
        "reserved_frame_control",
        "lge_invalid",
        "bcc_mismatch",
        "adr_invalid",
        "vlt2000_character_invalid",
        "vlt2000_field_invalid",
        "vlt2000_letter_unknown",
        "vlt2000_checksum_mismatch",
    };
    ASSERT_EQ(expected.size(), kProblemKindCount);
    for (std::size_t i = 0; i < kProblemKindCount; ++i) {
        const auto kind = static_cast<ProblemKind>(i);
        EXPECT_EQ(problem_kind_name(kind), expected[i]);
        // Only bytes left over after a complete telegram are a warning.
        EXPECT_EQ(problem_severity(kind),
                  kind == ProblemKind::TrailingBytes ? Severity::Warning : Severity::Error)
            << expected[i];
    }
    EXPECT_EQ(problem_kind_name(ProblemKind::Count), "unknown");
}

TEST(ProblemTest, NamesAreUnique) {
    std::set<std::string_view> names;
    for (const ProblemKindInfo& row : problem_catalogue())
        EXPECT_TRUE(names.insert(row.name).second) << row.name;
}

TEST(ProblemTest, TheComponentListingsCoverEveryKindOnce) {
    std::vector<int> listed(kProblemKindCount, 0);
    std::set<std::string_view> component_names;
    for (std::size_t c = 0; c < kProblemComponentCount; ++c) {
        const auto component = static_cast<ProblemComponent>(c);
        EXPECT_TRUE(component_names.insert(problem_component_name(component)).second);
        const std::vector<ProblemKind> kinds = problem_kinds_of(component);
        EXPECT_FALSE(kinds.empty()) << problem_component_name(component);
        for (ProblemKind kind : kinds) {
            ++listed[static_cast<std::size_t>(kind)];
            EXPECT_EQ(problem_component(kind), component) << problem_kind_name(kind);
        }
    }
    for (std::size_t i = 0; i < kProblemKindCount; ++i)
        EXPECT_EQ(listed[i], 1) << problem_kind_name(static_cast<ProblemKind>(i));
}

TEST(ProblemTest, DpServiceProblemsAreTheirOwnComponent) {
    EXPECT_EQ(problem_kinds_of(ProblemComponent::DpService),
              (std::vector<ProblemKind>{ProblemKind::ServiceDataShort,
                                        ProblemKind::CfgIdentifierTruncated,
                                        ProblemKind::DiagBlockTruncated}));
}

// The end delimiter's text names what was wanted: FDL's ED (expected left 0) in hex, VLT 2000's
// '>' as a character.
TEST(ProblemTest, EndDelimiterMessageNamesWhatWasWanted) {
    EXPECT_EQ(problem_message(Problem{ProblemKind::BadEndDelimiter, 9, 0, 0x17}),
              "byte 9: end delimiter is 0x17, expected 0x16");
    EXPECT_EQ(problem_message(Problem{ProblemKind::BadEndDelimiter, 21, '>', '<'}),
              "byte 21: end delimiter is '<', expected '>' (0x3E)");
}

}  // namespace
}  // namespace dpscope
