#include "capture/input_format.hpp"

#include <algorithm>
#include <cstdint>

namespace dpscope {

std::string_view input_format_name(InputFormat format) {
    switch (format) {
        case InputFormat::Auto: return "auto";
        case InputFormat::Pcap: return "pcap";
        case InputFormat::Pcapng: return "pcapng";
        case InputFormat::Raw: return "raw";
        case InputFormat::Hex: return "hex";
        case InputFormat::Serial: return "serial";
        case InputFormat::Text: return "text";
    }
    return "auto";
}

std::optional<InputFormat> input_format_from_name(std::string_view name) {
    for (InputFormat format :
         {InputFormat::Auto, InputFormat::Pcap, InputFormat::Pcapng, InputFormat::Raw,
          InputFormat::Hex, InputFormat::Serial, InputFormat::Text})
        if (input_format_name(format) == name) return format;
    return std::nullopt;
}

namespace {

bool is_hex_digit(std::uint8_t c) {
    return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
}

struct TextCount {
    std::size_t controls = 0;  // control bytes other than tab, CR and LF
    std::size_t not_utf8 = 0;  // bytes beyond ASCII that are no part of a UTF-8 character
};

// The length of the UTF-8 character starting at `at` (2 to 4), 0 when none starts there (also
// when `text` ends inside it: a head cut off there counts it as one byte that is no UTF-8).
std::size_t utf8_length(Bytes text, std::size_t at) {
    const std::uint8_t lead = text[at];
    std::size_t length = 0;
    if (lead >= 0xC2 && lead <= 0xDF)
        length = 2;
    else if (lead >= 0xE0 && lead <= 0xEF)
        length = 3;
    else if (lead >= 0xF0 && lead <= 0xF4)
        length = 4;
    else
        return 0;
    for (std::size_t i = 1; i < length; ++i) {
        if (at + i >= text.size() || (text[at + i] & 0xC0) != 0x80) return 0;
    }
    return length;
}

TextCount count_text(Bytes text) {
    TextCount count;
    for (std::size_t i = 0; i < text.size();) {
        const std::uint8_t c = text[i];
        if (c < 0x80) {
            if ((c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7F) ++count.controls;
            ++i;
            continue;
        }
        const std::size_t length = utf8_length(text, i);
        if (length == 0) {
            ++count.not_utf8;
            ++i;
        } else {
            i += length;
        }
    }
    return count;
}

// Does the first line that is not empty look like a line of `xxd` ("00000010: 8382 ...") or
// `hexdump -C` ("00000010  83 82 ...")? Their character column can hold a whole VLT 2000 telegram
// (xxd -c 32), which makes a hex dump no text log.
bool starts_like_hex_dump(Bytes head) {
    std::size_t i = 0;
    while (i < head.size() && (head[i] == '\n' || head[i] == '\r'))
        ++i;
    std::size_t digits = 0;
    while (i + digits < head.size() && is_hex_digit(head[i + digits]))
        ++digits;
    if (digits < 7 || i + digits + 1 >= head.size()) return false;
    const std::uint8_t after = head[i + digits];
    return after == ':' || (after == ' ' && head[i + digits + 1] == ' ');
}

}  // namespace

Bytes without_bom(Bytes text) {
    if (text.size() >= kUtf8Bom.size() &&
        std::equal(kUtf8Bom.begin(), kUtf8Bom.end(), text.begin(),
                   [](char a, std::uint8_t b) { return static_cast<std::uint8_t>(a) == b; }))
        return text.subspan(kUtf8Bom.size());
    return text;
}

bool looks_like_text(Bytes head) {
    head = without_bom(head);
    if (head.empty()) return false;
    const TextCount count = count_text(head);
    return (count.controls + count.not_utf8) * 10 <= head.size();
}

std::string_view text_input_hint() {
    return "it looks like text: --input-format hex reads a log of hex bytes, --input-format text "
           "a log of VLT 2000 telegrams ('<' ... '>')";
}

bool has_vlt2000_telegram_shape(Bytes text) {
    // '<', the two address digits, 18 printable characters, '>' (22 in all); a '<' among them
    // starts the count again, as the framer resynchronises there.
    std::size_t run = 0;  // characters since the last '<', that '<' included; 0: none open
    for (std::uint8_t c : text) {
        const bool fits = run <= 2 ? c >= '0' && c <= '9' : c >= 0x20 && c < 0x7F;
        if (c == '<') {
            run = 1;
        } else if (run == 0) {
            continue;
        } else if (run == 21 && c == '>') {
            return true;
        } else if (fits && run < 21) {
            ++run;
        } else {
            run = 0;
        }
    }
    return false;
}

InputFormat detect_input_format(Bytes head) {
    ByteReader reader(head);
    if (auto magic = reader.u32_be()) {
        switch (*magic) {
            case 0xA1B2C3D4:
            case 0xD4C3B2A1:
            case 0xA1B23C4D:
            case 0x4D3CB2A1: return InputFormat::Pcap;
            case 0x0A0D0D0A: return InputFormat::Pcapng;
            default: break;
        }
    }
    head = without_bom(head);
    const TextCount count = count_text(head);
    const bool text = !head.empty() && count.controls == 0 && count.not_utf8 <= head.size() / 32;
    bool hex_pair = false;
    for (std::size_t i = 0; i + 1 < head.size() && text && !hex_pair; ++i)
        hex_pair = is_hex_digit(head[i]) && is_hex_digit(head[i + 1]);
    if (text && has_vlt2000_telegram_shape(head) && !starts_like_hex_dump(head))
        return InputFormat::Text;
    return text && hex_pair ? InputFormat::Hex : InputFormat::Raw;
}

}  // namespace dpscope
