// The options of every protocol's decoder and tracker, as a command's options (cli/
// common_options.cpp) or the Wireshark plugin's preferences (wireshark/capture_replay.cpp) set
// them. A protocol's descriptor makes its decoder and tracker from it
// (ProtocolDescriptor::make_decoder, make_tracker, core/protocol_lane.hpp), taking the members
// that are its own. A protocol with options of its own adds its members here; one without uses
// what every protocol shares (timeout_ns).
#pragma once

#include <cstdint>
#include <memory>

#include "drives/parameter_naming.hpp"
#include "protocols/fc/fc_decoder.hpp"
#include "protocols/fc/fc_tracker.hpp"
#include "protocols/profibus/bus_decoder.hpp"
#include "protocols/profibus/session_tracker.hpp"
#include "protocols/vlt2000/vlt2000_decoder.hpp"
#include "protocols/vlt2000/vlt2000_tracker.hpp"

namespace dpscope {

struct LaneOptions {
    // Every protocol: --timeout-ms, after which an unanswered request is a finding (and a
    // telegram is no longer a response to it); each factory sets its decoder's and tracker's
    // time-outs from it.
    std::int64_t timeout_ns = 1'000'000'000;
    // The line the capture was made on (--baud, what the capture records, sniff's port), which a
    // protocol timed by the line (ProtocolDescriptor::timed_by_line) times its responses by; its
    // factory sets its tracker's line from these. 0: not known (the baud rate: the protocol's
    // default_baud; the bits a character takes: the protocol's own framing).
    std::uint32_t line_baud = 0;
    std::uint32_t character_bits = 0;
    // Every protocol: what names the PNUs of the capture's drives and scales their values
    // (drives/parameter_naming.hpp; made for the capture's bus once it is known); each factory
    // gives it to its decoder. Null: nothing is named.
    std::shared_ptr<const ParameterNaming> naming{};
    // PROFIBUS DP.
    DecoderOptions decoder;
    TrackerOptions tracker;
    // The FC protocol.
    FcDecoderOptions fc_decoder;
    FcTrackerOptions fc_tracker;
    // VLT 2000.
    Vlt2000DecoderOptions vlt2000_decoder;
    Vlt2000TrackerOptions vlt2000_tracker;
};

// A tracker's options timed by the line (ProtocolDescriptor::timed_by_line), with what the shared
// options say: the time-out, the line's baud rate (`default_baud` when not known) and the bits a
// character takes (the tracker's own framing when not known).
template <class TimedTrackerOptions>
TimedTrackerOptions on_the_line(TimedTrackerOptions tracker, const LaneOptions& options,
                                std::uint32_t default_baud) {
    tracker.timeout_ns = options.timeout_ns;
    tracker.line_baud = options.line_baud != 0 ? options.line_baud : default_baud;
    if (options.character_bits != 0) tracker.character_bits = options.character_bits;
    return tracker;
}

}  // namespace dpscope
