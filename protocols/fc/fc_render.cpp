// An FC protocol telegram in the telegram formats (formats/protocol_rendering.hpp): the text
// line's columns (the master "M", the drive's address or "all", frame type "FC", the block as the
// service), the csv columns that apply to it, the jsonl "fc_protocol" object (docs/formats.md),
// and the verbose tree field by field (STX, LGE, ADR, PKE, IND, PWE or text, PCD 1 bits, PCD 2,
// BCC).
#include <fmt/compile.h>

#include <algorithm>
#include <iterator>
#include <span>
#include <string>
#include <vector>

#include "formats/bit_meanings_json.hpp"
#include "formats/describe.hpp"
#include "formats/field_writers.hpp"
#include "formats/parameter_names.hpp"
#include "formats/protocol_rendering.hpp"
#include "formats/verbose_tree.hpp"
#include "protocols/fc/fc_describe.hpp"

namespace dpscope {

// ---- text

// The FC master has no address ("M"); a broadcast goes to "all". The frame type column says
// "FC", the service column the block.
void fc_text_columns(TextBuffer& b, const DecodedTelegram& t) {
    if (!t.has_roles) {
        append(b, "  ? → ?   ");
    } else if (t.direction == Direction::Request) {
        append(b, "  M → ");
        if (t.fc.broadcast)
            append(b, "all");
        else
            append_decimal_left(b, t.fc.address, 3);
        b.push_back(' ');
    } else {
        if (t.fc.broadcast)
            append(b, "all");
        else
            append_decimal_right(b, t.fc.address, 3);
        append(b, " → M   ");
    }
    append(b, t.has_roles ? "FC  " : "bad ");
    append_left(b, fc_block_name(t.fc.block), 14);
    append(b, t.direction == Direction::Request ? " req " : " rsp ");
    append_fc_detail(b, t);
}

// ---- csv

// The same columns for an FC protocol telegram (docs/formats.md): sd, da, sa, dsap, ssap, fc,
// ppo and spm stay empty; service is the block; slave the drive (0: broadcast); fcs_ok the
// BCC; rc the AK, ind the index, pva PWE (per the AK's width), meaning the AK's name, error
// and error_text the AK 7 fault code and its text; pcd PCD 1 and PCD 2.
void fc_csv_columns(TextBuffer& b, const DecodedTelegram& t) {
    const FcTelegram& fc = t.fc;
    put(b, t.frame, ',');
    if (t.has_time()) append_epoch_seconds(b, t.time_ns);
    put(b, ',', t.bytes.size(), ",,,,,,,", fc_block_name(fc.block), ',',
        direction_name(t.direction), ',');
    csv_optional(b, t.has_roles, t.master);
    csv_optional(b, t.has_roles, t.slave);
    csv_optional(b, t.request_frame != 0, static_cast<unsigned>(t.request_frame));
    append(b, fc.bcc_ok ? "true,," : "false,,");
    if (fc.has_pkw) {
        const bool rejected = fc_rejected(t);
        const bool pwe = fc.block == FcBlock::Parameter && !rejected;
        put(b, fc.pkw.rc, ",,", fc.pkw.pnu, ',', fc.pkw.ind, ',');
        if (pwe) append_decimal(b, pcv_value(fc.pkw, fc_ak_width(t)));
        b.push_back(',');
        csv_quoted(b, fc_ak_meaning(t));
        b.push_back(',');
        if (rejected) {
            put(b, fc_fault_code(fc), ',');
            csv_quoted(b, fc_fault_text_or_unknown(fc_fault_code(fc)));
        } else {
            b.push_back(',');
        }
    } else {
        append(b, ",,,,,,,");
    }
    b.push_back(',');
    if (fc.has_pcd) put(b, hex(fc.pcd1, 4), ' ', hex(fc.pcd2, 4));
    b.push_back(',');
    TextBuffer detail;
    append_fc_detail(detail, t);
    csv_quoted(b, std::string_view(detail.data(), detail.size()));
    b.push_back(',');
}

// ---- jsonl

// The FC protocol keys between "len" and "problems": the common header keys and the
// "fc_protocol" object (docs/formats.md, "FC protocol lines"); no FDL or DP key.
void fc_jsonl_keys(JsonWriter& w, const DecodedTelegram& t) {
    const FcTelegram& fc = t.fc;
    const bool request = t.direction == Direction::Request;
    w.key("direction").name(direction_name(t.direction));
    jsonl_role_keys(w, t);
    w.key("fc_protocol").begin_object();
    const bool has_lge = t.bytes.size() >= 2 && t.bytes[0] == kFcStx;
    w.key("lge").optional_integer(has_lge, fc.lge);
    w.key("adr").optional_integer(t.has_roles, fc.adr);
    w.key("address").optional_integer(t.has_roles, fc.address);
    w.key("address_format");
    if (t.has_roles)
        w.name(fc_address_format_name(fc.address_format));
    else
        w.null();
    w.key("broadcast");
    if (t.has_roles)
        w.boolean(fc.broadcast);
    else
        w.null();
    w.key("block").name(fc_block_name(fc.block));
    w.key("complete").boolean(fc.complete);
    const Pcv& pkw = fc.pkw;
    w.key("pke").optional_integer(fc.has_pkw, pkw.pca);
    w.key("ak").optional_integer(fc.has_pkw, pkw.rc);
    w.key("ak_name");
    if (fc.has_pkw)
        w.string(fc_ak_meaning(t));
    else
        w.null();
    w.key("ak_known");
    if (fc.has_pkw)
        w.boolean(fc_ak_defined(t));
    else
        w.null();
    w.key("pnu").optional_integer(fc.has_pkw, pkw.pnu);
    w.key("parameter");
    if (fc.has_pkw)
        w.string(fc_parameter_name(pkw.pnu));
    else
        w.null();
    w.key("index").optional_integer(fc.has_pkw, pkw.ind);
    w.key("ind_high").optional_integer(fc.has_pkw, fc.ind_high);
    const bool text = fc.has_pkw && fc.block == FcBlock::Text;
    w.key("text_mode");
    if (text && !fc_text_mode_name(fc.ind_high).empty())
        w.string(fc_text_mode_name(fc.ind_high));
    else
        w.null();
    w.key("text");
    if (text) {
        TextBuffer chars;
        append_fc_text(chars, fc.text);
        w.string(std::string_view(chars.data(), chars.size()));
    } else {
        w.null();
    }
    w.key("text_hex");
    if (text)
        hex_string(w, fc.text);
    else
        w.null();
    const bool pwe = fc.has_pkw && fc.block == FcBlock::Parameter;
    const bool rejected = pwe && fc_rejected(t);
    const ValueWidth width = pwe ? fc_ak_width(t) : ValueWidth::None;
    w.key("pwe").optional_integer(pwe && !rejected, pcv_value(pkw, width));
    w.key("pwe_raw").optional_integer(pwe, pkw.pva);
    w.key("width");
    if (pwe && !rejected && width == ValueWidth::Word)
        w.string("word");
    else if (pwe && !rejected && width == ValueWidth::DoubleWord)
        w.string("dword");
    else
        w.null();
    // The parameter's row in its database (issue 29): name, value in its unit, unit.
    parameter_jsonl_keys(w, parameter_view(t));
    w.key("fault_code").optional_integer(rejected, fc_fault_code(fc));
    w.key("fault_text");
    if (rejected)
        w.string(fc_fault_text_or_unknown(fc_fault_code(fc)));
    else
        w.null();
    w.key("pcd1").optional_integer(fc.has_pcd, fc.pcd1);
    w.key("pcd1_word");
    if (fc.has_pcd)
        w.name(request ? "control" : "status");
    else
        w.null();
    // The meaning of each bit 0..15 in the state it has (FC profile; "" where none).
    w.key("pcd1_bits");
    if (fc.has_pcd) {
        const WordBits& bits = request ? control_word_bits(PcdProfile::Fc, true)
                                       : status_word_bits(PcdProfile::Fc, true);
        thread_local BitMeaningsJson arrays;
        w.json_text(arrays.array(&bits, fc.pcd1, [&](unsigned bit) {
            return (fc.pcd1 >> bit) & 1 ? bits[bit].when_1 : bits[bit].when_0;
        }));
    } else {
        w.null();
    }
    w.key("pcd2").optional_integer(fc.has_pcd, fc.pcd2);
    w.key("pcd2_percent");
    if (fc.has_pcd)
        w.raw_value([&](TextBuffer& out) {
            append_hundredths(out, reference_percent_hundredths(fc.pcd2));
        });
    else
        w.null();
    w.key("bcc").optional_integer(fc.complete, fc.bcc);
    w.key("bcc_computed").optional_integer(fc.complete, fc.bcc_computed);
    w.key("bcc_ok");
    if (fc.complete)
        w.boolean(fc.bcc_ok);
    else
        w.null();
    w.end_object();
}

// ---- verbose

namespace {

class FcVerboseTree final : public VerboseTree {
  public:
    using VerboseTree::VerboseTree;

    // The FC protocol telegram field by field, from what FcDecoder stored.
    void render_fc(const DecodedTelegram& t) {
        const FcTelegram& fc = t.fc;
        TextBuffer& b = buffer();
        auto it = fmt::appender(b);
        const bool request = t.direction == Direction::Request;
        append(b, "FC protocol");
        if (t.has_roles) {
            put(b, ": ", fc_block_name(fc.block), request ? " block request" : " block response");
            if (fc.broadcast)
                append(b, " to every drive (broadcast)");
            else
                put(b, request ? " to drive " : " from drive ", fc.address);
            if (t.request_frame != 0) put(b, ", answers frame ", t.request_frame);
        }
        b.push_back('\n');
        if (t.bytes.empty()) return;
        if (t.bytes[0] != kFcStx) {
            field(1, FMT_COMPILE("STX: 0x{:02X} (not STX 0x02)"), t.bytes[0]);
            return;
        }
        put_line(1, "STX: 0x02");
        if (t.bytes.size() < 2) return;
        if (fc.block == FcBlock::Unknown)
            field(1, FMT_COMPILE("LGE: {} (no block has this length; telegram {} bytes)"), fc.lge,
                  fc.lge + 2);
        else
            put_line(1, "LGE: ", fc.lge, " (", fc_block_name(fc.block), " block, telegram ",
                     fc.lge + 2, " bytes)");
        if (!t.has_roles) return;
        line(1, "");
        put(b, "ADR: 0x", hex(fc.adr, 2), " (", fc_address_format_name(fc.address_format),
            " format, ");
        if (fc.broadcast)
            append(b, "broadcast)\n");
        else
            put(b, "address ", fc.address, ")\n");
        if (fc.has_pkw) {
            const Pcv& pkw = fc.pkw;
            field(1, FMT_COMPILE("PKE: 0x{:04X}"), pkw.pca);
            field(2, FMT_COMPILE("AK: {} = {}{}"), pkw.rc, fc_ak_meaning(t),
                  fc_ak_defined(t)
                      ? ""
                      : (request ? " (not a defined command)" : " (not a defined response)"));
            field(2, FMT_COMPILE("PNU: {} (parameter {})"), pkw.pnu, fc_parameter_name(pkw.pnu));
            const TelegramParameterView view = parameter_view(t);
            if (view.named.row) {
                TextBuffer details;
                append_parameter_details(details, view.named);
                field(3, FMT_COMPILE("name: {}"), std::string_view(details.data(), details.size()));
            }
            field(1, FMT_COMPILE("IND: 0x{:02X}{:02X}"), fc.ind_high, pkw.ind_low);
            std::string_view mode = fc_text_mode_name(fc.ind_high);
            if (fc.block == FcBlock::Text && !mode.empty())
                field(2, FMT_COMPILE("high byte: 0x{:02X} ({} text)"), fc.ind_high, mode);
            else
                field(2, FMT_COMPILE("high byte: 0x{:02X}"), fc.ind_high);
            field(2, FMT_COMPILE("index (low byte): {}"), pkw.ind);
            if (fc.block == FcBlock::Text) {
                line(1, "");
                fmt::format_to(it, FMT_COMPILE("Text: {} characters \""), fc.text.size());
                append_fc_text(b, fc.text);
                append(b, "\"\n");
            } else if (fc_rejected(t)) {
                const std::uint16_t code = fc_fault_code(fc);
                field(1, FMT_COMPILE("PWE: 0x{:08X}"), pkw.pva);
                field(2, FMT_COMPILE("Fault code: {} = {}"), code, fc_fault_text_or_unknown(code));
            } else {
                const ValueWidth width = fc_ak_width(t);
                if (width == ValueWidth::Word)
                    field(1, FMT_COMPILE("PWE: 0x{:08X}, word value {}"), pkw.pva,
                          pcv_value(pkw, width));
                else if (width == ValueWidth::DoubleWord)
                    field(1, FMT_COMPILE("PWE: 0x{:08X}, double word value {}"), pkw.pva, pkw.pva);
                else
                    field(1, FMT_COMPILE("PWE: 0x{:08X} (the AK carries no value)"), pkw.pva);
                if (view.value && view.parameter.has_raw) {
                    TextBuffer value;
                    append_value_details(value, *view.named.row, *view.value);
                    field(2, FMT_COMPILE("in its unit: {}"),
                          std::string_view(value.data(), value.size()));
                }
            }
        }
        if (fc.has_pcd) {
            put_line(1, "PCD 1 ", pcd_word_name(t.direction, 0), ": 0x", hex(fc.pcd1, 4),
                     request ? " (control word, FC profile)" : " (status word, FC profile)");
            word_bit_fields(2, fc.pcd1,
                            request ? control_word_bits(PcdProfile::Fc, true)
                                    : status_word_bits(PcdProfile::Fc, true));
            field(1, FMT_COMPILE("PCD 2 {}: 0x{:04X} = {:.2f} %"), pcd_word_name(t.direction, 1),
                  fc.pcd2, reference_percent(fc.pcd2));
        }
        if (fc.complete) {
            if (fc.bcc_ok)
                put_line(1, "BCC: 0x", hex(fc.bcc, 2), " (correct)");
            else
                field(1, FMT_COMPILE("BCC: 0x{:02X} (wrong: computed 0x{:02X})"), fc.bcc,
                      fc.bcc_computed);
        } else {
            field(1, FMT_COMPILE("BCC: missing (telegram cut short)"));
        }
    }
};

}  // namespace

void fc_verbose(TextBuffer& b, const DecodedTelegram& t) { FcVerboseTree(b).render_fc(t); }

}  // namespace dpscope
