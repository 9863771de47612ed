// Decodes a Danfoss FC protocol capture (RS-485, docs/protocol/fc-protocol.md) telegram by
// telegram, in capture order, into DecodedTelegram::fc. The bus has one master and no direction
// on the wire, so the decoder tells requests from responses (docs/decisions.md, "FC protocol:
// request or response"):
//   - a telegram that follows a request is its response when it carries the request's address
//     byte, has the same kind of block (process, or parameter/text), is not the request's bytes
//     again, has no AK only a command has (4, 13, 14), and comes within the response window;
//   - a telegram with AK 7 (only a response has it) is a response wherever it comes (from another
//     address than the request's it answers nothing: the request still waits);
//   - everything else is a request; a broadcast is answered by nobody, and neither is a damaged
//     request (wrong BCC, cut short): a drive drops it.
// The header's roles: master 0 (the FC master has no address), slave the drive's address (0 for
// a broadcast); a response names the request it answers.
#pragma once

#include <array>
#include <cstdint>
#include <memory>

#include "core/protocol_lane.hpp"
#include "core/telegram.hpp"
#include "core/time.hpp"
#include "protocols/fc/fc_telegram.hpp"

namespace dpscope {

struct FcDecoderOptions {
    // PNU bits: 12 (FC series [S001]) or 11 (VLT 2800, FCD 300 [P:FCD311-DG p97]).
    std::uint8_t pnu_bits = 12;
    // A telegram later than this after a request is not its response (no time: no limit).
    std::int64_t response_window_ns = 1'000'000'000;
    // What names the PNUs (drives/parameter_naming.hpp): put on every telegram decoded
    // (DecodedTelegram::naming); null: nothing. Set from LaneOptions::naming by the factory.
    std::shared_ptr<const ParameterNaming> naming{};
};

class FcDecoder final : public TelegramDecoder {
  public:
    explicit FcDecoder(FcDecoderOptions options = {}) noexcept;

    // Decodes one telegram. The result refers to `bytes` and stays valid until the next call.
    const DecodedTelegram& decode(Bytes bytes, std::int64_t time_ns, std::uint64_t frame) override;
    std::unique_ptr<TelegramDecoder> clone() const override {
        return std::make_unique<FcDecoder>(*this);
    }

    const FcDecoderOptions& options() const noexcept { return options_; }

  private:
    void parse(Bytes bytes);
    Direction direction_of(const FcTelegram& fc) const noexcept;

    // The request waiting for its response (at most one: the master waits for each answer).
    struct Pending {
        bool valid = false;
        std::uint64_t frame = 0;
        std::int64_t time_ns = kNoTime;
        std::uint8_t adr = 0;
        bool pkw = false;  // a parameter or text block
        std::uint16_t size = 0;
        std::array<std::uint8_t, 257> bytes{};
    };

    FcDecoderOptions options_;
    PkeLayout layout_;
    DecodedTelegram t_;
    Pending pending_;
};

}  // namespace dpscope
