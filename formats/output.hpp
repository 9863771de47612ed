// A buffered text sink. Renderers format into buffer(); end_record() hands full buffers to the
// stream (at 64 KiB, or after every record when flushing per record, e.g. on a terminal).
#pragma once

#include <fmt/format.h>

#include <cstdio>
#include <string_view>

namespace dpscope {

class Output {
  public:
    explicit Output(FILE* file, bool flush_each_record = false)
        : file_(file), flush_each_record_(flush_each_record) {}
    ~Output() { flush(); }
    Output(const Output&) = delete;
    Output& operator=(const Output&) = delete;

    fmt::memory_buffer& buffer() noexcept { return buffer_; }
    void append(std::string_view text) { buffer_.append(text.data(), text.data() + text.size()); }
    void put(char c) { buffer_.push_back(c); }

    void end_record() {
        if (flush_each_record_ || buffer_.size() >= kFlushAt) flush();
    }
    bool flush();
    bool failed() const noexcept { return failed_; }
    void set_flush_each_record(bool on) noexcept { flush_each_record_ = on; }

  private:
    static constexpr std::size_t kFlushAt = 1 << 16;
    FILE* file_;
    fmt::memory_buffer buffer_;
    bool flush_each_record_;
    bool failed_ = false;
};

}  // namespace dpscope
