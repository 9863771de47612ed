// A strict JSON syntax check for the fuzz targets: dpscope writes JSON (jsonl records, the report,
// the stats) and has no JSON reader; a target checks that what a renderer wrote parses (RFC 8259
// syntax, no tree built). Nesting deeper than 64 counts as invalid.
#pragma once

#include <cstddef>
#include <string_view>

namespace dpscope::fuzz {

namespace json_check_detail {

class Checker {
  public:
    explicit Checker(std::string_view text) : s_(text) {}
    bool document() {
        space();
        if (!value(0)) return false;
        space();
        return at_ == s_.size();
    }

  private:
    bool value(int depth) {
        if (depth > 64 || at_ >= s_.size()) return false;
        switch (s_[at_]) {
            case '{': return object(depth);
            case '[': return array(depth);
            case '"': return string();
            case 't': return word("true");
            case 'f': return word("false");
            case 'n': return word("null");
            default: return number();
        }
    }
    bool object(int depth) {
        ++at_;
        space();
        if (peek('}')) return ++at_, true;
        for (;;) {
            space();
            if (!string()) return false;
            space();
            if (!peek(':')) return false;
            ++at_;
            space();
            if (!value(depth + 1)) return false;
            space();
            if (peek('}')) return ++at_, true;
            if (!peek(',')) return false;
            ++at_;
        }
    }
    bool array(int depth) {
        ++at_;
        space();
        if (peek(']')) return ++at_, true;
        for (;;) {
            space();
            if (!value(depth + 1)) return false;
            space();
            if (peek(']')) return ++at_, true;
            if (!peek(',')) return false;
            ++at_;
        }
    }
    bool string() {
        if (!peek('"')) return false;
        ++at_;
        while (at_ < s_.size()) {
            const unsigned char c = static_cast<unsigned char>(s_[at_++]);
            if (c == '"') return true;
            if (c < 0x20) return false;
            if (c == '\\') {
                if (at_ >= s_.size()) return false;
                const char e = s_[at_++];
                if (e == 'u') {
                    for (int i = 0; i < 4; ++i, ++at_)
                        if (at_ >= s_.size() || !hex(s_[at_])) return false;
                } else if (std::string_view("\"\\/bfnrt").find(e) == std::string_view::npos) {
                    return false;
                }
            }
        }
        return false;
    }
    bool number() {
        if (peek('-')) ++at_;
        if (peek('0')) {
            ++at_;
        } else if (!digits()) {
            return false;
        }
        if (peek('.')) {
            ++at_;
            if (!digits()) return false;
        }
        if (peek('e') || peek('E')) {
            ++at_;
            if (peek('+') || peek('-')) ++at_;
            if (!digits()) return false;
        }
        return true;
    }
    bool digits() {
        const std::size_t start = at_;
        while (at_ < s_.size() && s_[at_] >= '0' && s_[at_] <= '9')
            ++at_;
        return at_ > start;
    }
    bool word(std::string_view w) {
        if (s_.substr(at_, w.size()) != w) return false;
        at_ += w.size();
        return true;
    }
    static bool hex(char c) {
        return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
    }
    bool peek(char c) const { return at_ < s_.size() && s_[at_] == c; }
    void space() {
        while (at_ < s_.size() &&
               (s_[at_] == ' ' || s_[at_] == '\n' || s_[at_] == '\r' || s_[at_] == '\t'))
            ++at_;
    }

    std::string_view s_;
    std::size_t at_ = 0;
};

}  // namespace json_check_detail

// True when `text` is one JSON value (whitespace around it allowed).
inline bool is_json(std::string_view text) { return json_check_detail::Checker(text).document(); }

}  // namespace dpscope::fuzz
