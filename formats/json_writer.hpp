// A small streaming JSON writer. It appends straight into a caller's fmt::memory_buffer (the
// buffer of Output, so the hot path allocates nothing), puts the commas between members and
// array items itself and escapes strings: callers never write a comma or a quote.
//
//   JsonWriter w(out.buffer());
//   w.begin_object();
//   w.key("frame").integer(12);
//   w.key("flags").begin_array().string("sync").string("freeze").end_array();
//   w.key("pnu").null();
//   w.end_object();                      // {"frame":12,"flags":["sync","freeze"],"pnu":null}
//
// One writer writes one JSON text (a jsonl line takes a new one). Keys are written as given: they
// are the program's own names (plain ASCII, nothing to escape). Strings are escaped as JSON
// requires ('"', '\\', control characters); bytes from 0x7F up are copied as they are, so UTF-8
// text stays UTF-8. Where the exact text of a number matters (six decimals, seconds with
// nanoseconds) number_text() and raw_value() write it verbatim.
#pragma once

#include <fmt/format.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include "formats/text_buffer.hpp"

namespace dpscope {

namespace json {

// A JSON string with the required escapes, appended to `out`.
void string(fmt::memory_buffer& out, std::string_view text);

inline void integer(fmt::memory_buffer& out, std::int64_t value) { append_signed(out, value); }

}  // namespace json

class JsonWriter {
  public:
    explicit JsonWriter(fmt::memory_buffer& out) noexcept : out_(out) {}
    JsonWriter(const JsonWriter&) = delete;
    JsonWriter& operator=(const JsonWriter&) = delete;

    JsonWriter& begin_object() {
        separate();
        out_.push_back('{');
        return opened();
    }
    JsonWriter& end_object() {
        out_.push_back('}');
        return closed();
    }
    JsonWriter& begin_array() {
        separate();
        out_.push_back('[');
        return opened();
    }
    JsonWriter& end_array() {
        out_.push_back(']');
        return closed();
    }

    // "name": — the next call writes its value.
    JsonWriter& key(std::string_view name) { return key_of_size(name.data(), name.size()); }
    // The same for a literal key, the usual case: inlined, its length folds to a constant where
    // the call is compiled, so the copy is a few stores instead of calls (jsonl writes some 30
    // keys per telegram). strlen, not N - 1: a char array holding a shorter name stays right.
    template <std::size_t N>
    [[gnu::always_inline]] JsonWriter& key(const char (&name)[N]) {
        return key_of_size(name, std::char_traits<char>::length(name));
    }

    [[gnu::always_inline]] JsonWriter& integer(std::int64_t value) {
        separate();
        json::integer(out_, value);
        return wrote();
    }
    [[gnu::always_inline]] JsonWriter& boolean(bool value) {
        return value ? literal("true") : literal("false");
    }
    [[gnu::always_inline]] JsonWriter& null() { return literal("null"); }
    JsonWriter& string(std::string_view text) {
        separate();
        json::string(out_, text);
        return wrote();
    }
    // An integer, or null when it is not present.
    [[gnu::always_inline]] JsonWriter& optional_integer(bool present, std::int64_t value) {
        return present ? integer(value) : null();
    }
    // A number whose text the caller formatted ("0.125000"); written verbatim.
    JsonWriter& number_text(std::string_view text) { return literal(text); }
    // A value whose text `write(buffer)` appends itself, verbatim (it must be valid JSON: a
    // number, or a string that needs no escapes, quotes included).
    template <typename Write>
    JsonWriter& raw_value(Write&& write) {
        separate();
        write(out_);
        return wrote();
    }

    // Nesting depth: 0 once every object and array begun has ended.
    std::size_t depth() const noexcept { return depth_; }
    fmt::memory_buffer& buffer() noexcept { return out_; }

  private:
    // Always inline, so that a literal key's constant `size` reaches memcpy.
    [[gnu::always_inline]] JsonWriter& key_of_size(const char* name, std::size_t size) {
        const std::size_t at = out_.size();
        const std::size_t comma = need_comma_ ? 1 : 0;
        out_.resize(at + comma + size + 3);
        char* p = out_.data() + at;
        if (comma) *p++ = ',';
        *p++ = '"';
        std::memcpy(p, name, size);
        p += size;
        *p++ = '"';
        *p = ':';
        need_comma_ = false;
        return *this;
    }
    [[gnu::always_inline]] void separate() {
        if (need_comma_) out_.push_back(',');
    }
    JsonWriter& opened() {
        ++depth_;
        need_comma_ = false;
        return *this;
    }
    [[gnu::always_inline]] JsonWriter& wrote() {
        need_comma_ = true;
        return *this;
    }
    JsonWriter& closed() {
        --depth_;
        return wrote();
    }
    [[gnu::always_inline]] JsonWriter& literal(std::string_view text) {
        separate();
        append(out_, text);
        return wrote();
    }

    fmt::memory_buffer& out_;
    std::size_t depth_ = 0;
    // A value was written at this level: the next key or item is preceded by a comma. One flag
    // is enough: begin_*() and key() clear it, every value and end_*() sets it.
    bool need_comma_ = false;
};

}  // namespace dpscope
