// Repairs a mutated telegram so that it passes the checks each protocol makes first (start and
// end characters, lengths, the checksum), so that a decoder target's mutations reach the fields
// behind those checks. The custom mutators of fuzz_profibus_decoder, fuzz_fc_decoder and
// fuzz_vlt2000_decoder call them (DPSCOPE_FUZZ_REPAIRING_MUTATOR); tests/fuzz_repair_test.cpp
// checks that a repaired telegram decodes without a checksum or length problem. Each works on the
// telegram in place, may shorten it or lengthen it (up to `max_size`) and returns its new size
// (new bytes are 0, '0' in a VLT 2000 telegram). Header-only, so it builds in the libFuzzer tree,
// the replay and the tests alike.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace dpscope::fuzz {

namespace repair_detail {

// Makes the telegram exactly `wanted` bytes when `max_size` allows it: cut, or padded with
// `fill`. Returns the size it has then (smaller than `wanted` only when max_size is).
inline std::size_t resize_to(std::uint8_t* data, std::size_t size, std::size_t max_size,
                             std::size_t wanted, std::uint8_t fill = 0) noexcept {
    const std::size_t target = std::min(wanted, max_size);
    if (target > size) std::memset(data + size, fill, target - size);
    return target;
}

// Ends an FDL telegram of `size` bytes whose FCS sums the bytes from `first` to the FCS: the
// FCS, then ED 0x16.
inline void end_fdl_telegram(std::uint8_t* data, std::size_t first, std::size_t size) noexcept {
    std::uint8_t fcs = 0;
    for (std::size_t i = first; i < size - 2; ++i)
        fcs = static_cast<std::uint8_t>(fcs + data[i]);
    data[size - 2] = fcs;
    data[size - 1] = 0x16;
}

}  // namespace repair_detail

// PROFIBUS FDL (protocols/profibus/fdl.hpp). By the first byte: SD2 0x68 gets LE = LEr = the data
// length (size - 6, brought into 4..249), the repeated SD, the FCS (sum of DA..DU mod 256) and ED
// 0x16; SD1 0x10 is made 6 bytes and SD3 0xA2 14, each with its FCS and ED. SD4, SC and a telegram
// with no start delimiter are left as they are.
inline std::size_t repair_fdl_telegram(std::uint8_t* data, std::size_t size,
                                       std::size_t max_size) noexcept {
    if (size == 0) return size;
    std::size_t fixed = 0;
    switch (data[0]) {
        case 0x10: fixed = 6; break;
        case 0xA2: fixed = 14; break;
        case 0x68: {
            // LE counts DA..DU: 4..249 bytes as the parser wants (the framer also takes 3), so
            // the telegram is 10..255.
            const std::size_t wanted = std::clamp<std::size_t>(size, 10, 255);
            size = repair_detail::resize_to(data, size, max_size, wanted);
            if (size < 10) return size;
            const auto le = static_cast<std::uint8_t>(size - 6);
            data[1] = le;
            data[2] = le;
            data[3] = 0x68;
            repair_detail::end_fdl_telegram(data, 4, size);
            return size;
        }
        default: return size;  // SD4, SC, no start delimiter
    }
    size = repair_detail::resize_to(data, size, max_size, fixed);
    if (size < fixed) return size;
    repair_detail::end_fdl_telegram(data, 1, fixed);
    return size;
}

// Danfoss FC (protocols/fc/fc_telegram.hpp): STX 0x02, LGE = size - 2 brought to a block length (6,
// or 10..255: a size of 8 or 12..257; 9..11 bytes become 8), and the BCC (XOR of STX..the last
// data byte). The address byte is left as it is.
inline std::size_t repair_fc_telegram(std::uint8_t* data, std::size_t size,
                                      std::size_t max_size) noexcept {
    std::size_t wanted = std::clamp<std::size_t>(size, 8, 257);
    if (wanted > 8 && wanted < 12) wanted = 8;
    size = repair_detail::resize_to(data, size, max_size, wanted);
    if (size < 8) return size;
    data[0] = 0x02;
    data[1] = static_cast<std::uint8_t>(size - 2);
    std::uint8_t bcc = 0;
    for (std::size_t i = 0; i + 1 < size; ++i)
        bcc ^= data[i];
    data[size - 1] = bcc;
    return size;
}

// VLT 2000 (protocols/vlt2000/vlt2000_telegram.hpp): 22 characters, '<' first, '>' last, and the
// checksum (offsets 19-20: the last two decimal digits of the sum of offsets 1..18) unless it reads
// "??" (not checked). A telegram cut short is padded with '0'; the fields between are left as they
// are, printable or not.
inline std::size_t repair_vlt2000_telegram(std::uint8_t* data, std::size_t size,
                                           std::size_t max_size) noexcept {
    size = repair_detail::resize_to(data, size, max_size, 22, '0');
    if (size < 22) return size;
    data[0] = '<';
    data[21] = '>';
    if (data[19] == '?' && data[20] == '?') return size;
    unsigned sum = 0;
    for (std::size_t i = 1; i < 19; ++i)
        sum += data[i];
    data[19] = static_cast<std::uint8_t>('0' + (sum % 100) / 10);
    data[20] = static_cast<std::uint8_t>('0' + sum % 10);
    return size;
}

}  // namespace dpscope::fuzz
