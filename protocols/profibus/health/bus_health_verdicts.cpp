// The bus-health verdicts (protocols/profibus/health/bus_health.hpp, rules in docs/bus-health.md):
// each station, each master and the segment judged against the thresholds, and the verdicts that
// turned bad.
#include <algorithm>
#include <vector>

#include "protocols/profibus/health/bus_health_state.hpp"

namespace dpscope {

namespace {

// Judges a count against a "from" threshold (0: off).
void judge_from(std::vector<VerdictReason>& reasons, const HealthThresholds& limits,
                HealthThreshold kind, double measured) {
    const double limit = limits.get(kind);
    if (limit > 0 && measured >= limit)
        reasons.push_back({kind, measured, health_threshold_row(kind).verdict});
}

// Judges a rate against a weak and a bad "above" threshold (the worse one only).
void judge_rate(std::vector<VerdictReason>& reasons, const HealthThresholds& limits,
                HealthThreshold weak, HealthThreshold bad, double count, double base) {
    if (base <= 0) return;
    const double percent = count / base * 100.0;
    if (percent > limits.get(bad))
        reasons.push_back({bad, percent, Verdict::Bad});
    else if (percent > limits.get(weak))
        reasons.push_back({weak, percent, Verdict::Weak});
}

void conclude(Judgement& judgement) {
    std::stable_sort(
        judgement.reasons.begin(), judgement.reasons.end(),
        [](const VerdictReason& a, const VerdictReason& b) { return a.verdict > b.verdict; });
    judgement.verdict = Verdict::Good;
    for (const VerdictReason& r : judgement.reasons)
        judgement.verdict = worse(judgement.verdict, r.verdict);
}

}  // namespace

std::span<const HealthEvent> BusHealthTracker::judge(bool publish) {
    using Impl = BusHealthTrackerImpl;
    State& s = *state_;
    s.verdict_events.clear();
    const HealthThresholds& limits = health_.thresholds;
    using enum HealthThreshold;

    if (publish) {
        health_.stations.clear();
        health_.masters.clear();
    }
    Verdict segment = Verdict::Good;
    auto turned_bad = [&](Verdict& last, Verdict now, std::uint8_t address, StationRole role) {
        if (now == Verdict::Bad && last != Verdict::Bad)
            s.verdict_events.push_back(HealthEvent{HealthEventKind::VerdictBad, address,
                                                   s.last_time_ns, s.last_frame, role});
        last = now;
    };

    for (State::Slot& slot : s.slots) {
        if (!slot.listed) continue;
        StationHealth& h = slot.health;
        h.role = Impl::role_of(slot);
        Judgement& j = h.judgement;
        j.reasons.clear();
        judge_from(j.reasons, limits, LostEventsBad, static_cast<double>(h.lost_events));
        judge_rate(j.reasons, limits, FcsErrorPercentWeak, FcsErrorPercentBad,
                   static_cast<double>(h.fcs_errors), static_cast<double>(h.link_telegrams()));
        judge_rate(j.reasons, limits, RepeatPercentWeak, RepeatPercentBad,
                   static_cast<double>(h.repeats), static_cast<double>(h.requests));
        judge_from(j.reasons, limits, RepeatsPerCycleWeak,
                   static_cast<double>(h.max_repeats_per_cycle));
        judge_rate(j.reasons, limits, NoAnswerPercentWeak, NoAnswerPercentBad,
                   static_cast<double>(h.no_answers), static_cast<double>(h.replies_due));
        // Illegal answers and resyncs: the worse of the two limits only.
        const double illegal = static_cast<double>(h.illegal_answers_total());
        const std::size_t before_illegal = j.reasons.size();
        judge_from(j.reasons, limits, IllegalAnswersBad, illegal);
        if (j.reasons.size() == before_illegal)
            judge_from(j.reasons, limits, IllegalAnswersWeak, illegal);
        const std::size_t before_resyncs = j.reasons.size();
        judge_from(j.reasons, limits, ResyncsBad, static_cast<double>(h.resyncs));
        if (j.reasons.size() == before_resyncs)
            judge_from(j.reasons, limits, ResyncsWeak, static_cast<double>(h.resyncs));
        judge_from(j.reasons, limits, DiagFaultsWeak, static_cast<double>(h.diag_faults));
        const double refusals =
            static_cast<double>(h.negative_answers[static_cast<std::size_t>(NegativeAnswer::UE)] +
                                h.negative_answers[static_cast<std::size_t>(NegativeAnswer::RR)] +
                                h.negative_answers[static_cast<std::size_t>(NegativeAnswer::RS)]);
        judge_from(j.reasons, limits, RefusalsWeak, refusals);
        conclude(j);
        turned_bad(slot.last_verdict, j.verdict, h.address, h.role);
        segment = worse(segment, j.verdict);
        if (publish) health_.stations.push_back(h);

        if (!slot.master) continue;
        State::Master& m = s.masters[h.address];
        Judgement& mj = m.health.judgement;
        mj.reasons.clear();
        const double target_ms = limits.get(TargetRotationMs);
        if (target_ms > 0 && m.health.token_rotation.count() > 0) {
            const double p95_ms = static_cast<double>(m.health.token_rotation.p95()) / 1e6;
            const double max_ms = static_cast<double>(m.health.token_rotation.max()) / 1e6;
            if (max_ms > 1.5 * target_ms)
                mj.reasons.push_back({TargetRotationMs, max_ms, Verdict::Bad});
            else if (p95_ms > target_ms)
                mj.reasons.push_back({TargetRotationMs, p95_ms, Verdict::Weak});
        }
        const double jitter_limit = limits.get(CycleJitterPercentWeak);
        if (jitter_limit > 0 && m.jitter_count > 0 && m.health.cycle.mean() > 0) {
            const double percent = m.health.cycle_jitter_ns / m.health.cycle.mean() * 100.0;
            if (percent > jitter_limit)
                mj.reasons.push_back({CycleJitterPercentWeak, percent, Verdict::Weak});
        }
        conclude(mj);
        turned_bad(m.last_verdict, mj.verdict, h.address, StationRole::Master);
        segment = worse(segment, mj.verdict);
        if (publish) health_.masters.push_back(m.health);
    }

    SegmentHealth& seg = health_.segment;
    Judgement& sj = seg.judgement;
    sj.reasons.clear();
    const double load = seg.load_percent();
    if (load >= 0) {
        if (load > limits.get(BusLoadPercentBad))
            sj.reasons.push_back({BusLoadPercentBad, load, Verdict::Bad});
        else if (load > limits.get(BusLoadPercentWeak))
            sj.reasons.push_back({BusLoadPercentWeak, load, Verdict::Weak});
    }
    // The segment's damaged telegrams, all of them, over all its telegrams (the rate its
    // "Damaged" line reads; those no station could be named for weigh here only).
    judge_rate(sj.reasons, limits, FcsErrorPercentWeak, FcsErrorPercentBad,
               static_cast<double>(seg.damaged), static_cast<double>(seg.telegrams));
    conclude(sj);
    sj.verdict = worse(sj.verdict, segment);
    turned_bad(s.segment_last_verdict, sj.verdict, kSegmentAddress, StationRole::Unknown);
    return s.verdict_events;
}

}  // namespace dpscope
