// The simulated session (simulator/simulator.hpp): the options resolved per bus, the seeded
// random numbers, the bus clock and the queue of telegrams, the cycles, the FC and VLT 2000 bus
// models' view of the session, and the faults armed per cycle and taken. The PROFIBUS DP
// telegrams: protocols/profibus/dp_bus_model.cpp; the session's length: simulator/session_span.cpp.
#include "simulator/simulator.hpp"

#include <algorithm>
#include <limits>

#include "protocols/profibus/dp_service.hpp"
#include "protocols/profibus/telegram_builder.hpp"
#include "simulator/session_defaults.hpp"

namespace dpscope {

using detail::slaves_or_default;

Result<void> check_simulator_faults(const SimulatorOptions& options) {
    return simulated_bus(options.bus).check_faults(options);
}

std::vector<std::string> faults_not_injected(const SimulatorOptions& options,
                                             const std::vector<Injection>& injections) {
    OnceFaultCheck check(options.faults);
    for (const Injection& injection : injections)
        check.record(injection);
    return check.missing();
}

Simulator::Simulator(SimulatorOptions options)
    : options_(std::move(options)),
      bus_(&simulated_bus(options_.bus)),
      once_faults_(options_.faults) {
    rng_state_ = options_.seed * 0x9E3779B97F4A7C15ULL + 0x2545F4914F6CDD1DULL;
    now_ = std::max<std::int64_t>(0, options_.start_time_ns);
    character_bits_ = bus_->character_bits;
    if (bus_->make_model) {
        // A bus of drives (FC, VLT 2000): its model, and one address-only entry per drive for
        // the faults.
        std::vector<std::uint8_t> drives;
        model_ = bus_->make_model(options_, drives);
        options_.slaves.clear();
        for (std::uint8_t address : drives) {
            Slave entry;
            entry.config.address = address;
            slaves_.push_back(entry);
        }
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

// A bus model's view of the session: its random numbers, faults and clock.
class Simulator::ModelEnvironment final : public BusEnvironment {
  public:
    explicit ModelEnvironment(Simulator& simulator) : simulator_(simulator) {}
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
    if (model_) {
        ModelEnvironment environment(*this);
        model_->cycle(environment, cycle_);
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
            if (model_) return bus_->fault_applies(spec.kind);
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
    // The bus's own: a VLT 2000 drive that does not reply, one cycle more, so that the master's
    // next command (which shows the reply missing) is in the capture.
    if (bus_->runs_on_ns)
        if (const std::int64_t runs_on = bus_->runs_on_ns(kind, options_); runs_on > 0)
            hold_open_until_ = std::max(hold_open_until_, later(now_, runs_on));
}

}  // namespace dpscope
