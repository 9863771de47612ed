// Decodes a VLT 2000 serial capture (docs/protocol/vlt2000.md) telegram by telegram, in capture
// order, into DecodedTelegram::vlt2000. Master and drives share the line and the telegram has no
// direction of its own, so the decoder tells commands from replies (docs/decisions.md, "VLT 2000:
// command or reply"):
//   - decimal position 9 (the command failed) only a drive sends: a reply wherever it comes;
//   - a telegram that follows a command is its reply when it carries the command's address and
//     control letter, is not the command's characters again, and comes within the response
//     window; a broadcast (address 00) is answered by nobody, but a telegram with address 00 and
//     its letter right after one is taken for a reply (the tracker reports it);
//   - everything else is a command; a command cut short or with a field that is no number
//     expects no reply (a drive drops it); one wrong only in its checksum may still be answered
//     (the error may be the tap's alone), so its reply is recognised.
// The header's roles: master 0 (the master has no address), slave the drive's address (0 for a
// broadcast); a reply names the command it answers.
#pragma once

#include <array>
#include <cstdint>
#include <memory>

#include "core/protocol_lane.hpp"
#include "core/telegram.hpp"
#include "core/time.hpp"
#include "protocols/vlt2000/vlt2000_telegram.hpp"

namespace dpscope {

struct Vlt2000DecoderOptions {
    // A telegram later than this after a command is not its reply (no time: no limit).
    std::int64_t response_window_ns = 1'000'000'000;
    // Judge the checksum (--vlt2000-checksum check|ignore). That the VLT 2000 uses the VLT
    // 3000/3500 rule is dpscope's reading (docs/protocol/vlt2000.md); with a drive that computes
    // it otherwise, `false` decodes its telegrams without a checksum problem.
    bool check_checksum = true;
    // What names the PNUs (drives/parameter_naming.hpp): put on every telegram decoded
    // (DecodedTelegram::naming); null: nothing. Set from LaneOptions::naming by the factory.
    std::shared_ptr<const ParameterNaming> naming{};
};

class Vlt2000Decoder final : public TelegramDecoder {
  public:
    explicit Vlt2000Decoder(Vlt2000DecoderOptions options = {}) noexcept;

    // Decodes one telegram. The result refers to `bytes` and stays valid until the next call.
    const DecodedTelegram& decode(Bytes bytes, std::int64_t time_ns, std::uint64_t frame) override;
    std::unique_ptr<TelegramDecoder> clone() const override {
        return std::make_unique<Vlt2000Decoder>(*this);
    }

    const Vlt2000DecoderOptions& options() const noexcept { return options_; }

  private:
    Direction direction_of(const Vlt2000Telegram& v) const noexcept;

    // The command waiting for its reply (at most one: the master waits for each).
    struct Pending {
        bool valid = false;
        std::uint64_t frame = 0;
        std::int64_t time_ns = kNoTime;
        std::uint8_t address = 0;
        std::uint8_t letter_char = 0;
        std::array<std::uint8_t, kVlt2000TelegramSize> bytes{};
    };

    Vlt2000DecoderOptions options_;
    DecodedTelegram t_;
    Pending pending_;
};

// Fills `v` from `bytes` (one record: a telegram, or what the framer took for one), recording
// every problem with its byte offset (a wrong checksum only when `check_checksum`).
void parse_vlt2000(Bytes bytes, Vlt2000Telegram& v, bool check_checksum = true) noexcept;

}  // namespace dpscope
