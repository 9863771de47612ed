// What a drive says about its own parameters in a capture (issue 29): a PROFIdrive parameter
// description (DP-V1 parameter access, attribute 0x20) read by the master names the parameter's
// unit and conversion index, and sometimes its name, type and element count. dpscope keeps what
// each station said, and from then on names and scales that station's parameter by it: the
// drive's own word beats a database row written from a manual (docs/parameters.md, "The drive's
// own description"). Pure data, no I/O; bounded (kMaxDescribedParameters).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>

#include "drives/parameter_database.hpp"

namespace dpscope {

// Description elements [FCPB p. 52, FC 300 PROFIBUS p. 48]: 0 the whole description (46 bytes:
// identifier V2, element count U16, standardisation factor float, variable attribute 2 bytes,
// 4 reserved, name 16 characters, limits, ...), 1 the identifier, 2 the element count, 4 the
// variable attribute (byte 1 the variable index: the physical unit; byte 2 the conversion index),
// 6 the name.
namespace description_element {
inline constexpr std::uint16_t kComplete = 0;
inline constexpr std::uint16_t kIdentifier = 1;
inline constexpr std::uint16_t kElements = 2;
inline constexpr std::uint16_t kVariableAttribute = 4;
inline constexpr std::uint16_t kName = 6;
inline constexpr std::size_t kCompleteBytes = 46;
}  // namespace description_element

// The most (station, PNU) pairs kept; a capture that describes more keeps the first ones.
inline constexpr std::size_t kMaxDescribedParameters = 4096;

// The unit a PROFIdrive variable index (the size index of the Danfoss manuals) stands for, in
// the base unit a conversion index scales to; the indices that name their unit (70 minutes, 74
// hours, 77 days of index 4 time; 67 revolutions a minute) give that unit. Empty: none known.
std::string_view described_unit(std::uint8_t variable_index, std::int8_t conversion) noexcept;

class DescribedParameters {
  public:
    // `database`: gives a conversion index its factor (--conversion-index included); may be null
    // (the defaults of conversion_of_index).
    explicit DescribedParameters(const ParameterDatabase* database = nullptr);

    // A positive answer to description element `subindex` of `pnu` of `station`: its value
    // bytes (as the block carried them), in `frame`. `listed`: the row a database has for the
    // PNU, whose name, type and elements stand where the description gives none.
    void learn(std::uint8_t station, std::uint16_t pnu, std::uint16_t subindex,
               std::span<const std::uint8_t> bytes, std::uint64_t frame,
               const ParameterRow* listed);

    // The row the drive's description makes of `pnu` of `station`: null until a description has
    // given it a name (its own, or the database row's) and either a conversion or a name.
    const ParameterRow* find(std::uint8_t station, std::uint16_t pnu) const noexcept;
    // The family the rows are shown as (id "drive", the source "DESC" they cite).
    const ParameterFamily& family() const noexcept { return family_; }
    std::size_t size() const noexcept { return described_.size(); }

  private:
    struct Described {
        ParameterRow row;
        bool has_name = false;
        bool has_attribute = false;
        std::optional<std::int8_t> conversion;
        std::uint8_t variable_index = 0;
    };
    void update(Described& d, const ParameterRow* listed) const;

    const ParameterDatabase* database_;
    ParameterFamily family_;
    std::map<std::uint32_t, Described> described_;  // key: station << 16 | PNU
};

}  // namespace dpscope
