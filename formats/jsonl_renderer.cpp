// One JSON object a telegram. Every key is present on every line (null where it does not apply);
// the schema is documented in README.md and is stable.
#include <iterator>
#include <vector>

#include "decoder/dp_payload.hpp"
#include "formats/describe.hpp"
#include "formats/json.hpp"
#include "formats/renderer.hpp"

namespace dpscope {

namespace {

using json::boolean;
using json::integer;
using json::null;
using json::raw;
using json::string;

void optional_int(TextBuffer& b, bool present, std::int64_t value) {
    if (present)
        integer(b, value);
    else
        null(b);
}

void flag_array(TextBuffer& b, std::uint8_t value, std::span<const FlagBit> flags,
                std::uint8_t ignore = 0) {
    b.push_back('[');
    bool first = true;
    for (const FlagBit& flag : flags) {
        if (!(value & flag.mask) || (flag.mask & ignore)) continue;
        if (!first) b.push_back(',');
        string(b, flag.name);
        first = false;
    }
    b.push_back(']');
}

void hex_string(TextBuffer& b, Bytes bytes) {
    b.push_back('"');
    append_hex(b, bytes, "");
    b.push_back('"');
}

class JsonlRenderer final : public TelegramRenderer {
  public:
    using TelegramRenderer::TelegramRenderer;

    void render(const DecodedTelegram& t, std::span<const Finding> findings) override {
        TextBuffer& b = out_.buffer();
        const FdlTelegram& f = t.fdl;
        const bool valid = f.type != FrameType::Invalid;
        const bool data_exchange = t.service == Service::DataExchange;
        raw(b, "{\"frame\":");
        integer(b, static_cast<std::int64_t>(t.frame));
        raw(b, ",\"time\":");
        json::time(b, t.time_ns);
        raw(b, ",\"len\":");
        integer(b, static_cast<std::int64_t>(t.bytes.size()));
        raw(b, ",\"sd\":");
        if (valid)
            string(b, frame_type_name(f.type));
        else
            null(b);
        raw(b, ",\"da\":");
        optional_int(b, f.has_addresses, f.da);
        raw(b, ",\"sa\":");
        optional_int(b, f.has_addresses, f.sa);
        raw(b, ",\"dsap\":");
        optional_int(b, f.has_dsap, f.dsap);
        raw(b, ",\"ssap\":");
        optional_int(b, f.has_ssap, f.ssap);
        raw(b, ",\"fc\":");
        if (f.has_fc) {
            raw(b, "{\"raw\":");
            integer(b, f.fc.raw);
            if (f.fc.is_request()) {
                raw(b, ",\"request\":true,\"fcb\":");
                boolean(b, f.fc.fcb());
                raw(b, ",\"fcv\":");
                boolean(b, f.fc.fcv());
                raw(b, ",\"function\":");
                string(b, request_function_name(f.fc));
            } else {
                raw(b, ",\"request\":false,\"station\":");
                string(b, station_type_name(f.fc.station_type()));
                raw(b, ",\"status\":");
                string(b, response_status_name(f.fc.function()));
            }
            b.push_back('}');
        } else {
            null(b);
        }
        raw(b, ",\"fcs_ok\":");
        boolean(b, f.fcs_ok);
        raw(b, ",\"service\":");
        string(b, service_name(t.service));
        raw(b, ",\"direction\":");
        string(b, direction_name(t.direction));
        raw(b, ",\"master\":");
        optional_int(b, t.has_roles, t.master);
        raw(b, ",\"slave\":");
        optional_int(b, t.has_roles, t.slave);
        raw(b, ",\"request_frame\":");
        optional_int(b, t.request_frame != 0, static_cast<std::int64_t>(t.request_frame));
        raw(b, ",\"ppo\":");
        optional_int(b, data_exchange && t.ppo.type != 0, t.ppo.type);
        raw(b, ",\"ppo_source\":");
        if (data_exchange)
            string(b, ppo_source_name(t.ppo.source));
        else
            null(b);
        raw(b, ",\"dialect\":");
        if (data_exchange)
            string(b, dialect_name(t.dialect));
        else
            null(b);
        raw(b, ",\"pcv\":");
        if (t.has_pcv)
            render_pcv(b, t);
        else
            null(b);
        raw(b, ",\"pcd\":");
        if (data_exchange) {
            b.push_back('[');
            ByteReader reader(t.pcd);
            bool first = true;
            while (auto word = reader.u16_be()) {
                if (!first) b.push_back(',');
                integer(b, *word);
                first = false;
            }
            b.push_back(']');
        } else {
            null(b);
        }
        render_service_objects(b, t);
        raw(b, ",\"data\":");
        if (!f.du.empty())
            hex_string(b, f.du);
        else
            null(b);
        raw(b, ",\"problems\":[");
        bool first = true;
        for (const Problem& p : t.problems()) {
            if (!first) b.push_back(',');
            first = false;
            raw(b, "{\"kind\":");
            string(b, problem_kind_name(p.kind));
            raw(b, ",\"severity\":");
            string(b, severity_name(problem_severity(p.kind)));
            raw(b, ",\"offset\":");
            integer(b, p.offset);
            raw(b, ",\"message\":");
            string(b, problem_message(p));
            b.push_back('}');
        }
        raw(b, "],\"findings\":[");
        first = true;
        for (const Finding& finding : findings) {
            if (!first) b.push_back(',');
            first = false;
            json::finding(b, finding);
        }
        raw(b, "]}\n");
        out_.end_record();
    }

    // A last line for findings that belong to no telegram:
    // {"end_of_capture":true,"findings":[...]}.
    void render_end_findings(std::span<const Finding> findings) override {
        if (findings.empty()) return;
        TextBuffer& b = out_.buffer();
        raw(b, "{\"end_of_capture\":true,\"findings\":[");
        bool first = true;
        for (const Finding& f : findings) {
            if (!first) b.push_back(',');
            first = false;
            json::finding(b, f);
        }
        raw(b, "]}\n");
        out_.end_record();
    }

  private:
    static void render_pcv(TextBuffer& b, const DecodedTelegram& t) {
        const Pcv& pcv = t.pcv;
        const bool request = t.direction == Direction::Request;
        ValueWidth width;
        bool known;
        bool rejected = false;
        if (request) {
            const RequestCode& code = request_code(t.dialect, pcv.rc);
            width = code.width;
            known = code.defined;
        } else {
            const ResponseCode& code = response_code(t.dialect, pcv.rc);
            width = code.width;
            known = code.kind != ResponseKind::Undefined;
            rejected = code.kind == ResponseKind::Rejected;
        }
        raw(b, "{\"pca\":");
        integer(b, pcv.pca);
        raw(b, ",\"rc\":");
        integer(b, pcv.rc);
        raw(b, ",\"spm\":");
        integer(b, pcv.spm ? 1 : 0);
        raw(b, ",\"pnu\":");
        integer(b, pcv.pnu);
        raw(b, ",\"ind\":");
        integer(b, pcv.ind);
        raw(b, ",\"ind_low\":");
        integer(b, pcv.ind_low);
        raw(b, ",\"pva\":");
        integer(b, pcv_value(pcv, width));
        raw(b, ",\"pva_raw\":");
        integer(b, pcv.pva);
        raw(b, ",\"width\":");
        if (width == ValueWidth::Word)
            string(b, "word");
        else if (width == ValueWidth::DoubleWord)
            string(b, "dword");
        else
            null(b);
        raw(b, ",\"meaning\":");
        string(b, t.pcv_meaning());
        raw(b, ",\"code_known\":");
        boolean(b, known);
        raw(b, ",\"error\":");
        if (rejected) {
            auto error = static_cast<std::uint16_t>(pcv.pva & 0xFFFF);
            integer(b, error);
            raw(b, ",\"error_text\":");
            std::string_view text = error_text(t.dialect, error);
            if (text.empty())
                null(b);
            else
                string(b, text);
        } else {
            raw(b, "null,\"error_text\":null");
        }
        b.push_back('}');
    }

    static void render_service_objects(TextBuffer& b, const DecodedTelegram& t) {
        const bool request = t.direction == Direction::Request;
        const bool has_data = !t.fdl.du.empty();
        ByteReader du(t.fdl.du, t.fdl.du_offset);
        ProblemList ignored;

        raw(b, ",\"diag\":");
        std::optional<SlaveDiag> diag;
        if (t.service == Service::SlaveDiag && !request && has_data)
            diag = parse_slave_diag(du, ignored);
        if (diag) {
            raw(b, "{\"ident\":");
            integer(b, diag->ident);
            raw(b, ",\"master\":");
            optional_int(b, diag->master_address != kNoMasterAddress, diag->master_address);
            raw(b, ",\"station_status\":[");
            integer(b, diag->station_status_1);
            b.push_back(',');
            integer(b, diag->station_status_2);
            b.push_back(',');
            integer(b, diag->station_status_3);
            raw(b, "],\"flags\":");
            std::vector<std::string_view> all;
            for (const FlagBit& flag : station_status_1_flags())
                if (diag->station_status_1 & flag.mask) all.push_back(flag.name);
            for (const FlagBit& flag : station_status_2_flags())
                if ((diag->station_status_2 & flag.mask) && flag.mask != kDiagAlwaysOne)
                    all.push_back(flag.name);
            for (const FlagBit& flag : station_status_3_flags())
                if (diag->station_status_3 & flag.mask) all.push_back(flag.name);
            b.push_back('[');
            for (std::size_t i = 0; i < all.size(); ++i) {
                if (i) b.push_back(',');
                string(b, all[i]);
            }
            raw(b, "],\"ext\":");
            if (diag->extended.empty())
                null(b);
            else
                hex_string(b, diag->extended);
            raw(b, ",\"dpv1\":");
            if (t.slave_dpv1 == SlaveDpv1::Unknown)
                null(b);
            else
                boolean(b, t.slave_dpv1 == SlaveDpv1::Enabled);
            b.push_back('}');
        } else {
            null(b);
        }

        raw(b, ",\"prm\":");
        std::optional<SetPrm> prm;
        if (t.service == Service::SetPrm && request) prm = parse_set_prm(du, ignored);
        if (prm) {
            raw(b, "{\"ident\":");
            integer(b, prm->ident);
            raw(b, ",\"station_status\":");
            integer(b, prm->station_status);
            raw(b, ",\"flags\":");
            flag_array(b, prm->station_status, set_prm_station_flags());
            raw(b, ",\"wd_fact_1\":");
            integer(b, prm->wd_fact_1);
            raw(b, ",\"wd_fact_2\":");
            integer(b, prm->wd_fact_2);
            raw(b, ",\"watchdog_ms\":");
            optional_int(b, prm->watchdog_on(), prm->watchdog_ms());
            raw(b, ",\"watchdog_ms_alt\":");
            optional_int(b, prm->watchdog_on() && prm->watchdog_base_uncertain(),
                         prm->watchdog_ms_10ms_base());
            raw(b, ",\"min_tsdr\":");
            integer(b, prm->min_tsdr);
            raw(b, ",\"group\":");
            integer(b, prm->group_ident);
            raw(b, ",\"dpv1_status\":");
            if (prm->has_dpv1_status) {
                b.push_back('[');
                for (std::size_t i = 0; i < 3; ++i) {
                    if (i) b.push_back(',');
                    integer(b, prm->dpv1_status[i]);
                }
                b.push_back(']');
            } else {
                null(b);
            }
            raw(b, ",\"user_prm\":");
            hex_string(b, prm->user_prm);
            b.push_back('}');
        } else {
            null(b);
        }

        raw(b, ",\"cfg\":");
        bool cfg = has_data && ((t.service == Service::ChkCfg && request) ||
                                (t.service == Service::GetCfg && !request));
        if (cfg) {
            std::vector<CfgModule> modules;
            parse_cfg(du, modules, ignored);
            raw(b, "{\"bytes\":[");
            for (std::size_t i = 0; i < t.fdl.du.size(); ++i) {
                if (i) b.push_back(',');
                integer(b, t.fdl.du[i]);
            }
            raw(b, "],\"modules\":[");
            for (std::size_t i = 0; i < modules.size(); ++i) {
                const CfgModule& m = modules[i];
                if (i) b.push_back(',');
                bool use_output = m.output_units != 0;
                raw(b, "{\"identifier\":");
                integer(b, m.identifier);
                raw(b, ",\"special\":");
                boolean(b, m.special);
                raw(b, ",\"dir\":");
                string(b, cfg_direction_name(m.direction));
                raw(b, ",\"out_bytes\":");
                integer(b, m.output_bytes());
                raw(b, ",\"in_bytes\":");
                integer(b, m.input_bytes());
                raw(b, ",\"unit\":");
                string(b, (use_output ? m.output_words : m.input_words) ? "word" : "byte");
                raw(b, ",\"consistent\":");
                boolean(b, use_output ? m.output_consistent : m.input_consistent);
                raw(b, ",\"manufacturer_bytes\":");
                integer(b, m.manufacturer_bytes);
                b.push_back('}');
            }
            PpoLayout layout = ppo_from_cfg(modules, PpoSource::ChkCfg);
            raw(b, "],\"ppo\":");
            optional_int(b, layout.type != 0, layout.type);
            raw(b, ",\"has_pcv\":");
            boolean(b, layout.has_pcv);
            b.push_back('}');
        } else {
            null(b);
        }

        raw(b, ",\"global_control\":");
        std::optional<GlobalControl> gc;
        if (t.service == Service::GlobalControl && request) gc = parse_global_control(du, ignored);
        if (gc) {
            raw(b, "{\"command\":");
            integer(b, gc->command);
            raw(b, ",\"flags\":");
            flag_array(b, gc->command, global_control_flags());
            raw(b, ",\"group\":");
            integer(b, gc->group_select);
            b.push_back('}');
        } else {
            null(b);
        }
    }
};

}  // namespace

std::unique_ptr<TelegramRenderer> make_jsonl_renderer(Output& out) {
    return std::make_unique<JsonlRenderer>(out);
}

}  // namespace dpscope
