#include "cli/alarm.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <thread>

extern char** environ;

namespace dpscope::cli {

namespace {

template <class List>
auto find_address(const List& list, std::uint8_t address) {
    return std::find_if(list.begin(), list.end(),
                        [address](const auto& item) { return item.address == address; });
}

std::string joined(const std::vector<std::string>& parts, std::string_view separator) {
    std::string text;
    for (const std::string& part : parts) {
        if (!text.empty()) text += separator;
        text += part;
    }
    return text;
}

}  // namespace

AlarmEvent describe_health_event(const HealthEvent& e, const BusHealth& health) {
    AlarmEvent event;
    event.kind = e.kind;
    event.address = e.address;
    event.role = e.role;
    event.time_ns = e.time_ns;
    event.frame = e.frame;
    const Judgement* judgement = nullptr;
    if (e.address == kSegmentAddress) {
        judgement = &health.segment.judgement;
    } else {
        auto master = find_address(health.masters, e.address);
        auto station = find_address(health.stations, e.address);
        if (e.role == StationRole::Master && master != health.masters.end())
            judgement = &master->judgement;
        else if (station != health.stations.end())
            judgement = &station->judgement;
        if (station != health.stations.end() && e.role == StationRole::Unknown)
            event.role = station->role;
    }
    if (judgement) {
        event.verdict = judgement->verdict;
        for (const VerdictReason& reason : judgement->reasons)
            event.reasons.push_back(describe_reason(reason, health.thresholds));
    }
    return event;
}

std::string iso8601_utc(std::int64_t time_ns) {
    if (time_ns == kNoTime) return "unknown";
    // Whole seconds rounded down, so that a time before 1970 keeps a positive fraction.
    std::int64_t seconds = time_ns / 1'000'000'000;
    std::int64_t rest = time_ns % 1'000'000'000;
    if (rest < 0) {
        --seconds;
        rest += 1'000'000'000;
    }
    const std::int64_t micros = rest / 1000;
    std::time_t t = static_cast<std::time_t>(seconds);
    std::tm utc{};
    if (gmtime_r(&t, &utc) == nullptr) return "unknown";
    return fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}:{:02}.{:06}Z", utc.tm_year + 1900,
                       utc.tm_mon + 1, utc.tm_mday, utc.tm_hour, utc.tm_min, utc.tm_sec, micros);
}

std::string event_subject(const AlarmEvent& e) {
    if (e.address == kSegmentAddress) return "the segment";
    if (e.role == StationRole::Master) return fmt::format("station {} (master)", e.address);
    return fmt::format("station {}", e.address);
}

std::string health_event_line(const AlarmEvent& e) {
    const std::string time = iso8601_utc(e.time_ns);
    switch (e.kind) {
        case HealthEventKind::StationLost:
        case HealthEventKind::StationReturned:
            return fmt::format("{} health: station {} {} ({}, frame {})", time, e.address,
                               e.kind == HealthEventKind::StationLost ? "lost" : "returned",
                               station_role_name(e.role), e.frame);
        case HealthEventKind::VerdictBad:
        case HealthEventKind::Count: break;
    }
    return fmt::format("{} health: verdict of {} turned {}{}{} (frame {})", time, event_subject(e),
                       verdict_name(e.verdict), e.reasons.empty() ? "" : ": ",
                       joined(e.reasons, "; "), e.frame);
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
        fmt::format("DPSCOPE_REASONS={}", joined(e.reasons, "; ")),
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

AlarmRunner::AlarmRunner(std::string command, Clock clock, Warn warn, std::int64_t interval_ns)
    : command_(std::move(command)),
      clock_(std::move(clock)),
      warn_(std::move(warn)),
      throttle_(interval_ns) {}

AlarmRunner::~AlarmRunner() = default;

void AlarmRunner::failure(std::string_view what) {
    if (failed_++ == 0 && warn_)
        warn_(fmt::format("--alarm: {} (further failures are only counted)", what));
}

bool AlarmRunner::raise(const AlarmEvent& e) {
    if (!raises_alarm(e.kind) || !throttle_.admit(e.kind, e.address, clock_())) return false;
    reap();
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
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK);
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
        running_.erase(running_.begin() + static_cast<std::ptrdiff_t>(i));
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

std::string AlarmRunner::summary() const {
    const std::uint64_t suppressed = throttle_.suppressed_total();
    if (started_ == 0 && suppressed == 0 && failed_ == 0) return {};
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
            suppressed, throttle_.interval_ns() / 1'000'000'000, joined(kinds, ", "));
    }
    if (failed_ > 0) text += fmt::format(", {} failed", failed_);
    if (!running_.empty())
        text += fmt::format(", {} still running (not waited for)", running_.size());
    return text;
}

}  // namespace dpscope::cli
