// The protocol a capture carries, as the capture layer needs to know it: how a byte stream (raw
// dump, hex log, serial port) splits into telegrams, and which pcap link types hold one telegram
// per record. The command line chooses it once per capture and hands it to open_source() and the
// pcap and pcapng readers (the serial source gets its framing rules); none of them names a
// protocol itself.
//
// PROFIBUS DP, the Danfoss FC protocol and the VLT 2000 telegram today. Another adds its framing
// rules in decoder/ and a CaptureProtocol here, and is listed in capture_protocols().
#pragma once

#include <span>
#include <string>
#include <string_view>

#include "core/framing_rules.hpp"
#include "core/telegram.hpp"

namespace dpscope {

// pcap link types (LINKTYPE_*) of PROFIBUS captures, one telegram per record from start to end
// delimiter: PROFIBUS_DL as Wireshark reads it, and USER0 as other tools write the same records.
inline constexpr int kLinkTypeProfibusDl = 257;
inline constexpr int kLinkTypeUser0 = 147;

struct PcapLinkType {
    int value = 0;          // the LINKTYPE_ number in a pcap or pcapng file
    std::string_view name;  // as libpcap names it: "PROFIBUS_DL"
};

struct CaptureProtocol {
    Protocol protocol;            // the decoder's name for it (core/telegram.hpp)
    const FramingRules& framing;  // raw, hex and serial input; static, outlives every source
    // The pcap link types whose records are its telegrams, in the order messages list them; the
    // first is the link type of an empty pcapng capture. (Its name for people, in messages, is
    // framing.protocol_name().)
    std::span<const PcapLinkType> link_types;

    // Are the records of a capture with this link type telegrams of the protocol?
    bool carried_by(int link_type) const noexcept;
};

// PROFIBUS DP: FDL framing (protocols/profibus/fdl_framing_rules.hpp), link types 257 and 147.
const CaptureProtocol& profibus_dp_protocol() noexcept;

// The Danfoss FC protocol on RS-485: FC framing (protocols/fc/fc_framing_rules.hpp), link type
// USER0.
const CaptureProtocol& fc_protocol() noexcept;

// The VLT 2000 serial telegram: VLT 2000 framing (protocols/vlt2000/vlt2000_framing_rules.hpp),
// link type USER0.
const CaptureProtocol& vlt2000_protocol() noexcept;

// The capture protocol of a decoder protocol.
const CaptureProtocol& capture_protocol(Protocol protocol) noexcept;

// Every protocol dpscope reads, for what is about link types in general (link_type_name).
std::span<const CaptureProtocol* const> capture_protocols() noexcept;

}  // namespace dpscope
