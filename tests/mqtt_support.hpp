// A real MQTT broker and subscriber for the tests of sniff --mqtt (no mock): a mosquitto process
// on a loopback port of its own, and a libmosquitto client that records every message it gets.
#pragma once

#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "tests/pty_support.hpp"

struct mosquitto;
struct mosquitto_message;

namespace dpscope::test {

// A loopback port no one listens on now.
int free_loopback_port();

// mosquitto on 127.0.0.1, anonymous clients allowed, its database saved after every change
// (persistence with autosave_on_changes): a broker killed with SIGKILL comes back with the
// subscriptions and the messages queued for them. Started by the constructor; ready when it
// accepts connections.
class MosquittoBroker {
  public:
    // `extra`: more lines of mosquitto.conf (a password file, a TLS listener's files).
    explicit MosquittoBroker(std::vector<std::string> extra = {});
    ~MosquittoBroker();
    MosquittoBroker(const MosquittoBroker&) = delete;
    MosquittoBroker& operator=(const MosquittoBroker&) = delete;

    int port() const { return port_; }
    std::string url() const;  // mqtt://127.0.0.1:PORT
    // Kills it (SIGKILL: a crash, no goodbye to anyone) and waits until it is gone.
    void kill();
    // Starts it again on the same port with the same database; waits until it is ready.
    void restart();
    bool running() const { return child_ != nullptr; }
    std::string log() const;
    // Waits (at most the patience) until the log has `text` with the database saved after it
    // (a subscription acknowledged and on disk, so that a kill keeps it).
    bool saved_after(std::string_view text) const;
    // Waits (at most the patience) until the log has `text`.
    bool log_says(std::string_view text) const;

  private:
    void start();
    std::string folder_;
    std::string config_;
    std::vector<std::string> extra_;
    int port_ = 0;
    std::unique_ptr<Child> child_;
};

struct ReceivedMessage {
    std::string topic;
    std::string payload;
    bool retained = false;
};

// A subscriber with a session the broker keeps (clean session off, QoS 1): what is published
// while it is away is kept for it. Records every message, duplicates included.
class MqttSubscriber {
  public:
    MqttSubscriber(int port, std::string filter, std::string client_id = "dpscope-test-subscriber");
    ~MqttSubscriber();
    MqttSubscriber(const MqttSubscriber&) = delete;
    MqttSubscriber& operator=(const MqttSubscriber&) = delete;

    // Whether the subscription was acknowledged (within the patience).
    bool subscribed();
    // Disconnects cleanly (the broker keeps the session and queues what comes for it) and
    // connects again. A test kills the broker while the subscriber is away: mosquitto 2.0.11
    // keeps the messages of a session it restored for a client that left before, not for one
    // that was connected when the broker died.
    void pause();
    void resume();
    std::vector<ReceivedMessage> messages() const;
    // Waits (at most the patience) until `done(messages)` holds.
    bool wait_for(const std::function<bool(const std::vector<ReceivedMessage>&)>& done);
    // The messages on `topic`, duplicates removed (QoS 1 may deliver twice), in order.
    std::vector<std::string> distinct_payloads(const std::string& topic) const;

  private:
    static void on_connect(struct mosquitto*, void* self, int rc);
    static void on_subscribe(struct mosquitto*, void* self, int, int, const int*);
    static void on_message(struct mosquitto*, void* self, const struct mosquitto_message* m);
    std::string filter_;
    struct mosquitto* client_ = nullptr;
    mutable std::mutex mutex_;
    mutable std::condition_variable changed_;
    std::vector<ReceivedMessage> messages_;
    int subscriptions_ = 0;
};

}  // namespace dpscope::test
