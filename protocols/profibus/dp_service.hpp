// PROFIBUS DP services, named by SAP and context.
#pragma once

#include <cstdint>
#include <string_view>

#include "protocols/profibus/fdl.hpp"

namespace dpscope {

enum class Service : std::uint8_t {
    Unknown,
    FdlStatus,
    SlaveDiag,
    SetPrm,
    ChkCfg,
    GetCfg,
    GlobalControl,
    DataExchange,
    RdInp,
    RdOutp,
    SetSlaveAdd,
    MsacC1,
    MsacC2,
    Token,
    ShortAck,
    Count
};

constexpr std::size_t kServiceCount = static_cast<std::size_t>(Service::Count);

// The stable names used in every output: "FDL_Status", "Slave_Diag", "Set_Prm", "Chk_Cfg",
// "Get_Cfg", "Global_Control", "Data_Exchange", "Rd_Inp", "Rd_Outp", "Set_Slave_Add", "MSAC_C1"
// (DP-V1 class-1 acyclic), "MSAC_C2" (DP-V1 class-2 acyclic), "Token", "Short_Ack", "Unknown".
std::string_view service_name(Service service);

// Service access points of DP (slave side unless noted).
namespace sap {
inline constexpr std::uint8_t kChkCfg = 62;  // also the master's SSAP for DP services
inline constexpr std::uint8_t kSetPrm = 61;
inline constexpr std::uint8_t kSlaveDiag = 60;
inline constexpr std::uint8_t kGetCfg = 59;
inline constexpr std::uint8_t kGlobalControl = 58;
inline constexpr std::uint8_t kRdOutp = 57;
inline constexpr std::uint8_t kRdInp = 56;
inline constexpr std::uint8_t kSetSlaveAdd = 55;
inline constexpr std::uint8_t kMasterMaster = 54;
inline constexpr std::uint8_t kExtUserPrm = 53;
inline constexpr std::uint8_t kMsacC1 = 51;           // DP-V1 class-1 read/write (slave and master)
inline constexpr std::uint8_t kAlarm = 50;            // DP-V1 alarm acknowledge (slave side)
inline constexpr std::uint8_t kMsacC2Master = 50;     // DP-V1 class-2 master SSAP
inline constexpr std::uint8_t kResourceManager = 49;  // DP-V1 class-2 Initiate
inline constexpr std::uint8_t kMaster = 62;           // the DP master's SAP
}  // namespace sap

// What a SAP number means: on the slave side the service ("Chk_Cfg", "Slave_Diag", ...), on the
// master side the master's role ("DP master", ...); "" when DP gives it no meaning.
std::string_view sap_name(std::uint8_t sap, bool slave_side);

// The service of a request (or token) judged from the telegram alone.
Service classify_request(const FdlTelegram& telegram) noexcept;

// The service of a response whose request is not in the capture, judged from its SAPs: a
// response carries the request's DSAP as its SSAP. No SAP and data: Data_Exchange.
Service classify_unpaired_response(const FdlTelegram& telegram) noexcept;

}  // namespace dpscope
