#include "capture/input_format.hpp"

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
    bool text = !head.empty();
    bool hex_pair = false;
    for (std::size_t i = 0; i < head.size() && text; ++i) {
        std::uint8_t c = head[i];
        bool printable = (c >= 0x20 && c < 0x7F) || c == '\t' || c == '\n' || c == '\r';
        text = printable;
        if (i + 1 < head.size() && is_hex_digit(c) && is_hex_digit(head[i + 1])) hex_pair = true;
    }
    if (text && has_vlt2000_telegram_shape(head) && !starts_like_hex_dump(head))
        return InputFormat::Text;
    return text && hex_pair ? InputFormat::Hex : InputFormat::Raw;
}

}  // namespace dpscope
