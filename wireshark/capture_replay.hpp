// What the Wireshark dissector keeps per capture: dpscope's own decoder and tracker, fed the
// capture's telegrams in order on Wireshark's first pass, and a way to decode any telegram again
// later, exactly as it was decoded then (Wireshark dissects a packet again whenever it is shown,
// in any order). No Wireshark header is included here, so the tests check it without Wireshark.
//
// Decoding is stateful (a Data_Exchange is split by the PPO its Chk_Cfg announced; a response
// takes its stations and parameter numbers from the request), so a telegram cannot be decoded
// again on its own. CaptureReplay keeps a copy of every telegram's bytes and, every
// kCheckpointInterval telegrams, a copy of the decoder as it was before that telegram; decoding
// telegram N again copies the checkpoint at or before N and decodes forward from there (at most
// kCheckpointInterval - 1 telegrams, a few tens of microseconds). A telegram shown right after
// the one before it (tshark's second pass, scrolling) continues from where the last one ended.
// The tracker runs once, on the first pass; its findings are kept per telegram.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <unordered_map>
#include <vector>

#include "core/finding.hpp"
#include "core/telegram.hpp"
#include "protocols/lane_options.hpp"

namespace dpscope {

// The decoder and tracker options of every bus (the dissector's preferences set them); the
// capture's protocol makes its decoder and tracker from them (ProtocolDescriptor::make_decoder).
using ReplayOptions = LaneOptions;

// The choices the decoder and tracker options are made of, as `dpscope decode`'s options name
// them; the defaults are decode's (--timeout-ms 1000, --fc-response-ms 20, 9600 baud for FC and
// VLT 2000, --fc-pnu-bits 12, the VLT 2000 checksum checked).
struct ReplayChoices {
    Dialect dialect = Dialect::Vlt;
    std::uint32_t timeout_ms = 1000;
    bool strict = false;
    std::uint32_t fc_response_ms = 20;
    std::uint32_t line_baud = 9600;
    std::uint8_t fc_pnu_bits = 12;
    bool vlt2000_checksum = true;
};

// Every bus's options from the choices, as cli/common_options.cpp resolves decode's options.
ReplayOptions replay_options(const ReplayChoices& choices);
inline ReplayOptions default_replay_options() { return replay_options(ReplayChoices{}); }

class CaptureReplay {
  public:
    static constexpr std::size_t kCheckpointInterval = 256;

    CaptureReplay(Protocol protocol, const ReplayOptions& options);
    ~CaptureReplay();
    CaptureReplay(const CaptureReplay&) = delete;
    CaptureReplay& operator=(const CaptureReplay&) = delete;

    Protocol protocol() const noexcept { return protocol_; }

    // Whether telegram `frame` was fed on the first pass.
    bool seen(std::uint64_t frame) const noexcept;
    // The first pass: decodes and tracks the next telegram of the capture. Frames come in
    // increasing order; a frame not after the last one fed is decoded again instead (see below).
    const DecodedTelegram& first_pass(std::uint64_t frame, Bytes bytes, std::int64_t time_ns);
    // Telegram `frame` decoded again, as on the first pass. A frame never fed is decoded on its
    // own by a fresh decoder (no context).
    const DecodedTelegram& decode_again(std::uint64_t frame, Bytes bytes, std::int64_t time_ns);

    // What the tracker found at telegram `frame` on the first pass.
    std::span<const Finding> findings(std::uint64_t frame) const noexcept;
    // The first response that answered the request in `frame` (0: none in the capture).
    std::uint64_t response_frame(std::uint64_t frame) const noexcept;
    // The time of telegram `frame` (kNoTime: unknown or never fed).
    std::int64_t time_of(std::uint64_t frame) const noexcept;
    // How many decodes decode_again() ran (for the tests: the replay stays short).
    std::uint64_t replayed_decodes() const noexcept { return replayed_; }

  private:
    struct Stored;        // a telegram's frame, time and bytes
    struct DecoderState;  // the decoder of the capture's bus, copyable
    struct Trackers;      // the tracker of the capture's bus

    const Stored* find(std::uint64_t frame) const noexcept;
    Bytes keep(Bytes bytes);

    Protocol protocol_;
    ReplayOptions options_;
    std::unique_ptr<DecoderState> decoder_;     // the first pass's
    std::unique_ptr<Trackers> trackers_;        // the first pass's
    std::unique_ptr<DecoderState> replay_;      // decoding again
    std::unique_ptr<DecoderState> standalone_;  // frames never fed
    std::size_t replay_next_ = 0;               // the index of the telegram replay_ decodes next
    std::vector<Stored> stored_;
    std::vector<std::unique_ptr<std::uint8_t[]>> chunks_;  // the telegrams' bytes, never moved
    std::size_t chunk_used_ = 0;
    std::size_t chunk_size_ = 0;
    std::vector<std::unique_ptr<DecoderState>>
        checkpoints_;  // before telegram k * kCheckpointInterval
    std::unordered_map<std::uint64_t, std::vector<Finding>> findings_;
    std::unordered_map<std::uint64_t, std::uint64_t> responses_;
    std::uint64_t replayed_ = 0;
};

}  // namespace dpscope
