// dpscope sniff as a service (issue 30): SIGHUP for logrotate (a file moved away started anew,
// never one overwritten; a rotation's next file; stop with a controlling terminal, reopen
// without), and the whole capture set up by a config file.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "capture/capture_writer.hpp"
#include "simulator/simulator.hpp"
#include "tests/pty_support.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::Capture;
using test::Child;
using test::play;
using test::PseudoTerminal;
using test::read_capture;
using test::Session;
using test::simulate;
using test::slurp;
using test::Sniffer;
using test::Telegrams;
using test::without_idle_gap;

// logrotate moves -w FILE away and sends SIGHUP: the moved file is closed complete, FILE starts
// anew, and the two hold the session between them.
TEST(SniffSighupTest, AFileMovedAwayIsClosedAndStartedAnew) {
    PseudoTerminal pty;
    const std::string pcap = test::temp_path("rotate-me.pcap");
    const std::string moved = pcap + ".1";
    Sniffer sniffer(without_idle_gap(
        {"sniff", "-i", pty.slave, "--baud", "1500000", "-q", "-w", pcap, "--sighup", "reopen"}));
    ASSERT_TRUE(sniffer.ready()) << sniffer.err();
    const Session session = simulate(40);
    const std::size_t half = session.played.size() / 2;
    play(pty, session, true, half);
    ASSERT_TRUE(test::wait_for_records(pcap, half)) << sniffer.err();
    // Not moved: written on.
    sniffer.signal(SIGHUP);
    ASSERT_TRUE(sniffer.err_says("SIGHUP: -w " + pcap + " was not moved away; writing on"))
        << sniffer.err();
    ASSERT_EQ(std::rename(pcap.c_str(), moved.c_str()), 0);
    sniffer.signal(SIGHUP);
    ASSERT_TRUE(sniffer.err_says("SIGHUP: -w " + pcap + " was moved away; writing a new " + pcap))
        << sniffer.err();
    play(pty, test::tail_of(session, half), true);
    ASSERT_TRUE(test::wait_for_records(pcap, session.expected.size() - half)) << sniffer.err();
    sniffer.signal(SIGINT);
    ASSERT_EQ(sniffer.wait(), 0) << sniffer.err();
    Capture first = read_capture(moved);
    Capture second = read_capture(pcap);
    EXPECT_EQ(first.status, InputStatus::Ok);
    EXPECT_EQ(second.status, InputStatus::Ok);
    Telegrams all = first.telegrams;
    all.insert(all.end(), second.telegrams.begin(), second.telegrams.end());
    EXPECT_EQ(all, session.expected);
    // The new file is read at the line's rate too (its header records the line).
    auto stats = test::run_dpscope({"decode", "-q", pcap});
    EXPECT_EQ(stats.exit_code, 0) << stats.err;
    std::remove(pcap.c_str());
    std::remove(moved.c_str());
}

// A file that holds data where FILE was is never overwritten: the capture goes on in the moved
// file.
TEST(SniffSighupTest, AnotherFileInThePlaceIsLeftAlone) {
    PseudoTerminal pty;
    const std::string pcap = test::temp_path("keep-other.pcap");
    const std::string moved = pcap + ".1";
    Sniffer sniffer(without_idle_gap(
        {"sniff", "-i", pty.slave, "--baud", "1500000", "-q", "-w", pcap, "--sighup", "reopen"}));
    ASSERT_TRUE(sniffer.ready()) << sniffer.err();
    const Session session = simulate(20);
    ASSERT_EQ(std::rename(pcap.c_str(), moved.c_str()), 0);
    {
        std::ofstream other(pcap);
        other << "someone else's data\n";
    }
    sniffer.signal(SIGHUP);
    ASSERT_TRUE(sniffer.err_says("is another file now, holding data; it is left alone"))
        << sniffer.err();
    play(pty, session, true);
    ASSERT_TRUE(test::wait_for_records(moved, session.expected.size())) << sniffer.err();
    sniffer.signal(SIGINT);
    ASSERT_EQ(sniffer.wait(), 0) << sniffer.err();
    EXPECT_EQ(slurp(pcap), "someone else's data\n");
    EXPECT_EQ(read_capture(moved).telegrams, session.expected);
    std::remove(pcap.c_str());
    std::remove(moved.c_str());
}

// With a rotation, SIGHUP starts the next file now.
TEST(SniffSighupTest, ARotationStartsItsNextFile) {
    PseudoTerminal pty;
    const std::string pcap = test::temp_path("hup-rotation.pcap");
    Sniffer sniffer(without_idle_gap({"sniff", "-i", pty.slave, "--baud", "1500000", "-q", "-w",
                                      pcap, "--rotate-size", "100M", "--sighup", "reopen"}));
    ASSERT_TRUE(sniffer.ready()) << sniffer.err();
    // Nothing written yet: nothing to start.
    sniffer.signal(SIGHUP);
    ASSERT_TRUE(sniffer.err_says("holds no telegram yet; writing on")) << sniffer.err();
    const Session session = simulate(40);
    const std::size_t half = session.played.size() / 2;
    play(pty, session, true, half);
    ASSERT_TRUE(test::wait_for_records(pcap, half, true)) << sniffer.err();
    sniffer.signal(SIGHUP);
    ASSERT_TRUE(sniffer.err_says("SIGHUP: started " + rotated_file_name(pcap, 2))) << sniffer.err();
    play(pty, test::tail_of(session, half), true);
    ASSERT_TRUE(test::wait_for_records(pcap, session.expected.size(), true)) << sniffer.err();
    sniffer.signal(SIGINT);
    ASSERT_EQ(sniffer.wait(), 0) << sniffer.err();
    Capture first = read_capture(rotated_file_name(pcap, 1));
    Capture second = read_capture(rotated_file_name(pcap, 2));
    EXPECT_EQ(first.telegrams.size(), half);
    Telegrams all = first.telegrams;
    all.insert(all.end(), second.telegrams.begin(), second.telegrams.end());
    EXPECT_EQ(all, session.expected);
    std::remove(rotated_file_name(pcap, 1).c_str());
    std::remove(rotated_file_name(pcap, 2).c_str());
}

// --sighup auto (the default): a sniffer without a controlling terminal (a service) reopens;
// one with a terminal stops, as when the terminal hangs up.
TEST(SniffSighupTest, AutoReopensForAServiceAndStopsForATerminal) {
    PseudoTerminal pty;
    const std::string pcap = test::temp_path("hup-auto.pcap");
    {
        test::ChildOptions service;
        service.new_session = true;
        Child sniffer(test::dpscope_argv(without_idle_gap(
                          {"sniff", "-i", pty.slave, "--baud", "1500000", "-q", "-w", pcap})),
                      service);
        ASSERT_TRUE(sniffer.err_says("capturing on")) << sniffer.err();
        sniffer.signal(SIGHUP);
        ASSERT_TRUE(sniffer.err_says("SIGHUP: -w " + pcap + " was not moved away"))
            << sniffer.err();
        sniffer.signal(SIGINT);
        EXPECT_EQ(sniffer.wait(), 0) << sniffer.err();
    }
    {
        PseudoTerminal terminal;
        test::ChildOptions interactive;
        interactive.new_session = true;
        interactive.controlling_terminal = terminal.slave;
        Child sniffer(test::dpscope_argv(without_idle_gap(
                          {"sniff", "-i", pty.slave, "--baud", "1500000", "-q", "-w", pcap})),
                      interactive);
        ASSERT_TRUE(sniffer.err_says("capturing on")) << sniffer.err();
        sniffer.signal(SIGHUP);
        EXPECT_EQ(sniffer.wait(), 0) << sniffer.err();
        EXPECT_EQ(sniffer.err().find("SIGHUP:"), std::string::npos) << sniffer.err();
    }
    std::remove(pcap.c_str());
}

// Everything sniff takes can come from a config file: a service's capture, set up by the file
// alone, runs as the same command line would.
TEST(SniffSighupTest, AConfigFileSetsUpTheWholeCapture) {
    PseudoTerminal pty;
    const std::string folder = test::temp_path("service");
    std::filesystem::create_directories(folder);
    const std::string config = folder + "/line3.conf";
    const std::string pcap = folder + "/line3.pcap";
    {
        std::ofstream out(config);
        out << "# line 3, drives 3 to 5\n"
            << "interface = " << pty.slave << "\n"
            << "baud = 1500000\n"
            << "idle-gap-ms = 0\n"
            << "write = " << pcap << "\n"
            << "rotate-size = 1M\n"
            << "ring = 3\n"
            << "display-filter = dpscope.station == 3\n"
            << "status-file = " << folder << "/status\n"
            << "trigger = dpscope.finding == \"stacked_request\"\n"
            << "trigger-dir = " << folder << "\n"
            << "stats-file = " << folder << "/stats.json\n"
            << "stats-format = json\n";
    }
    Sniffer sniffer({"sniff", "--config", config});
    ASSERT_TRUE(sniffer.ready()) << sniffer.err();
    SimulatorOptions options;
    options.cycles = 60;
    options.faults.push_back(*parse_fault_spec("stacked_request@20:3"));
    const Session session = simulate(options);
    play(pty, session, true);
    ASSERT_TRUE(test::wait_for_records(pcap, session.expected.size(), true)) << sniffer.err();
    sniffer.signal(SIGINT);
    ASSERT_EQ(sniffer.wait(), 0) << sniffer.err();
    EXPECT_EQ(read_capture(rotated_file_name(pcap, 1)).telegrams, session.expected);
    // -Y from the file: only station 3's telegrams are shown.
    const std::vector<std::string> lines = test::lines_of(sniffer.out());
    ASSERT_FALSE(lines.empty());
    EXPECT_TRUE(std::all_of(lines.begin(), lines.end(), [](const std::string& l) {
        return l.find(" → 3 ") != std::string::npos || l.find(" 3 → ") != std::string::npos;
    })) << sniffer.out();
    EXPECT_TRUE(std::filesystem::exists(folder + "/status"));
    EXPECT_NE(slurp(folder + "/stats.json").find("\"stations\""), std::string::npos);
    bool window = false;
    for (const auto& entry : std::filesystem::directory_iterator(folder))
        window = window || entry.path().filename().string().starts_with("trigger-");
    EXPECT_TRUE(window) << sniffer.err();
    std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace dpscope
