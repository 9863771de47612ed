// The bus-health tracker's live list and each station's state
// (protocols/profibus/health/bus_health_state.hpp): listing, the state machine with its timeline
// and events, lost and returned stations.
#include "protocols/profibus/health/bus_health_state.hpp"

namespace dpscope {

void BusHealthTrackerImpl::first_listed(State::Slot& slot, const DecodedTelegram& t) {
    slot.listed = true;
    slot.health.first_seen_ns = t.time_ns;
    slot.health.first_frame = t.frame;
    if (slot.health.last_seen_ns == kNoTime) {
        slot.health.last_seen_ns = t.time_ns;
        slot.health.last_frame = t.frame;
    }
}

void BusHealthTrackerImpl::set_state(State& s, State::Slot& slot, StationState next,
                                     const DecodedTelegram& t, bool returned) {
    StationHealth& h = slot.health;
    if (h.state == next && !returned) return;
    h.state = next;
    ++h.state_changes;
    if (h.timeline.size() < BusHealthTracker::kMaxStateChanges)
        h.timeline.push_back(StateChange{t.time_ns, t.frame, next, returned});
    (void)s;
}

StationRole BusHealthTrackerImpl::role_of(const State::Slot& slot) {
    if (slot.master) return StationRole::Master;
    if (slot.answered) return StationRole::Slave;
    return StationRole::Unknown;
}

void BusHealthTrackerImpl::emit(State& s, HealthEventKind kind, const State::Slot& slot,
                                const DecodedTelegram& t) {
    s.events.push_back(HealthEvent{kind, slot.health.address, t.time_ns, t.frame, role_of(slot)});
}

void BusHealthTrackerImpl::go_lost(State& s, State::Slot& slot, const DecodedTelegram& t) {
    if (slot.health.state == StationState::Lost) return;
    slot.parameterised = false;
    ++slot.health.lost_events;
    set_state(s, slot, StationState::Lost, t, false);
    emit(s, HealthEventKind::StationLost, slot, t);
}

void BusHealthTrackerImpl::make_master(State& s, State::Slot& slot, const DecodedTelegram& t) {
    slot.master = true;
    (void)s;
    (void)t;
}

void BusHealthTrackerImpl::unanswered_cycle(State& s, State::Slot& slot, const DecodedTelegram& t,
                                            std::uint64_t lost_cycles) {
    ++slot.unanswered_cycles;
    if (!slot.master && slot.unanswered_cycles >= lost_cycles) go_lost(s, slot, t);
}

void BusHealthTrackerImpl::state_from_answer(State& s, State::Slot& slot, Service service,
                                             bool data, const DecodedTelegram& t,
                                             std::uint64_t lost_cycles) {
    StationHealth& h = slot.health;
    if (slot.master) {
        if (h.state == StationState::Lost) master_sends(s, slot, s.masters[h.address], t);
        return;
    }
    const bool was_lost = h.state == StationState::Lost;
    StationState next = was_lost ? StationState::Unknown : h.state;
    switch (service) {
        case Service::SetPrm:
        case Service::ChkCfg:
            if (service == Service::SetPrm) slot.parameterised = true;
            if (slot.exchanged_since_prm) {
                ++h.resyncs;
                slot.exchanged_since_prm = false;
            }
            next = StationState::Configuring;
            slot.diag_streak = 0;
            break;
        case Service::DataExchange:
            next = StationState::DataExchange;
            exchanged(slot, data);
            break;
        case Service::SlaveDiag:
            if (was_lost ||
                (h.state != StationState::DataExchange && h.state != StationState::Configuring)) {
                next = StationState::DiagnosisOnly;
            } else if (h.state == StationState::DataExchange && ++slot.diag_streak >= lost_cycles) {
                next = StationState::DiagnosisOnly;
            }
            break;
        default: break;
    }
    if (was_lost) {
        ++h.returns;
        set_state(s, slot, next, t, true);
        emit(s, HealthEventKind::StationReturned, slot, t);
    } else {
        set_state(s, slot, next, t, false);
    }
}

}  // namespace dpscope
