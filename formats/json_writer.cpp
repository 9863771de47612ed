#include "formats/json_writer.hpp"

#include <iterator>

namespace dpscope::json {

namespace {

constexpr bool needs_escape(char c) noexcept {
    return c == '"' || c == '\\' || static_cast<unsigned char>(c) < 0x20;
}

}  // namespace

void string(fmt::memory_buffer& out, std::string_view text) {
    out.push_back('"');
    const char* run = text.data();  // start of the characters copied as they are
    const char* end = text.data() + text.size();
    for (const char* p = run; p != end; ++p) {
        const char c = *p;
        if (!needs_escape(c)) continue;
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
