// How each protocol's telegrams are written in the telegram formats (text, verbose, jsonl, csv):
// the part of each format that differs by protocol. Each protocol writes its part next to its
// decoder (protocols/<name>/<name>_render.cpp and the files beside it), in four functions named
// after its line in the registration list (protocols/protocol_list.hpp):
//   <name>_text_columns   the text line after the frame and time: source -> destination, frame
//                         type, service, req|rsp, detail (problems and findings follow, the same
//                         for every protocol)
//   <name>_verbose        the verbose tree between the frame's bytes and its problems
//   <name>_jsonl_keys     the jsonl keys between "len" and "problems" (schema: docs/formats.md)
//   <name>_csv_columns    the csv columns frame .. detail, each followed by its comma
// The renderers call them through the dispatchers below, made from the list: a direct call per
// protocol, which link-time optimisation can inline (through a table of function pointers the
// jsonl renderer took a fifth longer: the writer's state could no longer stay in registers).
// A protocol without one of them fails to link, naming it.
#pragma once

#include "core/telegram.hpp"
#include "formats/describe.hpp"
#include "formats/json_writer.hpp"

namespace dpscope {

#define DPSCOPE_PROTOCOL_RENDERING(Enum, name, Payload, member)                 \
    void name##_text_columns(TextBuffer& b, const DecodedTelegram& t);          \
    void name##_verbose(TextBuffer& b, const DecodedTelegram& t);               \
    void name##_jsonl_keys(JsonWriter& w, const DecodedTelegram& t);            \
    void name##_csv_columns(TextBuffer& b, const DecodedTelegram& t);
DPSCOPE_PROTOCOLS(DPSCOPE_PROTOCOL_RENDERING)
#undef DPSCOPE_PROTOCOL_RENDERING

// The telegram's protocol's part of each format.
#define DPSCOPE_PROTOCOL_DISPATCH(Enum, name, Payload, member, part, ...) \
    if (t.protocol == Protocol::Enum) return name##_##part(__VA_ARGS__);

inline void render_text_columns(TextBuffer& b, const DecodedTelegram& t) {
#define DPSCOPE_TEXT(Enum, name, Payload, member) \
    DPSCOPE_PROTOCOL_DISPATCH(Enum, name, Payload, member, text_columns, b, t)
    DPSCOPE_PROTOCOLS(DPSCOPE_TEXT)
#undef DPSCOPE_TEXT
}

inline void render_verbose(TextBuffer& b, const DecodedTelegram& t) {
#define DPSCOPE_VERBOSE(Enum, name, Payload, member) \
    DPSCOPE_PROTOCOL_DISPATCH(Enum, name, Payload, member, verbose, b, t)
    DPSCOPE_PROTOCOLS(DPSCOPE_VERBOSE)
#undef DPSCOPE_VERBOSE
}

inline void render_jsonl_keys(JsonWriter& w, const DecodedTelegram& t) {
#define DPSCOPE_JSONL(Enum, name, Payload, member) \
    DPSCOPE_PROTOCOL_DISPATCH(Enum, name, Payload, member, jsonl_keys, w, t)
    DPSCOPE_PROTOCOLS(DPSCOPE_JSONL)
#undef DPSCOPE_JSONL
}

inline void render_csv_columns(TextBuffer& b, const DecodedTelegram& t) {
#define DPSCOPE_CSV(Enum, name, Payload, member) \
    DPSCOPE_PROTOCOL_DISPATCH(Enum, name, Payload, member, csv_columns, b, t)
    DPSCOPE_PROTOCOLS(DPSCOPE_CSV)
#undef DPSCOPE_CSV
}

#undef DPSCOPE_PROTOCOL_DISPATCH

// The jsonl keys every protocol's part holds, in this order: "master" and "slave" (null when the
// telegram's roles are not known) and "request_frame" (the request an answer answers; null for
// none, frame 0 being no telegram's). Always inlined: GCC otherwise kept one copy for the four
// callers, and the call cost PROFIBUS jsonl 0.6 % more instructions.
[[gnu::always_inline]] inline void jsonl_role_keys(JsonWriter& w, const DecodedTelegram& t) {
    w.key("master").optional_integer(t.has_roles, t.master);
    w.key("slave").optional_integer(t.has_roles, t.slave);
    w.key("request_frame")
        .optional_integer(t.request_frame != 0, static_cast<std::int64_t>(t.request_frame));
}

}  // namespace dpscope
