#include "formats/json.hpp"

#include "formats/describe.hpp"

namespace dpscope::json {

void time(JsonWriter& w, std::int64_t time_ns) {
    if (time_ns == kNoTime)
        w.null();
    else
        w.epoch_seconds(time_ns);
}

void finding(JsonWriter& w, const Finding& f) {
    w.begin_object();
    w.key("kind").name(finding_kind_name(f.kind));
    w.key("severity").name(severity_name(f.severity));
    w.key("frame").integer(static_cast<std::int64_t>(f.frame));
    w.key("request_frame")
        .optional_integer(f.request_frame != 0, static_cast<std::int64_t>(f.request_frame));
    w.key("time");
    time(w, f.time_ns);
    w.key("master").optional_integer(f.has_stations, f.master);
    w.key("slave").optional_integer(f.has_stations, f.slave);
    w.key("pnu").optional_integer(f.pnu.has_value(), f.pnu.value_or(0));
    w.key("message").string(f.message);
    w.end_object();
}

void finding_kind_counts(JsonWriter& w,
                         const std::array<std::uint64_t, kFindingKindCount>& counts) {
    w.begin_object();
    for (std::size_t i = 0; i < kFindingKindCount; ++i)
        w.key(finding_kind_name(static_cast<FindingKind>(i)))
            .integer(static_cast<std::int64_t>(counts[i]));
    w.end_object();
}

}  // namespace dpscope::json
