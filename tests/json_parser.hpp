// A strict JSON parser for tests: dpscope has no JSON library, and its JSON output (jsonl, the
// report) must parse strictly. parse_json() fails the running test on invalid input.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace dpscope::test {

struct Json {
    enum class Type { Null, Bool, Number, String, Array, Object };
    // Defined below the class: clang (the coverage preset) would otherwise instantiate the
    // members' destructor while Json is still incomplete.
    Json();
    Json(const Json&);
    Json(Json&&) noexcept;
    Json& operator=(const Json&);
    Json& operator=(Json&&) noexcept;
    ~Json();

    Type type = Type::Null;
    bool boolean = false;
    std::string text;  // the number literal, or the decoded string
    std::vector<Json> items;
    std::vector<std::pair<std::string, Json>> members;

    bool is_null() const { return type == Type::Null; }
    const Json* find(std::string_view key) const {
        for (const auto& [name, value] : members)
            if (name == key) return &value;
        return nullptr;
    }
    const Json& operator[](std::string_view key) const {
        static const Json missing;
        const Json* value = find(key);
        if (!value) ADD_FAILURE() << "no key '" << key << "'";
        return value ? *value : missing;
    }
    const Json& operator[](std::size_t index) const {
        static const Json missing;
        if (index >= items.size()) ADD_FAILURE() << "no item " << index;
        return index < items.size() ? items[index] : missing;
    }
    std::vector<std::string> keys() const {
        std::vector<std::string> out;
        for (const auto& member : members)
            out.push_back(member.first);
        return out;
    }
    long long integer() const {
        EXPECT_EQ(type, Type::Number);
        EXPECT_EQ(text.find_first_of(".eE"), std::string::npos) << text;
        return std::strtoll(text.c_str(), nullptr, 10);
    }
    const std::string& string() const {
        EXPECT_EQ(type, Type::String);
        return text;
    }
};

inline Json::Json() = default;
inline Json::Json(const Json&) = default;
inline Json::Json(Json&&) noexcept = default;
inline Json& Json::operator=(const Json&) = default;
inline Json& Json::operator=(Json&&) noexcept = default;
inline Json::~Json() = default;

class JsonParser {
  public:
    explicit JsonParser(std::string_view text) : text_(text) {}

    // The whole text must be exactly one value (white space around it allowed).
    std::optional<Json> parse(std::string& error) {
        skip_space();
        std::optional<Json> result = value(0);
        if (result) {
            skip_space();
            if (pos_ != text_.size()) result = fail("text after the value");
        }
        if (!result) error = error_ + " at offset " + std::to_string(pos_);
        return result;
    }

  private:
    std::optional<Json> fail(std::string message) {
        if (error_.empty()) error_ = std::move(message);
        return std::nullopt;
    }
    bool at_end() const { return pos_ >= text_.size(); }
    char peek() const { return at_end() ? '\0' : text_[pos_]; }
    void skip_space() {
        while (!at_end() && (peek() == ' ' || peek() == '\t' || peek() == '\n' || peek() == '\r'))
            ++pos_;
    }
    bool literal(std::string_view word) {
        if (text_.substr(pos_, word.size()) != word) return false;
        pos_ += word.size();
        return true;
    }

    std::optional<Json> value(int depth) {
        if (depth > 64) return fail("nesting too deep");
        Json out;
        switch (peek()) {
            case '{': return object(depth);
            case '[': return array(depth);
            case '"': {
                auto s = string();
                if (!s) return std::nullopt;
                out.type = Json::Type::String;
                out.text = *s;
                return out;
            }
            case 't':
            case 'f':
                out.type = Json::Type::Bool;
                out.boolean = peek() == 't';
                if (!literal(out.boolean ? "true" : "false")) return fail("bad literal");
                return out;
            case 'n':
                if (!literal("null")) return fail("bad literal");
                return out;
            default: return number();
        }
    }

    std::optional<Json> number() {
        std::size_t start = pos_;
        auto digits = [&] {
            std::size_t from = pos_;
            while (!at_end() && peek() >= '0' && peek() <= '9')
                ++pos_;
            return pos_ - from;
        };
        if (peek() == '-') ++pos_;
        if (peek() == '0') {
            ++pos_;
        } else if (digits() == 0) {
            return fail("expected a value");
        }
        if (peek() == '.') {
            ++pos_;
            if (digits() == 0) return fail("digits expected after '.'");
        }
        if (peek() == 'e' || peek() == 'E') {
            ++pos_;
            if (peek() == '+' || peek() == '-') ++pos_;
            if (digits() == 0) return fail("digits expected in the exponent");
        }
        Json out;
        out.type = Json::Type::Number;
        out.text = std::string(text_.substr(start, pos_ - start));
        return out;
    }

    static void append_utf8(std::string& out, unsigned code) {
        if (code < 0x80) {
            out.push_back(static_cast<char>(code));
        } else if (code < 0x800) {
            out.push_back(static_cast<char>(0xC0 | (code >> 6)));
            out.push_back(static_cast<char>(0x80 | (code & 0x3F)));
        } else if (code < 0x10000) {
            out.push_back(static_cast<char>(0xE0 | (code >> 12)));
            out.push_back(static_cast<char>(0x80 | ((code >> 6) & 0x3F)));
            out.push_back(static_cast<char>(0x80 | (code & 0x3F)));
        } else {
            out.push_back(static_cast<char>(0xF0 | (code >> 18)));
            out.push_back(static_cast<char>(0x80 | ((code >> 12) & 0x3F)));
            out.push_back(static_cast<char>(0x80 | ((code >> 6) & 0x3F)));
            out.push_back(static_cast<char>(0x80 | (code & 0x3F)));
        }
    }

    std::optional<unsigned> hex4() {
        if (pos_ + 4 > text_.size()) return std::nullopt;
        unsigned code = 0;
        for (int i = 0; i < 4; ++i) {
            char c = text_[pos_++];
            code <<= 4;
            if (c >= '0' && c <= '9') {
                code |= static_cast<unsigned>(c - '0');
            } else if (c >= 'a' && c <= 'f') {
                code |= static_cast<unsigned>(c - 'a' + 10);
            } else if (c >= 'A' && c <= 'F') {
                code |= static_cast<unsigned>(c - 'A' + 10);
            } else {
                return std::nullopt;
            }
        }
        return code;
    }

    std::optional<std::string> string() {
        ++pos_;  // opening quote
        std::string out;
        for (;;) {
            if (at_end()) {
                fail("unterminated string");
                return std::nullopt;
            }
            char c = text_[pos_++];
            if (c == '"') return out;
            if (static_cast<unsigned char>(c) < 0x20) {
                fail("control character in a string");
                return std::nullopt;
            }
            if (c != '\\') {
                out.push_back(c);
                continue;
            }
            char e = at_end() ? '\0' : text_[pos_++];
            switch (e) {
                case '"': out.push_back('"'); break;
                case '\\': out.push_back('\\'); break;
                case '/': out.push_back('/'); break;
                case 'b': out.push_back('\b'); break;
                case 'f': out.push_back('\f'); break;
                case 'n': out.push_back('\n'); break;
                case 'r': out.push_back('\r'); break;
                case 't': out.push_back('\t'); break;
                case 'u': {
                    auto code = hex4();
                    if (!code || (*code >= 0xD800 && *code < 0xE000)) {
                        fail("bad \\u escape");
                        return std::nullopt;
                    }
                    append_utf8(out, *code);
                    break;
                }
                default: fail("bad escape"); return std::nullopt;
            }
        }
    }

    std::optional<Json> array(int depth) {
        ++pos_;
        Json out;
        out.type = Json::Type::Array;
        skip_space();
        if (peek() == ']') {
            ++pos_;
            return out;
        }
        for (;;) {
            skip_space();
            auto item = value(depth + 1);
            if (!item) return std::nullopt;
            out.items.push_back(std::move(*item));
            skip_space();
            if (peek() == ',') {
                ++pos_;
                continue;
            }
            if (peek() == ']') {
                ++pos_;
                return out;
            }
            return fail("expected ',' or ']'");
        }
    }

    std::optional<Json> object(int depth) {
        ++pos_;
        Json out;
        out.type = Json::Type::Object;
        skip_space();
        if (peek() == '}') {
            ++pos_;
            return out;
        }
        for (;;) {
            skip_space();
            if (peek() != '"') return fail("expected a key");
            auto key = string();
            if (!key) return std::nullopt;
            if (out.find(*key)) return fail("duplicate key " + *key);
            skip_space();
            if (peek() != ':') return fail("expected ':'");
            ++pos_;
            skip_space();
            auto item = value(depth + 1);
            if (!item) return std::nullopt;
            out.members.emplace_back(std::move(*key), std::move(*item));
            skip_space();
            if (peek() == ',') {
                ++pos_;
                continue;
            }
            if (peek() == '}') {
                ++pos_;
                return out;
            }
            return fail("expected ',' or '}'");
        }
    }

    std::string_view text_;
    std::size_t pos_ = 0;
    std::string error_;
};

inline std::optional<Json> parse_json(std::string_view text) {
    std::string error;
    std::optional<Json> result = JsonParser(text).parse(error);
    if (!result) ADD_FAILURE() << "invalid JSON (" << error << "): " << text;
    return result;
}

inline double number_of(const Json& value) {
    EXPECT_EQ(value.type, Json::Type::Number);
    return std::strtod(value.text.c_str(), nullptr);
}

}  // namespace dpscope::test
