#include "formats/report_timeline.hpp"

#include <algorithm>

namespace dpscope {

namespace {

std::uint16_t channel_key(std::uint8_t master, std::uint8_t slave) {
    return static_cast<std::uint16_t>((master & 0x7Fu) * 128u + (slave & 0x7Fu));
}

}  // namespace

Timeline::Bin& Timeline::bin(std::int64_t time_ns) {
    if (start_ns_ == kNoTime) start_ns_ = time_ns;
    std::int64_t offset = std::max<std::int64_t>(0, time_ns - start_ns_);
    while (offset / width_ns_ >= static_cast<std::int64_t>(kBins)) {
        // Halve the resolution: merge neighbouring bins.
        for (std::size_t i = 0; i < kBins / 2; ++i) {
            const Bin& a = bins_[2 * i];
            const Bin& b = bins_[2 * i + 1];
            bins_[i] = Bin{a.transactions + b.transactions, a.errors + b.errors,
                           a.warnings + b.warnings, a.notes + b.notes};
        }
        for (std::size_t i = kBins / 2; i < kBins; ++i)
            bins_[i] = Bin{};
        width_ns_ *= 2;
    }
    return bins_[static_cast<std::size_t>(offset / width_ns_)];
}

void Timeline::add_finding(std::int64_t time_ns, Severity severity) {
    Bin& b = bin(time_ns);
    switch (severity) {
        case Severity::Error: ++b.errors; break;
        case Severity::Warning: ++b.warnings; break;
        case Severity::Note: ++b.notes; break;
    }
}

void ChannelTimelines::add(std::span<const Finding> findings,
                           std::span<const CompletedTransaction> transactions) {
    // Everything the tracker reports at one telegram carries that telegram's time, so the order
    // in which it is placed does not matter.
    for (const Finding& f : findings)
        if (f.has_stations && f.time_ns != kNoTime)
            timeline(f.master, f.slave).add_finding(f.time_ns, f.severity);
    for (const CompletedTransaction& transaction : transactions)
        if (transaction.timed)
            timeline(transaction.master, transaction.slave).add_transaction(transaction.time_ns);
}

const Timeline& ChannelTimelines::of(std::uint8_t master, std::uint8_t slave) const {
    static const Timeline kEmpty;
    auto found = timelines_.find(channel_key(master, slave));
    return found == timelines_.end() ? kEmpty : found->second;
}

Timeline& ChannelTimelines::timeline(std::uint8_t master, std::uint8_t slave) {
    return timelines_[channel_key(master, slave)];
}

}  // namespace dpscope
