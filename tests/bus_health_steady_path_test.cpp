// The bus-health tracker's steady path (protocols/profibus/health/bus_health_state.hpp) against its
// full rules: the same simulated sessions, with every PROFIBUS fault at a rate, token rings,
// a line rate, and telegrams damaged byte by byte, fed to a tracker with the steady path and one
// without (BusHealthOptions::steady_path). Every figure, every event, at every judgement.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "formats/json_writer.hpp"
#include "protocols/profibus/bus_decoder.hpp"
#include "protocols/profibus/health/bus_health.hpp"
#include "protocols/profibus/health/bus_health_state.hpp"
#include "protocols/profibus/health/health_render.hpp"
#include "protocols/profibus/telegram_builder.hpp"
#include "simulator/simulator.hpp"

namespace dpscope {
namespace {

// Everything health() holds, as the stats JSON writes it, and what that rounds (durations in
// ms, series means) exactly.
std::string figures(const BusHealth& h) {
    fmt::memory_buffer out;
    {
        JsonWriter w(out);
        w.begin_object();
        health::write_json_members(w, h);
        w.end_object();
    }
    std::string text = fmt::to_string(out);
    const auto durations = [&](const DurationStats& d) {
        text += fmt::format(" {} {} {} {} {}", d.count(), d.min(), d.max(), d.mean(), d.p95());
    };
    const auto series = [&](const TimeSeries& s) {
        text += fmt::format(" /{}", s.samples_per_point());
        for (const TimeSeries::Point& p : s.points())
            text += fmt::format(" {} {} {} {} {} {}", p.first_ns, p.last_ns, p.min_ns, p.max_ns,
                                p.sum_ns, p.count);
    };
    for (const MasterHealth& m : h.masters) {
        durations(m.token_rotation);
        durations(m.cycle);
        series(m.token_rotation_series);
        series(m.cycle_series);
        text += fmt::format(" {}", m.cycle_jitter_ns);
    }
    text += fmt::format(" {} {}", h.segment.busy_ns, h.segment.end_ns);
    return text;
}

std::string events_text(std::span<const HealthEvent> events) {
    std::string text;
    for (const HealthEvent& e : events)
        text += fmt::format("{} {} {} {} {};", health_event_name(e.kind), e.address, e.time_ns,
                            e.frame, station_role_name(e.role));
    return text;
}

struct Session {
    SimulatorOptions options;
    std::uint32_t baud = 0;
    double damage_rate = 0;  // the chance a telegram has one byte changed
};

// Feeds both trackers the same telegram; false (and a failure) when their events differ.
bool same_events(BusHealthTracker& steady, BusHealthTracker& full, const DecodedTelegram& t) {
    const std::string steady_events = events_text(steady.observe(t));
    const std::string full_events = events_text(full.observe(t));
    if (steady_events == full_events) return true;
    ADD_FAILURE() << "events differ at frame " << t.frame << ":\n  steady: " << steady_events
                  << "\n  full:   " << full_events;
    return false;
}

// Feeds the session to both trackers; returns the number of telegrams.
std::uint64_t compare(const Session& session) {
    Simulator simulator(session.options);
    BusDecoder decoder;
    BusHealthOptions steady_options;
    steady_options.baud = session.baud;
    BusHealthOptions full_options = steady_options;
    full_options.steady_path = false;
    BusHealthTracker steady(steady_options);
    BusHealthTracker full(full_options);
    std::mt19937_64 random(session.options.seed);
    std::uniform_real_distribution<double> chance(0.0, 1.0);
    std::vector<std::uint8_t> bytes;
    std::int64_t time_ns = 0;
    std::uint64_t frame = 0;
    while (simulator.next(bytes, time_ns)) {
        ++frame;
        if (!bytes.empty() && chance(random) < session.damage_rate)
            bytes[random() % bytes.size()] ^= static_cast<std::uint8_t>(1 + random() % 255);
        const DecodedTelegram& t =
            decoder.decode(Bytes(bytes.data(), bytes.size()), time_ns, frame);
        if (!same_events(steady, full, t)) return frame;
        if (frame % 997 == 0) {
            const std::string steady_bad = events_text(steady.judge());
            const std::string full_bad = events_text(full.judge());
            EXPECT_EQ(steady_bad, full_bad) << "at frame " << frame;
            const std::string a = figures(steady.health());
            const std::string b = figures(full.health());
            if (a != b) {
                EXPECT_EQ(a, b) << "figures differ at frame " << frame;
                return frame;
            }
        }
    }
    steady.finish();
    full.finish();
    EXPECT_EQ(figures(steady.health()), figures(full.health()));
    EXPECT_EQ(full.steady_telegrams(), 0u);
    // A running bus is mostly steady polls: the short path is taken, not only never wrong.
    if (session.damage_rate == 0) {
        EXPECT_GT(steady.steady_telegrams(), frame / 2);
    }
    return frame;
}

SimulatorOptions base(std::uint64_t seed) {
    SimulatorOptions options;
    options.seed = seed;
    options.cycles = 400;
    for (const char* spec : {"3:1", "4:2:dpv1", "5:5", "6:3:dpv1", "7:1:profidrive:dpv1"})
        options.slaves.push_back(*parse_slave_spec(spec));
    return options;
}

// Every PROFIBUS fault, alone, at a rate high enough to happen many times.
TEST(BusHealthSteadyPathTest, EveryFaultGivesTheSameFiguresAndEvents) {
    std::uint64_t sessions = 0;
    for (std::size_t k = 0; k < kFaultKindCount; ++k) {
        const auto kind = static_cast<FaultKind>(k);
        if (!fault_applies_to_bus(kind, Protocol::ProfibusDp) ||
            fault_bus(kind) != Protocol::ProfibusDp)
            continue;
        SCOPED_TRACE(std::string(fault_kind_name(kind)));
        Session session{base(11 + k)};
        session.options.faults = {FaultSpec{kind, 0.03, std::nullopt, std::nullopt}};
        if (!check_simulator_faults(session.options)) continue;
        EXPECT_GT(compare(session), 1000u);
        ++sessions;
    }
    EXPECT_GT(sessions, 30u);  // the PROFIBUS catalogue, bus health's own faults included
}

// All of them at once, in a token ring, with a line rate (the bus-load path), and with telegrams
// damaged at random (every branch of the full rules: damaged requests and answers, unknown
// stations, broken addresses).
TEST(BusHealthSteadyPathTest, RingsLineRatesAndDamageGiveTheSameFiguresAndEvents) {
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
        SCOPED_TRACE(seed);
        Session session{base(seed)};
        session.options.cycles = 600;
        if (seed % 2 == 0) session.options.ring_masters = {1, 9};
        if (seed % 3 == 0) session.baud = 1'500'000;
        session.damage_rate = seed <= 3 ? 0.01 : 0.002;
        for (std::size_t k = 0; k < kFaultKindCount; ++k) {
            const auto kind = static_cast<FaultKind>(k);
            if (fault_bus(kind) != Protocol::ProfibusDp) continue;
            SimulatorOptions with = session.options;
            with.faults.push_back(FaultSpec{kind, 0.002, std::nullopt, std::nullopt});
            if (check_simulator_faults(with)) session.options = with;
        }
        EXPECT_GT(compare(session), 5000u);
    }
}

// Telegrams the simulator never sends, at random among five stations (two masters passing the
// token, three slaves; any of them may become the other): requests of every FDL function with
// and without FCV, reserved frame control bytes, requests to the sender itself and to all,
// answers of every status and station type from anyone to anyone (a master answering, an answer
// nobody asked for), short acknowledges, now and then a token to a slave; each decoded intact,
// both trackers compared after every one.
TEST(BusHealthSteadyPathTest, OddTelegramsGiveTheSameFiguresAndEvents) {
    constexpr std::uint8_t kStations[] = {1, 2, 3, 4, 5};
    constexpr std::uint8_t kMasters[] = {1, 2};
    constexpr std::uint8_t kSlaves[] = {3, 4, 5};
    constexpr FdlFunction kFunctions[] = {
        FdlFunction::SrdHigh,   FdlFunction::SrdLow, FdlFunction::SdaHigh, FdlFunction::SdnLow,
        FdlFunction::FdlStatus, FdlFunction::Msrd,   FdlFunction::Ident};
    constexpr FdlStatus kStatuses[] = {FdlStatus::Ok,
                                       FdlStatus::UserError,
                                       FdlStatus::NoService,
                                       FdlStatus::DataLow,
                                       FdlStatus::DataHigh,
                                       FdlStatus::NoResponseData,
                                       FdlStatus::NotReceivedDataHigh};
    constexpr int kSaps[] = {-1, -1, -1, 60, 61, 62, 51};  // none: Data_Exchange
    std::uint64_t steady_taken = 0;
    for (std::uint64_t seed = 1; seed <= 25; ++seed) {
        SCOPED_TRACE(seed);
        std::mt19937_64 random(seed);
        const auto pick = [&](std::size_t n) { return static_cast<std::size_t>(random() % n); };
        BusDecoder decoder;
        BusHealthOptions full_options;
        full_options.steady_path = false;
        BusHealthTracker steady;
        BusHealthTracker full(full_options);
        std::int64_t time_ns = 1'000'000'000;
        std::vector<std::uint8_t> bytes;
        std::uint8_t last_master = 1;
        std::uint8_t last_slave = 3;
        bool fcb = false;
        bool ok = true;
        for (std::uint64_t frame = 1; frame <= 4000 && ok; ++frame) {
            bytes.clear();
            const std::uint8_t a = kStations[pick(5)];
            const std::uint8_t b = pick(20) == 0 ? 127 : kStations[pick(5)];
            const std::size_t kind = pick(10);
            const std::uint8_t data[4] = {static_cast<std::uint8_t>(random()), 0x22, 0x33, 0x44};
            const int sap = kSaps[pick(std::size(kSaps))];
            const std::optional<std::uint8_t> dsap =
                sap < 0 ? std::nullopt
                        : std::optional<std::uint8_t>(static_cast<std::uint8_t>(sap));
            const std::optional<std::uint8_t> ssap =
                sap < 0 ? std::nullopt : std::optional<std::uint8_t>(std::uint8_t{62});
            if (kind <= 3) {
                // Mostly the steady kind: an SRD with FCV from the last master to the last slave.
                const bool steady_kind = kind <= 1;
                // (A slave that sends a request is a master from then on: now and then.)
                const std::uint8_t sa =
                    steady_kind ? last_master : (pick(100) == 0 ? a : kMasters[pick(2)]);
                const std::uint8_t da = steady_kind ? kSlaves[pick(3)] : b;
                fcb = pick(8) == 0 ? fcb : !fcb;  // now and then a repeat
                const FdlFunction function =
                    steady_kind ? FdlFunction::SrdHigh : kFunctions[pick(std::size(kFunctions))];
                auto fc = request_fc(function, fcb, steady_kind || pick(3) != 0);
                if (pick(30) == 0) fc = static_cast<std::uint8_t>(fc | 0x80);  // reserved
                append_telegram(bytes, {da, sa, fc, dsap, ssap, Bytes(data, pick(5))});
                last_master = sa;
                last_slave = da;
            } else if (kind <= 6) {
                // An answer: mostly from the slave asked to its master.
                const bool asked = kind <= 5;
                const std::uint8_t sa = asked ? last_slave : a;
                const std::uint8_t da = asked ? last_master : b;
                const FdlStatus status = kStatuses[pick(std::size(kStatuses))];
                const auto type = static_cast<std::uint8_t>(pick(4));
                const std::size_t length =
                    status == FdlStatus::DataLow || status == FdlStatus::DataHigh ? 1 + pick(4) : 0;
                append_telegram(bytes, {da, sa, response_fc(status, type),
                                        dsap ? ssap : std::nullopt, dsap, Bytes(data, length)});
            } else if (kind == 7) {
                append_short_ack(bytes);
            } else {
                // Between the two masters; now and then to another station, which makes it one.
                const std::uint8_t to = pick(300) == 0 ? b : kMasters[pick(2)];
                append_token(bytes, to, last_master);
                if (to != 127) last_master = to;
            }
            time_ns += 100'000 + static_cast<std::int64_t>(pick(50'000));
            const DecodedTelegram& t =
                decoder.decode(Bytes(bytes.data(), bytes.size()), time_ns, frame);
            ok = same_events(steady, full, t);
            if (frame % 250 == 0) {
                EXPECT_EQ(events_text(steady.judge()), events_text(full.judge()));
                ok = ok && figures(steady.health()) == figures(full.health());
                EXPECT_TRUE(ok) << "figures differ at frame " << frame;
            }
        }
        steady.finish();
        full.finish();
        EXPECT_EQ(figures(steady.health()), figures(full.health()));
        steady_taken += steady.steady_telegrams();
    }
    EXPECT_GT(steady_taken, 1000u);  // the odd telegrams are mixed with steady ones
}

// The tracker's per-address table (bus_health_state.hpp): an address without an entry gives the
// table's blank entry from peek() (a station never heard, which the steady tests turn away); made
// entries are peeked and iterated in address order, and making them leaves the blank entry as it
// was.
struct TableEntry {  // what the table needs of an entry, and what the steady tests read
    struct {
        std::uint8_t address = 0;
        StationState state = StationState::Unknown;
    } health;
    bool listed = false;
};

TEST(BusHealthStationTableTest, BlankUntilMadeThenPeekedAndIterated) {
    detail::StationTable<TableEntry> table;
    for (std::size_t address = 0; address < kStationCount; ++address)
        ASSERT_TRUE(table.is_blank(table.peek(address)));
    EXPECT_TRUE(table.begin() == table.end());
    table[70].listed = true;
    table[5].health.state = StationState::Active;
    ASSERT_FALSE(table.is_blank(table.peek(5)));
    EXPECT_EQ(table.peek(5)->health.address, 5);
    EXPECT_EQ(table.peek(5)->health.state, StationState::Active);
    EXPECT_EQ(table.peek(70), &table[70]);
    EXPECT_TRUE(table.peek(70)->listed);
    std::vector<int> visited;
    for (TableEntry& entry : table)
        visited.push_back(entry.health.address);
    EXPECT_EQ(visited, (std::vector<int>{5, 70}));
    const TableEntry* blank = table.peek(6);
    ASSERT_TRUE(table.is_blank(blank));
    EXPECT_FALSE(blank->listed);
    EXPECT_EQ(blank->health.state, StationState::Unknown);
    EXPECT_EQ(blank->health.address, 0);
    EXPECT_EQ(table.peek(6), table.peek(127));  // one blank entry for every empty address
}

}  // namespace
}  // namespace dpscope
