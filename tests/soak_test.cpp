// The soak test of the unattended monitor (issue 30): `simulate --device` plays a PROFIBUS bus
// with faults at a rate through a pseudo-terminal into `sniff` with the ring buffer, triggers,
// bus health and MQTT on, for DPSCOPE_SOAK_SECONDS (60 by default: the CI's version; bench/soak
// runs it for 10 minutes and more; DPSCOPE_SOAK_BAUD and DPSCOPE_SOAK_CYCLE_US set the bus).
// Then:
//   - no telegram lost: the ring's kept files hold the tail of the session, byte for byte, and
//     the telegrams the ring removed are counted; together they are every telegram played;
//   - flat memory: sniff's RSS when all has arrived is within 10 % of its RSS after the first
//     minute (a quarter of a shorter run);
//   - every trigger window present with the right telegrams: each trigger the session holds
//     (found offline in the same session by `decode -Y`) is a commented telegram in a window, and
//     each window is a run of the session's telegrams around its triggers;
//   - every event received: each finding and health event sniff counted arrived at a real MQTT
//     subscriber, and the figures count every telegram.
// The figures (rate, RSS, counts) are printed as "soak: ..." lines for bench/soak.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "capture/capture_writer.hpp"
#include "tests/json_parser.hpp"
#include "tests/mqtt_support.hpp"
#include "tests/pty_support.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::Child;
using test::MosquittoBroker;
using test::MqttSubscriber;
using test::PseudoTerminal;
using test::ReceivedMessage;
using test::Telegrams;

double soak_seconds() {
    if (const char* text = std::getenv("DPSCOPE_SOAK_SECONDS")) return std::atof(text);
#if defined(__SANITIZE_ADDRESS__)
    return 15;  // the sanitizer build checks the same paths; CI's time is short
#else
    return 60;
#endif
}

std::string soak_baud() {
    const char* text = std::getenv("DPSCOPE_SOAK_BAUD");
    return text ? text : "1500000";
}

// The DP master's cycle in microseconds (the simulator's default 2000; 100 at 12 Mbit/s keeps the
// bus busy all the time).
std::string soak_cycle_us() {
    const char* text = std::getenv("DPSCOPE_SOAK_CYCLE_US");
    return text ? text : "2000";
}

// A record of a pcapng file with its comment (opt_comment), read by the test itself: dpscope's
// reader has no use for comments.
struct CommentedRecord {
    std::vector<std::uint8_t> bytes;
    std::string comment;
};

std::uint32_t le32(const std::vector<std::uint8_t>& d, std::size_t at) {
    return d[at] | d[at + 1] << 8 | d[at + 2] << 16 | static_cast<std::uint32_t>(d[at + 3]) << 24;
}

std::vector<CommentedRecord> pcapng_records(const std::string& path) {
    const std::vector<std::uint8_t> d = test::read_file(path);
    std::vector<CommentedRecord> records;
    std::size_t at = 0;
    while (at + 12 <= d.size()) {
        const std::uint32_t type = le32(d, at);
        const std::uint32_t length = le32(d, at + 4);
        if (length < 12 || at + length > d.size()) break;
        if (type == 6) {  // enhanced packet block
            const std::uint32_t captured = le32(d, at + 20);
            CommentedRecord r;
            r.bytes.assign(d.begin() + static_cast<std::ptrdiff_t>(at + 28),
                           d.begin() + static_cast<std::ptrdiff_t>(at + 28 + captured));
            std::size_t option = at + 28 + ((captured + 3) & ~3u);
            while (option + 4 <= at + length - 4) {
                const unsigned code = d[option] | d[option + 1] << 8;
                const unsigned size = d[option + 2] | d[option + 3] << 8;
                if (code == 0) break;
                if (code == 1)
                    r.comment.assign(d.begin() + static_cast<std::ptrdiff_t>(option + 4),
                                     d.begin() + static_cast<std::ptrdiff_t>(option + 4 + size));
                option += 4 + ((size + 3) & ~3u);
            }
            records.push_back(std::move(r));
        }
        at += length;
    }
    return records;
}

// VmRSS of process `pid` in KiB.
long rss_kib(pid_t pid) {
    std::ifstream status("/proc/" + std::to_string(pid) + "/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind("VmRSS:", 0) == 0) return std::atol(line.c_str() + 6);
    return -1;
}

// The telegram count in sniff's status file ("dpscope: status: N telegrams, ...").
std::uint64_t status_telegrams(const std::string& path) {
    const std::string text = test::slurp(path);
    const std::size_t at = text.find("status: ");
    return at == std::string::npos ? 0 : std::strtoull(text.c_str() + at + 8, nullptr, 10);
}

// The frames `decode -T jsonl -Y EXPR` selects in `pcap`.
std::set<std::uint64_t> frames_selected(const std::string& pcap, const std::string& filter) {
    auto run = test::run_dpscope({"decode", "-T", "jsonl", "-Y", filter, pcap});
    EXPECT_EQ(run.exit_code, 0) << run.err;
    std::set<std::uint64_t> frames;
    for (const std::string& line : test::lines_of(run.out))
        if (line.rfind("{\"frame\":", 0) == 0)
            frames.insert(std::strtoull(line.c_str() + 9, nullptr, 10));
    return frames;
}

TEST(SoakTest, AnUnattendedMonitorLosesNothingAndStaysFlat) {
    const double seconds = soak_seconds();
    const std::string baud = soak_baud();
    const std::string folder = test::temp_path("soak");
    std::filesystem::create_directories(folder + "/cuts");
    // The bus: three slaves, faults at a rate (per cycle and slave): findings, lost stations.
    std::vector<std::string> session = {"--seed", "30",         "--baud",
                                        baud,     "--cycle-us", soak_cycle_us()};
    for (const char* fault : {"stacked_request=0.0004", "request_rejected=0.0004",
                              "orphan_response=0.0004", "station_lost=0.0001"})
        session.insert(session.end(), {"--fault", fault});
    // Cycles for the time asked: the simulated time of a short session, scaled.
    const auto simulate_to = [&](const std::string& pcap, std::uint64_t cycles) {
        std::vector<std::string> args = {"simulate", "-w", pcap, "--cycles",
                                         std::to_string(cycles)};
        args.insert(args.end(), session.begin(), session.end());
        auto run = test::run_dpscope(args);
        EXPECT_EQ(run.exit_code, 0) << run.err;
        return test::read_capture(pcap);
    };
    const test::Capture probe = simulate_to(folder + "/probe.pcap", 2000);
    ASSERT_GE(probe.times.size(), 2u);
    const double probe_seconds =
        static_cast<double>(probe.times.back() - probe.times.front()) / 1e9;
    const auto cycles = static_cast<std::uint64_t>(seconds / probe_seconds * 2000);
    const std::string reference = folder + "/reference.pcap";
    const test::Capture expected = simulate_to(reference, cycles);
    const std::size_t total = expected.telegrams.size();
    ASSERT_GT(total, 0u);
    std::uint64_t bytes = 0;
    for (const auto& t : expected.telegrams)
        bytes += t.size() + 16;

    const std::string trigger_lost = "health.event == \"station_lost\"";
    const std::string trigger_stacked = "dpscope.finding == \"stacked_request\"";
    MosquittoBroker broker;
    MqttSubscriber subscriber(broker.port(), "dpscope/soak/#");
    ASSERT_TRUE(subscriber.subscribed());
    PseudoTerminal bus;      // simulate plays onto its slave end
    PseudoTerminal adapter;  // sniff captures on its slave end
    const std::string ring = folder + "/ring.pcap";
    const std::string status = folder + "/status";
    // Files of about a tenth of the session, the last four kept: the ring removes most.
    const std::uint64_t rotate = std::max<std::uint64_t>(64 * 1024, bytes / 10);
    Child sniffer(test::dpscope_argv(test::without_idle_gap({"sniff",
                                                             "-i",
                                                             adapter.slave,
                                                             "--baud",
                                                             baud,
                                                             "-q",
                                                             "--stats",
                                                             "-w",
                                                             ring,
                                                             "--rotate-size",
                                                             std::to_string(rotate),
                                                             "--ring",
                                                             "4",
                                                             "--trigger",
                                                             trigger_lost,
                                                             "--trigger",
                                                             trigger_stacked,
                                                             "--pre",
                                                             "0.2",
                                                             "--post",
                                                             "0.2",
                                                             "--trigger-limit",
                                                             "100000",
                                                             "--trigger-dir",
                                                             folder + "/cuts",
                                                             "--mqtt",
                                                             broker.url(),
                                                             "--mqtt-segment",
                                                             "soak",
                                                             "--mqtt-queue",
                                                             "1000000",
                                                             "--mqtt-wait",
                                                             "120",
                                                             "--status-file",
                                                             status,
                                                             "--status-interval",
                                                             "0.5"})));
    ASSERT_TRUE(sniffer.err_says("capturing on")) << sniffer.err();
    const auto started = std::chrono::steady_clock::now();
    long rss_early = -1;
    {
        test::Relay relay(bus.master, adapter.master);
        std::vector<std::string> play = {"simulate", "--device", bus.slave, "--cycles",
                                         std::to_string(cycles)};
        play.insert(play.end(), session.begin(), session.end());
        Child simulator(test::dpscope_argv(play));
        // RSS after the first minute (a quarter of a shorter run): when that much has arrived.
        const double early = std::min(60.0 / seconds, 0.25);
        ASSERT_TRUE(test::wait_until(
            [&] {
                return status_telegrams(status) >=
                       static_cast<std::uint64_t>(early * static_cast<double>(total));
            },
            seconds * 4 + test::kPatienceSeconds))
            << sniffer.err();
        rss_early = rss_kib(sniffer.pid());
        EXPECT_EQ(simulator.wait(seconds * 4 + test::kPatienceSeconds), 0) << simulator.err();
        relay.stop();
    }
    const double played_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    // Everything played has arrived when the status says so (the status file is rewritten
    // every half second).
    ASSERT_TRUE(test::wait_until([&] { return status_telegrams(status) >= total; }))
        << test::slurp(status) << sniffer.err();
    const long rss_end = rss_kib(sniffer.pid());
    sniffer.signal(SIGINT);
    ASSERT_EQ(sniffer.wait(), 0) << sniffer.err();
    const std::string err = sniffer.err();

    // No telegram lost: the kept files are the session's tail, the removed ones are counted.
    const std::regex kept_pattern(
        "the ring kept files .*-([0-9]+)\\.pcap to .*-([0-9]+)\\.pcap \\([0-9]+ bytes\\); it "
        "removed the ([0-9]+) oldest, which held ([0-9]+) telegrams");
    std::smatch kept;
    ASSERT_TRUE(std::regex_search(err, kept, kept_pattern)) << err;
    const unsigned first_kept = static_cast<unsigned>(std::stoul(kept[1]));
    const unsigned last_kept = static_cast<unsigned>(std::stoul(kept[2]));
    const std::uint64_t removed = std::stoull(kept[4]);
    Telegrams tail;
    for (unsigned index = first_kept; index <= last_kept; ++index) {
        test::Capture part = test::read_capture(rotated_file_name(ring, index));
        EXPECT_EQ(part.status, InputStatus::Ok) << index;
        tail.insert(tail.end(), part.telegrams.begin(), part.telegrams.end());
    }
    EXPECT_FALSE(std::filesystem::exists(rotated_file_name(ring, first_kept - 1)));
    ASSERT_EQ(removed + tail.size(), total) << err;
    EXPECT_TRUE(std::equal(tail.begin(), tail.end(),
                           expected.telegrams.begin() + static_cast<std::ptrdiff_t>(removed)));

    // Flat memory.
    ASSERT_GT(rss_early, 0);
    EXPECT_LE(rss_end, rss_early * 11 / 10)
        << "RSS " << rss_early << " KiB early, " << rss_end << " KiB at the end";

    // Trigger windows: every trigger of the session is a commented telegram in a window, and each
    // window is a run of the session's telegrams.
    std::set<std::uint64_t> want = frames_selected(reference, trigger_lost);
    const std::set<std::uint64_t> stacked = frames_selected(reference, trigger_stacked);
    want.insert(stacked.begin(), stacked.end());
    ASSERT_FALSE(want.empty());
    std::set<std::uint64_t> found;
    std::size_t windows = 0;
    for (const auto& entry : std::filesystem::directory_iterator(folder + "/cuts")) {
        ++windows;
        const std::vector<CommentedRecord> records = pcapng_records(entry.path().string());
        std::optional<std::uint64_t> start;  // the window's first telegram's index in the session
        for (std::size_t i = 0; i < records.size(); ++i) {
            if (records[i].comment.empty()) continue;
            const std::size_t at = records[i].comment.rfind("(frame ");
            ASSERT_NE(at, std::string::npos) << records[i].comment;
            const std::uint64_t frame = std::stoull(records[i].comment.substr(at + 7));
            found.insert(frame);
            ASSERT_GE(frame, i + 1) << entry.path();
            if (!start) start = frame - 1 - i;
            EXPECT_EQ(*start, frame - 1 - i) << entry.path();
        }
        ASSERT_TRUE(start) << entry.path() << ": no triggering telegram";
        ASSERT_LE(*start + records.size(), total);
        for (std::size_t i = 0; i < records.size(); ++i)
            ASSERT_EQ(records[i].bytes, expected.telegrams[*start + i])
                << entry.path() << " record " << i;
    }
    EXPECT_EQ(found, want);

    // Every event at the MQTT subscriber: as many findings and health events as sniff counted.
    ASSERT_TRUE(subscriber.wait_for([](const std::vector<ReceivedMessage>& m) {
        return std::any_of(m.begin(), m.end(), [](const ReceivedMessage& r) {
            return r.topic == "dpscope/soak/status" &&
                   r.payload.find("stopped") != std::string::npos;
        });
    })) << err;
    const std::vector<std::string> stats = subscriber.distinct_payloads("dpscope/soak/stats");
    ASSERT_FALSE(stats.empty());
    auto last = test::parse_json(stats.back());
    ASSERT_TRUE(last);
    EXPECT_EQ((*last)["telegrams"].integer(), static_cast<long long>(total));
    EXPECT_EQ((*last)["mqtt_dropped"].integer(), 0);
    std::set<std::pair<std::string, long long>> findings;
    for (const std::string& payload : subscriber.distinct_payloads("dpscope/soak/finding")) {
        auto f = test::parse_json(payload);
        ASSERT_TRUE(f) << payload;
        findings.insert({(*f)["kind"].string(), (*f)["frame"].integer()});
    }
    EXPECT_EQ(static_cast<long long>(findings.size()), (*last)["findings"].integer());
    std::size_t health_lines = 0;
    for (const std::string& line : test::lines_of(sniffer.out()))
        if (line.find(" health: ") != std::string::npos) ++health_lines;
    EXPECT_EQ(subscriber.distinct_payloads("dpscope/soak/health").size(), health_lines);
    EXPECT_GT(health_lines, 0u);
    // The stacked requests the session holds are among the findings published.
    for (std::uint64_t frame : stacked)
        EXPECT_TRUE(findings.count({"stacked_request", static_cast<long long>(frame)})) << frame;

    std::printf(
        "soak: %.0f s played (%.0f s asked) at %s baud: %zu telegrams (%.0f/s), %llu removed by "
        "the ring, %zu kept in files %u to %u; %zu trigger windows for %zu triggers; %zu "
        "findings and %zu health events over MQTT; RSS %ld KiB after %.0f %% of the session, %ld "
        "KiB at its end\n",
        played_seconds, seconds, baud.c_str(), total, static_cast<double>(total) / played_seconds,
        static_cast<unsigned long long>(removed), tail.size(), first_kept, last_kept, windows,
        want.size(), findings.size(), health_lines, rss_early, std::min(60.0 / seconds, 0.25) * 100,
        rss_end);
    std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace dpscope
