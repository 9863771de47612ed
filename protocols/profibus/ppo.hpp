// PPO types (PROFIdrive "Parameter-Process data Objects") and how a slave's PPO type is found:
// from its configuration (Chk_Cfg or a Get_Cfg response), from the Data_Exchange length, or
// given by the user.
//
//   PPO 1: PCV (8 bytes) + 2 PCD words = 12 bytes    PPO 3: 2 PCD words  = 4 bytes
//   PPO 2: PCV + 6 PCD words           = 20 bytes    PPO 4: 6 PCD words  = 12 bytes
//   PPO 5: PCV + 10 PCD words          = 28 bytes
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include "protocols/profibus/dp_payload.hpp"

namespace dpscope {

enum class PpoSource : std::uint8_t { None, ChkCfg, GetCfg, Length, Option };

// "none", "chk_cfg", "get_cfg", "length", "option".
std::string_view ppo_source_name(PpoSource source);

inline constexpr std::size_t kPcvBytes = 8;

struct PpoLayout {
    std::uint8_t type = 0;           // 1..5; 0 when the layout is no standard PPO
    std::uint8_t alternative = 0;    // another type that fits as well (12 bytes: 1 or 4)
    bool has_pcv = false;            // the first 8 bytes are the parameter channel
    std::uint16_t output_bytes = 0;  // master -> slave (Data_Exchange request)
    std::uint16_t input_bytes = 0;   // slave -> master (Data_Exchange response)
    PpoSource source = PpoSource::None;

    bool known() const noexcept { return source != PpoSource::None; }
};

// The layout of a standard PPO type 1..5 (type 0 for anything else).
PpoLayout ppo_layout_of_type(std::uint8_t type, PpoSource source);

// From configuration modules. A first module of 8 bytes in and out followed by more data is the
// PKW/PCV; the rest is PCD. Free places and manufacturer data carry no I/O and are ignored.
PpoLayout ppo_from_cfg(std::span<const CfgModule> modules, PpoSource source);

// From the length of a Data_Exchange data unit, when no configuration was captured.
PpoLayout ppo_from_length(std::size_t length);

}  // namespace dpscope
