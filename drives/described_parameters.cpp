#include "drives/described_parameters.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>

namespace dpscope {

namespace {

// The physical units of the variable (size) index, each in the base unit a conversion index of 0
// counts [FCPB p. 80: time 4, energy 8, power 9, rotation 11, torque 16, temperature 17, voltage
// 21, current 22, resistance 23, ratio 24, relative change 27, frequency 28].
struct VariableUnit {
    std::uint8_t index;
    std::string_view unit;
};
constexpr VariableUnit kVariableUnits[] = {
    {4, "s"},  {8, "Wh"}, {9, "W"},    {11, "RPM"}, {16, "Nm"}, {17, "°C"},
    {21, "V"}, {22, "A"}, {23, "Ohm"}, {24, "%"},   {27, "%"},  {28, "Hz"},
};

// The identifier's data type (its low byte) as a row's type [FCPB p. 52; data types 3-7, 9, 33,
// 35]; nullopt for the others (a float, a time), which keep the listed row's or uint32.
std::optional<ParameterType> type_of_identifier(std::uint8_t data_type) noexcept {
    switch (data_type) {
        case 2: return ParameterType::Int8;
        case 3: return ParameterType::Int16;
        case 4: return ParameterType::Int32;
        case 5: return ParameterType::Uint8;
        case 6: return ParameterType::Uint16;
        case 7: return ParameterType::Uint32;
        case 9: return ParameterType::String;
        case 0x21: return ParameterType::N2;
        case 0x23: return ParameterType::V2;
        default: return std::nullopt;
    }
}

// A name as the drive sends it: up to 16 characters, padded with blanks or zeros; printable
// ASCII only (anything else ends it), trimmed.
std::string name_of(std::span<const std::uint8_t> bytes) {
    std::string name;
    for (std::uint8_t b : bytes.first(std::min<std::size_t>(bytes.size(), 16))) {
        if (b < 0x20 || b > 0x7E) break;
        name.push_back(static_cast<char>(b));
    }
    while (!name.empty() && name.back() == ' ')
        name.pop_back();
    const std::size_t first = name.find_first_not_of(' ');
    return first == std::string::npos ? std::string{} : name.substr(first);
}

}  // namespace

std::string_view described_unit(std::uint8_t variable_index, std::int8_t conversion) noexcept {
    if (variable_index == 4) {
        if (conversion == 70) return "min";
        if (conversion == 74) return "h";
        if (conversion == 77) return "d";
    }
    for (const VariableUnit& u : kVariableUnits)
        if (u.index == variable_index) return u.unit;
    return {};
}

DescribedParameters::DescribedParameters(const ParameterDatabase* database) : database_(database) {
    family_.id = "drive";
    family_.title = "the drive's own parameter description";
    family_.numbering = PnuNumbering::Plain;
    family_.sources.push_back(
        {"DESC",
         "the drive's parameter description read in this capture (PROFIdrive attribute 0x20)", ""});
}

void DescribedParameters::learn(std::uint8_t station, std::uint16_t pnu, std::uint16_t subindex,
                                std::span<const std::uint8_t> bytes, std::uint64_t frame,
                                const ParameterRow* listed) {
    namespace de = description_element;
    const bool useful = (subindex == de::kComplete && bytes.size() >= de::kCompleteBytes) ||
                        (subindex == de::kVariableAttribute && bytes.size() >= 2) ||
                        (subindex == de::kName && !bytes.empty()) ||
                        (subindex == de::kIdentifier && bytes.size() >= 2) ||
                        (subindex == de::kElements && bytes.size() >= 2);
    if (!useful) return;
    const std::uint32_t key = static_cast<std::uint32_t>(station & 0x7F) << 16 | pnu;
    auto at = described_.find(key);
    if (at == described_.end()) {
        if (described_.size() >= kMaxDescribedParameters) return;
        at = described_.emplace(key, Described{}).first;
        at->second.row.pnu = pnu;
        at->second.row.source_index = 0;
    }
    Described& d = at->second;
    const auto identifier = [&](std::span<const std::uint8_t> id) {
        if (std::optional<ParameterType> type = type_of_identifier(id[1])) d.row.type = *type;
    };
    const auto elements = [&](std::span<const std::uint8_t> count) {
        d.row.elements =
            std::max<std::uint32_t>(1, static_cast<std::uint32_t>(count[0]) << 8 | count[1]);
    };
    const auto attribute = [&](std::span<const std::uint8_t> va) {
        d.has_attribute = true;
        d.variable_index = va[0];
        d.conversion = static_cast<std::int8_t>(va[1]);
    };
    const auto name = [&](std::span<const std::uint8_t> text) {
        std::string n = name_of(text);
        if (n.empty()) return;
        d.row.name = std::move(n);
        d.has_name = true;
    };
    switch (subindex) {
        case de::kComplete:
            identifier(bytes.subspan(0, 2));
            elements(bytes.subspan(2, 2));
            attribute(bytes.subspan(8, 2));
            name(bytes.subspan(14, 16));
            break;
        case de::kIdentifier: identifier(bytes); break;
        case de::kElements: elements(bytes); break;
        case de::kVariableAttribute: attribute(bytes); break;
        case de::kName: name(bytes); break;
        default: break;
    }
    d.row.source = fmt::format("DESC frame {}", frame);
    update(d, listed);
}

void DescribedParameters::update(Described& d, const ParameterRow* listed) const {
    if (listed) {
        if (!d.has_name) d.row.name = listed->name;
        d.row.line = listed->line;
    }
    if (d.has_attribute && d.conversion) {
        d.row.conversion = *d.conversion;
        d.row.scaling =
            database_ ? database_->conversion(*d.conversion) : conversion_of_index(*d.conversion);
        const std::string_view unit = described_unit(d.variable_index, *d.conversion);
        d.row.unit = unit.empty() && listed ? listed->unit : std::string(unit);
    } else if (listed) {
        d.row.unit = listed->unit;
        d.row.conversion = listed->conversion;
        d.row.scaling = listed->scaling;
    }
}

const ParameterRow* DescribedParameters::find(std::uint8_t station,
                                              std::uint16_t pnu) const noexcept {
    const auto at = described_.find(static_cast<std::uint32_t>(station & 0x7F) << 16 | pnu);
    if (at == described_.end()) return nullptr;
    const Described& d = at->second;
    if (d.row.name.empty() || !(d.has_attribute || d.has_name)) return nullptr;
    return &d.row;
}

}  // namespace dpscope
