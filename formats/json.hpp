// The JSON shapes shared by the jsonl renderer and the JSON report, written with JsonWriter.
#pragma once

#include <array>
#include <cstdint>

#include "core/finding.hpp"
#include "formats/json_writer.hpp"

namespace dpscope::json {

// A finding as an object: kind, severity, frame, request_frame, time, master, slave, pnu,
// message (null where unknown). The same shape in jsonl and in the JSON report.
void finding(JsonWriter& w, const Finding& f);

// Finding counts by kind as an object with every kind: {"stacked_request":0,...}.
void finding_kind_counts(JsonWriter& w, const std::array<std::uint64_t, kFindingKindCount>& counts);

// Seconds since the epoch with nanoseconds ("1704067200.000123000"), or null for kNoTime.
void time(JsonWriter& w, std::int64_t time_ns);

}  // namespace dpscope::json
