// The VLT 2000 serial bus of `dpscope simulate --bus vlt2000` (docs/protocol/vlt2000.md): one
// master polls several drives in turn with the 22-character ASCII telegram, 8N1 at the baud rate
// (10 bits a character: 22.9 ms a telegram at 9600 baud), and waits for each reply. Every poll is
// one of the four letters: C (control word only; the drive replies with its status word), R (read
// a parameter; the reply carries its value and decimal position), U (update a parameter; the
// reply echoes the value) or I (read an element of the fault log, the index in bytes 13-18). Now
// and then the master sends a command the drive cannot carry out, and the reply has decimal
// position 9 with the reason code in bytes 17-18 (00..04: vlt2000_simulated_failure). Every
// twentieth cycle the master sends a broadcast (address 00), which nobody answers.
//
// Faults (fault_applies_to_vlt2000: the vlt2000_* kinds, garbage and malformed_telegram) change
// one poll of one drive; docs/decisions.md ("VLT 2000 simulator") says what each one sends.
// Pure logic: the bus model hands its telegrams to a BusEnvironment (the Simulator,
// simulator/bus_model.hpp).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "core/result.hpp"
#include "protocols/vlt2000/vlt2000_telegram.hpp"
#include "simulator/bus_model.hpp"
#include "simulator/fault_kind.hpp"
#include "simulator/fault_spec.hpp"

namespace dpscope {

// "ADDR", 1..99 (the two digits of the telegram; 00 is the broadcast). The RS-485 VLT 3000 takes
// up to 31 units on a segment, 99 with repeaters.
Result<std::uint8_t> parse_vlt2000_drive_spec(std::string_view text);

// The drives of a session given none: 1, 2 and 5.
std::vector<std::uint8_t> default_vlt2000_drives();

// Faults a VLT 2000 session can inject: the vlt2000_* kinds, garbage and malformed_telegram.
bool fault_applies_to_vlt2000(FaultKind kind) noexcept;

// An error when one of `faults` cannot be injected on a VLT 2000 bus with `drives` in a session
// of `cycles` cycles (0: no limit): a fault of another bus, a drive that is not simulated, a cycle
// past the end.
Result<void> check_vlt2000_faults(const std::vector<FaultSpec>& faults,
                                  const std::vector<std::uint8_t>& drives, std::uint64_t cycles);

// The fields of one telegram, as vlt2000_telegram builds it.
struct Vlt2000Fields {
    std::uint8_t address = 0;  // 0..99
    char letter = 'C';
    std::uint16_t word = 0;       // control or status word, 4 bits a character ('@'..'O')
    std::uint16_t parameter = 0;  // 0..9999
    bool negative = false;
    std::uint32_t digits = 0;  // 0..99999
    std::uint8_t decimals = 0;
    // Bytes 13-18 instead of sign and digits (letter I: the index, "000003"); 6 characters.
    std::string_view index;
    bool checksum_disabled = false;  // "??" instead of the checksum
};

// The 22 characters: '<', address, letter, word, parameter, sign, digits (or index), decimals,
// checksum (vlt2000_checksum_of) or "??", '>'.
std::vector<std::uint8_t> vlt2000_telegram(const Vlt2000Fields& fields);

// What the simulated drive does with a command it cannot carry out: the reason code of its reply
// (decimal position 9), or nothing when the command works. 00 the parameter does not exist, 01 no
// write access over the serial line (0500, the address), 02 no such index (0615 has 1..8), 03 an
// index read of a parameter without index, 04 an update of a read-only parameter (a read-out).
std::optional<std::uint8_t> vlt2000_simulated_failure(char letter, std::uint16_t parameter,
                                                      std::uint32_t index) noexcept;

// The simulated drive's status word for `control` (docs/decisions.md "VLT 2000 simulator"):
// control ready and VLT ready always; enabled unless the control word coasts (bits 1, 3); trip
// never; warning and not "frequency range OK" when running outside the warning band;
// speed at reference; serial communication control while the control word's data are valid (bit
// 10); running while the output frequency is above 0. The worked example of the VLT 3000 manual:
// control word 0x047F to a drive running at its reference outside the band gives 0x0B87.
std::uint16_t vlt2000_status_word(std::uint16_t control, bool running, bool at_reference,
                                  bool in_band) noexcept;

class Vlt2000BusModel final : public BusModel {
  public:
    explicit Vlt2000BusModel(std::vector<std::uint8_t> drives);

    // One cycle: the master polls every drive once (and sends a broadcast every twentieth cycle).
    void cycle(BusEnvironment& env, std::uint64_t number) override;

    const std::vector<std::uint8_t>& drives() const noexcept { return drives_; }

    // Timing (dpscope's choice, docs/decisions.md): the master's idle time before a command, the
    // drive's response delay, and how long the master waits for a reply before it moves on.
    static constexpr std::int64_t kMasterGapMinNs = 2'000'000;
    static constexpr std::int64_t kMasterGapMaxNs = 6'000'000;
    static constexpr std::int64_t kResponseMinNs = 2'000'000;
    static constexpr std::int64_t kResponseMaxNs = 8'000'000;
    static constexpr std::int64_t kMasterTimeoutNs = 100'000'000;

    // The control word the master runs the drives with (the VLT 3000 example's: ramp, start, data
    // valid) and the one that stops them (bit 6 ramp stop).
    static constexpr std::uint16_t kRunWord = 0x047F;
    static constexpr std::uint16_t kStopWord = 0x043F;

  private:
    struct Drive {
        std::uint8_t address = 1;
        std::uint16_t control = kRunWord;
        bool started = true;
        std::uint32_t reference = 80;       // 0516, %
        std::uint32_t ramp_up = 300;        // 0205, 0.01 s
        std::uint32_t ramp_down = 300;      // 0206, 0.01 s
        std::uint32_t max_frequency = 500;  // 0202, 0.1 Hz
        std::uint32_t frequency = 0;        // output, 0.1 Hz
        std::uint32_t hours = 12'345;       // 0600
        bool checksum_off = false;          // vlt2000_checksum_disabled: "??" from then on
    };
    // One command, and the drive's reply.
    struct Command {
        char letter = 'C';
        std::uint16_t parameter = 0;
        bool negative = false;
        std::uint32_t digits = 0;
        std::uint8_t decimals = 0;
        std::uint32_t index = 0;  // letter I
    };

    void poll(BusEnvironment& env, std::size_t index);
    void broadcast(BusEnvironment& env, std::uint64_t number);
    Command plan(BusEnvironment& env, const Drive& drive) const;
    Command perform(Drive& drive, const Command& command) const;
    std::vector<std::uint8_t> command_bytes(const Drive& drive, std::uint8_t address,
                                            const Command& command) const;
    std::vector<std::uint8_t> reply_bytes(const Drive& drive, std::uint8_t address,
                                          const Command& reply) const;
    std::uint16_t status_of(const Drive& drive) const;
    void send(BusEnvironment& env, std::vector<std::uint8_t> bytes, std::int64_t gap_ns,
              bool broadcast);
    static std::int64_t between(BusEnvironment& env, std::int64_t low, std::int64_t high);

    std::vector<std::uint8_t> drives_;
    std::vector<Drive> state_;
    // The letter of the last telegram when it was a broadcast (0 otherwise): a second broadcast
    // right after it takes the other letter, or a decoder would read it as a reply to the first.
    char last_broadcast_letter_ = 0;
};

}  // namespace dpscope
