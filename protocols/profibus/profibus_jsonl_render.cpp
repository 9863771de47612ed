// The jsonl keys of a PROFIBUS DP telegram between "len" and "problems": the FDL and DP keys, the
// PCV and PCD, the service's own objects, DP-V1 and PROFIdrive (docs/formats.md, the jsonl schema).
#include <algorithm>
#include <array>
#include <iterator>
#include <string>
#include <string_view>
#include <vector>

#include "formats/describe.hpp"
#include "formats/field_writers.hpp"
#include "formats/json.hpp"
#include "formats/parameter_names.hpp"
#include "formats/protocol_rendering.hpp"
#include "protocols/profibus/dp_payload.hpp"
#include "protocols/profibus/pcd.hpp"

namespace dpscope {

namespace {

// The "fc" object of a frame control byte: what it is follows from the byte alone.
void write_fc_object(JsonWriter& w, FrameControl fc) {
    w.begin_object();
    w.key("raw").integer(fc.raw);
    if (fc.is_request()) {
        w.key("request").boolean(true);
        w.key("fcb").boolean(fc.fcb());
        w.key("fcv").boolean(fc.fcv());
        w.key("function").name(request_function_name(fc));
    } else {
        w.key("request").boolean(false);
        w.key("station").name(station_type_name(fc.station_type()));
        w.key("status").name(response_status_name(fc.function()));
    }
    w.end_object();
}

// JSON text made once for each of `Count` values by `write`, for the parts of a line that follow
// from one small value (jsonl copies the text instead of writing it every line).
template <std::size_t Count, typename Write>
std::array<std::string, Count> json_texts(Write&& write) {
    std::array<std::string, Count> texts;
    for (std::size_t value = 0; value < Count; ++value)
        texts[value] = json::text_of([&](JsonWriter& w) { write(w, value); });
    return texts;
}

// write_fc_object() of a frame control byte (the texts made on first use).
const std::string& fc_object(FrameControl fc) {
    static const std::array<std::string, 256> objects =
        json_texts<256>([](JsonWriter& w, std::size_t raw) {
            write_fc_object(w, FrameControl{static_cast<std::uint8_t>(raw)});
        });
    return objects[fc.raw];
}

// The members "service" and "direction" of a telegram, as JSON text without braces (made on
// first use for every service and direction).
std::string_view service_members(Service service, Direction direction) {
    constexpr std::size_t kRows = kServiceCount * 2;  // a service's request, then its response
    static const std::array<std::string, kRows> objects =
        json_texts<kRows>([](JsonWriter& w, std::size_t index) {
            w.begin_object();
            w.key("service").name(service_name(static_cast<Service>(index / 2)));
            w.key("direction").name(direction_name(static_cast<Direction>(index % 2)));
            w.end_object();
        });
    // As service_name() and direction_name() read a value outside their enums: "Unknown",
    // "response".
    const auto row = static_cast<std::size_t>(service) < kServiceCount
                         ? static_cast<std::size_t>(service)
                         : static_cast<std::size_t>(Service::Unknown);
    const std::string& object = objects[row * 2 + (direction == Direction::Request ? 0 : 1)];
    return std::string_view(object).substr(1, object.size() - 2);
}

void render_pcv(JsonWriter& w, const DecodedTelegram& t) {
    const Pcv& pcv = t.dp.pcv;
    const bool request = t.direction == Direction::Request;
    ValueWidth width;
    bool known;
    bool rejected = false;
    if (request) {
        const RequestCode& code = request_code(t.dp.dialect, pcv.rc);
        width = code.width;
        known = code.defined;
    } else {
        const ResponseCode& code = response_code(t.dp.dialect, pcv.rc);
        width = code.width;
        known = code.kind != ResponseKind::Undefined;
        rejected = code.kind == ResponseKind::Rejected;
    }
    w.begin_object();
    w.key("pca").integer(pcv.pca);
    w.key("rc").integer(pcv.rc);
    w.key("spm").integer(pcv.spm ? 1 : 0);
    w.key("pnu").integer(pcv.pnu);
    w.key("ind").integer(pcv.ind);
    w.key("ind_low").integer(pcv.ind_low);
    w.key("pva").integer(pcv_value(pcv, width));
    w.key("pva_raw").integer(pcv.pva);
    w.key("width");
    if (width == ValueWidth::Word)
        w.name("word");
    else if (width == ValueWidth::DoubleWord)
        w.name("dword");
    else
        w.null();
    // The parameter's row in its drive's database (issue 29).
    parameter_jsonl_keys(w, parameter_view(t));
    w.key("meaning").name(t.dp.pcv_meaning(t.direction));
    w.key("code_known").boolean(known);
    if (rejected) {
        auto error = static_cast<std::uint16_t>(pcv.pva & 0xFFFF);
        w.key("error").integer(error);
        w.key("error_text").string(error_text_or_unknown(t.dp.dialect, error));
    } else {
        w.members("\"error\":null,\"error_text\":null");
    }
    w.end_object();
}

void render_number(JsonWriter& w, const ProfidriveNumber& n) {
    if (!n.is_real) {
        w.integer(n.integer);
        return;
    }
    w.raw_value([&n](TextBuffer& b) {
        if (n.single)
            fmt::format_to(std::back_inserter(b), "{}", static_cast<float>(n.real));
        else
            fmt::format_to(std::back_inserter(b), "{}", n.real);
    });
}

void render_profidrive(JsonWriter& w, const ProfidriveMessage& m, Dialect dialect,
                       const DecodedTelegram& t) {
    w.begin_object();
    w.key("response").boolean(m.is_response);
    w.key("reference").optional_integer(m.has_header, m.reference);
    std::string_view id_name =
        m.is_response ? profidrive_response_id_name(m.id) : profidrive_request_id_name(m.id);
    w.key(m.is_response ? "response_id" : "request_id").optional_integer(m.has_header, m.id);
    w.key("id_name");
    optional_name(w, m.has_header && !id_name.empty(), id_name);
    w.key("negative").boolean(m.negative());
    w.key("axis").optional_integer(m.has_header, m.axis);
    w.key("count").optional_integer(m.has_header, m.count);
    if (m.is_response) {
        w.key("request_frame")
            .optional_integer(m.has_request, static_cast<std::int64_t>(m.request_frame));
    }
    w.key("parameters").begin_array();
    std::size_t parameters = std::max(m.addresses.size(), m.blocks.size());
    for (std::size_t k = 0; k < parameters; ++k) {
        w.begin_object();
        bool address = k < m.addresses.size();
        const ProfidriveAddress a = address ? m.addresses[k] : ProfidriveAddress{};
        w.key("attribute").optional_integer(address, a.attribute);
        w.key("attribute_name");
        const std::string_view attribute_name =
            address ? profidrive_attribute_name(a.attribute) : std::string_view{};
        optional_name(w, !attribute_name.empty(), attribute_name);
        w.key("elements").optional_integer(address, a.elements);
        w.key("pnu").optional_integer(address, a.pnu);
        w.key("subindex").optional_integer(address, a.subindex);
        bool has_block = k < m.blocks.size();
        const ProfidriveValueBlock* block = has_block ? &m.blocks[k] : nullptr;
        w.key("format").optional_integer(has_block, has_block ? block->format : 0);
        w.key("format_name");
        if (block)
            w.name(profidrive_format_name(block->format));
        else
            w.null();
        w.key("value_count").optional_integer(has_block, has_block ? block->count : 0);
        w.key("values");
        bool values = block && !block->is_error() && block->format != profidrive::kFormatZero;
        if (values) {
            std::string text;
            append_profidrive_values(*block, text);
            w.string(text);
        } else {
            w.null();
        }
        w.key("numbers");
        std::size_t count = values ? profidrive_value_count(*block) : 0;
        if (values && count > 0 && profidrive_number(*block, 0)) {
            w.begin_array();
            for (std::size_t i = 0; i < count; ++i) {
                if (auto n = profidrive_number(*block, i))
                    render_number(w, *n);
                else
                    w.null();
            }
            w.end_array();
        } else {
            w.null();
        }
        // The parameter's row in its drive's database (issue 29): name, the value in its unit
        // (one whole number of the value attribute), unit.
        parameter_jsonl_keys(w, profidrive_parameter(t, m, k).row,
                             profidrive_value_in_unit(t, m, k));
        w.key("complete");
        if (block)
            w.boolean(block->complete);
        else
            w.null();
        w.key("error");
        if (block && block->is_error() && block->values.size() >= 2) {
            w.begin_object();
            w.key("number").integer(block->error_number());
            w.key("text").string(profidrive_error_text(block->error_number(), dialect));
            w.key("info").optional_integer(block->has_error_info(), block->error_info());
            w.end_object();
        } else {
            w.null();
        }
        w.end_object();
    }
    w.end_array();
    w.key("trailing").integer(m.trailing);
    w.end_object();
}

// The DP-V1 object's "initiate" and "abort" members.
void render_dpv1_initiate_abort(JsonWriter& w, const DecodedTelegram& t, const Dpv1Pdu& pdu) {
    using Layout = Dpv1Pdu::Layout;
    const bool initiate = pdu.layout == Layout::Initiate && pdu.complete;
    const bool abort = pdu.layout == Layout::Abort && pdu.complete;
    if (!initiate && !abort) {
        w.members("\"initiate\":null,\"abort\":null");
        return;
    }
    w.key("initiate");
    if (initiate) {
        const Dpv1Initiate& i = pdu.initiate;
        bool request = t.direction == Direction::Request;
        w.begin_object();
        w.key("send_timeout").optional_integer(request, i.send_timeout);
        w.key("max_len_data_unit").optional_integer(!request, i.max_len_data_unit);
        w.key("features_supported").integer(i.features_supported);
        w.key("profile_features_supported").integer(i.profile_features_supported);
        w.key("profile_ident_number").integer(i.profile_ident_number);
        w.key("s_type").optional_integer(i.has_addresses, i.s_type);
        w.key("s_len").optional_integer(i.has_addresses, i.s_len);
        w.key("d_type").optional_integer(i.has_addresses, i.d_type);
        w.key("d_len").optional_integer(i.has_addresses, i.d_len);
        w.key("s_addr");
        hex_string(w, i.s_addr);
        w.key("d_addr");
        hex_string(w, i.d_addr);
        w.end_object();
    } else {
        w.null();
    }
    w.key("abort");
    if (abort) {
        w.begin_object();
        w.key("subnet").integer(pdu.abort.subnet);
        w.key("instance").integer(pdu.abort.instance());
        w.key("instance_name").string(dpv1_abort_instance_name(pdu.abort.instance_reason));
        w.key("reason").integer(pdu.abort.reason());
        w.key("reason_name").string(dpv1_abort_reason_name(pdu.abort.instance_reason));
        w.end_object();
    } else {
        w.null();
    }
}

void render_dpv1(JsonWriter& w, const DecodedTelegram& t, const Dpv1Pdu& pdu) {
    using Layout = Dpv1Pdu::Layout;
    w.begin_object();
    bool has_function = pdu.layout != Layout::None;
    w.key("function").optional_integer(has_function, pdu.function);
    w.key("function_name");
    const std::string_view function_name =
        has_function ? dpv1_function_name(pdu.function) : std::string_view{};
    optional_name(w, !function_name.empty(), function_name);
    w.key("negative").boolean(pdu.negative());
    w.key("complete").boolean(pdu.complete);
    bool addressed = pdu.layout == Layout::Addressed && pdu.complete;
    bool alarm = addressed && pdu.base_function() == dpv1_function::kAlarmAck;
    w.key("slot").optional_integer(addressed, pdu.slot);
    w.key("index").optional_integer(addressed && !alarm, pdu.index);
    w.key("length").optional_integer(addressed && !alarm, pdu.length);
    w.key("data_length")
        .optional_integer(addressed || pdu.layout == Layout::Unknown,
                          static_cast<std::int64_t>(pdu.data.size()));
    w.key("alarm_type").optional_integer(alarm, pdu.index);
    w.key("specifier").optional_integer(alarm, pdu.length);
    if (pdu.layout == Layout::Error && pdu.complete) {
        w.key("error_decode").integer(pdu.error_decode);
        w.key("error_decode_name");
        optional_string(w, dpv1_error_decode_name(pdu.error_decode));
        w.key("error_code_1").integer(pdu.error_code_1);
        w.key("error_class").integer(pdu.error_code_1 >> 4);
        w.key("error_class_name");
        optional_string(w, dpv1_error_class_name(pdu.error_code_1));
        w.key("error_code").integer(pdu.error_code_1 & 0x0F);
        w.key("error_code_name").string(dpv1_error_code_name(pdu.error_code_1));
        w.key("error_code_2").integer(pdu.error_code_2);
    } else {
        w.members(
            "\"error_decode\":null,\"error_decode_name\":null,\"error_code_1\":null,"
            "\"error_class\":null,\"error_class_name\":null,\"error_code\":null,"
            "\"error_code_name\":null,\"error_code_2\":null");
    }
    render_dpv1_initiate_abort(w, t, pdu);
    w.end_object();
}

// "gsd": the slave's GSD file and what it names in this telegram (issue 29; docs/gsd.md).
void render_gsd(JsonWriter& w, const DecodedTelegram& t) {
    const GsdDevice& device = *t.dp.device;
    const DpServiceData& data = t.dp.service_data;
    w.key("gsd").begin_object();
    w.key("file").string(device.file);
    w.key("vendor").string(device.vendor);
    w.key("model").string(device.model);
    w.key("ident").optional_integer(device.ident_number.has_value(),
                                    device.ident_number.value_or(0));
    w.key("modules").begin_array();
    for (const GsdModuleMatch& m : data.gsd_modules()) {
        w.begin_object();
        w.key("slot").integer(m.first_identifier);
        w.key("slots").integer(m.identifiers);
        w.key("name");
        if (m.module)
            w.string(m.module->name);
        else
            w.null();
        w.end_object();
    }
    w.end_array();
    w.key("user_prm").begin_array();
    if (const GsdPrmReading* prm = data.gsd_prm())
        for (const GsdPrmValue& v : prm->values) {
            w.begin_object();
            w.key("name").string(v.prm->name);
            w.key("module");
            if (v.module)
                w.string(v.module->name);
            else
                w.null();
            w.key("byte").integer(v.offset);
            w.key("value").integer(v.value);
            w.key("text");
            if (v.text)
                w.string(v.text->text);
            else
                w.null();
            w.key("allowed").boolean(v.in_range);
            w.end_object();
        }
    w.end_array();
    w.key("diag").begin_array();
    for (const GsdDiagText& d : data.gsd_diag()) {
        w.begin_object();
        w.key("source").string(d.source == GsdDiagText::Source::Bit    ? "bit"
                               : d.source == GsdDiagText::Source::Area ? "area"
                                                                       : "slot");
        w.key("bit").integer(d.bit);
        w.key("byte").integer(d.offset);
        w.key("text").string(d.text);
        w.end_object();
    }
    w.end_array();
    w.end_object();
}

// "diag": a Slave_Diag answer's.
void render_diag(JsonWriter& w, const DecodedTelegram& t, const SlaveDiag& diag) {
    w.begin_object();
    w.key("ident").integer(diag.ident);
    w.key("master").optional_integer(diag.master_address != kNoMasterAddress, diag.master_address);
    w.key("station_status").begin_array();
    w.integer(diag.station_status_1);
    w.integer(diag.station_status_2);
    w.integer(diag.station_status_3);
    w.end_array();
    w.key("flags").begin_array();
    for (const FlagBit& flag : station_status_1_flags())
        if (diag.station_status_1 & flag.mask) w.string(flag.name);
    for (const FlagBit& flag : station_status_2_flags())
        if ((diag.station_status_2 & flag.mask) && flag.mask != kDiagAlwaysOne) w.string(flag.name);
    for (const FlagBit& flag : station_status_3_flags())
        if (diag.station_status_3 & flag.mask) w.string(flag.name);
    w.end_array();
    w.key("ext");
    if (diag.extended.empty())
        w.null();
    else
        hex_string(w, diag.extended);
    w.key("dpv1");
    if (t.dp.slave_dpv1 == SlaveDpv1::Unknown)
        w.null();
    else
        w.boolean(t.dp.slave_dpv1 == SlaveDpv1::Enabled);
    w.end_object();
}

// "prm": a Set_Prm request's.
void render_set_prm(JsonWriter& w, const SetPrm& prm) {
    w.begin_object();
    w.key("ident").integer(prm.ident);
    w.key("station_status").integer(prm.station_status);
    w.key("flags");
    flag_array(w, prm.station_status, set_prm_station_flags());
    w.key("wd_fact_1").integer(prm.wd_fact_1);
    w.key("wd_fact_2").integer(prm.wd_fact_2);
    w.key("watchdog_ms").optional_integer(prm.watchdog_on(), prm.watchdog_ms());
    w.key("watchdog_ms_alt")
        .optional_integer(prm.watchdog_on() && prm.watchdog_base_uncertain(),
                          prm.watchdog_ms_10ms_base());
    w.key("min_tsdr").integer(prm.min_tsdr);
    w.key("group").integer(prm.group_ident);
    w.key("dpv1_status");
    if (prm.has_dpv1_status) {
        w.begin_array();
        for (std::size_t i = 0; i < 3; ++i)
            w.integer(prm.dpv1_status[i]);
        w.end_array();
    } else {
        w.null();
    }
    w.key("user_prm");
    hex_string(w, prm.user_prm);
    w.end_object();
}

// "cfg": a Chk_Cfg request's or a Get_Cfg answer's modules.
void render_cfg(JsonWriter& w, const DecodedTelegram& t, const std::vector<CfgModule>& modules) {
    w.begin_object();
    w.key("bytes").begin_array();
    for (std::uint8_t byte : t.dp.fdl.du)
        w.integer(byte);
    w.end_array();
    w.key("modules").begin_array();
    for (const CfgModule& m : modules) {
        bool use_output = m.output_units != 0;
        w.begin_object();
        w.key("identifier").integer(m.identifier);
        w.key("special").boolean(m.special);
        w.key("dir").string(cfg_direction_name(m.direction));
        w.key("out_bytes").integer(m.output_bytes());
        w.key("in_bytes").integer(m.input_bytes());
        w.key("unit").string((use_output ? m.output_words : m.input_words) ? "word" : "byte");
        w.key("consistent").boolean(use_output ? m.output_consistent : m.input_consistent);
        w.key("manufacturer_bytes").integer(m.manufacturer_bytes);
        w.end_object();
    }
    w.end_array();
    PpoLayout layout = ppo_from_cfg(modules, PpoSource::ChkCfg);
    w.key("ppo").optional_integer(layout.type != 0, layout.type);
    w.key("has_pcv").boolean(layout.has_pcv);
    w.end_object();
}

// "global_control": a Global_Control request's.
void render_global_control(JsonWriter& w, const GlobalControl& gc) {
    w.begin_object();
    w.key("command").integer(gc.command);
    w.key("flags");
    flag_array(w, gc.command, global_control_flags());
    w.key("group").integer(gc.group_select);
    w.end_object();
}

void render_service_objects(JsonWriter& w, const DecodedTelegram& t) {
    const DpServiceData& data = t.dp.service_data;
    const SlaveDiag* diag = data.slave_diag();
    const SetPrm* prm = data.set_prm();
    // An empty configuration is null, as when there is none.
    const std::vector<CfgModule>* modules = data.cfg_modules();
    const bool cfg = modules && !t.dp.fdl.du.empty();
    // Only a request's: a response's bytes in this layout (DpServiceData) are not shown here.
    const GlobalControl* gc =
        t.direction == Direction::Request ? data.global_control() : nullptr;

    if (!diag && !prm && !cfg && !gc) {  // most lines: none of the four
        w.members("\"diag\":null,\"prm\":null,\"cfg\":null,\"global_control\":null");
    } else {
        w.key("diag");
        if (diag)
            render_diag(w, t, *diag);
        else
            w.null();
        w.key("prm");
        if (prm)
            render_set_prm(w, *prm);
        else
            w.null();
        w.key("cfg");
        if (cfg)
            render_cfg(w, t, *modules);
        else
            w.null();
        w.key("global_control");
        if (gc)
            render_global_control(w, *gc);
        else
            w.null();
    }

    // Only on the management lines of a slave that has a GSD file (--gsd): what the file says.
    if (t.dp.device && (prm || diag || cfg)) render_gsd(w, t);

    // Only on DP-V1 lines (MSAC_C1, MSAC_C2): other lines keep the schema they had.
    if (t.dp.service == Service::MsacC1 || t.dp.service == Service::MsacC2) {
        w.key("dpv1");
        if (const Dpv1Pdu* pdu = data.dpv1())
            render_dpv1(w, t, *pdu);
        else
            w.null();
        w.key("profidrive");
        if (const ProfidriveMessage* m = data.profidrive())
            render_profidrive(w, *m, t.dp.dialect, t);
        else
            w.null();
    }
}

}  // namespace

// The PROFIBUS keys between "len" and "problems".
void profibus_jsonl_keys(JsonWriter& w, const DecodedTelegram& t) {
    const FdlTelegram& f = t.dp.fdl;
    const bool valid = f.type != FrameType::Invalid;
    const bool data_exchange = t.dp.service == Service::DataExchange;
    w.key("sd");
    if (valid)
        w.name(frame_type_name(f.type));
    else
        w.null();
    w.key("da").optional_integer(f.has_addresses, f.da);
    w.key("sa").optional_integer(f.has_addresses, f.sa);
    if (!f.has_dsap && !f.has_ssap) {  // most telegrams: no address extension
        w.members("\"dsap\":null,\"ssap\":null");
    } else {
        w.key("dsap").optional_integer(f.has_dsap, f.dsap);
        w.key("ssap").optional_integer(f.has_ssap, f.ssap);
    }
    w.key("fc");
    if (f.has_fc)
        w.json_text(fc_object(f.fc));
    else
        w.null();
    w.key("fcs_ok").boolean(f.fcs_ok);
    w.members(service_members(t.dp.service, t.direction));
    jsonl_role_keys(w, t);
    if (!data_exchange && !t.dp.has_pcv) {  // no cyclic data: five nulls in one copy
        w.members("\"ppo\":null,\"ppo_source\":null,\"dialect\":null,\"pcv\":null,\"pcd\":null");
    } else {
        w.key("ppo").optional_integer(data_exchange && t.dp.ppo.type != 0, t.dp.ppo.type);
        w.key("ppo_source");
        if (data_exchange)
            w.name(ppo_source_name(t.dp.ppo.source));
        else
            w.null();
        // The dialect names the parameter channel's code tables: none without a PCV.
        w.key("dialect");
        if (data_exchange && t.dp.ppo.has_pcv)
            w.name(dialect_name(t.dp.dialect));
        else
            w.null();
        w.key("pcv");
        if (t.dp.has_pcv)
            render_pcv(w, t);
        else
            w.null();
        w.key("pcd");
        if (data_exchange) {
            w.begin_array();
            ByteReader reader(t.dp.pcd);
            while (auto word = reader.u16_be())
                w.integer(*word);
            w.end_array();
        } else {
            w.null();
        }
    }
    render_service_objects(w, t);
    w.key("data");
    if (!f.du.empty())
        hex_string(w, f.du);
    else
        w.null();
}

}  // namespace dpscope
