// Private to the bus-health renderers (formats/health_*.cpp): the tables and cells that several
// formats share, built from BusHealth once and written by each format in its own markup (text,
// Markdown, HTML), and the slave counters' columns that JSON and CSV list too. Not for other
// users: the renderers' interface is protocols/profibus/health/health_render.hpp.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "protocols/profibus/health/bus_health.hpp"

namespace dpscope::health::detail {

// A table: its headers, which columns are numbers (right-aligned), and its rows of cells.
struct Table {
    std::vector<std::string_view> headers;
    std::vector<bool> numeric;  // right-aligned
    std::vector<std::vector<std::string>> rows;
};

std::string number(std::uint64_t n);

// A station's own state at the end, its verdict and when it was seen.
Table live_list(const BusHealth& h);

struct SlaveColumn {
    std::string_view header;  // text, Markdown and HTML
    std::string_view id;      // CSV
    std::function<std::uint64_t(const StationHealth&)> value;
    // In the slave table of text, Markdown and HTML; the illegal and negative answers by kind are
    // CSV columns only: the table shows them in one cell each (illegal_cell, negative_cell).
    bool in_table = true;
};

// Every counter of a station as asked, in the order of the slave table and the CSV columns.
const std::vector<SlaveColumn>& slave_columns();

// The stations in_slave_table() lists, with their counters.
Table slave_table(const BusHealth& h);

// The target token rotation in ns (0: none given).
double target_rotation_ns(const BusHealth& h);

// min, mean, p95, max in ms; "-" each when nothing was measured.
std::array<std::string, 4> duration_cells(const DurationStats& d);

// Each master's tokens, token rotation, target, poll cycle, jitter and slaves polled.
Table master_table(const BusHealth& h);

// The stations and masters whose verdict is not good, with their reasons.
struct Judged {
    std::string who;
    const Judgement* judgement;
};

std::vector<Judged> not_good(const BusHealth& h);

// A threshold's value as the user gives it ("0.1", "3").
std::string threshold_value(double value);

}  // namespace dpscope::health::detail
