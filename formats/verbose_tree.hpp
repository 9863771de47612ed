// The verbose format's field tree (like tshark -V), as every protocol writes its part of it: one
// field a line, indented four spaces a level. A protocol's verbose writer derives from it
// (protocols/<name>/*_render.cpp) and is reached through its <name>_verbose
// (formats/protocol_rendering.hpp).
#pragma once

#include <fmt/compile.h>
#include <fmt/format.h>

#include <cstdint>
#include <cstring>
#include <iterator>
#include <span>
#include <string_view>
#include <utility>

#include "formats/describe.hpp"
#include "protocols/profibus/pcd.hpp"

namespace dpscope {

class VerboseTree {
  public:
    explicit VerboseTree(TextBuffer& buffer) noexcept : buffer_(buffer) {}

    TextBuffer& buffer() noexcept { return buffer_; }

    // The indentation of `level`, then `text` (no line end).
    void line(int level, std::string_view text) {
        TextBuffer& b = buffer_;
        if (level > 0)
            std::memset(append_room(b, 4 * static_cast<std::size_t>(level)), ' ',
                        4 * static_cast<std::size_t>(level));
        append(b, text);
    }

    // A whole line at `level`. `format` is a compile-time format string: FMT_COMPILE("...").
    template <typename Format, typename... Args>
    void field(int level, const Format& format, Args&&... args) {
        line(level, "");
        fmt::format_to(fmt::appender(buffer_), format, std::forward<Args>(args)...);
        buffer_.push_back('\n');
    }

    // A whole line at `level` from pieces written by put() (formats/text_buffer.hpp): the
    // faster form for the fields every telegram has.
    template <typename... Pieces>
    void put_line(int level, const Pieces&... pieces) {
        line(level, "");
        put(buffer_, pieces...);
        buffer_.push_back('\n');
    }

    // A control or status word's 16 bits, one line each at `level`, with the meaning of the
    // state each is in: "bit  3 = 1: enable".
    void word_bit_fields(int level, std::uint16_t word, const WordBits& bits) {
        // Each line in one append: the indentation, "bit NN = S: " from one template with the
        // number and the state S put in, the meaning and the line end.
        char start[] = "bit  0 = 0: ";
        constexpr std::size_t kStart = sizeof start - 1;
        const std::size_t indent = level > 0 ? 4 * static_cast<std::size_t>(level) : 0;
        for (int bit = 0; bit < 16; ++bit) {
            const bool set = (word >> bit) & 1;
            const WordBit& meaning = bits[static_cast<std::size_t>(bit)];
            start[4] = bit < 10 ? ' ' : '1';
            start[5] = static_cast<char>('0' + bit % 10);
            start[9] = set ? '1' : '0';
            const std::string_view text = set ? meaning.when_1 : meaning.when_0;
            char* p = append_room(buffer_, indent + kStart + text.size() + 1);
            std::memset(p, ' ', indent);
            p += indent;
            std::memcpy(p, start, kStart);
            if (!text.empty()) std::memcpy(p + kStart, text.data(), text.size());
            p[kStart + text.size()] = '\n';
        }
    }

    // "name: 0x05 (flag, flag)": a byte and the names of its set bits.
    void flags_field(int level, std::string_view name, std::uint8_t value,
                     std::span<const FlagBit> flags, std::uint8_t ignore = 0) {
        line(level, "");
        put(buffer_, name, ": ");
        append_hex_byte(buffer_, value);
        append(buffer_, " (");
        append_flags(buffer_, value, flags, "none", ignore);
        append(buffer_, ")\n");
    }

  private:
    TextBuffer& buffer_;
};

}  // namespace dpscope
