#include "protocols/vlt2000/vlt2000_bus_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <memory>

#include "core/protocol_descriptor.hpp"
#include "simulator/simulator.hpp"

namespace dpscope {

namespace {

// The simulated drive's parameters (dpscope's choice, docs/decisions.md "VLT 2000 simulator"; the
// numbering follows the VLT 2000/3000 groups, 0516 as in the VLT 3000 manual's example).
constexpr std::uint16_t kMaxFrequency = 202;  // maximum output frequency [0.1 Hz], U/R
constexpr std::uint16_t kRampUp = 205;        // ramp-up time [0.01 s], U/R
constexpr std::uint16_t kRampDown = 206;      // ramp-down time [0.01 s], U/R
constexpr std::uint16_t kAddress = 500;       // the drive's address: read, no serial write
constexpr std::uint16_t kReference = 516;     // bus reference [%], U/R
constexpr std::uint16_t kFrequency = 518;     // output frequency [0.1 Hz], read-out
constexpr std::uint16_t kCurrent = 520;       // motor current [0.001 A], read-out
constexpr std::uint16_t kTorque = 521;        // torque [0.1 %], read-out, negative when braking
constexpr std::uint16_t kDcVoltage = 525;     // DC link voltage [V], read-out
constexpr std::uint16_t kHours = 600;         // operating hours, read-out
constexpr std::uint16_t kFaultLog = 615;      // fault log: error code, indices 1..8
constexpr std::uint16_t kMissing = 999;       // no such parameter
constexpr std::uint32_t kFaultLogSize = 8;
constexpr std::uint32_t kFaultLogCodes[kFaultLogSize] = {14, 0, 7, 0, 29, 0, 0, 2};

constexpr bool is_read_out(std::uint16_t parameter) {
    return parameter == kFrequency || parameter == kCurrent || parameter == kTorque ||
           parameter == kDcVoltage || parameter == kHours || parameter == kFaultLog;
}

constexpr bool exists(std::uint16_t parameter) {
    return parameter == kMaxFrequency || parameter == kRampUp || parameter == kRampDown ||
           parameter == kAddress || parameter == kReference || is_read_out(parameter);
}

// Reason codes of a failed command [P:VLT3000 p80].
constexpr std::uint8_t kNoSuchParameter = 0, kNoAccess = 1, kNoSuchIndex = 2, kNotIndexed = 3,
                       kReadOnly = 4;

constexpr std::uint8_t kFailed = kVlt2000FailedDecimals;

void put_digits(std::vector<std::uint8_t>& out, std::uint32_t value, int count) {
    for (int i = count - 1; i >= 0; --i) {
        std::uint32_t d = value;
        for (int k = 0; k < i; ++k)
            d /= 10;
        out.push_back(static_cast<std::uint8_t>('0' + d % 10));
    }
}

}  // namespace

Result<std::uint8_t> parse_vlt2000_drive_spec(std::string_view text) {
    unsigned address = 0;
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), address);
    if (ec != std::errc() || end != text.data() + text.size() || address < 1 || address > 99)
        return Error{fmt::format(
            "{}: the address must be from 1 to 99 (two digits; 00 is the broadcast)", text)};
    return static_cast<std::uint8_t>(address);
}

std::vector<std::uint8_t> default_vlt2000_drives() { return {1, 2, 5}; }

bool fault_applies_to_vlt2000(FaultKind kind) noexcept {
    return fault_applies_to_bus(kind, Protocol::Vlt2000);
}

Result<void> check_vlt2000_faults(const std::vector<FaultSpec>& faults,
                                  const std::vector<std::uint8_t>& drives, std::uint64_t cycles) {
    for (const FaultSpec& spec : faults) {
        if (!fault_applies_to_vlt2000(spec.kind))
            return Error{fmt::format(
                "fault {}: {} fault; a VLT 2000 bus takes the vlt2000_* faults, garbage and "
                "malformed_telegram",
                describe_fault(spec),
                protocol_descriptor(fault_bus(spec.kind)).capture_noun)};
        if (spec.slave && std::find(drives.begin(), drives.end(), *spec.slave) == drives.end())
            return Error{fmt::format("fault {}: drive {} is not simulated", describe_fault(spec),
                                     *spec.slave)};
        if (spec.cycle && cycles != 0 && *spec.cycle >= cycles)
            return Error{fmt::format("fault {}: cycle {} is past the session's {} cycles (0..{})",
                                     describe_fault(spec), *spec.cycle, cycles, cycles - 1)};
    }
    return {};
}

std::vector<std::uint8_t> vlt2000_telegram(const Vlt2000Fields& f) {
    std::vector<std::uint8_t> out;
    out.reserve(kVlt2000TelegramSize);
    out.push_back(kVlt2000Start);
    put_digits(out, f.address % 100u, 2);
    out.push_back(static_cast<std::uint8_t>(f.letter));
    for (unsigned group = 0; group < 4; ++group)
        out.push_back(static_cast<std::uint8_t>(0x40 | ((f.word >> (4 * group)) & 0x0F)));
    put_digits(out, f.parameter % 10000u, 4);
    if (f.index.size() == 6) {
        out.insert(out.end(), f.index.begin(), f.index.end());
    } else {
        out.push_back(f.negative ? '-' : '+');
        put_digits(out, f.digits % 100000u, 5);
    }
    out.push_back(static_cast<std::uint8_t>('0' + f.decimals % 10));
    if (f.checksum_disabled) {
        out.push_back('?');
        out.push_back('?');
    } else {
        put_digits(out, vlt2000_checksum_of(Bytes(out.data(), out.size())), 2);
    }
    out.push_back(kVlt2000Stop);
    return out;
}

std::optional<std::uint8_t> vlt2000_simulated_failure(char letter, std::uint16_t parameter,
                                                      std::uint32_t index) noexcept {
    if (letter == 'C') return std::nullopt;  // the parameter is ignored
    if (!exists(parameter)) return kNoSuchParameter;
    if (letter == 'U') {
        if (parameter == kAddress) return kNoAccess;
        if (is_read_out(parameter)) return kReadOnly;
    }
    if (letter == 'I') {
        if (parameter != kFaultLog) return kNotIndexed;
        if (index < 1 || index > kFaultLogSize) return kNoSuchIndex;
    }
    return std::nullopt;
}

std::uint16_t vlt2000_status_word(std::uint16_t control, bool running, bool at_reference,
                                  bool in_band) noexcept {
    std::uint16_t status = 0x0003;                       // control ready, VLT ready
    if ((control & 0x000A) == 0x000A) status |= 0x0004;  // ON2, coasting possible: enabled
    if (running && !in_band) status |= 0x0080;           // warning
    if (at_reference) status |= 0x0100;
    if (control & 0x0400) status |= 0x0200;  // serial communication control
    if (!running || in_band) status |= 0x0400;
    if (running) status |= 0x0800;
    return status;
}

Vlt2000BusModel::Vlt2000BusModel(std::vector<std::uint8_t> drives) : drives_(std::move(drives)) {
    for (std::uint8_t address : drives_) {
        Drive drive;
        drive.address = address;
        drive.hours += address * 100u;
        state_.push_back(drive);
    }
}

std::int64_t Vlt2000BusModel::between(BusEnvironment& env, std::int64_t low, std::int64_t high) {
    return low + static_cast<std::int64_t>(env.random(static_cast<std::uint64_t>(high - low) + 1));
}

void Vlt2000BusModel::send(BusEnvironment& env, std::vector<std::uint8_t> bytes,
                           std::int64_t gap_ns, bool broadcast) {
    last_broadcast_letter_ = broadcast && bytes.size() > kVlt2000LetterAt
                                 ? static_cast<char>(bytes[kVlt2000LetterAt])
                                 : 0;
    env.send(std::move(bytes), gap_ns);
}

void Vlt2000BusModel::cycle(BusEnvironment& env, std::uint64_t number) {
    for (std::size_t i = 0; i < state_.size(); ++i)
        poll(env, i);
    if (number % 20 == 19) broadcast(env, number);
}

std::uint16_t Vlt2000BusModel::status_of(const Drive& drive) const {
    const std::uint32_t target = drive.started ? drive.reference * drive.max_frequency / 100 : 0;
    const bool running = drive.frequency > 0;
    const bool in_band = drive.frequency <= drive.max_frequency * 9 / 10;
    return vlt2000_status_word(drive.control, running, drive.frequency == target, in_band);
}

void Vlt2000BusModel::broadcast(BusEnvironment& env, std::uint64_t number) {
    // The run word to every drive, or a new bus reference (U 0516) for all; the other letter when
    // the telegram before was a broadcast with this one. Nobody replies.
    char letter = (number / 20) % 2 == 0 ? 'C' : 'U';
    if (letter == last_broadcast_letter_) letter = letter == 'C' ? 'U' : 'C';
    Command command;
    command.letter = letter;
    if (letter == 'U') {
        command.parameter = kReference;
        command.digits = static_cast<std::uint32_t>(60 + env.random(7) * 5);
    }
    Drive everyone;
    everyone.control = kRunWord;
    send(env, command_bytes(everyone, 0, command), between(env, kMasterGapMinNs, kMasterGapMaxNs),
         true);
    for (Drive& drive : state_) {
        drive.control = kRunWord;
        drive.started = true;
        if (letter == 'U') drive.reference = command.digits;
    }
    // A drive that replies although nobody should.
    for (std::size_t i = 0; i < state_.size(); ++i) {
        if (!env.inject(FaultKind::Vlt2000UnexpectedReply, i)) continue;
        Drive& drive = state_[i];
        env.send(reply_bytes(drive, 0, perform(drive, command)),
                 between(env, kResponseMinNs, kResponseMaxNs));
        last_broadcast_letter_ = 0;
        break;
    }
}

Vlt2000BusModel::Command Vlt2000BusModel::plan(BusEnvironment& env, const Drive& drive) const {
    const std::uint64_t roll = env.random(100);
    Command c;
    if (roll < 40) {
        // Control only: mostly the run word; a running drive is stopped now and then and started
        // again later.
        c.letter = 'C';
        return c;
    }
    if (roll < 68) {
        static constexpr std::uint16_t kReads[] = {kReference, kMaxFrequency, kRampUp,  kRampDown,
                                                   kAddress,   kFrequency,    kCurrent, kTorque,
                                                   kDcVoltage, kHours};
        c.letter = 'R';
        c.parameter = kReads[env.random(std::size(kReads))];
        return c;
    }
    if (roll < 84) {
        c.letter = 'U';
        switch (env.random(4)) {
            case 0:
                c.parameter = kReference;
                c.digits = static_cast<std::uint32_t>(50 + env.random(11) * 5);
                break;
            case 1:
                c.parameter = kMaxFrequency;
                c.digits = static_cast<std::uint32_t>(450 + env.random(5) * 50);
                c.decimals = 1;
                break;
            default:
                c.parameter = env.random(2) == 0 ? kRampUp : kRampDown;
                c.digits = static_cast<std::uint32_t>(100 + env.random(19) * 50);
                c.decimals = 2;
                break;
        }
        return c;
    }
    if (roll < 95) {
        c.letter = 'I';
        c.parameter = kFaultLog;
        c.index = static_cast<std::uint32_t>(1 + env.random(kFaultLogSize));
        return c;
    }
    // A command the drive cannot carry out, one for each reason code 00..04.
    switch (env.random(5)) {
        case 0:
            c.letter = 'R';
            c.parameter = kMissing;
            break;
        case 1:
            c.letter = 'U';
            c.parameter = kAddress;
            c.digits = drive.address + 10u;
            break;
        case 2:
            c.letter = 'I';
            c.parameter = kFaultLog;
            c.index = kFaultLogSize + 1;
            break;
        case 3:
            c.letter = 'I';
            c.parameter = kRampUp;
            c.index = 1;
            break;
        default:
            c.letter = 'U';
            c.parameter = kFrequency;
            c.digits = 500;
            c.decimals = 1;
            break;
    }
    return c;
}

Vlt2000BusModel::Command Vlt2000BusModel::perform(Drive& drive, const Command& command) const {
    Command reply = command;
    reply.index = 0;
    if (std::optional<std::uint8_t> reason =
            vlt2000_simulated_failure(command.letter, command.parameter, command.index)) {
        reply.negative = false;
        reply.digits = *reason;
        reply.decimals = kFailed;
        return reply;
    }
    if (command.letter == 'C') return reply;  // parameter and value as sent
    if (command.letter == 'U') {
        // The value as the drive took it, echoed.
        switch (command.parameter) {
            case kReference: drive.reference = std::min<std::uint32_t>(command.digits, 100); break;
            case kMaxFrequency: drive.max_frequency = command.digits; break;
            case kRampUp: drive.ramp_up = command.digits; break;
            case kRampDown: drive.ramp_down = command.digits; break;
            default: break;
        }
        return reply;
    }
    reply.negative = false;
    reply.decimals = 0;
    const std::uint32_t target = drive.started ? drive.reference * drive.max_frequency / 100 : 0;
    switch (command.parameter) {
        case kReference: reply.digits = drive.reference; break;
        case kMaxFrequency:
            reply.digits = drive.max_frequency;
            reply.decimals = 1;
            break;
        case kRampUp:
        case kRampDown:
            reply.digits = command.parameter == kRampUp ? drive.ramp_up : drive.ramp_down;
            reply.decimals = 2;
            break;
        case kAddress: reply.digits = drive.address; break;
        case kFrequency:
            reply.digits = drive.frequency;
            reply.decimals = 1;
            break;
        case kCurrent:
            // The seed's value example: 23.75 A is +23750 with three decimals.
            reply.digits = drive.frequency == 0 ? 850 : 2'000 + drive.frequency * 40;
            reply.decimals = 3;
            break;
        case kTorque:
            // Braking torque is negative.
            reply.negative = drive.frequency > target;
            reply.digits = drive.frequency > target   ? 350
                           : drive.frequency < target ? 1'200
                           : drive.frequency == 0     ? 0
                                                      : 450 + drive.frequency % 7;
            reply.decimals = 1;
            break;
        case kDcVoltage: reply.digits = 560 + drive.frequency % 9; break;
        case kHours: reply.digits = drive.hours; break;
        case kFaultLog: reply.digits = kFaultLogCodes[(command.index - 1) % kFaultLogSize]; break;
        default: break;
    }
    return reply;
}

std::vector<std::uint8_t> Vlt2000BusModel::command_bytes(const Drive& drive, std::uint8_t address,
                                                         const Command& command) const {
    Vlt2000Fields f;
    f.address = address;
    f.letter = command.letter;
    f.word = drive.control;
    f.parameter = command.parameter;
    f.negative = command.negative;
    f.digits = command.digits;
    f.decimals = command.decimals;
    f.checksum_disabled = drive.checksum_off;
    std::string index;
    if (command.letter == 'I') {
        index = fmt::format("{:06}", command.index % 1'000'000u);
        f.index = index;
    }
    return vlt2000_telegram(f);
}

std::vector<std::uint8_t> Vlt2000BusModel::reply_bytes(const Drive& drive, std::uint8_t address,
                                                       const Command& reply) const {
    Vlt2000Fields f;
    f.address = address;
    f.letter = reply.letter;
    f.word = status_of(drive);
    f.parameter = reply.parameter;
    f.negative = reply.negative;
    f.digits = reply.digits;
    f.decimals = reply.decimals;
    f.checksum_disabled = drive.checksum_off;
    return vlt2000_telegram(f);
}

void Vlt2000BusModel::poll(BusEnvironment& env, std::size_t index) {
    Drive& drive = state_[index];
    if (env.inject(FaultKind::Garbage, index)) {
        // Noise on the line: no '<', so no telegram starts inside it.
        std::vector<std::uint8_t> junk(3 + env.random(10));
        for (std::uint8_t& b : junk) {
            b = static_cast<std::uint8_t>(env.random(256));
            if (b == kVlt2000Start) b = 0xFF;
        }
        send(env, std::move(junk), between(env, kMasterGapMinNs, kMasterGapMaxNs), false);
    }
    // From here on the master and this drive send "??" instead of the checksum.
    if (!drive.checksum_off && env.inject(FaultKind::Vlt2000ChecksumDisabled, index))
        drive.checksum_off = true;

    Command command = plan(env, drive);
    if (command.letter == 'C') {
        if (drive.started && env.random(30) == 0) {
            drive.control = kStopWord;
            drive.started = false;
        } else if (!drive.started && env.random(3) == 0) {
            drive.control = kRunWord;
            drive.started = true;
        }
    }
    send(env, command_bytes(drive, drive.address, command),
         between(env, kMasterGapMinNs, kMasterGapMaxNs), false);
    if (env.inject(FaultKind::Vlt2000StackedRequest, index)) {
        // Before the drive had time to reply, the master sends it another command with another
        // letter (with the same one a decoder would take it for the reply). The drive replies to
        // that one.
        Command second;
        if (command.letter == 'C') {
            second.letter = 'R';
            second.parameter = kFrequency;
        }
        send(env, command_bytes(drive, drive.address, second), between(env, 500'000, 1'000'000),
             false);
        command = second;
    }

    const bool works =
        !vlt2000_simulated_failure(command.letter, command.parameter, command.index).has_value();
    const bool has_parameter = command.letter != 'C';
    if (works && env.inject(FaultKind::Vlt2000NoResponse, index)) {
        env.wait(kMasterTimeoutNs);
        // The master moves on to the next drive; with only one drive on the bus it sends a
        // broadcast first, so that its next poll of the drive is not a stacked command.
        if (state_.size() == 1) broadcast(env, 19);
    } else {
        Command reply = perform(drive, command);
        if (works && has_parameter && env.inject(FaultKind::Vlt2000MismatchedResponse, index)) {
            reply.parameter =
                static_cast<std::uint16_t>(reply.parameter >= 9999 ? 9998 : reply.parameter + 1);
        } else if (works && has_parameter && env.inject(FaultKind::Vlt2000CommandFailed, index)) {
            // U: read only (factory set-up selected); R, I: no access.
            reply.negative = false;
            reply.digits = command.letter == 'U' ? kReadOnly : kNoAccess;
            reply.decimals = kFailed;
        }
        std::vector<std::uint8_t> bytes = reply_bytes(drive, drive.address, reply);
        if (env.inject(FaultKind::Vlt2000ChecksumError, index)) {
            // Two digits, not the sum's.
            const auto wrong = static_cast<unsigned>(
                (vlt2000_checksum_of(Bytes(bytes.data(), bytes.size())) + 1 + env.random(99)) %
                100);
            bytes[kVlt2000ChecksumAt] = static_cast<std::uint8_t>('0' + wrong / 10);
            bytes[kVlt2000ChecksumAt + 1] = static_cast<std::uint8_t>('0' + wrong % 10);
        } else if (env.inject(FaultKind::MalformedTelegram, index)) {
            // Cut short: the line went quiet after 13 to 20 characters (the letter is there).
            bytes.resize(bytes.size() - 2 - env.random(8));
        }
        send(env, std::move(bytes), between(env, kResponseMinNs, kResponseMaxNs), false);
    }

    // The drive ramps its output toward the target, 4 Hz a poll; the hours count on.
    const std::uint32_t target = drive.started ? drive.reference * drive.max_frequency / 100 : 0;
    if (drive.frequency < target) drive.frequency = std::min(target, drive.frequency + 40);
    if (drive.frequency > target)
        drive.frequency = drive.frequency > target + 40 ? drive.frequency - 40 : target;
    if (env.random(200) == 0) ++drive.hours;
}

// The VLT 2000 bus in the simulated session (simulator/bus_model.hpp).
namespace {

std::vector<std::uint8_t> vlt2000_drives_of(const SimulatorOptions& options) {
    return options.vlt2000_drives.empty() ? default_vlt2000_drives() : options.vlt2000_drives;
}

std::unique_ptr<BusModel> make_vlt2000_model(SimulatorOptions& options,
                                             std::vector<std::uint8_t>& drives) {
    options.vlt2000_drives = vlt2000_drives_of(options);
    if (options.baud == 0) options.baud = vlt2000_protocol().default_baud;
    drives = options.vlt2000_drives;
    return std::make_unique<Vlt2000BusModel>(options.vlt2000_drives);
}

Result<void> check_vlt2000_session_faults(const SimulatorOptions& options) {
    return check_vlt2000_faults(options.faults, vlt2000_drives_of(options), options.cycles);
}

// A drive that does not reply: the session runs one cycle more, so that the master's next
// command (which shows the reply missing) is in the capture.
std::int64_t vlt2000_runs_on_ns(FaultKind kind, const SimulatorOptions& options) {
    if (kind != FaultKind::Vlt2000NoResponse) return 0;
    return Vlt2000BusModel::kMasterTimeoutNs + std::int64_t{options.cycle_us} * 1000 + 1'000'000;
}

// session_span_bound_ns of a VLT 2000 session.
std::int64_t vlt2000_session_span_bound_ns(const SimulatorOptions& options) {
    const double drives = static_cast<double>(vlt2000_drives_of(options).size());
    const double baud =
        options.baud == 0 ? vlt2000_protocol().default_baud : static_cast<double>(options.baud);
    // A telegram is 22 characters of 10 bits (garbage is shorter). A poll: garbage, a command, a
    // stacked one and the reply, each after a gap of at most the master's time-out (the longest
    // wait).
    constexpr double kTelegramBits = 22 * 10;
    const double wait_ns = static_cast<double>(Vlt2000BusModel::kMasterTimeoutNs);
    const double telegram_ns = kTelegramBits * 1e9 / baud + wait_ns;
    const double poll_ns = 4 * telegram_ns;
    // A cycle: every drive polled, a broadcast and a reply to it (twice with one drive). At
    // least --cycle-us.
    const double cycle_ns =
        std::max(static_cast<double>(options.cycle_us) * 1e3, drives * poll_ns + 4 * telegram_ns);
    const double cycles = session_cycles_bound(options);
    // After a missing reply the session runs one cycle more.
    const double span = (cycles + 1) * cycle_ns;
    return span_bound_of(span);
}

}  // namespace

const SimulatedBus& vlt2000_simulated_bus() noexcept {
    static const SimulatedBus bus{
        .protocol = Protocol::Vlt2000,
        .make_model = make_vlt2000_model,
        .check_faults = check_vlt2000_session_faults,
        .span_bound_ns = vlt2000_session_span_bound_ns,
        .fault_applies = fault_applies_to_vlt2000,
        .runs_on_ns = vlt2000_runs_on_ns,
        .character_bits = 10,  // 8N1
    };
    return bus;
}

}  // namespace dpscope
