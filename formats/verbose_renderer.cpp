// The whole field tree of each telegram, like tshark -V: the frame, its bytes, the protocol's
// fields (each protocol's <name>_verbose, in its folder), problems and findings.
#include <fmt/compile.h>

#include <iterator>

#include "formats/describe.hpp"
#include "formats/protocol_rendering.hpp"
#include "formats/renderer.hpp"
#include "formats/verbose_tree.hpp"

namespace dpscope {

namespace {

class VerboseRenderer final : public TelegramRenderer {
  public:
    using TelegramRenderer::TelegramRenderer;

    void render(const DecodedTelegram& t, std::span<const Finding> findings) override {
        TextBuffer& b = out_.buffer();
        auto it = fmt::appender(b);
        put(b, "Frame ", t.frame, ": ");
        append_counted(b, t.bytes.size(), "byte", "bytes");
        if (t.has_time()) {
            append(b, ", ");
            append_iso_time(b, t.time_ns);
        }
        b.push_back('\n');
        VerboseTree tree(b);
        tree.line(1, "Bytes: ");
        append_hex(b, t.bytes);
        b.push_back('\n');
        render_verbose(b, t);
        if (!t.problems().empty()) {
            append(b, "Problems\n");
            for (const Problem& p : t.problems()) {
                tree.line(1, "");
                fmt::format_to(it, FMT_COMPILE("{} ({}): {}\n"), problem_kind_name(p.kind),
                               severity_name(problem_severity(p.kind)), problem_message(p));
            }
        }
        if (!findings.empty()) {
            append(b, "Findings\n");
            for (const Finding& f : findings) {
                tree.line(1, "");
                fmt::format_to(it, FMT_COMPILE("{} {}: {}\n"), severity_name(f.severity),
                               finding_kind_name(f.kind), f.message);
            }
        }
        b.push_back('\n');
        out_.end_record();
    }

    void render_end_findings(std::span<const Finding> findings) override {
        if (findings.empty()) return;
        append(out_.buffer(), "End of capture\nFindings\n");
        VerboseTree tree(out_.buffer());
        for (const Finding& f : findings)
            tree.field(1, FMT_COMPILE("{} {}: {}"), severity_name(f.severity),
                       finding_kind_name(f.kind), f.message);
        out_.buffer().push_back('\n');
        out_.end_record();
    }
};

}  // namespace

std::unique_ptr<TelegramRenderer> make_verbose_renderer(Output& out) {
    return std::make_unique<VerboseRenderer>(out);
}

}  // namespace dpscope
