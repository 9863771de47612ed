// The Wireshark dissector plugin: captures of link type USER0 (147) as dpscope writes them, decoded
// by dpscope's own decoder library and judged by its trackers (wireshark/capture_replay.hpp), so
// that Wireshark shows what `dpscope decode` shows. This file only turns a DecodedTelegram into
// Wireshark's tree, columns and expert info; it parses no byte itself. The field names are listed
// in the README ("Wireshark", "Fields"), checked against the registered fields by
// tests/wireshark/field_table_test.sh.
#include <wireshark.h>
// wireshark.h first: it sets up what the epan headers need.
#include <epan/expert.h>
#include <epan/packet.h>
#include <epan/prefs.h>
#include <epan/proto.h>
#include <epan/proto_data.h>
#include <epan/tvbuff.h>
#include <fmt/format.h>

#include <charconv>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "capture/bus_tag.hpp"
#include "decoder/code_tables.hpp"
#include "decoder/dp_payload.hpp"
#include "decoder/pcd.hpp"
#include "decoder/profidrive.hpp"
#include "formats/describe.hpp"
#include "wireshark/capture_replay.hpp"

extern "C" {
WS_DLL_PUBLIC_DEF extern const gchar plugin_version[];
WS_DLL_PUBLIC_DEF extern const int plugin_want_major;
WS_DLL_PUBLIC_DEF extern const int plugin_want_minor;
WS_DLL_PUBLIC void plugin_register(void);
}

const gchar plugin_version[] = DPSCOPE_PLUGIN_VERSION;
const int plugin_want_major = WIRESHARK_VERSION_MAJOR;
const int plugin_want_minor = WIRESHARK_VERSION_MINOR;

namespace dpscope {
namespace {

// ---- registration tables ----------------------------------------------------------------------

int proto_dpscope = -1;
dissector_handle_t dpscope_handle = nullptr;

// Names and texts registered with Wireshark must live as long as the program.
std::deque<std::string>& kept_strings() {
    static std::deque<std::string> strings;
    return strings;
}
const char* keep(std::string text) { return kept_strings().emplace_back(std::move(text)).c_str(); }

// Every field: its id, registered from this table.
struct Field {
    int id = -1;
    const char* name;
    const char* abbrev;  // the display-filter name
    ftenum type;
    int display;
    const char* blurb;
};

#define DPSCOPE_FIELDS(X)                                                                          \
    X(bus, "Bus", "dpscope.bus", FT_STRING, BASE_NONE, "profibus, fc or vlt2000")                  \
    X(direction, "Direction", "dpscope.direction", FT_STRING, BASE_NONE, "request or response")    \
    X(master, "Master", "dpscope.master", FT_UINT8, BASE_DEC, "The master's address")              \
    X(slave, "Slave/drive", "dpscope.slave", FT_UINT8, BASE_DEC, "The slave's (drive's) address")  \
    X(request_frame, "Request in frame", "dpscope.request_frame", FT_FRAMENUM, BASE_NONE,          \
      "The request this response answers")                                                         \
    X(response_frame, "Response in frame", "dpscope.response_frame", FT_FRAMENUM, BASE_NONE,       \
      "The response that answered this request")                                                   \
    X(response_time, "Response time", "dpscope.response_time", FT_RELATIVE_TIME, BASE_NONE,        \
      "From the request to this response")                                                         \
    X(problem, "Problem", "dpscope.problem", FT_STRING, BASE_NONE,                                 \
      "A problem the decoder found (its kind)")                                                    \
    X(finding, "Finding", "dpscope.finding", FT_STRING, BASE_NONE,                                 \
      "A finding of dpscope's tracker (its kind)")                                                 \
    X(finding_severity, "Severity", "dpscope.finding.severity", FT_STRING, BASE_NONE,              \
      "error, warning or note")                                                                    \
    X(finding_request, "Related request", "dpscope.finding.request_frame", FT_FRAMENUM, BASE_NONE, \
      "The request the finding is about")                                                          \
    X(fdl_sd, "Start delimiter", "dpscope.fdl.sd", FT_UINT8, BASE_HEX, "SD1, SD2, SD3, SD4, SC")   \
    X(fdl_le, "LE", "dpscope.fdl.le", FT_UINT8, BASE_DEC, "SD2 length")                            \
    X(fdl_ler, "LEr", "dpscope.fdl.ler", FT_UINT8, BASE_DEC, "SD2 length repeated")                \
    X(fdl_da, "Destination address", "dpscope.fdl.da", FT_UINT8, BASE_DEC, NULL)                   \
    X(fdl_sa, "Source address", "dpscope.fdl.sa", FT_UINT8, BASE_DEC, NULL)                        \
    X(fdl_dsap, "DSAP", "dpscope.fdl.dsap", FT_UINT8, BASE_DEC, NULL)                              \
    X(fdl_ssap, "SSAP", "dpscope.fdl.ssap", FT_UINT8, BASE_DEC, NULL)                              \
    X(fdl_fc, "Frame control", "dpscope.fdl.fc", FT_UINT8, BASE_HEX, NULL)                         \
    X(fdl_fc_request, "Request", "dpscope.fdl.fc.request", FT_BOOLEAN, BASE_NONE, NULL)            \
    X(fdl_fc_fcb, "FCB", "dpscope.fdl.fc.fcb", FT_BOOLEAN, BASE_NONE, "Frame count bit")           \
    X(fdl_fc_fcv, "FCV", "dpscope.fdl.fc.fcv", FT_BOOLEAN, BASE_NONE, "Frame count bit valid")     \
    X(fdl_fc_function, "Function", "dpscope.fdl.fc.function", FT_UINT8, BASE_DEC, NULL)            \
    X(fdl_data, "Data unit", "dpscope.fdl.data", FT_BYTES, BASE_NONE, NULL)                        \
    X(fdl_fcs, "FCS", "dpscope.fdl.fcs", FT_UINT8, BASE_HEX, NULL)                                 \
    X(fdl_fcs_ok, "FCS correct", "dpscope.fdl.fcs_ok", FT_BOOLEAN, BASE_NONE, NULL)                \
    X(fdl_ed, "End delimiter", "dpscope.fdl.ed", FT_UINT8, BASE_HEX, NULL)                         \
    X(dp_service, "Service", "dpscope.dp.service", FT_STRING, BASE_NONE, "The DP service")         \
    X(dp_data, "Data", "dpscope.dp.data", FT_BYTES, BASE_NONE, NULL)                               \
    X(ppo_type, "PPO type", "dpscope.ppo.type", FT_UINT8, BASE_DEC, "0: no standard PPO")          \
    X(ppo_cfg_frame, "Announced in frame", "dpscope.ppo.cfg_frame", FT_FRAMENUM, BASE_NONE,        \
      "The Chk_Cfg or Get_Cfg that announced the layout")                                          \
    X(dialect, "Dialect", "dpscope.pcv.dialect", FT_STRING, BASE_NONE, "vlt, ge or profidrive")    \
    X(pcv, "PCV", "dpscope.pcv", FT_BYTES, BASE_NONE, "The parameter channel")                     \
    X(pcv_pca, "PCA", "dpscope.pcv.pca", FT_UINT16, BASE_HEX, "PKE: RC, SPM, PNU")                 \
    X(pcv_rc, "RC", "dpscope.pcv.rc", FT_UINT8, BASE_DEC, "Request or response code (AK)")         \
    X(pcv_spm, "SPM", "dpscope.pcv.spm", FT_BOOLEAN, BASE_NONE, "Spontaneous message toggle")      \
    X(pcv_pnu, "PNU", "dpscope.pcv.pnu", FT_UINT16, BASE_DEC, "Parameter number")                  \
    X(pcv_ind, "IND", "dpscope.pcv.ind", FT_UINT8, BASE_DEC, "Subindex")                           \
    X(pcv_pva, "PVA", "dpscope.pcv.pva", FT_UINT32, BASE_HEX, "Parameter value bytes")             \
    X(pcv_value, "Value", "dpscope.pcv.value", FT_UINT32, BASE_DEC, "As the code's width says")    \
    X(pcv_error, "Error number", "dpscope.pcv.error", FT_UINT16, BASE_DEC, "RC 7's error")         \
    X(pcd_profile, "Control/status word profile", "dpscope.pcd.profile", FT_STRING, BASE_NONE,     \
      "fc or profidrive")                                                                          \
    X(pcd, "PCD", "dpscope.pcd", FT_BYTES, BASE_NONE, "Process data")                              \
    X(pcd_ctw, "CTW", "dpscope.pcd.ctw", FT_UINT16, BASE_HEX, "Control word (PCD 1)")              \
    X(pcd_stw, "STW", "dpscope.pcd.stw", FT_UINT16, BASE_HEX, "Status word (PCD 1)")               \
    X(pcd_ref, "Reference", "dpscope.pcd.ref", FT_UINT16, BASE_HEX, "MRV / MAV (PCD 2)")           \
    X(pcd_word, "PCD word", "dpscope.pcd.word", FT_UINT16, BASE_HEX, "PCD 3 and later")            \
    X(diag_status1, "Station status 1", "dpscope.diag.status1", FT_UINT8, BASE_HEX, NULL)          \
    X(diag_status2, "Station status 2", "dpscope.diag.status2", FT_UINT8, BASE_HEX, NULL)          \
    X(diag_status3, "Station status 3", "dpscope.diag.status3", FT_UINT8, BASE_HEX, NULL)          \
    X(diag_master, "Master address", "dpscope.diag.master", FT_UINT8, BASE_DEC, NULL)              \
    X(diag_ident, "Ident number", "dpscope.diag.ident", FT_UINT16, BASE_HEX, NULL)                 \
    X(diag_ext, "Extended diagnosis", "dpscope.diag.ext", FT_BYTES, BASE_NONE, NULL)               \
    X(diag_block, "Block", "dpscope.diag.block", FT_BYTES, BASE_NONE,                              \
      "Extended diagnosis block as sent, its header byte first")                                   \
    X(diag_block_type, "Block type", "dpscope.diag.block_type", FT_STRING, BASE_NONE,              \
      "device-related, identifier-related, channel-related or revision")                           \
    X(prm_status, "Station status", "dpscope.prm.status", FT_UINT8, BASE_HEX, NULL)                \
    X(prm_wd_fact_1, "WD_Fact_1", "dpscope.prm.wd_fact_1", FT_UINT8, BASE_DEC, NULL)               \
    X(prm_wd_fact_2, "WD_Fact_2", "dpscope.prm.wd_fact_2", FT_UINT8, BASE_DEC, NULL)               \
    X(prm_watchdog_ms, "Watchdog time", "dpscope.prm.watchdog_ms", FT_UINT32, BASE_DEC,            \
      "ms; only with the watchdog on")                                                             \
    X(prm_watchdog_ms_alt, "Watchdog time with a 10 ms base", "dpscope.prm.watchdog_ms_alt",       \
      FT_UINT32, BASE_DEC, "ms; where the time base is uncertain")                                 \
    X(prm_min_tsdr, "min TSDR", "dpscope.prm.min_tsdr", FT_UINT8, BASE_DEC, "Bit times")           \
    X(prm_ident, "Ident number", "dpscope.prm.ident", FT_UINT16, BASE_HEX, NULL)                   \
    X(prm_group, "Group ident", "dpscope.prm.group", FT_UINT8, BASE_HEX, NULL)                     \
    X(prm_dpv1_status, "DPV1_Status", "dpscope.prm.dpv1_status", FT_UINT8, BASE_HEX, NULL)         \
    X(prm_user, "User_Prm_Data", "dpscope.prm.user", FT_BYTES, BASE_NONE, NULL)                    \
    X(cfg_identifiers, "Identifier bytes", "dpscope.cfg.identifiers", FT_BYTES, BASE_NONE, NULL)   \
    X(cfg_module, "Module", "dpscope.cfg.module", FT_UINT8, BASE_HEX, "An identifier byte")        \
    X(cfg_ppo, "PPO type", "dpscope.cfg.ppo", FT_UINT8, BASE_DEC,                                  \
      "The PPO the identifiers announce; 0: no standard PPO")                                      \
    X(gc_command, "Control command", "dpscope.gc.command", FT_UINT8, BASE_HEX, NULL)               \
    X(gc_group, "Group select", "dpscope.gc.group", FT_UINT8, BASE_HEX, NULL)                      \
    X(ssa_address, "New slave address", "dpscope.ssa.address", FT_UINT8, BASE_DEC, NULL)           \
    X(ssa_ident, "Ident number", "dpscope.ssa.ident", FT_UINT16, BASE_HEX, NULL)                   \
    X(ssa_no_add_chg, "No_Add_Chg", "dpscope.ssa.no_add_chg", FT_UINT8, BASE_DEC, NULL)            \
    X(dpv1_function, "DP-V1 function", "dpscope.dpv1.function", FT_UINT8, BASE_HEX, NULL)          \
    X(dpv1_negative, "Negative response", "dpscope.dpv1.negative", FT_BOOLEAN, BASE_NONE, NULL)    \
    X(dpv1_slot, "Slot", "dpscope.dpv1.slot", FT_UINT8, BASE_DEC, NULL)                            \
    X(dpv1_index, "Index", "dpscope.dpv1.index", FT_UINT8, BASE_DEC, NULL)                         \
    X(dpv1_length, "Length", "dpscope.dpv1.length", FT_UINT8, BASE_DEC, NULL)                      \
    X(dpv1_data, "Data", "dpscope.dpv1.data", FT_BYTES, BASE_NONE, NULL)                           \
    X(dpv1_error_decode, "Error_Decode", "dpscope.dpv1.error_decode", FT_UINT8, BASE_HEX, NULL)    \
    X(dpv1_error_code_1, "Error_Code_1", "dpscope.dpv1.error_code_1", FT_UINT8, BASE_HEX, NULL)    \
    X(dpv1_error_code_2, "Error_Code_2", "dpscope.dpv1.error_code_2", FT_UINT8, BASE_HEX, NULL)    \
    X(dpv1_send_timeout, "Send_Timeout", "dpscope.dpv1.send_timeout", FT_UINT16, BASE_DEC,         \
      "Initiate request, 10 ms units")                                                             \
    X(dpv1_max_len_data_unit, "Max_Len_Data_Unit", "dpscope.dpv1.max_len_data_unit", FT_UINT8,     \
      BASE_DEC, "Initiate response")                                                               \
    X(dpv1_features, "Features_Supported", "dpscope.dpv1.features_supported", FT_UINT16, BASE_HEX, \
      "Initiate")                                                                                  \
    X(dpv1_profile_features, "Profile_Features_Supported",                                         \
      "dpscope.dpv1.profile_features_supported", FT_UINT16, BASE_HEX, "Initiate")                  \
    X(dpv1_profile_ident, "Profile_Ident_Number", "dpscope.dpv1.profile_ident_number", FT_UINT16,  \
      BASE_HEX, "Initiate")                                                                        \
    X(dpv1_abort_subnet, "Subnet", "dpscope.dpv1.abort.subnet", FT_UINT8, BASE_DEC, "Abort")       \
    X(dpv1_abort_instance, "Instance", "dpscope.dpv1.abort.instance", FT_UINT8, BASE_DEC,          \
      "Abort: the instance that aborted (bits 4-5)")                                               \
    X(dpv1_abort_reason, "Reason code", "dpscope.dpv1.abort.reason", FT_UINT8, BASE_DEC,           \
      "Abort: bits 0-3")                                                                           \
    X(pd_reference, "Request reference", "dpscope.profidrive.reference", FT_UINT8, BASE_DEC, NULL) \
    X(pd_id, "Request/Response ID", "dpscope.profidrive.id", FT_UINT8, BASE_HEX, NULL)             \
    X(pd_axis, "Axis", "dpscope.profidrive.axis", FT_UINT8, BASE_DEC, NULL)                        \
    X(pd_count, "Number of parameters", "dpscope.profidrive.count", FT_UINT8, BASE_DEC, NULL)      \
    X(pd_request_frame, "Request in frame", "dpscope.profidrive.request_frame", FT_FRAMENUM,       \
      BASE_NONE, "The PROFIdrive request this response answers")                                   \
    X(pd_attribute, "Attribute", "dpscope.profidrive.attribute", FT_UINT8, BASE_HEX, NULL)         \
    X(pd_elements, "Number of elements", "dpscope.profidrive.elements", FT_UINT8, BASE_DEC, NULL)  \
    X(pd_pnu, "Parameter number", "dpscope.profidrive.pnu", FT_UINT16, BASE_DEC, NULL)             \
    X(pd_subindex, "Subindex", "dpscope.profidrive.subindex", FT_UINT16, BASE_DEC, NULL)           \
    X(pd_format, "Format", "dpscope.profidrive.format", FT_UINT8, BASE_HEX, NULL)                  \
    X(pd_values, "Values", "dpscope.profidrive.values", FT_BYTES, BASE_NONE,                       \
      "The value bytes as sent")                                                                   \
    X(pd_value, "Value", "dpscope.profidrive.value", FT_DOUBLE, BASE_NONE,                         \
      "One value as a number (N2/N4 in %, times in ms)")                                           \
    X(pd_error, "Error number", "dpscope.profidrive.error", FT_UINT16, BASE_HEX, NULL)             \
    X(pd_error_info, "Additional information", "dpscope.profidrive.error_info", FT_UINT16,         \
      BASE_DEC, NULL)                                                                              \
    X(fc_stx, "STX", "dpscope.fc.stx", FT_UINT8, BASE_HEX, NULL)                                   \
    X(fc_lge, "LGE", "dpscope.fc.lge", FT_UINT8, BASE_DEC, "Telegram length")                      \
    X(fc_block, "Block", "dpscope.fc.block", FT_STRING, BASE_NONE, "process, parameter or text")   \
    X(fc_adr, "ADR", "dpscope.fc.adr", FT_UINT8, BASE_HEX, "The address byte")                     \
    X(fc_address, "Drive address", "dpscope.fc.address", FT_UINT8, BASE_DEC, "0: broadcast")       \
    X(fc_broadcast, "Broadcast", "dpscope.fc.broadcast", FT_BOOLEAN, BASE_NONE, NULL)              \
    X(fc_pke, "PKE", "dpscope.fc.pke", FT_UINT16, BASE_HEX, NULL)                                  \
    X(fc_ak, "AK", "dpscope.fc.ak", FT_UINT8, BASE_DEC, "Command or response code")                \
    X(fc_pnu, "PNU", "dpscope.fc.pnu", FT_UINT16, BASE_DEC, "Parameter number")                    \
    X(fc_ind, "IND", "dpscope.fc.ind", FT_UINT16, BASE_HEX, NULL)                                  \
    X(fc_index, "Index", "dpscope.fc.index", FT_UINT8, BASE_DEC, "IND's low byte")                 \
    X(fc_pwe, "PWE", "dpscope.fc.pwe", FT_UINT32, BASE_HEX, "Parameter value")                     \
    X(fc_value, "Value", "dpscope.fc.value", FT_UINT32, BASE_DEC, NULL)                            \
    X(fc_fault, "Fault code", "dpscope.fc.fault", FT_UINT16, BASE_DEC, NULL)                       \
    X(fc_text, "Text", "dpscope.fc.text", FT_STRING, BASE_NONE, NULL)                              \
    X(fc_bcc, "BCC", "dpscope.fc.bcc", FT_UINT8, BASE_HEX, NULL)                                   \
    X(fc_bcc_ok, "BCC correct", "dpscope.fc.bcc_ok", FT_BOOLEAN, BASE_NONE, NULL)                  \
    X(vlt_start, "Start", "dpscope.vlt2000.start", FT_UINT8, BASE_HEX, NULL)                       \
    X(vlt_address, "Address", "dpscope.vlt2000.address", FT_UINT8, BASE_DEC, "00: broadcast")      \
    X(vlt_letter, "Control letter", "dpscope.vlt2000.letter", FT_STRING, BASE_NONE, "U, R, C, I")  \
    X(vlt_word, "Control/status word", "dpscope.vlt2000.word", FT_UINT16, BASE_HEX, NULL)          \
    X(vlt_parameter, "Parameter", "dpscope.vlt2000.parameter", FT_UINT16, BASE_DEC, NULL)          \
    X(vlt_negative, "Negative", "dpscope.vlt2000.negative", FT_BOOLEAN, BASE_NONE, NULL)           \
    X(vlt_value, "Value", "dpscope.vlt2000.value", FT_DOUBLE, BASE_NONE,                           \
      "The digits with the decimal position applied")                                              \
    X(vlt_index, "Index", "dpscope.vlt2000.index", FT_UINT32, BASE_DEC, NULL)                      \
    X(vlt_decimals, "Decimal position", "dpscope.vlt2000.decimals", FT_UINT8, BASE_DEC, NULL)      \
    X(vlt_failed, "Command failed", "dpscope.vlt2000.failed", FT_BOOLEAN, BASE_NONE, NULL)         \
    X(vlt_reason, "Reason code", "dpscope.vlt2000.reason", FT_UINT8, BASE_DEC, NULL)               \
    X(vlt_checksum, "Checksum", "dpscope.vlt2000.checksum", FT_STRING, BASE_NONE,                  \
      "As sent: two digits, or ?? when switched off")                                              \
    X(vlt_checksum_ok, "Checksum correct", "dpscope.vlt2000.checksum_ok", FT_BOOLEAN, BASE_NONE,   \
      "Only where the checksum was judged: not when it is ??")                                     \
    X(vlt_stop, "Stop", "dpscope.vlt2000.stop", FT_UINT8, BASE_HEX, NULL)

#define DPSCOPE_FIELD_ID(id, name, abbrev, type, display, blurb) int hf_##id = -1;
DPSCOPE_FIELDS(DPSCOPE_FIELD_ID)
#undef DPSCOPE_FIELD_ID

// The bits of PCD 1: dpscope.pcd.ctw.bit0 .. bit15, dpscope.pcd.stw.bit0 .. bit15.
int hf_ctw_bit[16];
int hf_stw_bit[16];

enum Subtree {
    kEttTop,
    kEttFdl,
    kEttFrameControl,
    kEttDp,
    kEttPcv,
    kEttPca,
    kEttPcd,
    kEttWord,
    kEttService,
    kEttBlock,
    kEttDpv1,
    kEttProfidrive,
    kEttParameter,
    kEttFc,
    kEttVlt2000,
    kEttProblems,
    kEttFindings,
    kEttCount
};
int ett[kEttCount];

// Expert info: one per problem kind; one per finding kind and severity.
expert_field ei_problem[kProblemKindCount];
expert_field ei_finding[kFindingKindCount][3];

int expert_severity(Severity severity) {
    switch (severity) {
        case Severity::Error: return PI_ERROR;
        case Severity::Warning: return PI_WARN;
        case Severity::Note: break;
    }
    return PI_NOTE;
}

int problem_group(ProblemKind kind) {
    switch (kind) {
        case ProblemKind::FcsMismatch:
        case ProblemKind::BccMismatch:
        case ProblemKind::Vlt2000ChecksumMismatch: return PI_CHECKSUM;
        default: return PI_MALFORMED;
    }
}

int finding_group(FindingKind kind) {
    switch (kind) {
        case FindingKind::FcsError:
        case FindingKind::FcBccError:
        case FindingKind::Vlt2000ChecksumError:
        case FindingKind::Vlt2000ChecksumDisabled: return PI_CHECKSUM;
        case FindingKind::MalformedTelegram: return PI_MALFORMED;
        case FindingKind::RequestRejected:
        case FindingKind::NoAuthority:
        case FindingKind::Dpv1NegativeResponse:
        case FindingKind::Dpv1ErrorPdu:
        case FindingKind::FcCommandRejected:
        case FindingKind::Vlt2000CommandFailed: return PI_RESPONSE_CODE;
        case FindingKind::ConfigMismatch:
        case FindingKind::UnknownCode:
        case FindingKind::Dpv1UnknownCode: return PI_PROTOCOL;
        default: return PI_SEQUENCE;
    }
}

// ---- preferences ------------------------------------------------------------------------------

enum BusPreference { kBusAuto, kBusProfibus, kBusFc, kBusVlt2000 };
const enum_val_t kBusValues[] = {
    {"auto", "From the capture (dpscope's tag, else the first byte)", kBusAuto},
    {"profibus", "PROFIBUS DP", kBusProfibus},
    {"fc", "Danfoss FC protocol", kBusFc},
    {"vlt2000", "VLT 2000 serial telegram", kBusVlt2000},
    {nullptr, nullptr, 0}};
const enum_val_t kDialectValues[] = {{"vlt", "vlt (Danfoss VLT 5000)", 0},
                                     {"ge", "ge (GE AF-600/AF-650)", 1},
                                     {"profidrive", "profidrive (PROFIdrive PKW)", 2},
                                     {nullptr, nullptr, 0}};
const enum_val_t kPnuBitsValues[] = {
    {"12", "12 (FC series)", 12}, {"11", "11 (VLT 2800, FCD 300)", 11}, {nullptr, nullptr, 0}};

struct Preferences {
    gint bus = kBusAuto;
    gint dialect = 0;
    guint timeout_ms = 1000;
    guint fc_response_ms = 20;
    gint fc_pnu_bits = 12;
    guint baud = 9600;
    gboolean vlt2000_checksum = TRUE;
    gboolean strict = FALSE;
};
Preferences prefs;

// The decoder and tracker options from the preferences, each range-checked as dpscope's command
// line checks it; a value out of range is set back to its default with a warning.
ReplayOptions options_from_preferences() {
    auto checked = [](guint& value, guint low, guint high, guint fallback, const char* name) {
        if (value < low || value > high) {
            ws_warning("dpscope: preference %s = %u is out of range %u to %u; using %u", name,
                       value, low, high, fallback);
            value = fallback;
        }
    };
    checked(prefs.timeout_ms, 1, 3'600'000, 1000, "timeout_ms");
    checked(prefs.fc_response_ms, 1, 60'000, 20, "fc_response_ms");
    checked(prefs.baud, 300, 12'000'000, 9600, "baud");
    static constexpr Dialect kDialects[] = {Dialect::Vlt, Dialect::Ge, Dialect::Profidrive};
    ReplayChoices choices;
    choices.dialect = kDialects[prefs.dialect >= 0 && prefs.dialect < 3 ? prefs.dialect : 0];
    choices.timeout_ms = prefs.timeout_ms;
    choices.strict = prefs.strict;
    choices.fc_response_ms = prefs.fc_response_ms;
    choices.line_baud = prefs.baud;
    choices.fc_pnu_bits = static_cast<std::uint8_t>(prefs.fc_pnu_bits == 11 ? 11 : 12);
    choices.vlt2000_checksum = prefs.vlt2000_checksum;
    return replay_options(choices);
}

// ---- the capture's state ----------------------------------------------------------------------

// One capture at a time: set up at the first telegram, dropped when the capture is closed or the
// preferences change (Wireshark then dissects everything again).
std::unique_ptr<CaptureReplay> capture;

void forget_capture() { capture.reset(); }

// The bus of the capture: the preference, else the tag of a pcapng interface dpscope wrote, else
// the first telegram's first byte (dpscope's rule for an untagged USER0 capture).
Protocol choose_protocol(packet_info* pinfo, tvbuff_t* tvb) {
    switch (prefs.bus) {
        case kBusProfibus: return Protocol::ProfibusDp;
        case kBusFc: return Protocol::Fc;
        case kBusVlt2000: return Protocol::Vlt2000;
        default: break;
    }
    if (pinfo->rec && (pinfo->rec->presence_flags & WTAP_HAS_INTERFACE_ID)) {
        const char* description = epan_get_interface_description(
            pinfo->epan, pinfo->rec->rec_header.packet_header.interface_id);
        if (description) {
            std::string_view text(description);
            if (text.starts_with(kPcapngBusTagPrefix))
                if (auto tagged = protocol_from_name(text.substr(kPcapngBusTagPrefix.size())))
                    return *tagged;
        }
    }
    if (tvb_captured_length(tvb) == 0) return Protocol::ProfibusDp;
    return protocol_of_untagged_user0(tvb_get_guint8(tvb, 0));
}

// ---- building the tree ------------------------------------------------------------------------

// A subtree of the telegram: items are placed at telegram offsets, cut to the bytes there are
// (an offset past the end is shown without bytes), so no item throws.
class Tree {
  public:
    Tree(proto_tree* tree, tvbuff_t* tvb) : tree_(tree), tvb_(tvb) {}

    proto_tree* get() const { return tree_; }

    Tree sub(proto_item* item, int subtree) const {
        return Tree(proto_item_add_subtree(item, ett[subtree]), tvb_);
    }
    Tree text(std::size_t at, std::size_t length, int subtree, const std::string& text) const {
        auto [o, l] = place(at, length);
        return Tree(proto_tree_add_subtree(tree_, tvb_, o, l, ett[subtree], nullptr, text.c_str()),
                    tvb_);
    }
    proto_item* uint(int hf, std::size_t at, std::size_t length, std::uint32_t value,
                     const std::string& shown) const {
        auto [o, l] = place(at, length);
        return proto_tree_add_uint_format_value(tree_, hf, tvb_, o, l, value, "%s", shown.c_str());
    }
    proto_item* uint(int hf, std::size_t at, std::size_t length, std::uint32_t value) const {
        auto [o, l] = place(at, length);
        return proto_tree_add_uint(tree_, hf, tvb_, o, l, value);
    }
    proto_item* boolean(int hf, std::size_t at, std::size_t length, bool value,
                        const std::string& shown) const {
        auto [o, l] = place(at, length);
        return proto_tree_add_boolean_format_value(tree_, hf, tvb_, o, l, value ? 1 : 0, "%s",
                                                   shown.c_str());
    }
    proto_item* boolean(int hf, std::size_t at, std::size_t length, bool value) const {
        return boolean(hf, at, length, value, value ? "True" : "False");
    }
    proto_item* string(int hf, std::size_t at, std::size_t length, const std::string& value,
                       const std::string& shown) const {
        auto [o, l] = place(at, length);
        return proto_tree_add_string_format_value(tree_, hf, tvb_, o, l, value.c_str(), "%s",
                                                  shown.c_str());
    }
    proto_item* string(int hf, std::size_t at, std::size_t length, const std::string& value) const {
        return string(hf, at, length, value, value);
    }
    proto_item* bytes(int hf, std::size_t at, std::size_t length) const {
        auto [o, l] = place(at, length);
        return proto_tree_add_item(tree_, hf, tvb_, o, l, ENC_NA);
    }
    proto_item* bytes(int hf, std::size_t at, std::size_t length, const std::string& shown) const {
        auto [o, l] = place(at, length);
        return proto_tree_add_bytes_format_value(tree_, hf, tvb_, o, l, nullptr, "%s",
                                                 shown.c_str());
    }
    proto_item* real(int hf, std::size_t at, std::size_t length, double value,
                     const std::string& shown) const {
        auto [o, l] = place(at, length);
        return proto_tree_add_double_format_value(tree_, hf, tvb_, o, l, value, "%s",
                                                  shown.c_str());
    }
    proto_item* generated(proto_item* item) const {
        proto_item_set_generated(item);
        return item;
    }

  private:
    std::pair<gint, gint> place(std::size_t at, std::size_t length) const {
        const std::size_t size = tvb_captured_length(tvb_);
        if (at >= size) return {0, 0};
        return {static_cast<gint>(at), static_cast<gint>(std::min(length, size - at))};
    }

    proto_tree* tree_;
    tvbuff_t* tvb_;
};

std::string buffer_text(const TextBuffer& b) { return std::string(b.data(), b.size()); }

std::string flags_text(std::uint8_t value, std::span<const FlagBit> flags,
                       std::uint8_t ignore = 0) {
    TextBuffer b;
    fmt::format_to(std::back_inserter(b), "0x{:02X} (", value);
    append_flags(b, value, flags, "none", ignore);
    b.push_back(')');
    return buffer_text(b);
}

// Characters as sent, as jsonl writes them (\xNN for a byte that is not printable).
std::string chars_text(Bytes bytes) {
    TextBuffer b;
    append_fc_text(b, bytes);
    return buffer_text(b);
}

std::string hex_text(Bytes bytes) {
    TextBuffer b;
    append_hex(b, bytes);
    return buffer_text(b);
}

// PCD 1 with its 16 bits, as `dpscope decode -V` words them.
void add_word_bits(const Tree& tree, proto_item* item, std::size_t at, std::uint16_t word,
                   bool control, const WordBits& bits) {
    Tree sub = tree.sub(item, kEttWord);
    for (unsigned bit = 0; bit < 16; ++bit) {
        const bool set = (word >> bit) & 1u;
        const WordBit& meaning = bits[bit];
        sub.boolean(control ? hf_ctw_bit[bit] : hf_stw_bit[bit], at, 2, set,
                    fmt::format("{}: {}", set ? 1 : 0, set ? meaning.when_1 : meaning.when_0));
    }
}

void add_fdl(const Tree& top, const DecodedTelegram& t) {
    const FdlTelegram& f = t.dp.fdl;
    Tree tree = top.text(0, f.size > 0 ? f.size : t.bytes.size(), kEttFdl, "PROFIBUS FDL");
    if (f.type == FrameType::Invalid) {
        if (!t.bytes.empty())
            tree.uint(hf_fdl_sd, 0, 1, t.bytes[0],
                      fmt::format("0x{:02X} (not a start delimiter)", t.bytes[0]));
        return;
    }
    tree.uint(hf_fdl_sd, 0, 1, t.bytes[0],
              fmt::format("{} (0x{:02X})", frame_type_name(f.type), t.bytes[0]));
    std::size_t address_at = 1;
    if (f.type == FrameType::Sd2) {
        tree.uint(hf_fdl_le, 1, 1, f.length_field);
        if (f.has_length_repeat) tree.uint(hf_fdl_ler, 2, 1, f.length_repeat);
        address_at = 4;
    }
    const bool request = f.has_fc && f.fc.is_request();
    if (f.has_addresses) {
        tree.uint(hf_fdl_da, address_at, 1, f.da,
                  fmt::format("{}{}", f.da, f.da == kBroadcastAddress ? " (broadcast)" : ""));
        tree.uint(hf_fdl_sa, address_at + 1, 1, f.sa);
    }
    if (f.has_fc) {
        TextBuffer b;
        fmt::format_to(std::back_inserter(b), "0x{:02X} (", f.fc.raw);
        append_frame_control(b, f.fc);
        b.push_back(')');
        const std::size_t at = address_at + 2;
        Tree fc = tree.sub(tree.uint(hf_fdl_fc, at, 1, f.fc.raw, buffer_text(b)), kEttFrameControl);
        fc.boolean(hf_fdl_fc_request, at, 1, f.fc.is_request());
        if (f.fc.is_request()) {
            fc.boolean(hf_fdl_fc_fcb, at, 1, f.fc.fcb());
            fc.boolean(hf_fdl_fc_fcv, at, 1, f.fc.fcv());
        }
        fc.uint(hf_fdl_fc_function, at, 1, f.fc.function());
    }
    std::size_t sap_at = address_at + 3;
    auto sap_text = [](std::uint8_t sap, bool slave_side) {
        std::string_view name = sap_name(sap, slave_side);
        return fmt::format("{} ({})", sap, name.empty() ? "no DP meaning" : name);
    };
    if (f.has_dsap) tree.uint(hf_fdl_dsap, sap_at++, 1, f.dsap, sap_text(f.dsap, request));
    if (f.has_ssap) tree.uint(hf_fdl_ssap, sap_at, 1, f.ssap, sap_text(f.ssap, !request));
    if (!f.du.empty()) tree.bytes(hf_fdl_data, f.du_offset, f.du.size());
    if (f.has_fcs && f.size >= 2) {
        tree.uint(hf_fdl_fcs, f.size - 2u, 1, f.fcs,
                  fmt::format("0x{:02X} ({})", f.fcs, f.fcs_ok ? "correct" : "wrong"));
        tree.boolean(hf_fdl_fcs_ok, f.size - 2u, 1, f.fcs_ok);
    }
    if ((f.type == FrameType::Sd1 || f.type == FrameType::Sd2 || f.type == FrameType::Sd3) &&
        t.bytes.size() >= f.size && f.size > 0)
        tree.uint(hf_fdl_ed, f.size - 1u, 1, t.bytes[f.size - 1]);
}

void add_pcv(const Tree& tree, const DecodedTelegram& t) {
    const bool request = t.direction == Direction::Request;
    const Pcv& pcv = t.dp.pcv;
    const std::size_t at = t.dp.fdl.du_offset;
    Tree sub = tree.sub(tree.bytes(hf_pcv, at, kPcvBytes), kEttPcv);
    Tree pca =
        sub.sub(sub.uint(hf_pcv_pca, at, 2, pcv.pca, fmt::format("0x{:04X}", pcv.pca)), kEttPca);
    const bool defined = request
                             ? request_code(t.dp.dialect, pcv.rc).defined
                             : response_code(t.dp.dialect, pcv.rc).kind != ResponseKind::Undefined;
    pca.uint(hf_pcv_rc, at, 2, pcv.rc,
             fmt::format("{} = {}{}", pcv.rc, t.dp.pcv_meaning(t.direction),
                         defined ? "" : " (not defined by the dialect)"));
    pca.boolean(hf_pcv_spm, at, 2, pcv.spm, pcv.spm ? "1" : "0");
    pca.uint(hf_pcv_pnu, at, 2, pcv.pnu);
    sub.uint(hf_pcv_ind, at + 2, 2, pcv.ind,
             fmt::format("{} (byte 4: 0x{:02X})", pcv.ind, pcv.ind_low));
    const ValueWidth width = request ? request_code(t.dp.dialect, pcv.rc).width
                                     : response_code(t.dp.dialect, pcv.rc).width;
    const bool rejected =
        !request && response_code(t.dp.dialect, pcv.rc).kind == ResponseKind::Rejected;
    if (rejected) {
        sub.uint(hf_pcv_pva, at + 4, 4, pcv.pva);
        const auto error = static_cast<std::uint16_t>(pcv.pva & 0xFFFF);
        sub.uint(hf_pcv_error, at + 6, 2, error,
                 fmt::format("{} = {}", error, error_text_or_unknown(t.dp.dialect, error)));
    } else if (width == ValueWidth::None) {
        sub.uint(hf_pcv_pva, at + 4, 4, pcv.pva,
                 fmt::format("0x{:08X} (the code carries no value)", pcv.pva));
    } else {
        sub.uint(hf_pcv_pva, at + 4, 4, pcv.pva);
        const bool word = width == ValueWidth::Word;
        sub.uint(hf_pcv_value, word ? at + 6 : at + 4, word ? 2 : 4, pcv_value(pcv, width),
                 fmt::format("{} ({})", pcv_value(pcv, width), word ? "word" : "double word"));
    }
}

void add_pcd(const Tree& tree, const DecodedTelegram& t) {
    ByteReader reader(t.dp.pcd, t.dp.pcd_offset);
    if (reader.empty()) return;
    const bool request = t.direction == Direction::Request;
    Tree sub = tree.sub(tree.bytes(hf_pcd, t.dp.pcd_offset, t.dp.pcd.size()), kEttPcd);
    proto_item_append_text(sub.get() ? proto_tree_get_parent(sub.get()) : nullptr, " (%zu words)",
                           reader.remaining() / 2);
    const WordBits& bits = request ? control_word_bits(t.dp.pcd_profile, t.dp.danfoss_pcd())
                                   : status_word_bits(t.dp.pcd_profile, t.dp.danfoss_pcd());
    for (std::size_t index = 0;; ++index) {
        const std::size_t at = reader.offset();
        auto word = reader.u16_be();
        if (!word) break;
        const std::string_view name = pcd_word_name(t.direction, index);
        if (index == 0) {
            proto_item* item = sub.uint(request ? hf_pcd_ctw : hf_pcd_stw, at, 2, *word,
                                        fmt::format("0x{:04X} (PCD 1 {})", *word, name));
            add_word_bits(sub, item, at, *word, request, bits);
        } else if (index == 1) {
            sub.uint(hf_pcd_ref, at, 2, *word,
                     fmt::format("0x{:04X} = {:.2f} % (PCD 2 {})", *word, reference_percent(*word),
                                 name));
        } else {
            sub.uint(hf_pcd_word, at, 2, *word,
                     fmt::format("0x{:04X} ({}) (PCD {})", *word, *word, index + 1));
        }
    }
}

void add_diag(const Tree& tree, const DecodedTelegram& t, const SlaveDiag& diag,
              std::span<const DiagBlock> blocks) {
    const std::size_t at = t.dp.fdl.du_offset;
    tree.uint(hf_diag_status1, at, 1, diag.station_status_1,
              flags_text(diag.station_status_1, station_status_1_flags()));
    tree.uint(hf_diag_status2, at + 1, 1, diag.station_status_2,
              flags_text(diag.station_status_2, station_status_2_flags()));
    tree.uint(hf_diag_status3, at + 2, 1, diag.station_status_3,
              flags_text(diag.station_status_3, station_status_3_flags()));
    tree.uint(hf_diag_master, at + 3, 1, diag.master_address,
              diag.master_address == kNoMasterAddress ? "255 (not parameterised)"
                                                      : fmt::format("{}", diag.master_address));
    tree.uint(hf_diag_ident, at + 4, 2, diag.ident);
    if (diag.extended.empty()) return;
    Tree ext =
        tree.sub(tree.bytes(hf_diag_ext, diag.extended_offset, diag.extended.size()), kEttBlock);
    for (const DiagBlock& block : blocks) {
        std::string text;
        switch (block.type) {
            case DiagBlockType::Channel:
                text = fmt::format("channel-related: module {}, channel {}, {}, {}: error {} ({})",
                                   block.module, block.channel, channel_io_text(block.io),
                                   channel_type_text(block.channel_type), block.error_type,
                                   channel_error_text(block.error_type));
                break;
            case DiagBlockType::Revision:
                text = fmt::format("revision number {}", block.revision);
                break;
            case DiagBlockType::Identifier: {
                text = "identifier-related: modules with diagnosis:";
                bool any = false;
                for (std::size_t i = 0; i < block.data.size(); ++i)
                    for (int bit = 0; bit < 8; ++bit)
                        if ((block.data[i] >> bit) & 1) {
                            text += fmt::format(" {}", i * 8 + static_cast<std::size_t>(bit));
                            any = true;
                        }
                if (!any) text += " none";
                break;
            }
            case DiagBlockType::Device: {
                text = "device-related: " + hex_text(block.data);
                if (t.dp.slave_dpv1 == SlaveDpv1::Enabled && block.data.size() >= 3)
                    text += fmt::format(" (DP-V1: {}, slot {})",
                                        dpv1_alarm_or_status_text(block.data[0]), block.data[1]);
                else if (t.dp.slave_dpv1 == SlaveDpv1::Disabled)
                    text += " (manufacturer-specific: Set_Prm did not enable DP-V1)";
                break;
            }
        }
        // The block as sent (header byte and data), its wording in the text.
        Tree sub =
            ext.sub(ext.bytes(hf_diag_block, block.offset, block.data.size() + 1, text), kEttBlock);
        sub.string(hf_diag_block_type, block.offset, 1,
                   std::string(diag_block_type_name(block.type)));
    }
}

void add_prm(const Tree& tree, const DecodedTelegram& t, const SetPrm& prm) {
    const std::size_t at = t.dp.fdl.du_offset;
    tree.uint(hf_prm_status, at, 1, prm.station_status,
              flags_text(prm.station_status, set_prm_station_flags()));
    std::string watchdog = fmt::format("Watchdog: factors {} x {}", prm.wd_fact_1, prm.wd_fact_2);
    if (prm.watchdog_on() && prm.watchdog_base_uncertain())
        watchdog += fmt::format(" = {} ms with WD_Base_1ms, or {} ms with a 10 ms base",
                                prm.watchdog_ms(), prm.watchdog_ms_10ms_base());
    else if (prm.watchdog_on())
        watchdog += fmt::format(" = {} ms", prm.watchdog_ms());
    else
        watchdog += " (off)";
    // The two factors as sent; the time (jsonl's watchdog_ms, watchdog_ms_alt) only with the
    // watchdog on.
    Tree wd = tree.text(at + 1, 2, kEttBlock, watchdog);
    wd.uint(hf_prm_wd_fact_1, at + 1, 1, prm.wd_fact_1);
    wd.uint(hf_prm_wd_fact_2, at + 2, 1, prm.wd_fact_2);
    if (prm.watchdog_on()) {
        wd.generated(wd.uint(hf_prm_watchdog_ms, at + 1, 2, prm.watchdog_ms(),
                             fmt::format("{} ms", prm.watchdog_ms())));
        if (prm.watchdog_base_uncertain())
            wd.generated(wd.uint(hf_prm_watchdog_ms_alt, at + 1, 2, prm.watchdog_ms_10ms_base(),
                                 fmt::format("{} ms", prm.watchdog_ms_10ms_base())));
    }
    tree.uint(hf_prm_min_tsdr, at + 3, 1, prm.min_tsdr);
    tree.uint(hf_prm_ident, at + 4, 2, prm.ident);
    tree.uint(hf_prm_group, at + 6, 1, prm.group_ident);
    if (prm.has_dpv1_status) {
        tree.uint(hf_prm_dpv1_status, at + 7, 1, prm.dpv1_status[0],
                  "1: " + flags_text(prm.dpv1_status[0], dpv1_status_1_flags()));
        tree.uint(hf_prm_dpv1_status, at + 8, 1, prm.dpv1_status[1],
                  "2: " + flags_text(prm.dpv1_status[1], dpv1_status_2_flags()));
        tree.uint(hf_prm_dpv1_status, at + 9, 1, prm.dpv1_status[2],
                  fmt::format("3: 0x{:02X} (Alarm_Mode {} = {})", prm.dpv1_status[2],
                              prm.dpv1_status[2] & 0x07, dpv1_alarm_mode_text(prm.dpv1_status[2])));
    }
    if (!prm.user_prm.empty()) tree.bytes(hf_prm_user, prm.user_prm_offset, prm.user_prm.size());
}

void add_cfg(const Tree& tree, const DecodedTelegram& t, std::span<const CfgModule> modules) {
    Tree sub =
        tree.sub(tree.bytes(hf_cfg_identifiers, t.dp.fdl.du_offset, t.dp.fdl.du.size()), kEttBlock);
    std::size_t number = 1;
    for (const CfgModule& m : modules) {
        std::string text;
        if (m.free_place) {
            text = "free place";
        } else {
            text = fmt::format("{}{}", m.special ? "special format, " : "",
                               cfg_direction_name(m.direction));
            if (m.output_units)
                text += fmt::format(" out {}{}", cfg_units(m.output_units, m.output_words),
                                    m.output_consistent ? " consistent" : "");
            if (m.input_units)
                text += fmt::format(" in {}{}", cfg_units(m.input_units, m.input_words),
                                    m.input_consistent ? " consistent" : "");
            if (m.manufacturer_bytes)
                text += fmt::format(", {}", counted(m.manufacturer_bytes, "manufacturer byte",
                                                    "manufacturer bytes"));
        }
        sub.uint(hf_cfg_module, m.offset, 1, m.identifier,
                 fmt::format("{}: 0x{:02X} {}", number++, m.identifier, text));
    }
    const PpoLayout layout = ppo_from_cfg(
        modules, t.dp.service == Service::ChkCfg ? PpoSource::ChkCfg : PpoSource::GetCfg);
    TextBuffer b;
    append_ppo_long(b, layout);
    tree.uint(hf_cfg_ppo, t.dp.fdl.du_offset, t.dp.fdl.du.size(), layout.type, buffer_text(b));
}

void add_profidrive(const Tree& tree, const DecodedTelegram& t, const ProfidriveMessage& m,
                    std::size_t at) {
    Tree pd =
        tree.text(at, t.bytes.size() - std::min(at, t.bytes.size()), kEttProfidrive,
                  fmt::format("PROFIdrive parameter {}", m.is_response ? "response" : "request"));
    if (!m.has_header) {
        pd.text(at, 0, kEttParameter, "header cut short");
        return;
    }
    pd.uint(hf_pd_reference, at, 1, m.reference);
    const std::string_view id_name =
        m.is_response ? profidrive_response_id_name(m.id) : profidrive_request_id_name(m.id);
    pd.uint(hf_pd_id, at + 1, 1, m.id,
            fmt::format("0x{:02X} ({})", m.id, id_name.empty() ? "not defined" : id_name));
    pd.uint(hf_pd_axis, at + 2, 1, m.axis);
    pd.uint(hf_pd_count, at + 3, 1, m.count);
    if (m.is_response && m.has_request)
        pd.generated(
            pd.uint(hf_pd_request_frame, 0, 0, static_cast<std::uint32_t>(m.request_frame)));
    const std::size_t parameters = std::max(m.addresses.size(), m.blocks.size());
    for (std::size_t k = 0; k < parameters; ++k) {
        Tree p = pd.text(at, 0, kEttParameter, fmt::format("Parameter {}", k + 1));
        if (k < m.addresses.size()) {
            const ProfidriveAddress& a = m.addresses[k];
            // A response's addresses are the request's, copied by the decoder: no bytes here.
            const std::size_t a_at = m.is_response ? t.bytes.size() : at + 4 + 6 * k;
            const std::string_view attribute = profidrive_attribute_name(a.attribute);
            p.uint(hf_pd_attribute, a_at, 1, a.attribute,
                   fmt::format("0x{:02X} ({})", a.attribute,
                               attribute.empty() ? "not defined" : attribute));
            p.uint(hf_pd_elements, a_at + 1, 1, a.elements);
            p.uint(hf_pd_pnu, a_at + 2, 2, a.pnu);
            p.uint(hf_pd_subindex, a_at + 4, 2, a.subindex);
        }
        if (k >= m.blocks.size()) continue;
        const ProfidriveValueBlock& block = m.blocks[k];
        const std::size_t b_at = block.values_offset >= 2 ? block.values_offset - 2u : at;
        p.uint(hf_pd_format, b_at, 1, block.format,
               fmt::format("0x{:02X} ({})", block.format, profidrive_format_name(block.format)));
        if (block.is_error()) {
            if (block.values.size() >= 2)
                p.uint(hf_pd_error, block.values_offset, 2, block.error_number(),
                       fmt::format("0x{:02X} ({})", block.error_number(),
                                   profidrive_error_text(block.error_number(), t.dp.dialect)));
            if (block.has_error_info())
                p.uint(hf_pd_error_info, block.values_offset + 2u, 2, block.error_info());
        } else if (block.format != profidrive::kFormatZero) {
            // The bytes as sent, worded in the text; each value that is a number (jsonl's
            // "numbers") in a field of its own.
            std::string values;
            append_profidrive_values(block, values);
            Tree sub = p.sub(p.bytes(hf_pd_values, block.values_offset, block.values.size(),
                                     values.empty() ? std::string("(no values)") : values),
                             kEttParameter);
            const std::size_t size =
                static_cast<std::size_t>(std::max(profidrive_format_size(block.format), 0));
            for (std::size_t i = 0; i < profidrive_value_count(block); ++i) {
                const std::optional<ProfidriveNumber> n = profidrive_number(block, i);
                if (!n) continue;
                const double number = n->is_real ? n->real : static_cast<double>(n->integer);
                sub.real(hf_pd_value, block.values_offset + i * size, size, number,
                         !n->is_real ? fmt::format("{}", n->integer)
                         : n->single ? fmt::format("{}", static_cast<float>(n->real))
                                     : fmt::format("{}", n->real));
            }
        }
    }
}

void add_dpv1(const Tree& tree, const DecodedTelegram& t, const Dpv1Pdu& pdu) {
    const std::size_t at = t.dp.fdl.du_offset;
    if (pdu.layout == Dpv1Pdu::Layout::None) {
        tree.text(at, 0, kEttDpv1, "DP-V1 PDU: none (empty data unit: a link-level poll)");
        return;
    }
    const std::string_view name = dpv1_function_name(pdu.function);
    Tree sub = tree.sub(tree.uint(hf_dpv1_function, at, 1, pdu.function,
                                  fmt::format("0x{:02X} ({}){}", pdu.function,
                                              name.empty() ? "not defined by DP-V1" : name,
                                              pdu.negative() ? ", negative response" : "")),
                        kEttDpv1);
    sub.boolean(hf_dpv1_negative, at, 1, pdu.negative());
    switch (pdu.layout) {
        case Dpv1Pdu::Layout::Error: {
            const std::string_view decode = dpv1_error_decode_name(pdu.error_decode);
            sub.uint(hf_dpv1_error_decode, at + 1, 1, pdu.error_decode,
                     fmt::format("0x{:02X} ({})", pdu.error_decode,
                                 decode.empty() ? "unknown" : decode));
            const std::string_view error_class = dpv1_error_class_name(pdu.error_code_1);
            sub.uint(
                hf_dpv1_error_code_1, at + 2, 1, pdu.error_code_1,
                fmt::format("0x{:02X} (class {} {}, code {} {})", pdu.error_code_1,
                            pdu.error_code_1 >> 4, error_class.empty() ? "reserved" : error_class,
                            pdu.error_code_1 & 0x0F, dpv1_error_code_name(pdu.error_code_1)));
            sub.uint(hf_dpv1_error_code_2, at + 3, 1, pdu.error_code_2);
            break;
        }
        case Dpv1Pdu::Layout::Addressed:
            sub.uint(hf_dpv1_slot, at + 1, 1, pdu.slot);
            sub.uint(hf_dpv1_index, at + 2, 1, pdu.index,
                     fmt::format(
                         "{}{}", pdu.index,
                         pdu.index == kProfidriveIndex ? " (PROFIdrive parameter channel)" : ""));
            sub.uint(hf_dpv1_length, at + 3, 1, pdu.length);
            if (!pdu.data.empty()) sub.bytes(hf_dpv1_data, pdu.data_offset, pdu.data.size());
            break;
        case Dpv1Pdu::Layout::Initiate: {
            // The fields as sent, where the PDU holds them (as jsonl's "initiate"). Request:
            // function, 3 reserved bytes, Send_Timeout; response: function, Max_Len_Data_Unit.
            if (!pdu.complete) break;
            const Dpv1Initiate& i = pdu.initiate;
            const bool request = t.direction == Direction::Request;
            if (request)
                sub.uint(hf_dpv1_send_timeout, at + 4, 2, i.send_timeout,
                         fmt::format("{} ({} ms)", i.send_timeout, i.send_timeout * 10));
            else
                sub.uint(hf_dpv1_max_len_data_unit, at + 1, 1, i.max_len_data_unit);
            const std::size_t features_at = request ? at + 6 : at + 2;
            sub.uint(hf_dpv1_features, features_at, 2, i.features_supported);
            sub.uint(hf_dpv1_profile_features, features_at + 2, 2, i.profile_features_supported);
            sub.uint(hf_dpv1_profile_ident, features_at + 4, 2, i.profile_ident_number);
            break;
        }
        case Dpv1Pdu::Layout::Abort:
            if (!pdu.complete) break;
            sub.uint(hf_dpv1_abort_subnet, at + 1, 1, pdu.abort.subnet);
            sub.uint(hf_dpv1_abort_instance, at + 2, 1, pdu.abort.instance(),
                     fmt::format("{} ({})", pdu.abort.instance(),
                                 dpv1_abort_instance_name(pdu.abort.instance_reason)));
            sub.uint(hf_dpv1_abort_reason, at + 2, 1, pdu.abort.reason(),
                     fmt::format("{} ({})", pdu.abort.reason(),
                                 dpv1_abort_reason_name(pdu.abort.instance_reason)));
            break;
        case Dpv1Pdu::Layout::Unknown:
            if (!pdu.data.empty()) sub.bytes(hf_dpv1_data, pdu.data_offset, pdu.data.size());
            break;
        case Dpv1Pdu::Layout::Idle:
        case Dpv1Pdu::Layout::None: break;
    }
    if (const ProfidriveMessage* m = t.dp.service_data.profidrive())
        add_profidrive(tree, t, *m, pdu.data_offset);
}

void add_dp(const Tree& top, const DecodedTelegram& t) {
    if (t.dp.fdl.type == FrameType::Invalid) return;
    std::string title =
        fmt::format("PROFIBUS DP: {} {}", service_name(t.dp.service), direction_name(t.direction));
    if (t.has_roles && t.dp.service != Service::Token)
        title += fmt::format(", master {} / slave {}", t.master, t.slave);
    Tree tree = top.text(t.dp.fdl.du_offset, t.dp.fdl.du.size(), kEttDp, title);
    tree.string(hf_dp_service, 0, 0, std::string(service_name(t.dp.service)));
    const DpServiceData& data = t.dp.service_data;
    switch (t.dp.service) {
        case Service::DataExchange: {
            TextBuffer b;
            append_ppo_long(b, t.dp.ppo);
            tree.uint(hf_ppo_type, 0, 0, t.dp.ppo.type, buffer_text(b));
            if (t.dp.ppo_cfg_frame != 0)
                tree.generated(tree.uint(hf_ppo_cfg_frame, 0, 0,
                                         static_cast<std::uint32_t>(t.dp.ppo_cfg_frame)));
            // The dialect names the parameter channel's code tables: none without a PCV.
            if (t.dp.ppo.has_pcv)
                tree.string(hf_dialect, 0, 0, std::string(dialect_name(t.dp.dialect)));
            tree.string(hf_pcd_profile, 0, 0, std::string(pcd_profile_name(t.dp.pcd_profile)),
                        fmt::format("{}{}", pcd_profile_name(t.dp.pcd_profile),
                                    t.dp.pcd_profile == PcdProfile::Profidrive && t.dp.danfoss_pcd()
                                        ? " (Danfoss)"
                                        : ""));
            if (t.dp.has_pcv) add_pcv(tree, t);
            add_pcd(tree, t);
            break;
        }
        case Service::SlaveDiag:
            if (const SlaveDiag* diag = data.slave_diag())
                add_diag(tree, t, *diag, data.diag_blocks());
            break;
        case Service::SetPrm:
            if (const SetPrm* prm = data.set_prm()) add_prm(tree, t, *prm);
            break;
        case Service::ChkCfg:
        case Service::GetCfg:
            if (const std::vector<CfgModule>* modules = data.cfg_modules();
                modules && !t.dp.fdl.du.empty())
                add_cfg(tree, t, *modules);
            break;
        case Service::GlobalControl:
            if (const GlobalControl* gc = data.global_control()) {
                tree.uint(hf_gc_command, t.dp.fdl.du_offset, 1, gc->command,
                          flags_text(gc->command, global_control_flags()));
                tree.uint(hf_gc_group, t.dp.fdl.du_offset + 1u, 1, gc->group_select,
                          fmt::format("0x{:02X}{}", gc->group_select,
                                      gc->group_select == 0 ? " (all slaves)" : ""));
            }
            break;
        case Service::SetSlaveAdd:
            if (const SetSlaveAdd* ssa = data.set_slave_add()) {
                const std::size_t at = t.dp.fdl.du_offset;
                tree.uint(hf_ssa_address, at, 1, ssa->new_address);
                tree.uint(hf_ssa_ident, at + 1, 2, ssa->ident);
                tree.uint(hf_ssa_no_add_chg, at + 3, 1, ssa->no_add_chg);
            }
            break;
        case Service::MsacC1:
        case Service::MsacC2:
            if (const Dpv1Pdu* pdu = data.dpv1()) {
                add_dpv1(tree, t, *pdu);
                break;
            }
            [[fallthrough]];
        default:
            if (!t.dp.fdl.du.empty())
                tree.bytes(hf_dp_data, t.dp.fdl.du_offset, t.dp.fdl.du.size());
            break;
    }
}

void add_fc(const Tree& top, const DecodedTelegram& t) {
    const FcTelegram& fc = t.fc;
    const bool request = t.direction == Direction::Request;
    std::string title = "FC protocol";
    if (t.has_roles) {
        title +=
            fmt::format(": {} block {}", fc_block_name(fc.block), request ? "request" : "response");
        title += fc.broadcast ? " to every drive (broadcast)"
                              : fmt::format(" {} drive {}", request ? "to" : "from", fc.address);
    }
    Tree tree = top.text(0, t.bytes.size(), kEttFc, title);
    if (t.bytes.empty()) return;
    if (t.bytes[0] != kFcStx) {
        tree.uint(hf_fc_stx, 0, 1, t.bytes[0], fmt::format("0x{:02X} (not STX 0x02)", t.bytes[0]));
        return;
    }
    tree.uint(hf_fc_stx, 0, 1, kFcStx);
    if (t.bytes.size() < 2) return;
    tree.uint(
        hf_fc_lge, 1, 1, fc.lge,
        fc.block == FcBlock::Unknown
            ? fmt::format("{} (no block has this length; telegram {} bytes)", fc.lge, fc.lge + 2)
            : fmt::format("{} ({} block, telegram {} bytes)", fc.lge, fc_block_name(fc.block),
                          fc.lge + 2));
    tree.string(hf_fc_block, 1, 1, std::string(fc_block_name(fc.block)));
    if (!t.has_roles) return;
    tree.uint(hf_fc_adr, 2, 1, fc.adr,
              fmt::format(
                  "0x{:02X} ({} format, {})", fc.adr, fc_address_format_name(fc.address_format),
                  fc.broadcast ? std::string("broadcast") : fmt::format("address {}", fc.address)));
    tree.uint(hf_fc_address, 2, 1, fc.address);
    tree.boolean(hf_fc_broadcast, 2, 1, fc.broadcast);
    std::size_t pcd_at = 3;
    if (fc.has_pkw) {
        const Pcv& pkw = fc.pkw;
        Tree pke = tree.sub(tree.uint(hf_fc_pke, 3, 2, pkw.pca, fmt::format("0x{:04X}", pkw.pca)),
                            kEttPca);
        pke.uint(hf_fc_ak, 3, 2, pkw.rc,
                 fmt::format("{} = {}{}", pkw.rc, fc_ak_meaning(t),
                             fc_ak_defined(t) ? ""
                             : request        ? " (not a defined command)"
                                              : " (not a defined response)"));
        pke.uint(hf_fc_pnu, 3, 2, pkw.pnu,
                 fmt::format("{} (parameter {})", pkw.pnu, fc_parameter_name(pkw.pnu)));
        const std::uint16_t ind = static_cast<std::uint16_t>(fc.ind_high << 8 | pkw.ind_low);
        const std::string_view mode = fc_text_mode_name(fc.ind_high);
        Tree ind_tree = tree.sub(tree.uint(hf_fc_ind, 5, 2, ind,
                                           fc.block == FcBlock::Text && !mode.empty()
                                               ? fmt::format("0x{:04X} ({} text)", ind, mode)
                                               : fmt::format("0x{:04X}", ind)),
                                 kEttPca);
        ind_tree.uint(hf_fc_index, 6, 1, pkw.ind);
        if (fc.block == FcBlock::Text) {
            TextBuffer b;
            append_fc_text(b, fc.text);
            tree.string(hf_fc_text, 7, fc.text.size(), buffer_text(b),
                        fmt::format("{} characters \"{}\"", fc.text.size(), buffer_text(b)));
            pcd_at = 7 + fc.text.size();
        } else {
            if (fc_rejected(t)) {
                const std::uint16_t code = fc_fault_code(fc);
                tree.uint(hf_fc_pwe, 7, 4, pkw.pva);
                tree.uint(hf_fc_fault, 9, 2, code,
                          fmt::format("{} = {}", code, fc_fault_text_or_unknown(code)));
            } else {
                const ValueWidth width = fc_ak_width(t);
                if (width == ValueWidth::None) {
                    tree.uint(hf_fc_pwe, 7, 4, pkw.pva,
                              fmt::format("0x{:08X} (the AK carries no value)", pkw.pva));
                } else {
                    tree.uint(hf_fc_pwe, 7, 4, pkw.pva);
                    const bool word = width == ValueWidth::Word;
                    tree.uint(hf_fc_value, word ? 9 : 7, word ? 2 : 4, pcv_value(pkw, width),
                              fmt::format("{} ({})", pcv_value(pkw, width),
                                          word ? "word" : "double word"));
                }
            }
            pcd_at = 11;
        }
    }
    if (fc.has_pcd) {
        proto_item* item = tree.uint(
            request ? hf_pcd_ctw : hf_pcd_stw, pcd_at, 2, fc.pcd1,
            fmt::format("0x{:04X} (PCD 1 {}, FC profile)", fc.pcd1, pcd_word_name(t.direction, 0)));
        add_word_bits(tree, item, pcd_at, fc.pcd1, request,
                      request ? control_word_bits(PcdProfile::Fc, true)
                              : status_word_bits(PcdProfile::Fc, true));
        tree.uint(hf_pcd_ref, pcd_at + 2, 2, fc.pcd2,
                  fmt::format("0x{:04X} = {:.2f} % (PCD 2 {})", fc.pcd2, reference_percent(fc.pcd2),
                              pcd_word_name(t.direction, 1)));
    }
    if (fc.complete) {
        const std::size_t at = t.bytes.size() - 1;
        tree.uint(hf_fc_bcc, at, 1, fc.bcc,
                  fc.bcc_ok ? fmt::format("0x{:02X} (correct)", fc.bcc)
                            : fmt::format("0x{:02X} (wrong: computed 0x{:02X})", fc.bcc,
                                          fc.bcc_computed));
        tree.boolean(hf_fc_bcc_ok, at, 1, fc.bcc_ok);
    }
}

void add_vlt2000(const Tree& top, const DecodedTelegram& t) {
    const Vlt2000Telegram& v = t.vlt2000;
    const bool request = t.direction == Direction::Request;
    const std::size_t size = t.bytes.size();
    const auto has = [&](std::size_t at, std::size_t count) { return at + count <= size; };
    std::string title = "VLT 2000 telegram";
    if (t.has_roles) {
        title += fmt::format(": {} {}", vlt2000_letter_text(t), request ? "command" : "reply");
        if (v.broadcast && request)
            title += " to every drive (broadcast, address 00)";
        else
            title += fmt::format(" {} drive {:02}", request ? "to" : "from", v.address);
    }
    Tree tree = top.text(0, size, kEttVlt2000, title);
    if (size == 0) return;
    tree.uint(hf_vlt_start, 0, 1, t.bytes[0],
              t.bytes[0] == kVlt2000Start ? std::string("'<'")
                                          : fmt::format("0x{:02X} (not '<')", t.bytes[0]));
    if (t.bytes[0] != kVlt2000Start || !has(kVlt2000AddressAt, 2)) return;
    if (t.has_roles)
        tree.uint(hf_vlt_address, kVlt2000AddressAt, 2, v.address,
                  fmt::format("{:02}{}", v.address,
                              v.broadcast ? " (broadcast: every drive acts, none replies)" : ""));
    if (!has(kVlt2000LetterAt, 1)) return;
    // The letter as sent (jsonl's "letter"), its name in the text.
    if (vlt2000_has_letter(t)) {
        const std::string letter = chars_text(t.bytes.subspan(kVlt2000LetterAt, 1));
        tree.string(hf_vlt_letter, kVlt2000LetterAt, 1, letter,
                    fmt::format("{} ({})", letter, vlt2000_letter_name(v.letter)));
    }
    if (!has(kVlt2000WordAt, 4)) return;
    proto_item* word =
        tree.uint(hf_vlt_word, kVlt2000WordAt, 4, v.word,
                  fmt::format("0x{:04X} ({} word, {})", v.word, request ? "control" : "status",
                              request ? "to the drive" : "from the drive"));
    Tree bits = tree.sub(word, kEttWord);
    for (unsigned bit = 0; bit < 16; ++bit) {
        const std::size_t at = kVlt2000WordAt + 3 - bit / 4;
        if (vlt2000_bit_kept(v, bit)) {
            if (bit % 4 == 0)
                bits.text(at, 1, kEttWord, fmt::format("bits {}-{}: group kept (P)", bit, bit + 3));
            continue;
        }
        const bool set = (v.word >> bit) & 1u;
        bits.boolean(request ? hf_ctw_bit[bit] : hf_stw_bit[bit], at, 1, set,
                     fmt::format("{}: {}", set ? 1 : 0, vlt2000_bit_meaning(v, t.direction, bit)));
    }
    if (!has(kVlt2000ParameterAt, 4)) return;
    if (v.has_parameter)
        tree.uint(hf_vlt_parameter, kVlt2000ParameterAt, 4, v.parameter,
                  fmt::format("{}{}", v.parameter,
                              v.letter == Vlt2000Letter::Control ? " (ignored with C)" : ""));
    if (!has(kVlt2000SignAt, 1)) return;
    if (v.letter == Vlt2000Letter::ReadIndex && !v.index.empty()) {
        if (v.has_index_number) tree.uint(hf_vlt_index, kVlt2000SignAt, 6, v.index_number);
    } else if (v.has_value && vlt2000_carries_value(v)) {
        // The sign and the value only where the telegram carries one, as jsonl has them: a
        // failed reply's bytes hold no value, a C command's are ignored (shown as text).
        tree.boolean(hf_vlt_negative, kVlt2000SignAt, 1, v.negative);
        // A number, as jsonl's value: read back from the text the renderers write, so the two
        // cannot differ.
        const std::string text = vlt2000_value_text(v);
        double number = 0;
        std::from_chars(text.data(), text.data() + text.size(), number);
        const std::string note = vlt2000_value_note(v);
        tree.real(
            hf_vlt_value, kVlt2000ValueAt, 5, number,
            fmt::format("{:05} = {}{}", v.digits, text, note.empty() ? note : " (" + note + ")"));
    } else if (v.has_value && v.letter == Vlt2000Letter::Control) {
        tree.text(
            kVlt2000SignAt, 6, kEttVlt2000,
            fmt::format("Value: {:05} = {} (ignored with C)", v.digits, vlt2000_value_text(v)));
    }
    if (v.has_decimals) tree.boolean(hf_vlt_failed, kVlt2000DecimalsAt, 1, v.failed);
    if (v.failed && v.has_reason)
        tree.uint(hf_vlt_reason, kVlt2000ReasonAt, 2, v.reason,
                  fmt::format("{:02} = {}", v.reason, vlt2000_reason_or_unknown(v)));
    if (!has(kVlt2000DecimalsAt, 1)) return;
    if (v.has_decimals) tree.uint(hf_vlt_decimals, kVlt2000DecimalsAt, 1, v.decimals);
    if (!has(kVlt2000ChecksumAt, 2)) return;
    // The two characters as sent ("??": switched off), the verdict in the text; checksum_ok only
    // where the checksum was judged (two digits), as jsonl's "checksum_ok".
    TextBuffer checksum;
    append_vlt2000_checksum(checksum, t);
    tree.string(hf_vlt_checksum, kVlt2000ChecksumAt, 2,
                chars_text(t.bytes.subspan(kVlt2000ChecksumAt, 2)), buffer_text(checksum));
    if (v.has_checksum) tree.boolean(hf_vlt_checksum_ok, kVlt2000ChecksumAt, 2, v.checksum_ok);
    if (has(kVlt2000StopAt, 1)) {
        const std::uint8_t stop = t.bytes[kVlt2000StopAt];
        tree.uint(
            hf_vlt_stop, kVlt2000StopAt, 1, stop,
            stop == kVlt2000Stop ? std::string("'>'") : fmt::format("0x{:02X} (not '>')", stop));
    }
}

// The request/response link: a response names its request and the time since it; a request the
// response that answered it.
void add_link(const Tree& tree, const DecodedTelegram& t) {
    if (t.direction == Direction::Response && t.request_frame != 0) {
        tree.generated(
            tree.uint(hf_request_frame, 0, 0, static_cast<std::uint32_t>(t.request_frame)));
        const std::int64_t request_ns = capture->time_of(t.request_frame);
        if (request_ns != kNoTime && t.has_time()) {
            const std::int64_t ns = t.time_ns - request_ns;
            nstime_t delta;
            delta.secs = static_cast<time_t>(ns / 1'000'000'000);
            delta.nsecs = static_cast<int>(ns % 1'000'000'000);
            tree.generated(
                proto_tree_add_time(tree.get(), hf_response_time, nullptr, 0, 0, &delta));
        }
    } else if (t.direction == Direction::Request) {
        if (const std::uint64_t response = capture->response_frame(t.frame))
            tree.generated(
                tree.uint(hf_response_frame, 0, 0, static_cast<std::uint32_t>(response)));
    }
}

void add_problems_and_findings(const Tree& top, packet_info* pinfo, const DecodedTelegram& t,
                               std::span<const Finding> findings) {
    if (!t.problems().empty()) {
        Tree tree = top.text(0, 0, kEttProblems, "Problems");
        for (const Problem& p : t.problems()) {
            const std::string name(problem_kind_name(p.kind));
            const std::string message = problem_message(p);
            proto_item* item = tree.string(
                hf_problem, p.offset, 1, name,
                fmt::format("{} ({}): {}", name, severity_name(problem_severity(p.kind)), message));
            expert_add_info_format(pinfo, item, &ei_problem[static_cast<std::size_t>(p.kind)], "%s",
                                   message.c_str());
        }
    }
    if (findings.empty()) return;
    Tree tree = top.text(0, 0, kEttFindings, "Findings");
    for (const Finding& f : findings) {
        const std::string name(finding_kind_name(f.kind));
        proto_item* item =
            tree.string(hf_finding, 0, 0, name,
                        fmt::format("{} {}: {}", severity_name(f.severity), name, f.message));
        Tree sub = tree.sub(item, kEttFindings);
        sub.string(hf_finding_severity, 0, 0, std::string(severity_name(f.severity)));
        if (f.request_frame != 0)
            sub.uint(hf_finding_request, 0, 0, static_cast<std::uint32_t>(f.request_frame));
        expert_add_info_format(
            pinfo, item,
            &ei_finding[static_cast<std::size_t>(f.kind)][static_cast<std::size_t>(f.severity)],
            "%s", f.message.c_str());
    }
}

// Runs of spaces (the text format's column padding) shrink to one for the Info column.
std::string info_text(const DecodedTelegram& t, std::span<const Finding> findings) {
    TextBuffer b;
    append_telegram_columns(b, t, findings);
    std::string info;
    info.reserve(b.size());
    for (char c : std::string_view(b.data(), b.size())) {
        if (c == ' ' && (info.empty() || info.back() == ' ')) continue;
        info.push_back(c);
    }
    while (!info.empty() && info.back() == ' ')
        info.pop_back();
    return info;
}

std::string_view protocol_column(Protocol protocol) {
    switch (protocol) {
        case Protocol::Fc: return "FC";
        case Protocol::Vlt2000: return "VLT 2000";
        case Protocol::ProfibusDp: break;
    }
    return "PROFIBUS";
}

// Source and destination as the text line has them: station addresses, "M" for the FC and VLT 2000
// master, "all" for a broadcast.
void set_address_columns(packet_info* pinfo, const DecodedTelegram& t) {
    std::string source;
    std::string destination;
    if (t.protocol == Protocol::ProfibusDp) {
        if (t.dp.fdl.has_addresses) {
            source = fmt::format("{}", t.dp.fdl.sa);
            destination = fmt::format("{}", t.dp.fdl.da);
        } else if (t.has_roles) {
            source = fmt::format("{}", t.slave);
            destination = fmt::format("{}", t.master);
        }
    } else if (t.has_roles) {
        const bool broadcast = t.protocol == Protocol::Fc ? t.fc.broadcast : t.vlt2000.broadcast;
        const std::string drive =
            broadcast && t.direction == Direction::Request ? std::string("all")
            : t.protocol == Protocol::Fc                   ? fmt::format("{}", t.fc.address)
                                         : fmt::format("{:02}", t.vlt2000.address);
        source = t.direction == Direction::Request ? "M" : drive;
        destination = t.direction == Direction::Request ? drive : "M";
    }
    if (!source.empty()) {
        col_add_str(pinfo->cinfo, COL_DEF_SRC, source.c_str());
        col_add_str(pinfo->cinfo, COL_DEF_DST, destination.c_str());
    }
}

int dissect_dpscope(tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree, void*) {
    const guint length = tvb_captured_length(tvb);
    if (!capture)
        capture = std::make_unique<CaptureReplay>(choose_protocol(pinfo, tvb),
                                                  options_from_preferences());
    const std::uint64_t frame = pinfo->num;
    const std::int64_t time_ns =
        pinfo->fd->has_ts
            ? static_cast<std::int64_t>(pinfo->abs_ts.secs) * 1'000'000'000 + pinfo->abs_ts.nsecs
            : kNoTime;
    const Bytes bytes =
        length == 0 ? Bytes() : Bytes(tvb_get_ptr(tvb, 0, static_cast<gint>(length)), length);
    const DecodedTelegram& t = PINFO_FD_VISITED(pinfo) || capture->seen(frame)
                                   ? capture->decode_again(frame, bytes, time_ns)
                                   : capture->first_pass(frame, bytes, time_ns);
    const std::span<const Finding> findings = capture->findings(frame);

    col_set_str(pinfo->cinfo, COL_PROTOCOL, protocol_column(capture->protocol()).data());
    set_address_columns(pinfo, t);
    col_clear(pinfo->cinfo, COL_INFO);
    col_add_str(pinfo->cinfo, COL_INFO, info_text(t, findings).c_str());

    proto_item* top_item = proto_tree_add_item(tree, proto_dpscope, tvb, 0, -1, ENC_NA);
    proto_item_append_text(top_item, ": %s", protocol_column(capture->protocol()).data());
    Tree top(proto_item_add_subtree(top_item, ett[kEttTop]), tvb);
    top.string(hf_bus, 0, 0, std::string(protocol_name(capture->protocol())));
    top.string(hf_direction, 0, 0, std::string(direction_name(t.direction)));
    if (t.has_roles) {
        if (t.protocol == Protocol::ProfibusDp) top.uint(hf_master, 0, 0, t.master);
        top.uint(hf_slave, 0, 0, t.slave);
    }
    add_link(top, t);
    switch (t.protocol) {
        case Protocol::Fc: add_fc(top, t); break;
        case Protocol::Vlt2000: add_vlt2000(top, t); break;
        case Protocol::ProfibusDp:
            add_fdl(top, t);
            add_dp(top, t);
            break;
    }
    add_problems_and_findings(top, pinfo, t, findings);
    return static_cast<int>(length);
}

void register_dpscope() {
    proto_dpscope = proto_register_protocol("dpscope (PROFIBUS DP, FC protocol, VLT 2000)",
                                            "dpscope", "dpscope");
    static std::vector<hf_register_info> fields;
#define DPSCOPE_FIELD_INFO(id, name, abbrev, type, display, blurb) \
    fields.push_back({&hf_##id, {name, abbrev, type, display, NULL, 0, blurb, HFILL}});
    DPSCOPE_FIELDS(DPSCOPE_FIELD_INFO)
#undef DPSCOPE_FIELD_INFO
    for (int bit = 0; bit < 16; ++bit) {
        fields.push_back(
            {&hf_ctw_bit[bit],
             {keep(fmt::format("CTW bit {}", bit)), keep(fmt::format("dpscope.pcd.ctw.bit{}", bit)),
              FT_BOOLEAN, BASE_NONE, NULL, 0, "A control word bit (PCD 1, VLT 2000 word)", HFILL}});
        fields.push_back(
            {&hf_stw_bit[bit],
             {keep(fmt::format("STW bit {}", bit)), keep(fmt::format("dpscope.pcd.stw.bit{}", bit)),
              FT_BOOLEAN, BASE_NONE, NULL, 0, "A status word bit (PCD 1, VLT 2000 word)", HFILL}});
    }
    proto_register_field_array(proto_dpscope, fields.data(), static_cast<int>(fields.size()));

    static gint* subtrees[kEttCount];
    for (int i = 0; i < kEttCount; ++i) {
        ett[i] = -1;
        subtrees[i] = &ett[i];
    }
    proto_register_subtree_array(subtrees, kEttCount);

    static std::vector<ei_register_info> experts;
    for (const ProblemKindInfo& info : problem_catalogue()) {
        experts.push_back(
            {&ei_problem[static_cast<std::size_t>(info.kind)],
             {keep(fmt::format("dpscope.problem.{}", info.name)), problem_group(info.kind),
              expert_severity(info.severity), keep(std::string(info.check)), EXPFILL}});
    }
    for (const FindingKindInfo& info : finding_catalogue()) {
        // One expert info per severity, all three with the kind's plain name, so that
        // `dpscope.finding.KIND` selects every finding of the kind: a kind's severity can depend
        // on what the telegram says (dpv1_error_pdu: a warning or a note by its error class).
        // The kind's default severity is registered last: Wireshark's severity table
        // (expert_severity_levels) finds a name's last registration.
        const char* abbrev = keep(fmt::format("dpscope.finding.{}", info.name));
        std::vector<Severity> severities;
        for (Severity severity : {Severity::Note, Severity::Warning, Severity::Error})
            if (severity != info.severity) severities.push_back(severity);
        severities.push_back(info.severity);
        for (Severity severity : severities)
            experts.push_back({&ei_finding[static_cast<std::size_t>(info.kind)]
                                          [static_cast<std::size_t>(severity)],
                               {abbrev, finding_group(info.kind), expert_severity(severity),
                                keep(std::string(info.rule)), EXPFILL}});
    }
    expert_module_t* expert = expert_register_protocol(proto_dpscope);
    expert_register_field_array(expert, experts.data(), static_cast<int>(experts.size()));

    module_t* module = prefs_register_protocol(proto_dpscope, forget_capture);
    prefs_register_enum_preference(module, "bus", "Bus",
                                   "The bus the USER0 capture carries (dpscope --bus)", &prefs.bus,
                                   kBusValues, FALSE);
    prefs_register_enum_preference(module, "dialect", "Parameter-channel dialect",
                                   "Code tables of the PROFIBUS parameter channel (--dialect)",
                                   &prefs.dialect, kDialectValues, FALSE);
    prefs_register_uint_preference(module, "timeout_ms", "Time-out (ms, 1-3600000)",
                                   "A request unanswered for longer is a finding (--timeout-ms)",
                                   10, &prefs.timeout_ms);
    prefs_register_uint_preference(module, "fc_response_ms", "FC late response (ms, 1-60000)",
                                   "An FC drive answering later is a finding (--fc-response-ms)",
                                   10, &prefs.fc_response_ms);
    prefs_register_enum_preference(module, "fc_pnu_bits", "FC PNU bits",
                                   "PKE bits holding the PNU (--fc-pnu-bits)", &prefs.fc_pnu_bits,
                                   kPnuBitsValues, FALSE);
    prefs_register_uint_preference(module, "baud", "Line baud rate (300-12000000)",
                                   "FC and VLT 2000: the line's rate (--baud)", 10, &prefs.baud);
    prefs_register_bool_preference(module, "vlt2000_checksum", "Check the VLT 2000 checksum",
                                   "--vlt2000-checksum check (on) or ignore (off)",
                                   &prefs.vlt2000_checksum);
    prefs_register_bool_preference(module, "strict", "Strict",
                                   "RC 8 after a read request is an unexpected response (--strict)",
                                   &prefs.strict);

    dpscope_handle = register_dissector("dpscope", dissect_dpscope, proto_dpscope);
    register_init_routine(forget_capture);
    register_cleanup_routine(forget_capture);
}

// USER0 is Wireshark's "DLT_USER" protocol by default; dpscope's dissector takes it over (the
// plugins' handoffs run after the built-in ones). The user DLT table can still name "dpscope"
// for USER1..15.
void handoff_dpscope() { dissector_add_uint("wtap_encap", WTAP_ENCAP_USER0, dpscope_handle); }

}  // namespace
}  // namespace dpscope

void plugin_register(void) {
    static proto_plugin plugin;
    plugin.register_protoinfo = dpscope::register_dpscope;
    plugin.register_handoff = dpscope::handoff_dpscope;
    proto_register_plugin(&plugin);
}
