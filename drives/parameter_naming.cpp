#include "drives/parameter_naming.hpp"

#include <string>
#include <utility>

#include "drives/shipped_databases.hpp"

namespace dpscope {

ParameterNaming::ParameterNaming(std::shared_ptr<const ParameterDatabase> database, Protocol bus,
                                 const std::array<Dialect, kStationCount>& dialects,
                                 const DriveHints& drives)
    : database_(std::move(database)),
      profile_(bus == Protocol::ProfibusDp ? database_->family(kProfileFamily) : nullptr) {
    for (std::size_t station = 0; station < kStationCount; ++station) {
        const auto address = static_cast<std::uint8_t>(station);
        families_[station] =
            database_->family(drive_family(bus, dialects[station], drives.of(address)));
        hinted_[station] = drives.of(address).has_value();
    }
}

void ParameterNaming::set_device_family(std::uint8_t station, std::string_view family) noexcept {
    if (hinted_[station & 0x7F]) return;
    if (const ParameterFamily* held = database_->family(family)) families_[station & 0x7F] = held;
}

DescribingNaming::DescribingNaming(const ParameterNaming& base)
    : described_(&base.database()), naming_(base) {
    naming_.describe_with(&described_);
}

DescribingNaming::DescribingNaming(const DescribingNaming& other)
    : described_(other.described_), naming_(other.naming_) {
    naming_.describe_with(&described_);
}

std::shared_ptr<const ParameterDatabase> shipped_parameter_database() {
    static const std::shared_ptr<const ParameterDatabase> database = [] {
        auto loaded = std::make_shared<ParameterDatabase>();
        for (const ShippedDatabase& shipped : shipped_databases())
            if (Result<ParameterFile> parsed = parse_parameter_database(shipped.text, shipped.file))
                loaded->add(std::move(parsed->family));
        return loaded;
    }();
    return database;
}

NamedParameter ParameterNaming::parameter(std::uint8_t station, std::uint16_t pnu) const noexcept {
    if (described_)
        if (const ParameterRow* row = described_->find(station, pnu))
            return {&described_->family(), row};
    const ParameterFamily* family = families_[station & 0x7F];
    if (family)
        if (const ParameterRow* row = family->find(pnu)) return {family, row};
    if (profile_ && is_profile_pnu(pnu))
        if (const ParameterRow* row = profile_->find(pnu)) return {profile_, row};
    return {};
}

}  // namespace dpscope
