// The whole field tree of each telegram, like tshark -V; an FC protocol telegram field by field
// (STX, LGE, ADR, PKE, IND, PWE or text, PCD 1 bits, PCD 2, BCC); a VLT 2000 telegram field by
// field with the byte numbers of each as the manual counts them, from 1 ([5-8] the control or
// status word, all 16 bits).
#include <algorithm>
#include <iterator>
#include <span>
#include <string>
#include <vector>

#include "formats/describe.hpp"
#include "formats/renderer.hpp"
#include "protocols/fc/fc_describe.hpp"
#include "protocols/profibus/dp_payload.hpp"
#include "protocols/vlt2000/vlt2000_describe.hpp"

namespace dpscope {

namespace {

class VerboseRenderer final : public TelegramRenderer {
  public:
    using TelegramRenderer::TelegramRenderer;

    void render(const DecodedTelegram& t, std::span<const Finding> findings) override {
        TextBuffer& b = out_.buffer();
        auto it = std::back_inserter(b);
        fmt::format_to(it, "Frame {}: {}", t.frame, counted(t.bytes.size(), "byte", "bytes"));
        if (t.has_time()) {
            append(b, ", ");
            append_iso_time(b, t.time_ns);
        }
        b.push_back('\n');
        line(1, "Bytes: ");
        append_hex(b, t.bytes);
        b.push_back('\n');
        if (t.protocol == Protocol::Fc) {
            render_fc(t);
        } else if (t.protocol == Protocol::Vlt2000) {
            render_vlt2000(t);
        } else {
            render_fdl(t);
            render_dp(t);
        }
        if (!t.problems().empty()) {
            append(b, "Problems\n");
            for (const Problem& p : t.problems()) {
                line(1, "");
                fmt::format_to(it, "{} ({}): {}\n", problem_kind_name(p.kind),
                               severity_name(problem_severity(p.kind)), problem_message(p));
            }
        }
        if (!findings.empty()) {
            append(b, "Findings\n");
            for (const Finding& f : findings) {
                line(1, "");
                fmt::format_to(it, "{} {}: {}\n", severity_name(f.severity),
                               finding_kind_name(f.kind), f.message);
            }
        }
        b.push_back('\n');
        out_.end_record();
    }

    void render_end_findings(std::span<const Finding> findings) override {
        if (findings.empty()) return;
        append(out_.buffer(), "End of capture\nFindings\n");
        for (const Finding& f : findings)
            field(1, "{} {}: {}", severity_name(f.severity), finding_kind_name(f.kind), f.message);
        out_.buffer().push_back('\n');
        out_.end_record();
    }

  private:
    void line(int level, std::string_view text) {
        TextBuffer& b = out_.buffer();
        for (int i = 0; i < level; ++i)
            append(b, "    ");
        append(b, text);
    }

    template <typename... Args>
    void field(int level, fmt::format_string<Args...> format, Args&&... args) {
        line(level, "");
        fmt::format_to(std::back_inserter(out_.buffer()), format, std::forward<Args>(args)...);
        out_.buffer().push_back('\n');
    }

    void flags_field(int level, std::string_view name, std::uint8_t value,
                     std::span<const FlagBit> flags, std::uint8_t ignore = 0) {
        line(level, "");
        fmt::format_to(std::back_inserter(out_.buffer()), "{}: 0x{:02X} (", name, value);
        append_flags(out_.buffer(), value, flags, "none", ignore);
        append(out_.buffer(), ")\n");
    }

    // The FC protocol telegram field by field, from what FcDecoder stored.
    void render_fc(const DecodedTelegram& t) {
        const FcTelegram& fc = t.fc;
        TextBuffer& b = out_.buffer();
        auto it = std::back_inserter(b);
        const bool request = t.direction == Direction::Request;
        append(b, "FC protocol");
        if (t.has_roles) {
            fmt::format_to(it, ": {} block {}", fc_block_name(fc.block),
                           request ? "request" : "response");
            if (fc.broadcast)
                append(b, " to every drive (broadcast)");
            else
                fmt::format_to(it, " {} drive {}", request ? "to" : "from", fc.address);
            if (t.request_frame != 0) fmt::format_to(it, ", answers frame {}", t.request_frame);
        }
        b.push_back('\n');
        if (t.bytes.empty()) return;
        if (t.bytes[0] != kFcStx) {
            field(1, "STX: 0x{:02X} (not STX 0x02)", t.bytes[0]);
            return;
        }
        field(1, "STX: 0x02");
        if (t.bytes.size() < 2) return;
        if (fc.block == FcBlock::Unknown)
            field(1, "LGE: {} (no block has this length; telegram {} bytes)", fc.lge, fc.lge + 2);
        else
            field(1, "LGE: {} ({} block, telegram {} bytes)", fc.lge, fc_block_name(fc.block),
                  fc.lge + 2);
        if (!t.has_roles) return;
        line(1, "");
        fmt::format_to(it, "ADR: 0x{:02X} ({} format, ", fc.adr,
                       fc_address_format_name(fc.address_format));
        if (fc.broadcast)
            append(b, "broadcast)\n");
        else
            fmt::format_to(it, "address {})\n", fc.address);
        if (fc.has_pkw) {
            const Pcv& pkw = fc.pkw;
            field(1, "PKE: 0x{:04X}", pkw.pca);
            field(2, "AK: {} = {}{}", pkw.rc, fc_ak_meaning(t),
                  fc_ak_defined(t)
                      ? ""
                      : (request ? " (not a defined command)" : " (not a defined response)"));
            field(2, "PNU: {} (parameter {})", pkw.pnu, fc_parameter_name(pkw.pnu));
            field(1, "IND: 0x{:02X}{:02X}", fc.ind_high, pkw.ind_low);
            std::string_view mode = fc_text_mode_name(fc.ind_high);
            if (fc.block == FcBlock::Text && !mode.empty())
                field(2, "high byte: 0x{:02X} ({} text)", fc.ind_high, mode);
            else
                field(2, "high byte: 0x{:02X}", fc.ind_high);
            field(2, "index (low byte): {}", pkw.ind);
            if (fc.block == FcBlock::Text) {
                line(1, "");
                fmt::format_to(it, "Text: {} characters \"", fc.text.size());
                append_fc_text(b, fc.text);
                append(b, "\"\n");
            } else if (fc_rejected(t)) {
                const std::uint16_t code = fc_fault_code(fc);
                field(1, "PWE: 0x{:08X}", pkw.pva);
                field(2, "Fault code: {} = {}", code, fc_fault_text_or_unknown(code));
            } else {
                const ValueWidth width = fc_ak_width(t);
                if (width == ValueWidth::Word)
                    field(1, "PWE: 0x{:08X}, word value {}", pkw.pva, pcv_value(pkw, width));
                else if (width == ValueWidth::DoubleWord)
                    field(1, "PWE: 0x{:08X}, double word value {}", pkw.pva, pkw.pva);
                else
                    field(1, "PWE: 0x{:08X} (the AK carries no value)", pkw.pva);
            }
        }
        if (fc.has_pcd) {
            field(1, "PCD 1 {}: 0x{:04X} ({} word, FC profile)", pcd_word_name(t.direction, 0),
                  fc.pcd1, request ? "control" : "status");
            const WordBits& bits = request ? control_word_bits(PcdProfile::Fc, true)
                                           : status_word_bits(PcdProfile::Fc, true);
            for (int bit = 0; bit < 16; ++bit) {
                const bool set = (fc.pcd1 >> bit) & 1;
                const WordBit& meaning = bits[static_cast<std::size_t>(bit)];
                field(2, "bit {:>2} = {}: {}", bit, set ? 1 : 0,
                      set ? meaning.when_1 : meaning.when_0);
            }
            field(1, "PCD 2 {}: 0x{:04X} = {:.2f} %", pcd_word_name(t.direction, 1), fc.pcd2,
                  reference_percent(fc.pcd2));
        }
        if (fc.complete) {
            if (fc.bcc_ok)
                field(1, "BCC: 0x{:02X} (correct)", fc.bcc);
            else
                field(1, "BCC: 0x{:02X} (wrong: computed 0x{:02X})", fc.bcc, fc.bcc_computed);
        } else {
            field(1, "BCC: missing (telegram cut short)");
        }
    }

    // The characters of bytes [at, at + count) as sent, quoted ('"' and '\\' escaped, other bytes
    // \xNN).
    std::string chars(const DecodedTelegram& t, std::size_t at, std::size_t count) {
        TextBuffer text;
        text.push_back('"');
        append_fc_text(text, t.bytes.subspan(at, count));
        text.push_back('"');
        return std::string(text.data(), text.size());
    }

    // The VLT 2000 telegram field by field, from what Vlt2000Decoder stored; each field with its
    // byte numbers as the manual counts them, from 1 ("[5-8]": offsets 4-7), and as far as the
    // record reaches.
    void render_vlt2000(const DecodedTelegram& t) {
        const Vlt2000Telegram& v = t.vlt2000;
        TextBuffer& b = out_.buffer();
        auto it = std::back_inserter(b);
        const bool request = t.direction == Direction::Request;
        const std::size_t size = t.bytes.size();
        const auto has = [&](std::size_t at, std::size_t count) { return at + count <= size; };
        append(b, "VLT 2000 telegram");
        if (t.has_roles) {
            fmt::format_to(it, ": {} {}", vlt2000_letter_text(t), request ? "command" : "reply");
            if (v.broadcast && request)
                append(b, " to every drive (broadcast, address 00)");
            else if (v.broadcast)
                append(b, " from address 00 (a broadcast; nobody should reply)");
            else
                fmt::format_to(it, " {} drive {:02}", request ? "to" : "from", v.address);
            if (t.request_frame != 0) fmt::format_to(it, ", answers frame {}", t.request_frame);
        }
        b.push_back('\n');
        if (size == 0) return;
        if (t.bytes[0] != kVlt2000Start) {
            field(1, "[1] Start: {} (not '<')", chars(t, 0, 1));
            return;
        }
        field(1, "[1] Start: '<'");
        if (!has(kVlt2000AddressAt, 2)) return;
        if (t.has_roles)
            field(1, "[2-3] Address: {:02}{}", v.address,
                  v.broadcast ? " (broadcast: every drive acts, none replies)" : "");
        else
            field(1, "[2-3] Address: {} (not two digits)", chars(t, kVlt2000AddressAt, 2));
        if (!has(kVlt2000LetterAt, 1)) return;
        field(1, "[4] Control letter: {} ({}{})", chars(t, kVlt2000LetterAt, 1),
              vlt2000_letter_name(v.letter),
              v.letter == Vlt2000Letter::Unknown ? ": not U, R, C or I" : "");
        if (!has(kVlt2000WordAt, 4)) return;
        field(1, "[5-8] {} word: {} = 0x{:04X} ({})", request ? "Control" : "Status",
              chars(t, kVlt2000WordAt, 4), v.word, request ? "to the drive" : "from the drive");
        for (unsigned bit = 0; bit < 16; ++bit) {
            if (vlt2000_bit_kept(v, bit)) {
                if (bit % 4 == 0) field(2, "bits {}-{}: group kept (P)", bit, bit + 3);
                continue;
            }
            field(2, "bit {:>2} = {}: {}", bit, (v.word >> bit) & 1u,
                  vlt2000_bit_meaning(v, t.direction, bit));
        }
        if (!has(kVlt2000ParameterAt, 4)) return;
        const bool control = v.letter == Vlt2000Letter::Control;
        const std::string_view ignored = control ? " (ignored with C)" : "";
        if (v.has_parameter)
            field(1, "[9-12] Parameter: {}{}", v.parameter, ignored);
        else
            field(1, "[9-12] Parameter: {} (not four digits)", chars(t, kVlt2000ParameterAt, 4));
        if (!has(kVlt2000SignAt, 1)) return;
        if (v.letter == Vlt2000Letter::ReadIndex && !v.index.empty()) {
            if (v.has_index_number)
                field(1, "[13-18] Index: {} = {}", chars(t, kVlt2000SignAt, 6), v.index_number);
            else
                field(1, "[13-18] Index: {} (not a number)", chars(t, kVlt2000SignAt, 6));
        } else {
            field(1, "[13] Sign: {} ({}){}", chars(t, kVlt2000SignAt, 1),
                  v.negative ? "negative" : "positive", ignored);
            if (!has(kVlt2000ValueAt, 5)) return;
            if (v.failed) {
                field(1, "[14-18] Value: {} (none: the command failed)",
                      chars(t, kVlt2000ValueAt, 5));
            } else if (v.has_value) {
                const std::string note = vlt2000_value_note(v);
                line(1, "");
                fmt::format_to(it, "[14-18] Value: {:05} = {}", v.digits, vlt2000_value_text(v));
                if (!note.empty()) fmt::format_to(it, " ({})", note);
                append(b, ignored);
                b.push_back('\n');
            } else {
                field(1, "[14-18] Value: {} (not five digits)", chars(t, kVlt2000ValueAt, 5));
            }
        }
        if (v.failed) {
            if (v.has_reason)
                field(2, "[17-18] Reason code: {:02} = {}", v.reason, vlt2000_reason_or_unknown(v));
            else
                field(2, "[17-18] Reason code: {} ({})", chars(t, kVlt2000ReasonAt, 2),
                      vlt2000_reason_or_unknown(v));
        }
        if (!has(kVlt2000DecimalsAt, 1)) return;
        if (!v.has_decimals)
            field(1, "[19] Decimal position: {} (not a digit)", chars(t, kVlt2000DecimalsAt, 1));
        else if (v.failed)
            field(1, "[19] Decimal position: 9 (unknown parameter or the command failed)");
        else if (v.decimals > 5)
            field(1, "[19] Decimal position: {} (out of range 0-5)", v.decimals);
        else
            field(1, "[19] Decimal position: {}", v.decimals);
        if (has(kVlt2000ChecksumAt, 2)) {
            line(1, "[20-21] Checksum: ");
            append_vlt2000_checksum(b, t);
            b.push_back('\n');
        } else {
            field(1, "[20-21] Checksum: missing (telegram cut short)");
            return;
        }
        if (!has(kVlt2000StopAt, 1)) return;
        if (t.bytes[kVlt2000StopAt] == kVlt2000Stop)
            field(1, "[22] Stop: '>'");
        else
            field(1, "[22] Stop: {} (not '>')", chars(t, kVlt2000StopAt, 1));
    }

    static std::string_view sap_label(std::uint8_t value, bool slave_side) {
        std::string_view name = sap_name(value, slave_side);
        return name.empty() ? "no DP meaning" : name;
    }

    void render_fdl(const DecodedTelegram& t) {
        const FdlTelegram& f = t.dp.fdl;
        TextBuffer& b = out_.buffer();
        auto it = std::back_inserter(b);
        append(b, "PROFIBUS FDL\n");
        if (f.type == FrameType::Invalid) {
            field(1, "Start delimiter: 0x{:02X} (not a start delimiter)",
                  t.bytes.empty() ? 0 : t.bytes[0]);
            return;
        }
        field(1, "Start delimiter: {} (0x{:02X})", frame_type_name(f.type), t.bytes[0]);
        if (f.type == FrameType::Sd2) {
            field(
                1, "Length: LE {}, LEr {}", f.length_field,
                f.has_length_repeat ? fmt::format("{}", f.length_repeat) : std::string("missing"));
        }
        if (f.has_addresses) {
            line(1, "");
            fmt::format_to(it, "Destination address: {}{}", f.da,
                           f.da == kBroadcastAddress ? " (broadcast)" : "");
            // The slave's SAP is the DSAP of a request and the SSAP of a response.
            bool request = f.has_fc && f.fc.is_request();
            if (f.has_dsap)
                fmt::format_to(it, ", DSAP {} ({})", f.dsap, sap_label(f.dsap, request));
            if (f.has_dest_segment) fmt::format_to(it, ", segment {}", f.dest_segment);
            b.push_back('\n');
            line(1, "");
            fmt::format_to(it, "Source address: {}", f.sa);
            if (f.has_ssap)
                fmt::format_to(it, ", SSAP {} ({})", f.ssap, sap_label(f.ssap, !request));
            if (f.has_source_segment) fmt::format_to(it, ", segment {}", f.source_segment);
            b.push_back('\n');
        }
        if (f.has_fc) {
            line(1, "");
            fmt::format_to(it, "Frame control: 0x{:02X} (", f.fc.raw);
            append_frame_control(b, f.fc);
            append(b, ")\n");
        }
        if (!f.du.empty())
            field(1, "Data unit: {} from byte {}", counted(f.du.size(), "byte", "bytes"),
                  f.du_offset);
        if (f.has_fcs) {
            if (f.fcs_ok)
                field(1, "FCS: 0x{:02X} (correct)", f.fcs);
            else
                field(1, "FCS: 0x{:02X} (wrong)", f.fcs);
        }
        if (f.type == FrameType::Sd1 || f.type == FrameType::Sd2 || f.type == FrameType::Sd3) {
            if (t.bytes.size() >= f.size && f.size > 0)
                field(1, "End delimiter: 0x{:02X}", t.bytes[f.size - 1]);
        }
    }

    void render_dp(const DecodedTelegram& t) {
        if (t.dp.fdl.type == FrameType::Invalid) return;
        TextBuffer& b = out_.buffer();
        auto it = std::back_inserter(b);
        fmt::format_to(it, "PROFIBUS DP: {} {}", service_name(t.dp.service),
                       direction_name(t.direction));
        if (t.has_roles && t.dp.service != Service::Token)
            fmt::format_to(it, ", master {} / slave {}", t.master, t.slave);
        if (t.request_frame != 0) fmt::format_to(it, ", answers frame {}", t.request_frame);
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
                    field(1, "Group select: 0x{:02X}{}", gc->group_select,
                          gc->group_select == 0 ? " (all slaves)" : "");
                }
                break;
            case Service::SetSlaveAdd:
                if (const SetSlaveAdd* ssa = data.set_slave_add()) {
                    field(1, "New slave address: {}", ssa->new_address);
                    field(1, "Ident number: 0x{:04X}", ssa->ident);
                    field(1, "No_Add_Chg: {}", ssa->no_add_chg);
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
    }

    void render_dpv1(const DecodedTelegram& t, const Dpv1Pdu& pdu) {
        TextBuffer& b = out_.buffer();
        if (pdu.layout == Dpv1Pdu::Layout::None) {
            field(1, "DP-V1 PDU: none (empty data unit: a link-level poll)");
            return;
        }
        std::string_view name = dpv1_function_name(pdu.function);
        field(1, "DP-V1 function: 0x{:02X} ({}){}", pdu.function,
              name.empty() ? "not defined by DP-V1" : name,
              pdu.negative() ? ", negative response" : "");
        if (!pdu.complete) field(2, "PDU cut short: the fields below are those read");
        switch (pdu.layout) {
            case Dpv1Pdu::Layout::Error: {
                std::string_view decode = dpv1_error_decode_name(pdu.error_decode);
                field(2, "Error_Decode: 0x{:02X} ({})", pdu.error_decode,
                      decode.empty() ? "unknown" : decode);
                std::string_view error_class = dpv1_error_class_name(pdu.error_code_1);
                field(2, "Error_Code_1: 0x{:02X}", pdu.error_code_1);
                field(3, "Error class: {} ({})", pdu.error_code_1 >> 4,
                      error_class.empty() ? "reserved" : error_class);
                field(3, "Error code: {} ({})", pdu.error_code_1 & 0x0F,
                      dpv1_error_code_name(pdu.error_code_1));
                field(2, "Error_Code_2: 0x{:02X}", pdu.error_code_2);
                break;
            }
            case Dpv1Pdu::Layout::Addressed:
                field(2, "Slot: {}", pdu.slot);
                if (pdu.base_function() == dpv1_function::kAlarmAck) {
                    field(2, "Alarm type: {}", pdu.index);
                    field(2, "Specifier: 0x{:02X}", pdu.length);
                } else {
                    field(2, "Index: {}{}", pdu.index,
                          pdu.index == kProfidriveIndex ? " (PROFIdrive parameter channel)" : "");
                    field(2, "Length: {}", pdu.length);
                }
                if (!pdu.data.empty()) {
                    line(2, "");
                    fmt::format_to(std::back_inserter(b), "Data ({} from byte {}): ",
                                   counted(pdu.data.size(), "byte", "bytes"), pdu.data_offset);
                    append_hex(b, pdu.data);
                    b.push_back('\n');
                }
                break;
            case Dpv1Pdu::Layout::Initiate: {
                const Dpv1Initiate& i = pdu.initiate;
                if (t.direction == Direction::Request)
                    field(2, "Send_Timeout: {} ({} ms)", i.send_timeout, i.send_timeout * 10);
                else
                    field(2, "Max_Len_Data_Unit: {}", i.max_len_data_unit);
                field(2, "Features_Supported: 0x{:04X}", i.features_supported);
                field(2, "Profile_Features_Supported: 0x{:04X}", i.profile_features_supported);
                field(2, "Profile_Ident_Number: 0x{:04X}", i.profile_ident_number);
                if (i.has_addresses) {
                    field(2, "S_Type: {}, S_Len: {}", i.s_type, i.s_len);
                    line(2, "S_Addr: ");
                    append_hex(b, i.s_addr);
                    b.push_back('\n');
                    field(2, "D_Type: {}, D_Len: {}", i.d_type, i.d_len);
                    line(2, "D_Addr: ");
                    append_hex(b, i.d_addr);
                    b.push_back('\n');
                }
                break;
            }
            case Dpv1Pdu::Layout::Abort:
                field(2, "Subnet: {}", pdu.abort.subnet);
                field(2, "Instance_Reason_Code: 0x{:02X}", pdu.abort.instance_reason);
                field(3, "Instance: {} ({})", pdu.abort.instance(),
                      dpv1_abort_instance_name(pdu.abort.instance_reason));
                field(3, "Reason code: {} ({})", pdu.abort.reason(),
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
            render_profidrive(*m, t.dp.dialect);
    }

    void render_profidrive(const ProfidriveMessage& m, Dialect dialect) {
        field(1, "PROFIdrive parameter {}", m.is_response ? "response" : "request");
        if (!m.has_header) {
            field(2, "header cut short");
            return;
        }
        field(2, "Request reference: {}", m.reference);
        std::string_view id_name =
            m.is_response ? profidrive_response_id_name(m.id) : profidrive_request_id_name(m.id);
        field(2, "{} ID: 0x{:02X} ({})", m.is_response ? "Response" : "Request", m.id,
              id_name.empty() ? "not defined" : id_name);
        field(2, "Axis: {}", m.axis);
        field(2, "Number of parameters: {}", m.count);
        if (m.is_response) {
            if (m.has_request)
                field(2, "Answers the request in frame {} (ref {}, ID 0x{:02X})", m.request_frame,
                      m.request_reference, m.request_id);
            else
                field(2, "Request not in the capture: parameter numbers unknown");
        }
        std::size_t parameters = std::max(m.addresses.size(), m.blocks.size());
        for (std::size_t k = 0; k < parameters; ++k) {
            field(2, "Parameter {}", k + 1);
            if (k < m.addresses.size()) {
                const ProfidriveAddress& a = m.addresses[k];
                std::string_view attribute = profidrive_attribute_name(a.attribute);
                field(3, "Attribute: 0x{:02X} ({})", a.attribute,
                      attribute.empty() ? "not defined" : attribute);
                field(3, "Number of elements: {}", a.elements);
                field(3, "Parameter number: {}", a.pnu);
                field(3, "Subindex: {}", a.subindex);
            }
            if (k >= m.blocks.size()) continue;
            const ProfidriveValueBlock& block = m.blocks[k];
            field(3, "Format: 0x{:02X} ({})", block.format, profidrive_format_name(block.format));
            field(3, "Number of values: {}", block.count);
            if (block.is_error()) {
                if (block.values.size() >= 2)
                    field(3, "Error number: 0x{:02X} ({})", block.error_number(),
                          profidrive_error_text(block.error_number(), dialect));
                if (block.has_error_info())
                    field(3, "Additional information: {}", block.error_info());
            } else if (block.format != profidrive::kFormatZero) {
                std::string values;
                append_profidrive_values(block, values);
                field(3, "Values: {}", values);
            }
            if (!block.complete) field(3, "(block cut short)");
            if (block.padded) field(3, "Pad byte");
        }
        if (m.trailing > 0) field(2, "{} after the message", counted(m.trailing, "byte", "bytes"));
    }

    void render_data_exchange(const DecodedTelegram& t) {
        TextBuffer& b = out_.buffer();
        line(1, "PPO: ");
        append_ppo_long(b, t.dp.ppo);
        b.push_back('\n');
        field(1, "Dialect: {}; control/status word profile: {}{}",
              t.dp.ppo.has_pcv ? dialect_name(t.dp.dialect) : "none (no parameter channel)",
              pcd_profile_name(t.dp.pcd_profile),
              t.dp.pcd_profile == PcdProfile::Profidrive && t.dp.danfoss_pcd() ? " (Danfoss)" : "");
        bool request = t.direction == Direction::Request;
        if (t.dp.has_pcv) {
            const Pcv& pcv = t.dp.pcv;
            field(1, "PCV (parameter channel), bytes {}-{}", t.dp.fdl.du_offset,
                  t.dp.fdl.du_offset + kPcvBytes - 1);
            field(2, "PCA: 0x{:04X}", pcv.pca);
            bool defined =
                request ? request_code(t.dp.dialect, pcv.rc).defined
                        : response_code(t.dp.dialect, pcv.rc).kind != ResponseKind::Undefined;
            field(3, "RC: {} = {}{}", pcv.rc, t.dp.pcv_meaning(t.direction),
                  defined ? "" : " (not defined by the dialect)");
            field(3, "SPM: {}", pcv.spm ? 1 : 0);
            field(3, "PNU: {}", pcv.pnu);
            field(2, "IND: {} (byte 4: 0x{:02X})", pcv.ind, pcv.ind_low);
            ValueWidth width = request ? request_code(t.dp.dialect, pcv.rc).width
                                       : response_code(t.dp.dialect, pcv.rc).width;
            bool rejected =
                !request && response_code(t.dp.dialect, pcv.rc).kind == ResponseKind::Rejected;
            if (rejected) {
                auto error = static_cast<std::uint16_t>(pcv.pva & 0xFFFF);
                field(2, "PVA: 0x{:08X}", pcv.pva);
                field(2, "Error number: {} = {}", error,
                      error_text_or_unknown(t.dp.dialect, error));
            } else if (width == ValueWidth::Word) {
                field(2, "PVA: 0x{:08X}, word value {}", pcv.pva, pcv_value(pcv, width));
            } else if (width == ValueWidth::DoubleWord) {
                field(2, "PVA: 0x{:08X}, double word value {}", pcv.pva, pcv.pva);
            } else {
                field(2, "PVA: 0x{:08X} (the code carries no value)", pcv.pva);
            }
        }
        ByteReader reader(t.dp.pcd, t.dp.pcd_offset);
        if (reader.empty()) return;
        field(1, "PCD ({} words)", reader.remaining() / 2);
        const WordBits& bits = request ? control_word_bits(t.dp.pcd_profile, t.dp.danfoss_pcd())
                                       : status_word_bits(t.dp.pcd_profile, t.dp.danfoss_pcd());
        for (std::size_t index = 0;; ++index) {
            auto word = reader.u16_be();
            if (!word) break;
            std::string_view name = pcd_word_name(t.direction, index);
            if (index == 0) {
                field(2, "PCD 1 {}: 0x{:04X}", name, *word);
                for (int bit = 0; bit < 16; ++bit) {
                    bool set = (*word >> bit) & 1;
                    const WordBit& meaning = bits[static_cast<std::size_t>(bit)];
                    field(3, "bit {:>2} = {}: {}", bit, set ? 1 : 0,
                          set ? meaning.when_1 : meaning.when_0);
                }
            } else if (index == 1) {
                field(2, "PCD 2 {}: 0x{:04X} = {:.2f} %", name, *word, reference_percent(*word));
            } else {
                field(2, "PCD {}: 0x{:04X} ({})", index + 1, *word, *word);
            }
        }
        if (!reader.empty()) field(2, "odd trailing byte: 0x{:02X}", *reader.u8());
    }

    void render_diag(const SlaveDiag& diag, std::span<const DiagBlock> blocks, SlaveDpv1 dpv1) {
        flags_field(1, "Station status 1", diag.station_status_1, station_status_1_flags());
        flags_field(1, "Station status 2", diag.station_status_2, station_status_2_flags());
        flags_field(1, "Station status 3", diag.station_status_3, station_status_3_flags());
        if (diag.master_address == kNoMasterAddress)
            field(1, "Master address: 255 (not parameterised)");
        else
            field(1, "Master address: {}", diag.master_address);
        field(1, "Ident number: 0x{:04X}", diag.ident);
        if (diag.extended.empty()) return;
        field(1, "Extended diagnosis: {}", counted(diag.extended.size(), "byte", "bytes"));
        for (const DiagBlock& block : blocks) {
            TextBuffer& b = out_.buffer();
            switch (block.type) {
                case DiagBlockType::Channel:
                    field(2, "channel-related: module {}, channel {}, {}, {}: error {} ({})",
                          block.module, block.channel, channel_io_text(block.io),
                          channel_type_text(block.channel_type), block.error_type,
                          channel_error_text(block.error_type));
                    break;
                case DiagBlockType::Revision: field(2, "revision number {}", block.revision); break;
                case DiagBlockType::Identifier: {
                    line(2, "identifier-related: modules with diagnosis:");
                    bool any = false;
                    for (std::size_t i = 0; i < block.data.size(); ++i)
                        for (int bit = 0; bit < 8; ++bit)
                            if ((block.data[i] >> bit) & 1) {
                                fmt::format_to(std::back_inserter(b), " {}", i * 8 + bit);
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
        auto it = std::back_inserter(out_.buffer());
        bool fits = block.data.size() >= 3;
        switch (dpv1) {
            case SlaveDpv1::Disabled:
                append(out_.buffer(), " (manufacturer-specific: Set_Prm did not enable DP-V1)");
                return;
            case SlaveDpv1::Enabled:
                if (fits)
                    fmt::format_to(it, " (DP-V1: {}, slot {})",
                                   dpv1_alarm_or_status_text(block.data[0]), block.data[1]);
                else
                    fmt::format_to(it, " (DP-V1, but {}: too short for an alarm or status)",
                                   counted(block.data.size(), "byte", "bytes"));
                return;
            case SlaveDpv1::Unknown:
                append(out_.buffer(), " (DP-V1 or manufacturer-specific: no Set_Prm seen");
                if (fits)
                    fmt::format_to(it, "; as DP-V1: {}, slot {}",
                                   dpv1_alarm_or_status_text(block.data[0]), block.data[1]);
                out_.buffer().push_back(')');
                return;
        }
    }

    void render_prm(const SetPrm& prm) {
        flags_field(1, "Station status", prm.station_status, set_prm_station_flags());
        std::string watchdog = " (off)";
        if (prm.watchdog_on() && prm.watchdog_base_uncertain())
            watchdog = fmt::format(
                " = {} ms with WD_Base_1ms, or {} ms if the bytes read as DPV1_Status are "
                "User_Prm_Data (10 ms base)",
                prm.watchdog_ms(), prm.watchdog_ms_10ms_base());
        else if (prm.watchdog_on())
            watchdog = fmt::format(" = {} ms", prm.watchdog_ms());
        field(1, "Watchdog: factors {} x {}{}", prm.wd_fact_1, prm.wd_fact_2, watchdog);
        field(1, "min TSDR: {} bit times", prm.min_tsdr);
        field(1, "Ident number: 0x{:04X}", prm.ident);
        field(1, "Group ident: 0x{:02X}", prm.group_ident);
        if (prm.has_dpv1_status) {
            flags_field(1, "DPV1_Status_1", prm.dpv1_status[0], dpv1_status_1_flags());
            flags_field(1, "DPV1_Status_2", prm.dpv1_status[1], dpv1_status_2_flags());
            line(1, "");
            fmt::format_to(std::back_inserter(out_.buffer()),
                           "DPV1_Status_3: 0x{:02X} (Alarm_Mode {} = {}", prm.dpv1_status[2],
                           prm.dpv1_status[2] & 0x07, dpv1_alarm_mode_text(prm.dpv1_status[2]));
            TextBuffer flags;
            if (append_flags(flags, prm.dpv1_status[2], dpv1_status_3_flags(), "")) {
                append(out_.buffer(), "; ");
                out_.buffer().append(flags.data(), flags.data() + flags.size());
            }
            append(out_.buffer(), ")\n");
        }
        if (!prm.user_prm.empty()) {
            line(1, "User_Prm_Data: ");
            append_hex(out_.buffer(), prm.user_prm);
            out_.buffer().push_back('\n');
        }
    }

    void render_cfg(const DecodedTelegram& t, std::span<const CfgModule> modules) {
        line(1, "Identifier bytes: ");
        append_hex(out_.buffer(), t.dp.fdl.du);
        out_.buffer().push_back('\n');
        std::size_t number = 1;
        for (const CfgModule& m : modules) {
            if (m.free_place) {
                field(2, "module {}: 0x00 free place", number++);
                continue;
            }
            std::string lengths;
            if (m.output_units)
                lengths += fmt::format(" out {}{}", cfg_units(m.output_units, m.output_words),
                                       m.output_consistent ? " consistent" : "");
            if (m.input_units)
                lengths += fmt::format(" in {}{}", cfg_units(m.input_units, m.input_words),
                                       m.input_consistent ? " consistent" : "");
            field(2, "module {}: 0x{:02X} {}{}{}{}", number++, m.identifier,
                  m.special ? "special format," : "", cfg_direction_name(m.direction), lengths,
                  m.manufacturer_bytes
                      ? fmt::format(", {}", counted(m.manufacturer_bytes, "manufacturer byte",
                                                    "manufacturer bytes"))
                      : std::string());
        }
        line(1, "Layout: ");
        append_ppo_long(out_.buffer(),
                        ppo_from_cfg(modules, t.dp.service == Service::ChkCfg ? PpoSource::ChkCfg
                                                                              : PpoSource::GetCfg));
        out_.buffer().push_back('\n');
    }
};

}  // namespace

std::unique_ptr<TelegramRenderer> make_verbose_renderer(Output& out) {
    return std::make_unique<VerboseRenderer>(out);
}

}  // namespace dpscope
