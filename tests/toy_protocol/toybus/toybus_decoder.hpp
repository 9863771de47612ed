// Decodes a toybus capture telegram by telegram, in capture order, into DecodedTelegram::toybus.
// The lead character says the direction ('?' and '!' from the master, '=' and '#' from a drive).
// A response names the request it answers when it carries the address and parameter of the
// request pending (the last one, within the response window). The header's roles: master 0 (the
// master has no address), slave the drive's address.
#pragma once

#include <cstdint>

#include "core/protocol_lane.hpp"
#include "core/telegram.hpp"
#include "core/time.hpp"
#include "protocols/toybus/toybus_telegram.hpp"

namespace dpscope {

struct ToybusDecoderOptions {
    // A response later than this after the request does not answer it (no time: no limit).
    std::int64_t response_window_ns = 1'000'000'000;
};

class ToybusDecoder final : public TelegramDecoder {
  public:
    explicit ToybusDecoder(ToybusDecoderOptions options = {}) noexcept;

    // Decodes one telegram. The result refers to `bytes` and stays valid until the next call.
    const DecodedTelegram& decode(Bytes bytes, std::int64_t time_ns, std::uint64_t frame) override;
    std::unique_ptr<TelegramDecoder> clone() const override {
        return std::make_unique<ToybusDecoder>(*this);
    }

    const ToybusDecoderOptions& options() const noexcept { return options_; }

  private:
    struct Pending {
        bool valid = false;
        std::uint64_t frame = 0;
        std::int64_t time_ns = kNoTime;
        std::uint8_t address = 0;
        std::uint16_t parameter = 0;
    };

    ToybusDecoderOptions options_;
    DecodedTelegram t_;
    Pending pending_;
};

// Fills `v` from `bytes` (one record), recording every problem with its byte offset.
void parse_toybus(Bytes bytes, ToybusTelegram& v) noexcept;

}  // namespace dpscope
