// The FC tracker: the Danfoss FC protocol composition of the rules, as the session tracker is the
// PROFIBUS DP one (docs/protocol/fc-protocol.md, docs/decisions.md "FC protocol: pairing"). It
// reads only the decoded telegram (the direction and the request a response answers, as FcDecoder
// inferred them) and judges:
//  - the link: fc_bcc_error (a BccMismatch problem) and malformed_telegram (any other problem of
//    error severity); a damaged telegram is reported and otherwise ignored, except that a damaged
//    answer from the drive a command went to ends the wait for it;
//  - the pairing, per drive address, of every command (process, parameter and text blocks) with
//    its response: the master waits for each answer, so a command is unanswered (fc_no_response)
//    when the master's next telegram goes to another drive, when --timeout-ms passes before
//    anything answers it, or when the capture ends past that time-out; a new command to the same
//    drive first is fc_stacked_request; an answer later than --fc-response-ms is
//    fc_late_response; a response from a drive no command is pending for is
//    fc_mismatched_response. Broadcasts expect no answer. What came before the capture is not
//    judged: the capture's first telegram (perhaps a response) neither way, unless its AK says
//    it is a command, and no response from a drive before the first command to it;
//  - the parameter channel of parameter and text blocks, through the parameter-channel engine with
//    the FC policy (no SPM bit, no lag, no cyclic repetition; Dialect::Fc code tables) and the FC
//    kinds: fc_mismatched_response (PNU or index differ), fc_unexpected_response_type,
//    fc_command_rejected (AK 7, with the fault code's text), and unknown_code.
// It counts per drive address what the report shows (FcStationStats). No I/O; memory is bounded
// per address and nothing is kept per telegram.
#pragma once

#include <array>
#include <bitset>
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <vector>

#include "core/finding.hpp"
#include "core/log_histogram.hpp"
#include "core/parameter_channel_engine.hpp"
#include "core/protocol_lane.hpp"
#include "core/telegram.hpp"

namespace dpscope {

struct FcTrackerOptions {
    std::int64_t timeout_ns = 1'000'000'000;  // --timeout-ms: no answer within it
    std::int64_t response_ns = 20'000'000;    // --fc-response-ms: an answer later is late
    // The line (--baud, 9600 unless given; sniff: the port's settings): a telegram's time is when
    // its first byte arrived, so a drive's response time runs from the command's last byte,
    // command bytes x character_bits / line_baud after its time. 0: no line time is subtracted
    // (the times given are already those of the commands' ends).
    std::uint32_t line_baud = 0;
    std::uint32_t character_bits = 11;  // 8E1: start, 8 data, parity, stop
};

// The finding kinds the FC tracker reports: its own (FindingComponent::FcProtocol),
// malformed_telegram and unknown_code, in enum order.
std::span<const FindingKind> fc_finding_kinds() noexcept;
bool is_fc_finding_kind(FindingKind kind) noexcept;

// How often a parameter was read and written.
struct FcParameterAccess {
    std::uint64_t reads = 0;
    std::uint64_t writes = 0;
};

// One drive address (address 0: the broadcasts).
struct FcStationStats {
    static constexpr std::size_t kMaxParameters = 256;

    std::uint8_t address = 0;
    std::uint64_t telegrams = 0;  // intact telegrams to or from it
    // Every command (every block kind, broadcasts included, damaged ones too: decode -q counts
    // the same) has one outcome, so commands = broadcasts + answered + no_responses + abandoned +
    // damaged + not_judged + open (commands_outcomes()).
    std::uint64_t commands = 0;
    std::uint64_t damaged_commands = 0;              // of those, damaged (bad BCC, cut short)
    std::uint64_t process_commands = 0;              // intact process blocks
    std::array<std::uint64_t, 16> commands_by_ak{};  // intact parameter and text blocks, by AK
    std::uint64_t broadcasts = 0;                    // nobody answers them
    std::uint64_t answered = 0;                      // answered: the transactions
    std::uint64_t no_responses = 0;                  // unanswered (fc_no_response)
    std::uint64_t abandoned = 0;   // the master sent the drive a new command first (stacked)
    std::uint64_t damaged = 0;     // the command or its answer damaged
    std::uint64_t not_judged = 0;  // the capture began with it (perhaps a response)
    // The capture ended while it waited for its answer, within its time-out (0 or 1; set by
    // finish()); not judged either.
    std::uint64_t open = 0;
    std::uint64_t responses = 0;  // every response from it, answering or not, damaged too
    std::uint64_t damaged_responses = 0;
    std::uint64_t late = 0;
    LogHistogram latency_ns;  // command -> response, where both carry a time
    std::uint64_t latency_sum_ns = 0;
    std::map<std::uint16_t, FcParameterAccess> parameters;  // PNU -> reads and writes
    std::uint64_t parameters_not_counted = 0;  // accesses to PNUs beyond kMaxParameters
    ParameterChannelStats channel;  // the engine's: outcomes, rejections by (PNU, fault code)
    std::array<std::uint64_t, kFindingKindCount> findings{};
    FindingSeverityCounts findings_by_severity{};
    std::int64_t first_time_ns = kNoTime;
    std::int64_t last_time_ns = kNoTime;

    bool timed() const noexcept { return first_time_ns != kNoTime; }
    std::uint64_t mean_latency_ns() const noexcept {
        return latency_ns.count() ? latency_sum_ns / latency_ns.count() : 0;
    }
    // The commands by outcome, added up: always equal to commands.
    std::uint64_t commands_outcomes() const noexcept {
        return broadcasts + answered + no_responses + abandoned + damaged + not_judged_total();
    }
    // Not judged: at the capture's start or end.
    std::uint64_t not_judged_total() const noexcept { return not_judged + open; }
};

class FcTracker final : public TelegramTracker {
  public:
    explicit FcTracker(FcTrackerOptions options = {});
    ~FcTracker() override;
    FcTracker(const FcTracker&) = delete;
    FcTracker& operator=(const FcTracker&) = delete;

    // Feeds the next FC telegram in capture order. Returns the findings discovered at it (some
    // concern an earlier command: their request_frame says which); valid until the next call.
    std::span<const Finding> track(const DecodedTelegram& t) override;
    // The end of the capture at `end_ns` (default: the last telegram's time): a command still
    // unanswered past the time-out then is reported; one within it is not judged.
    std::span<const Finding> finish(std::int64_t end_ns = kNoTime) override;
    // The command -> response pairs the last track() completed; valid until the next call.
    std::span<const CompletedTransaction> completed() const noexcept override { return completed_; }
    // Responses that began before their command could have ended at options().line_baud (their
    // response time is counted as 0): the line was faster than that.
    std::uint64_t early_responses() const noexcept { return early_responses_; }
    const FcTrackerOptions& options() const noexcept { return options_; }

    // The addresses seen, in address order.
    std::vector<const FcStationStats*> stations() const;
    const BusStats& bus() const noexcept { return bus_; }
    std::uint64_t findings(Severity severity) const noexcept {
        return by_severity_[static_cast<std::size_t>(severity)];
    }
    // Commands answered, over every address.
    std::uint64_t transactions() const noexcept;
    // The parameter number the last telegram's PKW is about (-1: none); a rejection without
    // PNU is about the command it answers.
    std::int32_t subject_pnu() const noexcept override { return subject_pnu_; }
    // Whether the drive with this address was seen.
    bool has_station(std::uint8_t address) const override;
    std::int64_t timeout_ns() const noexcept override { return options_.timeout_ns; }
    // Responses earlier than the line allows (early_responses()).
    std::vector<std::string> end_warnings(std::uint64_t telegrams) const override;

  private:
    struct Pending {
        bool active = false;
        std::uint8_t address = 0;
        std::uint64_t frame = 0;
        std::int64_t time_ns = kNoTime;
        std::int64_t wire_ns = 0;  // how long the command took on the line
        bool pkw = false;          // a parameter or text block
        std::uint8_t ak = 0;
        std::uint16_t pnu = 0;
        bool certain = false;  // its content says it is a command (AK 4, 13, 14)
    };

    FcStationStats& station(std::uint8_t address);
    void count(std::size_t from);
    bool check_intact(const DecodedTelegram& t);
    void command(FcStationStats& st, const DecodedTelegram& t);
    void response(FcStationStats& st, const DecodedTelegram& t);
    void close_pending();
    // Whether the pending command may be judged unanswered or stacked on: not when it is the
    // capture's first telegram, which may have been a response (unless its AK says otherwise).
    bool pending_judged() const noexcept;
    void check_deadline(std::int64_t now_ns, std::uint64_t frame);

    FcTrackerOptions options_;
    ParameterChannelEngine engine_;
    std::vector<std::int32_t> index_;  // address -> position in stations_
    std::vector<std::unique_ptr<FcStationStats>> stations_;
    Pending pending_;
    std::vector<Finding> current_;
    std::vector<CompletedTransaction> completed_;
    BusStats bus_;
    std::array<std::uint64_t, 3> by_severity_{};
    std::int64_t now_ns_ = kNoTime;
    std::uint64_t last_frame_ = 0;
    std::uint64_t first_addressed_frame_ = 0;  // the first telegram to or from a drive
    std::uint64_t early_responses_ = 0;
    // The drives a command went to: a response from another one is not judged (its command may
    // have come before the capture).
    std::bitset<kStationCount> commanded_;
    std::int32_t subject_pnu_ = -1;
};

}  // namespace dpscope
