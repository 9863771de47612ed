// A small XML parser for tests (the project has no XML library): the JUnit and HTML reports and
// the `dpscope stats` HTML page are checked with it. parse_xml() fails the running test on a
// document that is not well-formed.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace dpscope::test {

// ---- a small XML parser ----------------------------------------------------------------------
// Well-formedness: balanced tags, one root, quoted attributes without '<' and without duplicates,
// valid entity references, no raw '<' in text. In HTML mode also a DOCTYPE, void elements
// (<meta>), raw text in <style> and <script>, and named entities such as &middot;.

struct XmlNode {
    std::string name;
    std::vector<std::pair<std::string, std::string>> attributes;  // values unescaped
    std::vector<XmlNode> children;
    std::string text;   // character data directly inside, unescaped
    std::string inner;  // all character data inside, descendants included, in document order

    const std::string* find_attribute(std::string_view key) const {
        for (const auto& [attribute_name, value] : attributes)
            if (attribute_name == key) return &value;
        return nullptr;
    }
    std::string attribute(std::string_view key) const {
        const std::string* value = find_attribute(key);
        return value ? *value : std::string();
    }
    bool has_class(std::string_view wanted) const {
        std::string classes = attribute("class");
        std::size_t start = 0;
        while (start <= classes.size()) {
            std::size_t end = classes.find(' ', start);
            if (end == std::string::npos) end = classes.size();
            if (std::string_view(classes).substr(start, end - start) == wanted) return true;
            start = end + 1;
        }
        return false;
    }
    // Descendants named `tag` (with class `cls` unless empty), in document order.
    std::vector<const XmlNode*> all(std::string_view tag, std::string_view cls = {}) const {
        std::vector<const XmlNode*> out;
        collect(tag, cls, out);
        return out;
    }
    // Children named `tag`.
    std::vector<const XmlNode*> elements(std::string_view tag) const {
        std::vector<const XmlNode*> out;
        for (const XmlNode& child : children)
            if (child.name == tag) out.push_back(&child);
        return out;
    }

  private:
    void collect(std::string_view tag, std::string_view cls,
                 std::vector<const XmlNode*>& out) const {
        for (const XmlNode& child : children) {
            if (child.name == tag && (cls.empty() || child.has_class(cls))) out.push_back(&child);
            child.collect(tag, cls, out);
        }
    }
};

class XmlParser {
  public:
    XmlParser(std::string_view text, bool html) : text_(text), html_(html) {}

    std::optional<XmlNode> parse(std::string& error) {
        std::optional<XmlNode> result = document();
        if (!result) error = error_ + " at offset " + std::to_string(pos_);
        return result;
    }

  private:
    std::optional<XmlNode> fail(std::string message) {
        if (error_.empty()) error_ = std::move(message);
        return std::nullopt;
    }
    bool starts(std::string_view prefix) const {
        return text_.substr(pos_, prefix.size()) == prefix;
    }
    char peek() const { return pos_ < text_.size() ? text_[pos_] : '\0'; }
    bool skip_space() {
        std::size_t from = pos_;
        while (peek() == ' ' || peek() == '\n' || peek() == '\t' || peek() == '\r')
            ++pos_;
        return pos_ > from;
    }
    static bool name_start(char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' || c == ':';
    }
    std::string name() {
        std::size_t from = pos_;
        if (!name_start(peek())) return {};
        while (name_start(peek()) || (peek() >= '0' && peek() <= '9') || peek() == '-' ||
               peek() == '.')
            ++pos_;
        return std::string(text_.substr(from, pos_ - from));
    }
    static bool is_void(std::string_view tag) {
        for (std::string_view v : {"meta", "br", "hr", "img", "input", "link", "col", "wbr"})
            if (tag == v) return true;
        return false;
    }
    static void append_utf8(std::string& out, unsigned long code) {
        if (code < 0x80) {
            out.push_back(static_cast<char>(code));
        } else if (code < 0x800) {
            out.push_back(static_cast<char>(0xC0 | (code >> 6)));
            out.push_back(static_cast<char>(0x80 | (code & 0x3F)));
        } else {
            out.push_back(static_cast<char>(0xE0 | (code >> 12)));
            out.push_back(static_cast<char>(0x80 | ((code >> 6) & 0x3F)));
            out.push_back(static_cast<char>(0x80 | (code & 0x3F)));
        }
    }
    // Unescapes `raw` (text or an attribute value); false on a bad entity reference.
    bool decode(std::string_view raw, std::string& out) const {
        for (std::size_t i = 0; i < raw.size(); ++i) {
            if (raw[i] != '&') {
                out.push_back(raw[i]);
                continue;
            }
            std::size_t end = raw.find(';', i);
            if (end == std::string_view::npos || end - i > 10 || end == i + 1) return false;
            std::string_view entity = raw.substr(i + 1, end - i - 1);
            if (entity == "amp") {
                out += '&';
            } else if (entity == "lt") {
                out += '<';
            } else if (entity == "gt") {
                out += '>';
            } else if (entity == "quot") {
                out += '"';
            } else if (entity == "apos") {
                out += '\'';
            } else if (entity[0] == '#') {
                bool hex = entity.size() > 1 && entity[1] == 'x';
                std::string digits(entity.substr(hex ? 2 : 1));
                if (digits.empty()) return false;
                char* stop = nullptr;
                unsigned long code = std::strtoul(digits.c_str(), &stop, hex ? 16 : 10);
                if (*stop != '\0' || code == 0 || code > 0xFFFF) return false;
                append_utf8(out, code);
            } else if (html_ && std::all_of(entity.begin(), entity.end(), name_start)) {
                out += '&';  // a named HTML entity: kept as written
                out += entity;
                out += ';';
            } else {
                return false;
            }
            i = end;
        }
        return true;
    }

    bool close(XmlNode node, std::vector<XmlNode>& stack, std::optional<XmlNode>& root) {
        if (!stack.empty()) {
            stack.back().children.push_back(std::move(node));
            return true;
        }
        if (root) {
            fail("a second root element <" + node.name + ">");
            return false;
        }
        root = std::move(node);
        return true;
    }

    std::optional<XmlNode> document() {
        std::vector<XmlNode> stack;
        std::optional<XmlNode> root;
        if (starts("<?xml")) {
            std::size_t end = text_.find("?>", pos_);
            if (end == std::string_view::npos) return fail("unterminated XML declaration");
            pos_ = end + 2;
        }
        skip_space();
        if (html_) {
            if (!starts("<!DOCTYPE html>")) return fail("no <!DOCTYPE html>");
            pos_ += 15;
        }
        while (pos_ < text_.size()) {
            if (peek() != '<') {
                std::size_t end = std::min(text_.find('<', pos_), text_.size());
                std::string_view raw = text_.substr(pos_, end - pos_);
                if (stack.empty()) {
                    if (raw.find_first_not_of(" \t\r\n") != std::string_view::npos)
                        return fail("text outside the root element");
                } else {
                    std::string value;
                    if (!decode(raw, value)) return fail("bad entity reference");
                    stack.back().text += value;
                    for (XmlNode& open : stack)
                        open.inner += value;
                }
                pos_ = end;
                continue;
            }
            if (starts("<!--")) {
                std::size_t end = text_.find("-->", pos_);
                if (end == std::string_view::npos) return fail("unterminated comment");
                pos_ = end + 3;
                continue;
            }
            if (starts("</")) {
                pos_ += 2;
                std::string tag = name();
                skip_space();
                if (tag.empty() || peek() != '>') return fail("bad end tag");
                ++pos_;
                if (stack.empty() || stack.back().name != tag)
                    return fail("</" + tag + "> closes " +
                                (stack.empty() ? "nothing" : "<" + stack.back().name + ">"));
                XmlNode done = std::move(stack.back());
                stack.pop_back();
                if (!close(std::move(done), stack, root)) return std::nullopt;
                continue;
            }
            ++pos_;
            XmlNode node;
            node.name = name();
            if (node.name.empty()) return fail("'<' that starts no tag");
            bool self_closing = false;
            for (;;) {
                bool space = skip_space();
                if (starts("/>")) {
                    pos_ += 2;
                    self_closing = true;
                    break;
                }
                if (peek() == '>') {
                    ++pos_;
                    break;
                }
                if (!space) return fail("expected white space before an attribute");
                std::string key = name();
                if (key.empty()) return fail("bad attribute name");
                if (node.find_attribute(key)) return fail("duplicate attribute " + key);
                if (peek() != '=') return fail("attribute " + key + " without a value");
                ++pos_;
                if (peek() != '"') return fail("attribute " + key + " not quoted");
                ++pos_;
                std::size_t end = text_.find('"', pos_);
                if (end == std::string_view::npos) return fail("unterminated attribute value");
                std::string_view raw = text_.substr(pos_, end - pos_);
                if (raw.find('<') != std::string_view::npos) return fail("'<' in an attribute");
                std::string value;
                if (!decode(raw, value)) return fail("bad entity reference in an attribute");
                node.attributes.emplace_back(std::move(key), std::move(value));
                pos_ = end + 1;
            }
            if (self_closing || (html_ && is_void(node.name))) {
                if (!close(std::move(node), stack, root)) return std::nullopt;
                continue;
            }
            if (html_ && (node.name == "style" || node.name == "script")) {
                std::size_t end = text_.find("</" + node.name + ">", pos_);
                if (end == std::string_view::npos) return fail("unterminated <" + node.name + ">");
                node.text = node.inner = std::string(text_.substr(pos_, end - pos_));
                pos_ = end;
            }
            stack.push_back(std::move(node));
        }
        if (!stack.empty()) return fail("<" + stack.back().name + "> is not closed");
        if (!root) return fail("no root element");
        return root;
    }

    std::string_view text_;
    bool html_;
    std::size_t pos_ = 0;
    std::string error_;
};

inline std::optional<XmlNode> parse_xml(std::string_view text, bool html = false) {
    std::string error;
    std::optional<XmlNode> result = XmlParser(text, html).parse(error);
    if (!result) ADD_FAILURE() << "not well-formed (" << error << ")";
    return result;
}

}  // namespace dpscope::test
