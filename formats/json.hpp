// Small helpers for writing JSON text straight into a buffer, used by the jsonl renderer and the
// JSON report. Keys are written by the caller as literals; values go through these.
#pragma once

#include <fmt/format.h>

#include <cstdint>
#include <string_view>

#include "decoder/finding.hpp"

namespace dpscope::json {

inline void raw(fmt::memory_buffer& out, std::string_view text) {
    out.append(text.data(), text.data() + text.size());
}

inline void integer(fmt::memory_buffer& out, std::int64_t value) {
    fmt::format_int digits(value);
    out.append(digits.data(), digits.data() + digits.size());
}

inline void boolean(fmt::memory_buffer& out, bool value) { raw(out, value ? "true" : "false"); }

inline void null(fmt::memory_buffer& out) { raw(out, "null"); }

// A JSON string with the required escapes.
inline void string(fmt::memory_buffer& out, std::string_view text) {
    out.push_back('"');
    for (char c : text) {
        switch (c) {
            case '"': raw(out, "\\\""); break;
            case '\\': raw(out, "\\\\"); break;
            case '\n': raw(out, "\\n"); break;
            case '\r': raw(out, "\\r"); break;
            case '\t': raw(out, "\\t"); break;
            default:
                if (static_cast<unsigned char>(c) < 0x20)
                    fmt::format_to(std::back_inserter(out), "\\u{:04x}", static_cast<unsigned>(c));
                else
                    out.push_back(c);
        }
    }
    out.push_back('"');
}

// A finding as an object: kind, severity, frame, request_frame, time, master, slave, pnu,
// message (null where unknown). The same shape in jsonl and in the JSON report.
void finding(fmt::memory_buffer& out, const Finding& f);

// Seconds since the epoch with nanoseconds ("1704067200.000123000"), or null for kNoTime.
void time(fmt::memory_buffer& out, std::int64_t time_ns);

}  // namespace dpscope::json
