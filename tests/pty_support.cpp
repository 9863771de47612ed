#include "tests/pty_support.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <utility>

#include "capture/capture_writer.hpp"
#include "capture/pcap_source.hpp"
#include "capture/tty_player.hpp"
#include "protocols/profibus/bus_decoder.hpp"

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
        if (options.new_session) {
            setsid();
            if (!options.controlling_terminal.empty())
                open(options.controlling_terminal.c_str(), O_RDWR);  // becomes the session's
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
    int status = 0;
    const bool ended =
        reaped_ || wait_until([&] { return waitpid(pid_, &status, WNOHANG) == pid_; }, seconds);
    if (!ended) return -1;
    if (!reaped_) {
        reaped_ = true;
        exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }
    return exit_code_;
}

bool Child::err_says(std::string_view text, double seconds) const {
    return wait_until([&] { return err().find(text) != std::string::npos; }, seconds);
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

std::vector<std::string> without_idle_gap(std::vector<std::string> args) {
    args.insert(args.end(), {"--idle-gap-ms", "0"});
    return args;
}

bool wait_for_raw_mode(const PseudoTerminal& pty, double seconds) {
    return wait_until(
        [&] {
            termios settings{};
            return tcgetattr(pty.master, &settings) == 0 && (settings.c_lflag & ICANON) == 0;
        },
        seconds);
}

namespace {

std::uint32_t pcap_u32(const std::vector<std::uint8_t>& bytes, std::size_t at, bool swapped) {
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < 4; ++i)
        v |= static_cast<std::uint32_t>(bytes[at + i]) << (8 * (swapped ? 3 - i : i));
    return v;
}

}  // namespace

std::size_t pcap_records(const std::string& path) {
    const std::vector<std::uint8_t> bytes = read_file(path);
    if (bytes.size() < kPcapFileHeaderBytes) return 0;
    const std::uint32_t magic = pcap_u32(bytes, 0, false);
    const bool swapped = magic == 0xD4C3B2A1 || magic == 0x4D3CB2A1;
    std::size_t records = 0;
    for (std::size_t at = kPcapFileHeaderBytes; at + kPcapRecordHeaderBytes <= bytes.size();
         ++records) {
        at += kPcapRecordHeaderBytes + pcap_u32(bytes, at + 8, swapped);  // incl_len
        if (at > bytes.size()) break;
    }
    return records;
}

std::size_t rotated_pcap_records(const std::string& path) {
    std::size_t records = 0;
    for (unsigned index = 1;; ++index) {
        const std::string name = rotated_file_name(path, index);
        if (access(name.c_str(), F_OK) != 0) return records;
        records += pcap_records(name);
    }
}

bool wait_for_records(const std::string& path, std::size_t records, bool rotated) {
    return wait_until(
        [&] { return (rotated ? rotated_pcap_records(path) : pcap_records(path)) >= records; });
}

Relay::Relay(int from, int to)
    : thread_([this, from, to] {
          std::uint8_t buffer[4096];
          std::chrono::steady_clock::time_point give_up{};
          for (;;) {
              pollfd p{from, POLLIN, 0};
              ssize_t n = poll(&p, 1, 10) > 0 ? read(from, buffer, sizeof buffer) : 0;
              if (n > 0) {
                  for (ssize_t at = 0; at < n;) {
                      ssize_t w = ::write(to, buffer + at, static_cast<std::size_t>(n - at));
                      if (w > 0)
                          at += w;
                      else if (w < 0 && errno != EINTR)
                          return;  // the other end is gone: nothing more can be copied
                  }
                  continue;
              }
              // Nothing came: a quiet line (0), or no writer on the slave end (EIO: not yet, or
              // no more, and then everything it wrote has been read).
              const bool hung_up = n < 0 && errno == EIO;
              if (stop_) {
                  const auto now = std::chrono::steady_clock::now();
                  if (give_up == std::chrono::steady_clock::time_point{})
                      give_up = now + std::chrono::seconds(static_cast<int>(kPatienceSeconds));
                  if (hung_up || now >= give_up) return;
              }
              if (n < 0) std::this_thread::sleep_for(std::chrono::milliseconds(10));
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

Capture read_capture(const std::string& path, const ProtocolDescriptor& protocol) {
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

// `session` with the answers of `slave` taken out of the played telegrams in each of `windows`
// (played indices, from, to): the slave stops answering there, and is lost.
Session without_answers(const Session& session, std::uint8_t slave,
                        std::vector<std::pair<std::size_t, std::size_t>> windows) {
    BusDecoder decoder;
    Session out;
    for (std::size_t i = 0; i < session.played.size(); ++i) {
        const auto& bytes = session.played[i];
        const DecodedTelegram& t =
            decoder.decode(Bytes(bytes.data(), bytes.size()), kNoTime, i + 1);
        bool silent = std::any_of(windows.begin(), windows.end(),
                                  [i](auto w) { return i >= w.first && i < w.second; });
        if (silent && t.direction == Direction::Response && t.has_roles && t.slave == slave)
            continue;
        out.played.push_back(bytes);
        out.times.push_back(session.times[i]);
    }
    out.expected = out.played;  // no garbage in these sessions
    return out;
}

Session tail_of(const Session& session, std::size_t from) {
    Session rest;
    from = std::min(from, session.played.size());
    rest.played.assign(session.played.begin() + static_cast<std::ptrdiff_t>(from),
                       session.played.end());
    rest.times.assign(session.times.begin() + static_cast<std::ptrdiff_t>(from),
                      session.times.end());
    rest.expected = rest.played;
    return rest;
}

}  // namespace dpscope::test
