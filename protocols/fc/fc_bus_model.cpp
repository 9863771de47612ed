#include "protocols/fc/fc_bus_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <memory>

#include "core/protocol_descriptor.hpp"
#include "protocols/fc/fc_framing_rules.hpp"
#include "simulator/simulator.hpp"

namespace dpscope {

namespace {

template <typename T>
bool parse_number(std::string_view text, T& value) {
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    return ec == std::errc() && end == text.data() + text.size();
}

void put_u16(std::vector<std::uint8_t>& out, std::uint16_t value) {
    out.push_back(static_cast<std::uint8_t>(value >> 8));
    out.push_back(static_cast<std::uint8_t>(value));
}

// The AK codes [S001].
constexpr std::uint8_t kRead = 1, kWriteWord = 2, kWriteDouble = 3, kWriteDoubleEeprom = 13,
                       kWriteWordEeprom = 14, kText = 15;
constexpr std::uint8_t kValueWord = 1, kValueDouble = 2, kRejected = 7;
// AK 7 fault codes [S001].
constexpr std::uint32_t kCannotBeChanged = 1, kLimitExceeded = 2, kNotWhileRunning = 17;

constexpr std::uint16_t kControlWord = 0x047F;  // FC profile: ramp, start, data valid

// The drive's parameters the master touches (FC 302 numbering, PNU = x * 100 + yy).
constexpr std::uint16_t kSpeedHighLimit = 414;    // 4-14 Motor Speed High Limit [0.1 Hz], word
constexpr std::uint16_t kMotorFrequency = 123;    // 1-23 Motor Frequency [Hz], word
constexpr std::uint16_t kRampUp = 341;            // 3-41 Ramp 1 Ramp Up Time [0.01 s], double
constexpr std::uint16_t kRampDown = 342;          // 3-42 Ramp 1 Ramp Down Time [0.01 s], double
constexpr std::uint16_t kFrequency = 1613;        // 16-13 Frequency [0.1 Hz], read-only word
constexpr std::uint16_t kMotorCurrent = 1614;     // 16-14 Motor Current [0.01 A], read-only double
constexpr std::uint16_t kDcLinkVoltage = 1630;    // 16-30 DC Link Voltage [V], read-only word
constexpr std::uint16_t kAlarmLogCode = 1530;     // 15-30 Alarm Log: Error Code, 10 elements
constexpr std::uint16_t kFcType = 1540;           // 15-40 FC Type, text
constexpr std::uint16_t kSoftwareVersion = 1543;  // 15-43 Software Version, text
constexpr std::uint16_t kOrderingNumber = 1546;   // 15-46 Frequency Converter Ordering No, text

constexpr std::uint16_t kAlarmLog[10] = {14, 0, 13, 0, 4, 0, 0, 7, 0, 0};

bool is_word_write(std::uint8_t ak) { return ak == kWriteWord || ak == kWriteWordEeprom; }
bool is_double_write(std::uint8_t ak) { return ak == kWriteDouble || ak == kWriteDoubleEeprom; }

}  // namespace

Result<SimulatedDrive> parse_drive_spec(std::string_view text) {
    SimulatedDrive drive;
    auto colon = text.find(':');
    std::string_view address_text = text.substr(0, colon);
    if (colon != std::string_view::npos) {
        std::string_view format = text.substr(colon + 1);
        if (format == "1-31")
            drive.format = FcAddressFormat::Short;
        else if (format != "1-126")
            return Error{fmt::format("{}: the address format must be 1-126 or 1-31", text)};
    }
    unsigned address = 0;
    const unsigned highest = drive.format == FcAddressFormat::Short ? 31 : 126;
    if (!parse_number(address_text, address) || address < 1 || address > highest)
        return Error{fmt::format("{}: the address must be from 1 to {} in the {} format", text,
                                 highest, fc_address_format_name(drive.format))};
    drive.address = static_cast<std::uint8_t>(address);
    return drive;
}

std::uint8_t fc_adr_of(const SimulatedDrive& drive) noexcept {
    return drive.format == FcAddressFormat::Long ? static_cast<std::uint8_t>(0x80 | drive.address)
                                                 : static_cast<std::uint8_t>(drive.address & 0x1F);
}

std::vector<SimulatedDrive> default_drives() {
    return {{1, FcAddressFormat::Long}, {2, FcAddressFormat::Long}, {3, FcAddressFormat::Short}};
}

bool fault_applies_to_fc(FaultKind kind) noexcept {
    return fault_applies_to_bus(kind, Protocol::Fc);
}

Result<void> check_fc_faults(const std::vector<FaultSpec>& faults,
                             const std::vector<SimulatedDrive>& drives, std::uint64_t cycles) {
    for (const FaultSpec& spec : faults) {
        if (!fault_applies_to_fc(spec.kind))
            return Error{fmt::format(
                "fault {}: {} fault; an FC bus takes the fc_* faults, garbage and "
                "malformed_telegram",
                describe_fault(spec),
                protocol_descriptor(fault_bus(spec.kind)).capture_noun)};
        if (spec.slave && std::none_of(drives.begin(), drives.end(), [&](const SimulatedDrive& d) {
                return d.address == *spec.slave;
            }))
            return Error{fmt::format("fault {}: drive {} is not simulated", describe_fault(spec),
                                     *spec.slave)};
        if (spec.cycle && cycles != 0 && *spec.cycle >= cycles)
            return Error{fmt::format("fault {}: cycle {} is past the session's {} cycles (0..{})",
                                     describe_fault(spec), *spec.cycle, cycles, cycles - 1)};
    }
    return {};
}

std::vector<std::uint8_t> build_fc_telegram(std::uint8_t adr,
                                            const std::vector<std::uint8_t>& data) {
    std::vector<std::uint8_t> out;
    out.reserve(data.size() + 4);
    out.push_back(kFcStx);
    out.push_back(static_cast<std::uint8_t>(data.size() + 2));
    out.push_back(adr);
    out.insert(out.end(), data.begin(), data.end());
    out.push_back(fc_bcc_of(Bytes(out.data(), out.size())));
    return out;
}

FcBusModel::FcBusModel(std::vector<SimulatedDrive> drives) : drives_(std::move(drives)) {
    for (const SimulatedDrive& config : drives_) {
        Drive drive;
        drive.config = config;
        drive.adr = fc_adr_of(config);
        state_.push_back(drive);
    }
}

std::int64_t FcBusModel::between(BusEnvironment& env, std::int64_t low, std::int64_t high) {
    return low + static_cast<std::int64_t>(env.random(static_cast<std::uint64_t>(high - low) + 1));
}

void FcBusModel::cycle(BusEnvironment& env, std::uint64_t number) {
    for (std::size_t i = 0; i < state_.size(); ++i)
        poll(env, i);
    if (number % 50 == 49) broadcast(env, number);
}

void FcBusModel::broadcast(BusEnvironment& env, std::uint64_t number) {
    // A broadcast process block (1-126 format, ADR 0x80) or a word write of 1-23 to every drive
    // (1-31 format, bit 5: ADR 0x20). Nobody answers.
    std::vector<std::uint8_t> data;
    std::uint8_t adr = 0x80;
    if ((number / 50) % 2 == 1) {
        adr = 0x20;
        const std::uint16_t frequency = env.random(2) == 0 ? 50 : 60;
        put_u16(data, static_cast<std::uint16_t>(kWriteWord << 12 | kMotorFrequency));
        put_u16(data, 0);
        put_u16(data, 0);
        put_u16(data, frequency);
        for (Drive& drive : state_)
            drive.motor_frequency = frequency;
    }
    put_u16(data, kControlWord);
    put_u16(data, state_.empty() ? 0x2000 : state_.front().reference);
    env.send(build_fc_telegram(adr, data), between(env, kMasterGapMinNs, kMasterGapMaxNs));
}

FcBusModel::Command FcBusModel::plan(BusEnvironment& env) {
    const std::uint64_t roll = env.random(100);
    Command c;
    c.parameter = true;
    if (roll < 55 || roll >= 94) {
        c.parameter = false;
    } else if (roll < 65) {
        static constexpr std::uint16_t kWords[] = {kSpeedHighLimit, kMotorFrequency, kFrequency,
                                                   kDcLinkVoltage};
        c.ak = kRead;
        c.pnu = kWords[env.random(std::size(kWords))];
    } else if (roll < 70) {
        static constexpr std::uint16_t kDoubles[] = {kRampUp, kRampDown, kMotorCurrent};
        c.ak = kRead;
        c.pnu = kDoubles[env.random(std::size(kDoubles))];
    } else if (roll < 74) {
        c.ak = kRead;
        c.pnu = kAlarmLogCode;
        c.index = static_cast<std::uint8_t>(env.random(10));
    } else if (roll < 81) {
        c.ak = env.random(2) == 0 ? kWriteWord : kWriteWordEeprom;
        if (env.random(2) == 0) {
            c.pnu = kSpeedHighLimit;
            c.pwe = static_cast<std::uint32_t>(400 + env.random(21) * 10);
        } else {
            c.pnu = kMotorFrequency;
            c.pwe = env.random(2) == 0 ? 50 : 60;
        }
    } else if (roll < 87) {
        c.ak = env.random(2) == 0 ? kWriteDouble : kWriteDoubleEeprom;
        c.pnu = env.random(2) == 0 ? kRampUp : kRampDown;
        c.pwe = static_cast<std::uint32_t>(100 + env.random(91) * 10);
    } else if (roll < 92) {
        static constexpr std::uint16_t kTexts[] = {kFcType, kSoftwareVersion, kOrderingNumber};
        c.ak = kText;
        c.pnu = kTexts[env.random(std::size(kTexts))];
        c.ind_high = kFcTextRead;
    } else {
        // A write the drive refuses: a read-only parameter, or a value past the limit.
        c.ak = kWriteWordEeprom;
        if (roll == 92) {
            c.pnu = kFrequency;
            c.pwe = 500;
        } else {
            c.pnu = kSpeedHighLimit;
            c.pwe = 9000;
        }
    }
    return c;
}

FcBusModel::Answer FcBusModel::perform(Drive& drive, const Command& command) {
    Answer a;
    a.pnu = command.pnu;
    a.index = command.index;
    a.ind_high = command.ind_high;
    auto reject = [&](std::uint32_t code) {
        a.ak = kRejected;
        a.pwe = code;
        return a;
    };
    const std::uint32_t frequency = std::uint32_t{drive.actual} * 500 / 0x4000;
    switch (command.pnu) {
        case kSpeedHighLimit:
        case kMotorFrequency: {
            std::uint32_t& value =
                command.pnu == kSpeedHighLimit ? drive.speed_limit : drive.motor_frequency;
            if (is_word_write(command.ak)) {
                const std::uint32_t high = command.pnu == kSpeedHighLimit ? 5000 : 1000;
                if (command.pwe > high) return reject(kLimitExceeded);
                value = command.pwe;
            }
            a.ak = kValueWord;
            a.pwe = value;
            return a;
        }
        case kRampUp:
        case kRampDown: {
            std::uint32_t& value = command.pnu == kRampUp ? drive.ramp_up : drive.ramp_down;
            if (is_double_write(command.ak)) {
                if (command.pwe < 1 || command.pwe > 360000) return reject(kLimitExceeded);
                value = command.pwe;
            }
            a.ak = kValueDouble;
            a.pwe = value;
            return a;
        }
        case kFrequency:
        case kDcLinkVoltage:
        case kMotorCurrent:
        case kAlarmLogCode: {
            if (command.ak != kRead) return reject(kCannotBeChanged);
            a.ak = command.pnu == kMotorCurrent ? kValueDouble : kValueWord;
            a.pwe = command.pnu == kFrequency       ? frequency
                    : command.pnu == kDcLinkVoltage ? 560 + drive.actual % 7
                    : command.pnu == kMotorCurrent  ? 150 + frequency * 3
                                                    : kAlarmLog[command.index % 10];
            return a;
        }
        case kFcType:
        case kSoftwareVersion:
        case kOrderingNumber:
            a.ak = kText;
            a.text = command.pnu == kFcType            ? "FC-302"
                     : command.pnu == kSoftwareVersion ? "05.11"
                                                       : "131B0002";
            return a;
        default: return reject(0);  // illegal parameter number
    }
}

std::vector<std::uint8_t> FcBusModel::request_bytes(const Drive& drive,
                                                    const Command& command) const {
    std::vector<std::uint8_t> data;
    data.reserve(12);
    if (command.parameter) {
        put_u16(data, static_cast<std::uint16_t>(command.ak << 12 | (command.pnu & 0x0FFF)));
        data.push_back(command.ind_high);
        data.push_back(command.index);
        put_u16(data, static_cast<std::uint16_t>(command.pwe >> 16));
        put_u16(data, static_cast<std::uint16_t>(command.pwe));
    }
    put_u16(data, kControlWord);
    put_u16(data, drive.reference);
    return build_fc_telegram(drive.adr, data);
}

std::vector<std::uint8_t> FcBusModel::response_bytes(const Drive& drive, const Command& command,
                                                     const Answer& answer) const {
    std::vector<std::uint8_t> data;
    data.reserve(12 + answer.text.size());
    if (command.parameter) {
        put_u16(data, static_cast<std::uint16_t>(answer.ak << 12 | (answer.pnu & 0x0FFF)));
        data.push_back(answer.ind_high);
        data.push_back(answer.index);
        if (answer.ak == kText) {
            data.insert(data.end(), answer.text.begin(), answer.text.end());
        } else {
            put_u16(data, static_cast<std::uint16_t>(answer.pwe >> 16));
            put_u16(data, static_cast<std::uint16_t>(answer.pwe));
        }
    }
    put_u16(data, drive.actual == drive.reference ? 0x0F07 : 0x0E07);
    put_u16(data, drive.actual);
    return build_fc_telegram(drive.adr, data);
}

void FcBusModel::poll(BusEnvironment& env, std::size_t index) {
    Drive& drive = state_[index];
    if (env.inject(FaultKind::Garbage, index)) {
        // Noise on the line: no byte is an STX, so no telegram starts inside it.
        std::vector<std::uint8_t> junk(3 + env.random(10));
        for (std::uint8_t& b : junk) {
            b = static_cast<std::uint8_t>(env.random(256));
            if (b == kFcStx) b = 0xFF;
        }
        env.send(std::move(junk), between(env, kMasterGapMinNs, kMasterGapMaxNs));
    }
    Command command = plan(env);
    env.send(request_bytes(drive, command), between(env, kMasterGapMinNs, kMasterGapMaxNs));
    if (env.inject(FaultKind::FcStackedRequest, index)) {
        // Before the drive had time to answer, the master sends another command to it: a word
        // write to RAM and EEPROM (AK 14, which only a command has). The drive answers that one.
        Command second;
        second.parameter = true;
        second.ak = kWriteWordEeprom;
        second.pnu = kSpeedHighLimit;
        second.pwe = drive.speed_limit;
        env.send(request_bytes(drive, second), between(env, 500'000, 1'000'000));
        command = second;
    }

    bool answered = true;
    if (env.inject(FaultKind::FcNoResponse, index)) {
        answered = false;
        env.wait(kMasterTimeoutNs);
        // The master moves on to the next drive; with only one drive on the bus it sends a
        // broadcast first, so that its next poll of the drive is not read as the answer.
        if (state_.size() == 1) broadcast(env, 49);
    }
    if (answered) {
        Answer answer = perform(drive, command);
        if (command.parameter) {
            if (env.inject(FaultKind::FcMismatchedResponse, index)) {
                if (command.pnu == kAlarmLogCode)
                    answer.index = static_cast<std::uint8_t>((answer.index + 1) % 10);
                else
                    answer.pnu = static_cast<std::uint16_t>(answer.pnu + 1);
            } else if (answer.ak != kRejected &&
                       (is_word_write(command.ak) || is_double_write(command.ak) ||
                        command.ak == kText) &&
                       env.inject(FaultKind::FcUnexpectedResponseType, index)) {
                // A word write answered with a double word, a double-word write with a word, a
                // text read with a value.
                answer.ak = is_word_write(command.ak) ? kValueDouble : kValueWord;
                answer.ind_high = 0;
                answer.pwe = command.pwe;
            } else if (answer.ak != kRejected && env.inject(FaultKind::FcCommandRejected, index)) {
                answer = Answer{kRejected, command.pnu, 0, command.index, kNotWhileRunning, {}};
            }
        }
        const std::int64_t gap = env.inject(FaultKind::FcLateResponse, index)
                                     ? between(env, kLateResponseMinNs, kLateResponseMaxNs)
                                     : between(env, kResponseMinNs, kResponseMaxNs);
        std::vector<std::uint8_t> bytes = response_bytes(drive, command, answer);
        if (env.inject(FaultKind::FcBccError, index)) {
            bytes.back() ^= 0x5A;
        } else if (env.inject(FaultKind::MalformedTelegram, index)) {
            // Cut short: the line went quiet after the first few bytes (at least STX LGE ADR).
            bytes.resize(bytes.size() - 2 - env.random(3));
        }
        env.send(std::move(bytes), gap);
    }

    // Process data: the drive ramps toward the reference; the reference moves now and then.
    if (drive.actual < drive.reference)
        drive.actual =
            static_cast<std::uint16_t>(std::min<int>(drive.reference, drive.actual + 0x400));
    if (drive.actual > drive.reference)
        drive.actual =
            static_cast<std::uint16_t>(std::max<int>(drive.reference, drive.actual - 0x400));
    if (env.random(40) == 0) {
        static constexpr std::uint16_t kReferences[] = {0x1000, 0x2000, 0x3000, 0x4000};
        drive.reference = kReferences[env.random(std::size(kReferences))];
    }
}

// The FC bus in the simulated session (simulator/bus_model.hpp).
namespace {

std::vector<SimulatedDrive> fc_drives_or_default(const SimulatorOptions& options) {
    return options.drives.empty() ? default_drives() : options.drives;
}

std::unique_ptr<BusModel> make_fc_model(SimulatorOptions& options,
                                        std::vector<std::uint8_t>& drives) {
    options.drives = fc_drives_or_default(options);
    if (options.baud == 0) options.baud = fc_protocol().default_baud;
    for (const SimulatedDrive& drive : options.drives)
        drives.push_back(drive.address);
    return std::make_unique<FcBusModel>(options.drives);
}

Result<void> check_fc_session_faults(const SimulatorOptions& options) {
    return check_fc_faults(options.faults, fc_drives_or_default(options), options.cycles);
}

// session_span_bound_ns of an FC session.
std::int64_t fc_session_span_bound_ns(const SimulatorOptions& options) {
    const double drives = static_cast<double>(fc_drives_or_default(options).size());
    const double baud =
        options.baud == 0 ? fc_protocol().default_baud : static_cast<double>(options.baud);
    // A telegram is at most 257 bytes of 11 bits. A poll: garbage, a request, a stacked one and
    // the answer, each after a gap of at most the master's time-out (the longest wait).
    constexpr double kTelegramBits = 257 * 11;
    const double wait_ns = static_cast<double>(FcBusModel::kMasterTimeoutNs);
    const double poll_ns = 4 * (kTelegramBits * 1e9 / baud + wait_ns);
    // A cycle: every drive polled, a broadcast (twice with one drive). At least --cycle-us.
    const double cycle_ns = std::max(static_cast<double>(options.cycle_us) * 1e3,
                                     drives * poll_ns + 2 * (kTelegramBits * 1e9 / baud + wait_ns));
    const double cycles = session_cycles_bound(options);
    const double span = cycles * cycle_ns;
    return span_bound_of(span);
}

}  // namespace

const SimulatedBus& fc_simulated_bus() noexcept {
    static const SimulatedBus bus{
        .protocol = Protocol::Fc,
        .make_model = make_fc_model,
        .check_faults = check_fc_session_faults,
        .span_bound_ns = fc_session_span_bound_ns,
        .fault_applies = fault_applies_to_fc,
        .runs_on_ns = nullptr,
        .character_bits = 11,  // 8E1
    };
    return bus;
}

}  // namespace dpscope
