// How every output shows a named parameter (issue 29, docs/parameters.md, "In the outputs"): the
// text formats put the name after the number, " (16-13 Frequency)", and the value scaled into its
// unit after the raw value, " (50.0 Hz)"; jsonl adds "pnu_name", "value_scaled" and "unit" beside
// the raw numbers, which stay as they were. The row comes from the telegram's naming
// (named_parameter(), drives/parameter_naming.hpp): an array read and a binary search, no
// allocation.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "core/protocol_descriptor.hpp"
#include "drives/parameter_naming.hpp"
#include "formats/describe.hpp"
#include "formats/json_writer.hpp"

namespace dpscope {

// "16-13 Frequency" (a family numbered by group: the number as written, then the name) or
// "Frequency" (a family that writes the number as it is).
void append_parameter_label(TextBuffer& b, const NamedParameter& p);
// " (16-13 Frequency)" or " (Frequency)"; nothing without a row.
void append_parameter_name(TextBuffer& b, const NamedParameter& p);

// The verbose view's line about a named parameter: "16-13 Frequency (fc: unit Hz, conversion
// index -1, int32, source PG302 p. 212)"; nothing without a row.
void append_parameter_details(TextBuffer& b, const NamedParameter& p);
// The verbose view's line about a value in its unit: "50.0 Hz (conversion index -1)".
void append_value_details(TextBuffer& b, const ParameterRow& row, const ScaledValue& value);

// The raw value `bits` (a PWE, PVA or PROFIdrive value) in the row's unit: read by its type,
// scaled by its conversion index; nullopt when the row has none or no row is given.
std::optional<ScaledValue> parameter_value(const ParameterRow* row, std::uint32_t bits) noexcept;
// "50.0 Hz", "400 V", "12.34" (no unit).
void append_scaled(TextBuffer& b, const ParameterRow& row, const ScaledValue& value);
// " (50.0 Hz)" after a raw value; nothing when it is not scaled, or when scaling changes nothing
// and there is no unit (a count, an enumeration).
void append_parameter_value(TextBuffer& b, const ParameterRow* row, std::uint32_t bits);

// The parameter a telegram is about (its protocol's parameter_of), named by its naming, and its
// value in the parameter's unit: `named` null when no row names it; `value` nullopt when it
// carries no value or the row scales none. `present` false: the telegram is about no parameter.
struct TelegramParameterView {
    bool present = false;
    TelegramParameter parameter;
    NamedParameter named;
    std::optional<ScaledValue> value;
};
TelegramParameterView parameter_view(const DecodedTelegram& t) noexcept;
// " (50.0 Hz)" after the raw value the view's value comes from (see append_parameter_value).
void append_view_value(TextBuffer& b, const TelegramParameterView& view);

// For the Wireshark trees' item texts: " (16-13 Frequency)" (or "" without a row), and the
// view's value in its unit " (50.0 Hz)" (or "").
std::string parameter_name_text(const NamedParameter& p);
std::string view_value_text(const TelegramParameterView& view);

// A PNU in a report's tables: "1613 (16-13 Frequency)", or "1613" without a row in `family`.
std::string pnu_label(StationNaming names, std::uint16_t pnu);
// "pnu_name": the name of the PNU's row in `family`, or null.
void pnu_name_key(JsonWriter& w, StationNaming names, std::uint16_t pnu);

// jsonl: "pnu_name" (the row's name), "value_scaled" (the value in its unit, with the row's
// decimals; null when there is no value or it is not scaled) and "unit"; each null without a
// row.
void parameter_jsonl_keys(JsonWriter& w, const TelegramParameterView& view);
// The same keys from a row (or none) and a value in its unit (or none).
void parameter_jsonl_keys(JsonWriter& w, const ParameterRow* row,
                          const std::optional<ScaledValue>& value);

// csv: the last three columns, pnu_name, value_scaled and unit, each after a comma.
void parameter_csv_columns(TextBuffer& b, const TelegramParameterView& view);

}  // namespace dpscope
