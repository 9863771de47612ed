// What shared code asks of a protocol's decoder and tracker, whatever the protocol: the commands'
// pipeline (cli/pipeline.hpp), the Wireshark plugin's replay (wireshark/capture_replay.cpp) and
// the report and summary hold a capture's decoder and tracker through these two interfaces, made
// by the functions its descriptor names (ProtocolDescriptor::make_decoder, make_tracker), so none
// of them switches on the protocol. What only one protocol's code reads (a PROFIBUS slave's
// configuration, an FC drive's statistics) is read from its own class, by a cast in that
// protocol's folder (its report section, its summary part).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/finding.hpp"
#include "core/parameter_channel_engine.hpp"
#include "core/telegram.hpp"

namespace dpscope {

// A protocol's decoder: the next telegram of a capture in, its decoded form out. Decoding may
// keep state (a response decoded against its request), so a copy (clone) decodes on exactly as
// the original would.
class TelegramDecoder {
  public:
    virtual ~TelegramDecoder() = default;
    // Decodes one telegram. The result refers to `bytes` and stays valid until the next call.
    virtual const DecodedTelegram& decode(Bytes bytes, std::int64_t time_ns,
                                          std::uint64_t frame) = 0;
    // A copy of the decoder with its state.
    virtual std::unique_ptr<TelegramDecoder> clone() const = 0;
    // What names the PNUs as of now, when the decoder keeps its own (what the drives described,
    // the families their GSD files name: drives/parameter_naming.hpp); null: the capture's, as
    // it was given.
    virtual const ParameterNaming* naming() const noexcept { return nullptr; }

  protected:
    TelegramDecoder() = default;
    TelegramDecoder(const TelegramDecoder&) = default;
    TelegramDecoder& operator=(const TelegramDecoder&) = default;
};

// A protocol's tracker: judges the decoded telegrams in capture order, pairing requests with
// responses, and counts per station.
class TelegramTracker {
  public:
    virtual ~TelegramTracker() = default;
    // Feeds the next telegram; returns the findings discovered at it, valid until the next call.
    virtual std::span<const Finding> track(const DecodedTelegram& t) = 0;
    // The end of the capture at `end_ns` (kNoTime: the last telegram's time): what is still open
    // past the time-out is reported.
    virtual std::span<const Finding> finish(std::int64_t end_ns = kNoTime) = 0;
    // The request -> response pairs the last track() completed; valid until the next call.
    virtual std::span<const CompletedTransaction> completed() const noexcept = 0;
    // The parameter number the last telegram's parameter channel is about (-1: none).
    virtual std::int32_t subject_pnu() const noexcept = 0;
    // Whether the station (slave or drive) with this address took part in the capture.
    virtual bool has_station(std::uint8_t address) const = 0;
    // The time-out after which an unanswered request is a finding.
    virtual std::int64_t timeout_ns() const noexcept = 0;
    // Whether unusual responses are errors rather than warnings (--strict; PROFIBUS only).
    virtual bool strict() const noexcept { return false; }
    // What the user should be told once the capture has ended about how the options fit the
    // capture (a line faster than --baud, a checksum rule the drives do not follow), given the
    // number of telegrams decoded; one sentence each, without "warning:".
    virtual std::vector<std::string> end_warnings(std::uint64_t telegrams) const {
        (void)telegrams;
        return {};
    }

  protected:
    TelegramTracker() = default;
};

// Responses that began before their request could have ended at the line's rate: the line was
// faster. The warning the serial drive buses' trackers give for `early` such responses (none for
// 0) at `baud` with `bits` a character.
std::vector<std::string> early_response_warning(std::uint64_t early, std::uint32_t baud,
                                                std::uint32_t bits);

}  // namespace dpscope
