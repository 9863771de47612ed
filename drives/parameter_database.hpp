// Drive parameter databases (issue 29): what a drive family's parameter numbers (PNUs) mean, so
// that a PNU is shown with its name and a value scaled into its unit by the Danfoss conversion
// index (index -1: raw 500 is 50.0 Hz). Pure text parsing and lookups, no I/O: the caller reads a
// file's bytes and names it for messages. The file format, the family rule and the scaling are
// documented in docs/parameters.md.
//
//   # comment line
//   @family fc
//   @title Danfoss VLT FC series (FC 102, FC 202, FC 301, FC 302)
//   @numbering group
//   @source PG302 = Danfoss, VLT AutomationDrive FC 301/FC 302 Programming Guide, MG33MO02, 2014
//   # pnu | name | unit | conversion | type | elements | source
//   1613 | Frequency | Hz | -1 | int32 | 1 | PG302 p. 212
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"

namespace dpscope {

// The data type of a parameter, as the databases name it.
enum class ParameterType : std::uint8_t {
    Int8,
    Int16,
    Int32,
    Uint8,
    Uint16,
    Uint32,
    N2,      // PROFIdrive normalised value (16 bits)
    V2,      // bit sequence (16 bits)
    String,  // visible string
    Time,    // time of day / time difference
    Date,
};
std::string_view parameter_type_name(ParameterType type) noexcept;  // "int32", "n2", ...
std::optional<ParameterType> parameter_type_from_name(std::string_view name) noexcept;
// The names in the order of the enum, for messages: "int8, int16, ..., date".
std::string_view parameter_type_name_list() noexcept;

// How a family writes its PNUs: Group "16-13" (PNU 1613: group 16, number 13), Plain "518".
enum class PnuNumbering : std::uint8_t { Plain, Group };

// What a Danfoss conversion index does to a raw whole number: value = raw * factor, shown with
// `decimals` decimals. Plain powers of ten (-7 to 7: factor 10^index); 100 (factor 1, the index of
// temperatures in degrees Celsius); and the indices that name a unit which is no power of ten of
// the base unit (67 revolutions a minute, 70 minutes, 74 hours, 75, 77 days): the raw number counts
// that unit, which the row's unit names, so factor 1 (docs/parameters.md, "Scaling", where the
// sources that disagree are named; --conversion-index gives such an index another factor). Other
// indices give nullopt.
struct Conversion {
    double factor = 1.0;
    int decimals = 0;
};
std::optional<Conversion> conversion_of_index(int index) noexcept;

// --conversion-index INDEX=FACTOR: the factors given to conversion indices in place of dpscope's
// (a factor as written, "0.1", "3600": its decimals are the digits after its point).
struct ConversionOverride {
    std::int16_t index = 0;
    Conversion conversion;
};
// "74=0.1" -> index 74, factor 0.1, 1 decimal; the error says what is wrong (an index from -128 to
// 127, a factor above 0 and at most 1e9 written with at most 9 decimals).
Result<ConversionOverride> parse_conversion_override(std::string_view text);

// A value scaled into its unit: shown with `decimals` decimals ("50.0").
struct ScaledValue {
    double value = 0.0;
    int decimals = 0;
};
// "50.0", "-12.34", "1500".
std::string format_scaled(const ScaledValue& value);

// One row of a database: one parameter.
struct ParameterRow {
    std::uint16_t pnu = 0;
    std::string name;
    std::string unit;                        // "" when the file says '-'
    std::optional<std::int16_t> conversion;  // the conversion index; nullopt when '-'
    // What the index does (conversion_of_index, or a --conversion-index); nullopt: not scaled.
    std::optional<Conversion> scaling;
    ParameterType type = ParameterType::Uint16;
    std::uint32_t elements = 1;      // array elements (IND), at least 1
    std::string source;              // the source cell as written: "PG302 p. 212"
    std::uint32_t source_index = 0;  // its key's entry in the family's `sources`
    std::uint32_t line = 0;          // its line in the file it came from
};

// @source KEY = text: a document the rows cite.
struct ParameterSource {
    std::string key;
    std::string text;
    std::string file;  // the file that defined it (families merged from several files)
};

// A drive family's database: its rows sorted by PNU (one row a PNU).
struct ParameterFamily {
    std::string id;     // "fc": lower-case letters, digits, '-' and '_'
    std::string title;  // @title; the id when the file has none
    PnuNumbering numbering = PnuNumbering::Plain;
    std::vector<ParameterSource> sources;
    std::vector<ParameterRow> rows;  // sorted by PNU
    std::string file;                // the file that defined the family first

    // The row of `pnu`, or nullptr (a binary search).
    const ParameterRow* find(std::uint16_t pnu) const noexcept;
    // The PNU as the family writes it: "16-13" (group numbering) or "518".
    std::string format_pnu(std::uint16_t pnu) const;
};

// A parsed database file: its family, and what was accepted with a warning (a conversion index
// without a known meaning: its values are not scaled), each "FILE:LINE: what".
struct ParameterFile {
    ParameterFamily family;
    std::vector<std::string> warnings;
};

// Parses a database file's text; `file_name` names it in messages. An error is "FILE:LINE: what"
// (a row of fewer or more than 7 cells, a number that is none or out of its range, an unknown
// type or directive, a source key no @source defined, a PNU given twice (naming both lines), no
// @family before the first row).
Result<ParameterFile> parse_parameter_database(std::string_view text, std::string_view file_name);

// Whether `pattern` is a part of the row's name (without regard to case), of its number as the
// family writes it ("16-1") or of its plain number ("161"); every row matches "".
bool matches_pattern(const ParameterFamily& family, const ParameterRow& row,
                     std::string_view pattern);

// Whether `id` can name a family: 1 to 32 lower-case letters, digits, '-' or '_'.
bool is_family_id(std::string_view id) noexcept;

// A PNU typed by a person: "1613", or "16-13" (group G, number NN: G * 100 + NN); nullopt when
// `text` is neither or the PNU is above 65535.
std::optional<std::uint16_t> parse_pnu_text(std::string_view text) noexcept;

// The raw bits of a value (a PWE, 32 bits or fewer) as the whole number `type` reads them: the
// low 8 or 16 bits sign-extended for int8 and int16, the low bits for the unsigned types.
std::int64_t raw_value_of_type(ParameterType type, std::uint32_t bits) noexcept;

// `raw` scaled by the row's conversion (its `scaling`); nullopt when the row has none or a type
// that is not a number (v2, string, time, date).
std::optional<ScaledValue> scale_value(const ParameterRow& row, std::int64_t raw) noexcept;

// A parameter found by name: its family and row.
struct NamedParameter {
    const ParameterFamily* family = nullptr;
    const ParameterRow* row = nullptr;
};

// Every family dpscope knows: the shipped ones, then those of --params files.
class ParameterDatabase {
  public:
    // Adds a family; one already held takes the new family's rows (a PNU it has is replaced by
    // the new row, the others are added) and sources, and keeps its id, title and numbering.
    void add(ParameterFamily family);
    // Gives every row of conversion index `o.index` (those held and those added later) the
    // factor `o.conversion`.
    void override_conversion(const ConversionOverride& o);
    // What conversion index `index` does here: a --conversion-index given for it, else
    // conversion_of_index.
    std::optional<Conversion> conversion(int index) const noexcept;

    const ParameterFamily* family(std::string_view id) const noexcept;
    const std::deque<ParameterFamily>& families() const noexcept { return families_; }
    bool empty() const noexcept { return families_.empty(); }

    // The row of `pnu` in family `id`, or nullptr.
    const ParameterRow* lookup(std::string_view id, std::uint16_t pnu) const noexcept;

    // The parameters named `name` in the families `ids` (every family when empty), compared
    // without regard to case: those whose name is `name`, else those whose name contains it.
    // An error when there is none, or when they are more than one PNU (naming the candidates).
    // Several rows of one PNU (in different families) all come back.
    Result<std::vector<NamedParameter>> find_by_name(std::string_view name,
                                                     std::span<const std::string> ids = {}) const;

  private:
    std::deque<ParameterFamily> families_;
    std::vector<ConversionOverride> overrides_;  // a deque: a family's address never changes
};

}  // namespace dpscope
