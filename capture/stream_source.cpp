#include "capture/stream_source.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <deque>
#include <vector>

#include "capture/framed_source.hpp"
#include "capture/hex_log.hpp"
#include "decoder/stream_framer.hpp"

namespace dpscope {

namespace {}  // namespace

bool FramedSource::next(Record& record) {
    for (;;) {
        Poll result = poll(record);
        if (result == Poll::Telegram) return true;
        if (result == Poll::End) return false;
    }
}

FramedSource::Poll FramedSource::poll(Record& record) {
    while (cursor_ == entries_.size()) {
        entries_.clear();
        arena_.clear();
        cursor_ = 0;
        if (finished_) return Poll::End;
        Fill fill_result = fill();
        if (fill_result == Fill::End) {
            framer_.finish(*this);
            finished_ = true;
        } else if (fill_result == Fill::Idle && cursor_ == entries_.size()) {
            return Poll::Idle;
        }
    }
    const Entry& entry = entries_[cursor_++];
    record.bytes = Bytes(arena_.data() + entry.start, entry.length);
    record.time_ns = entry.time_ns;
    record.number = ++number_;
    record.offset = entry.offset;
    record.original_length = static_cast<std::uint32_t>(entry.length);
    return Poll::Telegram;
}

std::string FramedSource::where(std::uint64_t offset) const {
    return fmt::format("byte offset {}", offset);
}

void FramedSource::on_telegram(Bytes telegram, std::uint64_t offset) {
    entries_.push_back(Entry{arena_.size(), telegram.size(), offset, time_at(offset)});
    arena_.insert(arena_.end(), telegram.begin(), telegram.end());
}

void FramedSource::on_skipped(const SkippedBytes& skipped) {
    report(Severity::Warning,
           fmt::format("{}: {}: {}", name(), where(skipped.offset), describe_skip(skipped)));
}

namespace {

class RawSource final : public FramedSource {
  public:
    RawSource(FILE* file, std::string name) : FramedSource(std::move(name)), file_(file) {}
    ~RawSource() override { std::fclose(file_); }
    InputFormat format() const override { return InputFormat::Raw; }

  private:
    Fill fill() override {
        std::size_t got = std::fread(chunk_.data(), 1, chunk_.size(), file_);
        if (got > 0) {
            feed(Bytes(chunk_.data(), got));
            offset_ += got;
            return Fill::Fed;
        }
        if (std::ferror(file_)) {
            set_status(InputStatus::Damaged);
            report(Severity::Error, fmt::format("{}: byte offset {}: read error: {}", name(),
                                                offset_, std::strerror(errno)));
        }
        return Fill::End;
    }

    FILE* file_;
    std::vector<std::uint8_t> chunk_ = std::vector<std::uint8_t>(1 << 16);
    std::uint64_t offset_ = 0;
};

class HexSource final : public FramedSource {
  public:
    HexSource(FILE* file, std::string name) : FramedSource(std::move(name)), file_(file) {}
    ~HexSource() override {
        std::free(line_);
        std::fclose(file_);
    }
    InputFormat format() const override { return InputFormat::Hex; }

  private:
    struct Line {
        std::uint64_t start;   // stream offset of the line's first byte
        std::uint64_t number;  // 1-based line number in the file
        std::int64_t time_ns;
    };

    // One line per call, so typed input is decoded as soon as a telegram is complete.
    Fill fill() override {
        for (;;) {
            ssize_t length = getline(&line_, &capacity_, file_);
            if (length < 0) {
                if (std::ferror(file_)) {
                    set_status(InputStatus::Damaged);
                    report(Severity::Error, fmt::format("{}: line {}: read error: {}", name(),
                                                        line_number_ + 1, std::strerror(errno)));
                }
                return Fill::End;
            }
            ++line_number_;
            std::string_view text(line_, static_cast<std::size_t>(length));
            while (!text.empty() && (text.back() == '\n' || text.back() == '\r'))
                text.remove_suffix(1);
            bytes_.clear();
            HexLogLine parsed = parse_hex_log_line(text, bytes_);
            if (parsed.byte_count == 0) continue;
            lines_.push_back(Line{stream_offset_, line_number_, parsed.time_ns.value_or(kNoTime)});
            feed(Bytes(bytes_.data(), bytes_.size()));
            stream_offset_ += bytes_.size();
            return Fill::Fed;
        }
    }

    const Line* line_of(std::uint64_t offset) const {
        const Line* found = nullptr;
        for (const Line& line : lines_) {
            if (line.start > offset) break;
            found = &line;
        }
        return found;
    }

    std::int64_t time_at(std::uint64_t offset) override {
        // Telegrams come in stream order: lines wholly before this one are no longer needed.
        while (lines_.size() > 1 && lines_[1].start <= offset)
            lines_.pop_front();
        const Line* line = line_of(offset);
        return line ? line->time_ns : kNoTime;
    }

    std::string where(std::uint64_t offset) const override {
        const Line* line = line_of(offset);
        if (!line) return fmt::format("byte {}", offset);
        return fmt::format("line {} (byte {} of the decoded stream)", line->number, offset);
    }

    FILE* file_;
    char* line_ = nullptr;
    std::size_t capacity_ = 0;
    std::uint64_t line_number_ = 0;
    std::uint64_t stream_offset_ = 0;
    std::vector<std::uint8_t> bytes_;
    std::deque<Line> lines_;
};

class MemorySource final : public FramedSource {
  public:
    MemorySource(std::string name, Bytes bytes)
        : FramedSource(std::move(name)), bytes_(bytes.begin(), bytes.end()) {}
    InputFormat format() const override { return InputFormat::Hex; }

  private:
    Fill fill() override {
        if (done_) return Fill::End;
        done_ = true;
        feed(Bytes(bytes_.data(), bytes_.size()));
        return Fill::Fed;
    }
    std::string where(std::uint64_t offset) const override {
        return fmt::format("byte {}", offset);
    }

    std::vector<std::uint8_t> bytes_;
    bool done_ = false;
};

}  // namespace

std::unique_ptr<TelegramSource> make_raw_source(FILE* file, std::string name) {
    return std::make_unique<RawSource>(file, std::move(name));
}

std::unique_ptr<TelegramSource> make_hex_source(FILE* file, std::string name) {
    return std::make_unique<HexSource>(file, std::move(name));
}

std::unique_ptr<TelegramSource> make_memory_source(std::string name, Bytes bytes) {
    return std::make_unique<MemorySource>(std::move(name), bytes);
}

}  // namespace dpscope
