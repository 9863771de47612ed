// The wording of Danfoss FC protocol telegrams, shared by the renderers. Everything here reads
// what FcDecoder stored in DecodedTelegram::fc; nothing parses bytes again.
#include "protocols/fc/fc_describe.hpp"

#include <algorithm>
#include <iterator>

#include "formats/describe.hpp"
#include "formats/parameter_names.hpp"
#include "protocols/fc/fc_codes.hpp"
#include "protocols/profibus/pcd.hpp"

namespace dpscope {

void append_fc_parameter_name(TextBuffer& out, std::uint16_t pnu) {
    put(out, pnu / 100, '-');
    append_decimal_padded(out, pnu % 100, 2);
}

std::string fc_parameter_name(std::uint16_t pnu) {
    TextBuffer text;
    append_fc_parameter_name(text, pnu);
    return fmt::to_string(text);
}

std::string_view fc_ak_meaning(const DecodedTelegram& t) {
    // AK 15 is "read text" in seed 001, "read/write text" in the FC 102 guide: IND's high byte
    // 0x05 asks to write it.
    if (t.direction == Direction::Request && t.fc.pkw.rc == 15 && t.fc.ind_high == kFcTextWrite)
        return "Write text";
    return t.direction == Direction::Request ? fc_command(t.fc.pkw.rc).meaning
                                             : fc_response(t.fc.pkw.rc).meaning;
}

bool fc_ak_defined(const DecodedTelegram& t) {
    return t.direction == Direction::Request
               ? fc_command(t.fc.pkw.rc).defined
               : fc_response(t.fc.pkw.rc).kind != ResponseKind::Undefined;
}

ValueWidth fc_ak_width(const DecodedTelegram& t) {
    return t.direction == Direction::Request ? fc_command(t.fc.pkw.rc).width
                                             : fc_response(t.fc.pkw.rc).width;
}

bool fc_rejected(const DecodedTelegram& t) {
    return t.fc.has_pkw && t.direction == Direction::Response &&
           fc_response(t.fc.pkw.rc).kind == ResponseKind::Rejected;
}

std::uint16_t fc_fault_code(const FcTelegram& fc) {
    return static_cast<std::uint16_t>(fc.pkw.pva & 0xFFFF);
}

std::string_view fc_fault_text_or_unknown(std::uint32_t code) {
    std::string_view text = fc_fault_text(code);
    return text.empty() ? kUnknownFaultCode : text;
}

std::string_view fc_text_mode_name(std::uint8_t ind_high) {
    if (ind_high == kFcTextRead) return "read";
    if (ind_high == kFcTextWrite) return "write";
    return "";
}

void append_fc_text(TextBuffer& out, Bytes text) {
    for (std::uint8_t c : text) {
        if (c == '"' || c == '\\') {
            out.push_back('\\');
            out.push_back(static_cast<char>(c));
        } else if (c >= 0x20 && c < 0x7F) {
            out.push_back(static_cast<char>(c));
        } else {
            append(out, "\\x");
            append_hex_fixed(out, c, 2);
        }
    }
}

void append_fc_address(TextBuffer& out, const FcTelegram& fc) {
    put(out, "ADR 0x", hex(fc.adr, 2), " (", fc_address_format_name(fc.address_format),
        fc.broadcast ? ", broadcast)" : ")");
}

namespace {

void append_fc_pkw(TextBuffer& out, const DecodedTelegram& t) {
    const FcTelegram& fc = t.fc;
    put(out, "AK=", fc.pkw.rc, ' ', fc_ak_meaning(t));
    // The name as its database writes it (issue 29), else the FC series' group and number.
    const TelegramParameterView view = parameter_view(t);
    put(out, " PNU=", fc.pkw.pnu);
    if (view.named.row) {
        append_parameter_name(out, view.named);
    } else {
        append(out, " (");
        append_fc_parameter_name(out, fc.pkw.pnu);
        out.push_back(')');
    }
    put(out, " IND=", fc.pkw.ind);
    if (fc.block == FcBlock::Text) {
        std::string_view mode = fc_text_mode_name(fc.ind_high);
        if (mode.empty())
            put(out, " IND high 0x", hex(fc.ind_high, 2));
        else
            put(out, ' ', mode, " text");
        append(out, " \"");
        append_fc_text(out, fc.text);
        out.push_back('"');
        return;
    }
    if (fc_rejected(t)) {
        const std::uint16_t code = fc_fault_code(fc);
        put(out, " fault ", code, " (", fc_fault_text_or_unknown(code), ')');
        return;
    }
    put(out, " PWE=", pcv_value(fc.pkw, fc_ak_width(t)));
    append_view_value(out, view);
}

}  // namespace

void append_fc_detail(TextBuffer& out, const DecodedTelegram& t) {
    const FcTelegram& fc = t.fc;
    if (!t.has_roles) {  // no address byte: the bytes there are
        append_hex(out, t.bytes.first(std::min<std::size_t>(t.bytes.size(), 16)));
        return;
    }
    append_fc_address(out, fc);
    if (fc.has_pkw) {
        out.push_back(' ');
        append_fc_pkw(out, t);
    }
    if (fc.has_pcd) {
        put(out, " | ", pcd_word_name(t.direction, 0), "=0x", hex(fc.pcd1, 4), ' ',
            pcd_word_name(t.direction, 1), '=');
        append_hundredths(out, reference_percent_hundredths(fc.pcd2));
        out.push_back('%');
    }
    if (!fc.has_pkw && !fc.has_pcd && t.bytes.size() > 3) {  // cut short, or no known block
        Bytes data = t.bytes.subspan(3);
        append(out, " data ");
        append_hex(out, data.first(std::min<std::size_t>(data.size(), 16)));
        if (data.size() > 16) append(out, " ...");
    }
}

}  // namespace dpscope
