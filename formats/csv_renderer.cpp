// Comma-separated values, one row a telegram, with a header row. Fields that could hold a comma
// or a quote are quoted (RFC 4180). Both buses share the header; an FC protocol row fills the
// columns that apply to it, and so does a VLT 2000 row (README.md).
#include <iterator>

#include "formats/describe.hpp"
#include "formats/renderer.hpp"
#include "protocols/fc/fc_describe.hpp"
#include "protocols/vlt2000/vlt2000_describe.hpp"

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
        if (t.protocol == Protocol::Fc)
            render_fc_columns(t);
        else if (t.protocol == Protocol::Vlt2000)
            render_vlt2000_columns(t);
        else
            render_dp_columns(t);
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

  private:
    void opt(bool present, unsigned value) {
        if (present) fmt::format_to(std::back_inserter(out_.buffer()), "{}", value);
        out_.buffer().push_back(',');
    }

    // frame .. detail, each followed by its comma.
    void render_dp_columns(const DecodedTelegram& t) {
        TextBuffer& b = out_.buffer();
        auto it = std::back_inserter(b);
        const FdlTelegram& f = t.dp.fdl;
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
    }

    // The same columns for an FC protocol telegram (README.md): sd, da, sa, dsap, ssap, fc,
    // ppo and spm stay empty; service is the block; slave the drive (0: broadcast); fcs_ok the
    // BCC; rc the AK, ind the index, pva PWE (per the AK's width), meaning the AK's name, error
    // and error_text the AK 7 fault code and its text; pcd PCD 1 and PCD 2.
    void render_fc_columns(const DecodedTelegram& t) {
        TextBuffer& b = out_.buffer();
        auto it = std::back_inserter(b);
        const FcTelegram& fc = t.fc;
        fmt::format_to(it, "{},", t.frame);
        if (t.has_time()) append_epoch_seconds(b, t.time_ns);
        fmt::format_to(it, ",{},,,,,,,{},{},", t.bytes.size(), fc_block_name(fc.block),
                       direction_name(t.direction));
        opt(t.has_roles, t.master);
        opt(t.has_roles, t.slave);
        opt(t.request_frame != 0, static_cast<unsigned>(t.request_frame));
        fmt::format_to(it, "{},,", fc.bcc_ok ? "true" : "false");
        if (fc.has_pkw) {
            const bool rejected = fc_rejected(t);
            const bool pwe = fc.block == FcBlock::Parameter && !rejected;
            fmt::format_to(it, "{},,{},{},", fc.pkw.rc, fc.pkw.pnu, fc.pkw.ind);
            if (pwe) fmt::format_to(it, "{}", pcv_value(fc.pkw, fc_ak_width(t)));
            b.push_back(',');
            quoted(b, fc_ak_meaning(t));
            b.push_back(',');
            if (rejected) {
                fmt::format_to(it, "{},", fc_fault_code(fc));
                quoted(b, fc_fault_text_or_unknown(fc_fault_code(fc)));
            } else {
                b.push_back(',');
            }
        } else {
            append(b, ",,,,,,,");
        }
        b.push_back(',');
        if (fc.has_pcd) fmt::format_to(it, "{:04X} {:04X}", fc.pcd1, fc.pcd2);
        b.push_back(',');
        TextBuffer detail;
        append_fc_detail(detail, t);
        quoted(b, std::string_view(detail.data(), detail.size()));
        b.push_back(',');
    }

    // The same columns for a VLT 2000 telegram (README.md): sd, da, sa, dsap, ssap, fc, ppo, rc
    // and spm stay empty; service is the control letter with its name ("U update"); slave the
    // drive's address (0: broadcast); fcs_ok whether the checksum is right or "??" (not checked);
    // pnu the parameter (not for C), ind the index of an I telegram, pva the value with its
    // decimal point, meaning the letter's name, error and error_text a failed reply's reason code
    // and its text; pcd the control or status word in hex.
    void render_vlt2000_columns(const DecodedTelegram& t) {
        TextBuffer& b = out_.buffer();
        auto it = std::back_inserter(b);
        const Vlt2000Telegram& v = t.vlt2000;
        fmt::format_to(it, "{},", t.frame);
        if (t.has_time()) append_epoch_seconds(b, t.time_ns);
        fmt::format_to(it, ",{},,,,,,,", t.bytes.size());
        if (vlt2000_has_letter(t)) quoted(b, vlt2000_letter_text(t));
        fmt::format_to(it, ",{},", direction_name(t.direction));
        opt(t.has_roles, t.master);
        opt(t.has_roles, t.slave);
        opt(t.request_frame != 0, static_cast<unsigned>(t.request_frame));
        fmt::format_to(it, "{},,,,", v.checksum_ok || v.checksum_disabled ? "true" : "false");
        opt(v.has_parameter && v.letter != Vlt2000Letter::Control, v.parameter);
        opt(v.letter == Vlt2000Letter::ReadIndex && v.has_index_number, v.index_number);
        if (v.has_value && vlt2000_carries_value(v)) append(b, vlt2000_value_text(v));
        b.push_back(',');
        if (vlt2000_has_letter(t)) quoted(b, vlt2000_letter_name(v.letter));
        b.push_back(',');
        opt(v.failed && v.has_reason, v.reason);
        if (v.failed) quoted(b, vlt2000_reason_or_unknown(v));
        b.push_back(',');
        if (v.has_word) fmt::format_to(it, "{:04X}", v.word);
        b.push_back(',');
        TextBuffer detail;
        append_vlt2000_detail(detail, t);
        quoted(b, std::string_view(detail.data(), detail.size()));
        b.push_back(',');
    }
};

}  // namespace

std::unique_ptr<TelegramRenderer> make_csv_renderer(Output& out) {
    return std::make_unique<CsvRenderer>(out);
}

}  // namespace dpscope
