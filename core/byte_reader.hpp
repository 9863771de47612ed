// One bounds-checked cursor for every read the decoders make. A read past the end returns
// std::nullopt (or false) and leaves the cursor where it was; nothing throws and nothing reads
// outside the span. Parsing code asks the cursor, it never indexes the buffer itself.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

namespace dpscope {

using Bytes = std::span<const std::uint8_t>;

class ByteReader {
  public:
    // base_offset: where data[0] sits in the enclosing telegram, so offset() can name the byte
    // position a person sees in a hex dump of the whole telegram.
    explicit ByteReader(Bytes data, std::size_t base_offset = 0) noexcept
        : data_(data), base_offset_(base_offset) {}

    std::size_t position() const noexcept { return position_; }
    std::size_t offset() const noexcept { return base_offset_ + position_; }
    std::size_t remaining() const noexcept { return data_.size() - position_; }
    std::size_t size() const noexcept { return data_.size(); }
    bool empty() const noexcept { return position_ >= data_.size(); }

    std::optional<std::uint8_t> peek_u8(std::size_t ahead = 0) const noexcept {
        if (ahead >= remaining()) return std::nullopt;
        return data_[position_ + ahead];
    }

    std::optional<std::uint8_t> u8() noexcept {
        if (empty()) return std::nullopt;
        return data_[position_++];
    }

    std::optional<std::uint16_t> u16_be() noexcept {
        if (remaining() < 2) return std::nullopt;
        auto value = static_cast<std::uint16_t>((data_[position_] << 8) | data_[position_ + 1]);
        position_ += 2;
        return value;
    }

    std::optional<std::uint32_t> u32_be() noexcept {
        if (remaining() < 4) return std::nullopt;
        std::uint32_t value =
            (std::uint32_t{data_[position_]} << 24) | (std::uint32_t{data_[position_ + 1]} << 16) |
            (std::uint32_t{data_[position_ + 2]} << 8) | std::uint32_t{data_[position_ + 3]};
        position_ += 4;
        return value;
    }

    // The next n bytes as a sub-span, or nullopt when fewer remain.
    std::optional<Bytes> bytes(std::size_t n) noexcept {
        if (n > remaining()) return std::nullopt;
        Bytes out = data_.subspan(position_, n);
        position_ += n;
        return out;
    }

    // Everything not read yet; the cursor moves to the end.
    Bytes rest() noexcept {
        Bytes out = data_.subspan(position_);
        position_ = data_.size();
        return out;
    }

    // A reader over the next n bytes (or fewer, when fewer remain) whose offsets continue this
    // reader's numbering; this reader moves past them.
    ByteReader sub_reader(std::size_t n) noexcept {
        std::size_t take = n < remaining() ? n : remaining();
        ByteReader sub(data_.subspan(position_, take), offset());
        position_ += take;
        return sub;
    }

    bool skip(std::size_t n) noexcept {
        if (n > remaining()) return false;
        position_ += n;
        return true;
    }

  private:
    Bytes data_;
    std::size_t base_offset_ = 0;
    std::size_t position_ = 0;
};

}  // namespace dpscope
