#include "capture/tty_player.hpp"

#include <fmt/format.h>
#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>

#include "core/counted.hpp"
#include "core/time.hpp"

namespace dpscope {

namespace {

constexpr std::size_t kBatchBytes = 1 << 16;

std::int64_t monotonic_ns() {
    timespec now{};
    clock_gettime(CLOCK_MONOTONIC, &now);
    return static_cast<std::int64_t>(now.tv_sec) * 1'000'000'000 + now.tv_nsec;
}

void sleep_until(std::int64_t deadline_ns) {
    timespec until{static_cast<time_t>(deadline_ns / 1'000'000'000),
                   static_cast<long>(deadline_ns % 1'000'000'000)};
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &until, nullptr) == EINTR) {
    }
}

Result<void> write_all(int fd, const std::vector<std::uint8_t>& data) {
    std::size_t done = 0;
    while (done < data.size()) {
        ssize_t n = ::write(fd, data.data() + done, data.size() - done);
        if (n > 0) {
            done += static_cast<std::size_t>(n);
            continue;
        }
        if (n < 0 && errno == EINTR) continue;
        if (n < 0 && errno == EAGAIN) {
            pollfd descriptor{fd, POLLOUT, 0};
            ::poll(&descriptor, 1, 100);
            continue;
        }
        return Error{fmt::format("write failed after {}: {}", counted(done, "byte", "bytes"),
                                 n < 0 ? std::strerror(errno) : "device closed")};
    }
    return {};
}

}  // namespace

Result<PlayStats> play_telegrams(int fd, const TelegramGenerator& next, bool as_fast_as_possible,
                                 const std::atomic<bool>* stop) {
    PlayStats stats;
    std::vector<std::uint8_t> telegram;
    std::vector<std::uint8_t> batch;
    // Hands the batch to the device; an error ends playing.
    auto hand_over = [&]() -> Result<void> {
        if (batch.empty()) return {};
        Result<void> written = write_all(fd, batch);
        batch.clear();
        return written;
    };
    std::int64_t time = 0;
    std::int64_t first_time = kNoTime;
    const std::int64_t start = monotonic_ns();
    while (!(stop && stop->load()) && next(telegram, time)) {
        if (first_time == kNoTime) first_time = time;
        if (!as_fast_as_possible && time != kNoTime) {
            std::int64_t due = start + (time - first_time);
            if (due > monotonic_ns()) {
                // Hand over what is due before waiting for this one.
                if (Result<void> written = hand_over(); !written) return Error{written.error()};
                sleep_until(due);
            }
            stats.scheduled_ns = time - first_time;
        }
        batch.insert(batch.end(), telegram.begin(), telegram.end());
        ++stats.telegrams;
        stats.bytes += telegram.size();
        if (batch.size() >= kBatchBytes) {
            if (Result<void> written = hand_over(); !written) return Error{written.error()};
        }
    }
    if (Result<void> written = hand_over(); !written) return Error{written.error()};
    stats.wall_ns = monotonic_ns() - start;
    return stats;
}

}  // namespace dpscope
