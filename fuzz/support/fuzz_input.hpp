// What the fuzz targets share: a reader that takes choices from the front of an input (never
// failing: past the end every choice is 0), an Output that goes nowhere, and the glue for a custom
// mutator that lets libFuzzer mutate and then repairs what a protocol checks first.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <span>

#include "formats/output.hpp"

namespace dpscope::fuzz {

// Takes choices from the input, front to back. Past the end, every number is 0 and every span
// empty, so a target never needs to check the size first.
class FuzzInput {
  public:
    FuzzInput(const std::uint8_t* data, std::size_t size) noexcept : data_(data), size_(size) {}

    bool empty() const noexcept { return at_ >= size_; }
    std::size_t remaining() const noexcept { return size_ - at_; }

    std::uint8_t byte() noexcept { return at_ < size_ ? data_[at_++] : 0; }
    bool flag() noexcept { return (byte() & 1) != 0; }
    std::uint16_t u16() noexcept {
        const std::uint16_t high = byte();
        return static_cast<std::uint16_t>(high << 8 | byte());
    }
    std::uint32_t u32() noexcept {
        const std::uint32_t high = u16();
        return high << 16 | u16();
    }
    // A number in [low, high] (high >= low).
    std::uint32_t in_range(std::uint32_t low, std::uint32_t high) noexcept {
        const std::uint32_t span = high - low + 1;
        const std::uint32_t raw = span <= 0x100 ? byte() : span <= 0x10000 ? u16() : u32();
        return span == 0 ? raw : low + raw % span;
    }
    // One of `choices`.
    template <typename T, std::size_t N>
    const T& pick(const T (&choices)[N]) noexcept {
        return choices[in_range(0, N - 1)];
    }
    // The next `count` bytes (fewer at the end).
    std::span<const std::uint8_t> bytes(std::size_t count) noexcept {
        const std::size_t n = std::min(count, remaining());
        std::span<const std::uint8_t> out(data_ + at_, n);
        at_ += n;
        return out;
    }
    std::span<const std::uint8_t> rest() noexcept { return bytes(remaining()); }

  private:
    const std::uint8_t* data_;
    std::size_t size_;
    std::size_t at_ = 0;
};

// An Output whose text goes nowhere: targets clear its buffer after each record.
inline Output& null_output() {
    static FILE* sink = std::fopen("/dev/null", "w");
    static Output out{sink};
    return out;
}

}  // namespace dpscope::fuzz

// libFuzzer's own mutator (the replay driver has a stand-in that changes nothing).
extern "C" std::size_t LLVMFuzzerMutate(std::uint8_t* data, std::size_t size, std::size_t max_size);

// Defines the target's custom mutator: libFuzzer mutates, then `repair(data, size, max_size,
// seed)` (returning the new size) makes the input pass the checks in front of the layer (a
// checksum, a length byte), except for one mutation in `keep_broken_one_in`, which keeps its
// damage so that the checks themselves are fuzzed too.
#define DPSCOPE_FUZZ_REPAIRING_MUTATOR(repair, keep_broken_one_in)                            \
    extern "C" std::size_t LLVMFuzzerCustomMutator(std::uint8_t* data, std::size_t size,      \
                                                   std::size_t max_size, unsigned int seed) { \
        size = LLVMFuzzerMutate(data, size, max_size);                                        \
        if ((seed % (keep_broken_one_in)) == 0) return size;                                  \
        return repair(data, size, max_size, seed);                                            \
    }
