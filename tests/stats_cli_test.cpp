// dpscope stats from the command line, and the bus-health options of report: help, wrong options
// (format, thresholds, settings file), the PROFIBUS-only refusal, -w never onto the input and
// left as it was by a failed run, and the exit codes of --fail-on.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdio>
#include <string>
#include <vector>

#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::CommandResult;
using test::run_dpscope;

const std::string kFaults = "samples/faults.pcap";
const std::string kClean = "samples/ppo2.pcap";
constexpr const char* kBaud = "1500000";  // the rate samples/ were simulated at

std::string file_text(const std::string& path) {
    std::vector<std::uint8_t> bytes = test::read_file(path);
    return std::string(bytes.begin(), bytes.end());
}

void expect_usage_error(const CommandResult& r, const std::string& message) {
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_NE(r.err.find(message), std::string::npos) << "expected '" << message << "' in:\n"
                                                      << r.err;
}

TEST(StatsCliTest, HelpExplainsEveryOptionAndTheExitCodes) {
    CommandResult r = run_dpscope({"stats", "--help"});
    EXPECT_EQ(r.exit_code, 0);
    for (const char* option :
         {"-r,--read", "--input-format", "-T,--format", "text,json,markdown,html,csv", "-w,--write",
          "--fail-on", "bad,weak,never", "--baud", "--health-config", "--threshold", "NAME=VALUE",
          "-c,--count", "--bus", "--ppo", "Exit codes:", "For stats, 1 means", "PROFIBUS",
          "lost_cycles (default 3, 1 to 1000)", "bus_load_percent_bad"})
        EXPECT_NE(r.out.find(option), std::string::npos) << option << " missing from:\n" << r.out;
    CommandResult app = run_dpscope({"--help"});
    EXPECT_NE(app.out.find("stats"), std::string::npos) << app.out;
    CommandResult report = run_dpscope({"report", "--help"});
    for (const char* option : {"--health-config", "--threshold", "--baud"})
        EXPECT_NE(report.out.find(option), std::string::npos) << option;
}

TEST(StatsCliTest, WritesTheStatisticsOfAProfibusCapture) {
    for (const char* format : {"text", "json", "markdown", "html", "csv"}) {
        CommandResult r = run_dpscope({"stats", "-T", format, "--baud", kBaud, kClean});
        EXPECT_EQ(r.exit_code, 0) << format << ": " << r.err;
        EXPECT_FALSE(r.out.empty()) << format;
        EXPECT_TRUE(r.err.empty()) << format << ": " << r.err;
    }
    // -r, a file name and standard input read the same.
    CommandResult positional = run_dpscope({"stats", "-T", "json", kClean});
    CommandResult read = run_dpscope({"stats", "-T", "json", "-r", kClean});
    EXPECT_EQ(read.out, positional.out);
    CommandResult piped = run_dpscope({"stats", "-T", "json", "-"}, file_text(kClean));
    EXPECT_EQ(piped.exit_code, 0) << piped.err;
    EXPECT_FALSE(piped.out.empty());
}

TEST(StatsCliTest, WrongFormatAndMissingInputAreUsageErrors) {
    expect_usage_error(run_dpscope({"stats", "-T", "jsonl", kClean}),
                       "--format: 'jsonl' is not one of text, json, markdown, html, csv");
    expect_usage_error(run_dpscope({"stats", "--fail-on", "error", kClean}), "--fail-on");
    expect_usage_error(run_dpscope({"stats"}), "stats: no input; give a FILE or -r FILE");
    expect_usage_error(run_dpscope({"stats", "samples/no-such.pcap"}), "samples/no-such.pcap");
    expect_usage_error(run_dpscope({"stats", "--baud", "1200", kClean}),
                       "--baud: must be a whole number from 9600 to 12000000 baud, not '1200'");
    expect_usage_error(run_dpscope({"stats", "-c", "0", kClean}), "-c");
}

TEST(StatsCliTest, WrongThresholdsAreUsageErrorsNamingThem) {
    expect_usage_error(run_dpscope({"stats", "--threshold", "lost_cycle=3", kClean}),
                       "dpscope: error: --threshold lost_cycle=3: unknown threshold 'lost_cycle'; "
                       "the thresholds are: lost_cycles,");
    expect_usage_error(
        run_dpscope({"stats", "--threshold", "lost_cycles=0", kClean}),
        "dpscope: error: --threshold lost_cycles=0: threshold lost_cycles: 0 is out of range; "
        "give 1 to 1000");
    expect_usage_error(run_dpscope({"stats", "--threshold", "repeat_percent_bad=101", kClean}),
                       "threshold repeat_percent_bad: 101 is out of range; give 0 to 100 %");
    expect_usage_error(run_dpscope({"stats", "--threshold", "lost_cycles=2.5", kClean}),
                       "threshold lost_cycles: 2.5 is not a whole number");
    expect_usage_error(run_dpscope({"stats", "--threshold", "lost_cycles=three", kClean}),
                       "threshold lost_cycles: 'three' is not a number");
    expect_usage_error(run_dpscope({"stats", "--threshold", "lost_cycles", kClean}),
                       "--threshold lost_cycles: 'lost_cycles' is no threshold setting; write "
                       "NAME=VALUE");
    // report takes the same options, with the same errors.
    expect_usage_error(run_dpscope({"report", "--threshold", "lost_cycle=3", kClean}),
                       "--threshold lost_cycle=3: unknown threshold 'lost_cycle'");
}

TEST(StatsCliTest, SettingsFileErrorsNameTheFileAndLine) {
    const std::string missing = test::temp_path("no-such-health.toml");
    expect_usage_error(
        run_dpscope({"stats", "--health-config", missing, kClean}),
        "dpscope: error: --health-config " + missing + ": cannot read: No such file or directory");
    expect_usage_error(run_dpscope({"stats", "--health-config", test::source_dir(), kClean}),
                       "--health-config " + test::source_dir() + ": not a regular file");

    const std::string bad = test::temp_path("health-bad.toml");
    test::write_text_file(bad, "# thresholds\n[thresholds]\nlost_cycles = 4\nrepeat_percent = 2\n");
    expect_usage_error(
        run_dpscope({"stats", "--health-config", bad, kClean}),
        "dpscope: error: --health-config " + bad + ":4: unknown threshold 'repeat_percent'");
    const std::string range = test::temp_path("health-range.ini");
    test::write_text_file(range, "lost_cycles = 4\n\n; comment\nfcs_error_percent_bad = 200\n");
    expect_usage_error(run_dpscope({"report", "--health-config", range, kClean}),
                       range + ":4: threshold fcs_error_percent_bad: 200 is out of range");
    const std::string section = test::temp_path("health-section.ini");
    test::write_text_file(section, "[limits]\nlost_cycles = 4\n");
    expect_usage_error(run_dpscope({"stats", "--health-config", section, kClean}),
                       section + ":1: unknown section '[limits]'");

    const std::string good = test::temp_path("health-good.toml");
    test::write_text_file(good, "[thresholds]\nlost_cycles = 5  # slow master\n");
    CommandResult r = run_dpscope(
        {"stats", "--health-config", good, "--threshold", "lost_cycles=6", "-T", "json", kClean});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    CommandResult report = run_dpscope({"report", "--health-config", good, kClean});
    EXPECT_EQ(report.exit_code, 0) << report.err;
}

// A settings file that is no settings file is refused before it is read whole: a device that
// never ends, a FIFO, a file too large; a line quoted in an error is cut and shown without
// control characters or invalid UTF-8.
TEST(StatsCliTest, HostileSettingsFilesAreRefusedAndQuotedSafely) {
    expect_usage_error(run_dpscope({"stats", "--health-config", "/dev/zero", kClean}),
                       "dpscope: error: --health-config /dev/zero: not a regular file");
    const std::string fifo = test::temp_path("health.fifo");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    // Opened for reading, a FIFO waits for a writer: it is refused without waiting.
    expect_usage_error(run_dpscope({"stats", "--health-config", fifo, kClean}),
                       "--health-config " + fifo + ": not a regular file");
    const std::string big = test::temp_path("big.toml");
    test::write_text_file(big, std::string(200 * 1024, '#') + "\n");
    expect_usage_error(run_dpscope({"stats", "--health-config", big, kClean}),
                       "--health-config " + big + ": larger than 64 KiB");
    const std::string hostile = test::temp_path("hostile.toml");
    test::write_text_file(hostile, "lost_cycles = " + std::string(5000, 'x') + "\x1b[2J\xff\n");
    CommandResult quoted = run_dpscope({"stats", "--health-config", hostile, kClean});
    expect_usage_error(quoted, "--health-config " + hostile + ":1: threshold lost_cycles: '" +
                                   std::string(80, 'x') + "...' is not a number");
    EXPECT_LT(quoted.err.size(), 400u);
    const std::string section = test::temp_path("section.toml");
    test::write_text_file(section, "[sec\x1b[2J\xff]\n");
    CommandResult escaped = run_dpscope({"stats", "--health-config", section, kClean});
    expect_usage_error(escaped, "unknown section '[sec\xEF\xBF\xBD[2J\xEF\xBF\xBD]'");
    EXPECT_EQ(escaped.err.find('\x1b'), std::string::npos);
}

TEST(StatsCliTest, FcAndVlt2000CapturesAreRefused) {
    const std::string out = test::temp_path("stats-refused.txt");
    test::write_text_file(out, "before\n");
    CommandResult fc = run_dpscope({"stats", "-w", out, "samples/fc.pcap"});
    expect_usage_error(fc,
                       "dpscope: error: samples/fc.pcap: an FC protocol capture; bus health "
                       "(stats) is PROFIBUS-only");
    EXPECT_EQ(file_text(out), "before\n") << "a refused run leaves -w FILE as it was";
    expect_usage_error(run_dpscope({"stats", "samples/vlt2000.pcap"}),
                       "samples/vlt2000.pcap: a VLT 2000 capture; bus health (stats) is "
                       "PROFIBUS-only");
    expect_usage_error(run_dpscope({"stats", "--bus", "fc", "samples/fc-examples.hex"}),
                       "an FC protocol capture; bus health (stats) is PROFIBUS-only");
    // report takes them, without a bus-health section (and the health options do no harm).
    CommandResult report =
        run_dpscope({"report", "--threshold", "lost_cycles=5", "samples/fc-clean.pcap"});
    EXPECT_EQ(report.exit_code, 0) << report.err;
}

TEST(StatsCliTest, WriteNeverOntoTheInputAndAtomically) {
    const std::string capture = test::temp_path("stats-input.pcap");
    test::write_file(capture, test::read_file(test::source_dir() + "/" + kClean));
    expect_usage_error(run_dpscope({"stats", "-w", capture, capture}), "-w");
    EXPECT_EQ(test::read_file(capture), test::read_file(test::source_dir() + "/" + kClean));

    const std::string out = test::temp_path("stats-out.json");
    CommandResult written = run_dpscope({"stats", "-T", "json", "-w", out, kClean});
    EXPECT_EQ(written.exit_code, 0) << written.err;
    EXPECT_TRUE(written.out.empty());
    EXPECT_EQ(file_text(out), run_dpscope({"stats", "-T", "json", kClean}).out);
    // An unusable input leaves the file as it was.
    const std::string garbage = test::temp_path("stats-garbage.raw");
    test::write_text_file(garbage, "");
    CommandResult empty = run_dpscope({"stats", "-w", out, garbage});
    EXPECT_EQ(empty.exit_code, 2) << empty.err;
    EXPECT_EQ(file_text(out), run_dpscope({"stats", "-T", "json", kClean}).out);
    // An output in a directory that does not exist: exit 4.
    CommandResult nowhere = run_dpscope({"stats", "-w", "/nonexistent/dir/stats.txt", kClean});
    EXPECT_EQ(nowhere.exit_code, 4) << nowhere.err;
}

TEST(StatsCliTest, FailOnSetsTheExitCodeFromTheSegmentVerdict) {
    // The clean capture is good: 0 whatever --fail-on says.
    const auto clean = [](const char* fail_on, std::vector<std::string> more = {}) {
        std::vector<std::string> args = {"stats", "--fail-on", fail_on, "--baud", kBaud};
        for (std::string& arg : more)
            args.push_back(std::move(arg));
        args.push_back(kClean);
        return run_dpscope(args).exit_code;
    };
    for (const char* fail_on : {"bad", "weak", "never"})
        EXPECT_EQ(clean(fail_on), 0) << fail_on;
    // Any load above 0 % weak: exit 1 with --fail-on weak only.
    const std::vector<std::string> load_weak = {"--threshold", "bus_load_percent_weak=0"};
    EXPECT_EQ(clean("bad", load_weak), 0);
    EXPECT_EQ(clean("weak", load_weak), 1);
    // Any load above 0 % bad: exit 1 by default, 0 with --fail-on never.
    EXPECT_EQ(
        run_dpscope({"stats", "--baud", kBaud, "--threshold", "bus_load_percent_bad=0", kClean})
            .exit_code,
        1);
    EXPECT_EQ(clean("never", {"--threshold", "bus_load_percent_bad=0"}), 0);
    // Without --baud the load is unknown and judges nothing.
    EXPECT_EQ(run_dpscope({"stats", "--threshold", "bus_load_percent_bad=0", kClean}).exit_code, 0);
    // The command line wins over the settings file; the last --threshold for a name wins.
    const std::string config = test::temp_path("health-load.toml");
    test::write_text_file(config, "[thresholds]\nbus_load_percent_bad = 0\n");
    EXPECT_EQ(clean("bad", {"--health-config", config}), 1);
    EXPECT_EQ(clean("bad", {"--health-config", config, "--threshold", "bus_load_percent_bad=100"}),
              0);
    EXPECT_EQ(clean("bad", {"--threshold", "bus_load_percent_bad=100", "--threshold",
                            "bus_load_percent_bad=0"}),
              1);
    // The faults capture (damaged telegrams on two slaves' links) is bad.
    EXPECT_EQ(run_dpscope({"stats", kFaults}).exit_code, 1);
    EXPECT_EQ(run_dpscope({"stats", "--fail-on", "never", kFaults}).exit_code, 0);
    // report reads the same thresholds: its exit code follows its findings, not the verdict.
    CommandResult report = run_dpscope(
        {"report", "-T", "json", "--baud", kBaud, "--threshold", "bus_load_percent_bad=0", kClean});
    EXPECT_EQ(report.exit_code, 0) << report.err;
    for (const char* member : {"\"bus_health\"", "\"baud\":1500000", "\"load_percent\":23.774",
                               "\"bus_load_percent_bad\":0"})
        EXPECT_NE(report.out.find(member), std::string::npos) << member;
}

TEST(StatsCliTest, TruncatedCaptureExitsThreeUnlessTheVerdictFails) {
    CommandResult r = run_dpscope({"stats", "samples/truncated.pcap"});
    EXPECT_EQ(r.exit_code, 3) << r.err;
    EXPECT_FALSE(r.out.empty());
    CommandResult counted = run_dpscope({"stats", "-c", "10", "-T", "json", kClean});
    EXPECT_EQ(counted.exit_code, 0) << counted.err;
}

TEST(StatsCliTest, ABaudRateTooLowForTheCaptureIsWarnedAbout) {
    // samples/bus-health.pcap was made at 1500000 baud: at 187500 its telegrams need about three
    // times the capture's length.
    CommandResult slow = run_dpscope({"stats", "--baud", "187500", "samples/bus-health.pcap"});
    EXPECT_NE(slow.err.find("the line was faster than --baud says"), std::string::npos) << slow.err;
    CommandResult right = run_dpscope({"stats", "--baud", kBaud, "samples/bus-health.pcap"});
    EXPECT_EQ(right.err.find("the line was faster"), std::string::npos) << right.err;
}

TEST(StatsCliTest, SniffTakesTheThresholdsToo) {
    // Checked before the device is opened.
    CommandResult bad = run_dpscope(
        {"sniff", "-i", "/nonexistent/tty", "--baud", kBaud, "--stats", "--threshold", "nope=1"});
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_NE(bad.err.find("unknown threshold 'nope'"), std::string::npos) << bad.err;
    CommandResult help = run_dpscope({"sniff", "--help"});
    EXPECT_NE(help.out.find("--health-config"), std::string::npos);
    EXPECT_NE(help.out.find("--threshold"), std::string::npos);
}

}  // namespace
}  // namespace dpscope
