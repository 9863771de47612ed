// sniff --mqtt (issue 30) against a real mosquitto broker on a loopback port, with a real
// subscriber: the publisher alone (queue, drops, a broker killed and restarted), the payloads,
// the command line, and sniff end to end on a pseudo-terminal.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "formats/monitor_messages.hpp"
#include "monitor/mqtt_publisher.hpp"
#include "protocols/profibus/health/health_event_describe.hpp"
#include "tests/json_parser.hpp"
#include "tests/mqtt_support.hpp"
#include "tests/pty_support.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using monitor::MqttMessage;
using monitor::MqttPublisher;
using monitor::MqttSettings;
using test::MosquittoBroker;
using test::MqttSubscriber;
using test::ReceivedMessage;

// --- the broker's address, the topics, the payloads ---------------------------------------------

TEST(MqttTest, BrokerAddressesAreReadAndBadOnesNamed) {
    auto plain = monitor::parse_mqtt_url("mqtt://broker.plant");
    ASSERT_TRUE(plain) << plain.error();
    EXPECT_EQ(plain->host, "broker.plant");
    EXPECT_EQ(plain->port, 1883);
    EXPECT_FALSE(plain->tls);
    auto tls = monitor::parse_mqtt_url("mqtts://10.0.0.5:8884/");
    ASSERT_TRUE(tls) << tls.error();
    EXPECT_EQ(tls->host, "10.0.0.5");
    EXPECT_EQ(tls->port, 8884);
    EXPECT_TRUE(tls->tls);
    auto v6 = monitor::parse_mqtt_url("mqtt://[::1]:1884");
    ASSERT_TRUE(v6) << v6.error();
    EXPECT_EQ(v6->host, "::1");
    EXPECT_EQ(v6->port, 1884);
    EXPECT_EQ(monitor::parse_mqtt_url("mqtts://[fe80::1]")->port, 8883);
    for (const auto& [url, says] : std::vector<std::pair<std::string, std::string>>{
             {"tcp://broker", "not an MQTT broker address"},
             {"broker:1883", "not an MQTT broker address"},
             {"mqtt://", "host name is missing"},
             {"mqtt://:1883", "host name is missing"},
             {"mqtt://broker:", "port after ':' is missing"},
             {"mqtt://broker:0", "from 1 to 65535, not '0'"},
             {"mqtt://broker:65536", "from 1 to 65535, not '65536'"},
             {"mqtt://broker:12x", "not '12x'"},
             {"mqtt://user:secret@broker", "process list"},
             {"mqtt://[::1", "no closing ']'"},
             {"mqtt://bro ker", "is not a host name"}}) {
        auto parsed = monitor::parse_mqtt_url(url);
        ASSERT_FALSE(parsed) << url;
        EXPECT_NE(parsed.error().find(says), std::string::npos) << url << ": " << parsed.error();
    }
}

TEST(MqttTest, TopicsAreCheckedAndLaidOutUnderPrefixAndSegment) {
    auto topics = MqttTopics::make("plant1/hall2/dpscope", "line3");
    ASSERT_TRUE(topics) << topics.error();
    EXPECT_EQ(topics->status(), "plant1/hall2/dpscope/line3/status");
    EXPECT_EQ(topics->finding(), "plant1/hall2/dpscope/line3/finding");
    EXPECT_EQ(topics->health(), "plant1/hall2/dpscope/line3/health");
    EXPECT_EQ(topics->live(), "plant1/hall2/dpscope/line3/live");
    EXPECT_EQ(topics->verdict(5), "plant1/hall2/dpscope/line3/verdict/5");
    EXPECT_EQ(topics->verdict(0xFF), "plant1/hall2/dpscope/line3/verdict/segment");
    EXPECT_EQ(topics->stats(), "plant1/hall2/dpscope/line3/stats");
    for (const auto& [prefix, segment, says] :
         std::vector<std::tuple<std::string, std::string, std::string>>{
             {"dpscope/#", "line3", "wildcard"},
             {"dp+scope", "line3", "wildcard"},
             {"dpscope", "line+3", "wildcard"},
             {"/dpscope", "line3", "level is empty"},
             {"dpscope/", "line3", "level is empty"},
             {"a//b", "line3", "level is empty"},
             {"", "line3", "level is empty"},
             {"dpscope", "", "level is empty"},
             {"dpscope", "a/b", "one topic level"}}) {
        auto made = MqttTopics::make(prefix, segment);
        ASSERT_FALSE(made) << prefix << " " << segment;
        EXPECT_NE(made.error().find(says), std::string::npos) << made.error();
    }
}

TEST(MqttTest, PayloadsAreJsonWithTheDocumentedKeys) {
    MonitorIdentity who{"line3",   "/dev/ttyUSB0", "profibus",
                        1'500'000, "0.1.0",        1'704'067'200'000'000'000};
    auto online = test::parse_json(status_payload(who, "online"));
    ASSERT_TRUE(online);
    EXPECT_EQ(online->keys(), (std::vector<std::string>{"state", "segment", "device", "bus", "baud",
                                                        "version", "since"}));
    EXPECT_EQ((*online)["since"].string(), "2024-01-01T00:00:00Z");
    const std::uint64_t telegrams = 42;
    auto stopped = test::parse_json(status_payload(who, "offline", "stopped", &telegrams));
    ASSERT_TRUE(stopped);
    EXPECT_EQ((*stopped)["reason"].string(), "stopped");
    EXPECT_EQ((*stopped)["telegrams"].integer(), 42);

    MonitorFigures figures;
    figures.time_ns = 1'704'067'200'000'000'000;
    figures.telegrams = 1200;
    figures.rate = 399.96;
    figures.last_event = "station_lost 5 at frame 7";
    auto stats = test::parse_json(stats_payload(figures));
    ASSERT_TRUE(stats);
    EXPECT_EQ(stats->keys(),
              (std::vector<std::string>{"time", "telegrams", "rate", "bytes_skipped",
                                        "parity_errors", "disk_bytes", "findings", "health_events",
                                        "last_event", "mqtt_dropped", "mqtt_waiting"}));
    EXPECT_EQ((*stats)["rate"].text, "400.0");
    EXPECT_EQ(status_line(figures),
              "dpscope: status: 1200 telegrams, 400/s, 0 bytes skipped, 0 parity errors, 0 bytes "
              "on disk, last event station_lost 5 at frame 7");

    // A health event carries the --alarm variables by their lower-case names.
    AlarmEvent lost;
    lost.kind = HealthEventKind::StationLost;
    lost.address = 5;
    lost.role = StationRole::Slave;
    lost.time_ns = 1'704'067'200'123'456'789;
    lost.frame = 1234;
    lost.verdict = Verdict::Bad;
    lost.reasons = {"2 lost events (bad from 1)"};
    fmt::memory_buffer buffer;
    {
        JsonWriter w(buffer);
        health_event_json(w, lost);
    }
    EXPECT_EQ(
        std::string(buffer.data(), buffer.size()),
        "{\"event\":\"station_lost\",\"station\":5,\"role\":\"slave\",\"time\":\"2024-01-01T00:"
        "00:00.123456Z\",\"frame\":1234,\"verdict\":\"bad\",\"reasons\":[\"2 lost events (bad "
        "from 1)\"]}");
    lost.address = kSegmentAddress;
    lost.kind = HealthEventKind::VerdictBad;
    buffer.clear();
    {
        JsonWriter w(buffer);
        health_event_json(w, lost);
    }
    EXPECT_NE(std::string(buffer.data(), buffer.size())
                  .find("\"event\":\"verdict_bad\",\"station\":\"segment\",\"role\":\"segment\""),
              std::string::npos);
}

// --- the publisher against a real broker ---------------------------------------------------------

MqttSettings settings_for(const MosquittoBroker& broker, std::string client_id) {
    MqttSettings s;
    s.endpoint = *monitor::parse_mqtt_url(broker.url());
    s.client_id = std::move(client_id);
    s.birth = {"t/status", "online", 1, true};
    s.will = {"t/status", "offline", 1, true};
    s.retry_last_ms = 500;
    return s;
}

std::vector<std::string> numbered(int from, int to) {
    std::vector<std::string> out;
    for (int i = from; i < to; ++i)
        out.push_back("event " + std::to_string(i));
    return out;
}

TEST(MqttTest, PublisherDeliversEveryMessageInOrderAfterItsBirth) {
    MosquittoBroker broker;
    MqttSubscriber subscriber(broker.port(), "t/#");
    ASSERT_TRUE(subscriber.subscribed());
    auto publisher = MqttPublisher::start(settings_for(broker, "publisher-order"), {});
    ASSERT_TRUE(publisher) << publisher.error();
    for (const std::string& text : numbered(0, 500))
        (*publisher)->publish({"t/event", text, 1, false});
    ASSERT_TRUE((*publisher)->wait_until_delivered(120'000));
    ASSERT_TRUE(subscriber.wait_for(
        [](const auto& m) { return m.size() >= 501; }));  // the birth and 500 events
    EXPECT_EQ(subscriber.distinct_payloads("t/event"), numbered(0, 500));
    EXPECT_EQ(subscriber.messages().front().topic, "t/status");
    EXPECT_EQ(subscriber.messages().front().payload, "online");
    EXPECT_EQ((*publisher)->finish({"t/status", "offline, stopped", 1, true}, 120'000), 0u);
    ASSERT_TRUE(subscriber.wait_for(
        [](const auto& m) { return !m.empty() && m.back().payload == "offline, stopped"; }));
    const monitor::MqttCounters c = (*publisher)->counters();
    EXPECT_EQ(c.queued, 501u);
    EXPECT_EQ(c.dropped, 0u);
    EXPECT_EQ(c.connections, 1u);
}

TEST(MqttTest, ABrokerKilledAndRestartedLosesNothingThatWasQueued) {
    MosquittoBroker broker;
    MqttSubscriber subscriber(broker.port(), "t/#");
    ASSERT_TRUE(subscriber.subscribed());
    std::vector<std::string> warnings;
    std::mutex warnings_mutex;
    auto publisher =
        MqttPublisher::start(settings_for(broker, "publisher-restart"), [&](std::string_view w) {
            std::lock_guard lock(warnings_mutex);
            warnings.emplace_back(w);
        });
    ASSERT_TRUE(publisher) << publisher.error();
    for (const std::string& text : numbered(0, 200))
        (*publisher)->publish({"t/event", text, 1, false});
    ASSERT_TRUE((*publisher)->wait_until_delivered(120'000));
    ASSERT_TRUE(subscriber.wait_for([](const auto& m) { return m.size() >= 201; }));
    subscriber.pause();
    ASSERT_TRUE(broker.log_says("Client dpscope-test-subscriber disconnected")) << broker.log();
    broker.kill();
    // Queued while the broker is down: nothing blocks.
    for (const std::string& text : numbered(200, 400))
        (*publisher)->publish({"t/event", text, 1, false});
    EXPECT_TRUE(test::wait_until([&] { return !(*publisher)->counters().connected; }));
    broker.restart();
    ASSERT_TRUE((*publisher)->wait_until_delivered(120'000)) << broker.log();
    subscriber.resume();
    ASSERT_TRUE(subscriber.wait_for([](const auto& m) {
        std::set<std::string> seen;
        for (const ReceivedMessage& r : m)
            if (r.topic == "t/event") seen.insert(r.payload);
        return seen.size() == 400;
    })) << broker.log();
    EXPECT_EQ(subscriber.distinct_payloads("t/event"), numbered(0, 400));
    const monitor::MqttCounters c = (*publisher)->counters();
    EXPECT_EQ(c.dropped, 0u);
    EXPECT_EQ(c.connections, 2u);
    std::lock_guard lock(warnings_mutex);
    std::string all;
    for (const std::string& w : warnings)
        all += w + "\n";
    EXPECT_NE(all.find("lost the connection to mqtt://127.0.0.1:"), std::string::npos) << all;
    EXPECT_NE(all.find("connected to mqtt://127.0.0.1:"), std::string::npos) << all;
}

TEST(MqttTest, AFullQueueDropsNewEventsCountedAndKeepsOnlyTheLatestState) {
    MosquittoBroker broker;
    MqttSubscriber subscriber(broker.port(), "t/#");
    ASSERT_TRUE(subscriber.subscribed());
    subscriber.pause();
    ASSERT_TRUE(broker.log_says("Client dpscope-test-subscriber disconnected")) << broker.log();
    broker.kill();  // down from the start: everything waits
    MqttSettings s = settings_for(broker, "publisher-full");
    s.queue_limit = 5;
    auto publisher = MqttPublisher::start(s, {});
    ASSERT_TRUE(publisher) << publisher.error();
    (*publisher)->publish({"t/live", "state 1", 1, true});
    for (const std::string& text : numbered(0, 6))
        (*publisher)->publish({"t/event", text, 1, false});  // events 4 and 5 do not fit
    (*publisher)->publish({"t/live", "state 2", 1, true});   // replaces state 1 where it waits
    (*publisher)->publish({"t/verdict", "bad", 1, true});    // a state: takes event 0's place
    monitor::MqttCounters c = (*publisher)->counters();
    EXPECT_EQ(c.queued, 9u);
    EXPECT_EQ(c.dropped, 3u);
    EXPECT_EQ(c.replaced, 1u);
    EXPECT_EQ(c.waiting, 5u);
    broker.restart();
    ASSERT_TRUE((*publisher)->wait_until_delivered(120'000)) << broker.log();
    subscriber.resume();
    ASSERT_TRUE(subscriber.wait_for([](const auto& m) {
        return std::count_if(m.begin(), m.end(),
                             [](const ReceivedMessage& r) { return r.topic != "t/status"; }) >= 5;
    })) << broker.log();
    EXPECT_EQ(subscriber.distinct_payloads("t/event"), numbered(1, 4));
    EXPECT_EQ(subscriber.distinct_payloads("t/live"), std::vector<std::string>{"state 2"});
    EXPECT_EQ(subscriber.distinct_payloads("t/verdict"), std::vector<std::string>{"bad"});
}

}  // namespace
}  // namespace dpscope

// --- sniff --mqtt end to end
// ------------------------------------------------------------------------

namespace dpscope {
namespace {

using test::Child;
using test::PseudoTerminal;
using test::Session;

// The finding objects of jsonl text, as written ({"kind":...} inside "findings":[...]).
std::multiset<std::string> jsonl_findings(const std::string& jsonl) {
    std::multiset<std::string> found;
    for (const std::string& line : test::lines_of(jsonl)) {
        std::size_t at = line.find("\"findings\":[");
        if (at == std::string::npos) continue;
        at += 12;
        // Flat objects: from '{' to its '}', strings skipped.
        while (at < line.size() && line[at] == '{') {
            std::size_t end = at + 1;
            bool in_string = false;
            for (; end < line.size(); ++end) {
                const char c = line[end];
                if (in_string) {
                    if (c == '\\')
                        ++end;
                    else if (c == '"')
                        in_string = false;
                } else if (c == '"') {
                    in_string = true;
                } else if (c == '}') {
                    break;
                }
            }
            found.insert(line.substr(at, end + 1 - at));
            at = end + 1;
            if (at < line.size() && line[at] == ',') ++at;
        }
    }
    return found;
}

// A PROFIBUS session with protocol faults (findings) in which station 5 stops answering for a
// while (lost, then returned: health events).
Session faulty_session_with_a_lost_station() {
    SimulatorOptions options;
    options.seed = 9;
    options.cycles = 300;
    options.slaves = {{3, 1, Dialect::Vlt}, {4, 2, Dialect::Vlt}, {5, 5, Dialect::Vlt}};
    for (const char* fault : {"stacked_request@40:3", "request_rejected@60:4",
                              "orphan_response@100:3", "unknown_code@120:4"})
        options.faults.push_back(*parse_fault_spec(fault));
    return test::without_answers(test::simulate(options), 5, {{400, 500}});
}

std::vector<std::string> sniff_args(const PseudoTerminal& pty, const std::string& pcap,
                                    const MosquittoBroker& broker,
                                    std::vector<std::string> more = {}) {
    std::vector<std::string> args = {
        "sniff",  "-i",         pty.slave,        "--baud", "1500000",
        "-T",     "jsonl",      "--stats",        "-w",     pcap,
        "--mqtt", broker.url(), "--mqtt-segment", "line3",  "--mqtt-stats-interval",
        "0.2"};
    args.insert(args.end(), more.begin(), more.end());
    return test::without_idle_gap(args);
}

bool has_status(const std::vector<ReceivedMessage>& messages, std::string_view state) {
    return std::any_of(messages.begin(), messages.end(), [&](const ReceivedMessage& m) {
        return m.topic == "dpscope/line3/status" && m.payload.find(state) != std::string::npos;
    });
}

// Everything the capture found reaches the subscriber: each finding as jsonl printed it, each
// health event the --stats lines told, the live list, the verdicts, the figures, and the
// status from online to a clean offline.
TEST(SniffMqttTest, EveryFindingAndHealthEventReachesTheSubscriber) {
    MosquittoBroker broker;
    MqttSubscriber subscriber(broker.port(), "dpscope/#");
    ASSERT_TRUE(subscriber.subscribed());
    PseudoTerminal pty;
    const std::string pcap = test::temp_path("mqtt.pcap");
    Child sniffer(test::dpscope_argv(sniff_args(pty, pcap, broker)));
    ASSERT_TRUE(sniffer.err_says("capturing on")) << sniffer.err();
    ASSERT_TRUE(subscriber.wait_for([](const auto& m) { return has_status(m, "\"online\""); }));
    const Session session = faulty_session_with_a_lost_station();
    test::play(pty, session, true);
    ASSERT_TRUE(test::wait_for_records(pcap, session.expected.size())) << sniffer.err();
    sniffer.signal(SIGINT);
    ASSERT_EQ(sniffer.wait(), 0) << sniffer.err();
    ASSERT_TRUE(subscriber.wait_for([](const auto& m) { return has_status(m, "\"stopped\""); }))
        << sniffer.err();

    // Findings: the same objects, as many as jsonl printed.
    const std::multiset<std::string> printed = jsonl_findings(sniffer.out());
    ASSERT_GE(printed.size(), 4u) << sniffer.out().substr(0, 2000);
    std::multiset<std::string> published;
    for (const ReceivedMessage& m : subscriber.messages())
        if (m.topic == "dpscope/line3/finding") published.insert(m.payload);
    EXPECT_EQ(published, printed);

    // Health events: one per --stats line (on standard error beside jsonl).
    std::vector<std::string> health = subscriber.distinct_payloads("dpscope/line3/health");
    std::size_t lines = 0;
    for (const std::string& line : test::lines_of(sniffer.err()))
        if (line.find(" health: ") != std::string::npos) ++lines;
    EXPECT_EQ(health.size(), lines) << sniffer.err();
    std::set<std::string> kinds;
    for (const std::string& payload : health) {
        auto event = test::parse_json(payload);
        ASSERT_TRUE(event) << payload;
        kinds.insert((*event)["event"].string() + " " +
                     ((*event)["station"].type == test::Json::Type::String
                          ? (*event)["station"].string()
                          : std::to_string((*event)["station"].integer())));
    }
    EXPECT_TRUE(kinds.count("station_lost 5")) << sniffer.err();
    EXPECT_TRUE(kinds.count("station_returned 5")) << sniffer.err();

    // The live list: the last one lists the master and the three slaves.
    std::vector<std::string> live = subscriber.distinct_payloads("dpscope/line3/live");
    ASSERT_FALSE(live.empty());
    auto last_live = test::parse_json(live.back());
    ASSERT_TRUE(last_live);
    std::set<long long> addresses;
    for (const test::Json& station : (*last_live)["stations"].items)
        addresses.insert(station["address"].integer());
    EXPECT_TRUE(addresses.count(3) && addresses.count(4) && addresses.count(5)) << live.back();
    // Verdicts: each station's and the segment's, retained.
    for (const char* topic :
         {"dpscope/line3/verdict/3", "dpscope/line3/verdict/5", "dpscope/line3/verdict/segment"})
        EXPECT_FALSE(subscriber.distinct_payloads(topic).empty()) << topic;
    // The figures: the last counts every telegram.
    std::vector<std::string> stats = subscriber.distinct_payloads("dpscope/line3/stats");
    ASSERT_FALSE(stats.empty());
    auto last_stats = test::parse_json(stats.back());
    ASSERT_TRUE(last_stats);
    EXPECT_EQ((*last_stats)["telegrams"].integer(),
              static_cast<long long>(session.expected.size()));
    EXPECT_EQ((*last_stats)["findings"].integer(), static_cast<long long>(printed.size()));
    EXPECT_EQ((*last_stats)["mqtt_dropped"].integer(), 0);
    // The status: online first, a clean offline last with the telegrams.
    std::vector<std::string> status = subscriber.distinct_payloads("dpscope/line3/status");
    ASSERT_GE(status.size(), 2u);
    EXPECT_NE(status.front().find("\"state\":\"online\""), std::string::npos) << status.front();
    EXPECT_NE(status.back().find("\"state\":\"offline\",\"reason\":\"stopped\""), std::string::npos)
        << status.back();
    EXPECT_NE(status.back().find(fmt::format("\"telegrams\":{}", session.expected.size())),
              std::string::npos)
        << status.back();
    EXPECT_NE(sniffer.err().find("dpscope: mqtt: "), std::string::npos) << sniffer.err();
    EXPECT_NE(sniffer.err().find(" messages delivered to dpscope/line3"), std::string::npos)
        << sniffer.err();
    std::remove(pcap.c_str());
}

// The broker killed in the middle of the capture and started again: the capture goes on, the
// events of the outage wait and arrive, nothing is lost.
TEST(SniffMqttTest, ABrokerKilledMidCaptureAndRestartedLosesNoEvent) {
    MosquittoBroker broker;
    MqttSubscriber subscriber(broker.port(), "dpscope/#");
    ASSERT_TRUE(subscriber.subscribed());
    PseudoTerminal pty;
    const std::string pcap = test::temp_path("mqtt-restart.pcap");
    Child sniffer(test::dpscope_argv(sniff_args(pty, pcap, broker)));
    ASSERT_TRUE(sniffer.err_says("capturing on")) << sniffer.err();
    ASSERT_TRUE(subscriber.wait_for([](const auto& m) { return has_status(m, "\"online\""); }));
    const Session session = faulty_session_with_a_lost_station();
    const std::size_t half = session.played.size() / 2;
    test::play(pty, session, true, half);
    ASSERT_TRUE(test::wait_for_records(pcap, half)) << sniffer.err();
    // Before the subscriber goes: it has every event of the first half. A broker killed after
    // acknowledging a message but before saving it loses it for a subscriber that is away (the
    // publisher rightly sends it no more), so the test waits until a stats message counts the
    // half's telegrams with nothing waiting in the queue: every event before it was acknowledged,
    // and the broker delivers in order, so the subscriber had them all when it gets that one.
    ASSERT_TRUE(subscriber.wait_for([half](const std::vector<ReceivedMessage>& messages) {
        return std::any_of(messages.begin(), messages.end(), [half](const ReceivedMessage& m) {
            if (m.topic != "dpscope/line3/stats") return false;
            const std::optional<test::Json> stats = test::parse_json(m.payload);
            const test::Json* telegrams = stats ? stats->find("telegrams") : nullptr;
            const test::Json* waiting = stats ? stats->find("mqtt_waiting") : nullptr;
            return telegrams && waiting && waiting->text == "0" &&
                   std::strtoull(telegrams->text.c_str(), nullptr, 10) >= half;
        });
    })) << sniffer.err();
    subscriber.pause();
    ASSERT_TRUE(broker.log_says("Client dpscope-test-subscriber disconnected")) << broker.log();
    broker.kill();
    ASSERT_TRUE(sniffer.err_says("mqtt: lost the connection to mqtt://127.0.0.1:"))
        << sniffer.err();
    // The rest of the session while the broker is down.
    test::play(pty, test::tail_of(session, half), true);
    ASSERT_TRUE(test::wait_for_records(pcap, session.expected.size())) << sniffer.err();
    broker.restart();
    ASSERT_TRUE(sniffer.err_says("mqtt: connected to mqtt://127.0.0.1:")) << sniffer.err();
    subscriber.resume();
    sniffer.signal(SIGINT);
    ASSERT_EQ(sniffer.wait(), 0) << sniffer.err();
    ASSERT_TRUE(subscriber.wait_for([](const auto& m) { return has_status(m, "\"stopped\""); }))
        << sniffer.err() << broker.log();
    const std::multiset<std::string> printed = jsonl_findings(sniffer.out());
    std::set<std::string> distinct_printed(printed.begin(), printed.end());
    std::vector<std::string> published = subscriber.distinct_payloads("dpscope/line3/finding");
    EXPECT_EQ(std::set<std::string>(published.begin(), published.end()), distinct_printed);
    const std::vector<std::string> err_lines = test::lines_of(sniffer.err());
    EXPECT_EQ(subscriber.distinct_payloads("dpscope/line3/health").size(),
              static_cast<std::size_t>(std::count_if(
                  err_lines.begin(), err_lines.end(),
                  [](const std::string& l) { return l.find(" health: ") != std::string::npos; })))
        << sniffer.err();
    // The capture itself lost nothing.
    EXPECT_EQ(test::read_capture(pcap).telegrams, session.expected);
    std::remove(pcap.c_str());
}

// A sniffer that dies (SIGKILL) leaves its will: the status turns offline, "connection lost".
TEST(SniffMqttTest, ASnifferThatDiesIsSeenOfflineByItsWill) {
    MosquittoBroker broker;
    MqttSubscriber subscriber(broker.port(), "dpscope/#");
    ASSERT_TRUE(subscriber.subscribed());
    PseudoTerminal pty;
    Child sniffer(test::dpscope_argv(test::without_idle_gap(
        {"sniff", "-i", pty.slave, "--baud", "1500000", "-q", "--mqtt", broker.url()})));
    ASSERT_TRUE(sniffer.err_says("capturing on")) << sniffer.err();
    // The segment is named after the device by default.
    const std::string segment = pty.slave.substr(pty.slave.rfind('/') + 1);
    const std::string status = "dpscope/" + segment + "/status";
    ASSERT_TRUE(subscriber.wait_for([&](const auto& m) {
        return std::any_of(m.begin(), m.end(), [&](const ReceivedMessage& r) {
            return r.topic == status && r.payload.find("\"online\"") != std::string::npos;
        });
    }));
    sniffer.signal(SIGKILL);
    sniffer.wait();
    ASSERT_TRUE(subscriber.wait_for([&](const auto& m) {
        return std::any_of(m.begin(), m.end(), [&](const ReceivedMessage& r) {
            return r.topic == status &&
                   r.payload.find("\"state\":\"offline\",\"reason\":\"connection lost\"") !=
                       std::string::npos;
        });
    })) << broker.log();
}

// User name and password from a file or the environment, never the command line; a broker that
// refuses them is warned about and the capture goes on.
TEST(SniffMqttTest, CredentialsComeFromAFileOrTheEnvironment) {
    const std::string folder = test::temp_path("mqtt-credentials");
    std::filesystem::create_directories(folder);
    const std::string passwords = folder + "/passwords";
    ASSERT_EQ(
        std::system(("mosquitto_passwd -b -c " + passwords + " sniffer 's3cret pass'").c_str()), 0);
    MosquittoBroker broker({"allow_anonymous false", "password_file " + passwords});
    const std::string credentials = folder + "/credentials";
    {
        std::ofstream file(credentials);
        file << "# the plant's broker\nusername = sniffer\npassword = s3cret pass\n";
    }
    ::chmod(credentials.c_str(), 0600);
    const auto capture = [&](std::vector<std::string> more, test::ChildOptions options = {}) {
        PseudoTerminal pty;
        std::vector<std::string> args = {"sniff", "-i", pty.slave, "--baud", "1500000",
                                         "-q",    "-c", "20",      "--mqtt", broker.url()};
        args.insert(args.end(), more.begin(), more.end());
        options.stdin_from_null = false;
        Child sniffer(test::dpscope_argv(test::without_idle_gap(args)), options);
        EXPECT_TRUE(sniffer.err_says("capturing on")) << sniffer.err();
        test::play(pty, test::simulate(10), true);
        EXPECT_EQ(sniffer.wait(), 0) << sniffer.err();
        return sniffer.err();
    };
    std::string err = capture({"--mqtt-credentials", credentials, "--mqtt-wait", "60"});
    EXPECT_EQ(err.find("not delivered"), std::string::npos) << err;
    EXPECT_EQ(err.find("refused"), std::string::npos) << err;
    err =
        capture({"--mqtt-wait", "60"},
                {{{"DPSCOPE_MQTT_USERNAME", "sniffer"}, {"DPSCOPE_MQTT_PASSWORD", "s3cret pass"}}});
    EXPECT_EQ(err.find("not delivered"), std::string::npos) << err;
    // Refused: said once, the capture runs to its end, what waited is counted.
    err = capture({"--mqtt-wait", "0.5"},
                  {{{"DPSCOPE_MQTT_USERNAME", "sniffer"}, {"DPSCOPE_MQTT_PASSWORD", "wrong"}}});
    EXPECT_NE(
        err.find("the broker refused the connection: Connection Refused: not authorised; retrying"),
        std::string::npos)
        << err;
    EXPECT_NE(err.find("not delivered (the broker did not take them within --mqtt-wait)"),
              std::string::npos)
        << err;
    // A credentials file others may read is warned about.
    ::chmod(credentials.c_str(), 0644);
    err = capture({"--mqtt-credentials", credentials});
    EXPECT_NE(err.find("others may read it (mode 644); chmod 600 it"), std::string::npos) << err;
    std::filesystem::remove_all(folder);
}

TEST(SniffMqttTest, OptionsThatCannotWorkAreUsageErrors) {
    const std::string folder = test::temp_path("mqtt-usage");
    std::filesystem::create_directories(folder);
    const std::string bad = folder + "/bad-credentials";
    {
        std::ofstream file(bad);
        file << "username=a\nsecret=b\n";
    }
    const std::string no_user = folder + "/no-user";
    {
        std::ofstream file(no_user);
        file << "password=b\n";
    }
    const std::vector<std::string> base = {"sniff", "-i", "/dev/dpscope-no-such-tty", "--baud",
                                           "9600"};
    for (const auto& [more, says] : std::vector<std::pair<std::vector<std::string>, std::string>>{
             {{"--mqtt-topic", "plant"}, "--mqtt-topic is about the MQTT broker of --mqtt URL"},
             {{"--mqtt-credentials", bad}, "is about the MQTT broker of --mqtt URL"},
             {{"--mqtt", "tcp://broker"}, "not an MQTT broker address"},
             {{"--mqtt", "mqtt://user:pw@broker"}, "would show in the process list"},
             {{"--mqtt", "mqtt://broker", "--mqtt-topic", "a/#"}, "wildcard"},
             {{"--mqtt", "mqtt://broker", "--mqtt-segment", "a/b"}, "one topic level"},
             {{"--mqtt", "mqtt://broker", "--mqtt-credentials", folder + "/none"}, "cannot read"},
             {{"--mqtt", "mqtt://broker", "--mqtt-credentials", "/dev/zero"}, "not a regular file"},
             {{"--mqtt", "mqtt://broker", "--mqtt-credentials", bad},
              bad + ":2: expected username=NAME or password=SECRET"},
             {{"--mqtt", "mqtt://broker", "--mqtt-credentials", no_user}, "no username= line"},
             {{"--mqtt", "mqtt://broker", "--mqtt-ca", bad},
              "are for TLS: give the broker as mqtts://"},
             {{"--mqtt", "mqtts://broker", "--mqtt-cert", bad}, "go together"},
             {{"--mqtt", "mqtts://broker", "--mqtt-ca", folder + "/none"},
              "--mqtt-ca " + folder + "/none: cannot read it"},
             {{"--mqtt", "mqtt://broker", "--mqtt-queue", "0"}, "--mqtt-queue"},
             {{"--mqtt", "mqtt://broker", "--mqtt-queue", "1000001"}, "--mqtt-queue"},
             {{"--mqtt", "mqtt://broker", "--mqtt-stats-interval", "0.01"},
              "--mqtt-stats-interval"},
             {{"--mqtt", "mqtt://broker", "--mqtt-wait", "-1"}, "--mqtt-wait"}}) {
        std::vector<std::string> args = base;
        args.insert(args.end(), more.begin(), more.end());
        auto run = test::run_dpscope(args);
        EXPECT_EQ(run.exit_code, 2) << more.front() << " " << more.back() << "\n" << run.err;
        EXPECT_NE(run.err.find(says), std::string::npos) << run.err;
    }
    // The password in the environment without the user name.
    auto run = test::run_dpscope(
        {"sniff", "-i", "/dev/dpscope-no-such-tty", "--baud", "9600", "--mqtt", "mqtt://broker"});
    EXPECT_EQ(run.exit_code, 2);  // the device, after the MQTT options passed
    EXPECT_EQ(run.err.find("mqtt"), std::string::npos) << run.err;
    std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace dpscope

namespace dpscope {
namespace {

// mqtts: a broker with a certificate from a CA of the test's own, asking for a client
// certificate; sniff checks the broker's with --mqtt-ca and shows its own.
TEST(SniffMqttTest, TlsWithTheBrokersCaAndAClientCertificate) {
    const std::string folder = test::temp_path("mqtt-tls");
    std::filesystem::create_directories(folder);
    const std::string make_certificates =
        "cd " + folder +
        " && openssl req -x509 -newkey rsa:2048 -nodes -keyout ca.key -out ca.pem -days 2 "
        "-subj /CN=dpscope-test-ca 2>/dev/null"
        " && openssl req -newkey rsa:2048 -nodes -keyout server.key -out server.csr "
        "-subj /CN=127.0.0.1 2>/dev/null"
        " && echo subjectAltName=IP:127.0.0.1 > server.ext"
        " && openssl x509 -req -in server.csr -CA ca.pem -CAkey ca.key -CAcreateserial "
        "-out server.pem -days 2 -extfile server.ext 2>/dev/null"
        " && openssl req -newkey rsa:2048 -nodes -keyout client.key -out client.csr "
        "-subj /CN=sniffer 2>/dev/null"
        " && openssl x509 -req -in client.csr -CA ca.pem -CAkey ca.key -CAcreateserial "
        "-out client.pem -days 2 2>/dev/null";
    ASSERT_EQ(std::system(("bash -c '" + make_certificates + "'").c_str()), 0);
    const int tls_port = test::free_loopback_port();
    MosquittoBroker broker({"listener " + std::to_string(tls_port) + " 127.0.0.1",
                            "cafile " + folder + "/ca.pem", "certfile " + folder + "/server.pem",
                            "keyfile " + folder + "/server.key", "require_certificate true"});
    MqttSubscriber subscriber(broker.port(), "dpscope/#");
    ASSERT_TRUE(subscriber.subscribed());
    const std::string url = "mqtts://127.0.0.1:" + std::to_string(tls_port);
    const auto capture = [&](std::vector<std::string> more) {
        PseudoTerminal pty;
        std::vector<std::string> args = {"sniff",
                                         "-i",
                                         pty.slave,
                                         "--baud",
                                         "1500000",
                                         "-q",
                                         "-c",
                                         "20",
                                         "--mqtt",
                                         url,
                                         "--mqtt-segment",
                                         "tls",
                                         "--mqtt-ca",
                                         folder + "/ca.pem"};
        args.insert(args.end(), more.begin(), more.end());
        Child sniffer(test::dpscope_argv(test::without_idle_gap(args)));
        EXPECT_TRUE(sniffer.err_says("capturing on")) << sniffer.err();
        test::play(pty, test::simulate(10), true);
        EXPECT_EQ(sniffer.wait(), 0) << sniffer.err();
        return sniffer.err();
    };
    std::string err = capture({"--mqtt-cert", folder + "/client.pem", "--mqtt-key",
                               folder + "/client.key", "--mqtt-wait", "60"});
    EXPECT_EQ(err.find("not delivered"), std::string::npos) << err << broker.log();
    ASSERT_TRUE(subscriber.wait_for([](const auto& m) {
        return std::any_of(m.begin(), m.end(), [](const ReceivedMessage& r) {
            return r.topic == "dpscope/tls/status" &&
                   r.payload.find("\"stopped\"") != std::string::npos;
        });
    }));
    // Without the client certificate the broker refuses the handshake: warned, not delivered,
    // the capture unharmed.
    err = capture({"--mqtt-wait", "0.5"});
    EXPECT_NE(err.find("mqtt: cannot connect to " + url), std::string::npos) << err;
    EXPECT_NE(err.find("not delivered"), std::string::npos) << err;
    EXPECT_NE(err.find("20 telegrams"), std::string::npos) << err;
    std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace dpscope
