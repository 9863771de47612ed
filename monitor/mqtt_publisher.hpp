// Events to the plant's MQTT broker (issue 30): a publisher that never makes the capture wait.
//
// The capture thread hands messages to publish(), which only puts them into a bounded queue and
// wakes the publisher's own thread; that thread alone owns the libmosquitto client, connects,
// reconnects with a growing delay when the broker is down or goes away, sends the queue and
// collects the broker's acknowledgements (QoS 1). So a broker that is slow, down or restarting
// never stops the capture: messages wait in the queue, and what does not fit is dropped and
// counted (docs/decisions.md, "MQTT").
//
// Every connection is made with a fresh client: messages sent but not acknowledged when a
// connection is lost go back to the front of the queue and are sent again on the next one, so a
// subscriber may see a message twice (QoS 1, at least once) but never misses one that was queued.
// A birth message (retained) goes out first on every connection, and the broker holds the will
// (retained) to publish when the connection dies without a goodbye.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>

#include "core/result.hpp"

namespace dpscope::monitor {

// Where the broker is: mqtt://HOST[:PORT] (default 1883) or mqtts://HOST[:PORT] (TLS, default
// 8883); HOST may be an IPv6 address in brackets.
struct MqttEndpoint {
    std::string host;
    std::uint16_t port = 1883;
    bool tls = false;
};
Result<MqttEndpoint> parse_mqtt_url(std::string_view url);
// The libmosquitto dpscope runs with: "2.0.11" (dpscope --version).
std::string mqtt_library_version();

// The TLS files (empty: not given) can be read and go together: a message naming the option.
Result<void> check_tls_files(bool tls, const std::string& ca_file, const std::string& cert_file,
                             const std::string& key_file);

struct MqttMessage {
    std::string topic;
    std::string payload;
    int qos = 1;
    bool retain = false;
};

struct MqttSettings {
    MqttEndpoint endpoint;
    std::string client_id;
    std::string username;  // empty: none
    std::string password;
    // TLS (mqtts://): the CA certificates (a file; empty: the system's, /etc/ssl/certs), and a
    // client certificate with its key when the broker asks for one.
    std::string ca_file;
    std::string cert_file;
    std::string key_file;
    int keepalive_s = 30;
    // Messages waiting, at most; more are dropped and counted. A retained message replaces one
    // of its topic still waiting (only the latest state matters), so states are never dropped
    // for events.
    std::size_t queue_limit = 10000;
    // Sent on every connection before anything else, and held by the broker for a death.
    MqttMessage birth;
    MqttMessage will;
    // The delay before a new connection attempt: from the first, doubled after each failure up
    // to the last.
    std::int64_t retry_first_ms = 250;
    std::int64_t retry_last_ms = 10'000;
};

struct MqttCounters {
    std::uint64_t queued = 0;        // taken by publish()
    std::uint64_t acknowledged = 0;  // QoS 1 acknowledged by the broker, QoS 0 sent
    std::uint64_t dropped = 0;       // did not fit into the queue
    std::uint64_t replaced = 0;      // retained states replaced by a newer one while waiting
    std::uint64_t resent = 0;        // sent again after a connection was lost
    std::uint64_t connections = 0;   // connections the broker accepted
    std::uint64_t waiting = 0;       // in the queue or sent and not yet acknowledged (counters())
    bool connected = false;
};

class MqttPublisher {
  public:
    using Warn = std::function<void(std::string_view)>;

    // Checks the settings (the TLS files can be read) and starts the publisher's thread, which
    // connects in the background: a broker that is down is no error here. `warn` is called
    // from that thread (it must be thread-safe): once when a connection attempt first fails,
    // and when a lost connection comes back.
    static Result<std::unique_ptr<MqttPublisher>> start(MqttSettings settings, Warn warn);
    ~MqttPublisher();  // stops at once (no goodbye: the broker publishes the will)
    MqttPublisher(const MqttPublisher&) = delete;
    MqttPublisher& operator=(const MqttPublisher&) = delete;

    // Queues a message; never blocks on the network.
    void publish(MqttMessage message);
    // The end: queues `goodbye` (retained: the status that replaces the birth), waits up to
    // `timeout_ms` for everything queued to be acknowledged, then disconnects cleanly (the
    // broker then discards the will) and stops the thread. Returns the messages left
    // undelivered.
    std::uint64_t finish(MqttMessage goodbye, int timeout_ms);

    MqttCounters counters() const;

    // Waits up to `timeout_ms` until everything queued so far is acknowledged (tests).
    bool wait_until_delivered(int timeout_ms) const;

  private:
    struct State;
    explicit MqttPublisher(std::unique_ptr<State> state);
    std::unique_ptr<State> state_;
};

}  // namespace dpscope::monitor
