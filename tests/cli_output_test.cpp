// The dpscope executable's outputs: -w never overwrites an input and replaces an existing file
// only when the run succeeds; decode/hex -w writes the telegrams shown as a capture; option
// conflicts; --pnu by transaction; -q with filters; -l and the hex prompt on a terminal.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "core/text_encoding.hpp"
#include "tests/json_parser.hpp"
#include "tests/pty_support.hpp"
#include "tests/test_support.hpp"
#include "tests/xml_parser.hpp"

namespace dpscope {
namespace {

using test::CommandResult;
using test::lines_of;
using test::run_dpscope;

const std::string kFaults = "samples/faults.pcap";

std::string sample(const std::string& relative) { return test::source_dir() + "/" + relative; }

std::string content(const std::string& path) {
    std::vector<std::uint8_t> bytes = test::read_file(path);
    return std::string(bytes.begin(), bytes.end());
}

// A copy of a sample in the test's temporary directory.
std::string copy_of(const std::string& relative, std::string_view name) {
    std::string path = test::temp_path(name);
    test::write_file(path, test::read_file(sample(relative)));
    return path;
}

// No temporary file of dpscope's is left beside `path`.
void expect_no_leftovers(const std::string& path) {
    std::filesystem::path dir = std::filesystem::path(path).parent_path();
    for (const auto& entry : std::filesystem::directory_iterator(dir))
        EXPECT_EQ(entry.path().filename().string().find(".dpscope-"), std::string::npos)
            << entry.path();
}

// The text decode without the frame and time columns (what a conversion must keep).
std::vector<std::string> details_of(const std::string& text) {
    std::vector<std::string> details;
    for (const std::string& line : lines_of(text)) {
        std::istringstream in(line);
        std::string frame, time;
        in >> frame >> time;
        std::string rest;
        std::getline(in, rest);
        details.push_back(rest);
    }
    return details;
}

// ---- never destroy an input ------------------------------------------------------------------

TEST(CliOutputTest, HexCaptureRoundTripKeepsEveryFrameAndItsNumber) {
    // Issue #27 point 4: faults.pcap (458 telegrams, damaged ones among them) written with -F hex
    // and read back came back as 456, fc.pcap 964 as 960, and every later frame was renumbered.
    for (const std::string name : {"faults", "fc", "vlt2000"}) {
        SCOPED_TRACE(name);
        const std::string hex_file = test::temp_path(name + ".txt");
        CommandResult written =
            run_dpscope({"decode", "samples/" + name + ".pcap", "-F", "hex", "-w", hex_file});
        ASSERT_EQ(written.exit_code, 0) << written.err;
        CommandResult from_pcap =
            run_dpscope({"decode", "-T", "jsonl", "samples/" + name + ".pcap"});
        CommandResult from_hex = run_dpscope({"decode", "-T", "jsonl", hex_file});
        EXPECT_EQ(from_hex.exit_code, from_pcap.exit_code) << from_hex.err;
        EXPECT_EQ(lines_of(from_hex.out).size(), lines_of(from_pcap.out).size());
        EXPECT_EQ(from_hex.out, from_pcap.out);
        EXPECT_EQ(from_hex.err.find("read as"), std::string::npos) << from_hex.err;  // tagged
    }
}

TEST(CliOutputTest, RawCaptureOfDamagedTelegramsWarnsWhenWritten) {
    // A raw stream keeps no record boundaries: a damaged telegram written with -F raw is not
    // read back as it was, and the frames after it are numbered differently. Said once, naming
    // the first such frame; a capture without them writes silently.
    const std::string raw = test::temp_path("faults.raw");
    CommandResult r = run_dpscope({"decode", kFaults, "-F", "raw", "-w", raw});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("dpscope: warning: " + raw + ": frame "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("a raw stream keeps no record boundaries"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("-F hex or pcap keep every record"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    const std::string clean = test::temp_path("ppo1.raw");
    CommandResult quiet = run_dpscope({"decode", "samples/ppo1.pcap", "-F", "raw", "-w", clean});
    EXPECT_EQ(quiet.exit_code, 0) << quiet.err;
    EXPECT_TRUE(quiet.err.empty()) << quiet.err;
}

TEST(CliOutputTest, ReportRefusesToWriteOverItsInput) {
    std::string capture = copy_of(kFaults, "capture.pcap");
    const std::string before = content(capture);
    CommandResult same = run_dpscope({"report", "-T", "json", "-w", capture, "-r", capture});
    EXPECT_EQ(same.exit_code, 2);
    EXPECT_EQ(same.err, "dpscope: error: -w " + capture +
                            ": that is the input; writing it would destroy the capture\n");
    EXPECT_EQ(content(capture), before);

    // Through a symbolic link and a hard link: the same file by device and inode.
    std::string symlink = test::temp_path("symlink.pcap");
    ASSERT_EQ(::symlink(capture.c_str(), symlink.c_str()), 0);
    CommandResult linked = run_dpscope({"report", "-T", "html", "-w", symlink, capture});
    EXPECT_EQ(linked.exit_code, 2);
    EXPECT_NE(linked.err.find("that is the same file as the input " + capture), std::string::npos)
        << linked.err;
    std::string hardlink = test::temp_path("hardlink.pcap");
    ASSERT_EQ(::link(capture.c_str(), hardlink.c_str()), 0);
    CommandResult hard = run_dpscope({"report", "-w", capture, hardlink});
    EXPECT_EQ(hard.exit_code, 2) << hard.err;
    EXPECT_EQ(content(capture), before);
    expect_no_leftovers(capture);
}

TEST(CliOutputTest, DecodeRefusesToWriteOverItsInput) {
    std::string capture = copy_of(kFaults, "capture.pcap");
    const std::string before = content(capture);
    CommandResult r = run_dpscope({"decode", capture, "-w", capture});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("-w " + capture + ": that is the input"), std::string::npos) << r.err;
    EXPECT_EQ(content(capture), before);

    // Standard input redirected from the file that -w names.
    std::string command = "'" + test::dpscope_executable() + "' decode -w '" + capture + "' - < '" +
                          capture + "' 2>/dev/null";
    int status = std::system(command.c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 2);
    EXPECT_EQ(content(capture), before);
    // Standard output appended to the input while reading it.
    command = "'" + test::dpscope_executable() + "' decode -w - '" + capture + "' >> '" + capture +
              "' 2>/dev/null";
    status = std::system(command.c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 2);
    EXPECT_EQ(content(capture), before);
}

TEST(CliOutputTest, UnusableInputLeavesAnExistingReportAsItWas) {
    std::string out = test::temp_path("report.json");
    test::write_text_file(out, "the previous report\n");
    std::string empty = test::temp_path("empty.raw");
    test::write_text_file(empty, "");
    CommandResult r = run_dpscope({"report", "-T", "json", "-w", out, empty});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(content(out), "the previous report\n");

    std::string text = test::temp_path("notes.txt");
    test::write_text_file(text, "no hex here, only words\n");
    CommandResult no_hex = run_dpscope({"report", "-w", out, "--input-format", "hex", text});
    EXPECT_EQ(no_hex.exit_code, 2);
    EXPECT_EQ(content(out), "the previous report\n");
    expect_no_leftovers(out);

    // A usable input replaces it, with no temporary file left behind.
    CommandResult ok = run_dpscope({"report", "-T", "json", "-w", out, kFaults});
    EXPECT_EQ(ok.exit_code, 1) << ok.err;  // the sample has errors
    EXPECT_EQ(content(out).rfind("{\"dpscope\":", 0), 0u);
    expect_no_leftovers(out);
}

TEST(CliOutputTest, ReportKeepsTheModeOfTheFileItReplaces) {
    std::string out = test::temp_path("report.txt");
    test::write_text_file(out, "old\n");
    ASSERT_EQ(::chmod(out.c_str(), 0640), 0);
    CommandResult r = run_dpscope({"report", "--fail-on", "never", "-w", out, kFaults});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    struct stat info {};
    ASSERT_EQ(::stat(out.c_str(), &info), 0);
    EXPECT_EQ(info.st_mode & 0777, 0640u);
    EXPECT_NE(content(out).find("conformance report"), std::string::npos);
}

TEST(CliOutputTest, DecodeWriteIntoADeviceWritesDirectly) {
    CommandResult r = run_dpscope({"decode", kFaults, "-w", "/dev/null"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(r.out.empty());
    CommandResult full = run_dpscope({"decode", kFaults, "-w", "/dev/full"});
    EXPECT_EQ(full.exit_code, 4);
    EXPECT_NE(full.err.find("dpscope: error: /dev/full: write failed: No space left on device"),
              std::string::npos)
        << full.err;
}

// ---- decode -w: the telegrams shown, as a capture -----------------------------------------------

TEST(CliOutputTest, DecodeWriteTurnsARawDumpIntoAPcap) {
    std::string pcap = test::temp_path("serial.pcap");
    CommandResult w = run_dpscope({"decode", "samples/serial.raw", "-w", pcap});
    EXPECT_EQ(w.exit_code, 0) << w.err;
    EXPECT_TRUE(w.out.empty()) << "-w without -P prints nothing";
    std::vector<std::uint8_t> bytes = test::read_file(pcap);
    ASSERT_GE(bytes.size(), 24u);
    EXPECT_EQ(bytes[20] | bytes[21] << 8, 257);  // link type PROFIBUS_DL
    CommandResult raw = run_dpscope({"decode", "samples/serial.raw"});
    CommandResult back = run_dpscope({"decode", pcap});
    EXPECT_EQ(back.exit_code, 0) << back.err;
    EXPECT_EQ(details_of(back.out), details_of(raw.out));

    CommandResult user0 =
        run_dpscope({"decode", "samples/serial.raw", "-w", pcap, "--linktype", "user0"});
    EXPECT_EQ(user0.exit_code, 0) << user0.err;
    bytes = test::read_file(pcap);
    EXPECT_EQ(bytes[20] | bytes[21] << 8, 147);
}

TEST(CliOutputTest, DecodeWriteKeepsOnlyWhatIsShownAndPrintsWithP) {
    std::string pcap = test::temp_path("cut.pcap");
    CommandResult w =
        run_dpscope({"decode", kFaults, "--station", "4", "-c", "300", "-w", pcap, "-P"});
    EXPECT_EQ(w.exit_code, 0) << w.err;
    CommandResult shown = run_dpscope({"decode", kFaults, "--station", "4", "-c", "300"});
    EXPECT_EQ(w.out, shown.out);  // -P prints what is written
    CommandResult back = run_dpscope({"decode", "-T", "jsonl", pcap});
    std::vector<std::string> lines = lines_of(back.out);
    EXPECT_EQ(lines.size(), lines_of(shown.out).size());
    for (const std::string& line : lines) {
        bool four = line.find("\"da\":4,") != std::string::npos ||
                    line.find("\"sa\":4,") != std::string::npos ||
                    line.find("\"sd\":\"SC\"") != std::string::npos;
        EXPECT_TRUE(four) << line;
    }
}

TEST(CliOutputTest, PcapngCarriesFindingsAsPacketComments) {
    std::string pcapng = test::temp_path("faults.pcapng");
    CommandResult w = run_dpscope({"decode", kFaults, "-F", "pcapng", "-w", pcapng});
    EXPECT_EQ(w.exit_code, 0) << w.err;
    std::string bytes = content(pcapng);
    EXPECT_NE(bytes.find("note request_rejected: "), std::string::npos);
    EXPECT_NE(bytes.find("error stacked_request: "), std::string::npos);
    // The comments change nothing of the telegrams: the same decode, times included.
    CommandResult original = run_dpscope({"decode", kFaults});
    CommandResult back = run_dpscope({"decode", pcapng});
    EXPECT_EQ(back.exit_code, 0) << back.err;
    EXPECT_EQ(back.out, original.out);
}

TEST(CliOutputTest, DecodeWriteToStandardOutputMovesTextAside) {
    CommandResult pcap = run_dpscope({"decode", "-c", "3", kFaults, "-w", "-"});
    EXPECT_EQ(pcap.exit_code, 0) << pcap.err;
    ASSERT_GE(pcap.out.size(), 24u);
    EXPECT_EQ(static_cast<unsigned char>(pcap.out[0]), 0x4D);  // nanosecond pcap magic
    CommandResult back = run_dpscope({"decode", "-"}, pcap.out);
    EXPECT_EQ(lines_of(back.out).size(), 3u);
    CommandResult p = run_dpscope({"decode", kFaults, "-w", "-", "-P"});
    EXPECT_EQ(p.exit_code, 2);
    EXPECT_NE(p.err.find("-P prints the decode on standard output"), std::string::npos);
}

TEST(CliOutputTest, WriteOptionsWithoutWriteAreUsageErrors) {
    CommandResult f = run_dpscope({"decode", "-F", "pcapng", kFaults});
    EXPECT_EQ(f.exit_code, 2);
    EXPECT_EQ(f.err, "dpscope: error: -F goes with -w FILE, which is not given\n");
    CommandResult p = run_dpscope({"decode", "-P", kFaults});
    EXPECT_EQ(p.exit_code, 2);
    CommandResult link = run_dpscope({"decode", "--linktype", "1", "-w", "/dev/null", kFaults});
    EXPECT_EQ(link.exit_code, 2);
}

TEST(CliOutputTest, HexWritesTypedTelegramsAsACapture) {
    std::string pcap = test::temp_path("typed.pcap");
    CommandResult w = run_dpscope({"hex", "10 03 02 49 4E 16", "-w", pcap});
    EXPECT_EQ(w.exit_code, 0) << w.err;
    CommandResult back = run_dpscope({"decode", pcap});
    EXPECT_NE(back.out.find("2 → 3   SD1 FDL_Status     req"), std::string::npos) << back.out;
}

// ---- what is shown ---------------------------------------------------------------------------

TEST(CliOutputTest, PnuFilterShowsTheRejectionWithoutPnuOfThatParameter) {
    CommandResult r = run_dpscope({"decode", "--pnu", "207", kFaults});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    bool rejection = false;
    for (const std::string& line : lines_of(r.out)) {
        if (line.find("RC=7") == std::string::npos) continue;
        EXPECT_NE(line.find("PNU=0"), std::string::npos) << line;
        if (line.find("[note request_rejected]") != std::string::npos) rejection = true;
    }
    EXPECT_TRUE(rejection) << r.out;
    // A request about another parameter does not show that rejection.
    CommandResult other = run_dpscope({"decode", "--pnu", "516", kFaults});
    EXPECT_EQ(other.out.find("request_rejected"), std::string::npos) << other.out;
}

TEST(CliOutputTest, QuietWithAFilterSummarisesTheTelegramsSelected) {
    CommandResult shown = run_dpscope({"decode", "--station", "4", kFaults});
    CommandResult q = run_dpscope({"decode", "-q", "--station", "4", kFaults});
    EXPECT_EQ(q.exit_code, 0) << q.err;
    EXPECT_NE(q.out.find(", telegrams of the --station list (pcap)"), std::string::npos) << q.out;
    EXPECT_NE(q.out.find("  telegrams: " + std::to_string(lines_of(shown.out).size()) + ","),
              std::string::npos)
        << q.out;
    EXPECT_NE(q.out.find("      4: PPO 2"), std::string::npos) << q.out;
    EXPECT_EQ(q.out.find("      3: PPO"), std::string::npos) << q.out;
    EXPECT_EQ(q.out.find("      5: PPO"), std::string::npos) << q.out;
}

TEST(CliOutputTest, ConflictingOptionsAreUsageErrors) {
    CommandResult jsonl = run_dpscope({"decode", "-q", "-T", "jsonl", kFaults});
    EXPECT_EQ(jsonl.exit_code, 2);
    EXPECT_EQ(jsonl.err,
              "dpscope: error: -q prints only the text summary; it cannot be combined with -T "
              "jsonl (drop one of them)\n");
    EXPECT_TRUE(jsonl.out.empty());
    EXPECT_EQ(run_dpscope({"decode", "-q", "-V", kFaults}).exit_code, 2);
    EXPECT_EQ(run_dpscope({"hex", "-q", "-T", "text", "10 03 02 49 4E 16"}).exit_code, 2);

    CommandResult ppo = run_dpscope({"decode", "--ppo", "3=1", "--ppo", "3=2", kFaults});
    EXPECT_EQ(ppo.exit_code, 2);
    EXPECT_EQ(ppo.err,
              "dpscope: error: --ppo 3=2: slave 3 was already given PPO 1; give one type a "
              "slave\n");
    EXPECT_EQ(run_dpscope({"decode", "-q", "--ppo", "3=1", "--ppo", "3=1", kFaults}).exit_code, 0);
    CommandResult all =
        run_dpscope({"decode", "--dialect", "vlt", "--dialect", "profidrive", kFaults});
    EXPECT_EQ(all.exit_code, 2);
    EXPECT_NE(all.err.find("the dialect for every slave was already given as vlt"),
              std::string::npos);
    CommandResult one =
        run_dpscope({"report", "--dialect", "4=vlt", "--dialect", "4=profidrive", kFaults});
    EXPECT_EQ(one.exit_code, 2);
    EXPECT_NE(one.err.find("slave 4 was already given the vlt dialect"), std::string::npos);
    // A dialect for all slaves and another for one slave do not conflict.
    EXPECT_EQ(
        run_dpscope({"decode", "-q", "--dialect", "vlt", "--dialect", "4=profidrive", kFaults})
            .exit_code,
        0);
}

TEST(CliOutputTest, PpoOptionContradictingTheConfigurationIsAWarning) {
    CommandResult r = run_dpscope({"decode", "-q", "--ppo", "3=2", kFaults});
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_EQ(r.err,
              "dpscope: warning: --ppo 3=2: the Chk_Cfg in frame 7 announces PPO 1 for slave 3; "
              "decoded as PPO 2, as the option says\n");
    CommandResult agrees = run_dpscope({"decode", "-q", "--ppo", "3=1", kFaults});
    EXPECT_TRUE(agrees.err.empty()) << agrees.err;
    CommandResult report = run_dpscope({"report", "--ppo", "4=5", kFaults});
    EXPECT_NE(report.err.find("--ppo 4=5: the Chk_Cfg in frame"), std::string::npos) << report.err;
}

TEST(CliOutputTest, NumericOptionsNameTheirRange) {
    for (std::string value : {"1e18", "18446744073709551616", "nan", "-3", "0x10", "5.5"}) {
        CommandResult r = run_dpscope({"decode", "-c", value, kFaults});
        EXPECT_EQ(r.exit_code, 2) << value;
        EXPECT_NE(r.err.find("--count: must be a whole number from 1 to 9223372036854775807 "
                             "telegrams, not '" +
                             value + "'"),
                  std::string::npos)
            << r.err;
        EXPECT_TRUE(r.out.empty());
    }
    CommandResult timeout = run_dpscope({"report", "--timeout-ms", "inf", kFaults});
    EXPECT_EQ(timeout.exit_code, 2);
    EXPECT_NE(timeout.err.find("must be a whole number from 1 to 3600000 ms, not 'inf'"),
              std::string::npos)
        << timeout.err;
    EXPECT_EQ(run_dpscope({"decode", "--station", "128", kFaults}).exit_code, 2);
    EXPECT_EQ(run_dpscope({"decode", "--pnu", "65536", kFaults}).exit_code, 2);
}

// ---- -l and the terminal -----------------------------------------------------------------------

// dpscope ARGS with standard input from `stdin_fd`; its standard output and error are pipes.
struct Child {
    pid_t pid = -1;
    int out = -1;
    int err = -1;
    Child(const std::vector<std::string>& args, int stdin_fd) {
        int out_pipe[2], err_pipe[2];
        EXPECT_EQ(::pipe(out_pipe), 0);
        EXPECT_EQ(::pipe(err_pipe), 0);
        pid = ::fork();
        if (pid == 0) {
            ::dup2(stdin_fd, 0);
            ::dup2(out_pipe[1], 1);
            ::dup2(err_pipe[1], 2);
            test::exec_or_exit(test::dpscope_argv(args));
        }
        ::close(out_pipe[1]);
        ::close(err_pipe[1]);
        out = out_pipe[0];
        err = err_pipe[0];
    }
    ~Child() {
        if (pid > 0) {
            ::kill(pid, SIGKILL);
            ::waitpid(pid, nullptr, 0);
        }
        ::close(out);
        ::close(err);
    }
};

TEST(CliOutputTest, LineBufferedOutputReachesAPipeBeforeTheInputEnds) {
    int in[2];
    ASSERT_EQ(::pipe(in), 0);
    Child child({"hex", "-l", "-T", "text"}, in[0]);
    ::close(in[0]);
    const std::string line = "10 03 02 49 4E 16\n";
    ASSERT_EQ(::write(in[1], line.data(), line.size()), static_cast<ssize_t>(line.size()));
    // The input stays open: without -l the line would wait in the output buffer until the end.
    std::string out = test::read_until(child.out, "\n");
    EXPECT_NE(out.find("SD1 FDL_Status"), std::string::npos) << out;
    ::close(in[1]);
}

TEST(CliOutputTest, HexOnATerminalSaysItWaitsForInput) {
    test::PseudoTerminal terminal;
    int slave = ::open(terminal.slave.c_str(), O_RDWR | O_NOCTTY);
    ASSERT_GE(slave, 0);
    Child child({"hex"}, slave);
    ::close(slave);
    std::string err = test::read_until(child.err, "Ctrl-D");
    EXPECT_NE(err.find("dpscope hex: reading a hex log from the terminal"), std::string::npos)
        << err;
}

TEST(CliOutputTest, LineBufferedRawInputOnAPipeIsDecodedAsItArrives) {
    int in[2];
    ASSERT_EQ(::pipe(in), 0);
    Child child({"decode", "-l", "--input-format", "raw", "-"}, in[0]);
    ::close(in[0]);
    const std::vector<std::uint8_t> bytes = test::hex("10 03 02 49 4E 16 10 03 02 49 4E 16");
    ASSERT_EQ(::write(in[1], bytes.data(), bytes.size()), static_cast<ssize_t>(bytes.size()));
    // 12 bytes, not the 64 KiB a whole read buffer holds: they are decoded at once.
    std::string out = test::read_until(child.out, "\n");
    EXPECT_NE(out.find("SD1 FDL_Status"), std::string::npos) << out;
    ::close(in[1]);
}

// ---- from the new-user review -------------------------------------------------------------------

TEST(CliOutputTest, SniffRefusesToWriteOntoTheCaptureDevice) {
    test::PseudoTerminal pty;
    CommandResult w = run_dpscope({"sniff", "-i", pty.slave, "--baud", "9600", "-w", pty.slave});
    EXPECT_EQ(w.exit_code, 2);
    EXPECT_EQ(w.err, "dpscope: error: -w " + pty.slave + ": that is the capture device -i " +
                         pty.slave + "; writing to it would send the bytes onto the bus\n");
    CommandResult report =
        run_dpscope({"sniff", "-i", pty.slave, "--baud", "9600", "--report-file", pty.slave});
    EXPECT_EQ(report.exit_code, 2);
    EXPECT_NE(report.err.find("--report-file " + pty.slave + ": that is the capture device"),
              std::string::npos)
        << report.err;
}

TEST(CliOutputTest, OptionsThatWouldDoNothingAreUsageErrors) {
    CommandResult link = run_dpscope({"decode", kFaults, "--linktype", "user0"});
    EXPECT_EQ(link.exit_code, 2);
    EXPECT_EQ(link.err, "dpscope: error: --linktype goes with -w FILE, which is not given\n");
    CommandResult format = run_dpscope({"decode", kFaults, "-w", "/dev/null", "-T", "jsonl"});
    EXPECT_EQ(format.exit_code, 2);
    EXPECT_EQ(format.err,
              "dpscope: error: -T jsonl: with -w the decode is not printed; add -P to print it "
              "as well\n");
    EXPECT_EQ(run_dpscope({"decode", kFaults, "-w", "/dev/null", "-T", "jsonl", "-P"}).exit_code,
              0);
    test::PseudoTerminal pty;
    for (std::vector<std::string> extra : {std::vector<std::string>{"--rotate-size", "1M"},
                                           {"--rotate-seconds", "60"},
                                           {"--linktype", "user0"}}) {
        std::vector<std::string> args = {"sniff", "-i", pty.slave, "--baud", "9600"};
        args.insert(args.end(), extra.begin(), extra.end());
        CommandResult r = run_dpscope(args);
        EXPECT_EQ(r.exit_code, 2) << extra[0];
        EXPECT_EQ(r.err, "dpscope: error: " + extra[0] +
                             " is about the capture file of -w FILE, which is not given\n");
    }
    for (std::string command : {"decode", "report", "simulate"}) {
        CommandResult empty = run_dpscope({command, "-w", "", kFaults});
        EXPECT_EQ(empty.exit_code, 2) << command;
        EXPECT_NE(empty.err.find("--write: must be a file name, or - for standard output, not ''"),
                  std::string::npos)
            << empty.err;
    }
}

TEST(CliOutputTest, FiltersThatMatchNothingAreNamed) {
    CommandResult station = run_dpscope({"decode", "--station", "9", kFaults});
    EXPECT_EQ(station.exit_code, 0);
    EXPECT_TRUE(station.out.empty());
    EXPECT_EQ(station.err, "dpscope: warning: --station 9: no telegram to or from station 9 in " +
                               kFaults + "\n");
    CommandResult pnu = run_dpscope({"decode", "--pnu", "999", "--pnu", "207", kFaults});
    EXPECT_FALSE(pnu.out.empty());
    EXPECT_EQ(pnu.err,
              "dpscope: warning: --pnu 999: no parameter request or answer about PNU "
              "999 in " +
                  kFaults + "\n");
    CommandResult report = run_dpscope({"report", "--station", "128", kFaults});
    EXPECT_EQ(report.exit_code, 2);
    EXPECT_NE(report.err.find("--station: must be a whole number from 0 to 127, not '128'"),
              std::string::npos)
        << report.err;
}

TEST(CliOutputTest, AConvertedRawDumpStaysUntimed) {
    std::string pcap = test::temp_path("untimed.pcap");
    ASSERT_EQ(run_dpscope({"decode", "samples/serial.raw", "-w", pcap}).exit_code, 0);
    CommandResult report = run_dpscope({"report", pcap});
    EXPECT_NE(report.out.find("time-outs not judged (no timestamps)"), std::string::npos)
        << report.out;
    EXPECT_EQ(report.out.find("1970-01-01"), std::string::npos) << report.out;
    CommandResult jsonl = run_dpscope({"decode", "-c", "1", "-T", "jsonl", pcap});
    EXPECT_NE(jsonl.out.find("\"time\":null"), std::string::npos) << jsonl.out;
}

TEST(CliOutputTest, JunitSkipsTheTimeOutRulesWithoutTimestamps) {
    CommandResult r = run_dpscope({"report", "-T", "junit", "samples/serial.raw"});
    std::size_t skipped = 0;
    for (const std::string& line : lines_of(r.out))
        if (line.find("<skipped message=\"not judged: the capture carries no timestamps\"/>") !=
            std::string::npos)
            ++skipped;
    EXPECT_GE(skipped, 2u) << r.out;
    EXPECT_EQ(r.out.find("name=\"response_timeout: every request is answered within the "
                         "time-out\"/>"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("skipped=\"2\""), std::string::npos);
    CommandResult timed = run_dpscope({"report", "-T", "junit", kFaults});
    EXPECT_EQ(timed.out.find("<skipped"), std::string::npos);
}

TEST(CliOutputTest, SimulateStartIsDecimal) {
    CommandResult r = run_dpscope({"simulate", "-w", "-", "--start", "0x10"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(r.out.empty());
}

// A file name that is not UTF-8 (and holds a control character) comes out of every format as
// valid UTF-8, U+FFFD for each bad byte: JSON parses, JUnit and the HTML page are well-formed.
TEST(CliOutputTest, EveryOutputIsValidUtf8WhateverTheFileName) {
    const std::string capture = test::temp_folder() + "/cap\xFF\xFE\x01.pcap";
    test::write_file(capture, test::read_file(sample(kFaults)));
    const std::string shown = test::temp_folder() + "/cap\xEF\xBF\xBD\xEF\xBF\xBD\xEF\xBF\xBD.pcap";
    for (const char* format : {"text", "json", "markdown", "html", "junit"}) {
        CommandResult r = run_dpscope({"report", "-T", format, capture});
        EXPECT_EQ(r.exit_code, 1) << format << r.err;
        EXPECT_TRUE(is_valid_utf8(r.out)) << format;
        EXPECT_EQ(r.out.find('\x01'), std::string::npos) << format;
        EXPECT_NE(r.out.find(shown), std::string::npos) << format;
        if (std::string_view(format) == "json") {
            auto json = test::parse_json(r.out);
            ASSERT_TRUE(json) << r.out.substr(0, 200);
            EXPECT_EQ((*json)["input"]["file"].string(), shown);
        }
        if (std::string_view(format) == "junit") {
            EXPECT_TRUE(test::parse_xml(r.out)) << r.out;
        }
        if (std::string_view(format) == "html") {
            EXPECT_TRUE(test::parse_xml(r.out, true));
        }
    }
    for (const char* format : {"text", "json", "markdown", "html"}) {
        CommandResult r = run_dpscope({"stats", "-T", format, capture});
        EXPECT_TRUE(is_valid_utf8(r.out)) << format;
        EXPECT_NE(r.out.find(shown), std::string::npos) << format;
    }
    CommandResult summary = run_dpscope({"decode", "-q", capture});
    EXPECT_TRUE(is_valid_utf8(summary.out));
    EXPECT_NE(summary.out.find(shown), std::string::npos) << summary.out;
}

}  // namespace
}  // namespace dpscope
