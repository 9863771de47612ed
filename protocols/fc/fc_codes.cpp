#include "protocols/fc/fc_codes.hpp"

#include <array>

namespace dpscope {

namespace {

using W = ValueWidth;
using K = ResponseKind;

constexpr FcCommand kUndefinedCommand{"Not defined", W::None, false, false};

// [S001] table 7.5; AK 4 from [P:FC300-DG-B6 p291].
constexpr std::array<FcCommand, 16> kCommands{{
    {"No command", W::None, true, false},
    {"Read parameter value", W::None, true, false},
    {"Write parameter value in RAM (word)", W::Word, true, true},
    {"Write parameter value in RAM (double word)", W::DoubleWord, true, true},
    {"Read parameter description (early FC 300)", W::None, true, false},
    kUndefinedCommand,
    kUndefinedCommand,
    kUndefinedCommand,
    kUndefinedCommand,
    kUndefinedCommand,
    kUndefinedCommand,
    kUndefinedCommand,
    kUndefinedCommand,
    {"Write parameter value in RAM and EEPROM (double word)", W::DoubleWord, true, true},
    {"Write parameter value in RAM and EEPROM (word)", W::Word, true, true},
    {"Read text", W::None, true, false},
}};

constexpr FcResponse kUndefinedResponse{"Not defined", W::None, K::Undefined};

// [S001] table 7.6; AK 3 from [P:FC300-DG-B6 p291].
constexpr std::array<FcResponse, 16> kResponses{{
    {"No response", W::None, K::None},
    {"Parameter value transferred (word)", W::Word, K::Value},
    {"Parameter value transferred (double word)", W::DoubleWord, K::Value},
    {"Description element transferred (early FC 300)", W::DoubleWord, K::Value},
    kUndefinedResponse,
    kUndefinedResponse,
    kUndefinedResponse,
    {"Command cannot be performed", W::Word, K::Rejected},
    kUndefinedResponse,
    kUndefinedResponse,
    kUndefinedResponse,
    kUndefinedResponse,
    kUndefinedResponse,
    kUndefinedResponse,
    kUndefinedResponse,
    {"Text transferred", W::None, K::Text},
}};

struct FaultEntry {
    std::uint32_t code;
    std::string_view text;
};

// [S001] table 7.7, in its wording. 100 and above 100 are printed as "–" there: no text.
constexpr FaultEntry kFaults[] = {
    {0, "Illegal parameter number"},
    {1, "Parameter cannot be changed"},
    {2, "Upper or lower limit is exceeded"},
    {3, "Subindex is corrupted"},
    {4, "No array"},
    {5, "Wrong data type"},
    {6, "Not used"},
    {7, "Not used"},
    {9, "Description element is not available"},
    {11, "No parameter write access"},
    {15, "No text available"},
    {17, "Not applicable while running"},
    {18, "Other errors"},
    {130, "No bus access for this parameter"},
    {131, "Write to factory set-up is not possible"},
    {132, "No LCP access"},
    {252, "Unknown viewer"},
    {253, "Request is not supported"},
    {254, "Unknown attribute"},
    {255, "No error"},
};

}  // namespace

const FcCommand& fc_command(std::uint8_t ak) noexcept { return kCommands[ak & 0x0F]; }
const FcResponse& fc_response(std::uint8_t ak) noexcept { return kResponses[ak & 0x0F]; }

bool fc_command_only(std::uint8_t ak) noexcept { return ak == 4 || ak == 13 || ak == 14; }
bool fc_response_only(std::uint8_t ak) noexcept { return ak == 7; }

std::string_view fc_fault_text(std::uint32_t code) noexcept {
    for (const FaultEntry& entry : kFaults)
        if (entry.code == code) return entry.text;
    return {};
}

AnswerVerdict fc_judge_answer(std::uint8_t command_ak, std::uint8_t response_ak) noexcept {
    command_ak &= 0x0F;
    response_ak &= 0x0F;
    if (command_ak == 0) return response_ak == 0 ? AnswerVerdict::Positive : AnswerVerdict::Invalid;
    if (!fc_command(command_ak).defined) return AnswerVerdict::Invalid;
    if (response_ak == 7) return AnswerVerdict::Negative;
    bool positive = false;
    switch (command_ak) {
        case 1: positive = response_ak == 1 || response_ak == 2; break;
        case 2:
        case 14: positive = response_ak == 1; break;
        case 3:
        case 13: positive = response_ak == 2; break;
        case 4: positive = response_ak == 3; break;
        case 15: positive = response_ak == 15; break;
        default: break;
    }
    return positive ? AnswerVerdict::Positive : AnswerVerdict::Invalid;
}

}  // namespace dpscope
