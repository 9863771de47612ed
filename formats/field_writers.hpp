// Small field writers the telegram renderers share with every protocol's part of them
// (protocols/<name>/*_render.cpp): JSON values for the jsonl format, fields for the csv format.
#pragma once

#include <fmt/format.h>

#include <cstdint>
#include <iterator>
#include <span>
#include <string_view>

#include "formats/describe.hpp"
#include "formats/json_writer.hpp"

namespace dpscope {

// ---- jsonl

// Names of the set bits as an array of strings.
inline void flag_array(JsonWriter& w, std::uint8_t value, std::span<const FlagBit> flags) {
    w.begin_array();
    for (const FlagBit& flag : flags)
        if (value & flag.mask) w.string(flag.name);
    w.end_array();
}

// The bytes as one string of hex digits ("0a1b").
inline void hex_string(JsonWriter& w, Bytes bytes) {
    w.raw_value([bytes](TextBuffer& b) {
        b.push_back('"');
        append_hex(b, bytes, "");
        b.push_back('"');
    });
}

inline void optional_text(JsonWriter& w, bool present, std::string_view text) {
    if (present)
        w.string(text);
    else
        w.null();
}

// The same for the program's own names (JsonWriter::name(): no escape check; the names are
// checked in tests/json_writer_test.cpp).
inline void optional_name(JsonWriter& w, bool present, std::string_view name) {
    if (present)
        w.name(name);
    else
        w.null();
}

inline void optional_boolean(JsonWriter& w, bool present, bool value) {
    if (present)
        w.boolean(value);
    else
        w.null();
}

inline void optional_string(JsonWriter& w, std::string_view text) {
    if (text.empty())
        w.null();
    else
        w.string(text);
}

// ---- csv

// A CSV field in quotes, quotes inside doubled (RFC 4180).
inline void csv_quoted(TextBuffer& b, std::string_view text) {
    b.push_back('"');
    // The runs between quotes are copied whole; each quote is written twice.
    for (std::size_t quote; (quote = text.find('"')) != std::string_view::npos;) {
        append(b, text.substr(0, quote + 1));
        b.push_back('"');
        text.remove_prefix(quote + 1);
    }
    append(b, text);
    b.push_back('"');
}

// A number field followed by its comma; empty when not present.
inline void csv_optional(TextBuffer& b, bool present, unsigned value) {
    if (present) append_decimal(b, value);
    b.push_back(',');
}

}  // namespace dpscope
