// What names the PNUs of a capture's telegrams (issue 29): the drive family of each station,
// resolved once per capture by the family rule (drives/drive_family.hpp) from the bus, the
// PROFIBUS slaves' dialects and --drive, over the loaded databases. A decoder given one puts it
// on every telegram it decodes (DecodedTelegram::naming), so that the renderings, the report and
// the Wireshark plugin find a PNU's row with one array read and a binary search.
#pragma once

#include <array>
#include <cstdint>
#include <memory>

#include "core/code_tables.hpp"
#include "core/telegram.hpp"
#include "drives/described_parameters.hpp"
#include "drives/drive_family.hpp"
#include "drives/parameter_database.hpp"

namespace dpscope {

class ParameterNaming;

// What names one station's PNUs (ParameterNaming::parameter for one station): cheap to copy; a
// default one names nothing.
struct StationNaming {
    const ParameterNaming* naming = nullptr;
    std::uint8_t station = 0;

    NamedParameter operator()(std::uint16_t pnu) const noexcept;
};

class ParameterNaming {
  public:
    // `dialects`: each PROFIBUS slave's (ignored on the other buses).
    ParameterNaming(std::shared_ptr<const ParameterDatabase> database, Protocol bus,
                    const std::array<Dialect, kStationCount>& dialects, const DriveHints& drives);

    // The family that names the PNUs of `station`'s drive; nullptr when no database holds it.
    const ParameterFamily* family(std::uint8_t station) const noexcept {
        return families_[station & 0x7F];
    }
    // The row of `pnu` for `station`'s drive: its family and row, both null when there is none.
    NamedParameter parameter(std::uint8_t station, std::uint16_t pnu) const noexcept;
    StationNaming station(std::uint8_t address) const noexcept {
        return StationNaming{this, static_cast<std::uint8_t>(address & 0x7F)};
    }
    const ParameterDatabase& database() const noexcept { return *database_; }
    const std::shared_ptr<const ParameterDatabase>& database_ptr() const noexcept {
        return database_;
    }

    // A slave's device description (its GSD file) names its family: taken unless --drive named
    // one for the station (a family no database holds changes nothing).
    void set_device_family(std::uint8_t station, std::string_view family) noexcept;

    // What the drives of the capture said about their parameters (a decoder's, kept as it
    // decodes): a row there wins over the databases' (parameter()). Null: none.
    void describe_with(const DescribedParameters* described) noexcept { described_ = described; }

  private:
    std::shared_ptr<const ParameterDatabase> database_;
    std::array<const ParameterFamily*, kStationCount> families_{};
    std::array<bool, kStationCount> hinted_{};  // --drive named the station's family
    // On PROFIBUS, the profile family that names the profile PNUs a station's family has no row
    // for; null elsewhere or when not loaded.
    const ParameterFamily* profile_ = nullptr;
    const DescribedParameters* described_ = nullptr;
};

// A capture's naming with what its drives described put first (a decoder's, which learns the
// descriptions as it decodes): one object, so that a copy (a decoder's clone) names with its own
// copy of the descriptions.
class DescribingNaming {
  public:
    explicit DescribingNaming(const ParameterNaming& base);
    DescribingNaming(const DescribingNaming& other);
    DescribingNaming& operator=(const DescribingNaming&) = delete;

    const ParameterNaming& naming() const noexcept { return naming_; }
    ParameterNaming& naming() noexcept { return naming_; }
    DescribedParameters& described() noexcept { return described_; }

  private:
    DescribedParameters described_;
    ParameterNaming naming_;
};

// The shipped databases (drives/shipped_databases.hpp), parsed once; a database that does not
// parse is left out (a test keeps them free of errors). For what has no command line to name
// --params files: the Wireshark plugin.
std::shared_ptr<const ParameterDatabase> shipped_parameter_database();

inline NamedParameter StationNaming::operator()(std::uint16_t pnu) const noexcept {
    return naming ? naming->parameter(station, pnu) : NamedParameter{};
}

// What names the PNUs of `station`; names nothing without a naming.
inline StationNaming station_naming(const ParameterNaming* naming, std::uint8_t station) noexcept {
    return naming ? naming->station(station) : StationNaming{};
}

// The row naming `pnu` of the telegram's drive (its slave), by the naming its decoder was given;
// both null when there is none.
inline NamedParameter named_parameter(const DecodedTelegram& t, std::uint16_t pnu) noexcept {
    return t.naming ? t.naming->parameter(t.slave, pnu) : NamedParameter{};
}

}  // namespace dpscope
