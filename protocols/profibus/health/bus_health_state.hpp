// Private to the bus-health tracker (protocols/profibus/health/bus_health*.cpp): its state beyond
// what BusHealth holds, and BusHealthTrackerImpl, the friend that does the work of observe(),
// judge() and finish(). Not for other users: the tracker's interface is
// protocols/profibus/health/bus_health.hpp.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "protocols/profibus/dp_service.hpp"
#include "protocols/profibus/health/bus_health.hpp"

namespace dpscope {

namespace detail {

// Per-address entries (a station's Slot, a master's Master), each made on first use with its
// address: a capture names a handful of the 128 addresses, and all 128 made up front (about
// 100 KB) cost more than tracking a short capture. Iterating visits the entries made so far, in
// address order. An address with no entry yet points at the table's own blank entry (a station
// never heard: not listed, state Unknown), so that peek() can hand out a pointer without testing
// it; the blank entry is never written.
template <class Entry>
class StationTable {
  public:
    StationTable() { entries_.fill(&blank_); }
    ~StationTable() {
        for (Entry* entry : entries_)
            if (entry != &blank_) delete entry;
    }
    StationTable(const StationTable&) = delete;
    StationTable& operator=(const StationTable&) = delete;

    // Called several times a telegram: the made entry is returned inline, the first use of an
    // address makes it out of line.
    Entry& operator[](std::size_t address) {
        if (Entry* entry = entries_[address]; entry != &blank_) [[likely]]
            return *entry;
        return make(address);
    }
    // The entry made for `address`, or the blank entry: never null. The caller writes through it
    // only after a test that the blank entry fails (listed, or an active state): it is never
    // written.
    Entry* peek(std::size_t address) noexcept { return entries_[address]; }
    // Whether peek() gave the blank entry.
    bool is_blank(const Entry* entry) const noexcept { return entry == &blank_; }

    class iterator {
      public:
        iterator(const StationTable& table, std::size_t at) : table_(&table), at_(at) {
            skip_empty();
        }
        Entry& operator*() const { return *table_->entries_[at_]; }
        iterator& operator++() {
            ++at_;
            skip_empty();
            return *this;
        }
        bool operator==(const iterator& other) const { return at_ == other.at_; }

      private:
        void skip_empty() {
            while (at_ < kStationCount && table_->entries_[at_] == &table_->blank_)
                ++at_;
        }
        const StationTable* table_;
        std::size_t at_;
    };
    iterator begin() { return iterator(*this, 0); }
    iterator end() { return iterator(*this, kStationCount); }

  private:
    [[gnu::noinline]] Entry& make(std::size_t address) {
        auto entry = std::make_unique<Entry>();
        entry->health.address = static_cast<std::uint8_t>(address);
        entries_[address] = entry.get();
        return *entry.release();
    }

    Entry blank_{};
    std::array<Entry*, kStationCount> entries_;
};

// A set of the 128 station addresses (two words: tested and set inline).
class AddressSet {
  public:
    bool contains(std::uint8_t address) const noexcept {
        return (words_[(address >> 6) & 1] >> (address & 63) & 1) != 0;
    }
    void insert(std::uint8_t address) noexcept {
        words_[(address >> 6) & 1] |= std::uint64_t{1} << (address & 63);
    }
    void clear() noexcept { words_ = {}; }

  private:
    std::array<std::uint64_t, 2> words_{};
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
        detail::AddressSet polled_in_cycle;
        detail::AddressSet polled_ever;
        Verdict last_verdict = Verdict::Good;
    };
    // The request waiting for its reply (Pending::active): none, one the full rules took, or
    // one steady_request() took (an SRD request with FCV to a listed station, the token not
    // waiting: what steady_answer() would otherwise test again).
    static constexpr std::uint8_t kNoRequest = 0;
    static constexpr std::uint8_t kFullRequest = 1;
    static constexpr std::uint8_t kSteadyRequest = 2;
    struct Pending {
        std::uint8_t active = kNoRequest;
        std::uint8_t master = 0;
        std::uint8_t slave = 0;
        std::uint8_t function = 0;
        Service service = Service::Unknown;
        bool counted = false;  // counted as a request of a listed station
        Slot* slot = nullptr;  // the slave's entry (s.slots[slave]; entries never move)
    };

    detail::StationTable<Slot> slots;
    detail::StationTable<Master> masters;
    // Per master -> slave link (links[master][slave]), kLink* bits: its frame count (valid, the
    // last FCB), and whether an intact request was seen on it (before one, nothing the slave
    // sends that master is judged: a capture may begin with the answer to a request before it).
    static constexpr std::uint8_t kLinkFcbValid = 1;
    static constexpr std::uint8_t kLinkFcb = 2;
    static constexpr std::uint8_t kLinkAsked = 4;
    std::array<std::array<std::uint8_t, kStationCount>, kStationCount> links{};
    Pending pending;
    bool token_waiting = false;
    std::uint8_t token_holder = 0;
    std::vector<HealthEvent> events;
    std::vector<HealthEvent> verdict_events;
    std::int64_t last_time_ns = kNoTime;
    std::uint64_t last_frame = 0;
    Verdict segment_last_verdict = Verdict::Good;
    bool finished = false;
    std::uint64_t full_telegrams = 0;  // taken by the full rules (steady_telegrams(): the others)
    double ns_per_byte = 0;  // a character's time on the line (0: baud not known)
    // No line rate (ns_per_byte 0) and the segment's first time known: a telegram later than the
    // segment's end only moves the times (observe()).
    bool plain_times = false;
    std::uint64_t lost_cycles = 3;
    bool steady_path = true;  // BusHealthOptions::steady_path
};

// The work of observe() and finish(), out of the class to keep the public header small: a friend
// of BusHealthTracker that reaches its State.
class BusHealthTrackerImpl {
  public:
    using State = BusHealthTracker::State;

    // ---- the telegram's steps (protocols/profibus/health/bus_health_tracker.cpp)
    //
    // observe() counts the segment, then takes the telegrams of a running bus in a few steps
    // (the steady path): an intact SRD request (frame count valid) from the active master to a
    // listed station (steady_request), the intact answer to the request waiting from a listed
    // slave whose state it leaves as it is (steady_answer), the intact token passed on by the
    // active master holding it (steady_token). Each tests first and counts after, through the
    // same helpers as the full rules (heard_listed, master_sends, count_frame, count_request,
    // answered, count_answer, exchanged, master_polls, token_passed); a test that fails hands the
    // telegram, untouched, to the full rules (observe_rest). BusHealthSteadyPathTest compares the
    // two over simulated sessions with every fault. Each step returns the telegram's events
    // (none on the steady path).

    // observe() counts the segment; the times of a telegram that is not the usual one (the
    // first with a time, one without a time or not later than the segment's end, a line rate
    // known) are count_segment_times()'s, and observe_times() goes on from there.
    static std::span<const HealthEvent> observe_times(State& s, SegmentHealth& seg,
                                                      const DecodedTelegram& t);
    static void count_segment_times(State& s, SegmentHealth& seg, const DecodedTelegram& t);
    // A steady step for an intact telegram, else the full rules.
    static inline std::span<const HealthEvent> choose_path(State& s, SegmentHealth& seg,
                                                           const DecodedTelegram& t);
    // An intact telegram while no request waits, or ...
    static std::span<const HealthEvent> steady_request(State& s, SegmentHealth& seg,
                                                       const DecodedTelegram& t);
    // ... while one does.
    static std::span<const HealthEvent> steady_answer(State& s, SegmentHealth& seg,
                                                      const DecodedTelegram& t);
    // An intact token (from steady_request()).
    static std::span<const HealthEvent> steady_token(State& s, SegmentHealth& seg,
                                                     const DecodedTelegram& t);
    // The full rules for a telegram the segment has counted.
    static std::span<const HealthEvent> observe_rest(State& s, SegmentHealth& seg,
                                                     const DecodedTelegram& t);
    // The frame count of a link (State::links) after an SRD/SDA request with FCV set and `fcb`:
    // whether it repeats the last request (same FCB as last time).
    static inline bool count_frame(std::uint8_t& link, bool fcb);
    // A request for `service` to the listed station `slot` (`expects`: it waits for a reply;
    // `repeat`: an FDL retry): its counts. True when it starts a poll cycle (it waits for a reply
    // and is no retry): the caller closes the last one and opens it.
    static inline bool count_request(State::Slot& slot, Service service, bool repeat, bool expects);
    // The answer `fdl` of `slot` to a request of `function` for `service`: negative answers and
    // illegal ones (a wrong kind; a short acknowledge where data was due).
    static inline void count_answer(State::Slot& slot, const FdlTelegram& fdl,
                                    std::uint8_t function, Service service);
    // The slave asked answered: its counts and its poll cycle (answered).
    static void answered(State::Slot& slot) {
        ++slot.health.answers;
        slot.answered = true;
        slot.cycle_answered = true;
        slot.unanswered_cycles = 0;
    }

    // ---- the live list and each station's state
    // (protocols/profibus/health/bus_health_stations.cpp)

    // Lists the station (once): first seen now.
    static void list(State::Slot& slot, const DecodedTelegram& t) {
        if (!slot.listed) [[unlikely]]
            first_listed(slot, t);
    }
    static void first_listed(State::Slot& slot, const DecodedTelegram& t);
    static void set_state(State& s, State::Slot& slot, StationState next, const DecodedTelegram& t,
                          bool returned);
    static StationRole role_of(const State::Slot& slot);
    static void emit(State& s, HealthEventKind kind, const State::Slot& slot,
                     const DecodedTelegram& t);
    static void go_lost(State& s, State::Slot& slot, const DecodedTelegram& t);
    // A station that sent a telegram (listed now if it was not).
    static void heard(State& s, State::Slot& slot, const DecodedTelegram& t) {
        list(slot, t);
        heard_listed(slot, t);
        (void)s;
    }
    // heard() of a listed station.
    static void heard_listed(State::Slot& slot, const DecodedTelegram& t) {
        ++slot.health.telegrams_sent;
        slot.health.last_seen_ns = t.time_ns;
        slot.health.last_frame = t.frame;
    }
    static void make_master(State& s, State::Slot& slot, const DecodedTelegram& t);
    // Closes a slave's poll cycle: an unanswered one counts toward lost.
    static void close_cycle(State& s, State::Slot& slot, const DecodedTelegram& t,
                            std::uint64_t lost_cycles) {
        if (!slot.cycle_open) return;
        slot.cycle_open = false;
        if (!slot.cycle_answered) [[unlikely]]
            unanswered_cycle(s, slot, t, lost_cycles);
    }
    // A slave's poll cycle starts (close_cycle() closed the last one).
    static void open_cycle(State::Slot& slot) {
        slot.cycle_open = true;
        slot.cycle_answered = false;
        slot.cycle_repeats = 0;
    }
    // The rest of close_cycle() for a cycle that went unanswered.
    static void unanswered_cycle(State& s, State::Slot& slot, const DecodedTelegram& t,
                                 std::uint64_t lost_cycles);
    // A slave that answered Data_Exchange (`data`: with data), in whatever state: what its rules
    // remember of it (the state itself is state_from_answer's).
    static void exchanged(State::Slot& slot, bool data) {
        slot.diag_streak = 0;
        slot.parameterised = true;
        slot.exchanged_since_prm = true;
        if (data) slot.exchange_data_seen = true;
    }
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
    // Master `m` sent a Data_Exchange request (not a repeat) to `slave`: its poll cycle (a new
    // one when it polled `slave` in this one already).
    [[gnu::always_inline]] static void master_polls(State::Master& m, const DecodedTelegram& t,
                                                    std::uint8_t slave) {
        if (m.polled_in_cycle.contains(slave) || !m.cycle_started) [[unlikely]]
            new_poll_cycle(m, t);
        m.polled_in_cycle.insert(slave);
        if (!m.polled_ever.contains(slave)) [[unlikely]] {
            m.polled_ever.insert(slave);
            ++m.health.slaves_polled;
        }
    }
    // The poll cycle that ended (its time measured) and the one that starts at `t`.
    static void new_poll_cycle(State::Master& m, const DecodedTelegram& t);
};

}  // namespace dpscope
