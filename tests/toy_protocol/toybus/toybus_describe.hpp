// How a toybus telegram is worded for a person; the renderers and the Wireshark tree use it.
#pragma once

#include <string>
#include <string_view>

#include "formats/describe.hpp"

namespace dpscope {

// "read", "write", "value", "error", "unknown".
std::string_view toybus_kind_name(ToybusKind kind) noexcept;
// The lead character with its kind: "? read", "= value".
std::string toybus_kind_text(const ToybusTelegram& v);
// The detail column: "parameter 0100", "parameter 0100 = 01234", "parameter 0100 error 05";
// "answers frame N" where it is a response paired with its request.
void append_toybus_detail(TextBuffer& out, const DecodedTelegram& t);

}  // namespace dpscope
