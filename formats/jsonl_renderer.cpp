// One JSON object a telegram. Every key is present on every line of its bus (null where it does
// not apply); the schema is documented in docs/formats.md per bus and is stable. FC protocol lines
// carry the common keys and an "fc_protocol" object instead of the FDL/DP keys, VLT 2000 lines the
// common keys and a "vlt2000" object. Each protocol's keys are written by its
// <name>_jsonl_keys (formats/protocol_rendering.hpp).
#include "formats/describe.hpp"
#include "formats/json.hpp"
#include "formats/protocol_rendering.hpp"
#include "formats/renderer.hpp"

namespace dpscope {

namespace {

class JsonlRenderer final : public TelegramRenderer {
  public:
    using TelegramRenderer::TelegramRenderer;

    void render(const DecodedTelegram& t, std::span<const Finding> findings) override {
        JsonWriter w(out_.buffer());
        w.begin_object();
        w.key("frame").integer(static_cast<std::int64_t>(t.frame));
        w.key("time");
        json::time(w, t.time_ns);
        w.key("len").integer(static_cast<std::int64_t>(t.bytes.size()));
        render_jsonl_keys(w, t);
        if (t.problems().empty() && findings.empty()) {  // most lines: one copy
            w.members("\"problems\":[],\"findings\":[]");
        } else {
            w.key("problems").begin_array();
            for (const Problem& p : t.problems()) {
                w.begin_object();
                w.key("kind").string(problem_kind_name(p.kind));
                w.key("severity").string(severity_name(problem_severity(p.kind)));
                w.key("offset").integer(p.offset);
                w.key("message").string(problem_message(p));
                w.end_object();
            }
            w.end_array();
            w.key("findings").begin_array();
            for (const Finding& finding : findings)
                json::finding(w, finding);
            w.end_array();
        }
        w.end_object();
        out_.put('\n');
        out_.end_record();
    }

    // A last line for findings that belong to no telegram:
    // {"end_of_capture":true,"findings":[...]}.
    void render_end_findings(std::span<const Finding> findings) override {
        if (findings.empty()) return;
        JsonWriter w(out_.buffer());
        w.begin_object();
        w.key("end_of_capture").boolean(true);
        w.key("findings").begin_array();
        for (const Finding& f : findings)
            json::finding(w, f);
        w.end_array();
        w.end_object();
        out_.put('\n');
        out_.end_record();
    }

  private:
};

}  // namespace

std::unique_ptr<TelegramRenderer> make_jsonl_renderer(Output& out) {
    return std::make_unique<JsonlRenderer>(out);
}

}  // namespace dpscope
