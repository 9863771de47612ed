#include "formats/json_writer.hpp"

#include <cstdint>
#include <cstring>
#include <iterator>

#include "core/byte_word.hpp"
#include "core/text_encoding.hpp"

namespace dpscope::json {

namespace {

// Quotes, backslashes and control characters are escaped; bytes from 0x80 are checked for
// valid UTF-8 (JSON text is UTF-8: RFC 8259, section 8.1).
constexpr bool needs_escape(char c) noexcept {
    return c == '"' || c == '\\' || static_cast<unsigned char>(c) < 0x20 ||
           static_cast<unsigned char>(c) >= 0x80;
}

}  // namespace

// True when no byte of `text` needs an escape. Sixteen bytes a step (a vector of the GCC and
// Clang extension: SSE2 on x86-64, NEON on arm64), then eight (core/byte_word.hpp): a byte is
// flagged when it is 0x80 or more, below 0x20, or '"' or '\\'.
bool plain_text(std::string_view text) noexcept {
    using namespace byte_word;
    const char* p = text.data();
    std::size_t left = text.size();
    using Bytes16 = std::uint8_t __attribute__((vector_size(16)));
    for (; left >= 16; p += 16, left -= 16) {
        Bytes16 v;
        std::memcpy(&v, p, sizeof v);
        const auto flagged = (v >= 0x80) | (v < 0x20) | (v == '"') | (v == '\\');
        std::uint64_t halves[2];
        std::memcpy(halves, &flagged, sizeof halves);
        if ((halves[0] | halves[1]) != 0) return false;
    }
    for (; left >= 8; p += 8, left -= 8) {
        const std::uint64_t w = load(p);
        if ((any_high(w) | any_below(w, 0x20) | any_equal(w, '"') | any_equal(w, '\\')) != 0)
            return false;
    }
    bool plain = true;
    for (; left > 0; ++p, --left)
        plain &= !needs_escape(*p);
    return plain;
}

void string(fmt::memory_buffer& out, std::string_view text) {
    // Most strings are names that need no escape: one pass to check, one copy.
    if (plain_text(text)) {
        char* p = append_room(out, text.size() + 2);
        *p = '"';
        if (!text.empty()) std::memcpy(p + 1, text.data(), text.size());
        p[text.size() + 1] = '"';
        return;
    }
    out.push_back('"');
    const char* run = text.data();  // start of the characters copied as they are
    const char* end = text.data() + text.size();
    for (const char* p = run; p != end; ++p) {
        const char c = *p;
        if (!needs_escape(c)) continue;
        if (static_cast<unsigned char>(c) >= 0x80) {
            // A valid sequence is copied as it is; a byte that starts none becomes U+FFFD (a
            // file name need not be UTF-8).
            const std::size_t length =
                utf8_sequence_length(text, static_cast<std::size_t>(p - text.data()));
            if (length != 0) {
                p += length - 1;
                continue;
            }
            out.append(run, p);
            run = p + 1;
            out.append(kReplacementCharacter);
            continue;
        }
        out.append(run, p);
        run = p + 1;
        switch (c) {
            case '"': out.append(std::string_view("\\\"")); break;
            case '\\': out.append(std::string_view("\\\\")); break;
            case '\n': out.append(std::string_view("\\n")); break;
            case '\r': out.append(std::string_view("\\r")); break;
            case '\t': out.append(std::string_view("\\t")); break;
            default: fmt::format_to(std::back_inserter(out), "\\u{:04x}", static_cast<unsigned>(c));
        }
    }
    out.append(run, end);
    out.push_back('"');
}

}  // namespace dpscope::json
