// `sniff --alarm CMD`: a command run when a station is lost or a verdict turns bad, with the event
// in its environment; and the plain lines `sniff --stats` prints for health events when its
// output is no terminal. The throttle (once per event kind per station per minute) and the
// environment are pure and tested with an injected clock; AlarmRunner starts the commands
// (posix_spawn, never waiting for them during the capture) and reaps them.
#pragma once

#include <sys/types.h>

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "protocols/profibus/health/bus_health.hpp"
#include "protocols/profibus/health/health_event_describe.hpp"

namespace dpscope::cli {

// The variables the alarm command gets, as NAME=VALUE: DPSCOPE_EVENT (station_lost,
// verdict_bad), DPSCOPE_STATION (the address, or "segment"), DPSCOPE_ROLE (master, slave,
// unknown, segment), DPSCOPE_TIME (ISO 8601 UTC), DPSCOPE_FRAME, DPSCOPE_VERDICT (good, weak,
// bad), DPSCOPE_REASONS (the reasons joined by "; ", empty when good).
std::vector<std::string> alarm_environment(const AlarmEvent& e);

// Does `kind` raise an alarm? StationLost and VerdictBad do; StationReturned does not.
bool raises_alarm(HealthEventKind kind) noexcept;

// At most one alarm per event kind per station (the segment is one more) per interval of the
// clock given to admit(); what is held back is counted.
class AlarmThrottle {
  public:
    static constexpr std::int64_t kDefaultIntervalNs = 60'000'000'000;  // one minute

    explicit AlarmThrottle(std::int64_t interval_ns = kDefaultIntervalNs)
        : interval_ns_(interval_ns) {
        for (auto& row : last_)
            row.fill(kNoTime);
    }
    // True when an alarm of `kind` for `address` may go out at `now_ns` (and notes it); false,
    // counted as suppressed, when one went out less than the interval before.
    bool admit(HealthEventKind kind, std::uint8_t address, std::int64_t now_ns);
    std::uint64_t suppressed(HealthEventKind kind) const noexcept {
        return suppressed_[static_cast<std::size_t>(kind)];
    }
    std::uint64_t suppressed_total() const noexcept;
    std::int64_t interval_ns() const noexcept { return interval_ns_; }

  private:
    static constexpr std::size_t kKinds = static_cast<std::size_t>(HealthEventKind::Count);
    std::int64_t interval_ns_;
    std::array<std::array<std::int64_t, 256>, kKinds> last_{};
    std::array<std::uint64_t, kKinds> suppressed_{};
};

// Alarm commands running at once, at most: a command that hangs (or a bus where every station
// is lost at once) must not pile up processes without a limit (docs/decisions.md, "Bus health:
// sniff").
inline constexpr std::size_t kMaxRunningAlarms = 16;

// Runs the alarm command through /bin/sh -c with the event's variables added to the environment,
// its standard input from /dev/null and its standard output onto standard error (standard output
// may carry the pcap of -w -), no descriptor of ours inherited, in a process group of its own (so
// that it can be ended with what it started). Never waits during the capture.
class AlarmRunner {
  public:
    using Clock = std::function<std::int64_t()>;
    using Warn = std::function<void(std::string_view)>;

    // `clock`: the throttle's time (monotonic nanoseconds; injected by tests). `warn`: where
    // the one warning about a failing command, and the one about skipped alarms, go.
    // `max_running`: commands running at once, at most.
    AlarmRunner(std::string command, Clock clock, Warn warn,
                std::int64_t interval_ns = AlarmThrottle::kDefaultIntervalNs,
                std::size_t max_running = kMaxRunningAlarms);
    ~AlarmRunner();  // leaves commands still running alone (end_running() ends them)
    AlarmRunner(const AlarmRunner&) = delete;
    AlarmRunner& operator=(const AlarmRunner&) = delete;

    // Starts the command for `e` unless its kind raises no alarm, `max_running` commands are
    // still running (skipped and counted; the throttle's minute is not used up) or the throttle
    // holds it back. Returns whether it was started.
    bool raise(const AlarmEvent& e);
    // Collects the commands that have ended (waitpid WNOHANG); the first that failed (exit code
    // not 0, killed, or not started) is warned about, the rest counted.
    void reap();
    // The end of the capture: waits up to `timeout_ms` for the commands still running, then
    // reaps. Returns how many are still running.
    std::size_t finish(int timeout_ms);
    // Ends the commands still running with their process groups: SIGTERM, and SIGKILL to what
    // is left after `grace_ms`. Returns how many were ended (not counted as failed).
    std::size_t end_running(int grace_ms);

    std::uint64_t started() const noexcept { return started_; }
    std::uint64_t failed() const noexcept { return failed_; }
    std::uint64_t skipped() const noexcept { return skipped_; }
    std::uint64_t ended() const noexcept { return ended_; }
    std::size_t running() const noexcept { return running_.size(); }
    const AlarmThrottle& throttle() const noexcept { return throttle_; }
    // What the end of the capture says about the alarms ("" when nothing is worth saying):
    // "alarms: 2 run, 3 suppressed by the once-a-minute limit (station_lost 2, verdict_bad 1)";
    // skipped alarms, failures, commands ended at the end and commands left running are added.
    std::string summary() const;

    // For a handler of a signal that ends the process at once: sends SIGTERM to the process
    // group of every alarm command still running (of every runner). Async-signal-safe.
    static void end_all_after_signal() noexcept;

  private:
    void failure(std::string_view what);
    void forget(std::size_t index);  // running_[index] is reaped: no longer listed

    std::string command_;
    Clock clock_;
    Warn warn_;
    AlarmThrottle throttle_;
    std::size_t max_running_;
    std::vector<pid_t> running_;
    std::uint64_t started_ = 0;
    std::uint64_t failed_ = 0;
    std::uint64_t skipped_ = 0;
    std::uint64_t ended_ = 0;
};

}  // namespace dpscope::cli
