// How the rules hand out what they find: each appends its findings to a list its caller owns, in
// the order found, and the caller counts them.
#pragma once

#include <cstdint>
#include <vector>

#include "core/finding.hpp"

namespace dpscope {

using FindingList = std::vector<Finding>;

// Appends a finding of `kind` at its default severity, for the telegram `frame` at `time_ns`,
// about the request `request_frame` (0: none) on the channel `master` -> `slave` (when
// `has_stations`). Returns it for the message and the PNU.
inline Finding& add_finding(FindingList& out, FindingKind kind, std::uint64_t frame,
                            std::int64_t time_ns, std::uint64_t request_frame, bool has_stations,
                            std::uint8_t master, std::uint8_t slave) {
    Finding& f = out.emplace_back();
    f.kind = kind;
    f.severity = default_severity(kind);
    f.frame = frame;
    f.request_frame = request_frame;
    f.time_ns = time_ns;
    f.has_stations = has_stations;
    f.master = master;
    f.slave = slave;
    return f;
}

}  // namespace dpscope
