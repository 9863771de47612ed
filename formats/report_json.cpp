// The JSON report (schema in docs/formats.md, stable): one object, the findings all listed.
#include "formats/json.hpp"
#include "formats/report_model.hpp"
#include "protocols/profibus/health/health_render.hpp"

namespace dpscope::report {

void write_json(const ReportContext& c, const ReportModel& m, Output& out) {
    JsonWriter w(out.buffer());
    auto count = [&w](std::string_view key, std::uint64_t n) {
        w.key(key).integer(static_cast<std::int64_t>(n));
    };
    const TelegramTracker& tracker = *c.tracker;
    w.begin_object();
    w.key("dpscope").string(c.version);
    w.key("input").begin_object();
    w.key("file").string(c.input.name);
    w.key("format").string(c.input.format);
    w.key("damaged").boolean(c.input.damaged);
    count("bytes_skipped", c.input.bytes_skipped);
    w.key("first_time");
    json::time(w, c.summary->first_time_ns());
    w.key("last_time");
    json::time(w, c.summary->last_time_ns());
    w.end_object();
    w.key("options").begin_object();
    // An FC or VLT 2000 report names its bus and its bus's own options; a PROFIBUS DP report has
    // always been without them.
    const BusWording& bus = bus_wording(c);
    if (!bus.option.empty()) w.key("bus").string(bus.option);
    w.key("timeout_ms").integer(tracker.timeout_ns() / 1'000'000);
    if (const auto write_options = report_of(c).write_json_options) write_options(c, w);
    w.key("strict").boolean(tracker.strict());
    w.key("fail_on").string(fail_on_name(c.fail_on));
    w.key("allow_empty").boolean(c.allow_empty);
    w.key("stations");
    if (c.stations.empty()) {
        w.null();
    } else {
        w.begin_array();
        for (std::uint8_t station : c.stations)
            w.integer(station);
        w.end_array();
    }
    // Only when given: the reports of every capture without -Y stay as they were.
    if (!c.display_filter.empty()) w.key("display_filter").string(c.display_filter);
    w.end_object();
    w.key("result").string(m.fails ? "fail" : "pass");
    w.key("nothing_checked").boolean(m.nothing_checked);
    w.key("summary").begin_object();
    count("telegrams", c.summary->telegrams());
    count(bus.checksum_key, m.fcs_errors);
    count("transactions", m.transactions);
    w.key("findings").begin_object();
    count("error", m.errors());
    count("warning", m.warnings());
    count("note", m.notes());
    w.end_object();
    w.end_object();
    w.key("stations").begin_array();
    for (const auto& section : m.stations) {
        section->write_json(c, w);
        w.settle();
        out.end_record();
    }
    w.end_array();
    w.key("bus").begin_object();
    // Telegrams no station can be named for: the bus's kinds (a DP-V1 rule always has one).
    w.key("findings").begin_object();
    for (FindingKind kind : kAllKinds)
        if (is_bus_kind(c, kind))
            w.key(finding_kind_name(kind))
                .integer(static_cast<std::int64_t>(
                    bus_stats(c).findings[static_cast<std::size_t>(kind)]));
    w.end_object();
    w.end_object();
    if (c.health) {
        // The same objects as `dpscope stats -T json` ("stats JSON" in docs/formats.md).
        w.key("bus_health").begin_object();
        health::write_json_members(w, *c.health);
        w.end_object();
        w.settle();
        out.end_record();
    }
    w.key("findings").begin_array();
    c.findings->for_each([&](const Finding& f) {
        if (!shows(c, f)) return;
        json::finding(w, f);
        w.settle();
        out.end_record();
    });
    w.end_array();
    // What the list lacks (a full temporary folder), after listing: null when it is complete.
    w.key("findings_not_listed");
    if (c.findings->unlisted() == 0 && c.findings->lost().empty()) {
        w.null();
    } else {
        w.begin_object();
        count("count", c.findings->unlisted());
        w.key("reason").string(c.findings->lost());
        w.end_object();
    }
    w.end_object();
    out.put('\n');
    out.end_record();
}

}  // namespace dpscope::report
