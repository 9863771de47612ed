// The parameter channel: reading the 8 PCV bytes, the request/response code tables of both
// dialects (seed 000 VLT 5000, seed 002 GE AF-600, docs/protocol/parameter-channel.md), RC 7 error
// numbers, the pairing rules and the worked examples (same file, "Pairing requests with
// responses", "Worked examples").
#include "core/code_tables.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "protocols/fc/fc_codes.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::hex;

Pcv pcv_of(const std::string& text) {
    auto bytes = hex(text);
    ByteReader reader(Bytes(bytes.data(), bytes.size()));
    Pcv pcv;
    EXPECT_TRUE(read_pcv(reader, kPpoPkeLayout, pcv)) << text;
    EXPECT_TRUE(reader.empty());
    return pcv;
}

// ---- read_pcv and pcv_value ------------------------------------------------------------------

TEST(CodeTablesTest, ReadPcvSplitsTheFields) {
    Pcv pcv = pcv_of("60 64 05 07 12 34 56 78");
    EXPECT_EQ(pcv.pca, 0x6064);
    EXPECT_EQ(pcv.rc, 6);
    EXPECT_FALSE(pcv.spm);
    EXPECT_EQ(pcv.pnu, 100);
    EXPECT_EQ(pcv.ind, 5);
    EXPECT_EQ(pcv.ind_low, 7);
    EXPECT_EQ(pcv.pva, 0x12345678u);
}

TEST(CodeTablesTest, ReadPcvSpmAndFullPnuRange) {
    Pcv pcv = pcv_of("FF FF 00 00 00 00 00 00");
    EXPECT_EQ(pcv.rc, 15);
    EXPECT_TRUE(pcv.spm);
    EXPECT_EQ(pcv.pnu, 2047);
    Pcv spm_only = pcv_of("08 00 00 00 00 00 00 00");
    EXPECT_EQ(spm_only.rc, 0);
    EXPECT_TRUE(spm_only.spm);
    EXPECT_EQ(spm_only.pnu, 0);
}

TEST(CodeTablesTest, ReadPcvTruncatedLeavesReaderAlone) {
    auto bytes = hex("12 08 00 00 00 00 00");
    ByteReader reader(Bytes(bytes.data(), bytes.size()));
    Pcv pcv;
    pcv.pnu = 99;
    EXPECT_FALSE(read_pcv(reader, kPpoPkeLayout, pcv));
    EXPECT_EQ(reader.position(), 0u);
    EXPECT_EQ(pcv.pnu, 99);  // untouched
    ByteReader empty(Bytes{});
    EXPECT_FALSE(read_pcv(empty, kPpoPkeLayout, pcv));
}

TEST(CodeTablesTest, ReadPcvReadsOnlyEightBytes) {
    auto bytes = hex("12 08 00 00 00 00 00 F0 0F 07 20 00");
    ByteReader reader(Bytes(bytes.data(), bytes.size()), 7);
    Pcv pcv;
    ASSERT_TRUE(read_pcv(reader, kPpoPkeLayout, pcv));
    EXPECT_EQ(reader.position(), 8u);
    EXPECT_EQ(reader.offset(), 15u);
    EXPECT_EQ(reader.u16_be(), std::optional<std::uint16_t>(0x0F07));
}

TEST(CodeTablesTest, ReadPcvFollowsTheLayout) {
    // The Danfoss FC protocol's parameter block (docs/protocol/fc-protocol.md): a 12-bit PNU, no
    // SPM bit, the index in IND's second byte: reading parameter 30-00 (PNU 3000), index 1.
    constexpr PkeLayout kFcStyle{12, std::nullopt, IndexByte::Low};
    auto bytes = hex("1B B8 00 01 00 00 00 00");
    ByteReader fc_reader(Bytes(bytes.data(), bytes.size()));
    Pcv fc;
    ASSERT_TRUE(read_pcv(fc_reader, kFcStyle, fc));
    EXPECT_EQ(fc.rc, 1);
    EXPECT_FALSE(fc.spm);  // bit 11 is part of the PNU
    EXPECT_EQ(fc.pnu, 3000);
    EXPECT_EQ(fc.ind, 1);
    EXPECT_EQ(fc.ind_low, 1);
    // The same bytes in the PPO layout: bit 11 is SPM, the PNU 11 bits, the index in byte 3.
    ByteReader ppo_reader(Bytes(bytes.data(), bytes.size()));
    Pcv ppo;
    ASSERT_TRUE(read_pcv(ppo_reader, kPpoPkeLayout, ppo));
    EXPECT_EQ(ppo.rc, 1);
    EXPECT_TRUE(ppo.spm);
    EXPECT_EQ(ppo.pnu, 952);  // 3000 without bit 11
    EXPECT_EQ(ppo.ind, 0);
    EXPECT_EQ(ppo.ind_low, 1);
}

TEST(CodeTablesTest, PcvValueByWidth) {
    Pcv pcv = pcv_of("10 01 00 00 12 34 56 78");
    EXPECT_EQ(pcv_value(pcv, ValueWidth::Word), 0x5678u);
    EXPECT_EQ(pcv_value(pcv, ValueWidth::DoubleWord), 0x12345678u);
    EXPECT_EQ(pcv_value(pcv, ValueWidth::None), 0x12345678u);
}

// ---- Worked examples -------------------------------------------------------------------------

// docs/protocol/parameter-channel.md, worked examples: read motor current (PNU 520), 2.4 A = 240.
TEST(CodeTablesTest, WorkedExampleReadMotorCurrent) {
    Pcv request = pcv_of("12 08 00 00 00 00 00 00");
    EXPECT_EQ(request.rc, 1);
    EXPECT_FALSE(request.spm);
    EXPECT_EQ(request.pnu, 520);
    EXPECT_EQ(request_code(Dialect::Vlt, request.rc).meaning, "Request parameter value");

    Pcv response = pcv_of("12 08 00 00 00 00 00 F0");
    EXPECT_EQ(response.rc, 1);
    EXPECT_FALSE(response.spm);
    EXPECT_EQ(response.pnu, 520);
    const ResponseCode& code = response_code(Dialect::Vlt, response.rc);
    EXPECT_EQ(code.width, ValueWidth::Word);
    EXPECT_EQ(pcv_value(response, code.width), 240u);
    EXPECT_EQ(judge_answer(Dialect::Vlt, request.rc, response.rc, false), AnswerVerdict::Positive);
}

// docs/protocol/contradictions.md #3: the printed spontaneous-message example contradicts the bit
// layout; it is decoded per the bit layout (parameter-channel.md, "PCA / PKE word"), not per the
// manual's intent.
TEST(CodeTablesTest, WorkedExampleSpontaneousAnomalyFollowsTheBitLayout) {
    Pcv spontaneous = pcv_of("AC 1A 00 00 00 00 00 0A");
    EXPECT_EQ(spontaneous.rc, 10);
    EXPECT_TRUE(spontaneous.spm);
    EXPECT_EQ(spontaneous.pnu, 1050);
    EXPECT_EQ(response_code(Dialect::Vlt, spontaneous.rc).kind, ResponseKind::Spontaneous);
    EXPECT_EQ(pcv_value(spontaneous, response_code(Dialect::Vlt, spontaneous.rc).width), 10u);

    Pcv acknowledge = pcv_of("1C 08 00 00 00 00 00 00");
    EXPECT_EQ(acknowledge.rc, 1);
    EXPECT_TRUE(acknowledge.spm);
    EXPECT_EQ(acknowledge.pnu, 1032);

    // What the manual meant: AA 1A = RC 10, SPM, PNU 538.
    Pcv intended = pcv_of("AA 1A 00 00 00 00 00 0A");
    EXPECT_EQ(intended.rc, 10);
    EXPECT_TRUE(intended.spm);
    EXPECT_EQ(intended.pnu, 538);
}

// parameter-channel.md, worked examples: change ramp time (PNU 207) to 1000, the answer, and a
// rejection with PNU 0.
TEST(CodeTablesTest, WorkedExamplesChangeRampTime) {
    Pcv request = pcv_of("30 CF 00 00 00 00 03 E8");
    EXPECT_EQ(request.rc, 3);
    EXPECT_FALSE(request.spm);
    EXPECT_EQ(request.pnu, 207);
    const RequestCode& change = request_code(Dialect::Vlt, request.rc);
    EXPECT_EQ(change.width, ValueWidth::DoubleWord);
    EXPECT_TRUE(change.is_change);
    EXPECT_EQ(pcv_value(request, change.width), 1000u);

    Pcv response = pcv_of("20 CF 00 00 00 00 03 E8");
    EXPECT_EQ(response.rc, 2);
    EXPECT_EQ(response.pnu, 207);
    EXPECT_EQ(pcv_value(response, response_code(Dialect::Vlt, response.rc).width), 1000u);
    EXPECT_EQ(judge_answer(Dialect::Vlt, 3, 2, true), AnswerVerdict::Positive);

    Pcv rejected = pcv_of("70 00 00 00 00 00 00 02");
    EXPECT_EQ(rejected.rc, 7);
    EXPECT_EQ(rejected.pnu, 0);
    const ResponseCode& reject = response_code(Dialect::Vlt, rejected.rc);
    EXPECT_EQ(reject.kind, ResponseKind::Rejected);
    EXPECT_EQ(pcv_value(rejected, reject.width), 2u);
    EXPECT_EQ(error_text(Dialect::Vlt, 2), "Upper or lower value passed");
    EXPECT_EQ(judge_answer(Dialect::Vlt, 3, 7, true), AnswerVerdict::Negative);
}

// ---- Request and response codes --------------------------------------------------------------

struct RequestRow {
    std::uint8_t rc;
    const char* meaning;
    ValueWidth width;
    bool defined;
    bool is_change;
    bool is_array;
};

struct ResponseRow {
    std::uint8_t rc;
    const char* meaning;
    ValueWidth width;
    ResponseKind kind;
    bool is_array;
};

using W = ValueWidth;
using K = ResponseKind;

void check_requests(Dialect dialect, const std::vector<RequestRow>& rows) {
    ASSERT_EQ(rows.size(), 16u);
    for (const RequestRow& row : rows) {
        SCOPED_TRACE(std::string(dialect_name(dialect)) + " request RC " + std::to_string(row.rc));
        const RequestCode& code = request_code(dialect, row.rc);
        EXPECT_EQ(code.meaning, row.meaning);
        EXPECT_EQ(code.width, row.width);
        EXPECT_EQ(code.defined, row.defined);
        EXPECT_EQ(code.is_change, row.is_change);
        EXPECT_EQ(code.is_array, row.is_array);
    }
}

void check_responses(Dialect dialect, const std::vector<ResponseRow>& rows) {
    ASSERT_EQ(rows.size(), 16u);
    for (const ResponseRow& row : rows) {
        SCOPED_TRACE(std::string(dialect_name(dialect)) + " response RC " + std::to_string(row.rc));
        const ResponseCode& code = response_code(dialect, row.rc);
        EXPECT_EQ(code.meaning, row.meaning);
        EXPECT_EQ(code.width, row.width);
        EXPECT_EQ(code.kind, row.kind);
        EXPECT_EQ(code.is_array, row.is_array);
    }
}

// Seed 000 "RC content / Request" (seed 002 gives the same list, "long word" for double word).
TEST(CodeTablesTest, VltRequestCodes) {
    check_requests(
        Dialect::Vlt,
        {
            {0, "No request", W::None, true, false, false},
            {1, "Request parameter value", W::None, true, false, false},
            {2, "Change parameter value (word)", W::Word, true, true, false},
            {3, "Change parameter value (double word)", W::DoubleWord, true, true, false},
            {4, "Request description element", W::None, true, false, false},
            {5, "Change description element", W::DoubleWord, true, true, false},
            {6, "Request parameter value (array)", W::None, true, false, true},
            {7, "Change parameter value (array word)", W::Word, true, true, true},
            {8, "Change parameter value (array double word)", W::DoubleWord, true, true, true},
            {9, "Request number of array elements", W::None, true, false, false},
            {10, "Not assigned", W::None, false, false, false},
            {11, "Not assigned", W::None, false, false, false},
            {12, "Not assigned", W::None, false, false, false},
            {13, "Not assigned", W::None, false, false, false},
            {14, "Not assigned", W::None, false, false, false},
            {15, "Not assigned", W::None, false, false, false},
        });
}

// Seed 000 "Response"; seed 002 marks 9-12 "not used" (the ge dialect) but the vlt dialect
// supports them (docs/protocol/contradictions.md #2).
TEST(CodeTablesTest, VltResponseCodes) {
    check_responses(
        Dialect::Vlt,
        {
            {0, "No response", W::None, K::None, false},
            {1, "Transmit parameter value (word)", W::Word, K::Value, false},
            {2, "Transmit parameter value (double word)", W::DoubleWord, K::Value, false},
            {3, "Transmit description element", W::DoubleWord, K::Value, false},
            {4, "Transmit parameter value (array word)", W::Word, K::Value, true},
            {5, "Transmit parameter value (array double word)", W::DoubleWord, K::Value, true},
            {6, "Transmit number of array elements", W::Word, K::Value, false},
            {7, "Request not executable", W::Word, K::Rejected, false},
            {8, "No operating authority for PCV interface", W::None, K::NoAuthority, false},
            {9, "Spontaneous message (word)", W::Word, K::Spontaneous, false},
            {10, "Spontaneous message (double word)", W::DoubleWord, K::Spontaneous, false},
            {11, "Spontaneous message (array word)", W::Word, K::Spontaneous, true},
            {12, "Spontaneous message (array double word)", W::DoubleWord, K::Spontaneous, true},
            {13, "Not assigned", W::None, K::Undefined, false},
            {14, "Not assigned", W::None, K::Undefined, false},
            {15, "Not assigned", W::None, K::Undefined, false},
        });
}

// Seed 002 "RC content / Request", word for word: 10-15 "Not used".
TEST(CodeTablesTest, GeRequestCodes) {
    check_requests(
        Dialect::Ge,
        {
            {0, "No request", W::None, true, false, false},
            {1, "Request parameter value", W::None, true, false, false},
            {2, "Change parameter value (word)", W::Word, true, true, false},
            {3, "Change parameter value (long word)", W::DoubleWord, true, true, false},
            {4, "Request description element", W::None, true, false, false},
            {5, "Change description element", W::DoubleWord, true, true, false},
            {6, "Request parameter value (array)", W::None, true, false, true},
            {7, "Change parameter value (array word)", W::Word, true, true, true},
            {8, "Change parameter value (array long word)", W::DoubleWord, true, true, true},
            {9, "Request number of array elements", W::None, true, false, false},
            {10, "Not used", W::None, false, false, false},
            {11, "Not used", W::None, false, false, false},
            {12, "Not used", W::None, false, false, false},
            {13, "Not used", W::None, false, false, false},
            {14, "Not used", W::None, false, false, false},
            {15, "Not used", W::None, false, false, false},
        });
}

// Seed 002 "Response": 0-8 as printed, 9-12 and 13-15 "Not used", so undefined (an
// unknown_code finding, no spontaneous message).
TEST(CodeTablesTest, GeResponseCodes) {
    check_responses(
        Dialect::Ge,
        {
            {0, "No response", W::None, K::None, false},
            {1, "Transfer parameter value (word)", W::Word, K::Value, false},
            {2, "Transfer parameter value (long word)", W::DoubleWord, K::Value, false},
            {3, "Transfer description element", W::DoubleWord, K::Value, false},
            {4, "Transfer parameter value (array word)", W::Word, K::Value, true},
            {5, "Transfer parameter value (array long word)", W::DoubleWord, K::Value, true},
            {6, "Transfer number of array elements", W::Word, K::Value, false},
            {7, "Request rejected", W::Word, K::Rejected, false},
            {8, "Not serviceable by PCV interface", W::None, K::NoAuthority, false},
            {9, "Not used", W::None, K::Undefined, false},
            {10, "Not used", W::None, K::Undefined, false},
            {11, "Not used", W::None, K::Undefined, false},
            {12, "Not used", W::None, K::Undefined, false},
            {13, "Not used", W::None, K::Undefined, false},
            {14, "Not used", W::None, K::Undefined, false},
            {15, "Not used", W::None, K::Undefined, false},
        });
    for (std::uint8_t rc = 9; rc <= 12; ++rc) {
        EXPECT_EQ(response_code(Dialect::Vlt, rc).kind, K::Spontaneous) << int{rc};
        EXPECT_EQ(judge_answer(Dialect::Ge, 1, rc, false), AnswerVerdict::Invalid) << int{rc};
    }
    EXPECT_FALSE(has_spontaneous_messages(Dialect::Ge));
    EXPECT_TRUE(has_spontaneous_messages(Dialect::Vlt));
    EXPECT_TRUE(has_spontaneous_messages(Dialect::Profidrive));
}

// docs/protocol/parameter-channel.md, "Task identifiers".
TEST(CodeTablesTest, ProfidriveRequestCodes) {
    check_requests(
        Dialect::Profidrive,
        {
            {0, "No task", W::None, true, false, false},
            {1, "Request parameter value", W::None, true, false, false},
            {2, "Change parameter value (word)", W::Word, true, true, false},
            {3, "Change parameter value (double word)", W::DoubleWord, true, true, false},
            {4, "Request descriptive element", W::None, true, false, false},
            {5, "Change descriptive element", W::DoubleWord, true, true, false},
            {6, "Request parameter value (array)", W::None, true, false, true},
            {7, "Change parameter value (array word)", W::Word, true, true, true},
            {8, "Change parameter value (array double word)", W::DoubleWord, true, true, true},
            {9, "Request number of array elements", W::None, true, false, false},
            {10, "Reserved", W::None, false, false, false},
            {11, "Change parameter value (array double word) and store in EEPROM", W::DoubleWord,
             true, true, true},
            {12, "Change parameter value (array word) and store in EEPROM", W::Word, true, true,
             true},
            {13, "Change parameter value (double word) and store in EEPROM", W::DoubleWord, true,
             true, false},
            {14, "Change parameter value (word) and store in EEPROM", W::Word, true, true, false},
            {15, "Read or change text", W::None, true, true, false},
        });
}

// docs/protocol/parameter-channel.md, "Reply identifiers".
TEST(CodeTablesTest, ProfidriveResponseCodes) {
    check_responses(
        Dialect::Profidrive,
        {
            {0, "No reply", W::None, K::None, false},
            {1, "Transfer parameter value (word)", W::Word, K::Value, false},
            {2, "Transfer parameter value (double word)", W::DoubleWord, K::Value, false},
            {3, "Transfer descriptive element", W::DoubleWord, K::Value, false},
            {4, "Transfer parameter value (array word)", W::Word, K::Value, true},
            {5, "Transfer parameter value (array double word)", W::DoubleWord, K::Value, true},
            {6, "Transfer number of array elements", W::Word, K::Value, false},
            {7, "Request cannot be executed", W::Word, K::Rejected, false},
            {8, "No master authority for the PKW interface", W::None, K::NoAuthority, false},
            {9, "Parameter change report (word)", W::Word, K::Spontaneous, false},
            {10, "Parameter change report (double word)", W::DoubleWord, K::Spontaneous, false},
            {11, "Parameter change report (array word)", W::Word, K::Spontaneous, true},
            {12, "Parameter change report (array double word)", W::DoubleWord, K::Spontaneous,
             true},
            {13, "Reserved", W::None, K::Undefined, false},
            {14, "Reserved", W::None, K::Undefined, false},
            {15, "Transfer text", W::None, K::Text, false},
        });
}

TEST(CodeTablesTest, CodesAboveFifteenUseTheLowNibble) {
    EXPECT_EQ(&request_code(Dialect::Vlt, 0x12), &request_code(Dialect::Vlt, 2));
    EXPECT_EQ(&response_code(Dialect::Profidrive, 0xF7), &response_code(Dialect::Profidrive, 7));
}

TEST(CodeTablesTest, CorruptedPcvWithUndefinedCode) {
    Pcv pcv = pcv_of("D0 01 00 00 00 00 00 00");
    EXPECT_EQ(pcv.rc, 13);
    EXPECT_EQ(response_code(Dialect::Vlt, pcv.rc).kind, ResponseKind::Undefined);
    EXPECT_FALSE(request_code(Dialect::Vlt, pcv.rc).defined);
    EXPECT_EQ(response_code(Dialect::Profidrive, pcv.rc).kind, ResponseKind::Undefined);
    EXPECT_TRUE(request_code(Dialect::Profidrive, pcv.rc).defined);
}

// ---- Error numbers ---------------------------------------------------------------------------

// Seed 000 (0..19, wording verbatim: "2 Upper or lower value passed"); nothing else, not even
// GE's 130/131 (the ge dialect's).
TEST(CodeTablesTest, VltErrorNumbers) {
    const std::vector<std::pair<int, std::string>> errors = {
        {0, "Improper PNU"},
        {1, "Parameter value not changeable"},
        {2, "Upper or lower value passed"},
        {3, "Faulty subindex"},
        {4, "No array"},
        {5, "Wrong data type"},
        {6, "Setting not permitted (resettable only)"},
        {7, "Description element not changeable"},
        {8, "No PPO-Write for IR"},
        {9, "Description data not available"},
        {10, "Access group"},
        {11, "No parameter operating authority"},
        {12, "Keyword missing"},
        {13, "Text not readable in cyclical traffic"},
        {14, "Name not readable in cyclical traffic"},
        {15, "Text array not available"},
        {16, "PPO-Write missing"},
        {17, "Request temporarily unexecutable"},
        {18, "Other error"},
        {19, "Data not readable in cyclical traffic"},
    };
    std::set<int> defined;
    for (const auto& [number, text] : errors) {
        SCOPED_TRACE("vlt error " + std::to_string(number));
        EXPECT_EQ(error_text(Dialect::Vlt, static_cast<std::uint16_t>(number)), text);
        EXPECT_EQ(error_text_or_unknown(Dialect::Vlt, static_cast<std::uint16_t>(number)), text);
        defined.insert(number);
    }
    for (int number = 0; number < 300; ++number) {
        if (defined.count(number)) continue;
        EXPECT_EQ(error_text(Dialect::Vlt, static_cast<std::uint16_t>(number)), "")
            << "vlt error " << number;
        EXPECT_EQ(error_text_or_unknown(Dialect::Vlt, static_cast<std::uint16_t>(number)),
                  "unknown error number")
            << "vlt error " << number;
    }
    EXPECT_EQ(error_text(Dialect::Vlt, 0xFFFF), "");
    EXPECT_EQ(error_text(Dialect::Vlt, 130), "");
    EXPECT_EQ(error_text(Dialect::Vlt, 131), "");
    EXPECT_EQ(error_text_or_unknown(Dialect::Vlt, 130), "unknown error number");
}

// Seed 002 "Fault no. / Interpretation", word for word: 0..19, 130, 131.
TEST(CodeTablesTest, GeErrorNumbers) {
    const std::vector<std::pair<int, std::string>> errors = {
        {0, "Illegal PNU"},
        {1, "Parameter value cannot be changed"},
        {2, "Upper or lower limit exceeded"},
        {3, "Subindex corrupted"},
        {4, "No array"},
        {5, "Data type false"},
        {6, "Cannot be set by user (reset only)"},
        {7, "Description element cannot be changed"},
        {8, "IR required PPO-write not available"},
        {9, "Description data not available"},
        {10, "Access group"},
        {11, "No parameter write access"},
        {12, "Key word missing"},
        {13, "Text in cyclical transmission not readable"},
        {14, "Name in cyclical transmission not readable"},
        {15, "Text array not available"},
        {16, "PPO-write missing"},
        {17, "Request temporarily rejected"},
        {18, "Other fault"},
        {19, "Data in cyclical transmission not readable"},
        {130, "There is no network access to the parameter called"},
        {131, "Data change is not possible because factory setup has been selected"},
    };
    std::set<int> defined;
    for (const auto& [number, text] : errors) {
        SCOPED_TRACE("ge error " + std::to_string(number));
        EXPECT_EQ(error_text(Dialect::Ge, static_cast<std::uint16_t>(number)), text);
        defined.insert(number);
    }
    for (int number = 0; number < 300; ++number) {
        if (defined.count(number)) continue;
        EXPECT_EQ(error_text(Dialect::Ge, static_cast<std::uint16_t>(number)), "")
            << "ge error " << number;
        EXPECT_EQ(error_text_or_unknown(Dialect::Ge, static_cast<std::uint16_t>(number)),
                  "unknown error number")
            << "ge error " << number;
    }
    EXPECT_EQ(error_text(Dialect::Ge, 0xFFFF), "");
}

// docs/protocol/parameter-channel.md, "Error numbers (PWE 2 with AK 7)": 0..24 and the
// manufacturer numbers 101..107, 200, 201, 204.
TEST(CodeTablesTest, ProfidriveErrorNumbers) {
    const std::vector<std::pair<int, std::string>> errors = {
        {0, "Illegal parameter number"},
        {1, "Parameter value cannot be changed"},
        {2, "Upper or lower limit exceeded"},
        {3, "Faulty subindex"},
        {4, "No array"},
        {5, "Wrong data type"},
        {6, "Setting not allowed (reset only)"},
        {7, "Descriptive element cannot be changed"},
        {8, "PPO-Write requested in IR not available"},
        {9, "Description data not available"},
        {10, "Access group wrong"},
        {11, "No operating (change) rights"},
        {12, "Keyword (password) missing"},
        {13, "Text not readable in cyclic transfer"},
        {14, "Name not readable in cyclic transfer"},
        {15, "Text array not available"},
        {16, "PPO-Write missing"},
        {17, "Request cannot be executed in the current operating state"},
        {18, "Other error"},
        {19, "Data not readable in cyclic transfer"},
        {20, "Illegal value"},
        {21, "Response too long"},
        {22, "Illegal parameter address"},
        {23, "Illegal format"},
        {24, "Number of values inconsistent"},
        {101, "Parameter number currently deactivated (manufacturer)"},
        {102, "Channel width too small (manufacturer)"},
        {103, "Incorrect number of PKWs (manufacturer)"},
        {104, "Parameter value not permitted (manufacturer)"},
        {105, "Parameter is indexed (manufacturer)"},
        {106, "Task not implemented (manufacturer)"},
        {107, "No write access while controller enabled (manufacturer)"},
        {200, "Modified minimum not reached (manufacturer)"},
        {201, "Modified maximum exceeded (manufacturer)"},
        {204, "Access level does not allow change (manufacturer)"},
    };
    std::set<int> defined;
    for (const auto& [number, text] : errors) {
        SCOPED_TRACE("profidrive error " + std::to_string(number));
        EXPECT_EQ(error_text(Dialect::Profidrive, static_cast<std::uint16_t>(number)), text);
        defined.insert(number);
    }
    for (int number = 0; number < 300; ++number) {
        if (defined.count(number)) continue;
        EXPECT_EQ(error_text(Dialect::Profidrive, static_cast<std::uint16_t>(number)), "")
            << "profidrive error " << number;
    }
}

TEST(CodeTablesTest, ErrorNumbersDependOnTheDialect) {
    // GE/Danfoss 130 is not a PROFIdrive number; PROFIdrive 20 is not a VLT number.
    EXPECT_EQ(error_text(Dialect::Profidrive, 130), "");
    EXPECT_EQ(error_text(Dialect::Vlt, 20), "");
    EXPECT_EQ(error_text(Dialect::Vlt, 101), "");
    EXPECT_EQ(error_text(Dialect::Ge, 20), "");
    EXPECT_EQ(error_text(Dialect::Ge, 101), "");
}

// ---- Pairing (docs/protocol/parameter-channel.md) ----------------------------------------------

// The pairing table of docs/protocol/parameter-channel.md written out independently of the
// implementation.
AnswerVerdict expected_verdict(Dialect dialect, int request, int response, bool strict) {
    bool profidrive = dialect == Dialect::Profidrive;
    bool ge = dialect == Dialect::Ge;  // responses 9..12 "not used"
    bool request_defined =
        (request >= 0 && request <= 9) || (profidrive && request >= 11 && request <= 15);
    bool response_defined =
        (response >= 0 && response <= (ge ? 8 : 12)) || (profidrive && response == 15);
    if (!request_defined || !response_defined) return AnswerVerdict::Invalid;
    const std::vector<std::set<int>> positive = {
        {0}, {1, 2}, {1}, {2}, {3}, {3}, {4, 5}, {4}, {5}, {6}, {}, {5}, {4}, {2}, {1}, {15},
    };
    if (positive[static_cast<std::size_t>(request)].count(response)) return AnswerVerdict::Positive;
    if (request == 0) return AnswerVerdict::Invalid;
    if (response == 7) return AnswerVerdict::Negative;
    if (response == 8) {
        const std::set<int> change = {2, 3, 5, 7, 8, 11, 12, 13, 14, 15};
        if (change.count(request)) return AnswerVerdict::Negative;
        return strict ? AnswerVerdict::Invalid : AnswerVerdict::Unusual;
    }
    return AnswerVerdict::Invalid;
}

TEST(CodeTablesTest, JudgeAnswerMatchesThePairingTableForEveryCode) {
    for (Dialect dialect : {Dialect::Vlt, Dialect::Ge, Dialect::Profidrive}) {
        for (int strict = 0; strict < 2; ++strict) {
            for (int request = 0; request < 16; ++request) {
                for (int response = 0; response < 16; ++response) {
                    EXPECT_EQ(judge_answer(dialect, static_cast<std::uint8_t>(request),
                                           static_cast<std::uint8_t>(response), strict != 0),
                              expected_verdict(dialect, request, response, strict != 0))
                        << dialect_name(dialect) << " request " << request << " response "
                        << response << (strict ? " strict" : " lenient");
                }
            }
        }
    }
}

TEST(CodeTablesTest, JudgeAnswerNamedCases) {
    // Read answered with word or double word.
    EXPECT_EQ(judge_answer(Dialect::Vlt, 1, 1, false), AnswerVerdict::Positive);
    EXPECT_EQ(judge_answer(Dialect::Vlt, 1, 2, false), AnswerVerdict::Positive);
    EXPECT_EQ(judge_answer(Dialect::Vlt, 1, 3, false), AnswerVerdict::Invalid);
    // RC 8 after a read: unusual when lenient, invalid when strict.
    for (int code : {1, 4, 6, 9}) {
        auto read = static_cast<std::uint8_t>(code);
        EXPECT_EQ(judge_answer(Dialect::Vlt, read, 8, false), AnswerVerdict::Unusual);
        EXPECT_EQ(judge_answer(Dialect::Vlt, read, 8, true), AnswerVerdict::Invalid);
        EXPECT_EQ(judge_answer(Dialect::Profidrive, read, 8, false), AnswerVerdict::Unusual);
        EXPECT_EQ(judge_answer(Dialect::Profidrive, read, 8, true), AnswerVerdict::Invalid);
    }
    // RC 8 after a change: negative either way.
    EXPECT_EQ(judge_answer(Dialect::Vlt, 2, 8, true), AnswerVerdict::Negative);
    EXPECT_EQ(judge_answer(Dialect::Profidrive, 14, 8, true), AnswerVerdict::Negative);
    EXPECT_EQ(judge_answer(Dialect::Profidrive, 15, 8, true), AnswerVerdict::Negative);
    // RC 7 answers every request.
    for (std::uint8_t request = 1; request <= 9; ++request) {
        EXPECT_EQ(judge_answer(Dialect::Vlt, request, 7, true), AnswerVerdict::Negative);
        EXPECT_EQ(judge_answer(Dialect::Profidrive, request, 7, true), AnswerVerdict::Negative);
    }
    for (std::uint8_t request = 11; request <= 15; ++request)
        EXPECT_EQ(judge_answer(Dialect::Profidrive, request, 7, true), AnswerVerdict::Negative);
    // RC 0: no request, no response.
    EXPECT_EQ(judge_answer(Dialect::Vlt, 0, 0, true), AnswerVerdict::Positive);
    EXPECT_EQ(judge_answer(Dialect::Profidrive, 0, 0, true), AnswerVerdict::Positive);
    EXPECT_EQ(judge_answer(Dialect::Vlt, 0, 1, false), AnswerVerdict::Invalid);
    EXPECT_EQ(judge_answer(Dialect::Vlt, 1, 0, false), AnswerVerdict::Invalid);
    // Spontaneous messages are not answers.
    EXPECT_EQ(judge_answer(Dialect::Vlt, 1, 9, false), AnswerVerdict::Invalid);
    EXPECT_EQ(judge_answer(Dialect::Vlt, 3, 10, false), AnswerVerdict::Invalid);
    // Profidrive-only request codes.
    EXPECT_EQ(judge_answer(Dialect::Profidrive, 11, 5, true), AnswerVerdict::Positive);
    EXPECT_EQ(judge_answer(Dialect::Profidrive, 12, 4, true), AnswerVerdict::Positive);
    EXPECT_EQ(judge_answer(Dialect::Profidrive, 13, 2, true), AnswerVerdict::Positive);
    EXPECT_EQ(judge_answer(Dialect::Profidrive, 14, 1, true), AnswerVerdict::Positive);
    EXPECT_EQ(judge_answer(Dialect::Profidrive, 15, 15, true), AnswerVerdict::Positive);
    EXPECT_EQ(judge_answer(Dialect::Vlt, 14, 1, false), AnswerVerdict::Invalid);
    EXPECT_EQ(judge_answer(Dialect::Vlt, 15, 15, false), AnswerVerdict::Invalid);
    // Arrays.
    EXPECT_EQ(judge_answer(Dialect::Vlt, 6, 4, true), AnswerVerdict::Positive);
    EXPECT_EQ(judge_answer(Dialect::Vlt, 6, 5, true), AnswerVerdict::Positive);
    EXPECT_EQ(judge_answer(Dialect::Vlt, 7, 5, true), AnswerVerdict::Invalid);
    EXPECT_EQ(judge_answer(Dialect::Vlt, 9, 6, true), AnswerVerdict::Positive);
}

TEST(CodeTablesTest, DialectNames) {
    EXPECT_EQ(dialect_name(Dialect::Vlt), "vlt");
    EXPECT_EQ(dialect_name(Dialect::Profidrive), "profidrive");
    EXPECT_EQ(dialect_name(Dialect::Ge), "ge");
    EXPECT_EQ(dialect_from_name("vlt"), Dialect::Vlt);
    EXPECT_EQ(dialect_from_name("profidrive"), Dialect::Profidrive);
    EXPECT_EQ(dialect_from_name("ge"), Dialect::Ge);
    EXPECT_EQ(dialect_from_name("GE"), std::nullopt);
    EXPECT_EQ(kDialectNameList, "vlt, ge, profidrive");
    for (Dialect dialect : kDialects)
        EXPECT_EQ(dialect_from_name(dialect_name(dialect)), dialect);
    EXPECT_TRUE(danfoss_family(Dialect::Vlt));
    EXPECT_TRUE(danfoss_family(Dialect::Ge));
    EXPECT_FALSE(danfoss_family(Dialect::Profidrive));
    EXPECT_EQ(dialect_from_name("VLT"), std::nullopt);
    EXPECT_EQ(dialect_from_name(""), std::nullopt);
    EXPECT_EQ(dialect_from_name("fc"), std::nullopt);
}

TEST(CodeTablesTest, FcTablesAreTheFcCodes) {
    EXPECT_EQ(dialect_name(Dialect::Fc), "fc");
    EXPECT_FALSE(dialect_from_name("fc").has_value());  // no --dialect of a PROFIBUS slave
    for (Dialect dialect : kDialects)
        EXPECT_NE(dialect, Dialect::Fc);
    for (std::uint8_t ak = 0; ak < 16; ++ak) {
        EXPECT_EQ(request_code(Dialect::Fc, ak).meaning, fc_command(ak).meaning) << int(ak);
        EXPECT_EQ(request_code(Dialect::Fc, ak).defined, fc_command(ak).defined) << int(ak);
        EXPECT_EQ(request_code(Dialect::Fc, ak).is_change, fc_command(ak).is_change) << int(ak);
        EXPECT_EQ(response_code(Dialect::Fc, ak).kind, fc_response(ak).kind) << int(ak);
        for (std::uint8_t answer = 0; answer < 16; ++answer)
            EXPECT_EQ(judge_answer(Dialect::Fc, ak, answer, false), fc_judge_answer(ak, answer));
    }
    // Every command but "no command" has its index checked in the answer.
    EXPECT_FALSE(request_code(Dialect::Fc, 0).is_array);
    EXPECT_TRUE(request_code(Dialect::Fc, 1).is_array);
    EXPECT_EQ(response_code(Dialect::Fc, 7).kind, ResponseKind::Rejected);
    EXPECT_EQ(error_text(Dialect::Fc, 2), "Upper or lower limit is exceeded");
    EXPECT_EQ(error_text_or_unknown(Dialect::Fc, 100), kUnknownFaultCode);
    EXPECT_FALSE(has_spontaneous_messages(Dialect::Fc));
    EXPECT_EQ(code_label(Dialect::Fc), "AK");
    EXPECT_EQ(code_label(Dialect::Vlt), "RC");
    EXPECT_EQ(error_label(Dialect::Fc), "fault code");
    EXPECT_EQ(error_label(Dialect::Profidrive), "error");
}

}  // namespace
}  // namespace dpscope
