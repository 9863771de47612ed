// Decodes a capture telegram by telegram, in capture order. Keeps the little state a bus
// decoder needs and nothing per telegram: the request waiting for its reply (so a response is
// named after the request it answers) and, per slave, the PPO layout its configuration announced
// and the DP-V1 mode its Set_Prm set.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "decoder/code_tables.hpp"
#include "decoder/dp_payload.hpp"
#include "decoder/dp_service.hpp"
#include "decoder/fdl.hpp"
#include "decoder/pcd.hpp"
#include "decoder/ppo.hpp"
#include "decoder/time.hpp"

namespace dpscope {

inline constexpr std::size_t kStationCount = 128;

struct DecoderOptions {
    Dialect dialect = Dialect::Vlt;
    // Per-station overrides: dialect, PPO type (1..5), control/status word profile.
    std::array<std::optional<Dialect>, kStationCount> station_dialect{};
    std::array<std::uint8_t, kStationCount> station_ppo{};
    // When unset the profile follows the dialect: vlt -> fc, profidrive -> profidrive.
    std::optional<PcdProfile> pcd_profile;

    Dialect dialect_of(std::uint8_t station) const noexcept {
        return station_dialect[station & 0x7F].value_or(dialect);
    }
    PcdProfile pcd_profile_of(std::uint8_t station) const noexcept {
        if (pcd_profile) return *pcd_profile;
        return dialect_of(station) == Dialect::Vlt ? PcdProfile::Fc : PcdProfile::Profidrive;
    }
};

enum class Direction : std::uint8_t { Request, Response };
std::string_view direction_name(Direction direction);  // "request", "response"

// What the decoder knows about one slave.
struct StationConfig {
    PpoLayout ppo;                // from Chk_Cfg or Get_Cfg (source None until one is seen)
    std::uint64_t cfg_frame = 0;  // the frame that carried it
    // The first configuration that announced another layout than --ppo gives (0: none did).
    std::uint64_t overridden_cfg_frame = 0;
    PpoLayout overridden_ppo;
    bool has_ident = false;
    std::uint16_t ident = 0;              // from Set_Prm
    SlaveDpv1 dpv1 = SlaveDpv1::Unknown;  // from the last intact Set_Prm (DPV1_Enable)
    bool cfg_fault = false;               // from the last Slave_Diag
    // Without a configuration, a 12-byte Data_Exchange is PPO 1 or PPO 4. The master's control
    // word has bit 10 set ("data valid" / "control by PLC"): in bytes 9-10 it points to PPO 1, in
    // bytes 1-2 (and not in 9-10) to PPO 4. The last request that told them apart decides.
    std::uint8_t length12_type = 0;  // 0: no evidence yet
};

// A request that expected a reply and got none before the next request or token.
struct UnansweredRequest {
    std::uint64_t frame = 0;
    std::int64_t time_ns = kNoTime;
    std::uint8_t master = 0;
    std::uint8_t slave = 0;
    std::uint8_t function = 0;
    Service service = Service::Unknown;
};

struct DecodedTelegram {
    std::uint64_t frame = 0;         // 1-based record number
    std::int64_t time_ns = kNoTime;  // nanoseconds since the epoch; kNoTime when unknown
    Bytes bytes;                     // the record (valid until the next decode)
    FdlTelegram fdl;                 // layer 2, with every problem found at any layer
    Service service = Service::Unknown;
    Direction direction = Direction::Request;

    // DP roles: requests go master -> slave, responses slave -> master. A short acknowledge has
    // no addresses of its own; it takes them from the request it answers.
    bool has_roles = false;
    std::uint8_t master = 0;
    std::uint8_t slave = 0;
    std::uint64_t request_frame = 0;  // response: the request it answers (0: not in capture)
    std::optional<UnansweredRequest> unanswered;  // set on the telegram that ended the wait

    // Data_Exchange
    PpoLayout ppo;  // the layout used to split the data
    Dialect dialect = Dialect::Vlt;
    PcdProfile pcd_profile = PcdProfile::Fc;
    bool has_pcv = false;
    Pcv pcv;
    Bytes pcd;  // process data words
    std::uint16_t pcd_offset = 0;

    // Services other than Data_Exchange: the slave's DP-V1 mode as its Set_Prm said (how its
    // device-related diagnosis reads).
    SlaveDpv1 slave_dpv1 = SlaveDpv1::Unknown;

    const ProblemList& problems() const noexcept { return fdl.problems; }
    bool has_time() const noexcept { return time_ns != kNoTime; }
    // The parameter value as the code says (word / double word) and the code's meaning.
    std::uint32_t pcv_value() const noexcept;
    std::string_view pcv_meaning() const noexcept;
    // Whether PCD 1 follows a Danfoss profile: the FC profile, or the PROFIdrive profile of a
    // Danfoss drive (the vlt dialect), whose bits 11..15 are Danfoss-defined. A profidrive-dialect
    // slave in the PROFIdrive profile gets the generic words (bits 11..15 device-specific).
    bool danfoss_pcd() const noexcept {
        return pcd_profile == PcdProfile::Fc || dialect == Dialect::Vlt;
    }
};

class BusDecoder {
  public:
    explicit BusDecoder(DecoderOptions options = {});

    // Decodes one telegram. The result refers to `bytes` and stays valid until the next call.
    const DecodedTelegram& decode(Bytes bytes, std::int64_t time_ns, std::uint64_t frame);

    const StationConfig& station(std::uint8_t address) const noexcept {
        return stations_[address & 0x7F];
    }
    const DecoderOptions& options() const noexcept { return options_; }
    // The PPO layout the decoder uses for `slave`, for a data unit of `du_length` bytes.
    PpoLayout layout_for(std::uint8_t slave, std::size_t du_length) const noexcept {
        PpoLayout layout;
        layout_for(slave, du_length, layout);
        return layout;
    }
    // The same, written into `layout` (the hot path returns no struct by value).
    void layout_for(std::uint8_t slave, std::size_t du_length, PpoLayout& layout) const noexcept;

  private:
    struct PendingRequest {
        bool valid = false;
        std::uint64_t frame = 0;
        std::int64_t time_ns = kNoTime;
        std::uint8_t master = 0;
        std::uint8_t slave = 0;
        std::uint8_t function = 0;
        Service service = Service::Unknown;
    };

    void decode_request(DecodedTelegram& t);
    void decode_response(DecodedTelegram& t);
    void decode_service_data(DecodedTelegram& t);
    void decode_data_exchange(DecodedTelegram& t);
    void learn_length12_type(const DecodedTelegram& t);
    // --ppo for this slave contradicts the configuration just learnt: remember the first time.
    void note_ppo_override(StationConfig& station, std::uint8_t slave,
                           std::uint64_t frame) const noexcept;

    DecoderOptions options_;
    std::array<StationConfig, kStationCount> stations_{};
    PendingRequest pending_;
    DecodedTelegram current_;
};

}  // namespace dpscope
