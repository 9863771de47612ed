// The per-telegram renderers: telegrams built from an event script
// (fuzz/support/telegram_script.hpp, the same as fuzz_trackers': the bus, stations, codes, PNUs,
// values and time steps come from the input) are decoded by the bus's real decoder and tracked by
// its tracker, and every telegram with the findings at it is rendered by one of the per-telegram
// renderers (formats/renderer.hpp: text, verbose, jsonl, csv) in turn, the others passing over it
// (a filtered-out telegram): all four on every telegram cost about 1 ms a run, most of it in fmt;
// in turn, every renderer still sees every kind of telegram over a fuzzing run. The findings open
// at the end go to every renderer, and the decode summary (formats/summary.hpp) is rendered last.
// The output goes into a buffer that is checked and cleared after each telegram: the jsonl
// renderer must write one line a telegram that parses as JSON, and nothing may write a NUL byte.
// Whole-session reports and stats have their own target (fuzz_reports): together they were too
// slow.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string_view>
#include <type_traits>

#include "formats/output.hpp"
#include "formats/renderer.hpp"
#include "formats/summary.hpp"
#include "fuzz/support/fuzz_input.hpp"
#include "fuzz/support/json_check.hpp"
#include "fuzz/support/telegram_script.hpp"
#include "protocols/fc/fc_decoder.hpp"
#include "protocols/fc/fc_tracker.hpp"
#include "protocols/profibus/bus_decoder.hpp"
#include "protocols/profibus/session_tracker.hpp"
#include "protocols/vlt2000/vlt2000_decoder.hpp"
#include "protocols/vlt2000/vlt2000_tracker.hpp"

namespace {

using namespace dpscope;

constexpr std::size_t kMaxTelegrams = 6;
constexpr OutputFormat kFormats[] = {OutputFormat::Text, OutputFormat::Verbose, OutputFormat::Jsonl,
                                     OutputFormat::Csv};

void check(bool ok) {
    if (!ok) __builtin_trap();
}

// What a renderer wrote: no NUL byte; a jsonl record is one line ending in a newline.
void check_and_clear(Output& out, OutputFormat format, bool rendered) {
    const std::string_view text(out.buffer().data(), out.buffer().size());
    check(text.find('\0') == std::string_view::npos);
    if (format == OutputFormat::Jsonl && rendered) {
        check(!text.empty() && text.back() == '\n' && text.front() == '{');
        check(text.find('\n') == text.size() - 1);
        check(fuzz::is_json(text));
    }
    out.buffer().clear();
}

template <class Decoder, class Tracker>
void run_lane(const fuzz::TelegramScript& script, Decoder& decoder, Tracker& tracker) {
    Output& out = fuzz::null_output();
    out.buffer().clear();
    Summary summary;
    std::unique_ptr<TelegramRenderer> renderers[std::size(kFormats)];
    for (std::size_t i = 0; i < std::size(kFormats); ++i) {
        renderers[i] = make_renderer(kFormats[i], out);
        renderers[i]->begin();
        out.buffer().clear();
    }
    for (const fuzz::ScriptedTelegram& s : script.telegrams) {
        const DecodedTelegram& t = decoder.decode(script.telegram_bytes(s), s.time_ns, s.frame);
        std::span<const Finding> findings = tracker.track(t);
        summary.add(t);
        summary.add_findings(findings);
        // The renderers take turns (the script's line-rate byte sets where the turn starts), so
        // that every run stays fast; over a run of the fuzzer each renders every kind of
        // telegram. The others pass over it, as `decode` does with one it filters out.
        const std::size_t shown = (s.frame + script.turn) % std::size(kFormats);
        for (std::size_t i = 0; i < std::size(kFormats); ++i) {
            if (i == shown)
                renderers[i]->render(t, findings);
            else
                renderers[i]->pass_over(t);
            check_and_clear(out, kFormats[i], i == shown);
        }
    }
    std::span<const Finding> open_at_end = tracker.finish();
    summary.add_findings(open_at_end);
    for (std::size_t i = 0; i < std::size(kFormats); ++i) {
        renderers[i]->render_end_findings(open_at_end);
        renderers[i]->end();
        check_and_clear(out, kFormats[i], false);
    }
    // The summary names the PROFIBUS decoder's configuration (a default one for another bus).
    static const BusDecoder no_decoder;
    const BusDecoder* dp_decoder = &no_decoder;
    if constexpr (std::is_same_v<Decoder, BusDecoder>) dp_decoder = &decoder;
    summary.render_text(
        out, InputSummary{"fuzz", "raw", script.telegrams.size() % 3, script.strict}, *dp_decoder);
    check_and_clear(out, OutputFormat::Text, false);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static fuzz::TelegramScript script;
    fuzz::FuzzInput in(data, size);
    fuzz::build_telegram_script(in, script, kMaxTelegrams);
    fuzz::with_script_bus(script,
                          [&](auto& decoder, auto& tracker) { run_lane(script, decoder, tracker); });
    return 0;
}
