// dpscope sniff: its command line (the options and their help) and the checks of what the options
// say together, before anything is opened.
#include <fmt/format.h>

#include <cctype>
#include <cstdint>
#include <string>

#include "capture/capture_writer.hpp"
#include "capture/output_file.hpp"
#include "cli/commands.hpp"
#include "cli/common_options.hpp"
#include "cli/sniff_command.hpp"

namespace dpscope::cli {

namespace {

// Accepted ranges of the numeric options (named in their error messages).
constexpr double kMaxSeconds = 315'360'000;           // ten years
constexpr std::uint64_t kMinRotateSize = 512;         // the pcap header and the longest record fit
constexpr std::uint64_t kMaxRotateSize = 1ULL << 44;  // 16T
constexpr std::uint32_t kMaxIdleGapMs = 60'000;

// A size: a whole number of bytes with an optional unit k, M, G, T (powers of 1024, as
// CLI::AsSizeValue reads them, also written kb, KiB, ...), from kMinRotateSize to kMaxRotateSize.
CLI::Validator rotate_size_range() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            std::size_t digits = 0;
            while (digits < text.size() && text[digits] >= '0' && text[digits] <= '9')
                ++digits;
            std::uint64_t number = 0;
            bool ok = parse_whole_number(std::string_view(text).substr(0, digits), number);
            std::string unit;
            for (char c : text.substr(digits))
                unit += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
            if (!unit.empty() && unit != "b" && unit.back() == 'b') unit.pop_back();
            if (unit.size() == 2 && unit[1] == 'i') unit.pop_back();
            int shift = unit.empty() || unit == "b" ? 0
                        : unit == "k"               ? 10
                        : unit == "m"               ? 20
                        : unit == "g"               ? 30
                        : unit == "t"               ? 40
                                                    : -1;
            if (!ok || shift < 0 || number > (kMaxRotateSize >> shift) ||
                (number << shift) < kMinRotateSize)
                return fmt::format(
                    "must be a size from {} bytes to 16T (a whole number of bytes, or with k, M, "
                    "G or T), not {}",
                    kMinRotateSize, text);
            return {};
        },
        "512 to 16T", "size");
}

// Is `path` one of the files -w `output` writes (stem-NNNNN.ext when rotating)? Also through a
// link, to a file that does not exist yet.
bool is_capture_file(const std::string& given, const std::string& output, bool rotating) {
    if (!rotating) return same_file(given, output);
    const std::string path = link_target(given);
    // The index in stem-NNNNN.ext: the digits after the last '-' of the name.
    std::size_t slash = path.rfind('/');
    std::size_t dash = path.rfind('-');
    if (dash == std::string::npos || (slash != std::string::npos && dash < slash)) return false;
    std::size_t digits = dash + 1;
    while (digits < path.size() && path[digits] >= '0' && path[digits] <= '9')
        ++digits;
    std::uint64_t index = 0;
    if (!parse_whole_number(std::string_view(path).substr(dash + 1, digits - dash - 1), index) ||
        index == 0 || index > 0xFFFF'FFFFu)
        return false;
    return same_file(path, rotated_file_name(output, static_cast<unsigned>(index)));
}

// Checks --stats, --stats-file, --stats-format and --alarm against the bus, each other, -w and
// the report.
Result<void> check_stats_options(const SniffCommand& command, const ProtocolDescriptor& protocol) {
    const std::string& file = command.stats_file;
    const bool stats = command.stats || !file.empty();
    if ((stats || !command.alarm.empty()) && !protocol.has_bus_health)
        return Error{fmt::format(
            "{}: bus health is PROFIBUS statistics (FDL/DP link layer); the {} bus has none",
            stats ? "--stats" : "--alarm", protocol.traffic_name)};
    if (command.stats_format != "text" && file.empty())
        return Error{fmt::format(
            "--stats-format {}: the statistics would be mixed into the live output on standard "
            "output; give --stats-file FILE (- for standard output, the live output then goes to "
            "standard error)",
            command.stats_format)};
    if (file == "-" && command.output == "-")
        return Error{
            "--stats-file -: standard output already carries the pcap of -w -; give the "
            "statistics a file name"};
    if (file == "-" && command.report_file == "-")
        return Error{
            "--stats-file -: standard output already carries the report of --report-file -; "
            "give one of them a file name"};
    if (!file.empty() && file != "-" && !command.report_file.empty() &&
        command.report_file != "-" && same_file(file, command.report_file))
        return Error{
            fmt::format("--stats-file {}: it is the report file too; give another name", file)};
    if (!file.empty() && file != "-" && !command.output.empty() && command.output != "-" &&
        is_capture_file(file, command.output,
                        command.rotate_size > 0 || command.rotate_seconds > 0))
        return Error{
            fmt::format("--stats-file {}: it is the capture file of -w {}; give another name", file,
                        command.output)};
    return {};
}

// Checks --report, --report-format and --report-file against each other and -w.
Result<void> check_report_options(const SniffCommand& command) {
    const std::string& file = command.report_file;
    if (command.report_format != "text" && file.empty())
        return Error{fmt::format(
            "--report-format {}: the report would be mixed into the live output on standard "
            "output; give --report-file FILE (- for standard output, the live output then goes "
            "to standard error)",
            command.report_format)};
    if (file == "-" && command.output == "-")
        return Error{
            "--report-file -: standard output already carries the pcap of -w -; give the "
            "report a file name"};
    if (!file.empty() && file != "-" && !command.output.empty() && command.output != "-" &&
        is_capture_file(file, command.output,
                        command.rotate_size > 0 || command.rotate_seconds > 0))
        return Error{
            fmt::format("--report-file {}: it is the capture file of -w {}; give another name",
                        file, command.output)};
    return {};
}

}  // namespace

Result<void> check_sniff_usage(const SniffCommand& command, const ProtocolDescriptor& bus) {
    const bool pcap_to_stdout = command.output == "-";
    if (pcap_to_stdout && (command.rotate_size > 0 || command.rotate_seconds > 0)) {
        return Error{"-w -: cannot rotate standard output; give a file name to rotate"};
    }
    if (!command.status_file.empty() &&
        (command.status_file == command.output || command.status_file == command.report_file ||
         command.status_file == "-")) {
        return Error{
            fmt::format("--status-file {}: give a file of its own (not -, -w or "
                        "--report-file)",
                        command.status_file)};
    }
    // The ring keeps rotated files: it needs a rotation to have files to keep.
    if ((command.ring > 0 || command.max_disk > 0) && !command.output.empty() &&
        command.rotate_size == 0 && command.rotate_seconds == 0) {
        return Error{fmt::format(
            "{} keeps the files of a rotation: give --rotate-size or --rotate-seconds too",
            command.ring > 0 ? "--ring" : "--max-disk")};
    }
    if (command.max_disk > 0 && command.rotate_size > 0 &&
        command.max_disk < 2 * command.rotate_size) {
        return Error{
            fmt::format("--max-disk {} is less than two files of --rotate-size {}: the "
                        "ring could keep no complete file",
                        command.max_disk, command.rotate_size)};
    }
    if (Result<void> usage = check_report_options(command); !usage) return usage;
    if (Result<void> usage = check_stats_options(command, bus); !usage) return usage;
    // Options about the -w file mean nothing without one.
    if (command.output.empty()) {
        const char* unused = command.rotate_size > 0      ? "--rotate-size"
                             : command.rotate_seconds > 0 ? "--rotate-seconds"
                             : command.ring > 0           ? "--ring"
                             : command.max_disk > 0       ? "--max-disk"
                             : !command.link_type.empty() ? "--linktype"
                                                          : nullptr;
        if (unused) {
            return Error{
                fmt::format("{} is about the capture file of -w FILE, which is not given", unused)};
        }
    }
    // Written onto the port, the capture or the report would go out onto the bus.
    for (const auto& [option, path] :
         {std::pair<const char*, const std::string&>{"-w", command.output},
          std::pair<const char*, const std::string&>{"--report-file", command.report_file},
          std::pair<const char*, const std::string&>{"--stats-file", command.stats_file}}) {
        if (!path.empty() && path != "-" && same_file(path, command.device)) {
            return Error{
                fmt::format("{} {}: that is the capture device -i {}; writing to it would "
                            "send the bytes onto the bus",
                            option, path, command.device)};
        }
    }
    if (const std::string alone = mqtt_option_without_url(command.mqtt); !alone.empty())
        return Error{
            fmt::format("{} is about the MQTT broker of --mqtt URL, which is not given", alone)};
    return {};
}

void add_sniff_command(CLI::App& app, int& exit_code) {
    auto command = std::make_shared<SniffCommand>();
    CLI::App* sub = app.add_subcommand(
        "sniff",
        "Capture live from an RS-485 bus tap (a serial adapter, 8 data bits, even parity, 1 stop "
        "bit unless --parity and --stop-bits say otherwise, any baud rate the driver accepts; "
        "--bus fc for the Danfoss FC protocol, default 9600 baud; --bus vlt2000 for the VLT 2000 "
        "ASCII telegram on its RS-232 or RS-485 line, default 9600 baud 8N1; without --bus, "
        "PROFIBUS), "
        "decode and track as telegrams arrive, optionally "
        "write pcap. Stops on -c, --duration, Ctrl-C (SIGINT), SIGTERM or SIGHUP (see --sighup) "
        "with the capture file complete. The port is taken exclusively (lock file "
        "/run/lock/LCK..NAME, "
        "flock, TIOCEXCL) and its settings are put back as they were found when sniff ends.");
    sub->add_option("-i,--interface", command->device, "Serial device, e.g. /dev/ttyUSB0")
        ->required()
        ->type_name("DEVICE");
    sub->add_option("--baud", command->baud,
                    "Bus baud rate (PROFIBUS: 9600, 19200, 45450, 93750, 187500, 500000, 1500000, "
                    "3000000, 6000000, 12000000 or any rate the driver takes, required; FC "
                    "protocol: 2400 to 115200, default 9600; VLT 2000: default 9600, as the "
                    "drive's parameter 501 sets it; read back and checked)")
        ->check(whole_number(300, 16'000'000, " baud"));
    sub->add_option("--parity", command->parity,
                    "Parity bit of each character: even (PROFIBUS and the FC protocol's default, "
                    "8E1), odd or none (the VLT 2000's default, 8N1); set it as the drive's "
                    "parameter 8-33 (FC port parity) says")
        ->check(CLI::IsMember({"even", "odd", "none"}))
        ->type_name("PARITY")
        ->default_str("by --bus");
    sub->add_option("--stop-bits", command->stop_bits,
                    "Stop bits of each character: 1 (the default) or 2 (as FC drives set for "
                    "no parity, 8N2)")
        ->check(CLI::IsMember({1u, 2u}))
        ->type_name("N")
        ->default_str("1");
    sub->add_option("-w,--write", command->output,
                    "Write the telegrams to FILE as pcap, flushed at least every 100 ms; - writes "
                    "pcap to standard output (the decoded output then goes to standard error). The "
                    "capture records the line (baud rate, parity, stop bits), which decode, report "
                    "and stats then use without --baud")
        ->check(output_file_name())
        ->type_name("FILE");
    sub->add_option("--linktype", command->link_type,
                    "pcap link type: profibus (257, PROFIBUS_DL; PROFIBUS only, its default) or "
                    "user0 (147) for tools that cannot open 257 (the FC protocol's and the VLT "
                    "2000's default); a "
                    "USER0 capture records its bus for decode")
        ->check(CLI::IsMember({"profibus", "user0"}))
        ->default_str("by --bus");
    sub->add_option("--rotate-size", command->rotate_size,
                    "Start a new file before one would exceed SIZE (e.g. 100M); files are named "
                    "stem-00001.pcap, stem-00002.pcap, ...; no telegram is split or lost")
        ->transform(CLI::AsSizeValue(false))
        ->transform(rotate_size_range())  // transforms run last-added first: before AsSizeValue
        ->type_name("SIZE");
    sub->add_option("--rotate-seconds", command->rotate_seconds,
                    "Start a new file once the current one holds SECONDS of capture")
        ->check(finite_number(0.001, kMaxSeconds, " seconds"))
        ->type_name("SECONDS");
    sub->add_option("--status-interval", command->status_interval,
                    "Every SECONDS (0.1 to 86400), a status line on standard error for "
                    "monitoring: telegrams, their rate since the last line, bytes skipped, parity "
                    "errors, bytes on disk (-w, the ring's files) and the last event (a health "
                    "event or finding, with its frame); once more at the end")
        ->check(finite_number(0.1, 86400, " seconds"))
        ->type_name("SECONDS");
    sub->add_option("--status-file", command->status_file,
                    "Write the status line to FILE as well, replaced whole each time (written "
                    "beside it and renamed), for a monitoring agent; every --status-interval "
                    "seconds (default 10) and at the end")
        ->type_name("FILE");
    sub->add_option("--ring", command->ring,
                    "With --rotate-size or --rotate-seconds: keep only the last N files (2 to "
                    "100000), the current one included, as dumpcap -b files:N; the oldest is "
                    "removed only once the file after it is complete. At the end, what the ring "
                    "removed is counted on standard error")
        ->check(whole_number(2, 100000))
        ->type_name("N");
    sub->add_option("--max-disk", command->max_disk,
                    "With --rotate-size or --rotate-seconds: keep at most SIZE bytes in the files "
                    "(e.g. 10G), removing the oldest complete files, never the current one; at "
                    "least two files of --rotate-size")
        ->transform(CLI::AsSizeValue(false))
        ->transform(rotate_size_range())
        ->type_name("SIZE");
    sub->add_option("--duration", command->duration, "Stop after SECONDS")
        ->check(finite_number(0.001, kMaxSeconds, " seconds"))
        ->type_name("SECONDS");
    sub->add_flag("--report", command->report,
                  "At the end, print the conformance report of the capture (after the live "
                  "output, on standard output; see --report-file)");
    sub->add_option("--report-file", command->report_file,
                    "Write the report to FILE instead (implies --report); - puts it alone on "
                    "standard output and moves the live output to standard error (not with -w "
                    "-). Not the -w file")
        ->check(output_file_name())
        ->type_name("FILE");
    sub->add_option("--report-format", command->report_format,
                    "Format of the report: text, json, markdown, html, junit; all but text need "
                    "--report-file")
        ->check(CLI::IsMember({"text", "json", "markdown", "html", "junit"}))
        ->default_str("text");
    sub->add_option("--fail-on", command->fail_on,
                    "With --report: exit code 1 when a finding of this severity or above was "
                    "found: error, warning, never")
        ->check(CLI::IsMember({"error", "warning", "never"}))
        ->default_str("error");
    sub->add_flag("--allow-empty", command->allow_empty,
                  "With --report: a capture in which nothing could be checked (no Data_Exchange "
                  "telegram with a parameter channel) passes instead of exiting 1");
    sub->add_option("--idle-gap-ms", command->idle_gap_ms,
                    "Line idle time that ends an incomplete telegram (0: do not use idle time). "
                    "Keep it above a USB adapter's latency timer")
        ->check(whole_number(0, kMaxIdleGapMs, " ms"))
        ->default_str("50");
    sub->add_flag("--stats", command->stats,
                  "Bus health (PROFIBUS): on a terminal, a live table of the stations (role, "
                  "state, requests, answers, repeats, lost, illegal, damaged, verdict) redrawn "
                  "at most 4 times a second instead of a line per telegram; otherwise a line "
                  "per event (station lost, returned, verdict turned bad) beside the decode. At "
                  "the end the statistics, as `dpscope stats` gives them (see --stats-file)");
    sub->add_option("--stats-file", command->stats_file,
                    "Write the statistics at the end to FILE instead (implies --stats); - puts "
                    "them alone on standard output and moves the live output to standard error "
                    "(not with -w - or --report-file -). Not the -w file")
        ->check(output_file_name())
        ->type_name("FILE");
    sub->add_option("--stats-format", command->stats_format,
                    "Format of the statistics: text, json, markdown, html, csv; all but text "
                    "need --stats-file")
        ->check(CLI::IsMember({"text", "json", "markdown", "html", "csv"}))
        ->default_str("text");
    sub->add_option("--alarm", command->alarm,
                    "Run CMD (through /bin/sh -c) when a station is lost or a verdict turns bad "
                    "(PROFIBUS), with DPSCOPE_EVENT (station_lost, verdict_bad), DPSCOPE_STATION "
                    "(address or segment), DPSCOPE_ROLE, DPSCOPE_TIME (ISO 8601 UTC), "
                    "DPSCOPE_FRAME, DPSCOPE_VERDICT and DPSCOPE_REASONS in its environment; at "
                    "most once per event kind and station a minute; the capture never waits "
                    "for it; at most 16 run at once (more are skipped and counted), and those "
                    "still running 5 s after the capture ends are ended")
        ->type_name("CMD");
    sub->add_flag("--no-low-latency", command->no_low_latency,
                  "Do not ask the driver for low-latency mode (ASYNC_LOW_LATENCY)");
    sub->add_option("--config", command->config_file,
                    "Read options from FILE first: lines KEY = VALUE, KEY an option's long name "
                    "without -- (interface = /dev/ttyUSB0, stats = true, a repeatable option on "
                    "several lines; # starts a comment line); an option given on the command line "
                    "too is the command line's (docs/service.md)")
        ->type_name("FILE");
    sub->add_option("--sighup", command->sighup,
                    "What SIGHUP does: stop (the capture ends, as when the terminal hangs up), "
                    "reopen (for logrotate: -w FILE, once moved away, is started anew; with a "
                    "rotation the next file is started now), or auto: stop when sniff has a "
                    "controlling terminal, reopen when it has none (a service)")
        ->check(CLI::IsMember({"auto", "stop", "reopen"}))
        ->default_str("auto");
    add_mqtt_options(*sub, command->mqtt);
    add_display_options(*sub, command->options, "text");
    add_trigger_options(*sub, command->options, true);
    add_tracking_options(*sub, command->options);
    add_health_options(*sub, command->health);
    // A live line cannot be judged before it is read: sniff takes the bus from --bus only.
    sub->get_option("--bus")->description(
        "The bus on the line: profibus (PROFIBUS DP, the default), fc (Danfoss FC protocol on "
        "RS-485: 9600 baud 8E1 unless --baud, --parity, --stop-bits say otherwise) or vlt2000 "
        "(Danfoss VLT 2000 ASCII telegram: 9600 baud 8N1 unless they say otherwise)");
    sub->footer(std::string(kExitCodeHelp) +
                " For sniff: on 4 and 5 what was captured before is written and the file is a "
                "valid pcap; a closed standard error does not stop the capture, its messages are "
                "dropped and the exit code is 4; with --report, 1 when a finding reaches "
                "--fail-on.");
    sub->callback([command, &exit_code] { exit_code = run_sniff(*command); });
}

}  // namespace dpscope::cli
