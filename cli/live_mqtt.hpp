// `sniff --mqtt URL`: the capture's findings, health events, live list, verdicts, figures and
// its own status, published to the plant's MQTT broker (docs/mqtt.md). The topics and payloads
// are formats/monitor_messages.hpp and protocols/profibus/health/health_event_describe.hpp; the
// network is monitor/mqtt_publisher.hpp. This ties them to the capture loop.
#pragma once

#include <CLI/CLI.hpp>
#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "cli/live_health.hpp"
#include "core/finding.hpp"
#include "core/result.hpp"
#include "formats/monitor_messages.hpp"
#include "monitor/mqtt_publisher.hpp"

namespace dpscope::cli {

struct MqttOptions {
    std::string url;  // --mqtt
    std::string topic = "dpscope";
    std::string segment;      // empty: the device's name (ttyUSB0)
    std::string client_id;    // empty: dpscope-HOST-SEGMENT
    std::string credentials;  // a file with username= and password= lines
    std::string ca_file;
    std::string cert_file;
    std::string key_file;
    std::uint64_t queue = 10000;
    double stats_interval = 10;
    double wait_at_end = 5;  // seconds the end waits for the queue to be delivered
};

// The --mqtt options of sniff.
void add_mqtt_options(CLI::App& sub, MqttOptions& options);

// Whether an --mqtt-* option is given without --mqtt (a usage error): its name, or "".
std::string mqtt_option_without_url(const MqttOptions& options);

// The user name and password: from the file (lines username=NAME and password=SECRET; blank
// lines and # comments allowed), else from DPSCOPE_MQTT_USERNAME and DPSCOPE_MQTT_PASSWORD.
struct MqttCredentials {
    std::string username;
    std::string password;
};
Result<MqttCredentials> read_mqtt_credentials(const std::string& file);

class LiveMqtt : public HealthListener {
  public:
    // Resolves the options (address, topics, credentials, TLS files): a usage error, before
    // anything is opened.
    static Result<std::unique_ptr<LiveMqtt>> prepare(const MqttOptions& options,
                                                     MonitorIdentity identity);
    // Starts the publisher once the capture starts (`baud`: the port's); a broker that is down
    // is no error (it is warned about, and the events wait).
    Result<void> connect(std::uint32_t baud, std::int64_t since_ns);

    void on_findings(std::span<const Finding> findings);
    void on_health_event(const AlarmEvent& event) override;
    void on_judged(const BusHealth& health) override;
    // Called often by the capture loop: prints the publisher's warnings (here, on the capture's
    // thread) and, every --mqtt-stats-interval, publishes `figures()`.
    template <class Figures>
    void tick(std::int64_t now_ns, Figures&& figures) {
        say_warnings();
        if (now_ns - last_stats_ns_ >= stats_every_ns_) {
            last_stats_ns_ = now_ns;
            publish_stats(figures());
        }
    }
    void publish_stats(MonitorFigures figures);
    // The end: the last figures, the goodbye status, up to --mqtt-wait seconds for the broker to
    // take what waits. Returns the line the end prints ("mqtt: 120 messages delivered ...").
    std::string finish(const MonitorFigures& figures);
    monitor::MqttCounters counters() const { return publisher_->counters(); }

  private:
    LiveMqtt() = default;
    void say_warnings();
    // Publishes the verdict of `address` (kSegmentAddress: the segment's), retained, when it is
    // not the one last sent.
    void publish_verdict_on_change(const BusHealth& health, std::uint8_t address);

    monitor::MqttSettings settings_;
    std::unique_ptr<monitor::MqttPublisher> publisher_;
    MqttTopics topics_;
    MonitorIdentity identity_;
    std::int64_t stats_every_ns_ = 0;
    std::int64_t last_stats_ns_ = 0;
    int wait_at_end_ms_ = 0;
    std::string live_published_;                                        // the last live list sent
    // The last verdict sent for each station, and for the segment at kSegmentAddress.
    std::array<std::optional<Verdict>, 256> verdicts_published_{};
    // The publisher's warnings, from its thread, printed by the capture's.
    struct Warnings {
        std::mutex mutex;
        std::vector<std::string> lines;
    };
    std::shared_ptr<Warnings> warnings_ = std::make_shared<Warnings>();
};

}  // namespace dpscope::cli
