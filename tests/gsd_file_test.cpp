// The GSD parser (protocols/profibus/gsd/gsd_file.hpp) on device descriptions written for these
// tests: a made-up drive "TD-7" of a made-up vendor, in the project's own words. Every keyword
// dpscope reads, comments and continuation lines, case-insensitive keywords, 8-bit text, and
// broken files with FILE:LINE messages.
#include "protocols/profibus/gsd/gsd_file.hpp"

#include <gtest/gtest.h>

#include <string>

namespace dpscope {
namespace {

// A complete description: the header may follow any text; comments after ';'.
constexpr std::string_view kTestDrive = R"gsd(Device description written for dpscope's tests.
#Profibus_DP
GSD_Revision        = 4
Vendor_Name         = "Test Works"      ; not a real vendor
Model_Name          = "TD-7 drive"
Revision            = "1.0"
Ident_Number        = 0x0C7D
Protocol_Ident      = 0                 ; read by nobody: skipped
Station_Type        = 0
Slave_Family        = 1@Drives@TD
DPV1_Slave          = 1
MaxTsdr_9.6         = 60
MaxTsdr_1.5M        = 150
maxtsdr_12m         = 800               ; keywords in any case
Min_Slave_Intervall = 5
Modular_Station     = 1
Max_Module          = 2
Max_Input_Len       = 28
Max_Output_Len      = 28
Max_Data_Len        = 56
Max_Diag_Data_Len   = 16
User_Prm_Data_Len   = 3
Max_User_Prm_Data_Len = 3
Unit_Diag_Type      = 0

PrmText = 1
Text(0) = "stop"
Text(1) = "run; not a comment"
EndPrmText

ExtUserPrmData = 1 "Start mode"
Bit(2) 0 0-1
Prm_Text_Ref = 1
EndExtUserPrmData

ExtUserPrmData = 2 "Ramp"
Unsigned8 10 1-100
Changeable = 1
EndExtUserPrmData

ExtUserPrmData = 3 "Cycle"
Unsigned8 4 1,2,4,8
EndExtUserPrmData

Ext_User_Prm_Data_Const(0) = 0x00, 0x0A, 0x04
Ext_User_Prm_Data_Ref(0) = 1
Ext_User_Prm_Data_Ref(1) = 2
Ext_User_Prm_Data_Ref(2) = 3

Unit_Diag_Bit(16) = "Motor too hot"
Unit_Diag_Bit(17) = "Mains phase lost"
Unit_Diag_Area = 24-27
Value(0) = "no fault"
Value(3) = "ground fault"
Unit_Diag_Area_End

Module = "PPO 1 (4 PKW, 2 PZD)" 0xF3,0xF1
1
EndModule
Module = "PPO 3 (2 PZD) with a name long enough to be continued" \
         0xF1
2
Ext_User_Prm_Data_Const(0) = 0x01
EndModule
)gsd";

GsdDevice parsed(std::string_view text, std::string_view file = "td7.gsd") {
    Result<GsdDevice> device = parse_gsd(text, file);
    EXPECT_TRUE(device) << device.error();
    return device ? std::move(device).value() : GsdDevice{};
}

TEST(GsdFileTest, ReadsTheDevicesIdentityAndLimits) {
    const GsdDevice d = parsed(kTestDrive);
    EXPECT_EQ(d.file, "td7.gsd");
    EXPECT_EQ(d.gsd_revision, 4u);
    EXPECT_EQ(d.vendor, "Test Works");
    EXPECT_EQ(d.model, "TD-7 drive");
    EXPECT_EQ(d.revision, "1.0");
    EXPECT_EQ(d.ident_number, 0x0C7D);
    EXPECT_EQ(d.slave_family, "1@Drives@TD");
    EXPECT_TRUE(d.dpv1_slave);
    EXPECT_TRUE(d.modular_station);
    EXPECT_EQ(d.max_module, 2u);
    EXPECT_EQ(d.max_input_len, 28u);
    EXPECT_EQ(d.max_output_len, 28u);
    EXPECT_EQ(d.max_data_len, 56u);
    EXPECT_EQ(d.max_diag_data_len, 16u);
    EXPECT_EQ(d.user_prm_data_len, 3u);
    EXPECT_EQ(d.max_user_prm_data_len, 3u);
    EXPECT_EQ(d.min_slave_interval, 5u);
    EXPECT_EQ(d.unit_diag_type, 0u);
    EXPECT_EQ(d.max_tsdr_at("9.6"), 60u);
    EXPECT_EQ(d.max_tsdr_at("1.5M"), 150u);
    EXPECT_EQ(d.max_tsdr_at("12M"), 800u);  // written "maxtsdr_12m"
    EXPECT_EQ(d.max_tsdr_at("3M"), std::nullopt);
    EXPECT_EQ(d.keywords_skipped, 3u);  // Protocol_Ident, Station_Type, Changeable
}

TEST(GsdFileTest, ReadsUserParametersWithTheirTexts) {
    const GsdDevice d = parsed(kTestDrive);
    ASSERT_EQ(d.prm_texts.size(), 1u);
    const GsdPrmText* texts = d.prm_text(1);
    ASSERT_NE(texts, nullptr);
    ASSERT_EQ(texts->texts.size(), 2u);
    EXPECT_EQ(texts->texts[1].value, 1);
    EXPECT_EQ(texts->texts[1].text, "run; not a comment");  // ';' inside a string stays

    ASSERT_EQ(d.user_prms.size(), 3u);
    const GsdUserPrm* start = d.user_prm(1);
    ASSERT_NE(start, nullptr);
    EXPECT_EQ(start->name, "Start mode");
    EXPECT_EQ(start->type, GsdDataType::Bit);
    EXPECT_EQ(start->first_bit, 2);
    EXPECT_EQ(start->last_bit, 2);
    EXPECT_EQ(start->default_value, 0);
    EXPECT_EQ(start->max_value, 1);
    EXPECT_EQ(start->text_reference, 1u);
    const GsdUserPrm* ramp = d.user_prm(2);
    ASSERT_NE(ramp, nullptr);
    EXPECT_EQ(ramp->type, GsdDataType::Unsigned8);
    EXPECT_EQ(ramp->default_value, 10);
    EXPECT_EQ(ramp->min_value, 1);
    EXPECT_EQ(ramp->max_value, 100);
    EXPECT_TRUE(ramp->allowed.empty());
    const GsdUserPrm* cycle = d.user_prm(3);
    ASSERT_NE(cycle, nullptr);
    EXPECT_EQ(cycle->allowed, (std::vector<std::int64_t>{1, 2, 4, 8}));

    ASSERT_EQ(d.prm_consts.size(), 1u);
    EXPECT_EQ(d.prm_consts[0].offset, 0u);
    EXPECT_EQ(d.prm_consts[0].bytes, (std::vector<std::uint8_t>{0x00, 0x0A, 0x04}));
    ASSERT_EQ(d.prm_refs.size(), 3u);
    EXPECT_EQ(d.prm_refs[2].offset, 2u);
    EXPECT_EQ(d.prm_refs[2].reference, 3u);
}

TEST(GsdFileTest, ReadsModulesAndContinuedLines) {
    const GsdDevice d = parsed(kTestDrive);
    ASSERT_EQ(d.modules.size(), 2u);
    EXPECT_EQ(d.modules[0].name, "PPO 1 (4 PKW, 2 PZD)");
    EXPECT_EQ(d.modules[0].config, (std::vector<std::uint8_t>{0xF3, 0xF1}));
    EXPECT_EQ(d.modules[0].number, 1u);
    EXPECT_EQ(d.modules[1].name, "PPO 3 (2 PZD) with a name long enough to be continued");
    EXPECT_EQ(d.modules[1].config, (std::vector<std::uint8_t>{0xF1}));
    EXPECT_EQ(d.modules[1].number, 2u);
    ASSERT_EQ(d.modules[1].prm_consts.size(), 1u);
    EXPECT_EQ(d.modules[1].prm_consts[0].bytes, (std::vector<std::uint8_t>{0x01}));
    EXPECT_GT(d.modules[1].line, d.modules[0].line);
}

TEST(GsdFileTest, ReadsDiagnosisTexts) {
    const GsdDevice d = parsed(kTestDrive);
    ASSERT_EQ(d.unit_diag_bits.size(), 2u);
    EXPECT_EQ(d.unit_diag_bits[0].value, 16);
    EXPECT_EQ(d.unit_diag_bits[0].text, "Motor too hot");
    ASSERT_EQ(d.unit_diag_areas.size(), 1u);
    EXPECT_EQ(d.unit_diag_areas[0].first_bit, 24u);
    EXPECT_EQ(d.unit_diag_areas[0].last_bit, 27u);
    ASSERT_EQ(d.unit_diag_areas[0].values.size(), 2u);
    EXPECT_EQ(d.unit_diag_areas[0].values[1].value, 3);
    EXPECT_EQ(d.unit_diag_areas[0].values[1].text, "ground fault");
}

// Language variants are written in 8-bit code pages: ISO 8859-1 / Windows-1252 bytes become
// UTF-8; a file that is valid UTF-8 is read as it is. CR LF line ends are read as LF.
TEST(GsdFileTest, EightBitTextIsShownAsUtf8) {
    const std::string latin1 =
        "#Profibus_DP\r\nVendor_Name = \"M\xFC"
        "ller \x80\"\r\n"
        "Model_Name = \"Antrieb f\xFCr L\xFC"
        "fter\"\r\n";
    const GsdDevice d = parsed(latin1, "td7.gsg");
    EXPECT_EQ(d.vendor, "M\xC3\xBCller \xE2\x82\xAC");  // u-umlaut, euro sign (0x80 in 1252)
    EXPECT_EQ(d.model,
              "Antrieb f\xC3\xBCr L\xC3\xBC"
              "fter");
    const std::string utf8 = "#Profibus_DP\nModel_Name = \"Entra\xC3\xAEnement\"\n";
    EXPECT_EQ(parsed(utf8).model, "Entra\xC3\xAEnement");
}

TEST(GsdFileTest, BrokenFilesNameTheFileAndLine) {
    struct Case {
        std::string_view text;
        std::string_view message;
    };
    const Case cases[] = {
        {"GSD_Revision = 1\n", "bad.gsd:1: no \"#Profibus_DP\" line: not a PROFIBUS DP GSD file"},
        {"#Profibus_DP\nIdent_Number = 0xZZ\n", "bad.gsd:2: Ident_Number: '0xZZ' is not a number"},
        {"#Profibus_DP\nIdent_Number = 0x12345\n", "bad.gsd:2: Ident_Number: 74565 is not 16 bits"},
        {"#Profibus_DP\n\nModule = \"M\" 0xF1\n1\n",
         "bad.gsd:3: Module \"M\" has no EndModule "
         "before the file ends"},
        {"#Profibus_DP\nModule = \"M\" 0x1F1\nEndModule\n", "bad.gsd:2: Module: 497 is not a byte"},
        {"#Profibus_DP\nVendor_Name = \"open\n",
         "bad.gsd:2: a string is not closed (no '\"' "
         "before the line ends)"},
        {"#Profibus_DP\nPrmText = 1\nText(0) = \"a\"\n",
         "bad.gsd:2: PrmText 1 has no EndPrmText "
         "before the file ends"},
        {"#Profibus_DP\nExtUserPrmData = 4 \"x\"\nEndExtUserPrmData\n",
         "bad.gsd:3: ExtUserPrmData 4: no data type line before EndExtUserPrmData"},
        {"#Profibus_DP\nExtUserPrmData = 4 \"x\"\nBit(9) 0 0-1\n",
         "bad.gsd:3: Bit(9): a byte has bits 0 to 7"},
        {"#Profibus_DP\nExtUserPrmData = 4 \"x\"\nUnsigned8 3 9-2\n",
         "bad.gsd:3: Unsigned8: 9-2 is no range (the first is larger)"},
        {"#Profibus_DP\nUnit_Diag_Bit = \"x\"\n",
         "bad.gsd:2: Unit_Diag_Bit: the bit number in parentheses is missing"},
        {"#Profibus_DP\nUnit_Diag_Area = 9-3\nUnit_Diag_Area_End\n",
         "bad.gsd:2: Unit_Diag_Area: 9-3 is no range of bits"},
    };
    for (const Case& c : cases) {
        Result<GsdDevice> d = parse_gsd(c.text, "bad.gsd");
        ASSERT_FALSE(d) << c.text;
        EXPECT_EQ(d.error(), c.message) << c.text;
    }
}

TEST(GsdFileTest, UnknownKeywordsAndEmptyInputs) {
    const GsdDevice d = parsed("#profibus_dp\nSome_Future_Keyword = 7\nX_Thing(3) = \"y\"\n");
    EXPECT_EQ(d.keywords_skipped, 2u);
    EXPECT_TRUE(d.modules.empty());
    EXPECT_FALSE(parse_gsd("", "empty.gsd"));
    // A continuation at the very end and a lone backslash line do not break the parse.
    EXPECT_TRUE(parse_gsd("#Profibus_DP\nModel_Name = \"a\" \\\n", "x.gsd"));
    EXPECT_TRUE(parse_gsd(std::string_view("#Profibus_DP\n\0\n", 15), "nul.gsd"));
}

}  // namespace
}  // namespace dpscope
