// The wording of VLT 2000 serial telegrams, shared by the renderers. Everything here reads what
// Vlt2000Decoder stored in DecodedTelegram::vlt2000; nothing parses the characters again, except
// for showing those of a field that is not what it should be.
#include "protocols/vlt2000/vlt2000_describe.hpp"

#include <algorithm>
#include <cstring>
#include <iterator>
#include <string>
#include <vector>

#include "formats/describe.hpp"
#include "formats/parameter_names.hpp"
#include "protocols/fc/fc_describe.hpp"
#include "protocols/vlt2000/vlt2000_codes.hpp"

namespace dpscope {

bool vlt2000_has_letter(const DecodedTelegram& t) {
    return t.has_roles && t.bytes.size() > kVlt2000LetterAt;
}

void append_vlt2000_letter(TextBuffer& out, const DecodedTelegram& t) {
    if (!vlt2000_has_letter(t)) {
        append(out, "none");
        return;
    }
    const Vlt2000Telegram& v = t.vlt2000;
    if (v.letter_char > 0x20 && v.letter_char < 0x7F)
        out.push_back(static_cast<char>(v.letter_char));
    else
        append_hex_byte(out, v.letter_char);
    put(out, ' ', vlt2000_letter_name(v.letter));
}

std::string vlt2000_letter_text(const DecodedTelegram& t) {
    TextBuffer text;
    append_vlt2000_letter(text, t);
    return fmt::to_string(text);
}

std::string_view vlt2000_word_name(Direction direction) {
    return direction == Direction::Request ? "control" : "status";
}

std::string_view vlt2000_word_short_name(Direction direction) {
    return direction == Direction::Request ? "CTW" : "STW";
}

bool vlt2000_bit_kept(const Vlt2000Telegram& v, unsigned bit) {
    return bit < 16 && ((v.word_keep >> (bit / 4)) & 1u) != 0;
}

std::string_view vlt2000_bit_meaning(const Vlt2000Telegram& v, Direction direction, unsigned bit) {
    if (vlt2000_bit_kept(v, bit)) return "group kept (P)";
    const Vlt2000Bit& meaning =
        direction == Direction::Request ? vlt2000_control_bit(bit) : vlt2000_status_bit(bit);
    return (v.word >> bit) & 1u ? meaning.when_1 : meaning.when_0;
}

void append_vlt2000_word(TextBuffer& out, const Vlt2000Telegram& v, Direction direction) {
    put(out, vlt2000_word_short_name(direction), "=0x", hex(v.word, 4), " (");
    const std::size_t start = out.size();
    const auto separate = [&out, start](std::string_view separator) {
        if (out.size() != start) append(out, separator);
    };
    for (unsigned group = 0; group < 4; ++group)
        if ((v.word_keep >> group) & 1u) {
            separate(", ");
            put(out, "bits ", 4 * group, '-', 4 * group + 3, " group kept (P)");
        }
    // The meanings of the bits that are 1, and of those that are 0 where 0 is worth naming (an
    // OFF, a stop, "out of frequency range"), each meaning once. A control word without "data
    // valid" (bit 10) acts on nothing: its other 0 bits are not named.
    const bool control = direction == Direction::Request;
    const bool acts = !control || ((v.word >> 10) & 1u) != 0;
    std::string_view named[16];
    std::size_t named_count = 0;
    const std::size_t kept_end = out.size();
    for (unsigned bit = 0; bit < 16; ++bit) {
        if (vlt2000_bit_kept(v, bit)) continue;
        const bool set = ((v.word >> bit) & 1u) != 0;
        const Vlt2000Bit& row = control ? vlt2000_control_bit(bit) : vlt2000_status_bit(bit);
        if (!set && !(row.notable_0 && (acts || bit == 10))) continue;
        const std::string_view meaning = vlt2000_bit_meaning(v, direction, bit);
        const bool first_bit = out.size() == kept_end;
        if (meaning == "no function") {
            separate(first_bit ? "; " : ", ");
            put(out, "bit ", bit, " (no function)");
        } else if (std::find(named, named + named_count, meaning) == named + named_count) {
            separate(first_bit ? "; " : ", ");
            append(out, meaning);
            named[named_count++] = meaning;
        }
    }
    if (out.size() == start) append(out, "no bit set");
    out.push_back(')');
}

void append_vlt2000_value(TextBuffer& out, const Vlt2000Telegram& v) {
    const bool with_point = v.has_decimals && v.decimals > 0 && v.decimals <= 5;
    if (v.negative && v.digits != 0) out.push_back('-');
    if (!with_point) {
        append_decimal(out, v.digits);
        return;
    }
    const std::size_t at = out.size();
    append_decimal_padded(out, v.digits, v.decimals + 1);
    // The point goes before the last `decimals` digits.
    out.push_back('0');
    char* digits = out.data() + at;
    const std::size_t length = out.size() - at - 1;
    std::memmove(digits + length - v.decimals + 1, digits + length - v.decimals, v.decimals);
    digits[length - v.decimals] = '.';
}

std::string vlt2000_value_text(const Vlt2000Telegram& v) {
    TextBuffer text;
    append_vlt2000_value(text, v);
    return fmt::to_string(text);
}

std::string vlt2000_value_note(const Vlt2000Telegram& v) {
    if (!v.has_decimals)
        return fmt::format("no decimal position (byte {} is not a digit): the digits as sent",
                           kVlt2000DecimalsAt + kVlt2000FirstByteNumber);
    if (v.decimals > 5 && !v.failed)
        return fmt::format("decimal position {} is out of range (0-5): the digits as sent",
                           v.decimals);
    return {};
}

std::string_view vlt2000_reason_or_unknown(const Vlt2000Telegram& v) {
    if (!v.has_reason) return "no reason code given";
    const std::string_view text = vlt2000_reason_text(v.reason);
    return text.empty() ? "unknown reason code" : text;
}

bool vlt2000_carries_value(const Vlt2000Telegram& v) {
    return v.letter != Vlt2000Letter::Control && !v.failed &&
           !(v.letter == Vlt2000Letter::ReadIndex && !v.index.empty());
}

void append_vlt2000_index(TextBuffer& out, const Vlt2000Telegram& v) {
    append_fc_text(out, v.index);
}

bool vlt2000_checksum_judged_wrong(const DecodedTelegram& t) {
    const ProblemList& problems = t.vlt2000.problems;
    return std::any_of(problems.begin(), problems.end(), [](const Problem& p) {
        return p.kind == ProblemKind::Vlt2000ChecksumMismatch;
    });
}

void append_vlt2000_checksum(TextBuffer& out, const DecodedTelegram& t) {
    const Vlt2000Telegram& v = t.vlt2000;
    auto it = std::back_inserter(out);
    if (t.bytes.size() < kVlt2000ChecksumAt + 2 || t.bytes.empty() || t.bytes[0] != kVlt2000Start) {
        append(out, "missing (telegram cut short)");
        return;
    }
    if (v.checksum_disabled) {
        fmt::format_to(it, "?? (not checked; computed {:02})", v.checksum_computed);
    } else if (!v.has_checksum) {
        append(out, "\"");
        append_fc_text(out, t.bytes.subspan(kVlt2000ChecksumAt, 2));
        fmt::format_to(it, "\" (not two digits; computed {:02})", v.checksum_computed);
    } else if (v.checksum_ok) {
        fmt::format_to(it, "{:02} (correct)", v.checksum);
    } else {
        fmt::format_to(
            it, "{:02} (wrong: computed {:02}{})", v.checksum, v.checksum_computed,
            vlt2000_checksum_judged_wrong(t) ? "" : "; not judged, --vlt2000-checksum ignore");
    }
}

namespace {

// "reason 03 (text)", or the text alone when the reply gives no reason code.
void append_vlt2000_reason(TextBuffer& out, const Vlt2000Telegram& v) {
    if (v.has_reason) {
        append(out, "reason ");
        append_decimal_padded(out, v.reason, 2);
        put(out, " (", vlt2000_reason_or_unknown(v), ')');
    } else {
        append(out, vlt2000_reason_or_unknown(v));
    }
}

}  // namespace

void append_vlt2000_detail(TextBuffer& out, const DecodedTelegram& t) {
    const Vlt2000Telegram& v = t.vlt2000;
    if (!t.has_roles) {  // no address: the characters there are
        const Bytes shown = t.bytes.first(std::min<std::size_t>(t.bytes.size(), 24));
        out.push_back('"');
        append_fc_text(out, shown);
        out.push_back('"');
        if (t.bytes.size() > shown.size()) append(out, " ...");
        return;
    }
    bool first = true;
    const auto space = [&] {
        if (!first) out.push_back(' ');
        first = false;
    };
    if (v.has_word) {
        space();
        append_vlt2000_word(out, v, t.direction);
    }
    // A C telegram's parameter and value are ignored by the drive.
    if (v.has_parameter && v.letter != Vlt2000Letter::Control) {
        space();
        put(out, "parameter ", v.parameter);
        const TelegramParameterView view = parameter_view(t);
        append_parameter_name(out, view.named);
        if (v.letter == Vlt2000Letter::ReadIndex && !v.index.empty()) {
            if (v.has_index_number) {
                put(out, " index ", v.index_number);
            } else {
                append(out, " index \"");
                append_vlt2000_index(out, v);
                out.push_back('"');
            }
        }
        if (v.failed) {
            append(out, " failed: ");
            append_vlt2000_reason(out, v);
        } else if (v.has_value && vlt2000_carries_value(v) &&
                   !(t.direction == Direction::Request && v.letter == Vlt2000Letter::Read)) {
            // A read command's value is not used: the drive fills it in.
            append(out, " = ");
            append_vlt2000_value(out, v);
            // The value carries its own decimal point: its database adds the unit (issue 29).
            if (view.value && !view.named.row->unit.empty()) put(out, ' ', view.named.row->unit);
            if (!v.has_decimals || (v.decimals > 5 && !v.failed))
                put(out, " (", vlt2000_value_note(v), ')');
        }
    } else if (v.failed) {
        space();
        append(out, "failed: ");
        append_vlt2000_reason(out, v);
    }
    // The checksum only when it is not right (a wrong one is also a problem on the line).
    if (v.complete && !v.checksum_ok) {
        space();
        append(out, "checksum ");
        append_vlt2000_checksum(out, t);
    }
}

}  // namespace dpscope
