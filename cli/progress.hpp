// Progress of a long offline run (decode, report, stats on a big file): one line on standard error
// when it is a terminal, drawn at the first check and then refreshed in place at most
// kProgressRefreshNs apart, cleared at the end:
//   "dpscope: 412.0 MiB of 1.2 GiB (33 %), 2.31 M telegrams/s, ETA 0:42"
// Checking costs a counter per telegram; the clock and the source's position are read once every
// kProgressCheckEvery telegrams.
#pragma once

#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <string_view>

#include "capture/telegram_source.hpp"

namespace dpscope::cli {

// Inputs smaller than this get no progress line (the environment variable
// DPSCOPE_PROGRESS_MIN_BYTES, a whole number of bytes, sets another limit, for tests).
inline constexpr std::uint64_t kProgressMinBytes = 100ULL * 1000 * 1000;
inline constexpr std::int64_t kProgressRefreshNs = 250'000'000;  // at most 4 lines a second
inline constexpr std::uint64_t kProgressCheckEvery = 4096;       // telegrams between clock reads

// "1.2 GiB", "412.0 MiB", "900 KiB", "512 B".
std::string progress_bytes_text(std::uint64_t bytes);
// "0:42", "12:05", "1:02:03"; "?" for a negative (unknown) time.
std::string progress_eta_text(std::int64_t seconds);
// The line, without "\r": bytes read of `total`, the telegrams' rate over `elapsed_ns`, and the
// time left at the rate bytes were read so far.
std::string progress_line(std::uint64_t bytes, std::uint64_t total, std::uint64_t telegrams,
                          std::int64_t elapsed_ns);

// The minimum input size for a progress line: kProgressMinBytes, or DPSCOPE_PROGRESS_MIN_BYTES
// when it is a whole number.
std::uint64_t progress_min_bytes();

class ProgressMeter {
  public:
    using Clock = std::function<std::int64_t()>;           // monotonic nanoseconds
    using Writer = std::function<void(std::string_view)>;  // where the line goes

    // A meter over `total` bytes, drawing through `write` when `shown`; `clock` defaults to
    // std::chrono::steady_clock.
    ProgressMeter(std::uint64_t total, bool shown, Writer write, Clock clock = {});
    // For `source`: shown when standard error is a terminal, the input's size is known and at
    // least progress_min_bytes(), and `allowed` (decode: not when the decode itself is printed
    // on that terminal). Returned as a prvalue (the meter does not move: a line being shown is
    // known by its address).
    static ProgressMeter for_source(const TelegramSource& source, bool allowed = true);
    ~ProgressMeter();
    ProgressMeter(const ProgressMeter&) = delete;
    ProgressMeter& operator=(const ProgressMeter&) = delete;

    bool shown() const noexcept { return shown_; }
    // One telegram read; now and then asks `source` how far it got and redraws.
    void tick(const TelegramSource& source) {
        if (!shown_ || ++telegrams_ % kProgressCheckEvery != 0) return;
        update(source.bytes_read());
    }
    // `bytes` read so far: redraws when kProgressRefreshNs have passed since the last line.
    void update(std::uint64_t bytes);
    // Clears the line (at the end, or before a message goes to standard error); the next update
    // draws it again.
    void clear();
    std::uint64_t telegrams() const noexcept { return telegrams_; }

  private:
    std::uint64_t total_;
    bool shown_;
    Writer write_;
    Clock clock_;
    std::int64_t start_ns_ = 0;
    std::int64_t last_draw_ns_ = 0;
    std::uint64_t telegrams_ = 0;
    std::size_t drawn_ = 0;  // characters of the line on the screen (0: none)
};

// Clears the progress line being shown, if any (print_diagnostic calls it before a message).
void clear_progress_line();

}  // namespace dpscope::cli
