// DP services: requests classified from the telegram, responses without their request classified
// from their SAPs, and the SAP and service names.
#include "protocols/profibus/dp_service.hpp"

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "protocols/profibus/telegram_builder.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::hex;

FdlTelegram parse(const std::vector<std::uint8_t>& bytes) {
    FdlTelegram t;
    parse_fdl(Bytes(bytes.data(), bytes.size()), t);
    return t;
}

// A master (2) -> slave (3) request with optional SAPs.
FdlTelegram request(std::optional<std::uint8_t> dsap, std::optional<std::uint8_t> ssap,
                    const std::vector<std::uint8_t>& du = {},
                    FdlFunction function = FdlFunction::SrdHigh, std::uint8_t da = 3) {
    TelegramSpec spec;
    spec.da = da;
    spec.sa = 2;
    spec.fc = request_fc(function, true, true);
    spec.dsap = dsap;
    spec.ssap = ssap;
    spec.du = Bytes(du.data(), du.size());
    return parse(build_telegram(spec));
}

// A slave (3) -> master (2) response with optional SAPs.
FdlTelegram response(std::optional<std::uint8_t> dsap, std::optional<std::uint8_t> ssap,
                     const std::vector<std::uint8_t>& du = {}) {
    TelegramSpec spec;
    spec.da = 2;
    spec.sa = 3;
    spec.fc = response_fc(FdlStatus::DataLow);
    spec.dsap = dsap;
    spec.ssap = ssap;
    spec.du = Bytes(du.data(), du.size());
    return parse(build_telegram(spec));
}

TEST(DpServiceTest, ServiceNamesAreStable) {
    const std::vector<std::pair<Service, std::string>> names = {
        {Service::Unknown, "Unknown"},
        {Service::FdlStatus, "FDL_Status"},
        {Service::SlaveDiag, "Slave_Diag"},
        {Service::SetPrm, "Set_Prm"},
        {Service::ChkCfg, "Chk_Cfg"},
        {Service::GetCfg, "Get_Cfg"},
        {Service::GlobalControl, "Global_Control"},
        {Service::DataExchange, "Data_Exchange"},
        {Service::RdInp, "Rd_Inp"},
        {Service::RdOutp, "Rd_Outp"},
        {Service::SetSlaveAdd, "Set_Slave_Add"},
        {Service::MsacC1, "MSAC_C1"},
        {Service::MsacC2, "MSAC_C2"},
        {Service::Token, "Token"},
        {Service::ShortAck, "Short_Ack"},
    };
    ASSERT_EQ(names.size(), kServiceCount);
    for (const auto& [service, name] : names)
        EXPECT_EQ(service_name(service), name);
}

TEST(DpServiceTest, SapConstantsMatchTheProtocol) {
    EXPECT_EQ(sap::kChkCfg, 62);
    EXPECT_EQ(sap::kSetPrm, 61);
    EXPECT_EQ(sap::kSlaveDiag, 60);
    EXPECT_EQ(sap::kGetCfg, 59);
    EXPECT_EQ(sap::kGlobalControl, 58);
    EXPECT_EQ(sap::kRdOutp, 57);
    EXPECT_EQ(sap::kRdInp, 56);
    EXPECT_EQ(sap::kSetSlaveAdd, 55);
    EXPECT_EQ(sap::kMsacC1, 51);
}

TEST(DpServiceTest, RequestClassifiedByEveryDpSap) {
    const std::vector<std::pair<std::uint8_t, Service>> cases = {
        {62, Service::ChkCfg}, {61, Service::SetPrm},        {60, Service::SlaveDiag},
        {59, Service::GetCfg}, {58, Service::GlobalControl}, {57, Service::RdOutp},
        {56, Service::RdInp},  {55, Service::SetSlaveAdd},
    };
    for (const auto& [dsap, service] : cases) {
        SCOPED_TRACE("DSAP " + std::to_string(dsap));
        FdlTelegram t = request(dsap, sap::kMaster, {0x00, 0x00});
        ASSERT_TRUE(t.problems.empty());
        EXPECT_EQ(classify_request(t), service);
    }
}

TEST(DpServiceTest, ChkCfgRequestFromHexIsChkCfg) {
    FdlTelegram t = parse(hex("68 07 07 68 83 82 7D 3E 3E F3 F1 E2 16"));
    EXPECT_EQ(classify_request(t), Service::ChkCfg);
}

TEST(DpServiceTest, GlobalControlBroadcastIsGlobalControl) {
    FdlTelegram t = request(sap::kGlobalControl, sap::kMaster, {0x08, 0x00}, FdlFunction::SdnHigh,
                            kBroadcastAddress);
    EXPECT_EQ(t.da, 127);
    EXPECT_EQ(classify_request(t), Service::GlobalControl);
}

TEST(DpServiceTest, SapsWithoutDpMeaningAreUnknown) {
    EXPECT_EQ(classify_request(request(54, 54, {0x01})), Service::Unknown);  // master-master
    EXPECT_EQ(classify_request(request(53, 62, {0x01})), Service::Unknown);  // Set_Ext_Prm
    EXPECT_EQ(classify_request(request(63, 62, {0x01})), Service::Unknown);
    EXPECT_EQ(classify_request(request(52, 62, {0x01})), Service::Unknown);
}

TEST(DpServiceTest, DataExchangeIsAnSrdWithoutSaps) {
    EXPECT_EQ(classify_request(request(std::nullopt, std::nullopt, {0x04, 0x7F, 0x20, 0x00})),
              Service::DataExchange);
    EXPECT_EQ(classify_request(request(std::nullopt, std::nullopt, {0x04, 0x7F, 0x20, 0x00},
                                       FdlFunction::SrdLow)),
              Service::DataExchange);
    // No output data: an SD1 SRD poll is still Data_Exchange.
    FdlTelegram poll = request(std::nullopt, std::nullopt, {});
    EXPECT_EQ(poll.type, FrameType::Sd1);
    EXPECT_EQ(classify_request(poll), Service::DataExchange);
    // 8 octets travel in SD3.
    FdlTelegram sd3 = request(std::nullopt, std::nullopt, {1, 2, 3, 4, 5, 6, 7, 8});
    EXPECT_EQ(sd3.type, FrameType::Sd3);
    EXPECT_EQ(classify_request(sd3), Service::DataExchange);
}

TEST(DpServiceTest, SdnOrSdaWithoutSapsIsUnknown) {
    EXPECT_EQ(classify_request(request(std::nullopt, std::nullopt, {0x01}, FdlFunction::SdnHigh)),
              Service::Unknown);
    EXPECT_EQ(classify_request(request(std::nullopt, std::nullopt, {0x01}, FdlFunction::SdaLow)),
              Service::Unknown);
}

TEST(DpServiceTest, OnlySourceSapIsUnknown) {
    EXPECT_EQ(classify_request(request(std::nullopt, 62, {0x01})), Service::Unknown);
}

TEST(DpServiceTest, FdlStatusRequest) {
    FdlTelegram t = parse(hex("10 03 02 49 4E 16"));
    EXPECT_EQ(classify_request(t), Service::FdlStatus);
    EXPECT_EQ(classify_request(request(std::nullopt, std::nullopt, {}, FdlFunction::FdlStatus)),
              Service::FdlStatus);
}

TEST(DpServiceTest, TokenAndShortAck) {
    EXPECT_EQ(classify_request(parse(hex("DC 02 01"))), Service::Token);
    EXPECT_EQ(classify_request(parse(hex("E5"))), Service::ShortAck);
    EXPECT_EQ(classify_unpaired_response(parse(hex("E5"))), Service::ShortAck);
    EXPECT_EQ(classify_unpaired_response(parse(hex("DC 02 01"))), Service::Token);
}

TEST(DpServiceTest, MsacC1RequestAndAlarmAcknowledge) {
    // DP-V1 class-1 read: DSAP = SSAP = 51.
    EXPECT_EQ(classify_request(request(51, 51, {0x5E, 0x01, 0x2F, 0xF0})), Service::MsacC1);
    // Alarm acknowledge goes to slave SAP 50 from the class-1 master SAP 51.
    EXPECT_EQ(classify_request(request(50, 51, {0x5C, 0x00, 0x01, 0x00})), Service::MsacC1);
}

TEST(DpServiceTest, MsacC2Requests) {
    // Initiate to the resource manager, from the class-2 master SAP 50.
    EXPECT_EQ(classify_request(request(49, 50, {0x57, 0x00})), Service::MsacC2);
    // Connection SAPs 0..48.
    EXPECT_EQ(classify_request(request(0, 50, {0x5E})), Service::MsacC2);
    EXPECT_EQ(classify_request(request(48, 50, {0x5E})), Service::MsacC2);
    EXPECT_EQ(classify_request(request(20, 62, {0x5E})), Service::MsacC2);
    // SAP 50 to SAP 50: class-2 master, not the class-1 alarm acknowledge.
    EXPECT_EQ(classify_request(request(50, 50, {0x5E})), Service::MsacC2);
    // A class-2 master SSAP marks class 2 whatever the slave SAP is (except 51).
    EXPECT_EQ(classify_request(request(60, 50, {0x5E})), Service::MsacC2);
}

TEST(DpServiceTest, UnpairedResponseClassifiedBySourceSap) {
    const std::vector<std::pair<std::uint8_t, Service>> cases = {
        {62, Service::ChkCfg}, {61, Service::SetPrm},        {60, Service::SlaveDiag},
        {59, Service::GetCfg}, {58, Service::GlobalControl}, {57, Service::RdOutp},
        {56, Service::RdInp},  {55, Service::SetSlaveAdd},
    };
    for (const auto& [ssap, service] : cases) {
        SCOPED_TRACE("SSAP " + std::to_string(ssap));
        FdlTelegram t = response(sap::kMaster, ssap, {0x02, 0x05});
        EXPECT_EQ(classify_unpaired_response(t), service);
    }
}

TEST(DpServiceTest, UnpairedSlaveDiagResponseFromHex) {
    FdlTelegram t = parse(hex("A2 82 83 08 3E 3C 02 05 00 FF 04 02 93 16"));
    ASSERT_TRUE(t.problems.empty());
    EXPECT_EQ(classify_unpaired_response(t), Service::SlaveDiag);
    // The same telegram judged as a request: DSAP 62 = Chk_Cfg, which is why responses need
    // their own classifier.
    EXPECT_EQ(classify_request(t), Service::ChkCfg);
}

TEST(DpServiceTest, UnpairedMsacResponses) {
    EXPECT_EQ(classify_unpaired_response(response(51, 51, {0x5E, 0x01})), Service::MsacC1);
    EXPECT_EQ(classify_unpaired_response(response(51, 50, {0x5C})), Service::MsacC1);
    EXPECT_EQ(classify_unpaired_response(response(50, 49, {0xD7})), Service::MsacC2);
    EXPECT_EQ(classify_unpaired_response(response(50, 20, {0x5E})), Service::MsacC2);
    EXPECT_EQ(classify_unpaired_response(response(50, 60, {0x5E})), Service::MsacC2);
}

TEST(DpServiceTest, UnpairedResponseWithoutSaps) {
    // Data and no SAPs: the slave's inputs of a Data_Exchange.
    EXPECT_EQ(classify_unpaired_response(response(std::nullopt, std::nullopt, {0x0F, 0x07})),
              Service::DataExchange);
    // No data (SD1 acknowledgement): nothing to go by.
    FdlTelegram sd1 = response(std::nullopt, std::nullopt, {});
    EXPECT_EQ(sd1.type, FrameType::Sd1);
    EXPECT_EQ(classify_unpaired_response(sd1), Service::Unknown);
    // Only a destination SAP: not a DP pattern.
    EXPECT_EQ(classify_unpaired_response(response(62, std::nullopt, {0x01})), Service::Unknown);
    // An SSAP without DP meaning.
    EXPECT_EQ(classify_unpaired_response(response(62, 54, {0x01})), Service::Unknown);
}

TEST(DpServiceTest, InvalidTelegramIsUnknown) {
    FdlTelegram bad = parse(hex("2A 3F 9F"));
    EXPECT_EQ(classify_request(bad), Service::Unknown);
    EXPECT_EQ(classify_unpaired_response(bad), Service::Unknown);
    FdlTelegram empty = parse({});
    EXPECT_EQ(classify_request(empty), Service::Unknown);
}

TEST(DpServiceTest, TruncatedBeforeFrameControlIsUnknown) {
    FdlTelegram t = parse(hex("68 07 07 68 83 82"));
    ASSERT_TRUE(t.problems.contains(ProblemKind::Truncated));
    EXPECT_EQ(classify_request(t), Service::Unknown);
}

TEST(DpServiceTest, TruncatedAfterDestinationSapStillNamesTheService) {
    // Chk_Cfg cut after the DSAP byte: the SSAP is missing but DSAP 62 is known.
    FdlTelegram t = parse(hex("68 07 07 68 83 82 7D 3E"));
    ASSERT_TRUE(t.has_dsap);
    EXPECT_FALSE(t.has_ssap);
    EXPECT_EQ(classify_request(t), Service::ChkCfg);
}

TEST(DpServiceTest, TruncatedBeforeTheSapsIsNotDataExchange) {
    // Chk_Cfg cut right after FC: DA and SA announce SAP bytes (bit 7), so this is no
    // Data_Exchange (an SRD *without* SAPs) even though no SAP could be read.
    FdlTelegram t = parse(hex("68 07 07 68 83 82 7D"));
    ASSERT_TRUE(t.problems.contains(ProblemKind::AddressExtensionShort));
    EXPECT_EQ(classify_request(t), Service::Unknown);
}

TEST(DpServiceTest, CorruptedFcsDoesNotChangeTheService) {
    FdlTelegram t = parse(hex("68 07 07 68 83 82 7D 3E 3E F3 F1 00 16"));
    ASSERT_FALSE(t.fcs_ok);
    EXPECT_EQ(classify_request(t), Service::ChkCfg);
}

TEST(DpServiceTest, SapNamesSlaveSide) {
    EXPECT_EQ(sap_name(62, true), "Chk_Cfg");
    EXPECT_EQ(sap_name(61, true), "Set_Prm");
    EXPECT_EQ(sap_name(60, true), "Slave_Diag");
    EXPECT_EQ(sap_name(59, true), "Get_Cfg");
    EXPECT_EQ(sap_name(58, true), "Global_Control");
    EXPECT_EQ(sap_name(57, true), "Rd_Outp");
    EXPECT_EQ(sap_name(56, true), "Rd_Inp");
    EXPECT_EQ(sap_name(55, true), "Set_Slave_Add");
    EXPECT_EQ(sap_name(54, true), "master-master");
    EXPECT_EQ(sap_name(53, true), "Set_Ext_Prm");
    EXPECT_EQ(sap_name(51, true), "MSAC_C1");
    EXPECT_EQ(sap_name(50, true), "DP-V1 alarm");
    EXPECT_EQ(sap_name(49, true), "MSAC_C2 resource manager");
    EXPECT_EQ(sap_name(48, true), "MSAC_C2 connection");
    EXPECT_EQ(sap_name(0, true), "MSAC_C2 connection");
    EXPECT_EQ(sap_name(52, true), "");
    EXPECT_EQ(sap_name(63, true), "");
}

TEST(DpServiceTest, SapNamesMasterSide) {
    EXPECT_EQ(sap_name(62, false), "DP master");
    EXPECT_EQ(sap_name(51, false), "MSAC_C1 master");
    EXPECT_EQ(sap_name(50, false), "MSAC_C2 master");
    EXPECT_EQ(sap_name(54, false), "master-master");
    EXPECT_EQ(sap_name(10, false), "MSAC_C2 connection");
    EXPECT_EQ(sap_name(60, false), "");
    EXPECT_EQ(sap_name(63, false), "");
}

}  // namespace
}  // namespace dpscope
