// dpscope simulate: write a simulated bus session as a capture.
#include <fmt/format.h>
#include <signal.h>

#include <atomic>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "capture/capture_writer.hpp"
#include "capture/pcap_source.hpp"
#include "capture/serial_port.hpp"
#include "capture/simulator.hpp"
#include "capture/telegram_source.hpp"
#include "capture/tty_player.hpp"
#include "cli/commands.hpp"
#include "cli/common_options.hpp"

namespace dpscope::cli {

namespace {

struct SimulateCommand {
    std::string output;
    std::string output_format = "pcap";
    std::string link_type = "profibus";
    std::uint64_t seed = 1;
    std::uint32_t baud = 1'500'000;
    unsigned master = 2;
    std::vector<std::string> slaves;
    std::uint64_t cycles = 1000;
    std::uint64_t count = 0;
    std::uint32_t cycle_us = 2000;
    double start = 1'704'067'200.0;
    std::vector<std::string> faults;
    bool list_injections = false;
    bool no_start_up = false;
    std::string device;
    std::string replay;
    bool as_fast_as_possible = false;
};

std::atomic<bool> g_stop_playing{false};
// The first signal stops playing cleanly; a second one ends the process at once, with the port
// put back as it was found.
extern "C" void stop_playing(int signal_number) {
    if (g_stop_playing.exchange(true)) {
        SerialPort::restore_all_after_signal();
        ::signal(signal_number, SIG_DFL);
        ::raise(signal_number);
    }
}

// Lists the injected faults (with -v) and names each fault given once that the session ended
// before; returns the exit code.
int report_injections(const SimulateCommand& command, const SimulatorOptions& options,
                      const Simulator& simulator) {
    if (command.list_injections)
        for (const Injection& injection : simulator.injections())
            fmt::print(stderr, "injected {} on slave {} in cycle {} at telegram {}\n",
                       fault_kind_name(injection.kind), injection.slave, injection.cycle,
                       injection.telegram);
    std::vector<std::string> missing = faults_not_injected(options, simulator.injections());
    for (const std::string& fault : missing)
        print_error(fmt::format(
            "--fault {} was not injected: the session ended before it had a chance "
            "(give an earlier @CYCLE, more --cycles or a larger -c)",
            fault));
    return missing.empty() ? kExitOk : kExitUsage;
}

// Plays the simulated session (or a capture, with --replay) onto a tty.
int play_onto_device(const SimulateCommand& command, const SimulatorOptions& options,
                     Simulator* simulator) {
    std::string error;
    auto port = SerialPort::open({command.device, command.baud, false, true}, error);
    if (!port) {
        print_error(error);
        return kExitUsage;
    }
    std::unique_ptr<TelegramSource> replay;
    if (!command.replay.empty()) {
        OpenResult opened = open_source(command.replay, InputFormat::Auto);
        if (!opened.source) {
            print_error(opened.error);
            return kExitUsage;
        }
        replay = std::move(opened.source);
        replay->on_issue([](const InputIssue& issue) {
            print_diagnostic(issue.severity, issue.message);
        });
    }
    TelegramGenerator next = [&](std::vector<std::uint8_t>& bytes, std::int64_t& time) {
        if (!replay) return simulator->next(bytes, time);
        Record record;
        if (!replay->next(record)) return false;
        bytes.assign(record.bytes.begin(), record.bytes.end());
        time = record.time_ns;
        return true;
    };
    struct sigaction action {};
    action.sa_handler = stop_playing;
    sigemptyset(&action.sa_mask);
    action.sa_flags = 0;
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
    PlayStats stats;
    if (!play_telegrams(port->fd(), next, command.as_fast_as_possible, &g_stop_playing, stats,
                        error)) {
        print_error(fmt::format("{}: {}", command.device, error));
        return kExitOutputError;
    }
    int exit_code = kExitOk;
    // Stopped by a signal, the session is cut short on purpose: nothing to say of its faults.
    if (simulator && !g_stop_playing.load())
        exit_code = report_injections(command, options, *simulator);
    if (command.list_injections)
        fmt::print(stderr, "played {} telegrams ({} bytes) in {:.3f} s (scheduled {:.3f} s)\n",
                   stats.telegrams, stats.bytes, static_cast<double>(stats.wall_ns) / 1e9,
                   static_cast<double>(stats.scheduled_ns) / 1e9);
    return exit_code;
}

int run_simulate(const SimulateCommand& command) {
    SimulatorOptions options;
    options.seed = command.seed;
    options.baud = command.baud;
    options.master = static_cast<std::uint8_t>(command.master);
    options.cycles = command.cycles;
    options.max_telegrams = command.count;
    options.cycle_us = command.cycle_us;
    options.start_time_ns = static_cast<std::int64_t>(std::llround(command.start * 1e9));
    options.record_start_up = !command.no_start_up;
    std::string error;
    for (const std::string& text : command.slaves) {
        auto slave = parse_slave_spec(text, error);
        if (!slave) {
            print_error(fmt::format("--slave {}", error));
            return kExitUsage;
        }
        if (slave->address == options.master) {
            print_error(fmt::format("--slave {}: the master has address {}", text, command.master));
            return kExitUsage;
        }
        options.slaves.push_back(*slave);
    }
    for (const std::string& text : command.faults) {
        auto fault = parse_fault_spec(text, error);
        if (!fault) {
            print_error(fmt::format("--fault {}", error));
            return kExitUsage;
        }
        options.faults.push_back(*fault);
    }
    if (std::string unusable = check_simulator_faults(options); !unusable.empty()) {
        print_error(fmt::format("--{}", unusable));
        return kExitUsage;
    }
    if (command.cycles == 0 && command.count == 0) {
        print_error("simulate: --cycles 0 runs until -c N telegrams; give -c");
        return kExitUsage;
    }
    if (command.output.empty() == command.device.empty()) {
        print_error("simulate: give either -w FILE or --device PATH");
        return kExitUsage;
    }
    if (!command.replay.empty() && command.device.empty()) {
        print_error("simulate: --replay plays a capture onto --device PATH");
        return kExitUsage;
    }
    if (!command.device.empty()) {
        if (!command.replay.empty()) return play_onto_device(command, options, nullptr);
        Simulator simulator(options);
        return play_onto_device(command, options, &simulator);
    }
    CaptureFormat format =
        capture_format_from_name(command.output_format).value_or(CaptureFormat::Pcap);
    int link_type = command.link_type == "user0" ? kLinkTypeUser0 : kLinkTypeProfibusDl;
    WriterResult opened = open_capture_writer(command.output, format, link_type);
    if (!opened.writer) {
        print_error(opened.error);
        return kExitOutputError;
    }
    Simulator simulator(options);
    std::vector<std::uint8_t> bytes;
    std::int64_t time_ns = 0;
    while (simulator.next(bytes, time_ns)) {
        if (!opened.writer->write(Bytes(bytes.data(), bytes.size()), time_ns)) break;
    }
    if (!opened.writer->close()) {
        print_error(opened.writer->error());
        return kExitOutputError;
    }
    int exit_code = report_injections(command, options, simulator);
    if (command.list_injections) fmt::print(stderr, "wrote {} telegrams\n", simulator.telegrams());
    return exit_code;
}

}  // namespace

void add_simulate_command(CLI::App& app, int& exit_code) {
    auto command = std::make_shared<SimulateCommand>();
    CLI::App* sub = app.add_subcommand(
        "simulate",
        "Write a simulated PROFIBUS DP session: start-up of each slave (FDL_Status, Slave_Diag, "
        "Set_Prm, Chk_Cfg, Slave_Diag), then cyclic Data_Exchange with parameter requests and "
        "responses, token passing, gap polls and Global_Control, timed at the baud rate. The same "
        "options and seed give the same bytes.");
    sub->add_option("-w,--write", command->output, "Output file; - writes to standard output")
        ->type_name("FILE");
    sub->add_option("--device", command->device,
                    "Play the session onto a tty instead (a serial adapter or one end of a "
                    "pseudo-terminal), 8E1 at --baud, at the pace of the baud rate")
        ->type_name("PATH");
    sub->add_option("--replay", command->replay,
                    "With --device: play this capture (any input format dpscope reads) with its "
                    "recorded timing instead of a simulated session")
        ->type_name("FILE");
    sub->add_flag("--as-fast-as-possible", command->as_fast_as_possible,
                  "With --device: do not wait for the telegrams' times, write as fast as the "
                  "device takes them");
    sub->add_option("-F,--output-format", command->output_format,
                    "pcap (nanosecond timestamps), pcapng, raw (bytes as on the wire) or hex "
                    "(one line a telegram with its timestamp)")
        ->check(CLI::IsMember({"pcap", "pcapng", "raw", "hex"}))
        ->default_str("pcap");
    sub->add_option("--linktype", command->link_type,
                    "pcap link type: profibus (257, PROFIBUS_DL) or user0 (147) for tools that "
                    "cannot open 257")
        ->check(CLI::IsMember({"profibus", "user0"}))
        ->default_str("profibus");
    sub->add_option("--seed", command->seed, "Random seed; the same seed gives the same session")
        ->default_str("1");
    sub->add_option("--baud", command->baud, "Bus baud rate used for the timing")
        ->check(CLI::Range(9600u, 12'000'000u))
        ->default_str("1500000");
    sub->add_option("--master", command->master, "Address of the DP master")
        ->check(CLI::Range(0, 126))
        ->default_str("2");
    sub->add_option("--slave", command->slaves,
                    "ADDR:PPO[:DIALECT] adds a slave, e.g. 5:1 or 7:2:profidrive; repeatable. "
                    "Default: 3:1 4:2 5:5 (vlt)")
        ->type_name("SPEC")
        ->allow_extra_args(false);
    sub->add_option("--cycles", command->cycles,
                    "Data_Exchange cycles after start-up; 0 runs until -c telegrams")
        ->default_str("1000");
    sub->add_option("-c,--count", command->count, "Stop after writing N telegrams");
    sub->add_option("--cycle-us", command->cycle_us, "Target bus cycle time in microseconds")
        ->check(CLI::Range(100u, 1'000'000u))
        ->default_str("2000");
    sub->add_option("--start", command->start,
                    "Time of the first telegram, seconds since the epoch (UTC)")
        ->default_str("1704067200 (2024-01-01T00:00:00Z)");
    sub->add_option("--fault", command->faults,
                    "Inject a fault: KIND (once, at a cycle the seed picks), KIND@CYCLE (once, at "
                    "the first chance from that cycle), or KIND=RATE (chance per cycle and slave); "
                    "append :ADDR to pick the slave. Kinds: fcs_error (alias bad_fcs), garbage, "
                    "malformed_telegram, stacked_request, orphan_response, mismatched_response, "
                    "unexpected_response_type, response_timeout, request_rejected, no_authority, "
                    "spontaneous_message, spontaneous_unacknowledged, spm_violation, "
                    "config_mismatch, unknown_code, fdl_retry, fdl_no_response. Repeatable.")
        ->type_name("SPEC")
        ->allow_extra_args(false);
    sub->add_flag("--no-start-up", command->no_start_up,
                  "Leave the start-up out of the capture, as when a tap is clipped on a running "
                  "bus: slaves' PPO types must then be inferred from the Data_Exchange length");
    sub->add_flag("-v,--list-injections", command->list_injections,
                  "Print each injected fault (kind, slave, cycle, telegram number) on standard "
                  "error");
    sub->footer(std::string(kExitCodeHelp));
    sub->callback([command, &exit_code] { exit_code = run_simulate(*command); });
}

}  // namespace dpscope::cli
