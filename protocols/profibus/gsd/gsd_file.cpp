#include "protocols/profibus/gsd/gsd_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>

#include "core/text_encoding.hpp"

namespace dpscope {

namespace {

// Windows-1252's characters at 0x80..0x9F (0: none there, shown as U+FFFD); 0xA0..0xFF are
// ISO 8859-1's, the code points of the same number.
constexpr std::array<std::uint16_t, 32> kCp1252High{
    0x20AC, 0,      0x201A, 0x0192, 0x201E, 0x2026, 0x2020, 0x2021, 0x02C6, 0x2030, 0x0160,
    0x2039, 0x0152, 0,      0x017D, 0,      0,      0x2018, 0x2019, 0x201C, 0x201D, 0x2022,
    0x2013, 0x2014, 0x02DC, 0x2122, 0x0161, 0x203A, 0x0153, 0,      0x017E, 0x0178};

void append_utf8(std::string& out, std::uint32_t cp) {
    if (cp < 0x80) {
        out.push_back(static_cast<char>(cp));
    } else if (cp < 0x800) {
        out.push_back(static_cast<char>(0xC0 | (cp >> 6)));
        out.push_back(static_cast<char>(0x80 | (cp & 0x3F)));
    } else {
        out.push_back(static_cast<char>(0xE0 | (cp >> 12)));
        out.push_back(static_cast<char>(0x80 | ((cp >> 6) & 0x3F)));
        out.push_back(static_cast<char>(0x80 | (cp & 0x3F)));
    }
}

// The file's text as UTF-8: as it is when it is valid UTF-8, otherwise read as Windows-1252.
std::string as_utf8(std::string_view bytes) {
    if (is_valid_utf8(bytes)) return std::string(bytes);
    std::string out;
    out.reserve(bytes.size() + bytes.size() / 8);
    for (char c : bytes) {
        const auto b = static_cast<std::uint8_t>(c);
        if (b < 0x80)
            out.push_back(c);
        else if (b < 0xA0)
            append_utf8(out, kCp1252High[b - 0x80] ? kCp1252High[b - 0x80] : 0xFFFD);
        else
            append_utf8(out, b);
    }
    return out;
}

// A line as the grammar sees it: comments gone, continuation lines joined, and the number of
// the physical line it starts on.
struct LogicalLine {
    std::string text;
    std::uint32_t line = 0;
};

std::string_view trim(std::string_view s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front())))
        s.remove_prefix(1);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back())))
        s.remove_suffix(1);
    return s;
}

// Splits the text into logical lines. An unterminated string is an error at its line.
Result<std::vector<LogicalLine>> logical_lines(std::string_view text, std::string_view file) {
    std::vector<LogicalLine> lines;
    std::uint32_t number = 0;
    bool continuing = false;
    std::size_t at = 0;
    while (at <= text.size()) {
        std::size_t end = text.find('\n', at);
        if (end == std::string_view::npos) end = text.size();
        std::string_view physical = text.substr(at, end - at);
        at = end + 1;
        ++number;
        if (!physical.empty() && physical.back() == '\r') physical.remove_suffix(1);
        // Cut the comment: ';' outside a string.
        bool in_string = false;
        std::size_t cut = physical.size();
        for (std::size_t i = 0; i < physical.size(); ++i) {
            if (physical[i] == '"') in_string = !in_string;
            if (physical[i] == ';' && !in_string) {
                cut = i;
                break;
            }
        }
        if (in_string)
            return Error{fmt::format("{}:{}: a string is not closed (no '\"' before the line ends)",
                                     file, number)};
        std::string_view content = trim(physical.substr(0, cut));
        const bool continues = !content.empty() && content.back() == '\\';
        if (continues) content = trim(content.substr(0, content.size() - 1));
        if (continuing) {
            lines.back().text += ' ';
            lines.back().text += content;
        } else if (!content.empty() || continues) {
            lines.push_back(LogicalLine{std::string(content), number});
        }
        continuing = continues;
        if (end == text.size()) break;
    }
    return lines;
}

// A line split into its keyword, the argument in parentheses after it (if any) and what follows
// '=' (or, without '=', the rest of the line).
struct Statement {
    std::string_view keyword;
    std::optional<std::string_view> argument;
    bool assigned = false;
    std::string_view value;
};

Statement split(std::string_view line) {
    Statement s;
    std::size_t i = 0;
    while (i < line.size() && (std::isalnum(static_cast<unsigned char>(line[i])) ||
                               line[i] == '_' || line[i] == '.' || line[i] == '#'))
        ++i;
    s.keyword = line.substr(0, i);
    std::string_view rest = trim(line.substr(i));
    if (!rest.empty() && rest.front() == '(') {
        const std::size_t close = rest.find(')');
        if (close != std::string_view::npos) {
            s.argument = trim(rest.substr(1, close - 1));
            rest = trim(rest.substr(close + 1));
        }
    }
    if (!rest.empty() && rest.front() == '=') {
        s.assigned = true;
        rest = trim(rest.substr(1));
    }
    s.value = rest;
    return s;
}

// A whole number, decimal or 0x hex, with an optional sign.
std::optional<std::int64_t> number_of(std::string_view text) {
    text = trim(text);
    bool negative = false;
    if (!text.empty() && (text.front() == '-' || text.front() == '+')) {
        negative = text.front() == '-';
        text.remove_prefix(1);
    }
    int base = 10;
    if (text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X')) {
        base = 16;
        text.remove_prefix(2);
    }
    std::int64_t value = 0;
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value, base);
    if (text.empty() || ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
    return negative ? -value : value;
}

// What a parse keeps while it goes through the lines.
class GsdParser {
  public:
    GsdParser(std::string_view file, GsdDevice& device) : file_(file), device_(device) {}

    Result<void> line(const LogicalLine& l) {
        line_ = l.line;
        const Statement s = split(l.text);
        switch (block_) {
            case Block::None: return top(s, l.text);
            case Block::PrmText: return in_prm_text(s);
            case Block::UserPrm: return in_user_prm(s, l.text);
            case Block::Module: return in_module(s, l.text);
            case Block::DiagArea: return in_diag_area(s);
        }
        return {};
    }

    Result<void> end() const {
        if (block_ == Block::None) return {};
        return Error{fmt::format("{}:{}: {} has no {} before the file ends", file_, block_line_,
                                 block_what_, block_end_)};
    }

  private:
    enum class Block : std::uint8_t { None, PrmText, UserPrm, Module, DiagArea };

    Error error(std::string_view what) const {
        return Error{fmt::format("{}:{}: {}", file_, line_, what)};
    }

    Result<std::int64_t> number(std::string_view text, std::string_view keyword) const {
        if (const std::optional<std::int64_t> n = number_of(text)) return *n;
        return error(fmt::format("{}: '{}' is not a number", keyword, quoted_excerpt(text, 40)));
    }
    Result<std::uint32_t> count(std::string_view text, std::string_view keyword) const {
        Result<std::int64_t> n = number(text, keyword);
        if (!n) return Error{n.error()};
        if (*n < 0 || *n > 0xFFFF'FFFF)
            return error(fmt::format("{}: {} is out of range", keyword, *n));
        return static_cast<std::uint32_t>(*n);
    }
    // A quoted string at the start of `text`; `rest` gets what follows it.
    Result<std::string> string(std::string_view text, std::string_view keyword,
                               std::string_view* rest = nullptr) const {
        text = trim(text);
        if (text.empty() || text.front() != '"')
            return error(fmt::format("{}: a text in quotes is expected", keyword));
        const std::size_t close = text.find('"', 1);
        if (close == std::string_view::npos)
            return error(fmt::format("{}: the text is not closed", keyword));
        if (rest) *rest = trim(text.substr(close + 1));
        return std::string(text.substr(1, close - 1));
    }
    // Bytes separated by commas or spaces.
    Result<std::vector<std::uint8_t>> bytes(std::string_view text, std::string_view keyword) const {
        std::vector<std::uint8_t> out;
        std::size_t at = 0;
        while (at < text.size()) {
            std::size_t end = text.find_first_of(", \t", at);
            if (end == std::string_view::npos) end = text.size();
            const std::string_view item = text.substr(at, end - at);
            at = end + 1;
            if (trim(item).empty()) continue;
            Result<std::int64_t> n = number(item, keyword);
            if (!n) return Error{n.error()};
            if (*n < 0 || *n > 0xFF) return error(fmt::format("{}: {} is not a byte", keyword, *n));
            out.push_back(static_cast<std::uint8_t>(*n));
        }
        return out;
    }
    // "first-last" (BitArea, Unit_Diag_Area, a value range).
    Result<std::pair<std::int64_t, std::int64_t>> range(std::string_view text,
                                                        std::string_view keyword) const {
        // The '-' that separates them: not a sign at the start.
        const std::size_t dash = text.find('-', 1);
        if (dash == std::string_view::npos)
            return error(fmt::format("{}: a range first-last is expected", keyword));
        Result<std::int64_t> first = number(text.substr(0, dash), keyword);
        if (!first) return Error{first.error()};
        Result<std::int64_t> last = number(text.substr(dash + 1), keyword);
        if (!last) return Error{last.error()};
        return std::pair{*first, *last};
    }

    void open(Block block, std::string what, std::string_view end) {
        block_ = block;
        block_line_ = line_;
        block_what_ = std::move(what);
        block_end_ = end;
    }

    Result<void> top(const Statement& s, std::string_view text) {
        const std::string_view k = s.keyword;
        auto set_count = [&](std::optional<std::uint32_t>& field) -> Result<void> {
            Result<std::uint32_t> n = count(s.value, k);
            if (!n) return Error{n.error()};
            field = *n;
            return {};
        };
        auto set_string = [&](std::string& field) -> Result<void> {
            Result<std::string> t = string(s.value, k);
            if (!t) return Error{t.error()};
            field = std::move(*t);
            return {};
        };
        auto set_flag = [&](bool& field) -> Result<void> {
            Result<std::uint32_t> n = count(s.value, k);
            if (!n) return Error{n.error()};
            field = *n != 0;
            return {};
        };
        if (equal_ignoring_case(k, "#Profibus_DP")) return {};
        if (equal_ignoring_case(k, "GSD_Revision")) return set_count(device_.gsd_revision);
        if (equal_ignoring_case(k, "Vendor_Name")) return set_string(device_.vendor);
        if (equal_ignoring_case(k, "Model_Name")) return set_string(device_.model);
        if (equal_ignoring_case(k, "Revision")) return set_string(device_.revision);
        if (equal_ignoring_case(k, "Ident_Number")) {
            Result<std::uint32_t> n = count(s.value, k);
            if (!n) return Error{n.error()};
            if (*n > 0xFFFF) return error(fmt::format("Ident_Number: {} is not 16 bits", *n));
            device_.ident_number = static_cast<std::uint16_t>(*n);
            return {};
        }
        if (equal_ignoring_case(k, "Slave_Family")) {
            device_.slave_family = std::string(s.value);
            return {};
        }
        if (equal_ignoring_case(k, "DPV1_Slave")) return set_flag(device_.dpv1_slave);
        if (equal_ignoring_case(k, "Modular_Station")) return set_flag(device_.modular_station);
        if (equal_ignoring_case(k, "Max_Module")) return set_count(device_.max_module);
        if (equal_ignoring_case(k, "Max_Input_Len")) return set_count(device_.max_input_len);
        if (equal_ignoring_case(k, "Max_Output_Len")) return set_count(device_.max_output_len);
        if (equal_ignoring_case(k, "Max_Data_Len")) return set_count(device_.max_data_len);
        if (equal_ignoring_case(k, "User_Prm_Data_Len"))
            return set_count(device_.user_prm_data_len);
        if (equal_ignoring_case(k, "Max_User_Prm_Data_Len"))
            return set_count(device_.max_user_prm_data_len);
        if (equal_ignoring_case(k, "Max_Diag_Data_Len"))
            return set_count(device_.max_diag_data_len);
        if (equal_ignoring_case(k, "Min_Slave_Intervall"))
            return set_count(device_.min_slave_interval);
        if (equal_ignoring_case(k, "Unit_Diag_Type")) return set_count(device_.unit_diag_type);
        if (equal_ignoring_case(k, "User_Prm_Data")) {
            Result<std::vector<std::uint8_t>> b = bytes(s.value, k);
            if (!b) return Error{b.error()};
            device_.user_prm_data = std::move(*b);
            return {};
        }
        if (k.size() > 8 && equal_ignoring_case(k.substr(0, 8), "MaxTsdr_")) {
            Result<std::uint32_t> n = count(s.value, k);
            if (!n) return Error{n.error()};
            device_.max_tsdr.push_back(GsdMaxTsdr{std::string(k.substr(8)), *n});
            return {};
        }
        if (equal_ignoring_case(k, "Ext_User_Prm_Data_Ref") ||
            equal_ignoring_case(k, "Ext_User_Prm_Data_Const"))
            return prm_assignment(s, device_.prm_refs, device_.prm_consts);
        if (equal_ignoring_case(k, "Unit_Diag_Bit")) {
            if (!s.argument)
                return error("Unit_Diag_Bit: the bit number in parentheses is missing");
            Result<std::uint32_t> bit = count(*s.argument, k);
            if (!bit) return Error{bit.error()};
            Result<std::string> t = string(s.value, k);
            if (!t) return Error{t.error()};
            device_.unit_diag_bits.push_back(GsdValueText{*bit, std::move(*t)});
            return {};
        }
        if (equal_ignoring_case(k, "Unit_Diag_Area")) {
            Result<std::pair<std::int64_t, std::int64_t>> r = range(s.value, k);
            if (!r) return Error{r.error()};
            if (r->first < 0 || r->second < r->first)
                return error(
                    fmt::format("Unit_Diag_Area: {}-{} is no range of bits", r->first, r->second));
            device_.unit_diag_areas.push_back(GsdDiagArea{
                static_cast<std::uint32_t>(r->first), static_cast<std::uint32_t>(r->second), {}});
            open(Block::DiagArea, "Unit_Diag_Area", "Unit_Diag_Area_End");
            return {};
        }
        if (equal_ignoring_case(k, "PrmText")) {
            Result<std::uint32_t> n = count(s.value, k);
            if (!n) return Error{n.error()};
            device_.prm_texts.push_back(GsdPrmText{*n, {}, line_});
            open(Block::PrmText, fmt::format("PrmText {}", *n), "EndPrmText");
            return {};
        }
        if (equal_ignoring_case(k, "ExtUserPrmData")) {
            // ExtUserPrmData = n "name"
            const std::string_view v = s.value;
            const std::size_t quote = v.find('"');
            Result<std::uint32_t> n =
                count(quote == std::string_view::npos ? v : v.substr(0, quote), k);
            if (!n) return Error{n.error()};
            Result<std::string> name =
                string(quote == std::string_view::npos ? std::string_view() : v.substr(quote), k);
            if (!name) return Error{name.error()};
            GsdUserPrm prm;
            prm.reference = *n;
            prm.name = std::move(*name);
            prm.line = line_;
            device_.user_prms.push_back(std::move(prm));
            open(Block::UserPrm, fmt::format("ExtUserPrmData {}", *n), "EndExtUserPrmData");
            user_prm_typed_ = false;
            return {};
        }
        if (equal_ignoring_case(k, "Module")) {
            // Module = "name" bytes
            std::string_view rest;
            Result<std::string> name = string(s.value, k, &rest);
            if (!name) return Error{name.error()};
            Result<std::vector<std::uint8_t>> config = bytes(rest, k);
            if (!config) return Error{config.error()};
            GsdModule module;
            module.name = std::move(*name);
            module.config = std::move(*config);
            module.line = line_;
            device_.modules.push_back(std::move(module));
            open(Block::Module, fmt::format("Module \"{}\"", device_.modules.back().name),
                 "EndModule");
            module_lines_ = 0;
            return {};
        }
        (void)text;
        ++device_.keywords_skipped;
        return {};
    }

    Result<void> prm_assignment(const Statement& s, std::vector<GsdPrmRef>& refs,
                                std::vector<GsdPrmConst>& consts) {
        const std::string_view k = s.keyword;
        if (!s.argument)
            return error(fmt::format("{}: the byte offset in parentheses is missing", k));
        Result<std::uint32_t> offset = count(*s.argument, k);
        if (!offset) return Error{offset.error()};
        if (equal_ignoring_case(k, "Ext_User_Prm_Data_Ref")) {
            Result<std::uint32_t> reference = count(s.value, k);
            if (!reference) return Error{reference.error()};
            refs.push_back(GsdPrmRef{*offset, *reference});
            return {};
        }
        Result<std::vector<std::uint8_t>> b = bytes(s.value, k);
        if (!b) return Error{b.error()};
        consts.push_back(GsdPrmConst{*offset, std::move(*b)});
        return {};
    }

    Result<void> in_prm_text(const Statement& s) {
        if (equal_ignoring_case(s.keyword, "EndPrmText")) {
            block_ = Block::None;
            return {};
        }
        if (equal_ignoring_case(s.keyword, "Text")) {
            if (!s.argument) return error("Text: the value in parentheses is missing");
            Result<std::int64_t> value = number(*s.argument, "Text");
            if (!value) return Error{value.error()};
            Result<std::string> t = string(s.value, "Text");
            if (!t) return Error{t.error()};
            device_.prm_texts.back().texts.push_back(GsdValueText{*value, std::move(*t)});
            return {};
        }
        ++device_.keywords_skipped;
        return {};
    }

    Result<void> in_user_prm(const Statement& s, std::string_view text) {
        GsdUserPrm& prm = device_.user_prms.back();
        const std::string_view k = s.keyword;
        if (equal_ignoring_case(k, "EndExtUserPrmData")) {
            if (!user_prm_typed_)
                return error(
                    fmt::format("ExtUserPrmData {}: no data type line before "
                                "EndExtUserPrmData",
                                prm.reference));
            block_ = Block::None;
            return {};
        }
        if (equal_ignoring_case(k, "Prm_Text_Ref")) {
            Result<std::uint32_t> n = count(s.value, k);
            if (!n) return Error{n.error()};
            prm.text_reference = *n;
            return {};
        }
        struct TypeName {
            std::string_view name;
            GsdDataType type;
        };
        constexpr TypeName kTypes[] = {
            {"Bit", GsdDataType::Bit},
            {"BitArea", GsdDataType::BitArea},
            {"Unsigned8", GsdDataType::Unsigned8},
            {"Unsigned16", GsdDataType::Unsigned16},
            {"Unsigned32", GsdDataType::Unsigned32},
            {"Signed8", GsdDataType::Signed8},
            {"Signed16", GsdDataType::Signed16},
            {"Signed32", GsdDataType::Signed32},
        };
        for (const TypeName& t : kTypes) {
            if (!equal_ignoring_case(k, t.name)) continue;
            prm.type = t.type;
            if (t.type == GsdDataType::Bit || t.type == GsdDataType::BitArea) {
                if (!s.argument)
                    return error(fmt::format("{}: the bit in parentheses is missing", k));
                if (t.type == GsdDataType::Bit) {
                    Result<std::uint32_t> bit = count(*s.argument, k);
                    if (!bit) return Error{bit.error()};
                    if (*bit > 7)
                        return error(fmt::format("Bit({}): a byte has bits 0 to 7", *bit));
                    prm.first_bit = prm.last_bit = static_cast<std::uint8_t>(*bit);
                } else {
                    Result<std::pair<std::int64_t, std::int64_t>> r = range(*s.argument, k);
                    if (!r) return Error{r.error()};
                    if (r->first < 0 || r->second > 7 || r->second < r->first)
                        return error(fmt::format("BitArea({}-{}): a byte has bits 0 to 7", r->first,
                                                 r->second));
                    prm.first_bit = static_cast<std::uint8_t>(r->first);
                    prm.last_bit = static_cast<std::uint8_t>(r->second);
                }
            }
            // <default> <min>-<max> or <default> <v1>,<v2>,...
            std::string_view rest = trim(s.value);
            const std::size_t space = rest.find_first_of(" \t");
            if (space == std::string_view::npos)
                return error(
                    fmt::format("{}: a default value and the allowed values are expected", k));
            Result<std::int64_t> def = number(rest.substr(0, space), k);
            if (!def) return Error{def.error()};
            prm.default_value = *def;
            const std::string_view values = trim(rest.substr(space));
            if (values.find(',') != std::string_view::npos) {
                std::size_t at = 0;
                while (at <= values.size()) {
                    std::size_t end = values.find(',', at);
                    if (end == std::string_view::npos) end = values.size();
                    Result<std::int64_t> v = number(values.substr(at, end - at), k);
                    if (!v) return Error{v.error()};
                    prm.allowed.push_back(*v);
                    at = end + 1;
                }
                prm.min_value = *std::min_element(prm.allowed.begin(), prm.allowed.end());
                prm.max_value = *std::max_element(prm.allowed.begin(), prm.allowed.end());
            } else if (values.find('-', 1) != std::string_view::npos) {
                Result<std::pair<std::int64_t, std::int64_t>> r = range(values, k);
                if (!r) return Error{r.error()};
                if (r->second < r->first)
                    return error(fmt::format("{}: {}-{} is no range (the first is larger)", k,
                                             r->first, r->second));
                prm.min_value = r->first;
                prm.max_value = r->second;
            } else {
                Result<std::int64_t> v = number(values, k);
                if (!v) return Error{v.error()};
                prm.allowed.push_back(*v);
                prm.min_value = prm.max_value = *v;
            }
            user_prm_typed_ = true;
            return {};
        }
        (void)text;
        ++device_.keywords_skipped;  // Changeable, Visible, ...
        return {};
    }

    Result<void> in_module(const Statement& s, std::string_view text) {
        GsdModule& module = device_.modules.back();
        ++module_lines_;
        if (equal_ignoring_case(s.keyword, "EndModule")) {
            block_ = Block::None;
            return {};
        }
        // The module's reference number: a number alone on the line after Module.
        if (module_lines_ == 1 && !s.assigned && !s.argument) {
            if (const std::optional<std::int64_t> n = number_of(text); n && *n >= 0) {
                module.number = static_cast<std::uint32_t>(*n);
                return {};
            }
        }
        if (equal_ignoring_case(s.keyword, "Ext_User_Prm_Data_Ref") ||
            equal_ignoring_case(s.keyword, "Ext_User_Prm_Data_Const"))
            return prm_assignment(s, module.prm_refs, module.prm_consts);
        ++device_.keywords_skipped;
        return {};
    }

    Result<void> in_diag_area(const Statement& s) {
        if (equal_ignoring_case(s.keyword, "Unit_Diag_Area_End")) {
            block_ = Block::None;
            return {};
        }
        if (equal_ignoring_case(s.keyword, "Value")) {
            if (!s.argument) return error("Value: the value in parentheses is missing");
            Result<std::int64_t> value = number(*s.argument, "Value");
            if (!value) return Error{value.error()};
            Result<std::string> t = string(s.value, "Value");
            if (!t) return Error{t.error()};
            device_.unit_diag_areas.back().values.push_back(GsdValueText{*value, std::move(*t)});
            return {};
        }
        ++device_.keywords_skipped;
        return {};
    }

    std::string_view file_;
    GsdDevice& device_;
    std::uint32_t line_ = 0;
    Block block_ = Block::None;
    std::uint32_t block_line_ = 0;
    std::string block_what_;
    std::string_view block_end_;
    bool user_prm_typed_ = false;
    std::uint32_t module_lines_ = 0;
};

}  // namespace

std::string_view gsd_data_type_name(GsdDataType type) noexcept {
    switch (type) {
        case GsdDataType::Bit: return "Bit";
        case GsdDataType::BitArea: return "BitArea";
        case GsdDataType::Unsigned8: return "Unsigned8";
        case GsdDataType::Unsigned16: return "Unsigned16";
        case GsdDataType::Unsigned32: return "Unsigned32";
        case GsdDataType::Signed8: return "Signed8";
        case GsdDataType::Signed16: return "Signed16";
        case GsdDataType::Signed32: return "Signed32";
    }
    return "?";
}

std::optional<std::uint32_t> GsdDevice::max_tsdr_at(std::string_view rate) const {
    for (const GsdMaxTsdr& t : max_tsdr)
        if (equal_ignoring_case(t.rate, rate)) return t.bit_times;
    return std::nullopt;
}

const GsdPrmText* GsdDevice::prm_text(std::uint32_t reference) const noexcept {
    for (const GsdPrmText& t : prm_texts)
        if (t.reference == reference) return &t;
    return nullptr;
}

const GsdUserPrm* GsdDevice::user_prm(std::uint32_t reference) const noexcept {
    for (const GsdUserPrm& p : user_prms)
        if (p.reference == reference) return &p;
    return nullptr;
}

Result<GsdDevice> parse_gsd(std::string_view bytes, std::string_view file) {
    const std::string text = as_utf8(bytes);
    // A file without the header anywhere is no GSD (random bytes, another format): said as such
    // rather than as the first thing in it that does not parse.
    constexpr std::string_view kHeader = "#profibus_dp";
    const auto found =
        std::search(text.begin(), text.end(), kHeader.begin(), kHeader.end(),
                    [](char a, char b) { return (a >= 'A' && a <= 'Z' ? a + 32 : a) == b; });
    if (found == text.end())
        return Error{
            fmt::format("{}:1: no \"#Profibus_DP\" line: not a PROFIBUS DP GSD file", file)};
    Result<std::vector<LogicalLine>> lines = logical_lines(text, file);
    if (!lines) return Error{lines.error()};
    // Any text may come before the "#Profibus_DP" line; the description starts after it.
    auto header = std::find_if(lines->begin(), lines->end(), [](const LogicalLine& l) {
        return equal_ignoring_case(trim(l.text), "#Profibus_DP");
    });
    if (header == lines->end())
        return Error{
            fmt::format("{}:1: no \"#Profibus_DP\" line: not a PROFIBUS DP GSD file", file)};
    GsdDevice device;
    device.file = std::string(file);
    GsdParser parser(file, device);
    for (auto it = header + 1; it != lines->end(); ++it)
        if (Result<void> ok = parser.line(*it); !ok) return Error{ok.error()};
    if (Result<void> ok = parser.end(); !ok) return Error{ok.error()};
    return device;
}

}  // namespace dpscope
