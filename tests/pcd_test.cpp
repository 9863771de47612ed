// Process data words: the Danfoss control and status word bit tables for the PROFIdrive profile
// and the FC profile, and reference scaling (docs/protocol/process-data.md).
#include "protocols/profibus/pcd.hpp"

#include <fmt/compile.h>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "formats/text_buffer.hpp"

namespace dpscope {
namespace {

void check_bits(const WordBits& bits, const std::vector<WordBit>& expected) {
    ASSERT_EQ(expected.size(), 16u);
    for (std::size_t bit = 0; bit < 16; ++bit) {
        SCOPED_TRACE("bit " + std::to_string(bit));
        EXPECT_EQ(bits[bit].when_0, expected[bit].when_0);
        EXPECT_EQ(bits[bit].when_1, expected[bit].when_1);
    }
}

TEST(PcdTest, DanfossProfidriveProfileControlWord) {
    check_bits(control_word_bits(PcdProfile::Profidrive, true),
               {
                   {"OFF 1", "ON 1"},
                   {"OFF 2", "ON 2"},
                   {"OFF 3", "ON 3"},
                   {"coasting", "no coasting"},
                   {"quick stop", "ramp"},
                   {"hold frequency output", "use ramp"},
                   {"ramp stop", "start"},
                   {"no function", "reset"},
                   {"jog 1 off", "jog 1 on"},
                   {"jog 2 off", "jog 2 on"},
                   {"data invalid", "data valid"},
                   {"no function", "slow down"},
                   {"no function", "catch up"},
                   {"set-up select lsb 0", "set-up select lsb 1"},
                   {"set-up select msb 0", "set-up select msb 1"},
                   {"no function", "reverse"},
               });
}

TEST(PcdTest, DanfossProfidriveProfileStatusWord) {
    check_bits(status_word_bits(PcdProfile::Profidrive, true),
               {
                   {"control not ready", "control ready"},
                   {"drive not ready", "drive ready"},
                   {"coasting", "enable"},
                   {"no error", "trip"},
                   {"OFF 2", "ON 2"},
                   {"OFF 3", "ON 3"},
                   {"start possible", "start not possible"},
                   {"no warning", "warning"},
                   {"speed != reference", "speed = reference"},
                   {"local operation", "bus control"},
                   {"out of frequency limit", "frequency limit OK"},
                   {"no operation", "in operation"},
                   {"drive OK", "stopped, auto start"},
                   {"voltage OK", "voltage exceeded"},
                   {"torque OK", "torque exceeded"},
                   {"timer OK", "timer exceeded"},
               });
}

TEST(PcdTest, FcProfileControlWord) {
    check_bits(control_word_bits(PcdProfile::Fc, true),
               {
                   {"reference select lsb 0", "reference select lsb 1"},
                   {"reference select msb 0", "reference select msb 1"},
                   {"DC brake", "ramp"},
                   {"coasting", "no coasting"},
                   {"quick stop", "ramp"},
                   {"hold output frequency", "use ramp"},
                   {"ramp stop", "start"},
                   {"no function", "reset"},
                   {"no function", "jog"},
                   {"ramp 1", "ramp 2"},
                   {"data invalid", "data valid"},
                   {"no function", "relay 01 active"},
                   // contradictions.md #16: relay 02 or relay 04 depending on the model.
                   {"no function", "relay active (model-dependent)"},
                   {"set-up select lsb 0", "set-up select lsb 1"},
                   {"set-up select msb 0", "set-up select msb 1"},
                   {"no function", "reverse"},
               });
}

TEST(PcdTest, FcProfileStatusWord) {
    check_bits(status_word_bits(PcdProfile::Fc, true),
               {
                   {"control not ready", "control ready"},
                   {"drive not ready", "drive ready"},
                   {"coasting", "enable"},
                   {"no error", "trip"},
                   {"no error", "error (no trip)"},
                   {"reserved", "reserved"},
                   {"no error", "trip lock"},
                   {"no warning", "warning"},
                   {"speed != reference", "speed = reference"},
                   {"local operation", "bus control"},
                   {"out of frequency limit", "frequency limit OK"},
                   {"no operation", "in operation"},
                   {"drive OK", "stopped, auto start"},
                   {"voltage OK", "voltage exceeded"},
                   {"torque OK", "torque exceeded"},
                   {"timer OK", "timer exceeded"},
               });
}

TEST(PcdTest, ProfilesDifferWhereTheManualsDiffer) {
    // Bit 0 of the control word: ON 1 (PROFIdrive) vs reference select (FC).
    EXPECT_NE(control_word_bits(PcdProfile::Profidrive, true)[0].when_1,
              control_word_bits(PcdProfile::Fc, true)[0].when_1);
    // Bit 4 of the status word: ON 2 (PROFIdrive) vs error without trip (FC).
    EXPECT_EQ(status_word_bits(PcdProfile::Profidrive, true)[4].when_1, "ON 2");
    EXPECT_EQ(status_word_bits(PcdProfile::Fc, true)[4].when_1, "error (no trip)");
    // Bit 10 "data valid" is common to both control words.
    EXPECT_EQ(control_word_bits(PcdProfile::Profidrive, true)[10].when_1, "data valid");
    EXPECT_EQ(control_word_bits(PcdProfile::Fc, true)[10].when_1, "data valid");
}

// Generic PROFIdrive (docs/protocol/process-data.md): bits 0..10 are the profile's, bits 11..15
// of STW1 and ZSW1 are device-specific and get no Danfoss names.
TEST(PcdTest, GenericProfidriveHighBitsAreDeviceSpecific) {
    for (const WordBits* bits : {&control_word_bits(PcdProfile::Profidrive, false),
                                 &status_word_bits(PcdProfile::Profidrive, false)}) {
        for (std::size_t bit = 11; bit < 16; ++bit) {
            SCOPED_TRACE("bit " + std::to_string(bit));
            std::string expected = "device-specific bit " + std::to_string(bit);
            EXPECT_EQ((*bits)[bit].when_0, expected);
            EXPECT_EQ((*bits)[bit].when_1, expected);
        }
    }
    // Bits 0..10 are the same as in the Danfoss PROFIdrive profile.
    for (std::size_t bit = 0; bit < 11; ++bit) {
        SCOPED_TRACE("bit " + std::to_string(bit));
        EXPECT_EQ(control_word_bits(PcdProfile::Profidrive, false)[bit].when_1,
                  control_word_bits(PcdProfile::Profidrive, true)[bit].when_1);
        EXPECT_EQ(status_word_bits(PcdProfile::Profidrive, false)[bit].when_0,
                  status_word_bits(PcdProfile::Profidrive, true)[bit].when_0);
    }
    EXPECT_EQ(control_word_bits(PcdProfile::Profidrive, false)[10].when_1, "data valid");
    EXPECT_EQ(control_word_bits(PcdProfile::Profidrive, true)[11].when_1, "slow down");
    EXPECT_EQ(status_word_bits(PcdProfile::Profidrive, true)[15].when_1, "timer exceeded");
}

TEST(PcdTest, FcProfileIsDanfossWhateverTheFlag) {
    EXPECT_EQ(&control_word_bits(PcdProfile::Fc, false), &control_word_bits(PcdProfile::Fc, true));
    EXPECT_EQ(&status_word_bits(PcdProfile::Fc, false), &status_word_bits(PcdProfile::Fc, true));
}

TEST(PcdTest, ReferencePercentScaling) {
    EXPECT_DOUBLE_EQ(reference_percent(0x4000), 100.0);
    EXPECT_DOUBLE_EQ(reference_percent(0x2000), 50.0);
    EXPECT_DOUBLE_EQ(reference_percent(0xC000), -100.0);
    EXPECT_DOUBLE_EQ(reference_percent(0x0000), 0.0);
    EXPECT_DOUBLE_EQ(reference_percent(0xE000), -50.0);
    EXPECT_DOUBLE_EQ(reference_percent(0x1000), 25.0);
}

TEST(PcdTest, ReferencePercentExtremes) {
    EXPECT_DOUBLE_EQ(reference_percent(0x8000), -200.0);
    EXPECT_DOUBLE_EQ(reference_percent(0x7FFF), 32767 * 100.0 / 16384.0);
    EXPECT_DOUBLE_EQ(reference_percent(0xFFFF), -100.0 / 16384.0);
    EXPECT_DOUBLE_EQ(reference_percent(0x0001), 100.0 / 16384.0);
}

// The renderers write the percentage from whole hundredths (issue 31): for every word, the text
// is the text "{:.2f}" gives for the double, ties to the even hundredth (0x0200 is 3.125 %:
// "3.12") and negative values included.
TEST(PcdTest, ReferencePercentHundredthsWriteAsTwoDecimalsOfTheDouble) {
    for (std::uint32_t word = 0; word <= 0xFFFF; ++word) {
        const auto w = static_cast<std::uint16_t>(word);
        TextBuffer out;
        append_hundredths(out, reference_percent_hundredths(w));
        ASSERT_EQ(fmt::to_string(out), fmt::format(FMT_COMPILE("{:.2f}"), reference_percent(w)))
            << "word 0x" << std::hex << word;
    }
    EXPECT_EQ(reference_percent_hundredths(0x0200), 312);
    EXPECT_EQ(reference_percent_hundredths(0x0600), 938);
    EXPECT_EQ(reference_percent_hundredths(0xFE00), -312);
}

TEST(PcdTest, ProfileNames) {
    EXPECT_EQ(pcd_profile_name(PcdProfile::Profidrive), "profidrive");
    EXPECT_EQ(pcd_profile_name(PcdProfile::Fc), "fc");
    EXPECT_EQ(pcd_profile_from_name("profidrive"), PcdProfile::Profidrive);
    EXPECT_EQ(pcd_profile_from_name("fc"), PcdProfile::Fc);
    EXPECT_EQ(pcd_profile_from_name("FC"), std::nullopt);
    EXPECT_EQ(pcd_profile_from_name("vlt"), std::nullopt);
    EXPECT_EQ(pcd_profile_from_name(""), std::nullopt);
}

}  // namespace
}  // namespace dpscope
