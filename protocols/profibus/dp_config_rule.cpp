#include "protocols/profibus/dp_config_rule.hpp"

#include <fmt/format.h>

#include "core/counted.hpp"

namespace dpscope {

void check_announced_lengths(ConfigCheckState& state, const DecodedTelegram& t, FindingList& out) {
    const PpoLayout& ppo = t.dp.ppo;
    const bool request = t.direction == Direction::Request;
    const std::size_t actual = t.dp.fdl.du.size();
    // A response without data (SC, or a status such as RS after a restart) carries no inputs to
    // measure.
    if (!request && actual == 0) return;
    const std::size_t expected = request ? ppo.output_bytes : ppo.input_bytes;
    std::size_t& reported = request ? state.output_mismatch : state.input_mismatch;
    if (actual == expected) {
        reported = 0;
        return;
    }
    if (reported == actual + 1) return;  // already reported for this length
    reported = actual + 1;
    add_finding(out, FindingKind::ConfigMismatch, t.frame, t.time_ns, 0, t.has_roles, t.master,
                t.slave)
        .message = fmt::format("Data_Exchange {} carries {}; the {} in frame {} announced {}",
                               request ? "request" : "response", counted(actual, "byte", "bytes"),
                               ppo.source == PpoSource::ChkCfg ? "Chk_Cfg" : "Get_Cfg response",
                               t.dp.ppo_cfg_frame, expected);
}

}  // namespace dpscope
