// The filter language (issue 30; docs/filter.md): one expression language for what decode, hex
// and sniff show (-Y), what --station and --pnu select, and what a sniffer's triggers fire on.
// Fields by the Wireshark plugin's names (`dpscope.pcv.rc == 7`, `dpscope.station == 5`,
// `dpscope.finding == "stacked_request"`, `health.event == "station_lost"`), comparisons, `&&`,
// `||`, `!`, parentheses, `in {...}` and `contains`. Parsed once into a small tree; evaluated per
// telegram without allocating. A syntax error names its column.
#pragma once

#include <bitset>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/filter_field.hpp"
#include "core/protocol_descriptor.hpp"
#include "core/result.hpp"

namespace dpscope {

// The fields every bus has (frame.number, dpscope.bus, dpscope.direction, dpscope.master,
// dpscope.slave, dpscope.station, dpscope.finding..., dpscope.problem, health.*).
std::span<const FilterField> common_filter_fields() noexcept;

// The fields named `name`: the common one and each protocol's (a name several protocols define,
// such as dpscope.pnu, is each of them, for the telegrams of its bus); empty when none.
std::vector<const FilterField*> filter_fields_named(std::string_view name);

// Every field name, sorted, once each.
std::vector<std::string_view> filter_field_names();

enum class FilterOp : std::uint8_t { Eq, Ne, Lt, Le, Gt, Ge, Contains, In, Exists };

class DisplayFilter {
  public:
    // A value in the expression: an integer (or a range low..high in a set) or text.
    struct Literal {
        bool is_text = false;
        std::int64_t low = 0;
        std::int64_t high = 0;
        std::string text;
    };
    // A node of the tree: Or/And of two, Not of one, or a test of a field.
    struct Node {
        enum class Kind : std::uint8_t { Or, And, Not, Test } kind = Kind::Test;
        std::size_t left = 0, right = 0;
        // Test: fields_[field_first, +field_count) (a name several buses define is each of
        // theirs), the operator and literals_[literal_first, +literal_count) (a set's items).
        std::size_t field_first = 0, field_count = 0;
        FilterOp op = FilterOp::Exists;
        FilterType type = FilterType::Integer;
        std::size_t literal_first = 0, literal_count = 0;
    };

    // Parses `text`; an error is "column N: what" (1-based, in bytes).
    static Result<DisplayFilter> parse(std::string_view text);

    // Whether the input is selected.
    bool matches(const FilterInput& in) const noexcept;
    const std::string& text() const noexcept { return text_; }
    // Whether the expression reads a field whose name starts with `prefix` ("health.": the
    // bus health must be tracked for it).
    bool reads(std::string_view prefix) const noexcept;

  private:
    DisplayFilter() = default;
    bool evaluate(std::size_t node, const FilterInput& in) const noexcept;

    std::string text_;
    std::vector<Node> nodes_;
    std::vector<Literal> literals_;
    std::vector<const FilterField*> fields_;
    std::size_t root_ = 0;
    friend class FilterParser;
};

// Marks in `seen` each parameter the input is about, by the buses' `dpscope.pnu` fields (a
// cyclic PCV's from `in.subject_pnu`, the tracker's): what --pnu can select, for the warning
// about a --pnu no telegram names.
void mark_telegram_pnus(const FilterInput& in, PnuSet& seen);
// The same for the stations, by the `dpscope.station` fields: without findings in `in`, the
// stations the telegram is to or from (for the warning about a --station no telegram names).
void mark_telegram_stations(const FilterInput& in, std::bitset<kStationCount>& seen);

// --station/--pnu as the filter language says them: `dpscope.station in {3 5}`,
// `dpscope.pnu in {1613} || dpscope.finding.pnu in {1613}` (empty lists: "").
std::string station_filter_text(std::span<const std::uint8_t> stations);
std::string pnu_filter_text(std::span<const std::uint16_t> pnus);

}  // namespace dpscope
