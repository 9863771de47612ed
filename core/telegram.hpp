// The one telegram type every stage after the decoder consumes (trackers, renderers, summary,
// report, fuzzers): what every protocol has (frame, time, bytes, direction, the stations where
// known, problems) and the protocol's own payload. The protocol is chosen once per capture; the
// decoder reuses one DecodedTelegram, so no payload is built or freed per telegram.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

#include "core/byte_reader.hpp"
#include "core/problem.hpp"
#include "core/time.hpp"
#include "protocols/fc/fc_telegram.hpp"
#include "protocols/profibus/dp_telegram.hpp"
#include "protocols/vlt2000/vlt2000_telegram.hpp"

namespace dpscope {

// Station addresses are 0..127 (the header's master and slave).
inline constexpr std::size_t kStationCount = 128;

// The protocols dpscope decodes. One per capture.
enum class Protocol : std::uint8_t {
    ProfibusDp,  // PROFIBUS DP: the payload is `dp`
    Fc,          // the Danfoss FC protocol on RS-485: the payload is `fc`
    Vlt2000,     // the VLT 2000 serial telegram (ASCII; VLT 3000, 3500): the payload is `vlt2000`
};

// "profibus", "fc", "vlt2000": the name --bus takes and captures record.
std::string_view protocol_name(Protocol protocol) noexcept;
std::optional<Protocol> protocol_from_name(std::string_view name) noexcept;

struct DecodedTelegram {
    std::uint64_t frame = 0;         // 1-based record number
    std::int64_t time_ns = kNoTime;  // nanoseconds since the epoch; kNoTime when unknown
    Bytes bytes;                     // the record (valid until the next decode)
    Direction direction = Direction::Request;

    // The stations where known: requests go master -> slave, responses slave -> master. (In DP a
    // short acknowledge has no addresses of its own; it takes them from the request it answers.)
    bool has_roles = false;
    std::uint8_t master = 0;
    std::uint8_t slave = 0;
    std::uint64_t request_frame = 0;  // response: the request it answers (0: not in capture)

    // The payload: the member `protocol` names is the one that holds this telegram.
    Protocol protocol = Protocol::ProfibusDp;
    DpTelegram dp;
    FcTelegram fc;
    Vlt2000Telegram vlt2000;

    // Every problem found at any layer, with byte offsets.
    const ProblemList& problems() const noexcept {
        switch (protocol) {
            case Protocol::Fc: return fc.problems;
            case Protocol::Vlt2000: return vlt2000.problems;
            case Protocol::ProfibusDp: break;
        }
        return dp.fdl.problems;
    }
    bool has_time() const noexcept { return time_ns != kNoTime; }
};

}  // namespace dpscope
