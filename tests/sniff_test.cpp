// dpscope sniff end to end: a simulated session (with faults and garbage) played into one end of
// a pseudo-terminal, the dpscope executable capturing on the other end.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <pty.h>
#include <signal.h>
#include <sys/ioctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <termios.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>
#include <vector>

#include "capture/bus_tag.hpp"
#include "capture/capture_writer.hpp"
#include "capture/telegram_source.hpp"
#include "protocols/fc/fc_framing_rules.hpp"
#include "protocols/profibus/bus_decoder.hpp"
#include "protocols/profibus/health/bus_health.hpp"
#include "protocols/profibus/health/stats_render.hpp"
#include "protocols/profibus/session_tracker.hpp"
#include "simulator/simulator.hpp"
#include "tests/json_parser.hpp"
#include "tests/pty_support.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::same_settings;
using test::settings_of;

using test::Capture;
using test::play;
using test::PseudoTerminal;
using test::read_capture;
using test::Relay;
using test::Session;
using test::simulate;
using test::slurp;
using test::Sniffer;
using test::Telegrams;
using test::without_answers;
using test::without_idle_gap;

// Finding kinds with counts in the jsonl output of dpscope.
std::map<std::string, int> jsonl_finding_kinds(const std::string& jsonl) {
    std::map<std::string, int> kinds;
    std::size_t at = 0;
    const std::string key = "{\"kind\":\"";
    while ((at = jsonl.find(key, at)) != std::string::npos) {
        at += key.size();
        std::string kind = jsonl.substr(at, jsonl.find('"', at) - at);
        // Problem objects have the same key; findings are the ones with a "request_frame".
        std::size_t end = jsonl.find('}', at);
        if (jsonl.substr(at, end - at).find("\"request_frame\"") != std::string::npos)
            ++kinds[kind];
    }
    return kinds;
}

std::map<std::string, int> reference_finding_kinds(const Telegrams& telegrams) {
    BusDecoder decoder;
    SessionTracker tracker;
    std::map<std::string, int> kinds;
    std::uint64_t frame = 0;
    for (const auto& t : telegrams)
        for (const Finding& f :
             tracker.track(decoder.decode(Bytes(t.data(), t.size()), kNoTime, ++frame)))
            ++kinds[std::string(finding_kind_name(f.kind))];
    return kinds;
}

SimulatorOptions faulty_session() {
    SimulatorOptions options;
    options.seed = 9;
    options.cycles = 300;
    options.slaves = {{3, 1, Dialect::Vlt}, {4, 2, Dialect::Vlt}, {5, 5, Dialect::Vlt}};
    for (const char* fault :
         {"garbage@20:3", "garbage@50:4", "fcs_error@30:5", "stacked_request@40:3",
          "request_rejected@60:4", "spm_violation@80:5", "orphan_response@100:3",
          "unknown_code@120:4", "spontaneous_message@140:5", "config_mismatch@160:3"}) {
        options.faults.push_back(*parse_fault_spec(fault));
    }
    return options;
}

TEST(SniffTest, EveryTelegramArrivesIntactAndInOrderAndTheFindingsMatch) {
    PseudoTerminal pty;
    std::string pcap = test::temp_path("capture.pcap");
    // --timeout-ms: the reference has no times and finds no time-out; live, a request still open
    // at the stop is judged by the stop's wall-clock time, however late a loaded machine makes it.
    Sniffer sniffer(without_idle_gap({"sniff", "-i", pty.slave, "--baud", "1500000", "-w", pcap,
                                      "-T", "jsonl", "--timeout-ms", "3600000"}));
    ASSERT_TRUE(sniffer.ready()) << sniffer.err();
    Session session = simulate(faulty_session());
    play(pty, session, true);
    EXPECT_TRUE(test::wait_for_records(pcap, session.expected.size())) << sniffer.err();
    sniffer.signal(SIGINT);
    ASSERT_EQ(sniffer.wait(), 0) << sniffer.err();

    Capture capture = read_capture(pcap);
    EXPECT_EQ(capture.status, InputStatus::Ok);
    EXPECT_EQ(capture.link_type, 257);
    ASSERT_EQ(capture.telegrams.size(), session.expected.size());
    for (std::size_t i = 0; i < capture.telegrams.size(); ++i)
        ASSERT_EQ(capture.telegrams[i], session.expected[i]) << "telegram " << i + 1;
    // A telegram starts no earlier than the one before it has been sent (11 bits a byte).
    for (std::size_t i = 1; i < capture.times.size(); ++i)
        EXPECT_GE(capture.times[i] - capture.times[i - 1],
                  static_cast<std::int64_t>(capture.telegrams[i - 1].size()) * 7333)
            << i;

    std::map<std::string, int> reference = reference_finding_kinds(session.expected);
    EXPECT_EQ(jsonl_finding_kinds(sniffer.out()), reference);
    EXPECT_EQ(reference["stacked_request"], 1);
    EXPECT_EQ(reference["fcs_error"], 1);
    EXPECT_EQ(reference["request_rejected"], 1);
    // The garbage was skipped and said so, not taken for telegrams.
    EXPECT_NE(sniffer.err().find("no start delimiter"), std::string::npos) << sniffer.err();
    EXPECT_NE(sniffer.err().find(std::to_string(capture.telegrams.size()) + " telegrams"),
              std::string::npos)
        << sniffer.err();
    std::remove(pcap.c_str());
}

TEST(SniffTest, PacedAt12MbitNothingIsLost) {
    PseudoTerminal pty;
    std::string pcap = test::temp_path("paced.pcap");
    Sniffer sniffer(
        without_idle_gap({"sniff", "-i", pty.slave, "--baud", "12000000", "-w", pcap, "-q"}));
    ASSERT_TRUE(sniffer.ready()) << sniffer.err();
    SimulatorOptions options;
    options.seed = 4;
    options.baud = 12'000'000;
    options.cycle_us = 300;
    options.cycles = 1000;
    Session session = simulate(options);
    auto start = std::chrono::steady_clock::now();
    play(pty, session, false);
    auto played = std::chrono::steady_clock::now() - start;
    EXPECT_TRUE(test::wait_for_records(pcap, session.expected.size())) << sniffer.err();
    sniffer.signal(SIGTERM);
    ASSERT_EQ(sniffer.wait(), 0) << sniffer.err();
    Capture capture = read_capture(pcap);
    ASSERT_EQ(capture.telegrams, session.expected);
    // Played at the pace of the timestamps (about 0.3 s), not at once. (How much longer it took
    // depends on the machine's load: not judged.)
    double scheduled = static_cast<double>(session.times.back() - session.times.front()) / 1e9;
    double seconds = std::chrono::duration<double>(played).count();
    EXPECT_GE(seconds, scheduled * 0.95);
    // The summary (-q) counts the same telegrams.
    EXPECT_NE(sniffer.out().find("telegrams: " + std::to_string(session.expected.size())),
              std::string::npos)
        << sniffer.out();
    std::remove(pcap.c_str());
}

TEST(SniffTest, SigintInTheMiddleOfATelegramKeepsAValidCompleteFile) {
    PseudoTerminal pty;
    std::string pcap = test::temp_path("interrupted.pcap");
    Sniffer sniffer(
        {"sniff", "-i", pty.slave, "--baud", "1500000", "-w", pcap, "-q", "--idle-gap-ms", "0"});
    ASSERT_TRUE(sniffer.ready()) << sniffer.err();
    SimulatorOptions options;
    options.cycles = 50;
    Session session = simulate(options);
    const std::size_t whole = 120;
    play(pty, session, true, whole);
    const std::vector<std::uint8_t>& next = session.played[whole];
    ASSERT_GT(next.size(), 4u);
    pty.write(std::vector<std::uint8_t>(next.begin(), next.begin() + 4));  // half a telegram
    // The whole ones written, the half one is in the port's buffers (written before them) or
    // read: the stop takes what the driver still holds.
    EXPECT_TRUE(test::wait_for_records(pcap, whole)) << sniffer.err();
    sniffer.signal(SIGINT);
    ASSERT_EQ(sniffer.wait(), 0) << sniffer.err();
    Capture capture = read_capture(pcap);
    EXPECT_EQ(capture.status, InputStatus::Ok);
    ASSERT_EQ(capture.telegrams.size(), whole);
    for (std::size_t i = 0; i < whole; ++i)
        EXPECT_EQ(capture.telegrams[i], session.expected[i]);
    EXPECT_NE(sniffer.err().find("skipped 4 bytes: telegram cut off"), std::string::npos)
        << sniffer.err();
    std::remove(pcap.c_str());
}

TEST(SniffTest, DeviceVanishingEndsWithExitCode5AndAValidFile) {
    PseudoTerminal pty;
    std::string pcap = test::temp_path("vanished.pcap");
    Sniffer sniffer(
        without_idle_gap({"sniff", "-i", pty.slave, "--baud", "1500000", "-w", pcap, "-q"}));
    ASSERT_TRUE(sniffer.ready()) << sniffer.err();
    SimulatorOptions options;
    options.cycles = 20;
    Session session = simulate(options);
    play(pty, session, true);
    // A hang-up discards what the port has not handed out yet: unplugged once all was read.
    EXPECT_TRUE(test::wait_for_records(pcap, session.expected.size())) << sniffer.err();
    pty.close_master();  // the adapter is unplugged
    EXPECT_EQ(sniffer.wait(), 5) << sniffer.err();
    EXPECT_NE(sniffer.err().find("the device went away"), std::string::npos) << sniffer.err();
    Capture capture = read_capture(pcap);
    EXPECT_EQ(capture.status, InputStatus::Ok);
    EXPECT_EQ(capture.telegrams, session.expected);
    std::remove(pcap.c_str());
}

TEST(SniffTest, StopsAfterCountAndAfterDuration) {
    {
        PseudoTerminal pty;
        Sniffer sniffer(
            without_idle_gap({"sniff", "-i", pty.slave, "--baud", "1500000", "-c", "10"}));
        ASSERT_TRUE(sniffer.ready()) << sniffer.err();
        SimulatorOptions options;
        options.cycles = 20;
        play(pty, simulate(options), true);
        ASSERT_EQ(sniffer.wait(), 0) << sniffer.err();
        std::string out = sniffer.out();
        EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 10) << out;
    }
    {
        PseudoTerminal pty;
        auto start = std::chrono::steady_clock::now();
        Sniffer sniffer({"sniff", "-i", pty.slave, "--baud", "1500000", "--duration", "0.5"});
        ASSERT_EQ(sniffer.wait(), 0) << sniffer.err();
        double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        EXPECT_GE(seconds, 0.5);  // (an ignored --duration: wait() gives up, -1)
    }
}

// -Y shows only what the filter selects, live (docs/filter.md); the capture is counted whole.
TEST(SniffTest, DisplayFilterSelectsTheLiveLines) {
    PseudoTerminal pty;
    Sniffer sniffer(
        without_idle_gap({"sniff", "-i", pty.slave, "--baud", "1500000", "-c", "150", "-Y",
                          "dpscope.dp.service == \"Data_Exchange\" && "
                          "dpscope.direction == request"}));
    ASSERT_TRUE(sniffer.ready()) << sniffer.err();
    SimulatorOptions options;
    options.cycles = 60;
    play(pty, simulate(options), true);
    ASSERT_EQ(sniffer.wait(), 0) << sniffer.err();
    const std::string out = sniffer.out();
    // -c counts what is read: 150 telegrams, a third of them Data_Exchange requests.
    ASSERT_GT(std::count(out.begin(), out.end(), '\n'), 20) << out;
    ASSERT_LT(std::count(out.begin(), out.end(), '\n'), 100) << out;
    std::size_t start = 0;
    while (start < out.size()) {
        const std::size_t end = out.find('\n', start);
        const std::string line = out.substr(start, end - start);
        EXPECT_NE(line.find("Data_Exchange  req"), std::string::npos) << line;
        start = end + 1;
    }
}

// --trigger live: the window around the one stacked request of the faulty session goes to its own
// pcapng file in --trigger-dir, named after the finding and its slave.
TEST(SniffTest, ATriggerWritesTheWindowAroundTheEvent) {
    PseudoTerminal pty;
    const std::string folder = test::temp_path("triggers");
    std::filesystem::remove_all(folder);
    Session session = simulate(faulty_session());
    Sniffer sniffer(without_idle_gap(
        {"sniff", "-i", pty.slave, "--baud", "1500000", "-q", "--timeout-ms", "3600000",
         "--trigger", "dpscope.finding == stacked_request", "--pre", "3600", "--post", "3600",
         "--trigger-dir", folder, "-c", std::to_string(session.expected.size())}));
    ASSERT_TRUE(sniffer.ready()) << sniffer.err();
    play(pty, session, true);
    ASSERT_EQ(sniffer.wait(), 0) << sniffer.err();
    EXPECT_NE(sniffer.err().find("--trigger: 1 window written in " + folder), std::string::npos)
        << sniffer.err();
    std::vector<std::string> files;
    for (const auto& entry : std::filesystem::directory_iterator(folder))
        files.push_back(entry.path().string());
    ASSERT_EQ(files.size(), 1u);
    EXPECT_NE(files[0].find("-stacked_request-3.pcapng"), std::string::npos) << files[0];
    Capture window = read_capture(files[0]);
    EXPECT_EQ(window.status, InputStatus::Ok);
    // An hour before and after it: the whole session, however slowly it was played.
    EXPECT_EQ(window.telegrams.size(), session.expected.size());
    std::filesystem::remove_all(folder);
}

// --status-interval / --status-file: a status line for monitoring, on standard error and in a
// file replaced whole; the last one at the end counts every telegram and names the last event.
TEST(SniffTest, StatusLinesForMonitoring) {
    PseudoTerminal pty;
    const std::string status = test::temp_path("status.txt");
    Session session = simulate(faulty_session());
    Sniffer sniffer(
        without_idle_gap({"sniff", "-i", pty.slave, "--baud", "1500000", "-q", "--timeout-ms",
                          "3600000", "--status-interval", "0.1", "--status-file", status, "-c",
                          std::to_string(session.expected.size())}));
    ASSERT_TRUE(sniffer.ready()) << sniffer.err();
    play(pty, session, true);
    ASSERT_EQ(sniffer.wait(), 0) << sniffer.err();
    const std::string total = std::to_string(session.expected.size());
    EXPECT_NE(sniffer.err().find("dpscope: status: " + total + " telegrams, "), std::string::npos)
        << sniffer.err();
    const std::vector<std::uint8_t> bytes = test::read_file(status);
    const std::string line(bytes.begin(), bytes.end());
    EXPECT_EQ(line.rfind("dpscope: status: " + total + " telegrams, ", 0), 0u) << line;
    EXPECT_NE(line.find("last event "), std::string::npos) << line;
    EXPECT_EQ(line.find("last event none"), std::string::npos) << line;  // the faults were seen
    EXPECT_EQ(std::count(line.begin(), line.end(), '\n'), 1);
    std::remove(status.c_str());
    auto same =
        test::run_dpscope({"sniff", "-i", pty.slave, "--baud", "1500000", "--status-file", "-"});
    EXPECT_EQ(same.exit_code, 2);
    auto range = test::run_dpscope(
        {"sniff", "-i", pty.slave, "--baud", "1500000", "--status-interval", "0"});
    EXPECT_EQ(range.exit_code, 2);
}

TEST(SniffTest, RotationLosesNothingAtTheSeams) {
    PseudoTerminal pty;
    std::string pcap = test::temp_path("rotated.pcap");
    Sniffer sniffer(without_idle_gap({"sniff", "-i", pty.slave, "--baud", "1500000", "-w", pcap,
                                      "-q", "--rotate-size", "2000"}));
    ASSERT_TRUE(sniffer.ready()) << sniffer.err();
    SimulatorOptions options;
    options.cycles = 40;
    Session session = simulate(options);
    play(pty, session, true);
    EXPECT_TRUE(test::wait_for_records(pcap, session.expected.size(), true)) << sniffer.err();
    sniffer.signal(SIGINT);
    ASSERT_EQ(sniffer.wait(), 0) << sniffer.err();
    Telegrams all;
    unsigned files = 0;
    for (unsigned index = 1;; ++index) {
        std::string name = rotated_file_name(pcap, index);
        if (access(name.c_str(), F_OK) != 0) break;
        ++files;
        EXPECT_LE(test::read_file(name).size(), 2000u) << name;
        Capture part = read_capture(name);
        EXPECT_EQ(part.status, InputStatus::Ok);
        EXPECT_FALSE(part.telegrams.empty()) << name;
        all.insert(all.end(), part.telegrams.begin(), part.telegrams.end());
        std::remove(name.c_str());
    }
    EXPECT_GT(files, 3u);
    EXPECT_EQ(all, session.expected);
}

// --ring 3: the last three files stay, each a readable capture; the telegrams they hold are the
// end of the session, and the ring counts the ones it removed, so every telegram is accounted for.
TEST(SniffTest, TheRingKeepsTheLastFilesAndAccountsForTheRest) {
    PseudoTerminal pty;
    std::string pcap = test::temp_path("ring.pcap");
    SimulatorOptions options;
    options.cycles = 40;
    Session session = simulate(options);
    const std::size_t total = session.expected.size();
    // -c: the sniffer stops by itself once it has read the whole session.
    Sniffer sniffer(
        without_idle_gap({"sniff", "-i", pty.slave, "--baud", "1500000", "-w", pcap, "-q",
                          "--rotate-size", "2000", "--ring", "3", "-c", std::to_string(total)}));
    ASSERT_TRUE(sniffer.ready()) << sniffer.err();
    play(pty, session, true);
    ASSERT_EQ(sniffer.wait(), 0) << sniffer.err();
    Telegrams kept;
    unsigned files = 0;
    for (unsigned index = 1; index < 400; ++index) {
        std::string name = rotated_file_name(pcap, index);
        if (access(name.c_str(), F_OK) != 0) continue;
        ++files;
        Capture part = read_capture(name);
        EXPECT_EQ(part.status, InputStatus::Ok) << name;
        kept.insert(kept.end(), part.telegrams.begin(), part.telegrams.end());
        std::remove(name.c_str());
    }
    EXPECT_EQ(files, 3u);
    ASSERT_LT(kept.size(), total);
    // The tail of the session, whole and in order.
    EXPECT_TRUE(std::equal(kept.begin(), kept.end(), session.expected.end() - kept.size()));
    // "... it removed the N oldest, which held M telegrams": M + kept = the session.
    const std::string err = sniffer.err();
    const std::size_t held = err.find("which held ");
    ASSERT_NE(held, std::string::npos) << err;
    const std::size_t removed = std::stoul(err.substr(held + 11));
    EXPECT_EQ(removed + kept.size(), total) << err;
}

TEST(SniffTest, RotationByTimeSpan) {
    PseudoTerminal pty;
    std::string pcap = test::temp_path("timed.pcap");
    Sniffer sniffer(without_idle_gap({"sniff", "-i", pty.slave, "--baud", "1500000", "-w", pcap,
                                      "-q", "--rotate-seconds", "0.25"}));
    ASSERT_TRUE(sniffer.ready()) << sniffer.err();
    SimulatorOptions options;
    options.cycles = 500;  // 1 s of bus time, played at its pace
    Session session = simulate(options);
    play(pty, session, false);
    EXPECT_TRUE(test::wait_for_records(pcap, session.expected.size(), true)) << sniffer.err();
    sniffer.signal(SIGINT);
    ASSERT_EQ(sniffer.wait(), 0) << sniffer.err();
    Telegrams all;
    std::vector<std::int64_t> times;
    unsigned files = 0;
    for (unsigned index = 1;; ++index) {
        std::string name = rotated_file_name(pcap, index);
        if (access(name.c_str(), F_OK) != 0) break;
        ++files;
        Capture part = read_capture(name);
        EXPECT_EQ(part.status, InputStatus::Ok);
        ASSERT_FALSE(part.times.empty()) << name;
        EXPECT_LT(part.times.back() - part.times.front(), 250'000'000) << name;
        all.insert(all.end(), part.telegrams.begin(), part.telegrams.end());
        times.insert(times.end(), part.times.begin(), part.times.end());
        std::remove(name.c_str());
    }
    EXPECT_EQ(all, session.expected);
    // As many files as the rule makes of the times captured (the times are when the telegrams
    // arrived, so a loaded machine stretches them): a file starts with the first telegram 0.25 s
    // or more after the start of the one before, so neighbouring starts are at least 0.25 s and
    // at most 0.25 s plus the longest pause between two telegrams apart.
    ASSERT_FALSE(times.empty());
    std::int64_t longest_pause = 0;
    for (std::size_t i = 1; i < times.size(); ++i)
        longest_pause = std::max(longest_pause, times[i] - times[i - 1]);
    const std::int64_t span = times.back() - times.front();
    EXPECT_GT(files, 1u);
    EXPECT_LE(files, span / 250'000'000 + 1) << span;
    EXPECT_GE(files, span / (250'000'000 + longest_pause)) << span << ", " << longest_pause;
}

// `simulate --device` writes into a tty: here the slave side of a pty, read on the master once
// the simulator has ended. Everything it wrote, then the end: the master's read fails (EIO) only
// when the slave side is closed and nothing written into it is left unread.
std::vector<std::uint8_t> read_to_the_end(int fd) {
    std::vector<std::uint8_t> got;
    fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK);
    bool ended = test::wait_until([&] {
        std::uint8_t buffer[4096];
        for (;;) {
            ssize_t n = read(fd, buffer, sizeof buffer);
            if (n > 0)
                got.insert(got.end(), buffer, buffer + n);
            else
                return n < 0 && errno == EIO;
        }
    });
    EXPECT_TRUE(ended) << "the device still had no end after " << got.size() << " bytes";
    return got;
}

TEST(SniffTest, SimulatePlaysOntoADeviceAndReplaysACapture) {
    {
        PseudoTerminal pty;
        auto played = test::run_dpscope({"simulate", "--device", pty.slave, "--baud", "1500000",
                                         "--cycles", "20", "--as-fast-as-possible", "-v"});
        ASSERT_EQ(played.exit_code, 0) << played.err;
        auto raw = test::run_dpscope({"simulate", "-w", "-", "-F", "raw", "--cycles", "20"});
        std::vector<std::uint8_t> expected(raw.out.begin(), raw.out.end());
        EXPECT_EQ(read_to_the_end(pty.master), expected);
        EXPECT_NE(played.err.find("played "), std::string::npos) << played.err;
    }
    {
        PseudoTerminal pty;
        auto start = std::chrono::steady_clock::now();
        auto played = test::run_dpscope({"simulate", "--device", pty.slave, "--baud", "1500000",
                                         "--replay", "samples/faults.pcap"});
        double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        ASSERT_EQ(played.exit_code, 0) << played.err;
        Capture capture = read_capture(test::source_dir() + "/samples/faults.pcap");
        std::vector<std::uint8_t> expected;
        for (const auto& t : capture.telegrams)
            expected.insert(expected.end(), t.begin(), t.end());
        EXPECT_EQ(read_to_the_end(pty.master), expected);
        // Replayed at the pace of its timestamps (123 ms), not at once.
        double span = static_cast<double>(capture.times.back() - capture.times.front()) / 1e9;
        EXPECT_GE(seconds, span);
    }
    auto neither = test::run_dpscope({"simulate", "--cycles", "5"});
    EXPECT_EQ(neither.exit_code, 2);
    EXPECT_NE(neither.err.find("give either -w FILE or --device PATH"), std::string::npos);
}

TEST(SniffTest, PcapToStandardOutputWithUser0LinkType) {
    PseudoTerminal pty;
    Sniffer sniffer(without_idle_gap(
        {"sniff", "-i", pty.slave, "--baud", "500000", "-w", "-", "--linktype", "user0"}));
    ASSERT_TRUE(sniffer.ready()) << sniffer.err();
    SimulatorOptions options;
    options.cycles = 10;
    Session session = simulate(options);
    play(pty, session, true);
    EXPECT_TRUE(test::wait_for_records(sniffer.out_path(), session.expected.size()))
        << sniffer.err();
    sniffer.signal(SIGINT);
    ASSERT_EQ(sniffer.wait(), 0) << sniffer.err();
    std::string path = test::temp_path("stdout.pcap");
    test::write_text_file(path, sniffer.out());
    Capture capture = read_capture(path);
    EXPECT_EQ(capture.link_type, 147);
    EXPECT_EQ(capture.telegrams, session.expected);
    // The decoded lines went to standard error instead.
    EXPECT_NE(sniffer.err().find("Data_Exchange"), std::string::npos);
    std::remove(path.c_str());
}

TEST(SniffTest, FullDiskStopsWithExitCode4AndAValidFile) {
    PseudoTerminal pty;
    std::string pcap = test::temp_path("full.pcap");
    // A file size limit makes writes fail as on a full disk.
    Sniffer sniffer(
        without_idle_gap({"sniff", "-i", pty.slave, "--baud", "1500000", "-w", pcap, "-q"}), 3000);
    ASSERT_TRUE(sniffer.ready()) << sniffer.err();
    SimulatorOptions options;
    options.cycles = 30;  // about 7 KB: more than the limit, less than the pty buffers hold
    Session session = simulate(options);
    play(pty, session, false);
    EXPECT_EQ(sniffer.wait(), 4) << sniffer.err();
    EXPECT_NE(sniffer.err().find("write failed"), std::string::npos) << sniffer.err();
    Capture capture = read_capture(pcap);
    EXPECT_EQ(capture.status, InputStatus::Ok);  // whole records only
    EXPECT_GT(capture.telegrams.size(), 10u);
    EXPECT_LE(test::read_file(pcap).size(), 3000u);
    for (std::size_t i = 0; i < capture.telegrams.size(); ++i)
        EXPECT_EQ(capture.telegrams[i], session.expected[i]);
    std::remove(pcap.c_str());
}

TEST(SniffTest, ReportAtTheEnd) {
    PseudoTerminal pty;
    const std::string pcap = test::temp_path("report.pcap");  // to see when all has arrived
    Sniffer sniffer(without_idle_gap(
        {"sniff", "-i", pty.slave, "--baud", "1500000", "-q", "--report", "-w", pcap}));
    ASSERT_TRUE(sniffer.ready()) << sniffer.err();
    SimulatorOptions options = faulty_session();
    options.cycles = 200;
    Session session = simulate(options);
    play(pty, session, true);
    EXPECT_TRUE(test::wait_for_records(pcap, session.expected.size())) << sniffer.err();
    sniffer.signal(SIGINT);
    EXPECT_EQ(sniffer.wait(), 1) << sniffer.err();  // errors found, --fail-on error
    std::string out = sniffer.out();
    EXPECT_NE(out.find("telegrams: "), std::string::npos) << out;  // the summary (-q) ...
    EXPECT_NE(out.find("FAIL"), std::string::npos) << out;         // ... and the text report
}

// The lines of `text` from the first one starting with `from` on.
std::vector<std::string> lines_from(const std::string& text, const std::string& from) {
    std::vector<std::string> all = test::lines_of(text);
    auto first = std::find_if(all.begin(), all.end(),
                              [&](const std::string& l) { return l.rfind(from, 0) == 0; });
    return {first, all.end()};
}

std::vector<std::string> lines_with(const std::string& text, const std::string& part) {
    std::vector<std::string> found;
    for (const std::string& l : test::lines_of(text))
        if (l.find(part) != std::string::npos) found.push_back(l);
    return found;
}

TEST(SniffTest, DpV1SlavesAreDecodedAndTrackedLive) {
    const std::vector<std::string> session = {"--seed",   "23",
                                              "--cycles", "30",
                                              "--slave",  "3:3:dpv1",
                                              "--slave",  "4:2",
                                              "--slave",  "5:1:vlt:dpv1",
                                              "--fault",  "dpv1_stacked_request@3:3",
                                              "--fault",  "dpv1_reference_mismatch@3:5",
                                              "--fault",  "dpv1_negative_response@8:3",
                                              "--fault",  "dpv1_unexpected_response_id@8:5",
                                              "--fault",  "dpv1_parameter_count_mismatch@14:3",
                                              "--fault",  "dpv1_length_error@14:5",
                                              "--fault",  "dpv1_orphan_response@20:3",
                                              "--fault",  "dpv1_error_pdu@20:5"};
    const std::string reference = test::temp_path("dpv1-reference.pcap");
    const std::string pcap = test::temp_path("dpv1-live.pcap");
    std::vector<std::string> write = {"simulate", "-w", reference};
    write.insert(write.end(), session.begin(), session.end());
    ASSERT_EQ(test::run_dpscope(write).exit_code, 0);

    PseudoTerminal bus, adapter;
    // --timeout-ms: a request still open at the stop is judged live by the stop's wall-clock
    // time, however late a loaded machine makes it, and by `dpscope report` at the last telegram.
    const std::vector<std::string> patient = {"--timeout-ms", "3600000"};
    Sniffer sniffer(without_idle_gap({"sniff", "-i", adapter.slave, "--baud", "1500000", "-w", pcap,
                                      "--report", patient[0], patient[1]}));
    ASSERT_TRUE(sniffer.ready()) << sniffer.err();
    Capture expected = read_capture(reference);
    {
        Relay relay(bus.master, adapter.master);
        std::vector<std::string> play = {"simulate", "--device", bus.slave,
                                         "--baud",   "1500000",  "--as-fast-as-possible"};
        play.insert(play.end(), session.begin(), session.end());
        auto played = test::run_dpscope(play);
        ASSERT_EQ(played.exit_code, 0) << played.err;
    }
    EXPECT_TRUE(test::wait_for_records(pcap, expected.telegrams.size())) << sniffer.err();
    sniffer.signal(SIGINT);
    EXPECT_EQ(sniffer.wait(), 1) << sniffer.err();  // errors found, --fail-on error
    const std::string out = sniffer.out();

    // Every telegram arrived, the DP-V1 ones among them.
    Capture capture = read_capture(pcap);
    EXPECT_EQ(capture.status, InputStatus::Ok);
    ASSERT_EQ(capture.telegrams, expected.telegrams);
    auto decoded = test::run_dpscope({"decode", pcap});
    ASSERT_EQ(decoded.exit_code, 0) << decoded.err;
    std::vector<std::string> dpv1 = lines_with(decoded.out, "MSAC_C1");
    EXPECT_GT(dpv1.size(), 60u);
    // The live decode shows them as `dpscope decode` does, PROFIdrive parameters and findings.
    EXPECT_EQ(lines_with(out, "MSAC_C1"), dpv1);
    EXPECT_GT(lines_with(out, "| PROFIdrive req ").size(), 10u) << out;
    EXPECT_FALSE(lines_with(out, "| PROFIdrive rsp ").empty()) << out;
    EXPECT_FALSE(lines_with(out, "[error dpv1_stacked_request]").empty()) << out;

    // The report at the end: the same per-slave sections (the DP-V1 ones included) and the
    // same findings as `dpscope report` on the written capture.
    // (At the port's rate, as the live report's bus-health section has it.)
    auto offline = test::run_dpscope({"report", "--baud", "1500000", patient[0], patient[1], pcap});
    EXPECT_EQ(offline.exit_code, 1) << offline.err;
    std::vector<std::string> live_report = lines_from(out, "Slave ");
    ASSERT_GT(live_report.size(), 40u) << out;
    EXPECT_EQ(live_report, lines_from(offline.out, "Slave ")) << out;
    EXPECT_EQ(lines_with(out, ": DP-V1 parameter access").size(), 2u) << out;
    std::vector<std::string> findings = lines_from(out, "Findings (");
    for (const char* kind :
         {"dpv1_stacked_request", "dpv1_reference_mismatch", "dpv1_negative_response",
          "dpv1_unexpected_response_id", "dpv1_parameter_count_mismatch", "dpv1_orphan_response",
          "dpv1_error_pdu"}) {
        EXPECT_TRUE(std::any_of(findings.begin(), findings.end(),
                                [&](const std::string& l) {
                                    return l.find(std::string(" ") + kind + " ") !=
                                           std::string::npos;
                                }))
            << kind << "\n"
            << out;
    }
    std::remove(pcap.c_str());
    std::remove(reference.c_str());
}

// The kinds in the "Findings (" table of a text report and how often each one comes.
std::map<std::string, int> finding_kinds(const std::string& report) {
    std::map<std::string, int> kinds;
    std::vector<std::string> table = lines_from(report, "Findings (");
    for (std::size_t i = 2; i < table.size(); ++i) {  // after the title and the column heads
        std::istringstream fields(table[i]);
        std::string frame, time, severity, kind;
        if (!(fields >> frame >> time >> severity >> kind)) break;
        ++kinds[kind];
    }
    return kinds;
}

// The FC protocol live: four drives in both address formats and one fault of every FC kind,
// played in real time onto one pty and captured by `sniff --bus fc` (8E1, the FC default) on
// another. 115200 baud on both sides keeps the session under two seconds; the drives answer 2 to
// 8 ms after a command, the late answer comes 45 to 90 ms after it (the check is at 20 ms).
TEST(SniffTest, FcDrivesAreDecodedAndTrackedLive) {
    std::vector<std::string> session = {"--bus",    "fc", "--seed", "33",
                                        "--cycles", "40", "--baud", "115200"};
    for (const char* drive : {"1", "2:1-31", "17:1-31", "100"}) {
        session.push_back("--drive");
        session.push_back(drive);
    }
    for (const char* fault :
         {"fc_stacked_request@4:1", "fc_no_response@8:2", "fc_late_response@12:17",
          "fc_mismatched_response@16:100", "fc_unexpected_response_type@20:1",
          "fc_command_rejected@24:2", "fc_bcc_error@28:17", "malformed_telegram@32:100"}) {
        session.push_back("--fault");
        session.push_back(fault);
    }
    const std::string reference = test::temp_path("fc-reference.pcap");
    const std::string pcap = test::temp_path("fc-live.pcap");
    std::vector<std::string> write = {"simulate", "-w", reference};
    write.insert(write.end(), session.begin(), session.end());
    auto written = test::run_dpscope(write);
    ASSERT_EQ(written.exit_code, 0) << written.err;

    PseudoTerminal bus, adapter;
    // No idle gap: the master's next command follows the cut response within a few ms, but the
    // relay on a loaded machine can hold bytes back for any time, a telegram's last ones too.
    Sniffer sniffer(without_idle_gap(
        {"sniff", "-i", adapter.slave, "--bus", "fc", "--baud", "115200", "-w", pcap, "--report"}));
    ASSERT_TRUE(sniffer.ready()) << sniffer.err();
    EXPECT_NE(sniffer.err().find("at 115200 baud 8E1"), std::string::npos) << sniffer.err();
    Capture expected = read_capture(reference);
    {
        Relay relay(bus.master, adapter.master);
        // In real time (no --as-fast-as-possible): the response times are the session's.
        std::vector<std::string> play = {"simulate", "--device", bus.slave};
        play.insert(play.end(), session.begin(), session.end());
        auto played = test::run_dpscope(play);
        ASSERT_EQ(played.exit_code, 0) << played.err;
    }
    // All but the response cut short (below).
    EXPECT_TRUE(test::wait_for_records(pcap, expected.telegrams.size() - 1)) << sniffer.err();
    sniffer.signal(SIGINT);
    EXPECT_EQ(sniffer.wait(), 1) << sniffer.err();  // errors found, --fail-on error
    const std::string out = sniffer.out();
    const std::string err = sniffer.err();

    // Every telegram arrived in order, but the response cut short (malformed_telegram): in a byte
    // stream nothing ends it, the framer takes the next command's first bytes for its rest, finds
    // the BCC wrong and skips its bytes (a simulated capture has its own record for it).
    Capture capture = read_capture(pcap);
    EXPECT_EQ(capture.status, InputStatus::Ok);
    EXPECT_EQ(capture.link_type, kLinkTypeUser0);
    ASSERT_EQ(capture.telegrams.size() + 1, expected.telegrams.size());
    std::size_t cut = 0;
    while (cut < capture.telegrams.size() && capture.telegrams[cut] == expected.telegrams[cut])
        ++cut;
    ASSERT_LT(cut, expected.telegrams.size());
    const std::vector<std::uint8_t> short_one = expected.telegrams[cut];
    ASSERT_GE(short_one.size(), 2u);
    EXPECT_LT(short_one.size(), std::size_t{short_one[1]} + 2);  // shorter than its LGE says
    expected.telegrams.erase(expected.telegrams.begin() + static_cast<std::ptrdiff_t>(cut));
    EXPECT_EQ(capture.telegrams, expected.telegrams);
    EXPECT_NE(err.find("skipped " + std::to_string(short_one.size()) +
                       " bytes: BCC wrong and no telegram follows"),
              std::string::npos)
        << err;

    // The capture records its bus: decode reads it as FC without --bus, and says nothing of it
    // (the line rate is not recorded: --baud gives it).
    auto plain = test::run_dpscope({"decode", "--baud", "115200", pcap});
    EXPECT_EQ(plain.exit_code, 0) << plain.err;
    EXPECT_EQ(plain.err, "");
    EXPECT_EQ(lines_with(plain.out, " FC  ").size(), capture.telegrams.size()) << plain.out;
    // The live decode is `dpscope decode` of the written capture, line by line: the times are
    // the capture's. --baud: the response time starts at the command's last byte.
    auto decoded = test::run_dpscope({"decode", "--baud", "115200", pcap});
    ASSERT_EQ(decoded.exit_code, 0) << decoded.err;
    std::vector<std::string> lines = lines_with(decoded.out, " FC  ");
    ASSERT_EQ(lines.size(), capture.telegrams.size());
    EXPECT_EQ(lines_with(out, " FC  "), lines);
    EXPECT_FALSE(lines_with(out, "(1-31)").empty()) << out;  // both address formats
    EXPECT_FALSE(lines_with(out, "(1-126)").empty()) << out;
    EXPECT_FALSE(lines_with(out, "[error fc_stacked_request]").empty()) << out;

    // The report at the end: the same per-drive sections and findings as `dpscope report` on the
    // written capture.
    auto offline = test::run_dpscope({"report", "--baud", "115200", pcap});
    EXPECT_EQ(offline.exit_code, 1) << offline.err;
    std::vector<std::string> live_report = lines_from(out, "Drive ");
    ASSERT_GT(live_report.size(), 25u) << out;
    EXPECT_EQ(live_report, lines_from(offline.out, "Drive ")) << out;
    for (const char* drive : {"Drive 1 ", "Drive 2 ", "Drive 17 ", "Drive 100 "})
        EXPECT_EQ(lines_with(out, drive).size(), 1u) << drive << "\n" << out;

    // ... and the findings of the simulated session (`dpscope report` of the reference), kind by
    // kind, where they do not depend on the times. The cut response is no malformed_telegram
    // live: its command went unanswered (fc_no_response) before the master's next telegram.
    // fc_late_response depends on the times, and live they are when the bytes reached sniff:
    // on a loaded machine a 2 to 8 ms answer can reach it late, and the injected late answer
    // (45 to 90 ms) together with its command, on time. So drive 17's answers are judged
    // against the times the capture holds, computed here.
    auto simulated = test::run_dpscope({"report", "--baud", "115200", reference});
    EXPECT_EQ(simulated.exit_code, 1) << simulated.err;
    std::map<std::string, int> live_kinds = finding_kinds(out);
    std::map<std::string, int> reference_kinds = finding_kinds(simulated.out);
    EXPECT_EQ(live_kinds, finding_kinds(offline.out));
    for (const char* kind : {"fc_stacked_request", "fc_no_response", "fc_late_response",
                             "fc_mismatched_response", "fc_unexpected_response_type",
                             "fc_command_rejected", "fc_bcc_error", "malformed_telegram"})
        EXPECT_GE(reference_kinds[kind], 1) << kind << "\n" << simulated.out;
    for (const char* kind : {"fc_stacked_request", "fc_mismatched_response",
                             "fc_unexpected_response_type", "fc_command_rejected", "fc_bcc_error"})
        EXPECT_EQ(live_kinds[kind], reference_kinds[kind]) << kind << "\n" << out;
    EXPECT_EQ(live_kinds["fc_no_response"], reference_kinds["fc_no_response"] + 1) << out;
    EXPECT_EQ(live_kinds["malformed_telegram"], 0) << out;
    const auto fc_address = [](const std::vector<std::uint8_t>& t) {
        return t.size() < 3 ? -1 : (t[2] & 0x80) != 0 ? t[2] & 0x7F : t[2] & 0x1F;
    };
    const auto intact = [](const std::vector<std::uint8_t>& t) {
        std::uint8_t bcc = 0;
        for (std::uint8_t b : t)
            bcc ^= b;
        return bcc == 0;  // the BCC makes the XOR of the whole telegram 0
    };
    bool late_in_capture = false;  // a command to drive 17 answered more than 20 ms after it
    for (std::size_t i = 1; i < capture.telegrams.size(); ++i) {
        const auto& command = capture.telegrams[i - 1];
        const auto& answer = capture.telegrams[i];
        if (fc_address(command) != 17 || fc_address(answer) != 17 || !intact(answer)) continue;
        const std::int64_t on_the_wire =
            static_cast<std::int64_t>(command.size()) * 11 * 1'000'000'000 / 115200;
        late_in_capture |= capture.times[i] - capture.times[i - 1] - on_the_wire > 20'000'000;
    }
    bool late_found = false;
    for (const std::string& l : lines_from(out, "Findings ("))
        late_found |= l.find(" fc_late_response ") != std::string::npos &&
                      l.find(" 0 / 17 ") != std::string::npos;
    EXPECT_EQ(late_found, late_in_capture) << out;
    std::remove(pcap.c_str());
    std::remove(reference.c_str());
}

TEST(SniffTest, Vlt2000DrivesAreDecodedAndTrackedLive) {
    std::vector<std::string> session = {"--bus",    "vlt2000", "--seed", "41",
                                        "--cycles", "40",      "--baud", "115200"};
    for (const char* drive : {"1", "2", "17", "31"}) {
        session.push_back("--drive");
        session.push_back(drive);
    }
    for (const char* fault : {"vlt2000_stacked_request@3:1", "vlt2000_no_response@7:2",
                              "vlt2000_unexpected_reply@10:17", "vlt2000_mismatched_response@14:31",
                              "vlt2000_command_failed@18:1", "vlt2000_checksum_error@22:2",
                              "vlt2000_checksum_disabled@26:17", "malformed_telegram@30:31"}) {
        session.push_back("--fault");
        session.push_back(fault);
    }
    const std::string reference = test::temp_path("vlt2000-reference.pcap");
    const std::string pcap = test::temp_path("vlt2000-live-session.pcap");
    std::vector<std::string> write = {"simulate", "-w", reference};
    write.insert(write.end(), session.begin(), session.end());
    auto written = test::run_dpscope(write);
    ASSERT_EQ(written.exit_code, 0) << written.err;

    PseudoTerminal bus, adapter;
    // No idle gap: the relay on a loaded machine can hold bytes back for any time, within a
    // telegram too.
    Sniffer sniffer(without_idle_gap({"sniff", "-i", adapter.slave, "--bus", "vlt2000", "--baud",
                                      "115200", "-w", pcap, "--report"}));
    ASSERT_TRUE(sniffer.ready()) << sniffer.err();
    EXPECT_NE(sniffer.err().find("at 115200 baud 8N1"), std::string::npos) << sniffer.err();
    Capture expected = read_capture(reference);
    {
        Relay relay(bus.master, adapter.master);
        std::vector<std::string> play = {"simulate", "--device", bus.slave};
        play.insert(play.end(), session.begin(), session.end());
        auto played = test::run_dpscope(play);
        ASSERT_EQ(played.exit_code, 0) << played.err;
    }
    // All but the reply cut short (below).
    EXPECT_TRUE(test::wait_for_records(pcap, expected.telegrams.size() - 1)) << sniffer.err();
    sniffer.signal(SIGINT);
    EXPECT_EQ(sniffer.wait(), 1) << sniffer.err();  // errors found, --fail-on error
    const std::string out = sniffer.out();
    const std::string err = sniffer.err();

    // Every telegram arrived in order, but the reply cut short (malformed_telegram): in a byte
    // stream nothing ends it, its 22nd character is the next command's and no '>', and the framer
    // skips it up to that command's '<' (a simulated capture has its own record for it).
    Capture capture = read_capture(pcap);
    EXPECT_EQ(capture.status, InputStatus::Ok);
    EXPECT_EQ(capture.link_type, kLinkTypeUser0);
    ASSERT_EQ(capture.telegrams.size() + 1, expected.telegrams.size());
    std::size_t cut = 0;
    while (cut < capture.telegrams.size() && capture.telegrams[cut] == expected.telegrams[cut])
        ++cut;
    ASSERT_LT(cut, expected.telegrams.size());
    const std::vector<std::uint8_t> short_one = expected.telegrams[cut];
    EXPECT_LT(short_one.size(), kVlt2000TelegramSize);
    expected.telegrams.erase(expected.telegrams.begin() + static_cast<std::ptrdiff_t>(cut));
    EXPECT_EQ(capture.telegrams, expected.telegrams);
    EXPECT_NE(err.find("skipped " + std::to_string(short_one.size()) + " bytes"), std::string::npos)
        << err;

    // The capture records its bus: decode reads it as VLT 2000 without --bus and says nothing of
    // it; the live decode is `dpscope decode` of the written capture, line by line (the decode
    // lines: " VLT " but not the report's "Bus:" line).
    const auto decode_lines = [](const std::string& text) {
        std::vector<std::string> lines;
        for (const std::string& l : lines_with(text, " VLT "))
            if (l.find("Danfoss VLT") == std::string::npos) lines.push_back(l);
        return lines;
    };
    auto decoded = test::run_dpscope({"decode", "--baud", "115200", pcap});
    ASSERT_EQ(decoded.exit_code, 0) << decoded.err;
    EXPECT_EQ(decoded.err, "");
    std::vector<std::string> lines = decode_lines(decoded.out);
    ASSERT_EQ(lines.size(), capture.telegrams.size()) << decoded.out;
    const std::vector<std::string> live_lines = decode_lines(out);
    EXPECT_EQ(live_lines.size(), lines.size());
    for (std::size_t i = 0; i < std::min(live_lines.size(), lines.size()); ++i)
        if (live_lines[i] != lines[i]) {
            ADD_FAILURE() << "first difference, line " << i + 1 << ":\nlive:    " << live_lines[i]
                          << "\ndecoded: " << lines[i];
            break;
        }
    for (const char* letter :
         {" VLT C control ", " VLT R read ", " VLT U update ", " VLT I read index ", " M → all "})
        EXPECT_FALSE(lines_with(out, letter).empty()) << letter << "\n" << out;
    EXPECT_FALSE(lines_with(out, "[error vlt2000_stacked_request]").empty()) << out;

    // The report at the end: the same per-drive sections and findings as `dpscope report` on the
    // written capture.
    auto offline = test::run_dpscope({"report", "--baud", "115200", pcap});
    EXPECT_EQ(offline.exit_code, 1) << offline.err;
    std::vector<std::string> live_report = lines_from(out, "Drive ");
    ASSERT_GT(live_report.size(), 25u) << out;
    EXPECT_EQ(live_report, lines_from(offline.out, "Drive ")) << out;
    for (const char* drive : {"Drive 01 ", "Drive 02 ", "Drive 17 ", "Drive 31 "})
        EXPECT_EQ(lines_with(out, drive).size(), 1u) << drive << "\n" << out;

    // ... and the findings of the simulated session (`dpscope report` of the reference), kind by
    // kind: the cut reply is no malformed_telegram live: its command went unanswered
    // (vlt2000_no_response) before the master's next telegram.
    auto simulated = test::run_dpscope({"report", "--baud", "115200", reference});
    EXPECT_EQ(simulated.exit_code, 1) << simulated.err;
    std::map<std::string, int> live_kinds = finding_kinds(out);
    std::map<std::string, int> reference_kinds = finding_kinds(simulated.out);
    EXPECT_EQ(live_kinds, finding_kinds(offline.out));
    for (const char* kind :
         {"vlt2000_stacked_request", "vlt2000_no_response", "vlt2000_unexpected_reply",
          "vlt2000_mismatched_response", "vlt2000_command_failed", "vlt2000_checksum_error",
          "vlt2000_checksum_disabled", "malformed_telegram"})
        EXPECT_GE(reference_kinds[kind], 1) << kind << "\n" << simulated.out;
    for (const char* kind :
         {"vlt2000_stacked_request", "vlt2000_unexpected_reply", "vlt2000_mismatched_response",
          "vlt2000_command_failed", "vlt2000_checksum_error", "vlt2000_checksum_disabled"})
        EXPECT_EQ(live_kinds[kind], reference_kinds[kind]) << kind << "\n" << out;
    EXPECT_EQ(live_kinds["vlt2000_no_response"], reference_kinds["vlt2000_no_response"] + 1) << out;
    EXPECT_EQ(live_kinds["malformed_telegram"], 0) << out;
    std::remove(pcap.c_str());
    std::remove(reference.c_str());
}

// Plays a faulty session into a sniffer started with `args` (after -i and --baud) and stops it.
// (A -w file of its own tells when every telegram has arrived.)
int sniff_faulty_session(std::vector<std::string> args, std::string& out, std::string& err) {
    PseudoTerminal pty;
    const std::string pcap = test::temp_path("faulty.pcap");
    args.insert(args.begin(), {"sniff", "-i", pty.slave, "--baud", "1500000", "-w", pcap});
    Sniffer sniffer(without_idle_gap(args));
    EXPECT_TRUE(sniffer.ready()) << sniffer.err();
    SimulatorOptions options = faulty_session();
    options.cycles = 100;
    Session session = simulate(options);
    play(pty, session, true);
    EXPECT_TRUE(test::wait_for_records(pcap, session.expected.size())) << sniffer.err();
    sniffer.signal(SIGINT);
    int exit_code = sniffer.wait();
    out = sniffer.out();
    err = sniffer.err();
    return exit_code;
}

TEST(SniffTest, ReportFileHoldsTheReportAndStandardOutputTheLiveDecode) {
    std::string path = test::temp_path("report.json");
    std::string out, err;
    EXPECT_EQ(sniff_faulty_session({"--report-file", path, "--report-format", "json"}, out, err), 1)
        << err;
    auto report = test::read_file(path);
    auto json = test::parse_json(std::string(report.begin(), report.end()));
    ASSERT_TRUE(json);
    EXPECT_EQ((*json)["result"].text, "fail");
    EXPECT_EQ((*json)["input"]["format"].text, "serial");
    EXPECT_NE(out.find("Data_Exchange"), std::string::npos) << out;  // the live lines
    EXPECT_EQ(out.find("\"result\""), std::string::npos) << out;
    std::remove(path.c_str());

    // - : the report alone on standard output, the live decode on standard error.
    EXPECT_EQ(sniff_faulty_session({"--report-file", "-", "--report-format", "json"}, out, err), 1)
        << err;
    EXPECT_TRUE(test::parse_json(out)) << out;
    EXPECT_NE(err.find("Data_Exchange"), std::string::npos) << err;
}

TEST(SniffTest, ReportOptionsThatCannotWorkAreUsageErrors) {
    PseudoTerminal pty;
    const std::string pcap = test::temp_path("same.pcap");
    const std::string link = test::temp_path("link.json");
    test::write_text_file(pcap, "precious");
    std::filesystem::create_symlink(pcap, link);
    struct Case {
        std::vector<std::string> args;
        std::string message;
    };
    const std::vector<Case> cases = {
        {{"--report", "--report-format", "json"},
         "--report-format json: the report would be "
         "mixed into the live output"},
        {{"--report-format", "html"}, "give --report-file FILE"},
        {{"-w", "-", "--report-file", "-"}, "standard output already carries the pcap of -w -"},
        {{"-w", pcap, "--report-file", link},
         "--report-file " + link + ": it is the capture file of -w " + pcap},
        {{"-w", pcap, "--report-file", pcap}, "it is the capture file"},
    };
    const termios before = [&] {
        termios tio;
        std::memset(&tio, 0, sizeof tio);
        int fd = open(pty.slave.c_str(), O_RDWR | O_NOCTTY);
        tcgetattr(fd, &tio);
        close(fd);
        return tio;
    }();
    for (const Case& c : cases) {
        std::vector<std::string> args = {"sniff", "-i", pty.slave, "--baud", "1500000"};
        args.insert(args.end(), c.args.begin(), c.args.end());
        auto result = test::run_dpscope(args);
        EXPECT_EQ(result.exit_code, 2) << c.message;
        EXPECT_EQ(result.err.rfind("dpscope: error: --report", 0), 0u) << result.err;
        EXPECT_NE(result.err.find(c.message), std::string::npos) << result.err;
    }
    EXPECT_EQ(test::read_file(pcap).size(), 8u);  // nothing overwritten
    termios after;
    std::memset(&after, 0, sizeof after);
    int fd = open(pty.slave.c_str(), O_RDWR | O_NOCTTY);
    tcgetattr(fd, &after);
    close(fd);
    EXPECT_EQ(std::memcmp(&before, &after, sizeof before), 0);
    std::remove(link.c_str());
    std::remove(pcap.c_str());
}

TEST(SniffTest, NumericOptionsAreCheckedAgainstTheirRange) {
    PseudoTerminal pty;
    struct Case {
        std::vector<std::string> args;
        std::string message;
    };
    const std::string x = test::temp_path("x.pcap");  // never written: every case is refused
    const std::string seconds = "must be a number from 0.001 to 315360000 seconds, not ";
    const std::string size =
        "must be a size from 512 bytes to 16T (a whole number of bytes, or with k, M, G or T), "
        "not ";
    const std::vector<Case> cases = {
        {{"--duration", "nan"}, "--duration: " + seconds + "'nan'"},
        {{"--duration", "-1"}, "--duration: " + seconds + "'-1'"},
        {{"--duration", "1e300"}, "--duration: " + seconds + "'1e300'"},
        {{"--duration", "1e-300"}, "--duration: " + seconds + "'1e-300'"},
        {{"--duration", "inf"}, "--duration: " + seconds + "'inf'"},
        {{"-w", x, "--rotate-seconds", "inf"}, "--rotate-seconds: " + seconds + "'inf'"},
        {{"-w", x, "--rotate-seconds", "0"}, "--rotate-seconds: " + seconds + "'0'"},
        {{"-w", x, "--rotate-size", "0"}, "--rotate-size: " + size + "0"},
        {{"-w", x, "--rotate-size", "-5"}, "--rotate-size: " + size + "-5"},
        {{"-w", x, "--rotate-size", "1e30"}, "--rotate-size: " + size + "1e30"},
        {{"-w", x, "--rotate-size", "17T"}, "--rotate-size: " + size + "17T"},
        {{"-w", x, "--rotate-size", "5X"}, "--rotate-size: " + size + "5X"},
        {{"--idle-gap-ms", "-1"},
         "--idle-gap-ms: must be a whole number from 0 to 60000 ms, not '-1'"},
        {{"--idle-gap-ms", "1e30"}, "--idle-gap-ms: must be a whole number from 0 to 60000 ms"},
        {{"-c", "1e30"}, "--count: must be a whole number from 1 to 9223372036854775807 telegrams"},
        {{"-c", "1.5"}, "--count: must be a whole number from 1 to"},
        {{"-c", "0"},
         "--count: must be a whole number from 1 to 9223372036854775807 telegrams, not '0'"},
        {{"--timeout-ms", "nan"},
         "--timeout-ms: must be a whole number from 1 to 3600000 ms, not 'nan'"},
    };
    for (const Case& c : cases) {
        std::vector<std::string> args = {"sniff", "-i", pty.slave, "--baud", "1500000"};
        args.insert(args.end(), c.args.begin(), c.args.end());
        auto result = test::run_dpscope(args);
        EXPECT_EQ(result.exit_code, 2) << c.message;
        EXPECT_NE(result.err.find("dpscope: error: " + c.message), std::string::npos) << result.err;
    }
    for (const char* baud : {"0", "299", "16000001", "1e30", "-9600", "nan"}) {
        auto result = test::run_dpscope({"sniff", "-i", pty.slave, "--baud", baud});
        EXPECT_EQ(result.exit_code, 2) << baud;
        EXPECT_NE(
            result.err.find("--baud: must be a whole number from 300 to 16000000 baud, not '" +
                            std::string(baud) + "'"),
            std::string::npos)
            << result.err;
    }
    EXPECT_FALSE(std::filesystem::exists(x));
}

TEST(SniffTest, ThePortIsLeftAsItWasFoundOnEveryWayOut) {
    SimulatorOptions options;
    options.cycles = 30;
    Session session = simulate(options);
    const std::string pcap = test::temp_path("restore.pcap");
    // How each run ends: by a signal, by itself (-c, --duration), by a write error.
    struct Way {
        std::string name;
        std::vector<std::string> args;
        int signal_number;  // 0: none
        rlim_t file_size_limit;
        int exit_code;
    };
    const std::vector<Way> ways = {
        {"SIGINT", {"-q"}, SIGINT, RLIM_INFINITY, 0},
        {"SIGTERM", {"-q"}, SIGTERM, RLIM_INFINITY, 0},
        {"SIGHUP", {"-q", "--sighup", "stop"}, SIGHUP, RLIM_INFINITY, 0},
        {"-c", {"-c", "5"}, 0, RLIM_INFINITY, 0},
        {"--duration", {"--duration", "0.4"}, 0, RLIM_INFINITY, 0},
        {"write error", {"-q", "-w", pcap}, 0, 2000, 4},
    };
    for (const Way& way : ways) {
        PseudoTerminal pty;
        const termios before = settings_of(pty.slave);
        std::vector<std::string> args = {"sniff", "-i", pty.slave, "--baud", "187500"};
        args.insert(args.end(), way.args.begin(), way.args.end());
        Sniffer sniffer(args, way.file_size_limit);
        ASSERT_TRUE(sniffer.ready()) << sniffer.err();
        EXPECT_FALSE(same_settings(settings_of(pty.slave), before)) << way.name;
        play(pty, session, true);
        // A signal ends the run wherever it finds it, reading or between reads.
        if (way.signal_number != 0) sniffer.signal(way.signal_number);
        EXPECT_EQ(sniffer.wait(), way.exit_code) << way.name << ": " << sniffer.err();
        EXPECT_TRUE(same_settings(settings_of(pty.slave), before)) << way.name;
    }
    std::remove(pcap.c_str());

    // A second signal ends at once, and still puts the port back.
    PseudoTerminal pty;
    const termios before = settings_of(pty.slave);
    Sniffer sniffer({"sniff", "-i", pty.slave, "--baud", "187500", "-q"});
    ASSERT_TRUE(sniffer.ready()) << sniffer.err();
    sniffer.signal(SIGSTOP);  // both signals arrive together
    sniffer.signal(SIGTERM);
    sniffer.signal(SIGINT);
    sniffer.signal(SIGCONT);
    int exit_code = sniffer.wait();
    EXPECT_TRUE(exit_code == 128 + SIGINT || exit_code == 128 + SIGTERM) << exit_code;
    EXPECT_TRUE(same_settings(settings_of(pty.slave), before));

    // An output that cannot be opened: the port is not even set up.
    auto result = test::run_dpscope(
        {"sniff", "-i", pty.slave, "--baud", "187500", "-w", "/no-such-directory/x.pcap"});
    EXPECT_EQ(result.exit_code, 4) << result.err;
    EXPECT_EQ(result.err.find("capturing on"), std::string::npos) << result.err;
    EXPECT_TRUE(same_settings(settings_of(pty.slave), before));

    // simulate --device uses the same port set-up and puts it back too.
    result = test::run_dpscope({"simulate", "--device", pty.slave, "--baud", "187500", "--cycles",
                                "5", "--as-fast-as-possible"});
    EXPECT_EQ(result.exit_code, 0) << result.err;
    EXPECT_TRUE(same_settings(settings_of(pty.slave), before));
}

TEST(SniffTest, ASecondSnifferOnThePortIsRefusedAndTheFirstCapturesOn) {
    PseudoTerminal pty;
    const std::string pcap = test::temp_path("first.pcap");
    Sniffer first(
        without_idle_gap({"sniff", "-i", pty.slave, "--baud", "1500000", "-q", "-w", pcap}));
    ASSERT_TRUE(first.ready()) << first.err();
    // Even with the same -w file: refused before that file is touched.
    auto second =
        test::run_dpscope({"sniff", "-i", pty.slave, "--baud", "1500000", "-q", "-w", pcap});
    EXPECT_EQ(second.exit_code, 2) << second.err;
    EXPECT_NE(second.err.find("dpscope: error: " + pty.slave + " is in use"), std::string::npos)
        << second.err;
    auto simulator = test::run_dpscope(
        {"simulate", "--device", pty.slave, "--baud", "1500000", "--cycles", "5"});
    EXPECT_EQ(simulator.exit_code, 2) << simulator.err;
    EXPECT_NE(simulator.err.find(pty.slave + " is in use"), std::string::npos) << simulator.err;
    SimulatorOptions options;
    options.cycles = 30;
    Session session = simulate(options);
    play(pty, session, true);
    EXPECT_TRUE(test::wait_for_records(pcap, session.expected.size())) << first.err();
    first.signal(SIGINT);
    ASSERT_EQ(first.wait(), 0) << first.err();
    EXPECT_EQ(read_capture(pcap).telegrams, session.expected);
    std::remove(pcap.c_str());
}

TEST(SniffTest, UsageErrorsNameTheProblem) {
    // A device that cannot be set up leaves no empty output files behind.
    const std::string pcap = test::temp_path("never.pcap");
    const std::string json = test::temp_path("never.json");
    auto result = test::run_dpscope({"sniff", "-i", "/dev/null", "--baud", "1500000", "-w", pcap,
                                     "--report-file", json, "--report-format", "json"});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find("/dev/null: not a serial port"), std::string::npos) << result.err;
    EXPECT_FALSE(std::filesystem::exists(pcap));
    EXPECT_FALSE(std::filesystem::exists(json));
    // ... and an existing report file as it was: the report is staged, not opened over it.
    test::write_text_file(json, "the previous report\n");
    result = test::run_dpscope({"sniff", "-i", "/dev/null", "--baud", "1500000", "--report-file",
                                json, "--report-format", "json"});
    EXPECT_EQ(result.exit_code, 2);
    const std::vector<std::uint8_t> kept = test::read_file(json);
    EXPECT_EQ(std::string(kept.begin(), kept.end()), "the previous report\n");
    std::remove(json.c_str());
    result = test::run_dpscope({"sniff", "-i", "/dev/ttyS-missing", "--baud", "1500000"});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find("cannot open"), std::string::npos);
    PseudoTerminal pty;
    result = test::run_dpscope(
        {"sniff", "-i", pty.slave, "--baud", "1500000", "-w", "-", "--rotate-size", "1000"});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find("cannot rotate standard output"), std::string::npos) << result.err;
    // The ring needs a rotation and a -w file; --max-disk at least two files; --ring 2 to 100000.
    const std::string ring = test::temp_path("ring-never.pcap");
    result = test::run_dpscope(
        {"sniff", "-i", pty.slave, "--baud", "1500000", "-w", ring, "--ring", "3"});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find("--ring keeps the files of a rotation"), std::string::npos)
        << result.err;
    result = test::run_dpscope({"sniff", "-i", pty.slave, "--baud", "1500000", "-w", ring,
                                "--rotate-size", "1M", "--max-disk", "1M"});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find("less than two files of --rotate-size"), std::string::npos)
        << result.err;
    result = test::run_dpscope({"sniff", "-i", pty.slave, "--baud", "1500000", "--ring", "3"});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find("--ring is about the capture file of -w FILE"), std::string::npos);
    result = test::run_dpscope({"sniff", "-i", pty.slave, "--baud", "1500000", "-w", ring,
                                "--rotate-size", "1M", "--ring", "1"});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_FALSE(std::filesystem::exists(rotated_file_name(ring, 1)));
}

TEST(SniffTest, FcBusDefaultsTo9600Baud8E1AndWritesATaggedUser0Capture) {
    PseudoTerminal pty;
    const std::string pcap = test::temp_path("fc-live.pcap");
    Sniffer sniffer({"sniff", "-i", pty.slave, "--bus", "fc", "-w", pcap, "-T", "jsonl"});
    ASSERT_TRUE(sniffer.ready()) << sniffer.err();
    EXPECT_NE(sniffer.err().find("at 9600 baud 8E1"), std::string::npos) << sniffer.err();
    // Two FC telegrams (LGE 6: PCD block), BCC computed.
    std::vector<std::uint8_t> bytes;
    for (std::uint8_t adr : {std::uint8_t{0x81}, std::uint8_t{0x01}}) {
        std::vector<std::uint8_t> t{0x02, 0x06, adr, 0x04, 0x7C, 0x00, 0x00};
        t.push_back(fc_bcc_of(Bytes(t.data(), t.size())));
        bytes.insert(bytes.end(), t.begin(), t.end());
    }
    pty.write(bytes);
    EXPECT_TRUE(test::wait_for_records(pcap, 2)) << sniffer.err();
    sniffer.signal(SIGINT);
    ASSERT_EQ(sniffer.wait(), 0) << sniffer.err();
    EXPECT_EQ(test::lines_of(sniffer.out()).size(), 2u) << sniffer.out();
    const std::vector<std::uint8_t> file = test::read_file(pcap);
    ASSERT_GE(file.size(), 24u);
    EXPECT_EQ(std::string(file.begin() + 8, file.begin() + 12), "dpsc");
    Capture capture = read_capture(pcap);
    EXPECT_EQ(capture.link_type, kLinkTypeUser0);
    auto decoded = test::run_dpscope({"decode", "-T", "jsonl", pcap});
    EXPECT_EQ(decoded.exit_code, 0) << decoded.err;
    EXPECT_EQ(decoded.err, "");
    EXPECT_EQ(test::lines_of(decoded.out).size(), 2u);
}

// sniff -w records the line it captured on (baud rate, parity, stop bits), and decode, report
// and stats read the capture back at that rate without --baud: a command and its answer, sent
// back to back at 19200 baud 8O2 (12 bits a character), are no "response before the command
// ended", as they would be at the default 9600 baud 8E1.
TEST(SniffTest, ACaptureRecordsItsLineAndIsReadBackAtItsRate) {
    PseudoTerminal pty;
    const std::string pcap = test::temp_path("fc-19200.pcap");
    Sniffer sniffer({"sniff", "-i", pty.slave, "--bus", "fc", "--baud", "19200", "--parity", "odd",
                     "--stop-bits", "2", "-w", pcap, "-q"});
    ASSERT_TRUE(sniffer.ready()) << sniffer.err();
    std::vector<std::uint8_t> bytes = test::fc_parameter(1, 1, 414);
    const std::vector<std::uint8_t> response = test::fc_parameter(1, 1, 414, 0, 1500, 0x0607);
    bytes.insert(bytes.end(), response.begin(), response.end());
    pty.write(bytes);
    // Both records are in the file (flushed when the line is idle).
    const std::uintmax_t whole = 24 + 2 * (16 + 16);
    ASSERT_TRUE(test::wait_for_records(pcap, 2)) << sniffer.err();
    ASSERT_EQ(std::filesystem::file_size(pcap), whole);
    sniffer.signal(SIGINT);
    ASSERT_EQ(sniffer.wait(), 0) << sniffer.err();
    EXPECT_EQ(sniffer.err().find("began before"), std::string::npos) << sniffer.err();
    const std::vector<std::uint8_t> file = test::read_file(pcap);
    const CaptureLabel label = read_capture_label(Bytes(file.data(), file.size()));
    EXPECT_EQ(label.line, (LineSettings{19200, SerialParity::Odd, 2}));
    const test::CommandResult recorded = test::run_dpscope({"report", pcap});
    EXPECT_EQ(recorded.exit_code, 0) << recorded.err;
    EXPECT_EQ(recorded.err, "");
    EXPECT_EQ(recorded.out, test::run_dpscope({"report", "--baud", "19200", pcap}).out);
    EXPECT_NE(recorded.out.find("1 answered"), std::string::npos) << recorded.out;
    // The drive's latency is the same as with --baud 19200, and decode agrees too.
    const std::string latency = recorded.out.substr(recorded.out.find("latency ms"));
    EXPECT_EQ(latency.substr(0, latency.find('\n')),
              "latency ms     min 0.000  mean 0.000  p95 0.000  max 0.000");
    const test::CommandResult decoded = test::run_dpscope({"decode", pcap});
    EXPECT_EQ(decoded.err, "");
    EXPECT_EQ(decoded.out, test::run_dpscope({"decode", "--baud", "19200", pcap}).out);
}

// simulate --replay plays a capture on the line it records (sniff -w), unless --baud says
// otherwise (with a warning when they differ).
TEST(SniffTest, SimulateReplaysACaptureOnTheLineItRecords) {
    const std::string pcap = test::temp_path("fc-19200-8o2.pcap");
    {
        WriterResult opened = open_capture_writer(pcap, CaptureFormat::Pcap, kLinkTypeUser0,
                                                  Protocol::Fc, {19200, SerialParity::Odd, 2});
        ASSERT_TRUE(opened) << opened.error();
        const std::vector<std::uint8_t> command = test::fc_parameter(1, 1, 414);
        ASSERT_TRUE((*opened)->write(Bytes(command.data(), command.size()), 1'000'000'000));
        ASSERT_TRUE((*opened)->close());
    }
    for (const bool given : {false, true}) {
        PseudoTerminal pty;
        std::vector<std::string> args = {"simulate", "--bus",    "fc", "--device",
                                         pty.slave,  "--replay", pcap, "-v"};
        if (given) args.insert(args.end(), {"--baud", "9600"});
        const test::CommandResult played = test::run_dpscope(args);
        ASSERT_EQ(played.exit_code, 0) << played.err;
        EXPECT_NE(played.err.find(given ? "at 9600 baud 8O2" : "at 19200 baud 8O2"),
                  std::string::npos)
            << played.err;
        EXPECT_EQ(played.err.find("warning") != std::string::npos, given) << played.err;
        EXPECT_EQ(read_to_the_end(pty.master).size(), 16u);
    }
}

TEST(SniffTest, Vlt2000BusDefaultsTo9600Baud8N1AndWritesATaggedUser0Capture) {
    PseudoTerminal pty;
    const std::string pcap = test::temp_path("vlt2000-live.pcap");
    Sniffer sniffer({"sniff", "-i", pty.slave, "--bus", "vlt2000", "-w", pcap, "-T", "jsonl"});
    ASSERT_TRUE(sniffer.ready()) << sniffer.err();
    EXPECT_NE(sniffer.err().find("at 9600 baud 8N1"), std::string::npos) << sniffer.err();
    // A command and its reply (the VLT 3000 manual's example), with noise between them.
    const std::string line = "<01UOGD@0516+00080007>\x01<01UGHK@0516+00080007>";
    pty.write(std::vector<std::uint8_t>(line.begin(), line.end()));
    EXPECT_TRUE(test::wait_for_records(pcap, 2)) << sniffer.err();
    sniffer.signal(SIGINT);
    ASSERT_EQ(sniffer.wait(), 0) << sniffer.err();
    EXPECT_EQ(test::lines_of(sniffer.out()).size(), 2u) << sniffer.out();
    EXPECT_NE(sniffer.err().find("skipped 1 byte: no '<'"), std::string::npos) << sniffer.err();
    const std::vector<std::uint8_t> file = test::read_file(pcap);
    ASSERT_GE(file.size(), 24u);
    EXPECT_EQ(std::string(file.begin() + 8, file.begin() + 12), "dpsc");
    Capture capture = read_capture(pcap);
    EXPECT_EQ(capture.link_type, kLinkTypeUser0);
    auto decoded = test::run_dpscope({"decode", "-T", "jsonl", pcap});
    EXPECT_EQ(decoded.exit_code, 0) << decoded.err;
    EXPECT_EQ(decoded.err, "");
    EXPECT_EQ(test::lines_of(decoded.out).size(), 2u);
}

TEST(SniffTest, Vlt2000LineOptionsOverrideTheDefaults) {
    PseudoTerminal pty;
    Sniffer sniffer({"sniff", "-i", pty.slave, "--bus", "vlt2000", "--baud", "4800", "--parity",
                     "even", "--stop-bits", "2", "-c", "1"});
    ASSERT_TRUE(sniffer.ready()) << sniffer.err();
    EXPECT_NE(sniffer.err().find("at 4800 baud 8E2"), std::string::npos) << sniffer.err();
    sniffer.signal(SIGINT);
    EXPECT_EQ(sniffer.wait(), 0) << sniffer.err();
    auto link = test::run_dpscope(
        {"sniff", "-i", pty.slave, "--bus", "vlt2000", "-w", "-", "--linktype", "profibus"});
    EXPECT_EQ(link.exit_code, 2);
    EXPECT_NE(link.err.find("link type 257 (PROFIBUS_DL) is PROFIBUS only; a capture of VLT 2000 "
                            "is written as user0 (147)"),
              std::string::npos)
        << link.err;
    auto parity =
        test::run_dpscope({"sniff", "-i", pty.slave, "--bus", "vlt2000", "--parity", "x"});
    EXPECT_EQ(parity.exit_code, 2);
    EXPECT_NE(parity.err.find("--parity"), std::string::npos) << parity.err;
}

TEST(SniffTest, FcLineOptionsAreChecked) {
    PseudoTerminal pty;
    for (const char* baud : {"1200", "230400"}) {
        auto result = test::run_dpscope({"sniff", "-i", pty.slave, "--bus", "fc", "--baud", baud});
        EXPECT_EQ(result.exit_code, 2) << baud;
        EXPECT_NE(result.err.find("--baud: must be a whole number from 2400 to 115200 baud for the "
                                  "FC protocol (--bus fc), not '" +
                                  std::string(baud) + "'"),
                  std::string::npos)
            << result.err;
    }
    auto parity = test::run_dpscope({"sniff", "-i", pty.slave, "--bus", "fc", "--parity", "bogus"});
    EXPECT_EQ(parity.exit_code, 2);
    EXPECT_NE(parity.err.find("--parity"), std::string::npos) << parity.err;
    auto stop = test::run_dpscope({"sniff", "-i", pty.slave, "--bus", "fc", "--stop-bits", "3"});
    EXPECT_EQ(stop.exit_code, 2);
    EXPECT_NE(stop.err.find("--stop-bits"), std::string::npos) << stop.err;
    auto link = test::run_dpscope(
        {"sniff", "-i", pty.slave, "--bus", "fc", "-w", "-", "--linktype", "profibus"});
    EXPECT_EQ(link.exit_code, 2);
    EXPECT_NE(link.err.find("link type 257 (PROFIBUS_DL) is PROFIBUS only"), std::string::npos)
        << link.err;
    auto no_baud = test::run_dpscope({"sniff", "-i", pty.slave});
    EXPECT_EQ(no_baud.exit_code, 2);
    // The buses with a default line are named from the table of protocols.
    EXPECT_NE(no_baud.err.find("--baud is required for PROFIBUS DP (the FC protocol, --bus fc, "),
              std::string::npos)
        << no_baud.err;
    EXPECT_NE(no_baud.err.find("the VLT 2000, --bus vlt2000, "), std::string::npos) << no_baud.err;
    EXPECT_NE(no_baud.err.find("default to 9600)"), std::string::npos) << no_baud.err;
}

// --- sniff --stats and --alarm ----------------------------------------------------------------

// The text statistics of the capture at `pcap`, as sniff --stats at `baud` computes them live.
std::string reference_stats(const std::string& pcap, const std::string& device,
                            std::uint32_t baud) {
    BusHealthOptions options;
    options.baud = baud;
    BusHealthTracker tracker(options);
    BusDecoder decoder;
    OpenResult opened = open_source(pcap, InputFormat::Auto, profibus_protocol());
    EXPECT_TRUE(opened) << opened.error();
    if (!opened) return {};
    Record record;
    while (opened.value()->next(record))
        tracker.observe(decoder.decode(record.bytes, record.time_ns, record.number));
    tracker.finish();
    auto version = test::run_dpscope({"--version"});
    // "dpscope 0.1.0 (commit ...)": the second word of the first line.
    const std::size_t from = version.out.find(' ') + 1;
    std::string number = version.out.substr(from, version.out.find(' ', from) - from);
    StatsContext context{InputSummary{device, "serial", 0, false}, &tracker.health(), number};
    return test::output_text([&](Output& out) { render_stats(StatsFormat::Text, context, out); });
}

// dpscope running with standard output on a terminal (a pseudo-terminal of 120 x 40 without
// output processing), standard error in a file; what it draws is read as it comes.
class TerminalSniffer {
  public:
    explicit TerminalSniffer(std::vector<std::string> args) : err_(test::temp_path("err")) {
        winsize size{};
        size.ws_col = 120;
        size.ws_row = 40;
        int slave = -1;
        if (openpty(&master_, &slave, nullptr, nullptr, &size) != 0) return;
        termios mode{};
        tcgetattr(slave, &mode);
        mode.c_oflag &= ~static_cast<tcflag_t>(OPOST);  // the bytes as written
        tcsetattr(slave, TCSANOW, &mode);
        pid_ = fork();
        if (pid_ == 0) {
            int err = open(err_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
            dup2(slave, STDOUT_FILENO);
            dup2(err, STDERR_FILENO);
            close(master_);
            setenv("TZ", "UTC", 1);
            test::exec_or_exit(test::dpscope_argv(args));
        }
        close(slave);
        reader_ = std::thread([this] {
            char buffer[4096];
            for (;;) {
                pollfd p{master_, POLLIN, 0};
                if (poll(&p, 1, 20) <= 0) {
                    if (stop_) break;
                    continue;
                }
                ssize_t n = read(master_, buffer, sizeof buffer);
                if (n <= 0) break;  // EIO: the sniffer has closed the terminal
                std::lock_guard<std::mutex> lock(mutex_);
                out_.append(buffer, static_cast<std::size_t>(n));
            }
        });
    }
    ~TerminalSniffer() {
        if (pid_ > 0 && !reaped_) {
            kill(pid_, SIGKILL);
            waitpid(pid_, nullptr, 0);
        }
        stop_ = true;
        if (reader_.joinable()) reader_.join();
        if (master_ >= 0) close(master_);
        std::remove(err_.c_str());
    }
    bool ready() const {
        return test::wait_until([&] { return err().find("capturing on") != std::string::npos; });
    }
    void signal(int number) const { kill(pid_, number); }
    int wait() {
        int status = 0;
        if (!test::wait_until([&] { return waitpid(pid_, &status, WNOHANG) == pid_; })) return -1;
        reaped_ = true;
        stop_ = true;
        if (reader_.joinable()) reader_.join();
        return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }
    std::string out() {
        std::lock_guard<std::mutex> lock(mutex_);
        return out_;
    }
    std::string err() const { return slurp(err_); }

  private:
    std::string err_;
    int master_ = -1;
    pid_t pid_ = -1;
    bool reaped_ = false;
    std::atomic<bool> stop_{false};
    std::thread reader_;
    std::mutex mutex_;
    std::string out_;
};

TEST(SniffTest, StatsOnATerminalRedrawTheStationTableAtMost4TimesASecond) {
    PseudoTerminal pty;
    std::string pcap = test::temp_path("stats.pcap");
    TerminalSniffer sniffer(
        without_idle_gap({"sniff", "-i", pty.slave, "--baud", "1500000", "-w", pcap, "--stats"}));
    ASSERT_TRUE(sniffer.ready()) << sniffer.err();
    SimulatorOptions options;
    options.cycles = 600;  // 1.2 s of bus time, played at its pace
    Session session = without_answers(simulate(options), 5, {{1000, 1100}});
    play(pty, session, false);
    EXPECT_TRUE(test::wait_for_records(pcap, session.expected.size())) << sniffer.err();
    sniffer.signal(SIGINT);
    ASSERT_EQ(sniffer.wait(), 0) << sniffer.err();
    Capture capture = read_capture(pcap);
    ASSERT_EQ(capture.telegrams, session.expected);

    std::string out = sniffer.out();
    // The table and its heading, redrawn in place; no line per telegram.
    EXPECT_NE(out.find("dpscope sniff --stats: " + pty.slave + " at 1500000 baud 8E1: "),
              std::string::npos)
        << out;
    EXPECT_NE(out.find("telegrams in "), std::string::npos) << out;
    EXPECT_NE(out.find(", stopped\n"), std::string::npos) << out;
    EXPECT_NE(out.find("\r\x1b["), std::string::npos) << out;  // cursor up, then clear
    EXPECT_EQ(out.find("Data_Exchange"), std::string::npos) << out;
    // Each redraw goes back up over exactly the lines the one before drew (heading, table,
    // events); the table has a line per station once they are heard.
    std::size_t frames = 0;
    bool stations_shown = false;
    std::vector<double> drawn_at;  // the time in each heading: "N telegrams in S s", by sniff
    for (std::size_t at = out.find("\x1b[J"), next; at != std::string::npos; at = next) {
        next = out.find("\x1b[J", at + 1);
        std::string frame = out.substr(at, next == std::string::npos ? next : next - at);
        const std::size_t in = frame.find(" telegrams in ");
        EXPECT_NE(in, std::string::npos) << frame;
        if (in != std::string::npos) drawn_at.push_back(std::stod(frame.substr(in + 14)));
        if (next == std::string::npos) break;  // the last: the statistics follow it
        ++frames;
        const std::size_t drawn =
            static_cast<std::size_t>(std::count(frame.begin(), frame.end(), '\n'));
        const std::string up = "\r\x1b[" + std::to_string(drawn) + "A";
        EXPECT_EQ(frame.substr(frame.size() - std::min(frame.size(), up.size())), up) << frame;
        EXPECT_GE(drawn, 3u) << frame;
        if (frame.find("\n   3 slave ") != std::string::npos) stations_shown = true;
    }
    EXPECT_GE(frames, 2u);  // redrawn during the capture, not only at its end
    EXPECT_TRUE(stations_shown) << out;
    // At most 4 redraws a second, by sniff's own clock as its headings give it (to 0.1 s: a
    // quarter of a second between two is at least 0.2 there); the last one, at the stop, may
    // follow at once. (The times the test reads them at would be the scheduler's.)
    for (std::size_t i = 1; i + 1 < drawn_at.size(); ++i)
        EXPECT_GE(drawn_at[i] - drawn_at[i - 1], 0.2 - 1e-9) << i << "\n" << out;
    // The final statistics, as from the written capture.
    std::string expected = reference_stats(pcap, pty.slave, 1'500'000);
    ASSERT_FALSE(expected.empty());
    ASSERT_GE(out.size(), expected.size());
    EXPECT_EQ(out.substr(out.size() - expected.size()), expected) << out;
    std::remove(pcap.c_str());
}

TEST(SniffTest, StatsOffATerminalPrintAPlainLinePerHealthEvent) {
    PseudoTerminal pty;
    std::string pcap = test::temp_path("events.pcap");
    Sniffer sniffer(
        without_idle_gap({"sniff", "-i", pty.slave, "--baud", "1500000", "--stats", "-w", pcap}));
    ASSERT_TRUE(sniffer.ready()) << sniffer.err();
    SimulatorOptions options;
    options.cycles = 300;
    Session session = without_answers(simulate(options), 5, {{400, 500}});
    play(pty, session, true);
    EXPECT_TRUE(test::wait_for_records(pcap, session.expected.size())) << sniffer.err();
    sniffer.signal(SIGINT);
    ASSERT_EQ(sniffer.wait(), 0) << sniffer.err();
    std::string out = sniffer.out();
    EXPECT_EQ(out.find('\x1b'), std::string::npos) << out;           // no escapes
    EXPECT_NE(out.find("Data_Exchange"), std::string::npos) << out;  // the decode beside them
    std::vector<std::string> lost = lines_with(out, " health: station 5 lost (slave, frame ");
    std::vector<std::string> returned =
        lines_with(out, " health: station 5 returned (slave, frame ");
    EXPECT_EQ(lost.size(), 1u) << out;
    EXPECT_EQ(returned.size(), 1u) << out;
    // Lines start with the time (ISO 8601 UTC).
    for (const std::string& line : lost)
        EXPECT_EQ(line.find("Z health: "), 26u) << line;
    // No other station was lost.
    EXPECT_EQ(lines_with(out, " lost (").size(), 1u) << out;
    // The statistics at the end, after the live output.
    std::string expected = reference_stats(pcap, pty.slave, 1'500'000);
    ASSERT_FALSE(expected.empty());
    ASSERT_GE(out.size(), expected.size());
    EXPECT_EQ(out.substr(out.size() - expected.size()), expected) << out;
    std::remove(pcap.c_str());
}

TEST(SniffTest, AlarmRunsOncePerKindAndStationWithinTheMinute) {
    PseudoTerminal pty;
    // Each alarm writes its variables to a file of its own (they may run at the same time).
    std::string dir = test::temp_path("alarms");
    std::filesystem::create_directories(dir);
    const std::string pcap = test::temp_path("alarms.pcap");  // to see when all has arrived
    Sniffer sniffer(
        without_idle_gap({"sniff", "-i", pty.slave, "--baud", "1500000", "-q", "-w", pcap,
                          "--alarm", "env | grep ^DPSCOPE_ | sort > " + dir + "/alarm.$$"}));
    ASSERT_TRUE(sniffer.ready()) << sniffer.err();
    SimulatorOptions options;
    options.cycles = 400;
    // Station 5 stops answering twice: lost, back, lost again within the minute.
    Session session = without_answers(simulate(options), 5, {{400, 500}, {900, 1000}});
    play(pty, session, true);
    EXPECT_TRUE(test::wait_for_records(pcap, session.expected.size())) << sniffer.err();
    sniffer.signal(SIGINT);
    ASSERT_EQ(sniffer.wait(), 0) << sniffer.err();
    // One file per alarm, each variable once.
    std::map<std::pair<std::string, std::string>, int> alarms;
    std::string all;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        std::string text = slurp(entry.path().string());
        all += text + "--\n";
        std::map<std::string, std::string> block;
        for (const std::string& line : test::lines_of(text)) {
            std::size_t eq = line.find('=');
            EXPECT_EQ(block.count(line.substr(0, eq)), 0u) << line;
            block[line.substr(0, eq)] = line.substr(eq + 1);
        }
        ++alarms[{block["DPSCOPE_EVENT"], block["DPSCOPE_STATION"]}];
        for (const char* name : {"DPSCOPE_ROLE", "DPSCOPE_TIME", "DPSCOPE_FRAME", "DPSCOPE_VERDICT",
                                 "DPSCOPE_REASONS"})
            EXPECT_EQ(block.count(name), 1u) << name << "\n" << text;
        EXPECT_EQ(block["DPSCOPE_TIME"].back(), 'Z') << text;
    }
    EXPECT_EQ((alarms[{"station_lost", "5"}]), 1) << all;
    for (const auto& [key, count] : alarms)
        EXPECT_EQ(count, 1) << key.first << " " << key.second;
    // The second loss was held back, and the end says so.
    EXPECT_NE(sniffer.err().find("suppressed by the limit of one per event kind and station per "
                                 "60 s (station_lost 1"),
              std::string::npos)
        << sniffer.err();
    // -q: the output is the summary; no event lines without --stats.
    EXPECT_EQ(sniffer.out().find(" health: "), std::string::npos) << sniffer.out();
    std::filesystem::remove_all(dir);
}

// Alarm commands that hang are ended when the capture ends: none is left running (the shell
// nor what it started), and the end says how many were ended.
TEST(SniffTest, AlarmCommandsStillRunningAreEndedWhenTheCaptureEnds) {
    PseudoTerminal pty;
    const std::string pids = test::temp_path("alarm-pids.txt");
    Sniffer sniffer({"sniff", "-i", pty.slave, "--baud", "1500000", "-q", "--alarm",
                     "echo $$ >> " + pids + "; sleep 300; echo"});
    ASSERT_TRUE(sniffer.ready()) << sniffer.err();
    SimulatorOptions options;
    options.cycles = 400;
    // Station 5 stops answering: lost (and its verdict turns bad).
    Session session = without_answers(simulate(options), 5, {{400, 500}});
    play(pty, session, true);
    // The first alarm command has started.
    std::vector<std::string> started;
    test::wait_until([&] {
        started = test::lines_of(slurp(pids));
        return !started.empty();
    });
    ASSERT_FALSE(started.empty()) << sniffer.err();
    sniffer.signal(SIGINT);
    ASSERT_EQ(sniffer.wait(), 0) << sniffer.err();
    started = test::lines_of(slurp(pids));
    for (const std::string& line : started)
        EXPECT_TRUE(test::wait_for_processes_in_group(static_cast<pid_t>(std::stol(line)), 0))
            << line;
    EXPECT_NE(sniffer.err().find(std::to_string(started.size()) +
                                 " ended at the end (still running after the wait)"),
              std::string::npos)
        << sniffer.err();
}

TEST(SniffTest, StatsOptionsThatCannotWorkAreUsageErrors) {
    PseudoTerminal pty;
    auto fc = test::run_dpscope({"sniff", "-i", pty.slave, "--bus", "fc", "--stats"});
    EXPECT_EQ(fc.exit_code, 2);
    EXPECT_NE(fc.err.find("--stats: bus health is PROFIBUS statistics (FDL/DP link layer); the FC "
                          "protocol bus has none"),
              std::string::npos)
        << fc.err;
    auto vlt = test::run_dpscope({"sniff", "-i", pty.slave, "--bus", "vlt2000", "--alarm", "true"});
    EXPECT_EQ(vlt.exit_code, 2);
    EXPECT_NE(vlt.err.find("--alarm: bus health is PROFIBUS"), std::string::npos) << vlt.err;
    auto format = test::run_dpscope(
        {"sniff", "-i", pty.slave, "--baud", "1500000", "--stats", "--stats-format", "json"});
    EXPECT_EQ(format.exit_code, 2);
    EXPECT_NE(format.err.find("--stats-format json: "), std::string::npos) << format.err;
    auto both = test::run_dpscope(
        {"sniff", "-i", pty.slave, "--baud", "1500000", "-w", "-", "--stats-file", "-"});
    EXPECT_EQ(both.exit_code, 2);
    EXPECT_NE(both.err.find("--stats-file -: standard output already carries the pcap"),
              std::string::npos)
        << both.err;
    const std::string pcap = test::temp_path("stats-same.pcap");
    auto same = test::run_dpscope(
        {"sniff", "-i", pty.slave, "--baud", "1500000", "-w", pcap, "--stats-file", pcap});
    EXPECT_EQ(same.exit_code, 2);
    EXPECT_NE(same.err.find("it is the capture file of -w"), std::string::npos) << same.err;
    auto device = test::run_dpscope(
        {"sniff", "-i", pty.slave, "--baud", "1500000", "--stats-file", pty.slave});
    EXPECT_EQ(device.exit_code, 2);
    EXPECT_NE(device.err.find("that is the capture device"), std::string::npos) << device.err;
}

TEST(SniffTest, StatsFileHoldsTheStatisticsInTheFormatAsked) {
    std::string path = test::temp_path("stats.json");
    std::string out, err;
    EXPECT_EQ(sniff_faulty_session({"--stats-file", path, "--stats-format", "json"}, out, err), 0)
        << err;
    std::vector<std::uint8_t> bytes = test::read_file(path);
    EXPECT_FALSE(bytes.empty());
    EXPECT_NE(out.find("Data_Exchange"), std::string::npos) << out;  // the live lines
    std::remove(path.c_str());
    // - : alone on standard output, the live decode on standard error.
    EXPECT_EQ(sniff_faulty_session({"--stats-file", "-", "--stats-format", "csv", "-q"}, out, err),
              0)
        << err;
    EXPECT_EQ(out.find("telegrams: "), std::string::npos) << out;  // the -q summary is elsewhere
    EXPECT_NE(err.find("telegrams: "), std::string::npos) << err;
}

// dpscope sniff with standard error a pipe whose reader has gone (closed before the start):
// standard output into the file `out`. Waits on events only: the port in raw mode, the exit.
struct ClosedStderrRun {
    int exit_code = -1;  // -1: did not end in time
    std::string out;
};

ClosedStderrRun sniff_with_closed_stderr(const std::vector<std::string>& args, PseudoTerminal& pty,
                                         const Session& session) {
    ClosedStderrRun run;
    const std::string out = test::temp_path("closed-stderr-out");
    int fds[2];
    if (pipe2(fds, O_CLOEXEC) != 0) return run;
    close(fds[0]);  // nobody reads standard error
    pid_t child = fork();
    if (child == 0) {
        int out_fd = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        int null = open("/dev/null", O_RDONLY);
        dup2(out_fd, STDOUT_FILENO);
        dup2(fds[1], STDERR_FILENO);
        dup2(null, STDIN_FILENO);
        setenv("TZ", "UTC", 1);
        test::exec_or_exit(test::dpscope_argv(args));
    }
    close(fds[1]);
    if (test::wait_for_raw_mode(pty)) play(pty, session, true);
    // The patience only bounds a run that hangs.
    int status = 0;
    if (!test::wait_until([&] { return waitpid(child, &status, WNOHANG) == child; })) {
        kill(child, SIGKILL);
        waitpid(child, &status, 0);
        run.out = slurp(out);
        return run;
    }
    run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    run.out = slurp(out);
    return run;
}

// A closed standard error (the program reading it ended) never stops a capture: every message
// is dropped (counted), the capture runs to its end, the file holds every telegram, and the exit
// code is 4 (an output could not be written), not an abort (134) or SIGPIPE (141).
TEST(SniffTest, AClosedStandardErrorNeverStopsTheCapture) {
    Session session = simulate(20);
    const std::string count = std::to_string(session.expected.size());
    {
        // The pty's parity note is the first message, before "capturing on".
        PseudoTerminal pty;
        const std::string pcap = test::temp_path("closed-stderr.pcap");
        ClosedStderrRun run = sniff_with_closed_stderr(
            {"sniff", "-i", pty.slave, "--baud", "1500000", "-w", pcap, "-c", count}, pty, session);
        EXPECT_EQ(run.exit_code, 4);
        EXPECT_GE(test::lines_of(run.out).size(), session.expected.size()) << run.out;
        Capture capture = read_capture(pcap);
        EXPECT_EQ(capture.status, InputStatus::Ok);
        EXPECT_EQ(capture.telegrams.size(), session.expected.size());
        EXPECT_TRUE(capture.telegrams == session.expected);
    }
    {
        // -w -: the pcap on standard output, the live decode on the closed standard error.
        PseudoTerminal pty;
        ClosedStderrRun run = sniff_with_closed_stderr(
            {"sniff", "-i", pty.slave, "--baud", "1500000", "-w", "-", "-c", count}, pty, session);
        EXPECT_EQ(run.exit_code, 4);
        const std::string pcap = test::temp_path("closed-stderr-stdout.pcap");
        test::write_text_file(pcap, run.out);
        Capture capture = read_capture(pcap);
        EXPECT_EQ(capture.status, InputStatus::Ok);
        EXPECT_EQ(capture.telegrams.size(), session.expected.size());
        EXPECT_TRUE(capture.telegrams == session.expected);
    }
}

}  // namespace
}  // namespace dpscope
