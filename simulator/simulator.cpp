#include "simulator/simulator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

#include "decoder/dp_service.hpp"
#include "decoder/telegram_builder.hpp"

namespace dpscope {

namespace {

constexpr std::string_view kFaultNames[] = {
    "fcs_error",
    "garbage",
    "malformed_telegram",
    "stacked_request",
    "orphan_response",
    "mismatched_response",
    "unexpected_response_type",
    "response_timeout",
    "request_rejected",
    "no_authority",
    "spontaneous_message",
    "spontaneous_unacknowledged",
    "spm_violation",
    "config_mismatch",
    "unknown_code",
    "fdl_retry",
    "fdl_no_response",
};
static_assert(std::size(kFaultNames) == static_cast<std::size_t>(FaultKind::Count));

template <typename T>
bool parse_number(std::string_view text, T& value) {
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    return ec == std::errc() && end == text.data() + text.size();
}

}  // namespace

bool fault_needs_parameter_channel(FaultKind kind) noexcept {
    switch (kind) {
        case FaultKind::FcsError:
        case FaultKind::Garbage:
        case FaultKind::MalformedTelegram:
        case FaultKind::ConfigMismatch:
        case FaultKind::FdlRetry:
        case FaultKind::FdlNoResponse: return false;
        default: return true;
    }
}

namespace {

constexpr std::uint8_t kRead = 1, kWriteWord = 2, kWriteDword = 3, kReadDescription = 4,
                       kReadArray = 6, kReadCount = 9;
constexpr std::uint8_t kRejected = 7, kNoAuthority = 8, kSpontaneousWord = 9;
constexpr std::uint8_t kUndefinedCode = 13;
constexpr std::uint16_t kAlarmWordPnu = 538;

// Configuration identifiers as in the Danfoss GSD (module-consistent PCD).
std::vector<std::uint8_t> cfg_bytes_of(std::uint8_t ppo_type) {
    switch (ppo_type) {
        case 1: return {0xF3, 0xF1};
        case 2: return {0xF3, 0xF5};
        case 3: return {0xF1};
        case 4: return {0xF5};
        default: return {0xF3, 0xF9};
    }
}

}  // namespace

std::string_view fault_kind_name(FaultKind kind) {
    auto index = static_cast<std::size_t>(kind);
    return index < std::size(kFaultNames) ? kFaultNames[index] : "unknown";
}

std::optional<FaultKind> fault_kind_from_name(std::string_view name) {
    if (name == "bad_fcs") return FaultKind::FcsError;
    for (std::size_t i = 0; i < std::size(kFaultNames); ++i)
        if (kFaultNames[i] == name) return static_cast<FaultKind>(i);
    return std::nullopt;
}

std::optional<FaultSpec> parse_fault_spec(std::string_view text, std::string& error) {
    FaultSpec spec;
    std::string_view rest = text;
    if (auto colon = rest.rfind(':'); colon != std::string_view::npos) {
        unsigned address = 0;
        if (!parse_number(rest.substr(colon + 1), address) || address > 126) {
            error = fmt::format("{}: '{}' is not a station address from 0 to 126", text,
                                rest.substr(colon + 1));
            return std::nullopt;
        }
        spec.slave = static_cast<std::uint8_t>(address);
        rest = rest.substr(0, colon);
    }
    std::string_view name = rest;
    if (auto at = rest.find('@'); at != std::string_view::npos) {
        std::uint64_t cycle = 0;
        if (!parse_number(rest.substr(at + 1), cycle)) {
            error = fmt::format("{}: '{}' is not a cycle number", text, rest.substr(at + 1));
            return std::nullopt;
        }
        spec.cycle = cycle;
        name = rest.substr(0, at);
    } else if (auto eq = rest.find('='); eq != std::string_view::npos) {
        std::string number(rest.substr(eq + 1));
        char* end = nullptr;
        double rate = std::strtod(number.c_str(), &end);
        if (number.empty() || *end != '\0' || !(rate > 0) || rate > 1) {
            error = fmt::format("{}: rate '{}' must be a number in (0, 1]", text, number);
            return std::nullopt;
        }
        spec.rate = rate;
        name = rest.substr(0, eq);
    }
    auto kind = fault_kind_from_name(name);
    if (!kind) {
        std::string names;
        for (std::string_view n : kFaultNames)
            names += fmt::format("{}{}", names.empty() ? "" : ", ", n);
        error = fmt::format("{}: unknown kind '{}' (known: {})", text, name, names);
        return std::nullopt;
    }
    spec.kind = *kind;
    return spec;
}

std::optional<SimulatedSlave> parse_slave_spec(std::string_view text, std::string& error) {
    SimulatedSlave slave;
    auto first = text.find(':');
    if (first == std::string_view::npos) {
        error = fmt::format("{}: expected ADDR:PPO or ADDR:PPO:DIALECT", text);
        return std::nullopt;
    }
    unsigned address = 0, ppo = 0;
    auto second = text.find(':', first + 1);
    std::string_view ppo_text = text.substr(
        first + 1, second == std::string_view::npos ? std::string_view::npos : second - first - 1);
    if (!parse_number(text.substr(0, first), address) || address > 125) {
        error = fmt::format("{}: the address must be from 0 to 125", text);
        return std::nullopt;
    }
    if (!parse_number(ppo_text, ppo) || ppo < 1 || ppo > 5) {
        error = fmt::format("{}: the PPO type must be from 1 to 5", text);
        return std::nullopt;
    }
    slave.address = static_cast<std::uint8_t>(address);
    slave.ppo_type = static_cast<std::uint8_t>(ppo);
    if (second != std::string_view::npos) {
        auto dialect = dialect_from_name(text.substr(second + 1));
        if (!dialect) {
            error = fmt::format("{}: dialect must be vlt or profidrive", text);
            return std::nullopt;
        }
        slave.dialect = *dialect;
    }
    return slave;
}

namespace {

std::vector<SimulatedSlave> slaves_or_default(const SimulatorOptions& options) {
    if (!options.slaves.empty()) return options.slaves;
    return {{3, 1, Dialect::Vlt}, {4, 2, Dialect::Vlt}, {5, 5, Dialect::Vlt}};
}

bool has_parameter_channel(const SimulatedSlave& slave) {
    return ppo_layout_of_type(slave.ppo_type, PpoSource::Option).has_pcv;
}

std::string describe_fault(const FaultSpec& spec) {
    std::string text(fault_kind_name(spec.kind));
    if (spec.rate > 0) text += fmt::format("={}", spec.rate);
    if (spec.cycle) text += fmt::format("@{}", *spec.cycle);
    if (spec.slave) text += fmt::format(":{}", *spec.slave);
    return text;
}

}  // namespace

std::string check_simulator_faults(const SimulatorOptions& options) {
    const std::vector<SimulatedSlave> slaves = slaves_or_default(options);
    for (const FaultSpec& spec : options.faults) {
        const bool needs_pcv = fault_needs_parameter_channel(spec.kind);
        bool target = false;
        for (const SimulatedSlave& slave : slaves) {
            if (spec.slave && slave.address != *spec.slave) continue;
            if (!needs_pcv || has_parameter_channel(slave)) target = true;
        }
        if (!target) {
            if (spec.slave) {
                bool simulated = false;
                for (const SimulatedSlave& slave : slaves)
                    simulated = simulated || slave.address == *spec.slave;
                if (!simulated)
                    return fmt::format("fault {}: slave {} is not simulated", describe_fault(spec),
                                       *spec.slave);
                return fmt::format(
                    "fault {}: slave {} has no parameter channel (PPO 3 and 4 carry no PCV)",
                    describe_fault(spec), *spec.slave);
            }
            return fmt::format(
                "fault {}: no simulated slave has a parameter channel (PPO 1, 2 "
                "or 5)",
                describe_fault(spec));
        }
        if (spec.cycle && options.cycles != 0 && *spec.cycle >= options.cycles)
            return fmt::format("fault {}: cycle {} is past the session's {} cycles (0..{})",
                               describe_fault(spec), *spec.cycle, options.cycles,
                               options.cycles - 1);
    }
    return {};
}

std::int64_t session_span_bound_ns(const SimulatorOptions& options) {
    const double slaves = static_cast<double>(slaves_or_default(options).size());
    const double baud = options.baud == 0 ? 1'500'000.0 : static_cast<double>(options.baud);
    // A telegram (or garbage record) is at most 64 bytes of 11 bits, after a gap of at most
    // 100 bits; a slot time that expires is 100 bits.
    constexpr double kTelegramBits = 64 * 11 + 100;
    // Start-up: twelve telegrams per slave, then Global_Control and the token.
    const double start_up_bits = (slaves * 12 + 2) * kTelegramBits;
    // A cycle: per slave garbage, request, response and their repeats and two slot times; then a
    // gap poll and its slot time, Global_Control and the token. At least --cycle-us.
    const double cycle_bits = slaves * (5 * kTelegramBits + 200) + 3 * kTelegramBits + 100;
    const double cycle_ns =
        std::max(static_cast<double>(options.cycle_us) * 1e3, cycle_bits * 1e9 / baud);
    // Every cycle writes one telegram at least (the token).
    double cycles = static_cast<double>(options.cycles);
    if (options.max_telegrams != 0 &&
        (options.cycles == 0 || options.max_telegrams < options.cycles))
        cycles = static_cast<double>(options.max_telegrams);
    // After a time-out fault the session runs on until the master has given up, plus ten cycles.
    const double tail_ns = static_cast<double>(options.master_give_up_ms) * 1e6 +
                           static_cast<double>(options.cycle_us) * 1e4 + cycle_ns;
    const double span = start_up_bits * 1e9 / baud + cycles * cycle_ns + tail_ns;
    constexpr double kLargest = 9.2e18;  // below the largest int64 (9.22e18)
    return span >= kLargest ? std::numeric_limits<std::int64_t>::max()
                            : static_cast<std::int64_t>(std::ceil(span));
}

OnceFaultCheck::OnceFaultCheck(const std::vector<FaultSpec>& faults) {
    for (const FaultSpec& spec : faults)
        if (spec.rate == 0) once_.push_back(spec);
    found_.assign(once_.size(), false);
}

void OnceFaultCheck::record(const Injection& injection) {
    for (std::size_t i = 0; i < once_.size(); ++i) {
        const FaultSpec& spec = once_[i];
        if (found_[i] || injection.kind != spec.kind) continue;
        if (spec.slave && injection.slave != *spec.slave) continue;
        if (spec.cycle && injection.cycle < *spec.cycle) continue;
        found_[i] = true;
        return;
    }
}

std::vector<std::string> OnceFaultCheck::missing() const {
    std::vector<std::string> missing;
    for (std::size_t i = 0; i < once_.size(); ++i)
        if (!found_[i]) missing.push_back(describe_fault(once_[i]));
    return missing;
}

std::vector<std::string> faults_not_injected(const SimulatorOptions& options,
                                             const std::vector<Injection>& injections) {
    OnceFaultCheck check(options.faults);
    for (const Injection& injection : injections)
        check.record(injection);
    return check.missing();
}

Simulator::Simulator(SimulatorOptions options)
    : options_(std::move(options)), once_faults_(options_.faults) {
    options_.slaves = slaves_or_default(options_);
    if (options_.baud == 0) options_.baud = 1'500'000;
    rng_state_ = options_.seed * 0x9E3779B97F4A7C15ULL + 0x2545F4914F6CDD1DULL;
    now_ = std::max<std::int64_t>(0, options_.start_time_ns);
    std::uint8_t highest = options_.master;
    for (const SimulatedSlave& config : options_.slaves) {
        Slave slave;
        slave.config = config;
        slave.layout = ppo_layout_of_type(config.ppo_type, PpoSource::Option);
        slave.ident = config.dialect == Dialect::Vlt ? 0x0402 : 0x6001;
        slave.parameters = {
            {520, false, 240, false}, {518, false, 500, false}, {516, true, 5000, false},
            {207, true, 1000, false}, {208, true, 1000, false}, {215, false, 10, false},
            {615, false, 0, true},
        };
        slave.actual = 0;
        slaves_.push_back(std::move(slave));
        highest = std::max(highest, config.address);
    }
    gap_address_ = static_cast<std::uint8_t>(std::min(highest + 1, 125));
    // Faults given without a cycle or rate happen once, at a cycle the seed picks.
    for (FaultSpec& spec : options_.faults) {
        if (spec.rate == 0 && !spec.cycle) {
            std::uint64_t span = std::max<std::uint64_t>(1, options_.cycles / 2);
            spec.cycle = 20 + random(span);
        }
    }
    scheduled_done_.assign(options_.faults.size(), false);
    armed_.assign(static_cast<std::size_t>(FaultKind::Count) * slaves_.size(), 0);
}

std::uint64_t Simulator::random(std::uint64_t bound) {
    // splitmix64: the same sequence on every platform and standard library.
    std::uint64_t z = (rng_state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    return bound == 0 ? 0 : z % bound;
}

bool Simulator::chance(double p) {
    return static_cast<double>(random(1'000'000)) < p * 1'000'000.0;
}

std::int64_t Simulator::bit_ns(std::uint64_t bits) const {
    return static_cast<std::int64_t>(bits * 1'000'000'000ULL / options_.baud);
}

namespace {

// time + ns (both >= 0), stopping at the largest int64 instead of wrapping.
std::int64_t later(std::int64_t time, std::int64_t ns) {
    constexpr std::int64_t kLast = std::numeric_limits<std::int64_t>::max();
    return ns > kLast - time ? kLast : time + ns;
}

}  // namespace

void Simulator::advance(std::int64_t ns) { now_ = later(now_, ns); }

void Simulator::emit(std::vector<std::uint8_t> bytes, std::uint64_t gap_bits) {
    if (options_.max_telegrams != 0 && queued_ >= options_.max_telegrams) return;
    advance(bit_ns(gap_bits));
    if (!recording_) {
        advance(bit_ns(bytes.size() * 11));
        return;
    }
    std::int64_t at = now_;
    advance(bit_ns(bytes.size() * 11));
    queue_.emplace_back(std::move(bytes), at);
    ++queued_;
}

bool Simulator::next(std::vector<std::uint8_t>& bytes, std::int64_t& time_ns) {
    while (queue_.empty()) {
        bool limit_reached = options_.max_telegrams != 0 && queued_ >= options_.max_telegrams;
        if (limit_reached) return false;
        if (!started_) {
            started_ = true;
            recording_ = options_.record_start_up;
            generate_start_up();
            recording_ = true;
        } else if (options_.cycles == 0 ? options_.max_telegrams != 0
                                        : cycle_ < options_.cycles || now_ < hold_open_until_) {
            generate_cycle();
        } else {
            return false;
        }
    }
    bytes = std::move(queue_.front().first);
    time_ns = queue_.front().second;
    queue_.pop_front();
    ++emitted_;
    return true;
}

void Simulator::generate_start_up() {
    const std::uint8_t master = options_.master;
    for (Slave& slave : slaves_) {
        const std::uint8_t address = slave.config.address;
        auto request = [&](std::optional<std::uint8_t> dsap, std::vector<std::uint8_t> du,
                           FdlFunction function) {
            TelegramSpec spec{address,
                              master,
                              request_fc(function, slave.fcb, true),
                              dsap,
                              dsap ? std::optional<std::uint8_t>(sap::kMaster) : std::nullopt,
                              Bytes(du)};
            emit(build_telegram(spec), 60 + random(40));
        };
        auto response = [&](std::uint8_t ssap, std::vector<std::uint8_t> du) {
            TelegramSpec spec{master,       address, response_fc(FdlStatus::DataLow),
                              sap::kMaster, ssap,    Bytes(du)};
            emit(build_telegram(spec), 30 + random(70));
            slave.fcb = !slave.fcb;
        };
        auto short_ack = [&] {
            std::vector<std::uint8_t> ack;
            append_short_ack(ack);
            emit(std::move(ack), 30 + random(70));
            slave.fcb = !slave.fcb;
        };
        auto ident_hi = static_cast<std::uint8_t>(slave.ident >> 8);
        auto ident_lo = static_cast<std::uint8_t>(slave.ident);

        emit(build_telegram({address, master, request_fc(FdlFunction::FdlStatus), {}, {}, {}}),
             100);
        emit(build_telegram({master, address, response_fc(FdlStatus::Ok), {}, {}, {}}),
             30 + random(70));
        slave.fcb = true;  // the first SRD after FDL_Status carries FCB = 1, FCV = 1
        request(sap::kSlaveDiag, {}, FdlFunction::SrdHigh);
        response(sap::kSlaveDiag, {0x02, 0x05, 0x00, kNoMasterAddress, ident_hi, ident_lo});
        std::vector<std::uint8_t> prm = {0x88, 10, 10, 11, ident_hi, ident_lo, 0x00};
        if (slave.config.dialect == Dialect::Profidrive) prm.insert(prm.end(), {0x80, 0x00, 0x00});
        request(sap::kSetPrm, prm, FdlFunction::SrdHigh);
        short_ack();
        request(sap::kChkCfg, cfg_bytes_of(slave.config.ppo_type), FdlFunction::SrdHigh);
        short_ack();
        request(sap::kSlaveDiag, {}, FdlFunction::SrdHigh);
        response(sap::kSlaveDiag, {0x00, 0x0C, 0x00, master, ident_hi, ident_lo});
    }
    std::vector<std::uint8_t> operate = {0x00, 0x00};
    emit(build_telegram({kBroadcastAddress, master, request_fc(FdlFunction::SdnHigh),
                         sap::kGlobalControl, sap::kMaster, Bytes(operate)}),
         100);
    std::vector<std::uint8_t> token;
    append_token(token, master, master);
    emit(std::move(token), 40);
}

void Simulator::generate_cycle() {
    const std::int64_t cycle_start = now_;
    arm_faults();
    for (std::size_t i = 0; i < slaves_.size(); ++i)
        exchange(i);
    const std::uint8_t master = options_.master;
    if (cycle_ % 100 == 99) {
        // Gap maintenance: ask the next address whether a station appeared (nobody answers).
        emit(build_telegram({gap_address_, master, request_fc(FdlFunction::FdlStatus), {}, {}, {}}),
             60);
        advance(bit_ns(100));  // slot time expires
        // The next address nobody uses (the master and the slaves are on the bus).
        auto in_use = [&](std::uint8_t address) {
            if (address == master) return true;
            return std::any_of(slaves_.begin(), slaves_.end(),
                               [&](const Slave& slave) { return slave.config.address == address; });
        };
        for (int tries = 0; tries < 126; ++tries) {
            gap_address_ = static_cast<std::uint8_t>(gap_address_ >= 125 ? 1 : gap_address_ + 1);
            if (!in_use(gap_address_)) break;
        }
    }
    if (cycle_ % 250 == 249) {
        std::vector<std::uint8_t> operate = {0x00, 0x00};
        emit(build_telegram({kBroadcastAddress, master, request_fc(FdlFunction::SdnHigh),
                             sap::kGlobalControl, sap::kMaster, Bytes(operate)}),
             60);
    }
    std::vector<std::uint8_t> token;
    append_token(token, master, master);
    emit(std::move(token), 40);
    const std::int64_t cycle_ns = static_cast<std::int64_t>(options_.cycle_us) * 1000;
    if (now_ - cycle_start < cycle_ns) advance(cycle_ns - (now_ - cycle_start));
    ++cycle_;
}

void Simulator::arm_faults() {
    // Past its cycles the session only runs on for a time-out to show: nothing new happens (a
    // time-out injected there would keep it open again), and what was armed is dropped.
    if (options_.cycles != 0 && cycle_ >= options_.cycles) {
        std::fill(armed_.begin(), armed_.end(), 0);
        return;
    }
    const std::size_t count = slaves_.size();
    for (std::size_t j = 0; j < options_.faults.size(); ++j) {
        const FaultSpec& spec = options_.faults[j];
        auto eligible = [&](std::size_t i) {
            if (spec.slave && slaves_[i].config.address != *spec.slave) return false;
            return !fault_needs_parameter_channel(spec.kind) || slaves_[i].layout.has_pcv;
        };
        if (spec.rate > 0) {
            for (std::size_t i = 0; i < slaves_.size(); ++i)
                if (eligible(i) && chance(spec.rate))
                    ++armed_[static_cast<std::size_t>(spec.kind) * count + i];
            continue;
        }
        if (scheduled_done_[j] || cycle_ < *spec.cycle) continue;
        scheduled_done_[j] = true;
        std::vector<std::size_t> candidates;
        for (std::size_t i = 0; i < slaves_.size(); ++i)
            if (eligible(i)) candidates.push_back(i);
        if (!candidates.empty())
            ++armed_[static_cast<std::size_t>(spec.kind) * count +
                     candidates[random(candidates.size())]];
    }
}

bool Simulator::take_fault(FaultKind kind, std::size_t slave) {
    std::uint64_t& armed = armed_[static_cast<std::size_t>(kind) * slaves_.size() + slave];
    if (armed == 0) return false;
    --armed;
    return true;
}

void Simulator::record_injection(FaultKind kind, std::size_t slave) {
    const Injection injection{kind, cycle_, slaves_[slave].config.address, queued_ + 1};
    ++injection_count_;
    if (injections_.size() < kKeptInjections) injections_.push_back(injection);
    once_faults_.record(injection);
    if (on_injection_) on_injection_(injection);
    if (kind == FaultKind::ResponseTimeout || kind == FaultKind::SpontaneousUnacknowledged) {
        const std::int64_t give_up = std::int64_t{options_.master_give_up_ms} * 1'000'000;
        hold_open_until_ = std::max(
            hold_open_until_, later(now_, give_up + std::int64_t{options_.cycle_us} * 10'000));
    }
}

Simulator::Parameter* Simulator::find_parameter(Slave& slave, std::uint16_t pnu) {
    for (Parameter& p : slave.parameters)
        if (p.pnu == pnu) return &p;
    return nullptr;
}

Simulator::Request Simulator::choose_request(Slave& slave) {
    bool profidrive = slave.config.dialect == Dialect::Profidrive;
    std::uint64_t pick = random(100);
    if (pick < 10 && slave.last_request.rc == kRead) return slave.last_request;  // poll again
    if (pick < 55) {
        static constexpr std::uint16_t kReadable[] = {520, 518, 516, 207, 208, 215};
        return {kRead, kReadable[random(std::size(kReadable))], 0, 0};
    }
    if (pick < 67) {
        std::uint16_t pnu = random(2) ? 207 : 208;
        auto value = static_cast<std::uint32_t>(500 + 100 * random(20));
        std::uint8_t rc = profidrive && random(2) ? 13 : kWriteDword;  // 13: RAM + EEPROM
        return {rc, pnu, 0, value};
    }
    if (pick < 77) {
        std::uint8_t rc = profidrive && random(2) ? 14 : kWriteWord;
        return {rc, 215, 0, static_cast<std::uint32_t>(5 + random(20))};
    }
    if (pick < 87) return {kReadArray, 615, static_cast<std::uint8_t>(1 + random(10)), 0};
    if (pick < 94) return {kReadCount, 615, 0, 0};
    return {kReadDescription, 207, static_cast<std::uint8_t>(1 + random(4)), 0};
}

void Simulator::master_step(Slave& slave) {
    if (!slave.layout.has_pcv) return;
    const std::size_t index = static_cast<std::size_t>(&slave - slaves_.data());
    const std::int64_t give_up = static_cast<std::int64_t>(options_.master_give_up_ms) * 1'000'000;
    const Request& seen = slave.master_seen_answer;
    const bool saw = slave.master_saw_response;
    const bool spontaneous_seen = saw && seen.rc >= kSpontaneousWord && seen.rc <= 12;
    // The master reacts to the response of the previous cycle (cycle_ - 1). The slave lags one
    // cycle, so only a response from a cycle after the request was first sent can answer it.
    const bool fresh = cycle_ >= slave.request_cycle + 2;
    if (spontaneous_seen) {
        if (slave.master_seen_spm != slave.master_acked_slave_spm) {  // a new message
            bool hold_back = slave.spontaneous_late_ack && now_ - slave.spontaneous_time < give_up;
            if (!hold_back) {
                slave.master_spm = !slave.master_spm;  // acknowledge
                slave.master_acked_slave_spm = slave.master_seen_spm;
            }
        }
    } else if (saw && fresh && slave.master_busy && seen.rc != 0 &&
               response_code(slave.config.dialect, seen.rc).kind != ResponseKind::Undefined &&
               (seen.pnu == slave.master_request.pnu || seen.rc == kRejected ||
                seen.rc == kNoAuthority || slave.answer_mismatched)) {
        // An answer to this request (a late answer to an abandoned request names another PNU).
        // RC 7 and 8 need not echo the PNU. An injected wrong-PNU answer ends the request too.
        // A code the dialect does not define is no answer: the master keeps waiting.
        slave.master_busy = false;
        slave.answer_mismatched = false;  // consumed: its repeats answer nothing else
        slave.last_request = slave.master_request;
        slave.next_request = choose_request(slave);
        slave.has_next = true;
        bool positive = seen.rc != kRejected && seen.rc != kNoAuthority;
        // Straight on to the next request (no RC 0 cycle) only for another parameter than the
        // one the slave's answer shows, or its stale repeats would pass for the new answer.
        bool direct = positive && slave.next_request.pnu != slave.last_request.pnu &&
                      slave.next_request.pnu != seen.pnu && random(3) == 0;
        slave.idle_cycles = direct ? 0 : static_cast<std::uint32_t>(1 + random(4));
    }
    if (slave.master_busy && now_ - slave.request_time > give_up) {
        slave.master_busy = false;  // give up on it
        slave.last_request = slave.master_request;
        slave.has_next = false;
        slave.idle_cycles = static_cast<std::uint32_t>(1 + random(3));
    }
    if (slave.master_busy && take_fault(FaultKind::StackedRequest, index)) {
        record_injection(FaultKind::StackedRequest, index);
        // Another parameter than the pending one and than the last one answered: the slave's
        // register may still hold that answer, and a real master could not tell it from a new one.
        Request other = choose_request(slave);
        for (std::uint16_t pnu : {std::uint16_t{520}, std::uint16_t{518}, std::uint16_t{516}}) {
            if (other.pnu != slave.master_request.pnu && other.pnu != slave.last_request.pnu &&
                other.pnu != slave.master_seen_answer.pnu)
                break;
            other = {kRead, pnu, 0, 0};
        }
        slave.master_request = other;
        slave.request_time = now_;
        slave.request_cycle = cycle_;
    }
    const bool message_pending =
        spontaneous_seen && slave.master_seen_spm != slave.master_acked_slave_spm;
    if (!message_pending && !slave.spontaneous_active &&
        take_fault(FaultKind::SpmViolation, index)) {
        record_injection(FaultKind::SpmViolation, index);
        slave.master_spm = !slave.master_spm;
    }
    if (!slave.master_busy) {
        if (slave.idle_cycles > 0) {
            --slave.idle_cycles;
        } else if (!message_pending) {
            slave.master_busy = true;
            slave.master_request = slave.has_next ? slave.next_request : choose_request(slave);
            slave.has_next = false;
            slave.request_time = now_;
            slave.request_cycle = cycle_;
        }
    }
}

Simulator::Request Simulator::compute_answer(Slave& slave, std::size_t index) {
    const Request& r = slave.current;
    if (take_fault(FaultKind::RequestRejected, index)) {
        record_injection(FaultKind::RequestRejected, index);
        // Half the time as in the Danfoss FCM 300 example: PCA 70 00, no PNU echo.
        if (random(2) == 0) return {kRejected, 0, 0, 2};
        return {kRejected, r.pnu, r.ind, 2};
    }
    if (request_code(slave.config.dialect, r.rc).is_change &&
        take_fault(FaultKind::NoAuthority, index)) {
        record_injection(FaultKind::NoAuthority, index);
        return {kNoAuthority, r.pnu, r.ind, 0};
    }
    Parameter* p = find_parameter(slave, r.pnu);
    Request answer;
    switch (r.rc) {
        case kRead:
            answer = {static_cast<std::uint8_t>(p && p->dword ? 2 : 1), r.pnu, r.ind,
                      p ? p->value : 0};
            break;
        case kWriteWord:
        case 14:
            if (p) p->value = r.pva & 0xFFFF;
            answer = {1, r.pnu, r.ind, r.pva & 0xFFFF};
            break;
        case kWriteDword:
        case 13:
            if (p) p->value = r.pva;
            answer = {2, r.pnu, r.ind, r.pva};
            break;
        case kReadDescription: answer = {3, r.pnu, r.ind, 0x0405u + r.ind}; break;
        case kReadArray: answer = {4, r.pnu, r.ind, 0x0100u + r.ind}; break;
        case kReadCount: answer = {6, r.pnu, 0, 10}; break;
        default: answer = {kRejected, r.pnu, r.ind, 18}; break;
    }
    slave.answer_mismatched = false;
    if (take_fault(FaultKind::MismatchedResponse, index)) {
        record_injection(FaultKind::MismatchedResponse, index);
        answer.pnu = static_cast<std::uint16_t>(r.pnu + 1);
        slave.answer_mismatched = true;
    } else if (take_fault(FaultKind::UnexpectedResponseType, index)) {
        record_injection(FaultKind::UnexpectedResponseType, index);
        answer.rc = r.rc == kReadCount ? 1 : 6;
    }
    return answer;
}

void Simulator::slave_step(Slave& slave, std::size_t index) {
    if (!slave.layout.has_pcv) return;
    bool override_active = false;
    Request override_answer;
    if (!slave.seen_valid) {
        slave.answer = {};
    } else {
        // The master acknowledges a spontaneous message by toggling its SPM.
        if (slave.spontaneous_active && slave.seen_spm != slave.spontaneous_master_spm)
            slave.spontaneous_active = false;
        if (slave.seen.rc == 0) {
            slave.working = false;
            slave.current = {};
            slave.answer = {};
        } else if (slave.seen != slave.current) {
            slave.current = slave.seen;
            slave.working = true;
            slave.ready_cycle = cycle_ + random(3);
        }
        if (!slave.spontaneous_active) {
            bool start = false;
            bool late = false;
            if (slave.working && take_fault(FaultKind::SpontaneousMessage, index)) {
                record_injection(FaultKind::SpontaneousMessage, index);
                start = true;
            } else if (!slave.working && !slave.master_busy && slave.seen.rc == 0 &&
                       take_fault(FaultKind::SpontaneousUnacknowledged, index)) {
                record_injection(FaultKind::SpontaneousUnacknowledged, index);
                start = late = true;
            }
            if (start) {
                slave.slave_spm = !slave.slave_spm;
                slave.spontaneous_active = true;
                slave.spontaneous_late_ack = late;
                slave.spontaneous_master_spm = slave.seen_spm;
                slave.spontaneous_time = now_;
                slave.spontaneous = {kSpontaneousWord, kAlarmWordPnu, 0, 0x000A};
            }
        }
        if (slave.working && cycle_ >= slave.ready_cycle && !slave.spontaneous_active) {
            if (take_fault(FaultKind::UnknownCode, index)) {
                record_injection(FaultKind::UnknownCode, index);
                override_active = true;  // the real answer follows in the next cycle
                override_answer = {kUndefinedCode, slave.current.pnu, slave.current.ind, 0};
            } else if (take_fault(FaultKind::ResponseTimeout, index)) {
                record_injection(FaultKind::ResponseTimeout, index);
                slave.working = false;  // never answers
            } else {
                slave.answer = compute_answer(slave, index);
                slave.working = false;
            }
        }
        // An orphan: an answer out of nothing, on a channel idle on both sides (the slave's last
        // output was RC 0 too, so it cannot pass for the previous answer repeated).
        if (!override_active && !slave.working && !slave.master_busy && slave.seen.rc == 0 &&
            slave.answer.rc == 0 && slave.out.rc == 0 && !slave.spontaneous_active &&
            take_fault(FaultKind::OrphanResponse, index)) {
            record_injection(FaultKind::OrphanResponse, index);
            override_active = true;
            override_answer = {1, 520, 0, 240};
        }
    }
    if (override_active) {
        slave.out = override_answer;
    } else if (slave.spontaneous_active) {
        slave.out = slave.spontaneous;
    } else {
        slave.out = slave.answer;
    }
}

void Simulator::exchange(std::size_t index) {
    Slave& slave = slaves_[index];
    const std::uint8_t master = options_.master;
    const std::uint8_t address = slave.config.address;
    if (take_fault(FaultKind::Garbage, index)) {
        record_injection(FaultKind::Garbage, index);
        std::vector<std::uint8_t> junk(3 + random(10));
        for (std::uint8_t& b : junk) {
            b = static_cast<std::uint8_t>(random(256));
            if (is_start_delimiter(b) || b == kEndDelimiter) b ^= 0x01;
        }
        emit(std::move(junk), 20);
    }
    master_step(slave);

    // Master outputs: PCV, control word, main reference, further PCD words.
    std::vector<std::uint8_t> output;
    const Request idle{};
    const Request& request = slave.master_busy ? slave.master_request : idle;
    if (slave.layout.has_pcv)
        append_pcv(output, request.rc, slave.master_spm, request.pnu, request.ind, request.pva);
    append_u16_be(output, 0x047F);
    append_u16_be(output, slave.reference);
    output.resize(slave.layout.output_bytes, 0);
    if (take_fault(FaultKind::ConfigMismatch, index)) {
        record_injection(FaultKind::ConfigMismatch, index);
        output.insert(output.end(), {0x00, 0x00});
    }
    std::vector<std::uint8_t> request_bytes =
        build_telegram({address,
                        master,
                        request_fc(FdlFunction::SrdHigh, slave.fcb, true),
                        {},
                        {},
                        Bytes(output)});
    emit(request_bytes, 40 + random(30));

    // Slave inputs: PCV, status word, main actual value, further PCD words.
    slave_step(slave, index);
    std::vector<std::uint8_t> input;
    if (slave.layout.has_pcv)
        append_pcv(input, slave.out.rc, slave.slave_spm, slave.out.pnu, slave.out.ind,
                   slave.out.pva);
    bool at_reference = slave.actual == slave.reference;
    append_u16_be(input, at_reference ? 0x0F07 : 0x0E07);
    append_u16_be(input, slave.actual);
    for (std::uint16_t extra = 240; input.size() < slave.layout.input_bytes; extra += 10)
        append_u16_be(input, extra);
    std::vector<std::uint8_t> response_bytes =
        build_telegram({master, address, response_fc(FdlStatus::DataLow), {}, {}, Bytes(input)});

    // The slave now knows this cycle's master PCV (it acts on it in the next cycle).
    slave.seen = request;
    slave.seen_spm = slave.master_spm;
    slave.seen_valid = true;

    // Link faults. The master retries once (with the same FCB) when a response is lost or
    // damaged; after that it moves on.
    enum class Fate { Delivered, Lost, BadFcs, Truncated };
    Fate first = Fate::Delivered;
    bool retry_lost = false;
    if (take_fault(FaultKind::FdlRetry, index)) {
        record_injection(FaultKind::FdlRetry, index);
        first = Fate::Lost;
    } else if (take_fault(FaultKind::FdlNoResponse, index)) {
        record_injection(FaultKind::FdlNoResponse, index);
        first = Fate::Lost;
        retry_lost = true;
    } else if (take_fault(FaultKind::FcsError, index)) {
        record_injection(FaultKind::FcsError, index);
        first = Fate::BadFcs;
    } else if (take_fault(FaultKind::MalformedTelegram, index)) {
        record_injection(FaultKind::MalformedTelegram, index);
        first = Fate::Truncated;
    }
    bool delivered = true;
    switch (first) {
        case Fate::Delivered: emit(response_bytes, 30 + random(70)); break;
        case Fate::Lost: advance(bit_ns(100)); break;  // slot time expires
        case Fate::BadFcs: {
            std::vector<std::uint8_t> bad = response_bytes;
            bad[bad.size() - 2] ^= 0x5A;
            emit(std::move(bad), 30 + random(70));
            break;
        }
        case Fate::Truncated: {
            std::vector<std::uint8_t> cut(response_bytes.begin(), response_bytes.end() - 2);
            emit(std::move(cut), 30 + random(70));
            break;
        }
    }
    if (first != Fate::Delivered) {
        emit(request_bytes, 40 + random(30));  // retry: same telegram, same FCB
        if (retry_lost) {
            advance(bit_ns(100));
            delivered = false;
        } else {
            emit(response_bytes, 30 + random(70));
        }
    }
    slave.master_saw_response = delivered;
    if (delivered) {
        slave.master_seen_answer = slave.out;
        slave.master_seen_spm = slave.slave_spm;
    }
    slave.fcb = !slave.fcb;

    // Process data: the drive ramps toward the reference; the reference moves now and then.
    if (slave.actual < slave.reference)
        slave.actual =
            static_cast<std::uint16_t>(std::min<int>(slave.reference, slave.actual + 0x100));
    if (slave.actual > slave.reference)
        slave.actual =
            static_cast<std::uint16_t>(std::max<int>(slave.reference, slave.actual - 0x100));
    if (cycle_ % 400 == 399) {
        static constexpr std::uint16_t kReferences[] = {0x1000, 0x2000, 0x3000, 0x4000};
        slave.reference = kReferences[random(std::size(kReferences))];
    }
}

}  // namespace dpscope
