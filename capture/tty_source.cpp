#include "capture/tty_source.hpp"

#include <fmt/format.h>
#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <ctime>

#include "core/counted.hpp"

namespace dpscope {

namespace {

constexpr std::size_t kReadSize = 1 << 16;
constexpr std::uint64_t kParityReportsShown = 20;

}  // namespace

std::int64_t wall_clock_ns() {
    timespec now{};
    clock_gettime(CLOCK_REALTIME, &now);
    return static_cast<std::int64_t>(now.tv_sec) * 1'000'000'000 + now.tv_nsec;
}

TtySource::TtySource(std::unique_ptr<SerialPort> port, int fd, std::string name,
                     TtySourceOptions options, const FramingRules& rules)
    : FramedSource(std::move(name), rules),
      port_(std::move(port)),
      fd_(fd),
      options_(options),
      character_ns_(character_ns(options.baud, options.character_bits)),
      raw_(kReadSize) {}

FramedSource::Fill TtySource::fill() {
    if (stop_requested_) {
        // Take what the driver still holds, then end.
        bool hangup = false;
        for (int i = 0; i < 64 && read_available(hangup); ++i) {
        }
        return Fill::End;
    }
    // While a telegram is incomplete, wake up exactly when the line has been idle for the gap,
    // so a pause just over it is caught (and a busy moment of ours is never taken for one).
    int timeout_ms = options_.poll_ms;
    if (options_.idle_gap_ns > 0 && !gap_marked_ && pending_bytes() > 0) {
        std::int64_t left = options_.idle_gap_ns - (options_.clock() - last_data_ns_);
        timeout_ms = static_cast<int>(
            std::clamp<std::int64_t>((left + 999'999) / 1'000'000, 0, options_.poll_ms));
    }
    pollfd descriptor{fd_, POLLIN, 0};
    int ready = ::poll(&descriptor, 1, timeout_ms);
    if (ready < 0) {
        if (errno == EINTR) return Fill::Idle;
        set_status(InputStatus::Damaged);
        report(Severity::Error, fmt::format("{}: poll failed: {}", name(), std::strerror(errno)));
        return Fill::End;
    }
    if (ready == 0) {
        std::int64_t now = options_.clock();
        if (options_.idle_gap_ns > 0 && !gap_marked_ &&
            now - last_data_ns_ >= options_.idle_gap_ns) {
            gap_marked_ = true;
            if (pending_bytes() > 0) {
                ++idle_gaps_;
                mark_gap();
            }
        }
        return Fill::Idle;
    }
    bool hangup = false;
    bool got = false;
    if (descriptor.revents & POLLIN) got = read_available(hangup);
    if (hangup || (!got && (descriptor.revents & (POLLHUP | POLLERR | POLLNVAL)))) {
        if (status() != InputStatus::Damaged) {
            set_status(InputStatus::Damaged);
            report(Severity::Error,
                   fmt::format("{}: the device went away (hang-up; unplugged?) after {}", name(),
                               counted(stream_offset_, "byte", "bytes")));
        }
        return Fill::End;
    }
    return got ? Fill::Fed : Fill::Idle;
}

// One non-blocking read. True if bytes came; `hangup` when the device is gone.
bool TtySource::read_available(bool& hangup) {
    ssize_t n = ::read(fd_, raw_.data(), raw_.size());
    if (n > 0) {
        std::int64_t arrival = options_.clock();
        ++reads_;
        unescape_and_feed(raw_.data(), static_cast<std::size_t>(n), arrival);
        last_data_ns_ = arrival;
        gap_marked_ = false;
        return true;
    }
    if (n == 0) {
        hangup = true;  // a tty read returns 0 only after a hang-up
        return false;
    }
    if (errno == EAGAIN || errno == EINTR) return false;
    if (errno == EIO || errno == ENXIO || errno == ENODEV) {
        hangup = true;
        return false;
    }
    if (status() != InputStatus::Damaged) {
        set_status(InputStatus::Damaged);
        report(Severity::Error,
               fmt::format("{}: read error after {}: {}", name(),
                           counted(stream_offset_, "byte", "bytes"), std::strerror(errno)));
    }
    hangup = true;
    return false;
}

void TtySource::unescape_and_feed(const std::uint8_t* data, std::size_t size,
                                  std::int64_t arrival_ns) {
    clean_.clear();
    for (std::size_t i = 0; i < size; ++i) {
        std::uint8_t byte = data[i];
        if (!options_.parity_marked) {
            clean_.push_back(byte);
            continue;
        }
        // PARMRK: FF FF is a real FF; FF 00 X is X received with a parity or framing error.
        switch (escape_) {
            case Escape::None:
                if (byte == 0xFF)
                    escape_ = Escape::SawFF;
                else
                    clean_.push_back(byte);
                break;
            case Escape::SawFF:
                if (byte == 0x00) {
                    escape_ = Escape::SawFF00;
                } else {
                    clean_.push_back(0xFF);
                    if (byte != 0xFF) clean_.push_back(byte);
                    escape_ = Escape::None;
                }
                break;
            case Escape::SawFF00:
                ++parity_errors_;
                if (parity_errors_ <= kParityReportsShown)
                    report(Severity::Warning,
                           fmt::format("{}: {}: parity or framing error (byte 0x{:02X}){}", name(),
                                       where(stream_offset_ + clean_.size()), byte,
                                       parity_errors_ == kParityReportsShown
                                           ? "; further ones are only counted"
                                           : ""));
                clean_.push_back(byte);
                escape_ = Escape::None;
                break;
        }
    }
    if (clean_.empty()) return;
    chunks_.push_back(Chunk{stream_offset_, clean_.size(), arrival_ns});
    stream_offset_ += clean_.size();
    feed(Bytes(clean_.data(), clean_.size()));
    drop_old_chunks();
}

void TtySource::drop_old_chunks() {
    // Keep the chunks that hold bytes the framer has not decided on yet.
    std::uint64_t first_pending = stream_offset_ - pending_bytes();
    while (chunks_.size() > 1 && chunks_.front().start + chunks_.front().length <= first_pending)
        chunks_.pop_front();
}

std::int64_t TtySource::time_at(std::uint64_t offset) {
    std::int64_t time = options_.clock();
    for (auto it = chunks_.rbegin(); it != chunks_.rend(); ++it) {
        if (offset >= it->start) {
            std::uint64_t last = it->start + it->length - 1;
            std::uint64_t behind = last > offset ? last - offset : 0;
            time = it->arrival_ns - static_cast<std::int64_t>(behind) * character_ns_;
            break;
        }
    }
    // The bytes since the previous telegram's start (it and any skipped bytes) were on the wire
    // before this one started: a read that returned late for the earlier bytes, early for these,
    // or a clock set back, never puts two telegrams closer together than that.
    if (last_time_ns_ != kNoTime) {
        std::uint64_t between = offset > last_offset_ ? offset - last_offset_ : 0;
        // Rounded up, so that no rounding puts them closer than the exact wire time (11 bits a
        // byte at options_.baud).
        const double wire_ns =
            std::ceil(static_cast<double>(between) * 11e9 / static_cast<double>(options_.baud));
        std::int64_t earliest =
            last_time_ns_ + std::max<std::int64_t>(1, static_cast<std::int64_t>(wire_ns));
        time = std::max(time, earliest);
    }
    last_time_ns_ = time;
    last_offset_ = offset;
    return time;
}

std::string TtySource::where(std::uint64_t offset) const {
    return fmt::format("byte offset {} of the stream", offset);
}

}  // namespace dpscope
