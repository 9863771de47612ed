// Private to the bus-health tracker (protocols/profibus/health/bus_health*.cpp): its state beyond
// what BusHealth holds, and BusHealthTrackerImpl, the friend that does the work of observe(),
// judge() and finish(). Not for other users: the tracker's interface is
// protocols/profibus/health/bus_health.hpp.
#pragma once

#include <array>
#include <bitset>
#include <cstdint>
#include <memory>
#include <vector>

#include "protocols/profibus/dp_service.hpp"
#include "protocols/profibus/health/bus_health.hpp"

namespace dpscope {

namespace detail {

// Per-address entries (a station's Slot, a master's Master), each made on first use with its
// address: a capture names a handful of the 128 addresses, and all 128 made up front (about
// 100 KB) cost more than tracking a short capture. Iterating visits the entries made so far, in
// address order.
template <class Entry>
class StationTable {
  public:
    // Called several times a telegram: the made entry is returned inline, the first use of an
    // address makes it out of line.
    Entry& operator[](std::size_t address) {
        if (Entry* entry = entries_[address].get(); entry != nullptr) [[likely]]
            return *entry;
        return make(address);
    }

    class iterator {
      public:
        using Slots = std::array<std::unique_ptr<Entry>, kStationCount>;
        iterator(Slots& entries, std::size_t at) : entries_(&entries), at_(at) { skip_empty(); }
        Entry& operator*() const { return *(*entries_)[at_]; }
        iterator& operator++() {
            ++at_;
            skip_empty();
            return *this;
        }
        bool operator==(const iterator& other) const { return at_ == other.at_; }

      private:
        void skip_empty() {
            while (at_ < kStationCount && !(*entries_)[at_])
                ++at_;
        }
        Slots* entries_;
        std::size_t at_;
    };
    iterator begin() { return iterator(entries_, 0); }
    iterator end() { return iterator(entries_, kStationCount); }

  private:
    [[gnu::noinline]] Entry& make(std::size_t address) {
        std::unique_ptr<Entry>& entry = entries_[address];
        entry = std::make_unique<Entry>();
        entry->health.address = static_cast<std::uint8_t>(address);
        return *entry;
    }

    std::array<std::unique_ptr<Entry>, kStationCount> entries_;
};

}  // namespace detail

// The tracker's state beyond what BusHealth holds.
struct BusHealthTracker::State {
    // A station's counters and what its rules remember.
    struct Slot {
        StationHealth health;
        bool listed = false;
        bool master = false;    // sent a token or request, got the token, or said so
        bool answered = false;  // answered a request
        // Poll cycles (slave side).
        bool cycle_open = false;
        bool cycle_answered = false;
        std::uint64_t cycle_repeats = 0;
        std::uint64_t unanswered_cycles = 0;
        std::uint64_t diag_streak = 0;  // Slave_Diag answers in a row while in data exchange
        bool exchange_data_seen = false;
        // Answered Set_Prm or Data_Exchange (since listed or since lost): its diagnosis from then
        // on can show a fault (before, Station_Not_Ready and Prm_Req are the start-up's).
        bool parameterised = false;
        // Answered Data_Exchange since it last answered Set_Prm or Chk_Cfg: the next of those
        // answered is a resync (whatever came between, e.g. being lost and diagnosis polls).
        bool exchanged_since_prm = false;
        Verdict last_verdict = Verdict::Good;
    };
    struct Master {
        MasterHealth health;
        std::uint64_t tokens_missed_in_row = 0;
        std::int64_t last_token_ns = kNoTime;
        std::int64_t cycle_start_ns = kNoTime;
        bool cycle_started = false;
        std::int64_t last_cycle_ns = -1;
        double jitter_sum = 0;
        std::uint64_t jitter_count = 0;
        std::bitset<kStationCount> polled_in_cycle;
        std::bitset<kStationCount> polled_ever;
        Verdict last_verdict = Verdict::Good;
    };
    // The request waiting for its reply.
    struct Pending {
        bool active = false;
        std::uint8_t master = 0;
        std::uint8_t slave = 0;
        std::uint8_t function = 0;
        Service service = Service::Unknown;
        bool counted = false;  // counted as a request of a listed station
        Slot* slot = nullptr;  // the slave's entry (s.slots[slave]; entries never move)
    };

    detail::StationTable<Slot> slots;
    detail::StationTable<Master> masters;
    // Frame count per master -> slave link: bit 0 valid, bit 1 the last FCB.
    std::array<std::array<std::uint8_t, kStationCount>, kStationCount> link_fcb{};
    // The links (master -> slave) an intact request was seen on: before it, nothing the slave
    // sends that master is judged (a capture may begin with the answer to a request before it).
    std::array<std::bitset<kStationCount>, kStationCount> link_asked{};
    Pending pending;
    bool token_waiting = false;
    std::uint8_t token_holder = 0;
    std::vector<HealthEvent> events;
    std::vector<HealthEvent> verdict_events;
    std::int64_t last_time_ns = kNoTime;
    std::uint64_t last_frame = 0;
    Verdict segment_last_verdict = Verdict::Good;
    bool finished = false;
    double ns_per_byte = 0;  // a character's time on the line (0: baud not known)
    std::uint64_t lost_cycles = 3;
};

// The work of observe() and finish(), out of the class to keep the public header small: a friend
// of BusHealthTracker that reaches its State.
class BusHealthTrackerImpl {
  public:
    using State = BusHealthTracker::State;

    // ---- the live list and each station's state
    // (protocols/profibus/health/bus_health_stations.cpp)

    // Lists the station (once): first seen now.
    static void list(State::Slot& slot, const DecodedTelegram& t);
    static void set_state(State& s, State::Slot& slot, StationState next, const DecodedTelegram& t,
                          bool returned);
    static StationRole role_of(const State::Slot& slot);
    static void emit(State& s, HealthEventKind kind, const State::Slot& slot,
                     const DecodedTelegram& t);
    static void go_lost(State& s, State::Slot& slot, const DecodedTelegram& t);
    // A station that sent a telegram.
    static void heard(State& s, State::Slot& slot, const DecodedTelegram& t);
    static void make_master(State& s, State::Slot& slot, const DecodedTelegram& t);
    // Closes a slave's poll cycle: an unanswered one counts toward lost.
    static void close_cycle(State& s, State::Slot& slot, const DecodedTelegram& t,
                            std::uint64_t lost_cycles);
    // The state of the station that answered a request for `service` (`data`: with data): a
    // slave's from the service, a lost master's back to active.
    static void state_from_answer(State& s, State::Slot& slot, Service service, bool data,
                                  const DecodedTelegram& t, std::uint64_t lost_cycles);

    // ---- the masters: token passing and rotation, poll cycle
    // (protocols/profibus/health/bus_health_masters.cpp)

    // A master (`slot`, its entry `m`) sent a telegram: it is active (back from lost when it
    // was). Inline: every request passes here, and only a change of state does more.
    static void master_sends(State& s, State::Slot& slot, State::Master& m,
                             const DecodedTelegram& t) {
        slot.master = true;
        m.tokens_missed_in_row = 0;
        if (slot.health.state != StationState::Active) [[unlikely]]
            becomes_active(s, slot, t);
    }
    // The rest of master_sends(): a master not active until now (lost, or not yet seen sending).
    static void becomes_active(State& s, State::Slot& slot, const DecodedTelegram& t);
    // The telegram after a token passed (s.token_waiting): the token was taken when it is its
    // receiver's own; not taken lost_cycles times in a row, the receiver is lost.
    static void check_token_taken(State& s, const DecodedTelegram& t, bool damaged, bool addressed,
                                  std::uint64_t lost_cycles);
    // An intact token (SD4): passed by its sender, received by its addressee (token rotation).
    static void token_passed(State& s, const DecodedTelegram& t);
    // Master `m` sent a Data_Exchange request (not a repeat) to `slave`: its poll cycle.
    static void master_polls(State::Master& m, const DecodedTelegram& t, std::uint8_t slave);
};

}  // namespace dpscope
