// dpscope simulate: write a simulated bus session as a capture.
#include <fmt/format.h>
#include <signal.h>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "capture/bus_tag.hpp"
#include "capture/capture_writer.hpp"
#include "capture/output_file.hpp"
#include "capture/pcap_source.hpp"
#include "capture/serial_port.hpp"
#include "capture/telegram_source.hpp"
#include "capture/tty_player.hpp"
#include "cli/commands.hpp"
#include "cli/common_options.hpp"
#include "cli/pipeline.hpp"
#include "core/counted.hpp"
#include "simulator/simulator.hpp"

namespace dpscope::cli {

namespace {

struct SimulateCommand {
    std::string output;
    std::string output_format = "pcap";
    std::string link_type = "profibus";
    std::string bus = "profibus";
    std::vector<std::string> drives;  // --bus fc, --bus vlt2000
    // Given on the command line (not defaults): --baud, --linktype, --master, --no-start-up.
    bool baud_given = false;
    bool link_type_given = false;
    bool master_given = false;
    std::uint64_t seed = 1;
    std::uint32_t baud = 1'500'000;
    unsigned master = 2;
    std::vector<std::string> slaves;
    std::uint64_t cycles = 1000;
    std::uint64_t count = 0;
    std::uint32_t cycle_us = 2000;
    std::string start = "1704067200";
    std::vector<std::string> faults;
    std::vector<unsigned> ring_masters;  // --masters
    std::uint32_t token_hold_us = 100;
    bool token_hold_given = false;
    bool list_injections = false;
    bool no_start_up = false;
    std::string device;
    std::string replay;
    bool as_fast_as_possible = false;
};

constexpr std::uint64_t kLargest = std::numeric_limits<std::uint64_t>::max();

// The VLT 2000's baud rates (parameter 501; its values were not found): as the FC protocol's,
// 2400 to 115200 (docs/decisions.md "VLT 2000 simulator").
constexpr std::uint32_t kVlt2000MinBaud = 2400;
constexpr std::uint32_t kVlt2000MaxBaud = 115'200;

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

// With -v, lists each injected fault as it happens (nothing is kept per injection).
void list_injections(const SimulateCommand& command, Simulator& simulator) {
    if (!command.list_injections) return;
    simulator.on_injection([](const Injection& injection) {
        fmt::print(stderr, "injected {} on slave {} in cycle {} at telegram {}\n",
                   fault_kind_name(injection.kind), injection.slave, injection.cycle,
                   injection.telegram);
    });
}

// Names each fault given once that the session ended before; returns the exit code.
int report_injections(const Simulator& simulator) {
    std::vector<std::string> missing = simulator.faults_not_injected();
    for (const std::string& fault : missing)
        print_error(
            fmt::format("--fault {} was not injected: the session ended before it had a chance "
                        "(give an earlier @CYCLE, more --cycles or a larger -c)",
                        fault));
    return missing.empty() ? kExitOk : kExitUsage;
}

// Plays the simulated session (or a capture, with --replay) onto a tty.
int play_onto_device(const SimulateCommand& command, Simulator* simulator) {
    // The bus's parity (8E1 for PROFIBUS and the FC protocol, 8N1 for the VLT 2000).
    const ProtocolDescriptor& bus =
        protocol_descriptor(protocol_from_name(command.bus).value_or(Protocol::ProfibusDp));
    SerialSettings serial{command.device, command.baud, false, true};
    serial.parity = serial_parity_from_name(bus.default_parity).value_or(SerialParity::Even);
    std::unique_ptr<TelegramSource> replay;
    if (!command.replay.empty()) {
        // The simulator makes the --bus protocol; a capture played in its place is one too.
        BusChoice choice;
        OpenResult opened = open_source(command.replay, InputFormat::Auto, &bus, choice);
        if (!opened) {
            print_error(opened.error());
            return kExitUsage;
        }
        replay = std::move(opened).value();
        replay->on_issue(
            [](const InputIssue& issue) { print_diagnostic(issue.severity, issue.message); });
        // A capture that records its line (sniff -w) is played on that line unless --baud says
        // otherwise (docs/decisions.md, "The line recorded in a capture").
        const LineSettings& line = choice.line;
        if (line.known() && !command.baud_given) serial.baud = line.baud;
        if (line.known() && command.baud_given && line.baud != command.baud)
            print_warning(fmt::format(
                "{}: the capture records its line as {}, but --baud says {}; played at {} baud, "
                "as --baud says",
                command.replay, describe_line(line), command.baud, command.baud));
        if (line.frame_known()) {
            serial.parity = *line.parity;
            serial.stop_bits = line.stop_bits;
        }
    }
    Result<std::unique_ptr<SerialPort>> port = SerialPort::open(serial);
    if (!port) {
        print_error(port.error());
        return kExitUsage;
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
    Result<PlayStats> played =
        play_telegrams((*port)->fd(), next, command.as_fast_as_possible, &g_stop_playing);
    if (!played) {
        print_error(fmt::format("{}: {}", command.device, played.error()));
        return kExitOutputError;
    }
    const PlayStats& stats = *played;
    int exit_code = kExitOk;
    // Stopped by a signal, the session is cut short on purpose: nothing to say of its faults.
    if (simulator && !g_stop_playing.load()) exit_code = report_injections(*simulator);
    if (command.list_injections)
        fmt::print(stderr, "played {} ({}) in {:.3f} s (scheduled {:.3f} s) at {} baud {}\n",
                   counted(stats.telegrams, "telegram", "telegrams"),
                   counted(stats.bytes, "byte", "bytes"), static_cast<double>(stats.wall_ns) / 1e9,
                   static_cast<double>(stats.scheduled_ns) / 1e9, serial.baud,
                   serial_frame_name(serial.parity, serial.stop_bits));
    return exit_code;
}

// The last second a capture's timestamps hold: a pcap record's seconds field has 32 bits, which
// libpcap (and so tcpdump and dpscope) reads as signed. One limit for every -F, so that the same
// options give the same session in each.
constexpr std::int64_t kLastSecond = 2'147'483'647;
constexpr std::string_view kLastTime = "2038-01-19T03:14:07Z";
constexpr std::int64_t kNanosPerSecond = 1'000'000'000;

// --start: seconds since the epoch, finite, from 0 to kLastSecond.
Result<std::int64_t> parse_start(const std::string& text) {
    std::optional<double> seconds = parse_finite_number(text);
    if (!seconds || *seconds < 0 || *seconds > static_cast<double>(kLastSecond))
        return Error{fmt::format(
            "--start {}: must be seconds since the epoch from 0 to {} (1970-01-01T00:00:00Z to "
            "{}, the last time a capture's timestamps hold)",
            text, kLastSecond, kLastTime)};
    return static_cast<std::int64_t>(std::llround(*seconds * 1e9));
}

// The session must end by kLastTime: a capture cannot date a telegram later (libpcap would read
// it as 1901). The error names the option to change.
Result<void> check_session_fits(const SimulateCommand& command, const SimulatorOptions& options) {
    constexpr std::int64_t kLast = kLastSecond * kNanosPerSecond + (kNanosPerSecond - 1);
    const std::int64_t span = session_span_bound_ns(options);
    const auto seconds = [](std::int64_t ns) {
        return ns / kNanosPerSecond + (ns % kNanosPerSecond != 0 ? 1 : 0);
    };
    if (span > kLast) {
        const bool by_count =
            command.count != 0 && (command.cycles == 0 || command.count < command.cycles);
        return Error{fmt::format(
            "{} {}: the session could last longer than the {} s a capture's timestamps span "
            "(1970-01-01T00:00:00Z to {}); give {}",
            by_count ? "-c" : "--cycles", by_count ? command.count : command.cycles, kLastSecond,
            kLastTime, by_count ? "a smaller -c" : "fewer --cycles")};
    }
    if (options.start_time_ns > kLast - span)
        return Error{fmt::format(
            "--start {}: the session lasts up to {} s and would end after {}, the last time a "
            "capture's timestamps hold; give --start from 0 to {}",
            command.start, seconds(span), kLastTime, (kLast - span) / kNanosPerSecond)};
    return {};
}

int run_simulate(const SimulateCommand& command) {
    Result<std::int64_t> start_ns = parse_start(command.start);
    if (!start_ns) {
        print_error(start_ns.error());
        return kExitUsage;
    }
    SimulatorOptions options;
    const ProtocolDescriptor& bus =
        protocol_descriptor(protocol_from_name(command.bus).value_or(Protocol::ProfibusDp));
    const bool fc = bus.protocol == Protocol::Fc;
    const bool vlt2000 = bus.protocol == Protocol::Vlt2000;
    const bool profibus = bus.protocol == Protocol::ProfibusDp;
    options.bus = bus.protocol;
    options.seed = command.seed;
    // A bus with a default line runs at it unless --baud says otherwise, within its rates.
    options.baud = bus.default_baud != 0 && !command.baud_given ? bus.default_baud : command.baud;
    if (bus.min_baud != 0 && (options.baud < bus.min_baud || options.baud > bus.max_baud)) {
        print_error(
            fmt::format("--baud: must be a whole number from {} to {} baud for the {}, "
                        "not '{}'",
                        bus.min_baud, bus.max_baud, bus.traffic_name, options.baud));
        return kExitUsage;
    }
    if (vlt2000 && (options.baud < kVlt2000MinBaud || options.baud > kVlt2000MaxBaud)) {
        print_error(fmt::format(
            "--baud: must be a whole number from {} to {} baud for the VLT 2000, not '{}'",
            kVlt2000MinBaud, kVlt2000MaxBaud, options.baud));
        return kExitUsage;
    }
    if (profibus && options.baud < 9600) {
        print_error(fmt::format(
            "--baud: must be a whole number from 9600 to 12000000 baud for PROFIBUS, not '{}'",
            options.baud));
        return kExitUsage;
    }
    if (fc) {
        if (!command.slaves.empty()) {
            print_error(
                fmt::format("--slave {}: slaves are PROFIBUS DP stations; an FC bus has "
                            "drives (--drive ADDR[:1-31|1-126])",
                            command.slaves.front()));
            return kExitUsage;
        }
        if (command.master_given) {
            print_error("--master: the FC master has no address; leave --master out with --bus fc");
            return kExitUsage;
        }
        if (command.link_type_given && command.link_type != "user0") {
            print_error("--linktype profibus: an FC capture has link type user0 (147)");
            return kExitUsage;
        }
        for (const std::string& text : command.drives) {
            Result<SimulatedDrive> drive = parse_drive_spec(text);
            if (!drive) {
                print_error(fmt::format("--drive {}", drive.error()));
                return kExitUsage;
            }
            for (std::size_t i = 0; i < options.drives.size(); ++i) {
                if (options.drives[i].address == drive->address) {
                    print_error(fmt::format(
                        "--drive {} and --drive {} both give address {}: one drive per address",
                        command.drives[i], text, drive->address));
                    return kExitUsage;
                }
            }
            options.drives.push_back(*drive);
        }
    } else if (vlt2000) {
        if (!command.slaves.empty()) {
            print_error(
                fmt::format("--slave {}: slaves are PROFIBUS DP stations; a VLT 2000 bus has "
                            "drives (--drive ADDR)",
                            command.slaves.front()));
            return kExitUsage;
        }
        if (command.master_given) {
            print_error(
                "--master: the VLT 2000 master has no address; leave --master out with --bus "
                "vlt2000");
            return kExitUsage;
        }
        if (command.link_type_given && command.link_type != "user0") {
            print_error("--linktype profibus: a VLT 2000 capture has link type user0 (147)");
            return kExitUsage;
        }
        for (const std::string& text : command.drives) {
            Result<std::uint8_t> drive = parse_vlt2000_drive_spec(text);
            if (!drive) {
                print_error(fmt::format("--drive {}", drive.error()));
                return kExitUsage;
            }
            for (std::size_t i = 0; i < options.vlt2000_drives.size(); ++i) {
                if (options.vlt2000_drives[i] == *drive) {
                    print_error(fmt::format(
                        "--drive {} and --drive {} both give address {}: one drive per address",
                        command.drives[i], text, *drive));
                    return kExitUsage;
                }
            }
            options.vlt2000_drives.push_back(*drive);
        }
    } else if (!command.drives.empty()) {
        print_error(
            fmt::format("--drive {}: drives are for --bus fc and --bus vlt2000; a PROFIBUS DP "
                        "bus has slaves (--slave ADDR:PPO)",
                        command.drives.front()));
        return kExitUsage;
    }
    options.master = static_cast<std::uint8_t>(command.master);
    options.cycles = command.cycles;
    options.max_telegrams = command.count;
    options.cycle_us = command.cycle_us;
    options.start_time_ns = *start_ns;
    options.record_start_up = !command.no_start_up;
    for (const std::string& text : command.slaves) {
        Result<SimulatedSlave> slave = parse_slave_spec(text);
        if (!slave) {
            print_error(fmt::format("--slave {}", slave.error()));
            return kExitUsage;
        }
        if (slave->address == options.master) {
            print_error(fmt::format("--slave {}: the master has address {}", text, command.master));
            return kExitUsage;
        }
        for (std::size_t i = 0; i < options.slaves.size(); ++i) {
            if (options.slaves[i].address == slave->address) {
                print_error(
                    fmt::format("--slave {} and --slave {} both give address {}: one slave per "
                                "address",
                                command.slaves[i], text, slave->address));
                return kExitUsage;
            }
        }
        options.slaves.push_back(*slave);
    }
    if (!command.ring_masters.empty() && !profibus) {
        print_error(fmt::format(
            "--masters: a token ring is PROFIBUS; leave --masters out with --bus {}", command.bus));
        return kExitUsage;
    }
    if (command.token_hold_given && command.ring_masters.empty()) {
        print_error("--token-hold-us: only with --masters (the masters that hold the token)");
        return kExitUsage;
    }
    for (unsigned address : command.ring_masters) {
        if (address == options.master) {
            print_error(fmt::format("--masters: {} is the DP master (--master)", address));
            return kExitUsage;
        }
        // Without --slave the slaves are 3, 4 and 5.
        bool slave = options.slaves.empty() && address >= 3 && address <= 5;
        for (const SimulatedSlave& config : options.slaves)
            slave = slave || config.address == address;
        if (slave) {
            print_error(fmt::format("--masters: {} is a slave's address", address));
            return kExitUsage;
        }
        if (std::find(options.ring_masters.begin(), options.ring_masters.end(), address) !=
            options.ring_masters.end()) {
            print_error(fmt::format("--masters: {} is given twice", address));
            return kExitUsage;
        }
        options.ring_masters.push_back(static_cast<std::uint8_t>(address));
    }
    options.token_hold_us = command.token_hold_us;
    for (const std::string& text : command.faults) {
        Result<FaultSpec> fault = parse_fault_spec(text, options.bus);
        if (!fault) {
            print_error(fmt::format("--fault {}", fault.error()));
            return kExitUsage;
        }
        options.faults.push_back(*fault);
    }
    if (Result<void> injectable = check_simulator_faults(options); !injectable) {
        print_error(fmt::format("--{}", injectable.error()));
        return kExitUsage;
    }
    if (command.cycles == 0 && command.count == 0) {
        print_error("simulate: --cycles 0 runs until -c N telegrams; give -c");
        return kExitUsage;
    }
    if (Result<void> fits = check_session_fits(command, options); !fits) {
        print_error(fits.error());
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
        // The port runs at the session's baud rate (9600 on an FC or VLT 2000 bus unless
        // --baud).
        SimulateCommand playing = command;
        playing.baud = options.baud;
        if (!command.replay.empty()) return play_onto_device(playing, nullptr);
        Simulator simulator(options);
        list_injections(playing, simulator);
        return play_onto_device(playing, &simulator);
    }
    CaptureFormat format =
        capture_format_from_name(command.output_format).value_or(CaptureFormat::Pcap);
    int link_type = command.link_type == "user0" ? kLinkTypeUser0 : bus.written_link_type().value;
    // Written beside the file and moved into place once complete: a write error (disk full)
    // leaves an existing file as it was.
    Result<std::unique_ptr<PendingOutputFile>> opened_file =
        PendingOutputFile::open(command.output);
    if (!opened_file) {
        print_error(opened_file.error());
        return kExitOutputError;
    }
    std::unique_ptr<PendingOutputFile> file = std::move(opened_file).value();
    // No line recorded: the samples made with it stay as they are (docs/decisions.md).
    WriterResult opened = open_capture_writer(file->file(), file->name(), format, link_type,
                                              options.bus, LineSettings{}, file->is_staged());
    file->release_file();  // the writer closes it
    if (!opened) {
        print_error(fmt::format("{}{}", opened.error(), file->left_as_it_was()));
        return kExitOutputError;
    }
    Simulator simulator(options);
    list_injections(command, simulator);
    std::vector<std::uint8_t> bytes;
    std::int64_t time_ns = 0;
    while (simulator.next(bytes, time_ns)) {
        if (!opened.value()->write(Bytes(bytes.data(), bytes.size()), time_ns)) break;
    }
    if (Result<void> closed = opened.value()->close(); !closed) {
        print_error(fmt::format("{}{}", closed.error(), file->left_as_it_was()));
        file->discard();
        return kExitOutputError;
    }
    // A fault given that the session ended before: the session is not the one asked for, and
    // goes beside an existing file.
    int exit_code = report_injections(simulator);
    exit_code = finish_staged_output(
        *file, exit_code, exit_code == kExitOk ? "" : "a --fault was not injected", "-w", {});
    if (command.list_injections) fmt::print(stderr, "wrote {} telegrams\n", simulator.telegrams());
    return exit_code;
}

// --fault's help: the forms, then the kinds of each bus.
std::string fault_help() {
    return fmt::format(
        "Inject a fault: KIND (once, at a cycle the seed picks), KIND@CYCLE (once, at the first "
        "chance from that cycle), or KIND=RATE (chance per cycle and slave); append :ADDR to "
        "pick the slave (or drive). Kinds with --bus profibus: {} (the dpv1_* kinds need a dpv1 "
        "slave; the bus-health kinds: {}). With --bus fc: {}. With --bus vlt2000: {}. Repeatable.",
        fault_kind_names(Protocol::ProfibusDp, true), bus_health_fault_help(),
        fault_kind_names(Protocol::Fc), fault_kind_names(Protocol::Vlt2000));
}

}  // namespace

void add_simulate_command(CLI::App& app, int& exit_code) {
    auto command = std::make_shared<SimulateCommand>();
    CLI::App* sub = app.add_subcommand(
        "simulate",
        "Write a simulated PROFIBUS DP session: start-up of each slave (FDL_Status, Slave_Diag, "
        "Set_Prm, Chk_Cfg, Slave_Diag), then cyclic Data_Exchange with parameter requests and "
        "responses, token passing, gap polls and Global_Control, timed at the baud rate; or, with "
        "--bus fc, a Danfoss FC protocol session, with --bus vlt2000 a VLT 2000 serial session "
        "(a master polling drives). The same options and seed give the same bytes.");
    sub->add_option("--bus", command->bus,
                    "profibus: a PROFIBUS DP bus (the default). fc: a Danfoss FC protocol bus on "
                    "RS-485 (9600 baud 8E1 unless --baud): the master polls each --drive in turn "
                    "with process blocks (control word, reference) and parameter commands (word "
                    "and double-word reads and writes, indexed reads of 15-30, text reads, a few "
                    "writes the drive refuses with AK 7), and sends a broadcast every 50 cycles; "
                    "the drives answer within 2 to 8 ms. vlt2000: a VLT 2000 (3000, 3500) serial "
                    "bus, the 22-character ASCII telegram (9600 baud 8N1 unless --baud): the "
                    "master polls each --drive in turn with the letters C (control word; the "
                    "status word back), R (read), U (update; the value echoed) and I (read index "
                    "of the fault log 0615), a few commands the drive cannot carry out (decimal "
                    "position 9, reason codes 00 to 04), and a broadcast (address 00) every 20 "
                    "cycles; the drives reply within 2 to 8 ms. No start-up and no token; pcap "
                    "and pcapng get link type user0 with the bus recorded")
        ->check(CLI::IsMember(bus_names()))
        ->default_str("profibus");
    sub->add_option("--drive", command->drives,
                    "With --bus fc: ADDR[:FORMAT] adds a drive, FORMAT the address byte's format "
                    "the master uses: 1-126 (the default, ADDR 1..126) or 1-31 (ADDR 1..31), e.g. "
                    "7, 3:1-31; repeatable. Default: 1 2 (1-126) and 3:1-31. With --bus vlt2000: "
                    "ADDR from 1 to 99; default 1 2 5")
        ->type_name("SPEC")
        ->allow_extra_args(false);
    sub->add_option("-w,--write", command->output,
                    "Output file; - writes to standard output. FILE is written (an existing one "
                    "replaced) only by a run that exits 0; a --fault the session ended before "
                    "(exit code 2) writes the session to FILE.partial and leaves FILE as it was; a "
                    "write error writes nothing")
        ->check(output_file_name())
        ->type_name("FILE");
    sub->add_option("--device", command->device,
                    "Play the session onto a tty instead (a serial adapter or one end of a "
                    "pseudo-terminal), 8E1 at --baud (8N1 with --bus vlt2000), at the pace of the "
                    "baud rate")
        ->type_name("PATH");
    sub->add_option("--replay", command->replay,
                    "With --device: play this capture (any input format dpscope reads) with its "
                    "recorded timing instead of a simulated session, on the line it records "
                    "(sniff -w: baud rate, parity, stop bits) unless --baud")
        ->type_name("FILE");
    sub->add_flag("--as-fast-as-possible", command->as_fast_as_possible,
                  "With --device: do not wait for the telegrams' times, write as fast as the "
                  "device takes them");
    sub->add_option("-F,--write-format", command->output_format,
                    "Capture format for -w, as in decode: pcap (nanosecond timestamps), pcapng, "
                    "raw (bytes as on the wire) or hex (one line a telegram with its timestamp)")
        ->check(CLI::IsMember({"pcap", "pcapng", "raw", "hex"}))
        ->type_name("FORMAT")
        ->default_str("pcap");
    // Its name before issue 27, still read (not shown in --help): -F is --write-format in every
    // subcommand now.
    sub->add_option("--output-format", command->output_format)
        ->check(CLI::IsMember({"pcap", "pcapng", "raw", "hex"}))
        ->group("");
    sub->add_option("--linktype", command->link_type,
                    "pcap link type: profibus (257, PROFIBUS_DL) or user0 (147) for tools that "
                    "cannot open 257; always user0 with --bus fc and vlt2000")
        ->check(CLI::IsMember({"profibus", "user0"}))
        ->default_str("profibus");
    sub->add_option("--seed", command->seed, "Random seed; the same seed gives the same session")
        ->check(whole_number(0, kLargest))
        ->default_str("1");
    sub->add_option("--baud", command->baud,
                    "Bus baud rate used for the timing (default 1500000; PROFIBUS 9600 to "
                    "12000000; with --bus fc or vlt2000 2400 to 115200, default 9600)")
        ->check(whole_number(2400, 12'000'000, " baud"))
        ->default_str("1500000");
    sub->add_option("--master", command->master,
                    "Address of the DP master (PROFIBUS only: the FC and VLT 2000 masters have "
                    "none)")
        ->check(whole_number(0, 126))
        ->default_str("2");
    sub->add_option("--slave", command->slaves,
                    "ADDR:PPO[:DIALECT][:dpv1] adds a slave, DIALECT vlt (the default), ge or "
                    "profidrive, e.g. 5:1, 6:1:ge, 7:2:profidrive or "
                    "8:3:vlt:dpv1; repeatable. Default: 3:1 4:2 5:5 (vlt). A dpv1 slave has "
                    "DP-V1 enabled in its Set_Prm, and after each cycle's Data_Exchange the "
                    "master runs PROFIdrive parameter access with it (MSAC_C1, slot 0, index 47: "
                    "a Write with the request, Reads until the response)")
        ->type_name("SPEC")
        ->allow_extra_args(false);
    sub->add_option("--cycles", command->cycles,
                    "Data_Exchange cycles after start-up (with --bus fc or vlt2000: polling rounds "
                    "of all drives); 0 runs until -c telegrams")
        ->check(whole_number(0, kLargest))
        ->default_str("1000");
    sub->add_option("-c,--count", command->count, "Stop after writing N telegrams")
        ->check(whole_number(0, kLargest));
    sub->add_option("--cycle-us", command->cycle_us,
                    "Target bus cycle time in microseconds: the DP master starts a cycle every "
                    "--cycle-us, or as soon as the last one is done when its polls (and the "
                    "token ring) take longer")
        ->check(whole_number(100, 1'000'000))
        ->default_str("2000");
    sub->add_option("--masters", command->ring_masters,
                    "ADDR[,ADDR...]: further active masters in a token ring with the DP master "
                    "(PROFIBUS only). At the end of each cycle the DP master passes the token to "
                    "the first, each holds it for --token-hold-us (every 20th cycle it gap-polls a "
                    "free address with FDL_Status meanwhile) and passes it to the next, the last "
                    "back to the DP master. Every master's token rotation, and the DP master's "
                    "poll cycle, is then --cycle-us, or when longer the cycle's work: the DP "
                    "master's polls plus, per further master, its token (3 characters) and its "
                    "hold. Without --masters the DP master passes the token to itself")
        ->delimiter(',')
        ->check(whole_number(0, 126))
        ->type_name("ADDR[,ADDR...]")
        ->allow_extra_args(false);
    sub->add_option("--token-hold-us", command->token_hold_us,
                    "With --masters: how long each further master holds the token, in "
                    "microseconds (at least the 33-bit sync pause)")
        ->check(whole_number(0, 1'000'000))
        ->default_str("100");
    sub->add_option("--start", command->start,
                    "Time of the first telegram, seconds since the epoch (UTC), 0 to 2147483647; "
                    "the session must end by 2038-01-19T03:14:07Z, the last time pcap readers "
                    "date right")
        ->type_name("SECONDS")
        ->default_str("1704067200 (2024-01-01T00:00:00Z)");
    sub->add_option("--fault", command->faults, fault_help())
        ->type_name("SPEC")
        ->allow_extra_args(false);
    sub->add_flag("--no-start-up", command->no_start_up,
                  "Leave the start-up out of the capture, as when a tap is clipped on a running "
                  "bus: slaves' PPO types must then be inferred from the Data_Exchange length "
                  "(an FC bus has no start-up)");
    sub->add_flag("-v,--list-injections", command->list_injections,
                  "Print each injected fault (kind, slave, cycle, telegram number) on standard "
                  "error");
    sub->footer(std::string(kExitCodeHelp));
    sub->callback([command, sub, &exit_code] {
        command->baud_given = sub->count("--baud") > 0;
        command->link_type_given = sub->count("--linktype") > 0;
        command->master_given = sub->count("--master") > 0;
        command->token_hold_given = sub->count("--token-hold-us") > 0;
        exit_code = run_simulate(*command);
    });
}

}  // namespace dpscope::cli
