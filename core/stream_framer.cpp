#include "core/stream_framer.hpp"

namespace dpscope {

void FramerCore::compact() {
    if (start_ == 0) return;
    buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(start_));
    buffer_offset_ += start_;
    start_ = 0;
}

}  // namespace dpscope
