#include "capture/capture_protocol.hpp"

#include <algorithm>
#include <array>

#include "decoder/fdl_framing_rules.hpp"

namespace dpscope {

namespace {

constexpr std::array<PcapLinkType, 2> kProfibusLinkTypes{{
    {kLinkTypeProfibusDl, "PROFIBUS_DL"},
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

std::span<const CaptureProtocol* const> capture_protocols() noexcept {
    static const std::array<const CaptureProtocol*, 1> protocols{&profibus_dp_protocol()};
    return protocols;
}

}  // namespace dpscope
