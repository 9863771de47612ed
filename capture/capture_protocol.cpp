#include "capture/capture_protocol.hpp"

#include <algorithm>
#include <array>

#include "protocols/fc/fc_framing_rules.hpp"
#include "protocols/profibus/fdl_framing_rules.hpp"
#include "protocols/vlt2000/vlt2000_framing_rules.hpp"

namespace dpscope {

namespace {

constexpr std::array<PcapLinkType, 2> kProfibusLinkTypes{{
    {kLinkTypeProfibusDl, "PROFIBUS_DL"},
    {kLinkTypeUser0, "USER0"},
}};

// The FC protocol has no link type of its own: dpscope writes it as USER0 and records the bus in
// the file (capture/bus_tag.hpp).
constexpr std::array<PcapLinkType, 1> kUser0LinkTypes{{
    {kLinkTypeUser0, "USER0"},
}};

}  // namespace

bool CaptureProtocol::carried_by(int link_type) const noexcept {
    return std::any_of(link_types.begin(), link_types.end(),
                       [link_type](const PcapLinkType& type) { return type.value == link_type; });
}

const CaptureProtocol& profibus_dp_protocol() noexcept {
    static const CaptureProtocol protocol{Protocol::ProfibusDp, fdl_framing_rules(),
                                          kProfibusLinkTypes};
    return protocol;
}

const CaptureProtocol& fc_protocol() noexcept {
    static const CaptureProtocol protocol{Protocol::Fc, fc_framing_rules(), kUser0LinkTypes};
    return protocol;
}

const CaptureProtocol& vlt2000_protocol() noexcept {
    static const CaptureProtocol protocol{Protocol::Vlt2000, vlt2000_framing_rules(),
                                          kUser0LinkTypes};
    return protocol;
}

const CaptureProtocol& capture_protocol(Protocol protocol) noexcept {
    switch (protocol) {
        case Protocol::Fc: return fc_protocol();
        case Protocol::Vlt2000: return vlt2000_protocol();
        case Protocol::ProfibusDp: break;
    }
    return profibus_dp_protocol();
}

std::span<const CaptureProtocol* const> capture_protocols() noexcept {
    static const std::array<const CaptureProtocol*, 3> protocols{
        &profibus_dp_protocol(), &fc_protocol(), &vlt2000_protocol()};
    return protocols;
}

}  // namespace dpscope
