// The Danfoss FC protocol bus of `dpscope simulate --bus fc` (docs/protocol/fc-protocol.md): one
// master polls several drives in turn, 8E1 at the baud rate (11 bits a character). Each poll is a
// process block (control word and reference; status word and actual value back) or a parameter
// command with the process data beside it: reads of word and double-word parameters, indexed reads
// (15-30 alarm log), word writes (AK 2/14, answered with AK 1), double-word writes (AK 3/13,
// answered with AK 2), text reads (AK 15, IND high 0x04, answered with a text block LGE 10 + n),
// and now and then a write the drive refuses (AK 7: 1 read-only parameter, 2 out of range). Every
// fiftieth cycle the master also sends a broadcast, which nobody answers.
//
// Faults (simulator/fault_kind.hpp, fault_is_fc, plus the shared garbage and malformed_telegram)
// change one poll of one drive; docs/decisions.md ("FC simulator") says what each one sends.
// Pure logic: the bus model hands its telegrams to a BusEnvironment (the Simulator,
// simulator/bus_model.hpp).
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "core/result.hpp"
#include "protocols/fc/fc_telegram.hpp"
#include "simulator/bus_model.hpp"
#include "simulator/fault_kind.hpp"
#include "simulator/fault_spec.hpp"

namespace dpscope {

struct SimulatedDrive {
    std::uint8_t address = 1;
    // The address byte's format the master uses for this drive: 1-126 (bit 7 set) by default, as
    // the FC 360 documents and [C:boruta_fc] builds it; 1-31 only for addresses 1..31.
    FcAddressFormat format = FcAddressFormat::Long;
};

// "ADDR" or "ADDR:FORMAT" with FORMAT 1-126 (the default, ADDR 1..126) or 1-31 (ADDR 1..31),
// e.g. "7", "3:1-31", "100:1-126".
Result<SimulatedDrive> parse_drive_spec(std::string_view text);

// The address byte the master sends to `drive`.
std::uint8_t fc_adr_of(const SimulatedDrive& drive) noexcept;

// The drives of a session given none: 1 and 2 in the 1-126 format, 3 in the 1-31 format.
std::vector<SimulatedDrive> default_drives();

// An error when one of `faults` cannot be injected on an FC bus with `drives` in a session of
// `cycles` cycles (0: no limit): a PROFIBUS fault, a drive that is not simulated, a cycle past
// the end.
Result<void> check_fc_faults(const std::vector<FaultSpec>& faults,
                             const std::vector<SimulatedDrive>& drives, std::uint64_t cycles);

// Faults an FC session can inject: the fc_* kinds, garbage and malformed_telegram.
bool fault_applies_to_fc(FaultKind kind) noexcept;

// Building FC telegrams: STX, LGE, ADR, `data`, BCC.
std::vector<std::uint8_t> build_fc_telegram(std::uint8_t adr,
                                            const std::vector<std::uint8_t>& data);

class FcBusModel final : public BusModel {
  public:
    explicit FcBusModel(std::vector<SimulatedDrive> drives);

    // One cycle: the master polls every drive once (and sends a broadcast every fiftieth cycle).
    void cycle(BusEnvironment& env, std::uint64_t number) override;

    const std::vector<SimulatedDrive>& drives() const noexcept { return drives_; }

    // Timing (dpscope's choice, docs/decisions.md): the master's idle time before a telegram,
    // the drive's response time (below the 20 ms fc_late_response judges by), the late one, and
    // how long the master waits for an answer before it moves on.
    static constexpr std::int64_t kMasterGapMinNs = 1'000'000;
    static constexpr std::int64_t kMasterGapMaxNs = 4'000'000;
    static constexpr std::int64_t kResponseMinNs = 2'000'000;
    static constexpr std::int64_t kResponseMaxNs = 8'000'000;
    static constexpr std::int64_t kLateResponseMinNs = 45'000'000;
    static constexpr std::int64_t kLateResponseMaxNs = 90'000'000;
    static constexpr std::int64_t kMasterTimeoutNs = 100'000'000;

  private:
    struct Drive {
        SimulatedDrive config;
        std::uint8_t adr = 0;
        std::uint16_t reference = 0x2000;
        std::uint16_t actual = 0;
        std::uint32_t speed_limit = 500;  // 4-14, 0.1 Hz
        std::uint32_t ramp_up = 300;      // 3-41, 0.01 s
        std::uint32_t ramp_down = 300;    // 3-42, 0.01 s
        std::uint32_t motor_frequency = 50;
    };
    // One parameter command (or none: a process block) and what the drive answers.
    struct Command {
        bool parameter = false;
        std::uint8_t ak = 0;
        std::uint16_t pnu = 0;
        std::uint8_t ind_high = 0;
        std::uint8_t index = 0;
        std::uint32_t pwe = 0;
    };
    struct Answer {
        std::uint8_t ak = 0;
        std::uint16_t pnu = 0;
        std::uint8_t ind_high = 0;
        std::uint8_t index = 0;
        std::uint32_t pwe = 0;
        std::string_view text;  // AK 15
    };

    void poll(BusEnvironment& env, std::size_t index);
    void broadcast(BusEnvironment& env, std::uint64_t number);
    static Command plan(BusEnvironment& env);
    Answer perform(Drive& drive, const Command& command);
    std::vector<std::uint8_t> request_bytes(const Drive& drive, const Command& command) const;
    std::vector<std::uint8_t> response_bytes(const Drive& drive, const Command& command,
                                             const Answer& answer) const;
    static std::int64_t between(BusEnvironment& env, std::int64_t low, std::int64_t high);

    std::vector<SimulatedDrive> drives_;
    std::vector<Drive> state_;
};

}  // namespace dpscope
