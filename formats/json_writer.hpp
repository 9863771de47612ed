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
// True when no byte of `text` needs an escape (nor a check as UTF-8): it is copied as it is.
bool plain_text(std::string_view text) noexcept;

}  // namespace json

class JsonWriter {
  public:
    explicit JsonWriter(fmt::memory_buffer& out) noexcept : out_(out) {}
    ~JsonWriter() { commit(); }
    JsonWriter(const JsonWriter&) = delete;
    JsonWriter& operator=(const JsonWriter&) = delete;

    JsonWriter& begin_object() {
        separate();
        put_char('{');
        return opened();
    }
    JsonWriter& end_object() {
        put_char('}');
        return closed();
    }
    JsonWriter& begin_array() {
        separate();
        put_char('[');
        return opened();
    }
    JsonWriter& end_array() {
        put_char(']');
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
        std::uint64_t magnitude = static_cast<std::uint64_t>(value);
        if (value < 0) {
            put_char('-');
            magnitude = 0 - magnitude;
        }
        // Most of a line's integers (addresses, SAPs, codes, indices) have one or two digits:
        // written here, without the general writer's call.
        if (magnitude < 100) {
            char* p = room(2);
            if (magnitude < 10) {
                *p = static_cast<char>('0' + magnitude);
                cursor_ += 1;
            } else {
                std::memcpy(p, text_detail::kDigitPairs + 2 * magnitude, 2);
                cursor_ += 2;
            }
            return wrote();
        }
        const int digits = text_detail::decimal_digits(magnitude);
        text_detail::write_decimal_backwards(room(20) + digits, magnitude);
        cursor_ += digits;
        return wrote();
    }
    // Seconds since 1970 with nine decimals (write_epoch_seconds()).
    JsonWriter& epoch_seconds(std::int64_t time_ns) {
        separate();
        char* p = room(text_detail::kEpochSecondsMax);
        cursor_ = text_detail::write_epoch_seconds(p, time_ns);
        return wrote();
    }
    [[gnu::always_inline]] JsonWriter& boolean(bool value) {
        return value ? literal("true") : literal("false");
    }
    [[gnu::always_inline]] JsonWriter& null() { return literal("null"); }
    JsonWriter& string(std::string_view text) {
        separate();
        if (json::plain_text(text)) {
            put_quoted(text);
        } else {
            let_go();
            json::string(out_, text);
        }
        return wrote();
    }
    // A name from the program's own code tables (a bit's meaning, a block's name): the same as
    // string(), without the check for bytes to escape, which such names never have
    // (tests/json_writer_test.cpp checks the tables this is used for). Never for user data.
    JsonWriter& name(std::string_view text) {
        separate();
        put_quoted(text);
        return wrote();
    }
    // An integer, or null when it is not present.
    [[gnu::always_inline]] JsonWriter& optional_integer(bool present, std::int64_t value) {
        return present ? integer(value) : null();
    }
    // Members of the object being written, spelled out as JSON text by the caller
    // ("\"a\":null,\"b\":null"): a run of keys with constant values in one copy, where a line
    // has many of them (the jsonl objects a telegram does not have). After a comma when due.
    [[gnu::always_inline]] JsonWriter& members(std::string_view text) { return literal(text); }
    // A number whose text the caller formatted ("0.125000"); written verbatim.
    JsonWriter& number_text(std::string_view text) { return literal(text); }
    // A value that is JSON text already (an array kept by BitMeaningsJson); copied verbatim.
    JsonWriter& json_text(std::string_view text) { return literal(text); }
    // A value whose text `write(buffer)` appends itself, verbatim (it must be valid JSON: a
    // number, or a string that needs no escapes, quotes included).
    template <typename Write>
    JsonWriter& raw_value(Write&& write) {
        separate();
        let_go();
        write(out_);
        return wrote();
    }

    // Nesting depth: 0 once every object and array begun has ended.
    std::size_t depth() const noexcept { return depth_; }
    // Everything written so far is in the buffer: call it before the buffer is flushed in the
    // middle of a document (Output::end_record) or written by another hand. (A complete top-level
    // value is there without it.)
    void settle() noexcept { let_go(); }
    // The buffer, with everything written so far in it.
    fmt::memory_buffer& buffer() noexcept {
        let_go();
        return out_;
    }

  private:
    // The writer keeps a cursor into the buffer's spare capacity and tells the buffer its new
    // size only when a top-level value is complete, when someone else is to write into the
    // buffer, or at the end: the buffer's own size update was a call for every piece (issue 31).
    [[gnu::always_inline]] char* room(std::size_t n) {
        if (static_cast<std::size_t>(limit_ - cursor_) < n) more_room(n);
        return cursor_;
    }
    void more_room(std::size_t n) {
        commit();
        out_.reserve(out_.size() + (n > 2048 ? n : 2048));
        cursor_ = out_.data() + out_.size();
        limit_ = out_.data() + out_.capacity();
    }
    // The buffer's size takes in what was written through the cursor.
    void commit() noexcept {
        if (cursor_) out_.try_resize(static_cast<std::size_t>(cursor_ - out_.data()));
    }
    // Before the buffer is written by another hand (which may move its storage).
    void let_go() noexcept {
        commit();
        cursor_ = limit_ = nullptr;
    }
    [[gnu::always_inline]] void put_char(char c) {
        *room(1) = c;
        ++cursor_;
    }
    // `text` in quotes, as it is (nothing in it to escape).
    [[gnu::always_inline]] void put_quoted(std::string_view text) {
        char* p = room(text.size() + 2);
        *p = '"';
        if (!text.empty()) std::memcpy(p + 1, text.data(), text.size());
        p[text.size() + 1] = '"';
        cursor_ += text.size() + 2;
    }
    // Always inline, so that a literal key's constant `size` reaches memcpy.
    [[gnu::always_inline]] JsonWriter& key_of_size(const char* name, std::size_t size) {
        const std::size_t comma = need_comma_ ? 1 : 0;
        char* p = room(comma + size + 3);
        cursor_ += comma + size + 3;
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
        if (need_comma_) put_char(',');
    }
    JsonWriter& opened() {
        ++depth_;
        need_comma_ = false;
        return *this;
    }
    // A value was written; one at the top level is complete: the buffer is told, and the writer
    // lets it go (its caller may write a line end into it next).
    [[gnu::always_inline]] JsonWriter& wrote() {
        need_comma_ = true;
        if (depth_ == 0) let_go();
        return *this;
    }
    JsonWriter& closed() {
        --depth_;
        return wrote();
    }
    [[gnu::always_inline]] JsonWriter& literal(std::string_view text) {
        separate();
        if (!text.empty()) std::memcpy(room(text.size()), text.data(), text.size());
        cursor_ += text.size();
        return wrote();
    }

    fmt::memory_buffer& out_;
    char* cursor_ = nullptr;  // where the next character goes (null: none asked for yet)
    char* limit_ = nullptr;   // the end of the buffer's capacity
    std::size_t depth_ = 0;
    // A value was written at this level: the next key or item is preceded by a comma. One flag
    // is enough: begin_*() and key() clear it, every value and end_*() sets it.
    bool need_comma_ = false;
};

namespace json {

// The JSON text `write` writes through a JsonWriter (write(JsonWriter&)), as a string: an MQTT
// message, or a value made once to be copied into many lines.
template <class Write>
std::string text_of(Write&& write) {
    fmt::memory_buffer buffer;
    {
        JsonWriter w(buffer);
        write(w);
    }
    return std::string(buffer.data(), buffer.size());
}

}  // namespace json

}  // namespace dpscope
