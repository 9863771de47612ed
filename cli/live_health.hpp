// `sniff --stats` while capturing: the health tracker's events as plain lines (no terminal) or
// the live station table redrawn in place (a terminal), and the --alarm commands.
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "cli/alarm.hpp"
#include "formats/output.hpp"
#include "protocols/profibus/health/bus_health.hpp"

namespace dpscope::cli {

// Told of every health event, described, and of the statistics after each judgement (the MQTT
// events, cli/live_mqtt.hpp).
class HealthListener {
  public:
    virtual ~HealthListener() = default;
    virtual void on_health_event(const AlarmEvent& event) = 0;
    virtual void on_judged(const BusHealth& health) = 0;
};

class LiveHealth {
  public:
    static constexpr std::int64_t kRedrawEveryNs = 250'000'000;  // at most 4 redraws a second

    // How the events and the statistics are shown.
    enum class Show {
        Table,          // the station table redrawn in place (a terminal), recent events under it
        Lines,          // one plain line per event in `out`
        StandardError,  // one plain line per event on standard error (the output is jsonl, csv)
        Nothing,        // --alarm alone
    };

    // `out` writes to `stream`. `heading` names the capture ("/dev/ttyUSB0 at 12000000 baud
    // 8E1"). `alarms`: the --alarm runner, or null.
    LiveHealth(BusHealthTracker& tracker, Output& out, FILE* stream, Show show, std::string heading,
               AlarmRunner* alarms);

    // The events the last telegram caused (Pipeline::health_events()).
    void on_events(std::span<const HealthEvent> events);
    // Called often (after each telegram and when the line is idle): judges at most every
    // kRedrawEveryNs of `now_ns` (monotonic), reports verdicts that turned bad, redraws.
    void tick(std::int64_t now_ns, std::uint64_t telegrams, double seconds);
    // Before Pipeline::finish(): the last verdicts; the tracker finished at the last telegram.
    void before_finish();
    // After it: the last table (a terminal).
    void after_finish(std::uint64_t telegrams, double seconds);

    std::uint64_t redraws() const noexcept { return redraws_; }
    // `listener` (or null) is told of events and judgements from now on.
    void listen(HealthListener* listener) noexcept { listener_ = listener; }

  private:
    void handle(const HealthEvent& event);
    void judged();
    void redraw(std::uint64_t telegrams, double seconds, bool final);

    BusHealthTracker& tracker_;
    Output& out_;
    FILE* stream_;
    Show show_;
    std::string heading_;
    AlarmRunner* alarms_;
    HealthListener* listener_ = nullptr;
    std::int64_t last_tick_ns_ = 0;
    bool ticked_ = false;
    std::vector<std::string> recent_;  // the last event lines, shown under the table
    unsigned drawn_lines_ = 0;
    std::uint64_t redraws_ = 0;
};

}  // namespace dpscope::cli
