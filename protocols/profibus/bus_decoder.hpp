// Decodes a capture telegram by telegram, in capture order. Keeps the little state a bus
// decoder needs and nothing per telegram: the request waiting for its reply (so a response is
// named after the request it answers), per slave the PPO layout its configuration announced and
// the DP-V1 mode its Set_Prm set, and the last PROFIdrive parameter request per master, slave,
// slot and index (a parameter response carries no parameter numbers; it is named after it).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "core/code_tables.hpp"
#include "core/protocol_lane.hpp"
#include "core/telegram.hpp"
#include "core/time.hpp"
#include "drives/parameter_naming.hpp"
#include "protocols/profibus/dp_payload.hpp"
#include "protocols/profibus/dp_service.hpp"
#include "protocols/profibus/dpv1/dpv1.hpp"
#include "protocols/profibus/dpv1/profidrive.hpp"
#include "protocols/profibus/fdl.hpp"
#include "protocols/profibus/pcd.hpp"
#include "protocols/profibus/ppo.hpp"

namespace dpscope {

struct DecoderOptions {
    Dialect dialect = Dialect::Vlt;
    // Per-station overrides: dialect, PPO type (1..5), control/status word profile.
    std::array<std::optional<Dialect>, kStationCount> station_dialect{};
    std::array<std::uint8_t, kStationCount> station_ppo{};
    // When unset the profile follows the dialect: vlt, ge -> fc; profidrive -> profidrive.
    std::optional<PcdProfile> pcd_profile;
    // The GSD files given (--gsd, --gsd-dir); null: none.
    std::shared_ptr<const GsdLibrary> gsd;
    // What names the PNUs (drives/parameter_naming.hpp): put on every telegram decoded
    // (DecodedTelegram::naming); null: nothing. Set from LaneOptions::naming by the factory.
    std::shared_ptr<const ParameterNaming> naming{};

    Dialect dialect_of(std::uint8_t station) const noexcept {
        return station_dialect[station & 0x7F].value_or(dialect);
    }
    // Every station's dialect (dialect_of), indexed by address.
    std::array<Dialect, kStationCount> station_dialects() const noexcept {
        std::array<Dialect, kStationCount> dialects{};
        for (std::size_t station = 0; station < kStationCount; ++station)
            dialects[station] = dialect_of(static_cast<std::uint8_t>(station));
        return dialects;
    }
    PcdProfile pcd_profile_of(std::uint8_t station) const noexcept {
        if (pcd_profile) return *pcd_profile;
        return danfoss_family(dialect_of(station)) ? PcdProfile::Fc : PcdProfile::Profidrive;
    }
};

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
    // Its GSD file: forced for the address, else the first whose Ident_Number a Set_Prm or
    // Slave_Diag of the slave carried. Null: none.
    const GsdDevice* device = nullptr;
    // Its configuration by that GSD (the last Chk_Cfg or Get_Cfg): the module of each run of
    // identifiers in slot order (null: no module matched), and of each identifier (slot).
    bool gsd_modules_known = false;
    std::vector<const GsdModule*> gsd_modules;
    std::vector<const GsdModule*> gsd_slots;
};

class BusDecoder final : public TelegramDecoder {
  public:
    explicit BusDecoder(DecoderOptions options = {});

    // Decodes one telegram. The result refers to `bytes` and stays valid until the next call.
    const DecodedTelegram& decode(Bytes bytes, std::int64_t time_ns, std::uint64_t frame) override;
    std::unique_ptr<TelegramDecoder> clone() const override {
        return std::make_unique<BusDecoder>(*this);
    }

    const StationConfig& station(std::uint8_t address) const noexcept {
        return stations_[address & 0x7F];
    }
    const DecoderOptions& options() const noexcept { return options_; }
    const ParameterNaming* naming() const noexcept override {
        return naming_ ? &naming_->naming() : nullptr;
    }
    // The PPO layout the decoder uses for `slave`, for a data unit of `du_length` bytes.
    PpoLayout layout_for(std::uint8_t slave, std::size_t du_length) const noexcept {
        PpoLayout layout;
        layout_for(slave, du_length, layout);
        return layout;
    }
    // The same, written into `layout` (the hot path returns no struct by value).
    void layout_for(std::uint8_t slave, std::size_t du_length, PpoLayout& layout) const noexcept;

  private:
    void decode_request(DecodedTelegram& t);
    void decode_response(DecodedTelegram& t);
    void decode_service_data(DecodedTelegram& t);
    // Reads the data unit of a telegram that carries its service's data (carries_service_data),
    // stores what it decoded to on the telegram, and learns the slave's configuration from it.
    void read_service_data(DecodedTelegram& t, StationConfig& station);
    // DP gives a response to Global_Control or Set_Slave_Add no data, but the text and verbose
    // views show the data of one that has some in the request's layout; this reads it for them.
    void read_response_in_request_layout(DecodedTelegram& t);
    void decode_data_exchange(DecodedTelegram& t);
    // MSAC_C1 / MSAC_C2: the DP-V1 PDU and, on index 47, the PROFIdrive request or response.
    void read_dpv1(DecodedTelegram& t, ByteReader du);
    struct KeptProfidriveRequest {
        std::uint8_t master = 0;
        std::uint8_t slave = 0;
        std::uint8_t slot = 0;
        std::uint8_t index = 0;
        std::uint64_t frame = 0;
        std::uint8_t id = 0;
        std::uint8_t reference = 0;
        bool answered = false;  // an intact response was named after it
        std::vector<ProfidriveAddress> addresses;
    };
    // At most this many kept requests (memory stays flat); a new key then replaces the oldest.
    static constexpr std::size_t kKeptProfidriveRequests = 256;
    void keep_profidrive_request(const DecodedTelegram& t, const Dpv1Pdu& pdu,
                                 const ProfidriveMessage& request);
    // The kept request a response on `pdu`'s slot and index answers: null when there is none
    // or it has named a response already.
    KeptProfidriveRequest* kept_profidrive_request(const DecodedTelegram& t,
                                                   const Dpv1Pdu& pdu) noexcept;
    void learn_length12_type(const DecodedTelegram& t);
    // A positive answer to a description request (attribute 0x20): what the drive says about
    // its parameters names and scales them from now on (drives/described_parameters.hpp).
    void learn_descriptions(const DecodedTelegram& t, const ProfidriveMessage& response);
    // The GSD of the slave that sent or was sent `ident` (when it has none yet).
    void match_gsd(StationConfig& station, std::uint16_t ident) noexcept;
    // The family the station's GSD names (family_of_device) names its PNUs from now on.
    void take_device_family(const StationConfig& station) noexcept;
    // What the slave's GSD says about the service data just read.
    void read_gsd(DecodedTelegram& t, StationConfig& station);
    // --ppo for this slave contradicts the configuration just learnt: remember the first time.
    void note_ppo_override(StationConfig& station, std::uint8_t slave,
                           std::uint64_t frame) const noexcept;

    DecoderOptions options_;
    std::array<StationConfig, kStationCount> stations_{};
    // The request waiting for its reply (valid while has_pending_): a response is named after it,
    // and the next request or token reports it as unanswered.
    bool has_pending_ = false;
    UnansweredRequest pending_;
    std::vector<KeptProfidriveRequest> profidrive_requests_;
    std::vector<std::uint16_t> identifier_offsets_;  // read_gsd's, kept for its capacity
    // The naming put on the telegrams: the options', with what the drives described first.
    std::optional<DescribingNaming> naming_;
    DecodedTelegram current_;
};

}  // namespace dpscope
