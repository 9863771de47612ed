// Which drive family's database names the PNUs of a station (issue 29; the rule is in
// docs/decisions.md, "Drive parameter databases"): a hint when there is one (--drive, and later
// what a slave's GSD file says), else the bus's own family (the FC protocol: fc; VLT 2000:
// vlt2000), else for a PROFIBUS slave its parameter-channel dialect's (vlt: vlt5000, ge: af600,
// profidrive: fc).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "core/code_tables.hpp"
#include "core/telegram.hpp"

namespace dpscope {

// The family of a PROFIBUS slave decoded in `dialect`: vlt5000, af600 or fc.
std::string_view family_of_dialect(Dialect dialect) noexcept;

// The family whose database names the PNUs of a station on `bus`; `dialect` is the PROFIBUS
// slave's (ignored on the other buses). The result names a family that may not be loaded.
std::string_view drive_family(Protocol bus, Dialect dialect,
                              std::optional<std::string_view> hint = std::nullopt) noexcept;

// --drive [ADDR=]FAMILY: the family named for every station, and for single stations (a station's
// own wins). Empty: none named.
struct DriveHints {
    std::string all;
    std::array<std::string, kStationCount> station{};

    // The family named for `station`, if any.
    std::optional<std::string_view> of(std::uint8_t station) const noexcept;
};

}  // namespace dpscope
