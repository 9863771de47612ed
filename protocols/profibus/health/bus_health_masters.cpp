// The bus-health tracker's masters (protocols/profibus/health/bus_health_state.hpp): active when
// they send, tokens taken or not, token rotation, and the Data_Exchange poll cycle with its jitter.
#include <cmath>

#include "protocols/profibus/health/bus_health_state.hpp"

namespace dpscope {

void BusHealthTrackerImpl::becomes_active(State& s, State::Slot& slot, const DecodedTelegram& t) {
    const bool was_lost = slot.health.state == StationState::Lost;
    set_state(s, slot, StationState::Active, t, was_lost);
    if (was_lost) {
        ++slot.health.returns;
        emit(s, HealthEventKind::StationReturned, slot, t);
    }
}

void BusHealthTrackerImpl::check_token_taken(State& s, const DecodedTelegram& t, bool damaged,
                                             bool addressed, std::uint64_t lost_cycles) {
    const FdlTelegram& fdl = t.dp.fdl;
    s.token_waiting = false;
    if (!damaged) {
        State::Master& m = s.masters[s.token_holder];
        if (!(addressed && fdl.sa == s.token_holder)) {
            ++m.health.tokens_not_taken;
            ++m.tokens_missed_in_row;
            if (m.tokens_missed_in_row >= lost_cycles) go_lost(s, s.slots[s.token_holder], t);
        }
    }
}

void BusHealthTrackerImpl::token_passed(State& s, const DecodedTelegram& t) {
    const FdlTelegram& fdl = t.dp.fdl;
    if (!fdl.has_addresses) return;
    State::Slot& sender = s.slots[fdl.sa];
    heard(s, sender, t);
    State::Master& sending = s.masters[fdl.sa];
    master_sends(s, sender, sending, t);
    ++sending.health.tokens_passed;
    if (fdl.da != kBroadcastAddress) {
        State::Slot& receiver = s.slots[fdl.da];
        list(receiver, t);
        make_master(s, receiver, t);
        State::Master& m = s.masters[fdl.da];
        ++m.health.tokens_received;
        if (t.time_ns != kNoTime) {
            if (m.last_token_ns != kNoTime && t.time_ns >= m.last_token_ns) {
                const std::int64_t rotation = t.time_ns - m.last_token_ns;
                m.health.token_rotation.add(rotation);
                m.health.token_rotation_series.add(t.time_ns, rotation);
            }
            m.last_token_ns = t.time_ns;
        }
        s.token_waiting = true;
        s.token_holder = fdl.da;
    }
}

void BusHealthTrackerImpl::new_poll_cycle(State::Master& m, const DecodedTelegram& t) {
    if (m.cycle_started && t.time_ns != kNoTime && m.cycle_start_ns != kNoTime &&
        t.time_ns >= m.cycle_start_ns) {
        const std::int64_t cycle = t.time_ns - m.cycle_start_ns;
        m.health.cycle.add(cycle);
        m.health.cycle_series.add(t.time_ns, cycle);
        if (m.last_cycle_ns >= 0) {
            m.jitter_sum += std::fabs(static_cast<double>(cycle - m.last_cycle_ns));
            ++m.jitter_count;
            m.health.cycle_jitter_ns = m.jitter_sum / static_cast<double>(m.jitter_count);
        }
        m.last_cycle_ns = cycle;
    }
    m.cycle_started = true;
    m.cycle_start_ns = t.time_ns;
    m.polled_in_cycle.clear();
}

}  // namespace dpscope
