// The PROFIBUS DP configuration rule (config_mismatch): a Data_Exchange telegram must carry as
// many output (request) or input (response) bytes as the slave's configuration announced, in
// its Chk_Cfg request or Get_Cfg response. docs/protocol/fdl-and-dp.md.
#pragma once

#include <cstddef>

#include "core/finding_list.hpp"
#include "core/telegram.hpp"

namespace dpscope {

// The lengths already reported on one channel, kept by the caller: a length that disagrees is
// reported once until the lengths agree again (the length + 1; 0: they agree).
struct ConfigCheckState {
    std::size_t output_mismatch = 0;
    std::size_t input_mismatch = 0;
};

// Reports a length that disagrees with what the configuration announced.
void check_announced_lengths(ConfigCheckState& state, const DecodedTelegram& t, FindingList& out);

// config_mismatch, for an intact Data_Exchange telegram whose layout a configuration announced.
// Inline for the usual case: a layout no configuration announced is not checked.
inline void check_config(ConfigCheckState& state, const DecodedTelegram& t, FindingList& out) {
    if (t.dp.ppo.source == PpoSource::ChkCfg || t.dp.ppo.source == PpoSource::GetCfg)
        check_announced_lengths(state, t, out);
}

}  // namespace dpscope
