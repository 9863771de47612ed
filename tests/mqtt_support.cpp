#include "tests/mqtt_support.hpp"

#include <arpa/inet.h>
#include <mosquitto.h>
#include <netinet/in.h>
#include <pwd.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <stdexcept>

namespace dpscope::test {

namespace {}  // namespace

// The broker takes it a moment later.
int free_loopback_port() {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    address.sin_port = 0;
    ::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address);
    socklen_t size = sizeof address;
    ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &size);
    const int port = ntohs(address.sin_port);
    ::close(fd);
    return port;
}

namespace {

bool accepts_connections(int port) {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    address.sin_port = htons(static_cast<std::uint16_t>(port));
    const bool ok = ::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0;
    ::close(fd);
    return ok;
}

std::string mosquitto_program() {
    for (const char* path : {"/usr/sbin/mosquitto", "/usr/bin/mosquitto"})
        if (::access(path, X_OK) == 0) return path;
    return "mosquitto";
}

}  // namespace

MosquittoBroker::MosquittoBroker(std::vector<std::string> extra) : extra_(std::move(extra)) {
    folder_ = temp_path("mosquitto");
    std::filesystem::create_directories(folder_);
    for (int attempt = 0; attempt < 5 && !child_; ++attempt) {
        port_ = free_loopback_port();
        start();
    }
    if (!child_) throw std::runtime_error("mosquitto did not start: " + log());
}

MosquittoBroker::~MosquittoBroker() {
    kill();
    std::filesystem::remove_all(folder_);
}

std::string MosquittoBroker::url() const { return "mqtt://127.0.0.1:" + std::to_string(port_); }

void MosquittoBroker::start() {
    config_ = folder_ + "/mosquitto.conf";
    std::ofstream conf(config_);
    conf << "listener " << port_ << " 127.0.0.1\n"
         << "allow_anonymous true\n"
         << "persistence true\n"
         << "persistence_location " << folder_ << "/\n"
         << "autosave_on_changes true\n"
         << "autosave_interval 1\n"
         << "log_dest file " << folder_ << "/mosquitto.log\n"
         << "log_type all\n";
    // Started as root, mosquitto would become the user "mosquitto", who may not write here.
    if (const passwd* me = ::getpwuid(::geteuid())) conf << "user " << me->pw_name << "\n";
    for (const std::string& line : extra_)
        conf << line << "\n";
    conf.close();
    child_ = std::make_unique<Child>(std::vector<std::string>{mosquitto_program(), "-c", config_});
    // Ready when it accepts connections; gone when it could not listen (the port was taken).
    bool ready = false;
    wait_until([&] {
        if (accepts_connections(port_)) return ready = true;
        return child_->wait(0) >= 0;
    });
    if (!ready) child_.reset();
}

void MosquittoBroker::kill() {
    if (!child_) return;
    child_->signal(SIGKILL);
    child_->wait();
    child_.reset();
}

void MosquittoBroker::restart() {
    kill();
    start();
    if (!child_) throw std::runtime_error("mosquitto did not start again: " + log());
}

std::string MosquittoBroker::log() const { return slurp(folder_ + "/mosquitto.log"); }

bool MosquittoBroker::saved_after(std::string_view text) const {
    return wait_until([&] {
        const std::string all = log();
        const std::size_t at = all.find(text);
        return at != std::string::npos &&
               all.find("Saving in-memory database", at) != std::string::npos;
    });
}

bool MosquittoBroker::log_says(std::string_view text) const {
    return wait_until([&] { return log().find(text) != std::string::npos; });
}

MqttSubscriber::MqttSubscriber(int port, std::string filter, std::string client_id)
    : filter_(std::move(filter)) {
    mosquitto_lib_init();
    client_ = mosquitto_new(client_id.c_str(), false, this);
    mosquitto_connect_callback_set(client_, on_connect);
    mosquitto_subscribe_callback_set(client_, on_subscribe);
    mosquitto_message_callback_set(client_, on_message);
    mosquitto_reconnect_delay_set(client_, 1, 1, false);
    mosquitto_connect_async(client_, "127.0.0.1", port, 30);
    mosquitto_loop_start(client_);
}

MqttSubscriber::~MqttSubscriber() {
    mosquitto_disconnect(client_);
    mosquitto_loop_stop(client_, true);
    mosquitto_destroy(client_);
}

void MqttSubscriber::on_connect(struct mosquitto* m, void* self, int rc) {
    auto* s = static_cast<MqttSubscriber*>(self);
    if (rc == 0) mosquitto_subscribe(m, nullptr, s->filter_.c_str(), 1);
}

void MqttSubscriber::on_subscribe(struct mosquitto*, void* self, int, int, const int*) {
    auto* s = static_cast<MqttSubscriber*>(self);
    std::lock_guard lock(s->mutex_);
    ++s->subscriptions_;
    s->changed_.notify_all();
}

void MqttSubscriber::on_message(struct mosquitto*, void* self, const struct mosquitto_message* m) {
    auto* s = static_cast<MqttSubscriber*>(self);
    std::lock_guard lock(s->mutex_);
    s->messages_.push_back(
        {m->topic,
         std::string(static_cast<const char*>(m->payload), static_cast<std::size_t>(m->payloadlen)),
         m->retain});
    s->changed_.notify_all();
}

bool MqttSubscriber::subscribed() {
    std::unique_lock lock(mutex_);
    return changed_.wait_for(lock, std::chrono::duration<double>(kPatienceSeconds),
                             [&] { return subscriptions_ > 0; });
}

void MqttSubscriber::pause() {
    mosquitto_disconnect(client_);
    mosquitto_loop_stop(client_, false);
}

void MqttSubscriber::resume() {
    mosquitto_reconnect_async(client_);
    mosquitto_loop_start(client_);
}

std::vector<ReceivedMessage> MqttSubscriber::messages() const {
    std::lock_guard lock(mutex_);
    return messages_;
}

bool MqttSubscriber::wait_for(
    const std::function<bool(const std::vector<ReceivedMessage>&)>& done) {
    std::unique_lock lock(mutex_);
    return changed_.wait_for(lock, std::chrono::duration<double>(kPatienceSeconds),
                             [&] { return done(messages_); });
}

std::vector<std::string> MqttSubscriber::distinct_payloads(const std::string& topic) const {
    std::lock_guard lock(mutex_);
    std::vector<std::string> payloads;
    std::set<std::string> seen;
    for (const ReceivedMessage& m : messages_)
        if (m.topic == topic && seen.insert(m.payload).second) payloads.push_back(m.payload);
    return payloads;
}

}  // namespace dpscope::test
