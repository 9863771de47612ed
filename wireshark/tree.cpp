// The helpers of tree.hpp.
#include "wireshark/tree.hpp"

#include <fmt/format.h>

namespace dpscope::wireshark {

std::string buffer_text(const TextBuffer& b) { return std::string(b.data(), b.size()); }

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

}  // namespace dpscope::wireshark
