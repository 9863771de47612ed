#include "drives/parameter_database.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <iterator>
#include <utility>

#include "core/text_encoding.hpp"

namespace dpscope {

namespace {

constexpr std::array<std::string_view, 11> kTypeNames = {
    "int8", "int16", "int32", "uint8", "uint16", "uint32", "n2", "v2", "string", "time", "date"};

// The cells of a row, in order; a row has exactly these.
constexpr std::string_view kRowCells = "pnu | name | unit | conversion | type | elements | source";
constexpr std::size_t kRowCellCount = 7;

// The largest power of ten a conversion index names (10^7 and 10^-7: a 32-bit value scaled by
// them stays exact in a double).
constexpr int kLargestPowerIndex = 7;

std::string_view trim(std::string_view text) noexcept {
    const auto blank = [](char c) { return c == ' ' || c == '\t'; };
    while (!text.empty() && blank(text.front()))
        text.remove_prefix(1);
    while (!text.empty() && blank(text.back()))
        text.remove_suffix(1);
    return text;
}

template <typename T>
bool parse_decimal(std::string_view text, T& value) noexcept {
    if (text.empty() || text.front() == '+') return false;
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    return ec == std::errc() && end == text.data() + text.size();
}

bool all_digits(std::string_view text) noexcept {
    return !text.empty() &&
           std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// Text a person reads in every output: valid UTF-8 without control characters.
bool is_clean_text(std::string_view text) noexcept {
    return is_valid_utf8(text) && std::none_of(text.begin(), text.end(), [](char c) {
               const auto u = static_cast<unsigned char>(c);
               return u < 0x20 || u == 0x7F;
           });
}

bool is_source_key(std::string_view key) noexcept {
    return !key.empty() && key.size() <= 32 && std::all_of(key.begin(), key.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
               c == '-' || c == '_' || c == '.';
    });
}

// Reads one file, line by line; every error names the file and the line.
class DatabaseParser {
  public:
    DatabaseParser(std::string_view text, std::string_view file) : text_(text), file_(file) {
        file_result_.family.file = std::string(file);
    }

    Result<ParameterFile> parse() {
        if (text_.substr(0, 3) == "\xEF\xBB\xBF") text_.remove_prefix(3);  // a UTF-8 BOM
        std::size_t at = 0;
        while (at <= text_.size()) {
            std::size_t end = text_.find('\n', at);
            if (end == std::string_view::npos) end = text_.size();
            std::string_view line = text_.substr(at, end - at);
            if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
            ++line_;
            if (Result<void> read = read_line(trim(line)); !read) return Error{read.error()};
            at = end + 1;
        }
        ParameterFamily& family = file_result_.family;
        if (family.id.empty())
            return Error{
                fmt::format("{}:1: no @family line: a database begins with '@family ID'", file_)};
        if (family.title.empty()) family.title = family.id;
        std::stable_sort(
            family.rows.begin(), family.rows.end(),
            [](const ParameterRow& a, const ParameterRow& b) { return a.pnu < b.pnu; });
        for (std::size_t i = 1; i < family.rows.size(); ++i) {
            const ParameterRow& first = family.rows[i - 1];
            const ParameterRow& second = family.rows[i];
            if (first.pnu == second.pnu)
                return Error{fmt::format("{}:{}: PNU {} is given twice, on line {} and on line {}",
                                         file_, second.line, family.format_pnu(second.pnu),
                                         first.line, second.line)};
        }
        return std::move(file_result_);
    }

  private:
    Error fail(std::string_view what) const {
        return Error{fmt::format("{}:{}: {}", file_, line_, what)};
    }

    Result<void> read_line(std::string_view line) {
        if (line.empty() || line.front() == '#') return {};
        if (!is_valid_utf8(line)) return fail("the line is no valid UTF-8 text");
        if (line.front() == '@') return read_directive(line);
        if (file_result_.family.id.empty())
            return fail("a row before '@family ID': a database begins with its @family line");
        return read_row(line);
    }

    Result<void> read_directive(std::string_view line) {
        const std::size_t space = line.find_first_of(" \t");
        const std::string_view name =
            line.substr(1, space == std::string_view::npos ? line.npos : space - 1);
        const std::string_view value =
            space == std::string_view::npos ? std::string_view() : trim(line.substr(space));
        ParameterFamily& family = file_result_.family;
        if (name != "family" && family.id.empty())
            return fail(
                fmt::format("@{} before '@family ID': a database begins with its @family "
                            "line",
                            quoted_excerpt(name, 40)));
        if (!is_clean_text(value))
            return fail(fmt::format("@{}: a control character in the value", name));
        if (name == "family") {
            if (!family.id.empty())
                return fail(fmt::format("a second @family ('{}'); a file holds one family, '{}'",
                                        quoted_excerpt(value, 40), family.id));
            if (!is_family_id(value))
                return fail(
                    fmt::format("@family '{}': an id is 1 to 32 lower-case letters, digits, "
                                "'-' or '_'",
                                quoted_excerpt(value, 40)));
            family.id = std::string(value);
            return {};
        }
        if (name == "title") {
            if (value.empty()) return fail("@title without a title");
            family.title = std::string(value);
            return {};
        }
        if (name == "numbering") {
            if (!family.rows.empty())
                return fail(
                    "@numbering after the first row: it says how the rows write their "
                    "PNUs");
            if (value == "group")
                family.numbering = PnuNumbering::Group;
            else if (value == "plain")
                family.numbering = PnuNumbering::Plain;
            else
                return fail(fmt::format("@numbering '{}': group (PNU 1613 written 16-13) or plain",
                                        quoted_excerpt(value, 40)));
            return {};
        }
        if (name == "source") {
            const std::size_t equals = value.find('=');
            if (equals == std::string_view::npos)
                return fail("@source without '=': write '@source KEY = document'");
            const std::string_view key = trim(value.substr(0, equals));
            const std::string_view text = trim(value.substr(equals + 1));
            if (!is_source_key(key))
                return fail(
                    fmt::format("@source '{}': a key is 1 to 32 letters, digits, '-', '_' "
                                "or '.'",
                                quoted_excerpt(key, 40)));
            if (text.empty()) return fail(fmt::format("@source {} names no document", key));
            for (const ParameterSource& source : family.sources)
                if (source.key == key) return fail(fmt::format("@source {} is defined twice", key));
            family.sources.push_back(
                ParameterSource{std::string(key), std::string(text), family.file});
            return {};
        }
        return fail(fmt::format("unknown directive @{} (@family, @title, @numbering, @source)",
                                quoted_excerpt(name, 40)));
    }

    Result<void> read_row(std::string_view line) {
        std::array<std::string_view, kRowCellCount> cells;
        std::size_t count = 0;
        std::size_t at = 0;
        while (true) {
            const std::size_t bar = line.find('|', at);
            const std::string_view cell =
                trim(line.substr(at, bar == std::string_view::npos ? line.npos : bar - at));
            if (count < kRowCellCount) cells[count] = cell;
            ++count;
            if (bar == std::string_view::npos) break;
            at = bar + 1;
        }
        if (count < kRowCellCount)
            return fail(fmt::format("a row of {} {}: a row has 7 ({}); is the line cut short?",
                                    count, count == 1 ? "cell" : "cells", kRowCells));
        if (count > kRowCellCount)
            return fail(fmt::format("a row of {} cells: a row has 7 ({}); a name holds no '|'",
                                    count, kRowCells));
        if (!is_clean_text(line)) return fail("a control character in the row");
        ParameterFamily& family = file_result_.family;
        ParameterRow row;
        row.line = line_;
        Result<std::uint16_t> pnu = read_pnu(cells[0]);
        if (!pnu) return Error{pnu.error()};
        row.pnu = *pnu;
        if (cells[1].empty() || cells[1] == "-") return fail("a row without a name");
        row.name = std::string(cells[1]);
        if (cells[2].empty()) return fail("an empty unit; write '-' for none");
        if (cells[2] != "-") row.unit = std::string(cells[2]);
        if (cells[3] != "-") {
            std::int16_t index = 0;
            if (!parse_decimal(cells[3], index) || index < -128 || index > 127)
                return fail(
                    fmt::format("conversion '{}': a conversion index is a whole number "
                                "from -128 to 127, or '-' for none",
                                quoted_excerpt(cells[3], 40)));
            row.conversion = index;
            row.scaling = conversion_of_index(index);
            if (!row.scaling)
                file_result_.warnings.push_back(fmt::format(
                    "{}:{}: conversion index {} has no meaning dpscope knows: the values of PNU {} "
                    "are not scaled",
                    file_, line_, index, family.format_pnu(row.pnu)));
        }
        std::optional<ParameterType> type = parameter_type_from_name(cells[4]);
        if (!type)
            return fail(fmt::format("type '{}' is none of {}", quoted_excerpt(cells[4], 40),
                                    parameter_type_name_list()));
        row.type = *type;
        if (!parse_decimal(cells[5], row.elements) || row.elements < 1 || row.elements > 65535)
            return fail(fmt::format("elements '{}': a whole number from 1 to 65535",
                                    quoted_excerpt(cells[5], 40)));
        const std::string_view key = cells[6].substr(0, cells[6].find_first_of(" \t"));
        if (key.empty()) return fail("a row without a source: cite a @source key");
        const auto source = std::find_if(family.sources.begin(), family.sources.end(),
                                         [&](const ParameterSource& s) { return s.key == key; });
        if (source == family.sources.end())
            return fail(fmt::format("source '{}' is no @source key defined above the row",
                                    quoted_excerpt(key, 40)));
        row.source = std::string(cells[6]);
        row.source_index = static_cast<std::uint32_t>(source - family.sources.begin());
        family.rows.push_back(std::move(row));
        return {};
    }

    Result<std::uint16_t> read_pnu(std::string_view cell) const {
        const bool grouped = cell.find('-') != std::string_view::npos;
        if (grouped && file_result_.family.numbering != PnuNumbering::Group)
            return fail(
                fmt::format("PNU '{}' is written as a group; this file's @numbering is "
                            "plain (write the number, or '@numbering group' above the "
                            "rows)",
                            quoted_excerpt(cell, 40)));
        if (std::optional<std::uint16_t> pnu = parse_pnu_text(cell)) return *pnu;
        return fail(fmt::format(
            "PNU '{}': a whole number from 0 to 65535{}", quoted_excerpt(cell, 40),
            file_result_.family.numbering == PnuNumbering::Group ? " or GROUP-NN (16-13)" : ""));
    }

    std::string_view text_;
    std::string_view file_;
    std::uint32_t line_ = 0;
    ParameterFile file_result_;
};

}  // namespace

std::string_view parameter_type_name(ParameterType type) noexcept {
    const auto index = static_cast<std::size_t>(type);
    return index < kTypeNames.size() ? kTypeNames[index] : "?";
}

std::optional<ParameterType> parameter_type_from_name(std::string_view name) noexcept {
    for (std::size_t i = 0; i < kTypeNames.size(); ++i)
        if (kTypeNames[i] == name) return static_cast<ParameterType>(i);
    return std::nullopt;
}

std::string_view parameter_type_name_list() noexcept {
    return "int8, int16, int32, uint8, uint16, uint32, n2, v2, string, time, date";
}

std::optional<Conversion> conversion_of_index(int index) noexcept {
    switch (index) {
        case 67:   // revolutions a minute
        case 70:   // minutes
        case 74:   // hours
        case 75:   // (3 600 000 in the FC 300 Design Guide: hours counted in milliseconds' base)
        case 77:   // days
        case 100:  // degrees Celsius
            return Conversion{1.0, 0};
        default: break;
    }
    if (index < -kLargestPowerIndex || index > kLargestPowerIndex) return std::nullopt;
    return Conversion{std::pow(10.0, index), index < 0 ? -index : 0};
}

std::string format_scaled(const ScaledValue& value) {
    return fmt::format("{:.{}f}", value.value, value.decimals);
}

const ParameterRow* ParameterFamily::find(std::uint16_t pnu) const noexcept {
    const auto it =
        std::lower_bound(rows.begin(), rows.end(), pnu,
                         [](const ParameterRow& row, std::uint16_t p) { return row.pnu < p; });
    return it != rows.end() && it->pnu == pnu ? &*it : nullptr;
}

std::string ParameterFamily::format_pnu(std::uint16_t pnu) const {
    if (numbering == PnuNumbering::Group) return fmt::format("{}-{:02}", pnu / 100, pnu % 100);
    return fmt::format("{}", pnu);
}

Result<ParameterFile> parse_parameter_database(std::string_view text, std::string_view file_name) {
    return DatabaseParser(text, file_name).parse();
}

bool is_family_id(std::string_view id) noexcept {
    return !id.empty() && id.size() <= 32 && std::all_of(id.begin(), id.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_';
    });
}

bool matches_pattern(const ParameterFamily& family, const ParameterRow& row,
                     std::string_view pattern) {
    return pattern.empty() || contains_ignoring_case(row.name, pattern) ||
           family.format_pnu(row.pnu).find(pattern) != std::string::npos ||
           std::to_string(row.pnu).find(pattern) != std::string::npos;
}

std::optional<std::uint16_t> parse_pnu_text(std::string_view text) noexcept {
    const std::size_t dash = text.find('-');
    if (dash == std::string_view::npos) {
        std::uint16_t pnu = 0;
        if (!all_digits(text) || !parse_decimal(text, pnu)) return std::nullopt;
        return pnu;
    }
    const std::string_view group_text = text.substr(0, dash);
    const std::string_view number_text = text.substr(dash + 1);
    unsigned group = 0, number = 0;
    if (!all_digits(group_text) || group_text.size() > 3 || number_text.size() != 2 ||
        !all_digits(number_text) || !parse_decimal(group_text, group) ||
        !parse_decimal(number_text, number))
        return std::nullopt;
    const unsigned pnu = group * 100 + number;
    if (pnu > 65535) return std::nullopt;
    return static_cast<std::uint16_t>(pnu);
}

std::int64_t raw_value_of_type(ParameterType type, std::uint32_t bits) noexcept {
    switch (type) {
        case ParameterType::Int8: return static_cast<std::int8_t>(bits & 0xFF);
        case ParameterType::Int16:
        case ParameterType::N2: return static_cast<std::int16_t>(bits & 0xFFFF);
        case ParameterType::Int32: return static_cast<std::int32_t>(bits);
        case ParameterType::Uint8: return bits & 0xFF;
        case ParameterType::Uint16:
        case ParameterType::V2: return bits & 0xFFFF;
        default: return bits;
    }
}

std::optional<ScaledValue> scale_value(const ParameterRow& row, std::int64_t raw) noexcept {
    switch (row.type) {
        case ParameterType::V2:
        case ParameterType::String:
        case ParameterType::Time:
        case ParameterType::Date: return std::nullopt;
        default: break;
    }
    if (!row.scaling) return std::nullopt;
    const Conversion& conversion = *row.scaling;
    // A factor of a power of ten below 1 divides by its inverse, which is exact where multiplying
    // by the inexact factor is not (0.1: 3 * 0.1 is 0.30000000000000004).
    const double inverse = 1.0 / conversion.factor;
    const double value = conversion.factor < 1.0 && inverse == std::round(inverse)
                             ? static_cast<double>(raw) / inverse
                             : static_cast<double>(raw) * conversion.factor;
    return ScaledValue{value, conversion.decimals};
}

Result<ConversionOverride> parse_conversion_override(std::string_view text) {
    const auto fail = [&](std::string_view why) {
        return Error{fmt::format("'{}': {}", quoted_excerpt(text, 40), why)};
    };
    const std::size_t equals = text.find('=');
    if (equals == std::string_view::npos)
        return fail("write INDEX=FACTOR, e.g. 74=0.1 (a conversion index and its factor)");
    const std::string_view index_text = text.substr(0, equals);
    const std::string_view factor_text = text.substr(equals + 1);
    std::int16_t index = 0;
    if (!parse_decimal(index_text, index) || index < -128 || index > 127)
        return fail("the conversion index is a whole number from -128 to 127");
    // The factor: digits with at most one point, at most 9 after it.
    const std::size_t point = factor_text.find('.');
    const std::string_view whole = factor_text.substr(0, point);
    const std::string_view fraction =
        point == std::string_view::npos ? std::string_view{} : factor_text.substr(point + 1);
    const auto digits = [](std::string_view part) {
        return std::all_of(part.begin(), part.end(), [](char c) { return c >= '0' && c <= '9'; });
    };
    if (factor_text.empty() || (whole.empty() && fraction.empty()) || !digits(whole) ||
        !digits(fraction) || (point != std::string_view::npos && fraction.empty()) ||
        whole.size() > 10 || fraction.size() > 9)
        return fail("the factor is a decimal number such as 0.1 or 3600 (at most 9 decimals)");
    const double factor = std::strtod(std::string(factor_text).c_str(), nullptr);
    if (!(factor > 0.0) || factor > 1e9)
        return fail("the factor is above 0 and at most 1000000000");
    return ConversionOverride{index, Conversion{factor, static_cast<int>(fraction.size())}};
}

void ParameterDatabase::override_conversion(const ConversionOverride& o) {
    std::erase_if(overrides_, [&](const ConversionOverride& held) { return held.index == o.index; });
    overrides_.push_back(o);
    for (ParameterFamily& family : families_)
        for (ParameterRow& row : family.rows)
            if (row.conversion == o.index) row.scaling = o.conversion;
}

std::optional<Conversion> ParameterDatabase::conversion(int index) const noexcept {
    for (const ConversionOverride& o : overrides_)
        if (o.index == index) return o.conversion;
    return conversion_of_index(index);
}

void ParameterDatabase::add(ParameterFamily family) {
    for (ParameterRow& row : family.rows)
        for (const ConversionOverride& o : overrides_)
            if (row.conversion == o.index) row.scaling = o.conversion;
    for (ParameterFamily& held : families_) {
        if (held.id != family.id) continue;
        const auto offset = static_cast<std::uint32_t>(held.sources.size());
        held.sources.insert(held.sources.end(), std::make_move_iterator(family.sources.begin()),
                            std::make_move_iterator(family.sources.end()));
        for (ParameterRow& row : family.rows) {
            row.source_index += offset;
            const auto at =
                std::lower_bound(held.rows.begin(), held.rows.end(), row.pnu,
                                 [](const ParameterRow& r, std::uint16_t p) { return r.pnu < p; });
            if (at != held.rows.end() && at->pnu == row.pnu)
                *at = std::move(row);
            else
                held.rows.insert(at, std::move(row));
        }
        return;
    }
    families_.push_back(std::move(family));
}

const ParameterFamily* ParameterDatabase::family(std::string_view id) const noexcept {
    for (const ParameterFamily& family : families_)
        if (family.id == id) return &family;
    return nullptr;
}

const ParameterRow* ParameterDatabase::lookup(std::string_view id,
                                              std::uint16_t pnu) const noexcept {
    const ParameterFamily* held = family(id);
    return held ? held->find(pnu) : nullptr;
}

Result<std::vector<NamedParameter>> ParameterDatabase::find_by_name(
    std::string_view name, std::span<const std::string> ids) const {
    const std::string_view wanted = trim(name);
    if (wanted.empty()) return Error{"an empty parameter name"};
    std::vector<NamedParameter> exact, partial;
    for (const ParameterFamily& family : families_) {
        if (!ids.empty() && std::find(ids.begin(), ids.end(), family.id) == ids.end()) continue;
        for (const ParameterRow& row : family.rows) {
            if (equal_ignoring_case(row.name, wanted))
                exact.push_back({&family, &row});
            else if (contains_ignoring_case(row.name, wanted))
                partial.push_back({&family, &row});
        }
    }
    std::vector<NamedParameter>& found = exact.empty() ? partial : exact;
    const std::string where =
        ids.empty() ? std::string("any drive family")
                    : fmt::format("the drive famil{} {}", ids.size() == 1 ? "y" : "ies",
                                  fmt::join(ids, ", "));
    if (found.empty())
        return Error{
            fmt::format("no parameter of {} is named '{}'", where, quoted_excerpt(wanted))};
    const std::uint16_t pnu = found.front().row->pnu;
    if (std::all_of(found.begin(), found.end(),
                    [&](const NamedParameter& p) { return p.row->pnu == pnu; }))
        return std::move(found);
    constexpr std::size_t kListed = 8;
    std::string candidates;
    for (std::size_t i = 0; i < found.size() && i < kListed; ++i)
        fmt::format_to(std::back_inserter(candidates), "{}{} {} {}", i == 0 ? "" : "; ",
                       found[i].family->id, found[i].family->format_pnu(found[i].row->pnu),
                       found[i].row->name);
    if (found.size() > kListed)
        fmt::format_to(std::back_inserter(candidates), "; and {} more", found.size() - kListed);
    return Error{fmt::format(
        "'{}' {} several parameters of {} ({}); give its number or more of "
        "its name",
        quoted_excerpt(wanted), exact.empty() ? "is in the names of" : "names", where, candidates)};
}

}  // namespace dpscope
