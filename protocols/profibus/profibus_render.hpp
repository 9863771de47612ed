// The parts of PROFIBUS DP's rendering that have files of their own (protocols/profibus/
// profibus_render.cpp holds the rest and the ProtocolRendering record).
#pragma once

#include "core/telegram.hpp"
#include "formats/describe.hpp"
#include "formats/json_writer.hpp"

namespace dpscope {

// The verbose tree of an FDL telegram and its DP service (profibus_verbose_render.cpp).
void profibus_verbose(TextBuffer& b, const DecodedTelegram& t);
// The jsonl keys of a DP telegram between "len" and "problems" (profibus_jsonl_render.cpp).
void profibus_jsonl_keys(JsonWriter& w, const DecodedTelegram& t);

}  // namespace dpscope
