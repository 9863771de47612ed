#include "monitor/mqtt_publisher.hpp"

#include <fmt/format.h>
#include <mosquitto.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <map>
#include <mutex>
#include <thread>

namespace dpscope::monitor {

namespace {

// Messages handed to the client and not yet acknowledged, at most (libmosquitto's own limit of
// messages in flight is 20; the birth is one more).
constexpr std::size_t kMaxInFlight = 16;
// The longest the thread sleeps: the client's keep-alive is handled at least this often.
constexpr int kLongestSleepMs = 1000;

std::int64_t monotonic_ms() {
    return std::chrono::duration_cast<std::chrono::milliseconds>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

bool parse_port(std::string_view text, std::uint16_t& port) {
    if (text.empty() || text.size() > 5) return false;
    unsigned value = 0;
    for (char c : text) {
        if (c < '0' || c > '9') return false;
        value = value * 10 + static_cast<unsigned>(c - '0');
    }
    if (value == 0 || value > 65535) return false;
    port = static_cast<std::uint16_t>(value);
    return true;
}

// libmosquitto's text without its full stop, to go inside a sentence.
std::string without_full_stop(std::string text) {
    if (!text.empty() && text.back() == '.') text.pop_back();
    return text;
}

// libmosquitto's reason for `rc`, in lower case: "the connection was refused".
std::string reason(int rc) {
    std::string text =
        without_full_stop(rc == MOSQ_ERR_ERRNO ? std::strerror(errno) : mosquitto_strerror(rc));
    if (!text.empty()) text.front() = static_cast<char>(std::tolower(text.front()));
    return text;
}

void initialise_library() {
    static std::once_flag once;
    std::call_once(once, [] { mosquitto_lib_init(); });
}

}  // namespace

std::string mqtt_library_version() {
    int major = 0, minor = 0, revision = 0;
    mosquitto_lib_version(&major, &minor, &revision);
    return fmt::format("{}.{}.{}", major, minor, revision);
}

Result<MqttEndpoint> parse_mqtt_url(std::string_view url) {
    MqttEndpoint endpoint;
    std::string_view rest;
    if (url.starts_with("mqtt://")) {
        rest = url.substr(7);
    } else if (url.starts_with("mqtts://")) {
        rest = url.substr(8);
        endpoint.tls = true;
        endpoint.port = 8883;
    } else {
        return Error{fmt::format(
            "{}: not an MQTT broker address; give mqtt://HOST[:PORT] or mqtts://HOST[:PORT]", url)};
    }
    if (!rest.empty() && rest.back() == '/') rest.remove_suffix(1);
    if (rest.find('@') != std::string_view::npos)
        return Error{fmt::format(
            "{}: a user name or password in the address would show in the process list; give "
            "them with --mqtt-credentials FILE or DPSCOPE_MQTT_USERNAME and "
            "DPSCOPE_MQTT_PASSWORD",
            url)};
    std::string_view host = rest;
    std::string_view port;
    if (rest.starts_with('[')) {
        const std::size_t close = rest.find(']');
        if (close == std::string_view::npos)
            return Error{fmt::format("{}: the IPv6 address has no closing ']'", url)};
        host = rest.substr(1, close - 1);
        std::string_view after = rest.substr(close + 1);
        if (!after.empty()) {
            if (after.front() != ':')
                return Error{fmt::format("{}: expected :PORT after the IPv6 address", url)};
            port = after.substr(1);
            if (port.empty()) return Error{fmt::format("{}: the port after ':' is missing", url)};
        }
    } else if (const std::size_t colon = rest.rfind(':'); colon != std::string_view::npos) {
        host = rest.substr(0, colon);
        port = rest.substr(colon + 1);
        if (port.empty()) return Error{fmt::format("{}: the port after ':' is missing", url)};
    }
    if (host.empty()) return Error{fmt::format("{}: the host name is missing", url)};
    if (host.find_first_of("/?# ") != std::string_view::npos)
        return Error{fmt::format("{}: '{}' is not a host name", url, host)};
    if (!port.empty() && !parse_port(port, endpoint.port))
        return Error{fmt::format("{}: the port must be a whole number from 1 to 65535, not '{}'",
                                 url, port)};
    endpoint.host = std::string(host);
    return endpoint;
}

Result<void> check_tls_files(bool tls, const std::string& ca_file, const std::string& cert_file,
                             const std::string& key_file) {
    for (const auto& [option, path] :
         {std::pair<const char*, const std::string&>{"--mqtt-ca", ca_file},
          std::pair<const char*, const std::string&>{"--mqtt-cert", cert_file},
          std::pair<const char*, const std::string&>{"--mqtt-key", key_file}}) {
        if (!path.empty() && ::access(path.c_str(), R_OK) != 0)
            return Error{
                fmt::format("{} {}: cannot read it: {}", option, path, std::strerror(errno))};
    }
    if (cert_file.empty() != key_file.empty())
        return Error{"--mqtt-cert and --mqtt-key go together: give both or neither"};
    if (!tls && (!ca_file.empty() || !cert_file.empty()))
        return Error{
            "--mqtt-ca, --mqtt-cert and --mqtt-key are for TLS: give the broker as "
            "mqtts://HOST[:PORT]"};
    return {};
}

struct MqttPublisher::State {
    MqttSettings settings;
    Warn warn;

    // Shared with the capture thread, under `mutex`.
    mutable std::mutex mutex;
    mutable std::condition_variable changed;  // a message acknowledged, the connection changed
    std::deque<MqttMessage> queue;
    std::map<int, MqttMessage> in_flight;  // by libmosquitto's message id
    MqttCounters counters;
    bool stop = false;
    bool goodbye = false;  // stop with a DISCONNECT (no will)
    int wake_fd = -1;

    // The publisher's thread alone.
    mosquitto* client = nullptr;
    bool connected = false;
    int refused = 0;  // the broker's CONNACK refusal, seen in on_connect
    std::int64_t retry_ms = 0;
    std::int64_t next_attempt_ms = 0;
    std::uint64_t failed_attempts = 0;
    bool warned_failure = false;
    bool lost = false;  // a connection was lost (or never made): the next one is said
    std::thread thread;

    std::string address() const {
        return fmt::format("{}://{}:{}", settings.endpoint.tls ? "mqtts" : "mqtt",
                           settings.endpoint.host, settings.endpoint.port);
    }
    void wake() const {
        const std::uint64_t one = 1;
        [[maybe_unused]] ssize_t n = ::write(wake_fd, &one, sizeof one);
    }
    void run();
    void open_connection();
    void close_connection(std::string_view why);
    void send_queued();
    bool publish_now(const MqttMessage& m);
    static void on_connect(mosquitto*, void* user, int rc);
    static void on_publish(mosquitto*, void* user, int mid);
};

void MqttPublisher::State::on_connect(mosquitto*, void* user, int rc) {
    auto* s = static_cast<State*>(user);
    if (rc != 0) {
        s->refused = rc;
        return;
    }
    s->connected = true;
    s->retry_ms = s->settings.retry_first_ms;
    s->failed_attempts = 0;
    {
        std::lock_guard lock(s->mutex);
        ++s->counters.connections;
        s->counters.connected = true;
    }
    s->changed.notify_all();
    if (s->lost && s->warn)
        s->warn(fmt::format("mqtt: connected to {}; sending what waited", s->address()));
    s->lost = false;
    s->warned_failure = false;
    // The birth before anything queued (retained: a dashboard that subscribes later sees it).
    if (!s->settings.birth.topic.empty()) s->publish_now(s->settings.birth);
}

void MqttPublisher::State::on_publish(mosquitto*, void* user, int mid) {
    auto* s = static_cast<State*>(user);
    {
        std::lock_guard lock(s->mutex);
        if (s->in_flight.erase(mid) == 0) return;
        ++s->counters.acknowledged;
    }
    s->changed.notify_all();
}

bool MqttPublisher::State::publish_now(const MqttMessage& m) {
    int mid = 0;
    // Put into in_flight under the lock before the acknowledgement can be read (it is read on
    // this thread, after this call).
    const int rc =
        mosquitto_publish(client, &mid, m.topic.c_str(), static_cast<int>(m.payload.size()),
                          m.payload.data(), m.qos, m.retain);
    std::lock_guard lock(mutex);
    if (rc != MOSQ_ERR_SUCCESS) {
        // Not taken (the connection broke while writing): back to the front, sent again.
        queue.push_front(m);
        return false;
    }
    in_flight.emplace(mid, m);
    return true;
}

void MqttPublisher::State::open_connection() {
    refused = 0;
    client = mosquitto_new(settings.client_id.empty() ? nullptr : settings.client_id.c_str(), true,
                           this);
    if (!client) {
        close_connection("cannot create an MQTT client (out of memory)");
        return;
    }
    mosquitto_int_option(client, MOSQ_OPT_PROTOCOL_VERSION, MQTT_PROTOCOL_V311);
    mosquitto_connect_callback_set(client, on_connect);
    mosquitto_publish_callback_set(client, on_publish);
    if (!settings.username.empty())
        mosquitto_username_pw_set(client, settings.username.c_str(),
                                  settings.password.empty() ? nullptr : settings.password.c_str());
    if (!settings.will.topic.empty())
        mosquitto_will_set(client, settings.will.topic.c_str(),
                           static_cast<int>(settings.will.payload.size()),
                           settings.will.payload.data(), settings.will.qos, settings.will.retain);
    if (settings.endpoint.tls) {
        const char* ca_file = settings.ca_file.empty() ? nullptr : settings.ca_file.c_str();
        const int rc = mosquitto_tls_set(
            client, ca_file, ca_file ? nullptr : "/etc/ssl/certs",
            settings.cert_file.empty() ? nullptr : settings.cert_file.c_str(),
            settings.key_file.empty() ? nullptr : settings.key_file.c_str(), nullptr);
        if (rc != MOSQ_ERR_SUCCESS) {
            close_connection(fmt::format("TLS set-up failed: {}", reason(rc)));
            return;
        }
    }
    const int rc = mosquitto_connect_async(client, settings.endpoint.host.c_str(),
                                           settings.endpoint.port, settings.keepalive_s);
    if (rc != MOSQ_ERR_SUCCESS) close_connection(reason(rc));
}

void MqttPublisher::State::close_connection(std::string_view why) {
    const bool was_connected = connected;
    connected = false;
    if (client) {
        mosquitto_destroy(client);
        client = nullptr;
    }
    std::size_t requeued = 0;
    {
        std::lock_guard lock(mutex);
        // Sent and not acknowledged: first in the queue again, in their order (the birth is sent
        // anew by the next connection anyway).
        for (auto it = in_flight.rbegin(); it != in_flight.rend(); ++it) {
            if (it->second.topic == settings.birth.topic && it->second.retain &&
                it->second.payload == settings.birth.payload)
                continue;
            queue.push_front(std::move(it->second));
            ++requeued;
        }
        in_flight.clear();
        counters.resent += requeued;
        counters.connected = false;
    }
    changed.notify_all();
    ++failed_attempts;
    next_attempt_ms = monotonic_ms() + retry_ms;
    if (was_connected) {
        if (warn)
            warn(
                fmt::format("mqtt: lost the connection to {} ({}); events wait in the queue "
                            "(at most {}) and go out on reconnection",
                            address(), why, settings.queue_limit));
    } else if (!warned_failure) {
        if (warn)
            warn(
                fmt::format("mqtt: cannot connect to {}: {}; retrying in the background, events "
                            "wait in the queue (at most {})",
                            address(), why, settings.queue_limit));
        warned_failure = true;
    }
    lost = true;
    retry_ms = std::min(retry_ms * 2, settings.retry_last_ms);
}

void MqttPublisher::State::send_queued() {
    while (connected) {
        MqttMessage next;
        {
            std::lock_guard lock(mutex);
            if (queue.empty() || in_flight.size() >= kMaxInFlight) return;
            next = std::move(queue.front());
            queue.pop_front();
        }
        if (!publish_now(next)) return;
    }
}

void MqttPublisher::State::run() {
    retry_ms = settings.retry_first_ms;
    next_attempt_ms = monotonic_ms();
    for (;;) {
        bool stopping = false;
        bool clean = false;
        {
            std::lock_guard lock(mutex);
            stopping = stop;
            clean = goodbye;
        }
        if (stopping) {
            if (client && connected && clean) {
                mosquitto_disconnect(client);
                // The DISCONNECT out of the socket before it is closed.
                for (int i = 0; i < 10 && mosquitto_want_write(client); ++i)
                    if (mosquitto_loop_write(client, 1) != MOSQ_ERR_SUCCESS) break;
            }
            if (client) mosquitto_destroy(client);
            client = nullptr;
            return;
        }
        const std::int64_t now = monotonic_ms();
        if (!client && now >= next_attempt_ms) open_connection();
        if (connected) send_queued();
        pollfd fds[2] = {{wake_fd, POLLIN, 0}, {-1, 0, 0}};
        nfds_t count = 1;
        const int socket = client ? mosquitto_socket(client) : -1;
        if (socket >= 0) {
            fds[1] = {socket,
                      static_cast<short>(POLLIN | (mosquitto_want_write(client) ? POLLOUT : 0)), 0};
            count = 2;
        }
        int timeout = kLongestSleepMs;
        if (!client)
            timeout = static_cast<int>(
                std::clamp<std::int64_t>(next_attempt_ms - now, 0, kLongestSleepMs));
        ::poll(fds, count, timeout);
        if (fds[0].revents & POLLIN) {
            std::uint64_t value = 0;
            [[maybe_unused]] ssize_t n = ::read(wake_fd, &value, sizeof value);
        }
        if (!client) continue;
        int rc = MOSQ_ERR_SUCCESS;
        if (count == 2 && (fds[1].revents & (POLLIN | POLLHUP | POLLERR)))
            rc = mosquitto_loop_read(client, 1);
        if (refused != 0) {  // loop_read says CONN_REFUSED too; the reason is the broker's
            close_connection(fmt::format("the broker refused the connection: {}",
                                         without_full_stop(mosquitto_connack_string(refused))));
            continue;
        }
        if (rc == MOSQ_ERR_SUCCESS && count == 2 && (fds[1].revents & POLLOUT))
            rc = mosquitto_loop_write(client, 1);
        if (rc == MOSQ_ERR_SUCCESS) rc = mosquitto_loop_misc(client);
        if (rc != MOSQ_ERR_SUCCESS) close_connection(reason(rc));
    }
}

Result<std::unique_ptr<MqttPublisher>> MqttPublisher::start(MqttSettings settings, Warn warn) {
    if (Result<void> files = check_tls_files(settings.endpoint.tls, settings.ca_file,
                                             settings.cert_file, settings.key_file);
        !files)
        return Error{files.error()};
    initialise_library();
    auto state = std::make_unique<State>();
    state->settings = std::move(settings);
    state->warn = std::move(warn);
    state->wake_fd = ::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
    if (state->wake_fd < 0)
        return Error{fmt::format("mqtt: cannot make an eventfd: {}", std::strerror(errno))};
    State* raw = state.get();
    state->thread = std::thread([raw] { raw->run(); });
    return std::unique_ptr<MqttPublisher>(new MqttPublisher(std::move(state)));
}

MqttPublisher::MqttPublisher(std::unique_ptr<State> state) : state_(std::move(state)) {}

MqttPublisher::~MqttPublisher() {
    if (state_->thread.joinable()) {
        {
            std::lock_guard lock(state_->mutex);
            state_->stop = true;
        }
        state_->wake();
        state_->thread.join();
    }
    if (state_->wake_fd >= 0) ::close(state_->wake_fd);
}

void MqttPublisher::publish(MqttMessage message) {
    {
        std::lock_guard lock(state_->mutex);
        MqttCounters& c = state_->counters;
        ++c.queued;
        auto& queue = state_->queue;
        if (message.retain) {
            // Only the latest state of a topic matters: replace one still waiting.
            auto same = std::find_if(queue.begin(), queue.end(), [&](const MqttMessage& m) {
                return m.retain && m.topic == message.topic;
            });
            if (same != queue.end()) {
                *same = std::move(message);
                ++c.replaced;
                return;
            }
        }
        if (queue.size() >= state_->settings.queue_limit) {
            // Full: an event waits no more (the newest is dropped); a state takes the place of
            // the oldest event, so states are never lost for events.
            auto event = std::find_if(queue.begin(), queue.end(),
                                      [](const MqttMessage& m) { return !m.retain; });
            ++c.dropped;
            if (!message.retain || event == queue.end()) return;
            queue.erase(event);
        }
        queue.push_back(std::move(message));
    }
    state_->wake();
}

bool MqttPublisher::wait_until_delivered(int timeout_ms) const {
    std::unique_lock lock(state_->mutex);
    return state_->changed.wait_for(lock, std::chrono::milliseconds(timeout_ms), [&] {
        return state_->queue.empty() && state_->in_flight.empty() && state_->counters.connected;
    });
}

std::uint64_t MqttPublisher::finish(MqttMessage goodbye, int timeout_ms) {
    if (!goodbye.topic.empty()) publish(std::move(goodbye));
    wait_until_delivered(timeout_ms);
    std::uint64_t left = 0;
    {
        std::lock_guard lock(state_->mutex);
        left = state_->queue.size() + state_->in_flight.size();
        state_->stop = true;
        state_->goodbye = true;
    }
    state_->wake();
    if (state_->thread.joinable()) state_->thread.join();
    return left;
}

MqttCounters MqttPublisher::counters() const {
    std::lock_guard lock(state_->mutex);
    MqttCounters c = state_->counters;
    c.waiting = state_->queue.size() + state_->in_flight.size();
    return c;
}

}  // namespace dpscope::monitor
