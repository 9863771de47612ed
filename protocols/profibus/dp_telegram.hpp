// The PROFIBUS DP payload of a decoded telegram: layer 2 (FDL), the DP service, and what the
// decoder read from the service's data. Filled by BusDecoder (protocols/profibus/bus_decoder.hpp).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "core/code_tables.hpp"
#include "core/direction.hpp"
#include "core/time.hpp"
#include "protocols/profibus/dp_payload.hpp"
#include "protocols/profibus/dp_service.hpp"
#include "protocols/profibus/dpv1/dpv1.hpp"
#include "protocols/profibus/dpv1/profidrive.hpp"
#include "protocols/profibus/fdl.hpp"
#include "protocols/profibus/gsd/gsd_library.hpp"
#include "protocols/profibus/pcd.hpp"
#include "protocols/profibus/ppo.hpp"

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

// Whether a telegram carries the data unit its DP service defines: the request of Set_Prm,
// Chk_Cfg, Global_Control and Set_Slave_Add; the response of Slave_Diag and Get_Cfg when it is a
// data telegram (SD2, SD3), not an SC or SD1 acknowledgement. The decoder reads service data by
// this rule; renderers show what it stored.
bool carries_service_data(Service service, Direction direction, FrameType type) noexcept;

// What the decoder read from the data unit of a DP management service (Data_Exchange's is the
// PPO split in DpTelegram). At most one service's data is valid, named by kind(); each accessor
// returns null unless its data is the valid one. A telegram whose data did not even have the fixed
// part holds nothing; one whose data broke off later holds what was read before the break.
// The decoder reuses one DpServiceData: reset() only clears the kind, and the vectors keep their
// capacity, so reading service data stops allocating once they have grown.
// Besides the data carries_service_data() names, a data-carrying response to Global_Control or
// Set_Slave_Add holds its bytes read in the request's layout (the text and verbose views show
// them; JSONL does not), with nothing reported when they do not fit.
class DpServiceData {
  public:
    enum class Kind : std::uint8_t {
        None,
        SlaveDiag,
        SetPrm,
        Cfg,
        GlobalControl,
        SetSlaveAdd,
        Dpv1
    };

    Kind kind() const noexcept { return kind_; }
    // Slave_Diag: the fixed part, and the blocks its extended diagnosis decoded to.
    const SlaveDiag* slave_diag() const noexcept {
        return kind_ == Kind::SlaveDiag ? &slave_diag_ : nullptr;
    }
    std::span<const DiagBlock> diag_blocks() const noexcept {
        return kind_ == Kind::SlaveDiag ? std::span<const DiagBlock>(diag_blocks_)
                                        : std::span<const DiagBlock>();
    }
    const SetPrm* set_prm() const noexcept { return kind_ == Kind::SetPrm ? &set_prm_ : nullptr; }
    // Chk_Cfg or Get_Cfg: the identifier bytes as modules (empty when the data unit is).
    const std::vector<CfgModule>* cfg_modules() const noexcept {
        return kind_ == Kind::Cfg ? &cfg_modules_ : nullptr;
    }
    const GlobalControl* global_control() const noexcept {
        return kind_ == Kind::GlobalControl ? &global_control_ : nullptr;
    }
    const SetSlaveAdd* set_slave_add() const noexcept {
        return kind_ == Kind::SetSlaveAdd ? &set_slave_add_ : nullptr;
    }
    // MSAC_C1 / MSAC_C2: the DP-V1 PDU; and, for a Write request or Read response on index 47,
    // the PROFIdrive parameter request or response it carries.
    const Dpv1Pdu* dpv1() const noexcept { return kind_ == Kind::Dpv1 ? &dpv1_ : nullptr; }
    const ProfidriveMessage* profidrive() const noexcept {
        return kind_ == Kind::Dpv1 && has_profidrive_ ? &profidrive_ : nullptr;
    }

    // What the slave's GSD file says about the data (issue 29; empty, or null, unless the slave
    // has a GSD): the module each run of Chk_Cfg / Get_Cfg identifiers stands for; the user
    // parameters of a Set_Prm; the texts of a Slave_Diag's extended diagnosis.
    std::span<const GsdModuleMatch> gsd_modules() const noexcept {
        return kind_ == Kind::Cfg && has_gsd_ ? std::span<const GsdModuleMatch>(gsd_modules_)
                                              : std::span<const GsdModuleMatch>();
    }
    const GsdPrmReading* gsd_prm() const noexcept {
        return kind_ == Kind::SetPrm && has_gsd_ ? &gsd_prm_ : nullptr;
    }
    std::span<const GsdDiagText> gsd_diag() const noexcept {
        return kind_ == Kind::SlaveDiag && has_gsd_ ? std::span<const GsdDiagText>(gsd_diag_)
                                                    : std::span<const GsdDiagText>();
    }

    // For the decoder. Each store makes its service's data the valid one; the returned vector
    // is emptied for the parser to append to.
    void reset() noexcept {
        kind_ = Kind::None;
        has_gsd_ = false;
    }
    // After the store of the service's own data: its GSD reading, emptied to be filled.
    std::vector<GsdModuleMatch>& store_gsd_modules() noexcept {
        has_gsd_ = true;
        gsd_modules_.clear();
        return gsd_modules_;
    }
    GsdPrmReading& store_gsd_prm() noexcept {
        has_gsd_ = true;
        return gsd_prm_;
    }
    std::vector<GsdDiagText>& store_gsd_diag() noexcept {
        has_gsd_ = true;
        gsd_diag_.clear();
        return gsd_diag_;
    }
    std::vector<DiagBlock>& store_slave_diag(const SlaveDiag& diag) noexcept {
        kind_ = Kind::SlaveDiag;
        slave_diag_ = diag;
        diag_blocks_.clear();
        return diag_blocks_;
    }
    void store_set_prm(const SetPrm& prm) noexcept {
        kind_ = Kind::SetPrm;
        set_prm_ = prm;
    }
    std::vector<CfgModule>& store_cfg() noexcept {
        kind_ = Kind::Cfg;
        cfg_modules_.clear();
        return cfg_modules_;
    }
    void store_global_control(const GlobalControl& control) noexcept {
        kind_ = Kind::GlobalControl;
        global_control_ = control;
    }
    void store_set_slave_add(const SetSlaveAdd& add) noexcept {
        kind_ = Kind::SetSlaveAdd;
        set_slave_add_ = add;
    }
    Dpv1Pdu& store_dpv1() noexcept {
        kind_ = Kind::Dpv1;
        dpv1_ = Dpv1Pdu{};
        has_profidrive_ = false;
        return dpv1_;
    }
    // Only after store_dpv1(); the message is cleared for the parser to fill.
    ProfidriveMessage& store_profidrive() noexcept {
        has_profidrive_ = true;
        profidrive_.clear();
        return profidrive_;
    }

  private:
    Kind kind_ = Kind::None;
    SlaveDiag slave_diag_;
    std::vector<DiagBlock> diag_blocks_;
    SetPrm set_prm_;
    std::vector<CfgModule> cfg_modules_;
    GlobalControl global_control_;
    SetSlaveAdd set_slave_add_;
    Dpv1Pdu dpv1_;
    bool has_profidrive_ = false;
    ProfidriveMessage profidrive_;
    bool has_gsd_ = false;
    std::vector<GsdModuleMatch> gsd_modules_;
    GsdPrmReading gsd_prm_;
    std::vector<GsdDiagText> gsd_diag_;
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

    // Services other than Data_Exchange: what the service's data unit decoded to.
    DpServiceData service_data;
    // The slave's DP-V1 mode as its Set_Prm said (how its device-related diagnosis reads).
    SlaveDpv1 slave_dpv1 = SlaveDpv1::Unknown;
    // The slave's GSD file (--gsd, --gsd-dir), matched by its Ident_Number or forced for its
    // address; null when it has none.
    const GsdDevice* device = nullptr;

    // The parameter value as the code says (word / double word) and the code's meaning; a
    // request's codes are request codes, a response's response codes.
    std::uint32_t pcv_value(Direction direction) const noexcept;
    std::string_view pcv_meaning(Direction direction) const noexcept;
    // Whether PCD 1 follows a Danfoss profile: the FC profile, or the PROFIdrive profile of a
    // Danfoss-family drive (the vlt and ge dialects), whose bits 11..15 are Danfoss-defined. A
    // profidrive-dialect slave in the PROFIdrive profile gets the generic words (bits 11..15
    // device-specific).
    bool danfoss_pcd() const noexcept {
        return pcd_profile == PcdProfile::Fc || danfoss_family(dialect);
    }
};

// Every problem found at any layer of a DP telegram (DecodedTelegram::problems()).
inline const ProblemList& payload_problems(const DpTelegram& dp) noexcept {
    return dp.fdl.problems;
}

}  // namespace dpscope
