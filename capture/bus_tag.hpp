// Which bus a capture carries, as far as the capture itself says it: the tag dpscope writes into
// its pcap and pcapng files, and the choice of a protocol for a capture that is read without
// --bus (docs/decisions.md, "The bus recorded in USER0 captures" and "Choosing the bus").
//
// pcap: the file header's fields thiszone (bytes 8-11) and sigfigs (bytes 12-15), which the pcap
// specification has writers fill with 0 and readers ignore, hold the ASCII magic "dpsc" and the
// bus number (1 PROFIBUS DP, 2 FC protocol, 3 VLT 2000) as a 32-bit word in the file's byte order.
// pcapng: the first interface description block carries the option if_description (code 3)
// "dpscope bus=profibus", "dpscope bus=fc" or "dpscope bus=vlt2000".
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "capture/capture_protocol.hpp"
#include "capture/input_format.hpp"
#include "decoder/byte_reader.hpp"

namespace dpscope {

// pcap file header bytes 8-11 of a tagged capture: "dpsc".
inline constexpr std::uint8_t kPcapBusTagMagic[4] = {'d', 'p', 's', 'c'};
// pcapng if_description of a tagged interface: the prefix, then the protocol name ("fc").
inline constexpr std::string_view kPcapngBusTagPrefix = "dpscope bus=";

// The bus number written into a pcap header (1 PROFIBUS DP, 2 FC protocol, 3 VLT 2000), and
// back.
std::uint32_t pcap_bus_number(Protocol protocol) noexcept;
std::optional<Protocol> protocol_of_pcap_bus_number(std::uint32_t number) noexcept;

// Writes the tag into the 24-byte pcap file header `header` (whose magic gives the byte order).
void put_pcap_bus_tag(std::uint8_t* header, Protocol protocol) noexcept;

// The if_description text of an interface of `protocol`: "dpscope bus=fc".
std::string pcapng_bus_description(Protocol protocol);

// What a capture file says about its bus, read from its first bytes.
struct CaptureLabel {
    int link_type = -1;              // of a pcap file, or of the first pcapng interface; -1 unknown
    std::optional<Protocol> tagged;  // the bus dpscope recorded, if any
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
    const CaptureProtocol* protocol = &profibus_dp_protocol();
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
