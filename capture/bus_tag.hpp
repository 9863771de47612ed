// Which bus a capture carries, as far as the capture itself says it: the tag dpscope writes into
// its pcap and pcapng files, and the choice of a protocol for a capture that is read without
// --bus (docs/decisions.md, "The bus recorded in USER0 captures" and "Choosing the bus").
//
// pcap: the file header's fields thiszone (bytes 8-11) and sigfigs (bytes 12-15), which the pcap
// specification has writers fill with 0 and readers ignore, hold the ASCII magic "dpsc" and a
// 32-bit word in the file's byte order: bits 0-3 the bus number (1 PROFIBUS DP, 2 FC protocol,
// 3 VLT 2000), and the line the capture was made on where it is known (0: unknown): bits 4-5
// the parity (1 none, 2 odd, 3 even), bits 6-7 the stop bits (1 or 2), bits 8-31 the baud rate.
// Files of dpscope before the line was recorded hold the bus number alone.
// pcapng: the first interface description block carries the option if_description (code 3)
// "dpscope bus=profibus", "dpscope bus=fc" or "dpscope bus=vlt2000", and the line as if_speed
// (code 8, bits per second: the baud rate) and an opt_comment (code 1) "dpscope frame=8E1".
// (docs/decisions.md, "The line recorded in a capture".)
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "core/protocol_descriptor.hpp"
#include "capture/input_format.hpp"
#include "capture/serial_port.hpp"
#include "core/byte_reader.hpp"

namespace dpscope {

// pcap file header bytes 8-11 of a tagged capture: "dpsc".
inline constexpr std::uint8_t kPcapBusTagMagic[4] = {'d', 'p', 's', 'c'};
// pcapng if_description of a tagged interface: the prefix, then the protocol name ("fc").
inline constexpr std::string_view kPcapngBusTagPrefix = "dpscope bus=";

// pcapng opt_comment of an interface whose character frame is known: the prefix, then "8E1".
inline constexpr std::string_view kPcapngFramePrefix = "dpscope frame=";

// The serial line a capture was made on, as far as it is known: the baud rate (0: unknown), the
// parity and the stop bits (unknown when not recorded).
struct LineSettings {
    std::uint32_t baud = 0;
    std::optional<SerialParity> parity;
    unsigned stop_bits = 0;  // 1 or 2; 0: unknown
    bool known() const noexcept { return baud != 0; }
    bool frame_known() const noexcept { return parity.has_value() && stop_bits != 0; }
    bool operator==(const LineSettings&) const = default;
};

// Baud rates a capture may record (sniff's --baud range); others are not read as a line.
inline constexpr std::uint32_t kMinLineBaud = 300;
inline constexpr std::uint32_t kMaxLineBaud = 16'000'000;

// "19200 baud 8E1", or "19200 baud" when the frame is not known.
std::string describe_line(const LineSettings& line);

// The bus number written into a pcap header (1 PROFIBUS DP, 2 FC protocol, 3 VLT 2000), and
// back.
std::uint32_t pcap_bus_number(Protocol protocol) noexcept;
std::optional<Protocol> protocol_of_pcap_bus_number(std::uint32_t number) noexcept;

// The 32-bit word of the pcap tag (bytes 12-15): the bus number and the line, as above.
std::uint32_t pcap_tag_word(Protocol protocol, const LineSettings& line) noexcept;

// Writes the tag into the 24-byte pcap file header `header` (whose magic gives the byte order).
void put_pcap_bus_tag(std::uint8_t* header, Protocol protocol,
                      const LineSettings& line = {}) noexcept;

// The if_description text of an interface of `protocol`: "dpscope bus=fc".
std::string pcapng_bus_description(Protocol protocol);

// What a capture file says about its bus, read from its first bytes.
struct CaptureLabel {
    int link_type = -1;              // of a pcap file, or of the first pcapng interface; -1 unknown
    std::optional<Protocol> tagged;  // the bus dpscope recorded, if any
    LineSettings line;               // the line the capture records (pcap tag, pcapng if_speed)
    std::optional<std::uint8_t> first_byte;  // of the first record (needs the head to reach it)
};

// Reads a pcap file header or a pcapng section header and first interface (and the first
// packet's first byte) from `head`, the first bytes of the file. Fields it cannot reach stay
// unknown.
CaptureLabel read_capture_label(Bytes head);

// The bus of a USER0 capture without dpscope's tag, by its first record's first byte: STX (0x02)
// is the FC protocol, '<' the VLT 2000 telegram, anything else PROFIBUS DP. choose_bus() and the
// Wireshark dissector (wireshark/) both use it.
Protocol protocol_of_untagged_user0(std::uint8_t first_byte) noexcept;

// The bus chosen for a capture, and why.
struct BusChoice {
    const ProtocolDescriptor* protocol = &profibus_protocol();
    // Why, for a note on standard error: "41 telegrams framed in the first 700 bytes".
    std::string reason;
    // The choice was not obvious from the capture (a byte stream, an untagged USER0 capture) and
    // is worth saying.
    bool say = false;
    // A byte stream that one bus frames and no other frames a byte of: the choice is plain
    // (`dpscope hex` does not say it for telegrams typed on its command line).
    bool unambiguous = false;
    // Not enough input yet to choose (a byte stream that is still arriving).
    bool need_more = false;
    // The bus the capture's tag names (pcap, pcapng).
    std::optional<Protocol> tagged;
    // The line the capture records (pcap, pcapng): baud 0 when it records none.
    LineSettings line;
};

// Chooses the bus of a capture of input kind `format` (pcap, pcapng, raw, hex or text) from its
// first bytes `head`; `complete`: `head` is the whole input (or as much as will be judged). A pcap
// or pcapng file: link type 257 is PROFIBUS, a tag names its bus, an untagged USER0 capture is FC
// when its first record starts with STX (0x02) and PROFIBUS otherwise. A raw or hex byte
// stream: each protocol's framing rules are run over it, and the one that frames the most bytes
// as telegrams wins (a tie, or none at all: PROFIBUS). A text log of ASCII telegrams (Text) is
// VLT 2000. need_more is set when `complete` is false
// and the head does not decide yet.
BusChoice choose_bus(Bytes head, InputFormat format, bool complete);

// Bytes of a byte stream judged for the choice (the first 64 KiB).
inline constexpr std::size_t kBusChoiceBytes = 64 * 1024;

}  // namespace dpscope
