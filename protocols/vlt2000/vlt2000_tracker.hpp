// The VLT 2000 tracker: the VLT 2000 serial telegram's composition of the rules, as the FC tracker
// is the FC protocol's (docs/protocol/vlt2000.md, docs/decisions.md "VLT 2000"). It reads only the
// decoded telegram (the direction and the command a reply answers, as Vlt2000Decoder inferred
// them) and judges:
//  - the link: vlt2000_checksum_error (a wrong checksum) and malformed_telegram (any other problem
//    of error severity); a damaged telegram is reported and otherwise ignored, except that a
//    damaged reply from the drive a command went to ends the wait for it; vlt2000_checksum_disabled
//    (a note, once per address) when telegrams to or from an address carry "??";
//  - the pairing, per address, of every command with its reply: the master waits for each reply,
//    so a command is unanswered (vlt2000_no_response) when the master's next telegram goes to
//    another drive, when --timeout-ms passes, or when the capture ends past it; a new command to
//    the same drive first is vlt2000_stacked_request (the capture's first telegram, which may
//    have been a reply, is judged neither way); a reply from a drive no command is pending
//    for, or with another control letter or parameter (a C command's parameter is ignored), is
//    vlt2000_mismatched_response (not before the first command to that drive: its command may
//    have come before the capture); a reply to a broadcast is vlt2000_unexpected_reply; a reply
//    with decimal position 9 is vlt2000_command_failed (a note, with the reason code);
//  - the parameter channel through the parameter-channel engine with the VLT 2000 policy (no SPM
//    bit, no lag, no cyclic repetition; Dialect::Vlt2000: the letters as codes 1..4, a failed
//    command as 7), which counts the transactions, their outcome and latency per address. The
//    tracker words the findings itself; the engine reports none.
// It counts per address what the report shows (Vlt2000StationStats). No I/O; memory is bounded per
// address and nothing is kept per telegram.
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

struct Vlt2000TrackerOptions {
    std::int64_t timeout_ns = 1'000'000'000;  // --timeout-ms: no reply within it
    // The line (--baud, 9600 unless given; sniff: the port's settings): a telegram's time is when
    // its first character arrived, so a drive's reply time runs from the command's last
    // character, 22 x character_bits / line_baud after its time. 0: no line time is subtracted.
    std::uint32_t line_baud = 0;
    std::uint32_t character_bits = 10;  // 8N1: start, 8 data, stop
};

// The finding kinds the VLT 2000 tracker reports: its own (FindingComponent::Vlt2000Protocol) and
// malformed_telegram, in enum order.
std::span<const FindingKind> vlt2000_finding_kinds() noexcept;
bool is_vlt2000_finding_kind(FindingKind kind) noexcept;

// How often a parameter was read (R, I) and updated (U).
struct Vlt2000ParameterAccess {
    std::uint64_t reads = 0;
    std::uint64_t writes = 0;
};

// One address (address 0: the broadcasts).
struct Vlt2000StationStats {
    static constexpr std::size_t kMaxParameters = 256;
    static constexpr std::size_t kMaxReasons = 100;  // reason codes 00..99

    std::uint8_t address = 0;
    std::uint64_t telegrams = 0;  // intact telegrams to or from it
    // Every command (every letter, broadcasts included, damaged ones too: decode -q counts the
    // same) has one outcome, so commands = broadcasts + answered + no_responses + abandoned +
    // damaged + not_judged + open (commands_outcomes()).
    std::uint64_t commands = 0;
    std::uint64_t damaged_commands = 0;                 // of those, damaged (checksum, cut short)
    std::array<std::uint64_t, 4> commands_by_letter{};  // intact ones: U, R, C, I
    std::uint64_t broadcasts = 0;                       // nobody replies to them
    std::uint64_t answered = 0;                         // answered: the transactions
    std::uint64_t no_responses = 0;                     // unanswered (vlt2000_no_response)
    std::uint64_t abandoned = 0;   // the master sent the drive a new command first (stacked)
    std::uint64_t damaged = 0;     // the command or its reply damaged
    std::uint64_t not_judged = 0;  // the capture began with it (perhaps a reply)
    // The capture ended while it waited for its reply, within its time-out (0 or 1; set by
    // finish()); not judged either.
    std::uint64_t open = 0;
    std::uint64_t replies = 0;  // every reply from it, answering or not, damaged too
    std::uint64_t damaged_replies = 0;
    std::uint64_t failed = 0;  // intact replies with decimal position 9
    std::map<std::uint8_t, std::uint64_t> failures_by_reason;  // reason code -> count
    std::uint64_t failures_without_reason = 0;
    std::uint64_t checksum_errors = 0;
    std::uint64_t checksum_disabled = 0;  // intact telegrams with "??"
    LogHistogram latency_ns;              // command -> reply, where both carry a time
    std::uint64_t latency_sum_ns = 0;
    std::map<std::uint16_t, Vlt2000ParameterAccess> parameters;  // parameter -> reads, writes
    std::uint64_t parameters_not_counted = 0;                    // beyond kMaxParameters
    ParameterChannelStats channel;  // the engine's: outcomes by transaction
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

class Vlt2000Tracker final : public TelegramTracker {
  public:
    explicit Vlt2000Tracker(Vlt2000TrackerOptions options = {});
    ~Vlt2000Tracker() override;
    Vlt2000Tracker(const Vlt2000Tracker&) = delete;
    Vlt2000Tracker& operator=(const Vlt2000Tracker&) = delete;

    // Feeds the next VLT 2000 telegram in capture order. Returns the findings discovered at it
    // (some concern an earlier command: their request_frame says which); valid until the next
    // call.
    std::span<const Finding> track(const DecodedTelegram& t) override;
    // The end of the capture at `end_ns` (default: the last telegram's time): a command still
    // unanswered past the time-out then is reported; one within it is not judged.
    std::span<const Finding> finish(std::int64_t end_ns = kNoTime) override;
    // The command -> reply pairs the last track() completed; valid until the next call.
    std::span<const CompletedTransaction> completed() const noexcept override { return completed_; }
    const Vlt2000TrackerOptions& options() const noexcept { return options_; }
    // Replies that began before their command could have ended at options().line_baud (their
    // reply time is counted as 0): the line was faster than that.
    std::uint64_t early_responses() const noexcept { return early_responses_; }

    // The addresses seen, in address order.
    std::vector<const Vlt2000StationStats*> stations() const;
    const BusStats& bus() const noexcept { return bus_; }
    std::uint64_t findings(Severity severity) const noexcept {
        return by_severity_[static_cast<std::size_t>(severity)];
    }
    // Commands answered, over every address.
    std::uint64_t transactions() const noexcept;
    // The parameter number the last telegram is about (-1: none, and for a C telegram).
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
        std::uint8_t letter_char = 0;
        Vlt2000Letter letter = Vlt2000Letter::Unknown;
        std::uint16_t parameter = 0;
    };

    Vlt2000StationStats& station(std::uint8_t address);
    void count();
    bool check_intact(const DecodedTelegram& t, bool answers_pending);
    void command(Vlt2000StationStats& st, const DecodedTelegram& t);
    void reply(Vlt2000StationStats& st, const DecodedTelegram& t);
    void close_pending();
    // Whether the pending command may be judged unanswered or stacked on: not when it is the
    // capture's first telegram, which may have been a reply.
    bool pending_judged() const noexcept;
    void check_deadline(std::int64_t now_ns, std::uint64_t frame);
    ParameterChannelSample sample_of(const DecodedTelegram& t, std::uint64_t cycle) const;

    Vlt2000TrackerOptions options_;
    ParameterChannelEngine engine_;
    std::vector<std::int32_t> index_;  // address -> position in stations_
    std::vector<std::unique_ptr<Vlt2000StationStats>> stations_;
    std::array<bool, 100> checksum_disabled_said_{};
    Pending pending_;
    // The last command with a wrong checksum (reported, not tracked): a reply to it (the decoder
    // pairs one, the error may be the tap's alone) is no finding of its own.
    std::uint64_t damaged_command_frame_ = 0;
    std::uint64_t early_responses_ = 0;
    std::vector<Finding> current_;
    std::vector<CompletedTransaction> completed_;
    BusStats bus_;
    std::array<std::uint64_t, 3> by_severity_{};
    std::int64_t now_ns_ = kNoTime;
    std::uint64_t last_frame_ = 0;
    std::uint64_t first_addressed_frame_ = 0;
    // The drives a command went to: a reply from another one is not judged (its command may
    // have come before the capture).
    std::bitset<kStationCount> commanded_;
    std::int32_t subject_pnu_ = -1;
};

}  // namespace dpscope
