#include "capture/trigger_recorder.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <ctime>
#include <utility>

namespace dpscope {

namespace {

constexpr std::int64_t kHourNs = 3600LL * 1'000'000'000;
constexpr std::uint64_t kHeldOverhead = 32;  // what a held telegram costs beside its bytes

}  // namespace

TriggerRecorder::TriggerRecorder(TriggerOptions options) : options_(std::move(options)) {}

std::string TriggerRecorder::file_name(const std::string& folder, std::int64_t time_ns,
                                       const TriggerHit& hit) {
    std::string stamp = "notime";
    if (time_ns != kNoTime) {
        const std::time_t seconds = static_cast<std::time_t>(time_ns / 1'000'000'000);
        std::tm utc{};
        gmtime_r(&seconds, &utc);
        char text[32];
        std::strftime(text, sizeof text, "%Y%m%dT%H%M%SZ", &utc);
        stamp = text;
    }
    std::string event;
    for (char c : hit.event)
        event.push_back(
            (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ? c : '_');
    if (event.empty()) event = "match";
    std::string name = fmt::format("trigger-{}-{}", stamp, event);
    if (hit.station >= 0) name += fmt::format("-{}", hit.station);
    const std::string base =
        folder.empty() || folder.back() == '/' ? folder + name : folder + "/" + name;
    return base + ".pcapng";
}

void TriggerRecorder::hold(Bytes telegram, std::int64_t time_ns, std::int64_t record_ns) {
    if (options_.pre_ns <= 0) return;
    pre_.push_back(
        Held{std::vector<std::uint8_t>(telegram.begin(), telegram.end()), time_ns, record_ns});
    pre_bytes_ += telegram.size() + kHeldOverhead;
    // Older than --pre, or over the cap: let go (the cap's are counted).
    while (!pre_.empty() && time_ns != kNoTime && pre_.front().time_ns != kNoTime &&
           time_ns - pre_.front().time_ns > options_.pre_ns) {
        pre_bytes_ -= pre_.front().bytes.size() + kHeldOverhead;
        pre_.pop_front();
    }
    while (pre_bytes_ > options_.max_pre_bytes && pre_.size() > 1) {
        pre_bytes_ -= pre_.front().bytes.size() + kHeldOverhead;
        pre_.pop_front();
        ++stats_.pre_dropped;
    }
}

Result<void> TriggerRecorder::open_window(std::int64_t time_ns, const TriggerHit& hit) {
    const std::string first = file_name(options_.folder, time_ns, hit);
    std::string name = first;
    // A name already there (two windows of one event in one second, a file of an earlier run):
    // the next number, never over a file the user has.
    for (unsigned n = 2; ::access(name.c_str(), F_OK) == 0; ++n)
        name = fmt::format("{}-{}.pcapng", first.substr(0, first.size() - 7), n);
    WriterResult opened = open_capture_writer(name, CaptureFormat::Pcapng, options_.link_type,
                                              options_.bus, options_.line);
    if (!opened) return Error{opened.error()};
    window_ = std::move(opened).value();
    window_name_ = name;
    stats_.files.push_back(name);
    ++stats_.windows;
    // The --pre seconds before the trigger, both ends included.
    for (const Held& h : pre_) {
        if (time_ns != kNoTime && h.time_ns != kNoTime && time_ns - h.time_ns > options_.pre_ns)
            continue;
        if (Result<void> w = window_->write(Bytes(h.bytes.data(), h.bytes.size()), h.record_ns); !w)
            return w;
    }
    pre_.clear();
    pre_bytes_ = 0;
    return {};
}

Result<void> TriggerRecorder::close_window() {
    if (!window_) return {};
    Result<void> closed = window_->close();
    window_.reset();
    window_end_ns_ = kNoTime;
    return closed;
}

Result<void> TriggerRecorder::feed(Bytes telegram, std::int64_t record_ns, const TriggerHit* hit) {
    // A telegram without a time is taken as at the time of the one before (and written as it
    // came, without one).
    std::int64_t time_ns = record_ns == kNoTime ? last_time_ns_ : record_ns;
    if (time_ns != kNoTime) last_time_ns_ = time_ns;
    if (window_ && time_ns != kNoTime && window_end_ns_ != kNoTime && time_ns > window_end_ns_)
        if (Result<void> closed = close_window(); !closed) return closed;
    if (hit) {
        ++stats_.hits;
        if (!window_) {
            while (!starts_.empty() && time_ns != kNoTime && time_ns - starts_.front() >= kHourNs)
                starts_.pop_front();
            if (options_.limit_per_hour > 0 && starts_.size() >= options_.limit_per_hour) {
                ++stats_.suppressed;
                hold(telegram, time_ns, record_ns);
                return {};
            }
            starts_.push_back(time_ns);
            if (Result<void> opened = open_window(time_ns, *hit); !opened) return opened;
        }
        if (time_ns != kNoTime) window_end_ns_ = time_ns + options_.post_ns;
        return window_->write(telegram, record_ns, hit->comment);
    }
    if (window_) return window_->write(telegram, record_ns);
    hold(telegram, time_ns, record_ns);
    return {};
}

Result<void> TriggerRecorder::finish() { return close_window(); }

}  // namespace dpscope
