// Triggers (issue 30): keep the minutes around an event. The telegrams of the last `pre` seconds
// are held in memory (bounded by a size cap); when a trigger fires, they are written with the
// next `post` seconds to a pcapng file of their own, named after the time and the event
// (trigger-20261128T101500Z-station_lost-7.pcapng), the triggering telegram marked with a
// comment. A trigger inside an open window extends it; at most `limit_per_hour` windows start in
// an hour of capture time, so a storm cannot fill the disk. Fed by sniff (live) and decode
// (offline, cutting a long capture into its windows); the filter that fires is the caller's.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "capture/capture_writer.hpp"
#include "core/result.hpp"
#include "core/telegram.hpp"

namespace dpscope {

struct TriggerOptions {
    std::string folder;                         // where the files go (exists)
    std::int64_t pre_ns = 0;                    // --pre
    std::int64_t post_ns = 0;                   // --post
    std::uint64_t max_pre_bytes = 64ull << 20;  // the in-memory ring's cap
    unsigned limit_per_hour = 60;               // --trigger-limit
    int link_type = 0;
    Protocol bus = Protocol::ProfibusDp;
    LineSettings line;
};

// Why a telegram fires: the event (for the file name: "station_lost", a finding's kind, or
// "match"), the station it is about (-1: none) and the comment put on it.
struct TriggerHit {
    std::string event;
    int station = -1;
    std::string comment;
};

struct TriggerStats {
    std::uint64_t windows = 0;       // files written
    std::uint64_t hits = 0;          // telegrams that fired (extensions included)
    std::uint64_t suppressed = 0;    // hits that would have started a window over the limit
    std::uint64_t pre_dropped = 0;   // telegrams the pre-ring let go for its size cap
    std::vector<std::string> files;  // the files written, in order
};

class TriggerRecorder {
  public:
    explicit TriggerRecorder(TriggerOptions options);

    // Each telegram in order; `hit` when a trigger fired on it. An error (a file that cannot be
    // written) names the file; recording stops then, the capture goes on.
    Result<void> feed(Bytes telegram, std::int64_t time_ns, const TriggerHit* hit);
    // Closes an open window (the capture ended inside it).
    Result<void> finish();
    const TriggerStats& stats() const noexcept { return stats_; }

    // trigger-<UTC time>-<event>[-<station>].pcapng in `folder` (event: letters, digits, '_').
    static std::string file_name(const std::string& folder, std::int64_t time_ns,
                                 const TriggerHit& hit);

  private:
    struct Held {
        std::vector<std::uint8_t> bytes;
        std::int64_t time_ns = kNoTime;    // its time, or the one before's (what --pre counts)
        std::int64_t record_ns = kNoTime;  // its time as it came (what is written)
    };
    Result<void> open_window(std::int64_t time_ns, const TriggerHit& hit);
    Result<void> close_window();
    void hold(Bytes telegram, std::int64_t time_ns, std::int64_t record_ns);

    TriggerOptions options_;
    std::deque<Held> pre_;
    std::uint64_t pre_bytes_ = 0;
    std::unique_ptr<CaptureWriter> window_;
    std::string window_name_;
    std::int64_t window_end_ns_ = kNoTime;
    std::deque<std::int64_t> starts_;  // the windows of the last hour (capture time)
    std::int64_t last_time_ns_ = kNoTime;
    TriggerStats stats_;
};

}  // namespace dpscope
