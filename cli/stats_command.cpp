// dpscope stats: the bus-health statistics of a PROFIBUS capture (docs/bus-health.md).
#include <fmt/format.h>

#include <bitset>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

#include "capture/output_file.hpp"
#include "capture/telegram_source.hpp"
#include "cli/commands.hpp"
#include "cli/common_options.hpp"
#include "cli/pipeline.hpp"
#include "cli/progress.hpp"
#include "cli/version.hpp"
#include "filter/display_filter.hpp"
#include "protocols/profibus/health/stats_render.hpp"

namespace dpscope::cli {

namespace {

struct StatsCommand {
    DecodeOptionValues options;
    HealthOptionValues health;
    std::string file;
    std::string read_option;
    std::string input_format = "auto";
    std::string format = "text";
    std::string output = "-";
    std::string fail_on = "bad";
    bool allow_empty = false;
};

// Renders the statistics and returns the exit code.
int write_stats(const StatsCommand& command, const Pipeline& pipeline, const TelegramSource& source,
                const std::bitset<kStationCount>* selected, Output& out) {
    const BusHealth& all = pipeline.health()->health();
    // -Y: the stations and masters the selected telegrams are to or from; the segment and its
    // verdict stay the whole capture's.
    BusHealth shown;
    if (selected) {
        shown = all;
        std::erase_if(shown.stations,
                      [&](const StationHealth& s) { return !selected->test(s.address); });
        std::erase_if(shown.masters,
                      [&](const MasterHealth& m) { return !selected->test(m.address); });
    }
    const BusHealth& health = selected ? shown : all;
    InputSummary input = describe_input(source);
    if (selected) input.name += ", stations of the telegrams the -Y filter selects";
    const StatsFormat format = stats_format_from_name(command.format).value_or(StatsFormat::Text);
    render_stats(format, StatsContext{input, &health, kVersion}, out);
    if (!out.flush()) {
        print_error(fmt::format("cannot write the statistics to {}: {}",
                                command.output == "-" ? "standard output" : command.output,
                                std::strerror(errno)));
        return kExitOutputError;
    }
    const HealthFailOn fail_on =
        health_fail_on_from_name(command.fail_on).value_or(HealthFailOn::Bad);
    if (verdict_fails(health.segment.judgement.verdict, fail_on)) return kExitFindings;
    if (source.status() == InputStatus::Damaged) return kExitDamagedInput;
    if (!health.segment.judged()) return empty_input_exit(source, command.allow_empty);
    return kExitOk;
}

int run_stats(const StatsCommand& command) {
    const std::string path = !command.read_option.empty() ? command.read_option : command.file;
    if (path.empty()) {
        print_error("stats: no input; give a FILE or -r FILE (- for standard input)");
        return kExitUsage;
    }
    Result<DecodeSettings> settings = resolve_decode_options(command.options, "text");
    if (!settings) {
        print_error(settings.error());
        return kExitUsage;
    }
    Result<HealthThresholds> thresholds = resolve_health_options(command.health);
    if (!thresholds) {
        print_error(thresholds.error());
        return kExitUsage;
    }
    settings->track_health = true;
    settings->health.thresholds = *thresholds;
    // settings->health.baud: --baud, else the line the capture records, else 0 (the bus load
    // is unknown); set by resolve_decode_options and open_input.
    if (Result<void> distinct = check_not_an_input({path}, command.output, "-w"); !distinct) {
        print_error(distinct.error());
        return kExitUsage;
    }
    OpenResult opened = open_input(
        path, input_format_from_name(command.input_format).value_or(InputFormat::Auto), *settings);
    if (!opened) {
        print_error(opened.error());
        return kExitUsage;
    }
    TelegramSource& source = *opened.value();
    if (!settings->protocol->has_bus_health) {
        print_error(fmt::format(
            "{}: {} capture; bus health (stats) is PROFIBUS-only: it judges the FDL/DP link "
            "layer (token, polls, retries, live list); dpscope report gives the figures of each "
            "drive",
            source.name(), settings->protocol->capture_noun));
        return kExitUsage;
    }
    // Written beside OUT and moved into place only once the statistics are complete: an unusable
    // input or a write error leaves an existing OUT as it was.
    return write_staged_output(command.output, path, [&](Output& out, std::string&) {
        Output diagnostics(stderr);
        report_input_issues(source, diagnostics);
        // The parameter channel's findings are not shown: only a -Y filter reads them.
        Pipeline pipeline(*settings, PipelineParts{.parameter_findings = settings->filtering(),
                                                   .health_events = settings->filtering()});
        Record record;
        std::uint64_t read = 0;
        std::span<const Finding> findings;
        std::bitset<kStationCount> selected;  // -Y: the stations of the selected telegrams
        source.stop_after(settings->count);
        {
            ProgressMeter progress = ProgressMeter::for_source(source);
            while (source.next(record)) {
                ++read;
                const DecodedTelegram& t = pipeline.feed(record, findings);
                if (settings->filtering() && selected_by_filter(*settings, pipeline, t, findings))
                    mark_telegram_stations(FilterInput{t}, selected);
                progress.tick(source);
            }
        }
        pipeline.finish();
        warn_ppo_overrides(pipeline.decoder());
        if (Result<void> found =
                check_telegrams_found(source, read, *settings->protocol, settings->bus_given);
            !found) {
            print_error(found.error());
            return kExitUsage;
        }
        return write_stats(command, pipeline, source, settings->filtering() ? &selected : nullptr,
                           out);
    });
}

}  // namespace

void add_stats_command(CLI::App& app, int& exit_code) {
    auto command = std::make_shared<StatsCommand>();
    CLI::App* sub = app.add_subcommand(
        "stats",
        "Bus-health statistics of a PROFIBUS DP capture (docs/bus-health.md): the live list of "
        "stations with their role and state over time, per slave requests, answers, no answers, "
        "FDL retries, lost and returned, illegal and negative answers, diagnosis faults, damaged "
        "telegrams and resyncs; per master the token rotation and poll cycle (min / mean / p95 / "
        "max, jitter); telegrams per second and, with --baud, the bus load; a verdict (good, "
        "weak, bad) for each station and the segment from documented thresholds. PROFIBUS only; "
        "exit code 1 when the segment's verdict reaches --fail-on.");
    sub->add_option("file", command->file, "Capture file to read; - reads standard input")
        ->type_name("FILE");
    sub->add_option("-r,--read", command->read_option,
                    "Capture file to read (as tshark -r); - reads standard input")
        ->type_name("FILE");
    sub->add_option("--input-format", command->input_format,
                    "Input kind: auto (detect from the content), pcap, pcapng, raw, hex")
        ->check(CLI::IsMember({"auto", "pcap", "pcapng", "raw", "hex"}))
        ->default_str("auto");
    sub->add_option("-T,--format", command->format,
                    "Output format: text, json (stable schema, docs/formats.md), markdown, html (one "
                    "self-contained page with an SVG timeline of each station's state and plots "
                    "of cycle time and token rotation), csv (one row per station and master)")
        ->check(CLI::IsMember({"text", "json", "markdown", "html", "csv"}))
        ->default_str("text");
    sub->add_option("-w,--write", command->output,
                    "Write the statistics to FILE; - is standard output. FILE is written (an "
                    "existing one replaced) only by a run that exits 0 or 1; a damaged input (exit "
                    "code 3) writes them to FILE.partial and leaves FILE as it was; an unusable "
                    "input or a write error writes nothing; never when FILE is the input")
        ->check(output_file_name())
        ->type_name("FILE")
        ->default_str("-");
    sub->add_option("--fail-on", command->fail_on,
                    "Exit code 1 when the segment's verdict is this or worse: bad, weak, or never")
        ->check(CLI::IsMember({"bad", "weak", "never"}))
        ->default_str("bad");
    sub->add_option("--baud", command->options.baud,
                    "The line's baud rate when the capture was made (PROFIBUS: 9600 to 12000000, "
                    "e.g. 1500000): the bus load and idle time need it; without it they are "
                    "unknown. Default: the line the capture records (sniff -w); a --baud given "
                    "wins, with a warning when they differ")
        ->check(whole_number(9600, 12'000'000, " baud"))
        ->type_name("BAUD");
    add_allow_empty_option(*sub, command->allow_empty);
    add_health_options(*sub, command->health);
    add_display_filter_option(*sub, command->options,
                              "List only the stations and masters that telegrams the filter EXPR "
                              "selects are to or from (docs/filter.md); every telegram still "
                              "counts in their figures, and the segment's line and verdict (and "
                              "--fail-on) are the whole capture's.");
    sub->add_option("-c,--count", command->options.count, "Stop after reading N telegrams")
        ->check(whole_number(1, kMaxCount, " telegrams"))
        ->type_name("N");
    sub->add_option("--bus", command->options.bus,
                    "The bus the capture carries; stats reads profibus only (the default for a "
                    "pcap of link type 257; a raw or hex byte stream is tried with each bus's "
                    "framing)")
        ->check(CLI::IsMember(bus_names()))
        ->type_name("BUS");
    sub->add_option("--ppo", command->options.ppo,
                    "ADDR=TYPE: decode slave ADDR (0 to 126) as PPO TYPE (1 to 5) instead of "
                    "inferring the type from Chk_Cfg, Get_Cfg or the Data_Exchange length; "
                    "repeatable")
        ->type_name("ADDR=TYPE")
        ->allow_extra_args(false);
    sub->footer(std::string(kExitCodeHelp) +
                " For stats, 1 means the segment's verdict reached --fail-on (bad by default), "
                "and takes precedence over 3.");
    sub->callback([command, &exit_code] { exit_code = run_stats(*command); });
}

}  // namespace dpscope::cli
