// The progress line of long offline runs (cli/progress.*): its text and ETA, the refresh limit
// (an injected clock), that it is cleared, and that dpscope shows it only on a terminal (a
// pseudo-terminal as standard error, with DPSCOPE_PROGRESS_MIN_BYTES lowering the size limit).
#include "cli/progress.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <string>
#include <vector>

#include "tests/pty_support.hpp"
#include "tests/test_support.hpp"

namespace dpscope::cli {
namespace {

TEST(ProgressTest, BytesAndTimesAreShortAndReadable) {
    EXPECT_EQ(progress_bytes_text(0), "0 B");
    EXPECT_EQ(progress_bytes_text(1023), "1023 B");
    EXPECT_EQ(progress_bytes_text(1024), "1 KiB");
    EXPECT_EQ(progress_bytes_text(5 * 1024 * 1024 + 512 * 1024), "5.5 MiB");
    EXPECT_EQ(progress_bytes_text(3ULL * 1024 * 1024 * 1024), "3.0 GiB");
    EXPECT_EQ(progress_eta_text(-1), "?");
    EXPECT_EQ(progress_eta_text(0), "0:00");
    EXPECT_EQ(progress_eta_text(42), "0:42");
    EXPECT_EQ(progress_eta_text(725), "12:05");
    EXPECT_EQ(progress_eta_text(3723), "1:02:03");
}

TEST(ProgressTest, LineSaysBytesRateAndTimeLeft) {
    constexpr std::uint64_t kMiB = 1024 * 1024;
    // A quarter read in 10 s: 30 s left; 25 M telegrams in 10 s.
    EXPECT_EQ(progress_line(100 * kMiB, 400 * kMiB, 25'000'000, 10'000'000'000),
              "dpscope: 100.0 MiB of 400.0 MiB (25 %), 2.50 M telegrams/s, ETA 0:30");
    EXPECT_EQ(progress_line(300 * kMiB, 400 * kMiB, 1500, 2'000'000'000),
              "dpscope: 300.0 MiB of 400.0 MiB (75 %), 750 telegrams/s, ETA 0:01");
    EXPECT_EQ(progress_line(200 * kMiB, 400 * kMiB, 9000, 1'000'000'000),
              "dpscope: 200.0 MiB of 400.0 MiB (50 %), 9.0 k telegrams/s, ETA 0:01");
    // Nothing read yet, or no time passed: the time left is not known.
    EXPECT_EQ(progress_line(0, 400 * kMiB, 0, 1'000'000'000),
              "dpscope: 0 B of 400.0 MiB (0 %), 0 telegrams/s, ETA ?");
    EXPECT_EQ(progress_line(kMiB, 400 * kMiB, 10, 0),
              "dpscope: 1.0 MiB of 400.0 MiB (0 %), 0 telegrams/s, ETA ?");
    // A position past the size (a file that grew) is shown as the end.
    EXPECT_EQ(progress_line(500 * kMiB, 400 * kMiB, 10, 1'000'000'000),
              "dpscope: 400.0 MiB of 400.0 MiB (100 %), 10 telegrams/s, ETA 0:00");
}

struct Screen {
    std::vector<std::string> writes;
    ProgressMeter::Writer writer() {
        return [this](std::string_view text) { writes.emplace_back(text); };
    }
};

TEST(ProgressTest, RedrawsAtMostFourTimesASecondAndClearsAtTheEnd) {
    std::int64_t now = 1'000'000'000;
    Screen screen;
    {
        ProgressMeter meter(1000, true, screen.writer(), [&now] { return now; });
        EXPECT_TRUE(meter.shown());
        meter.update(100);  // the first check draws
        ASSERT_EQ(screen.writes.size(), 1u);
        EXPECT_EQ(screen.writes[0].substr(0, 10), "\rdpscope: ");
        EXPECT_NE(screen.writes[0].find("100 B of 1000 B (10 %)"), std::string::npos)
            << screen.writes[0];
        now += 100'000'000;
        meter.update(200);  // 0.1 s later: not redrawn
        now += 149'999'999;
        meter.update(300);  // 0.249999999 s after the last line: still not
        EXPECT_EQ(screen.writes.size(), 1u);
        now += 1;
        meter.update(400);  // 0.25 s: redrawn
        ASSERT_EQ(screen.writes.size(), 2u);
        EXPECT_NE(screen.writes[1].find("400 B of 1000 B (40 %)"), std::string::npos)
            << screen.writes[1];
        // Over 10 s of updates every millisecond, at most 4 lines a second.
        for (int i = 0; i < 10'000; ++i) {
            now += 1'000'000;
            meter.update(500);
        }
        EXPECT_EQ(screen.writes.size(), 2u + 40u);
    }
    // The meter's end clears the line: spaces over it, the cursor back at the start.
    const std::string& last = screen.writes.back();
    ASSERT_GE(last.size(), 3u);
    EXPECT_EQ(last.front(), '\r');
    EXPECT_EQ(last.back(), '\r');
    EXPECT_EQ(last.find_first_not_of(' ', 1), last.size() - 1) << last;
    EXPECT_EQ(last.size(), screen.writes[1].size() + 1);
}

TEST(ProgressTest, AShorterLineCoversTheLongerOneBefore) {
    std::int64_t now = 0;
    Screen screen;
    ProgressMeter meter(2'000'000'000, true, screen.writer(), [&now] { return now; });
    now = 1;
    meter.update(1'500'000'000);  // "1.4 GiB of 1.9 GiB"
    now += kProgressRefreshNs;
    meter.update(0);  // "0 B of ...": shorter, padded with spaces
    ASSERT_EQ(screen.writes.size(), 2u);
    EXPECT_EQ(screen.writes[1].size(), screen.writes[0].size());
    EXPECT_EQ(screen.writes[1].back(), ' ');
}

TEST(ProgressTest, TicksReadThePositionOnlyEveryFourThousandTelegrams) {
    std::int64_t now = 0;
    int clock_reads = 0;
    Screen screen;
    std::unique_ptr<TelegramSource> source =
        memory_source("memory", Bytes(), profibus_protocol());
    ProgressMeter meter(1000, true, screen.writer(), [&] {
        ++clock_reads;
        return now;
    });
    const int at_start = clock_reads;
    for (std::uint64_t i = 1; i < kProgressCheckEvery; ++i)
        meter.tick(*source);
    EXPECT_EQ(clock_reads, at_start);
    EXPECT_TRUE(screen.writes.empty());
    meter.tick(*source);
    EXPECT_EQ(clock_reads, at_start + 1);
    EXPECT_EQ(screen.writes.size(), 1u);
    EXPECT_EQ(meter.telegrams(), kProgressCheckEvery);
}

TEST(ProgressTest, NothingIsDrawnWhenNotShown) {
    Screen screen;
    {
        ProgressMeter meter(1000, false, screen.writer(), [] { return std::int64_t{0}; });
        meter.update(500);
        meter.clear();
    }
    EXPECT_TRUE(screen.writes.empty());
}

// Sets an environment variable for the scope.
struct ScopedEnvironment {
    ScopedEnvironment(const char* name, const char* value) : name_(name) { setenv(name, value, 1); }
    ~ScopedEnvironment() { unsetenv(name_); }
    const char* name_;
};

TEST(ProgressTest, MinimumSizeFromTheEnvironment) {
    EXPECT_EQ(progress_min_bytes(), kProgressMinBytes);
    {
        ScopedEnvironment env("DPSCOPE_PROGRESS_MIN_BYTES", "1");
        EXPECT_EQ(progress_min_bytes(), 1u);
    }
    for (const char* bad : {"", "-1", "12x", "0x10", "99999999999999999999999"}) {
        ScopedEnvironment env("DPSCOPE_PROGRESS_MIN_BYTES", bad);
        EXPECT_EQ(progress_min_bytes(), kProgressMinBytes) << bad;
    }
}

// A capture big enough for a few checks (kProgressCheckEvery telegrams each).
const std::string& capture_of_many_telegrams() {
    static const std::string path = [] {
        std::string p = test::temp_path("progress.pcap");
        test::CommandResult r =
            test::run_dpscope({"simulate", "-w", p, "--cycles", "0", "-c", "20000", "--seed", "5"});
        EXPECT_EQ(r.exit_code, 0) << r.err;
        return p;
    }();
    return path;
}

// dpscope `args` with standard error on a pseudo-terminal (standard output to /dev/null) and
// DPSCOPE_PROGRESS_MIN_BYTES set to `min_bytes`: what it wrote on the terminal, and its exit code.
std::pair<std::string, int> run_on_terminal(const std::vector<std::string>& args,
                                            const std::string& min_bytes) {
    test::PseudoTerminal pty;
    pid_t pid = fork();
    if (pid == 0) {
        int terminal = open(pty.slave.c_str(), O_RDWR | O_NOCTTY);
        int null = open("/dev/null", O_WRONLY);
        if (terminal < 0 || null < 0) _exit(126);
        dup2(null, STDOUT_FILENO);
        dup2(terminal, STDERR_FILENO);
        if (chdir(test::source_dir().c_str()) != 0) _exit(126);
        setenv("DPSCOPE_PROGRESS_MIN_BYTES", min_bytes.c_str(), 1);
        test::exec_or_exit(test::dpscope_argv(args));
    }
    std::string seen;
    int status = 0;
    // Read what it draws until it ends (within the patience: a bound for a hang).
    const bool ended = test::wait_until([&] {
        for (;;) {
            pollfd readable{pty.master, POLLIN, 0};
            if (poll(&readable, 1, 0) <= 0) break;
            char buffer[4096];
            ssize_t n = read(pty.master, buffer, sizeof buffer);
            if (n <= 0) break;  // hung up (EIO): the child is ending, or not there yet
            seen.append(buffer, static_cast<std::size_t>(n));
        }
        return waitpid(pid, &status, WNOHANG) == pid;
    });
    if (!ended) {
        kill(pid, SIGKILL);
        waitpid(pid, &status, 0);
        ADD_FAILURE() << "dpscope did not end";
    }
    // What the child wrote between the last poll and its end is still in the terminal: read it
    // (a read fails with EIO once the buffer is empty and the child's side is closed).
    for (;;) {
        pollfd readable{pty.master, POLLIN, 0};
        if (poll(&readable, 1, 100) <= 0) break;
        char buffer[4096];
        ssize_t n = read(pty.master, buffer, sizeof buffer);
        if (n <= 0) break;
        seen.append(buffer, static_cast<std::size_t>(n));
    }
    return {seen, WIFEXITED(status) ? WEXITSTATUS(status) : -1};
}

void expect_drawn_and_cleared(const std::string& seen) {
    const std::size_t line = seen.find("\rdpscope: ");
    ASSERT_NE(line, std::string::npos) << seen;
    EXPECT_NE(seen.find("telegrams/s, ETA ", line), std::string::npos) << seen;
    // It ends cleared: spaces over the line, the cursor back at the start.
    ASSERT_GE(seen.size(), 2u);
    EXPECT_EQ(seen.back(), '\r');
    const std::size_t blank = seen.find_last_not_of(' ', seen.size() - 2);
    EXPECT_EQ(seen[blank], '\r') << seen;
    EXPECT_GT(seen.size() - 2 - blank, 20u);
}

TEST(ProgressTest, ShownOnATerminalForAnInputOverTheLimitAndCleared) {
    const std::string& capture = capture_of_many_telegrams();
    auto [stats_seen, stats_exit] = run_on_terminal({"stats", capture}, "1");
    EXPECT_EQ(stats_exit, 0);
    expect_drawn_and_cleared(stats_seen);
    auto [report_seen, report_exit] = run_on_terminal({"report", "-T", "json", capture}, "1");
    EXPECT_EQ(report_exit, 0);
    expect_drawn_and_cleared(report_seen);
    auto [decode_seen, decode_exit] = run_on_terminal({"decode", "-q", capture}, "1");
    EXPECT_EQ(decode_exit, 0);
    expect_drawn_and_cleared(decode_seen);
}

TEST(ProgressTest, NotShownForAnInputUnderTheLimit) {
    const std::string& capture = capture_of_many_telegrams();
    auto [seen, exit_code] = run_on_terminal({"stats", capture}, "1000000000");
    EXPECT_EQ(exit_code, 0);
    EXPECT_EQ(seen.find("dpscope: "), std::string::npos) << seen;
}

TEST(ProgressTest, NotShownWhenStandardErrorIsNoTerminal) {
    const std::string& capture = capture_of_many_telegrams();
    ScopedEnvironment env("DPSCOPE_PROGRESS_MIN_BYTES", "1");
    for (const std::vector<std::string>& args : {std::vector<std::string>{"stats", capture},
                                                 {"report", capture},
                                                 {"decode", "-q", capture}}) {
        test::CommandResult r = test::run_dpscope(args);
        EXPECT_EQ(r.exit_code, 0) << r.err;
        EXPECT_TRUE(r.err.empty()) << args[0] << ": " << r.err;
    }
    // Nor in this process (standard error of the tests is not the meter's business when it is
    // redirected): for_source asks isatty.
    if (isatty(STDERR_FILENO) == 0) {
        OpenResult opened = open_source(capture, InputFormat::Auto, profibus_protocol());
        ASSERT_TRUE(opened) << opened.error();
        EXPECT_GT((*opened)->input_size(), 0u);
        EXPECT_FALSE(ProgressMeter::for_source(**opened).shown());
    }
}

TEST(ProgressTest, SourcePositionFollowsTheReading) {
    const std::string& capture = capture_of_many_telegrams();
    OpenResult opened = open_source(capture, InputFormat::Auto, profibus_protocol());
    ASSERT_TRUE(opened) << opened.error();
    TelegramSource& source = **opened;
    const std::uint64_t size = source.input_size();
    EXPECT_EQ(size, test::read_file(capture).size());
    Record record;
    std::uint64_t last = 0;
    std::uint64_t n = 0;
    while (source.next(record)) {
        if (++n % 1000 != 0) continue;
        const std::uint64_t position = source.bytes_read();
        EXPECT_GE(position, last);
        EXPECT_LE(position, size);
        EXPECT_GE(position, record.offset);  // a pcap record's offset: read past it
        last = position;
    }
    EXPECT_EQ(source.bytes_read(), size);
    // Bytes in memory and standard input have no known size.
    EXPECT_EQ(memory_source("memory", Bytes(), profibus_protocol())->input_size(), 0u);
}

}  // namespace
}  // namespace dpscope::cli
