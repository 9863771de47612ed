// dpscope as a Wireshark extcap interface: the extcap options driven directly (interfaces, link
// type, capture options, bad values), captures into a fifo and a file from a pseudo-terminal, and
// tshark capturing on the extcap interface while `dpscope simulate --device` plays a session.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

#include <filesystem>
#include <map>
#include <mutex>
#include <regex>
#include <set>
#include <thread>
#include <vector>

#include "capture/serial_ports.hpp"
#include "capture/telegram_source.hpp"
#include "tests/pty_support.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

namespace fs = std::filesystem;
using test::Capture;
using test::Child;
using test::play;
using test::PseudoTerminal;
using test::read_capture;
using test::Relay;
using test::Session;
using test::simulate;
using test::wait_for_raw_mode;

Child extcap_capture(std::vector<std::string> args) {
    args.insert(args.begin(), "--capture");
    return Child(test::dpscope_argv(args));
}

// An extcap sentence: its keyword and its {name=value} fields, or nullopt when malformed.
struct Sentence {
    std::string keyword;
    std::map<std::string, std::string> fields;
};

std::optional<Sentence> parse_sentence(const std::string& line) {
    static const std::regex whole(R"(^(extcap|interface|dlt|arg|value) (\{[a-z]+=[^{}]*\})+$)");
    if (!std::regex_match(line, whole)) return std::nullopt;
    Sentence s;
    s.keyword = line.substr(0, line.find(' '));
    static const std::regex one(R"(\{([a-z]+)=([^{}]*)\})");
    for (auto it = std::sregex_iterator(line.begin(), line.end(), one);
         it != std::sregex_iterator(); ++it) {
        if (!s.fields.emplace((*it)[1].str(), (*it)[2].str()).second) return std::nullopt;
    }
    return s;
}

std::vector<Sentence> sentences_of(const std::string& out) {
    std::vector<Sentence> all;
    for (const std::string& line : test::lines_of(out)) {
        std::optional<Sentence> s = parse_sentence(line);
        EXPECT_TRUE(s) << "malformed extcap sentence: " << line;
        if (s) all.push_back(*s);
    }
    return all;
}

TEST(ExtcapTest, InterfacesAreListedInWellFormedSentences) {
    auto listed = test::run_dpscope({"--extcap-interfaces", "--extcap-version=4.0"});
    ASSERT_EQ(listed.exit_code, 0) << listed.err;
    EXPECT_EQ(listed.err, "");
    std::vector<Sentence> sentences = sentences_of(listed.out);
    ASSERT_GE(sentences.size(), 2u) << listed.out;
    EXPECT_EQ(sentences[0].keyword, "extcap");
    EXPECT_FALSE(sentences[0].fields["version"].empty());
    std::set<std::string> values;
    for (std::size_t i = 1; i < sentences.size(); ++i) {
        Sentence& s = sentences[i];
        EXPECT_EQ(s.keyword, "interface");
        EXPECT_FALSE(s.fields["display"].empty());
        const std::string& value = s.fields["value"];
        EXPECT_TRUE(value == "dpscope" || value.rfind("dpscope-", 0) == 0) << value;
        EXPECT_TRUE(values.insert(value).second) << "listed twice: " << value;
    }
    EXPECT_EQ(values.count("dpscope"), 1u);
    // Each port of this machine is listed, under its name.
    for (const SerialPortEntry& port : list_serial_ports())
        EXPECT_EQ(values.count("dpscope-" + port.name), 1u) << port.name;
    // Without --extcap-version as well; a second action is an error.
    EXPECT_EQ(test::run_dpscope({"--extcap-interfaces"}).out, listed.out);
    auto two = test::run_dpscope({"--extcap-interfaces", "--extcap-dlts"});
    EXPECT_EQ(two.exit_code, 2);
    EXPECT_NE(two.err.find("give one of"), std::string::npos) << two.err;
    // The extcap options have their own help; the subcommands are as they were.
    auto help = test::run_dpscope({"--extcap-interfaces", "--help"});
    EXPECT_EQ(help.exit_code, 0);
    EXPECT_NE(help.out.find("--fifo"), std::string::npos) << help.out;
    EXPECT_EQ(test::run_dpscope({"--version"}).exit_code, 0);
}

TEST(ExtcapTest, SerialPortsAreFoundInSysfsWithTheirByIdNames) {
    const fs::path root = test::temp_path("fake-root");
    const fs::path sys = root / "sys";
    const fs::path dev = root / "dev";
    fs::create_directories(sys / "devices" / "usb1" / "1-1");
    fs::create_directories(sys / "devices" / "pnp0" / "00:01");
    fs::create_directories(sys / "devices" / "platform" / "serial8250");
    fs::create_directories(dev / "serial" / "by-id");
    auto tty = [&](const std::string& name, const std::string& device, bool node) {
        fs::create_directories(sys / "class" / "tty" / name);
        if (!device.empty())
            fs::create_directory_symlink(sys / "devices" / device,
                                         sys / "class" / "tty" / name / "device");
        if (node) test::write_file((dev / name).string(), {});
    };
    tty("ttyUSB10", "usb1/1-1", true);
    tty("ttyUSB2", "usb1/1-1", true);
    tty("ttyUSB0", "usb1/1-1", true);
    tty("ttyS0", "pnp0/00:01", true);
    tty("ttyS1", "platform/serial8250", true);  // a placeholder of the 8250 driver
    tty("tty1", "", true);                      // a virtual console: no device
    tty("ttyACM0", "usb1/1-1", false);          // no device node
    fs::create_symlink("../../ttyUSB0", dev / "serial" / "by-id" / "usb-FTDI_FT232R_A1B2-if00");
    std::vector<SerialPortEntry> ports = list_serial_ports(sys.string(), dev.string());
    std::vector<std::string> names;
    for (const SerialPortEntry& p : ports)
        names.push_back(p.name);
    EXPECT_EQ(names, (std::vector<std::string>{"ttyS0", "ttyUSB0", "ttyUSB2", "ttyUSB10"}));
    ASSERT_EQ(ports.size(), 4u);
    EXPECT_EQ(ports[1].device, (dev / "ttyUSB0").string());
    EXPECT_EQ(ports[1].by_id, "usb-FTDI_FT232R_A1B2-if00");
    EXPECT_EQ(ports[0].by_id, "");
    // Roots that do not exist: no ports, no failure.
    EXPECT_TRUE(list_serial_ports((root / "none").string(), (root / "none").string()).empty());
    fs::remove_all(root);
}

TEST(ExtcapTest, TheLinkTypeIsUser0) {
    for (const char* interface : {"dpscope", "dpscope-ttyUSB0"}) {
        auto dlts = test::run_dpscope({"--extcap-dlts", "--extcap-interface", interface});
        ASSERT_EQ(dlts.exit_code, 0) << dlts.err;
        std::vector<Sentence> sentences = sentences_of(dlts.out);
        ASSERT_EQ(sentences.size(), 1u) << dlts.out;
        EXPECT_EQ(sentences[0].keyword, "dlt");
        EXPECT_EQ(sentences[0].fields["number"], "147");
        EXPECT_EQ(sentences[0].fields["name"], "USER0");
    }
}

TEST(ExtcapTest, TheCaptureOptionsAreWellFormedAndTheirValuesAccepted) {
    for (const std::string interface : {"dpscope", "dpscope-ttyUSB0"}) {
        auto config = test::run_dpscope({"--extcap-config", "--extcap-interface", interface});
        ASSERT_EQ(config.exit_code, 0) << config.err;
        std::map<std::string, std::string> call_of;  // arg number -> call
        std::map<std::string, std::string> type_of;  // arg number -> type
        std::map<std::string, int> defaults_of;      // arg number -> values marked default
        std::map<std::string, std::vector<std::string>> values_of;
        std::map<std::string, std::string> default_value;  // call -> {default=...} of the arg
        for (Sentence& s : sentences_of(config.out)) {
            if (s.keyword == "arg") {
                for (const char* key : {"number", "call", "display", "type"})
                    EXPECT_FALSE(s.fields[key].empty()) << key << " in " << config.out;
                EXPECT_TRUE(call_of.emplace(s.fields["number"], s.fields["call"]).second);
                type_of[s.fields["number"]] = s.fields["type"];
                if (s.fields.count("default"))
                    default_value[s.fields["call"]] = s.fields["default"];
                if (s.fields["call"] == "--device") {
                    EXPECT_EQ(s.fields.count("required") == 1, interface == "dpscope");
                }
            } else {
                ASSERT_EQ(s.keyword, "value") << config.out;
                ASSERT_EQ(call_of.count(s.fields["arg"]), 1u) << "value of an unknown arg";
                values_of[s.fields["arg"]].push_back(s.fields["value"]);
                if (s.fields["default"] == "true") ++defaults_of[s.fields["arg"]];
            }
        }
        for (const char* call : {"--device", "--bus", "--baud", "--parity", "--stop-bits"}) {
            bool found = false;
            for (const auto& [number, c] : call_of)
                found = found || c == call;
            EXPECT_TRUE(found) << call;
        }
        // Wireshark 4.0 knows no editselector: every list is a selector with one default.
        for (const auto& [number, type] : type_of) {
            EXPECT_NE(type, "editselector");
            if (type == "selector") {
                EXPECT_FALSE(values_of[number].empty()) << call_of[number];
                EXPECT_EQ(defaults_of[number], 1) << call_of[number];
            }
        }
        if (interface == "dpscope-ttyUSB0") {
            EXPECT_EQ(default_value["--device"], "/dev/ttyUSB0");
        }
        // Every value offered, and every default, is one the command line accepts (the options
        // are checked whatever the action).
        for (const auto& [number, values] : values_of)
            for (const std::string& value : values) {
                auto checked = test::run_dpscope(
                    {"--extcap-dlts", "--extcap-interface", interface, call_of[number], value});
                EXPECT_EQ(checked.exit_code, 0) << call_of[number] << " " << value << checked.err;
            }
        for (const auto& [call, value] : default_value) {
            auto checked =
                test::run_dpscope({"--extcap-dlts", "--extcap-interface", interface, call, value});
            EXPECT_EQ(checked.exit_code, 0) << call << " " << value << checked.err;
        }
    }
}

TEST(ExtcapTest, BadValuesAreClearErrors) {
    struct Case {
        std::vector<std::string> args;
        std::string message;
    };
    const std::string unused = test::temp_path("unused");  // never made: every case is refused
    const std::vector<Case> cases = {
        {{"--extcap-config", "--extcap-interface", "eth0"}, "--extcap-interface eth0: not a"},
        {{"--extcap-config", "--extcap-interface", "dpscope-../etc"}, "not a dpscope interface"},
        {{"--extcap-dlts"}, "--extcap-interface is required"},
        {{"--extcap-config", "--extcap-interface", "dpscope", "--baud", "100"},
         "--baud: must be 0 (the bus's default) or a whole number from 300 to 16000000"},
        {{"--extcap-config", "--extcap-interface", "dpscope", "--baud", "20000000"},
         "not '20000000'"},
        {{"--extcap-config", "--extcap-interface", "dpscope", "--baud", "-9600"}, "--baud"},
        {{"--extcap-config", "--extcap-interface", "dpscope", "--bus", "can"}, "--bus"},
        {{"--extcap-config", "--extcap-interface", "dpscope", "--parity", "mark"}, "--parity"},
        {{"--extcap-config", "--extcap-interface", "dpscope", "--stop-bits", "3"}, "--stop-bits"},
        {{"--extcap-config", "--extcap-interface", "dpscope", "--idle-gap-ms", "70000"},
         "--idle-gap-ms"},
        {{"--extcap-config", "--extcap-interface", "dpscope", "--speed", "1"}, "--speed"},
        {{"--capture", "--extcap-interface", "dpscope", "--device", "/dev/null", "--baud",
          "1500000"},
         "--capture needs --fifo PATH"},
        {{"--capture", "--extcap-interface", "dpscope", "--fifo", unused, "--baud", "1500000"},
         "--device is required for interface dpscope"},
        {{"--capture", "--extcap-interface", "dpscope-ttyUSB0", "--fifo", unused,
          "--extcap-capture-filter", "port 80"},
         "--extcap-capture-filter 'port 80': dpscope has no capture filter"},
        // As sniff validates them: PROFIBUS needs a rate, the FC protocol takes 2400 to 115200.
        {{"--capture", "--extcap-interface", "dpscope", "--device", "/dev/null", "--fifo", unused},
         "--baud is required for PROFIBUS"},
        {{"--capture", "--extcap-interface", "dpscope", "--device", "/dev/null", "--fifo", unused,
          "--bus", "fc", "--baud", "1500000"},
         "from 2400 to 115200 baud for the FC protocol"},
    };
    for (const Case& c : cases) {
        auto result = test::run_dpscope(c.args);
        EXPECT_EQ(result.exit_code, 2) << c.args[0] << " " << c.message;
        EXPECT_NE(result.err.find(c.message), std::string::npos) << result.err;
        EXPECT_EQ(result.err.find("dpscope: error: "), 0u) << result.err;
        EXPECT_EQ(result.out, "");
    }
    EXPECT_FALSE(fs::exists(unused));
}

// Reads a fifo until its writer closes it, in a thread.
class FifoReader {
  public:
    explicit FifoReader(std::string path)
        : thread_([this, path = std::move(path)] {
              int fd = open(path.c_str(), O_RDONLY);
              if (fd < 0) return;
              char buffer[4096];
              for (;;) {
                  ssize_t n = read(fd, buffer, sizeof buffer);
                  if (n <= 0) break;
                  std::lock_guard<std::mutex> lock(mutex_);
                  bytes_.append(buffer, static_cast<std::size_t>(n));
              }
              close(fd);
          }) {}
    ~FifoReader() { join(); }
    void join() {
        if (thread_.joinable()) thread_.join();
    }
    std::string bytes() {
        std::lock_guard<std::mutex> lock(mutex_);
        return bytes_;
    }

  private:
    std::mutex mutex_;
    std::string bytes_;
    std::thread thread_;
};

TEST(ExtcapTest, CapturesIntoAFifoLiveAndEndsOnSigterm) {
    const std::string fifo = test::temp_path("extcap.fifo");
    ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
    PseudoTerminal pty;
    // --idle-gap-ms 0: the test's thread writing the pty can pause within a telegram for as long
    // as a loaded machine keeps it waiting; a gap would cut the telegram off.
    Child capture = extcap_capture({"--extcap-interface", "dpscope", "--fifo", fifo, "--device",
                                    pty.slave, "--baud", "1500000", "--idle-gap-ms", "0"});
    FifoReader reader(fifo);
    ASSERT_TRUE(wait_for_raw_mode(pty)) << capture.err();
    Session session = simulate(20);
    play(pty, session, true);
    // Each telegram is in the fifo as soon as it is decoded: all of them before any stop.
    const std::size_t expected_bytes = [&] {
        std::size_t n = 24;
        for (const auto& t : session.played)
            n += 16 + t.size();
        return n;
    }();
    EXPECT_TRUE(test::wait_until([&] { return reader.bytes().size() >= expected_bytes; }));
    EXPECT_EQ(reader.bytes().size(), expected_bytes);
    capture.signal(SIGTERM);
    EXPECT_EQ(capture.wait(), 0) << capture.err();
    reader.join();
    EXPECT_EQ(capture.err(), "");  // Wireshark shows anything on standard error as an error
    EXPECT_EQ(capture.out(), "");
    const std::string pcap = test::temp_path("from-fifo.pcap");
    test::write_text_file(pcap, reader.bytes());
    Capture got = read_capture(pcap, profibus_protocol());
    EXPECT_EQ(got.status, InputStatus::Ok);
    EXPECT_EQ(got.link_type, 147);
    EXPECT_EQ(got.telegrams, session.played);
    // The port is put back as it was found.
    termios after{};
    ASSERT_EQ(tcgetattr(pty.master, &after), 0);
    EXPECT_NE(after.c_lflag & ICANON, 0u);
}

TEST(ExtcapTest, WiresharkClosingTheFifoEndsTheCaptureQuietly) {
    const std::string fifo = test::temp_path("closed.fifo");
    ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
    PseudoTerminal pty;
    Child capture = extcap_capture(
        {"--extcap-interface", "dpscope", "--fifo", fifo, "--device", pty.slave, "--bus", "fc"});
    int fd = open(fifo.c_str(), O_RDONLY);
    ASSERT_GE(fd, 0);
    ASSERT_TRUE(wait_for_raw_mode(pty)) << capture.err();
    char header[24];
    ASSERT_EQ(read(fd, header, sizeof header), 24);
    close(fd);  // Wireshark is gone; the bus is quiet
    EXPECT_EQ(capture.wait(), 0) << capture.err();
    EXPECT_EQ(capture.err(), "");
}

TEST(ExtcapTest, CapturesIntoAFileWithTheBusTagAndEndsCompleteOnSigterm) {
    const std::string pcap = test::temp_path("extcap-file.pcap");
    PseudoTerminal pty;
    // dpscope-NAME with --device: the device given wins over /dev/NAME. (--idle-gap-ms 0: the
    // test's thread writing the pty can pause within a telegram on a loaded machine.)
    Child capture = extcap_capture({"--extcap-interface", "dpscope-ttyUSB99", "--fifo", pcap,
                                    "--device", pty.slave, "--baud", "500000", "--parity", "even",
                                    "--stop-bits", "1", "--idle-gap-ms", "0"});
    ASSERT_TRUE(wait_for_raw_mode(pty)) << capture.err();
    Session session = simulate(10);
    play(pty, session, true);
    // Each telegram is written and flushed as it comes: stopped once all of them are there.
    EXPECT_TRUE(test::wait_for_records(pcap, session.played.size())) << capture.err();
    capture.signal(SIGTERM);
    EXPECT_EQ(capture.wait(), 0) << capture.err();
    EXPECT_EQ(capture.err(), "");
    // Read with the FC protocol asked for: the file's own tag says PROFIBUS.
    auto decoded = test::run_dpscope({"decode", "-q", pcap});
    EXPECT_EQ(decoded.exit_code, 0) << decoded.err;
    Capture got = read_capture(pcap, profibus_protocol());
    EXPECT_EQ(got.status, InputStatus::Ok);
    EXPECT_EQ(got.link_type, 147);
    EXPECT_EQ(got.telegrams, session.played);
    std::vector<std::uint8_t> bytes = test::read_file(pcap);
    ASSERT_GE(bytes.size(), 24u);
    EXPECT_EQ(std::string(bytes.begin() + 8, bytes.begin() + 12), "dpsc");

    // The port of a dpscope-NAME interface is /dev/NAME: one that does not exist is named.
    auto missing = test::run_dpscope({"--capture", "--extcap-interface", "dpscope-ttyUSB99",
                                      "--fifo", test::temp_path("never.pcap"), "--baud", "9600"});
    EXPECT_NE(missing.exit_code, 0);
    EXPECT_NE(missing.err.find("/dev/ttyUSB99"), std::string::npos) << missing.err;
}

std::string find_tshark() {
    for (const char* dir : {"/usr/bin", "/usr/local/bin", "/bin"}) {
        std::string path = std::string(dir) + "/tshark";
        if (access(path.c_str(), X_OK) == 0) return path;
    }
    return {};
}

TEST(ExtcapTest, TsharkCapturesOnTheExtcapInterface) {
    const std::string tshark = find_tshark();
    if (tshark.empty()) GTEST_SKIP() << "tshark is not installed (Debian package tshark)";
    // The personal extcap folder of Wireshark 4.0 (~/.config/wireshark/extcap), in a HOME of
    // the test's own: a link named dpscope to the dpscope built with the tests. (Wireshark
    // ignores WIRESHARK_EXTCAP_DIR when run as root; it reads the personal folder either way.)
    const fs::path home = test::temp_path("tshark-home");
    fs::create_directories(home / ".config" / "wireshark" / "extcap");
    fs::create_symlink(fs::absolute(test::dpscope_executable()),
                       home / ".config" / "wireshark" / "extcap" / "dpscope");
    const std::map<std::string, std::string> env = {
        {"HOME", home.string()}, {"XDG_CONFIG_HOME", (home / ".config").string()}};

    // tshark -D lists the interface dpscope (with the personal folder's extcap).
    Child list({tshark, "-D"}, {env});
    ASSERT_EQ(list.wait(), 0) << list.err();
    EXPECT_NE(list.out().find(". dpscope (dpscope: serial bus sniffer"), std::string::npos)
        << list.out();

    const std::vector<std::string> session = {"--seed", "5", "--cycles", "30"};
    const std::string reference = test::temp_path("tshark-reference.pcap");
    std::vector<std::string> write = {"simulate", "-w", reference};
    write.insert(write.end(), session.begin(), session.end());
    ASSERT_EQ(test::run_dpscope(write).exit_code, 0);
    Capture expected = read_capture(reference, profibus_protocol());
    ASSERT_GT(expected.telegrams.size(), 50u);

    PseudoTerminal bus, adapter;
    const fs::path out = home / "live.pcapng";
    // The extcap's options are tshark preferences: extcap.<interface>.<option without dashes>.
    // No idle gap: the relay (a thread of the test) can pause within a telegram for as long as a
    // loaded machine keeps it waiting. -a duration: only a bound for a capture that never
    // completes; tshark ends at -c.
    const int duration = static_cast<int>(test::kPatienceSeconds) / 2;
    Child capture({tshark, "-i", "dpscope", "-o", "extcap.dpscope.device:" + adapter.slave, "-o",
                   "extcap.dpscope.baud:1500000", "-o", "extcap.dpscope.idlegapms:0", "-c",
                   std::to_string(expected.telegrams.size()), "-a",
                   "duration:" + std::to_string(duration), "-w", out.string()},
                  {env});
    ASSERT_TRUE(wait_for_raw_mode(adapter)) << capture.err();
    {
        Relay relay(bus.master, adapter.master);
        std::vector<std::string> play = {"simulate", "--device", bus.slave,
                                         "--baud",   "1500000",  "--as-fast-as-possible"};
        play.insert(play.end(), session.begin(), session.end());
        auto played = test::run_dpscope(play);
        ASSERT_EQ(played.exit_code, 0) << played.err;
    }
    ASSERT_EQ(capture.wait(), 0) << capture.err();
    Capture got = read_capture(out.string(), profibus_protocol());
    EXPECT_EQ(got.status, InputStatus::Ok);
    EXPECT_EQ(got.link_type, 147);
    EXPECT_EQ(got.telegrams, expected.telegrams);
    // tshark's file decodes as dpscope's own capture does (the times are the live ones).
    auto live = test::run_dpscope({"decode", "-T", "csv", "--bus", "profibus", out.string()});
    auto offline = test::run_dpscope({"decode", "-T", "csv", reference});
    ASSERT_EQ(live.exit_code, 0) << live.err;
    EXPECT_EQ(test::lines_of(live.out).size(), test::lines_of(offline.out).size());
    fs::remove_all(home);
}

}  // namespace
}  // namespace dpscope
