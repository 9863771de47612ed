// The PROFIBUS subtrees of the dissector: the FDL telegram and its DP service (profibus_tree.cpp).
#pragma once

#include "core/telegram.hpp"
#include "wireshark/tree.hpp"

namespace dpscope::wireshark {

// The FDL telegram: start delimiter, lengths, addresses, frame control, SAPs, FCS.
void add_fdl(const Tree& top, const DecodedTelegram& t);

// The DP service and its data: PPO, PCV and PCD of a Data_Exchange, diagnosis, parameters,
// configuration, Global_Control, Set_Slave_Add, DP-V1 with its PROFIdrive parameter access.
void add_dp(const Tree& top, const DecodedTelegram& t);

}  // namespace dpscope::wireshark
