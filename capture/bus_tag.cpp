#include "capture/bus_tag.hpp"

#include <fmt/format.h>

#include <cstring>
#include <vector>

#include "capture/hex_log.hpp"
#include "core/counted.hpp"
#include "core/stream_framer.hpp"

namespace dpscope {

namespace {

constexpr std::uint32_t kPcapngSectionHeader = 0x0A0D0D0A;
constexpr std::uint32_t kPcapngInterface = 1;
constexpr std::uint32_t kPcapngObsoletePacket = 2;
constexpr std::uint32_t kPcapngSimplePacket = 3;
constexpr std::uint32_t kPcapngEnhancedPacket = 6;
constexpr std::uint16_t kOptComment = 1;
constexpr std::uint16_t kIfDescription = 3;
constexpr std::uint16_t kIfSpeed = 8;

// A 16- or 32-bit word of `head` at `at` in the given byte order; nullopt past its end.
std::optional<std::uint32_t> word(Bytes head, std::size_t at, std::size_t size, bool big) {
    if (at > head.size() || size > head.size() - at) return std::nullopt;
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < size; ++i) {
        std::size_t byte = big ? i : size - 1 - i;
        v = v << 8 | head[at + byte];
    }
    return v;
}

// The line in a pcap tag word (bits 4-31, see bus_tag.hpp); what is 0 or out of range stays
// unknown.
LineSettings line_of_pcap_tag_word(std::uint32_t tag) {
    LineSettings line;
    const std::uint32_t baud = tag >> 8;
    if (baud >= kMinLineBaud && baud <= kMaxLineBaud) line.baud = baud;
    const std::uint32_t parity = (tag >> 4) & 3;
    const std::uint32_t stop_bits = (tag >> 6) & 3;
    if (parity != 0 && (stop_bits == 1 || stop_bits == 2)) {
        line.parity = parity == 1   ? SerialParity::None
                      : parity == 2 ? SerialParity::Odd
                                    : SerialParity::Even;
        line.stop_bits = stop_bits;
    }
    return line;
}

// The frame of a pcapng comment "dpscope frame=8E1" into `line` (left as it is otherwise).
void read_frame_comment(std::string_view text, LineSettings& line) {
    if (!text.starts_with(kPcapngFramePrefix)) return;
    text.remove_prefix(kPcapngFramePrefix.size());
    if (text.size() != 3 || text[0] != '8' || (text[2] != '1' && text[2] != '2')) return;
    std::optional<SerialParity> parity = text[1] == 'E'   ? std::optional(SerialParity::Even)
                                         : text[1] == 'O' ? std::optional(SerialParity::Odd)
                                         : text[1] == 'N' ? std::optional(SerialParity::None)
                                                          : std::nullopt;
    if (!parity) return;
    line.parity = parity;
    line.stop_bits = static_cast<unsigned>(text[2] - '0');
}

void read_pcap_label(Bytes head, CaptureLabel& label) {
    // The magic in the file's byte order: A1B2C3D4 or A1B23C4D when read big-endian.
    std::optional<std::uint32_t> magic = word(head, 0, 4, true);
    if (!magic) return;
    const bool big = *magic == 0xA1B2C3D4 || *magic == 0xA1B23C4D;
    if (std::optional<std::uint32_t> link = word(head, 20, 4, big))
        label.link_type = static_cast<int>(*link & 0x0FFFFFFF);  // upper bits: FCS flags
    if (head.size() >= 16 && std::memcmp(head.data() + 8, kPcapBusTagMagic, 4) == 0) {
        const std::uint32_t tag = *word(head, 12, 4, big);
        label.tagged = protocol_of_pcap_bus_number(tag & 0xF);
        if (label.tagged) label.line = line_of_pcap_tag_word(tag);
    }
    // The first record: a 16-byte header (captured length at 8) and its data.
    std::optional<std::uint32_t> captured = word(head, 24 + 8, 4, big);
    if (captured && *captured > 0 && head.size() > 40) label.first_byte = head[40];
}

void read_pcapng_label(Bytes head, CaptureLabel& label) {
    std::optional<std::uint32_t> order = word(head, 8, 4, true);
    if (!order || (*order != 0x1A2B3C4D && *order != 0x4D3C2B1A)) return;
    const bool big = *order == 0x1A2B3C4D;
    bool interface_seen = false;
    for (std::size_t at = 0; at < head.size();) {
        std::optional<std::uint32_t> type = word(head, at, 4, big);
        std::optional<std::uint32_t> length = word(head, at + 4, 4, big);
        if (!type || !length || *length < 12 || *length % 4 != 0) return;
        if (at > 0 && *type == kPcapngSectionHeader) return;  // one section is enough
        const std::size_t end = at + *length;
        if (*type == kPcapngInterface && !interface_seen) {
            interface_seen = true;
            if (std::optional<std::uint32_t> link = word(head, at + 8, 2, big))
                label.link_type = static_cast<int>(*link);
            for (std::size_t option = at + 16; option + 4 <= end - 4;) {
                std::optional<std::uint32_t> code = word(head, option, 2, big);
                std::optional<std::uint32_t> size = word(head, option + 2, 2, big);
                if (!code || !size || *code == 0) break;
                if (option + 4 + *size > head.size()) break;
                std::string_view text(reinterpret_cast<const char*>(head.data() + option + 4),
                                      *size);
                if (*code == kIfDescription && text.starts_with(kPcapngBusTagPrefix))
                    label.tagged = protocol_from_name(text.substr(kPcapngBusTagPrefix.size()));
                if (*code == kOptComment) read_frame_comment(text, label.line);
                if (*code == kIfSpeed && *size == 8) {
                    // A 64-bit number in the section's byte order: bits per second, the baud.
                    const std::uint64_t first = *word(head, option + 4, 4, big);
                    const std::uint64_t second = *word(head, option + 8, 4, big);
                    const std::uint64_t speed = big ? first << 32 | second : second << 32 | first;
                    if (speed >= kMinLineBaud && speed <= kMaxLineBaud)
                        label.line.baud = static_cast<std::uint32_t>(speed);
                }
                option += 4 + (*size + 3) / 4 * 4;
            }
        } else if (*type == kPcapngEnhancedPacket || *type == kPcapngObsoletePacket ||
                   *type == kPcapngSimplePacket) {
            const bool simple = *type == kPcapngSimplePacket;
            const std::size_t data = at + (simple ? 12 : 28);
            std::optional<std::uint32_t> captured = word(head, at + (simple ? 8 : 20), 4, big);
            if (captured && *captured > 0 && data < head.size() && data < end)
                label.first_byte = head[data];
            return;
        }
        if (end > head.size()) return;
        at = end;
    }
}

// Bytes framed as telegrams by one protocol's rules.
struct FramedCount : FramingSink {
    std::uint64_t telegrams = 0;
    std::uint64_t bytes = 0;
    void on_telegram(Bytes telegram, std::uint64_t) override {
        ++telegrams;
        bytes += telegram.size();
    }
    void on_skipped(const SkippedBytes&) override {}
};

FramedCount count_framed(Bytes stream, const ProtocolDescriptor& protocol, bool complete) {
    FramedCount count;
    StreamFramer framer(protocol.framing);
    framer.feed(stream, count);
    if (complete) framer.finish(count);
    return count;
}

// The bytes of a hex log's whole lines (all of it when `complete`).
std::vector<std::uint8_t> hex_bytes(Bytes head, bool complete) {
    std::vector<std::uint8_t> bytes;
    head = without_bom(head);
    std::string_view text(reinterpret_cast<const char*>(head.data()), head.size());
    while (!text.empty()) {
        std::size_t end = text.find('\n');
        if (end == std::string_view::npos && !complete) break;  // a line still being written
        std::string_view line = text.substr(0, end);
        parse_hex_log_line(line, bytes);
        if (end == std::string_view::npos) break;
        text.remove_prefix(end + 1);
    }
    return bytes;
}

BusChoice choose_by_label(const CaptureLabel& label, bool complete) {
    BusChoice choice;
    choice.tagged = label.tagged;
    choice.line = label.line;
    if (label.tagged) {
        choice.protocol = &protocol_descriptor(*label.tagged);
        choice.reason = "the capture records its bus (dpscope's tag)";
        return choice;
    }
    if (label.link_type < 0 && !complete) {
        choice.need_more = true;
        return choice;
    }
    if (label.link_type != kLinkTypeUser0) {
        // 257 is PROFIBUS; any other link type is refused later, naming it.
        choice.reason = fmt::format("link type {}", label.link_type);
        return choice;
    }
    if (!label.first_byte) {
        choice.need_more = !complete;
        choice.reason = "a USER0 capture without a bus tag or records";
        return choice;
    }
    const ProtocolDescriptor& protocol =
        protocol_descriptor(protocol_of_untagged_user0(*label.first_byte));
    choice.protocol = &protocol;
    if (protocol.lead_byte) {
        choice.reason = fmt::format(
            "a USER0 capture without a bus tag whose first record starts with {}",
            protocol.lead_byte_text);
        choice.say = true;
    } else {
        choice.reason =
            fmt::format("a USER0 capture without a bus tag whose first record starts with 0x{:02X}",
                        *label.first_byte);
    }
    return choice;
}

}  // namespace

std::uint32_t pcap_bus_number(Protocol protocol) noexcept {
    return protocol_descriptor(protocol).pcap_bus_number;
}

std::optional<Protocol> protocol_of_pcap_bus_number(std::uint32_t number) noexcept {
    for (const ProtocolDescriptor* descriptor : protocol_table())
        if (descriptor->pcap_bus_number == number) return descriptor->protocol;
    return std::nullopt;
}

std::string describe_line(const LineSettings& line) {
    if (!line.frame_known()) return fmt::format("{} baud", line.baud);
    return fmt::format("{} baud {}", line.baud, serial_frame_name(*line.parity, line.stop_bits));
}

std::uint32_t pcap_tag_word(Protocol protocol, const LineSettings& line) noexcept {
    std::uint32_t word = pcap_bus_number(protocol);
    if (line.baud >= kMinLineBaud && line.baud <= kMaxLineBaud) word |= line.baud << 8;
    if (line.frame_known() && (line.stop_bits == 1 || line.stop_bits == 2)) {
        const std::uint32_t parity = *line.parity == SerialParity::None  ? 1
                                     : *line.parity == SerialParity::Odd ? 2
                                                                         : 3;
        word |= parity << 4 | line.stop_bits << 6;
    }
    return word;
}

void put_pcap_bus_tag(std::uint8_t* header, Protocol protocol, const LineSettings& line) noexcept {
    const bool big = header[0] == 0xA1;
    std::memcpy(header + 8, kPcapBusTagMagic, 4);
    const std::uint32_t number = pcap_tag_word(protocol, line);
    for (std::size_t i = 0; i < 4; ++i) {
        const std::size_t shift = 8 * (big ? 3 - i : i);
        header[12 + i] = static_cast<std::uint8_t>(number >> shift);
    }
}

std::string pcapng_bus_description(Protocol protocol) {
    return fmt::format("{}{}", kPcapngBusTagPrefix, protocol_name(protocol));
}

CaptureLabel read_capture_label(Bytes head) {
    CaptureLabel label;
    switch (detect_input_format(head)) {
        case InputFormat::Pcap: read_pcap_label(head, label); break;
        case InputFormat::Pcapng: read_pcapng_label(head, label); break;
        case InputFormat::Hex: {
            // A hex capture written by dpscope names its bus in its first line.
            const Bytes text = without_bom(head);
            std::string_view line(reinterpret_cast<const char*>(text.data()), text.size());
            label.tagged = hex_capture_bus(line.substr(0, line.find('\n')));
            break;
        }
        default: break;
    }
    return label;
}

Protocol protocol_of_untagged_user0(std::uint8_t first_byte) noexcept {
    for (const ProtocolDescriptor* descriptor : protocol_table())
        if (descriptor->lead_byte == first_byte) return descriptor->protocol;
    return protocol_table().front()->protocol;
}

BusChoice choose_bus(Bytes head, InputFormat format, bool complete) {
    if (head.size() >= kBusChoiceBytes) complete = true;
    if (format == InputFormat::Pcap || format == InputFormat::Pcapng)
        return choose_by_label(read_capture_label(head), complete);
    if (const ProtocolDescriptor* owner = text_log_protocol();
        owner && format == InputFormat::Text) {
        BusChoice choice;
        choice.protocol = owner;
        choice.reason = fmt::format("a text log of ASCII telegrams ({})", owner->text_log_shape);
        choice.say = true;
        return choice;
    }
    std::vector<std::uint8_t> text_bytes;
    Bytes stream = head.first(std::min(head.size(), kBusChoiceBytes));
    if (format == InputFormat::Hex) {
        if (const CaptureLabel label = read_capture_label(head); label.tagged) {
            BusChoice choice;
            choice.tagged = label.tagged;
            choice.protocol = &protocol_descriptor(*label.tagged);
            choice.reason = "the capture records its bus (dpscope's tag)";
            return choice;
        }
        text_bytes = hex_bytes(stream, complete);
        stream = Bytes(text_bytes.data(), text_bytes.size());
    }
    // Each bus's framing over the same bytes; a bus is a candidate when its telegrams cover at
    // least half of them (less would be refused as no capture anyway, see stream_source.hpp).
    const auto qualifies = [&](const FramedCount& count) {
        return count.bytes > 0 && count.bytes * 2 >= stream.size();
    };
    const ProtocolDescriptor* best = nullptr;
    FramedCount best_count;
    const ProtocolDescriptor* second = nullptr;
    FramedCount second_count;
    unsigned qualified = 0;
    for (const ProtocolDescriptor* protocol : protocol_table()) {
        FramedCount count = count_framed(stream, *protocol, complete);
        if (qualifies(count)) ++qualified;
        // Strictly more bytes wins: a tie stays with the bus listed first (PROFIBUS).
        if (!best || count.bytes > best_count.bytes) {
            second = best;
            second_count = best_count;
            best = protocol;
            best_count = count;
        } else if (!second || count.bytes > second_count.bytes) {
            second = protocol;
            second_count = count;
        }
    }
    BusChoice choice;
    // A byte stream still arriving is decided once one bus has framed 32 telegrams and four times
    // the bytes of any other.
    if (!complete && !(best_count.telegrams >= 32 && second_count.bytes * 4 <= best_count.bytes &&
                       qualifies(best_count))) {
        choice.need_more = true;
        return choice;
    }
    const std::string what = format == InputFormat::Hex
                                 ? counted(stream.size(), "hex byte", "hex bytes")
                                 : counted(stream.size(), "byte", "bytes");
    if (!qualifies(best_count)) {
        choice.reason = fmt::format("no bus frames half of the first {}", what);
        return choice;
    }
    choice.protocol = best;
    choice.reason =
        fmt::format("{} framed in the first {}, {} by {} framing",
                    counted(best_count.telegrams, "telegram", "telegrams"), what,
                    second_count.bytes == 0 ? std::string("none")
                                            : counted(second_count.bytes, "byte", "bytes"),
                    second ? second->framing.protocol_name() : std::string_view("other"));
    // A byte stream names no bus: the choice is always said (issue #10: "say which was chosen").
    (void)qualified;
    choice.say = true;
    choice.unambiguous = second_count.bytes == 0;
    return choice;
}

}  // namespace dpscope
