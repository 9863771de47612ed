// dpscope as a Wireshark extcap capture interface (Wireshark's doc/extcap.adoc): Wireshark runs
// the program in its extcap folder with --extcap-interfaces, --extcap-dlts, --extcap-config and
// --capture --fifo PATH; dpscope answers in extcap sentences and captures into the fifo.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "capture/serial_ports.hpp"
#include "cli/commands.hpp"
#include "cli/common_options.hpp"
#include "cli/sniff_command.hpp"
#include "cli/version.hpp"

namespace dpscope::cli {

namespace {

// The interface whose port is given with --device, and the prefix of the per-port interfaces.
constexpr std::string_view kGenericInterface = "dpscope";
constexpr std::string_view kPortInterfacePrefix = "dpscope-";
// USER0: dpscope's telegrams, the bus named in the pcap header (capture/bus_tag.hpp).
constexpr int kExtcapDlt = 147;
constexpr std::uint32_t kMinBaud = 300;
constexpr std::uint32_t kMaxBaud = 16'000'000;
constexpr std::uint32_t kMaxIdleGapMs = 60'000;

// The baud rates offered in Wireshark's dialog: PROFIBUS's (9.6k to 12M) and the usual serial
// rates of the FC protocol (2400 to 115200); the command line takes any rate sniff takes.
struct BaudChoice {
    std::uint32_t baud;
    const char* buses;
};
constexpr BaudChoice kBaudChoices[] = {{2400, "FC"},
                                       {4800, "FC"},
                                       {9600, "PROFIBUS, FC, VLT 2000"},
                                       {19200, "PROFIBUS, FC"},
                                       {38400, "FC"},
                                       {45450, "PROFIBUS"},
                                       {57600, "FC"},
                                       {93750, "PROFIBUS"},
                                       {115200, "FC"},
                                       {187500, "PROFIBUS"},
                                       {500000, "PROFIBUS"},
                                       {1500000, "PROFIBUS"},
                                       {3000000, "PROFIBUS"},
                                       {6000000, "PROFIBUS"},
                                       {12000000, "PROFIBUS"}};

struct ExtcapCommand {
    bool list_interfaces = false;
    bool list_dlts = false;
    bool list_config = false;
    bool capture = false;
    std::string wireshark_version;  // --extcap-version=X: Wireshark's, not used
    std::string interface;
    std::string fifo;
    std::string capture_filter;
    std::string control_in;  // toolbar controls: dpscope has none; accepted and not used
    std::string control_out;
    bool debug = false;
    std::string debug_file;
    // The capture's options (the dialog's fields).
    std::string device;
    std::string bus = "profibus";
    std::uint32_t baud = 0;      // 0: the bus's default, as sniff has it
    std::string parity = "bus";  // bus: the bus's default
    unsigned stop_bits = 1;
    std::uint32_t idle_gap_ms = 50;
};

// Text inside an extcap sentence's {...}: no braces (Wireshark's parser ends a field at '}').
std::string field(std::string_view text) {
    std::string out(text);
    for (char& c : out) {
        if (c == '{') c = '(';
        if (c == '}') c = ')';
        if (c == '\n' || c == '\r') c = ' ';
    }
    return out;
}

// "--baud": 0 (the bus's default) or a whole number of baud from 300 to 16000000.
CLI::Validator extcap_baud() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            std::uint32_t baud = 0;
            if (parse_whole_number(std::string_view(text), baud) &&
                (baud == 0 || (baud >= kMinBaud && baud <= kMaxBaud)))
                return {};
            return fmt::format(
                "must be 0 (the bus's default) or a whole number from {} to {} baud, not '{}'",
                kMinBaud, kMaxBaud, text);
        },
        "0 or 300 to 16000000 baud", "baud");
}

// The serial device of interface `name`: dpscope-NAME is /dev/NAME; dpscope has none of its
// own (--device gives it). An error names an interface that is not dpscope's.
Result<std::string> interface_device(const std::string& name) {
    if (name == kGenericInterface) return std::string();
    if (name.rfind(kPortInterfacePrefix, 0) == 0) {
        std::string port = name.substr(kPortInterfacePrefix.size());
        bool plain = !port.empty() && port != "." && port != "..";
        for (char c : port) {
            bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                      c == '_' || c == '-' || c == '.';
            plain = plain && ok;
        }
        if (plain) return "/dev/" + port;
    }
    return Error{fmt::format(
        "--extcap-interface {}: not a dpscope interface (dpscope, or dpscope-PORT for a serial "
        "port /dev/PORT; --extcap-interfaces lists them)",
        name)};
}

void print_interfaces() {
    std::printf("extcap {version=%s}{display=dpscope PROFIBUS DP and Danfoss serial-bus sniffer}\n",
                std::string(kVersion).c_str());
    std::printf(
        "interface {value=%s}{display=dpscope: serial bus sniffer (port given in the "
        "options)}\n",
        std::string(kGenericInterface).c_str());
    for (const SerialPortEntry& port : list_serial_ports()) {
        std::string display = fmt::format("dpscope: serial bus sniffer on {}", port.device);
        if (!port.by_id.empty()) display += fmt::format(" ({})", port.by_id);
        std::printf("interface {value=%s%s}{display=%s}\n",
                    std::string(kPortInterfacePrefix).c_str(), field(port.name).c_str(),
                    field(display).c_str());
    }
}

void print_dlts() {
    std::printf(
        "dlt {number=%d}{name=USER0}{display=dpscope telegrams (USER0, the bus named in the "
        "pcap header)}\n",
        kExtcapDlt);
}

// The capture options of `interface` (its device as the default of --device).
void print_config(const std::string& device) {
    int number = 0;
    const bool generic = device.empty();
    std::printf(
        "arg {number=%d}{call=--device}{display=Serial port}{type=string}{tooltip=The serial "
        "device of the RS-485 tap (or any tty), e.g. /dev/ttyUSB0}%s%s{group=Serial line}\n",
        number, generic ? "{required=true}" : "",
        generic ? "" : fmt::format("{{default={}}}", field(device)).c_str());
    ++number;
    std::printf(
        "arg {number=%d}{call=--bus}{display=Bus}{type=selector}{tooltip=The bus on the line, "
        "as sniff --bus}{group=Serial line}\n",
        number);
    std::printf("value {arg=%d}{value=profibus}{display=PROFIBUS DP}{default=true}\n", number);
    std::printf("value {arg=%d}{value=fc}{display=Danfoss FC protocol}{default=false}\n", number);
    std::printf("value {arg=%d}{value=vlt2000}{display=Danfoss VLT 2000}{default=false}\n", number);
    ++number;
    std::printf(
        "arg {number=%d}{call=--baud}{display=Baud rate}{type=selector}{tooltip=The line's baud "
        "rate (PROFIBUS: required, 9600 to 12000000; FC protocol: 2400 to 115200, default 9600; "
        "VLT 2000: default 9600)}{group=Serial line}\n",
        number);
    std::printf(
        "value {arg=%d}{value=0}{display=The bus's default (FC, VLT 2000: 9600; PROFIBUS has "
        "none)}{default=true}\n",
        number);
    for (const BaudChoice& choice : kBaudChoices)
        std::printf("value {arg=%d}{value=%u}{display=%u (%s)}{default=false}\n", number,
                    choice.baud, choice.baud, choice.buses);
    ++number;
    std::printf(
        "arg {number=%d}{call=--parity}{display=Parity}{type=selector}{tooltip=The parity bit "
        "of each character}{group=Serial line}\n",
        number);
    std::printf(
        "value {arg=%d}{value=bus}{display=The bus's default (even; VLT 2000: none)}"
        "{default=true}\n",
        number);
    for (const char* parity : {"even", "odd", "none"})
        std::printf("value {arg=%d}{value=%s}{display=%s}{default=false}\n", number, parity,
                    parity);
    ++number;
    std::printf(
        "arg {number=%d}{call=--stop-bits}{display=Stop bits}{type=selector}{tooltip=Stop bits "
        "of each character}{group=Serial line}\n",
        number);
    std::printf("value {arg=%d}{value=1}{display=1}{default=true}\n", number);
    std::printf("value {arg=%d}{value=2}{display=2}{default=false}\n", number);
    ++number;
    std::printf(
        "arg {number=%d}{call=--idle-gap-ms}{display=Idle gap (ms)}{type=unsigned}{range=0,%u}"
        "{default=50}{tooltip=Line idle time that ends an incomplete telegram (0: not used); "
        "keep it above a USB adapter's latency timer}{group=Serial line}\n",
        number, kMaxIdleGapMs);
}

int run_extcap_command(const ExtcapCommand& command) {
    const int actions = int{command.list_interfaces} + int{command.list_dlts} +
                        int{command.list_config} + int{command.capture};
    if (actions != 1) {
        print_error(
            "give one of --extcap-interfaces, --extcap-dlts, --extcap-config, --capture (see "
            "--help)");
        return kExitUsage;
    }
    if (command.list_interfaces) {
        print_interfaces();
        return std::fflush(stdout) == 0 ? kExitOk : kExitOutputError;
    }
    if (command.interface.empty()) {
        print_error("--extcap-interface is required (--extcap-interfaces lists them)");
        return kExitUsage;
    }
    Result<std::string> device = interface_device(command.interface);
    if (!device) {
        print_error(device.error());
        return kExitUsage;
    }
    if (command.list_dlts) {
        print_dlts();
        return std::fflush(stdout) == 0 ? kExitOk : kExitOutputError;
    }
    if (command.list_config) {
        print_config(*device);
        return std::fflush(stdout) == 0 ? kExitOk : kExitOutputError;
    }
    // --capture
    if (!command.capture_filter.empty()) {
        print_error(fmt::format(
            "--extcap-capture-filter '{}': dpscope has no capture filter; capture everything "
            "and use a display filter",
            command.capture_filter));
        return kExitUsage;
    }
    if (command.fifo.empty()) {
        print_error("--capture needs --fifo PATH (where the pcap goes)");
        return kExitUsage;
    }
    SniffCommand sniff;
    sniff.device = command.device.empty() ? *device : command.device;
    if (sniff.device.empty()) {
        print_error(fmt::format(
            "--device is required for interface {}: the serial port to capture on, e.g. "
            "/dev/ttyUSB0",
            command.interface));
        return kExitUsage;
    }
    sniff.options.bus = command.bus;
    sniff.baud = command.baud;
    sniff.parity = command.parity == "bus" ? std::string() : command.parity;
    sniff.stop_bits = command.stop_bits;
    sniff.idle_gap_ms = command.idle_gap_ms;
    sniff.output = command.fifo;
    sniff.link_type = "user0";
    sniff.extcap = true;
    return run_sniff(sniff);
}

}  // namespace

bool is_extcap_call(int argc, char** argv) {
    if (argc < 2) return false;
    const std::string_view first = argv[1];
    return first.rfind("--extcap-", 0) == 0 || first == "--capture";
}

int run_extcap(int argc, char** argv) {
    CLI::App app{
        "dpscope as a Wireshark extcap capture interface: Wireshark (or tshark -i) runs dpscope "
        "from its extcap folder with these options to list the serial ports, the link type and "
        "the capture options, and to capture into a fifo as USER0 pcap. Install: a link named "
        "dpscope to the dpscope program in the extcap folder (docs/wireshark.md).",
        "dpscope"};
    app.failure_message([](const CLI::App*, const CLI::Error& e) {
        return fmt::format(
            "dpscope: error: {}\nRun 'dpscope --extcap-interfaces --help' for "
            "the extcap options.\n",
            e.what());
    });
    auto command = ExtcapCommand{};
    app.add_flag("--extcap-interfaces", command.list_interfaces,
                 "List the interfaces: dpscope (port given with --device) and dpscope-PORT for "
                 "each serial port found");
    app.add_option("--extcap-version", command.wireshark_version,
                   "Wireshark's version (given with --extcap-interfaces; not used)")
        ->expected(0, 1)
        ->type_name("VERSION");
    app.add_flag("--extcap-dlts", command.list_dlts,
                 "List the link type of --extcap-interface: USER0 (147)");
    app.add_flag("--extcap-config", command.list_config,
                 "List the capture options of --extcap-interface");
    app.add_flag("--capture", command.capture,
                 "Capture on --extcap-interface into --fifo until stopped (SIGTERM, SIGINT) or "
                 "Wireshark closes the fifo");
    app.add_option("--extcap-interface", command.interface, "The interface")
        ->type_name("INTERFACE");
    app.add_option("--fifo", command.fifo, "Where the capture goes (pcap, link type USER0)")
        ->type_name("PATH");
    app.add_option("--extcap-capture-filter", command.capture_filter,
                   "A capture filter: dpscope has none (a non-empty one is an error); use "
                   "display filters")
        ->type_name("FILTER");
    app.add_option("--extcap-control-in", command.control_in, "Not used (no toolbar controls)")
        ->type_name("PATH");
    app.add_option("--extcap-control-out", command.control_out, "Not used (no toolbar controls)")
        ->type_name("PATH");
    app.add_flag("--debug", command.debug, "Not used");
    app.add_option("--debug-file", command.debug_file, "Not used")->type_name("PATH");
    app.add_option("--device", command.device,
                   "Serial device (required for interface dpscope; for dpscope-PORT, instead "
                   "of /dev/PORT)")
        ->type_name("DEVICE");
    app.add_option("--bus", command.bus, "The bus on the line: profibus, fc or vlt2000")
        ->check(CLI::IsMember(bus_names()))
        ->type_name("BUS")
        ->default_str("profibus");
    app.add_option("--baud", command.baud,
                   "Baud rate: 0 for the bus's default (FC protocol, VLT 2000: 9600; PROFIBUS has "
                   "none), or 300 to 16000000 (FC protocol: 2400 to 115200), as sniff --baud")
        ->check(extcap_baud())
        ->default_str("0");
    app.add_option("--parity", command.parity,
                   "Parity: bus (the bus's default: even; VLT 2000: none), even, odd or none")
        ->check(CLI::IsMember({"bus", "even", "odd", "none"}))
        ->type_name("PARITY")
        ->default_str("bus");
    app.add_option("--stop-bits", command.stop_bits, "Stop bits: 1 or 2")
        ->check(CLI::IsMember({1u, 2u}))
        ->type_name("N")
        ->default_str("1");
    app.add_option("--idle-gap-ms", command.idle_gap_ms,
                   "Line idle time that ends an incomplete telegram (0: not used)")
        ->check(whole_number(0, kMaxIdleGapMs, " ms"))
        ->default_str("50");
    app.footer(std::string(kExitCodeHelp));
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        int rc = app.exit(e);
        return rc == 0 ? kExitOk : kExitUsage;
    }
    return run_extcap_command(command);
}

}  // namespace dpscope::cli
