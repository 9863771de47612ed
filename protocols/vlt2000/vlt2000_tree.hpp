// The VLT 2000 subtree of the dissector (vlt2000_tree.cpp).
#pragma once

#include "core/telegram.hpp"
#include "wireshark/tree.hpp"

namespace dpscope::wireshark {

// The VLT 2000 telegram: start, address, control letter, control/status word, parameter, value,
// decimal position, checksum, stop.
void add_vlt2000(const Tree& top, const DecodedTelegram& t);

}  // namespace dpscope::wireshark
