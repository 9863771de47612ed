// dpscope sniff: live capture from an RS-485 adapter (or any tty) at a PROFIBUS baud rate.
#include "cli/sniff_command.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <poll.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "capture/capture_writer.hpp"
#include "capture/output_file.hpp"
#include "capture/pcap_source.hpp"
#include "capture/serial_port.hpp"
#include "capture/tty_source.hpp"
#include "cli/alarm.hpp"
#include "cli/commands.hpp"
#include "cli/common_options.hpp"
#include "cli/live_health.hpp"
#include "cli/live_mqtt.hpp"
#include "cli/pipeline.hpp"
#include "cli/version.hpp"
#include "formats/monitor_messages.hpp"
#include "formats/report.hpp"
#include "formats/report_model.hpp"
#include "protocols/profibus/health/stats_render.hpp"

namespace dpscope::cli {

namespace {

std::atomic<bool> g_stop_requested{false};
std::atomic<bool> g_reopen_requested{false};

// The buses whose line has a default rate, for the message that --baud is missing: "the FC
// protocol, --bus fc, and the VLT 2000, --bus vlt2000, default to 9600".
std::string buses_with_default_baud() {
    std::vector<std::string> buses;
    std::vector<std::uint32_t> rates;
    for (const ProtocolDescriptor* p : protocol_table())
        if (p->default_baud != 0) {
            buses.push_back(fmt::format("the {}, --bus {}", p->traffic_name, p->name));
            rates.push_back(p->default_baud);
        }
    std::string text;
    for (std::size_t i = 0; i < buses.size(); ++i)
        text += (i == 0 ? "" : i + 1 == buses.size() ? ", and " : ", ") + buses[i];
    if (rates.empty()) return "no bus has a default rate";
    const bool one_rate = std::all_of(rates.begin(), rates.end(),
                                      [&](std::uint32_t r) { return r == rates.front(); });
    return one_rate ? fmt::format("{}, default to {}", text, rates.front())
                    : fmt::format("{}, have rates of their own", text);
}

// The first signal ends the capture cleanly; a second one ends the process at once, with the
// serial port put back as it was found and the staged report and statistics files removed.
extern "C" void request_stop(int signal_number) {
    if (g_stop_requested.exchange(true)) {
        SerialPort::restore_all_after_signal();
        PendingOutputFile::remove_all_after_signal();
        AlarmRunner::end_all_after_signal();
        ::signal(signal_number, SIG_DFL);
        ::raise(signal_number);
    }
}

extern "C" void request_reopen(int) { g_reopen_requested.store(true); }

// Does sniff have a controlling terminal (run from a shell), or none (a service)?
bool has_controlling_terminal() {
    const int fd = ::open("/dev/tty", O_RDONLY | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) return false;
    ::close(fd);
    return true;
}

// SIGINT, SIGTERM and SIGHUP (the terminal went away) end the capture cleanly; with
// `hup_reopens`, SIGHUP asks for the -w file to be reopened instead (logrotate). A closed pipe on
// standard output is a write error that ends it (exit code 4), not a SIGPIPE that would leave
// the port in raw mode.
void install_stop_handlers(bool hup_reopens) {
    g_stop_requested.store(false);
    g_reopen_requested.store(false);
    struct sigaction action {};
    action.sa_handler = request_stop;
    sigemptyset(&action.sa_mask);
    action.sa_flags = 0;  // no SA_RESTART: poll() returns at once
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
    if (hup_reopens) action.sa_handler = request_reopen;
    sigaction(SIGHUP, &action, nullptr);
    ::signal(SIGPIPE, SIG_IGN);
}

// Which file a path names (device and inode), to see whether logrotate moved it away.
struct FileIdentity {
    dev_t device = 0;
    ino_t inode = 0;
    bool known = false;
};

FileIdentity identity_of(const std::string& path) {
    struct stat info {};
    if (::stat(path.c_str(), &info) != 0) return {};
    return {info.st_dev, info.st_ino, true};
}

// SIGHUP with reopen: a rotation starts its next file; a single -w FILE that was moved away
// (logrotate) is closed, complete, and FILE started anew. A FILE still in place, or replaced by a
// file that holds data, is written on: nothing is ever overwritten. Returns what to say.
Result<std::string> reopen_capture(std::unique_ptr<CaptureWriter>& writer, FileIdentity& ours,
                                   const std::string& path, int link_type, Protocol bus,
                                   const LineSettings& line) {
    if (writer->rotation_stats()) {
        Result<std::string> next = writer->start_next_file();
        if (!next) return Error{next.error()};
        return next->empty()
                   ? fmt::format("SIGHUP: {} holds no telegram yet; writing on",
                                 rotated_file_name(path, writer->rotation_stats()->files_written))
                   : fmt::format("SIGHUP: started {}", *next);
    }
    struct stat info {};
    const bool exists = ::stat(path.c_str(), &info) == 0;
    if (exists && info.st_dev == ours.device && info.st_ino == ours.inode)
        return fmt::format("SIGHUP: -w {} was not moved away; writing on", path);
    if (exists && (!S_ISREG(info.st_mode) || info.st_size > 0))
        return fmt::format(
            "SIGHUP: {} is another file now, holding data; it is left alone and the capture goes "
            "on in the file that was moved away",
            path);
    if (Result<void> closed = writer->close(); !closed) return Error{closed.error()};
    WriterResult opened = open_capture_writer(path, CaptureFormat::Pcap, link_type, bus, line);
    if (!opened) return Error{opened.error()};
    writer = std::move(opened).value();
    ours = identity_of(path);
    return fmt::format("SIGHUP: -w {} was moved away; writing a new {}", path, path);
}

std::int64_t monotonic_ns() {
    timespec now{};
    clock_gettime(CLOCK_MONOTONIC, &now);
    return static_cast<std::int64_t>(now.tv_sec) * 1'000'000'000 + now.tv_nsec;
}

// The extcap's fifo, opened a second time (write end, non-blocking) once Wireshark reads it:
// poll() says POLLERR on it when the last reader has closed the fifo.
class ReaderWatch {
  public:
    explicit ReaderWatch(const std::string& path) {
        struct stat info {};
        if (path.empty() || path == "-" || ::stat(path.c_str(), &info) != 0 ||
            !S_ISFIFO(info.st_mode))
            return;
        fd_ = ::open(path.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC);
        // No reader any more (ENXIO): Wireshark closed the fifo before the watch was set up.
        gone_at_open_ = fd_ < 0 && errno == ENXIO;
    }
    ~ReaderWatch() {
        if (fd_ >= 0) ::close(fd_);
    }
    ReaderWatch(const ReaderWatch&) = delete;
    ReaderWatch& operator=(const ReaderWatch&) = delete;
    bool reader_gone() const {
        if (fd_ < 0) return gone_at_open_;
        pollfd watched{fd_, POLLOUT, 0};
        return ::poll(&watched, 1, 0) > 0 && (watched.revents & POLLERR) != 0;
    }

  private:
    int fd_ = -1;
    bool gone_at_open_ = false;
};

constexpr std::int64_t kFlushEveryNs = 50'000'000;  // at most 100 ms in buffers, with margin

// How long the end of the capture waits for --alarm commands still running, and how long
// those still running then have between SIGTERM and SIGKILL.
constexpr int kAlarmWaitAtEndMs = 5000;
constexpr int kAlarmEndGraceMs = 1000;

}  // namespace

int run_sniff(const SniffCommand& command) {
    // A closed pipe is a write error, from the first message on (standard error's reader may
    // have gone before the capture starts), not a SIGPIPE that ends the process.
    ::signal(SIGPIPE, SIG_IGN);
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
    settings->health.thresholds = *thresholds;
    // The line: PROFIBUS runs at the baud rate given (8E1); the FC protocol at 2400 to 115200
    // baud, 9600 8E1 unless --baud, --parity and --stop-bits say otherwise; the VLT 2000 at 9600
    // 8N1 (its manual: 8 data bits, no parity, 1 stop bit) unless they say otherwise.
    // Each bus's line is in its descriptor (default_baud, min_baud, max_baud, default_parity).
    const ProtocolDescriptor& bus = *settings->protocol;
    const std::uint32_t baud = command.baud != 0 ? command.baud : bus.default_baud;
    if (baud == 0) {
        print_error(fmt::format("--baud is required for {} ({})", bus.traffic_name,
                                buses_with_default_baud()));
        return kExitUsage;
    }
    if (bus.min_baud != 0 && (baud < bus.min_baud || baud > bus.max_baud)) {
        print_error(fmt::format(
            "--baud: must be a whole number from {} to {} baud for the {} (--bus {}), not '{}'",
            bus.min_baud, bus.max_baud, bus.traffic_name, bus.name, baud));
        return kExitUsage;
    }
    const SerialParity parity =
        serial_parity_from_name(command.parity)
            .value_or(serial_parity_from_name(bus.default_parity).value_or(SerialParity::Even));
    Result<int> link_type =
        capture_link_type(*settings->protocol, command.link_type.empty()
                                                   ? std::nullopt
                                                   : std::optional<int>(command.link_type == "user0"
                                                                            ? kLinkTypeUser0
                                                                            : kLinkTypeProfibusDl));
    if (!link_type) {
        print_error(link_type.error());
        return kExitUsage;
    }
    const bool pcap_to_stdout = command.output == "-";
    if (Result<void> usage = check_sniff_usage(command, bus); !usage) {
        print_error(usage.error());
        return kExitUsage;
    }
    // --mqtt: the address, topics, credentials and TLS files checked before anything is opened;
    // the publisher starts with the capture.
    std::unique_ptr<LiveMqtt> mqtt;
    if (!command.mqtt.url.empty()) {
        MonitorIdentity identity;
        identity.device = command.device;
        identity.bus = std::string(bus.name);
        identity.version = kVersion;
        Result<std::unique_ptr<LiveMqtt>> prepared = LiveMqtt::prepare(command.mqtt, identity);
        if (!prepared) {
            print_error(prepared.error());
            return kExitUsage;
        }
        mqtt = std::move(prepared).value();
    }
    const bool report = command.report || !command.report_file.empty();
    const bool report_to_stdout = command.report_file == "-";
    const bool stats = command.stats || !command.stats_file.empty();
    const bool stats_to_stdout = command.stats_file == "-";
    // The port is claimed first (its lock file: a port in use is no reason to truncate the -w
    // file), then the outputs are opened, and only then is the port opened and set up: a bad
    // output path leaves it untouched.
    SerialSettings serial;
    serial.device = command.device;
    serial.baud = baud;
    serial.parity = parity;
    serial.stop_bits = command.stop_bits;
    serial.low_latency = !command.no_low_latency;
    Result<std::unique_ptr<SerialPort>> claimed = SerialPort::claim(serial);
    if (!claimed) {
        print_error(claimed.error());
        return kExitUsage;
    }
    std::unique_ptr<SerialPort> port = std::move(claimed).value();
    // The -w file (the first one of a rotation) starts staged, with its pcap header written
    // beside it, and is moved into place once the port is set up: a port that fails or a full
    // disk leaves an existing file as it was and makes no empty one. From then on it is written
    // where it is, a valid pcap of every whole record written whenever the capture ends by itself.
    std::unique_ptr<PendingOutputFile> capture_file;
    std::unique_ptr<CaptureWriter> writer;
    // The line as asked (the port, set up later, reads it back within 1 %): decode, report and
    // stats read the capture at its rate without --baud.
    const LineSettings capture_line{baud, parity, command.stop_bits};
    if (!command.output.empty()) {
        const bool rotating = command.rotate_size > 0 || command.rotate_seconds > 0;
        const std::string first = rotating ? rotated_file_name(command.output, 1) : command.output;
        Result<std::unique_ptr<PendingOutputFile>> staged = PendingOutputFile::open(first);
        if (!staged) {
            print_error(staged.error());
            return kExitOutputError;
        }
        capture_file = std::move(staged).value();
        RotationOptions rotation{command.rotate_size,
                                 static_cast<std::int64_t>(command.rotate_seconds * 1e9),
                                 command.ring, command.max_disk};
        WriterResult opened =
            open_rotating_writer(command.output, CaptureFormat::Pcap, *link_type, rotation,
                                 settings->protocol->protocol, capture_line, capture_file->file());
        capture_file->release_file();  // the writer closes it
        if (!opened) {
            print_error(opened.error());
            return kExitOutputError;
        }
        writer = std::move(opened).value();
    }
    // --trigger: the windows' files go to --trigger-dir, else beside the -w file, else here.
    std::unique_ptr<TriggerRecorder> triggers;
    std::string trigger_folder;
    if (settings->trigger) {
        trigger_folder = command.options.trigger_dir;
        if (trigger_folder.empty()) {
            const std::filesystem::path output(command.output);
            trigger_folder =
                !command.output.empty() && command.output != "-" && output.has_parent_path()
                    ? output.parent_path().string()
                    : std::string(".");
        }
        Result<std::unique_ptr<TriggerRecorder>> made =
            make_trigger_recorder(*settings, trigger_folder, "--trigger-dir");
        if (!made) {
            print_error(made.error());
            return kExitUsage;
        }
        triggers = std::move(made).value();
    }
    // The report is staged like every other file output: written beside FILE and moved into
    // place only when it is complete, so a run that fails leaves an existing FILE as it was.
    std::unique_ptr<PendingOutputFile> report_file;
    if (!command.report_file.empty()) {
        Result<std::unique_ptr<PendingOutputFile>> opened =
            PendingOutputFile::open(command.report_file);
        if (!opened) {
            print_error(fmt::format("--report-file {}", opened.error()));
            return kExitOutputError;
        }
        report_file = std::move(opened).value();
    }
    std::unique_ptr<PendingOutputFile> stats_file;
    if (!command.stats_file.empty() && !stats_to_stdout) {
        Result<std::unique_ptr<PendingOutputFile>> opened =
            PendingOutputFile::open(command.stats_file);
        if (!opened) {
            print_error(fmt::format("--stats-file {}", opened.error()));
            return kExitOutputError;
        }
        stats_file = std::move(opened).value();
    }
    // SIGHUP: stop, or reopen (logrotate; a service has no controlling terminal).
    const bool hup_reopens =
        command.sighup == "reopen" || (command.sighup == "auto" && !has_controlling_terminal());
    install_stop_handlers(hup_reopens);  // from here on, a signal never leaves the port in raw mode
    if (Result<void> configured = port->configure(); !configured) {
        print_error(configured.error());
        writer.reset();
        capture_file.reset();  // discards the staged files: existing ones stay as they were
        report_file.reset();
        stats_file.reset();
        return kExitUsage;
    }
    if (capture_file) {
        if (Result<void> placed = capture_file->commit(); !placed) {
            print_error(placed.error());
            return kExitOutputError;  // the port is put back as it was found
        }
    }
    FileIdentity capture_identity =
        command.output.empty() || pcap_to_stdout ? FileIdentity{} : identity_of(command.output);
    FILE* text_stream = pcap_to_stdout || report_to_stdout || stats_to_stdout ? stderr : stdout;
    const bool extcap = command.extcap;
    if (!extcap) {
        if (!port->note().empty()) print_warning(fmt::format("{}", port->note()));
        write_standard_error(fmt::format("dpscope: capturing on {} at {} baud {}{}; Ctrl-C stops\n",
                                         command.device, port->baud(), port->frame(),
                                         port->low_latency() ? ", low latency" : ""));
    }
    const int fd = port->fd();
    TtySourceOptions tty_options;
    tty_options.baud = port->baud();
    tty_options.parity_marked = port->parity_marked();
    tty_options.character_bits = character_bits(parity, command.stop_bits);
    // The tracker measures the drive's response time from a command's last byte.
    settings->lanes.line_baud = port->baud();
    settings->lanes.character_bits = tty_options.character_bits;
    tty_options.idle_gap_ns = static_cast<std::int64_t>(command.idle_gap_ms) * 1'000'000;
    // Bus health: the bus load at the port's rate and character (8E1: 11 bits).
    // The report at the end has its bus-health section too (PROFIBUS), as `dpscope report` has.
    // LiveHealth judges the verdicts on the wall clock, also while the line is quiet.
    settings->judge_in_capture_time = false;
    // --mqtt publishes the health events too (PROFIBUS).
    settings->track_health = settings->track_health || stats || !command.alarm.empty() || report ||
                             (!command.mqtt.url.empty() && bus.has_bus_health);
    settings->health.baud = port->baud();
    settings->health.character_bits = tty_options.character_bits;
    const std::string heading =
        fmt::format("{} at {} baud {}", command.device, port->baud(), port->frame());
    TtySource source(std::move(port), fd, command.device, tty_options, settings->protocol->framing);

    Output out(text_stream, settings->line_buffered || isatty(fileno(text_stream)) != 0);
    const char* text_stream_name = text_stream == stdout ? "standard output" : "standard error";
    // The live output on standard error (-w -, --report-file -, --stats-file -) is dropped
    // when standard error cannot be written, as every message there is; the capture runs on.
    const bool text_on_stderr = text_stream == stderr;
    bool live_output_dropped = false;
    report_input_issues(source, out);
    Pipeline pipeline(
        *settings,
        PipelineParts{.timelines = report && report_format_from_name(command.report_format) ==
                                                 ReportFormat::Html});
    // --stats on a terminal: the station table, redrawn in place, instead of a line per
    // telegram (docs/decisions.md, "Bus health: sniff").
    const bool stats_table = stats && isatty(fileno(text_stream)) != 0;
    std::unique_ptr<AlarmRunner> alarms;
    if (!command.alarm.empty())
        alarms = std::make_unique<AlarmRunner>(command.alarm, monotonic_ns,
                                               [](std::string_view m) { print_warning(m); });
    std::unique_ptr<LiveHealth> live;
    if (pipeline.health()) {
        // Off a terminal, a line per event beside the decode; not inside jsonl or csv lines.
        const bool plain = settings->quiet || settings->format == OutputFormat::Text ||
                           settings->format == OutputFormat::Verbose;
        const LiveHealth::Show show = !stats        ? LiveHealth::Show::Nothing
                                      : stats_table ? LiveHealth::Show::Table
                                      : plain       ? LiveHealth::Show::Lines
                                                    : LiveHealth::Show::StandardError;
        live = std::make_unique<LiveHealth>(*pipeline.health(), out, text_stream, show, heading,
                                            alarms.get());
        live->listen(mqtt.get());
    }
    std::unique_ptr<TelegramRenderer> renderer;
    if (!settings->quiet && !stats_table && !extcap) {
        renderer = make_renderer(settings->format, out);
        renderer->begin();
    }
    FindingLog log;

    const std::int64_t start = monotonic_ns();
    if (mqtt) {
        if (Result<void> connected = mqtt->connect(tty_options.baud, wall_clock_ns()); !connected) {
            print_error(connected.error());
            return kExitUsage;
        }
    }
    const std::int64_t duration_ns = std::llround(command.duration * 1e9);
    std::int64_t last_flush = start;
    std::uint64_t telegrams = 0;
    bool output_failed = false;
    bool stopping = false;
    // extcap: Wireshark's fifo, watched for its reader going away (-1: not a fifo).
    ReaderWatch reader_watch(extcap ? command.output : std::string());
    bool reader_left = false;
    // A failed write or flush (disk full, a closed pipe) ends the capture; the file stays valid.
    // Wireshark closing the extcap's fifo is the end of its capture, not an error.
    auto stop_on_write_error = [&](const std::string& message) {
        if (reader_watch.reader_gone())
            reader_left = true;
        else if (!output_failed)
            print_error(fmt::format("{}; stopping the capture", message));
        output_failed = true;
        stopping = true;
        source.request_stop();
    };
    Record record;
    std::span<const Finding> findings;
    // --status-interval: a line for monitoring (standard error, and --status-file).
    const double status_seconds = command.status_interval > 0   ? command.status_interval
                                  : command.status_file.empty() ? 0.0
                                                                : 10.0;
    const std::int64_t status_every_ns = std::llround(status_seconds * 1e9);
    std::int64_t last_status = start;
    std::string last_event = "none";
    std::uint64_t findings_seen = 0;
    std::uint64_t health_events_seen = 0;
    // The figures now, the rate since `since` (its time and telegram count, moved to now).
    struct Since {
        std::int64_t ns;
        std::uint64_t telegrams = 0;
    };
    const auto figures = [&](std::int64_t now, Since& since) {
        MonitorFigures f;
        f.time_ns = wall_clock_ns();
        f.telegrams = telegrams;
        const double span_s = static_cast<double>(now - since.ns) / 1e9;
        f.rate = span_s > 0 ? static_cast<double>(telegrams - since.telegrams) / span_s : 0.0;
        since = {now, telegrams};
        if (writer)
            if (const RotationStats* ring = writer->rotation_stats())
                f.disk_bytes = ring->bytes_kept;
        if (f.disk_bytes == 0 && !command.output.empty() && command.output != "-") {
            struct stat info {};
            if (::stat(command.output.c_str(), &info) == 0)
                f.disk_bytes = static_cast<std::uint64_t>(info.st_size);
        }
        f.bytes_skipped = source.bytes_skipped();
        f.parity_errors = source.parity_errors();
        f.findings = findings_seen;
        f.health_events = health_events_seen;
        f.last_event = last_event;
        return f;
    };
    Since status_since{start};
    Since mqtt_since{start};
    const auto write_status = [&](std::int64_t now) {
        const std::string line = status_line(figures(now, status_since)) + "\n";
        if (command.status_interval > 0) write_standard_error(line);
        if (!command.status_file.empty()) {
            const std::string temporary = command.status_file + ".tmp";
            if (FILE* f = std::fopen(temporary.c_str(), "w")) {
                const bool ok = std::fputs(line.c_str(), f) >= 0;
                if (std::fclose(f) == 0 && ok)
                    std::rename(temporary.c_str(), command.status_file.c_str());
            }
        }
        last_status = now;
    };
    std::array<FilterEvent, 8> event_buffer;  // each telegram's health events (made once)
    for (;;) {
        std::int64_t now = monotonic_ns();
        if (status_every_ns > 0 && now - last_status >= status_every_ns) write_status(now);
        if (!stopping &&
            (g_stop_requested.load() || (duration_ns > 0 && now - start >= duration_ns))) {
            stopping = true;
            source.request_stop();
        }
        if (g_reopen_requested.exchange(false)) {
            if (writer && !output_failed && !pcap_to_stdout &&
                (writer->rotation_stats() || capture_identity.known)) {
                Result<std::string> reopened =
                    reopen_capture(writer, capture_identity, command.output, *link_type,
                                   settings->protocol->protocol, capture_line);
                if (!reopened)
                    stop_on_write_error(reopened.error());
                else if (!extcap)
                    write_standard_error(fmt::format("dpscope: {}\n", *reopened));
            } else if (!extcap) {
                write_standard_error("dpscope: SIGHUP: no capture file to reopen; going on\n");
            }
        }
        FramedSource::Poll polled = source.poll(record);
        if (polled == FramedSource::Poll::End) break;
        if (polled == FramedSource::Poll::Telegram) {
            ++telegrams;
            if (writer && !output_failed) {
                if (Result<void> written = writer->write(record.bytes, record.time_ns); !written)
                    stop_on_write_error(written.error());
                // extcap: Wireshark shows each telegram as it comes.
                else if (extcap)
                    if (Result<void> flushed = writer->flush(); !flushed)
                        stop_on_write_error(flushed.error());
            }
            const DecodedTelegram& t = pipeline.feed(record, findings);
            if (report && !findings.empty()) log.append(findings);
            const std::span<const FilterEvent> events =
                filter_events(pipeline.health_events(), event_buffer);
            show(renderer.get(), *settings, t, findings, pipeline.subject_pnu(), events);
            if (triggers) {
                const std::optional<TriggerHit> hit =
                    trigger_hit(*settings, t, findings, pipeline.subject_pnu(), events);
                if (Result<void> fed =
                        triggers->feed(record.bytes, record.time_ns, hit ? &*hit : nullptr);
                    !fed) {
                    print_error(
                        fmt::format("--trigger: {}; no more windows are written", fed.error()));
                    triggers.reset();
                }
            }
            if (live) live->on_events(pipeline.health_events());
            findings_seen += findings.size();
            health_events_seen += pipeline.health_events().size();
            if (mqtt && !findings.empty()) mqtt->on_findings(findings);
            if (!events.empty())
                last_event = fmt::format("{} {} at frame {}", events.back().event,
                                         events.back().station, record.number);
            else if (!findings.empty())
                last_event = fmt::format("{} at frame {}", finding_kind_name(findings.back().kind),
                                         record.number);
            // -c N: exactly N telegrams, not what else the driver still holds.
            if (settings->count != 0 && telegrams >= settings->count) break;
        }
        if (now - last_flush >= kFlushEveryNs || polled == FramedSource::Poll::Idle) {
            if (writer && !output_failed) {
                if (Result<void> flushed = writer->flush(); !flushed)
                    stop_on_write_error(flushed.error());
            }
            if (!out.flush() && !output_failed) {
                if (!text_on_stderr)
                    stop_on_write_error(fmt::format("{}: write failed: {}", text_stream_name,
                                                    std::strerror(errno)));
                else if (!live_output_dropped)
                    live_output_dropped = true;
            }
            last_flush = now;
            // A quiet bus writes nothing that could fail: the fifo is watched as well.
            if (!stopping && reader_watch.reader_gone()) {
                reader_left = true;
                output_failed = true;  // nothing more is written into it
                stopping = true;
                source.request_stop();
            }
        }
        if (live) live->tick(now, telegrams, static_cast<double>(now - start) / 1e9);
        if (mqtt) mqtt->tick(now, [&] { return figures(now, mqtt_since); });
    }
    if (status_every_ns > 0 || !command.status_file.empty()) write_status(monotonic_ns());
    if (live) live->before_finish();
    // Judged at the stop: a request left unanswered past the time-out before it is reported.
    std::span<const Finding> open_at_end = pipeline.finish(wall_clock_ns());
    warn_ppo_overrides(pipeline.decoder());
    if (report) log.append(open_at_end);
    findings_seen += open_at_end.size();
    if (mqtt) mqtt->on_findings(open_at_end);
    if (renderer) {
        renderer->render_end_findings(open_at_end);
        renderer->end();
    }
    if (writer) {
        Result<void> closed = writer->close();
        if (!closed && !output_failed) {
            print_error(closed.error());
            output_failed = true;
        }
        // What the ring removed: every telegram is in a file kept or counted here.
        if (const RotationStats* ring = writer->rotation_stats();
            ring && ring->files_removed > 0 && !extcap)
            write_standard_error(fmt::format(
                "dpscope: the ring kept files {} to {} ({} bytes); it removed the {} oldest, "
                "which held {} telegrams\n",
                rotated_file_name(command.output, ring->files_removed + 1),
                rotated_file_name(command.output, ring->files_written), ring->bytes_kept,
                ring->files_removed, ring->records_removed));
    }
    if (triggers) {
        if (Result<void> finished = triggers->finish(); !finished)
            print_error(fmt::format("--trigger: {}", finished.error()));
        if (!extcap) say_trigger_stats(triggers->stats(), trigger_folder);
    }
    double seconds = static_cast<double>(monotonic_ns() - start) / 1e9;
    if (live) live->after_finish(telegrams, seconds);
    if (mqtt) {
        const std::string said = mqtt->finish(figures(monotonic_ns(), mqtt_since));
        if (!extcap) write_standard_error(fmt::format("dpscope: {}\n", said));
    }
    out.flush();
    if (!extcap)
        write_standard_error(
            fmt::format("dpscope: {} telegrams, {} bytes in {:.1f} s; {} bytes skipped, {} parity "
                        "errors, {} telegrams cut off by line idle time\n",
                        telegrams, source.bytes_read(), seconds, source.bytes_skipped(),
                        source.parity_errors(), source.idle_gaps()));
    if (settings->quiet)
        pipeline.summary().render_text(out, describe_input(source), pipeline.decoder(),
                                       &pipeline.tracker());
    if (stats) {
        StatsContext context{describe_input(source), &pipeline.health()->health(),
                             std::string(kVersion)};
        const StatsFormat format =
            stats_format_from_name(command.stats_format).value_or(StatsFormat::Text);
        if (!stats_file) {
            // Standard output: after the live output, or alone on it (--stats-file -).
            if (stats_to_stdout) {
                Output stats_out(stdout);
                render_stats(format, context, stats_out);
                if (!stats_out.flush()) output_failed = true;
            } else {
                render_stats(format, context, out);
            }
        } else {
            Output stats_out(stats_file->file());
            render_stats(format, context, stats_out);
            if (!stats_out.flush()) {
                print_error(fmt::format("--stats-file {}: cannot write the statistics: {}",
                                        command.stats_file, std::strerror(errno)));
                stats_file->discard();
                output_failed = true;
            } else if (Result<void> committed = stats_file->commit(); !committed) {
                print_error(fmt::format("--stats-file {}", committed.error()));
                output_failed = true;
            }
        }
    }
    if (alarms) {
        alarms->finish(kAlarmWaitAtEndMs);
        alarms->end_running(kAlarmEndGraceMs);
        if (std::string said = alarms->summary(); !said.empty())
            write_standard_error(fmt::format("dpscope: {}\n", said));
    }
    int exit_code = kExitOk;
    if (report) {
        ReportContext context = report_context(
            pipeline, source, log, fail_on_from_name(command.fail_on).value_or(FailOn::Error));
        context.allow_empty = command.allow_empty;
        const ReportFormat format =
            report_format_from_name(command.report_format).value_or(ReportFormat::Text);
        bool fails = false;
        if (command.report_file.empty()) {
            fails = render_report(format, context, out);
        } else {
            Output report_out(report_file->file());
            fails = render_report(format, context, report_out);
            if (!report_out.flush()) {
                print_error(fmt::format("--report-file {}: cannot write the report: {}",
                                        command.report_file, std::strerror(errno)));
                report_file->discard();
                output_failed = true;
            } else if (Result<void> committed = report_file->commit(); !committed) {
                print_error(fmt::format("--report-file {}", committed.error()));
                output_failed = true;
            }
        }
        // A report that cannot list every finding says so itself; the run exits 4.
        if (const std::string lost = report::not_listed_text(context); !lost.empty()) {
            print_error(fmt::format("{}; the report says so", lost));
            output_failed = true;
        }
        if (fails) exit_code = kExitFindings;
    }
    if (!out.flush()) {
        if (!text_on_stderr) output_failed = true;
        live_output_dropped = text_on_stderr;
    }
    // Standard error could not be written (its reader gone, a full disk): the capture ran to its
    // end; what was dropped is said once more (standard error may take it by now) and the exit
    // code is 4, an output that could not be written.
    if (const std::uint64_t dropped = dropped_standard_error_messages();
        (dropped > 0 || live_output_dropped) && !reader_left) {
        print_error(fmt::format(
            "standard error could not be written: {} dropped{}",
            dropped == 1 ? std::string("1 message") : fmt::format("{} messages", dropped),
            live_output_dropped ? ", and the live output with them" : ""));
        output_failed = true;
    }
    if (output_failed && !reader_left) return kExitOutputError;
    if (source.status() == InputStatus::Damaged) return kExitDeviceError;
    return exit_code;
}

}  // namespace dpscope::cli
