#include "formats/output.hpp"

namespace dpscope {

bool Output::flush() {
    if (buffer_.size() > 0) {
        if (std::fwrite(buffer_.data(), 1, buffer_.size(), file_) != buffer_.size()) failed_ = true;
        buffer_.clear();
    }
    if (std::fflush(file_) != 0) failed_ = true;
    return !failed_;
}

}  // namespace dpscope
