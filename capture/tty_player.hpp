// Plays telegrams onto a tty (a serial port, or the master side of a pseudo-terminal): at the
// pace of their timestamps, which the simulator derives from the baud rate, or as fast as the
// device takes them.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/result.hpp"

namespace dpscope {

// Yields the next telegram and its time; false at the end.
using TelegramGenerator = std::function<bool(std::vector<std::uint8_t>&, std::int64_t&)>;

struct PlayStats {
    std::uint64_t telegrams = 0;
    std::uint64_t bytes = 0;
    std::int64_t scheduled_ns = 0;  // last telegram's time minus the first's
    std::int64_t wall_ns = 0;       // how long playing took
};

// Writes every telegram to `fd` (blocking or not) and says how many went out, how many bytes
// and how long it took. Paced: each telegram goes out when its time, relative to the first, has
// passed. Stops early when `stop` becomes true. An error says how far a failed write got.
Result<PlayStats> play_telegrams(int fd, const TelegramGenerator& next, bool as_fast_as_possible,
                                 const std::atomic<bool>* stop);

}  // namespace dpscope
