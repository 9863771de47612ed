// The report's "device" part of a PROFIBUS DP slave that has a GSD file (issue 29): which file,
// vendor and model, the modules of its configuration, its answer times against MaxTsdr and its
// polls against Min_Slave_Intervall, and each GSD check run with how often it was broken
// (protocols/profibus/gsd/gsd_rules.hpp). Follows the slave's cyclic and DP-V1 sections.
#pragma once

#include <memory>

#include "formats/report_model.hpp"
#include "protocols/profibus/session_tracker.hpp"

namespace dpscope::report {

// `modules`: the slave's configuration by its GSD (the decoder's; empty when none was seen).
std::unique_ptr<StationSection> make_gsd_section(const ChannelStats& stats,
                                                 std::vector<const GsdModule*> modules);

}  // namespace dpscope::report
