#include "formats/parameter_names.hpp"

#include <fmt/compile.h>
#include <fmt/format.h>

#include <iterator>

#include "formats/field_writers.hpp"

namespace dpscope {

void append_parameter_label(TextBuffer& b, const NamedParameter& p) {
    if (!p.row) return;
    if (p.family->numbering == PnuNumbering::Group)
        fmt::format_to(fmt::appender(b), FMT_COMPILE("{}-{:02} "), p.row->pnu / 100,
                       p.row->pnu % 100);
    append(b, p.row->name);
}

void append_parameter_name(TextBuffer& b, const NamedParameter& p) {
    if (!p.row) return;
    append(b, " (");
    append_parameter_label(b, p);
    b.push_back(')');
}

void append_parameter_details(TextBuffer& b, const NamedParameter& p) {
    if (!p.row) return;
    append_parameter_label(b, p);
    fmt::format_to(fmt::appender(b), FMT_COMPILE(" ({}: "), p.family->id);
    if (!p.row->unit.empty())
        fmt::format_to(fmt::appender(b), FMT_COMPILE("unit {}, "), p.row->unit);
    if (p.row->conversion)
        fmt::format_to(fmt::appender(b), FMT_COMPILE("conversion index {}, "), *p.row->conversion);
    append(b, parameter_type_name(p.row->type));
    if (p.row->elements > 1) fmt::format_to(fmt::appender(b), FMT_COMPILE("[{}]"), p.row->elements);
    fmt::format_to(fmt::appender(b), FMT_COMPILE(", source {})"), p.row->source);
}

void append_value_details(TextBuffer& b, const ParameterRow& row, const ScaledValue& value) {
    append_scaled(b, row, value);
    if (row.conversion)
        fmt::format_to(fmt::appender(b), FMT_COMPILE(" (conversion index {})"), *row.conversion);
}

std::optional<ScaledValue> parameter_value(const ParameterRow* row, std::uint32_t bits) noexcept {
    if (!row) return std::nullopt;
    return scale_value(*row, raw_value_of_type(row->type, bits));
}

void append_scaled(TextBuffer& b, const ParameterRow& row, const ScaledValue& value) {
    fmt::format_to(fmt::appender(b), FMT_COMPILE("{:.{}f}"), value.value, value.decimals);
    if (!row.unit.empty()) {
        b.push_back(' ');
        append(b, row.unit);
    }
}

std::string parameter_name_text(const NamedParameter& p) {
    TextBuffer b;
    append_parameter_name(b, p);
    return fmt::to_string(b);
}

std::string view_value_text(const TelegramParameterView& view) {
    TextBuffer b;
    append_view_value(b, view);
    return fmt::to_string(b);
}

std::string pnu_label(StationNaming names, std::uint16_t pnu) {
    const NamedParameter named = names(pnu);
    if (!named.row) return fmt::format(FMT_COMPILE("{}"), pnu);
    TextBuffer b;
    fmt::format_to(fmt::appender(b), FMT_COMPILE("{}"), pnu);
    append_parameter_name(b, named);
    return fmt::to_string(b);
}

void pnu_name_key(JsonWriter& w, StationNaming names, std::uint16_t pnu) {
    const NamedParameter named = names(pnu);
    w.key("pnu_name");
    if (named.row)
        w.string(named.row->name);
    else
        w.null();
}

namespace {

// Whether showing the value in its unit says nothing the raw number does not: no unit, and a
// conversion that leaves the number as it is.
bool says_nothing(const ParameterRow& row, const ScaledValue& value) noexcept {
    return row.unit.empty() && value.decimals == 0 && row.conversion &&
           (*row.conversion == 0 || *row.conversion == 100);
}

}  // namespace

void append_parameter_value(TextBuffer& b, const ParameterRow* row, std::uint32_t bits) {
    const std::optional<ScaledValue> value = parameter_value(row, bits);
    if (!value || says_nothing(*row, *value)) return;
    append(b, " (");
    append_scaled(b, *row, *value);
    b.push_back(')');
}

TelegramParameterView parameter_view(const DecodedTelegram& t) noexcept {
    TelegramParameterView view;
    const auto parameter_of = protocol_descriptor(t.protocol).parameter_of;
    if (!parameter_of) return view;
    const std::optional<TelegramParameter> p = parameter_of(t);
    if (!p) return view;
    view.present = true;
    view.parameter = *p;
    view.named = named_parameter(t, p->pnu);
    if (!view.named.row) return view;
    if (p->has_raw)
        view.value = parameter_value(view.named.row, p->raw);
    else if (p->has_decimal)
        view.value = ScaledValue{p->decimal, p->decimals};
    return view;
}

void append_view_value(TextBuffer& b, const TelegramParameterView& view) {
    if (!view.value || !view.named.row || !view.parameter.has_raw) return;
    if (says_nothing(*view.named.row, *view.value)) return;
    append(b, " (");
    append_scaled(b, *view.named.row, *view.value);
    b.push_back(')');
}

namespace {

void write_scaled(fmt::memory_buffer& out, const ScaledValue& value) {
    fmt::format_to(fmt::appender(out), FMT_COMPILE("{:.{}f}"), value.value, value.decimals);
}

}  // namespace

void parameter_jsonl_keys(JsonWriter& w, const TelegramParameterView& view) {
    parameter_jsonl_keys(w, view.named.row, view.value);
}

void parameter_jsonl_keys(JsonWriter& w, const ParameterRow* row,
                          const std::optional<ScaledValue>& value) {
    w.key("pnu_name");
    if (row)
        w.string(row->name);
    else
        w.null();
    w.key("value_scaled");
    if (value)
        w.raw_value([&](fmt::memory_buffer& out) { write_scaled(out, *value); });
    else
        w.null();
    w.key("unit");
    if (row && !row->unit.empty())
        w.string(row->unit);
    else
        w.null();
}

void parameter_csv_columns(TextBuffer& b, const TelegramParameterView& view) {
    const ParameterRow* row = view.named.row;
    b.push_back(',');
    if (row) csv_quoted(b, row->name);
    b.push_back(',');
    if (view.value) write_scaled(b, *view.value);
    b.push_back(',');
    if (row && !row->unit.empty()) csv_quoted(b, row->unit);
}

}  // namespace dpscope
