// The Wireshark dissector's registration table, private to the plugin: every field's id, the
// subtrees and the expert infos. The files that build the tree (dissector.cpp, profibus_tree.cpp,
// fc_tree.cpp, vlt2000_tree.cpp) add their items with these ids; register_fields()
// (dissector_fields.cpp) registers them all. The field names are listed in docs/wireshark.md
// ("Fields"), checked against the registered fields by
// tests/wireshark/field_table_test.sh.
#pragma once

#include <wireshark.h>
// wireshark.h first: it sets up what the epan headers need.
#include <epan/expert.h>
#include <epan/proto.h>

#include "core/finding.hpp"
#include "core/problem.hpp"

// Every field: X(id, name, abbrev (the display-filter name), type, display, blurb). Its id is
// hf_<id>, registered from this table.
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
    X(gsd_file, "GSD file", "dpscope.gsd.file", FT_STRING, BASE_NONE,                              \
      "The slave's GSD file (the gsd_folder preference), matched by ident")                        \
    X(gsd_device, "Device", "dpscope.gsd.device", FT_STRING, BASE_NONE,                            \
      "Vendor and model from the slave's GSD file")                                                \
    X(gsd_module, "GSD module", "dpscope.gsd.module", FT_STRING, BASE_NONE,                        \
      "The GSD module a run of Chk_Cfg/Get_Cfg identifiers stands for")                            \
    X(gsd_prm, "User parameter", "dpscope.gsd.prm", FT_STRING, BASE_NONE,                          \
      "A Set_Prm user parameter read by the GSD: name=value")                                      \
    X(gsd_diag, "Diagnosis text", "dpscope.gsd.diag", FT_STRING, BASE_NONE,                        \
      "A diagnosis text the GSD gives a bit, area or slot")                                        \
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

namespace dpscope::wireshark {

#define DPSCOPE_FIELD_ID(id, name, abbrev, type, display, blurb) extern int hf_##id;
DPSCOPE_FIELDS(DPSCOPE_FIELD_ID)
#undef DPSCOPE_FIELD_ID

// The bits of PCD 1: dpscope.pcd.ctw.bit0 .. bit15, dpscope.pcd.stw.bit0 .. bit15.
extern int hf_ctw_bit[16];
extern int hf_stw_bit[16];

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
    kEttGsd,
    kEttCount
};
extern int ett[kEttCount];

// Expert info: one per problem kind; one per finding kind and severity.
extern expert_field ei_problem[kProblemKindCount];
extern expert_field ei_finding[kFindingKindCount][3];

// Registers every field, subtree and expert info above with the protocol.
void register_fields(int protocol);

}  // namespace dpscope::wireshark
