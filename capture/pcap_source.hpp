// pcap captures read through libpcap, pcapng captures by dpscope's own block reader (any number
// of interfaces and link types; packets of interfaces with other link types are skipped with a
// warning). The link types decoded are those of the capture's protocol (core/protocol_descriptor.hpp:
// for PROFIBUS DP 257 PROFIBUS_DL and 147 USER0, one telegram per record).
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>

#include "core/protocol_descriptor.hpp"
#include "capture/telegram_source.hpp"

namespace dpscope {

// The classic pcap file format: a 24-byte file header, then a 16-byte header per record.
inline constexpr std::uint64_t kPcapFileHeaderBytes = 24;
inline constexpr std::uint64_t kPcapRecordHeaderBytes = 16;

// Takes ownership of `file`. An error when libpcap cannot read the file or the link type is not
// one of `protocol`'s. `classic_pcap`: the file starts with a pcap (not pcapng) header, so record
// byte offsets can be counted and named in messages.
OpenResult open_pcap_source(FILE* file, const std::string& name, bool classic_pcap,
                            const ProtocolDescriptor& protocol);

// Takes ownership of `file`, positioned at the start of a pcapng file. An error when it is no
// pcapng file or none of its interfaces has a link type of `protocol`. Records carry the byte
// offset of their block.
OpenResult open_pcapng_source(FILE* file, const std::string& name, const ProtocolDescriptor& protocol);

// The name a protocol gives the link type ("PROFIBUS_DL", "USER0"), or libpcap's name for it.
std::string link_type_name(int link_type);
// The libpcap dpscope runs with: "1.10.3 (with TPACKET_V3)" (dpscope --version).
std::string pcap_library_version();

}  // namespace dpscope
