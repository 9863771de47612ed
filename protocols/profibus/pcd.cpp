#include "protocols/profibus/pcd.hpp"

namespace dpscope {

std::string_view pcd_profile_name(PcdProfile profile) {
    return profile == PcdProfile::Fc ? "fc" : "profidrive";
}

std::optional<PcdProfile> pcd_profile_from_name(std::string_view name) {
    if (name == "fc") return PcdProfile::Fc;
    if (name == "profidrive") return PcdProfile::Profidrive;
    return std::nullopt;
}

namespace {

// Danfoss control word, PROFIdrive profile (FC 361 DG, MCA 120, GE AF-650).
constexpr WordBits kDanfossProfidriveControl{{
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
}};

// Danfoss status word, PROFIdrive profile (FC 301 DG, FC 300 DG).
constexpr WordBits kDanfossProfidriveStatus{{
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
}};

// Generic PROFIdrive STW1/ZSW1: bits 0..10 as the Danfoss PROFIdrive profile words (which
// follow the standard there), bits 11..15 device-specific (docs/protocol/process-data.md).
constexpr WordBits with_device_specific_high_bits(WordBits bits) {
    bits[11] = {"device-specific bit 11", "device-specific bit 11"};
    bits[12] = {"device-specific bit 12", "device-specific bit 12"};
    bits[13] = {"device-specific bit 13", "device-specific bit 13"};
    bits[14] = {"device-specific bit 14", "device-specific bit 14"};
    bits[15] = {"device-specific bit 15", "device-specific bit 15"};
    return bits;
}
constexpr WordBits kProfidriveControl = with_device_specific_high_bits(kDanfossProfidriveControl);
constexpr WordBits kProfidriveStatus = with_device_specific_high_bits(kDanfossProfidriveStatus);

// Danfoss control word, FC profile (FC 102 DS, FC 300 PB). Bit 12 names a relay that differs
// between models.
constexpr WordBits kFcControl{{
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
    {"no function", "relay active (model-dependent)"},
    {"set-up select lsb 0", "set-up select lsb 1"},
    {"set-up select msb 0", "set-up select msb 1"},
    {"no function", "reverse"},
}};

// Danfoss status word, FC profile (FC 202 DG, MCA 121).
constexpr WordBits kFcStatus{{
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
}};

}  // namespace

const WordBits& control_word_bits(PcdProfile profile, bool danfoss) {
    if (profile == PcdProfile::Fc) return kFcControl;
    return danfoss ? kDanfossProfidriveControl : kProfidriveControl;
}

const WordBits& status_word_bits(PcdProfile profile, bool danfoss) {
    if (profile == PcdProfile::Fc) return kFcStatus;
    return danfoss ? kDanfossProfidriveStatus : kProfidriveStatus;
}

double reference_percent(std::uint16_t word) noexcept {
    return static_cast<std::int16_t>(word) * 100.0 / 16384.0;
}

std::int32_t reference_percent_hundredths(std::uint16_t word) noexcept {
    // word * 100 / 16384 % is word * 10000 / 16384 = word * 625 / 1024 hundredths, exactly.
    const std::int32_t value = static_cast<std::int16_t>(word);
    const std::int32_t magnitude = (value < 0 ? -value : value) * 625;
    std::int32_t hundredths = magnitude / 1024;
    const std::int32_t rest = magnitude % 1024;
    if (rest > 512 || (rest == 512 && (hundredths & 1) != 0)) ++hundredths;
    return value < 0 ? -hundredths : hundredths;
}

}  // namespace dpscope
