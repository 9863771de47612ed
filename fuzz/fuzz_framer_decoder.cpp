// Feeds arbitrary bytes through the stream framer in chunks whose sizes the input chooses, decodes
// every telegram with one BusDecoder (so state carries over), renders each telegram in one of the
// output formats (taking turns, so every renderer sees every kind of telegram over a run) and also
// decodes the whole input as a single capture record.
#include <cstdint>
#include <cstdio>
#include <memory>
#include <vector>

#include "decoder/bus_decoder.hpp"
#include "decoder/fdl_framing_rules.hpp"
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
    std::uint64_t frame = 0;
    std::vector<std::unique_ptr<dpscope::TelegramRenderer>> renderers;

    RenderAll() {
        for (auto format : {dpscope::OutputFormat::Text, dpscope::OutputFormat::Verbose,
                            dpscope::OutputFormat::Jsonl, dpscope::OutputFormat::Csv})
            renderers.push_back(dpscope::make_renderer(format, output()));
    }

    void decode(dpscope::Bytes telegram) {
        const dpscope::DecodedTelegram& t =
            decoder.decode(telegram, 1'000'000'000LL * 1700000000, ++frame);
        renderers[frame % renderers.size()]->render(t, {});
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
    return 0;
}
