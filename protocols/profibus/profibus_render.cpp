// A PROFIBUS DP telegram in the telegram formats (formats/protocol_rendering.hpp): the text line's
// columns and the csv columns here; the verbose tree and the jsonl keys in
// profibus_verbose_render.cpp and profibus_jsonl_render.cpp.
#include <fmt/compile.h>

#include <algorithm>
#include <iterator>
#include <string>

#include "formats/describe.hpp"
#include "formats/field_writers.hpp"
#include "formats/protocol_rendering.hpp"
#include "protocols/profibus/dp_payload.hpp"

namespace dpscope {

// ---- text

// source → destination, frame type, service, req|rsp, detail.
void profibus_text_columns(TextBuffer& b, const DecodedTelegram& t) {
    if (t.dp.fdl.has_addresses || t.has_roles) {
        const bool fdl = t.dp.fdl.has_addresses;
        append_decimal_right(b, fdl ? t.dp.fdl.sa : t.slave, 3);
        append(b, " → ");
        append_decimal_left(b, fdl ? t.dp.fdl.da : t.master, 3);
        b.push_back(' ');
    } else {
        append(b, "  ? → ?   ");
    }
    append_left(b, t.dp.fdl.type == FrameType::Invalid ? "bad" : frame_type_name(t.dp.fdl.type), 3);
    b.push_back(' ');
    append_left(b, service_name(t.dp.service), 14);
    append(b, t.direction == Direction::Request ? " req " : " rsp ");
    if (t.dp.fdl.type == FrameType::Invalid)
        append_hex(b, t.bytes.first(std::min<std::size_t>(t.bytes.size(), 16)));
    else
        append_service_detail(b, t);
}

// ---- csv

// frame .. detail, each followed by its comma.
void profibus_csv_columns(TextBuffer& b, const DecodedTelegram& t) {
    const FdlTelegram& f = t.dp.fdl;
    put(b, t.frame, ',');
    if (t.has_time()) append_epoch_seconds(b, t.time_ns);
    put(b, ',', t.bytes.size(), ',', f.type == FrameType::Invalid ? "" : frame_type_name(f.type),
        ',');
    csv_optional(b, f.has_addresses, f.da);
    csv_optional(b, f.has_addresses, f.sa);
    csv_optional(b, f.has_dsap, f.dsap);
    csv_optional(b, f.has_ssap, f.ssap);
    if (f.has_fc) append_hex_byte(b, f.fc.raw);
    put(b, ',', service_name(t.dp.service), ',', direction_name(t.direction), ',');
    csv_optional(b, t.has_roles, t.master);
    csv_optional(b, t.has_roles, t.slave);
    csv_optional(b, t.request_frame != 0, static_cast<unsigned>(t.request_frame));
    append(b, f.fcs_ok ? "true," : "false,");
    csv_optional(b, t.dp.service == Service::DataExchange && t.dp.ppo.type != 0, t.dp.ppo.type);
    if (t.dp.has_pcv) {
        const bool rejected =
            t.direction == Direction::Response &&
            response_code(t.dp.dialect, t.dp.pcv.rc).kind == ResponseKind::Rejected;
        put(b, t.dp.pcv.rc, ',', t.dp.pcv.spm ? '1' : '0', ',', t.dp.pcv.pnu, ',', t.dp.pcv.ind,
            ',', t.dp.pcv_value(t.direction), ',');
        csv_quoted(b, t.dp.pcv_meaning(t.direction));
        b.push_back(',');
        if (rejected) {
            auto error = static_cast<std::uint16_t>(t.dp.pcv.pva & 0xFFFF);
            put(b, error, ',');
            csv_quoted(b, error_text_or_unknown(t.dp.dialect, error));
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
            append_hex_fixed(b, *word, 4);
            first = false;
        }
    }
    b.push_back(',');
    TextBuffer detail;
    if (f.type != FrameType::Invalid) append_service_detail(detail, t);
    csv_quoted(b, std::string_view(detail.data(), detail.size()));
    b.push_back(',');
}

}  // namespace dpscope
