#include "formats/json.hpp"

#include "formats/describe.hpp"

namespace dpscope::json {

void time(fmt::memory_buffer& out, std::int64_t time_ns) {
    if (time_ns == kNoTime)
        null(out);
    else
        append_epoch_seconds(out, time_ns);
}

void finding(fmt::memory_buffer& out, const Finding& f) {
    raw(out, "{\"kind\":");
    string(out, finding_kind_name(f.kind));
    raw(out, ",\"severity\":");
    string(out, severity_name(f.severity));
    raw(out, ",\"frame\":");
    integer(out, static_cast<std::int64_t>(f.frame));
    raw(out, ",\"request_frame\":");
    if (f.request_frame != 0)
        integer(out, static_cast<std::int64_t>(f.request_frame));
    else
        null(out);
    raw(out, ",\"time\":");
    time(out, f.time_ns);
    raw(out, ",\"master\":");
    if (f.has_stations)
        integer(out, f.master);
    else
        null(out);
    raw(out, ",\"slave\":");
    if (f.has_stations)
        integer(out, f.slave);
    else
        null(out);
    raw(out, ",\"pnu\":");
    if (f.pnu)
        integer(out, *f.pnu);
    else
        null(out);
    raw(out, ",\"message\":");
    string(out, f.message);
    out.push_back('}');
}

}  // namespace dpscope::json
