// Micro-benchmarks of the decoder's parts on a simulated session held in memory.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "core/protocol_descriptor.hpp"
#include "core/stream_framer.hpp"
#include "formats/output.hpp"
#include "formats/renderer.hpp"
#include "protocols/lane_options.hpp"
#include "protocols/profibus/bus_decoder.hpp"
#include "protocols/profibus/fdl_framing_rules.hpp"
#include "simulator/fault_spec.hpp"
#include "simulator/simulator.hpp"

namespace {

struct Session {
    std::vector<std::vector<std::uint8_t>> telegrams;
    std::vector<std::int64_t> times;
    std::vector<std::uint8_t> stream;
};

const Session& session() {
    static Session s = [] {
        Session built;
        dpscope::SimulatorOptions options;
        options.cycles = 0;
        options.max_telegrams = 100'000;
        dpscope::Simulator simulator(options);
        std::vector<std::uint8_t> bytes;
        std::int64_t time = 0;
        while (simulator.next(bytes, time)) {
            built.stream.insert(built.stream.end(), bytes.begin(), bytes.end());
            built.telegrams.push_back(bytes);
            built.times.push_back(time);
        }
        return built;
    }();
    return s;
}

void BM_ParseFdl(benchmark::State& state) {
    const Session& s = session();
    dpscope::FdlTelegram t;
    for (auto _ : state) {
        for (const auto& bytes : s.telegrams) {
            dpscope::parse_fdl(dpscope::Bytes(bytes.data(), bytes.size()), t);
            benchmark::DoNotOptimize(t);
        }
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(s.telegrams.size()));
}
BENCHMARK(BM_ParseFdl);

void BM_BusDecoder(benchmark::State& state) {
    const Session& s = session();
    for (auto _ : state) {
        dpscope::BusDecoder decoder;
        std::uint64_t frame = 0;
        for (std::size_t i = 0; i < s.telegrams.size(); ++i) {
            const auto& bytes = s.telegrams[i];
            benchmark::DoNotOptimize(
                decoder.decode(dpscope::Bytes(bytes.data(), bytes.size()), s.times[i], ++frame));
        }
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(s.telegrams.size()));
}
BENCHMARK(BM_BusDecoder);

struct CountingSink final : dpscope::StreamFramer::Sink {
    std::uint64_t telegrams = 0;
    void on_telegram(dpscope::Bytes, std::uint64_t) override { ++telegrams; }
    void on_skipped(const dpscope::SkippedBytes&) override {}
};

void BM_StreamFramer(benchmark::State& state) {
    const Session& s = session();
    const std::size_t chunk = static_cast<std::size_t>(state.range(0));
    for (auto _ : state) {
        dpscope::StreamFramer framer(dpscope::fdl_framing_rules());
        CountingSink sink;
        for (std::size_t at = 0; at < s.stream.size(); at += chunk)
            framer.feed(dpscope::Bytes(s.stream.data() + at, std::min(chunk, s.stream.size() - at)),
                        sink);
        framer.finish(sink);
        benchmark::DoNotOptimize(sink.telegrams);
    }
    state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(s.stream.size()));
}
BENCHMARK(BM_StreamFramer)->Arg(64)->Arg(4096)->Arg(65536);

// Each bus's session for the renderers: PROFIBUS DP (three PPO slaves), the DP-V1 mix (as
// bench/run's: five slaves, three of them DP-V1), the FC protocol and VLT 2000 (their default
// drives); 20,000 telegrams each, held in memory.
enum class Bus { Profibus, Dpv1, Fc, Vlt2000 };

struct BusSession {
    dpscope::Protocol protocol = dpscope::Protocol::ProfibusDp;
    std::vector<std::vector<std::uint8_t>> telegrams;
    std::vector<std::int64_t> times;
};

const BusSession& bus_session(Bus bus) {
    static BusSession sessions[4];
    BusSession& s = sessions[static_cast<int>(bus)];
    if (!s.telegrams.empty()) return s;
    dpscope::SimulatorOptions options;
    options.cycles = 0;
    options.max_telegrams = 20'000;
    options.seed = 7;
    if (bus == Bus::Fc) options.bus = dpscope::Protocol::Fc;
    if (bus == Bus::Vlt2000) options.bus = dpscope::Protocol::Vlt2000;
    if (bus == Bus::Dpv1)
        for (const char* spec : {"3:1", "4:2:dpv1", "5:5", "6:3:dpv1", "7:1:profidrive:dpv1"})
            options.slaves.push_back(dpscope::parse_slave_spec(spec).value());
    s.protocol = options.bus;
    dpscope::Simulator simulator(options);
    std::vector<std::uint8_t> bytes;
    std::int64_t time = 0;
    while (simulator.next(bytes, time)) {
        s.telegrams.push_back(bytes);
        s.times.push_back(time);
    }
    return s;
}

// Each bus's decoder alone: what BM_Render adds to it is the renderer's cost.
void BM_Decode(benchmark::State& state, Bus bus) {
    const BusSession& s = bus_session(bus);
    const dpscope::ProtocolDescriptor& protocol = dpscope::protocol_descriptor(s.protocol);
    for (auto _ : state) {
        auto decoder = protocol.make_decoder(dpscope::LaneOptions{});
        for (std::size_t i = 0; i < s.telegrams.size(); ++i)
            benchmark::DoNotOptimize(&decoder->decode(
                dpscope::Bytes(s.telegrams[i].data(), s.telegrams[i].size()), s.times[i], i + 1));
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(s.telegrams.size()));
}

// One renderer on one bus's telegrams (decoded as they go, as decode does), written to /dev/null
// through Output: the figure to watch for a renderer's regression (issue 31). Items: telegrams.
void BM_Render(benchmark::State& state, Bus bus, dpscope::OutputFormat format) {
    const BusSession& s = bus_session(bus);
    const dpscope::ProtocolDescriptor& protocol = dpscope::protocol_descriptor(s.protocol);
    FILE* sink = std::fopen("/dev/null", "w");
    for (auto _ : state) {
        dpscope::Output out(sink);
        auto renderer = dpscope::make_renderer(format, out);
        auto decoder = protocol.make_decoder(dpscope::LaneOptions{});
        for (std::size_t i = 0; i < s.telegrams.size(); ++i) {
            renderer->render(
                decoder->decode(dpscope::Bytes(s.telegrams[i].data(), s.telegrams[i].size()),
                                s.times[i], i + 1),
                {});
            out.end_record();
        }
    }
    std::fclose(sink);
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(s.telegrams.size()));
}
// Registered by name: BM_Decode/fc, BM_Render/fc/jsonl, ...
const bool kBusBenchmarksRegistered = [] {
    const std::pair<Bus, const char*> buses[] = {{Bus::Profibus, "profibus"},
                                                 {Bus::Dpv1, "dpv1"},
                                                 {Bus::Fc, "fc"},
                                                 {Bus::Vlt2000, "vlt2000"}};
    for (const auto& [bus, name] : buses) {
        benchmark::RegisterBenchmark((std::string("BM_Decode/") + name).c_str(), BM_Decode, bus);
        for (dpscope::OutputFormat format :
             {dpscope::OutputFormat::Text, dpscope::OutputFormat::Verbose,
              dpscope::OutputFormat::Jsonl, dpscope::OutputFormat::Csv})
            benchmark::RegisterBenchmark((std::string("BM_Render/") + name + "/" +
                                          std::string(dpscope::output_format_name(format)))
                                             .c_str(),
                                         BM_Render, bus, format);
    }
    return true;
}();

// The simulator itself, clean and with faults armed faster than they can be taken (orphan
// responses need an idle channel): the time per telegram must not grow with the session.
void BM_Simulator(benchmark::State& state) {
    dpscope::SimulatorOptions options;
    options.cycles = 0;
    options.max_telegrams = static_cast<std::uint64_t>(state.range(0));
    if (state.range(1) != 0)
        options.faults = {
            dpscope::FaultSpec{dpscope::FaultKind::OrphanResponse, 0.3, std::nullopt, std::nullopt},
            dpscope::FaultSpec{dpscope::FaultKind::FcsError, 0.01, std::nullopt, std::nullopt}};
    std::vector<std::uint8_t> bytes;
    std::int64_t time = 0;
    for (auto _ : state) {
        dpscope::Simulator simulator(options);
        while (simulator.next(bytes, time))
            benchmark::DoNotOptimize(bytes.data());
    }
    state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_Simulator)->Args({100'000, 0})->Args({100'000, 1})->Args({1'000'000, 1});

}  // namespace

BENCHMARK_MAIN();
