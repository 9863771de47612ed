// dpscope report: the protocol-conformance report of a capture.
#include <fmt/format.h>

#include <algorithm>
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
#include "formats/report.hpp"
#include "formats/report_model.hpp"

namespace dpscope::cli {

namespace {

struct ReportCommand {
    DecodeOptionValues options;
    HealthOptionValues health;
    std::string file;
    std::string read_option;
    std::string input_format = "auto";
    std::string format = "text";
    std::string output = "-";
    std::string fail_on = "error";
    std::vector<unsigned> stations;
    bool allow_empty = false;
};

// The addresses `--station` can name in the capture: the slaves of a PROFIBUS DP capture, the
// drive addresses of an FC or VLT 2000 one.
bool station_in_capture(const Pipeline& pipeline, unsigned station) {
    return station < kStationCount &&
           pipeline.tracker().has_station(static_cast<std::uint8_t>(station));
}

// Renders the report of what `pipeline` read from `source` and returns the exit code; sets
// `partial_why` when the report is whole but the run did not succeed.
int write_report(const ReportCommand& command, ReportFormat format, const Pipeline& pipeline,
                 const TelegramSource& source, const FindingLog& log, Output& out,
                 std::string& partial_why) {
    ReportContext context = report_context(
        pipeline, source, log, fail_on_from_name(command.fail_on).value_or(FailOn::Error));
    context.allow_empty = command.allow_empty;
    context.display_filter = command.options.display_filter;
    for (unsigned station : command.stations) {
        context.stations.push_back(static_cast<std::uint8_t>(station));
        if (!station_in_capture(pipeline, station)) {
            const std::string_view noun = report::bus_wording(pipeline.protocol()).station;
            print_warning(
                fmt::format("--station {}: no {} {} in the capture", station, noun, station));
        }
    }
    const bool fails = render_report(format, context, out);
    if (!out.flush()) {
        print_error(fmt::format("cannot write the report to {}: {}",
                                command.output == "-" ? "standard output" : command.output,
                                std::strerror(errno)));
        return kExitOutputError;
    }
    // A report that cannot list every finding (a full temporary folder) says so itself, and is
    // no success: its counts are exact, its list is not.
    if (const std::string lost = report::not_listed_text(context); !lost.empty()) {
        print_error(fmt::format("{}; the report says so", lost));
        partial_why = "the report could not list every finding";
        return kExitOutputError;
    }
    if (fails) return kExitFindings;
    if (source.status() == InputStatus::Damaged) return kExitDamagedInput;
    return kExitOk;
}

int run_report(const ReportCommand& command) {
    std::string path = !command.read_option.empty() ? command.read_option : command.file;
    if (path.empty()) {
        print_error("report: no input; give a FILE or -r FILE (- for standard input)");
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
    OpenResult opened = open_input(
        path, input_format_from_name(command.input_format).value_or(InputFormat::Auto), *settings);
    if (!opened) {
        print_error(opened.error());
        return kExitUsage;
    }
    if (Result<void> distinct = check_not_an_input({path}, command.output, "-w"); !distinct) {
        print_error(distinct.error());
        return kExitUsage;
    }
    TelegramSource& source = *opened.value();
    // The bus-health section of a PROFIBUS capture (the Pipeline keeps no tracker for another).
    settings->track_health = settings->protocol->has_bus_health;
    settings->health.thresholds = *thresholds;
    // settings->health.baud: --baud, else the line the capture records, else 0 (the bus load
    // is unknown); set by resolve_decode_options and open_input.
    // Written beside OUT and moved into place only once the report is complete: an unusable
    // input or a write error leaves an existing OUT as it was.
    return write_staged_output(command.output, path, [&](Output& out, std::string& partial_why) {
        Output diagnostics(stderr);
        report_input_issues(source, diagnostics);
        const ReportFormat format =
            report_format_from_name(command.format).value_or(ReportFormat::Text);
        Pipeline pipeline(*settings, PipelineParts{.timelines = format == ReportFormat::Html,
                                                   .health_events = settings->filtering()});
        FindingLog log;
        Record record;
        std::uint64_t read = 0;
        std::span<const Finding> findings;
        source.stop_after(settings->count);
        {
            ProgressMeter progress = ProgressMeter::for_source(source);
            while (source.next(record)) {
                ++read;
                const DecodedTelegram& t = pipeline.feed(record, findings);
                // -Y: every telegram is tracked; the report lists the findings of those the
                // filter selects (and, as decode shows them, those open at the end).
                if (!findings.empty() && selected_by_filter(*settings, pipeline, t, findings))
                    log.append(findings);
                progress.tick(source);
            }
        }
        log.append(pipeline.finish());
        warn_ppo_overrides(pipeline.decoder());
        if (Result<void> found =
                check_telegrams_found(source, read, *settings->protocol, settings->bus_given);
            !found) {
            print_error(found.error());
            return kExitUsage;
        }
        return write_report(command, format, pipeline, source, log, out, partial_why);
    });
}

}  // namespace

void add_report_command(CLI::App& app, int& exit_code) {
    auto command = std::make_shared<ReportCommand>();
    CLI::App* sub = app.add_subcommand(
        "report",
        "Protocol-conformance report of a capture: pairs every parameter request with its "
        "response and lists, per slave, transactions, latency, parameters, rejections and "
        "handshake findings; exit code 1 when a finding reaches --fail-on, or when nothing was "
        "checked (no Data_Exchange telegram with a parameter channel; FC: no command to a drive; "
        "VLT 2000: no command answered) without --allow-empty.");
    sub->add_option("file", command->file, "Capture file to read; - reads standard input")
        ->type_name("FILE");
    sub->add_option("-r,--read", command->read_option,
                    "Capture file to read (as tshark -r); - reads standard input")
        ->type_name("FILE");
    sub->add_option("--input-format", command->input_format,
                    "Input kind: auto (detect from the content), pcap, pcapng, raw, hex, text (a "
                    "log of VLT 2000 telegrams '<...>')")
        ->check(CLI::IsMember({"auto", "pcap", "pcapng", "raw", "hex", "text"}))
        ->default_str("auto");
    sub->add_option("-T,--format", command->format,
                    "Report format: text, json (stable schema, docs/formats.md), markdown, html (one "
                    "self-contained page with SVG charts), junit (JUnit XML for CI servers)")
        ->check(CLI::IsMember({"text", "json", "markdown", "html", "junit"}))
        ->default_str("text");
    sub->add_option("-w,--write", command->output,
                    "Write the report to FILE; - is standard output. FILE is written (an existing "
                    "one replaced) only by a run that exits 0 or 1; a damaged input (exit code 3) "
                    "writes the report to FILE.partial and leaves FILE as it was; an unusable "
                    "input or a write error writes nothing; never when FILE is the input")
        ->check(output_file_name())
        ->type_name("FILE")
        ->default_str("-");
    sub->add_option("--fail-on", command->fail_on,
                    "Exit code 1 when a finding of this severity or above is in the report: "
                    "error, warning, or never")
        ->check(CLI::IsMember({"error", "warning", "never"}))
        ->default_str("error");
    sub->add_option("--station", command->stations,
                    "Report only slave ADDR (repeatable; of an FC or VLT 2000 capture the drive "
                    "address ADDR); telegrams of other stations are still decoded")
        ->check(whole_number(0, 127))
        ->type_name("ADDR")
        ->allow_extra_args(false);
    sub->add_flag("--allow-empty", command->allow_empty,
                  "Pass a capture in which nothing was checked (no telegrams, or no Data_Exchange "
                  "telegram with a parameter channel from the slaves reported; FC: no command to a "
                  "drive; VLT 2000: no command a drive answered); by default the "
                  "report says \"nothing checked\" and exits 1");
    add_display_filter_option(*sub, command->options,
                              "List only the findings of telegrams the filter EXPR selects "
                              "(docs/filter.md), and judge --fail-on by them; every telegram is "
                              "still decoded and tracked (a request and its answer are paired "
                              "whatever the filter says), the sections' figures are the whole "
                              "capture's, and findings open at the end are listed");
    add_tracking_options(*sub, command->options);
    add_line_options(*sub, command->options);
    add_health_options(*sub, command->health);
    sub->footer(std::string(kExitCodeHelp) + " For report, 1 takes precedence over 3.");
    sub->callback([command, &exit_code] { exit_code = run_report(*command); });
}

}  // namespace dpscope::cli
