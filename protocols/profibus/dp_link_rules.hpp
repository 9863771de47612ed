// The PROFIBUS link rules (FDL, layer 2), judged on each decoded telegram apart from what it
// carries: fcs_error and malformed_telegram (a damaged telegram is reported and otherwise
// ignored), fdl_retry (a request repeated with the same frame count bit) and fdl_no_response (a
// request that expected a reply and got none). docs/protocol/fdl-and-dp.md.
#pragma once

#include "core/finding_list.hpp"
#include "core/telegram.hpp"

namespace dpscope {

// The frame count of the requests on one master -> slave link: the FCB of the last SRD/SDA
// request. Kept by the caller per channel.
struct FrameCountState {
    bool valid = false;
    bool last_fcb = false;
};

// The two checks run on every telegram test the usual case (nothing to report) inline and
// report out of line.
void report_reply_missing(const DecodedTelegram& t, FindingList& out);
bool report_damage(const DecodedTelegram& t, FindingList& out);

// fdl_no_response: `t` ended the wait for a reply to an SRD or SDA request that never came.
inline void check_reply_missing(const DecodedTelegram& t, FindingList& out) {
    if (t.dp.unanswered) report_reply_missing(t, out);
}

// fcs_error, malformed_telegram (a problem of error severity at any layer). Returns whether `t`
// is intact: only an intact telegram is read any further.
inline bool check_intact(const DecodedTelegram& t, FindingList& out) {
    if (t.dp.fdl.fcs_ok && t.problems().empty()) return true;
    return report_damage(t, out);
}

// fdl_retry, for an intact telegram with its stations. Returns whether `t` repeats the last
// request with the same FCB. FDL_Status and requests without a valid FCB restart the count.
bool check_frame_count(FrameCountState& state, const DecodedTelegram& t, FindingList& out);

// For a damaged telegram with its stations: is it an SRD/SDA request the slave drops? Its FCB
// still counts, for the master repeats the request with it (and the repeat is then no retry of
// a request the slave received).
bool note_dropped_request(FrameCountState& state, const DecodedTelegram& t);

}  // namespace dpscope
