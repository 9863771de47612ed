// Comma-separated values, one row a telegram, with a header row. Fields that could hold a comma
// or a quote are quoted (RFC 4180).
#include <iterator>

#include "formats/describe.hpp"
#include "formats/renderer.hpp"

namespace dpscope {

namespace {

constexpr std::string_view kHeader =
    "frame,time,len,sd,da,sa,dsap,ssap,fc,service,direction,master,slave,request_frame,fcs_ok,"
    "ppo,rc,spm,pnu,ind,pva,meaning,error,error_text,pcd,detail,problems,findings\n";

void quoted(TextBuffer& b, std::string_view text) {
    b.push_back('"');
    for (char c : text) {
        if (c == '"') b.push_back('"');
        b.push_back(c);
    }
    b.push_back('"');
}

class CsvRenderer final : public TelegramRenderer {
  public:
    using TelegramRenderer::TelegramRenderer;

    void begin() override { append(out_.buffer(), kHeader); }

    void render(const DecodedTelegram& t, std::span<const Finding> findings) override {
        TextBuffer& b = out_.buffer();
        auto it = std::back_inserter(b);
        const FdlTelegram& f = t.dp.fdl;
        auto opt = [&](bool present, unsigned value) {
            if (present) fmt::format_to(it, "{}", value);
            b.push_back(',');
        };
        fmt::format_to(it, "{},", t.frame);
        if (t.has_time()) append_epoch_seconds(b, t.time_ns);
        fmt::format_to(it, ",{},{},", t.bytes.size(),
                       f.type == FrameType::Invalid ? "" : frame_type_name(f.type));
        opt(f.has_addresses, f.da);
        opt(f.has_addresses, f.sa);
        opt(f.has_dsap, f.dsap);
        opt(f.has_ssap, f.ssap);
        if (f.has_fc) fmt::format_to(it, "0x{:02X}", f.fc.raw);
        fmt::format_to(it, ",{},{},", service_name(t.dp.service), direction_name(t.direction));
        opt(t.has_roles, t.master);
        opt(t.has_roles, t.slave);
        opt(t.request_frame != 0, static_cast<unsigned>(t.request_frame));
        fmt::format_to(it, "{},", f.fcs_ok ? "true" : "false");
        opt(t.dp.service == Service::DataExchange && t.dp.ppo.type != 0, t.dp.ppo.type);
        if (t.dp.has_pcv) {
            const bool rejected =
                t.direction == Direction::Response &&
                response_code(t.dp.dialect, t.dp.pcv.rc).kind == ResponseKind::Rejected;
            fmt::format_to(it, "{},{},{},{},{},", t.dp.pcv.rc, t.dp.pcv.spm ? 1 : 0, t.dp.pcv.pnu,
                           t.dp.pcv.ind, t.dp.pcv_value(t.direction));
            quoted(b, t.dp.pcv_meaning(t.direction));
            b.push_back(',');
            if (rejected) {
                auto error = static_cast<std::uint16_t>(t.dp.pcv.pva & 0xFFFF);
                fmt::format_to(it, "{},", error);
                quoted(b, error_text_or_unknown(t.dp.dialect, error));
            } else {
                b.push_back(',');
            }
        } else {
            append(b, ",,,,,,,");
        }
        b.push_back(',');
        if (t.dp.service == Service::DataExchange) {
            ByteReader reader(t.dp.pcd);
            bool first = true;
            while (auto word = reader.u16_be()) {
                if (!first) b.push_back(' ');
                fmt::format_to(it, "{:04X}", *word);
                first = false;
            }
        }
        b.push_back(',');
        TextBuffer detail;
        if (f.type != FrameType::Invalid) append_service_detail(detail, t);
        quoted(b, std::string_view(detail.data(), detail.size()));
        b.push_back(',');
        bool first = true;
        for (const Problem& p : t.problems()) {
            if (!first) b.push_back(' ');
            fmt::format_to(it, "{}@{}", problem_kind_name(p.kind), p.offset);
            first = false;
        }
        b.push_back(',');
        first = true;
        for (const Finding& finding : findings) {
            if (!first) b.push_back(' ');
            append(b, finding_kind_name(finding.kind));
            first = false;
        }
        b.push_back('\n');
        out_.end_record();
    }
};

}  // namespace

std::unique_ptr<TelegramRenderer> make_csv_renderer(Output& out) {
    return std::make_unique<CsvRenderer>(out);
}

}  // namespace dpscope
