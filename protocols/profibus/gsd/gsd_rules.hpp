// The GSD rules: a PROFIBUS DP slave checked against its own GSD file (issue 29; docs/gsd.md).
// The decoder matched the slave to its GSD and read its management telegrams by it
// (DpTelegram::device, DpServiceData::gsd_*); these rules judge what it read:
//  - gsd_ident_mismatch: a Set_Prm or Slave_Diag with another Ident_Number than the GSD's;
//  - gsd_unknown_module: Chk_Cfg / Get_Cfg identifiers no module of the GSD has;
//  - gsd_config_limit: more modules than Max_Module, more input, output or data bytes than
//    Max_Input_Len, Max_Output_Len, Max_Data_Len;
//  - gsd_user_prm_length: Set_Prm user parameter bytes other than the GSD describes;
//  - gsd_user_prm_range: a user parameter outside the values its ExtUserPrmData allows;
//  - gsd_diag_too_long: a Slave_Diag answer longer than Max_Diag_Data_Len;
//  - gsd_late_response: an answer later than MaxTsdr at the line's baud rate (with times and
//    the baud rate known); the first of a run of late answers is reported, all are counted;
//  - gsd_poll_interval: Data_Exchange requests closer than Min_Slave_Intervall (the first of a
//    run reported, all counted).
// No I/O; the state is a few numbers per channel.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "core/finding_list.hpp"
#include "core/log_histogram.hpp"
#include "core/telegram.hpp"
#include "core/time.hpp"

namespace dpscope {

inline constexpr std::size_t kGsdCheckCount = 8;  // the kinds above, in FindingKind order
inline constexpr FindingKind kFirstGsdKind = FindingKind::GsdIdentMismatch;
// The kinds of the GSD rules (component DeviceDescription), in FindingKind order.
inline constexpr std::array<FindingKind, kGsdCheckCount> kGsdKinds = [] {
    std::array<FindingKind, kGsdCheckCount> kinds{};
    for (std::size_t i = 0; i < kGsdCheckCount; ++i)
        kinds[i] = static_cast<FindingKind>(static_cast<std::size_t>(kFirstGsdKind) + i);
    return kinds;
}();
// The index of a GSD rule's kind in kGsdKinds and GsdCheckStats' arrays.
constexpr std::size_t gsd_rule_index(FindingKind kind) noexcept {
    return static_cast<std::size_t>(kind) - static_cast<std::size_t>(kFirstGsdKind);
}

// What the rules found about one slave (the report's "device" part).
struct GsdCheckStats {
    const GsdDevice* device = nullptr;  // its GSD (null: none matched)
    // Per rule (FindingKind - kFirstGsdKind): telegrams it judged, and how many broke it.
    std::array<std::uint64_t, kGsdCheckCount> judged{};
    std::array<std::uint64_t, kGsdCheckCount> broken{};
    std::uint64_t judged_by(FindingKind kind) const noexcept {
        return judged[gsd_rule_index(kind)];
    }
    std::uint64_t broken_by(FindingKind kind) const noexcept {
        return broken[gsd_rule_index(kind)];
    }
    // The slave's answer times (from the end of the request to the answer's first byte), in ns,
    // when times and the baud rate are known; and MaxTsdr at that rate in ns (0: not known).
    LogHistogram response_ns;
    std::uint64_t response_sum_ns = 0;
    std::uint64_t max_tsdr_ns = 0;
    // Data_Exchange poll intervals, in ns.
    LogHistogram poll_interval_ns;
    std::uint64_t min_slave_interval_ns = 0;
};

// What the rules remember of one channel between telegrams.
struct GsdCheckState {
    GsdCheckStats stats;
    std::uint64_t request_frame = 0;  // the last request that expects an answer
    std::int64_t request_end_ns = kNoTime;
    std::int64_t last_poll_ns = kNoTime;
    bool late_run = false;  // in a run of late answers (reported at its first)
    bool fast_run = false;  // in a run of polls too close
    bool max_tsdr_read = false;  // stats.max_tsdr_ns is worked out (0: the GSD gives none)
};

// The line as the rules need it: its baud rate (0: not known, no timing rule), and what follows
// from it, worked out once (gsd_line()).
struct GsdLine {
    std::uint32_t baud = 0;
    std::uint64_t character_fs = 0;  // a character's time (11 bits) in femtoseconds
    std::string_view rate;  // as MaxTsdr_<rate> writes it ("1.5M"); "" for no PROFIBUS rate
};
GsdLine gsd_line(std::uint32_t baud) noexcept;

// Judges an intact telegram of a slave that has a GSD (t.dp.device). `retry`: a Data_Exchange
// request repeated with the same FCB (no new poll).
void check_gsd(GsdCheckState& state, const DecodedTelegram& t, const GsdLine& line, bool retry,
               FindingList& out);

// "12M", "1.5M", "187.5", "9.6": how a GSD writes the baud rate in MaxTsdr_<rate>; "" for a
// rate PROFIBUS does not have.
std::string_view gsd_rate_name(std::uint32_t baud) noexcept;

}  // namespace dpscope
