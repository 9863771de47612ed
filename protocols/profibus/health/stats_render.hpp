// `dpscope stats`: the bus-health picture of a PROFIBUS capture
// (protocols/profibus/health/bus_health.hpp) in text, json, markdown, html (with an SVG timeline of
// each station's state and a plot of cycle time and token rotation) and csv; and the live station
// table of `sniff --stats`. Renderers only render: every figure and verdict comes from the
// BusHealth they are given.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "formats/output.hpp"
#include "formats/summary.hpp"
#include "protocols/profibus/health/bus_health.hpp"

namespace dpscope {

enum class StatsFormat { Text, Json, Markdown, Html, Csv };

std::string_view stats_format_name(StatsFormat format);
std::optional<StatsFormat> stats_format_from_name(std::string_view name);

struct StatsContext {
    InputSummary input;
    const BusHealth* health = nullptr;
    std::string version;  // dpscope's version, named in the output
};

// Writes the statistics of `context` in `format`.
void render_stats(StatsFormat format, const StatsContext& context, Output& out);

// The live station table of `sniff --stats`: one line per listed station (address, role, state,
// requests, answers, no answers, repeats, lost, illegal, damaged, verdict) and a segment line.
// `width`: the terminal's columns (0: no limit).
void render_live_table(const BusHealth& health, Output& out, unsigned width = 0);

}  // namespace dpscope
