// What the kind catalogues (core/finding.cpp, core/problem.cpp) share: the compile-time
// checks (one row per enum value in enum order, so that a kind is its row's index; names neither
// empty nor used twice, for they leave the program in every output format) and the listing of a
// component's kinds.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace dpscope::catalogue {

template <typename Row>
constexpr bool one_row_per_kind_in_order(std::span<const Row> rows, std::size_t kind_count) {
    if (rows.size() != kind_count) return false;
    for (std::size_t i = 0; i < rows.size(); ++i)
        if (static_cast<std::size_t>(rows[i].kind) != i) return false;
    return true;
}

template <typename Row>
constexpr bool names_unique(std::span<const Row> rows) {
    for (std::size_t i = 0; i < rows.size(); ++i) {
        if (rows[i].name.empty()) return false;
        for (std::size_t j = 0; j < i; ++j)
            if (rows[i].name == rows[j].name) return false;
    }
    return true;
}

// The kinds of `rows` that belong to `component`, in catalogue order.
template <typename Row, typename Component>
auto kinds_of(std::span<const Row> rows, Component component) {
    std::vector<decltype(Row::kind)> kinds;
    for (const Row& row : rows)
        if (row.component == component) kinds.push_back(row.kind);
    return kinds;
}

}  // namespace dpscope::catalogue
