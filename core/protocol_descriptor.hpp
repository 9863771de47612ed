// What every layer below the command line needs to know about a protocol, in one record per
// protocol: its names, its framing rules, the pcap link types that carry it, how dpscope's captures
// record it, and the few questions about its telegrams that the shared code asks (which stations
// a telegram is about, which parameter it names). Each protocol fills in its own record in its
// folder (protocols/<name>/<name>_protocol.cpp); the table of them is made from the registration
// list (protocols/protocol_list.hpp), so shared code loops over protocol_table() or looks one up
// instead of switching on Protocol.
#pragma once

#include <bitset>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string_view>

#include "core/filter_field.hpp"
#include "core/framing_rules.hpp"
#include "core/telegram.hpp"

namespace dpscope {

class TelegramDecoder;  // core/protocol_lane.hpp
class TelegramTracker;
struct LaneOptions;  // protocols/lane_options.hpp

// pcap link types (LINKTYPE_*) dpscope reads: PROFIBUS_DL as Wireshark reads it, and USER0, which
// other tools write PROFIBUS records in and dpscope writes every other bus in (recording the bus
// in the file: capture/bus_tag.hpp).
inline constexpr int kLinkTypeProfibusDl = 257;
inline constexpr int kLinkTypeUser0 = 147;

struct PcapLinkType {
    int value = 0;          // the LINKTYPE_ number in a pcap or pcapng file
    std::string_view name;  // as libpcap names it: "PROFIBUS_DL"
};

// One bit per parameter number (PNU) 0..65535.
using PnuSet = std::bitset<65536>;

// The one parameter a telegram is about and the value it carries (ProtocolDescriptor::
// parameter_of): what a parameter database names and scales in every output.
struct TelegramParameter {
    std::uint16_t pnu = 0;
    // The value as a raw whole number (a PWE, a PVA), which the parameter's row reads by its type
    // and scales by its conversion index.
    bool has_raw = false;
    std::uint32_t raw = 0;
    // A value that carries its own decimal point (VLT 2000), already in the parameter's unit.
    bool has_decimal = false;
    double decimal = 0.0;
    int decimals = 0;
};

struct ProtocolDescriptor {
    Protocol protocol;       // its value in DecodedTelegram::protocol
    std::string_view name;   // what --bus takes and captures record: "profibus", "fc"
    std::string_view title;  // in messages: "PROFIBUS DP", "the FC protocol (RS-485)"
    // In messages about a capture of it: "{} capture" ("a PROFIBUS DP", "an FC protocol").
    std::string_view capture_noun;
    // Raw, hex and serial input; static, outlives every source. (framing.protocol_name() is the
    // name messages about link types use.)
    const FramingRules& framing;
    // The most bytes a telegram of it has: no framer cuts a longer one from a byte stream.
    std::size_t max_telegram_bytes = 0;
    // The pcap link types whose records are its telegrams, in the order messages list them; the
    // first is the one dpscope writes and the link type of an empty pcapng capture.
    std::span<const PcapLinkType> link_types;
    // The bus number in the tag word of a pcap file dpscope writes (capture/bus_tag.hpp).
    std::uint32_t pcap_bus_number = 0;
    // A USER0 capture without a bus tag is of this protocol when its first record starts with this
    // byte (described in messages as `lead_byte_text`); nullopt: not told by its first byte (the
    // first protocol of the table is what is left).
    std::optional<std::uint8_t> lead_byte;
    std::string_view lead_byte_text;
    // Its telegrams are ASCII text shaped like this (e.g. "'<' ... '>'"), and a text log of them
    // is its traffic; empty: a text log is not this protocol's.
    std::string_view text_log_shape;
    // Its traffic or bus in messages: "the {} bus", "{} traffic" ("FC protocol", "VLT 2000").
    std::string_view traffic_name;
    // Whether the bus-health statistics (protocols/profibus/health/) judge its link layer:
    // dpscope stats, sniff --stats and --alarm, the report's bus-health section.
    bool has_bus_health = false;
    // Whether its tracker times commands and responses by the line's baud rate (--baud), as the
    // serial drive buses do; PROFIBUS uses --baud only for the bus load of the bus health.
    bool timed_by_line = false;
    // The serial line it runs on unless the command line says otherwise (sniff): the baud rate
    // (0: none, --baud must be given), the rates its devices support (0: not checked) and the
    // parity ("even", "none").
    std::uint32_t default_baud = 0;
    std::uint32_t min_baud = 0;
    std::uint32_t max_baud = 0;
    std::string_view default_parity = "even";
    // Whether its masters have station addresses (PROFIBUS); otherwise a telegram and a finding
    // are about their drive alone (FC, VLT 2000).
    bool masters_addressed = false;
    // The drive family whose parameter database names its PNUs (drives/, docs/parameters.md):
    // "fc", "vlt2000"; empty: each station's own (a PROFIBUS slave's by its dialect,
    // drives/drive_family.hpp).
    std::string_view drive_family = {};
    // The fields of its own the filter language reads (core/filter_field.hpp, docs/filter.md):
    // `dpscope.pcv.rc`, `dpscope.fc.ak`, ...; the fields of every bus are filter/'s. Its
    // `dpscope.pnu` says which parameters a telegram is about (--pnu, mark_telegram_pnus).
    std::span<const FilterField> filter_fields = {};
    // The one parameter the telegram is about, with the value it carries; nullopt when it is
    // about none (a process-data telegram, the idle PCV) or several (a DP-V1 request may address
    // up to 39). Null: the protocol names no parameters.
    std::optional<TelegramParameter> (*parameter_of)(const DecodedTelegram& t) noexcept = nullptr;
    // Its decoder and tracker, made with the options that are its own (protocols/
    // lane_options.hpp): what the commands' pipeline and the Wireshark plugin feed.
    std::unique_ptr<TelegramDecoder> (*make_decoder)(const LaneOptions& options) = nullptr;
    std::unique_ptr<TelegramTracker> (*make_tracker)(const LaneOptions& options) = nullptr;

    // Are the records of a capture with this link type telegrams of the protocol?
    bool carried_by(int link_type) const noexcept;
    // The link type dpscope writes the protocol's captures in.
    const PcapLinkType& written_link_type() const noexcept { return link_types.front(); }
};

// Every protocol, in the order of the registration list (protocols/protocol_list.hpp); the first
// is the default bus.
std::span<const ProtocolDescriptor* const> protocol_table() noexcept;
// The descriptor of a protocol.
const ProtocolDescriptor& protocol_descriptor(Protocol protocol) noexcept;
// The protocol --bus `name` names; null for none.
const ProtocolDescriptor* protocol_by_name(std::string_view name) noexcept;
// The one protocol a pcap link type carries (257: PROFIBUS); null when several share it (USER0)
// or none does.
const ProtocolDescriptor* only_protocol_of_link_type(int link_type) noexcept;
// The protocol whose traffic a text log is (text_log_shape); null for none.
const ProtocolDescriptor* text_log_protocol() noexcept;

// Each protocol's descriptor, by the name its line in protocols/protocol_list.hpp gives it:
// profibus_protocol(), fc_protocol(), ... (defined in protocols/<name>/<name>_protocol.cpp).
#define DPSCOPE_PROTOCOL_DESCRIPTOR(Enum, name, Payload, member) \
    const ProtocolDescriptor& name##_protocol() noexcept;
DPSCOPE_PROTOCOLS(DPSCOPE_PROTOCOL_DESCRIPTOR)
#undef DPSCOPE_PROTOCOL_DESCRIPTOR

}  // namespace dpscope
