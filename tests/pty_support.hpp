// Helpers for the tests that run dpscope (or tshark) as a child process on a pseudo-terminal and
// play a simulated session into it: sniff_test.cpp and extcap_test.cpp.
#pragma once

#include <sys/resource.h>
#include <sys/types.h>

#include <atomic>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "core/protocol_descriptor.hpp"
#include "capture/telegram_source.hpp"
#include "simulator/simulator.hpp"
#include "tests/test_support.hpp"

namespace dpscope::test {

using Telegrams = std::vector<std::vector<std::uint8_t>>;

struct ChildOptions {
    ChildOptions(std::map<std::string, std::string> env_ = {},
                 rlim_t file_size_limit_ = RLIM_INFINITY, bool stdin_from_null_ = true)
        : env(std::move(env_)),
          file_size_limit(file_size_limit_),
          stdin_from_null(stdin_from_null_) {}
    std::map<std::string, std::string> env;  // set in the child (after TZ=UTC, so they win)
    rlim_t file_size_limit = RLIM_INFINITY;  // RLIMIT_FSIZE of the child (a full disk)
    // Standard input from /dev/null (extcap, tshark); false keeps the test's own (as sniff_test
    // always ran dpscope sniff, which reads its port, not standard input).
    bool stdin_from_null = true;
    // A session of its own (setsid): no controlling terminal, as a service has; with
    // `controlling_terminal` (a pty's slave), that terminal becomes its controlling one.
    bool new_session = false;
    std::string controlling_terminal;
};

// A program running as a child process (argv[0] found on PATH unless it names a file), with
// TZ=UTC, standard output and error in files (removed with the Child). Killed if still running
// when destroyed.
class Child {
  public:
    explicit Child(std::vector<std::string> argv, ChildOptions options = {});
    ~Child();
    Child(const Child&) = delete;
    Child& operator=(const Child&) = delete;
    void signal(int number) const;
    // The exit code (128 + N for signal N), or -1 if it does not end within the time.
    int wait(double seconds = kPatienceSeconds);
    // Whether standard error says `text` within `seconds`.
    bool err_says(std::string_view text, double seconds = kPatienceSeconds) const;
    std::string out() const;
    std::string err() const;
    const std::string& out_path() const { return out_; }  // the file standard output goes to
    pid_t pid() const { return pid_; }

  private:
    std::string out_;
    std::string err_;
    pid_t pid_ = -1;
    bool reaped_ = false;
    int exit_code_ = -1;
};

// In a child process after fork(): runs `argv` (argv[0] found on PATH unless it names a file);
// if that fails, the child ends with exit code 127.
[[noreturn]] void exec_or_exit(std::vector<std::string> argv);

// The dpscope built with the tests, with `args`: the argv of a Child or of exec_or_exit.
std::vector<std::string> dpscope_argv(const std::vector<std::string>& args);

// dpscope running as a child process, standard output and error in files (standard input the
// test's own, as it always was here).
class Sniffer : public Child {
  public:
    explicit Sniffer(std::vector<std::string> args, rlim_t file_size_limit = RLIM_INFINITY)
        : Child(dpscope_argv(args), {{}, file_size_limit, false}) {}
    // Waits until the sniffer says it is capturing.
    bool ready() const { return err_says("capturing on"); }
};

// `args` of dpscope capturing on a pty the test writes into (sniff), with --idle-gap-ms 0: a
// thread of the test writing the pty, or relaying into it, can pause anywhere, within a telegram
// too, for as long as a loaded machine keeps it waiting, and an idle gap would cut the telegram
// off. Only the tests of the gap itself keep one (tty_source_test, with a clock of its own).
std::vector<std::string> without_idle_gap(std::vector<std::string> args);

// Whether the program on the slave side has put the line into raw mode (sniff configures the
// port after opening its outputs): the master shares the slave's settings.
bool wait_for_raw_mode(const PseudoTerminal& pty, double seconds = kPatienceSeconds);

// The whole records in the pcap file at `path` so far (a file being written may end in part of
// one); 0 when it does not exist or has no file header yet.
std::size_t pcap_records(const std::string& path);
// The same, over the files a rotating writer makes of `path` (rotated_file_name(path, 1), 2, ...).
std::size_t rotated_pcap_records(const std::string& path);
// Waits until the pcap file at `path` (rotated: its rotated files) holds `records` whole records:
// the capturing program has read, framed and written every telegram played to it. Then a signal
// that stops it races with nothing. Whether they arrived within the patience.
bool wait_for_records(const std::string& path, std::size_t records, bool rotated = false);

// Copies what arrives on one pty's master to another's until stopped: `simulate --device` plays
// onto the slave end of the first, the program under test (sniff, the extcap) captures on the
// slave end of the second (a null-modem cable between two ports).
class Relay {
  public:
    Relay(int from, int to);
    ~Relay() { stop(); }
    Relay(const Relay&) = delete;
    Relay& operator=(const Relay&) = delete;
    // Once the program writing into `from` has ended: copies the rest, then ends. The event is
    // the master's read failing (EIO), which it does only when the slave end is closed and
    // everything written into it has been read, not a quiet time.
    void stop();

  private:
    std::atomic<bool> stop_{false};
    std::thread thread_;
};

// A PROFIBUS session from the simulator: the telegrams to play, in order, with their times.
struct Session {
    Telegrams played;    // every record the simulator produced, garbage included
    Telegrams expected;  // the telegrams a sniffer must capture (garbage is no telegram)
    std::vector<std::int64_t> times;
};

Session simulate(SimulatorOptions options);
Session simulate(std::uint64_t cycles);  // the default session, `cycles` long, no faults

// Plays the first `count` telegrams of `s.played` into the master of `pty` (fails the test if
// playing fails).
void play(const PseudoTerminal& pty, const Session& s, bool as_fast_as_possible,
          std::size_t count = SIZE_MAX);

// The part of `session` from played telegram `from` on (to play the rest after a pause).
Session tail_of(const Session& session, std::size_t from);

// `session` with the answers of `slave` taken out of the played telegrams in each of `windows`
// (played indices, from, to): the slave stops answering there, and is lost.
Session without_answers(const Session& session, std::uint8_t slave,
                        std::vector<std::pair<std::size_t, std::size_t>> windows);

// A capture read back with dpscope's reader (the bus from the capture's own tag, if it has one).
struct Capture {
    Telegrams telegrams;
    std::vector<std::int64_t> times;
    InputStatus status = InputStatus::Unusable;
    int link_type = 0;
};

Capture read_capture(const std::string& path,
                     const ProtocolDescriptor& protocol = profibus_protocol());

}  // namespace dpscope::test
