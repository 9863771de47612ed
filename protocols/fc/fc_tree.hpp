// The FC protocol subtree of the dissector (fc_tree.cpp).
#pragma once

#include "core/telegram.hpp"
#include "wireshark/tree.hpp"

namespace dpscope::wireshark {

// The FC telegram: STX, LGE, ADR, the PKW (PKE, IND, PWE or text), PCD 1 and 2, BCC.
void add_fc(const Tree& top, const DecodedTelegram& t);

}  // namespace dpscope::wireshark
