// The PROFIBUS DP payload of a decoded telegram: layer 2 (FDL), the DP service, and what the
// decoder read from the service's data. Filled by BusDecoder (decoder/bus_decoder.hpp).
#pragma once

#include <cstdint>
#include <optional>

#include "decoder/code_tables.hpp"
#include "decoder/direction.hpp"
#include "decoder/dp_payload.hpp"
#include "decoder/dp_service.hpp"
#include "decoder/fdl.hpp"
#include "decoder/pcd.hpp"
#include "decoder/ppo.hpp"
#include "decoder/time.hpp"

namespace dpscope {

// A request that expected a reply and got none before the next request or token.
struct UnansweredRequest {
    std::uint64_t frame = 0;
    std::int64_t time_ns = kNoTime;
    std::uint8_t master = 0;
    std::uint8_t slave = 0;
    std::uint8_t function = 0;
    Service service = Service::Unknown;
};

struct DpTelegram {
    FdlTelegram fdl;  // layer 2, with every problem found at any layer
    Service service = Service::Unknown;
    std::optional<UnansweredRequest> unanswered;  // set on the telegram that ended the wait

    // Data_Exchange
    PpoLayout ppo;  // the layout used to split the data
    // The Chk_Cfg request or Get_Cfg response that announced `ppo` (0 when it came from elsewhere).
    std::uint64_t ppo_cfg_frame = 0;
    Dialect dialect = Dialect::Vlt;
    PcdProfile pcd_profile = PcdProfile::Fc;
    bool has_pcv = false;
    Pcv pcv;
    Bytes pcd;  // process data words
    std::uint16_t pcd_offset = 0;

    // Services other than Data_Exchange: the slave's DP-V1 mode as its Set_Prm said (how its
    // device-related diagnosis reads).
    SlaveDpv1 slave_dpv1 = SlaveDpv1::Unknown;

    // The parameter value as the code says (word / double word) and the code's meaning; a
    // request's codes are request codes, a response's response codes.
    std::uint32_t pcv_value(Direction direction) const noexcept;
    std::string_view pcv_meaning(Direction direction) const noexcept;
    // Whether PCD 1 follows a Danfoss profile: the FC profile, or the PROFIdrive profile of a
    // Danfoss drive (the vlt dialect), whose bits 11..15 are Danfoss-defined. A profidrive-dialect
    // slave in the PROFIdrive profile gets the generic words (bits 11..15 device-specific).
    bool danfoss_pcd() const noexcept {
        return pcd_profile == PcdProfile::Fc || dialect == Dialect::Vlt;
    }
};

}  // namespace dpscope
