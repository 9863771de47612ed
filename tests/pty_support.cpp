#include "tests/pty_support.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <utility>

#include "capture/tty_player.hpp"

namespace dpscope::test {

Child::Child(std::vector<std::string> argv, ChildOptions options)
    : out_(temp_path("child-out")), err_(temp_path("child-err")) {
    pid_ = fork();
    if (pid_ == 0) {
        int out = open(out_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        int err = open(err_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        dup2(out, STDOUT_FILENO);
        dup2(err, STDERR_FILENO);
        if (options.stdin_from_null) {
            int null = open("/dev/null", O_RDONLY);
            dup2(null, STDIN_FILENO);
        }
        if (options.file_size_limit != RLIM_INFINITY) {
            rlimit limit{options.file_size_limit, options.file_size_limit};
            setrlimit(RLIMIT_FSIZE, &limit);
        }
        setenv("TZ", "UTC", 1);
        for (const auto& [name, value] : options.env)
            setenv(name.c_str(), value.c_str(), 1);
        exec_or_exit(std::move(argv));
    }
}

Child::~Child() {
    if (pid_ > 0 && !reaped_) {
        kill(pid_, SIGKILL);
        waitpid(pid_, nullptr, 0);
    }
    std::remove(out_.c_str());
    std::remove(err_.c_str());
}

void Child::signal(int number) const { kill(pid_, number); }

int Child::wait(double seconds) {
    for (int i = 0; i < seconds * 100; ++i) {
        int status = 0;
        if (waitpid(pid_, &status, WNOHANG) == pid_) {
            reaped_ = true;
            return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return -1;
}

bool Child::err_says(std::string_view text, double seconds) const {
    for (int i = 0; i < seconds * 100; ++i) {
        if (err().find(text) != std::string::npos) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
}

std::string Child::out() const { return slurp(out_); }
std::string Child::err() const { return slurp(err_); }

void exec_or_exit(std::vector<std::string> argv) {
    std::vector<char*> pointers;
    for (std::string& a : argv)
        pointers.push_back(a.data());
    pointers.push_back(nullptr);
    execvp(pointers[0], pointers.data());
    _exit(127);
}

std::vector<std::string> dpscope_argv(const std::vector<std::string>& args) {
    std::vector<std::string> argv = {dpscope_executable()};
    argv.insert(argv.end(), args.begin(), args.end());
    return argv;
}

bool wait_for_raw_mode(const PseudoTerminal& pty, double seconds) {
    for (int i = 0; i < seconds * 100; ++i) {
        termios settings{};
        if (tcgetattr(pty.master, &settings) == 0 && (settings.c_lflag & ICANON) == 0) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
}

Relay::Relay(int from, int to)
    : thread_([this, from, to] {
          std::uint8_t buffer[4096];
          for (int quiet = 0; !stop_ || quiet < 30;) {
              pollfd p{from, POLLIN, 0};
              ssize_t n = poll(&p, 1, 10) > 0 ? read(from, buffer, sizeof buffer) : 0;
              if (n <= 0) {
                  ++quiet;
                  if (n < 0) std::this_thread::sleep_for(std::chrono::milliseconds(10));
                  continue;
              }
              quiet = 0;
              for (ssize_t at = 0; at < n;) {
                  ssize_t w = ::write(to, buffer + at, static_cast<std::size_t>(n - at));
                  if (w > 0) at += w;
              }
          }
      }) {}

void Relay::stop() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
}

Session simulate(SimulatorOptions options) {
    Simulator simulator(options);
    Session s;
    std::vector<std::uint8_t> bytes;
    std::int64_t time = 0;
    while (simulator.next(bytes, time)) {
        s.played.push_back(bytes);
        s.times.push_back(time);
    }
    std::vector<std::uint64_t> garbage;
    for (const Injection& i : simulator.injections())
        if (i.kind == FaultKind::Garbage) garbage.push_back(i.telegram);
    for (std::size_t i = 0; i < s.played.size(); ++i)
        if (std::find(garbage.begin(), garbage.end(), i + 1) == garbage.end())
            s.expected.push_back(s.played[i]);
    return s;
}

Session simulate(std::uint64_t cycles) {
    SimulatorOptions options;
    options.cycles = cycles;
    return simulate(options);
}

void play(const PseudoTerminal& pty, const Session& s, bool as_fast_as_possible,
          std::size_t count) {
    std::size_t next = 0;
    TelegramGenerator generator = [&](std::vector<std::uint8_t>& bytes, std::int64_t& time) {
        if (next >= s.played.size() || next >= count) return false;
        bytes = s.played[next];
        time = s.times[next];
        ++next;
        return true;
    };
    Result<PlayStats> played = play_telegrams(pty.master, generator, as_fast_as_possible, nullptr);
    ASSERT_TRUE(played) << played.error();
}

Capture read_capture(const std::string& path, const CaptureProtocol& protocol) {
    Capture c;
    OpenResult opened = open_source(path, InputFormat::Auto, protocol);
    EXPECT_TRUE(opened) << opened.error();
    if (!opened) return c;
    Record record;
    while (opened.value()->next(record)) {
        c.telegrams.emplace_back(record.bytes.begin(), record.bytes.end());
        c.times.push_back(record.time_ns);
    }
    c.status = opened.value()->status();
    c.link_type = opened.value()->link_type();
    return c;
}

}  // namespace dpscope::test
