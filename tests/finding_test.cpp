// The finding catalogue: one row per kind, names and default severities fixed (they are in every
// output format), every kind in exactly one component.
#include "core/finding.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "simulator/fault_kind.hpp"

namespace dpscope {
namespace {

TEST(FindingTest, EveryKindHasExactlyOneRowInEnumOrder) {
    auto catalogue = finding_catalogue();
    ASSERT_EQ(catalogue.size(), kFindingKindCount);
    for (std::size_t i = 0; i < kFindingKindCount; ++i) {
        const auto kind = static_cast<FindingKind>(i);
        EXPECT_EQ(catalogue[i].kind, kind) << i;
        EXPECT_EQ(&finding_kind_info(kind), &catalogue[i]) << i;
    }
}

TEST(FindingTest, NamesAndSeveritiesAreTheDocumentedOnes) {
    // The names leave the program (jsonl, csv, reports, --fault): they never change.
    const std::vector<std::pair<std::string, Severity>> expected = {
        {"stacked_request", Severity::Error},
        {"orphan_response", Severity::Warning},
        {"mismatched_response", Severity::Error},
        {"unexpected_response_type", Severity::Error},
        {"response_timeout", Severity::Error},
        {"request_rejected", Severity::Note},
        {"no_authority", Severity::Warning},
        {"spontaneous_message", Severity::Note},
        {"spontaneous_unacknowledged", Severity::Warning},
        {"spm_violation", Severity::Warning},
        {"fcs_error", Severity::Error},
        {"malformed_telegram", Severity::Error},
        {"config_mismatch", Severity::Error},
        {"unknown_code", Severity::Warning},
        {"fdl_retry", Severity::Note},
        {"fdl_no_response", Severity::Warning},
        {"dpv1_stacked_request", Severity::Error},
        {"dpv1_reference_mismatch", Severity::Error},
        {"dpv1_unexpected_response_id", Severity::Error},
        {"dpv1_parameter_count_mismatch", Severity::Error},
        {"dpv1_orphan_response", Severity::Warning},
        {"dpv1_response_timeout", Severity::Error},
        {"dpv1_negative_response", Severity::Note},
        {"dpv1_length_error", Severity::Error},
        {"dpv1_error_pdu", Severity::Note},
        {"dpv1_unknown_code", Severity::Warning},
        {"fc_stacked_request", Severity::Error},
        {"fc_no_response", Severity::Error},
        {"fc_late_response", Severity::Warning},
        {"fc_mismatched_response", Severity::Error},
        {"fc_unexpected_response_type", Severity::Error},
        {"fc_command_rejected", Severity::Note},
        {"fc_bcc_error", Severity::Error},
        {"vlt2000_stacked_request", Severity::Error},
        {"vlt2000_no_response", Severity::Error},
        {"vlt2000_unexpected_reply", Severity::Error},
        {"vlt2000_mismatched_response", Severity::Error},
        {"vlt2000_command_failed", Severity::Note},
        {"vlt2000_checksum_error", Severity::Error},
        {"vlt2000_checksum_disabled", Severity::Note},
        {"gsd_ident_mismatch", Severity::Error},
        {"gsd_unknown_module", Severity::Error},
        {"gsd_config_limit", Severity::Error},
        {"gsd_user_prm_length", Severity::Error},
        {"gsd_user_prm_range", Severity::Error},
        {"gsd_diag_too_long", Severity::Warning},
        {"gsd_late_response", Severity::Warning},
        {"gsd_poll_interval", Severity::Warning},
    };
    ASSERT_EQ(expected.size(), kFindingKindCount);
    for (std::size_t i = 0; i < kFindingKindCount; ++i) {
        const auto kind = static_cast<FindingKind>(i);
        EXPECT_EQ(finding_kind_name(kind), expected[i].first);
        EXPECT_EQ(default_severity(kind), expected[i].second) << expected[i].first;
        EXPECT_FALSE(finding_rule_text(kind).empty()) << expected[i].first;
    }
}

TEST(FindingTest, NamesAreUniqueAndReadBack) {
    std::set<std::string_view> names;
    for (const FindingKindInfo& row : finding_catalogue()) {
        EXPECT_TRUE(names.insert(row.name).second) << row.name;
        EXPECT_EQ(finding_kind_from_name(row.name), row.kind) << row.name;
    }
    EXPECT_FALSE(finding_kind_from_name("no_such_finding"));
    EXPECT_FALSE(finding_kind_from_name(""));
}

TEST(FindingTest, TheComponentListingsCoverEveryKindOnce) {
    std::vector<int> listed(kFindingKindCount, 0);
    std::set<std::string_view> component_names;
    for (std::size_t c = 0; c < kFindingComponentCount; ++c) {
        const auto component = static_cast<FindingComponent>(c);
        EXPECT_TRUE(component_names.insert(finding_component_name(component)).second);
        const std::vector<FindingKind> kinds = finding_kinds_of(component);
        EXPECT_FALSE(kinds.empty()) << finding_component_name(component);
        for (FindingKind kind : kinds) {
            ++listed[static_cast<std::size_t>(kind)];
            EXPECT_EQ(finding_component(kind), component) << finding_kind_name(kind);
        }
    }
    for (std::size_t i = 0; i < kFindingKindCount; ++i)
        EXPECT_EQ(listed[i], 1) << finding_kind_name(static_cast<FindingKind>(i));
}

std::vector<std::string_view> names_of(FindingComponent component) {
    std::vector<std::string_view> names;
    for (FindingKind kind : finding_kinds_of(component))
        names.push_back(finding_kind_name(kind));
    return names;
}

TEST(FindingTest, LinkAndConfigurationRulesAreComponentsOfTheirOwn) {
    EXPECT_EQ(names_of(FindingComponent::ProfibusLink),
              (std::vector<std::string_view>{"fcs_error", "malformed_telegram", "fdl_retry",
                                             "fdl_no_response"}));
    EXPECT_EQ(names_of(FindingComponent::DpConfiguration),
              (std::vector<std::string_view>{"config_mismatch"}));
    EXPECT_EQ(names_of(FindingComponent::ParameterChannel).size(), 11u);
}

TEST(FindingTest, SimulatorFaultsAreNamedAfterTheCatalogue) {
    for (std::size_t i = 0; i < kFaultKindCount; ++i) {
        const auto fault = static_cast<FaultKind>(i);
        if (auto finding = fault_finding_kind(fault)) {
            EXPECT_EQ(fault_kind_name(fault).data(), finding_kind_name(*finding).data())
                << fault_kind_name(fault);  // the same characters, not a copy
        }
    }
}

}  // namespace
}  // namespace dpscope
