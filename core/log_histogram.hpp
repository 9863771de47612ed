// A histogram of non-negative integers (latencies in nanoseconds or in bus cycles) whose memory
// does not grow with the number of samples: values below 128 are counted exactly, larger ones in
// 64 steps per power of two, so a percentile read from it is within 1.6 % of the true value.
// Minimum, maximum and count are exact.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <vector>

namespace dpscope {

class LogHistogram {
  public:
    // Inline (a sample per poll cycle, token or answer): a new bucket is made out of line.
    [[gnu::always_inline]] void add(std::uint64_t value) {
        const std::size_t bucket = bucket_of(value);
        if (bucket >= counts_.size()) [[unlikely]]
            grow(bucket);
        ++counts_[bucket];
        min_ = std::min(min_, value);
        max_ = std::max(max_, value);
        ++count_;
    }

    std::uint64_t count() const noexcept { return count_; }
    // 0 when empty.
    std::uint64_t min() const noexcept { return count_ == 0 ? 0 : min_; }
    std::uint64_t max() const noexcept { return max_; }

    // Nearest-rank percentile (p in 0..100): the middle of the bucket holding the sample of rank
    // ceil(p/100 * count), clamped to [min, max]. 0 when empty.
    std::uint64_t percentile(double p) const {
        if (count_ == 0) return 0;
        auto rank = static_cast<std::uint64_t>(p / 100.0 * static_cast<double>(count_) + 0.999999);
        rank = std::clamp<std::uint64_t>(rank, 1, count_);
        std::uint64_t seen = 0;
        for (std::size_t b = 0; b < counts_.size(); ++b) {
            seen += counts_[b];
            if (seen >= rank) {
                std::uint64_t middle = lower_of(b) + (upper_of(b) - lower_of(b)) / 2;
                return std::clamp(middle, min(), max_);
            }
        }
        return max_;
    }

    // Calls f(lower, upper, count) for every non-empty bucket, in increasing order.
    template <typename F>
    void for_each_bucket(F&& f) const {
        for (std::size_t b = 0; b < counts_.size(); ++b)
            if (counts_[b]) f(lower_of(b), upper_of(b), counts_[b]);
    }

    static std::size_t bucket_of(std::uint64_t value) noexcept {
        if (value < kExact) return static_cast<std::size_t>(value);
        int octave = 63 - std::countl_zero(value);  // >= 7
        std::uint64_t sub = (value >> (octave - kSubBits)) & (kSteps - 1);
        return kExact + static_cast<std::size_t>(octave - 7) * kSteps +
               static_cast<std::size_t>(sub);
    }
    static std::uint64_t lower_of(std::size_t bucket) noexcept {
        if (bucket < kExact) return bucket;
        int octave = 7 + static_cast<int>((bucket - kExact) / kSteps);
        std::uint64_t sub = (bucket - kExact) % kSteps;
        return (kSteps + sub) << (octave - kSubBits);
    }
    static std::uint64_t upper_of(std::size_t bucket) noexcept {
        if (bucket < kExact) return bucket;
        int octave = 7 + static_cast<int>((bucket - kExact) / kSteps);
        return lower_of(bucket) + (std::uint64_t{1} << (octave - kSubBits)) - 1;
    }

  private:
    [[gnu::noinline]] void grow(std::size_t bucket) { counts_.resize(bucket + 1, 0); }

    static constexpr int kSubBits = 6;
    static constexpr std::uint64_t kSteps = 64;
    static constexpr std::uint64_t kExact = 128;

    std::vector<std::uint32_t> counts_;
    std::uint64_t count_ = 0;
    std::uint64_t min_ = UINT64_MAX;  // of the samples (none: the greatest value)
    std::uint64_t max_ = 0;
};

}  // namespace dpscope
