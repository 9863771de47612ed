// BusDecoder: responses named after their request, unpaired responses, unanswered requests, PPO
// layout from configuration / option / length, dialects and profiles per station, PCV/PCD split,
// station configuration and problems in the service data.
#include "protocols/profibus/bus_decoder.hpp"

#include <gtest/gtest.h>

#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "protocols/profibus/telegram_builder.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::hex;

constexpr std::uint8_t kMasterAddress = 2;

// Owns the telegram bytes so a DecodedTelegram's spans stay valid while a test looks at it.
class Bus {
  public:
    explicit Bus(DecoderOptions options = {}) : decoder(options) {}

    const DecodedTelegram& decode(std::vector<std::uint8_t> bytes, std::int64_t time_ns = kNoTime) {
        frames_.push_back(std::move(bytes));
        const auto& stored = frames_.back();
        return decoder.decode(Bytes(stored.data(), stored.size()), time_ns, frames_.size());
    }

    BusDecoder decoder;

  private:
    std::deque<std::vector<std::uint8_t>> frames_;
};

std::vector<std::uint8_t> telegram(std::uint8_t da, std::uint8_t sa, std::uint8_t fc,
                                   std::optional<std::uint8_t> dsap,
                                   std::optional<std::uint8_t> ssap,
                                   const std::vector<std::uint8_t>& du) {
    TelegramSpec spec;
    spec.da = da;
    spec.sa = sa;
    spec.fc = fc;
    spec.dsap = dsap;
    spec.ssap = ssap;
    spec.du = Bytes(du.data(), du.size());
    return build_telegram(spec);
}

// Master -> slave DP service request (SRD high) with SAPs.
std::vector<std::uint8_t> service_request(std::uint8_t slave, std::uint8_t dsap,
                                          const std::vector<std::uint8_t>& du = {},
                                          FdlFunction function = FdlFunction::SrdHigh) {
    return telegram(slave, kMasterAddress, request_fc(function, true, true), dsap, sap::kMaster,
                    du);
}

// Slave -> master DP service response with SAPs.
std::vector<std::uint8_t> service_response(std::uint8_t slave, std::uint8_t ssap,
                                           const std::vector<std::uint8_t>& du) {
    return telegram(kMasterAddress, slave, response_fc(FdlStatus::DataLow), sap::kMaster, ssap, du);
}

std::vector<std::uint8_t> exchange_request(std::uint8_t slave,
                                           const std::vector<std::uint8_t>& du) {
    return telegram(slave, kMasterAddress, request_fc(FdlFunction::SrdHigh, true, true),
                    std::nullopt, std::nullopt, du);
}

std::vector<std::uint8_t> exchange_response(std::uint8_t slave,
                                            const std::vector<std::uint8_t>& du) {
    return telegram(kMasterAddress, slave, response_fc(FdlStatus::DataLow), std::nullopt,
                    std::nullopt, du);
}

std::vector<std::uint8_t> token(std::uint8_t da = kMasterAddress,
                                std::uint8_t sa = kMasterAddress) {
    std::vector<std::uint8_t> out;
    append_token(out, da, sa);
    return out;
}

std::vector<std::uint8_t> short_ack() { return hex("E5"); }

std::vector<std::uint8_t> bytes_of(Bytes bytes) { return {bytes.begin(), bytes.end()}; }

// ---- Pairing ---------------------------------------------------------------------------------

TEST(BusDecoderTest, ShortAckAfterChkCfgIsNamedChkCfg) {
    Bus bus;
    const DecodedTelegram& request = bus.decode(service_request(3, sap::kChkCfg, hex("F3 F1")));
    EXPECT_EQ(request.frame, 1u);
    EXPECT_EQ(request.dp.service, Service::ChkCfg);
    EXPECT_EQ(request.direction, Direction::Request);
    EXPECT_TRUE(request.has_roles);
    EXPECT_EQ(request.master, 2);
    EXPECT_EQ(request.slave, 3);
    EXPECT_EQ(request.request_frame, 0u);
    EXPECT_FALSE(request.dp.unanswered);
    EXPECT_TRUE(request.problems().empty());

    const DecodedTelegram& ack = bus.decode(short_ack());
    EXPECT_EQ(ack.frame, 2u);
    EXPECT_EQ(ack.dp.fdl.type, FrameType::ShortAck);
    EXPECT_EQ(ack.dp.service, Service::ChkCfg);
    EXPECT_EQ(ack.direction, Direction::Response);
    EXPECT_EQ(ack.request_frame, 1u);
    EXPECT_TRUE(ack.has_roles);
    EXPECT_EQ(ack.master, 2);
    EXPECT_EQ(ack.slave, 3);

    const DecodedTelegram& next = bus.decode(token());
    EXPECT_FALSE(next.dp.unanswered);
}

TEST(BusDecoderTest, ResponsesAreNamedAfterTheRequestTheyAnswer) {
    Bus bus;
    bus.decode(service_request(3, sap::kSlaveDiag));
    const DecodedTelegram& diag =
        bus.decode(service_response(3, sap::kSlaveDiag, hex("02 05 00 FF 04 02")));
    EXPECT_EQ(diag.dp.fdl.type, FrameType::Sd3);
    EXPECT_EQ(diag.dp.service, Service::SlaveDiag);
    EXPECT_EQ(diag.request_frame, 1u);

    bus.decode(service_request(3, sap::kSetPrm, hex("88 0A 0A 0B 04 02 00")));
    const DecodedTelegram& prm_ack = bus.decode(short_ack());
    EXPECT_EQ(prm_ack.dp.service, Service::SetPrm);
    EXPECT_EQ(prm_ack.request_frame, 3u);

    bus.decode(exchange_request(3, hex("04 7F 20 00")));
    const DecodedTelegram& inputs = bus.decode(exchange_response(3, hex("0F 07 20 00")));
    EXPECT_EQ(inputs.dp.service, Service::DataExchange);
    EXPECT_EQ(inputs.request_frame, 5u);
    EXPECT_EQ(inputs.direction, Direction::Response);

    bus.decode(telegram(3, 2, request_fc(FdlFunction::FdlStatus), std::nullopt, std::nullopt, {}));
    const DecodedTelegram& status =
        bus.decode(telegram(2, 3, response_fc(FdlStatus::Ok), std::nullopt, std::nullopt, {}));
    EXPECT_EQ(status.dp.fdl.type, FrameType::Sd1);
    EXPECT_EQ(status.dp.service, Service::FdlStatus);
    EXPECT_EQ(status.request_frame, 7u);
}

TEST(BusDecoderTest, UnpairedResponsesAreClassifiedBySourceSap) {
    Bus bus;
    const DecodedTelegram& diag =
        bus.decode(service_response(3, sap::kSlaveDiag, hex("02 05 00 FF 04 02")));
    EXPECT_EQ(diag.dp.service, Service::SlaveDiag);
    EXPECT_EQ(diag.direction, Direction::Response);
    EXPECT_EQ(diag.request_frame, 0u);
    EXPECT_TRUE(diag.has_roles);
    EXPECT_EQ(diag.master, 2);
    EXPECT_EQ(diag.slave, 3);

    const DecodedTelegram& cfg = bus.decode(service_response(4, sap::kGetCfg, hex("F1")));
    EXPECT_EQ(cfg.dp.service, Service::GetCfg);
    EXPECT_EQ(cfg.slave, 4);

    const DecodedTelegram& inputs = bus.decode(exchange_response(5, hex("0F 07 20 00")));
    EXPECT_EQ(inputs.dp.service, Service::DataExchange);
    EXPECT_EQ(inputs.request_frame, 0u);

    const DecodedTelegram& ack = bus.decode(short_ack());
    EXPECT_EQ(ack.dp.service, Service::ShortAck);
    EXPECT_EQ(ack.direction, Direction::Response);
    EXPECT_FALSE(ack.has_roles);
}

TEST(BusDecoderTest, ResponseFromAnotherStationDoesNotAnswerThePendingRequest) {
    Bus bus;
    bus.decode(exchange_request(3, hex("04 7F 20 00")));
    const DecodedTelegram& other = bus.decode(exchange_response(4, hex("0F 07 20 00")));
    EXPECT_EQ(other.request_frame, 0u);
    EXPECT_EQ(other.slave, 4);
    const DecodedTelegram& next = bus.decode(token());
    ASSERT_TRUE(next.dp.unanswered);
    EXPECT_EQ(next.dp.unanswered->frame, 1u);
    EXPECT_EQ(next.dp.unanswered->slave, 3);
}

TEST(BusDecoderTest, ResponseToAnotherMasterDoesNotAnswerThePendingRequest) {
    Bus bus;
    bus.decode(exchange_request(3, hex("04 7F 20 00")));
    const DecodedTelegram& other = bus.decode(telegram(
        1, 3, response_fc(FdlStatus::DataLow), std::nullopt, std::nullopt, hex("0F 07 20 00")));
    EXPECT_EQ(other.request_frame, 0u);
    EXPECT_EQ(other.master, 1);
}

// ---- Unanswered requests ---------------------------------------------------------------------

TEST(BusDecoderTest, UnansweredSrdReportedOnTheNextRequest) {
    Bus bus;
    bus.decode(exchange_request(3, hex("04 7F 20 00")), 1000);
    const DecodedTelegram& next = bus.decode(exchange_request(4, hex("04 7F 20 00")), 2000);
    ASSERT_TRUE(next.dp.unanswered);
    EXPECT_EQ(next.dp.unanswered->frame, 1u);
    EXPECT_EQ(next.dp.unanswered->time_ns, 1000);
    EXPECT_EQ(next.dp.unanswered->master, 2);
    EXPECT_EQ(next.dp.unanswered->slave, 3);
    EXPECT_EQ(next.dp.unanswered->function, static_cast<std::uint8_t>(FdlFunction::SrdHigh));
    EXPECT_EQ(next.dp.unanswered->service, Service::DataExchange);
    EXPECT_EQ(next.time_ns, 2000);
    EXPECT_TRUE(next.has_time());

    // The second request is answered normally.
    const DecodedTelegram& answer = bus.decode(exchange_response(4, hex("0F 07 20 00")));
    EXPECT_EQ(answer.request_frame, 2u);
    EXPECT_FALSE(bus.decode(token()).dp.unanswered);
}

TEST(BusDecoderTest, UnansweredRequestReportedOnTheTokenOnlyOnce) {
    Bus bus;
    bus.decode(service_request(3, sap::kSlaveDiag));
    const DecodedTelegram& first = bus.decode(token());
    EXPECT_EQ(first.dp.service, Service::Token);
    ASSERT_TRUE(first.dp.unanswered);
    EXPECT_EQ(first.dp.unanswered->service, Service::SlaveDiag);
    EXPECT_EQ(first.dp.unanswered->time_ns, kNoTime);
    EXPECT_FALSE(bus.decode(token()).dp.unanswered);
}

TEST(BusDecoderTest, UnansweredSdaIsReported) {
    Bus bus;
    bus.decode(service_request(3, sap::kGlobalControl, hex("08 00"), FdlFunction::SdaHigh));
    const DecodedTelegram& next = bus.decode(token());
    ASSERT_TRUE(next.dp.unanswered);
    EXPECT_EQ(next.dp.unanswered->function, static_cast<std::uint8_t>(FdlFunction::SdaHigh));
}

TEST(BusDecoderTest, NoReplyExpectedAfterSdnOrBroadcast) {
    Bus bus;
    // Global_Control: SDN to the broadcast address.
    const DecodedTelegram& gc = bus.decode(service_request(kBroadcastAddress, sap::kGlobalControl,
                                                           hex("08 00"), FdlFunction::SdnHigh));
    EXPECT_EQ(gc.dp.service, Service::GlobalControl);
    EXPECT_FALSE(bus.decode(token()).dp.unanswered);
    // SDN to a single slave.
    bus.decode(service_request(3, sap::kGlobalControl, hex("08 00"), FdlFunction::SdnLow));
    EXPECT_FALSE(bus.decode(token()).dp.unanswered);
    // Even an SRD to the broadcast address waits for nobody.
    bus.decode(exchange_request(kBroadcastAddress, hex("00 00")));
    EXPECT_FALSE(bus.decode(token()).dp.unanswered);
    // A token itself waits for nothing.
    bus.decode(token(3, 2));
    EXPECT_FALSE(bus.decode(token()).dp.unanswered);
}

TEST(BusDecoderTest, InvalidTelegramKeepsTheRequestPending) {
    Bus bus;
    bus.decode(exchange_request(3, hex("04 7F 20 00")));
    const DecodedTelegram& garbage = bus.decode(hex("2A 3F 9F"));
    EXPECT_EQ(garbage.dp.fdl.type, FrameType::Invalid);
    EXPECT_EQ(garbage.dp.service, Service::Unknown);
    EXPECT_EQ(garbage.direction, Direction::Request);
    EXPECT_FALSE(garbage.has_roles);
    EXPECT_FALSE(garbage.dp.unanswered);
    EXPECT_TRUE(garbage.problems().contains(ProblemKind::BadStartDelimiter));
    const DecodedTelegram& answer = bus.decode(exchange_response(3, hex("0F 07 20 00")));
    EXPECT_EQ(answer.request_frame, 1u);
}

TEST(BusDecoderTest, TokenHasRolesFromItsAddresses) {
    Bus bus;
    const DecodedTelegram& t = bus.decode(token(5, 2));
    EXPECT_EQ(t.dp.service, Service::Token);
    EXPECT_EQ(t.direction, Direction::Request);
    EXPECT_TRUE(t.has_roles);
    EXPECT_EQ(t.master, 2);
    EXPECT_EQ(t.slave, 5);
    EXPECT_FALSE(t.dp.has_pcv);
}

// ---- PPO layout ------------------------------------------------------------------------------

TEST(BusDecoderTest, PpoFromChkCfgSplitsDataExchange) {
    Bus bus;
    bus.decode(service_request(3, sap::kChkCfg, hex("F3 F1")));
    const StationConfig& config = bus.decoder.station(3);
    EXPECT_EQ(config.ppo.type, 1);
    EXPECT_EQ(config.ppo.source, PpoSource::ChkCfg);
    EXPECT_EQ(config.cfg_frame, 1u);
    bus.decode(short_ack());

    const DecodedTelegram& out =
        bus.decode(exchange_request(3, hex("10 01 00 00 00 00 00 00 04 7F 20 00")));
    EXPECT_EQ(out.dp.service, Service::DataExchange);
    EXPECT_EQ(out.dp.ppo.type, 1);
    EXPECT_EQ(out.dp.ppo.source, PpoSource::ChkCfg);
    ASSERT_TRUE(out.dp.has_pcv);
    EXPECT_EQ(out.dp.pcv.rc, 1);
    EXPECT_EQ(out.dp.pcv.pnu, 1);
    EXPECT_EQ(out.dp.pcd_offset, 15);
    EXPECT_EQ(bytes_of(out.dp.pcd), hex("04 7F 20 00"));
}

TEST(BusDecoderTest, PpoFromGetCfgResponse) {
    Bus bus;
    const DecodedTelegram& request = bus.decode(service_request(3, sap::kGetCfg));
    EXPECT_EQ(request.dp.service, Service::GetCfg);
    const DecodedTelegram& response = bus.decode(service_response(3, sap::kGetCfg, hex("F5")));
    EXPECT_EQ(response.dp.service, Service::GetCfg);
    EXPECT_EQ(response.request_frame, 1u);
    const StationConfig& config = bus.decoder.station(3);
    EXPECT_EQ(config.ppo.type, 4);
    EXPECT_EQ(config.ppo.source, PpoSource::GetCfg);
    EXPECT_FALSE(config.ppo.has_pcv);
    EXPECT_EQ(config.cfg_frame, 2u);

    // 12 bytes are PPO 4 here, whatever the length heuristic would say.
    auto du = hex("10 01 00 00 00 00 00 00 04 7F 20 00");
    const DecodedTelegram& out = bus.decode(exchange_request(3, du));
    EXPECT_EQ(out.dp.ppo.type, 4);
    EXPECT_FALSE(out.dp.has_pcv);
    EXPECT_EQ(out.dp.pcd_offset, 7);
    EXPECT_EQ(bytes_of(out.dp.pcd), du);
}

TEST(BusDecoderTest, UnpairedGetCfgResponseAlsoConfigures) {
    Bus bus;
    bus.decode(service_response(6, sap::kGetCfg, hex("F3 F5")));
    EXPECT_EQ(bus.decoder.station(6).ppo.type, 2);
    EXPECT_EQ(bus.decoder.station(6).ppo.source, PpoSource::GetCfg);
}

TEST(BusDecoderTest, PpoOptionOverridesConfiguration) {
    DecoderOptions options;
    options.station_ppo[3] = 4;
    Bus bus(options);
    bus.decode(service_request(3, sap::kChkCfg, hex("F3 F1")));
    EXPECT_EQ(bus.decoder.station(3).ppo.type, 1);  // still recorded
    auto du = hex("10 01 00 00 00 00 00 00 04 7F 20 00");
    const DecodedTelegram& out = bus.decode(exchange_request(3, du));
    EXPECT_EQ(out.dp.ppo.type, 4);
    EXPECT_EQ(out.dp.ppo.source, PpoSource::Option);
    EXPECT_FALSE(out.dp.has_pcv);
    EXPECT_EQ(bytes_of(out.dp.pcd), du);

    // Other stations are not affected.
    EXPECT_EQ(bus.decoder.layout_for(4, 12).source, PpoSource::Length);
    EXPECT_EQ(bus.decoder.layout_for(3, 20).type, 4);
    EXPECT_EQ(bus.decoder.layout_for(3 | 0x80, 4).source, PpoSource::Option);
}

TEST(BusDecoderTest, PpoOption3GivesPcdOnly) {
    DecoderOptions options;
    options.station_ppo[3] = 3;
    Bus bus(options);
    const DecodedTelegram& out = bus.decode(exchange_request(3, hex("04 7F 20 00")));
    EXPECT_EQ(out.dp.ppo.type, 3);
    EXPECT_EQ(out.dp.ppo.source, PpoSource::Option);
    EXPECT_FALSE(out.dp.has_pcv);
    EXPECT_EQ(out.dp.pcd_offset, 7);
    EXPECT_EQ(bytes_of(out.dp.pcd), hex("04 7F 20 00"));
}

TEST(BusDecoderTest, PpoFromLength) {
    Bus bus;
    struct LengthCase {
        std::size_t length;
        std::uint8_t type;
        bool has_pcv;
        std::size_t pcd;
    };
    for (const LengthCase& c : std::vector<LengthCase>{
             {4, 3, false, 4}, {20, 2, true, 12}, {28, 5, true, 20}, {8, 0, false, 8}}) {
        SCOPED_TRACE("length " + std::to_string(c.length));
        std::vector<std::uint8_t> du(c.length, 0x00);
        const DecodedTelegram& t = bus.decode(exchange_request(3, du));
        EXPECT_EQ(t.dp.ppo.type, c.type);
        EXPECT_EQ(t.dp.ppo.source, PpoSource::Length);
        EXPECT_EQ(t.dp.has_pcv, c.has_pcv);
        EXPECT_EQ(t.dp.pcd.size(), c.pcd);
        bus.decode(exchange_response(3, du));
    }
}

TEST(BusDecoderTest, TwelveBytesWithoutEvidenceArePpo1) {
    Bus bus;
    const DecodedTelegram& t = bus.decode(exchange_request(3, std::vector<std::uint8_t>(12, 0)));
    EXPECT_EQ(t.dp.ppo.type, 1);
    EXPECT_EQ(t.dp.ppo.alternative, 4);
    EXPECT_TRUE(t.dp.has_pcv);
    EXPECT_EQ(t.dp.pcd.size(), 4u);
    EXPECT_EQ(bus.decoder.station(3).length12_type, 0);
}

TEST(BusDecoderTest, TwelveBytesWithControlWordFirstArePpo4) {
    Bus bus;
    auto du = hex("04 7F 20 00 00 00 00 00 00 00 00 00");
    const DecodedTelegram& out = bus.decode(exchange_request(3, du));
    EXPECT_EQ(bus.decoder.station(3).length12_type, 4);
    EXPECT_EQ(out.dp.ppo.type, 4);
    EXPECT_EQ(out.dp.ppo.alternative, 1);
    EXPECT_EQ(out.dp.ppo.source, PpoSource::Length);
    EXPECT_FALSE(out.dp.has_pcv);
    EXPECT_EQ(bytes_of(out.dp.pcd), du);
    // The slave's answer uses the same layout.
    const DecodedTelegram& in =
        bus.decode(exchange_response(3, hex("0F 07 20 00 00 00 00 00 00 00 00 00")));
    EXPECT_EQ(in.dp.ppo.type, 4);
    EXPECT_FALSE(in.dp.has_pcv);
    EXPECT_EQ(in.dp.pcd.size(), 12u);
}

TEST(BusDecoderTest, TwelveBytesWithControlWordInBytes9And10ArePpo1) {
    Bus bus;
    const DecodedTelegram& out =
        bus.decode(exchange_request(3, hex("10 01 00 00 00 00 00 00 04 7F 20 00")));
    EXPECT_EQ(bus.decoder.station(3).length12_type, 1);
    EXPECT_EQ(out.dp.ppo.type, 1);
    EXPECT_TRUE(out.dp.has_pcv);
    EXPECT_EQ(out.dp.pcv.pnu, 1);
    EXPECT_EQ(bytes_of(out.dp.pcd), hex("04 7F 20 00"));
}

TEST(BusDecoderTest, TwelveBytesWithBit10InBothWordsArePpo1) {
    // PCA 14 00 = RC 1, PNU 1024: bit 10 is a PNU bit here; bytes 9-10 decide.
    Bus bus;
    const DecodedTelegram& out =
        bus.decode(exchange_request(3, hex("14 00 00 00 00 00 00 00 04 7F 20 00")));
    EXPECT_EQ(out.dp.ppo.type, 1);
    EXPECT_EQ(out.dp.pcv.pnu, 1024);
}

TEST(BusDecoderTest, LastTwelveByteRequestWithEvidenceDecides) {
    Bus bus;
    bus.decode(exchange_request(3, hex("04 7F 20 00 00 00 00 00 00 00 00 00")));
    EXPECT_EQ(bus.decoder.station(3).length12_type, 4);
    bus.decode(exchange_request(3, hex("10 01 00 00 00 00 00 00 04 7F 20 00")));
    EXPECT_EQ(bus.decoder.station(3).length12_type, 1);
    // No evidence: the last decision stays.
    const DecodedTelegram& t = bus.decode(exchange_request(3, std::vector<std::uint8_t>(12, 0)));
    EXPECT_EQ(bus.decoder.station(3).length12_type, 1);
    EXPECT_EQ(t.dp.ppo.type, 1);
    // Evidence for another station does not leak.
    EXPECT_EQ(bus.decoder.station(4).length12_type, 0);
}

TEST(BusDecoderTest, ResponsesDoNotTeachTheTwelveByteType) {
    Bus bus;
    bus.decode(exchange_response(3, hex("04 7F 20 00 00 00 00 00 00 00 00 00")));
    EXPECT_EQ(bus.decoder.station(3).length12_type, 0);
}

TEST(BusDecoderTest, ConfiguredStationsDoNotUseTheHeuristic) {
    Bus bus;
    bus.decode(service_request(3, sap::kChkCfg, hex("F5")));
    const DecodedTelegram& out =
        bus.decode(exchange_request(3, hex("10 01 00 00 00 00 00 00 04 7F 20 00")));
    EXPECT_EQ(out.dp.ppo.type, 4);
    EXPECT_EQ(out.dp.ppo.source, PpoSource::ChkCfg);
    EXPECT_EQ(bus.decoder.station(3).length12_type, 0);
}

// ---- Dialects and profiles -------------------------------------------------------------------

TEST(BusDecoderTest, DecoderOptionsDefaults) {
    DecoderOptions options;
    EXPECT_EQ(options.dialect, Dialect::Vlt);
    EXPECT_EQ(options.dialect_of(3), Dialect::Vlt);
    EXPECT_EQ(options.pcd_profile_of(3), PcdProfile::Fc);
    options.station_dialect[3] = Dialect::Profidrive;
    EXPECT_EQ(options.dialect_of(3), Dialect::Profidrive);
    EXPECT_EQ(options.dialect_of(3 | 0x80), Dialect::Profidrive);
    EXPECT_EQ(options.pcd_profile_of(3), PcdProfile::Profidrive);
    EXPECT_EQ(options.dialect_of(4), Dialect::Vlt);
    EXPECT_EQ(options.pcd_profile_of(4), PcdProfile::Fc);
    options.pcd_profile = PcdProfile::Fc;
    EXPECT_EQ(options.pcd_profile_of(3), PcdProfile::Fc);
    options.dialect = Dialect::Profidrive;
    EXPECT_EQ(options.dialect_of(4), Dialect::Profidrive);
    options.pcd_profile.reset();
    EXPECT_EQ(options.pcd_profile_of(4), PcdProfile::Profidrive);
}

TEST(BusDecoderTest, PerStationDialectAndProfile) {
    DecoderOptions options;
    options.station_dialect[3] = Dialect::Profidrive;
    options.station_ppo[3] = 1;
    options.station_ppo[4] = 1;
    Bus bus(options);

    std::vector<std::uint8_t> du;
    append_pcv(du, 14, false, 202, 0, 50);
    append_u16_be(du, 0x047F);
    append_u16_be(du, 0x2000);
    const DecodedTelegram& to3 = bus.decode(exchange_request(3, du));
    EXPECT_EQ(to3.dp.dialect, Dialect::Profidrive);
    EXPECT_EQ(to3.dp.pcd_profile, PcdProfile::Profidrive);
    ASSERT_TRUE(to3.dp.has_pcv);
    EXPECT_EQ(to3.dp.pcv_meaning(to3.direction),
              "Change parameter value (word) and store in EEPROM");
    EXPECT_EQ(to3.dp.pcv_value(to3.direction), 50u);
    const DecodedTelegram& from3 = bus.decode(exchange_response(3, du));
    EXPECT_EQ(from3.dp.dialect, Dialect::Profidrive);
    EXPECT_EQ(from3.dp.pcd_profile, PcdProfile::Profidrive);

    const DecodedTelegram& to4 = bus.decode(exchange_request(4, du));
    EXPECT_EQ(to4.dp.dialect, Dialect::Vlt);
    EXPECT_EQ(to4.dp.pcd_profile, PcdProfile::Fc);
    EXPECT_EQ(to4.dp.pcv_meaning(to4.direction), "Not assigned");
}

TEST(BusDecoderTest, ExplicitPcdProfileAppliesToEveryStation) {
    DecoderOptions options;
    options.dialect = Dialect::Profidrive;
    options.pcd_profile = PcdProfile::Fc;
    Bus bus(options);
    const DecodedTelegram& t = bus.decode(exchange_request(9, hex("04 7F 20 00")));
    EXPECT_EQ(t.dp.dialect, Dialect::Profidrive);
    EXPECT_EQ(t.dp.pcd_profile, PcdProfile::Fc);
}

// ---- PCV and PCD -----------------------------------------------------------------------------

TEST(BusDecoderTest, Ppo2SplitsPcvAndPcd) {
    DecoderOptions options;
    options.station_ppo[3] = 2;
    Bus bus(options);
    auto out_du = hex("30 CF 00 00 00 00 03 E8  04 7F 20 00 00 00 00 00 00 00 00 00");
    const DecodedTelegram& out = bus.decode(exchange_request(3, out_du));
    EXPECT_EQ(out.dp.ppo.type, 2);
    ASSERT_TRUE(out.dp.has_pcv);
    EXPECT_EQ(out.dp.pcv.rc, 3);
    EXPECT_EQ(out.dp.pcv.pnu, 207);
    EXPECT_EQ(out.dp.pcv_value(out.direction), 1000u);
    EXPECT_EQ(out.dp.pcv_meaning(out.direction), "Change parameter value (double word)");
    EXPECT_EQ(out.dp.pcd_offset, 15);
    ASSERT_EQ(out.dp.pcd.size(), 12u);
    EXPECT_EQ(out.dp.pcd[0], 0x04);
    EXPECT_EQ(out.dp.pcd[1], 0x7F);

    auto in_du = hex("20 CF 00 00 00 00 03 E8  0F 07 20 00 00 00 00 00 00 00 00 00");
    const DecodedTelegram& in = bus.decode(exchange_response(3, in_du));
    ASSERT_TRUE(in.dp.has_pcv);
    EXPECT_EQ(in.dp.pcv.rc, 2);
    EXPECT_EQ(in.dp.pcv_value(in.direction), 1000u);
    EXPECT_EQ(in.dp.pcv_meaning(in.direction), "Transmit parameter value (double word)");
    EXPECT_EQ(bytes_of(in.dp.pcd), hex("0F 07 20 00 00 00 00 00 00 00 00 00"));
}

TEST(BusDecoderTest, PcvValueFollowsTheResponseWidth) {
    DecoderOptions options;
    options.station_ppo[3] = 1;
    Bus bus(options);
    const DecodedTelegram& in =
        bus.decode(exchange_response(3, hex("12 08 00 00 00 AB 00 F0 0F 07 20 00")));
    ASSERT_TRUE(in.dp.has_pcv);
    EXPECT_EQ(in.dp.pcv.pnu, 520);
    EXPECT_EQ(in.dp.pcv_value(in.direction), 0xF0u);  // word: bytes 7-8 only
    EXPECT_EQ(in.dp.pcv_meaning(in.direction), "Transmit parameter value (word)");
    const DecodedTelegram& rejected =
        bus.decode(exchange_response(3, hex("70 00 00 00 00 00 00 02 0F 07 20 00")));
    EXPECT_EQ(rejected.dp.pcv.rc, 7);
    EXPECT_EQ(rejected.dp.pcv_value(rejected.direction), 2u);
    EXPECT_EQ(rejected.dp.pcv_meaning(rejected.direction), "Request not executable");
}

TEST(BusDecoderTest, Ppo5SplitsPcvAndTenPcdWords) {
    DecoderOptions options;
    options.station_ppo[3] = 5;
    Bus bus(options);
    std::vector<std::uint8_t> du(28, 0x11);
    const DecodedTelegram& out = bus.decode(exchange_request(3, du));
    EXPECT_TRUE(out.dp.has_pcv);
    EXPECT_EQ(out.dp.pcd.size(), 20u);
    EXPECT_EQ(out.dp.pcd_offset, 15);
}

TEST(BusDecoderTest, Ppo1OptionWithShortDataHasNoPcv) {
    DecoderOptions options;
    options.station_ppo[3] = 1;
    Bus bus(options);
    const DecodedTelegram& out = bus.decode(exchange_request(3, hex("04 7F 20 00")));
    EXPECT_EQ(out.dp.ppo.type, 1);
    EXPECT_FALSE(out.dp.has_pcv);
    EXPECT_EQ(bytes_of(out.dp.pcd), hex("04 7F 20 00"));
    EXPECT_EQ(out.dp.pcd_offset, 7);
}

TEST(BusDecoderTest, EightByteDataExchangeInSd3) {
    DecoderOptions options;
    options.station_ppo[3] = 1;
    Bus bus(options);
    const DecodedTelegram& out = bus.decode(exchange_request(3, hex("12 08 00 00 00 00 00 00")));
    EXPECT_EQ(out.dp.fdl.type, FrameType::Sd3);
    EXPECT_EQ(out.dp.service, Service::DataExchange);
    ASSERT_TRUE(out.dp.has_pcv);
    EXPECT_EQ(out.dp.pcv.pnu, 520);
    EXPECT_TRUE(out.dp.pcd.empty());
    EXPECT_EQ(out.dp.pcd_offset, 12);
}

TEST(BusDecoderTest, StateOfThePreviousTelegramIsCleared) {
    DecoderOptions options;
    options.station_ppo[3] = 1;
    Bus bus(options);
    bus.decode(exchange_request(3, hex("12 08 00 00 00 00 00 00 04 7F 20 00")), 5);
    const DecodedTelegram& t = bus.decode(token());
    EXPECT_FALSE(t.dp.has_pcv);
    EXPECT_TRUE(t.dp.pcd.empty());
    EXPECT_EQ(t.dp.pcd_offset, 0);
    EXPECT_FALSE(t.dp.ppo.known());
    EXPECT_EQ(t.request_frame, 0u);
    EXPECT_FALSE(t.has_time());
}

TEST(BusDecoderTest, CorruptedFcsStillDecodesThePcv) {
    DecoderOptions options;
    options.station_ppo[3] = 1;
    Bus bus(options);
    auto bytes = exchange_request(3, hex("12 08 00 00 00 00 00 00 04 7F 20 00"));
    bytes[bytes.size() - 2] ^= 0xFF;
    const DecodedTelegram& t = bus.decode(bytes);
    EXPECT_TRUE(t.problems().contains(ProblemKind::FcsMismatch));
    EXPECT_FALSE(t.dp.fdl.fcs_ok);
    EXPECT_EQ(t.dp.service, Service::DataExchange);
    ASSERT_TRUE(t.dp.has_pcv);
    EXPECT_EQ(t.dp.pcv.pnu, 520);
}

TEST(BusDecoderTest, TruncatedDataExchangeKeepsWhatIsThere) {
    DecoderOptions options;
    options.station_ppo[3] = 2;
    Bus bus(options);
    auto bytes = exchange_request(3, std::vector<std::uint8_t>(20, 0x22));
    bytes.resize(12);  // header + 5 data bytes
    const DecodedTelegram& t = bus.decode(bytes);
    EXPECT_TRUE(t.problems().contains(ProblemKind::Truncated));
    EXPECT_EQ(t.dp.service, Service::DataExchange);
    EXPECT_FALSE(t.dp.has_pcv);
    EXPECT_EQ(t.dp.pcd.size(), 5u);
}

// ---- Station configuration -------------------------------------------------------------------

TEST(BusDecoderTest, SetPrmRecordsTheIdentNumber) {
    Bus bus;
    EXPECT_FALSE(bus.decoder.station(3).has_ident);
    const DecodedTelegram& t =
        bus.decode(service_request(3, sap::kSetPrm, hex("88 0A 0A 0B 04 02 00")));
    EXPECT_EQ(t.dp.service, Service::SetPrm);
    EXPECT_TRUE(t.problems().empty());
    EXPECT_TRUE(bus.decoder.station(3).has_ident);
    EXPECT_EQ(bus.decoder.station(3).ident, 0x0402);
    bus.decode(short_ack());
    bus.decode(service_request(3, sap::kSetPrm, hex("88 0A 0A 0B 12 34 00 80 00 00")));
    EXPECT_EQ(bus.decoder.station(3).ident, 0x1234);
    EXPECT_FALSE(bus.decoder.station(4).has_ident);
}

TEST(BusDecoderTest, SlaveDiagRecordsCfgFault) {
    Bus bus;
    bus.decode(service_request(3, sap::kSlaveDiag));
    bus.decode(service_response(3, sap::kSlaveDiag, hex("04 05 00 02 04 02")));
    EXPECT_TRUE(bus.decoder.station(3).cfg_fault);
    // A short acknowledge carries no diagnosis and changes nothing.
    bus.decode(service_request(3, sap::kSlaveDiag));
    bus.decode(short_ack());
    EXPECT_TRUE(bus.decoder.station(3).cfg_fault);
    bus.decode(service_request(3, sap::kSlaveDiag));
    bus.decode(service_response(3, sap::kSlaveDiag, hex("00 0C 00 02 04 02")));
    EXPECT_FALSE(bus.decoder.station(3).cfg_fault);
}

TEST(BusDecoderTest, ChkCfgResponseDoesNotConfigure) {
    Bus bus;
    // A Chk_Cfg request with data is configuration; the SC answer is not.
    bus.decode(service_request(3, sap::kChkCfg, hex("F1")));
    EXPECT_EQ(bus.decoder.station(3).ppo.type, 3);
    EXPECT_EQ(bus.decoder.station(3).cfg_frame, 1u);
    bus.decode(short_ack());
    EXPECT_EQ(bus.decoder.station(3).cfg_frame, 1u);
    // A later Chk_Cfg replaces the configuration.
    bus.decode(service_request(3, sap::kChkCfg, hex("F3 F9")));
    EXPECT_EQ(bus.decoder.station(3).ppo.type, 5);
    EXPECT_EQ(bus.decoder.station(3).cfg_frame, 3u);
}

// ---- Problems in service data ----------------------------------------------------------------

TEST(BusDecoderTest, ShortSetPrmIsAProblem) {
    Bus bus;
    const DecodedTelegram& t = bus.decode(service_request(3, sap::kSetPrm, hex("88 0A 0A 0B 04")));
    ASSERT_EQ(t.problems().size(), 1u);
    const Problem& p = t.problems()[0];
    EXPECT_EQ(p.kind, ProblemKind::ServiceDataShort);
    EXPECT_EQ(p.offset, 9);
    EXPECT_EQ(p.expected, 7u);
    EXPECT_EQ(p.actual, 5u);
    EXPECT_FALSE(bus.decoder.station(3).has_ident);
}

TEST(BusDecoderTest, ShortSlaveDiagIsAProblem) {
    Bus bus;
    bus.decode(service_request(3, sap::kSlaveDiag));
    const DecodedTelegram& t = bus.decode(service_response(3, sap::kSlaveDiag, hex("04 05 00 02")));
    EXPECT_EQ(t.dp.service, Service::SlaveDiag);
    ASSERT_EQ(t.problems().size(), 1u);
    EXPECT_EQ(t.problems()[0].kind, ProblemKind::ServiceDataShort);
    EXPECT_EQ(t.problems()[0].offset, 9);
    EXPECT_EQ(t.problems()[0].expected, 6u);
    EXPECT_EQ(t.problems()[0].actual, 4u);
    EXPECT_FALSE(bus.decoder.station(3).cfg_fault);
}

TEST(BusDecoderTest, ShortGlobalControlAndSetSlaveAddAreProblems) {
    Bus bus;
    const DecodedTelegram& gc = bus.decode(
        service_request(kBroadcastAddress, sap::kGlobalControl, hex("08"), FdlFunction::SdnHigh));
    ASSERT_EQ(gc.problems().size(), 1u);
    EXPECT_EQ(gc.problems()[0].kind, ProblemKind::ServiceDataShort);
    EXPECT_EQ(gc.problems()[0].expected, 2u);

    const DecodedTelegram& ssa =
        bus.decode(service_request(126, sap::kSetSlaveAdd, hex("05 04 02")));
    EXPECT_EQ(ssa.dp.service, Service::SetSlaveAdd);
    ASSERT_EQ(ssa.problems().size(), 1u);
    EXPECT_EQ(ssa.problems()[0].kind, ProblemKind::ServiceDataShort);
    EXPECT_EQ(ssa.problems()[0].expected, 4u);
    EXPECT_EQ(ssa.problems()[0].actual, 3u);

    const DecodedTelegram& ok =
        bus.decode(service_request(126, sap::kSetSlaveAdd, hex("05 04 02 00")));
    EXPECT_TRUE(ok.problems().empty());
}

TEST(BusDecoderTest, TruncatedCfgIdentifierIsAProblem) {
    Bus bus;
    const DecodedTelegram& t = bus.decode(service_request(3, sap::kChkCfg, hex("F3 C0 C3")));
    ASSERT_EQ(t.problems().size(), 1u);
    EXPECT_EQ(t.problems()[0].kind, ProblemKind::CfgIdentifierTruncated);
    EXPECT_EQ(t.problems()[0].offset, 10);
    // The module read before the cut is still used.
    EXPECT_EQ(bus.decoder.station(3).ppo.output_bytes, 8);
}

TEST(BusDecoderTest, TruncatedDiagBlockIsAProblem) {
    Bus bus;
    bus.decode(service_request(3, sap::kSlaveDiag));
    const DecodedTelegram& t =
        bus.decode(service_response(3, sap::kSlaveDiag, hex("08 0C 00 02 04 02 05 AA")));
    ASSERT_EQ(t.problems().size(), 1u);
    EXPECT_EQ(t.problems()[0].kind, ProblemKind::DiagBlockTruncated);
    EXPECT_EQ(t.problems()[0].offset, 15);
    EXPECT_EQ(t.problems()[0].expected, 5u);
    EXPECT_EQ(t.problems()[0].actual, 2u);
}

// ---- Service data stored on the telegram -----------------------------------------------------

TEST(BusDecoderTest, CarriesServiceDataNamesTheTelegramWithTheServicesData) {
    for (Service service :
         {Service::SetPrm, Service::ChkCfg, Service::GlobalControl, Service::SetSlaveAdd}) {
        EXPECT_TRUE(carries_service_data(service, Direction::Request, FrameType::Sd2));
        EXPECT_FALSE(carries_service_data(service, Direction::Response, FrameType::Sd2));
    }
    for (Service service : {Service::SlaveDiag, Service::GetCfg}) {
        EXPECT_FALSE(carries_service_data(service, Direction::Request, FrameType::Sd2));
        EXPECT_TRUE(carries_service_data(service, Direction::Response, FrameType::Sd2));
        EXPECT_TRUE(carries_service_data(service, Direction::Response, FrameType::Sd3));
        EXPECT_FALSE(carries_service_data(service, Direction::Response, FrameType::Sd1));
        EXPECT_FALSE(carries_service_data(service, Direction::Response, FrameType::ShortAck));
    }
    // A DP-V1 PDU travels both ways, in data telegrams only.
    for (Service service : {Service::MsacC1, Service::MsacC2}) {
        for (Direction direction : {Direction::Request, Direction::Response}) {
            EXPECT_TRUE(carries_service_data(service, direction, FrameType::Sd2));
            EXPECT_FALSE(carries_service_data(service, direction, FrameType::Sd1));
            EXPECT_FALSE(carries_service_data(service, direction, FrameType::ShortAck));
        }
    }
    for (Service service :
         {Service::DataExchange, Service::RdInp, Service::Token, Service::Unknown})
        for (Direction direction : {Direction::Request, Direction::Response})
            EXPECT_FALSE(carries_service_data(service, direction, FrameType::Sd2));
}

TEST(BusDecoderTest, SlaveDiagAndItsExtendedDiagnosisAreStored) {
    Bus bus;
    const DecodedTelegram& request = bus.decode(service_request(3, sap::kSlaveDiag));
    EXPECT_EQ(request.dp.service_data.kind(), DpServiceData::Kind::None);
    // Device-related block (3 bytes), channel-related block, revision.
    const DecodedTelegram& t = bus.decode(
        service_response(3, sap::kSlaveDiag, hex("08 0C 00 02 04 02 03 AA BB 81 42 A6 C5")));
    EXPECT_TRUE(t.problems().empty());
    const DpServiceData& data = t.dp.service_data;
    EXPECT_EQ(data.kind(), DpServiceData::Kind::SlaveDiag);
    const SlaveDiag* diag = data.slave_diag();
    ASSERT_NE(diag, nullptr);
    EXPECT_EQ(diag->station_status_1, 0x08);
    EXPECT_EQ(diag->station_status_2, 0x0C);
    EXPECT_EQ(diag->master_address, 2);
    EXPECT_EQ(diag->ident, 0x0402);
    EXPECT_EQ(bytes_of(diag->extended), hex("03 AA BB 81 42 A6 C5"));
    ASSERT_EQ(data.diag_blocks().size(), 3u);
    EXPECT_EQ(data.diag_blocks()[0].type, DiagBlockType::Device);
    EXPECT_EQ(bytes_of(data.diag_blocks()[0].data), hex("AA BB"));
    EXPECT_EQ(data.diag_blocks()[1].type, DiagBlockType::Channel);
    EXPECT_EQ(data.diag_blocks()[1].module, 1);
    EXPECT_EQ(data.diag_blocks()[1].channel, 2);
    EXPECT_EQ(data.diag_blocks()[2].type, DiagBlockType::Revision);
    EXPECT_EQ(data.diag_blocks()[2].revision, 5);
    EXPECT_EQ(data.set_prm(), nullptr);
    EXPECT_EQ(data.cfg_modules(), nullptr);
    EXPECT_EQ(data.global_control(), nullptr);
    EXPECT_EQ(data.set_slave_add(), nullptr);

    // The next diagnosis replaces the blocks rather than adding to them.
    bus.decode(service_request(3, sap::kSlaveDiag));
    const DecodedTelegram& next =
        bus.decode(service_response(3, sap::kSlaveDiag, hex("08 0C 00 02 04 02 C1")));
    ASSERT_EQ(next.dp.service_data.diag_blocks().size(), 1u);
    EXPECT_EQ(next.dp.service_data.diag_blocks()[0].type, DiagBlockType::Revision);
}

TEST(BusDecoderTest, SetPrmIsStored) {
    Bus bus;
    const DecodedTelegram& t =
        bus.decode(service_request(3, sap::kSetPrm, hex("88 0A 0A 0B 12 34 00 80 00 00 AB")));
    const SetPrm* prm = t.dp.service_data.set_prm();
    ASSERT_NE(prm, nullptr);
    EXPECT_EQ(prm->station_status, 0x88);
    EXPECT_EQ(prm->ident, 0x1234);
    EXPECT_TRUE(prm->dpv1_enabled());
    EXPECT_EQ(bytes_of(prm->user_prm), hex("AB"));
    EXPECT_EQ(t.dp.service_data.slave_diag(), nullptr);
    // Its acknowledgement carries no data.
    EXPECT_EQ(bus.decode(short_ack()).dp.service_data.kind(), DpServiceData::Kind::None);
}

TEST(BusDecoderTest, ChkCfgAndGetCfgModulesAreStored) {
    Bus bus;
    const DecodedTelegram& chk = bus.decode(service_request(3, sap::kChkCfg, hex("F3 F1")));
    const std::vector<CfgModule>* modules = chk.dp.service_data.cfg_modules();
    ASSERT_NE(modules, nullptr);
    ASSERT_EQ(modules->size(), 2u);
    EXPECT_EQ((*modules)[0].identifier, 0xF3);
    EXPECT_EQ((*modules)[1].identifier, 0xF1);
    // A Chk_Cfg response is no configuration, whatever it carries.
    EXPECT_EQ(bus.decode(service_response(3, sap::kChkCfg, hex("F1"))).dp.service_data.kind(),
              DpServiceData::Kind::None);

    const DecodedTelegram& get = bus.decode(service_request(3, sap::kGetCfg));
    EXPECT_EQ(get.dp.service_data.cfg_modules(), nullptr);
    const DecodedTelegram& answer = bus.decode(service_response(3, sap::kGetCfg, hex("F1")));
    ASSERT_NE(answer.dp.service_data.cfg_modules(), nullptr);
    ASSERT_EQ(answer.dp.service_data.cfg_modules()->size(), 1u);
    EXPECT_EQ((*answer.dp.service_data.cfg_modules())[0].identifier, 0xF1);
}

TEST(BusDecoderTest, GlobalControlAndSetSlaveAddAreStored) {
    Bus bus;
    const DecodedTelegram& gc = bus.decode(service_request(kBroadcastAddress, sap::kGlobalControl,
                                                           hex("08 01"), FdlFunction::SdnHigh));
    const GlobalControl* control = gc.dp.service_data.global_control();
    ASSERT_NE(control, nullptr);
    EXPECT_EQ(control->command, 0x08);
    EXPECT_EQ(control->group_select, 0x01);

    const DecodedTelegram& ssa =
        bus.decode(service_request(126, sap::kSetSlaveAdd, hex("05 04 02 01 EE")));
    const SetSlaveAdd* add = ssa.dp.service_data.set_slave_add();
    ASSERT_NE(add, nullptr);
    EXPECT_EQ(add->new_address, 5);
    EXPECT_EQ(add->ident, 0x0402);
    EXPECT_EQ(add->no_add_chg, 1);
    EXPECT_EQ(bytes_of(add->rem_slave_data), hex("EE"));
}

// DP gives such a response no data; the text views show its bytes in the request's layout, but
// data that does not fit them is no problem of the response.
TEST(BusDecoderTest, ResponseToGlobalControlHoldsItsBytesWithoutProblems) {
    Bus bus;
    bus.decode(service_request(3, sap::kGlobalControl, hex("08 00")));
    const DecodedTelegram& t = bus.decode(service_response(3, sap::kGlobalControl, hex("02 07")));
    EXPECT_EQ(t.dp.service, Service::GlobalControl);
    ASSERT_NE(t.dp.service_data.global_control(), nullptr);
    EXPECT_EQ(t.dp.service_data.global_control()->command, 0x02);
    EXPECT_TRUE(t.problems().empty());

    bus.decode(service_request(3, sap::kSetSlaveAdd, hex("05 04 02 00")));
    const DecodedTelegram& short_one =
        bus.decode(service_response(3, sap::kSetSlaveAdd, hex("05")));
    EXPECT_EQ(short_one.dp.service_data.kind(), DpServiceData::Kind::None);
    EXPECT_TRUE(short_one.problems().empty());
}

TEST(BusDecoderTest, TruncatedServiceDataKeepsWhatWasRead) {
    Bus bus;
    // The diagnosis and the block before the cut channel-related block are kept.
    bus.decode(service_request(3, sap::kSlaveDiag));
    const DecodedTelegram& diag =
        bus.decode(service_response(3, sap::kSlaveDiag, hex("08 0C 00 02 04 02 C1 81 42")));
    ASSERT_EQ(diag.problems().size(), 1u);
    EXPECT_EQ(diag.problems()[0].kind, ProblemKind::DiagBlockTruncated);
    ASSERT_NE(diag.dp.service_data.slave_diag(), nullptr);
    EXPECT_EQ(diag.dp.service_data.slave_diag()->ident, 0x0402);
    ASSERT_EQ(diag.dp.service_data.diag_blocks().size(), 1u);
    EXPECT_EQ(diag.dp.service_data.diag_blocks()[0].type, DiagBlockType::Revision);

    // The module before the cut special identifier is kept.
    const DecodedTelegram& cfg = bus.decode(service_request(3, sap::kChkCfg, hex("F3 C0 C3")));
    ASSERT_EQ(cfg.problems().size(), 1u);
    EXPECT_EQ(cfg.problems()[0].kind, ProblemKind::CfgIdentifierTruncated);
    ASSERT_NE(cfg.dp.service_data.cfg_modules(), nullptr);
    ASSERT_EQ(cfg.dp.service_data.cfg_modules()->size(), 1u);
    EXPECT_EQ((*cfg.dp.service_data.cfg_modules())[0].identifier, 0xF3);

    // Without the fixed part there is nothing to keep.
    bus.decode(short_ack());
    const DecodedTelegram& prm = bus.decode(service_request(3, sap::kSetPrm, hex("88 0A 0A 0B")));
    ASSERT_EQ(prm.problems().size(), 1u);
    EXPECT_EQ(prm.problems()[0].kind, ProblemKind::ServiceDataShort);
    EXPECT_EQ(prm.dp.service_data.kind(), DpServiceData::Kind::None);
}

TEST(BusDecoderTest, DataExchangeAfterSlaveDiagHoldsNoServiceData) {
    Bus bus;
    bus.decode(service_request(3, sap::kSlaveDiag));
    const DecodedTelegram& diag =
        bus.decode(service_response(3, sap::kSlaveDiag, hex("08 0C 00 02 04 02 C1")));
    EXPECT_NE(diag.dp.service_data.slave_diag(), nullptr);
    const DecodedTelegram& exchange = bus.decode(exchange_request(3, hex("04 7F 20 00")));
    EXPECT_EQ(exchange.dp.service, Service::DataExchange);
    EXPECT_EQ(exchange.dp.service_data.kind(), DpServiceData::Kind::None);
    EXPECT_EQ(exchange.dp.service_data.slave_diag(), nullptr);
    EXPECT_TRUE(exchange.dp.service_data.diag_blocks().empty());
    // Nor does a token or a telegram that could not be read.
    bus.decode(service_request(3, sap::kSetPrm, hex("88 0A 0A 0B 04 02 00")));
    EXPECT_EQ(bus.decode(token()).dp.service_data.kind(), DpServiceData::Kind::None);
    bus.decode(service_request(3, sap::kSetPrm, hex("88 0A 0A 0B 04 02 00")));
    EXPECT_EQ(bus.decode(hex("FF 00")).dp.service_data.kind(), DpServiceData::Kind::None);
}

// A device-related diagnosis block reads as DP-V1 alarm/status only for a slave whose Set_Prm
// enabled DP-V1; the decoder keeps that per slave.
TEST(BusDecoderTest, SetPrmDecidesTheSlavesDpv1Mode) {
    Bus bus;
    const auto diag = hex("08 0C 00 02 04 02 05 81 01 00 00");
    auto diag_of = [&](std::uint8_t slave) -> const DecodedTelegram& {
        bus.decode(service_request(slave, sap::kSlaveDiag));
        return bus.decode(service_response(slave, sap::kSlaveDiag, diag));
    };
    EXPECT_EQ(diag_of(3).dp.slave_dpv1, SlaveDpv1::Unknown);  // no Set_Prm seen yet

    bus.decode(service_request(3, sap::kSetPrm, hex("88 0A 0A 0B 04 02 00 80 00 00")));
    EXPECT_EQ(bus.decoder.station(3).dpv1, SlaveDpv1::Enabled);
    EXPECT_EQ(diag_of(3).dp.slave_dpv1, SlaveDpv1::Enabled);
    EXPECT_EQ(diag_of(4).dp.slave_dpv1, SlaveDpv1::Unknown);  // another slave

    // DP-V1 status bytes without DPV1_Enable, and DP-V0 User_Prm_Data (a reserved bit set).
    bus.decode(service_request(3, sap::kSetPrm, hex("88 0A 0A 0B 04 02 00 00 00 00")));
    EXPECT_EQ(diag_of(3).dp.slave_dpv1, SlaveDpv1::Disabled);
    bus.decode(service_request(4, sap::kSetPrm, hex("88 0A 0A 0B 04 02 00 81 00 00")));
    EXPECT_EQ(diag_of(4).dp.slave_dpv1, SlaveDpv1::Disabled);
    bus.decode(service_request(5, sap::kSetPrm, hex("88 0A 0A 0B 04 02 00")));
    EXPECT_EQ(diag_of(5).dp.slave_dpv1, SlaveDpv1::Disabled);

    // A Set_Prm with a bad FCS is dropped by the slave: the mode stays.
    auto damaged = service_request(3, sap::kSetPrm, hex("88 0A 0A 0B 04 02 00 80 00 00"));
    damaged[damaged.size() - 2] ^= 0xFF;
    EXPECT_FALSE(bus.decode(damaged).dp.fdl.fcs_ok);
    EXPECT_EQ(diag_of(3).dp.slave_dpv1, SlaveDpv1::Disabled);
    // A Set_Prm too short for its fixed part says nothing either.
    bus.decode(service_request(3, sap::kSetPrm, hex("88 0A 0A")));
    EXPECT_EQ(bus.decoder.station(3).dpv1, SlaveDpv1::Disabled);
    // Data_Exchange carries no DP-V1 mode.
    EXPECT_EQ(bus.decode(exchange_request(3, hex("04 7F 20 00"))).dp.slave_dpv1,
              SlaveDpv1::Unknown);
}

TEST(BusDecoderTest, ReservedFrameControlIsAProblemAndExpectsNoReply) {
    Bus bus;
    // 0xCD: bit 7 with SRD high. SD2 with SAPs: FC at byte 6.
    const DecodedTelegram& bad =
        bus.decode(telegram(3, kMasterAddress, 0xCD, sap::kSlaveDiag, sap::kMaster, {}));
    ASSERT_EQ(bad.problems().size(), 1u);
    EXPECT_EQ(bad.problems()[0].kind, ProblemKind::ReservedFrameControl);
    EXPECT_EQ(bad.problems()[0].offset, 6);
    EXPECT_EQ(bad.problems()[0].actual, 0xCDu);
    EXPECT_FALSE(bus.decode(service_request(4, sap::kSlaveDiag)).dp.unanswered.has_value());

    // 0xC0 to the broadcast address: a clock value request, no problem.
    const DecodedTelegram& clock = bus.decode(
        telegram(127, kMasterAddress, 0xC0, std::nullopt, std::nullopt, hex("01 02 03 04")));
    EXPECT_TRUE(clock.problems().empty());
    EXPECT_TRUE(clock.dp.fdl.fc.is_clock_value());

    // A response with bit 7 set (0x88: DL) is reserved too; SD1: FC at byte 3.
    const DecodedTelegram& response = bus.decode(hex("10 02 03 88 8D 16"));
    ASSERT_EQ(response.problems().size(), 1u);
    EXPECT_EQ(response.problems()[0].kind, ProblemKind::ReservedFrameControl);
    EXPECT_EQ(response.problems()[0].offset, 3);
}

TEST(BusDecoderTest, DanfossPcdNamesOnlyForDanfossSlaves) {
    DecoderOptions options;
    options.station_dialect[3] = Dialect::Profidrive;
    options.station_ppo[3] = 3;
    options.station_ppo[4] = 3;
    {
        Bus bus(options);
        // Generic PROFIdrive slave, PROFIdrive profile: bits 11..15 are device-specific.
        EXPECT_FALSE(bus.decode(exchange_request(3, hex("04 7F 20 00"))).dp.danfoss_pcd());
        // vlt slave, FC profile by default.
        EXPECT_TRUE(bus.decode(exchange_request(4, hex("04 7F 20 00"))).dp.danfoss_pcd());
    }
    options.pcd_profile = PcdProfile::Profidrive;
    {
        Bus bus(options);
        EXPECT_FALSE(bus.decode(exchange_request(3, hex("04 7F 20 00"))).dp.danfoss_pcd());
        // A Danfoss drive (vlt) in its PROFIdrive profile keeps the Danfoss names.
        const DecodedTelegram& danfoss = bus.decode(exchange_request(4, hex("04 7F 20 00")));
        EXPECT_EQ(danfoss.dp.pcd_profile, PcdProfile::Profidrive);
        EXPECT_TRUE(danfoss.dp.danfoss_pcd());
    }
    options.pcd_profile = PcdProfile::Fc;
    {
        Bus bus(options);
        EXPECT_TRUE(bus.decode(exchange_request(3, hex("04 7F 20 00"))).dp.danfoss_pcd());
    }
}

TEST(BusDecoderTest, DirectionNames) {
    EXPECT_EQ(direction_name(Direction::Request), "request");
    EXPECT_EQ(direction_name(Direction::Response), "response");
}

// ---- DP-V1 and PROFIdrive ------------------------------------------------------------------

std::vector<std::uint8_t> msac_request(std::uint8_t slave, const std::vector<std::uint8_t>& du,
                                       std::uint8_t dsap = sap::kMsacC1,
                                       std::uint8_t ssap = sap::kMsacC1) {
    return telegram(slave, kMasterAddress, request_fc(FdlFunction::SrdHigh, true, true), dsap, ssap,
                    du);
}

std::vector<std::uint8_t> msac_response(std::uint8_t slave, const std::vector<std::uint8_t>& du,
                                        std::uint8_t ssap = sap::kMsacC1,
                                        std::uint8_t dsap = sap::kMsacC1) {
    return telegram(kMasterAddress, slave, response_fc(FdlStatus::DataLow), dsap, ssap, du);
}

TEST(BusDecoderTest, Dpv1WriteStateConflictAndReadResponseNamedAfterTheRequest) {
    Bus bus;
    const DecodedTelegram& write =
        bus.decode(msac_request(5, hex("5F 00 2F 0A 05 01 00 01 10 01 00 0C 00 04")));
    EXPECT_EQ(write.dp.service, Service::MsacC1);
    const Dpv1Pdu* pdu = write.dp.service_data.dpv1();
    ASSERT_NE(pdu, nullptr);
    EXPECT_TRUE(pdu->is_write());
    EXPECT_TRUE(pdu->on_parameter_channel());
    const ProfidriveMessage* request = write.dp.service_data.profidrive();
    ASSERT_NE(request, nullptr);
    EXPECT_FALSE(request->is_response);
    EXPECT_EQ(request->reference, 5);
    ASSERT_EQ(request->addresses.size(), 1u);
    EXPECT_EQ(request->addresses[0].pnu, 12);
    EXPECT_TRUE(write.problems().empty());

    const DecodedTelegram& echo = bus.decode(msac_response(5, hex("5F 00 2F 0A")));
    EXPECT_EQ(echo.request_frame, 1u);
    ASSERT_NE(echo.dp.service_data.dpv1(), nullptr);
    EXPECT_EQ(echo.dp.service_data.dpv1()->length, 10);
    EXPECT_EQ(echo.dp.service_data.profidrive(), nullptr);  // a write response has no data

    for (int poll = 0; poll < 2; ++poll) {
        const DecodedTelegram& read = bus.decode(msac_request(5, hex("5E 00 2F F0")));
        ASSERT_NE(read.dp.service_data.dpv1(), nullptr);
        EXPECT_TRUE(read.dp.service_data.dpv1()->is_read());
        EXPECT_EQ(read.dp.service_data.profidrive(), nullptr);
        const DecodedTelegram& busy = bus.decode(msac_response(5, hex("DE 80 B5 00")));
        ASSERT_NE(busy.dp.service_data.dpv1(), nullptr);
        EXPECT_TRUE(busy.dp.service_data.dpv1()->is_state_conflict());
        EXPECT_EQ(busy.dp.service_data.profidrive(), nullptr);
    }

    bus.decode(msac_request(5, hex("5E 00 2F F0")));
    const DecodedTelegram& answer =
        bus.decode(msac_response(5, hex("5E 00 2F 08 05 01 00 01 42 01 00 03")));
    const ProfidriveMessage* response = answer.dp.service_data.profidrive();
    ASSERT_NE(response, nullptr);
    EXPECT_TRUE(response->is_response);
    EXPECT_TRUE(response->has_request);
    EXPECT_EQ(response->request_frame, 1u);
    EXPECT_EQ(response->request_reference, 5);
    EXPECT_EQ(response->request_id, 0x01);
    ASSERT_EQ(response->addresses.size(), 1u);
    EXPECT_EQ(response->addresses[0].pnu, 12);
    EXPECT_EQ(response->addresses[0].subindex, 4);
    ASSERT_EQ(response->blocks.size(), 1u);
    EXPECT_EQ(response->blocks[0].format, 0x42);
    EXPECT_TRUE(answer.problems().empty());
}

TEST(BusDecoderTest, Dpv1RequestNamesOneResponseOnly) {
    Bus bus;
    bus.decode(msac_request(5, hex("5F 00 2F 0A 05 01 00 01 10 01 00 0C 00 04")));
    bus.decode(msac_response(5, hex("5F 00 2F 0A")));
    bus.decode(msac_request(5, hex("5E 00 2F F0")));
    const DecodedTelegram& first =
        bus.decode(msac_response(5, hex("5E 00 2F 08 05 01 00 01 42 01 00 03")));
    ASSERT_NE(first.dp.service_data.profidrive(), nullptr);
    EXPECT_TRUE(first.dp.service_data.profidrive()->has_request);
    // The same response again, with no new request written: an orphan, named after nothing.
    bus.decode(msac_request(5, hex("5E 00 2F F0")));
    const DecodedTelegram& again =
        bus.decode(msac_response(5, hex("5E 00 2F 08 05 01 00 01 42 01 00 03")));
    ASSERT_NE(again.dp.service_data.profidrive(), nullptr);
    EXPECT_FALSE(again.dp.service_data.profidrive()->has_request);
    EXPECT_TRUE(again.dp.service_data.profidrive()->addresses.empty());
}

TEST(BusDecoderTest, Dpv1ResponseNamesOnlyTheRequestOfItsSlaveSlotAndIndex) {
    Bus bus;
    bus.decode(msac_request(5, hex("5F 00 2F 0A 05 01 00 01 10 01 00 0C 00 04")));
    bus.decode(msac_response(5, hex("5F 00 2F 0A")));
    // Another slave's read response: its request is not in the capture.
    bus.decode(msac_request(6, hex("5E 00 2F F0")));
    const DecodedTelegram& other =
        bus.decode(msac_response(6, hex("5E 00 2F 08 07 01 00 01 42 01 00 03")));
    ASSERT_NE(other.dp.service_data.profidrive(), nullptr);
    EXPECT_FALSE(other.dp.service_data.profidrive()->has_request);
    EXPECT_EQ(other.dp.service_data.profidrive()->request_frame, 0u);
    EXPECT_TRUE(other.dp.service_data.profidrive()->addresses.empty());
    // Same slave, another slot.
    bus.decode(msac_request(5, hex("5E 01 2F F0")));
    const DecodedTelegram& slot =
        bus.decode(msac_response(5, hex("5E 01 2F 08 05 01 00 01 42 01 00 03")));
    ASSERT_NE(slot.dp.service_data.profidrive(), nullptr);
    EXPECT_FALSE(slot.dp.service_data.profidrive()->has_request);
}

TEST(BusDecoderTest, Dpv1ReadResponseWithoutItsRequestInTheCapture) {
    Bus bus;
    bus.decode(msac_request(5, hex("5E 00 2F F0")));
    const DecodedTelegram& answer =
        bus.decode(msac_response(5, hex("5E 00 2F 08 09 01 01 01 42 01 00 03")));
    const ProfidriveMessage* response = answer.dp.service_data.profidrive();
    ASSERT_NE(response, nullptr);
    EXPECT_FALSE(response->has_request);
    EXPECT_EQ(response->reference, 9);
    EXPECT_TRUE(response->addresses.empty());
}

TEST(BusDecoderTest, Dpv1LengthByteBoundsTheProfidriveMessage) {
    Bus bus;
    // Length 4 announces the header alone; the address after it is not part of the message.
    const DecodedTelegram& write =
        bus.decode(msac_request(5, hex("5F 00 2F 04 05 01 00 01 10 01 00 0C 00 04")));
    const ProfidriveMessage* request = write.dp.service_data.profidrive();
    ASSERT_NE(request, nullptr);
    EXPECT_TRUE(request->addresses.empty());
    ASSERT_EQ(write.problems().size(), 1u);
    EXPECT_EQ(write.problems()[0].kind, ProblemKind::ServiceDataShort);
    // Length 20 with 10 bytes: the message is what the data holds.
    bus.decode(msac_response(5, hex("5F 00 2F 14")));
    const DecodedTelegram& longer =
        bus.decode(msac_request(5, hex("5F 00 2F 14 06 01 00 01 10 01 00 0C 00 04")));
    ASSERT_NE(longer.dp.service_data.profidrive(), nullptr);
    EXPECT_EQ(longer.dp.service_data.profidrive()->addresses.size(), 1u);
}

TEST(BusDecoderTest, Dpv1EmptyDataUnitIsALinkLevelPoll) {
    Bus bus;
    const DecodedTelegram& poll = bus.decode(msac_request(5, {}));
    EXPECT_EQ(poll.dp.service, Service::MsacC1);
    const Dpv1Pdu* pdu = poll.dp.service_data.dpv1();
    ASSERT_NE(pdu, nullptr);
    EXPECT_EQ(pdu->layout, Dpv1Pdu::Layout::None);
    EXPECT_EQ(poll.dp.service_data.profidrive(), nullptr);
    EXPECT_TRUE(poll.problems().empty());
}

TEST(BusDecoderTest, Dpv1Class2InitiateAndConnectionDecode) {
    Bus bus;
    const DecodedTelegram& initiate = bus.decode(
        msac_request(5, hex("57 00 00 00 03 E8 01 00 00 00 00 00 00 02 00 02 02 31 05 30"),
                     sap::kResourceManager, sap::kMsacC2Master));
    EXPECT_EQ(initiate.dp.service, Service::MsacC2);
    const Dpv1Pdu* pdu = initiate.dp.service_data.dpv1();
    ASSERT_NE(pdu, nullptr);
    EXPECT_EQ(pdu->layout, Dpv1Pdu::Layout::Initiate);
    EXPECT_EQ(pdu->initiate.send_timeout, 1000);
    EXPECT_EQ(pdu->initiate.s_addr.size(), 2u);

    const DecodedTelegram& accepted =
        bus.decode(msac_response(5, hex("57 F0 01 00 00 00 00 00 00 02 00 02 02 31 05 30"),
                                 sap::kResourceManager, sap::kMsacC2Master));
    EXPECT_EQ(accepted.dp.service, Service::MsacC2);
    ASSERT_NE(accepted.dp.service_data.dpv1(), nullptr);
    EXPECT_EQ(accepted.dp.service_data.dpv1()->initiate.max_len_data_unit, 240);

    // The connection SAP (here 48): a class-2 Write carrying a PROFIdrive request.
    const DecodedTelegram& write = bus.decode(
        msac_request(5, hex("5F 00 2F 0A 0C 01 00 01 10 00 03 96 00 00"), 48, sap::kMsacC2Master));
    EXPECT_EQ(write.dp.service, Service::MsacC2);
    ASSERT_NE(write.dp.service_data.profidrive(), nullptr);
    EXPECT_EQ(write.dp.service_data.profidrive()->addresses[0].pnu, 918);
    bus.decode(msac_response(5, hex("5F 00 2F 0A"), 48, sap::kMsacC2Master));
    bus.decode(msac_request(5, hex("5E 00 2F F0"), 48, sap::kMsacC2Master));
    const DecodedTelegram& read = bus.decode(
        msac_response(5, hex("5E 00 2F 08 0C 81 00 01 44 01 00 00"), 48, sap::kMsacC2Master));
    const ProfidriveMessage* response = read.dp.service_data.profidrive();
    ASSERT_NE(response, nullptr);
    EXPECT_TRUE(response->negative());
    EXPECT_TRUE(response->has_request);
    EXPECT_EQ(response->addresses[0].pnu, 918);

    const DecodedTelegram& abort =
        bus.decode(msac_request(5, hex("58 00 13"), 48, sap::kMsacC2Master));
    ASSERT_NE(abort.dp.service_data.dpv1(), nullptr);
    EXPECT_EQ(abort.dp.service_data.dpv1()->layout, Dpv1Pdu::Layout::Abort);
}

TEST(BusDecoderTest, Dpv1CutShortPduIsAProblemAndDecodingGoesOn) {
    Bus bus;
    const DecodedTelegram& cut = bus.decode(msac_request(5, hex("5F 00")));
    ASSERT_EQ(cut.problems().size(), 1u);
    EXPECT_EQ(cut.problems()[0].kind, ProblemKind::ServiceDataShort);
    EXPECT_EQ(cut.problems()[0].offset, 10);  // SD2 header 4, DA SA FC, DSAP SSAP, function
    const DecodedTelegram& next = bus.decode(msac_request(5, hex("5E 00 2F F0")));
    EXPECT_TRUE(next.problems().empty());
}

// ../shared/protocol.md section 6.6 (ABB FPBA-01), whole DP-V1 PDUs through the decoder.
TEST(BusDecoderTest, Dpv1WorkedExamplesOfTheProtocolNotes) {
    Bus bus;
    const DecodedTelegram& single =
        bus.decode(msac_request(5, hex("5F 01 2F 0A 05 01 01 01 10 01 00 0C 00 04")));
    ASSERT_NE(single.dp.service_data.dpv1(), nullptr);
    EXPECT_EQ(single.dp.service_data.dpv1()->slot, 1);
    EXPECT_EQ(single.dp.service_data.dpv1()->length, 10);
    const ProfidriveMessage* m = single.dp.service_data.profidrive();
    ASSERT_NE(m, nullptr);
    EXPECT_EQ(m->reference, 5);
    EXPECT_EQ(m->id, 0x01);
    EXPECT_EQ(m->axis, 1);
    ASSERT_EQ(m->addresses.size(), 1u);
    EXPECT_EQ(m->addresses[0].attribute, 0x10);
    EXPECT_EQ(m->addresses[0].elements, 1);
    EXPECT_EQ(m->addresses[0].pnu, 12);
    EXPECT_EQ(m->addresses[0].subindex, 4);
    EXPECT_TRUE(single.problems().empty());
    bus.decode(msac_response(5, hex("5F 01 2F 0A")));

    const DecodedTelegram& three = bus.decode(msac_request(
        5, hex("5F 01 2F 16 06 01 01 03 10 01 00 0C 00 04 10 01 00 14 00 08 10 01 00 1E 00 13")));
    ASSERT_NE(three.dp.service_data.profidrive(), nullptr);
    EXPECT_EQ(three.dp.service_data.dpv1()->length, 22);
    const auto& addresses = three.dp.service_data.profidrive()->addresses;
    ASSERT_EQ(addresses.size(), 3u);
    EXPECT_EQ(addresses[1].pnu, 20);
    EXPECT_EQ(addresses[1].subindex, 8);
    EXPECT_EQ(addresses[2].pnu, 30);
    EXPECT_EQ(addresses[2].subindex, 19);
    EXPECT_TRUE(three.problems().empty());
    bus.decode(msac_response(5, hex("5F 01 2F 16")));

    const DecodedTelegram& station =
        bus.decode(msac_request(5, hex("5F 01 2F 0A 09 01 01 01 10 00 03 96 00 00")));
    ASSERT_NE(station.dp.service_data.profidrive(), nullptr);
    EXPECT_EQ(station.dp.service_data.profidrive()->addresses[0].pnu, 918);
    EXPECT_EQ(station.dp.service_data.profidrive()->addresses[0].elements, 0);
    bus.decode(msac_response(5, hex("5F 01 2F 0A")));
    bus.decode(msac_request(5, hex("5E 01 2F F0")));
    const DecodedTelegram& answer =
        bus.decode(msac_response(5, hex("5E 01 2F 08 09 01 01 01 42 01 00 03")));
    const ProfidriveMessage* response = answer.dp.service_data.profidrive();
    ASSERT_NE(response, nullptr);
    EXPECT_EQ(response->reference, 9);
    EXPECT_EQ(response->id, 0x01);
    EXPECT_EQ(response->axis, 1);
    EXPECT_EQ(response->count, 1);
    ASSERT_EQ(response->blocks.size(), 1u);
    EXPECT_EQ(response->blocks[0].format, 0x42);
    EXPECT_EQ(profidrive_number(response->blocks[0], 0)->integer, 3);
    EXPECT_TRUE(response->has_request);
    EXPECT_EQ(response->request_frame, 5u);
    EXPECT_EQ(response->addresses[0].pnu, 918);
    EXPECT_TRUE(answer.problems().empty());
}

// The decoder keeps at most 256 PROFIdrive requests (BusDecoder::kKeptProfidriveRequests), one
// per master, slave, slot and index. A Write on a 257th key takes the place of the request kept
// longest: a response to that one is named after nothing, the newer ones still name theirs.
TEST(BusDecoderTest, Dpv1KeptRequestsAreBoundedAndTheOldestMakesRoom) {
    constexpr int kKept = 256;  // BusDecoder::kKeptProfidriveRequests (private)
    // A Write on `slot` (index 47) reading PNU 0x100 + slot.
    const auto write = [](std::uint8_t slot) {
        return std::vector<std::uint8_t>{
            0x5F, slot, 0x2F, 0x0A,             // Write, slot, index 47, 10 bytes
            0x05, 0x01, 0x00, 0x01,             // reference 5, request value, axis 0, 1 PNU
            0x10, 0x01, 0x01, slot, 0x00, 0x00  // value, 1 element, PNU, subindex 0
        };
    };
    const auto read = [](std::uint8_t slot) {
        return std::vector<std::uint8_t>{0x5E, slot, 0x2F, 0xF0};
    };
    // The parameter response on `slot`: reference 5, request parameter (+), one Word: 3.
    const auto response = [](std::uint8_t slot) {
        return std::vector<std::uint8_t>{
            0x5E, slot, 0x2F, 0x08,  // Read, slot, index 47, 8 bytes
            0x05, 0x01, 0x00, 0x01,  // reference 5, response ID 0x01, axis 0, 1 parameter
            0x42, 0x01, 0x00, 0x03   // Word, 1 value: 3
        };
    };
    Bus bus;
    // Slave 5, slots 0..255: frames 1..256 fill the store.
    for (int slot = 0; slot < kKept; ++slot)
        bus.decode(msac_request(5, write(static_cast<std::uint8_t>(slot))));
    // Slave 6, slot 0 (frame 257): slave 5's slot 0, written in frame 1, makes room.
    bus.decode(msac_request(6, write(0)));

    // Reads `slot` of `slave` and returns the parameter response's message.
    const auto answer = [&](std::uint8_t slave, std::uint8_t slot) {
        bus.decode(msac_request(slave, read(slot)));
        return bus.decode(msac_response(slave, response(slot))).dp.service_data.profidrive();
    };
    // The response names the request of `frame` and its PNU.
    const auto expect_named = [&](std::uint8_t slave, std::uint8_t slot, std::uint64_t frame,
                                  std::uint16_t pnu) {
        SCOPED_TRACE(testing::Message() << "slave " << int{slave} << " slot " << int{slot});
        const ProfidriveMessage* m = answer(slave, slot);
        ASSERT_NE(m, nullptr);
        EXPECT_TRUE(m->has_request);
        EXPECT_EQ(m->request_frame, frame);
        ASSERT_EQ(m->addresses.size(), 1u);
        EXPECT_EQ(m->addresses[0].pnu, pnu);
    };

    const ProfidriveMessage* evicted = answer(5, 0);
    ASSERT_NE(evicted, nullptr);
    EXPECT_FALSE(evicted->has_request);
    EXPECT_EQ(evicted->request_frame, 0u);
    EXPECT_TRUE(evicted->addresses.empty());
    expect_named(5, 1, 2, 0x101);    // the next oldest, slot 1 of frame 2, is still kept
    expect_named(6, 0, 257, 0x100);  // and so is the request that took the place
}

}  // namespace
}  // namespace dpscope
