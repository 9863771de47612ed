// The parameter-channel engine: follows the cyclic parameter channel of every (master, slave)
// pair sample by sample, pairs each parameter request with its response and reports where the
// handshake was broken (docs/protocol/parameter-channel.md). It knows no carrier: a carrier (the
// PROFIBUS DP session tracker; later the Danfoss FC protocol) turns each of its telegrams that
// carries a parameter channel into a ParameterChannelSample and says how its channel behaves in
// a ParameterChannelPolicy. No I/O; memory is bounded per channel and nothing is kept per sample.
//
// How the channel is read:
//  - The master repeats its PCV in every cycle until it is answered; a new request is a change
//    of the master's PCV (RC, PNU, IND, PVA; SPM is not part of the request). RC 0 is no request.
//    Identical consecutive requests are told apart by the RC 0 cycle between them.
//  - The slave keeps returning its answer while the request stands, one cycle late where the
//    policy says so (PROFIBUS DP). A response equal to the previous one is a repeat and counts
//    once. The previous response arriving in the cycle in which the master moved on is no
//    orphan where the response lags; neither is the late answer to a request the master
//    abandoned.
//  - An answer (any code but 0 and the spontaneous codes) ends the pending request: a
//    transaction, positive, rejected (RC 7), without authority (RC 8), mismatched (other PNU, or
//    other IND for array codes) or of an unexpected type. Latency runs from the first telegram
//    carrying the request to the first carrying its answer, in ms and in the carrier's cycles.
//  - RC 9..12 are spontaneous messages. With an SPM bit the slave toggles SPM and repeats the
//    message until the master toggles its own SPM; the pending request stays pending meanwhile.
//    Without one a message is reported when it changes, and no acknowledgement is awaited.
//  - A carrier whose requests are not repeated cyclically (the FC protocol: each master telegram
//    with a PKW is a command of its own, each response an answer) says so in the policy: every
//    master sample is then a new request and every slave sample an answer, never a repeat.
//  - The policy names the finding kind each of the engine's findings is reported as (the
//    carrier's own kinds), or none where the carrier judges that itself.
#pragma once

#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "core/channel_index.hpp"
#include "core/code_tables.hpp"
#include "core/direction.hpp"
#include "core/finding_list.hpp"
#include "core/log_histogram.hpp"
#include "core/time.hpp"

namespace dpscope {

// The finding kind the engine reports each of its findings as; nullopt: not reported (the
// carrier judges it itself). The defaults are the parameter-channel kinds.
struct ParameterChannelKinds {
    std::optional<FindingKind> stacked_request = FindingKind::StackedRequest;
    std::optional<FindingKind> orphan_response = FindingKind::OrphanResponse;
    std::optional<FindingKind> mismatched_response = FindingKind::MismatchedResponse;
    std::optional<FindingKind> unexpected_response_type = FindingKind::UnexpectedResponseType;
    std::optional<FindingKind> response_timeout = FindingKind::ResponseTimeout;
    std::optional<FindingKind> request_rejected = FindingKind::RequestRejected;
    std::optional<FindingKind> no_authority = FindingKind::NoAuthority;
    std::optional<FindingKind> spontaneous_message = FindingKind::SpontaneousMessage;
    std::optional<FindingKind> spontaneous_unacknowledged = FindingKind::SpontaneousUnacknowledged;
    std::optional<FindingKind> spm_violation = FindingKind::SpmViolation;
    std::optional<FindingKind> unknown_code = FindingKind::UnknownCode;
};

// How a carrier's parameter channel behaves.
struct ParameterChannelPolicy {
    // The PKE has an SPM bit (PROFIBUS PPO): a spontaneous message toggles it and the master
    // acknowledges by toggling its own. The FC protocol has none.
    bool has_spm_bit = true;
    // The slave's response is prepared before the request of its cycle arrives, so it answers a
    // request one cycle late (PROFIBUS Data_Exchange). Without the lag the response in the same
    // exchange answers the request (the FC protocol).
    bool response_lags_one_cycle = true;
    // The master repeats its request in every cycle until it is answered, and the slave its
    // answer (PROFIBUS Data_Exchange). Without it (the FC protocol) every master sample is a new
    // request and every slave sample an answer to the request pending, never a repeat.
    bool cyclic_requests = true;
    bool strict = false;                      // RC 8 after a read is an unexpected answer
    std::int64_t timeout_ns = 1'000'000'000;  // no answer within it: a time-out
    ParameterChannelKinds kinds;
};

// One telegram with a parameter channel, as its carrier read it.
struct ParameterChannelSample {
    std::uint64_t frame = 0;
    std::int64_t time_ns = kNoTime;
    Direction direction = Direction::Request;  // request: the master's PCV; response: the slave's
    std::uint8_t master = 0;  // the channel (addresses 0..127); the same in both directions
    std::uint8_t slave = 0;
    Pcv pcv;
    Dialect dialect = Dialect::Vlt;  // the code tables the PCV is read with
    // The channel's cycles so far, counted by the carrier (this telegram's included): what
    // latency in cycles and the one-cycle lag are measured in.
    std::uint64_t cycle = 0;
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

// What the engine counts on one channel.
struct ParameterChannelStats {
    // Samples: telegrams with a parameter channel. None means nothing was checked.
    std::uint64_t parameter_telegrams = 0;
    std::uint64_t requests = 0;  // distinct parameter requests
    TransactionCounts transactions;
    std::uint64_t timeouts = 0;
    std::uint64_t abandoned = 0;  // dropped by the master before an answer
    std::uint64_t spontaneous = 0;
    LogHistogram latency_ns;
    LogHistogram latency_cycles;
    std::map<std::uint16_t, std::uint64_t> pnu_requests;      // PNU -> requests
    std::map<std::uint16_t, std::uint64_t> rejection_errors;  // error number -> count
    std::map<std::pair<std::uint16_t, std::uint16_t>, std::uint64_t> rejections;  // (PNU, error)
};

// A request answered: the transaction a sample completed.
struct CompletedTransaction {
    std::uint8_t master = 0;
    std::uint8_t slave = 0;
    std::uint64_t frame = 0;         // the answer
    std::int64_t time_ns = kNoTime;  // the answer's time
    bool timed = false;              // request and answer carry a time: the latency is known
};

class ParameterChannelEngine {
  public:
    explicit ParameterChannelEngine(ParameterChannelPolicy policy = {});
    ~ParameterChannelEngine();
    ParameterChannelEngine(const ParameterChannelEngine&) = delete;
    ParameterChannelEngine& operator=(const ParameterChannelEngine&) = delete;

    // Makes the channel `master` -> `slave` known (addresses 0..127), counting into `stats`:
    // the caller keeps them, beside its own counts for the channel, at the same address for the
    // engine's life. Time-outs are checked channel by channel in the order they were added.
    // Adding a channel again changes nothing.
    void add_channel(std::uint8_t master, std::uint8_t slave, ParameterChannelStats& stats);

    // Feeds the next sample of a channel added before (others are ignored), appending the
    // findings it shows to `out`. Returns the transaction it completed, if any.
    std::optional<CompletedTransaction> track(const ParameterChannelSample& sample,
                                              FindingList& out);
    // The carrier knows the request pending on the channel will not be answered (the FC master
    // sent its next telegram): it ends unanswered, without a finding (the carrier has reported
    // it), and a later answer finds no request pending.
    void abandon(std::uint8_t master, std::uint8_t slave);

    // The time is now `now_ns` (at the telegram `frame`, or the end of the capture): appends to
    // `out` the requests and spontaneous messages left unanswered past the time-out.
    void advance(std::int64_t now_ns, std::uint64_t frame, FindingList& out) {
        // Nothing can have passed its deadline before the earliest one (the per-telegram case).
        if (now_ns >= next_deadline_ns_) check_deadlines(now_ns, frame, out);
    }

    // The parameter number the last sample is about: the PCV's own PNU, except for a rejection
    // (RC 7) or "no authority" (RC 8) that leaves the PNU out (PNU 0): that one is about the
    // request it answers.
    std::int32_t subject_pnu() const noexcept { return subject_pnu_; }

  private:
    struct Channel;

    void master_pcv(Channel& ch, const ParameterChannelSample& s, FindingList& out);
    std::optional<CompletedTransaction> slave_pcv(Channel& ch, const ParameterChannelSample& s,
                                                  FindingList& out);
    void spontaneous_message(Channel& ch, const ParameterChannelSample& s, FindingList& out);
    CompletedTransaction answered(Channel& ch, const ParameterChannelSample& s);
    void check_deadlines(std::int64_t now_ns, std::uint64_t frame, FindingList& out);

    ParameterChannelPolicy policy_;
    ChannelIndex index_;  // (master, slave) -> position in channels_
    std::vector<std::unique_ptr<Channel>> channels_;
    std::int64_t next_deadline_ns_ = std::numeric_limits<std::int64_t>::max();
    std::int32_t subject_pnu_ = -1;
};

}  // namespace dpscope
