#include "protocols/profibus/health/health_event_describe.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <ctime>

namespace dpscope {

namespace {

template <class List>
auto find_address(const List& list, std::uint8_t address) {
    return std::find_if(list.begin(), list.end(),
                        [address](const auto& item) { return item.address == address; });
}

// The judgement health holds for `address` seen in `role`: a master's own judgement when it acts
// as a master and has one, else the station's (kSegmentAddress: the segment's); null when
// health does not list it.
const Judgement* judgement_of(const BusHealth& health, std::uint8_t address, StationRole role) {
    if (address == kSegmentAddress) return &health.segment.judgement;
    auto master = find_address(health.masters, address);
    auto station = find_address(health.stations, address);
    if (role == StationRole::Master && master != health.masters.end()) return &master->judgement;
    if (station != health.stations.end()) return &station->judgement;
    return nullptr;
}

// The role the live list gives `address` (Unknown when it does not list it).
StationRole listed_role(const BusHealth& health, std::uint8_t address) {
    auto station = find_address(health.stations, address);
    return station != health.stations.end() ? station->role : StationRole::Unknown;
}

void station_and_role(JsonWriter& w, std::uint8_t address, StationRole role) {
    if (address == kSegmentAddress) {
        w.key("station").string("segment");
        w.key("role").string("segment");
    } else {
        w.key("station").integer(address);
        w.key("role").string(station_role_name(role));
    }
}

}  // namespace

AlarmEvent describe_health_event(const HealthEvent& e, const BusHealth& health) {
    AlarmEvent event;
    event.kind = e.kind;
    event.address = e.address;
    event.role = e.role;
    event.time_ns = e.time_ns;
    event.frame = e.frame;
    const Judgement* judgement = judgement_of(health, e.address, e.role);
    if (e.address != kSegmentAddress && e.role == StationRole::Unknown)
        event.role = listed_role(health, e.address);
    if (judgement) {
        event.verdict = judgement->verdict;
        for (const VerdictReason& reason : judgement->reasons)
            event.reasons.push_back(describe_reason(reason, health.thresholds));
    }
    return event;
}

std::string iso8601_utc(std::int64_t time_ns) {
    if (time_ns == kNoTime) return "unknown";
    // Whole seconds rounded down, so that a time before 1970 keeps a positive fraction.
    std::int64_t seconds = time_ns / 1'000'000'000;
    std::int64_t rest = time_ns % 1'000'000'000;
    if (rest < 0) {
        --seconds;
        rest += 1'000'000'000;
    }
    const std::int64_t micros = rest / 1000;
    std::time_t t = static_cast<std::time_t>(seconds);
    std::tm utc{};
    if (gmtime_r(&t, &utc) == nullptr) return "unknown";
    return fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}:{:02}.{:06}Z", utc.tm_year + 1900,
                       utc.tm_mon + 1, utc.tm_mday, utc.tm_hour, utc.tm_min, utc.tm_sec, micros);
}

std::string event_subject(const AlarmEvent& e) {
    if (e.address == kSegmentAddress) return "the segment";
    if (e.role == StationRole::Master) return fmt::format("station {} (master)", e.address);
    return fmt::format("station {}", e.address);
}

std::string health_event_line(const AlarmEvent& e) {
    const std::string time = iso8601_utc(e.time_ns);
    switch (e.kind) {
        case HealthEventKind::StationLost:
        case HealthEventKind::StationReturned:
            return fmt::format("{} health: station {} {} ({}, frame {})", time, e.address,
                               e.kind == HealthEventKind::StationLost ? "lost" : "returned",
                               station_role_name(e.role), e.frame);
        case HealthEventKind::VerdictBad:
        case HealthEventKind::Count: break;
    }
    return fmt::format("{} health: verdict of {} turned {}{}{} (frame {})", time, event_subject(e),
                       verdict_name(e.verdict), e.reasons.empty() ? "" : ": ",
                       fmt::join(e.reasons, "; "), e.frame);
}

void health_event_json(JsonWriter& w, const AlarmEvent& e) {
    w.begin_object();
    w.key("event").string(health_event_name(e.kind));
    station_and_role(w, e.address, e.role);
    w.key("time").string(iso8601_utc(e.time_ns));
    w.key("frame").integer(static_cast<std::int64_t>(e.frame));
    w.key("verdict").string(verdict_name(e.verdict));
    w.key("reasons").begin_array();
    for (const std::string& reason : e.reasons)
        w.string(reason);
    w.end_array();
    w.end_object();
}

void live_list_json(JsonWriter& w, const BusHealth& health) {
    w.begin_object();
    w.key("stations").begin_array();
    for (const StationHealth& s : health.stations) {
        w.begin_object();
        w.key("address").integer(s.address);
        w.key("role").string(station_role_name(s.role));
        w.key("state").string(station_state_name(s.state));
        w.end_object();
    }
    w.end_array();
    w.end_object();
}

Verdict verdict_of(const BusHealth& health, std::uint8_t address) {
    const Judgement* j = judgement_of(health, address, listed_role(health, address));
    return j ? j->verdict : Verdict::Good;
}

void verdict_json(JsonWriter& w, const BusHealth& health, std::uint8_t address) {
    const StationRole role = listed_role(health, address);
    const Judgement* j = judgement_of(health, address, role);
    w.begin_object();
    station_and_role(w, address, role);
    w.key("verdict").string(verdict_name(j ? j->verdict : Verdict::Good));
    w.key("reasons").begin_array();
    if (j)
        for (const VerdictReason& reason : j->reasons)
            w.string(describe_reason(reason, health.thresholds));
    w.end_array();
    w.end_object();
}

}  // namespace dpscope
