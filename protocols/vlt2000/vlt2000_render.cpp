// A VLT 2000 telegram in the telegram formats (formats/protocol_rendering.hpp): the text line's
// columns (the master "M", the drive's two-digit address or "all", frame type "VLT", the control
// letter with its name as the service), the csv columns that apply to it, the jsonl "vlt2000"
// object (docs/formats.md), and the verbose tree field by field with the byte numbers of each as
// the manual counts them, from 1 ([5-8] the control or status word, all 16 bits).
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
#include "protocols/vlt2000/vlt2000_describe.hpp"

namespace dpscope {

// ---- text

namespace {

// The drive's address as the text columns show it: "{:02}" in a column of three, on the right
// (a reply's source) or on the left (a command's destination).
void put_vlt2000_address(TextBuffer& b, unsigned address, bool right) {
    const int digits = address < 10 ? 2 : text_detail::decimal_digits(address);
    if (right && digits < 3) b.push_back(' ');
    append_decimal_padded(b, address, 2);
    if (!right && digits < 3) b.push_back(' ');
}

}  // namespace

// The VLT 2000 master has no address either ("M"); a drive is shown by its two-digit address
// as the telegram carries it, a broadcast (00) goes to "all".
void vlt2000_text_columns(TextBuffer& b, const DecodedTelegram& t) {
    if (!t.has_roles) {
        append(b, "  ? → ?   ");
    } else {
        // A reply with address 00 (nobody should send one) comes from "00".
        if (t.direction == Direction::Request) {
            append(b, "  M → ");
            if (t.vlt2000.broadcast)
                append(b, "all");
            else
                put_vlt2000_address(b, t.vlt2000.address, false);
            b.push_back(' ');
        } else {
            put_vlt2000_address(b, t.vlt2000.address, true);
            append(b, " → M   ");
        }
    }
    append(b, t.has_roles ? "VLT " : "bad ");
    if (t.has_roles) {
        const std::size_t at = b.size();
        append_vlt2000_letter(b, t);
        const std::size_t shown =
            text_detail::shown_width(std::string_view(b.data() + at, b.size() - at));
        if (shown < 14) text_detail::append_spaces(b, 14 - shown);
    } else {
        append(b, "-             ");
    }
    append(b, t.direction == Direction::Request ? " req " : " rsp ");
    append_vlt2000_detail(b, t);
}

// ---- csv

// The same columns for a VLT 2000 telegram (docs/formats.md): sd, da, sa, dsap, ssap, fc, ppo, rc
// and spm stay empty; service is the control letter with its name ("U update"); slave the
// drive's address (0: broadcast); fcs_ok whether the checksum is right or "??" (not checked);
// pnu the parameter (not for C), ind the index of an I telegram, pva the value with its
// decimal point, meaning the letter's name, error and error_text a failed reply's reason code
// and its text; pcd the control or status word in hex.
void vlt2000_csv_columns(TextBuffer& b, const DecodedTelegram& t) {
    const Vlt2000Telegram& v = t.vlt2000;
    put(b, t.frame, ',');
    if (t.has_time()) append_epoch_seconds(b, t.time_ns);
    put(b, ',', t.bytes.size(), ",,,,,,,");
    if (vlt2000_has_letter(t)) {
        TextBuffer letter;
        append_vlt2000_letter(letter, t);
        csv_quoted(b, std::string_view(letter.data(), letter.size()));
    }
    put(b, ',', direction_name(t.direction), ',');
    csv_optional(b, t.has_roles, t.master);
    csv_optional(b, t.has_roles, t.slave);
    csv_optional(b, t.request_frame != 0, static_cast<unsigned>(t.request_frame));
    append(b, v.checksum_ok || v.checksum_disabled ? "true,,,," : "false,,,,");
    csv_optional(b, v.has_parameter && v.letter != Vlt2000Letter::Control, v.parameter);
    csv_optional(b, v.letter == Vlt2000Letter::ReadIndex && v.has_index_number, v.index_number);
    if (v.has_value && vlt2000_carries_value(v)) append_vlt2000_value(b, v);
    b.push_back(',');
    if (vlt2000_has_letter(t)) csv_quoted(b, vlt2000_letter_name(v.letter));
    b.push_back(',');
    csv_optional(b, v.failed && v.has_reason, v.reason);
    if (v.failed) csv_quoted(b, vlt2000_reason_or_unknown(v));
    b.push_back(',');
    if (v.has_word) append_hex_fixed(b, v.word, 4);
    b.push_back(',');
    TextBuffer detail;
    append_vlt2000_detail(detail, t);
    csv_quoted(b, std::string_view(detail.data(), detail.size()));
    b.push_back(',');
}

// ---- jsonl

// The VLT 2000 keys between "len" and "problems": the common header keys and the "vlt2000"
// object (docs/formats.md, "VLT 2000 telegrams"); no FDL or DP key.
void vlt2000_jsonl_keys(JsonWriter& w, const DecodedTelegram& t) {
    const Vlt2000Telegram& v = t.vlt2000;
    w.key("direction").name(direction_name(t.direction));
    jsonl_role_keys(w, t);
    w.key("vlt2000").begin_object();
    w.key("complete").boolean(v.complete);
    w.key("address").optional_integer(t.has_roles, v.address);
    w.key("broadcast");
    optional_boolean(w, t.has_roles, v.broadcast);
    const bool letter = vlt2000_has_letter(t);
    w.key("letter");
    if (letter) {
        TextBuffer chars;  // as append_fc_text writes it: \xNN for what is not printable
        append_fc_text(chars, t.bytes.subspan(kVlt2000LetterAt, 1));
        w.string(std::string_view(chars.data(), chars.size()));
    } else
        w.null();
    w.key("letter_name");
    optional_name(w, letter, vlt2000_letter_name(v.letter));
    w.key("word_name");
    optional_name(w, v.has_word, vlt2000_word_name(t.direction));
    w.key("word").optional_integer(v.has_word, v.word);
    // The meaning of each bit 0..15 in the state it has ("group kept (P)" for a kept group).
    w.key("word_bits");
    if (v.has_word) {
        // Keyed by the word, its kept groups and the direction (control or status bits).
        thread_local BitMeaningsJson arrays;
        const std::uint32_t key = v.word | (static_cast<std::uint32_t>(v.word_keep) & 0xFu) << 16 |
                                  (t.direction == Direction::Request ? 1u : 0u) << 20;
        w.json_text(arrays.array(
            &arrays, key, [&](unsigned bit) { return vlt2000_bit_meaning(v, t.direction, bit); }));
    } else {
        w.null();
    }
    w.key("word_kept");
    if (v.has_word) {
        w.begin_array();
        for (unsigned group = 0; group < 4; ++group)
            if ((v.word_keep >> group) & 1u) w.integer(group);
        w.end_array();
    } else {
        w.null();
    }
    w.key("parameter").optional_integer(v.has_parameter, v.parameter);
    const bool value = v.has_value && vlt2000_carries_value(v);
    w.key("negative");
    optional_boolean(w, value, v.negative);
    w.key("digits").optional_integer(value, v.digits);
    w.key("value_text");
    const std::string text = value ? vlt2000_value_text(v) : std::string();
    optional_text(w, value, text);
    w.key("value");
    if (value)
        w.number_text(text);
    else
        w.null();
    const std::string note = value ? vlt2000_value_note(v) : std::string();
    w.key("value_note");
    optional_text(w, !note.empty(), note);
    w.key("decimals").optional_integer(v.has_decimals, v.decimals);
    // The parameter's row in its database (issue 29): its name, the value (which carries its own
    // decimal point) and the unit.
    parameter_jsonl_keys(w, parameter_view(t));
    const bool index = v.letter == Vlt2000Letter::ReadIndex && !v.index.empty();
    w.key("index");
    if (index) {
        TextBuffer chars;
        append_vlt2000_index(chars, v);
        w.string(std::string_view(chars.data(), chars.size()));
    } else {
        w.null();
    }
    w.key("index_number").optional_integer(index && v.has_index_number, v.index_number);
    w.key("failed");
    optional_boolean(w, v.has_decimals, v.failed);
    w.key("reason").optional_integer(v.failed && v.has_reason, v.reason);
    w.key("reason_text");
    optional_text(w, v.failed, vlt2000_reason_or_unknown(v));
    const bool checksum_there =
        t.bytes.size() >= kVlt2000ChecksumAt + 2 && t.bytes[0] == kVlt2000Start;
    w.key("checksum").optional_integer(v.has_checksum, v.checksum);
    w.key("checksum_computed").optional_integer(checksum_there, v.checksum_computed);
    w.key("checksum_disabled");
    optional_boolean(w, checksum_there, v.checksum_disabled);
    w.key("checksum_ok");
    optional_boolean(w, v.has_checksum, v.checksum_ok);
    w.end_object();
}

// ---- verbose

namespace {

class Vlt2000VerboseTree final : public VerboseTree {
  public:
    using VerboseTree::VerboseTree;

  private:
    // The characters of bytes [at, at + count) as sent, quoted ('"' and '\\' escaped, other bytes
    // \xNN), appended to `out`.
    static void append_chars(TextBuffer& out, const DecodedTelegram& t, std::size_t at,
                             std::size_t count) {
        out.push_back('"');
        append_fc_text(out, t.bytes.subspan(at, count));
        out.push_back('"');
    }
    // The same as a string, for a field's format; and appended to the tree's buffer.
    static std::string chars(const DecodedTelegram& t, std::size_t at, std::size_t count) {
        TextBuffer text;
        append_chars(text, t, at, count);
        return fmt::to_string(text);
    }
    void put_chars(const DecodedTelegram& t, std::size_t at, std::size_t count) {
        append_chars(buffer(), t, at, count);
    }

    // `label` and a two-digit number ("{:02}").
    static void put_two_digits(TextBuffer& b, std::string_view label, unsigned value) {
        append(b, label);
        append_decimal_padded(b, value, 2);
    }

  public:
    // The VLT 2000 telegram field by field, from what Vlt2000Decoder stored; each field with its
    // byte numbers as the manual counts them, from 1 ("[5-8]": offsets 4-7), and as far as the
    // record reaches.
    void render_vlt2000(const DecodedTelegram& t) {
        const Vlt2000Telegram& v = t.vlt2000;
        TextBuffer& b = buffer();
        const bool request = t.direction == Direction::Request;
        const std::size_t size = t.bytes.size();
        const auto has = [&](std::size_t at, std::size_t count) { return at + count <= size; };
        append(b, "VLT 2000 telegram");
        if (t.has_roles) {
            append(b, ": ");
            append_vlt2000_letter(b, t);
            append(b, request ? " command" : " reply");
            if (v.broadcast && request)
                append(b, " to every drive (broadcast, address 00)");
            else if (v.broadcast)
                append(b, " from address 00 (a broadcast; nobody should reply)");
            else
                put_two_digits(b, request ? " to drive " : " from drive ", v.address);
            if (t.request_frame != 0) put(b, ", answers frame ", t.request_frame);
        }
        b.push_back('\n');
        if (size == 0) return;
        if (t.bytes[0] != kVlt2000Start) {
            field(1, FMT_COMPILE("[1] Start: {} (not '<')"), chars(t, 0, 1));
            return;
        }
        put_line(1, "[1] Start: '<'");
        if (!has(kVlt2000AddressAt, 2)) return;
        if (t.has_roles) {
            line(1, "");
            put_two_digits(b, "[2-3] Address: ", v.address);
            put(b, v.broadcast ? " (broadcast: every drive acts, none replies)\n" : "\n");
        } else
            field(1, FMT_COMPILE("[2-3] Address: {} (not two digits)"),
                  chars(t, kVlt2000AddressAt, 2));
        if (!has(kVlt2000LetterAt, 1)) return;
        line(1, "[4] Control letter: ");
        put_chars(t, kVlt2000LetterAt, 1);
        put(b, " (", vlt2000_letter_name(v.letter),
            v.letter == Vlt2000Letter::Unknown ? ": not U, R, C or I)\n" : ")\n");
        if (!has(kVlt2000WordAt, 4)) return;
        line(1, request ? "[5-8] Control word: " : "[5-8] Status word: ");
        put_chars(t, kVlt2000WordAt, 4);
        put(b, " = 0x", hex(v.word, 4), request ? " (to the drive)\n" : " (from the drive)\n");
        for (unsigned bit = 0; bit < 16; ++bit) {
            if (vlt2000_bit_kept(v, bit)) {
                if (bit % 4 == 0) put_line(2, "bits ", bit, '-', bit + 3, ": group kept (P)");
                continue;
            }
            put_line(2, bit < 10 ? "bit  " : "bit ", bit,
                     (v.word >> bit) & 1u ? " = 1: " : " = 0: ",
                     vlt2000_bit_meaning(v, t.direction, bit));
        }
        if (!has(kVlt2000ParameterAt, 4)) return;
        const bool control = v.letter == Vlt2000Letter::Control;
        const std::string_view ignored = control ? " (ignored with C)" : "";
        if (v.has_parameter)
            put_line(1, "[9-12] Parameter: ", v.parameter, ignored);
        else
            field(1, FMT_COMPILE("[9-12] Parameter: {} (not four digits)"),
                  chars(t, kVlt2000ParameterAt, 4));
        const TelegramParameterView view = parameter_view(t);
        if (view.named.row) {
            TextBuffer details;
            append_parameter_details(details, view.named);
            field(2, FMT_COMPILE("name: {}"), std::string_view(details.data(), details.size()));
        }
        if (!has(kVlt2000SignAt, 1)) return;
        if (v.letter == Vlt2000Letter::ReadIndex && !v.index.empty()) {
            if (v.has_index_number)
                field(1, FMT_COMPILE("[13-18] Index: {} = {}"), chars(t, kVlt2000SignAt, 6),
                      v.index_number);
            else
                field(1, FMT_COMPILE("[13-18] Index: {} (not a number)"),
                      chars(t, kVlt2000SignAt, 6));
        } else {
            line(1, "[13] Sign: ");
            put_chars(t, kVlt2000SignAt, 1);
            put(b, v.negative ? " (negative)" : " (positive)", ignored, '\n');
            if (!has(kVlt2000ValueAt, 5)) return;
            if (v.failed) {
                field(1, FMT_COMPILE("[14-18] Value: {} (none: the command failed)"),
                      chars(t, kVlt2000ValueAt, 5));
            } else if (v.has_value) {
                line(1, "[14-18] Value: ");
                append_decimal_padded(b, v.digits, 5);
                append(b, " = ");
                append_vlt2000_value(b, v);
                if (!v.has_decimals || v.decimals > 5) put(b, " (", vlt2000_value_note(v), ')');
                append(b, ignored);
                b.push_back('\n');
                if (view.value && !view.named.row->unit.empty())
                    field(2, FMT_COMPILE("in its unit: {} {}"), vlt2000_value_text(v),
                          view.named.row->unit);
            } else {
                field(1, FMT_COMPILE("[14-18] Value: {} (not five digits)"),
                      chars(t, kVlt2000ValueAt, 5));
            }
        }
        if (v.failed) {
            if (v.has_reason)
                field(2, FMT_COMPILE("[17-18] Reason code: {:02} = {}"), v.reason,
                      vlt2000_reason_or_unknown(v));
            else
                field(2, FMT_COMPILE("[17-18] Reason code: {} ({})"), chars(t, kVlt2000ReasonAt, 2),
                      vlt2000_reason_or_unknown(v));
        }
        if (!has(kVlt2000DecimalsAt, 1)) return;
        if (!v.has_decimals)
            field(1, FMT_COMPILE("[19] Decimal position: {} (not a digit)"),
                  chars(t, kVlt2000DecimalsAt, 1));
        else if (v.failed)
            field(1, FMT_COMPILE(
                         "[19] Decimal position: 9 (unknown parameter or the command failed)"));
        else if (v.decimals > 5)
            field(1, FMT_COMPILE("[19] Decimal position: {} (out of range 0-5)"), v.decimals);
        else
            put_line(1, "[19] Decimal position: ", v.decimals);
        if (has(kVlt2000ChecksumAt, 2)) {
            line(1, "[20-21] Checksum: ");
            append_vlt2000_checksum(b, t);
            b.push_back('\n');
        } else {
            field(1, FMT_COMPILE("[20-21] Checksum: missing (telegram cut short)"));
            return;
        }
        if (!has(kVlt2000StopAt, 1)) return;
        if (t.bytes[kVlt2000StopAt] == kVlt2000Stop)
            put_line(1, "[22] Stop: '>'");
        else
            field(1, FMT_COMPILE("[22] Stop: {} (not '>')"), chars(t, kVlt2000StopAt, 1));
    }
};

}  // namespace

void vlt2000_verbose(TextBuffer& b, const DecodedTelegram& t) {
    Vlt2000VerboseTree(b).render_vlt2000(t);
}

}  // namespace dpscope
