#include "cli/live_mqtt.hpp"

#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <optional>

#include "cli/common_options.hpp"
#include "cli/small_file.hpp"
#include "formats/json_writer.hpp"
#include "protocols/profibus/health/health_event_describe.hpp"

namespace dpscope::cli {

namespace {

// The device's name as a topic level: "/dev/ttyUSB0" -> "ttyUSB0" ('+', '#' made '_').
std::string default_segment(const std::string& device) {
    std::string name =
        device.substr(device.rfind('/') == std::string::npos ? 0 : device.rfind('/') + 1);
    for (char& c : name)
        if (c == '+' || c == '#') c = '_';
    return name.empty() ? std::string("bus") : name;
}

std::string host_name() {
    char name[256] = {};
    if (::gethostname(name, sizeof name - 1) != 0 || name[0] == '\0') return "host";
    return name;
}

}  // namespace

void add_mqtt_options(CLI::App& sub, MqttOptions& o) {
    sub.add_option("--mqtt", o.url,
                   "Publish findings, health events, the live list, verdicts, figures and the "
                   "sniffer's own status to the MQTT broker at URL (mqtt://HOST[:PORT], default "
                   "port 1883; mqtts://HOST[:PORT] for TLS, default 8883); topics under "
                   "--mqtt-topic/--mqtt-segment (docs/mqtt.md). A broker that is down never "
                   "stops the capture: messages wait in a queue and go out on reconnection")
        ->type_name("URL");
    sub.add_option("--mqtt-topic", o.topic, "Topic prefix (levels separated by /, no + or #)")
        ->default_str("dpscope")
        ->type_name("PREFIX");
    sub.add_option("--mqtt-segment", o.segment,
                   "The segment's name, the topic level under the prefix (default: the device's "
                   "name, e.g. ttyUSB0)")
        ->type_name("NAME");
    sub.add_option("--mqtt-client-id", o.client_id,
                   "MQTT client identifier (default dpscope-HOST-SEGMENT)")
        ->type_name("ID");
    sub.add_option("--mqtt-credentials", o.credentials,
                   "Read the broker's user name and password from FILE (lines username=NAME and "
                   "password=SECRET); without it, from DPSCOPE_MQTT_USERNAME and "
                   "DPSCOPE_MQTT_PASSWORD in the environment. Never on the command line")
        ->type_name("FILE");
    sub.add_option("--mqtt-ca", o.ca_file,
                   "mqtts: the CA certificates (PEM) that sign the broker's certificate (default: "
                   "the system's, /etc/ssl/certs)")
        ->type_name("FILE");
    sub.add_option("--mqtt-cert", o.cert_file,
                   "mqtts: a client certificate (PEM) for a broker that asks for one; with "
                   "--mqtt-key")
        ->type_name("FILE");
    sub.add_option("--mqtt-key", o.key_file, "mqtts: the client certificate's key (PEM)")
        ->type_name("FILE");
    sub.add_option("--mqtt-queue", o.queue,
                   "Messages that may wait for the broker (1 to 1000000); more events are "
                   "dropped and counted (states replace their older value and are never "
                   "dropped for events)")
        ->check(whole_number(1, 1'000'000))
        ->default_str("10000")
        ->type_name("N");
    sub.add_option("--mqtt-stats-interval", o.stats_interval,
                   "Publish the figures (telegrams, rate, bytes skipped, parity errors, bytes "
                   "on disk, findings, last event) every SECONDS (0.1 to 86400)")
        ->check(finite_number(0.1, 86400, " seconds"))
        ->default_str("10")
        ->type_name("SECONDS");
    sub.add_option("--mqtt-wait", o.wait_at_end,
                   "At the end, wait up to SECONDS (0 to 3600) for the broker to take what "
                   "waits in the queue")
        ->check(finite_number(0, 3600, " seconds"))
        ->default_str("5")
        ->type_name("SECONDS");
}

std::string mqtt_option_without_url(const MqttOptions& o) {
    if (!o.url.empty()) return {};
    const MqttOptions defaults;
    if (o.topic != defaults.topic) return "--mqtt-topic";
    if (o.segment != defaults.segment) return "--mqtt-segment";
    if (o.client_id != defaults.client_id) return "--mqtt-client-id";
    if (o.credentials != defaults.credentials) return "--mqtt-credentials";
    if (o.ca_file != defaults.ca_file) return "--mqtt-ca";
    if (o.cert_file != defaults.cert_file) return "--mqtt-cert";
    if (o.key_file != defaults.key_file) return "--mqtt-key";
    if (o.queue != defaults.queue) return "--mqtt-queue";
    if (o.stats_interval != defaults.stats_interval) return "--mqtt-stats-interval";
    if (o.wait_at_end != defaults.wait_at_end) return "--mqtt-wait";
    return {};
}

Result<MqttCredentials> read_mqtt_credentials(const std::string& file) {
    MqttCredentials credentials;
    if (file.empty()) {
        if (const char* user = std::getenv("DPSCOPE_MQTT_USERNAME")) credentials.username = user;
        if (const char* password = std::getenv("DPSCOPE_MQTT_PASSWORD"))
            credentials.password = password;
        if (credentials.username.empty() && !credentials.password.empty())
            return Error{"DPSCOPE_MQTT_PASSWORD is set without DPSCOPE_MQTT_USERNAME"};
        return credentials;
    }
    Result<std::string> text = read_small_file(file, 64 * 1024, "--mqtt-credentials",
                                               "a file of username= and password= lines");
    if (!text) return Error{text.error()};
    unsigned number = 0;
    for (const std::string_view line : settings_lines(*text)) {
        ++number;
        if (line.empty() || line.front() == '#') continue;
        const std::size_t equals = line.find('=');
        const std::string_view key =
            equals == std::string::npos ? line : trimmed(line.substr(0, equals));
        if (equals == std::string::npos || (key != "username" && key != "password"))
            return Error{
                fmt::format("--mqtt-credentials {}:{}: expected username=NAME or password=SECRET",
                            file, number)};
        // Blanks around the value are trimmed: an editor leaves them unseen.
        (key == "username" ? credentials.username : credentials.password) =
            std::string(trimmed(line.substr(equals + 1)));
    }
    if (credentials.username.empty())
        return Error{fmt::format("--mqtt-credentials {}: no username= line", file)};
    struct stat info {};
    if (::stat(file.c_str(), &info) == 0 && (info.st_mode & 077) != 0)
        print_warning(
            fmt::format("--mqtt-credentials {}: others may read it (mode {:o}); chmod "
                        "600 it",
                        file, info.st_mode & 0777));
    return credentials;
}

Result<std::unique_ptr<LiveMqtt>> LiveMqtt::prepare(const MqttOptions& o,
                                                    MonitorIdentity identity) {
    Result<monitor::MqttEndpoint> endpoint = monitor::parse_mqtt_url(o.url);
    if (!endpoint) return Error{fmt::format("--mqtt {}", endpoint.error())};
    if (identity.segment.empty())
        identity.segment = o.segment.empty() ? default_segment(identity.device) : o.segment;
    Result<MqttTopics> topics = MqttTopics::make(o.topic, identity.segment);
    if (!topics) return Error{topics.error()};
    Result<MqttCredentials> credentials = read_mqtt_credentials(o.credentials);
    if (!credentials) return Error{credentials.error()};
    Result<void> files =
        monitor::check_tls_files(endpoint->tls, o.ca_file, o.cert_file, o.key_file);
    if (!files) return Error{files.error()};

    std::unique_ptr<LiveMqtt> live(new LiveMqtt());
    live->topics_ = *topics;
    live->identity_ = identity;
    live->stats_every_ns_ = std::llround(o.stats_interval * 1e9);
    live->wait_at_end_ms_ = static_cast<int>(std::llround(o.wait_at_end * 1000));
    monitor::MqttSettings& settings = live->settings_;
    settings.endpoint = *endpoint;
    settings.client_id = o.client_id.empty()
                             ? fmt::format("dpscope-{}-{}", host_name(), identity.segment)
                             : o.client_id;
    settings.username = credentials->username;
    settings.password = credentials->password;
    settings.ca_file = o.ca_file;
    settings.cert_file = o.cert_file;
    settings.key_file = o.key_file;
    settings.queue_limit = static_cast<std::size_t>(o.queue);
    return live;
}

Result<void> LiveMqtt::connect(std::uint32_t baud, std::int64_t since_ns) {
    identity_.baud = baud;
    identity_.since_ns = since_ns;
    settings_.birth = {topics_.status(), status_payload(identity_, "online"), 1, true};
    settings_.will = {topics_.status(), status_payload(identity_, "offline", "connection lost"), 1,
                      true};
    std::shared_ptr<Warnings> warnings = warnings_;
    Result<std::unique_ptr<monitor::MqttPublisher>> publisher =
        monitor::MqttPublisher::start(settings_, [warnings](std::string_view message) {
            std::lock_guard lock(warnings->mutex);
            warnings->lines.emplace_back(message);
        });
    if (!publisher) return Error{publisher.error()};
    publisher_ = std::move(publisher).value();
    last_stats_ns_ = 0;
    return {};
}

void LiveMqtt::say_warnings() {
    std::vector<std::string> lines;
    {
        std::lock_guard lock(warnings_->mutex);
        if (warnings_->lines.empty()) return;
        lines.swap(warnings_->lines);
    }
    for (const std::string& line : lines)
        print_warning(line);
}

void LiveMqtt::on_findings(std::span<const Finding> findings) {
    for (const Finding& f : findings)
        publisher_->publish({topics_.finding(), finding_payload(f), 1, false});
}

void LiveMqtt::on_health_event(const AlarmEvent& event) {
    publisher_->publish({topics_.health(),
                         json::text_of([&](JsonWriter& w) { health_event_json(w, event); }), 1, false});
}

void LiveMqtt::on_judged(const BusHealth& health) {
    std::string live = json::text_of([&](JsonWriter& w) { live_list_json(w, health); });
    if (live != live_published_) {
        publisher_->publish({topics_.live(), live, 1, true});
        live_published_ = std::move(live);
    }
    for (const StationHealth& station : health.stations)
        publish_verdict_on_change(health, station.address);
    if (health.segment.judged()) publish_verdict_on_change(health, kSegmentAddress);
}

void LiveMqtt::publish_verdict_on_change(const BusHealth& health, std::uint8_t address) {
    const Verdict verdict = verdict_of(health, address);
    std::optional<Verdict>& sent = verdicts_published_[address];
    if (sent == verdict) return;
    sent = verdict;
    publisher_->publish({topics_.verdict(address),
                         json::text_of([&](JsonWriter& w) { verdict_json(w, health, address); }), 1,
                         true});
}

void LiveMqtt::publish_stats(MonitorFigures figures) {
    const monitor::MqttCounters c = publisher_->counters();
    figures.mqtt_dropped = c.dropped;
    figures.mqtt_waiting = c.waiting;
    publisher_->publish({topics_.stats(), stats_payload(figures), 1, true});
}

std::string LiveMqtt::finish(const MonitorFigures& figures) {
    publish_stats(figures);
    const std::uint64_t telegrams = figures.telegrams;
    const std::uint64_t left = publisher_->finish(
        {topics_.status(), status_payload(identity_, "offline", "stopped", &telegrams), 1, true},
        wait_at_end_ms_);
    say_warnings();
    const monitor::MqttCounters c = publisher_->counters();
    std::string line =
        fmt::format("mqtt: {} messages delivered to {}", c.acknowledged, topics_.base());
    if (c.dropped > 0)
        line += fmt::format(", {} dropped (the queue of --mqtt-queue was full)", c.dropped);
    if (c.resent > 0) line += fmt::format(", {} sent again after a lost connection", c.resent);
    if (left > 0)
        line += fmt::format(
            ", {} not delivered (the broker did not take them within "
            "--mqtt-wait)",
            left);
    return line;
}

}  // namespace dpscope::cli
