#include "protocols/vlt2000/vlt2000_codes.hpp"

#include <array>
#include <cmath>

namespace dpscope {

std::string_view vlt2000_letter_name(Vlt2000Letter letter) noexcept {
    switch (letter) {
        case Vlt2000Letter::Update: return "update";
        case Vlt2000Letter::Read: return "read";
        case Vlt2000Letter::Control: return "control";
        case Vlt2000Letter::ReadIndex: return "read index";
        case Vlt2000Letter::Unknown: break;
    }
    return "unknown";
}

double Vlt2000Telegram::value() const noexcept {
    const double whole = static_cast<double>(signed_digits());
    if (!has_decimals || decimals > 5) return whole;
    return whole / std::pow(10.0, decimals);
}

Vlt2000Letter vlt2000_letter_of(std::uint8_t c) noexcept {
    switch (c) {
        case 'U': return Vlt2000Letter::Update;
        case 'R': return Vlt2000Letter::Read;
        case 'C': return Vlt2000Letter::Control;
        case 'I': return Vlt2000Letter::ReadIndex;
        default: return Vlt2000Letter::Unknown;
    }
}

char vlt2000_letter_char(Vlt2000Letter letter) noexcept {
    switch (letter) {
        case Vlt2000Letter::Update: return 'U';
        case Vlt2000Letter::Read: return 'R';
        case Vlt2000Letter::Control: return 'C';
        case Vlt2000Letter::ReadIndex: return 'I';
        case Vlt2000Letter::Unknown: break;
    }
    return '?';
}

std::uint8_t vlt2000_code(Vlt2000Letter letter) noexcept {
    switch (letter) {
        case Vlt2000Letter::Read: return kVlt2000CodeRead;
        case Vlt2000Letter::Update: return kVlt2000CodeUpdate;
        case Vlt2000Letter::Control: return kVlt2000CodeControl;
        case Vlt2000Letter::ReadIndex: return kVlt2000CodeReadIndex;
        case Vlt2000Letter::Unknown: break;
    }
    return 0;
}

Vlt2000Letter vlt2000_letter_of_code(std::uint8_t code) noexcept {
    switch (code) {
        case kVlt2000CodeRead: return Vlt2000Letter::Read;
        case kVlt2000CodeUpdate: return Vlt2000Letter::Update;
        case kVlt2000CodeControl: return Vlt2000Letter::Control;
        case kVlt2000CodeReadIndex: return Vlt2000Letter::ReadIndex;
        default: return Vlt2000Letter::Unknown;
    }
}

namespace {

// Control word: VLT 2000 manual MG.20.B6.02 p. 37 (table "Control word"), VLT 3000 MG.30.A7.02
// p. 75; the names in dpscope's words (docs/protocol/vlt2000.md).
constexpr std::array<Vlt2000Bit, 16> kControlBits{{
    {"OFF1 (ramp stop, relay off)", "ON1", true},
    {"OFF2 (coast, relay off)", "ON2", true},
    {"OFF3 (quick stop, relay off)", "ON3", true},
    {"coast", "coasting possible", true},
    {"quick stop", "ramp (no quick stop)", true},
    {"hold output frequency", "ramp (no hold)", true},
    {"ramp stop", "start", true},
    {"no function", "reset"},
    {"no function", "jog 1"},
    {"no function", "jog 2"},
    {"data not valid: no change", "data valid", true},
    {"no function", "no function"},
    {"no function", "no function"},
    {"set-up select bit 0", "set-up select bit 0"},
    {"set-up select bit 1", "set-up select bit 1"},
    {"no function", "reversing"},
}};

// Status word: VLT 2000 manual p. 56 (table "Status word"); checked against the VLT 3000 example
// (0x0B87: ready, running at reference, warning, out of frequency range) [P:VLT3000 p80].
constexpr std::array<Vlt2000Bit, 16> kStatusBits{{
    {"control not ready", "control ready", true},
    {"VLT not ready", "VLT ready", true},
    {"coasting", "enabled", true},
    {"no trip", "trip"},
    {"no OFF2", "OFF2 active"},
    {"no OFF3", "OFF3 active"},
    {"no trip lock", "trip lock"},
    {"no warning", "warning"},
    {"speed not at reference", "speed at reference"},
    {"local control", "serial communication control"},
    {"out of frequency range", "frequency range OK", true},
    {"not running", "running"},
    {"VLT OK", "stopped, auto start"},
    {"voltage OK", "voltage warning"},
    {"current OK", "current limit"},
    {"timers OK", "thermal warning (timer exceeded)"},
}};

constexpr Vlt2000Bit kNoBit{"", ""};

struct Tables {
    std::array<RequestCode, 16> requests{};
    std::array<ResponseCode, 16> responses{};
};

constexpr Tables make_tables() {
    Tables t;
    t.requests[kVlt2000CodeRead] = RequestCode{"Read (R)", ValueWidth::DoubleWord, true, false};
    t.requests[kVlt2000CodeUpdate] = RequestCode{"Update (U)", ValueWidth::DoubleWord, true, true};
    t.requests[kVlt2000CodeControl] = RequestCode{"Control (C)", ValueWidth::None, true, false};
    t.requests[kVlt2000CodeReadIndex] =
        RequestCode{"Read index (I)", ValueWidth::DoubleWord, true, false};
    t.responses[kVlt2000CodeRead] =
        ResponseCode{"Read reply (R)", ValueWidth::DoubleWord, ResponseKind::Value};
    t.responses[kVlt2000CodeUpdate] =
        ResponseCode{"Update reply (U)", ValueWidth::DoubleWord, ResponseKind::Value};
    t.responses[kVlt2000CodeControl] =
        ResponseCode{"Control reply (C)", ValueWidth::None, ResponseKind::Value};
    t.responses[kVlt2000CodeReadIndex] =
        ResponseCode{"Read index reply (I)", ValueWidth::DoubleWord, ResponseKind::Value};
    t.responses[kVlt2000CodeFailed] = ResponseCode{"Command failed (decimal position 9)",
                                                   ValueWidth::None, ResponseKind::Rejected};
    return t;
}

constexpr Tables kTables = make_tables();

}  // namespace

const Vlt2000Bit& vlt2000_control_bit(unsigned bit) noexcept {
    return bit < kControlBits.size() ? kControlBits[bit] : kNoBit;
}

const Vlt2000Bit& vlt2000_status_bit(unsigned bit) noexcept {
    return bit < kStatusBits.size() ? kStatusBits[bit] : kNoBit;
}

// Reason codes: 00-04 [P:VLT3000 p80], 05-08 and 99 [P:VLT3500 p92] (the VLT 3000 lists the same
// codes); the texts in dpscope's words (docs/protocol/vlt2000.md, "Reply").
std::string_view vlt2000_reason_text(std::uint32_t reason) noexcept {
    switch (reason) {
        case 0: return "parameter does not exist";
        case 1: return "no read/write access";
        case 2: return "index does not exist";
        case 3: return "index read on a parameter without index";
        case 4: return "read only, e.g. factory set-up selected";
        case 5: return "cannot be changed while the motor is running";
        case 6: return "value outside the parameter's range";
        case 7: return "illegal value in byte 19, the decimal position";
        case 8: return "value read is above 99999";
        case 99: return "other fault";
        default: return "";
    }
}

AnswerVerdict vlt2000_judge_answer(std::uint8_t command_code, std::uint8_t reply_code) noexcept {
    if (vlt2000_letter_of_code(command_code) == Vlt2000Letter::Unknown)
        return AnswerVerdict::Invalid;
    if (reply_code == command_code) return AnswerVerdict::Positive;
    if (reply_code == kVlt2000CodeFailed) return AnswerVerdict::Negative;
    return AnswerVerdict::Invalid;
}

const RequestCode& vlt2000_request_code(std::uint8_t code) noexcept {
    return kTables.requests[code & 0x0F];
}

const ResponseCode& vlt2000_response_code(std::uint8_t code) noexcept {
    return kTables.responses[code & 0x0F];
}

}  // namespace dpscope
