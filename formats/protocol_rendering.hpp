// How each protocol's telegrams are written in the telegram formats (text, verbose, jsonl, csv):
// the part of each format that differs by protocol, one record per protocol. Each protocol fills
// in its record in its folder (protocols/<name>/<name>_render.cpp, `<name>_rendering()`); the
// renderers look the telegram's protocol up here instead of switching on it. The table is made
// from the registration list (protocols/protocol_list.hpp): formats/protocol_renderings.cpp.
#pragma once

#include "core/telegram.hpp"
#include "formats/describe.hpp"
#include "formats/json_writer.hpp"

namespace dpscope {

struct ProtocolRendering {
    Protocol protocol;
    // The text format's line after the frame and time: source → destination, frame type,
    // service, req|rsp, detail (the problems and findings follow, the same for every protocol).
    void (*text_columns)(TextBuffer& b, const DecodedTelegram& t);
    // The verbose format's field tree between the frame's bytes and its problems.
    void (*verbose)(TextBuffer& b, const DecodedTelegram& t);
    // The jsonl keys between "len" and "problems" (the schema per bus is in README.md).
    void (*jsonl_keys)(JsonWriter& w, const DecodedTelegram& t);
    // The csv columns frame .. detail, each followed by its comma.
    void (*csv_columns)(TextBuffer& b, const DecodedTelegram& t);
};

// The rendering of a protocol.
const ProtocolRendering& protocol_rendering(Protocol protocol) noexcept;

// Each protocol's rendering, by the name its line in protocols/protocol_list.hpp gives it.
#define DPSCOPE_PROTOCOL_RENDERING(Enum, name, Payload, member) \
    const ProtocolRendering& name##_rendering() noexcept;
DPSCOPE_PROTOCOLS(DPSCOPE_PROTOCOL_RENDERING)
#undef DPSCOPE_PROTOCOL_RENDERING

}  // namespace dpscope
