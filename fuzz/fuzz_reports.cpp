// The whole-session reports: telegrams built from an event script
// (fuzz/support/telegram_script.hpp, as in fuzz_trackers) are decoded and tracked the way `dpscope
// report` and `dpscope stats` do it (cli/pipeline.hpp: the bus's decoder and tracker, a
// BusHealthTracker for PROFIBUS, the Summary, a FindingLog and, for HTML, the channel timelines),
// then either the conformance report (formats/report.hpp) is rendered in one input-chosen format
// (text, JSON, Markdown, HTML, JUnit XML: their PCV, DP-V1, FC, VLT 2000 and bus-health sections)
// with an input-chosen --fail-on, --allow-empty and --station filter, or, for PROFIBUS when the
// input says so, the bus-health statistics (protocols/profibus/health/stats_render.hpp) in one
// input-chosen StatsFormat and the live table at an input-chosen width. One output a run (not all
// of them) keeps each run fast; the corpus holds inputs for every one. JSON output must parse
// (fuzz/support/json_check.hpp); no output may hold a NUL.
//
// Input layout: byte 0 the report format (bits 0-2, mod 5), --fail-on (bits 3-4), --allow-empty
// (bit 5), a --station filter (bit 6: the station in byte 1's low bits), the statistics instead
// of the report (bit 7, PROFIBUS only); byte 1 the stats format (bits 5-7, mod 5), byte 2 the
// live table's width (0: the default, else 20 + byte); then the event script.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "formats/finding_log.hpp"
#include "formats/output.hpp"
#include "formats/report.hpp"
#include "formats/report_timeline.hpp"
#include "formats/summary.hpp"
#include "fuzz/support/fuzz_input.hpp"
#include "fuzz/support/json_check.hpp"
#include "fuzz/support/telegram_script.hpp"
#include "protocols/fc/fc_decoder.hpp"
#include "protocols/fc/fc_tracker.hpp"
#include "protocols/profibus/bus_decoder.hpp"
#include "protocols/profibus/health/bus_health.hpp"
#include "protocols/profibus/health/stats_render.hpp"
#include "protocols/profibus/session_tracker.hpp"
#include "protocols/vlt2000/vlt2000_decoder.hpp"
#include "protocols/vlt2000/vlt2000_tracker.hpp"

namespace {

using namespace dpscope;

constexpr std::size_t kMaxTelegrams = 12;
constexpr ReportFormat kReportFormats[] = {ReportFormat::Text, ReportFormat::Json,
                                           ReportFormat::Markdown, ReportFormat::Html,
                                           ReportFormat::Junit};
constexpr StatsFormat kStatsFormats[] = {StatsFormat::Text, StatsFormat::Json,
                                         StatsFormat::Markdown, StatsFormat::Html,
                                         StatsFormat::Csv};
constexpr FailOn kFailOns[] = {FailOn::Error, FailOn::Warning, FailOn::Never, FailOn::Error};

void check(bool ok) {
    if (!ok) __builtin_trap();
}

void check_and_clear(Output& out, bool json) {
    const std::string_view text(out.buffer().data(), out.buffer().size());
    check(!text.empty());
    check(text.find('\0') == std::string_view::npos);
    if (json) check(fuzz::is_json(text));
    out.buffer().clear();
}

struct Choices {
    ReportFormat report = ReportFormat::Text;
    FailOn fail_on = FailOn::Error;
    bool allow_empty = false;
    std::optional<std::uint8_t> station;
    StatsFormat stats = StatsFormat::Text;
    unsigned width = 0;
    // PROFIBUS: the bus-health statistics and the live table instead of the report (one of the
    // two a run keeps a run as short as on the other buses).
    bool stats_instead = false;
};

// Decodes and tracks the script as the report command's Pipeline does, then renders.
template <class Decoder, class Tracker>
void run_lane(const fuzz::TelegramScript& script, const Choices& choices, Decoder& decoder,
              Tracker& tracker, ReportContext& context, BusHealthTracker* health) {
    Summary summary;
    FindingLog log;
    ChannelTimelines timelines;
    const bool keep_timelines = choices.report == ReportFormat::Html;
    for (const fuzz::ScriptedTelegram& s : script.telegrams) {
        const DecodedTelegram& t = decoder.decode(script.telegram_bytes(s), s.time_ns, s.frame);
        std::span<const Finding> findings = tracker.track(t);
        if (health) (void)health->observe(t);
        summary.add(t);
        summary.add_findings(findings);
        if (keep_timelines) timelines.add(findings, tracker.completed());
        if (!findings.empty()) log.append(findings);
    }
    std::span<const Finding> open_at_end = tracker.finish();
    if (health) health->finish();
    summary.add_findings(open_at_end);
    if (keep_timelines) timelines.add(open_at_end, {});
    log.append(open_at_end);

    Output& out = fuzz::null_output();
    out.buffer().clear();
    context.input = InputSummary{"fuzz.raw", "raw", script.telegrams.size() % 5,
                                 script.telegrams.size() % 7 == 3};
    context.summary = &summary;
    context.decoder = &decoder;
    context.tracker = &tracker;
    context.timelines = &timelines;
    context.health = health ? &health->health() : nullptr;
    context.findings = &log;
    context.fail_on = choices.fail_on;
    context.allow_empty = choices.allow_empty;
    if (choices.station) context.stations.push_back(*choices.station);
    context.version = "fuzz";
    if (!health || !choices.stats_instead) {
        const bool fails = render_report(choices.report, context, out);
        check(fails == report_fails(context));
        check_and_clear(out, choices.report == ReportFormat::Json);
    } else {
        render_stats(choices.stats, StatsContext{context.input, &health->health(), "fuzz"}, out);
        check_and_clear(out, choices.stats == StatsFormat::Json);
        render_live_table(health->health(), out, choices.width);
        check_and_clear(out, false);
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static fuzz::TelegramScript script;
    fuzz::FuzzInput in(data, size);
    Choices choices;
    const std::uint8_t report = in.byte();
    const std::uint8_t stats = in.byte();
    const std::uint8_t width = in.byte();
    choices.report = kReportFormats[(report & 7) % std::size(kReportFormats)];
    choices.fail_on = kFailOns[(report >> 3) & 3];
    choices.allow_empty = (report & 0x20) != 0;
    choices.stats_instead = (report & 0x80) != 0;
    if (report & 0x40) choices.station = static_cast<std::uint8_t>(stats & 0x1F);
    choices.stats = kStatsFormats[(stats >> 5) % std::size(kStatsFormats)];
    choices.width = width == 0 ? 0u : 20u + width;
    fuzz::build_telegram_script(in, script, kMaxTelegrams);

    // The script's bus is fed; the report reads that bus's decoder and tracker.
    ReportContext context;
    switch (script.bus) {
        case fuzz::ScriptBus::Profibus: {
            context.protocol = Protocol::ProfibusDp;
            BusHealthOptions options;
            options.baud = script.baud;
            BusHealthTracker health(options);
            BusDecoder decoder(script.decoder_options());
            SessionTracker tracker(script.tracker_options());
            run_lane(script, choices, decoder, tracker, context, &health);
            break;
        }
        case fuzz::ScriptBus::Fc: {
            context.protocol = Protocol::Fc;
            FcDecoder decoder(script.fc_decoder_options());
            FcTracker tracker(script.fc_tracker_options());
            run_lane(script, choices, decoder, tracker, context, nullptr);
            break;
        }
        case fuzz::ScriptBus::Vlt2000: {
            context.protocol = Protocol::Vlt2000;
            Vlt2000Decoder decoder(script.vlt2000_decoder_options());
            Vlt2000Tracker tracker(script.vlt2000_tracker_options());
            run_lane(script, choices, decoder, tracker, context, nullptr);
            break;
        }
    }
    return 0;
}
