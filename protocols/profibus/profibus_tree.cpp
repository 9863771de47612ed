// The PROFIBUS subtrees: the FDL telegram, the DP service with its PPO, PCV and PCD, diagnosis,
// parameters and configuration, and DP-V1 with its PROFIdrive parameter access; the columns and
// PROFIBUS's record in the table of protocol trees.
#include <fmt/format.h>

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/code_tables.hpp"
#include "formats/describe.hpp"
#include "formats/parameter_names.hpp"
#include "protocols/profibus/dp_payload.hpp"
#include "protocols/profibus/dpv1/profidrive.hpp"
#include "protocols/profibus/pcd.hpp"
#include "wireshark/protocol_tree.hpp"

namespace dpscope::wireshark {
namespace {

std::string flags_text(std::uint8_t value, std::span<const FlagBit> flags,
                       std::uint8_t ignore = 0) {
    TextBuffer b;
    fmt::format_to(std::back_inserter(b), "0x{:02X} (", value);
    append_flags(b, value, flags, "none", ignore);
    b.push_back(')');
    return buffer_text(b);
}

std::string hex_text(Bytes bytes) {
    TextBuffer b;
    append_hex(b, bytes);
    return buffer_text(b);
}

// The FDL telegram: start delimiter, lengths, addresses, frame control, SAPs, FCS.
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
    // The name and value in its unit from its drive's database (issue 29).
    const TelegramParameterView view = parameter_view(t);
    pca.uint(hf_pcv_pnu, at, 2, pcv.pnu,
             fmt::format("{}{}", pcv.pnu, parameter_name_text(view.named)));
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
                 fmt::format("{} ({}){}", pcv_value(pcv, width), word ? "word" : "double word",
                             view_value_text(view)));
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

// What the slave's GSD file says about a management telegram (issue 29; docs/gsd.md).
void add_gsd(const Tree& tree, const DecodedTelegram& t) {
    const GsdDevice* device = t.dp.device;
    if (!device) return;
    const DpServiceData& data = t.dp.service_data;
    Tree gsd = tree.text(0, 0, kEttGsd, fmt::format("GSD: {}", gsd_device_title(*device)));
    gsd.string(hf_gsd_file, 0, 0, device->file);
    gsd.string(hf_gsd_device, 0, 0, gsd_device_title(*device));
    for (const GsdModuleMatch& m : data.gsd_modules())
        gsd.string(hf_gsd_module, m.offset, m.length,
                   m.module ? m.module->name : std::string("no module of the GSD"),
                   fmt::format("{} (slot {})",
                               m.module ? m.module->name : std::string("no module of the GSD"),
                               m.first_identifier));
    if (const GsdPrmReading* prm = data.gsd_prm())
        for (const GsdPrmValue& v : prm->values) {
            TextBuffer b;
            append_gsd_value(b, v);
            const std::string text = fmt::to_string(b);
            gsd.string(hf_gsd_prm, v.offset, 1, text);
        }
    for (const GsdDiagText& d : data.gsd_diag()) {
        TextBuffer b;
        append_gsd_diag_text(b, d);
        gsd.string(hf_gsd_diag, d.offset, 1, std::string(d.text), fmt::to_string(b));
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
            p.uint(hf_pd_pnu, a_at + 2, 2, a.pnu,
                   fmt::format("{}{}", a.pnu, parameter_name_text(profidrive_parameter(t, m, k))));
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

// The DP service and its data: PPO, PCV and PCD of a Data_Exchange, diagnosis, parameters,
// configuration, Global_Control, Set_Slave_Add, DP-V1 with its PROFIdrive parameter access.
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
            if (const SlaveDiag* diag = data.slave_diag()) {
                add_diag(tree, t, *diag, data.diag_blocks());
                add_gsd(tree, t);
            }
            break;
        case Service::SetPrm:
            if (const SetPrm* prm = data.set_prm()) {
                add_prm(tree, t, *prm);
                add_gsd(tree, t);
            }
            break;
        case Service::ChkCfg:
        case Service::GetCfg:
            if (const std::vector<CfgModule>* modules = data.cfg_modules();
                modules && !t.dp.fdl.du.empty()) {
                add_cfg(tree, t, *modules);
                add_gsd(tree, t);
            }
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

// The FDL telegram, then the DP service it carries.
void add_profibus(const Tree& top, const DecodedTelegram& t) {
    add_fdl(top, t);
    add_dp(top, t);
}

// The FDL addresses; a telegram without them (the short acknowledgement) goes from the slave to
// the master of the request it answers.
AddressColumns profibus_address_columns(const DecodedTelegram& t) {
    if (t.dp.fdl.has_addresses)
        return {fmt::format("{}", t.dp.fdl.sa), fmt::format("{}", t.dp.fdl.da)};
    if (t.has_roles) return {fmt::format("{}", t.slave), fmt::format("{}", t.master)};
    return {};
}

}  // namespace

const ProtocolTree& profibus_tree() noexcept {
    static const ProtocolTree tree{
        .protocol = Protocol::ProfibusDp,
        .column = "PROFIBUS",
        .bus_description = "PROFIBUS DP",
        .shows_master = true,
        .add_subtree = add_profibus,
        .address_columns = profibus_address_columns,
    };
    return tree;
}

}  // namespace dpscope::wireshark
