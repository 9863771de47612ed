// The FC protocol in the dissector: its subtree (STX, LGE, ADR, the PKW with PKE, IND and PWE or
// text, PCD 1 and 2, BCC), its columns and its record in the table of protocol trees.
#include <fmt/format.h>

#include <string>
#include <string_view>

#include "core/code_tables.hpp"
#include "formats/describe.hpp"
#include "formats/parameter_names.hpp"
#include "protocols/fc/fc_describe.hpp"
#include "protocols/profibus/pcd.hpp"
#include "wireshark/protocol_tree.hpp"

namespace dpscope::wireshark {
namespace {

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
        // The name and value in its unit from its drive's database (issue 29).
        const TelegramParameterView view = parameter_view(t);
        // "414 (parameter 4-14 Motor Speed High Limit [Hz])"; a family that writes its numbers
        // otherwise names it apart: "518 (parameter 5-18) (Frequency)".
        const bool grouped = view.named.row && view.named.family->numbering == PnuNumbering::Group;
        pke.uint(hf_fc_pnu, 3, 2, pkw.pnu,
                 grouped ? fmt::format("{} (parameter {} {})", pkw.pnu, fc_parameter_name(pkw.pnu),
                                       view.named.row->name)
                         : fmt::format("{} (parameter {}){}", pkw.pnu, fc_parameter_name(pkw.pnu),
                                       parameter_name_text(view.named)));
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
                              fmt::format("{} ({}){}", pcv_value(pkw, width),
                                          word ? "word" : "double word", view_value_text(view)));
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

// The drive's address as the text line writes it.
AddressColumns fc_address_columns(const DecodedTelegram& t) {
    return drive_address_columns(t, t.fc.broadcast, fmt::format("{}", t.fc.address));
}

}  // namespace

const ProtocolTree& fc_tree() noexcept {
    static const ProtocolTree tree{
        .protocol = Protocol::Fc,
        .column = "FC",
        .bus_description = "Danfoss FC protocol",
        .shows_master = false,
        .add_subtree = add_fc,
        .address_columns = fc_address_columns,
    };
    return tree;
}

}  // namespace dpscope::wireshark
