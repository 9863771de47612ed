// The one telegram type every stage after the decoder consumes (trackers, renderers, summary,
// report, fuzzers): what every protocol has (frame, time, bytes, direction, the stations where
// known, problems) and the protocol's own payload. The protocol is chosen once per capture; the
// decoder reuses one DecodedTelegram, so no payload is built or freed per telegram.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "core/byte_reader.hpp"
#include "core/problem.hpp"
#include "core/time.hpp"
#include "protocols/protocol_list.hpp"

namespace dpscope {

// Station addresses are 0..127 (the header's master and slave).
inline constexpr std::size_t kStationCount = 128;

// The protocols dpscope decodes, one per capture, as protocols/protocol_list.hpp registers them.
enum class Protocol : std::uint8_t {
#define DPSCOPE_PROTOCOL_ENUM(Enum, name, Payload, member) Enum,
    DPSCOPE_PROTOCOLS(DPSCOPE_PROTOCOL_ENUM)
#undef DPSCOPE_PROTOCOL_ENUM
};
inline constexpr std::size_t kProtocolCount = 0
#define DPSCOPE_PROTOCOL_COUNT(Enum, name, Payload, member) +1
    DPSCOPE_PROTOCOLS(DPSCOPE_PROTOCOL_COUNT);
#undef DPSCOPE_PROTOCOL_COUNT

// The record of `protocol` in one of the per-layer tables made from the registration list (the
// descriptors, the report's buses, the plugin's trees): a table is in the enum's order, and a
// value that names no protocol gets the first record (the default bus).
template <class Record>
const Record& protocol_record(std::span<const Record* const> table, Protocol protocol) noexcept {
    const auto index = static_cast<std::size_t>(protocol);
    return *table[index < table.size() ? index : 0];
}

// "profibus", "fc", "vlt2000": the name --bus takes and captures record (the descriptor's name;
// both are defined with the table, protocols/protocol_table.cpp).
std::string_view protocol_name(Protocol protocol) noexcept;
std::optional<Protocol> protocol_from_name(std::string_view name) noexcept;

class ParameterNaming;  // drives/parameter_naming.hpp

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
    // What names the PNUs of its drive (the slave) and scales their values: the naming its
    // decoder was given for the capture (drives/parameter_naming.hpp); null: none.
    const ParameterNaming* naming = nullptr;

    // The payload: the member `protocol` names is the one that holds this telegram.
    Protocol protocol{};
#define DPSCOPE_PROTOCOL_PAYLOAD(Enum, name, Payload, member) Payload member;
    DPSCOPE_PROTOCOLS(DPSCOPE_PROTOCOL_PAYLOAD)
#undef DPSCOPE_PROTOCOL_PAYLOAD

    // Every problem found at any layer, with byte offsets (each payload's payload_problems()).
    const ProblemList& problems() const noexcept {
#define DPSCOPE_PROTOCOL_PROBLEMS(Enum, name, Payload, member) \
    if (protocol == Protocol::Enum) return payload_problems(member);
        DPSCOPE_PROTOCOLS(DPSCOPE_PROTOCOL_PROBLEMS)
#undef DPSCOPE_PROTOCOL_PROBLEMS
        return kNoProblems;
    }
    bool has_time() const noexcept { return time_ns != kNoTime; }
};

}  // namespace dpscope
