#include "wireshark/capture_replay.hpp"

#include <algorithm>
#include <cstring>

#include "core/protocol_descriptor.hpp"
#include "core/protocol_lane.hpp"

namespace dpscope {

ReplayOptions replay_options(const ReplayChoices& choices) {
    ReplayOptions options;
    options.timeout_ns = static_cast<std::int64_t>(choices.timeout_ms) * 1'000'000;
    options.decoder.dialect = choices.dialect;
    options.tracker.strict = choices.strict;
    options.fc_tracker.response_ns = static_cast<std::int64_t>(choices.fc_response_ms) * 1'000'000;
    options.line_baud = choices.line_baud;
    options.fc_decoder.pnu_bits = choices.fc_pnu_bits;
    options.vlt2000_decoder.check_checksum = choices.vlt2000_checksum;
    return options;
}

struct CaptureReplay::Stored {
    std::uint64_t frame = 0;
    std::int64_t time_ns = kNoTime;
    Bytes bytes;
};

struct CaptureReplay::DecoderState {
    std::unique_ptr<TelegramDecoder> decoder;

    DecoderState(Protocol protocol, const ReplayOptions& options)
        : decoder(protocol_descriptor(protocol).make_decoder(options)) {}
    DecoderState(const DecoderState& other) : decoder(other.decoder->clone()) {}

    const DecodedTelegram& decode(Bytes bytes, std::int64_t time_ns, std::uint64_t frame) {
        return decoder->decode(bytes, time_ns, frame);
    }
};

struct CaptureReplay::Trackers {
    std::unique_ptr<TelegramTracker> tracker;

    Trackers(Protocol protocol, const ReplayOptions& options)
        : tracker(protocol_descriptor(protocol).make_tracker(options)) {}

    std::span<const Finding> track(const DecodedTelegram& t) { return tracker->track(t); }
};

namespace {

// The options with what names the PNUs: the shipped parameter databases (the plugin reads no
// --params files), each station's family by the family rule with the dialect chosen.
ReplayOptions with_naming(Protocol protocol, ReplayOptions options) {
    if (options.naming) return options;
    options.naming = std::make_shared<ParameterNaming>(
        shipped_parameter_database(), protocol, options.decoder.station_dialects(), DriveHints{});
    return options;
}

}  // namespace

CaptureReplay::CaptureReplay(Protocol protocol, const ReplayOptions& options)
    : protocol_(protocol),
      options_(with_naming(protocol, options)),
      decoder_(std::make_unique<DecoderState>(protocol, options_)),
      trackers_(std::make_unique<Trackers>(protocol, options_)) {}

CaptureReplay::~CaptureReplay() = default;

const CaptureReplay::Stored* CaptureReplay::find(std::uint64_t frame) const noexcept {
    auto it = std::lower_bound(stored_.begin(), stored_.end(), frame,
                               [](const Stored& s, std::uint64_t f) { return s.frame < f; });
    return it != stored_.end() && it->frame == frame ? &*it : nullptr;
}

bool CaptureReplay::seen(std::uint64_t frame) const noexcept { return find(frame) != nullptr; }

// The bytes go into chunks that never move, so the views the decoder keeps (a request's bytes,
// the telegram's own) stay valid for the capture's lifetime.
Bytes CaptureReplay::keep(Bytes bytes) {
    constexpr std::size_t kChunk = 1 << 20;
    if (bytes.empty()) return {};
    if (chunks_.empty() || chunk_used_ + bytes.size() > chunk_size_) {
        chunk_size_ = std::max(kChunk, bytes.size());
        chunks_.push_back(std::make_unique<std::uint8_t[]>(chunk_size_));
        chunk_used_ = 0;
    }
    std::uint8_t* at = chunks_.back().get() + chunk_used_;
    std::memcpy(at, bytes.data(), bytes.size());
    chunk_used_ += bytes.size();
    return Bytes(at, bytes.size());
}

const DecodedTelegram& CaptureReplay::first_pass(std::uint64_t frame, Bytes bytes,
                                                 std::int64_t time_ns) {
    if (!stored_.empty() && frame <= stored_.back().frame)
        return decode_again(frame, bytes, time_ns);
    if (stored_.size() % kCheckpointInterval == 0)
        checkpoints_.push_back(std::make_unique<DecoderState>(*decoder_));
    stored_.push_back(Stored{frame, time_ns, keep(bytes)});
    const DecodedTelegram& t = decoder_->decode(stored_.back().bytes, time_ns, frame);
    std::span<const Finding> found = trackers_->track(t);
    if (!found.empty()) findings_[frame].assign(found.begin(), found.end());
    if (t.direction == Direction::Response && t.request_frame != 0)
        responses_.try_emplace(t.request_frame, frame);
    return t;
}

const DecodedTelegram& CaptureReplay::decode_again(std::uint64_t frame, Bytes bytes,
                                                   std::int64_t time_ns) {
    const Stored* stored = find(frame);
    if (stored == nullptr) {
        standalone_ = std::make_unique<DecoderState>(protocol_, options_);
        return standalone_->decode(bytes, time_ns, frame);
    }
    const auto index = static_cast<std::size_t>(stored - stored_.data());
    if (!replay_ || replay_next_ > index || index - replay_next_ >= kCheckpointInterval) {
        const std::size_t checkpoint = index / kCheckpointInterval;
        replay_ = std::make_unique<DecoderState>(*checkpoints_[checkpoint]);
        replay_next_ = checkpoint * kCheckpointInterval;
    }
    for (; replay_next_ < index; ++replay_next_, ++replayed_) {
        const Stored& s = stored_[replay_next_];
        replay_->decode(s.bytes, s.time_ns, s.frame);
    }
    ++replay_next_;
    ++replayed_;
    return replay_->decode(stored->bytes, stored->time_ns, stored->frame);
}

std::span<const Finding> CaptureReplay::findings(std::uint64_t frame) const noexcept {
    auto it = findings_.find(frame);
    return it == findings_.end() ? std::span<const Finding>()
                                 : std::span<const Finding>(it->second);
}

std::uint64_t CaptureReplay::response_frame(std::uint64_t frame) const noexcept {
    auto it = responses_.find(frame);
    return it == responses_.end() ? 0 : it->second;
}

std::int64_t CaptureReplay::time_of(std::uint64_t frame) const noexcept {
    const Stored* stored = find(frame);
    return stored ? stored->time_ns : kNoTime;
}

}  // namespace dpscope
