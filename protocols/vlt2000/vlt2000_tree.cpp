// The VLT 2000 telegram in the dissector: its subtree (start, address, control letter,
// control/status word, parameter, value, decimal position, checksum, stop), its columns and its
// record in the table of protocol trees.
#include <fmt/format.h>

#include <charconv>
#include <string>

#include "formats/describe.hpp"
#include "formats/parameter_names.hpp"
#include "protocols/fc/fc_describe.hpp"
#include "protocols/vlt2000/vlt2000_describe.hpp"
#include "wireshark/protocol_tree.hpp"

namespace dpscope::wireshark {
namespace {

// Characters as sent, as jsonl writes them (\xNN for a byte that is not printable).
std::string chars_text(Bytes bytes) {
    TextBuffer b;
    append_fc_text(b, bytes);
    return buffer_text(b);
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
    // The name and unit from its drive's database (issue 29).
    const TelegramParameterView view = parameter_view(t);
    if (v.has_parameter)
        tree.uint(hf_vlt_parameter, kVlt2000ParameterAt, 4, v.parameter,
                  fmt::format("{}{}{}", v.parameter, parameter_name_text(view.named),
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
            fmt::format("{:05} = {}{}{}", v.digits, text,
                        view.value && !view.named.row->unit.empty() ? " " + view.named.row->unit
                                                                    : std::string(),
                        note.empty() ? note : " (" + note + ")"));
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

// The drive's address as the text line writes it: two digits.
AddressColumns vlt2000_address_columns(const DecodedTelegram& t) {
    return drive_address_columns(t, t.vlt2000.broadcast, fmt::format("{:02}", t.vlt2000.address));
}

}  // namespace

const ProtocolTree& vlt2000_tree() noexcept {
    static const ProtocolTree tree{
        .protocol = Protocol::Vlt2000,
        .column = "VLT 2000",
        .bus_description = "VLT 2000 serial telegram",
        .shows_master = false,
        .add_subtree = add_vlt2000,
        .address_columns = vlt2000_address_columns,
    };
    return tree;
}

}  // namespace dpscope::wireshark
