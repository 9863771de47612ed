#include "protocols/profibus/gsd/gsd_rules.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <string>

#include "core/counted.hpp"

namespace dpscope {

namespace {

// PROFIBUS sends 11 bits a character (start, 8 data, even parity, stop).
constexpr std::uint64_t kBitsPerCharacter = 11;

Finding& add(FindingList& out, GsdCheckStats& stats, FindingKind kind, const DecodedTelegram& t,
             std::uint64_t request_frame = 0) {
    ++stats.broken[gsd_rule_index(kind)];
    return add_finding(out, kind, t.frame, t.time_ns, request_frame, true, t.master, t.slave);
}

void judged(GsdCheckStats& stats, FindingKind kind) noexcept {
    ++stats.judged[gsd_rule_index(kind)];
}

void check_ident(GsdCheckState& state, const DecodedTelegram& t, std::uint16_t ident,
                 std::string_view where, FindingList& out) {
    const GsdDevice& device = *t.dp.device;
    if (!device.ident_number) return;
    judged(state.stats, FindingKind::GsdIdentMismatch);
    if (ident == *device.ident_number) return;
    add(out, state.stats, FindingKind::GsdIdentMismatch, t).message =
        fmt::format("{} of slave {} carries ident 0x{:04X}; its GSD {} ({}) is for 0x{:04X}", where,
                    t.slave, ident, device.file, gsd_device_title(device), *device.ident_number);
}

void check_config(GsdCheckState& state, const DecodedTelegram& t, FindingList& out) {
    const GsdDevice& device = *t.dp.device;
    const DpServiceData& data = t.dp.service_data;
    const std::vector<CfgModule>* modules = data.cfg_modules();
    if (!modules) return;
    const std::string_view what = t.dp.service == Service::ChkCfg ? "Chk_Cfg" : "Get_Cfg";
    const std::span<const GsdModuleMatch> matches = data.gsd_modules();
    if (!device.modules.empty()) {
        judged(state.stats, FindingKind::GsdUnknownModule);
        std::string unknown;
        for (const GsdModuleMatch& m : matches) {
            if (m.module) continue;
            if (!unknown.empty()) unknown += ", ";
            const Bytes bytes = t.bytes.subspan(m.offset, m.length);
            for (std::size_t i = 0; i < bytes.size(); ++i)
                unknown += fmt::format("{}{:02X}", i ? " " : "", bytes[i]);
            unknown += fmt::format(" (slot {})", m.first_identifier);
        }
        if (!unknown.empty())
            add(out, state.stats, FindingKind::GsdUnknownModule, t).message =
                fmt::format("{} to slave {}: no module of its GSD {} has the identifiers {}", what,
                            t.slave, device.file, unknown);
    }
    std::uint32_t inputs = 0;
    std::uint32_t outputs = 0;
    for (const CfgModule& m : *modules) {
        inputs += m.input_bytes();
        outputs += m.output_bytes();
    }
    std::string over;
    auto limit = [&](std::optional<std::uint32_t> max, std::uint64_t value, std::string_view name,
                     std::string_view unit) {
        if (!max) return;
        if (value > *max)
            over += fmt::format("{}{} {} (GSD {} {})", over.empty() ? "" : ", ", value, unit, name,
                                *max);
    };
    const bool any =
        device.max_module || device.max_input_len || device.max_output_len || device.max_data_len;
    if (!any) return;
    judged(state.stats, FindingKind::GsdConfigLimit);
    // Modules: the runs of identifiers, a free place (0x00, no data) not counted.
    std::uint64_t module_count = 0;
    if (matches.empty()) {
        for (const CfgModule& m : *modules)
            module_count += m.free_place ? 0 : 1;
    } else {
        for (const GsdModuleMatch& m : matches) {
            const Bytes bytes = t.bytes.subspan(m.offset, m.length);
            module_count += m.module || std::any_of(bytes.begin(), bytes.end(),
                                                    [](std::uint8_t b) { return b != 0; });
        }
    }
    limit(device.max_module, module_count, "Max_Module", "modules");
    limit(device.max_input_len, inputs, "Max_Input_Len", "input bytes");
    limit(device.max_output_len, outputs, "Max_Output_Len", "output bytes");
    limit(device.max_data_len, std::uint64_t{inputs} + outputs, "Max_Data_Len", "data bytes");
    if (!over.empty())
        add(out, state.stats, FindingKind::GsdConfigLimit, t).message =
            fmt::format("{} to slave {} asks more than its GSD {} allows: {}", what, t.slave,
                        device.file, over);
}

void check_user_prm(GsdCheckState& state, const DecodedTelegram& t, FindingList& out) {
    const GsdDevice& device = *t.dp.device;
    const GsdPrmReading* reading = t.dp.service_data.gsd_prm();
    if (!reading) return;
    // The length: when the GSD says it (User_Prm_Data_Len, or parameter blocks), and the
    // modules' parameters are known where modules have any.
    bool modules_have_prm = false;
    for (const GsdModule& m : device.modules)
        modules_have_prm = modules_have_prm || !m.prm_refs.empty() || !m.prm_consts.empty();
    const bool described = device.user_prm_data_len || !device.prm_refs.empty() ||
                           !device.prm_consts.empty() || !device.user_prm_data.empty();
    const std::size_t actual = t.dp.fdl.du.size() > 7 ? t.dp.fdl.du.size() - 7 : 0;
    if (described && (!modules_have_prm || reading->modules_known)) {
        judged(state.stats, FindingKind::GsdUserPrmLength);
        if (actual != reading->described_length)
            add(out, state.stats, FindingKind::GsdUserPrmLength, t).message = fmt::format(
                "Set_Prm to slave {} carries {} of user parameters; its GSD {} describes {}",
                t.slave, counted(actual, "byte", "bytes"), device.file, reading->described_length);
    } else if (device.max_user_prm_data_len) {
        judged(state.stats, FindingKind::GsdUserPrmLength);
        if (actual > *device.max_user_prm_data_len)
            add(out, state.stats, FindingKind::GsdUserPrmLength, t).message = fmt::format(
                "Set_Prm to slave {} carries {} of user parameters; its GSD {} allows at most {} "
                "(Max_User_Prm_Data_Len)",
                t.slave, counted(actual, "byte", "bytes"), device.file,
                *device.max_user_prm_data_len);
    }
    if (reading->values.empty()) return;
    judged(state.stats, FindingKind::GsdUserPrmRange);
    std::string bad;
    for (const GsdPrmValue& v : reading->values) {
        if (v.in_range) continue;
        if (!bad.empty()) bad += ", ";
        if (v.prm->allowed.empty())
            bad += fmt::format("\"{}\" = {} (allowed {} to {})", v.prm->name, v.value,
                               v.prm->min_value, v.prm->max_value);
        else
            bad += fmt::format("\"{}\" = {} (allowed {})", v.prm->name, v.value,
                               fmt::join(v.prm->allowed, ", "));
    }
    if (!bad.empty())
        add(out, state.stats, FindingKind::GsdUserPrmRange, t).message = fmt::format(
            "Set_Prm to slave {}: user parameters outside their GSD values: {}", t.slave, bad);
}

void check_diag_length(GsdCheckState& state, const DecodedTelegram& t, FindingList& out) {
    const GsdDevice& device = *t.dp.device;
    if (!device.max_diag_data_len || !t.dp.service_data.slave_diag()) return;
    judged(state.stats, FindingKind::GsdDiagTooLong);
    const std::size_t length = t.dp.fdl.du.size();
    if (length > *device.max_diag_data_len)
        add(out, state.stats, FindingKind::GsdDiagTooLong, t).message = fmt::format(
            "slave {} sent {} of diagnosis; its GSD {} says at most {} (Max_Diag_Data_Len)",
            t.slave, counted(length, "byte", "bytes"), device.file, *device.max_diag_data_len);
}

void check_timing(GsdCheckState& state, const DecodedTelegram& t, const GsdLine& line, bool retry,
                  FindingList& out) {
    GsdCheckStats& stats = state.stats;
    const GsdDevice& device = *t.dp.device;
    if (t.direction == Direction::Request) {
        state.request_frame = 0;
        if (!t.dp.fdl.has_fc || !function_expects_reply(t.dp.fdl.fc.function())) return;
        state.request_frame = t.frame;
        state.request_end_ns =
            t.has_time() && line.character_fs != 0
                ? t.time_ns + static_cast<std::int64_t>(
                                  (t.bytes.size() * line.character_fs + 500'000) / 1'000'000)
                : kNoTime;
        // Polls: Data_Exchange requests, a retry no new one.
        if (t.dp.service != Service::DataExchange || retry || !t.has_time()) return;
        if (device.min_slave_interval && state.last_poll_ns != kNoTime) {
            const auto interval = static_cast<std::uint64_t>(
                std::max<std::int64_t>(0, t.time_ns - state.last_poll_ns));
            stats.min_slave_interval_ns = std::uint64_t{*device.min_slave_interval} * 100'000;
            stats.poll_interval_ns.add(interval);
            judged(stats, FindingKind::GsdPollInterval);
            if (interval < stats.min_slave_interval_ns) {
                if (!state.fast_run)
                    add(out, stats, FindingKind::GsdPollInterval, t).message = fmt::format(
                        "slave {} polled {:.3f} ms after its last poll; its GSD {} asks for at "
                        "least {:.1f} ms (Min_Slave_Intervall {})",
                        t.slave, static_cast<double>(interval) / 1e6, device.file,
                        static_cast<double>(stats.min_slave_interval_ns) / 1e6,
                        *device.min_slave_interval);
                else
                    ++stats.broken[gsd_rule_index(FindingKind::GsdPollInterval)];
                state.fast_run = true;
            } else {
                state.fast_run = false;
            }
        }
        state.last_poll_ns = t.time_ns;
        return;
    }
    if (t.request_frame == 0 || t.request_frame != state.request_frame) return;
    state.request_frame = 0;
    if (!t.has_time() || state.request_end_ns == kNoTime || line.baud == 0) return;
    const auto answer =
        static_cast<std::uint64_t>(std::max<std::int64_t>(0, t.time_ns - state.request_end_ns));
    stats.response_ns.add(answer);
    stats.response_sum_ns += answer;
    if (!state.max_tsdr_read) {
        // MaxTsdr at the line's rate, worked out once.
        state.max_tsdr_read = true;
        if (const std::optional<std::uint32_t> bits = device.max_tsdr_at(line.rate))
            stats.max_tsdr_ns = std::uint64_t{*bits} * 1'000'000'000ULL / line.baud;
    }
    if (stats.max_tsdr_ns == 0) return;
    judged(stats, FindingKind::GsdLateResponse);
    if (answer <= stats.max_tsdr_ns) {
        state.late_run = false;
        return;
    }
    if (state.late_run) {
        ++stats.broken[gsd_rule_index(FindingKind::GsdLateResponse)];
        return;
    }
    state.late_run = true;
    add(out, stats, FindingKind::GsdLateResponse, t, t.request_frame).message = fmt::format(
        "slave {} answered frame {} after {:.1f} us; its GSD {} gives MaxTsdr {} bit times at {} "
        "baud ({:.1f} us)",
        t.slave, t.request_frame, static_cast<double>(answer) / 1e3, device.file,
        device.max_tsdr_at(line.rate).value_or(0), line.baud,
        static_cast<double>(stats.max_tsdr_ns) / 1e3);
}

}  // namespace

std::string_view gsd_rate_name(std::uint32_t baud) noexcept {
    switch (baud) {
        case 9'600: return "9.6";
        case 19'200: return "19.2";
        case 31'250: return "31.25";
        case 45'450: return "45.45";
        case 93'750: return "93.75";
        case 187'500: return "187.5";
        case 500'000: return "500";
        case 1'500'000: return "1.5M";
        case 3'000'000: return "3M";
        case 6'000'000: return "6M";
        case 12'000'000: return "12M";
        default: return "";
    }
}

GsdLine gsd_line(std::uint32_t baud) noexcept {
    GsdLine line;
    line.baud = baud;
    if (baud == 0) return line;
    line.character_fs = kBitsPerCharacter * 1'000'000'000'000'000ULL / baud;
    line.rate = gsd_rate_name(baud);
    return line;
}

void check_gsd(GsdCheckState& state, const DecodedTelegram& t, const GsdLine& line, bool retry,
               FindingList& out) {
    state.stats.device = t.dp.device;
    const DpServiceData& data = t.dp.service_data;
    switch (t.dp.service) {
        case Service::SetPrm:
            if (const SetPrm* prm = data.set_prm()) {
                check_ident(state, t, prm->ident, "Set_Prm", out);
                check_user_prm(state, t, out);
            }
            break;
        case Service::SlaveDiag:
            if (const SlaveDiag* diag = data.slave_diag()) {
                check_ident(state, t, diag->ident, "Slave_Diag", out);
                check_diag_length(state, t, out);
            }
            break;
        case Service::ChkCfg:
        case Service::GetCfg: check_config(state, t, out); break;
        default: break;
    }
    check_timing(state, t, line, retry, out);
}

}  // namespace dpscope
