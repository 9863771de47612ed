#include "cli/progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <charconv>
#include <chrono>
#include <cstdlib>
#include <cstring>

namespace dpscope::cli {

namespace {

// The meter whose line is on the screen, if any.
ProgressMeter* g_shown_line = nullptr;

std::int64_t steady_now_ns() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

}  // namespace

std::string progress_bytes_text(std::uint64_t bytes) {
    constexpr std::uint64_t kKiB = 1024;
    if (bytes < kKiB) return fmt::format("{} B", bytes);
    if (bytes < kKiB * kKiB) return fmt::format("{} KiB", bytes / kKiB);
    const double b = static_cast<double>(bytes);
    if (bytes < kKiB * kKiB * kKiB) return fmt::format("{:.1f} MiB", b / (1024.0 * 1024.0));
    return fmt::format("{:.1f} GiB", b / (1024.0 * 1024.0 * 1024.0));
}

std::string progress_eta_text(std::int64_t seconds) {
    if (seconds < 0) return "?";
    const std::int64_t h = seconds / 3600, m = seconds / 60 % 60, s = seconds % 60;
    if (h > 0) return fmt::format("{}:{:02}:{:02}", h, m, s);
    return fmt::format("{}:{:02}", m, s);
}

std::string progress_line(std::uint64_t bytes, std::uint64_t total, std::uint64_t telegrams,
                          std::int64_t elapsed_ns) {
    if (bytes > total) bytes = total;
    const unsigned percent = total == 0 ? 0
                                        : static_cast<unsigned>(static_cast<double>(bytes) * 100.0 /
                                                                static_cast<double>(total));
    const double seconds = static_cast<double>(elapsed_ns) / 1e9;
    const double rate = seconds > 0 ? static_cast<double>(telegrams) / seconds : 0.0;
    std::int64_t eta = -1;
    if (seconds > 0 && bytes > 0)
        eta = static_cast<std::int64_t>(
            static_cast<double>(total - bytes) * seconds / static_cast<double>(bytes) + 0.5);
    const std::string rate_text = rate >= 1e6   ? fmt::format("{:.2f} M ", rate / 1e6)
                                  : rate >= 1e3 ? fmt::format("{:.1f} k ", rate / 1e3)
                                                : fmt::format("{:.0f} ", rate);
    return fmt::format("dpscope: {} of {} ({} %), {}telegrams/s, ETA {}",
                       progress_bytes_text(bytes), progress_bytes_text(total), percent, rate_text,
                       progress_eta_text(eta));
}

std::uint64_t progress_min_bytes() {
    const char* text = std::getenv("DPSCOPE_PROGRESS_MIN_BYTES");
    if (text == nullptr || *text == '\0') return kProgressMinBytes;
    std::uint64_t value = 0;
    const char* end = text + std::strlen(text);
    auto [stop, error] = std::from_chars(text, end, value);
    return error == std::errc() && stop == end ? value : kProgressMinBytes;
}

ProgressMeter::ProgressMeter(std::uint64_t total, bool shown, Writer write, Clock clock)
    : total_(total),
      shown_(shown),
      write_(std::move(write)),
      clock_(clock ? std::move(clock) : Clock(steady_now_ns)) {
    start_ns_ = shown_ ? clock_() : 0;
    last_draw_ns_ = start_ns_ - kProgressRefreshNs;  // the first check draws the line
}

ProgressMeter ProgressMeter::for_source(const TelegramSource& source, bool allowed) {
    const std::uint64_t total = source.input_size();
    const bool shown =
        allowed && total > 0 && total >= progress_min_bytes() && ::isatty(STDERR_FILENO) != 0;
    return ProgressMeter(total, shown, [](std::string_view text) {
        std::fwrite(text.data(), 1, text.size(), stderr);
        std::fflush(stderr);
    });
}

ProgressMeter::~ProgressMeter() { clear(); }

void ProgressMeter::update(std::uint64_t bytes) {
    if (!shown_) return;
    const std::int64_t now = clock_();
    if (now - last_draw_ns_ < kProgressRefreshNs) return;
    last_draw_ns_ = now;
    std::string line = progress_line(bytes, total_, telegrams_, now - start_ns_);
    const std::size_t length = line.size();
    // Spaces over what is left of a longer line before.
    if (length < drawn_) line.append(drawn_ - length, ' ');
    write_("\r" + line);
    drawn_ = length > drawn_ ? length : drawn_;
    g_shown_line = this;
}

void ProgressMeter::clear() {
    if (g_shown_line == this) g_shown_line = nullptr;
    if (drawn_ == 0) return;
    write_("\r" + std::string(drawn_, ' ') + "\r");
    drawn_ = 0;
}

void clear_progress_line() {
    if (g_shown_line != nullptr) g_shown_line->clear();
}

}  // namespace dpscope::cli
