#include "formats/monitor_messages.hpp"

#include <fmt/format.h>

#include <ctime>

#include "formats/json.hpp"
#include "formats/json_writer.hpp"

namespace dpscope {

namespace {

// "2026-11-26T04:05:06Z" (UTC, whole seconds; the figures need no more).
std::string utc_seconds(std::int64_t time_ns) {
    std::time_t t = static_cast<std::time_t>(time_ns / 1'000'000'000);
    std::tm utc{};
    if (gmtime_r(&t, &utc) == nullptr) return "unknown";
    return fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}:{:02}Z", utc.tm_year + 1900, utc.tm_mon + 1,
                       utc.tm_mday, utc.tm_hour, utc.tm_min, utc.tm_sec);
}

Result<void> check_level(std::string_view level, std::string_view option, std::string_view whole) {
    if (level.empty())
        return Error{
            fmt::format("{} '{}': a topic level is empty (two '/' in a row, or one at "
                        "the start or the end)",
                        option, whole)};
    for (char c : level)
        if (c == '+' || c == '#' || c == '\0')
            return Error{
                fmt::format("{} '{}': '{}' is a wildcard of subscriptions, not allowed in a topic",
                            option, whole, c == '\0' ? std::string("\\0") : std::string(1, c))};
    return {};
}

}  // namespace

std::string status_line(const MonitorFigures& f) {
    return fmt::format(
        "dpscope: status: {} telegrams, {:.0f}/s, {} bytes skipped, {} parity errors, {} bytes on "
        "disk, last event {}",
        f.telegrams, f.rate, f.bytes_skipped, f.parity_errors, f.disk_bytes, f.last_event);
}

Result<MqttTopics> MqttTopics::make(std::string_view prefix, std::string_view segment) {
    std::size_t start = 0;
    for (;;) {
        const std::size_t slash = prefix.find('/', start);
        const std::string_view level = prefix.substr(
            start, slash == std::string_view::npos ? std::string_view::npos : slash - start);
        if (Result<void> ok = check_level(level, "--mqtt-topic", prefix); !ok)
            return Error{ok.error()};
        if (slash == std::string_view::npos) break;
        start = slash + 1;
    }
    if (segment.find('/') != std::string_view::npos)
        return Error{fmt::format("--mqtt-segment '{}': one topic level, without '/'", segment)};
    if (Result<void> ok = check_level(segment, "--mqtt-segment", segment); !ok)
        return Error{ok.error()};
    MqttTopics topics;
    topics.base_ = fmt::format("{}/{}", prefix, segment);
    return topics;
}

std::string MqttTopics::verdict(std::uint8_t address) const {
    return address == 0xFF ? base_ + "/verdict/segment"
                           : fmt::format("{}/verdict/{}", base_, address);
}

std::string status_payload(const MonitorIdentity& who, std::string_view state,
                           std::string_view reason, const std::uint64_t* telegrams) {
    return json::text_of([&](JsonWriter& w) {
        w.begin_object();
        w.key("state").string(state);
        if (!reason.empty()) w.key("reason").string(reason);
        w.key("segment").string(who.segment);
        w.key("device").string(who.device);
        w.key("bus").string(who.bus);
        w.key("baud").integer(who.baud);
        w.key("version").string(who.version);
        w.key("since").string(utc_seconds(who.since_ns));
        if (telegrams) w.key("telegrams").integer(static_cast<std::int64_t>(*telegrams));
        w.end_object();
    });
}

std::string finding_payload(const Finding& f) {
    return json::text_of([&](JsonWriter& w) { json::finding(w, f); });
}

std::string stats_payload(const MonitorFigures& f) {
    return json::text_of([&](JsonWriter& w) {
        w.begin_object();
        w.key("time").string(utc_seconds(f.time_ns));
        w.key("telegrams").integer(static_cast<std::int64_t>(f.telegrams));
        w.key("rate").number_text(fmt::format("{:.1f}", f.rate));
        w.key("bytes_skipped").integer(static_cast<std::int64_t>(f.bytes_skipped));
        w.key("parity_errors").integer(static_cast<std::int64_t>(f.parity_errors));
        w.key("disk_bytes").integer(static_cast<std::int64_t>(f.disk_bytes));
        w.key("findings").integer(static_cast<std::int64_t>(f.findings));
        w.key("health_events").integer(static_cast<std::int64_t>(f.health_events));
        w.key("last_event").string(f.last_event);
        w.key("mqtt_dropped").integer(static_cast<std::int64_t>(f.mqtt_dropped));
        w.key("mqtt_waiting").integer(static_cast<std::int64_t>(f.mqtt_waiting));
        w.end_object();
    });
}

}  // namespace dpscope
