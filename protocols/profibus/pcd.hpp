// Process data (PCD/PZD) words: the control word (CTW, master -> drive) and status word (STW,
// drive -> master) in PCD 1, the main reference / actual value in PCD 2 (0x4000 = 100 %).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

namespace dpscope {

// profidrive: PROFIdrive STW1/ZSW1 (bits 0..10 standard, 11..15 device-specific); on a Danfoss
//             drive its "PROFIdrive profile" (par. 8-10), which names bits 11..15 too.
// fc:         Danfoss "FC profile" (VLT 5000 par. 512, FC series par. 8-10).
enum class PcdProfile : std::uint8_t { Profidrive, Fc };

std::string_view pcd_profile_name(PcdProfile profile);  // "profidrive", "fc"
std::optional<PcdProfile> pcd_profile_from_name(std::string_view name);

struct WordBit {
    std::string_view when_0;  // meaning when the bit is 0 ("" when it has none)
    std::string_view when_1;  // meaning when the bit is 1
};

using WordBits = std::array<WordBit, 16>;

// The bit meanings of PCD 1. `danfoss` selects the Danfoss names of bits 11..15 in the
// profidrive profile (generic PROFIdrive: "device-specific bit N"); the fc profile is Danfoss's.
const WordBits& control_word_bits(PcdProfile profile, bool danfoss);
const WordBits& status_word_bits(PcdProfile profile, bool danfoss);

// A 16-bit reference or actual value as a percentage: signed, 0x4000 = 100 %, 0xC000 = -100 %.
double reference_percent(std::uint16_t word) noexcept;
// The same percentage in whole hundredths, rounded as "{:.2f}" rounds reference_percent() (to
// nearest, a tie to the even hundredth): the renderers write it with append_hundredths()
// instead of formatting a double (tests/pcd_test.cpp compares all 65,536 words).
std::int32_t reference_percent_hundredths(std::uint16_t word) noexcept;

}  // namespace dpscope
