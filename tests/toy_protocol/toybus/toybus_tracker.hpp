// The toybus tracker. It reads only the decoded telegram and feeds the parameter-channel engine
// (core/parameter_channel_engine.hpp) one sample per intact telegram, so that the engine pairs
// each request with its response per drive and reports, with its own finding kinds, what breaks
// the handshake: stacked_request, orphan_response, mismatched_response (another parameter),
// response_timeout, request_rejected (an error response '#'). The toy has no code tables of its
// own: its telegrams are given the codes of the VLT (PROFIBUS) dialect, read '?' as RC 1, write
// '!' as RC 2, value '=' as RC 1 (which answers both), error '#' as RC 7 with EE as the error
// number. A telegram with an error problem is malformed_telegram and otherwise ignored.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "core/finding.hpp"
#include "core/parameter_channel_engine.hpp"
#include "core/protocol_lane.hpp"
#include "core/telegram.hpp"

namespace dpscope {

struct ToybusTrackerOptions {
    std::int64_t timeout_ns = 1'000'000'000;  // --timeout-ms: no response within it
};

// The kinds the toybus tracker reports, in enum order.
std::span<const FindingKind> toybus_finding_kinds() noexcept;
bool is_toybus_finding_kind(FindingKind kind) noexcept;

// One drive address.
struct ToybusStationStats {
    std::uint8_t address = 0;
    std::uint64_t telegrams = 0;    // intact telegrams to or from it
    std::uint64_t reads = 0;        // intact '?'
    std::uint64_t writes = 0;       // intact '!'
    std::uint64_t values = 0;       // intact '='
    std::uint64_t errors = 0;       // intact '#'
    std::uint64_t damaged = 0;      // telegrams with an error problem
    ParameterChannelStats channel;  // the engine's: transactions, time-outs, latency
    std::array<std::uint64_t, kFindingKindCount> findings{};
    FindingSeverityCounts findings_by_severity{};
};

class ToybusTracker final : public TelegramTracker {
  public:
    explicit ToybusTracker(ToybusTrackerOptions options = {});
    ~ToybusTracker() override;
    ToybusTracker(const ToybusTracker&) = delete;
    ToybusTracker& operator=(const ToybusTracker&) = delete;

    // Feeds the next telegram in capture order; the findings found at it, valid until the next
    // call.
    std::span<const Finding> track(const DecodedTelegram& t) override;
    // The end of the capture (default: the last telegram's time): requests left unanswered past
    // the time-out.
    std::span<const Finding> finish(std::int64_t end_ns = kNoTime) override;
    // The request -> response pairs the last track() completed.
    std::span<const CompletedTransaction> completed() const noexcept override { return completed_; }
    const ToybusTrackerOptions& options() const noexcept { return options_; }
    // The parameter number the last telegram names (-1: none).
    std::int32_t subject_pnu() const noexcept override { return subject_pnu_; }
    bool has_station(std::uint8_t address) const override { return index_[address & 0x7F] != 0; }
    std::int64_t timeout_ns() const noexcept override { return options_.timeout_ns; }

    // The addresses seen, in address order.
    std::vector<const ToybusStationStats*> stations() const;
    const BusStats& bus() const noexcept { return bus_; }
    std::uint64_t transactions() const noexcept;

  private:
    ToybusStationStats& station(std::uint8_t address);
    void count();

    ToybusTrackerOptions options_;
    ParameterChannelEngine engine_;
    std::array<std::int32_t, kStationCount> index_{};  // address -> position + 1 in stations_
    std::vector<std::unique_ptr<ToybusStationStats>> stations_;
    std::vector<Finding> current_;
    std::vector<CompletedTransaction> completed_;
    BusStats bus_;
    std::int64_t now_ns_ = kNoTime;
    std::uint64_t last_frame_ = 0;
    std::int32_t subject_pnu_ = -1;
};

}  // namespace dpscope
