// Which drive family's database names the PNUs of a station (issue 29; the rule is in
// docs/decisions.md, "Drive parameter databases"): a hint when there is one (--drive, and later
// what a slave's GSD file says), else the bus's own family (the FC protocol: fc; VLT 2000:
// vlt2000), else for a PROFIBUS slave its parameter-channel dialect's (vlt: vlt5000, ge: af600,
// profidrive: profidrive, the profile's own parameters, whoever made the drive). On PROFIBUS, a
// profile parameter (is_profile_pnu) a station's family has no row for is named by the
// profidrive family (ParameterNaming).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "core/code_tables.hpp"
#include "core/telegram.hpp"

namespace dpscope {

// The family of a PROFIBUS slave decoded in `dialect`: vlt5000, af600 or profidrive.
std::string_view family_of_dialect(Dialect dialect) noexcept;

// The family of the PROFIdrive profile's parameters (drives/databases/profidrive.params).
inline constexpr std::string_view kProfileFamily = "profidrive";

// A PNU the PROFIdrive profile defines for every drive (900 to 999 and 60000 to 65535); the others
// are the maker's.
constexpr bool is_profile_pnu(std::uint16_t pnu) noexcept {
    return (pnu >= 900 && pnu <= 999) || pnu >= 60000;
}

// The family whose database names the PNUs of a station on `bus`; `dialect` is the PROFIBUS
// slave's (ignored on the other buses). The result names a family that may not be loaded.
std::string_view drive_family(Protocol bus, Dialect dialect,
                              std::optional<std::string_view> hint = std::nullopt) noexcept;

// The family a slave's GSD file names by its Vendor_Name and Model_Name (issue 29; after --drive,
// before the bus and the dialect): Danfoss "VLT 5000"/"VLT 5xxx" vlt5000, Danfoss "FC 1xx/2xx/3xx"
// or a VLT drive name of the FC series ("AutomationDrive", "HVAC Drive", "AQUA Drive") fc, GE
// "AF-600"/"AF-650" af600; nullopt for any other device (matched without regard to case).
std::optional<std::string_view> family_of_device(std::string_view vendor,
                                                 std::string_view model) noexcept;

// --drive [ADDR=]FAMILY: the family named for every station, and for single stations (a station's
// own wins). Empty: none named.
struct DriveHints {
    std::string all;
    std::array<std::string, kStationCount> station{};

    // The family named for `station`, if any.
    std::optional<std::string_view> of(std::uint8_t station) const noexcept;
};

}  // namespace dpscope
