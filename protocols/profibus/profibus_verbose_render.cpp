// The verbose tree (like tshark -V) of a PROFIBUS telegram: the FDL frame, then its DP service
// field by field (Data_Exchange with the PPO's PCV and PCD, diagnosis, parameters, configuration,
// DP-V1 and PROFIdrive parameter access).
#include <fmt/compile.h>

#include <algorithm>
#include <iterator>
#include <span>
#include <string>
#include <vector>

#include "formats/describe.hpp"
#include "formats/parameter_names.hpp"
#include "formats/protocol_rendering.hpp"
#include "formats/verbose_tree.hpp"
#include "protocols/profibus/dp_payload.hpp"

namespace dpscope {

namespace {

class ProfibusVerboseTree final : public VerboseTree {
  public:
    using VerboseTree::VerboseTree;

  private:
    static std::string_view sap_label(std::uint8_t value, bool slave_side) {
        std::string_view name = sap_name(value, slave_side);
        return name.empty() ? "no DP meaning" : name;
    }

  public:
    void render_fdl(const DecodedTelegram& t) {
        const FdlTelegram& f = t.dp.fdl;
        TextBuffer& b = buffer();
        auto it = fmt::appender(b);
        append(b, "PROFIBUS FDL\n");
        if (f.type == FrameType::Invalid) {
            field(1, FMT_COMPILE("Start delimiter: 0x{:02X} (not a start delimiter)"),
                  t.bytes.empty() ? 0 : t.bytes[0]);
            return;
        }
        put_line(1, "Start delimiter: ", frame_type_name(f.type), " (0x", hex(t.bytes[0], 2), ')');
        if (f.type == FrameType::Sd2) {
            field(1, FMT_COMPILE("Length: LE {}, LEr {}"), f.length_field,
                  f.has_length_repeat ? fmt::format(FMT_COMPILE("{}"), f.length_repeat)
                                      : std::string("missing"));
        }
        if (f.has_addresses) {
            line(1, "");
            put(b, "Destination address: ", f.da, f.da == kBroadcastAddress ? " (broadcast)" : "");
            // The slave's SAP is the DSAP of a request and the SSAP of a response.
            bool request = f.has_fc && f.fc.is_request();
            if (f.has_dsap) put(b, ", DSAP ", f.dsap, " (", sap_label(f.dsap, request), ')');
            if (f.has_dest_segment) fmt::format_to(it, FMT_COMPILE(", segment {}"), f.dest_segment);
            b.push_back('\n');
            line(1, "");
            put(b, "Source address: ", f.sa);
            if (f.has_ssap) put(b, ", SSAP ", f.ssap, " (", sap_label(f.ssap, !request), ')');
            if (f.has_source_segment)
                fmt::format_to(it, FMT_COMPILE(", segment {}"), f.source_segment);
            b.push_back('\n');
        }
        if (f.has_fc) {
            line(1, "");
            put(b, "Frame control: 0x", hex(f.fc.raw, 2), " (");
            append_frame_control(b, f.fc);
            append(b, ")\n");
        }
        if (!f.du.empty()) {
            line(1, "Data unit: ");
            append_counted(b, f.du.size(), "byte", "bytes");
            put(b, " from byte ", f.du_offset, '\n');
        }
        if (f.has_fcs) put_line(1, "FCS: 0x", hex(f.fcs, 2), f.fcs_ok ? " (correct)" : " (wrong)");
        if (f.type == FrameType::Sd1 || f.type == FrameType::Sd2 || f.type == FrameType::Sd3) {
            if (t.bytes.size() >= f.size && f.size > 0)
                put_line(1, "End delimiter: 0x", hex(t.bytes[f.size - 1], 2));
        }
    }

    void render_dp(const DecodedTelegram& t) {
        if (t.dp.fdl.type == FrameType::Invalid) return;
        TextBuffer& b = buffer();
        put(b, "PROFIBUS DP: ", service_name(t.dp.service), ' ', direction_name(t.direction));
        if (t.has_roles && t.dp.service != Service::Token)
            put(b, ", master ", t.master, " / slave ", t.slave);
        if (t.request_frame != 0) put(b, ", answers frame ", t.request_frame);
        b.push_back('\n');
        const DpServiceData& data = t.dp.service_data;
        switch (t.dp.service) {
            case Service::DataExchange: render_data_exchange(t); break;
            case Service::SlaveDiag:
                if (const SlaveDiag* diag = data.slave_diag())
                    render_diag(*diag, data.diag_blocks(), t.dp.slave_dpv1);
                break;
            case Service::SetPrm:
                if (const SetPrm* prm = data.set_prm()) render_prm(*prm);
                break;
            case Service::ChkCfg:
            case Service::GetCfg:
                if (const std::vector<CfgModule>* modules = data.cfg_modules();
                    modules && !t.dp.fdl.du.empty())
                    render_cfg(t, *modules);
                break;
            case Service::GlobalControl:
                if (const GlobalControl* gc = data.global_control()) {
                    flags_field(1, "Control command", gc->command, global_control_flags());
                    field(1, FMT_COMPILE("Group select: 0x{:02X}{}"), gc->group_select,
                          gc->group_select == 0 ? " (all slaves)" : "");
                }
                break;
            case Service::SetSlaveAdd:
                if (const SetSlaveAdd* ssa = data.set_slave_add()) {
                    field(1, FMT_COMPILE("New slave address: {}"), ssa->new_address);
                    field(1, FMT_COMPILE("Ident number: 0x{:04X}"), ssa->ident);
                    field(1, FMT_COMPILE("No_Add_Chg: {}"), ssa->no_add_chg);
                    if (!ssa->rem_slave_data.empty()) {
                        line(1, "Rem_Slave_Data: ");
                        append_hex(b, ssa->rem_slave_data);
                        b.push_back('\n');
                    }
                }
                break;
            case Service::MsacC1:
            case Service::MsacC2:
                if (const Dpv1Pdu* pdu = data.dpv1()) {
                    render_dpv1(t, *pdu);
                    break;
                }
                [[fallthrough]];
            default:
                if (!t.dp.fdl.du.empty()) {
                    line(1, "Data: ");
                    append_hex(b, t.dp.fdl.du);
                    b.push_back('\n');
                }
                break;
        }
        render_gsd(t);
    }

    // What the slave's GSD file says about a management telegram's data (issue 29).
    void render_gsd(const DecodedTelegram& t) {
        const GsdDevice* device = t.dp.device;
        const DpServiceData& data = t.dp.service_data;
        const GsdPrmReading* prm = data.gsd_prm();
        if (!device ||
            (data.gsd_modules().empty() && !prm && data.gsd_diag().empty() && !data.slave_diag()))
            return;
        field(1, FMT_COMPILE("GSD: {} ({}{})"), device->file, gsd_device_title(*device),
              device->ident_number
                  ? fmt::format(FMT_COMPILE(", ident 0x{:04X}"), *device->ident_number)
                  : std::string());
        for (const GsdModuleMatch& m : data.gsd_modules()) {
            line(2, m.module ? fmt::format(FMT_COMPILE("module \"{}\""), m.module->name)
                             : std::string("no module of the GSD"));
            auto it = fmt::appender(buffer());
            if (m.identifiers > 1)
                fmt::format_to(it, FMT_COMPILE(": slots {}-{} ("), m.first_identifier,
                               m.first_identifier + m.identifiers - 1);
            else
                fmt::format_to(it, FMT_COMPILE(": slot {} ("), m.first_identifier);
            append_hex(buffer(), t.bytes.subspan(m.offset, m.length));
            append(buffer(), ")\n");
        }
        if (prm) {
            for (const GsdPrmValue& v : prm->values) {
                line(2, "");
                fmt::format_to(
                    fmt::appender(buffer()), FMT_COMPILE("user parameter \"{}\" (byte {}{}): "),
                    v.prm->name, v.offset,
                    v.module ? fmt::format(FMT_COMPILE(", module \"{}\""), v.module->name)
                             : std::string());
                if (v.text)
                    fmt::format_to(fmt::appender(buffer()), FMT_COMPILE("{} ({})"), v.value,
                                   v.text->text);
                else
                    fmt::format_to(fmt::appender(buffer()), FMT_COMPILE("{}"), v.value);
                if (!v.in_range) append(buffer(), " (not allowed)");
                buffer().push_back('\n');
            }
            const bool module_prms =
                std::any_of(device->modules.begin(), device->modules.end(),
                            [](const GsdModule& m) { return !m.prm_refs.empty(); });
            if (!prm->modules_known && module_prms)
                field(2, FMT_COMPILE(
                             "module parameters not read: no configuration of the slave seen yet"));
        }
        for (const GsdDiagText& d : data.gsd_diag()) {
            line(2, "diagnosis ");
            append_gsd_diag_text(buffer(), d);
            auto it = fmt::appender(buffer());
            switch (d.source) {
                case GsdDiagText::Source::Bit:
                    fmt::format_to(it, FMT_COMPILE(" (bit {}"), d.bit);
                    break;
                case GsdDiagText::Source::Area:
                    fmt::format_to(it, FMT_COMPILE(" (bits from {} = {}"), d.bit, d.value);
                    break;
                case GsdDiagText::Source::Slot: fmt::format_to(it, FMT_COMPILE(" (")); break;
            }
            fmt::format_to(it, FMT_COMPILE("{}byte {})\n"),
                           d.source == GsdDiagText::Source::Slot ? "" : ", ", d.offset);
        }
    }

    void render_dpv1(const DecodedTelegram& t, const Dpv1Pdu& pdu) {
        TextBuffer& b = buffer();
        if (pdu.layout == Dpv1Pdu::Layout::None) {
            field(1, FMT_COMPILE("DP-V1 PDU: none (empty data unit: a link-level poll)"));
            return;
        }
        std::string_view name = dpv1_function_name(pdu.function);
        field(1, FMT_COMPILE("DP-V1 function: 0x{:02X} ({}){}"), pdu.function,
              name.empty() ? "not defined by DP-V1" : name,
              pdu.negative() ? ", negative response" : "");
        if (!pdu.complete) field(2, FMT_COMPILE("PDU cut short: the fields below are those read"));
        switch (pdu.layout) {
            case Dpv1Pdu::Layout::Error: {
                std::string_view decode = dpv1_error_decode_name(pdu.error_decode);
                field(2, FMT_COMPILE("Error_Decode: 0x{:02X} ({})"), pdu.error_decode,
                      decode.empty() ? "unknown" : decode);
                std::string_view error_class = dpv1_error_class_name(pdu.error_code_1);
                field(2, FMT_COMPILE("Error_Code_1: 0x{:02X}"), pdu.error_code_1);
                field(3, FMT_COMPILE("Error class: {} ({})"), pdu.error_code_1 >> 4,
                      error_class.empty() ? "reserved" : error_class);
                field(3, FMT_COMPILE("Error code: {} ({})"), pdu.error_code_1 & 0x0F,
                      dpv1_error_code_name(pdu.error_code_1));
                field(2, FMT_COMPILE("Error_Code_2: 0x{:02X}"), pdu.error_code_2);
                break;
            }
            case Dpv1Pdu::Layout::Addressed:
                field(2, FMT_COMPILE("Slot: {}"), pdu.slot);
                if (pdu.base_function() == dpv1_function::kAlarmAck) {
                    field(2, FMT_COMPILE("Alarm type: {}"), pdu.index);
                    field(2, FMT_COMPILE("Specifier: 0x{:02X}"), pdu.length);
                } else {
                    field(2, FMT_COMPILE("Index: {}{}"), pdu.index,
                          pdu.index == kProfidriveIndex ? " (PROFIdrive parameter channel)" : "");
                    field(2, FMT_COMPILE("Length: {}"), pdu.length);
                }
                if (!pdu.data.empty()) {
                    line(2, "");
                    fmt::format_to(fmt::appender(b), FMT_COMPILE("Data ({} from byte {}): "),
                                   counted(pdu.data.size(), "byte", "bytes"), pdu.data_offset);
                    append_hex(b, pdu.data);
                    b.push_back('\n');
                }
                break;
            case Dpv1Pdu::Layout::Initiate: {
                const Dpv1Initiate& i = pdu.initiate;
                if (t.direction == Direction::Request)
                    field(2, FMT_COMPILE("Send_Timeout: {} ({} ms)"), i.send_timeout,
                          i.send_timeout * 10);
                else
                    field(2, FMT_COMPILE("Max_Len_Data_Unit: {}"), i.max_len_data_unit);
                field(2, FMT_COMPILE("Features_Supported: 0x{:04X}"), i.features_supported);
                field(2, FMT_COMPILE("Profile_Features_Supported: 0x{:04X}"),
                      i.profile_features_supported);
                field(2, FMT_COMPILE("Profile_Ident_Number: 0x{:04X}"), i.profile_ident_number);
                if (i.has_addresses) {
                    field(2, FMT_COMPILE("S_Type: {}, S_Len: {}"), i.s_type, i.s_len);
                    line(2, "S_Addr: ");
                    append_hex(b, i.s_addr);
                    b.push_back('\n');
                    field(2, FMT_COMPILE("D_Type: {}, D_Len: {}"), i.d_type, i.d_len);
                    line(2, "D_Addr: ");
                    append_hex(b, i.d_addr);
                    b.push_back('\n');
                }
                break;
            }
            case Dpv1Pdu::Layout::Abort:
                field(2, FMT_COMPILE("Subnet: {}"), pdu.abort.subnet);
                field(2, FMT_COMPILE("Instance_Reason_Code: 0x{:02X}"), pdu.abort.instance_reason);
                field(3, FMT_COMPILE("Instance: {} ({})"), pdu.abort.instance(),
                      dpv1_abort_instance_name(pdu.abort.instance_reason));
                field(3, FMT_COMPILE("Reason code: {} ({})"), pdu.abort.reason(),
                      dpv1_abort_reason_name(pdu.abort.instance_reason));
                break;
            case Dpv1Pdu::Layout::Unknown:
                if (!pdu.data.empty()) {
                    line(2, "Data: ");
                    append_hex(b, pdu.data);
                    b.push_back('\n');
                }
                break;
            case Dpv1Pdu::Layout::Idle:
            case Dpv1Pdu::Layout::None: break;
        }
        if (const ProfidriveMessage* m = t.dp.service_data.profidrive())
            render_profidrive(*m, t.dp.dialect, &t);
    }

    // With `t`, each parameter's name and a value in its unit (issue 29).
    void render_profidrive(const ProfidriveMessage& m, Dialect dialect,
                           const DecodedTelegram* t = nullptr) {
        field(1, FMT_COMPILE("PROFIdrive parameter {}"), m.is_response ? "response" : "request");
        if (!m.has_header) {
            field(2, FMT_COMPILE("header cut short"));
            return;
        }
        field(2, FMT_COMPILE("Request reference: {}"), m.reference);
        std::string_view id_name =
            m.is_response ? profidrive_response_id_name(m.id) : profidrive_request_id_name(m.id);
        field(2, FMT_COMPILE("{} ID: 0x{:02X} ({})"), m.is_response ? "Response" : "Request", m.id,
              id_name.empty() ? "not defined" : id_name);
        field(2, FMT_COMPILE("Axis: {}"), m.axis);
        field(2, FMT_COMPILE("Number of parameters: {}"), m.count);
        if (m.is_response) {
            if (m.has_request)
                field(2, FMT_COMPILE("Answers the request in frame {} (ref {}, ID 0x{:02X})"),
                      m.request_frame, m.request_reference, m.request_id);
            else
                field(2, FMT_COMPILE("Request not in the capture: parameter numbers unknown"));
        }
        std::size_t parameters = std::max(m.addresses.size(), m.blocks.size());
        for (std::size_t k = 0; k < parameters; ++k) {
            field(2, FMT_COMPILE("Parameter {}"), k + 1);
            if (k < m.addresses.size()) {
                const ProfidriveAddress& a = m.addresses[k];
                std::string_view attribute = profidrive_attribute_name(a.attribute);
                field(3, FMT_COMPILE("Attribute: 0x{:02X} ({})"), a.attribute,
                      attribute.empty() ? "not defined" : attribute);
                field(3, FMT_COMPILE("Number of elements: {}"), a.elements);
                field(3, FMT_COMPILE("Parameter number: {}"), a.pnu);
                if (t) {
                    const NamedParameter named = profidrive_parameter(*t, m, k);
                    if (named.row) {
                        TextBuffer details;
                        append_parameter_details(details, named);
                        field(4, FMT_COMPILE("name: {}"),
                              std::string_view(details.data(), details.size()));
                    }
                }
                field(3, FMT_COMPILE("Subindex: {}"), a.subindex);
            }
            if (k >= m.blocks.size()) continue;
            const ProfidriveValueBlock& block = m.blocks[k];
            field(3, FMT_COMPILE("Format: 0x{:02X} ({})"), block.format,
                  profidrive_format_name(block.format));
            field(3, FMT_COMPILE("Number of values: {}"), block.count);
            if (block.is_error()) {
                if (block.values.size() >= 2)
                    field(3, FMT_COMPILE("Error number: 0x{:02X} ({})"), block.error_number(),
                          profidrive_error_text(block.error_number(), dialect));
                if (block.has_error_info())
                    field(3, FMT_COMPILE("Additional information: {}"), block.error_info());
            } else if (block.format != profidrive::kFormatZero) {
                std::string values;
                append_profidrive_values(block, values);
                field(3, FMT_COMPILE("Values: {}"), values);
                if (t) {
                    if (const std::optional<ScaledValue> value =
                            profidrive_value_in_unit(*t, m, k)) {
                        TextBuffer text;
                        append_value_details(text, *profidrive_parameter(*t, m, k).row, *value);
                        field(4, FMT_COMPILE("in its unit: {}"),
                              std::string_view(text.data(), text.size()));
                    }
                }
            }
            if (!block.complete) field(3, FMT_COMPILE("(block cut short)"));
            if (block.padded) field(3, FMT_COMPILE("Pad byte"));
        }
        if (m.trailing > 0)
            field(2, FMT_COMPILE("{} after the message"), counted(m.trailing, "byte", "bytes"));
    }

    void render_data_exchange(const DecodedTelegram& t) {
        TextBuffer& b = buffer();
        line(1, "PPO: ");
        append_ppo_long(b, t.dp.ppo);
        b.push_back('\n');
        put_line(
            1, "Dialect: ",
            t.dp.ppo.has_pcv ? dialect_name(t.dp.dialect) : "none (no parameter channel)",
            "; control/status word profile: ", pcd_profile_name(t.dp.pcd_profile),
            t.dp.pcd_profile == PcdProfile::Profidrive && t.dp.danfoss_pcd() ? " (Danfoss)" : "");
        bool request = t.direction == Direction::Request;
        if (t.dp.has_pcv) {
            const Pcv& pcv = t.dp.pcv;
            put_line(1, "PCV (parameter channel), bytes ", t.dp.fdl.du_offset, '-',
                     t.dp.fdl.du_offset + kPcvBytes - 1);
            put_line(2, "PCA: 0x", hex(pcv.pca, 4));
            bool defined =
                request ? request_code(t.dp.dialect, pcv.rc).defined
                        : response_code(t.dp.dialect, pcv.rc).kind != ResponseKind::Undefined;
            put_line(3, "RC: ", pcv.rc, " = ", t.dp.pcv_meaning(t.direction),
                     defined ? "" : " (not defined by the dialect)");
            put_line(3, "SPM: ", pcv.spm ? '1' : '0');
            put_line(3, "PNU: ", pcv.pnu);
            const TelegramParameterView view = parameter_view(t);
            if (view.named.row) {
                TextBuffer details;
                append_parameter_details(details, view.named);
                field(4, FMT_COMPILE("name: {}"), std::string_view(details.data(), details.size()));
            }
            put_line(2, "IND: ", pcv.ind, " (byte 4: 0x", hex(pcv.ind_low, 2), ')');
            ValueWidth width = request ? request_code(t.dp.dialect, pcv.rc).width
                                       : response_code(t.dp.dialect, pcv.rc).width;
            bool rejected =
                !request && response_code(t.dp.dialect, pcv.rc).kind == ResponseKind::Rejected;
            if (rejected) {
                auto error = static_cast<std::uint16_t>(pcv.pva & 0xFFFF);
                field(2, FMT_COMPILE("PVA: 0x{:08X}"), pcv.pva);
                field(2, FMT_COMPILE("Error number: {} = {}"), error,
                      error_text_or_unknown(t.dp.dialect, error));
            } else if (width == ValueWidth::Word) {
                put_line(2, "PVA: 0x", hex(pcv.pva, 8), ", word value ", pcv_value(pcv, width));
            } else if (width == ValueWidth::DoubleWord) {
                put_line(2, "PVA: 0x", hex(pcv.pva, 8), ", double word value ", pcv.pva);
            } else {
                put_line(2, "PVA: 0x", hex(pcv.pva, 8), " (the code carries no value)");
            }
            if (view.value && view.parameter.has_raw) {
                TextBuffer value;
                append_value_details(value, *view.named.row, *view.value);
                field(3, FMT_COMPILE("in its unit: {}"),
                      std::string_view(value.data(), value.size()));
            }
        }
        ByteReader reader(t.dp.pcd, t.dp.pcd_offset);
        if (reader.empty()) return;
        put_line(1, "PCD (", reader.remaining() / 2, " words)");
        const WordBits& bits = request ? control_word_bits(t.dp.pcd_profile, t.dp.danfoss_pcd())
                                       : status_word_bits(t.dp.pcd_profile, t.dp.danfoss_pcd());
        for (std::size_t index = 0;; ++index) {
            auto word = reader.u16_be();
            if (!word) break;
            std::string_view name = pcd_word_name(t.direction, index);
            if (index == 0) {
                put_line(2, "PCD 1 ", name, ": 0x", hex(*word, 4));
                word_bit_fields(3, *word, bits);
            } else if (index == 1) {
                // "{:.2f}" of reference_percent(), from whole hundredths (no double formatted).
                line(2, "");
                put(b, "PCD 2 ", name, ": 0x", hex(*word, 4), " = ");
                append_hundredths(b, reference_percent_hundredths(*word));
                append(b, " %\n");
            } else {
                put_line(2, "PCD ", index + 1, ": 0x", hex(*word, 4), " (", *word, ')');
            }
        }
        if (!reader.empty()) field(2, FMT_COMPILE("odd trailing byte: 0x{:02X}"), *reader.u8());
    }

    void render_diag(const SlaveDiag& diag, std::span<const DiagBlock> blocks, SlaveDpv1 dpv1) {
        flags_field(1, "Station status 1", diag.station_status_1, station_status_1_flags());
        flags_field(1, "Station status 2", diag.station_status_2, station_status_2_flags());
        flags_field(1, "Station status 3", diag.station_status_3, station_status_3_flags());
        if (diag.master_address == kNoMasterAddress)
            field(1, FMT_COMPILE("Master address: 255 (not parameterised)"));
        else
            field(1, FMT_COMPILE("Master address: {}"), diag.master_address);
        field(1, FMT_COMPILE("Ident number: 0x{:04X}"), diag.ident);
        if (diag.extended.empty()) return;
        field(1, FMT_COMPILE("Extended diagnosis: {}"),
              counted(diag.extended.size(), "byte", "bytes"));
        for (const DiagBlock& block : blocks) {
            TextBuffer& b = buffer();
            switch (block.type) {
                case DiagBlockType::Channel:
                    field(2,
                          FMT_COMPILE(
                              "channel-related: module {}, channel {}, {}, {}: error {} ({})"),
                          block.module, block.channel, channel_io_text(block.io),
                          channel_type_text(block.channel_type), block.error_type,
                          channel_error_text(block.error_type));
                    break;
                case DiagBlockType::Revision:
                    field(2, FMT_COMPILE("revision number {}"), block.revision);
                    break;
                case DiagBlockType::Identifier: {
                    line(2, "identifier-related: modules with diagnosis:");
                    bool any = false;
                    for (std::size_t i = 0; i < block.data.size(); ++i)
                        for (int bit = 0; bit < 8; ++bit)
                            if ((block.data[i] >> bit) & 1) {
                                fmt::format_to(fmt::appender(b), FMT_COMPILE(" {}"), i * 8 + bit);
                                any = true;
                            }
                    if (!any) append(b, " none");
                    b.push_back('\n');
                    break;
                }
                case DiagBlockType::Device:
                    line(2, "device-related: ");
                    append_hex(b, block.data);
                    render_device_block(block, dpv1);
                    b.push_back('\n');
                    break;
            }
        }
    }

    // A device-related block is a DP-V1 alarm or status (type, slot, specifier) only when the
    // slave's Set_Prm enabled DP-V1; otherwise its bytes are manufacturer-specific.
    void render_device_block(const DiagBlock& block, SlaveDpv1 dpv1) {
        auto it = fmt::appender(buffer());
        bool fits = block.data.size() >= 3;
        switch (dpv1) {
            case SlaveDpv1::Disabled:
                append(buffer(), " (manufacturer-specific: Set_Prm did not enable DP-V1)");
                return;
            case SlaveDpv1::Enabled:
                if (fits)
                    fmt::format_to(it, FMT_COMPILE(" (DP-V1: {}, slot {})"),
                                   dpv1_alarm_or_status_text(block.data[0]), block.data[1]);
                else
                    fmt::format_to(
                        it, FMT_COMPILE(" (DP-V1, but {}: too short for an alarm or status)"),
                        counted(block.data.size(), "byte", "bytes"));
                return;
            case SlaveDpv1::Unknown:
                append(buffer(), " (DP-V1 or manufacturer-specific: no Set_Prm seen");
                if (fits)
                    fmt::format_to(it, FMT_COMPILE("; as DP-V1: {}, slot {}"),
                                   dpv1_alarm_or_status_text(block.data[0]), block.data[1]);
                buffer().push_back(')');
                return;
        }
    }

    void render_prm(const SetPrm& prm) {
        flags_field(1, "Station status", prm.station_status, set_prm_station_flags());
        std::string watchdog = " (off)";
        if (prm.watchdog_on() && prm.watchdog_base_uncertain())
            watchdog = fmt::format(
                FMT_COMPILE(
                    " = {} ms with WD_Base_1ms, or {} ms if the bytes read as DPV1_Status are "
                    "User_Prm_Data (10 ms base)"),
                prm.watchdog_ms(), prm.watchdog_ms_10ms_base());
        else if (prm.watchdog_on())
            watchdog = fmt::format(FMT_COMPILE(" = {} ms"), prm.watchdog_ms());
        field(1, FMT_COMPILE("Watchdog: factors {} x {}{}"), prm.wd_fact_1, prm.wd_fact_2,
              watchdog);
        field(1, FMT_COMPILE("min TSDR: {} bit times"), prm.min_tsdr);
        field(1, FMT_COMPILE("Ident number: 0x{:04X}"), prm.ident);
        field(1, FMT_COMPILE("Group ident: 0x{:02X}"), prm.group_ident);
        if (prm.has_dpv1_status) {
            flags_field(1, "DPV1_Status_1", prm.dpv1_status[0], dpv1_status_1_flags());
            flags_field(1, "DPV1_Status_2", prm.dpv1_status[1], dpv1_status_2_flags());
            line(1, "");
            fmt::format_to(fmt::appender(buffer()),
                           FMT_COMPILE("DPV1_Status_3: 0x{:02X} (Alarm_Mode {} = {}"),
                           prm.dpv1_status[2], prm.dpv1_status[2] & 0x07,
                           dpv1_alarm_mode_text(prm.dpv1_status[2]));
            TextBuffer flags;
            if (append_flags(flags, prm.dpv1_status[2], dpv1_status_3_flags(), "")) {
                append(buffer(), "; ");
                buffer().append(flags.data(), flags.data() + flags.size());
            }
            append(buffer(), ")\n");
        }
        if (!prm.user_prm.empty()) {
            line(1, "User_Prm_Data: ");
            append_hex(buffer(), prm.user_prm);
            buffer().push_back('\n');
        }
    }

    void render_cfg(const DecodedTelegram& t, std::span<const CfgModule> modules) {
        line(1, "Identifier bytes: ");
        append_hex(buffer(), t.dp.fdl.du);
        buffer().push_back('\n');
        std::size_t number = 1;
        for (const CfgModule& m : modules) {
            if (m.free_place) {
                field(2, FMT_COMPILE("module {}: 0x00 free place"), number++);
                continue;
            }
            std::string lengths;
            if (m.output_units)
                lengths +=
                    fmt::format(FMT_COMPILE(" out {}{}"), cfg_units(m.output_units, m.output_words),
                                m.output_consistent ? " consistent" : "");
            if (m.input_units)
                lengths +=
                    fmt::format(FMT_COMPILE(" in {}{}"), cfg_units(m.input_units, m.input_words),
                                m.input_consistent ? " consistent" : "");
            field(2, FMT_COMPILE("module {}: 0x{:02X} {}{}{}{}"), number++, m.identifier,
                  m.special ? "special format," : "", cfg_direction_name(m.direction), lengths,
                  m.manufacturer_bytes
                      ? fmt::format(FMT_COMPILE(", {}"),
                                    counted(m.manufacturer_bytes, "manufacturer byte",
                                            "manufacturer bytes"))
                      : std::string());
        }
        line(1, "Layout: ");
        append_ppo_long(buffer(),
                        ppo_from_cfg(modules, t.dp.service == Service::ChkCfg ? PpoSource::ChkCfg
                                                                              : PpoSource::GetCfg));
        buffer().push_back('\n');
    }
};

}  // namespace

void profibus_verbose(TextBuffer& b, const DecodedTelegram& t) {
    ProfibusVerboseTree tree(b);
    tree.render_fdl(t);
    tree.render_dp(t);
}

}  // namespace dpscope
