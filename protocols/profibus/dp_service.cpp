#include "protocols/profibus/dp_service.hpp"

namespace dpscope {

std::string_view service_name(Service service) {
    switch (service) {
        case Service::Unknown: return "Unknown";
        case Service::FdlStatus: return "FDL_Status";
        case Service::SlaveDiag: return "Slave_Diag";
        case Service::SetPrm: return "Set_Prm";
        case Service::ChkCfg: return "Chk_Cfg";
        case Service::GetCfg: return "Get_Cfg";
        case Service::GlobalControl: return "Global_Control";
        case Service::DataExchange: return "Data_Exchange";
        case Service::RdInp: return "Rd_Inp";
        case Service::RdOutp: return "Rd_Outp";
        case Service::SetSlaveAdd: return "Set_Slave_Add";
        case Service::MsacC1: return "MSAC_C1";
        case Service::MsacC2: return "MSAC_C2";
        case Service::Token: return "Token";
        case Service::ShortAck: return "Short_Ack";
        case Service::Count: break;
    }
    return "Unknown";
}

std::string_view sap_name(std::uint8_t value, bool slave_side) {
    if (!slave_side) {
        switch (value) {
            case sap::kMaster: return "DP master";
            case sap::kMsacC1: return "MSAC_C1 master";
            case sap::kMsacC2Master: return "MSAC_C2 master";
            case sap::kMasterMaster: return "master-master";
            default: return value <= 48 ? "MSAC_C2 connection" : "";
        }
    }
    switch (value) {
        case sap::kChkCfg: return "Chk_Cfg";
        case sap::kSetPrm: return "Set_Prm";
        case sap::kSlaveDiag: return "Slave_Diag";
        case sap::kGetCfg: return "Get_Cfg";
        case sap::kGlobalControl: return "Global_Control";
        case sap::kRdOutp: return "Rd_Outp";
        case sap::kRdInp: return "Rd_Inp";
        case sap::kSetSlaveAdd: return "Set_Slave_Add";
        case sap::kMasterMaster: return "master-master";
        case sap::kExtUserPrm: return "Set_Ext_Prm";
        case sap::kMsacC1: return "MSAC_C1";
        case sap::kAlarm: return "DP-V1 alarm";
        case sap::kResourceManager: return "MSAC_C2 resource manager";
        default: return value <= 48 ? "MSAC_C2 connection" : "";
    }
}

namespace {

Service service_of_slave_sap(std::uint8_t value, bool peer_is_msac_c1) noexcept {
    switch (value) {
        case sap::kChkCfg: return Service::ChkCfg;
        case sap::kSetPrm: return Service::SetPrm;
        case sap::kSlaveDiag: return Service::SlaveDiag;
        case sap::kGetCfg: return Service::GetCfg;
        case sap::kGlobalControl: return Service::GlobalControl;
        case sap::kRdOutp: return Service::RdOutp;
        case sap::kRdInp: return Service::RdInp;
        case sap::kSetSlaveAdd: return Service::SetSlaveAdd;
        case sap::kMsacC1: return Service::MsacC1;
        case sap::kAlarm: return peer_is_msac_c1 ? Service::MsacC1 : Service::MsacC2;
        case sap::kResourceManager: return Service::MsacC2;
        default: return value <= 48 ? Service::MsacC2 : Service::Unknown;
    }
}

}  // namespace

Service classify_request(const FdlTelegram& t) noexcept {
    switch (t.type) {
        case FrameType::Sd4: return Service::Token;
        case FrameType::ShortAck: return Service::ShortAck;
        case FrameType::Invalid: return Service::Unknown;
        default: break;
    }
    if (!t.has_fc) return Service::Unknown;
    // SAP bytes announced but none could be read: it is no Data_Exchange (an SRD without SAPs),
    // and which DP service it was cannot be told. (With the DSAP read, the service is known.)
    bool saps_lost =
        !t.has_dsap && !t.has_ssap && t.problems.contains(ProblemKind::AddressExtensionShort);
    if (saps_lost) return Service::Unknown;
    std::uint8_t function = t.fc.function();
    if (function == static_cast<std::uint8_t>(FdlFunction::FdlStatus)) return Service::FdlStatus;
    if (t.has_dsap) {
        // A master-class-2 SSAP marks a DP-V1 class-2 exchange whatever the slave's SAP.
        if (t.has_ssap && t.ssap == sap::kMsacC2Master && t.dsap != sap::kMsacC1)
            return Service::MsacC2;
        return service_of_slave_sap(t.dsap, t.has_ssap && t.ssap == sap::kMsacC1);
    }
    if (t.has_ssap) return Service::Unknown;
    if (function_is_srd(function)) return Service::DataExchange;
    return Service::Unknown;
}

Service classify_unpaired_response(const FdlTelegram& t) noexcept {
    switch (t.type) {
        case FrameType::ShortAck: return Service::ShortAck;
        case FrameType::Sd4: return Service::Token;
        case FrameType::Invalid: return Service::Unknown;
        default: break;
    }
    if (!t.has_dsap && !t.has_ssap && t.problems.contains(ProblemKind::AddressExtensionShort))
        return Service::Unknown;
    if (t.has_ssap) {
        if (t.has_dsap && t.dsap == sap::kMsacC2Master && t.ssap != sap::kMsacC1)
            return Service::MsacC2;
        return service_of_slave_sap(t.ssap, t.has_dsap && t.dsap == sap::kMsacC1);
    }
    if (t.has_dsap) return Service::Unknown;
    if (!t.du.empty()) return Service::DataExchange;
    return Service::Unknown;
}

}  // namespace dpscope
