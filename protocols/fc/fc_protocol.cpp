// The Danfoss FC protocol as the shared code sees it (core/protocol_descriptor.hpp).
#include <array>
#include <optional>

#include "core/protocol_descriptor.hpp"
#include "protocols/fc/fc_framing_rules.hpp"

namespace dpscope {

namespace {

// The FC protocol has no link type of its own: dpscope writes it as USER0 and records the bus in
// the file (capture/bus_tag.hpp).
constexpr std::array<PcapLinkType, 1> kFcLinkTypes{{{kLinkTypeUser0, "USER0"}}};

// The parameter an FC telegram names: its PKW's PNU (a response echoes its request's); none
// without a PKW.
std::optional<std::uint16_t> fc_named_pnu(const DecodedTelegram& t) noexcept {
    if (!t.fc.has_pkw) return std::nullopt;
    return t.fc.pkw.pnu;
}

bool fc_addresses_pnu(const DecodedTelegram& t, std::uint16_t pnu) noexcept {
    return fc_named_pnu(t) == pnu;
}

void fc_mark_pnus(const DecodedTelegram& t, PnuSet& seen) noexcept {
    if (const auto pnu = fc_named_pnu(t)) seen.set(*pnu);
}

}  // namespace

const ProtocolDescriptor& fc_protocol() noexcept {
    static const ProtocolDescriptor descriptor{
        .protocol = Protocol::Fc,
        .name = "fc",
        .title = "the FC protocol (RS-485)",
        .capture_noun = "an FC protocol",
        .framing = fc_framing_rules(),
        .link_types = kFcLinkTypes,
        .pcap_bus_number = 2,
        .lead_byte = kFcStx,
        .lead_byte_text = "STX (0x02)",
        .text_log_shape = {},
        .traffic_name = "FC protocol",
        .has_bus_health = false,
        .timed_by_line = true,
        .masters_addressed = false,
        .addresses_pnu = fc_addresses_pnu,
        .mark_pnus = fc_mark_pnus,
    };
    return descriptor;
}

}  // namespace dpscope
