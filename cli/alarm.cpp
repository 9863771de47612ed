#include "cli/alarm.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <thread>

extern char** environ;

namespace dpscope::cli {

namespace {

// The commands running, where a signal handler can reach them without locking or allocating:
// a shell's PID (its process group) from its start until it is reaped, so that the PID cannot
// have been taken by another process.
constexpr std::size_t kRegisteredGroups = 64;
std::atomic<pid_t> g_running_groups[kRegisteredGroups];

void register_group(pid_t pid) noexcept {
    for (std::atomic<pid_t>& slot : g_running_groups) {
        pid_t empty = 0;
        if (slot.compare_exchange_strong(empty, pid)) return;
    }
}

void unregister_group(pid_t pid) noexcept {
    for (std::atomic<pid_t>& slot : g_running_groups) {
        pid_t expected = pid;
        if (slot.compare_exchange_strong(expected, 0)) return;
    }
}

}  // namespace

void AlarmRunner::end_all_after_signal() noexcept {
    for (std::atomic<pid_t>& slot : g_running_groups)
        if (const pid_t pid = slot.load(); pid > 0) ::kill(-pid, SIGTERM);
}

std::vector<std::string> alarm_environment(const AlarmEvent& e) {
    const bool segment = e.address == kSegmentAddress;
    return {
        fmt::format("DPSCOPE_EVENT={}", health_event_name(e.kind)),
        fmt::format("DPSCOPE_STATION={}",
                    segment ? std::string("segment") : std::to_string(e.address)),
        fmt::format("DPSCOPE_ROLE={}",
                    segment ? std::string_view("segment") : station_role_name(e.role)),
        fmt::format("DPSCOPE_TIME={}", iso8601_utc(e.time_ns)),
        fmt::format("DPSCOPE_FRAME={}", e.frame),
        fmt::format("DPSCOPE_VERDICT={}", verdict_name(e.verdict)),
        fmt::format("DPSCOPE_REASONS={}", fmt::join(e.reasons, "; ")),
    };
}

bool raises_alarm(HealthEventKind kind) noexcept {
    return kind == HealthEventKind::StationLost || kind == HealthEventKind::VerdictBad;
}

bool AlarmThrottle::admit(HealthEventKind kind, std::uint8_t address, std::int64_t now_ns) {
    const auto k = static_cast<std::size_t>(kind);
    if (k >= kKinds) return false;
    std::int64_t& last = last_[k][address];
    if (last != kNoTime && now_ns - last < interval_ns_) {
        ++suppressed_[k];
        return false;
    }
    last = now_ns;
    return true;
}

std::uint64_t AlarmThrottle::suppressed_total() const noexcept {
    std::uint64_t total = 0;
    for (std::uint64_t n : suppressed_)
        total += n;
    return total;
}

AlarmRunner::AlarmRunner(std::string command, Clock clock, Warn warn, std::int64_t interval_ns,
                         std::size_t max_running)
    : command_(std::move(command)),
      clock_(std::move(clock)),
      warn_(std::move(warn)),
      throttle_(interval_ns),
      max_running_(std::max<std::size_t>(1, max_running)) {}

AlarmRunner::~AlarmRunner() = default;

void AlarmRunner::failure(std::string_view what) {
    if (failed_++ == 0 && warn_)
        warn_(fmt::format("--alarm: {} (further failures are only counted)", what));
}

bool AlarmRunner::raise(const AlarmEvent& e) {
    if (!raises_alarm(e.kind)) return false;
    reap();
    if (running_.size() >= max_running_) {
        if (skipped_++ == 0 && warn_)
            warn_(fmt::format(
                "--alarm: {} commands are still running, the most at once; alarms are skipped "
                "until one ends (further ones are only counted)",
                running_.size()));
        return false;
    }
    if (!throttle_.admit(e.kind, e.address, clock_())) return false;
    // The environment: ours without any DPSCOPE_ variable the event sets, then the event's.
    std::vector<std::string> added = alarm_environment(e);
    std::vector<char*> envp;
    for (char** variable = environ; variable && *variable; ++variable) {
        bool replaced = std::any_of(added.begin(), added.end(), [&](const std::string& a) {
            std::size_t name = a.find('=') + 1;
            return std::strncmp(*variable, a.c_str(), name) == 0;
        });
        if (!replaced) envp.push_back(*variable);
    }
    for (std::string& a : added)
        envp.push_back(a.data());
    envp.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_adddup2(&actions, STDERR_FILENO, STDOUT_FILENO);
    posix_spawn_file_actions_addclosefrom_np(&actions, STDERR_FILENO + 1);
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    // The command starts with default signal handling (sniff ignores SIGPIPE) and none blocked.
    sigset_t defaults;
    sigemptyset(&defaults);
    for (int s : {SIGPIPE, SIGINT, SIGTERM, SIGHUP})
        sigaddset(&defaults, s);
    sigset_t none;
    sigemptyset(&none);
    posix_spawnattr_setsigdefault(&attributes, &defaults);
    posix_spawnattr_setsigmask(&attributes, &none);
    // A process group of its own: end_running() ends the shell with what it started (a shell
    // that runs `sleep 300; echo` stays the sleep's parent).
    posix_spawnattr_setpgroup(&attributes, 0);
    posix_spawnattr_setflags(
        &attributes, POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETPGROUP);
    std::string shell = "/bin/sh";
    std::string dash_c = "-c";
    std::vector<char*> argv = {shell.data(), dash_c.data(), command_.data(), nullptr};
    pid_t pid = -1;
    int error = posix_spawn(&pid, shell.c_str(), &actions, &attributes, argv.data(), envp.data());
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
    if (error != 0) {
        failure(fmt::format("cannot start /bin/sh: {}", std::strerror(error)));
        return false;
    }
    ++started_;
    running_.push_back(pid);
    register_group(pid);
    return true;
}

void AlarmRunner::reap() {
    for (std::size_t i = 0; i < running_.size();) {
        int status = 0;
        pid_t done = ::waitpid(running_[i], &status, WNOHANG);
        if (done == 0 || (done < 0 && errno == EINTR)) {
            ++i;
            continue;
        }
        forget(i);
        if (done < 0) continue;  // not our child any more (reaped elsewhere)
        if (WIFEXITED(status) && WEXITSTATUS(status) != 0)
            failure(
                fmt::format("the command '{}' exited with code {}", command_, WEXITSTATUS(status)));
        else if (WIFSIGNALED(status))
            failure(
                fmt::format("the command '{}' was ended by signal {}", command_, WTERMSIG(status)));
    }
}

std::size_t AlarmRunner::finish(int timeout_ms) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    reap();
    while (!running_.empty() && std::chrono::steady_clock::now() < deadline) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        reap();
    }
    return running_.size();
}

void AlarmRunner::forget(std::size_t index) {
    unregister_group(running_[index]);
    running_.erase(running_.begin() + static_cast<std::ptrdiff_t>(index));
}

std::size_t AlarmRunner::end_running(int grace_ms) {
    reap();
    if (running_.empty()) return 0;
    // Each command's process group is its shell's PID, which stays taken (the shell is not
    // reaped before the SIGKILL below, only waited for with WNOWAIT): no other group is hit.
    for (pid_t pid : running_)
        ::kill(-pid, SIGTERM);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(grace_ms);
    for (;;) {
        bool all_exited = true;
        for (pid_t pid : running_) {
            siginfo_t info{};
            if (::waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 &&
                info.si_pid == 0)
                all_exited = false;
        }
        if (all_exited || std::chrono::steady_clock::now() >= deadline) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    // What is left of each group (the shell, or a command that ignored SIGTERM after the shell
    // ended) is killed, then the shells are reaped.
    const std::size_t ended = running_.size();
    while (!running_.empty()) {
        const pid_t pid = running_.back();
        ::kill(-pid, SIGKILL);
        int status = 0;
        while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
        }
        forget(running_.size() - 1);
    }
    ended_ += ended;
    return ended;
}

std::string AlarmRunner::summary() const {
    const std::uint64_t suppressed = throttle_.suppressed_total();
    if (started_ == 0 && suppressed == 0 && failed_ == 0 && skipped_ == 0) return {};
    std::string text = fmt::format("alarms: {} run", started_);
    if (suppressed > 0) {
        std::vector<std::string> kinds;
        for (HealthEventKind kind : {HealthEventKind::StationLost, HealthEventKind::VerdictBad})
            if (throttle_.suppressed(kind) > 0)
                kinds.push_back(
                    fmt::format("{} {}", health_event_name(kind), throttle_.suppressed(kind)));
        text += fmt::format(
            ", {} suppressed by the limit of one per event kind and station per "
            "{} s ({})",
            suppressed, throttle_.interval_ns() / 1'000'000'000, fmt::join(kinds, ", "));
    }
    if (skipped_ > 0)
        text +=
            fmt::format(", {} skipped at the limit of {} running at once", skipped_, max_running_);
    if (failed_ > 0) text += fmt::format(", {} failed", failed_);
    if (ended_ > 0)
        text += fmt::format(", {} ended at the end (still running after the wait)", ended_);
    if (!running_.empty())
        text += fmt::format(", {} still running (not waited for)", running_.size());
    return text;
}

}  // namespace dpscope::cli
