// PROFIBUS DP as the shared code sees it (core/protocol_descriptor.hpp).
#include <algorithm>
#include <array>

#include "core/protocol_descriptor.hpp"
#include "protocols/profibus/fdl_framing_rules.hpp"

namespace dpscope {

namespace {

constexpr std::array<PcapLinkType, 2> kProfibusLinkTypes{{
    {kLinkTypeProfibusDl, "PROFIBUS_DL"},
    {kLinkTypeUser0, "USER0"},
}};

// A DP telegram names parameters only in a PROFIdrive parameter request or response (DP-V1).
bool profibus_addresses_pnu(const DecodedTelegram& t, std::uint16_t pnu) noexcept {
    const ProfidriveMessage* message = t.dp.service_data.profidrive();
    if (!message) return false;
    return std::any_of(message->addresses.begin(), message->addresses.end(),
                       [&](const ProfidriveAddress& a) { return a.pnu == pnu; });
}

}  // namespace

const ProtocolDescriptor& profibus_protocol() noexcept {
    static const ProtocolDescriptor descriptor{
        .protocol = Protocol::ProfibusDp,
        .name = "profibus",
        .title = "PROFIBUS DP",
        .framing = fdl_framing_rules(),
        .link_types = kProfibusLinkTypes,
        .pcap_bus_number = 1,
        .lead_byte = std::nullopt,  // what an untagged USER0 capture is when no other bus fits
        .lead_byte_text = {},
        .text_log_shape = {},
        .traffic_name = {},
        .masters_addressed = true,
        .addresses_pnu = profibus_addresses_pnu,
    };
    return descriptor;
}

}  // namespace dpscope
