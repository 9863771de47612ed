// DP management payloads: Slave_Diag with extended diagnosis, Set_Prm (DP-V0 and DP-V1),
// Chk_Cfg identifiers (compact and special format), Global_Control and Set_Slave_Add.
#include "protocols/profibus/dp_payload.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::hex;

ByteReader reader_of(const std::vector<std::uint8_t>& bytes, std::size_t base = 0) {
    return ByteReader(Bytes(bytes.data(), bytes.size()), base);
}

std::vector<std::uint8_t> copy(Bytes bytes) { return {bytes.begin(), bytes.end()}; }

std::vector<CfgModule> cfg(const std::vector<std::uint8_t>& bytes, ProblemList& problems,
                           bool* ok = nullptr) {
    std::vector<CfgModule> modules;
    bool result = parse_cfg(reader_of(bytes, 9), modules, problems);
    if (ok) *ok = result;
    return modules;
}

// ---- Slave_Diag ------------------------------------------------------------------------------

TEST(DpPayloadTest, SlaveDiagFixedPart) {
    auto du = hex("02 05 00 FF 04 02");
    ProblemList problems;
    auto diag = parse_slave_diag(reader_of(du, 8), problems);
    ASSERT_TRUE(diag);
    EXPECT_TRUE(problems.empty());
    EXPECT_EQ(diag->station_status_1, 0x02);
    EXPECT_EQ(diag->station_status_2, 0x05);
    EXPECT_EQ(diag->station_status_3, 0x00);
    EXPECT_EQ(diag->master_address, kNoMasterAddress);
    EXPECT_EQ(diag->ident, 0x0402);
    EXPECT_TRUE(diag->extended.empty());
    EXPECT_EQ(diag->extended_offset, 14);
}

TEST(DpPayloadTest, SlaveDiagWithExtendedDiagnosis) {
    auto du = hex("0C 0C 00 02 04 02  03 AA BB  42 01  81 42 A6  C5");
    ProblemList problems;
    auto diag = parse_slave_diag(reader_of(du, 9), problems);
    ASSERT_TRUE(diag);
    EXPECT_EQ(diag->station_status_1 & kDiagCfgFault, kDiagCfgFault);
    EXPECT_EQ(diag->station_status_1 & kDiagExtDiag, kDiagExtDiag);
    EXPECT_EQ(diag->station_status_2 & kDiagWatchdogOn, kDiagWatchdogOn);
    EXPECT_EQ(diag->station_status_2 & kDiagAlwaysOne, kDiagAlwaysOne);
    EXPECT_EQ(diag->master_address, 2);
    EXPECT_EQ(diag->extended_offset, 15);
    EXPECT_EQ(copy(diag->extended), hex("03 AA BB 42 01 81 42 A6 C5"));

    std::vector<DiagBlock> blocks;
    parse_extended_diag(ByteReader(diag->extended, diag->extended_offset), blocks, problems);
    EXPECT_TRUE(problems.empty());
    ASSERT_EQ(blocks.size(), 4u);

    EXPECT_EQ(blocks[0].type, DiagBlockType::Device);
    EXPECT_EQ(blocks[0].offset, 15);
    EXPECT_EQ(copy(blocks[0].data), hex("AA BB"));

    EXPECT_EQ(blocks[1].type, DiagBlockType::Identifier);
    EXPECT_EQ(blocks[1].offset, 18);
    EXPECT_EQ(copy(blocks[1].data), hex("01"));

    EXPECT_EQ(blocks[2].type, DiagBlockType::Channel);
    EXPECT_EQ(blocks[2].offset, 20);
    EXPECT_EQ(blocks[2].module, 1);
    EXPECT_EQ(blocks[2].io, 1);  // input
    EXPECT_EQ(blocks[2].channel, 2);
    EXPECT_EQ(blocks[2].channel_type, 5);  // word
    EXPECT_EQ(blocks[2].error_type, 6);    // line break
    EXPECT_EQ(channel_type_text(blocks[2].channel_type), "word");
    EXPECT_EQ(channel_error_text(blocks[2].error_type), "line break");

    EXPECT_EQ(blocks[3].type, DiagBlockType::Revision);
    EXPECT_EQ(blocks[3].offset, 23);
    EXPECT_EQ(blocks[3].revision, 5);
}

TEST(DpPayloadTest, SlaveDiagTruncated) {
    auto du = hex("02 05 00 FF 04");
    ProblemList problems;
    EXPECT_FALSE(parse_slave_diag(reader_of(du, 9), problems));
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_EQ(problems[0].kind, ProblemKind::ServiceDataShort);
    EXPECT_EQ(problems[0].offset, 9);
    EXPECT_EQ(problems[0].expected, 6u);
    EXPECT_EQ(problems[0].actual, 5u);
}

TEST(DpPayloadTest, ExtendedDiagBlockLongerThanDataIsTruncated) {
    // Device block announces 5 bytes (header included) but only 3 are there.
    auto ext = hex("42 01 05 AA BB");
    ProblemList problems;
    std::vector<DiagBlock> blocks;
    parse_extended_diag(reader_of(ext, 15), blocks, problems);
    ASSERT_EQ(blocks.size(), 2u);
    EXPECT_EQ(blocks[0].type, DiagBlockType::Identifier);
    EXPECT_EQ(blocks[1].type, DiagBlockType::Device);
    EXPECT_EQ(copy(blocks[1].data), hex("AA BB"));  // what is there is kept
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_EQ(problems[0].kind, ProblemKind::DiagBlockTruncated);
    EXPECT_EQ(problems[0].offset, 17);
    EXPECT_EQ(problems[0].expected, 5u);
    EXPECT_EQ(problems[0].actual, 3u);
}

TEST(DpPayloadTest, ChannelBlockCutOffIsReportedAndDropped) {
    auto ext = hex("C1 83 05");
    ProblemList problems;
    std::vector<DiagBlock> blocks;
    parse_extended_diag(reader_of(ext, 20), blocks, problems);
    ASSERT_EQ(blocks.size(), 1u);
    EXPECT_EQ(blocks[0].type, DiagBlockType::Revision);
    EXPECT_EQ(blocks[0].revision, 1);
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_EQ(problems[0].kind, ProblemKind::DiagBlockTruncated);
    EXPECT_EQ(problems[0].offset, 21);
    EXPECT_EQ(problems[0].expected, 3u);
    EXPECT_EQ(problems[0].actual, 2u);
}

TEST(DpPayloadTest, ChannelBlockOutputAndInputOutput) {
    auto ext = hex("83 81 21  BF FF 3F");
    ProblemList problems;
    std::vector<DiagBlock> blocks;
    parse_extended_diag(reader_of(ext), blocks, problems);
    EXPECT_TRUE(problems.empty());
    ASSERT_EQ(blocks.size(), 2u);
    EXPECT_EQ(blocks[0].module, 3);
    EXPECT_EQ(blocks[0].io, 2);  // output
    EXPECT_EQ(blocks[0].channel, 1);
    EXPECT_EQ(blocks[0].channel_type, 1);  // bit
    EXPECT_EQ(blocks[0].error_type, 1);    // short circuit
    EXPECT_EQ(blocks[1].module, 63);
    EXPECT_EQ(blocks[1].io, 3);
    EXPECT_EQ(blocks[1].channel, 63);
    EXPECT_EQ(blocks[1].channel_type, 1);
    EXPECT_EQ(blocks[1].error_type, 31);
}

TEST(DpPayloadTest, DiagTextTables) {
    EXPECT_EQ(channel_error_text(1), "short circuit");
    EXPECT_EQ(channel_error_text(2), "undervoltage");
    EXPECT_EQ(channel_error_text(3), "overvoltage");
    EXPECT_EQ(channel_error_text(4), "overload");
    EXPECT_EQ(channel_error_text(5), "overtemperature");
    EXPECT_EQ(channel_error_text(7), "upper limit value exceeded");
    EXPECT_EQ(channel_error_text(8), "lower limit value exceeded");
    EXPECT_EQ(channel_error_text(9), "error");
    EXPECT_EQ(channel_error_text(0), "reserved");
    EXPECT_EQ(channel_error_text(15), "reserved");
    EXPECT_EQ(channel_error_text(16), "manufacturer-specific");
    EXPECT_EQ(channel_type_text(1), "bit");
    EXPECT_EQ(channel_type_text(2), "2 bits");
    EXPECT_EQ(channel_type_text(3), "4 bits");
    EXPECT_EQ(channel_type_text(4), "byte");
    EXPECT_EQ(channel_type_text(6), "2 words");
    EXPECT_EQ(channel_type_text(0), "reserved");
    EXPECT_EQ(channel_type_text(7), "reserved");
    EXPECT_EQ(dpv1_alarm_or_status_text(0x01), "diagnostic alarm");
    EXPECT_EQ(dpv1_alarm_or_status_text(0x02), "process alarm");
    EXPECT_EQ(dpv1_alarm_or_status_text(0x06), "update alarm");
    EXPECT_EQ(dpv1_alarm_or_status_text(0x20), "manufacturer-specific alarm");
    EXPECT_EQ(dpv1_alarm_or_status_text(0x07), "reserved alarm");
    EXPECT_EQ(dpv1_alarm_or_status_text(0x81), "status message");
    EXPECT_EQ(dpv1_alarm_or_status_text(0x82), "module status");
    EXPECT_EQ(dpv1_alarm_or_status_text(0xA0), "manufacturer-specific status");
    EXPECT_EQ(dpv1_alarm_or_status_text(0x83), "DXB_Link_Status");  // was "reserved status"
    EXPECT_EQ(diag_block_type_name(DiagBlockType::Device), "device-related");
    EXPECT_EQ(diag_block_type_name(DiagBlockType::Channel), "channel-related");
    EXPECT_EQ(diag_block_type_name(DiagBlockType::Identifier), "identifier-related");
}

// Channel-related I/O type, bits 7..6 of the channel byte: 00 is reserved, not input/output.
TEST(DpPayloadTest, ChannelIoTypes) {
    EXPECT_EQ(channel_io_text(0), "reserved I/O type");
    EXPECT_EQ(channel_io_text(1), "input");
    EXPECT_EQ(channel_io_text(2), "output");
    EXPECT_EQ(channel_io_text(3), "input/output");
    auto du = hex("81 02 A6  81 C2 A6");  // module 1, channel 2, I/O type 00 then 11
    ProblemList problems;
    std::vector<DiagBlock> blocks;
    parse_extended_diag(reader_of(du, 15), blocks, problems);
    EXPECT_TRUE(problems.empty());
    ASSERT_EQ(blocks.size(), 2u);
    EXPECT_EQ(blocks[0].io, 0);
    EXPECT_EQ(channel_io_text(blocks[0].io), "reserved I/O type");
    EXPECT_EQ(blocks[0].channel, 2);
    EXPECT_EQ(blocks[1].io, 3);
    EXPECT_EQ(channel_io_text(blocks[1].io), "input/output");
}

// DP-V1 alarm types (bit 7 clear) and status types (bit 7 set).
TEST(DpPayloadTest, Dpv1AlarmAndStatusTypes) {
    const std::vector<std::pair<int, std::string>> alarms = {
        {0, "reserved alarm"},
        {1, "diagnostic alarm"},
        {2, "process alarm"},
        {3, "pull alarm"},
        {4, "plug alarm"},
        {5, "status alarm"},
        {6, "update alarm"},
        {7, "reserved alarm"},
        {31, "reserved alarm"},
        {32, "manufacturer-specific alarm"},
        {126, "manufacturer-specific alarm"},
        {127, "reserved alarm"},
    };
    for (const auto& [code, text] : alarms)
        EXPECT_EQ(dpv1_alarm_or_status_text(static_cast<std::uint8_t>(code)), text) << code;
    const std::vector<std::pair<int, std::string>> statuses = {
        {0, "reserved status"},
        {1, "status message"},
        {2, "module status"},
        {3, "DXB_Link_Status"},
        {4, "reserved status"},
        {29, "reserved status"},
        {30, "PrmCmdAck"},
        {31, "Red_State"},
        {32, "manufacturer-specific status"},
        {126, "manufacturer-specific status"},
        {127, "reserved status"},
    };
    for (const auto& [code, text] : statuses)
        EXPECT_EQ(dpv1_alarm_or_status_text(static_cast<std::uint8_t>(0x80 | code)), text) << code;
}

TEST(DpPayloadTest, StationStatusFlagTables) {
    auto s1 = station_status_1_flags();
    ASSERT_EQ(s1.size(), 8u);
    EXPECT_EQ(s1[2].mask, 0x04);
    EXPECT_EQ(s1[2].name, "Cfg_Fault");
    EXPECT_EQ(s1[6].mask, 0x40);
    EXPECT_EQ(s1[6].name, "Prm_Fault");
    auto s2 = station_status_2_flags();
    ASSERT_EQ(s2.size(), 8u);
    EXPECT_EQ(s2[0].name, "Prm_Req");
    EXPECT_EQ(s2[3].mask, kDiagWatchdogOn);
    auto s3 = station_status_3_flags();
    ASSERT_EQ(s3.size(), 1u);
    EXPECT_EQ(s3[0].mask, 0x80);
    EXPECT_EQ(s3[0].name, "Ext_Diag_Overflow");
}

// ---- Set_Prm ---------------------------------------------------------------------------------

TEST(DpPayloadTest, SetPrmDpV0) {
    auto du = hex("88 0A 0A 0B 04 02 00");
    ProblemList problems;
    auto prm = parse_set_prm(reader_of(du, 9), problems);
    ASSERT_TRUE(prm);
    EXPECT_TRUE(problems.empty());
    EXPECT_EQ(prm->station_status, 0x88);
    EXPECT_TRUE(prm->watchdog_on());
    EXPECT_EQ(prm->wd_fact_1, 10);
    EXPECT_EQ(prm->wd_fact_2, 10);
    EXPECT_EQ(prm->watchdog_ms(), 1000u);  // 10 x 10 x 10 ms
    EXPECT_EQ(prm->min_tsdr, 11);
    EXPECT_EQ(prm->ident, 0x0402);
    EXPECT_EQ(prm->group_ident, 0);
    EXPECT_FALSE(prm->has_dpv1_status);
    EXPECT_TRUE(prm->user_prm.empty());
    EXPECT_EQ(prm->user_prm_offset, 16);
}

TEST(DpPayloadTest, SetPrmDpV1StatusDetected) {
    auto du = hex("B8 05 14 0B 04 02 01  80 01 08  11 22");
    ProblemList problems;
    auto prm = parse_set_prm(reader_of(du, 9), problems);
    ASSERT_TRUE(prm);
    EXPECT_TRUE(prm->has_dpv1_status);
    EXPECT_EQ(prm->dpv1_status[0], 0x80);
    EXPECT_EQ(prm->dpv1_status[1], 0x01);
    EXPECT_EQ(prm->dpv1_status[2], 0x08);
    EXPECT_EQ(copy(prm->user_prm), hex("11 22"));
    EXPECT_EQ(prm->user_prm_offset, 19);
    EXPECT_EQ(prm->group_ident, 1);
    EXPECT_EQ(prm->watchdog_ms(), 1000u);  // 5 x 20 x 10 ms
}

TEST(DpPayloadTest, SetPrmWatchdogBase1ms) {
    auto du = hex("88 05 14 0B 04 02 00  84 00 00");
    ProblemList problems;
    auto prm = parse_set_prm(reader_of(du), problems);
    ASSERT_TRUE(prm);
    ASSERT_TRUE(prm->has_dpv1_status);
    EXPECT_EQ(prm->watchdog_ms(), 100u);  // 5 x 20 x 1 ms
    // The same bytes may be a DP-V0 slave's User_Prm_Data: the 10 ms reading is kept too.
    EXPECT_TRUE(prm->watchdog_base_uncertain());
    EXPECT_EQ(prm->watchdog_ms_10ms_base(), 1000u);
    EXPECT_TRUE(prm->dpv1_enabled());  // 0x84: DPV1_Enable and WD_Base_1ms
}

TEST(DpPayloadTest, SetPrmWatchdogHasOneReadingWithoutWdBase1ms) {
    for (const char* du : {"88 05 14 0B 04 02 00 80 00 00",  // DP-V1 status, 10 ms base
                           "88 05 14 0B 04 02 00 85 00 00",  // reserved bit: User_Prm_Data
                           "88 05 14 0B 04 02 00 84 00",     // too few user bytes
                           "88 05 14 0B 04 02 00"}) {
        SCOPED_TRACE(du);
        ProblemList problems;
        auto prm = parse_set_prm(reader_of(hex(du)), problems);
        ASSERT_TRUE(prm);
        EXPECT_FALSE(prm->watchdog_base_uncertain());
        EXPECT_EQ(prm->watchdog_ms(), 1000u);
        EXPECT_EQ(prm->watchdog_ms_10ms_base(), 1000u);
    }
}

TEST(DpPayloadTest, SetPrmDpv1Enable) {
    ProblemList problems;
    EXPECT_TRUE(
        parse_set_prm(reader_of(hex("88 05 14 0B 04 02 00 80 00 00")), problems)->dpv1_enabled());
    EXPECT_FALSE(
        parse_set_prm(reader_of(hex("88 05 14 0B 04 02 00 00 00 00")), problems)->dpv1_enabled());
    EXPECT_FALSE(parse_set_prm(reader_of(hex("88 05 14 0B 04 02 00 81 00 00")), problems)
                     ->dpv1_enabled());  // reserved bit: not DP-V1 status bytes
    EXPECT_FALSE(parse_set_prm(reader_of(hex("88 05 14 0B 04 02 00 80")), problems)
                     ->dpv1_enabled());  // too short
    EXPECT_TRUE(problems.empty());
}

// DPV1_Status_3: Alarm_Mode in bits 2..0, Prm_Structure, IsoM_Req, PrmCmd (bit 7).
TEST(DpPayloadTest, Dpv1Status3AlarmModeAndPrmCmd) {
    const char* modes[] = {"1 alarm of each type", "2 alarms in total",  "4 alarms in total",
                           "8 alarms in total",    "12 alarms in total", "16 alarms in total",
                           "24 alarms in total",   "32 alarms in total"};
    for (std::uint8_t mode = 0; mode < 8; ++mode)
        EXPECT_EQ(dpv1_alarm_mode_text(static_cast<std::uint8_t>(0x98 | mode)), modes[mode]);
    auto flags = dpv1_status_3_flags();
    ASSERT_EQ(flags.size(), 3u);
    EXPECT_EQ(flags[0].mask, 0x08);
    EXPECT_EQ(flags[0].name, "Prm_Structure");
    EXPECT_EQ(flags[1].mask, 0x10);
    EXPECT_EQ(flags[1].name, "IsoM_Req");
    EXPECT_EQ(flags[2].mask, 0x80);
    EXPECT_EQ(flags[2].name, "PrmCmd");
    // PrmCmd and an Alarm_Mode are no reserved bits: the bytes still read as DP-V1 status.
    ProblemList problems;
    auto prm = parse_set_prm(reader_of(hex("88 05 14 0B 04 02 00 80 00 87")), problems);
    ASSERT_TRUE(prm);
    EXPECT_TRUE(prm->has_dpv1_status);
    EXPECT_EQ(prm->dpv1_status[2], 0x87);
}

TEST(DpPayloadTest, SetPrmWithReservedBitsIsNotDpV1) {
    // Status byte 1 bit 0, status byte 2 bit 1 and status byte 3 bit 5 are reserved.
    for (const char* user : {"81 00 00 33", "80 02 00 33", "80 00 20 33", "80 00 40 33"}) {
        SCOPED_TRACE(user);
        auto du = hex("88 01 01 0B 04 02 00");
        auto extra = hex(user);
        du.insert(du.end(), extra.begin(), extra.end());
        ProblemList problems;
        auto prm = parse_set_prm(reader_of(du), problems);
        ASSERT_TRUE(prm);
        EXPECT_FALSE(prm->has_dpv1_status);
        EXPECT_EQ(copy(prm->user_prm), extra);
        EXPECT_EQ(prm->user_prm_offset, 7);
        EXPECT_EQ(prm->watchdog_ms(), 10u);
    }
}

TEST(DpPayloadTest, SetPrmWithFewerThanThreeUserBytesIsNotDpV1) {
    auto du = hex("88 01 01 0B 04 02 00 80 00");
    ProblemList problems;
    auto prm = parse_set_prm(reader_of(du), problems);
    ASSERT_TRUE(prm);
    EXPECT_FALSE(prm->has_dpv1_status);
    EXPECT_EQ(copy(prm->user_prm), hex("80 00"));
}

TEST(DpPayloadTest, SetPrmWatchdogOffFlag) {
    auto du = hex("00 01 01 0B 04 02 00");
    ProblemList problems;
    auto prm = parse_set_prm(reader_of(du), problems);
    ASSERT_TRUE(prm);
    EXPECT_FALSE(prm->watchdog_on());
}

TEST(DpPayloadTest, SetPrmTruncated) {
    auto du = hex("88 0A 0A 0B 04 02");
    ProblemList problems;
    EXPECT_FALSE(parse_set_prm(reader_of(du, 9), problems));
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_EQ(problems[0].kind, ProblemKind::ServiceDataShort);
    EXPECT_EQ(problems[0].offset, 9);
    EXPECT_EQ(problems[0].expected, 7u);
    EXPECT_EQ(problems[0].actual, 6u);
}

TEST(DpPayloadTest, SetPrmFlagTables) {
    auto station = set_prm_station_flags();
    ASSERT_EQ(station.size(), 5u);
    EXPECT_EQ(station[0].mask, 0x08);
    EXPECT_EQ(station[0].name, "WD_On");
    EXPECT_EQ(station[4].mask, 0x80);
    EXPECT_EQ(station[4].name, "Lock_Req");
    auto s1 = dpv1_status_1_flags();
    ASSERT_EQ(s1.size(), 4u);
    EXPECT_EQ(s1[0].mask, 0x04);
    EXPECT_EQ(s1[0].name, "WD_Base_1ms");
    EXPECT_EQ(s1[3].mask, 0x80);
    EXPECT_EQ(s1[3].name, "DPV1_Enable");
    auto s2 = dpv1_status_2_flags();
    ASSERT_FALSE(s2.empty());
    EXPECT_EQ(s2[0].mask, 0x01);
    EXPECT_EQ(s2[0].name, "Chk_Cfg_Mode");
    auto s3 = dpv1_status_3_flags();
    ASSERT_EQ(s3.size(), 3u);  // Alarm_Mode (bits 2..0) is a number: dpv1_alarm_mode_text
    EXPECT_EQ(s3[0].name, "Prm_Structure");
    EXPECT_EQ(s3[2].name, "PrmCmd");
}

// ---- Chk_Cfg / Get_Cfg -----------------------------------------------------------------------

TEST(DpPayloadTest, CompactIdentifiersPpo1) {
    ProblemList problems;
    bool ok = false;
    auto modules = cfg(hex("F3 F1"), problems, &ok);
    EXPECT_TRUE(ok);
    EXPECT_TRUE(problems.empty());
    ASSERT_EQ(modules.size(), 2u);
    const CfgModule& pkw = modules[0];
    EXPECT_EQ(pkw.offset, 9);
    EXPECT_EQ(pkw.identifier, 0xF3);
    EXPECT_FALSE(pkw.special);
    EXPECT_FALSE(pkw.free_place);
    EXPECT_EQ(pkw.direction, CfgDirection::InputOutput);
    EXPECT_EQ(pkw.input_units, 4);
    EXPECT_EQ(pkw.output_units, 4);
    EXPECT_TRUE(pkw.input_words);
    EXPECT_TRUE(pkw.output_words);
    EXPECT_TRUE(pkw.input_consistent);
    EXPECT_TRUE(pkw.output_consistent);
    EXPECT_EQ(pkw.input_bytes(), 8);
    EXPECT_EQ(pkw.output_bytes(), 8);
    EXPECT_EQ(modules[1].offset, 10);
    EXPECT_EQ(modules[1].input_bytes(), 4);
    EXPECT_EQ(modules[1].output_bytes(), 4);
}

TEST(DpPayloadTest, CompactIdentifierBitFields) {
    ProblemList problems;
    // 71: word-consistent 2 words in/out; 13: 4 input bytes; 2F: 16 output bytes; B7: 8 bytes
    // in/out consistent; E3: 4 output words consistent; D3: 4 input words consistent.
    auto modules = cfg(hex("71 13 2F B7 E3 D3"), problems);
    ASSERT_EQ(modules.size(), 6u);
    EXPECT_FALSE(modules[0].input_consistent);
    EXPECT_TRUE(modules[0].input_words);
    EXPECT_EQ(modules[0].input_bytes(), 4);

    EXPECT_EQ(modules[1].direction, CfgDirection::Input);
    EXPECT_EQ(modules[1].input_bytes(), 4);
    EXPECT_EQ(modules[1].output_bytes(), 0);
    EXPECT_FALSE(modules[1].input_words);

    EXPECT_EQ(modules[2].direction, CfgDirection::Output);
    EXPECT_EQ(modules[2].output_units, 16);
    EXPECT_EQ(modules[2].output_bytes(), 16);
    EXPECT_EQ(modules[2].input_bytes(), 0);

    EXPECT_EQ(modules[3].direction, CfgDirection::InputOutput);
    EXPECT_FALSE(modules[3].input_words);
    EXPECT_TRUE(modules[3].input_consistent);
    EXPECT_EQ(modules[3].input_bytes(), 8);
    EXPECT_EQ(modules[3].output_bytes(), 8);

    EXPECT_EQ(modules[4].direction, CfgDirection::Output);
    EXPECT_EQ(modules[4].output_bytes(), 8);
    EXPECT_EQ(modules[4].input_bytes(), 0);
    EXPECT_TRUE(modules[4].output_consistent);

    EXPECT_EQ(modules[5].direction, CfgDirection::Input);
    EXPECT_EQ(modules[5].input_bytes(), 8);
    EXPECT_EQ(modules[5].output_bytes(), 0);
}

TEST(DpPayloadTest, SpecialFormatPkwC0C3C3) {
    ProblemList problems;
    bool ok = false;
    auto modules = cfg(hex("C0 C3 C3 F1"), problems, &ok);
    EXPECT_TRUE(ok);
    ASSERT_EQ(modules.size(), 2u);
    const CfgModule& pkw = modules[0];
    EXPECT_TRUE(pkw.special);
    EXPECT_FALSE(pkw.free_place);
    EXPECT_EQ(pkw.direction, CfgDirection::InputOutput);
    EXPECT_EQ(pkw.manufacturer_bytes, 0);
    EXPECT_EQ(pkw.output_units, 4);
    EXPECT_EQ(pkw.input_units, 4);
    EXPECT_TRUE(pkw.output_words);
    EXPECT_TRUE(pkw.input_consistent);
    EXPECT_EQ(pkw.output_bytes(), 8);
    EXPECT_EQ(pkw.input_bytes(), 8);
    EXPECT_EQ(modules[1].offset, 12);
    EXPECT_EQ(modules[1].identifier, 0xF1);
}

TEST(DpPayloadTest, SpecialFormatOutputFirstThenInput) {
    // C0 with output 3 words (42) and input 5 bytes (04).
    ProblemList problems;
    auto modules = cfg(hex("C0 42 04"), problems);
    ASSERT_EQ(modules.size(), 1u);
    EXPECT_EQ(modules[0].output_bytes(), 6);
    EXPECT_TRUE(modules[0].output_words);
    EXPECT_FALSE(modules[0].output_consistent);
    EXPECT_EQ(modules[0].input_bytes(), 5);
    EXPECT_FALSE(modules[0].input_words);
}

TEST(DpPayloadTest, SpecialFormatSingleDirectionAndLongLengths) {
    ProblemList problems;
    // 80: output length byte only (BF = 64 bytes consistent); 40: input length byte only (7F =
    // 64 words).
    auto modules = cfg(hex("80 BF 40 7F"), problems);
    ASSERT_EQ(modules.size(), 2u);
    EXPECT_EQ(modules[0].direction, CfgDirection::Output);
    EXPECT_EQ(modules[0].output_units, 64);
    EXPECT_EQ(modules[0].output_bytes(), 64);
    EXPECT_TRUE(modules[0].output_consistent);
    EXPECT_EQ(modules[0].input_bytes(), 0);
    EXPECT_EQ(modules[1].direction, CfgDirection::Input);
    EXPECT_EQ(modules[1].input_bytes(), 128);
    EXPECT_EQ(modules[1].output_bytes(), 0);
}

TEST(DpPayloadTest, FreePlaceAndManufacturerBytes) {
    ProblemList problems;
    bool ok = false;
    // 00 free place; 43: input length byte 05 (6 bytes) + 3 manufacturer bytes; 02: no length
    // bytes, 2 manufacturer bytes; 21: 2 output bytes.
    auto modules = cfg(hex("00 43 05 AA BB CC 02 DD EE 21"), problems, &ok);
    EXPECT_TRUE(ok);
    EXPECT_TRUE(problems.empty());
    ASSERT_EQ(modules.size(), 4u);
    EXPECT_TRUE(modules[0].special);
    EXPECT_TRUE(modules[0].free_place);
    EXPECT_EQ(modules[0].direction, CfgDirection::None);
    EXPECT_EQ(modules[0].input_bytes(), 0);
    EXPECT_EQ(modules[0].output_bytes(), 0);

    EXPECT_TRUE(modules[1].special);
    EXPECT_FALSE(modules[1].free_place);
    EXPECT_EQ(modules[1].offset, 10);
    EXPECT_EQ(modules[1].manufacturer_bytes, 3);
    EXPECT_EQ(modules[1].direction, CfgDirection::Input);
    EXPECT_EQ(modules[1].input_bytes(), 6);
    EXPECT_EQ(modules[1].output_bytes(), 0);

    EXPECT_EQ(modules[2].offset, 15);
    EXPECT_EQ(modules[2].manufacturer_bytes, 2);
    EXPECT_FALSE(modules[2].free_place);
    EXPECT_EQ(modules[2].direction, CfgDirection::None);
    EXPECT_EQ(modules[2].input_bytes(), 0);

    EXPECT_EQ(modules[3].offset, 18);
    EXPECT_EQ(modules[3].direction, CfgDirection::Output);
    EXPECT_EQ(modules[3].output_bytes(), 2);
}

TEST(DpPayloadTest, SpecialIdentifierTruncatedKeepsEarlierModules) {
    ProblemList problems;
    bool ok = true;
    auto modules = cfg(hex("F1 C0 C3"), problems, &ok);
    EXPECT_FALSE(ok);
    ASSERT_EQ(modules.size(), 1u);
    EXPECT_EQ(modules[0].identifier, 0xF1);
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_EQ(problems[0].kind, ProblemKind::CfgIdentifierTruncated);
    EXPECT_EQ(problems[0].offset, 10);
    EXPECT_EQ(problems[0].expected, 2u);
    EXPECT_EQ(problems[0].actual, 1u);
}

TEST(DpPayloadTest, ManufacturerBytesMissingIsTruncated) {
    // 45 announces an input length byte and 5 manufacturer bytes; only 3 bytes follow.
    ProblemList problems;
    bool ok = true;
    auto modules = cfg(hex("45 01 AA BB"), problems, &ok);
    EXPECT_FALSE(ok);
    EXPECT_TRUE(modules.empty());
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_EQ(problems[0].kind, ProblemKind::CfgIdentifierTruncated);
    EXPECT_EQ(problems[0].offset, 9);
    EXPECT_EQ(problems[0].expected, 6u);
    EXPECT_EQ(problems[0].actual, 3u);
}

TEST(DpPayloadTest, EmptyConfigurationHasNoModules) {
    ProblemList problems;
    bool ok = false;
    auto modules = cfg({}, problems, &ok);
    EXPECT_TRUE(ok);
    EXPECT_TRUE(modules.empty());
    EXPECT_TRUE(problems.empty());
}

TEST(DpPayloadTest, CfgDirectionNames) {
    EXPECT_EQ(cfg_direction_name(CfgDirection::None), "-");
    EXPECT_EQ(cfg_direction_name(CfgDirection::Input), "in");
    EXPECT_EQ(cfg_direction_name(CfgDirection::Output), "out");
    EXPECT_EQ(cfg_direction_name(CfgDirection::InputOutput), "in/out");
}

// ---- Global_Control and Set_Slave_Add --------------------------------------------------------

TEST(DpPayloadTest, GlobalControl) {
    auto du = hex("08 01");
    ProblemList problems;
    auto gc = parse_global_control(reader_of(du, 9), problems);
    ASSERT_TRUE(gc);
    EXPECT_TRUE(problems.empty());
    EXPECT_EQ(gc->command, 0x08);
    EXPECT_EQ(gc->group_select, 0x01);
    auto flags = global_control_flags();
    ASSERT_EQ(flags.size(), 5u);
    EXPECT_EQ(flags[0].mask, 0x02);
    EXPECT_EQ(flags[0].name, "Clear_Data");
    EXPECT_EQ(flags[2].mask, 0x08);
    EXPECT_EQ(flags[2].name, "Freeze");
    EXPECT_EQ(flags[4].mask, 0x20);
    EXPECT_EQ(flags[4].name, "Sync");
}

TEST(DpPayloadTest, GlobalControlTruncated) {
    auto du = hex("08");
    ProblemList problems;
    EXPECT_FALSE(parse_global_control(reader_of(du, 9), problems));
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_EQ(problems[0].kind, ProblemKind::ServiceDataShort);
    EXPECT_EQ(problems[0].offset, 9);
    EXPECT_EQ(problems[0].expected, 2u);
    EXPECT_EQ(problems[0].actual, 1u);
}

TEST(DpPayloadTest, SetSlaveAdd) {
    auto du = hex("05 04 02 01 AA BB");
    ProblemList problems;
    auto ssa = parse_set_slave_add(reader_of(du, 9), problems);
    ASSERT_TRUE(ssa);
    EXPECT_TRUE(problems.empty());
    EXPECT_EQ(ssa->new_address, 5);
    EXPECT_EQ(ssa->ident, 0x0402);
    EXPECT_EQ(ssa->no_add_chg, 1);
    EXPECT_EQ(copy(ssa->rem_slave_data), hex("AA BB"));
}

TEST(DpPayloadTest, SetSlaveAddTruncated) {
    auto du = hex("05 04 02");
    ProblemList problems;
    EXPECT_FALSE(parse_set_slave_add(reader_of(du, 9), problems));
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_EQ(problems[0].kind, ProblemKind::ServiceDataShort);
    EXPECT_EQ(problems[0].expected, 4u);
    EXPECT_EQ(problems[0].actual, 3u);
    EXPECT_EQ(problem_message(problems[0]), "byte 9: service data has 3 bytes, needs at least 4");
}

}  // namespace
}  // namespace dpscope
