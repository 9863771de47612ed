// Tests on eight bytes at once: a word read from the bytes (memcpy, any alignment) is flagged
// when any of its bytes meets the test. A set flag may be a false alarm only for a byte after a
// real one, so "no flag" is exact; callers then look at the flagged word byte by byte. Used where
// every byte of a line is checked: JSON's escape check (formats/json_writer.cpp) and VLT 2000's
// printable characters (protocols/vlt2000/vlt2000_decoder.cpp).
#pragma once

#include <cstdint>
#include <cstring>

namespace dpscope::byte_word {

inline constexpr std::uint64_t kOnes = 0x0101010101010101ULL;
inline constexpr std::uint64_t kHighs = 0x8080808080808080ULL;

// The eight bytes from `p`.
inline std::uint64_t load(const void* p) noexcept {
    std::uint64_t w;
    std::memcpy(&w, p, sizeof w);
    return w;
}
// Some byte is 0x80 or more.
constexpr std::uint64_t any_high(std::uint64_t w) noexcept { return w & kHighs; }
// Some byte is below `n` (n at most 0x80).
constexpr std::uint64_t any_below(std::uint64_t w, std::uint8_t n) noexcept {
    return (w - kOnes * n) & ~w & kHighs;
}
// Some byte equals `c`.
constexpr std::uint64_t any_equal(std::uint64_t w, std::uint8_t c) noexcept {
    return any_below(w ^ (kOnes * c), 1);
}

}  // namespace dpscope::byte_word
