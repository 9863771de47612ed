// A toybus telegram in the telegram formats (formats/protocol_rendering.hpp): the text line's
// columns (the master "M", the drive's two-digit address, frame type "TOY", the lead character
// with its kind as the service), the csv columns that apply, the jsonl "toybus" object and the
// verbose tree field by field.
#include <iterator>

#include "formats/field_writers.hpp"
#include "formats/protocol_rendering.hpp"
#include "formats/verbose_tree.hpp"
#include "protocols/toybus/toybus_describe.hpp"

namespace dpscope {

void toybus_text_columns(TextBuffer& b, const DecodedTelegram& t) {
    auto it = std::back_inserter(b);
    if (!t.has_roles) {
        append(b, "  ? → ?   ");
    } else {
        const std::string drive = fmt::format("{:02}", t.toybus.address);
        if (t.direction == Direction::Request)
            fmt::format_to(it, "{:>3} → {:<3} ", "M", drive);
        else
            fmt::format_to(it, "{:>3} → {:<3} ", drive, "M");
    }
    fmt::format_to(it, "{:<3} {:<14} {} ", t.has_roles ? "TOY" : "bad", toybus_kind_text(t.toybus),
                   t.direction == Direction::Request ? "req" : "rsp");
    append_toybus_detail(b, t);
}

// The shared csv columns (docs/formats.md): service is the kind ("? read"), pnu the parameter,
// pva the value, error the error number; the FDL, PPO, checksum and PCD columns stay empty.
void toybus_csv_columns(TextBuffer& b, const DecodedTelegram& t) {
    auto it = std::back_inserter(b);
    const ToybusTelegram& v = t.toybus;
    fmt::format_to(it, "{},", t.frame);
    if (t.has_time()) append_epoch_seconds(b, t.time_ns);
    fmt::format_to(it, ",{},,,,,,,", t.bytes.size());
    csv_quoted(b, toybus_kind_text(v));
    fmt::format_to(it, ",{},", direction_name(t.direction));
    csv_optional(b, t.has_roles, t.master);
    csv_optional(b, t.has_roles, t.slave);
    csv_optional(b, t.request_frame != 0, static_cast<unsigned>(t.request_frame));
    append(b, ",,,,");  // fcs_ok, ppo, rc, spm
    csv_optional(b, v.has_parameter, v.parameter);
    b.push_back(',');  // ind
    csv_optional(b, v.has_value, v.value);
    csv_quoted(b, toybus_kind_name(v.kind));
    b.push_back(',');
    csv_optional(b, v.has_error, v.error);
    append(b, ",,");  // error_text, pcd
    TextBuffer detail;
    append_toybus_detail(detail, t);
    csv_quoted(b, std::string_view(detail.data(), detail.size()));
    b.push_back(',');
}

// The keys between "len" and "problems": the common header keys and the "toybus" object.
void toybus_jsonl_keys(JsonWriter& w, const DecodedTelegram& t) {
    const ToybusTelegram& v = t.toybus;
    w.key("direction").string(direction_name(t.direction));
    jsonl_role_keys(w, t);
    w.key("toybus").begin_object();
    w.key("kind").string(toybus_kind_name(v.kind));
    w.key("complete").boolean(v.complete);
    w.key("address").optional_integer(v.has_address, v.address);
    w.key("parameter").optional_integer(v.has_parameter, v.parameter);
    w.key("value").optional_integer(v.has_value, v.value);
    w.key("error").optional_integer(v.has_error, v.error);
    w.key("crlf").boolean(v.crlf);
    w.end_object();
}

void toybus_verbose(TextBuffer& b, const DecodedTelegram& t) {
    const ToybusTelegram& v = t.toybus;
    VerboseTree tree(b);
    fmt::format_to(std::back_inserter(b), "toybus telegram: {} {}\n", toybus_kind_text(v),
                   t.direction == Direction::Request ? "request" : "response");
    if (v.has_address) tree.field(1, "[1-2] Drive: {:02}", v.address);
    if (v.has_parameter) tree.field(1, "[4-7] Parameter: {:04}", v.parameter);
    if (v.has_value) tree.field(1, "[9-13] Value: {:05}", v.value);
    if (v.has_error) tree.field(1, "[9-10] Error: {:02}", v.error);
    const bool ended = !t.bytes.empty() && t.bytes.back() == '\n';
    tree.field(1, "Line end: {}", !ended ? "missing" : v.crlf ? "CR LF" : "LF");
    if (t.request_frame != 0) tree.field(1, "Answers frame {}", t.request_frame);
}

}  // namespace dpscope
