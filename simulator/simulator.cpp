#include "simulator/simulator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "decoder/dp_service.hpp"
#include "decoder/telegram_builder.hpp"

namespace dpscope {

namespace {

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

// Set_Prm's parameter data: lock, watchdog 10 x 10 ms, min TSDR 11 bit times, the ident number,
// group 0; DPV1_Status_1..3 with DPV1_Enable (bit 7 of the first) for a DP-V1 slave.
std::vector<std::uint8_t> prm_bytes_of(const SimulatedSlave& config, std::uint16_t ident) {
    std::vector<std::uint8_t> prm = {
        0x88, 10, 10, 11, static_cast<std::uint8_t>(ident >> 8), static_cast<std::uint8_t>(ident),
        0x00};
    if (config.dialect == Dialect::Profidrive || config.dpv1) {
        prm.push_back(0x80);
        prm.push_back(0x00);
        prm.push_back(0x00);
    }
    return prm;
}

std::vector<SimulatedSlave> slaves_or_default(const SimulatorOptions& options) {
    if (!options.slaves.empty()) return options.slaves;
    return {{3, 1, Dialect::Vlt}, {4, 2, Dialect::Vlt}, {5, 5, Dialect::Vlt}};
}

std::vector<SimulatedDrive> drives_or_default(const SimulatorOptions& options) {
    return options.drives.empty() ? default_drives() : options.drives;
}

constexpr std::uint32_t kFcDefaultBaud = 9600;
constexpr std::uint32_t kVlt2000DefaultBaud = 9600;

std::vector<std::uint8_t> vlt2000_drives_or_default(const SimulatorOptions& options) {
    return options.vlt2000_drives.empty() ? default_vlt2000_drives() : options.vlt2000_drives;
}

// session_span_bound_ns of a VLT 2000 session.
std::int64_t vlt2000_session_span_bound_ns(const SimulatorOptions& options) {
    const double drives = static_cast<double>(vlt2000_drives_or_default(options).size());
    const double baud = options.baud == 0 ? kVlt2000DefaultBaud : static_cast<double>(options.baud);
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
    double cycles = static_cast<double>(options.cycles);
    if (options.max_telegrams != 0 &&
        (options.cycles == 0 || options.max_telegrams < options.cycles))
        cycles = static_cast<double>(options.max_telegrams);
    // After a missing reply the session runs one cycle more.
    const double span = (cycles + 1) * cycle_ns;
    constexpr double kLargest = 9.2e18;
    return span >= kLargest ? std::numeric_limits<std::int64_t>::max()
                            : static_cast<std::int64_t>(std::ceil(span));
}

// session_span_bound_ns of an FC session.
std::int64_t fc_session_span_bound_ns(const SimulatorOptions& options) {
    const double drives = static_cast<double>(drives_or_default(options).size());
    const double baud = options.baud == 0 ? kFcDefaultBaud : static_cast<double>(options.baud);
    // A telegram is at most 257 bytes of 11 bits. A poll: garbage, a request, a stacked one and
    // the answer, each after a gap of at most the master's time-out (the longest wait).
    constexpr double kTelegramBits = 257 * 11;
    const double wait_ns = static_cast<double>(FcBusModel::kMasterTimeoutNs);
    const double poll_ns = 4 * (kTelegramBits * 1e9 / baud + wait_ns);
    // A cycle: every drive polled, a broadcast (twice with one drive). At least --cycle-us.
    const double cycle_ns = std::max(static_cast<double>(options.cycle_us) * 1e3,
                                     drives * poll_ns + 2 * (kTelegramBits * 1e9 / baud + wait_ns));
    double cycles = static_cast<double>(options.cycles);
    if (options.max_telegrams != 0 &&
        (options.cycles == 0 || options.max_telegrams < options.cycles))
        cycles = static_cast<double>(options.max_telegrams);
    const double span = cycles * cycle_ns;
    constexpr double kLargest = 9.2e18;
    return span >= kLargest ? std::numeric_limits<std::int64_t>::max()
                            : static_cast<std::int64_t>(std::ceil(span));
}

}  // namespace

Result<void> check_simulator_faults(const SimulatorOptions& options) {
    if (options.bus == Protocol::Fc)
        return check_fc_faults(options.faults, drives_or_default(options), options.cycles);
    if (options.bus == Protocol::Vlt2000)
        return check_vlt2000_faults(options.faults, vlt2000_drives_or_default(options),
                                    options.cycles);
    return check_faults(options.faults, slaves_or_default(options), options.cycles);
}

std::int64_t session_span_bound_ns(const SimulatorOptions& options) {
    if (options.bus == Protocol::Fc) return fc_session_span_bound_ns(options);
    if (options.bus == Protocol::Vlt2000) return vlt2000_session_span_bound_ns(options);
    const double slaves = static_cast<double>(slaves_or_default(options).size());
    const double baud = options.baud == 0 ? 1'500'000.0 : static_cast<double>(options.baud);
    // A telegram (or garbage record) is at most 64 bytes of 11 bits, after a gap of at most
    // 100 bits; a slot time that expires is 100 bits.
    constexpr double kTelegramBits = 64 * 11 + 100;
    // Start-up: twelve telegrams per slave, then Global_Control and the token.
    const double start_up_bits = (slaves * 12 + 2) * kTelegramBits;
    // A cycle: per slave garbage, request, response and their repeats and two slot times; then a
    // gap poll and its slot time, Global_Control and the token. At least --cycle-us.
    double cycle_bits = slaves * (5 * kTelegramBits + 200) + 3 * kTelegramBits + 100;
    // A DP-V1 slave adds a DP-V1 request and response per cycle, each at most 255 bytes.
    for (const SimulatedSlave& slave : slaves_or_default(options))
        if (slave.dpv1) cycle_bits += 2 * (255 * 11 + 100);
    // Bus-health faults: a slave parameterised anew (ten telegrams more) or a second repeat; a
    // token ring: per further master two tokens, a gap poll, its slot time and the hold.
    bool health_faults = false;
    for (const FaultSpec& spec : options.faults)
        health_faults = health_faults || spec.kind >= FaultKind::StationLost;
    if (health_faults) cycle_bits += slaves * 10 * kTelegramBits;
    const double ring = static_cast<double>(options.ring_masters.size());
    cycle_bits += ring * (3 * kTelegramBits + 100);
    double cycle_ns =
        std::max(static_cast<double>(options.cycle_us) * 1e3, cycle_bits * 1e9 / baud);
    cycle_ns += ring * std::max(static_cast<double>(options.token_hold_us) * 1e3, 40 * 1e9 / baud);
    // Every cycle writes one telegram at least (the token).
    double cycles = static_cast<double>(options.cycles);
    if (options.max_telegrams != 0 &&
        (options.cycles == 0 || options.max_telegrams < options.cycles))
        cycles = static_cast<double>(options.max_telegrams);
    // After a time-out fault the session runs on until the master has given up, plus ten cycles.
    // A slave lost (station_lost) in the last cycle is silent, then parameterised anew, after it.
    const double tail_ns =
        static_cast<double>(options.master_give_up_ms) * 1e6 +
        static_cast<double>(options.cycle_us) * 1e4 + cycle_ns +
        (health_faults ? static_cast<double>(kStationLostCycles + 1) * cycle_ns : 0.0);
    const double span = start_up_bits * 1e9 / baud + cycles * cycle_ns + tail_ns;
    constexpr double kLargest = 9.2e18;  // below the largest int64 (9.22e18)
    return span >= kLargest ? std::numeric_limits<std::int64_t>::max()
                            : static_cast<std::int64_t>(std::ceil(span));
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
    rng_state_ = options_.seed * 0x9E3779B97F4A7C15ULL + 0x2545F4914F6CDD1DULL;
    now_ = std::max<std::int64_t>(0, options_.start_time_ns);
    if (options_.bus == Protocol::Fc) {
        // An FC bus: the drives, and one address-only entry each for the faults.
        options_.drives = drives_or_default(options_);
        options_.slaves.clear();
        if (options_.baud == 0) options_.baud = kFcDefaultBaud;
        for (const SimulatedDrive& drive : options_.drives) {
            Slave entry;
            entry.config.address = drive.address;
            slaves_.push_back(entry);
        }
        fc_.emplace(options_.drives);
        started_ = true;  // no start-up
    } else if (options_.bus == Protocol::Vlt2000) {
        // A VLT 2000 bus: likewise, 8N1.
        options_.vlt2000_drives = vlt2000_drives_or_default(options_);
        options_.slaves.clear();
        if (options_.baud == 0) options_.baud = kVlt2000DefaultBaud;
        character_bits_ = 10;
        for (std::uint8_t address : options_.vlt2000_drives) {
            Slave entry;
            entry.config.address = address;
            slaves_.push_back(entry);
        }
        vlt2000_.emplace(options_.vlt2000_drives);
        started_ = true;  // no start-up
    } else {
        options_.slaves = slaves_or_default(options_);
        if (options_.baud == 0) options_.baud = 1'500'000;
    }
    std::uint8_t highest = options_.master;
    for (const SimulatedSlave& config : options_.slaves) {
        Slave slave;
        slave.config = config;
        slave.layout = ppo_layout_of_type(config.ppo_type, PpoSource::Option);
        slave.ident = config.dialect == Dialect::Vlt  ? 0x0402
                      : config.dialect == Dialect::Ge ? 0x6002
                                                      : 0x6001;
        if (slave.layout.has_pcv)
            slave.channel.emplace(config.dialect,
                                  std::int64_t{options_.master_give_up_ms} * 1'000'000);
        if (config.dpv1)
            slave.dpv1.emplace(config.dialect, config.address,
                               std::int64_t{options_.master_give_up_ms} * 1'000'000);
        slave.actual = 0;
        slaves_.push_back(std::move(slave));
        highest = std::max(highest, config.address);
    }
    gap_address_ = static_cast<std::uint8_t>(std::min(highest + 1, 125));
    if (!options_.ring_masters.empty()) {
        for (int tries = 0; tries < 126 && address_in_use(gap_address_); ++tries)
            gap_address_ = static_cast<std::uint8_t>(gap_address_ >= 125 ? 1 : gap_address_ + 1);
        for (std::uint8_t ring_master : options_.ring_masters) {
            std::uint8_t gap = ring_master;
            for (int tries = 0; tries < 126; ++tries) {
                gap = static_cast<std::uint8_t>(gap >= 125 ? 1 : gap + 1);
                if (!address_in_use(gap)) break;
            }
            ring_gap_addresses_.push_back(gap);
        }
    }
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
    emit_after(std::move(bytes), bit_ns(gap_bits));
}

void Simulator::emit_after(std::vector<std::uint8_t> bytes, std::int64_t gap_ns) {
    if (options_.max_telegrams != 0 && queued_ >= options_.max_telegrams) return;
    advance(gap_ns);
    if (!recording_) {
        advance(bit_ns(bytes.size() * character_bits_));
        return;
    }
    std::int64_t at = now_;
    advance(bit_ns(bytes.size() * character_bits_));
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
        } else if (options_.cycles == 0
                       ? options_.max_telegrams != 0
                       : cycle_ < options_.cycles || now_ < hold_open_until_ || recovering_ > 0) {
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
        request(sap::kSetPrm, prm_bytes_of(slave.config, slave.ident), FdlFunction::SrdHigh);
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
    if (!options_.ring_masters.empty()) {
        pass_token_ring();
        return;
    }
    std::vector<std::uint8_t> token;
    append_token(token, master, master);
    emit(std::move(token), 40);
}

// The FC bus model's view of the session: its random numbers, faults and clock.
class Simulator::FcEnvironment final : public FcBusEnvironment {
  public:
    explicit FcEnvironment(Simulator& simulator) : simulator_(simulator) {}
    std::uint64_t random(std::uint64_t bound) override { return simulator_.random(bound); }
    bool inject(FaultKind kind, std::size_t drive) override {
        return simulator_.inject(kind, drive);
    }
    void send(std::vector<std::uint8_t> bytes, std::int64_t gap_ns) override {
        simulator_.emit_after(std::move(bytes), gap_ns);
    }
    void wait(std::int64_t ns) override { simulator_.advance(ns); }

  private:
    Simulator& simulator_;
};

// The VLT 2000 bus model's view of the session: its random numbers, faults and clock.
class Simulator::Vlt2000Environment final : public Vlt2000BusEnvironment {
  public:
    explicit Vlt2000Environment(Simulator& simulator) : simulator_(simulator) {}
    std::uint64_t random(std::uint64_t bound) override { return simulator_.random(bound); }
    bool inject(FaultKind kind, std::size_t drive) override {
        return simulator_.inject(kind, drive);
    }
    void send(std::vector<std::uint8_t> bytes, std::int64_t gap_ns) override {
        simulator_.emit_after(std::move(bytes), gap_ns);
    }
    void wait(std::int64_t ns) override { simulator_.advance(ns); }

  private:
    Simulator& simulator_;
};

void Simulator::generate_cycle() {
    const std::int64_t cycle_start = now_;
    arm_faults();
    if (fc_ || vlt2000_) {
        if (fc_) {
            FcEnvironment environment(*this);
            fc_->cycle(environment, cycle_);
        } else {
            Vlt2000Environment environment(*this);
            vlt2000_->cycle(environment, cycle_);
        }
        const std::int64_t cycle_ns = static_cast<std::int64_t>(options_.cycle_us) * 1000;
        if (now_ - cycle_start < cycle_ns) advance(cycle_ns - (now_ - cycle_start));
        ++cycle_;
        return;
    }
    for (std::size_t i = 0; i < slaves_.size(); ++i)
        exchange(i);
    // Acyclic services after the cyclic exchanges: parameter access with each DP-V1 slave.
    for (std::size_t i = 0; i < slaves_.size(); ++i)
        if (slaves_[i].dpv1 && slaves_[i].silent == 0 && !slaves_[i].reparameterise)
            parameter_access(i);
    const std::uint8_t master = options_.master;
    if (cycle_ % 100 == 99) {
        // Gap maintenance: ask the next address whether a station appeared (nobody answers).
        emit(build_telegram({gap_address_, master, request_fc(FdlFunction::FdlStatus), {}, {}, {}}),
             60);
        advance(bit_ns(100));  // slot time expires
        // The next address nobody uses (the masters and the slaves are on the bus).
        for (int tries = 0; tries < 126; ++tries) {
            gap_address_ = static_cast<std::uint8_t>(gap_address_ >= 125 ? 1 : gap_address_ + 1);
            if (!address_in_use(gap_address_)) break;
        }
    }
    if (cycle_ % 250 == 249) {
        std::vector<std::uint8_t> operate = {0x00, 0x00};
        emit(build_telegram({kBroadcastAddress, master, request_fc(FdlFunction::SdnHigh),
                             sap::kGlobalControl, sap::kMaster, Bytes(operate)}),
             60);
    }
    if (options_.ring_masters.empty()) {
        std::vector<std::uint8_t> token;
        append_token(token, master, master);
        emit(std::move(token), 40);
    } else {
        pass_token_ring();
    }
    const std::int64_t cycle_ns = static_cast<std::int64_t>(options_.cycle_us) * 1000;
    if (now_ - cycle_start < cycle_ns) advance(cycle_ns - (now_ - cycle_start));
    ++cycle_;
}

bool Simulator::address_in_use(std::uint8_t address) const {
    if (address == options_.master) return true;
    if (std::find(options_.ring_masters.begin(), options_.ring_masters.end(), address) !=
        options_.ring_masters.end())
        return true;
    return std::any_of(slaves_.begin(), slaves_.end(),
                       [&](const Slave& slave) { return slave.config.address == address; });
}

void Simulator::pass_token_ring() {
    const std::int64_t hold_ns = std::max<std::int64_t>(std::int64_t{options_.token_hold_us} * 1000,
                                                        bit_ns(40));  // at least the sync pause
    std::uint8_t holder = options_.master;
    for (std::size_t i = 0; i < options_.ring_masters.size(); ++i) {
        const std::uint8_t next = options_.ring_masters[i];
        std::vector<std::uint8_t> token;
        append_token(token, next, holder);
        if (i == 0) {
            emit(std::move(token), 40);
        } else {
            emit_after(std::move(token), 0);  // the previous holder's hold ends now
        }
        const std::int64_t received = now_;
        // Gap maintenance now and then: is there a new station at the next free address?
        if (cycle_ % 20 == 10) {
            std::uint8_t& gap = ring_gap_addresses_[i];
            emit(build_telegram({gap, next, request_fc(FdlFunction::FdlStatus), {}, {}, {}}), 60);
            advance(bit_ns(100));  // slot time expires
            for (int tries = 0; tries < 126; ++tries) {
                gap = static_cast<std::uint8_t>(gap >= 125 ? 1 : gap + 1);
                if (!address_in_use(gap)) break;
            }
        }
        if (now_ - received < hold_ns) advance(hold_ns - (now_ - received));
        holder = next;
    }
    std::vector<std::uint8_t> token;
    append_token(token, options_.master, holder);
    emit_after(std::move(token), 0);
}

void Simulator::request_srd(Slave& slave, std::optional<std::uint8_t> dsap,
                            std::vector<std::uint8_t> du) {
    TelegramSpec spec{slave.config.address,
                      options_.master,
                      request_fc(FdlFunction::SrdHigh, slave.fcb, true),
                      dsap,
                      dsap ? std::optional<std::uint8_t>(sap::kMaster) : std::nullopt,
                      Bytes(du)};
    emit(build_telegram(spec), 60 + random(40));
}

void Simulator::answer_sd2(Slave& slave, std::optional<std::uint8_t> ssap,
                           std::vector<std::uint8_t> du, FdlStatus status) {
    TelegramSpec spec{options_.master,
                      slave.config.address,
                      response_fc(status),
                      ssap ? std::optional<std::uint8_t>(sap::kMaster) : std::nullopt,
                      ssap,
                      Bytes(du)};
    emit(build_telegram(spec), 30 + random(70));
    slave.fcb = !slave.fcb;
}

void Simulator::answer_short_ack(Slave& slave) {
    std::vector<std::uint8_t> ack;
    append_short_ack(ack);
    emit(std::move(ack), 30 + random(70));
    slave.fcb = !slave.fcb;
}

void Simulator::silent_poll(std::size_t index) {
    // A lost slave: the master asks for its diagnosis instead of exchanging data, repeats the
    // request once (retry limit 1) and hears nothing.
    Slave& slave = slaves_[index];
    request_srd(slave, sap::kSlaveDiag, {});
    advance(bit_ns(100));  // slot time expires
    request_srd(slave, sap::kSlaveDiag, {});
    advance(bit_ns(100));
    slave.fcb = !slave.fcb;
    if (--slave.silent == 0) slave.reparameterise = true;
}

void Simulator::parameterise_again(std::size_t index) {
    // The slave answers the master's Slave_Diag: not parameterised (Station_Not_Ready, Prm_Req,
    // no master); the master parameterises and configures it, and checks its diagnosis again.
    Slave& slave = slaves_[index];
    const auto ident_hi = static_cast<std::uint8_t>(slave.ident >> 8);
    const auto ident_lo = static_cast<std::uint8_t>(slave.ident);
    request_srd(slave, sap::kSlaveDiag, {});
    answer_sd2(slave, sap::kSlaveDiag, {0x02, 0x05, 0x00, kNoMasterAddress, ident_hi, ident_lo});
    request_srd(slave, sap::kSetPrm, prm_bytes_of(slave.config, slave.ident));
    answer_short_ack(slave);
    request_srd(slave, sap::kChkCfg, cfg_bytes_of(slave.config.ppo_type));
    answer_short_ack(slave);
    request_srd(slave, sap::kSlaveDiag, {});
    answer_sd2(slave, sap::kSlaveDiag, {0x00, 0x0C, 0x00, options_.master, ident_hi, ident_lo});
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
            if (fc_) return fault_applies_to_fc(spec.kind);
            if (vlt2000_) return fault_applies_to_vlt2000(spec.kind);
            if (fault_needs_dpv1(spec.kind) && !slaves_[i].dpv1) return false;
            if (fault_needs_spontaneous_messages(spec.kind) &&
                !has_spontaneous_messages(slaves_[i].config.dialect))
                return false;
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

void Simulator::take(FaultKind kind, std::size_t slave, std::uint64_t& armed) {
    --armed;
    const Injection injection{kind, cycle_, slaves_[slave].config.address, queued_ + 1};
    ++injection_count_;
    if (injections_.size() < kKeptInjections) injections_.push_back(injection);
    once_faults_.record(injection);
    if (on_injection_) on_injection_(injection);
    if (kind == FaultKind::ResponseTimeout || kind == FaultKind::SpontaneousUnacknowledged ||
        kind == FaultKind::Dpv1ResponseTimeout) {
        const std::int64_t give_up = std::int64_t{options_.master_give_up_ms} * 1'000'000;
        hold_open_until_ = std::max(
            hold_open_until_, later(now_, give_up + std::int64_t{options_.cycle_us} * 10'000));
    }
    // A VLT 2000 drive that does not reply: one cycle more, so that the master's next command
    // (which shows the reply missing) is in the capture.
    if (kind == FaultKind::Vlt2000NoResponse)
        hold_open_until_ = std::max(
            hold_open_until_, later(now_, Vlt2000BusModel::kMasterTimeoutNs +
                                              std::int64_t{options_.cycle_us} * 1000 + 1'000'000));
}

// A slave's parameter-channel model draws on the session's random sequence, on the faults armed
// for that slave, and on the bus clock.
class Simulator::SlaveEnvironment final : public ChannelEnvironment {
  public:
    SlaveEnvironment(Simulator& simulator, std::size_t index)
        : simulator_(simulator), index_(index) {}
    std::uint64_t random(std::uint64_t bound) override { return simulator_.random(bound); }
    bool inject(FaultKind kind) override { return simulator_.inject(kind, index_); }
    std::int64_t now() const override { return simulator_.now_; }
    std::uint64_t cycle() const override { return simulator_.cycle_; }

  private:
    Simulator& simulator_;
    std::size_t index_;
};

void Simulator::parameter_access(std::size_t index) {
    Slave& slave = slaves_[index];
    const std::uint8_t master = options_.master;
    const std::uint8_t address = slave.config.address;
    SlaveEnvironment environment(*this, index);
    std::vector<std::uint8_t> pdu;
    if (!slave.dpv1->master_request(environment, pdu)) return;
    emit(build_telegram({address, master, request_fc(FdlFunction::SrdHigh, slave.fcb, true),
                         sap::kMsacC1, sap::kMsacC1, Bytes(pdu)}),
         40 + random(30));
    slave.dpv1->slave_response(environment, pdu);
    emit(build_telegram({master, address, response_fc(FdlStatus::DataLow), sap::kMsacC1,
                         sap::kMsacC1, Bytes(pdu)}),
         30 + random(70));
    slave.fcb = !slave.fcb;
}

void Simulator::exchange(std::size_t index) {
    Slave& slave = slaves_[index];
    const std::uint8_t master = options_.master;
    const std::uint8_t address = slave.config.address;
    if (slave.silent > 0) {
        silent_poll(index);
        return;
    }
    if (slave.reparameterise) {
        // Back from station_lost: it answers the master's Slave_Diag again.
        parameterise_again(index);
        slave.reparameterise = false;
        --recovering_;
        return;
    }
    if (inject(FaultKind::Garbage, index)) {
        std::vector<std::uint8_t> junk(3 + random(10));
        for (std::uint8_t& b : junk) {
            b = static_cast<std::uint8_t>(random(256));
            if (is_start_delimiter(b) || b == kEndDelimiter) b ^= 0x01;
        }
        emit(std::move(junk), 20);
    }
    if (inject(FaultKind::AnswerWrongKind, index)) {
        // The master checks the station with FDL_Status; the slave answers with data.
        emit(build_telegram({address, master, request_fc(FdlFunction::FdlStatus), {}, {}, {}}),
             60 + random(40));
        std::vector<std::uint8_t> data = {0x0F, 0x07};
        emit(
            build_telegram({master, address, response_fc(FdlStatus::DataLow), {}, {}, Bytes(data)}),
            30 + random(70));
        slave.fcb = true;  // the first SRD after FDL_Status carries FCB = 1
    }
    SlaveEnvironment environment(*this, index);
    if (slave.channel) slave.channel->master_step(environment);

    // Master outputs: PCV, control word, main reference, further PCD words.
    std::vector<std::uint8_t> output;
    if (slave.channel) {
        const SimulatedPcv request = slave.channel->master_pcv();
        append_pcv(output, request.rc, slave.channel->master_spm(), request.pnu, request.ind,
                   request.pva);
    }
    append_u16_be(output, 0x047F);
    append_u16_be(output, slave.reference);
    output.resize(slave.layout.output_bytes, 0);
    if (inject(FaultKind::ConfigMismatch, index)) {
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
    if (slave.channel) slave.channel->slave_step(environment);
    std::vector<std::uint8_t> input;
    if (slave.channel) {
        const SimulatedPcv answer = slave.channel->slave_pcv();
        append_pcv(input, answer.rc, slave.channel->slave_spm(), answer.pnu, answer.ind,
                   answer.pva);
    }
    bool at_reference = slave.actual == slave.reference;
    append_u16_be(input, at_reference ? 0x0F07 : 0x0E07);
    append_u16_be(input, slave.actual);
    for (std::uint16_t extra = 240; input.size() < slave.layout.input_bytes; extra += 10)
        append_u16_be(input, extra);
    std::vector<std::uint8_t> response_bytes =
        build_telegram({master, address, response_fc(FdlStatus::DataLow), {}, {}, Bytes(input)});

    // The slave now knows this cycle's master PCV (it acts on it in the next cycle).
    if (slave.channel) slave.channel->slave_sees_request();

    // Link faults. The master retries once (with the same FCB) when a response is lost or
    // damaged; after that it moves on.
    enum class Fate { Delivered, Lost, BadFcs, Truncated };
    Fate first = Fate::Delivered;
    bool retry_lost = false;
    bool second_retry = false;  // repeats: the first repeat is lost too
    if (inject(FaultKind::FdlRetry, index)) {
        first = Fate::Lost;
    } else if (inject(FaultKind::FdlNoResponse, index)) {
        first = Fate::Lost;
        retry_lost = true;
    } else if (inject(FaultKind::FcsError, index)) {
        first = Fate::BadFcs;
    } else if (inject(FaultKind::MalformedTelegram, index)) {
        first = Fate::Truncated;
    } else if (inject(FaultKind::StationLost, index)) {
        // Silent from now on for kStationLostCycles cycles, this one included.
        first = Fate::Lost;
        retry_lost = true;
        slave.silent = kStationLostCycles - 1;
        slave.reparameterise = slave.silent == 0;
        ++recovering_;
    } else if (inject(FaultKind::Repeats, index)) {
        first = Fate::Lost;
        second_retry = true;
    }
    // What the slave answers when its response gets through.
    enum class Answer { Data, ShortAck, Refusal, DataHigh };
    Answer answer = Answer::Data;
    bool resync = false;
    bool answer_twice = false;
    if (first == Fate::Delivered) {
        if (inject(FaultKind::AnswerShortAck, index)) {
            answer = Answer::ShortAck;
        } else if (inject(FaultKind::Refusal, index)) {
            answer = Answer::Refusal;
        } else if (inject(FaultKind::Resync, index)) {
            answer = Answer::DataHigh;
            resync = true;
        } else if (inject(FaultKind::DiagFault, index)) {
            answer = Answer::DataHigh;
        } else if (inject(FaultKind::AnswerNotAsked, index)) {
            answer_twice = true;
        }
    }
    bool delivered = true;
    switch (first) {
        case Fate::Delivered:
            switch (answer) {
                case Answer::Data: emit(response_bytes, 30 + random(70)); break;
                case Answer::ShortAck: {
                    std::vector<std::uint8_t> ack;
                    append_short_ack(ack);
                    emit(std::move(ack), 30 + random(70));
                    delivered = false;
                    break;
                }
                case Answer::Refusal:
                    emit(build_telegram(
                             {master, address, response_fc(FdlStatus::NoService), {}, {}, {}}),
                         30 + random(70));
                    delivered = false;
                    break;
                case Answer::DataHigh:
                    emit(build_telegram({master,
                                         address,
                                         response_fc(FdlStatus::DataHigh),
                                         {},
                                         {},
                                         Bytes(input)}),
                         30 + random(70));
                    break;
            }
            if (answer_twice) emit(response_bytes, 30 + random(70));
            break;
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
    if (second_retry) {
        emit(request_bytes, 40 + random(30));  // the first repeat, lost as well
        advance(bit_ns(100));
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
    if (slave.channel) slave.channel->master_sees_response(delivered);
    slave.fcb = !slave.fcb;
    if (answer == Answer::DataHigh) {
        // Diagnosis pending: the master asks for it before the next Data_Exchange.
        if (resync) {
            // The slave left data exchange (a watchdog, a restart): parameterised again.
            parameterise_again(index);
        } else {
            const auto ident_hi = static_cast<std::uint8_t>(slave.ident >> 8);
            const auto ident_lo = static_cast<std::uint8_t>(slave.ident);
            request_srd(slave, sap::kSlaveDiag, {});
            // Ext_Diag with a device-related block (header: length 3, two bytes).
            answer_sd2(slave, sap::kSlaveDiag,
                       {0x08, 0x0C, 0x00, master, ident_hi, ident_lo, 0x03, 0x01, 0x00});
        }
    }

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
