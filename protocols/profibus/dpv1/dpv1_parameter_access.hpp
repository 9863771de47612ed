// The DP-V1 parameter-access tracker: follows PROFIdrive parameter access over DP-V1 (MSAC_C1 and
// MSAC_C2) per master and slave and reports where it went wrong
// (docs/protocol/dpv1-parameter-access.md, "Sequence" and "Checks a tracker can make"). No I/O;
// memory is bounded per channel and nothing is kept per telegram.
//
// How the exchange is read:
//  - One transaction per (master, slave, slot, index): a DP-V1 Write carrying a PROFIdrive
//    parameter request, the Write response (or a negative one, which ends it), Reads until the
//    parameter response comes (a Read answered "state conflict", Error_Code_1 0xB5, is a poll:
//    counted, no finding), and the Read response that completes it. Latency runs from the Write
//    to that Read response.
//  - A transaction without its response within the time-out is counted as timed out once. It
//    stays known, so a response (or refusal) after the time-out ends it as "late": checked like
//    any response, no orphan, neither completed nor in the latency. A new Write to its slot and
//    index ends it silently (the master gave up).
//  - The DP-V1 response may come in a later FDL response than the one to its request (the
//    slave answers link polls with an empty data unit or a short acknowledge meanwhile): a
//    response is paired with the last DP-V1 request of the same function on the channel, not
//    with the FDL request it follows. Telegrams without a DP-V1 PDU are no part of it.
//  - A Write repeated unchanged before its Write response (an FDL retry) is the same request.
//  - A parameter response before the first parameter request written on the channel is not
//    judged (a capture may begin while a request made before it is under way).
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <vector>

#include "core/channel_index.hpp"
#include "core/code_tables.hpp"
#include "core/finding_list.hpp"
#include "core/log_histogram.hpp"
#include "core/telegram.hpp"
#include "core/time.hpp"

namespace dpscope {

// What the tracker counts on one channel (master -> slave).
struct Dpv1Stats {
    // At most this many distinct PNUs are counted per channel; the others only in
    // parameters_not_counted.
    static constexpr std::size_t kMaxParameters = 256;
    // At most this many distinct error numbers are listed per channel; the others only in
    // negative_errors_not_listed.
    static constexpr std::size_t kMaxNegativeErrors = 256;

    struct ParameterUse {
        std::uint64_t reads = 0;   // in request-value requests
        std::uint64_t writes = 0;  // in change requests
    };

    // Every transaction started ends in exactly one of completed, refused, abandoned and
    // timeouts, or is still open: started = completed + refused + abandoned + timeouts + open.
    std::uint64_t telegrams = 0;  // telegrams with a DP-V1 PDU, both directions
    std::uint64_t started = 0;    // parameter requests written
    std::uint64_t completed = 0;  // answered by a parameter response within the time-out
    std::uint64_t refused = 0;    // ended by a negative Write or Read response (error PDU)
    std::uint64_t abandoned = 0;  // replaced by a new request before the response was read
    std::uint64_t timeouts = 0;   // no response within the time-out
    std::uint64_t late = 0;       // of the timeouts: answered (or refused) after it
    std::uint64_t open = 0;       // neither ended nor timed out (yet, or at the end)
    std::uint64_t polls = 0;      // Reads answered "state conflict"
    std::uint64_t max_polls = 0;  // the most in one transaction, whatever its end
    LogHistogram latency_ns;      // Write to the completing Read response
    std::uint64_t latency_sum_ns = 0;
    std::map<std::uint16_t, ParameterUse> parameters;  // PNU -> accesses
    std::uint64_t parameters_not_counted = 0;          // accesses to PNUs beyond kMaxParameters
    std::uint64_t negative_responses = 0;
    std::map<std::uint16_t, std::uint64_t> negative_errors;  // error number -> blocks
    std::uint64_t negative_errors_not_listed = 0;  // blocks with numbers beyond the first 256
    std::uint64_t error_pdus = 0;                  // negative DP-V1 responses other than polls
    Dialect dialect = Dialect::Vlt;
    std::int64_t first_time_ns = kNoTime;
    std::int64_t last_time_ns = kNoTime;

    std::uint64_t latency_mean_ns() const noexcept {
        return latency_ns.count() ? latency_sum_ns / latency_ns.count() : 0;
    }
};

class Dpv1ParameterAccessTracker {
  public:
    explicit Dpv1ParameterAccessTracker(std::int64_t timeout_ns = 1'000'000'000);
    ~Dpv1ParameterAccessTracker();
    Dpv1ParameterAccessTracker(const Dpv1ParameterAccessTracker&) = delete;
    Dpv1ParameterAccessTracker& operator=(const Dpv1ParameterAccessTracker&) = delete;

    // Makes the channel `master` -> `slave` known (addresses 0..127), counting into `stats`,
    // which the caller keeps at the same address for the tracker's life. Time-outs are checked
    // channel by channel in the order they were added. Adding a channel again changes nothing.
    void add_channel(std::uint8_t master, std::uint8_t slave, Dpv1Stats& stats);

    // Feeds a telegram of a channel added before whose service data is a DP-V1 PDU
    // (`t.dp.service_data.dpv1()`), appending what it shows to `out`. Others are ignored.
    void track(const DecodedTelegram& t, FindingList& out);
    // The time is now `now_ns` (at the telegram `frame`, or the end of the capture): appends to
    // `out` the transactions left without a response past the time-out.
    void advance(std::int64_t now_ns, std::uint64_t frame, FindingList& out) {
        if (now_ns >= next_deadline_ns_) check_deadlines(now_ns, frame, out);
    }

  private:
    struct Channel;
    struct Transaction;

    void request(Channel& ch, const DecodedTelegram& t, const Dpv1Pdu& pdu, FindingList& out);
    void response(Channel& ch, const DecodedTelegram& t, const Dpv1Pdu& pdu, FindingList& out);
    void write_request(Channel& ch, const DecodedTelegram& t, const Dpv1Pdu& pdu,
                       const ProfidriveMessage& request, FindingList& out);
    void error_pdu(Channel& ch, const DecodedTelegram& t, const Dpv1Pdu& pdu, FindingList& out);
    void parameter_response(Channel& ch, const DecodedTelegram& t, const Dpv1Pdu& pdu, int read_max,
                            FindingList& out);
    void check_deadlines(std::int64_t now_ns, std::uint64_t frame, FindingList& out);

    std::int64_t timeout_ns_;
    ChannelIndex index_;  // (master, slave) -> position in channels_
    std::vector<std::unique_ptr<Channel>> channels_;
    std::int64_t next_deadline_ns_ = std::numeric_limits<std::int64_t>::max();
};

}  // namespace dpscope
