// dpscope sniff: live capture from an RS-485 adapter (or any tty) at a PROFIBUS baud rate.
#include <fmt/format.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <ctime>
#include <memory>
#include <string>

#include "capture/capture_writer.hpp"
#include "capture/pcap_source.hpp"
#include "capture/serial_port.hpp"
#include "capture/tty_source.hpp"
#include "cli/commands.hpp"
#include "cli/common_options.hpp"
#include "cli/pipeline.hpp"
#include "cli/version.hpp"
#include "formats/report.hpp"

namespace dpscope::cli {

namespace {

std::atomic<bool> g_stop_requested{false};

extern "C" void request_stop(int) { g_stop_requested.store(true); }

// SIGINT and SIGTERM end the capture cleanly; a second SIGINT (handler reset) ends at once.
void install_stop_handlers() {
    g_stop_requested.store(false);
    struct sigaction action {};
    action.sa_handler = request_stop;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESETHAND;  // no SA_RESTART: poll() returns at once
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
}

std::int64_t monotonic_ns() {
    timespec now{};
    clock_gettime(CLOCK_MONOTONIC, &now);
    return static_cast<std::int64_t>(now.tv_sec) * 1'000'000'000 + now.tv_nsec;
}

constexpr std::int64_t kFlushEveryNs = 50'000'000;  // at most 100 ms in buffers, with margin

struct SniffCommand {
    DecodeOptionValues options;
    std::string device;
    std::uint32_t baud = 0;
    std::string output;
    std::string link_type = "profibus";
    std::uint64_t rotate_size = 0;
    double rotate_seconds = 0;
    double duration = 0;
    bool report = false;
    std::string report_format = "text";
    std::string fail_on = "error";
    std::uint32_t idle_gap_ms = 50;
    bool no_low_latency = false;
};

int run_sniff(const SniffCommand& command) {
    std::string error;
    auto settings = resolve_decode_options(command.options, "text", error);
    if (!settings) {
        print_error(error);
        return kExitUsage;
    }
    const bool pcap_to_stdout = command.output == "-";
    if (pcap_to_stdout && (command.rotate_size > 0 || command.rotate_seconds > 0)) {
        print_error("-w -: cannot rotate standard output; give a file name to rotate");
        return kExitUsage;
    }
    auto port =
        SerialPort::open({command.device, command.baud, !command.no_low_latency, false}, error);
    if (!port) {
        print_error(error);
        return kExitUsage;
    }
    std::unique_ptr<CaptureWriter> writer;
    if (!command.output.empty()) {
        RotationOptions rotation{command.rotate_size,
                                 static_cast<std::int64_t>(command.rotate_seconds * 1e9)};
        int link_type = command.link_type == "user0" ? kLinkTypeUser0 : kLinkTypeProfibusDl;
        WriterResult opened =
            open_rotating_writer(command.output, CaptureFormat::Pcap, link_type, rotation);
        if (!opened.writer) {
            print_error(opened.error);
            return kExitOutputError;
        }
        writer = std::move(opened.writer);
    }
    FILE* text_stream = pcap_to_stdout ? stderr : stdout;
    if (!port->note().empty()) print_warning(fmt::format("{}", port->note()));
    std::fprintf(stderr, "dpscope: capturing on %s at %u baud 8E1%s; Ctrl-C stops\n",
                 command.device.c_str(), port->baud(), port->low_latency() ? ", low latency" : "");
    const int fd = port->fd();
    TtySourceOptions tty_options;
    tty_options.baud = port->baud();
    tty_options.parity_marked = port->parity_marked();
    tty_options.idle_gap_ns = static_cast<std::int64_t>(command.idle_gap_ms) * 1'000'000;
    TtySource source(std::move(port), fd, command.device, tty_options);

    Output out(text_stream, settings->line_buffered || isatty(fileno(text_stream)) != 0);
    report_input_issues(source, out);
    Pipeline pipeline(*settings);
    std::unique_ptr<TelegramRenderer> renderer;
    if (!settings->quiet) {
        renderer = make_renderer(settings->format, out);
        renderer->begin();
    }
    FindingLog log;
    install_stop_handlers();

    const std::int64_t start = monotonic_ns();
    const std::int64_t duration_ns = static_cast<std::int64_t>(command.duration * 1e9);
    std::int64_t last_flush = start;
    std::uint64_t telegrams = 0;
    bool output_failed = false;
    bool stopping = false;
    // A failed write or flush (disk full) ends the capture; the file stays valid.
    auto stop_on_write_error = [&] {
        print_error(fmt::format("{}; stopping the capture", writer->error()));
        output_failed = true;
        stopping = true;
        source.request_stop();
    };
    Record record;
    std::span<const Finding> findings;
    for (;;) {
        std::int64_t now = monotonic_ns();
        if (!stopping &&
            (g_stop_requested.load() || (duration_ns > 0 && now - start >= duration_ns))) {
            stopping = true;
            source.request_stop();
        }
        FramedSource::Poll polled = source.poll(record);
        if (polled == FramedSource::Poll::End) break;
        if (polled == FramedSource::Poll::Telegram) {
            ++telegrams;
            if (writer && !output_failed && !writer->write(record.bytes, record.time_ns))
                stop_on_write_error();
            const DecodedTelegram& t = pipeline.feed(record, findings);
            if (command.report && !findings.empty()) log.append(findings);
            show(renderer.get(), *settings, t, findings, pipeline.tracker().subject_pnu());
            // -c N: exactly N telegrams, not what else the driver still holds.
            if (settings->count != 0 && telegrams >= settings->count) break;
        }
        if (now - last_flush >= kFlushEveryNs || polled == FramedSource::Poll::Idle) {
            if (writer && !output_failed && !writer->flush()) stop_on_write_error();
            out.flush();
            last_flush = now;
        }
    }
    // Judged at the stop: a request left unanswered past the time-out before it is reported.
    std::span<const Finding> open_at_end = pipeline.finish(wall_clock_ns());
    warn_ppo_overrides(pipeline.decoder());
    if (command.report) log.append(open_at_end);
    if (renderer) {
        renderer->render_end_findings(open_at_end);
        renderer->end();
    }
    if (writer && !writer->close() && !output_failed) {
        print_error(writer->error());
        output_failed = true;
    }
    double seconds = static_cast<double>(monotonic_ns() - start) / 1e9;
    out.flush();
    std::fprintf(stderr,
                 "dpscope: %llu telegrams, %llu bytes in %.1f s; %llu bytes skipped, %llu parity "
                 "errors, %llu telegrams cut off by line idle time\n",
                 static_cast<unsigned long long>(telegrams),
                 static_cast<unsigned long long>(source.bytes_read()), seconds,
                 static_cast<unsigned long long>(source.bytes_skipped()),
                 static_cast<unsigned long long>(source.parity_errors()),
                 static_cast<unsigned long long>(source.idle_gaps()));
    if (settings->quiet)
        pipeline.summary().render_text(out, describe_input(source), pipeline.decoder());
    int exit_code = kExitOk;
    if (command.report) {
        ReportContext context = report_context(
            pipeline, source, log, fail_on_from_name(command.fail_on).value_or(FailOn::Error));
        render_report(report_format_from_name(command.report_format).value_or(ReportFormat::Text),
                      context, out);
        if (report_fails(context)) exit_code = kExitFindings;
    }
    if (!out.flush()) output_failed = true;
    if (output_failed) return kExitOutputError;
    if (source.status() == InputStatus::Damaged) return kExitDeviceError;
    return exit_code;
}

}  // namespace

void add_sniff_command(CLI::App& app, int& exit_code) {
    auto command = std::make_shared<SniffCommand>();
    CLI::App* sub = app.add_subcommand(
        "sniff",
        "Capture live from an RS-485 bus tap (a serial adapter, 8 data bits, even parity, 1 stop "
        "bit, any baud rate the driver accepts), decode and track as telegrams arrive, optionally "
        "write pcap. Stops on -c, --duration, Ctrl-C (SIGINT) or SIGTERM with the capture file "
        "complete.");
    sub->add_option("-i,--interface", command->device, "Serial device, e.g. /dev/ttyUSB0")
        ->required()
        ->type_name("DEVICE");
    sub->add_option("--baud", command->baud,
                    "Bus baud rate (9600, 19200, 45450, 93750, 187500, 500000, 1500000, 3000000, "
                    "6000000, 12000000 or any rate the driver takes; read back and checked)")
        ->required()
        ->check(CLI::Range(300u, 16'000'000u));
    sub->add_option("-w,--write", command->output,
                    "Write the telegrams to FILE as pcap, flushed at least every 100 ms; - writes "
                    "pcap to standard output (the decoded output then goes to standard error)")
        ->type_name("FILE");
    sub->add_option("--linktype", command->link_type,
                    "pcap link type: profibus (257, PROFIBUS_DL) or user0 (147) for tools that "
                    "cannot open 257")
        ->check(CLI::IsMember({"profibus", "user0"}))
        ->default_str("profibus");
    sub->add_option("--rotate-size", command->rotate_size,
                    "Start a new file before one would exceed SIZE (e.g. 100M); files are named "
                    "stem-00001.pcap, stem-00002.pcap, ...; no telegram is split or lost")
        ->transform(CLI::AsSizeValue(false))
        ->type_name("SIZE");
    sub->add_option("--rotate-seconds", command->rotate_seconds,
                    "Start a new file once the current one holds SECONDS of capture")
        ->check(finite_number(0, 31'536'000, true))
        ->type_name("SECONDS");
    sub->add_option("--duration", command->duration, "Stop after SECONDS")
        ->check(finite_number(0, 31'536'000, true))
        ->type_name("SECONDS");
    sub->add_flag("--report", command->report,
                  "At the end, print the conformance report of the capture");
    sub->add_option("--report-format", command->report_format,
                    "Format of --report: text, json, markdown, html, junit")
        ->check(CLI::IsMember({"text", "json", "markdown", "html", "junit"}))
        ->default_str("text");
    sub->add_option("--fail-on", command->fail_on,
                    "With --report: exit code 1 when a finding of this severity or above was "
                    "found: error, warning, never")
        ->check(CLI::IsMember({"error", "warning", "never"}))
        ->default_str("error");
    sub->add_option("--idle-gap-ms", command->idle_gap_ms,
                    "Line idle time that ends an incomplete telegram (0: do not use idle time). "
                    "Keep it above a USB adapter's latency timer")
        ->default_str("50");
    sub->add_flag("--no-low-latency", command->no_low_latency,
                  "Do not ask the driver for low-latency mode (ASYNC_LOW_LATENCY)");
    add_display_options(*sub, command->options, "text");
    add_tracking_options(*sub, command->options);
    sub->footer(std::string(kExitCodeHelp) +
                " For sniff: on 4 and 5 what was captured before is written and the file is a "
                "valid pcap; with --report, 1 when a finding reaches --fail-on.");
    sub->callback([command, &exit_code] { exit_code = run_sniff(*command); });
}

}  // namespace dpscope::cli
