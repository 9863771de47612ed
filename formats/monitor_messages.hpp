// What a monitoring `sniff` tells about itself (issue 30): the status line of --status-interval
// and --status-file, and the MQTT topics with their JSON payloads (docs/mqtt.md). Pure text: the
// publisher (monitor/) sends what these make; nothing here knows the network.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "core/finding.hpp"
#include "core/result.hpp"

namespace dpscope {

// The figures of a running capture, as the status line and the MQTT statistics give them.
struct MonitorFigures {
    std::int64_t time_ns = 0;     // wall clock when taken
    std::uint64_t telegrams = 0;  // so far
    double rate = 0;              // telegrams a second since the figures before
    std::uint64_t bytes_skipped = 0;
    std::uint64_t parity_errors = 0;
    std::uint64_t disk_bytes = 0;  // in -w's file or the ring's files
    std::uint64_t findings = 0;
    std::uint64_t health_events = 0;
    std::string last_event = "none";  // "station_lost 5 at frame 1234", "fcs_error at frame 9"
    std::uint64_t mqtt_dropped = 0;   // events the MQTT queue had no room for
    std::uint64_t mqtt_waiting = 0;   // in the MQTT queue or not yet acknowledged
};

// "dpscope: status: 1200 telegrams, 400/s, 0 bytes skipped, 0 parity errors, 4096 bytes on
// disk, last event none" (no newline).
std::string status_line(const MonitorFigures& f);

// The topics under PREFIX/SEGMENT:
//   status          retained  {"state":"online"|"offline",...}: birth, will and goodbye
//   finding         events    each finding, as jsonl gives it
//   health          events    each health event: station_lost, station_returned, verdict_bad
//   live            retained  the live list, on change
//   verdict/N       retained  station N's verdict (verdict/segment: the segment's), on change
//   stats           retained  the figures, every --mqtt-stats-interval seconds
class MqttTopics {
  public:
    // Checks `prefix` (levels separated by '/', none empty, no '+' or '#') and `segment` (one
    // level) and makes the topics.
    static Result<MqttTopics> make(std::string_view prefix, std::string_view segment);
    std::string status() const { return base_ + "/status"; }
    std::string finding() const { return base_ + "/finding"; }
    std::string health() const { return base_ + "/health"; }
    std::string live() const { return base_ + "/live"; }
    std::string verdict(std::uint8_t address) const;  // 0xFF: the segment
    std::string stats() const { return base_ + "/stats"; }
    const std::string& base() const { return base_; }

  private:
    std::string base_;
};

// What the status topic says about the capture.
struct MonitorIdentity {
    std::string segment;
    std::string device;  // "/dev/ttyUSB0"
    std::string bus;     // "profibus"
    std::uint32_t baud = 0;
    std::string version;
    std::int64_t since_ns = 0;  // the capture's start (wall clock)
};

// {"state":"online","segment":"line3","device":"/dev/ttyUSB0","bus":"profibus","baud":1500000,
//  "version":"0.1.0","since":"2026-...Z"}; "offline" adds "reason" ("stopped": a clean end, with
// "telegrams"; "connection lost": the will the broker publishes when the sniffer dies).
std::string status_payload(const MonitorIdentity& who, std::string_view state,
                           std::string_view reason = {}, const std::uint64_t* telegrams = nullptr);

// The finding as jsonl writes it (json::finding).
std::string finding_payload(const Finding& f);

// {"time":"2026-...Z","telegrams":1200,"rate":400.0,"bytes_skipped":0,"parity_errors":0,
//  "disk_bytes":4096,"findings":3,"health_events":1,"last_event":"...","mqtt_dropped":0,
//  "mqtt_waiting":0}
std::string stats_payload(const MonitorFigures& f);

}  // namespace dpscope
