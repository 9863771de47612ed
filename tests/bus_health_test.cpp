// Bus health: hand-built telegram sequences decoded through BusDecoder and fed to the tracker,
// with exact counters asserted for every rule of docs/bus-health.md.
#include "protocols/profibus/health/bus_health.hpp"

#include <gtest/gtest.h>

#include <array>
#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include "protocols/profibus/bus_decoder.hpp"
#include "protocols/profibus/telegram_builder.hpp"
#include "simulator/simulator.hpp"

namespace dpscope {
namespace {

constexpr std::uint8_t kMaster = 1;
constexpr std::int64_t kMs = 1'000'000;
constexpr std::int64_t kStart = 1'000'000'000'000;

const std::uint8_t kOutputs[2] = {0x11, 0x22};
const std::uint8_t kInputs[2] = {0x33, 0x44};
const std::uint8_t kPrm[7] = {0x88, 0x01, 0x01, 0x0B, 0x00, 0x12, 0x34};
const std::uint8_t kCfg[1] = {0x31};

class BusHealthTest : public ::testing::Test {
  protected:
    BusHealthTest() { configure({}); }

    void configure(BusHealthOptions options) {
        tracker_ = std::make_unique<BusHealthTracker>(options);
        decoder_ = std::make_unique<BusDecoder>();
    }
    BusHealthTracker& tracker() { return *tracker_; }

    // Feeds one telegram, `gap` after the previous one (kNoTime: no time at all).
    std::vector<HealthEvent> feed(const std::vector<std::uint8_t>& bytes, std::int64_t gap = kMs) {
        kept_.push_back(bytes);
        const std::vector<std::uint8_t>& b = kept_.back();
        std::int64_t time = kNoTime;
        if (gap != kNoTime) {
            now_ += gap;
            time = now_;
        }
        const DecodedTelegram& t = decoder_->decode(Bytes(b.data(), b.size()), time, ++frame_);
        std::span<const HealthEvent> events = tracker_->observe(t);
        return {events.begin(), events.end()};
    }

    bool fcb(std::uint8_t slave) { return fcb_[slave] = !fcb_[slave]; }

    // Requests from the master (next FCB unless `repeat`).
    std::vector<std::uint8_t> dx(std::uint8_t slave, bool repeat = false,
                                 std::uint8_t master = kMaster) {
        const bool bit = repeat ? fcb_[slave] : fcb(slave);
        return build_telegram({slave, master, request_fc(FdlFunction::SrdHigh, bit, true),
                               std::nullopt, std::nullopt, Bytes(kOutputs, 2)});
    }
    std::vector<std::uint8_t> sap_request(std::uint8_t slave, std::uint8_t dsap, Bytes du,
                                          FdlFunction function = FdlFunction::SrdHigh) {
        return build_telegram(
            {slave, kMaster, request_fc(function, fcb(slave), true), dsap, 62, du});
    }
    std::vector<std::uint8_t> diag(std::uint8_t slave) { return sap_request(slave, 60, {}); }
    std::vector<std::uint8_t> prm(std::uint8_t slave) {
        return sap_request(slave, 61, Bytes(kPrm, 7));
    }
    std::vector<std::uint8_t> cfg(std::uint8_t slave) {
        return sap_request(slave, 62, Bytes(kCfg, 1));
    }
    std::vector<std::uint8_t> get_cfg(std::uint8_t slave) { return sap_request(slave, 59, {}); }
    std::vector<std::uint8_t> status_request(std::uint8_t da, std::uint8_t sa = kMaster) {
        return build_telegram(
            {da, sa, request_fc(FdlFunction::FdlStatus), std::nullopt, std::nullopt, {}});
    }
    std::vector<std::uint8_t> sdn(std::uint8_t da) {
        return build_telegram({da, kMaster, request_fc(FdlFunction::SdnHigh), std::nullopt,
                               std::nullopt, Bytes(kOutputs, 2)});
    }
    std::vector<std::uint8_t> sda(std::uint8_t da) {
        return build_telegram({da, kMaster, request_fc(FdlFunction::SdaHigh, fcb(da), true),
                               std::nullopt, std::nullopt, Bytes(kOutputs, 2)});
    }

    // Responses to the master.
    static std::vector<std::uint8_t> data(std::uint8_t slave, std::uint8_t master = kMaster) {
        return build_telegram({master, slave, response_fc(FdlStatus::DataLow), std::nullopt,
                               std::nullopt, Bytes(kInputs, 2)});
    }
    static std::vector<std::uint8_t> sd1(std::uint8_t slave, FdlStatus status,
                                         std::uint8_t station_type = 0) {
        return build_telegram(
            {kMaster, slave, response_fc(status, station_type), std::nullopt, std::nullopt, {}});
    }
    std::vector<std::uint8_t> diag_data(std::uint8_t slave, std::uint8_t s1 = 0,
                                        std::uint8_t s2 = 0x04) {
        diag_du_.push_back({s1, s2, 0x00, kMaster, 0x12, 0x34});
        const std::vector<std::uint8_t>& du = diag_du_.back();
        return build_telegram(
            {kMaster, slave, response_fc(FdlStatus::DataLow), 62, 60, Bytes(du.data(), du.size())});
    }
    static std::vector<std::uint8_t> sc() {
        std::vector<std::uint8_t> out;
        append_short_ack(out);
        return out;
    }
    static std::vector<std::uint8_t> token(std::uint8_t da, std::uint8_t sa) {
        std::vector<std::uint8_t> out;
        append_token(out, da, sa);
        return out;
    }
    static std::vector<std::uint8_t> damaged(std::vector<std::uint8_t> bytes) {
        bytes[bytes.size() - 2] ^= 0x01;  // the FCS
        return bytes;
    }

    // One Data_Exchange poll answered with data.
    void exchange(std::uint8_t slave) {
        feed(dx(slave));
        feed(data(slave));
    }
    // Brings a slave into data exchange: diag, prm, cfg, diag, dx.
    void start_up(std::uint8_t slave) {
        feed(diag(slave));
        feed(diag_data(slave, 0x02));
        feed(prm(slave));
        feed(sc());
        feed(cfg(slave));
        feed(sc());
        feed(diag(slave));
        feed(diag_data(slave));
        exchange(slave);
    }

    const StationHealth* station(std::uint8_t address) {
        for (const StationHealth& s : tracker_->health().stations)
            if (s.address == address) return &s;
        return nullptr;
    }
    const MasterHealth* master(std::uint8_t address) {
        for (const MasterHealth& m : tracker_->health().masters)
            if (m.address == address) return &m;
        return nullptr;
    }
    std::int64_t now() const { return now_; }

  private:
    std::unique_ptr<BusHealthTracker> tracker_;
    std::unique_ptr<BusDecoder> decoder_;
    std::deque<std::vector<std::uint8_t>> kept_;
    std::deque<std::vector<std::uint8_t>> diag_du_;
    std::array<bool, 128> fcb_{};
    std::uint64_t frame_ = 0;
    std::int64_t now_ = kStart;
};

bool has_reason(const Judgement& j, HealthThreshold kind, Verdict verdict) {
    for (const VerdictReason& r : j.reasons)
        if (r.threshold == kind && r.verdict == verdict) return true;
    return false;
}

// ---- listing and roles -----------------------------------------------------------------------

TEST_F(BusHealthTest, GapPollDoesNotList) {
    feed(status_request(5));
    feed(status_request(6));
    feed(token(kMaster, kMaster));
    tracker().finish();
    const BusHealth& h = tracker().health();
    ASSERT_EQ(h.stations.size(), 1u);
    EXPECT_EQ(h.stations[0].address, kMaster);
    EXPECT_EQ(h.stations[0].role, StationRole::Master);
    EXPECT_EQ(h.stations[0].state, StationState::Active);
    EXPECT_EQ(h.segment.telegrams, 3u);
}

TEST_F(BusHealthTest, FdlStatusAnswerListsWithItsRole) {
    feed(status_request(5));
    feed(sd1(5, FdlStatus::Ok, 0));  // a slave
    feed(status_request(6));
    feed(sd1(6, FdlStatus::Ok, 2));  // a master ready for the ring
    feed(status_request(7));
    feed(sd1(7, FdlStatus::Ok, 3));  // a master in the ring
    tracker().finish();
    ASSERT_NE(station(5), nullptr);
    EXPECT_EQ(station(5)->role, StationRole::Slave);
    EXPECT_EQ(station(5)->requests, 1u);
    EXPECT_EQ(station(5)->answers, 1u);
    EXPECT_EQ(station(5)->no_answers, 0u);
    EXPECT_EQ(station(6)->role, StationRole::Master);
    EXPECT_EQ(station(7)->role, StationRole::Master);
    EXPECT_NE(master(6), nullptr);
    EXPECT_EQ(tracker().health().stations.size(), 4u);  // 1, 5, 6, 7
}

TEST_F(BusHealthTest, RolesAndShortAckListsTheStationAsked) {
    feed(prm(3));
    feed(sc());
    feed(dx(4));  // addressed, never heard
    tracker().finish();
    EXPECT_EQ(station(kMaster)->role, StationRole::Master);
    EXPECT_EQ(station(kMaster)->telegrams_sent, 2u);
    EXPECT_EQ(station(3)->role, StationRole::Slave);
    EXPECT_EQ(station(3)->telegrams_sent, 1u);
    EXPECT_EQ(station(3)->state, StationState::Configuring);
    EXPECT_EQ(station(4)->role, StationRole::Unknown);
    EXPECT_EQ(station(4)->state, StationState::Unknown);
    EXPECT_EQ(station(4)->first_frame, 3u);
    ASSERT_EQ(tracker().health().masters.size(), 1u);
    EXPECT_EQ(tracker().health().masters[0].requests, 2u);
}

TEST_F(BusHealthTest, BroadcastCountsForNobody) {
    feed(sdn(127));
    tracker().finish();
    EXPECT_EQ(tracker().health().stations.size(), 1u);
    EXPECT_EQ(station(kMaster)->requests, 0u);
    EXPECT_EQ(master(kMaster)->requests, 1u);
}

// ---- states --------------------------------------------------------------------------------

TEST_F(BusHealthTest, StartUpStatesAndTimeline) {
    start_up(3);
    tracker().finish();
    const StationHealth* s = station(3);
    ASSERT_NE(s, nullptr);
    EXPECT_EQ(s->state, StationState::DataExchange);
    ASSERT_EQ(s->timeline.size(), 3u);
    EXPECT_EQ(s->timeline[0].state, StationState::DiagnosisOnly);
    EXPECT_EQ(s->timeline[1].state, StationState::Configuring);
    EXPECT_EQ(s->timeline[2].state, StationState::DataExchange);
    EXPECT_EQ(s->timeline[2].frame, 10u);
    EXPECT_EQ(s->state_changes, 3u);
    EXPECT_EQ(s->requests, 5u);
    EXPECT_EQ(s->answers, 5u);
    EXPECT_EQ(s->diag_requests, 2u);
    EXPECT_EQ(s->diag_answers, 2u);
    EXPECT_EQ(s->diag_faults, 0u);  // Station_Not_Ready before Set_Prm is the start-up's
    EXPECT_EQ(s->resyncs, 0u);
    EXPECT_EQ(s->judgement.verdict, Verdict::Good);
    EXPECT_TRUE(s->judgement.reasons.empty());
}

TEST_F(BusHealthTest, DiagnosisOnlyAfterLostCyclesOfDiagInDataExchange) {
    start_up(3);
    feed(diag(3));
    feed(diag_data(3));
    feed(diag(3));
    feed(diag_data(3));
    tracker().judge();
    EXPECT_EQ(station(3)->state, StationState::DataExchange);
    feed(diag(3));
    feed(diag_data(3));
    tracker().judge();
    EXPECT_EQ(station(3)->state, StationState::DiagnosisOnly);
    exchange(3);
    tracker().judge();
    EXPECT_EQ(station(3)->state, StationState::DataExchange);
    EXPECT_EQ(station(3)->state_changes, 5u);
}

TEST_F(BusHealthTest, ResyncCountsOncePerReparameterisation) {
    start_up(3);
    feed(prm(3));
    feed(sc());
    feed(cfg(3));
    feed(sc());
    exchange(3);
    feed(cfg(3));
    feed(sc());
    tracker().finish();
    EXPECT_EQ(station(3)->resyncs, 2u);
    EXPECT_EQ(station(3)->state, StationState::Configuring);
    EXPECT_TRUE(has_reason(station(3)->judgement, HealthThreshold::ResyncsWeak, Verdict::Weak));
}

// ---- cycles, repeats, no answers, lost -----------------------------------------------------

TEST_F(BusHealthTest, RepeatsAndMaxPerCycle) {
    start_up(3);
    feed(dx(3));
    feed(dx(3, true));
    feed(dx(3, true));
    feed(data(3));
    feed(dx(3));
    feed(dx(3, true));
    feed(data(3));
    tracker().finish();
    const StationHealth* s = station(3);
    EXPECT_EQ(s->repeats, 3u);
    EXPECT_EQ(s->max_repeats_per_cycle, 2u);
    EXPECT_EQ(s->no_answers, 3u);  // each repeat followed an unanswered request
    EXPECT_EQ(s->requests, 10u);
    EXPECT_EQ(s->lost_events, 0u);
    EXPECT_TRUE(has_reason(s->judgement, HealthThreshold::RepeatPercentBad, Verdict::Bad));
    EXPECT_TRUE(has_reason(s->judgement, HealthThreshold::RepeatsPerCycleWeak, Verdict::Weak));
    EXPECT_TRUE(has_reason(s->judgement, HealthThreshold::NoAnswerPercentBad, Verdict::Bad));
    EXPECT_EQ(s->judgement.reasons.back().verdict, Verdict::Weak);  // worst first
    EXPECT_EQ(s->judgement.reasons.front().verdict, Verdict::Bad);
}

TEST_F(BusHealthTest, FdlStatusResetsTheFrameCount) {
    start_up(3);
    feed(dx(3));
    feed(data(3));
    feed(status_request(3));
    feed(sd1(3, FdlStatus::Ok));
    feed(dx(3, true));  // same FCB, but the link restarted
    feed(data(3));
    tracker().finish();
    EXPECT_EQ(station(3)->repeats, 0u);
}

TEST_F(BusHealthTest, LostAfterThreeUnansweredCyclesAndReturned) {
    start_up(3);
    EXPECT_TRUE(feed(dx(3)).empty());
    feed(dx(3));
    feed(dx(3));
    std::vector<HealthEvent> events = feed(dx(3));  // closes the third unanswered cycle
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(events[0].kind, HealthEventKind::StationLost);
    EXPECT_EQ(events[0].address, 3);
    EXPECT_EQ(events[0].role, StationRole::Slave);
    events = feed(data(3));
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(events[0].kind, HealthEventKind::StationReturned);
    tracker().finish();
    const StationHealth* s = station(3);
    EXPECT_EQ(s->lost_events, 1u);
    EXPECT_EQ(s->returns, 1u);
    EXPECT_EQ(s->no_answers, 3u);
    EXPECT_EQ(s->state, StationState::DataExchange);
    ASSERT_GE(s->timeline.size(), 2u);
    EXPECT_EQ(s->timeline[s->timeline.size() - 2].state, StationState::Lost);
    EXPECT_TRUE(s->timeline.back().returned);
    EXPECT_EQ(s->judgement.verdict, Verdict::Bad);
    EXPECT_TRUE(has_reason(s->judgement, HealthThreshold::LostEventsBad, Verdict::Bad));
}

TEST_F(BusHealthTest, LostCyclesFiveAndFinishClosesTheLastCycles) {
    BusHealthOptions options;
    ASSERT_TRUE(options.thresholds.set(HealthThreshold::LostCycles, 5).has_value());
    configure(options);
    start_up(3);
    for (int i = 0; i < 5; ++i)
        feed(dx(3));
    tracker().judge();
    EXPECT_EQ(station(3)->lost_events, 0u);
    feed(token(kMaster, kMaster));  // ends the wait for the fifth reply
    tracker().finish();
    EXPECT_EQ(station(3)->lost_events, 1u);
    EXPECT_EQ(station(3)->state, StationState::Lost);
}

TEST_F(BusHealthTest, NeverAnsweringStationIsLostOnceListed) {
    for (int i = 0; i < 4; ++i)
        feed(dx(9));
    tracker().judge();
    EXPECT_EQ(station(9)->state, StationState::Lost);
    EXPECT_EQ(station(9)->role, StationRole::Unknown);
    EXPECT_EQ(station(9)->no_answers, 3u);
}

TEST_F(BusHealthTest, ResyncOnReturnThroughSetPrm) {
    start_up(3);
    for (int i = 0; i < 4; ++i)
        feed(dx(3));
    feed(prm(3));
    feed(sc());
    tracker().finish();
    EXPECT_EQ(station(3)->returns, 1u);
    EXPECT_EQ(station(3)->resyncs, 1u);
    EXPECT_EQ(station(3)->state, StationState::Configuring);
}

// ---- illegal answers ------------------------------------------------------------------------

TEST_F(BusHealthTest, NotAskedAnswers) {
    start_up(3);
    exchange(4);
    exchange(5);
    feed(status_request(3, 2));  // master 2 has asked station 3 something before
    feed(build_telegram({2, 3, response_fc(FdlStatus::Ok), std::nullopt, std::nullopt, {}}));
    feed(data(4));  // nothing waits
    feed(dx(3));
    feed(data(5));  // another station than the one asked
    feed(dx(3));
    feed(data(3, 2));  // to another master
    feed(sc());        // a stray short acknowledge: the segment's
    tracker().finish();
    EXPECT_EQ(station(4)->illegal_answers[0], 1u);
    EXPECT_EQ(station(5)->illegal_answers[0], 1u);
    EXPECT_EQ(station(3)->illegal_answers[0], 1u);
    EXPECT_EQ(station(3)->no_answers, 2u);
    EXPECT_EQ(tracker().health().segment.unasked_short_acks, 1u);
    EXPECT_TRUE(
        has_reason(station(4)->judgement, HealthThreshold::IllegalAnswersWeak, Verdict::Weak));
}

TEST_F(BusHealthTest, WrongKindAnswers) {
    start_up(3);
    feed(sda(3));
    feed(data(3));  // data to SDA
    feed(sda(3));
    feed(sd1(3, FdlStatus::NoResponseData));  // SRD status to SDA
    feed(sda(3));
    feed(sc());  // right
    feed(dx(3));
    feed(sd1(3, FdlStatus::Ok));  // SDA acknowledgement to SRD
    feed(status_request(3));
    feed(data(3));  // data to FDL_Status
    tracker().finish();
    const std::size_t wrong = static_cast<std::size_t>(IllegalAnswer::WrongKind);
    EXPECT_EQ(station(3)->illegal_answers[wrong], 4u);
    EXPECT_EQ(station(3)->illegal_answers_total(), 4u);
}

TEST_F(BusHealthTest, ShortAckWhereDataWasDue) {
    start_up(3);
    feed(diag(3));
    feed(sc());
    feed(get_cfg(3));
    feed(sd1(3, FdlStatus::NoResponseData));
    feed(dx(3));
    feed(sc());  // answered with data before
    feed(dx(4));
    feed(sc());  // never answered with data: allowed
    feed(get_cfg(3));
    feed(sd1(3, FdlStatus::NoService));  // a refusal, not a short acknowledge
    tracker().finish();
    const std::size_t kind = static_cast<std::size_t>(IllegalAnswer::ShortAck);
    EXPECT_EQ(station(3)->illegal_answers[kind], 3u);
    EXPECT_EQ(station(4)->illegal_answers_total(), 0u);
}

// ---- diagnosis and negative answers ---------------------------------------------------------

TEST_F(BusHealthTest, DiagFaultBits) {
    start_up(3);  // Station_Not_Ready before Set_Prm: not counted
    feed(diag(3));
    feed(diag_data(3, 0x02));  // Station_Not_Ready
    feed(diag(3));
    feed(diag_data(3, 0x04));  // Cfg_Fault
    feed(diag(3));
    feed(diag_data(3, 0x08 | 0x40));  // Ext_Diag, Prm_Fault
    feed(diag(3));
    feed(diag_data(3, 0x00, 0x04 | 0x02));  // Stat_Diag
    feed(diag(3));
    feed(diag_data(3, 0x80));  // Master_Lock: no fault
    tracker().finish();
    const StationHealth* s = station(3);
    EXPECT_EQ(s->diag_requests, 7u);
    EXPECT_EQ(s->diag_answers, 7u);
    EXPECT_EQ(s->diag_faults, 4u);
    EXPECT_EQ(s->diag_fault_bits[static_cast<std::size_t>(DiagFault::StationNotReady)], 1u);
    EXPECT_EQ(s->diag_fault_bits[static_cast<std::size_t>(DiagFault::CfgFault)], 1u);
    EXPECT_EQ(s->diag_fault_bits[static_cast<std::size_t>(DiagFault::ExtDiag)], 1u);
    EXPECT_EQ(s->diag_fault_bits[static_cast<std::size_t>(DiagFault::PrmFault)], 1u);
    EXPECT_EQ(s->diag_fault_bits[static_cast<std::size_t>(DiagFault::StatDiag)], 1u);
}

TEST_F(BusHealthTest, NegativeAnswersByStatus) {
    start_up(3);
    const FdlStatus statuses[] = {FdlStatus::UserError,     FdlStatus::NoResource,
                                  FdlStatus::NoService,     FdlStatus::NoResponseData,
                                  FdlStatus::DataHigh,      FdlStatus::NotReceivedDataHigh,
                                  FdlStatus::NoResponseData};
    for (FdlStatus status : statuses) {
        feed(dx(3));
        feed(sd1(3, status));
    }
    tracker().finish();
    const StationHealth* s = station(3);
    EXPECT_EQ(s->negative_answers[static_cast<std::size_t>(NegativeAnswer::UE)], 1u);
    EXPECT_EQ(s->negative_answers[static_cast<std::size_t>(NegativeAnswer::RR)], 1u);
    EXPECT_EQ(s->negative_answers[static_cast<std::size_t>(NegativeAnswer::RS)], 1u);
    EXPECT_EQ(s->negative_answers[static_cast<std::size_t>(NegativeAnswer::NR)], 2u);
    EXPECT_EQ(s->negative_answers[static_cast<std::size_t>(NegativeAnswer::DH)], 1u);
    EXPECT_EQ(s->negative_answers[static_cast<std::size_t>(NegativeAnswer::RDH)], 1u);
    EXPECT_EQ(s->negative_answers_total(), 7u);
    EXPECT_TRUE(has_reason(s->judgement, HealthThreshold::RefusalsWeak, Verdict::Weak));
}

// ---- damaged telegrams ----------------------------------------------------------------------

TEST_F(BusHealthTest, DamagedTelegramAttribution) {
    start_up(3);
    start_up(4);
    feed(dx(3));
    feed(damaged(data(3)));  // in the answer's place: station 3
    feed(damaged(dx(4)));    // a request: its DA
    feed(damaged(data(4)));  // a response, nothing waiting: its SA
    feed(damaged(dx(50)));   // an unlisted address: the segment's
    feed({0x68, 0x05});      // truncated: no addresses
    tracker().finish();
    const SegmentHealth& seg = tracker().health().segment;
    EXPECT_EQ(seg.damaged, 5u);
    EXPECT_EQ(seg.unattributed_damaged, 2u);
    EXPECT_EQ(station(3)->fcs_errors, 1u);
    EXPECT_EQ(station(4)->fcs_errors, 2u);
    EXPECT_EQ(station(3)->no_answers, 0u);
    EXPECT_EQ(station(50), nullptr);
    EXPECT_TRUE(
        has_reason(station(3)->judgement, HealthThreshold::FcsErrorPercentBad, Verdict::Bad));
    EXPECT_EQ(seg.judgement.verdict, Verdict::Bad);
    EXPECT_TRUE(has_reason(seg.judgement, HealthThreshold::FcsErrorPercentBad, Verdict::Bad));
}

TEST_F(BusHealthTest, GarbageNeverCrashes) {
    start_up(3);
    const std::vector<std::vector<std::uint8_t>> garbage = {{},
                                                            {0x10},
                                                            {0x10, 0x03},
                                                            {0x68},
                                                            {0x68, 0xFF, 0xFF, 0x68},
                                                            {0xA2, 0x03, 0x01},
                                                            {0xDC},
                                                            {0xDC, 0x7F},
                                                            {0xE5, 0xE5},
                                                            {0x00, 0x01, 0x02},
                                                            {0x16}};
    for (const auto& g : garbage) {
        feed(dx(3));
        feed(g);
    }
    for (const auto& g : garbage)
        feed(g, kNoTime);
    tracker().finish();
    const SegmentHealth& seg = tracker().health().segment;
    EXPECT_EQ(seg.telegrams, 10u + 2 * 11 + 11);
    EXPECT_GE(seg.damaged, 10u);
}

// ---- masters --------------------------------------------------------------------------------

TEST_F(BusHealthTest, TokenRotationAndMasterLost) {
    feed(token(2, kMaster), 0);
    feed(token(kMaster, 2), 3 * kMs);
    feed(token(2, kMaster), 7 * kMs);   // rotation of 2: 10 ms
    feed(token(kMaster, 2), 3 * kMs);   // rotation of 1: 10 ms
    feed(token(2, kMaster), 11 * kMs);  // rotation of 2: 14 ms
    // Master 2 stops taking the token: master 1 passes it again and again.
    std::vector<HealthEvent> events;
    for (int i = 0; i < 3; ++i) {
        events = feed(token(2, kMaster), 5 * kMs);
    }
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(events[0].kind, HealthEventKind::StationLost);
    EXPECT_EQ(events[0].address, 2);
    EXPECT_EQ(events[0].role, StationRole::Master);
    events = feed(token(kMaster, 2), 5 * kMs);
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(events[0].kind, HealthEventKind::StationReturned);
    tracker().finish();
    const MasterHealth* m2 = master(2);
    ASSERT_NE(m2, nullptr);
    EXPECT_EQ(m2->tokens_received, 6u);
    EXPECT_EQ(m2->tokens_passed, 3u);
    EXPECT_EQ(m2->tokens_not_taken, 3u);
    EXPECT_EQ(m2->token_rotation.count(), 5u);
    EXPECT_EQ(m2->token_rotation.min(), 5 * kMs);
    EXPECT_EQ(m2->token_rotation.max(), 14 * kMs);
    EXPECT_EQ(station(2)->lost_events, 1u);
    EXPECT_EQ(station(2)->returns, 1u);
    EXPECT_EQ(station(2)->state, StationState::Active);
    EXPECT_EQ(master(kMaster)->token_rotation.count(), 2u);
    EXPECT_EQ(master(kMaster)->tokens_passed, 6u);
}

TEST_F(BusHealthTest, CycleTimeJitterAndSlavesPolled) {
    start_up(3);
    start_up(4);
    // Cycles of 10, 12, 10 ms: starts at the second poll of station 3 in a cycle.
    const std::int64_t gaps[] = {10, 12, 10};
    exchange(3);
    exchange(4);
    for (std::int64_t gap : gaps) {
        feed(dx(3), gap * kMs - 3 * kMs);
        feed(data(3));
        exchange(4);
    }
    tracker().finish();
    const MasterHealth* m = master(kMaster);
    ASSERT_NE(m, nullptr);
    EXPECT_EQ(m->slaves_polled, 2u);
    // The first cycle ran from station 3's start-up exchange into station 4's start-up.
    ASSERT_EQ(m->cycle.count(), 4u);
    EXPECT_EQ(m->cycle.max(), 12 * kMs);
    EXPECT_EQ(m->cycle_series.points().size(), 4u);
    EXPECT_EQ(m->cycle_series.points().back().max_ns, 10 * kMs);
}

TEST_F(BusHealthTest, CycleJitterIsTheMeanAbsoluteDifference) {
    start_up(3);
    const std::int64_t gaps[] = {10, 14, 10, 10};
    for (std::int64_t gap : gaps) {
        feed(dx(3), gap * kMs - kMs);
        feed(data(3));
    }
    tracker().finish();
    const MasterHealth* m = master(kMaster);
    // Cycles: (start-up exchange to first) 10, 14, 10, 10 ms: differences 4, 4, 0.
    ASSERT_EQ(m->cycle.count(), 4u);
    EXPECT_DOUBLE_EQ(m->cycle_jitter_ns, 8.0 * kMs / 3.0);
    // 2.67 ms of an 11 ms mean: 24 % > 10 %.
    EXPECT_TRUE(has_reason(m->judgement, HealthThreshold::CycleJitterPercentWeak, Verdict::Weak));
}

TEST_F(BusHealthTest, TargetRotationWeakAndBad) {
    BusHealthOptions options;
    ASSERT_TRUE(options.thresholds.set(HealthThreshold::TargetRotationMs, 10).has_value());
    configure(options);
    for (int i = 0; i < 30; ++i)
        feed(token(kMaster, kMaster), 9 * kMs);
    tracker().judge();
    EXPECT_EQ(master(kMaster)->judgement.verdict, Verdict::Good);
    for (int i = 0; i < 5; ++i)
        feed(token(kMaster, kMaster), 12 * kMs);
    tracker().judge();
    EXPECT_EQ(master(kMaster)->judgement.verdict, Verdict::Weak);
    feed(token(kMaster, kMaster), 16 * kMs);
    std::span<const HealthEvent> bad = tracker().judge();
    EXPECT_EQ(master(kMaster)->judgement.verdict, Verdict::Bad);
    ASSERT_EQ(bad.size(), 2u);  // the master and the segment
    EXPECT_EQ(bad[0].kind, HealthEventKind::VerdictBad);
    EXPECT_EQ(bad[0].address, kMaster);
    EXPECT_EQ(bad[0].role, StationRole::Master);
    EXPECT_EQ(bad[1].address, kSegmentAddress);
    EXPECT_TRUE(tracker().judge().empty());  // only on turning bad
}

// ---- capture, load, time --------------------------------------------------------------------

TEST_F(BusHealthTest, RatesLoadAndIdle) {
    BusHealthOptions options;
    options.baud = 1'100'000;  // 11 bits: 10 us per byte
    configure(options);
    feed(token(kMaster, kMaster), 0);       // 3 bytes: 30 us
    feed(token(kMaster, kMaster), 70'000);  // ends at 100 us
    tracker().finish();
    const SegmentHealth& seg = tracker().health().segment;
    EXPECT_EQ(seg.telegrams, 2u);
    EXPECT_EQ(seg.bytes, 6u);
    EXPECT_EQ(seg.end_ns - seg.first_ns, 100'000);
    EXPECT_NEAR(seg.busy_ns, 60'000, 1e-6);
    EXPECT_NEAR(seg.load_percent(), 60.0, 1e-9);
    EXPECT_NEAR(seg.idle_s(), 40e-6, 1e-12);
    EXPECT_NEAR(seg.telegrams_per_second(), 20'000, 1e-6);
}

// The segment's times whatever order the telegrams' times come in: the first time is the first
// telegram that has one, the end the latest time; a telegram without a time, at the same time or
// earlier (a capture's clock stepping back) moves neither, and the next later one moves the end.
TEST_F(BusHealthTest, SegmentTimesWhateverOrderTheTimesComeIn) {
    const SegmentHealth& seg = tracker().health().segment;
    feed(token(kMaster, kMaster), kNoTime);
    EXPECT_EQ(seg.first_ns, kNoTime);
    EXPECT_EQ(seg.end_ns, kNoTime);
    feed(token(kMaster, kMaster), kMs);
    const std::int64_t first = now();
    EXPECT_EQ(seg.first_ns, first);
    EXPECT_EQ(seg.end_ns, first);
    feed(token(kMaster, kMaster), 2 * kMs);
    EXPECT_EQ(seg.end_ns, first + 2 * kMs);
    feed(token(kMaster, kMaster), -5 * kMs);  // earlier than the first
    EXPECT_EQ(seg.end_ns, first + 2 * kMs);
    feed(token(kMaster, kMaster), 5 * kMs);  // the same time as the end
    feed(token(kMaster, kMaster), kNoTime);
    EXPECT_EQ(seg.first_ns, first);
    EXPECT_EQ(seg.end_ns, first + 2 * kMs);
    feed(token(kMaster, kMaster), kMs);
    EXPECT_EQ(seg.end_ns, first + 3 * kMs);
    tracker().finish();
    EXPECT_EQ(seg.telegrams, 7u);
    EXPECT_EQ(seg.bytes, 21u);
    EXPECT_EQ(seg.first_ns, first);
    EXPECT_EQ(seg.end_ns, first + 3 * kMs);
    EXPECT_EQ(seg.busy_ns, 0.0);  // no baud
    // A rotation between timed tokens in order: not to the one that went back, nor from the one
    // without a time.
    EXPECT_EQ(master(kMaster)->token_rotation.count(), 3u);
}

TEST_F(BusHealthTest, BusLoadVerdicts) {
    BusHealthOptions options;
    options.baud = 1'100'000;
    ASSERT_TRUE(options.thresholds.set(HealthThreshold::BusLoadPercentWeak, 50).has_value());
    configure(options);
    feed(token(kMaster, kMaster), 0);
    feed(token(kMaster, kMaster), 70'000);
    tracker().finish();
    EXPECT_EQ(tracker().health().segment.judgement.verdict, Verdict::Weak);
    EXPECT_TRUE(has_reason(tracker().health().segment.judgement,
                           HealthThreshold::BusLoadPercentWeak, Verdict::Weak));
}

TEST_F(BusHealthTest, FinishAtAGivenEnd) {
    BusHealthOptions options;
    options.baud = 1'100'000;
    configure(options);
    feed(token(kMaster, kMaster), 0);
    const std::int64_t start = now();
    tracker().finish(start + 1'000'000);
    const SegmentHealth& seg = tracker().health().segment;
    EXPECT_DOUBLE_EQ(seg.duration_s(), 0.001);
    EXPECT_NEAR(seg.load_percent(), 3.0, 1e-9);
}

TEST_F(BusHealthTest, CaptureWithoutTimesHasCountsOnly) {
    start_up(3);  // with times; the tracker below gets none
    configure({});
    for (int i = 0; i < 3; ++i) {
        feed(token(kMaster, kMaster), kNoTime);
        feed(dx(3), kNoTime);
        feed(data(3), kNoTime);
    }
    tracker().finish();
    const BusHealth& h = tracker().health();
    EXPECT_FALSE(h.segment.has_time());
    EXPECT_EQ(h.segment.telegrams, 9u);
    EXPECT_EQ(h.segment.telegrams_per_second(), 0.0);
    EXPECT_LT(h.segment.load_percent(), 0.0);
    EXPECT_EQ(master(kMaster)->tokens_received, 3u);
    EXPECT_EQ(master(kMaster)->token_rotation.count(), 0u);
    EXPECT_EQ(master(kMaster)->cycle.count(), 0u);
    EXPECT_EQ(station(3)->answers, 3u);
    EXPECT_EQ(station(3)->first_seen_ns, kNoTime);
}

TEST_F(BusHealthTest, OtherProtocolsAreIgnored) {
    DecodedTelegram t;
    t.protocol = Protocol::Fc;
    EXPECT_TRUE(tracker().observe(t).empty());
    tracker().finish();
    EXPECT_EQ(tracker().health().segment.telegrams, 0u);
}

// ---- verdicts -------------------------------------------------------------------------------

TEST_F(BusHealthTest, VerdictBadOnlyOnTurningBad) {
    start_up(3);
    for (int i = 0; i < 4; ++i)
        feed(dx(3));
    std::span<const HealthEvent> bad = tracker().judge();
    ASSERT_EQ(bad.size(), 2u);
    EXPECT_EQ(bad[0].address, 3);
    EXPECT_EQ(bad[0].role, StationRole::Slave);
    EXPECT_EQ(bad[1].address, kSegmentAddress);
    EXPECT_TRUE(tracker().judge().empty());
    feed(data(3));
    EXPECT_TRUE(tracker().judge().empty());  // still bad: a lost event stays
}

// judge_verdicts(): the same verdicts and turned-bad events as judge(), without copying the
// figures out: health() stays as the last judge() left it.
TEST_F(BusHealthTest, JudgeVerdictsLeavesTheFiguresAsLastPublished) {
    start_up(3);
    tracker().judge();
    const std::uint64_t published_requests = station(3)->requests;
    for (int i = 0; i < 4; ++i)
        feed(dx(3));
    std::span<const HealthEvent> bad = tracker().judge_verdicts();
    ASSERT_EQ(bad.size(), 2u);
    EXPECT_EQ(bad[0].address, 3);
    EXPECT_EQ(bad[1].address, kSegmentAddress);
    EXPECT_EQ(station(3)->requests, published_requests);  // not copied out
    EXPECT_TRUE(tracker().judge().empty());  // already bad: judge_verdicts() remembered it
    EXPECT_EQ(station(3)->requests, published_requests + 4);
    EXPECT_EQ(station(3)->judgement.verdict, Verdict::Bad);
}

TEST_F(BusHealthTest, ChangedThresholdsChangeVerdicts) {
    BusHealthOptions options;
    ASSERT_TRUE(options.thresholds.set(HealthThreshold::LostEventsBad, 0).has_value());
    ASSERT_TRUE(options.thresholds.set(HealthThreshold::NoAnswerPercentBad, 50).has_value());
    ASSERT_TRUE(options.thresholds.set(HealthThreshold::NoAnswerPercentWeak, 40).has_value());
    ASSERT_TRUE(options.thresholds.set(HealthThreshold::DiagFaultsWeak, 0).has_value());
    configure(options);
    start_up(3);
    for (int i = 0; i < 4; ++i)
        feed(dx(3));
    feed(data(3));
    tracker().finish();
    // 3 of 9 due replies unanswered (33 %, under the raised limits), the lost event not judged.
    const StationHealth* s = station(3);
    EXPECT_EQ(s->lost_events, 1u);
    EXPECT_EQ(s->no_answers, 3u);
    EXPECT_EQ(s->replies_due, 9u);
    EXPECT_EQ(s->judgement.verdict, Verdict::Good);
    EXPECT_TRUE(s->judgement.reasons.empty());
}

TEST_F(BusHealthTest, RatesNeedATelegramInTheBase) {
    tracker().finish();
    EXPECT_EQ(tracker().health().segment.judgement.verdict, Verdict::Good);
    EXPECT_TRUE(tracker().health().segment.judgement.reasons.empty());
}

// A capture clipped onto a running bus (or sniff started on one) may begin with a response whose
// request came before it: nothing a slave sends to a master before the first request seen from
// that master to that slave is judged illegal (docs/bus-health.md, "Illegal answers").
TEST_F(BusHealthTest, NothingBeforeTheFirstRequestOnTheLinkIsAnIllegalAnswer) {
    feed(data(3));  // the capture's first telegram: the answer to a poll before it
    exchange(3);
    exchange(3);
    tracker().judge();
    EXPECT_EQ(station(3)->judgement.verdict, Verdict::Good);
    // Station 4 answers master 1 while station 3 is asked, before master 1 ever asked it; and
    // station 3 answers master 2, which has asked it nothing yet.
    feed(dx(3));
    feed(data(4));
    feed(data(3, 2));
    exchange(4);
    exchange(3);
    tracker().finish();
    ASSERT_NE(station(3), nullptr);
    ASSERT_NE(station(4), nullptr);
    EXPECT_EQ(station(3)->illegal_answers_total(), 0u);
    EXPECT_EQ(station(4)->illegal_answers_total(), 0u);
    for (int address : {3, 4})
        for (const VerdictReason& reason :
             station(static_cast<std::uint8_t>(address))->judgement.reasons)
            EXPECT_NE(reason.threshold, HealthThreshold::IllegalAnswersWeak) << address;
    EXPECT_EQ(station(4)->judgement.verdict, Verdict::Good);
    // Heard all the same: station 3 sent five telegrams, station 4 two.
    EXPECT_EQ(station(3)->telegrams_sent, 5u);
    EXPECT_EQ(station(4)->telegrams_sent, 2u);
    // Once the link has carried a request, the same answers are judged.
    feed(data(4));
    feed(data(3));
    tracker().finish();
    EXPECT_EQ(station(3)->illegal_answers[0], 1u);
    EXPECT_EQ(station(4)->illegal_answers[0], 1u);
}

TEST_F(BusHealthTest, IllegalAnswersBadFromTen) {
    start_up(3);
    exchange(5);
    for (int i = 0; i < 9; ++i)
        feed(data(5));
    tracker().judge();
    EXPECT_EQ(station(5)->judgement.verdict, Verdict::Weak);
    feed(data(5));
    tracker().judge();
    EXPECT_EQ(station(5)->judgement.verdict, Verdict::Bad);
    ASSERT_EQ(station(5)->judgement.reasons.size(), 1u);
    EXPECT_EQ(station(5)->judgement.reasons[0].threshold, HealthThreshold::IllegalAnswersBad);
    EXPECT_EQ(station(5)->judgement.reasons[0].measured, 10.0);
}

TEST_F(BusHealthTest, DescribeReason) {
    const HealthThresholds thresholds;
    EXPECT_EQ(
        describe_reason({HealthThreshold::RepeatPercentWeak, 0.25, Verdict::Weak}, thresholds),
        "repeat_percent_weak: 0.25 % (weak above 0.1 %)");
}

// ---- timeline cap and the time series ---------------------------------------------------------

TEST_F(BusHealthTest, TimelineIsCappedButAllChangesCounted) {
    start_up(3);
    const std::uint64_t changes = 2 * BusHealthTracker::kMaxStateChanges;
    for (std::uint64_t i = 0; i < changes / 2; ++i) {
        feed(cfg(3), 100'000);
        feed(sc(), 100'000);
        exchange(3);
    }
    tracker().finish();
    EXPECT_EQ(station(3)->timeline.size(), BusHealthTracker::kMaxStateChanges);
    EXPECT_EQ(station(3)->state_changes, 3 + changes);
    EXPECT_EQ(station(3)->resyncs, changes / 2);
}

// A clean simulated session (start-up and 1000 cycles of three slaves): every slave in data
// exchange, nothing illegal, lost or damaged, and the master's cycle near the simulator's target.
TEST(BusHealthSimulatedTest, CleanSessionIsGood) {
    SimulatorOptions options;
    Simulator simulator(options);
    BusDecoder decoder;
    BusHealthOptions health_options;
    health_options.baud = options.baud;
    BusHealthTracker tracker(health_options);
    std::vector<std::uint8_t> bytes;
    std::int64_t time = 0;
    std::uint64_t frame = 0;
    std::uint64_t events = 0;
    while (simulator.next(bytes, time))
        events += tracker.observe(decoder.decode(Bytes(bytes.data(), bytes.size()), time, ++frame))
                      .size();
    tracker.finish();
    const BusHealth& h = tracker.health();
    EXPECT_EQ(events, 0u);
    EXPECT_EQ(h.segment.telegrams, frame);
    EXPECT_EQ(h.segment.damaged, 0u);
    ASSERT_EQ(h.stations.size(), 4u);  // the master 2 and slaves 3, 4, 5
    for (const StationHealth& s : h.stations) {
        EXPECT_EQ(s.illegal_answers_total(), 0u) << int(s.address);
        EXPECT_EQ(s.lost_events, 0u) << int(s.address);
        EXPECT_EQ(s.repeats, 0u) << int(s.address);
        if (s.address == 2) {
            EXPECT_EQ(s.role, StationRole::Master);
            continue;
        }
        EXPECT_EQ(s.role, StationRole::Slave) << int(s.address);
        EXPECT_EQ(s.state, StationState::DataExchange) << int(s.address);
        EXPECT_EQ(s.no_answers, 0u) << int(s.address);
        EXPECT_EQ(s.answers, s.requests) << int(s.address);
        EXPECT_EQ(s.judgement.verdict, Verdict::Good) << int(s.address);
    }
    ASSERT_EQ(h.masters.size(), 1u);
    EXPECT_EQ(h.masters[0].slaves_polled, 3u);
    EXPECT_GE(h.masters[0].cycle.count(), 999u);
    EXPECT_NEAR(h.masters[0].cycle.mean(), options.cycle_us * 1000.0, options.cycle_us * 100.0);
    EXPECT_GT(h.segment.load_percent(), 0.0);
    EXPECT_EQ(h.segment.judgement.verdict, Verdict::Good);
}

TEST(TimeSeriesTest, MergesPairwiseWhenFull) {
    TimeSeries series;
    for (std::int64_t i = 0; i < 512; ++i)
        series.add(i, i);
    EXPECT_EQ(series.points().size(), 512u);
    EXPECT_EQ(series.samples_per_point(), 1u);
    series.add(512, 512);
    EXPECT_EQ(series.points().size(), 257u);
    EXPECT_EQ(series.samples_per_point(), 2u);
    EXPECT_EQ(series.points()[0].first_ns, 0);
    EXPECT_EQ(series.points()[0].last_ns, 1);
    EXPECT_EQ(series.points()[0].min_ns, 0);
    EXPECT_EQ(series.points()[0].max_ns, 1);
    EXPECT_DOUBLE_EQ(series.points()[0].mean_ns(), 0.5);
    EXPECT_EQ(series.points()[256].count, 1u);
    series.add(513, 600);
    EXPECT_EQ(series.points().size(), 257u);
    EXPECT_EQ(series.points()[256].count, 2u);
    EXPECT_EQ(series.points()[256].max_ns, 600);
    std::uint64_t total = 0;
    for (std::int64_t i = 514; i < 5000; ++i)
        series.add(i, 1);
    for (const TimeSeries::Point& p : series.points())
        total += p.count;
    EXPECT_EQ(total, 5000u);
    EXPECT_LE(series.points().size(), TimeSeries::kMaxPoints);
    EXPECT_EQ(series.points().front().first_ns, 0);
    EXPECT_EQ(series.points().back().last_ns, 4999);
}

TEST(BusHealthNamesTest, Names) {
    EXPECT_EQ(station_role_name(StationRole::Master), "master");
    EXPECT_EQ(station_state_name(StationState::DiagnosisOnly), "diagnosis only");
    EXPECT_EQ(station_state_id(StationState::DataExchange), "data_exchange");
    EXPECT_EQ(illegal_answer_id(IllegalAnswer::ShortAck), "short_ack");
    EXPECT_EQ(diag_fault_name(DiagFault::PrmFault), "Prm_Fault");
    EXPECT_EQ(negative_answer_name(NegativeAnswer::RDH), "RDH");
    EXPECT_EQ(health_event_name(HealthEventKind::VerdictBad), "verdict_bad");
    EXPECT_EQ(health_event_name(HealthEventKind::StationLost), "station_lost");
    EXPECT_EQ(health_event_name(HealthEventKind::StationReturned), "station_returned");
}

// An SDA is acknowledged, not answered with data: an SD1 carrying the SRD status DL (data low)
// is an answer of the wrong kind, an SD1 with status OK the right one.
TEST_F(BusHealthTest, SdaAnsweredWithTheDataLowStatusIsTheWrongKind) {
    start_up(3);
    feed(sda(3));
    feed(sd1(3, FdlStatus::DataLow));  // wrong
    feed(sda(3));
    feed(sd1(3, FdlStatus::Ok));  // right
    tracker().finish();
    const StationHealth* s = station(3);
    ASSERT_NE(s, nullptr);
    EXPECT_EQ(s->illegal_answers[static_cast<std::size_t>(IllegalAnswer::WrongKind)], 1u);
    EXPECT_EQ(s->illegal_answers_total(), 1u);
    EXPECT_EQ(s->negative_answers_total(), 0u);  // neither status is a negative answer
    EXPECT_EQ(s->no_answers, 0u);
}

// An SRD without a valid frame count (FCV 0) restarts the link's frame count, as FDL_Status
// does (FdlStatusResetsTheFrameCount): the next request with the FCB of the one before it is no
// repeat; the one after that, with the same FCB again, is.
TEST_F(BusHealthTest, RequestWithoutFcvRestartsTheFrameCount) {
    start_up(3);
    feed(dx(3));
    feed(data(3));
    feed(build_telegram({3, kMaster, request_fc(FdlFunction::SrdHigh, false, false), std::nullopt,
                         std::nullopt, Bytes(kOutputs, 2)}));
    feed(data(3));
    feed(dx(3, true));  // the FCB of the last counted request, but the link restarted
    feed(data(3));
    tracker().judge();  // the counts so far
    EXPECT_EQ(station(3)->repeats, 0u);
    feed(dx(3, true));  // the same FCB once more: a repeat
    feed(data(3));
    tracker().finish();
    EXPECT_EQ(station(3)->repeats, 1u);
}

}  // namespace
}  // namespace dpscope
