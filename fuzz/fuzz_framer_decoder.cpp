// Feeds arbitrary bytes through the stream framer in chunks whose sizes the input chooses, decodes
// every telegram with one BusDecoder (so state carries over, DP-V1 requests naming the responses'
// PROFIdrive parameters included), tracks it with one SessionTracker (every rule: the DP link
// rules, the parameter-channel engine, the DP-V1 parameter-access tracker), renders it with the
// findings at it in one of the output formats (taking turns, so every renderer sees every kind of
// telegram over a run) and also decodes and tracks the whole input as a single capture record,
// then finishes the session (what is still open is reported). Every PROFIBUS telegram also goes to
// a BusHealthTracker (lost_cycles 1..5 and the baud, unknown or 1.5 Mbit/s, chosen by the input's
// second byte), judged every few telegrams and finished at the end; its statistics are then
// rendered in every stats format and as the live table (at a width the input chooses). The same
// input then goes through the Danfoss FC protocol's framer, FcDecoder and FcTracker, and through
// the VLT 2000 telegram's framer, Vlt2000Decoder and Vlt2000Tracker, rendered the same way.
#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <span>
#include <type_traits>
#include <vector>

#include "decoder/bus_decoder.hpp"
#include "decoder/bus_health.hpp"
#include "decoder/fc_decoder.hpp"
#include "decoder/fc_framing_rules.hpp"
#include "decoder/fc_tracker.hpp"
#include "decoder/fdl_framing_rules.hpp"
#include "decoder/session_tracker.hpp"
#include "decoder/stream_framer.hpp"
#include "decoder/vlt2000_decoder.hpp"
#include "decoder/vlt2000_framing_rules.hpp"
#include "decoder/vlt2000_tracker.hpp"
#include "formats/output.hpp"
#include "formats/renderer.hpp"
#include "formats/stats.hpp"

namespace {

dpscope::Output& output() {
    static FILE* sink = std::fopen("/dev/null", "w");
    static dpscope::Output out{sink};
    return out;
}

// One protocol's decoder and tracker, and the framing rules its stream is cut by.
template <typename Decoder, typename Tracker>
struct RenderAll final : dpscope::StreamFramer::Sink {
    explicit RenderAll(const dpscope::FramingRules& rules_) : rules(rules_) {
        for (auto format : {dpscope::OutputFormat::Text, dpscope::OutputFormat::Verbose,
                            dpscope::OutputFormat::Jsonl, dpscope::OutputFormat::Csv})
            renderers.push_back(dpscope::make_renderer(format, output()));
    }

    const dpscope::FramingRules& rules;
    Decoder decoder;
    Tracker tracker;
    std::uint64_t frame = 0;
    std::int64_t time_ns = 1'000'000'000LL * 1700000000;
    std::vector<std::unique_ptr<dpscope::TelegramRenderer>> renderers;
    // PROFIBUS only: the bus-health tracker every telegram also goes to, and how often (in
    // telegrams) it is judged.
    std::optional<dpscope::BusHealthTracker> health;
    std::uint64_t judge_every = 1;

    void decode(dpscope::Bytes telegram) {
        // The clock advances 1 ms a telegram, so that time-outs fire over a long input.
        time_ns += 1'000'000;
        const dpscope::DecodedTelegram& t = decoder.decode(telegram, time_ns, ++frame);
        std::span<const dpscope::Finding> findings = tracker.track(t);
        (void)tracker.completed();
        renderers[frame % renderers.size()]->render(t, findings);
        output().buffer().clear();
        if (health) {
            (void)health->observe(t);
            if (frame % judge_every == 0) (void)health->judge();
        }
    }
    void on_telegram(dpscope::Bytes telegram, std::uint64_t) override { decode(telegram); }
    void on_skipped(const dpscope::SkippedBytes& skipped) override {
        (void)rules.describe_skip(skipped);
    }
};

// Finishes the bus-health tracker and renders its statistics in every format and as the live
// table, `choice` picking the table's width (0: no limit, or 40 to 160 columns).
void render_health(dpscope::BusHealthTracker& health, std::uint8_t choice) {
    health.finish();
    dpscope::StatsContext context;
    context.input.name = "fuzz";
    context.input.format = "raw";
    context.health = &health.health();
    context.version = "fuzz";
    for (auto format :
         {dpscope::StatsFormat::Text, dpscope::StatsFormat::Json, dpscope::StatsFormat::Markdown,
          dpscope::StatsFormat::Html, dpscope::StatsFormat::Csv}) {
        dpscope::render_stats(format, context, output());
        output().buffer().clear();
    }
    unsigned width = (choice & 0x04) != 0 ? 40u + (choice % 121u) : 0u;
    dpscope::render_live_table(health.health(), output(), width);
    output().buffer().clear();
}

// Frames the input in chunks whose size its first byte chooses (a 0x00 byte marks a line gap),
// decodes, tracks and renders every telegram, then the whole input as one record.
template <typename Decoder, typename Tracker>
void run(const std::uint8_t* data, std::size_t size, const dpscope::FramingRules& rules) {
    RenderAll<Decoder, Tracker> all(rules);
    std::uint8_t choice = size > 1 ? data[1] : 0;
    if constexpr (std::is_same_v<Decoder, dpscope::BusDecoder>) {
        dpscope::BusHealthOptions options;
        (void)options.thresholds.set(dpscope::HealthThreshold::LostCycles, (choice % 5) + 1);
        options.baud = (choice & 0x08) != 0 ? 1'500'000 : 0;
        all.health.emplace(options);
        all.judge_every = ((choice >> 4) % 8) + 1;
    }
    dpscope::StreamFramer framer(rules);
    std::size_t chunk = size > 0 ? (data[0] % 17) + 1 : 1;
    for (std::size_t at = 0; at < size; at += chunk) {
        std::size_t n = std::min(chunk, size - at);
        framer.feed(dpscope::Bytes(data + at, n), all);
        if (n > 0 && data[at] == 0x00) framer.mark_gap(all);
    }
    framer.finish(all);
    all.decode(dpscope::Bytes(data, size));
    (void)all.tracker.finish();
    if (all.health) render_health(*all.health, choice);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    run<dpscope::BusDecoder, dpscope::SessionTracker>(data, size, dpscope::fdl_framing_rules());
    run<dpscope::FcDecoder, dpscope::FcTracker>(data, size, dpscope::fc_framing_rules());
    run<dpscope::Vlt2000Decoder, dpscope::Vlt2000Tracker>(data, size,
                                                          dpscope::vlt2000_framing_rules());
    return 0;
}
