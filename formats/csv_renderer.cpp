// Comma-separated values, one row a telegram, with a header row. Fields that could hold a comma
// or a quote are quoted (RFC 4180). Both buses share the header; an FC protocol row fills the
// columns that apply to it, and so does a VLT 2000 row (docs/formats.md). Each protocol's columns
// are written by its <name>_csv_columns (formats/protocol_rendering.hpp).
#include <fmt/compile.h>

#include <iterator>

#include "formats/describe.hpp"
#include "formats/parameter_names.hpp"
#include "formats/protocol_rendering.hpp"
#include "formats/renderer.hpp"

namespace dpscope {

namespace {

constexpr std::string_view kHeader =
    "frame,time,len,sd,da,sa,dsap,ssap,fc,service,direction,master,slave,request_frame,fcs_ok,"
    "ppo,rc,spm,pnu,ind,pva,meaning,error,error_text,pcd,detail,problems,findings,pnu_name,"
    "value_scaled,unit\n";

class CsvRenderer final : public TelegramRenderer {
  public:
    using TelegramRenderer::TelegramRenderer;

    void begin() override { append(out_.buffer(), kHeader); }

    void render(const DecodedTelegram& t, std::span<const Finding> findings) override {
        TextBuffer& b = out_.buffer();
        auto it = fmt::appender(b);
        render_csv_columns(b, t);
        bool first = true;
        for (const Problem& p : t.problems()) {
            if (!first) b.push_back(' ');
            fmt::format_to(it, FMT_COMPILE("{}@{}"), problem_kind_name(p.kind), p.offset);
            first = false;
        }
        b.push_back(',');
        first = true;
        for (const Finding& finding : findings) {
            if (!first) b.push_back(' ');
            append(b, finding_kind_name(finding.kind));
            first = false;
        }
        // The parameter's row in its database (issue 29), after every column of before.
        parameter_csv_columns(b, parameter_view(t));
        b.push_back('\n');
        out_.end_record();
    }

  private:
};

}  // namespace

std::unique_ptr<TelegramRenderer> make_csv_renderer(Output& out) {
    return std::make_unique<CsvRenderer>(out);
}

}  // namespace dpscope
