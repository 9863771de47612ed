// The dissector's registration table: the ids of dissector_fields.hpp and their registration.
#include "wireshark/dissector_fields.hpp"

#include <fmt/format.h>

#include <deque>
#include <string>
#include <vector>

namespace dpscope::wireshark {

#define DPSCOPE_FIELD_ID(id, name, abbrev, type, display, blurb) int hf_##id = -1;
DPSCOPE_FIELDS(DPSCOPE_FIELD_ID)
#undef DPSCOPE_FIELD_ID

int hf_ctw_bit[16];
int hf_stw_bit[16];

int ett[kEttCount];

expert_field ei_problem[kProblemKindCount];
expert_field ei_finding[kFindingKindCount][3];

namespace {

// Names and texts registered with Wireshark must live as long as the program.
std::deque<std::string>& kept_strings() {
    static std::deque<std::string> strings;
    return strings;
}
const char* keep(std::string text) { return kept_strings().emplace_back(std::move(text)).c_str(); }

int expert_severity(Severity severity) {
    switch (severity) {
        case Severity::Error: return PI_ERROR;
        case Severity::Warning: return PI_WARN;
        case Severity::Note: break;
    }
    return PI_NOTE;
}

int problem_group(ProblemKind kind) {
    switch (kind) {
        case ProblemKind::FcsMismatch:
        case ProblemKind::BccMismatch:
        case ProblemKind::Vlt2000ChecksumMismatch: return PI_CHECKSUM;
        default: return PI_MALFORMED;
    }
}

int finding_group(FindingKind kind) {
    switch (kind) {
        case FindingKind::FcsError:
        case FindingKind::FcBccError:
        case FindingKind::Vlt2000ChecksumError:
        case FindingKind::Vlt2000ChecksumDisabled: return PI_CHECKSUM;
        case FindingKind::MalformedTelegram: return PI_MALFORMED;
        case FindingKind::RequestRejected:
        case FindingKind::NoAuthority:
        case FindingKind::Dpv1NegativeResponse:
        case FindingKind::Dpv1ErrorPdu:
        case FindingKind::FcCommandRejected:
        case FindingKind::Vlt2000CommandFailed: return PI_RESPONSE_CODE;
        case FindingKind::ConfigMismatch:
        case FindingKind::UnknownCode:
        case FindingKind::Dpv1UnknownCode: return PI_PROTOCOL;
        default: return PI_SEQUENCE;
    }
}

}  // namespace

void register_fields(int protocol) {
    static std::vector<hf_register_info> fields;
#define DPSCOPE_FIELD_INFO(id, name, abbrev, type, display, blurb) \
    fields.push_back({&hf_##id, {name, abbrev, type, display, NULL, 0, blurb, HFILL}});
    DPSCOPE_FIELDS(DPSCOPE_FIELD_INFO)
#undef DPSCOPE_FIELD_INFO
    for (int bit = 0; bit < 16; ++bit) {
        fields.push_back(
            {&hf_ctw_bit[bit],
             {keep(fmt::format("CTW bit {}", bit)), keep(fmt::format("dpscope.pcd.ctw.bit{}", bit)),
              FT_BOOLEAN, BASE_NONE, NULL, 0, "A control word bit (PCD 1, VLT 2000 word)", HFILL}});
        fields.push_back(
            {&hf_stw_bit[bit],
             {keep(fmt::format("STW bit {}", bit)), keep(fmt::format("dpscope.pcd.stw.bit{}", bit)),
              FT_BOOLEAN, BASE_NONE, NULL, 0, "A status word bit (PCD 1, VLT 2000 word)", HFILL}});
    }
    proto_register_field_array(protocol, fields.data(), static_cast<int>(fields.size()));

    static gint* subtrees[kEttCount];
    for (int i = 0; i < kEttCount; ++i) {
        ett[i] = -1;
        subtrees[i] = &ett[i];
    }
    proto_register_subtree_array(subtrees, kEttCount);

    static std::vector<ei_register_info> experts;
    for (const ProblemKindInfo& info : problem_catalogue()) {
        experts.push_back(
            {&ei_problem[static_cast<std::size_t>(info.kind)],
             {keep(fmt::format("dpscope.problem.{}", info.name)), problem_group(info.kind),
              expert_severity(info.severity), keep(std::string(info.check)), EXPFILL}});
    }
    for (const FindingKindInfo& info : finding_catalogue()) {
        // One expert info per severity, all three with the kind's plain name, so that
        // `dpscope.finding.KIND` selects every finding of the kind: a kind's severity can depend
        // on what the telegram says (dpv1_error_pdu: a warning or a note by its error class).
        // The kind's default severity is registered last: Wireshark's severity table
        // (expert_severity_levels) finds a name's last registration.
        const char* abbrev = keep(fmt::format("dpscope.finding.{}", info.name));
        std::vector<Severity> severities;
        for (Severity severity : {Severity::Note, Severity::Warning, Severity::Error})
            if (severity != info.severity) severities.push_back(severity);
        severities.push_back(info.severity);
        for (Severity severity : severities)
            experts.push_back({&ei_finding[static_cast<std::size_t>(info.kind)]
                                          [static_cast<std::size_t>(severity)],
                               {abbrev, finding_group(info.kind), expert_severity(severity),
                                keep(std::string(info.rule)), EXPFILL}});
    }
    expert_module_t* expert = expert_register_protocol(protocol);
    expert_register_field_array(expert, experts.data(), static_cast<int>(experts.size()));
}

}  // namespace dpscope::wireshark
