// The position of each (master, slave) channel in a tracker's list of channels, by the two 7-bit
// addresses. A row of 128 positions is made for a master when its first channel is added: a
// tracker that sees a few masters keeps a few rows (a table of all 128 x 128 made each tracker
// cost 64 KiB to make and fill, most of the time of a short capture and of a fuzz run).
#pragma once

#include <array>
#include <cstdint>
#include <memory>

namespace dpscope {

class ChannelIndex {
  public:
    static constexpr std::int32_t kNone = -1;

    // The position of the channel master -> slave, kNone when it was never set.
    std::int32_t find(std::uint8_t master, std::uint8_t slave) const noexcept {
        const Row* row = rows_[master & 0x7Fu].get();
        return row ? (*row)[slave & 0x7Fu] : kNone;
    }
    void set(std::uint8_t master, std::uint8_t slave, std::int32_t position) {
        std::unique_ptr<Row>& row = rows_[master & 0x7Fu];
        if (!row) {
            row = std::make_unique<Row>();
            row->fill(kNone);
        }
        (*row)[slave & 0x7Fu] = position;
    }

  private:
    using Row = std::array<std::int32_t, 128>;
    std::array<std::unique_ptr<Row>, 128> rows_{};
};

}  // namespace dpscope
