// The session tracker: the PROFIBUS DP composition of the rules. It turns each decoded telegram
// into the link checks (protocols/profibus/dp_link_rules.hpp: fcs_error, malformed_telegram,
// fdl_retry, fdl_no_response), the configuration check (protocols/profibus/dp_config_rule.hpp:
// config_mismatch) and, for a Data_Exchange telegram with a parameter channel, a sample for the
// parameter-channel engine (core/parameter_channel_engine.hpp), which pairs requests with
// responses; every DP-V1 telegram (MSAC_C1, MSAC_C2) goes to the DP-V1 parameter-access tracker
// (protocols/profibus/dpv1/dpv1_parameter_access.hpp), which follows PROFIdrive parameter access;
// it counts every finding per channel and keeps the DP statistics beside the engine's. No I/O;
// memory is bounded per channel and nothing is kept per telegram.
//
// What the DP carrier tells the engine:
//  - A cycle is a Data_Exchange request from the master to the slave; an FDL retry (the same
//    FCB again) is no new cycle, unless the slave dropped the request it repeats (bad FCS).
//  - The slave's response lags one cycle, and the PKE has an SPM bit (the PPO's layout).
//  - A telegram with a bad FCS, or malformed, is reported and otherwise ignored; except that a
//    DP-V1 telegram with a correct FCS still goes to the DP-V1 tracker, whose length rule says
//    in DP-V1 terms what a PROFIdrive message cut short or too long is. Where it does, for data
//    cut short, that dpv1_length_error is the one finding (no malformed_telegram beside it).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "core/channel_index.hpp"
#include "core/finding.hpp"
#include "core/parameter_channel_engine.hpp"
#include "core/protocol_lane.hpp"
#include "core/telegram.hpp"
#include "protocols/profibus/dp_config_rule.hpp"
#include "protocols/profibus/dp_link_rules.hpp"
#include "protocols/profibus/dpv1/dpv1_parameter_access.hpp"
#include "protocols/profibus/gsd/gsd_rules.hpp"

namespace dpscope {

struct TrackerOptions {
    std::int64_t timeout_ns = 1'000'000'000;  // --timeout-ms
    bool strict = false;                      // RC 8 after a read is an unexpected answer
    // The line's baud rate (--baud, the capture's record; 0: not known): the GSD rules time a
    // slave's answers against MaxTsdr at it.
    std::uint32_t line_baud = 0;
};

// What one slave's telegrams say about its dialect: a slave decoded with the wrong code tables
// shows it (docs/decisions.md, "Dialect hint"). In this order, the first that applies:
//  - Ident: its ident number (Set_Prm, or a Slave_Diag answer) is one the sources name for a
//    dialect other than the decoded one (dialect_of_ident(): the Danfoss VLT 5000/6000's).
//  - Codes: at least kMinimum telegrams with a code the decoded dialect does not define, every
//    one of them a code another dialect defines (a PROFIdrive drive decoded as vlt).
//  - Errors: rejections (RC 7) with an error number the decoded dialect does not define, every
//    one of them defined by another dialect (a GE AF-600 decoded as vlt: fault numbers 130,
//    131); one is enough.
// The other dialect is the first such in kDialects order. Only intact telegrams count: Set_Prm
// requests and Slave_Diag answers for the ident, Data_Exchange telegrams with a parameter channel
// for codes and error numbers.
class DialectEvidence {
  public:
    static constexpr std::uint64_t kMinimum = 10;
    enum class Basis : std::uint8_t { None, Ident, Codes, Errors };

    void add(const DecodedTelegram& t) noexcept;
    // Telegrams whose code the decoded dialect does not define.
    std::uint64_t undefined() const noexcept { return undefined_; }
    // Rejection telegrams whose error number the decoded dialect does not define, and the first
    // kNamedErrors distinct such numbers.
    static constexpr std::size_t kNamedErrors = 4;
    std::uint64_t undefined_errors() const noexcept { return undefined_errors_; }
    std::span<const std::uint16_t> undefined_error_numbers() const noexcept {
        return std::span<const std::uint16_t>(error_numbers_.data(), named_errors_);
    }
    // More distinct numbers than kNamedErrors were seen.
    bool more_error_numbers() const noexcept { return more_errors_; }
    bool has_ident() const noexcept { return has_ident_; }
    std::uint16_t ident() const noexcept { return ident_; }
    // The dialect the telegrams with a PCV were decoded with (vlt before the first).
    Dialect decoded() const noexcept { return decoded_; }
    // The dialect to decode the slave with instead, or nullopt; and what that rests on.
    std::optional<Dialect> hint() const noexcept { return judge().first; }
    Basis basis() const noexcept { return judge().second; }

  private:
    std::pair<std::optional<Dialect>, Basis> judge() const noexcept;
    void note_dialect(Dialect dialect) noexcept;

    Dialect decoded_ = Dialect::Vlt;
    std::uint64_t undefined_ = 0;
    // Of those, the codes each other dialect defines (indexed by Dialect).
    std::array<std::uint64_t, std::size(kDialects)> other_defines_{};
    std::uint64_t undefined_errors_ = 0;
    std::array<std::uint16_t, kNamedErrors> error_numbers_{};
    std::size_t named_errors_ = 0;
    bool more_errors_ = false;
    // Of those, the error numbers each other dialect defines (indexed by Dialect).
    std::array<std::uint64_t, std::size(kDialects)> other_defines_error_{};
    bool has_ident_ = false;
    std::uint16_t ident_ = 0;
    bool pcv_seen_ = false;  // an intact Data_Exchange telegram with a parameter channel
};

// One channel: the engine's counts and the DP carrier's.
struct ChannelStats : ParameterChannelStats {
    std::uint8_t master = 0;
    std::uint8_t slave = 0;
    PpoLayout ppo;  // the layout of the last Data_Exchange telegram
    Dialect dialect = Dialect::Vlt;
    std::uint64_t data_exchange = 0;  // Data_Exchange telegrams, both directions
    std::uint64_t cycles = 0;         // Data_Exchange requests (retries not counted)
    std::array<std::uint64_t, kFindingKindCount> findings{};  // every rule's
    // The same split by the severity each finding had (a kind's severity can vary: options such
    // as --strict, dpv1_error_pdu by error class).
    FindingSeverityCounts findings_by_severity{};
    std::int64_t first_time_ns = kNoTime;
    std::int64_t last_time_ns = kNoTime;
    Dpv1Stats dpv1;  // DP-V1 parameter access (protocols/profibus/dpv1/dpv1_parameter_access.hpp)
    // The slave against its GSD file (protocols/profibus/gsd/gsd_rules.hpp); null when the
    // slave has none.
    const GsdCheckStats* gsd = nullptr;
};

class SessionTracker final : public TelegramTracker {
  public:
    explicit SessionTracker(TrackerOptions options = {});
    ~SessionTracker() override;
    SessionTracker(const SessionTracker&) = delete;
    SessionTracker& operator=(const SessionTracker&) = delete;

    // Feeds the next telegram in capture order. Returns the findings discovered at it (some may
    // concern earlier telegrams: their request_frame says which); valid until the next call.
    std::span<const Finding> track(const DecodedTelegram& t) override;
    // The end of the capture at `end_ns` (a live capture's stop time; default: the last
    // telegram's time): what is still open past the time-out then is reported.
    std::span<const Finding> finish(std::int64_t end_ns = kNoTime) override;
    // The transactions the last track() completed; valid until the next call.
    std::span<const CompletedTransaction> completed() const noexcept override { return completed_; }

    // Channels ordered by slave, then master.
    std::vector<const ChannelStats*> channels() const;
    const BusStats& bus() const noexcept { return bus_; }
    std::uint64_t findings(Severity severity) const noexcept {
        return by_severity_[static_cast<std::size_t>(severity)];
    }
    // Parameter-channel transactions and completed DP-V1 parameter-access transactions.
    std::uint64_t transactions() const noexcept;
    const TrackerOptions& options() const noexcept { return options_; }
    // The parameter number the last tracked telegram's parameter channel is about, -1 when it
    // carries none: the PCV's own PNU, except for a rejection (RC 7) or "no authority" (RC 8)
    // that leaves the PNU out (PNU 0): that one is about the request it answers.
    std::int32_t subject_pnu() const noexcept override { return subject_pnu_; }
    // Whether a channel of the slave with this address was seen.
    bool has_station(std::uint8_t address) const override;
    std::int64_t timeout_ns() const noexcept override { return options_.timeout_ns; }
    bool strict() const noexcept override { return options_.strict; }

  private:
    struct Channel {
        ChannelStats stats;
        FrameCountState frame_count;
        ConfigCheckState config;
        std::unique_ptr<GsdCheckState> gsd;  // made at the slave's first telegram with a GSD
        // A damaged request (bad FCS) was dropped by the slave: its retry is the cycle.
        bool damaged_request = false;
    };

    Channel& channel(std::uint8_t master, std::uint8_t slave);
    // Counts the findings current_[from] to current_[to - 1], per severity and per channel
    // (making the channel of each in the order found).
    void count(std::size_t from, std::size_t to);
    void track_channel(Channel& ch, const DecodedTelegram& t, bool intact);

    TrackerOptions options_;
    GsdLine gsd_line_;  // the line as the GSD rules time it (options_.line_baud)
    ParameterChannelEngine engine_;
    Dpv1ParameterAccessTracker dpv1_;
    ChannelIndex index_;  // (master, slave) -> position in channels_
    std::vector<std::unique_ptr<Channel>> channels_;
    std::vector<Finding> current_;
    std::vector<CompletedTransaction> completed_;
    BusStats bus_;
    std::array<std::uint64_t, 3> by_severity_{};
    std::int64_t now_ns_ = kNoTime;
    std::uint64_t last_frame_ = 0;
    std::int32_t subject_pnu_ = -1;
};

}  // namespace dpscope
