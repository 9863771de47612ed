// The --alarm throttle, environment and runner of `sniff` (cli/alarm.hpp), with an injected clock.
#include "cli/alarm.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <future>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/test_support.hpp"

namespace dpscope::cli {
namespace {

constexpr std::int64_t kSecond = 1'000'000'000;

AlarmEvent lost_event(std::uint8_t address) {
    AlarmEvent e;
    e.kind = HealthEventKind::StationLost;
    e.address = address;
    e.role = StationRole::Slave;
    e.time_ns = 1'704'067'200'123'456'789;  // 2024-01-01T00:00:00.123456789Z
    e.frame = 1234;
    e.verdict = Verdict::Bad;
    e.reasons = {"lost events: 1 (bad from 1)", "no answers: 3 % (weak above 1 %)"};
    return e;
}

TEST(AlarmTest, ThrottleLetsOneAlarmPerKindAndStationAMinute) {
    AlarmThrottle throttle;
    EXPECT_TRUE(throttle.admit(HealthEventKind::StationLost, 5, 0));
    EXPECT_FALSE(throttle.admit(HealthEventKind::StationLost, 5, 59 * kSecond));
    // Another station, another kind, the segment: each has its own minute.
    EXPECT_TRUE(throttle.admit(HealthEventKind::StationLost, 6, 1 * kSecond));
    EXPECT_TRUE(throttle.admit(HealthEventKind::VerdictBad, 5, 2 * kSecond));
    EXPECT_TRUE(throttle.admit(HealthEventKind::VerdictBad, kSegmentAddress, 3 * kSecond));
    EXPECT_FALSE(throttle.admit(HealthEventKind::VerdictBad, kSegmentAddress, 4 * kSecond));
    // A minute after the one that went out (not after the one held back).
    EXPECT_TRUE(throttle.admit(HealthEventKind::StationLost, 5, 60 * kSecond));
    EXPECT_FALSE(throttle.admit(HealthEventKind::StationLost, 5, 119 * kSecond));
    EXPECT_EQ(throttle.suppressed(HealthEventKind::StationLost), 2u);
    EXPECT_EQ(throttle.suppressed(HealthEventKind::VerdictBad), 1u);
    EXPECT_EQ(throttle.suppressed_total(), 3u);
}

TEST(AlarmTest, EnvironmentNamesTheEvent) {
    std::vector<std::string> env = alarm_environment(lost_event(5));
    std::vector<std::string> expected = {
        "DPSCOPE_EVENT=station_lost",
        "DPSCOPE_STATION=5",
        "DPSCOPE_ROLE=slave",
        "DPSCOPE_TIME=2024-01-01T00:00:00.123456Z",
        "DPSCOPE_FRAME=1234",
        "DPSCOPE_VERDICT=bad",
        "DPSCOPE_REASONS=lost events: 1 (bad from 1); no answers: 3 % (weak above 1 %)",
    };
    EXPECT_EQ(env, expected);

    AlarmEvent segment;
    segment.kind = HealthEventKind::VerdictBad;
    segment.address = kSegmentAddress;
    segment.time_ns = kNoTime;
    segment.verdict = Verdict::Bad;
    env = alarm_environment(segment);
    EXPECT_EQ(env[0], "DPSCOPE_EVENT=verdict_bad");
    EXPECT_EQ(env[1], "DPSCOPE_STATION=segment");
    EXPECT_EQ(env[2], "DPSCOPE_ROLE=segment");
    EXPECT_EQ(env[3], "DPSCOPE_TIME=unknown");
    EXPECT_EQ(env[6], "DPSCOPE_REASONS=");
}

TEST(AlarmTest, PlainLinesSayWhatHappened) {
    AlarmEvent e = lost_event(5);
    EXPECT_EQ(health_event_line(e),
              "2024-01-01T00:00:00.123456Z health: station 5 lost (slave, frame 1234)");
    e.kind = HealthEventKind::StationReturned;
    EXPECT_EQ(health_event_line(e),
              "2024-01-01T00:00:00.123456Z health: station 5 returned (slave, frame 1234)");
    e.kind = HealthEventKind::VerdictBad;
    e.role = StationRole::Master;
    e.address = 2;
    EXPECT_EQ(health_event_line(e),
              "2024-01-01T00:00:00.123456Z health: verdict of station 2 (master) turned bad: "
              "lost events: 1 (bad from 1); no answers: 3 % (weak above 1 %) (frame 1234)");
    e.address = kSegmentAddress;
    e.reasons.clear();
    EXPECT_NE(health_event_line(e).find("verdict of the segment turned bad (frame 1234)"),
              std::string::npos);
    // Before 1970: the second before, not a negative fraction.
    EXPECT_EQ(iso8601_utc(-1), "1969-12-31T23:59:59.999999Z");
}

TEST(AlarmTest, DescribesTheStationsJudgement) {
    BusHealth health;
    StationHealth station;
    station.address = 5;
    station.role = StationRole::Slave;
    station.judgement.verdict = Verdict::Bad;
    station.judgement.reasons.push_back({HealthThreshold::LostEventsBad, 2, Verdict::Bad});
    health.stations.push_back(station);
    MasterHealth master;
    master.address = 2;
    master.judgement.verdict = Verdict::Weak;
    health.masters.push_back(master);
    StationHealth master_station;
    master_station.address = 2;
    master_station.role = StationRole::Master;
    health.stations.push_back(master_station);
    health.segment.judgement.verdict = Verdict::Bad;

    AlarmEvent e = describe_health_event(
        HealthEvent{HealthEventKind::StationLost, 5, 100, 7, StationRole::Unknown}, health);
    EXPECT_EQ(e.role, StationRole::Slave);  // from the live list
    EXPECT_EQ(e.verdict, Verdict::Bad);
    ASSERT_EQ(e.reasons.size(), 1u);
    EXPECT_EQ(e.reasons[0], describe_reason(station.judgement.reasons[0], health.thresholds));
    EXPECT_EQ(e.frame, 7u);
    EXPECT_EQ(e.time_ns, 100);

    e = describe_health_event(
        HealthEvent{HealthEventKind::VerdictBad, 2, 0, 1, StationRole::Master}, health);
    EXPECT_EQ(e.verdict, Verdict::Weak);  // the master's own judgement
    e = describe_health_event(
        HealthEvent{HealthEventKind::VerdictBad, kSegmentAddress, 0, 1, StationRole::Unknown},
        health);
    EXPECT_EQ(e.verdict, Verdict::Bad);
    // A station not (or no longer) listed: the event as it is.
    e = describe_health_event(
        HealthEvent{HealthEventKind::StationLost, 9, 0, 1, StationRole::Unknown}, health);
    EXPECT_EQ(e.verdict, Verdict::Good);
    EXPECT_TRUE(e.reasons.empty());
}

std::string file_text(const std::string& path) {
    std::vector<std::uint8_t> bytes = test::read_file(path);
    return std::string(bytes.begin(), bytes.end());
}

// How long finish() may wait for the commands: they take milliseconds, but a loaded machine may
// take its time starting a shell. Only a bound for a command that hangs.
constexpr int kPatienceMs = static_cast<int>(test::kPatienceSeconds * 1000);

// Lets a command waiting in `read line < FIFO` go on: opens the fifo for writing once the
// command has opened it for reading, and writes the line. Whether it could within the patience.
bool release(const std::string& fifo) {
    int fd = -1;
    if (!test::wait_until([&] { return (fd = open(fifo.c_str(), O_WRONLY | O_NONBLOCK)) >= 0; }))
        return false;
    const bool written = write(fd, "\n", 1) == 1;
    close(fd);
    return written;
}

// Waits until `path` holds `lines` lines (the commands run on their own; at most the patience).
std::vector<std::string> wait_for_lines(const std::string& path, std::size_t lines) {
    std::vector<std::string> got;
    test::wait_until([&] {
        got = test::lines_of(file_text(path));
        return got.size() >= lines;
    });
    return got;
}

TEST(AlarmTest, RunnerRunsTheCommandWithTheEventInItsEnvironmentOncePerMinute) {
    std::string path = test::temp_path("alarms.txt");
    std::int64_t now = 0;
    std::vector<std::string> warnings;
    AlarmRunner runner(
        "echo \"$DPSCOPE_EVENT $DPSCOPE_STATION $DPSCOPE_ROLE $DPSCOPE_FRAME $DPSCOPE_TIME\" >> " +
            path,
        [&] { return now; }, [&](std::string_view w) { warnings.emplace_back(w); });
    EXPECT_TRUE(runner.raise(lost_event(5)));
    now = 30 * kSecond;
    EXPECT_FALSE(runner.raise(lost_event(5)));  // within the minute
    AlarmEvent returned = lost_event(5);
    returned.kind = HealthEventKind::StationReturned;
    EXPECT_FALSE(runner.raise(returned));  // no alarm for a return
    now = 61 * kSecond;
    AlarmEvent other = lost_event(6);
    other.frame = 99;
    EXPECT_TRUE(runner.raise(other));
    EXPECT_TRUE(runner.raise(lost_event(5)));   // a minute later
    EXPECT_EQ(runner.finish(kPatienceMs), 0u);  // then every line is written
    std::vector<std::string> lines = test::lines_of(file_text(path));
    std::sort(lines.begin(), lines.end());
    std::vector<std::string> expected = {
        "station_lost 5 slave 1234 2024-01-01T00:00:00.123456Z",
        "station_lost 5 slave 1234 2024-01-01T00:00:00.123456Z",
        "station_lost 6 slave 99 2024-01-01T00:00:00.123456Z",
    };
    EXPECT_EQ(lines, expected);
    EXPECT_EQ(runner.started(), 3u);
    EXPECT_EQ(runner.failed(), 0u);
    EXPECT_TRUE(warnings.empty());
    EXPECT_EQ(runner.summary(),
              "alarms: 3 run, 1 suppressed by the limit of one per event kind and station per "
              "60 s (station_lost 1)");
}

TEST(AlarmTest, AFailingCommandGetsOneWarning) {
    std::int64_t now = 0;
    std::vector<std::string> warnings;
    AlarmRunner runner(
        "exit 3", [&] { return now; }, [&](std::string_view w) { warnings.emplace_back(w); });
    EXPECT_TRUE(runner.raise(lost_event(5)));
    EXPECT_TRUE(runner.raise(lost_event(6)));
    EXPECT_TRUE(runner.raise(lost_event(7)));
    EXPECT_EQ(runner.finish(kPatienceMs), 0u);
    EXPECT_EQ(runner.failed(), 3u);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("exited with code 3"), std::string::npos) << warnings[0];
    EXPECT_EQ(runner.summary(), "alarms: 3 run, 3 failed");
}

TEST(AlarmTest, NeverWaitsForASlowCommandDuringTheCapture) {
    // The command runs until the test lets it end (it waits for a line from a fifo), however
    // long raise() and reap() take on a loaded machine. Were it waited for, only the watchdog
    // would let it end, at its deadline, and it says so.
    const std::string fifo = test::temp_path("release.fifo");
    ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
    std::int64_t now = 0;
    AlarmRunner runner(
        "read line < '" + fifo + "'", [&] { return now; }, nullptr);
    std::promise<void> back;
    std::atomic<bool> released_by_watchdog{false};
    std::thread watchdog([&, came_back = back.get_future()] {
        if (came_back.wait_for(std::chrono::duration<double>(test::kPatienceSeconds)) !=
            std::future_status::ready) {
            released_by_watchdog = true;
            release(fifo);
        }
    });
    EXPECT_TRUE(runner.raise(lost_event(5)));
    runner.reap();
    back.set_value();
    watchdog.join();
    EXPECT_FALSE(released_by_watchdog) << "raise() waited for the command to end";
    EXPECT_EQ(runner.running(), 1u);
    // At the end it is waited for at most the time given, then left running.
    EXPECT_EQ(runner.finish(50), 1u);
    EXPECT_NE(runner.summary().find("1 still running"), std::string::npos) << runner.summary();
    EXPECT_TRUE(release(fifo));
    EXPECT_EQ(runner.finish(kPatienceMs), 0u);
}

// Alarm commands that hang do not pile up: at most `max_running` run at once, an alarm beyond
// that is skipped (counted, one warning) without using up its station's minute, and at the end
// the commands still running are ended with their process group (the shell and what it
// started), first with SIGTERM, after the grace period with SIGKILL.
TEST(AlarmTest, HangingCommandsAreCappedAndEndedAtTheEnd) {
    const std::string pids = test::temp_path("pids.txt");
    std::int64_t now = 0;
    std::vector<std::string> warnings;
    // The shell stays the sleep's parent (a command follows it): the pair seen piling up.
    AlarmRunner runner(
        "echo $$ >> " + pids + "; sleep 300; echo", [&] { return now; },
        [&](std::string_view w) { warnings.emplace_back(w); }, AlarmThrottle::kDefaultIntervalNs,
        2);
    EXPECT_TRUE(runner.raise(lost_event(5)));
    EXPECT_TRUE(runner.raise(lost_event(6)));
    EXPECT_FALSE(runner.raise(lost_event(7)));  // two are running: skipped
    EXPECT_FALSE(runner.raise(lost_event(8)));
    EXPECT_EQ(runner.running(), 2u);
    EXPECT_EQ(runner.skipped(), 2u);
    EXPECT_EQ(runner.started(), 2u);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0],
              "--alarm: 2 commands are still running, the most at once; alarms are skipped "
              "until one ends (further ones are only counted)");
    std::vector<std::string> started = wait_for_lines(pids, 2);
    ASSERT_EQ(started.size(), 2u);
    std::vector<pid_t> groups;
    for (const std::string& line : started)
        groups.push_back(static_cast<pid_t>(std::stol(line)));
    for (pid_t group : groups)
        EXPECT_TRUE(test::wait_for_processes_in_group(group, 2));  // the shell and its sleep
    EXPECT_EQ(runner.finish(0), 2u);
    EXPECT_EQ(runner.end_running(2000), 2u);
    EXPECT_EQ(runner.running(), 0u);
    for (pid_t group : groups)
        EXPECT_TRUE(test::wait_for_processes_in_group(group, 0)) << group;
    EXPECT_EQ(runner.failed(), 0u);  // ended by us, not failed
    EXPECT_EQ(runner.summary(),
              "alarms: 2 run, 2 skipped at the limit of 2 running at once, 2 ended at the end "
              "(still running after the wait)");
    // The skipped station's alarm goes out once there is room.
    EXPECT_TRUE(runner.raise(lost_event(7)));
    EXPECT_EQ(runner.end_running(2000), 1u);
}

// A command that ignores SIGTERM is killed after the grace period.
TEST(AlarmTest, ACommandIgnoringSigtermIsKilledAfterTheGracePeriod) {
    const std::string pids = test::temp_path("pids.txt");
    std::int64_t now = 0;
    AlarmRunner runner(
        "trap '' TERM; echo $$ >> " + pids + "; sleep 300; echo", [&] { return now; }, nullptr);
    EXPECT_TRUE(runner.raise(lost_event(5)));
    std::vector<std::string> started = wait_for_lines(pids, 1);
    ASSERT_EQ(started.size(), 1u);
    const auto group = static_cast<pid_t>(std::stol(started[0]));
    EXPECT_EQ(runner.end_running(100), 1u);
    EXPECT_TRUE(test::wait_for_processes_in_group(group, 0));
    EXPECT_EQ(runner.running(), 0u);
}

TEST(AlarmTest, TheCommandInheritsNoDescriptorAndWritesNothingOnStandardOutput) {
    std::string path = test::temp_path("fds.txt");
    int pipe_fds[2];
    ASSERT_EQ(pipe(pipe_fds), 0);  // an open descriptor the command must not get
    std::int64_t now = 0;
    AlarmRunner runner(
        "ls /proc/self/fd > " + path, [&] { return now; }, nullptr);
    EXPECT_TRUE(runner.raise(lost_event(5)));
    EXPECT_EQ(runner.finish(kPatienceMs), 0u);
    std::vector<std::string> fds = test::lines_of(file_text(path));
    close(pipe_fds[0]);
    close(pipe_fds[1]);
    // 0, 1, 2 and the one ls opened for /proc/self/fd (the lowest free: 3), nothing else.
    std::vector<std::string> expected = {"0", "1", "2", "3"};
    EXPECT_EQ(fds, expected);
}

}  // namespace
}  // namespace dpscope::cli
