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
#include "protocols/profibus/health/health_render.hpp"
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
        const std::string steady_events = events_text(steady.observe(t));
        const std::string full_events = events_text(full.observe(t));
        if (steady_events != full_events) {
            ADD_FAILURE() << "events differ at frame " << frame << ":\n  steady: " << steady_events
                          << "\n  full:   " << full_events;
            return frame;
        }
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

}  // namespace
}  // namespace dpscope
