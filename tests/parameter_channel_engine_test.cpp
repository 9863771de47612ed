// The parameter-channel engine on its own: samples fed by hand, no FDL bytes. A pair, a stacked
// request, an orphan, a time-out, the spontaneous-message handshake with and without an SPM bit,
// and the one-cycle lag as a policy.
#include "core/parameter_channel_engine.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace dpscope {
namespace {

constexpr std::int64_t kMs = 1'000'000;
constexpr std::int64_t kStart = 1'704'067'200'000'000'000;

Pcv pcv(std::uint8_t rc, std::uint16_t pnu = 0, std::uint32_t pva = 0, bool spm = false) {
    Pcv p;
    p.rc = rc;
    p.pnu = pnu;
    p.pva = pva;
    p.spm = spm;
    return p;
}

const Pcv kIdle = pcv(0);
const Pcv kRead520 = pcv(1, 520);
const Pcv kValue520 = pcv(1, 520, 240);
const Pcv kRead518 = pcv(1, 518);

// Master 2 and slave 3: one sample per telegram, a request and a response per 2 ms cycle.
class EngineChannel {
  public:
    explicit EngineChannel(ParameterChannelPolicy policy = {}) : engine_(policy) {
        engine_.add_channel(2, 3, stats);
    }

    // One cycle: the master's request, then the slave's response.
    void cycle(const Pcv& master, const Pcv& slave) {
        ++cycle_;
        feed(Direction::Request, master);
        now_ += 200'000;
        feed(Direction::Response, slave);
        now_ += 1'800'000;
    }
    // Time passes without telegrams; the engine is told at the next frame.
    void advance_ms(std::int64_t ms) {
        now_ += ms * kMs;
        engine_.advance(now_, frame_ + 1, findings);
    }
    std::uint64_t frame() const noexcept { return frame_; }

    ParameterChannelStats stats;
    std::vector<Finding> findings;
    std::vector<CompletedTransaction> transactions;

  private:
    void feed(Direction direction, const Pcv& p) {
        engine_.advance(now_, ++frame_, findings);
        ParameterChannelSample sample{frame_, now_, direction, 2, 3, p, Dialect::Vlt, cycle_};
        if (auto done = engine_.track(sample, findings)) transactions.push_back(*done);
    }

    ParameterChannelEngine engine_;
    std::int64_t now_ = kStart;
    std::uint64_t frame_ = 0;
    std::uint64_t cycle_ = 0;
};

ParameterChannelPolicy without_lag() {
    ParameterChannelPolicy policy;
    policy.response_lags_one_cycle = false;
    return policy;
}

ParameterChannelPolicy without_spm_bit() {
    ParameterChannelPolicy policy;
    policy.has_spm_bit = false;
    return policy;
}

std::vector<FindingKind> kinds(const std::vector<Finding>& findings) {
    std::vector<FindingKind> out;
    for (const Finding& f : findings)
        out.push_back(f.kind);
    return out;
}

TEST(ParameterChannelEngineTest, PairsARequestWithItsAnswerACycleLater) {
    EngineChannel ch;
    ch.cycle(kRead520, kIdle);  // frames 1, 2: the slave answers a cycle late
    ch.cycle(kRead520, kValue520);
    ch.cycle(kIdle, kValue520);  // the lagging answer when the master moved on: no orphan
    ch.cycle(kIdle, kIdle);
    EXPECT_TRUE(ch.findings.empty());
    EXPECT_EQ(ch.stats.requests, 1u);
    EXPECT_EQ(ch.stats.transactions.positive, 1u);
    EXPECT_EQ(ch.stats.pnu_requests.at(520), 1u);
    EXPECT_EQ(ch.stats.parameter_telegrams, 8u);
    EXPECT_EQ(ch.stats.latency_cycles.max(), 1u);
    EXPECT_EQ(ch.stats.latency_ns.max(), static_cast<std::uint64_t>(2 * kMs + 200'000));
    ASSERT_EQ(ch.transactions.size(), 1u);
    const CompletedTransaction& done = ch.transactions[0];
    EXPECT_EQ(done.master, 2);
    EXPECT_EQ(done.slave, 3);
    EXPECT_EQ(done.frame, 4u);
    EXPECT_EQ(done.time_ns, kStart + 2 * kMs + 200'000);
    EXPECT_TRUE(done.timed);
}

TEST(ParameterChannelEngineTest, WithoutTheLagTheSameExchangeAnswers) {
    EngineChannel lagging;
    EngineChannel immediate(without_lag());
    for (EngineChannel* ch : {&lagging, &immediate}) {
        ch->cycle(kIdle, kIdle);
        ch->cycle(kRead520, kValue520);
        ch->cycle(kIdle, kIdle);
    }
    // A lagging slave cannot have answered a request in the cycle it appeared: an orphan, and the
    // request is abandoned.
    EXPECT_EQ(kinds(lagging.findings), std::vector{FindingKind::OrphanResponse});
    EXPECT_EQ(lagging.stats.transactions.total(), 0u);
    EXPECT_EQ(lagging.stats.abandoned, 1u);
    // Without the lag it is the answer, in the same cycle.
    EXPECT_TRUE(immediate.findings.empty());
    EXPECT_EQ(immediate.stats.transactions.positive, 1u);
    EXPECT_EQ(immediate.stats.latency_cycles.max(), 0u);
}

TEST(ParameterChannelEngineTest, WithoutTheLagAnAnswerAfterTheMasterMovedOnIsAnOrphan) {
    EngineChannel ch(without_lag());
    ch.cycle(kRead520, kValue520);
    ch.cycle(kIdle, pcv(1, 520, 241));  // the slave answers 520 again, nothing asked
    EXPECT_EQ(kinds(ch.findings), std::vector{FindingKind::OrphanResponse});
}

TEST(ParameterChannelEngineTest, StackedRequest) {
    EngineChannel ch;
    ch.cycle(kRead520, kIdle);  // frame 1
    ch.cycle(kRead518, kIdle);  // frame 3: 520 still unanswered
    ASSERT_EQ(kinds(ch.findings), std::vector{FindingKind::StackedRequest});
    const Finding& f = ch.findings[0];
    EXPECT_EQ(f.frame, 3u);
    EXPECT_EQ(f.request_frame, 1u);
    EXPECT_EQ(f.pnu, 520);
    EXPECT_TRUE(f.has_stations);
    EXPECT_EQ(f.master, 2);
    EXPECT_EQ(f.slave, 3);
    EXPECT_EQ(f.message,
              "new request RC 1 (Request parameter value) PNU 518 while RC 1 (Request parameter "
              "value) PNU 520 from frame 1 was still unanswered");
    EXPECT_EQ(ch.stats.requests, 2u);
}

TEST(ParameterChannelEngineTest, OrphanIsReportedOnce) {
    EngineChannel ch;
    ch.cycle(kIdle, kIdle);
    ch.cycle(kIdle, kIdle);
    ch.cycle(kIdle, kValue520);         // frame 6
    ch.cycle(kIdle, pcv(1, 520, 241));  // refreshed: the same orphan
    ASSERT_EQ(kinds(ch.findings), std::vector{FindingKind::OrphanResponse});
    EXPECT_EQ(ch.findings[0].frame, 6u);
    EXPECT_EQ(ch.findings[0].request_frame, 0u);
    EXPECT_EQ(ch.findings[0].pnu, 520);
}

TEST(ParameterChannelEngineTest, TimeoutIsReportedOnceAtTheFirstTelegramPastTheDeadline) {
    EngineChannel ch;
    ch.cycle(kRead520, kIdle);  // frame 1 at kStart; now 2 ms later
    ch.advance_ms(997);
    EXPECT_TRUE(ch.findings.empty());
    ch.advance_ms(2);  // told at frame 3
    ASSERT_EQ(kinds(ch.findings), std::vector{FindingKind::ResponseTimeout});
    const Finding& f = ch.findings[0];
    EXPECT_EQ(f.frame, 3u);
    EXPECT_EQ(f.request_frame, 1u);
    EXPECT_EQ(f.time_ns, kStart + 1001 * kMs);
    EXPECT_EQ(f.message,
              "no answer to request RC 1 (Request parameter value) PNU 520 from frame 1 within "
              "1000 ms");
    EXPECT_EQ(ch.stats.timeouts, 1u);
    ch.advance_ms(5000);
    EXPECT_EQ(ch.findings.size(), 1u);
    // A request that timed out is not stacked as well when the master moves on.
    ch.cycle(kRead518, kIdle);
    EXPECT_EQ(ch.findings.size(), 1u);
}

TEST(ParameterChannelEngineTest, TimeoutsComeInTheOrderChannelsWereAdded) {
    ParameterChannelEngine engine;
    ParameterChannelStats five, three;
    engine.add_channel(2, 5, five);
    engine.add_channel(2, 3, three);
    std::vector<Finding> findings;
    engine.track({1, kStart, Direction::Request, 2, 3, kRead520, Dialect::Vlt, 1}, findings);
    engine.track({2, kStart, Direction::Request, 2, 5, kRead518, Dialect::Vlt, 1}, findings);
    engine.advance(kStart + 2000 * kMs, 3, findings);
    ASSERT_EQ(findings.size(), 2u);
    EXPECT_EQ(findings[0].slave, 5);
    EXPECT_EQ(findings[1].slave, 3);
    // A channel never added is not followed.
    ParameterChannelSample unknown{4, kStart, Direction::Request, 2, 9, kRead520, Dialect::Vlt, 1};
    EXPECT_FALSE(engine.track(unknown, findings).has_value());
    EXPECT_EQ(findings.size(), 2u);
}

// RC 9 in the vlt dialect: a spontaneous message (word).
Pcv spontaneous(bool spm) { return pcv(9, 101, 7, spm); }

TEST(ParameterChannelEngineTest, SpmHandshakeAcknowledgedByTheMastersToggle) {
    EngineChannel ch;
    ch.cycle(kIdle, kIdle);
    ch.cycle(kIdle, spontaneous(true));               // the slave toggles SPM
    ch.cycle(kIdle, spontaneous(true));               // repeated until acknowledged
    ch.cycle(pcv(0, 0, 0, true), spontaneous(true));  // the master toggles: acknowledged
    ch.advance_ms(2000);
    ASSERT_EQ(kinds(ch.findings), std::vector{FindingKind::SpontaneousMessage});
    EXPECT_EQ(ch.findings[0].message,
              "spontaneous message RC 9 (Spontaneous message (word)) PNU 101 value 7 with SPM 1");
    EXPECT_EQ(ch.stats.spontaneous, 1u);
}

TEST(ParameterChannelEngineTest, SpmHandshakeNotAcknowledgedInTime) {
    EngineChannel ch;
    ch.cycle(kIdle, kIdle);
    ch.cycle(kIdle, spontaneous(true));  // frame 4
    ch.advance_ms(2000);
    ASSERT_EQ(kinds(ch.findings), (std::vector{FindingKind::SpontaneousMessage,
                                               FindingKind::SpontaneousUnacknowledged}));
    EXPECT_EQ(ch.findings[1].request_frame, 4u);
    // A toggle after the time-out still acknowledges it: no SPM violation.
    ch.cycle(pcv(0, 0, 0, true), spontaneous(true));
    EXPECT_EQ(ch.findings.size(), 2u);
    // A toggle with nothing pending is one.
    ch.cycle(kIdle, spontaneous(true));
    EXPECT_EQ(ch.findings.back().kind, FindingKind::SpmViolation);
}

TEST(ParameterChannelEngineTest, WithoutAnSpmBitNoHandshakeIsAwaited) {
    EngineChannel ch(without_spm_bit());
    ch.cycle(kIdle, kIdle);
    ch.cycle(kIdle, spontaneous(false));
    ch.cycle(kIdle, spontaneous(false));               // the same message again
    ch.advance_ms(2000);                               // nothing to acknowledge: no time-out
    ch.cycle(pcv(0, 0, 0, true), spontaneous(false));  // an SPM the layout has not: ignored
    ch.cycle(kIdle, pcv(9, 101, 8));                   // another message: a change of the PCV
    ASSERT_EQ(kinds(ch.findings),
              (std::vector{FindingKind::SpontaneousMessage, FindingKind::SpontaneousMessage}));
    EXPECT_EQ(ch.findings[0].message,
              "spontaneous message RC 9 (Spontaneous message (word)) PNU 101 value 7");
    EXPECT_EQ(ch.stats.spontaneous, 2u);
}

TEST(ParameterChannelEngineTest, SpontaneousMessageKeepsTheRequestPending) {
    EngineChannel ch;
    ch.cycle(kRead520, kIdle);
    ch.cycle(kRead520, spontaneous(true));
    ch.cycle(pcv(1, 520, 0, true), kValue520);  // acknowledged; then answered
    ch.cycle(pcv(0, 0, 0, true), kIdle);        // the master keeps its SPM
    EXPECT_EQ(kinds(ch.findings), std::vector{FindingKind::SpontaneousMessage});
    EXPECT_EQ(ch.stats.transactions.positive, 1u);
}

TEST(ParameterChannelEngineTest, RejectionWithoutItsPnuIsAboutTheRequest) {
    ParameterChannelEngine engine;
    ParameterChannelStats stats;
    engine.add_channel(2, 3, stats);
    std::vector<Finding> findings;
    engine.track({1, kStart, Direction::Request, 2, 3, kRead520, Dialect::Vlt, 1}, findings);
    EXPECT_EQ(engine.subject_pnu(), 520);
    engine.track({2, kStart, Direction::Response, 2, 3, kIdle, Dialect::Vlt, 1}, findings);
    engine.track({3, kStart, Direction::Request, 2, 3, kRead520, Dialect::Vlt, 2}, findings);
    auto done = engine.track({4, kStart, Direction::Response, 2, 3, pcv(7, 0, 2), Dialect::Vlt, 2},
                             findings);
    EXPECT_EQ(engine.subject_pnu(), 520);
    ASSERT_TRUE(done.has_value());
    EXPECT_EQ(done->frame, 4u);
    ASSERT_EQ(kinds(findings), std::vector{FindingKind::RequestRejected});
    EXPECT_EQ(findings[0].request_frame, 1u);
    EXPECT_EQ(stats.transactions.rejected, 1u);
    EXPECT_EQ(stats.rejection_errors.at(2), 1u);
}

// The FC carrier's policy: no lag, no SPM bit, no cyclic repetition, its own kinds.
ParameterChannelPolicy not_cyclic() {
    ParameterChannelPolicy policy;
    policy.has_spm_bit = false;
    policy.response_lags_one_cycle = false;
    policy.cyclic_requests = false;
    return policy;
}

TEST(ParameterChannelEngineTest, WithoutCyclicRepetitionEveryRequestIsNewAndEveryResponseAnAnswer) {
    EngineChannel cyclic(without_lag());
    EngineChannel commands(not_cyclic());
    for (EngineChannel* ch : {&cyclic, &commands}) {
        ch->cycle(kRead520, kValue520);
        ch->cycle(kRead520, kValue520);  // the same request and answer again
        ch->cycle(kRead520, kValue520);
    }
    // Cyclic: one request standing, answered once, the rest repeats.
    EXPECT_EQ(cyclic.stats.requests, 1u);
    EXPECT_EQ(cyclic.stats.transactions.positive, 1u);
    // Not cyclic: three commands, three answers.
    EXPECT_TRUE(commands.findings.empty());
    EXPECT_EQ(commands.stats.requests, 3u);
    EXPECT_EQ(commands.stats.transactions.positive, 3u);
    EXPECT_EQ(commands.transactions.size(), 3u);
}

TEST(ParameterChannelEngineTest, PolicyKindsRenameOrSilenceFindings) {
    ParameterChannelPolicy policy = not_cyclic();
    policy.kinds.stacked_request = std::nullopt;
    policy.kinds.mismatched_response = FindingKind::FcMismatchedResponse;
    policy.kinds.request_rejected = FindingKind::FcCommandRejected;
    EngineChannel ch(policy);
    ch.cycle(kRead520, kIdle);             // unanswered ...
    ch.cycle(kRead518, pcv(1, 520, 240));  // ... a new one (stacked: silenced), answered
    ch.cycle(kRead520, pcv(7, 520, 2));    // rejected
    EXPECT_EQ(kinds(ch.findings),
              (std::vector{FindingKind::FcMismatchedResponse, FindingKind::FcCommandRejected}));
    EXPECT_EQ(ch.stats.transactions.mismatched, 1u);
    EXPECT_EQ(ch.stats.transactions.rejected, 1u);
    EXPECT_EQ(ch.stats.abandoned, 0u);
}

TEST(ParameterChannelEngineTest, AbandonEndsThePendingRequestWithoutAFinding) {
    ParameterChannelPolicy policy = not_cyclic();
    policy.kinds.orphan_response = std::nullopt;
    policy.kinds.response_timeout = std::nullopt;
    ParameterChannelEngine engine(policy);
    ParameterChannelStats stats;
    engine.add_channel(0, 1, stats);
    std::vector<Finding> findings;
    engine.track(
        ParameterChannelSample{1, kStart, Direction::Request, 0, 1, kRead520, Dialect::Fc, 1},
        findings);
    engine.abandon(0, 1);
    // A later answer finds nothing pending; the time-out is the carrier's.
    EXPECT_FALSE(engine
                     .track(ParameterChannelSample{2, kStart + kMs, Direction::Response, 0, 1,
                                                   kValue520, Dialect::Fc, 1},
                            findings)
                     .has_value());
    engine.advance(kStart + 5000 * kMs, 3, findings);
    EXPECT_TRUE(findings.empty());
    EXPECT_EQ(stats.abandoned, 1u);
    EXPECT_EQ(stats.timeouts, 0u);
    EXPECT_EQ(stats.transactions.total(), 0u);
}

}  // namespace
}  // namespace dpscope
