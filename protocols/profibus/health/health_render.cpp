// The figures and words every bus-health format and its users share
// (protocols/profibus/health/health_render.hpp); the formats themselves are
// protocols/profibus/health/health_json_render.cpp, health_text_render.cpp and the others it names.
#include "protocols/profibus/health/health_render.hpp"

namespace dpscope::health {

std::string ms(double ns) { return fmt::format("{:.3f}", ns / 1e6); }

std::string when(std::int64_t time_ns, std::uint64_t frame) {
    if (time_ns == kNoTime) return fmt::format("frame {}", frame);
    TextBuffer b;
    append_iso_time(b, time_ns);
    return fmt::to_string(b);
}

std::string reasons_text(const Judgement& judgement, const HealthThresholds& thresholds) {
    std::string text;
    for (const VerdictReason& reason : judgement.reasons) {
        if (!text.empty()) text += "; ";
        text += describe_reason(reason, thresholds);
    }
    return text;
}

std::string segment_cause(const BusHealth& h) {
    const Verdict verdict = h.segment.judgement.verdict;
    for (const VerdictReason& reason : h.segment.judgement.reasons)
        if (reason.verdict == verdict) return "";  // its own reasons say it
    std::string text;
    auto add = [&](std::string_view who) {
        text += text.empty() ? "from " : ", ";
        text += who;
    };
    for (const StationHealth& s : h.stations)
        if (verdict != Verdict::Good && s.judgement.verdict == verdict)
            add(fmt::format("station {} ({})", s.address, station_role_name(s.role)));
    for (const MasterHealth& m : h.masters)
        if (verdict != Verdict::Good && m.judgement.verdict == verdict)
            add(fmt::format("master {} (token and cycle)", m.address));
    return text;
}

bool in_slave_table(const StationHealth& s) {
    return s.role != StationRole::Master || s.requests > 0 || s.answers > 0;
}

bool differs_from_default(const HealthThresholds& thresholds, HealthThreshold kind) {
    static const HealthThresholds defaults;
    return thresholds.get(kind) != defaults.get(kind);
}

}  // namespace dpscope::health
