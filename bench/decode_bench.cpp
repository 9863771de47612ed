// Micro-benchmarks of the decoder's parts on a simulated session held in memory.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <vector>

#include "core/stream_framer.hpp"
#include "formats/output.hpp"
#include "formats/renderer.hpp"
#include "protocols/profibus/bus_decoder.hpp"
#include "protocols/profibus/fdl_framing_rules.hpp"
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

void BM_Render(benchmark::State& state) {
    const Session& s = session();
    auto format = static_cast<dpscope::OutputFormat>(state.range(0));
    FILE* sink = std::fopen("/dev/null", "w");
    for (auto _ : state) {
        dpscope::Output out(sink);
        auto renderer = dpscope::make_renderer(format, out);
        dpscope::BusDecoder decoder;
        std::uint64_t frame = 0;
        for (std::size_t i = 0; i < s.telegrams.size(); ++i) {
            const auto& bytes = s.telegrams[i];
            renderer->render(
                decoder.decode(dpscope::Bytes(bytes.data(), bytes.size()), s.times[i], ++frame),
                {});
        }
    }
    std::fclose(sink);
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(s.telegrams.size()));
}
BENCHMARK(BM_Render)
    ->Arg(static_cast<int>(dpscope::OutputFormat::Text))
    ->Arg(static_cast<int>(dpscope::OutputFormat::Jsonl))
    ->Arg(static_cast<int>(dpscope::OutputFormat::Csv));

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
