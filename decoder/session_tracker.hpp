// The session tracker: follows the cyclic parameter channel of every (master, slave) pair
// telegram by telegram, pairs each parameter request with its response and reports where the
// handshake was broken (docs/protocol/parameter-channel.md). No I/O; memory is bounded per
// channel and nothing is kept per telegram.
//
// How the channel is read:
//  - The master repeats its PCV in every Data_Exchange cycle until it is answered; a new request
//    is a change of the master's PCV (RC, PNU, IND, PVA; SPM is not part of the request). RC 0 is
//    no request. Identical consecutive requests are told apart by the RC 0 cycle between them.
//  - The slave keeps returning its answer while the request stands, one cycle late. A response
//    equal to the previous one is a repeat and counts once. The previous response arriving in the
//    cycle in which the master moved on is no orphan; neither is the late answer to a request
//    the master abandoned.
//  - An answer (any code but 0 and the spontaneous codes) ends the pending request: a
//    transaction, positive, rejected (RC 7), without authority (RC 8), mismatched (other PNU, or
//    other IND for array codes) or of an unexpected type. Latency runs from the first telegram
//    carrying the request to the first carrying its answer, in ms and in cycles (master
//    Data_Exchange requests to the slave).
//  - RC 9..12 are spontaneous messages: the slave toggles SPM and repeats the message until the
//    master toggles its own SPM; the pending request stays pending meanwhile.
//  - A telegram with a bad FCS, or malformed, is reported and otherwise ignored.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "decoder/bus_decoder.hpp"
#include "decoder/finding.hpp"
#include "decoder/log_histogram.hpp"

namespace dpscope {

struct TrackerOptions {
    std::int64_t timeout_ns = 1'000'000'000;  // --timeout-ms
    bool strict = false;                      // RC 8 after a read is an unexpected answer
};

// Events over time in a fixed number of bins whose width doubles as the capture grows, for the
// timeline of the HTML report.
class Timeline {
  public:
    static constexpr std::size_t kBins = 240;
    struct Bin {
        std::uint32_t transactions = 0;
        std::uint32_t errors = 0;
        std::uint32_t warnings = 0;
        std::uint32_t notes = 0;
    };

    void add_transaction(std::int64_t time_ns) { bin(time_ns).transactions++; }
    void add_finding(std::int64_t time_ns, Severity severity);

    bool empty() const noexcept { return start_ns_ == kNoTime; }
    std::int64_t start_ns() const noexcept { return start_ns_; }
    std::int64_t bin_width_ns() const noexcept { return width_ns_; }
    const std::array<Bin, kBins>& bins() const noexcept { return bins_; }

  private:
    Bin& bin(std::int64_t time_ns);

    std::int64_t start_ns_ = kNoTime;
    std::int64_t width_ns_ = 10'000'000;  // 10 ms to begin with
    std::array<Bin, kBins> bins_{};
};

struct TransactionCounts {
    std::uint64_t positive = 0;
    std::uint64_t rejected = 0;
    std::uint64_t no_authority = 0;
    std::uint64_t mismatched = 0;
    std::uint64_t unexpected = 0;

    std::uint64_t total() const noexcept {
        return positive + rejected + no_authority + mismatched + unexpected;
    }
};

// What the parameter-channel codes of one slave say about its dialect: a slave decoded with
// the wrong code tables (a PROFIdrive drive decoded as vlt) shows codes its dialect does not
// define but the other one does. The rule (docs/decisions.md): at least kMinimum telegrams with
// a code the decoded dialect does not define, every one of them a code the other dialect
// defines. Only intact Data_Exchange telegrams with a parameter channel count.
class DialectEvidence {
  public:
    static constexpr std::uint64_t kMinimum = 10;

    void add(const DecodedTelegram& t) noexcept;
    // Telegrams whose code the decoded dialect does not define.
    std::uint64_t undefined() const noexcept { return undefined_; }
    // The dialect to decode the slave with instead, or nullopt.
    std::optional<Dialect> hint() const noexcept;

  private:
    Dialect decoded_ = Dialect::Vlt;
    std::uint64_t undefined_ = 0;
    std::uint64_t other_defines_ = 0;  // of those, codes the other dialect defines
};

struct ChannelStats {
    std::uint8_t master = 0;
    std::uint8_t slave = 0;
    PpoLayout ppo;  // the layout of the last Data_Exchange telegram
    Dialect dialect = Dialect::Vlt;
    std::uint64_t data_exchange = 0;  // Data_Exchange telegrams, both directions
    std::uint64_t cycles = 0;         // Data_Exchange requests (retries not counted)
    std::uint64_t requests = 0;       // distinct parameter requests
    // Data_Exchange telegrams with a parameter channel (PCV): none means nothing was checked.
    std::uint64_t parameter_telegrams = 0;
    TransactionCounts transactions;
    std::uint64_t timeouts = 0;
    std::uint64_t abandoned = 0;  // dropped by the master before an answer
    std::uint64_t spontaneous = 0;
    LogHistogram latency_ns;
    LogHistogram latency_cycles;
    std::map<std::uint16_t, std::uint64_t> pnu_requests;      // PNU -> requests
    std::map<std::uint16_t, std::uint64_t> rejection_errors;  // error number -> count
    std::map<std::pair<std::uint16_t, std::uint16_t>, std::uint64_t> rejections;  // (PNU, error)
    std::array<std::uint64_t, kFindingKindCount> findings{};
    Timeline timeline;
    std::int64_t first_time_ns = kNoTime;
    std::int64_t last_time_ns = kNoTime;
};

// Counts for what no channel can be named for (garbage on the bus).
struct BusStats {
    std::array<std::uint64_t, kFindingKindCount> findings{};
};

class SessionTracker {
  public:
    // `decoder` is consulted for the slaves' configurations (Chk_Cfg lengths).
    SessionTracker(const BusDecoder& decoder, TrackerOptions options = {});
    ~SessionTracker();
    SessionTracker(const SessionTracker&) = delete;
    SessionTracker& operator=(const SessionTracker&) = delete;

    // Feeds the next telegram in capture order. Returns the findings discovered at it (some may
    // concern earlier telegrams: their request_frame says which); valid until the next call.
    std::span<const Finding> track(const DecodedTelegram& t);
    // The end of the capture at `end_ns` (a live capture's stop time; default: the last
    // telegram's time): what is still open past the time-out then is reported.
    std::span<const Finding> finish(std::int64_t end_ns = kNoTime);

    // Channels ordered by slave, then master.
    std::vector<const ChannelStats*> channels() const;
    const BusStats& bus() const noexcept { return bus_; }
    std::uint64_t findings(Severity severity) const noexcept {
        return by_severity_[static_cast<std::size_t>(severity)];
    }
    std::uint64_t transactions() const noexcept;
    const TrackerOptions& options() const noexcept { return options_; }
    // The parameter number the last tracked telegram's parameter channel is about, -1 when it
    // carries none: the PCV's own PNU, except for a rejection (RC 7) or "no authority" (RC 8)
    // that leaves the PNU out (PNU 0): that one is about the request it answers.
    std::int32_t subject_pnu() const noexcept { return subject_pnu_; }

  private:
    struct Channel;

    Channel& channel(std::uint8_t master, std::uint8_t slave);
    Finding& add(FindingKind kind, const DecodedTelegram& t, std::uint64_t request_frame);
    Finding& add_for(FindingKind kind, std::uint64_t frame, std::int64_t time_ns,
                     std::uint64_t request_frame, bool has_stations, std::uint8_t master,
                     std::uint8_t slave);
    void check_link(const DecodedTelegram& t, bool& usable);
    void check_frame_count(Channel& ch, const DecodedTelegram& t, bool& retry);
    void check_config(Channel& ch, const DecodedTelegram& t);
    void master_pcv(Channel& ch, const DecodedTelegram& t);
    void slave_pcv(Channel& ch, const DecodedTelegram& t);
    void answered(Channel& ch, const DecodedTelegram& t);
    void check_deadlines(const DecodedTelegram* at, std::int64_t now_ns);

    const BusDecoder& decoder_;
    TrackerOptions options_;
    std::vector<std::int32_t> index_;  // master * 128 + slave -> position in channels_
    std::vector<std::unique_ptr<Channel>> channels_;
    std::vector<Finding> current_;
    BusStats bus_;
    std::array<std::uint64_t, 3> by_severity_{};
    std::int64_t now_ns_ = kNoTime;
    std::int64_t next_deadline_ns_ = std::numeric_limits<std::int64_t>::max();
    std::uint64_t last_frame_ = 0;
    std::int32_t subject_pnu_ = -1;
};

}  // namespace dpscope
