// Feeds arbitrary bytes through the stream framer in chunks whose sizes the input chooses, decodes
// every telegram with one BusDecoder (so state carries over, DP-V1 requests naming the responses'
// PROFIdrive parameters included), tracks it with one SessionTracker (every rule: the DP link
// rules, the parameter-channel engine, the DP-V1 parameter-access tracker), renders it with the
// findings at it in one of the output formats (taking turns, so every renderer sees every kind of
// telegram over a run) and also decodes and tracks the whole input as a single capture record,
// then finishes the session (what is still open is reported).
#include <cstdint>
#include <cstdio>
#include <memory>
#include <span>
#include <vector>

#include "decoder/bus_decoder.hpp"
#include "decoder/fdl_framing_rules.hpp"
#include "decoder/session_tracker.hpp"
#include "decoder/stream_framer.hpp"
#include "formats/output.hpp"
#include "formats/renderer.hpp"

namespace {

dpscope::Output& output() {
    static FILE* sink = std::fopen("/dev/null", "w");
    static dpscope::Output out{sink};
    return out;
}

struct RenderAll final : dpscope::StreamFramer::Sink {
    dpscope::BusDecoder decoder;
    dpscope::SessionTracker tracker;
    std::uint64_t frame = 0;
    std::int64_t time_ns = 1'000'000'000LL * 1700000000;
    std::vector<std::unique_ptr<dpscope::TelegramRenderer>> renderers;

    RenderAll() {
        for (auto format : {dpscope::OutputFormat::Text, dpscope::OutputFormat::Verbose,
                            dpscope::OutputFormat::Jsonl, dpscope::OutputFormat::Csv})
            renderers.push_back(dpscope::make_renderer(format, output()));
    }

    void decode(dpscope::Bytes telegram) {
        // The clock advances 1 ms a telegram, so that time-outs fire over a long input.
        time_ns += 1'000'000;
        const dpscope::DecodedTelegram& t = decoder.decode(telegram, time_ns, ++frame);
        std::span<const dpscope::Finding> findings = tracker.track(t);
        (void)tracker.completed();
        renderers[frame % renderers.size()]->render(t, findings);
        output().buffer().clear();
    }
    void on_telegram(dpscope::Bytes telegram, std::uint64_t) override { decode(telegram); }
    void on_skipped(const dpscope::SkippedBytes& skipped) override {
        (void)dpscope::fdl_framing_rules().describe_skip(skipped);
    }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    RenderAll all;
    dpscope::StreamFramer framer(dpscope::fdl_framing_rules());
    std::size_t chunk = size > 0 ? (data[0] % 17) + 1 : 1;
    for (std::size_t at = 0; at < size; at += chunk) {
        std::size_t n = std::min(chunk, size - at);
        framer.feed(dpscope::Bytes(data + at, n), all);
        if (n > 0 && data[at] == 0x00) framer.mark_gap(all);
    }
    framer.finish(all);
    all.decode(dpscope::Bytes(data, size));
    (void)all.tracker.finish();
    (void)all.tracker.channels();
    (void)all.tracker.transactions();
    return 0;
}
