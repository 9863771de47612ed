// A BusHealth built by hand with known numbers, for the renderers' tests (stats_test.cpp and the
// report's bus-health section in report_test.cpp): a master 2, a slave 5 that was lost once and
// returned, a slave 7 never heard; a capture of 2 s at 1.5 Mbit/s with a quarter of it busy.
#pragma once

#include <cstdint>

#include "protocols/profibus/health/bus_health.hpp"

namespace dpscope::test {

// 2024-01-01T00:00:00Z.
inline constexpr std::int64_t kHealthStart = 1'704'067'200'000'000'000;
inline constexpr std::int64_t kMs = 1'000'000;

inline BusHealth health_sample(bool timed = true, std::uint32_t baud = 1'500'000) {
    auto at = [timed](std::int64_t ms) { return timed ? kHealthStart + ms * kMs : kNoTime; };
    BusHealth h;
    (void)h.thresholds.set(HealthThreshold::TargetRotationMs, 15);

    SegmentHealth& seg = h.segment;
    seg.telegrams = 1000;
    seg.bytes = 12'000;
    seg.damaged = 3;
    seg.unattributed_damaged = 1;
    seg.unasked_short_acks = 2;
    seg.first_ns = at(0);
    seg.end_ns = at(2000);
    seg.baud = baud;
    seg.busy_ns = baud ? 0.5e9 : 0;
    seg.judgement = {Verdict::Bad, {{HealthThreshold::LostEventsBad, 1, Verdict::Bad}}};

    StationHealth master;
    master.address = 2;
    master.role = StationRole::Master;
    master.state = StationState::Active;
    master.first_seen_ns = at(0);
    master.last_seen_ns = at(1999);
    master.first_frame = 1;
    master.last_frame = 999;
    master.telegrams_sent = 500;
    master.timeline = {{at(0), 1, StationState::Active, false}};
    master.state_changes = 1;
    h.stations.push_back(master);

    StationHealth slave;
    slave.address = 5;
    slave.role = StationRole::Slave;
    slave.state = StationState::DataExchange;
    slave.first_seen_ns = at(100);
    slave.last_seen_ns = at(1998);
    slave.first_frame = 10;
    slave.last_frame = 998;
    slave.telegrams_sent = 390;
    slave.requests = 400;
    slave.answers = 390;
    slave.no_answers = 10;
    slave.replies_due = 400;
    slave.repeats = 4;
    slave.max_repeats_per_cycle = 2;
    slave.lost_events = 1;
    slave.returns = 1;
    slave.resyncs = 1;
    slave.diag_requests = 6;
    slave.diag_answers = 6;
    slave.diag_faults = 2;
    slave.diag_fault_bits = {2, 0, 1, 0, 0};
    slave.illegal_answers = {1, 0, 2};
    slave.negative_answers = {0, 1, 0, 0, 3, 0};
    slave.fcs_errors = 2;
    slave.timeline = {{at(100), 10, StationState::Configuring, false},
                      {at(200), 20, StationState::DataExchange, false},
                      {at(1000), 500, StationState::Lost, false},
                      {at(1500), 700, StationState::DataExchange, true}};
    slave.state_changes = 4;
    slave.judgement = {Verdict::Bad,
                       {{HealthThreshold::LostEventsBad, 1, Verdict::Bad},
                        {HealthThreshold::RepeatPercentWeak, 1, Verdict::Weak}}};
    h.stations.push_back(slave);

    StationHealth unheard;
    unheard.address = 7;
    unheard.first_seen_ns = at(300);
    unheard.last_seen_ns = at(300);
    unheard.first_frame = 30;
    unheard.last_frame = 30;
    unheard.requests = 3;
    unheard.no_answers = 3;
    unheard.timeline = {{at(300), 30, StationState::Unknown, false}};
    unheard.state_changes = 1;
    h.stations.push_back(unheard);

    MasterHealth m;
    m.address = 2;
    m.tokens_received = 100;
    m.tokens_passed = 100;
    m.requests = 409;
    m.slaves_polled = 1;
    if (timed) {
        // Cycles of 10 and 12 ms, rotations of 20 ms.
        m.cycle.add(10 * kMs);
        m.cycle.add(12 * kMs);
        m.cycle_series.add(at(500), 10 * kMs);
        m.cycle_series.add(at(1500), 12 * kMs);
        m.cycle_jitter_ns = 2 * kMs;
        m.token_rotation.add(20 * kMs);
        m.token_rotation_series.add(at(600), 20 * kMs);
    }
    m.judgement = {Verdict::Weak, {{HealthThreshold::TargetRotationMs, 20, Verdict::Weak}}};
    h.masters.push_back(m);
    return h;
}

}  // namespace dpscope::test
