// What the dissector's tree builders share: Tree, a subtree of the telegram that places items at
// telegram offsets and never throws, and the helpers every protocol's tree uses.
#pragma once

#include <wireshark.h>
// wireshark.h first: it sets up what the epan headers need.
#include <epan/proto.h>
#include <epan/tvbuff.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>

#include "formats/describe.hpp"
#include "protocols/profibus/pcd.hpp"
#include "wireshark/dissector_fields.hpp"

namespace dpscope::wireshark {

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

// The text a TextBuffer holds.
std::string buffer_text(const TextBuffer& b);

// PCD 1 with its 16 bits, as `dpscope decode -V` words them.
void add_word_bits(const Tree& tree, proto_item* item, std::size_t at, std::uint16_t word,
                   bool control, const WordBits& bits);

}  // namespace dpscope::wireshark
