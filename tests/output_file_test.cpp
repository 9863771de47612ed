// Staged file outputs (capture/output_file.hpp) and what the commands do with them: an existing
// file is replaced only by a run that succeeds (exit code 0 or 1); the output of a run that did
// not is left beside it as FILE.partial.
#include "capture/output_file.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "tests/pty_support.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::CommandResult;
using test::lines_of;
using test::run_dpscope;

std::string content(const std::string& path) {
    std::vector<std::uint8_t> bytes = test::read_file(path);
    return std::string(bytes.begin(), bytes.end());
}

bool exists(const std::string& path) {
    struct stat info {};
    return ::lstat(path.c_str(), &info) == 0;
}

// A copy of a sample in the test's folder.
std::string copy_of(const std::string& relative, std::string_view name) {
    std::string path = test::temp_path(name);
    test::write_file(path, test::read_file(test::source_dir() + "/" + relative));
    return path;
}

// The names in the test's folder that are dpscope's staging files.
std::vector<std::string> staging_files() {
    std::vector<std::string> found;
    for (const auto& entry : std::filesystem::directory_iterator(test::temp_folder()))
        if (entry.path().filename().string().find(".dpscope-") != std::string::npos)
            found.push_back(entry.path().filename().string());
    return found;
}

// ---- a run that does not succeed leaves an existing file as it was ----------------------------

TEST(OutputFileTest, DecodeOfADamagedCaptureLeavesTheFileAndWritesThePartialBeside) {
    const std::string keep = copy_of("samples/faults.pcap", "keep.pcap");
    const std::string before = content(keep);
    CommandResult r = run_dpscope({"decode", "samples/truncated.pcap", "-w", keep});
    EXPECT_EQ(r.exit_code, 3) << r.err;
    EXPECT_TRUE(content(keep) == before) << "a run that exits 3 replaced the file";
    // What was read is kept beside it, and standard error says where.
    ASSERT_TRUE(exists(keep + ".partial"));
    CommandResult partial = run_dpscope({"decode", keep + ".partial"});
    EXPECT_EQ(partial.exit_code, 0) << partial.err;
    EXPECT_EQ(lines_of(partial.out).size(), 101u);
    EXPECT_NE(r.err.find("dpscope: warning: -w " + keep +
                         ": the input ended in damage (exit code "
                         "3), so " +
                         keep + " is left as it was; what was written is in " + keep + ".partial"),
              std::string::npos)
        << r.err;
    EXPECT_TRUE(staging_files().empty());

    // Without a file to keep, the output of a damaged input goes beside the name all the same:
    // a file under the name given always comes from a run that succeeded.
    const std::string fresh = test::temp_path("fresh.pcap");
    CommandResult f = run_dpscope({"decode", "samples/truncated.pcap", "-w", fresh});
    EXPECT_EQ(f.exit_code, 3);
    EXPECT_FALSE(exists(fresh));
    EXPECT_TRUE(exists(fresh + ".partial"));
    EXPECT_NE(
        f.err.find("so " + fresh + " is not made; what was written is in " + fresh + ".partial"),
        std::string::npos)
        << f.err;
}

TEST(OutputFileTest, ReportAndStatsOfADamagedCaptureLeaveTheFile) {
    for (const std::string command : {"report", "stats"}) {
        const std::string out = test::temp_path(command + ".txt");
        test::write_text_file(out, "the previous output\n");
        CommandResult r = run_dpscope({command, "samples/truncated.pcap", "-w", out});
        EXPECT_EQ(r.exit_code, 3) << command << ": " << r.err;
        EXPECT_EQ(content(out), "the previous output\n") << command;
        EXPECT_FALSE(content(out + ".partial").empty()) << command;
        EXPECT_NE(r.err.find("what was written is in " + out + ".partial"), std::string::npos)
            << r.err;
    }
    EXPECT_TRUE(staging_files().empty());
}

TEST(OutputFileTest, AReportThatFailsItsGateStillReplacesTheFile) {
    // Exit code 1 is a result, not a failed run: the report is the one asked for.
    const std::string out = test::temp_path("report.txt");
    test::write_text_file(out, "the previous output\n");
    CommandResult r = run_dpscope({"report", "samples/faults.pcap", "-w", out});
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(content(out).find("conformance report"), std::string::npos);
    EXPECT_FALSE(exists(out + ".partial"));
}

TEST(OutputFileTest, SimulateWithAFaultNotInjectedLeavesTheFile) {
    const std::string keep = copy_of("samples/faults.pcap", "keep.pcap");
    const std::string before = content(keep);
    CommandResult r = run_dpscope({"simulate", "-w", keep, "-c", "20", "--fault", "fcs_error@900"});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_TRUE(content(keep) == before) << "the file was replaced";
    ASSERT_TRUE(exists(keep + ".partial"));
    EXPECT_EQ(lines_of(run_dpscope({"decode", keep + ".partial"}).out).size(), 20u);
    EXPECT_NE(r.err.find("dpscope: warning: -w " + keep +
                         ": a --fault was not injected (exit "
                         "code 2), so " +
                         keep + " is left as it was; what was written is in " + keep + ".partial"),
              std::string::npos)
        << r.err;
}

// dpscope ARGS with standard input from `stdin_fd`, standard output and error on pipes.
class Running {
  public:
    // `file_size_limit`: RLIMIT_FSIZE of the child (standard output and error are pipes, which it
    // does not limit).
    // `env`: NAME=VALUE set in the child.
    Running(const std::vector<std::string>& args, int stdin_fd,
            rlim_t file_size_limit = RLIM_INFINITY, std::vector<std::string> env = {}) {
        int out_pipe[2], err_pipe[2];
        EXPECT_EQ(::pipe2(out_pipe, O_CLOEXEC), 0);
        EXPECT_EQ(::pipe2(err_pipe, O_CLOEXEC), 0);
        pid_ = ::fork();
        if (pid_ == 0) {
            ::dup2(stdin_fd, 0);
            ::dup2(out_pipe[1], 1);
            ::dup2(err_pipe[1], 2);
            const rlimit limit{file_size_limit, file_size_limit};
            ::setrlimit(RLIMIT_FSIZE, &limit);
            for (std::string& setting : env)
                ::putenv(setting.data());
            test::exec_or_exit(test::dpscope_argv(args));
        }
        ::close(out_pipe[1]);
        ::close(err_pipe[1]);
        out_ = out_pipe[0];
        err_ = err_pipe[0];
    }
    ~Running() {
        if (pid_ > 0) {
            ::kill(pid_, SIGKILL);
            ::waitpid(pid_, nullptr, 0);
        }
        ::close(out_);
        ::close(err_);
    }
    Running(const Running&) = delete;
    Running& operator=(const Running&) = delete;

    void signal(int number) const { ::kill(pid_, number); }
    // What standard output (or error) says, up to and including `want` (or to its end); waits at
    // most the patience.
    std::string out_until(std::string_view want) const { return test::read_until(out_, want); }
    std::string err_until(std::string_view want) const { return test::read_until(err_, want); }
    // The wait status once it has ended (standard output and error are drained meanwhile).
    int wait() {
        int status = 0;
        ::waitpid(pid_, &status, 0);
        pid_ = -1;
        return status;
    }

  private:
    pid_t pid_ = -1;
    int out_ = -1;
    int err_ = -1;
};

TEST(OutputFileTest, HexThatEndsInAReadErrorLeavesTheFile) {
    // Standard input is a TCP connection that is reset after a telegram was read: the next read
    // fails (ECONNRESET), and hex exits 3.
    const std::string keep = copy_of("samples/faults.pcap", "keep.pcap");
    const std::string before = content(keep);
    int listener = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    ASSERT_GE(listener, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t length = sizeof address;
    ASSERT_EQ(::bind(listener, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
    ASSERT_EQ(::listen(listener, 1), 0);
    ASSERT_EQ(::getsockname(listener, reinterpret_cast<sockaddr*>(&address), &length), 0);
    int reader = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    ASSERT_EQ(::connect(reader, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
    int writer = ::accept4(listener, nullptr, nullptr, SOCK_CLOEXEC);
    ASSERT_GE(writer, 0);
    ::close(listener);
    Running hex({"hex", "--bus", "profibus", "-l", "-P", "-w", keep}, reader);
    ::close(reader);
    const std::string line = "10 03 02 49 4E 16\n";
    ASSERT_EQ(::write(writer, line.data(), line.size()), static_cast<ssize_t>(line.size()));
    EXPECT_NE(hex.out_until("FDL_Status").find("FDL_Status"), std::string::npos);
    linger reset{1, 0};
    ::setsockopt(writer, SOL_SOCKET, SO_LINGER, &reset, sizeof reset);
    ::close(writer);
    const int status = hex.wait();
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 3) << hex.err_until("never said");
    EXPECT_TRUE(content(keep) == before) << "the file was replaced";
    EXPECT_TRUE(exists(keep + ".partial"));
    EXPECT_TRUE(staging_files().empty());
}

// ---- a signal removes the staging file -------------------------------------------------------

// Waits (at most the patience) until a staging file is in the test's folder.
bool staging_file_appears() {
    return test::wait_until([] { return !staging_files().empty(); });
}

// A pcap header and a few records of samples/faults.pcap: a capture whose end has not come yet.
std::vector<std::uint8_t> start_of_capture() {
    std::vector<std::uint8_t> bytes = test::read_file(test::source_dir() + "/samples/faults.pcap");
    bytes.resize(24 + 3 * 22);  // the header and the first three records (6-byte telegrams)
    return bytes;
}

TEST(OutputFileTest, ASignalRemovesTheStagingFileAndLeavesTheTarget) {
    struct Case {
        std::vector<std::string> args;
        int signal;
    };
    const std::string keep = copy_of("samples/faults.pcap", "keep.out");
    const std::string before = content(keep);
    const std::vector<Case> cases = {
        {{"decode", "-w", keep, "-"}, SIGINT},
        {{"decode", "-w", keep, "-"}, SIGTERM},
        {{"decode", "-w", keep, "-"}, SIGHUP},
        {{"report", "-w", keep, "-"}, SIGINT},
        {{"stats", "-w", keep, "-"}, SIGTERM},
        {{"hex", "--bus", "profibus", "-w", keep}, SIGHUP},
        {{"simulate", "-w", keep, "--cycles", "1000000000"}, SIGINT},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.args[0] + " " + std::to_string(c.signal));
        int in[2];
        ASSERT_EQ(::pipe2(in, O_CLOEXEC), 0);
        Running running(c.args, in[0]);
        ::close(in[0]);
        // The input stays open: the command waits for more while its output is staged.
        if (c.args[0] == "hex") {
            const std::string line = "10 03 02 49 4E 16\n";
            ASSERT_EQ(::write(in[1], line.data(), line.size()), static_cast<ssize_t>(line.size()));
        } else {
            const std::vector<std::uint8_t> bytes = start_of_capture();
            ASSERT_EQ(::write(in[1], bytes.data(), bytes.size()),
                      static_cast<ssize_t>(bytes.size()));
        }
        ASSERT_TRUE(staging_file_appears());
        running.signal(c.signal);
        const int status = running.wait();
        ::close(in[1]);
        EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == c.signal) << status;
        EXPECT_EQ(staging_files(), std::vector<std::string>{});
        for (const std::string& left : staging_files())  // the next case starts clean
            std::filesystem::remove(test::temp_folder() + "/" + left);
        EXPECT_TRUE(content(keep) == before) << "the file was replaced";
        EXPECT_FALSE(exists(keep + ".partial"));
    }
}

TEST(OutputFileTest, SniffEndedAtOnceRemovesItsStagedReportAndStatistics) {
    // A second signal ends sniff at once (the first asks for a clean stop): the report and the
    // statistics, staged until the end, are not left behind as hidden files.
    test::PseudoTerminal pty;
    const std::string report = test::temp_path("report.txt");
    const std::string stats = test::temp_path("stats.txt");
    test::write_text_file(report, "the previous report\n");
    test::Child sniff(test::dpscope_argv({"sniff", "-i", pty.slave, "--baud", "9600", "-q",
                                          "--report-file", report, "--stats-file", stats}));
    ASSERT_TRUE(sniff.err_says("capturing on")) << sniff.err();
    EXPECT_EQ(staging_files().size(), 2u);
    sniff.signal(SIGSTOP);  // both signals arrive together
    sniff.signal(SIGINT);
    sniff.signal(SIGTERM);
    sniff.signal(SIGCONT);
    const int code = sniff.wait();
    EXPECT_TRUE(code == 128 + SIGINT || code == 128 + SIGTERM) << code << sniff.err();
    EXPECT_EQ(staging_files(), std::vector<std::string>{});
    EXPECT_EQ(content(report), "the previous report\n");
    EXPECT_FALSE(exists(stats));
}

// ---- links to files that do not exist yet ------------------------------------------------------

TEST(OutputFileTest, SameFileFollowsALinkToAFileThatDoesNotExistYet) {
    const std::string capture = test::temp_path("capture.pcap");
    const std::string link = test::temp_path("report.txt");
    ASSERT_EQ(::symlink(capture.c_str(), link.c_str()), 0);
    EXPECT_TRUE(same_file(link, capture));
    EXPECT_TRUE(same_file(capture, link));
    // Relative to the link's folder, and through a chain of links.
    const std::string relative = test::temp_path("relative.txt");
    ASSERT_EQ(::symlink(std::filesystem::path(capture).filename().c_str(), relative.c_str()), 0);
    EXPECT_TRUE(same_file(relative, capture));
    const std::string chain = test::temp_path("chain.txt");
    ASSERT_EQ(::symlink(relative.c_str(), chain.c_str()), 0);
    EXPECT_TRUE(same_file(chain, link));
    EXPECT_FALSE(same_file(chain, test::temp_path("other.pcap")));
    // A loop of links is no file and the same as nothing else.
    const std::string loop_a = test::temp_path("loop-a");
    const std::string loop_b = test::temp_path("loop-b");
    ASSERT_EQ(::symlink(loop_b.c_str(), loop_a.c_str()), 0);
    ASSERT_EQ(::symlink(loop_a.c_str(), loop_b.c_str()), 0);
    EXPECT_FALSE(same_file(loop_a, capture));
}

TEST(OutputFileTest, SniffRefusesAReportOrStatisticsFileLinkedToTheCaptureToBe) {
    test::PseudoTerminal pty;
    const std::string capture = test::temp_path("capture.pcap");
    const std::string link = test::temp_path("link.txt");
    ASSERT_EQ(::symlink(capture.c_str(), link.c_str()), 0);
    for (const std::string option : {"--report-file", "--stats-file"}) {
        CommandResult r = run_dpscope({"sniff", "-i", pty.slave, "--baud", "9600", "--duration",
                                       "0.2", "-w", capture, option, link});
        EXPECT_EQ(r.exit_code, 2) << option << ": " << r.err;
        EXPECT_NE(r.err.find(option + " " + link + ": it is the capture file of -w " + capture),
                  std::string::npos)
            << r.err;
        EXPECT_FALSE(exists(capture)) << option;
    }
    // One of the rotated files: stem-00001.pcap.
    const std::string rotated = test::temp_path("rotated.txt");
    const std::string first = capture.substr(0, capture.size() - 5) + "-00001.pcap";
    ASSERT_EQ(::symlink(first.c_str(), rotated.c_str()), 0);
    CommandResult r = run_dpscope({"sniff", "-i", pty.slave, "--baud", "9600", "--duration", "0.2",
                                   "-w", capture, "--rotate-size", "1M", "--report-file", rotated});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    // The report file and the statistics file linked to one file that does not exist yet.
    const std::string shared = test::temp_path("both.txt");
    const std::string report = test::temp_path("report.txt");
    ASSERT_EQ(::symlink(shared.c_str(), report.c_str()), 0);
    const std::string stats = test::temp_path("stats.txt");
    ASSERT_EQ(::symlink(shared.c_str(), stats.c_str()), 0);
    CommandResult both = run_dpscope({"sniff", "-i", pty.slave, "--baud", "9600", "--duration",
                                      "0.2", "--report-file", report, "--stats-file", stats});
    EXPECT_EQ(both.exit_code, 2) << both.err;
    EXPECT_NE(both.err.find("it is the report file too"), std::string::npos) << both.err;
}

TEST(OutputFileTest, AnOutputThroughALinkToNoFileYetCreatesTheFileTheLinkNames) {
    // The link stays and names the report, as for a link to a file that exists.
    const std::string target = test::temp_path("target.txt");
    const std::string link = test::temp_path("link.txt");
    ASSERT_EQ(::symlink(target.c_str(), link.c_str()), 0);
    CommandResult r =
        run_dpscope({"report", "--fail-on", "never", "-w", link, "samples/faults.pcap"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    struct stat info {};
    ASSERT_EQ(::lstat(link.c_str(), &info), 0);
    EXPECT_TRUE(S_ISLNK(info.st_mode));
    EXPECT_NE(content(target).find("conformance report"), std::string::npos);
}

// ---- sniff -w and a port that cannot be used ----------------------------------------------------

TEST(OutputFileTest, SniffOnAPortThatFailsLeavesAnExistingCaptureFile) {
    // /dev/null is a character device, so it is claimed, and then found to be no serial port.
    const std::string keep = copy_of("samples/faults.pcap", "keep.pcap");
    const std::string before = content(keep);
    CommandResult r = run_dpscope({"sniff", "-i", "/dev/null", "--baud", "9600", "-w", keep});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("/dev/null: not a serial port"), std::string::npos) << r.err;
    EXPECT_TRUE(content(keep) == before) << "the capture file was emptied";
    // The first file of a rotation too.
    const std::string stem = test::temp_path("rotated.pcap");
    const std::string first = stem.substr(0, stem.size() - 5) + "-00001.pcap";
    test::write_file(first, test::read_file(keep));
    CommandResult rotated = run_dpscope(
        {"sniff", "-i", "/dev/null", "--baud", "9600", "-w", stem, "--rotate-size", "1M"});
    EXPECT_EQ(rotated.exit_code, 2) << rotated.err;
    EXPECT_TRUE(content(first) == before) << "the first rotated file was emptied";
    EXPECT_FALSE(exists(stem));
    EXPECT_TRUE(staging_files().empty());
}

TEST(OutputFileTest, SniffOnAFullDiskLeavesNoEmptyCaptureFile) {
    // A file size limit of 0 fails the pcap header's write as a full disk does.
    test::PseudoTerminal pty;
    const std::string fresh = test::temp_path("fresh.pcap");
    const int no_input = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
    Running sniff({"sniff", "-i", pty.slave, "--baud", "9600", "-q", "-w", fresh}, no_input, 0);
    const std::string err = sniff.err_until("never said");
    const int status = sniff.wait();
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 4) << status << err;
    EXPECT_NE(err.find("dpscope: error: " + fresh + ": write failed: File too large"),
              std::string::npos)
        << err;
    EXPECT_EQ(err.find("capturing on"), std::string::npos) << err;
    EXPECT_FALSE(exists(fresh)) << "a 0-byte file was left";
    // An existing file stays as it was.
    const std::string keep = copy_of("samples/faults.pcap", "keep.pcap");
    const std::string before = content(keep);
    Running again({"sniff", "-i", pty.slave, "--baud", "9600", "-q", "-w", keep}, no_input, 0);
    const int again_status = again.wait();
    ::close(no_input);
    EXPECT_TRUE(WIFEXITED(again_status) && WEXITSTATUS(again_status) == 4) << again_status;
    EXPECT_TRUE(content(keep) == before) << "the capture file was emptied";
    EXPECT_TRUE(staging_files().empty());
}

// ---- the owner of a file replaced ---------------------------------------------------------------

TEST(OutputFileTest, AReplacedFileKeepsItsOwner) {
    if (::geteuid() != 0) GTEST_SKIP() << "only root can give a file to another user";
    const uid_t nobody_uid = 65534;
    const gid_t nogroup_gid = 65534;
    const std::string out = test::temp_path("report.txt");
    test::write_text_file(out, "old\n");
    ASSERT_EQ(::chown(out.c_str(), nobody_uid, nogroup_gid), 0);
    // Directly and through a symbolic link.
    const std::string link = test::temp_path("link.txt");
    ASSERT_EQ(::symlink(out.c_str(), link.c_str()), 0);
    for (const std::string& name : {out, link}) {
        CommandResult r =
            run_dpscope({"report", "--fail-on", "never", "-w", name, "samples/faults.pcap"});
        EXPECT_EQ(r.exit_code, 0) << r.err;
        struct stat info {};
        ASSERT_EQ(::stat(out.c_str(), &info), 0);
        EXPECT_EQ(info.st_uid, nobody_uid) << name;
        EXPECT_EQ(info.st_gid, nogroup_gid) << name;
        EXPECT_NE(content(out).find("conformance report"), std::string::npos);
    }
    // A new file is the user's own.
    const std::string fresh = test::temp_path("fresh.txt");
    ASSERT_EQ(
        run_dpscope({"report", "--fail-on", "never", "-w", fresh, "samples/faults.pcap"}).exit_code,
        0);
    struct stat info {};
    ASSERT_EQ(::stat(fresh.c_str(), &info), 0);
    EXPECT_EQ(info.st_uid, ::geteuid());
}

// ---- one message for a full disk ----------------------------------------------------------------

TEST(OutputFileTest, AFullDiskUnderAStagedOutputSaysOneThing) {
    // A file size limit of 2048 bytes fails a write as a full disk does. The staged output is
    // thrown away, so nothing is said of what it kept.
    const std::string keep = copy_of("samples/faults.pcap", "keep.pcap");
    const std::string before = content(keep);
    const std::string fresh = test::temp_path("fresh.pcap");
    const int no_input = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
    struct Case {
        std::vector<std::string> args;
        std::string said;
    };
    const std::vector<Case> cases = {
        {{"decode", "samples/faults.pcap", "-w", keep},
         "dpscope: error: " + keep +
             ": write failed: File too large; the file is left as it was\n"},
        {{"decode", "samples/faults.pcap", "-F", "pcapng", "-w", keep},
         "dpscope: error: " + keep +
             ": write failed: File too large; the file is left as it was\n"},
        {{"simulate", "--cycles", "1000", "-w", fresh},
         "dpscope: error: " + fresh + ": write failed: File too large; no file is made\n"},
    };
    for (const Case& c : cases) {
        Running run(c.args, no_input, 2048);
        const std::string err = run.err_until("never said");
        const int status = run.wait();
        EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 4) << status;
        EXPECT_EQ(err, c.said);
    }
    ::close(no_input);
    EXPECT_TRUE(content(keep) == before) << "the file was replaced";
    EXPECT_FALSE(exists(fresh));
    EXPECT_TRUE(staging_files().empty());
}

// ---- a report that cannot list every finding ----------------------------------------------------

// The line of `text` that starts with `start` ("" when there is none).
std::string line_starting(const std::string& text, const std::string& start) {
    for (const std::string& line : lines_of(text))
        if (line.rfind(start, 0) == 0) return line;
    return "";
}

TEST(OutputFileTest, AReportThatCannotListEveryFindingSaysSoAndExits4) {
    // 9,046 findings: more than the 4096 kept in memory, so the report spills them into a file in
    // the temporary folder, $TMPDIR.
    const std::string capture = test::temp_path("many.pcap");
    ASSERT_EQ(
        run_dpscope({"simulate", "-w", capture, "--cycles", "3000", "--fault", "fcs_error=0.5"})
            .exit_code,
        0);
    CommandResult whole = run_dpscope({"report", capture});
    ASSERT_EQ(whole.exit_code, 1) << whole.err;
    const std::string counts = line_starting(whole.out, "  findings ");
    ASSERT_EQ(counts, "  findings       4523 errors, 0 warnings, 4523 notes");
    EXPECT_EQ(whole.out.find("could not be listed"), std::string::npos);

    const int no_input = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
    const std::string missing = "TMPDIR=" + test::temp_folder() + "/no-such-folder";
    const std::string folder = "TMPDIR=" + test::temp_folder();
    struct Case {
        std::string name;
        std::vector<std::string> args;
        rlim_t file_size_limit;
        std::string tmpdir;
    };
    const std::vector<Case> cases = {
        {"a TMPDIR that does not exist", {"report", capture}, RLIM_INFINITY, missing},
        // The spill file may hold 100 kB: the write that goes past fails as on a full disk.
        {"a spill file that fills up", {"report", capture}, 100'000, folder},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        Running report(c.args, no_input, c.file_size_limit, {c.tmpdir});
        const std::string out = report.out_until("never said");
        const std::string err = report.err_until("never said");
        const int status = report.wait();
        EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 4) << status << err;
        EXPECT_EQ(line_starting(out, "  findings "), counts) << "the counts changed";
        EXPECT_NE(out.find("findings could not be listed"), std::string::npos) << out;
        EXPECT_NE(err.find("findings could not be listed"), std::string::npos) << err;
    }

    // JSON: the counts, and what is not listed and why.
    Running json({"report", "-T", "json", capture}, no_input, RLIM_INFINITY, {missing});
    const std::string out = json.out_until("never said");
    const int status = json.wait();
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 4) << status;
    EXPECT_NE(out.find("\"findings\":{\"error\":4523,\"warning\":0,\"note\":4523}"),
              std::string::npos);
    EXPECT_NE(out.find("\"findings_not_listed\":{\"count\":4950,\"reason\":\"cannot make a "
                       "temporary file in "),
              std::string::npos)
        << out.substr(out.size() > 400 ? out.size() - 400 : 0);
    CommandResult complete = run_dpscope({"report", "-T", "json", capture});
    EXPECT_NE(complete.out.find("\"findings_not_listed\":null}"), std::string::npos);

    // Written with -w: an existing file stays, the report goes beside it.
    const std::string keep = test::temp_path("report.txt");
    test::write_text_file(keep, "the previous report\n");
    Running written({"report", capture, "-w", keep}, no_input, RLIM_INFINITY, {missing});
    const std::string said = written.err_until("never said");
    const int written_status = written.wait();
    EXPECT_TRUE(WIFEXITED(written_status) && WEXITSTATUS(written_status) == 4) << said;
    EXPECT_EQ(content(keep), "the previous report\n");
    EXPECT_NE(content(keep + ".partial").find("findings could not be listed"), std::string::npos);
    ::close(no_input);
}

}  // namespace
}  // namespace dpscope
