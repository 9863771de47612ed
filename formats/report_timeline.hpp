// The timelines of the HTML report: per channel, transactions and findings over time. Built
// telegram by telegram from what the session tracker reports at each (its findings and the
// transactions it completed), by whoever feeds the tracker (cli/pipeline.hpp).
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <span>

#include "core/finding.hpp"
#include "core/parameter_channel_engine.hpp"
#include "core/time.hpp"

namespace dpscope {

// Events over time in a fixed number of bins whose width doubles as the capture grows.
class Timeline {
  public:
    static constexpr std::size_t kBins = 240;
    struct Bin {
        std::uint32_t transactions = 0;
        std::uint32_t errors = 0;
        std::uint32_t warnings = 0;
        std::uint32_t notes = 0;
    };

    void add_transaction(std::int64_t time_ns) { bin(time_ns).transactions++; }
    void add_finding(std::int64_t time_ns, Severity severity);

    bool empty() const noexcept { return start_ns_ == kNoTime; }
    std::int64_t start_ns() const noexcept { return start_ns_; }
    std::int64_t bin_width_ns() const noexcept { return width_ns_; }
    const std::array<Bin, kBins>& bins() const noexcept { return bins_; }

  private:
    Bin& bin(std::int64_t time_ns);

    std::int64_t start_ns_ = kNoTime;
    std::int64_t width_ns_ = 10'000'000;  // 10 ms to begin with
    std::array<Bin, kBins> bins_{};
};

// The timeline of each (master, slave) channel. A transaction is placed at its answer when its
// latency is known (both telegrams carry a time); a finding naming its stations at its time.
class ChannelTimelines {
  public:
    // What the tracker reported at one telegram (or at the end of the capture).
    void add(std::span<const Finding> findings, std::span<const CompletedTransaction> transactions);
    // The channel's timeline; an empty one when nothing happened on it.
    const Timeline& of(std::uint8_t master, std::uint8_t slave) const;

  private:
    Timeline& timeline(std::uint8_t master, std::uint8_t slave);

    std::map<std::uint16_t, Timeline> timelines_;  // master * 128 + slave
};

}  // namespace dpscope
