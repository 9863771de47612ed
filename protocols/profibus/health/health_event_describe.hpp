// A bus-health event told to people and programs: with the verdict and reasons its station had,
// as a plain line (sniff --stats), as the --alarm command's variables (cli/alarm.hpp) and as the
// JSON object of the MQTT events (monitor/). One description, so the three say the same.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "formats/json_writer.hpp"
#include "protocols/profibus/health/bus_health.hpp"

namespace dpscope {

// A health event with what the statistics said about its station when it happened.
struct AlarmEvent {
    HealthEventKind kind = HealthEventKind::StationLost;
    std::uint8_t address = 0;  // kSegmentAddress: the segment
    StationRole role = StationRole::Unknown;
    std::int64_t time_ns = kNoTime;  // capture time of the telegram that caused it
    std::uint64_t frame = 0;
    Verdict verdict = Verdict::Good;
    std::vector<std::string> reasons;  // describe_reason() of the judgement, the worst first
};

// The event `e` with the verdict and reasons `health` holds for its station: a master's own
// judgement for a master with one, the station's otherwise, the segment's for kSegmentAddress.
AlarmEvent describe_health_event(const HealthEvent& e, const BusHealth& health);

// "2026-11-26T04:05:06.123456Z" (UTC, microseconds); "unknown" for kNoTime.
std::string iso8601_utc(std::int64_t time_ns);

// "station 5", "station 2 (master)", "the segment".
std::string event_subject(const AlarmEvent& e);

// One plain line (no newline) for the live output of `sniff --stats` off a terminal:
// "2026-...Z health: station 5 lost (slave, frame 1234)",
// "2026-...Z health: station 5 returned (slave, frame 2345)",
// "2026-...Z health: verdict of station 5 turned bad: <reason>; <reason> (frame 3456)".
std::string health_event_line(const AlarmEvent& e);

// The event as a JSON object with the --alarm command's variables by their lower-case names:
// {"event":"station_lost","station":5,"role":"slave","time":"2026-...Z","frame":1234,
//  "verdict":"bad","reasons":["..."]}; the segment is "station":"segment","role":"segment".
void health_event_json(JsonWriter& w, const AlarmEvent& e);

// The live list as a JSON object: {"stations":[{"address":2,"role":"master","state":"active"},
// ...]}, by address.
void live_list_json(JsonWriter& w, const BusHealth& health);

// A station's verdict (kSegmentAddress: the segment's) as a JSON object:
// {"station":5,"role":"slave","verdict":"weak","reasons":["..."]}. A master's own judgement for
// a station that is a master.
void verdict_json(JsonWriter& w, const BusHealth& health, std::uint8_t address);

// The verdict of a station (kSegmentAddress: the segment) as health holds it; Good for a
// station it does not list.
Verdict verdict_of(const BusHealth& health, std::uint8_t address);

}  // namespace dpscope
