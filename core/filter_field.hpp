// The fields of the filter language (filter/, docs/filter.md; issue 30): what a telegram, its
// findings and the health events it caused hold under a name the Wireshark plugin's display
// filter also uses (`dpscope.pcv.rc`). Each protocol lists its own fields (its descriptor's
// `filter_fields`); the fields every bus has are filter/'s. A field yields zero or more values
// of one type; a comparison holds when one of them satisfies it, as in Wireshark.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include "core/finding.hpp"
#include "core/telegram.hpp"

namespace dpscope {

enum class FilterType : std::uint8_t {
    Integer,  // compared as numbers; `true`/`false` are 1/0
    Text,     // compared as text; `contains`
};

struct FilterValue {
    std::int64_t integer = 0;
    std::string_view text;
};

// A health event a telegram caused (PROFIBUS bus health): station_lost, station_returned,
// verdict_bad; the station's address (255: the segment) and the verdict it gave ("bad") or "".
struct FilterEvent {
    std::string_view event;
    std::string_view verdict;
    std::uint16_t station = 0;
};

// What a filter is evaluated on: the telegram as decoded, what the trackers found on it, the
// tracker's PNU of a cyclic parameter-channel telegram (-1: none), and the health events it caused.
struct FilterInput {
    const DecodedTelegram& t;
    std::span<const Finding> findings = {};
    std::int32_t subject_pnu = -1;
    std::span<const FilterEvent> events = {};
};

// Sees a field's values one by one; returns true to stop (the comparison holds).
class FilterVisitor {
  public:
    virtual bool visit(const FilterValue& value) const = 0;

  protected:
    ~FilterVisitor() = default;
};

// Shows a field's value: a number, or text.
inline bool visit_integer(const FilterVisitor& visit, std::int64_t value) {
    return visit.visit(FilterValue{value, {}});
}
inline bool visit_text(const FilterVisitor& visit, std::string_view value) {
    return visit.visit(FilterValue{0, value});
}

struct FilterField {
    std::string_view name;  // "dpscope.pcv.rc"
    FilterType type = FilterType::Integer;
    // Shows the visitor each value the input has; true when the visitor stopped.
    bool (*values)(const FilterInput& in, const FilterVisitor& visit) = nullptr;
    std::string_view description;  // one line for docs/filter.md and `dpscope filter --fields`
};

}  // namespace dpscope
