#include "capture/text_log.hpp"

#include <fmt/format.h>
#include <sys/stat.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <optional>
#include <vector>

#include "capture/framed_source.hpp"
#include "capture/hex_log.hpp"
#include "capture/stream_source.hpp"
#include "protocols/vlt2000/vlt2000_telegram.hpp"

namespace dpscope {

namespace {

bool printable(std::uint8_t c) { return c >= 0x20 && c <= 0x7E; }

class TextLogSource final : public FramedSource {
  public:
    TextLogSource(FILE* file, std::string name, const FramingRules& rules, std::string line_word,
                  std::unique_ptr<std::string> text = nullptr)
        : FramedSource(std::move(name), rules),
          text_(std::move(text)),
          file_(file),
          rules_(rules),
          line_word_(std::move(line_word)) {
        struct stat info {};
        regular_ = fileno(file) >= 0 && ::fstat(fileno(file), &info) == 0 && S_ISREG(info.st_mode);
    }
    ~TextLogSource() override { std::fclose(file_); }
    InputFormat format() const override { return InputFormat::Text; }

  private:
    enum class Broken { LineEnd, InputEnd, NotPrintable, NoStop };

    Fill fill() override {
        const std::size_t got = regular_ ? std::fread(chunk_.data(), 1, chunk_.size(), file_)
                                         : read_available(file_, chunk_.data(), chunk_.size());
        if (got == 0) {
            if (std::ferror(file_)) {
                set_status(InputStatus::Damaged);
                report(Severity::Error, fmt::format("{}: {} {}: read error: {}", name(), line_word_,
                                                    line_, std::strerror(errno)));
            }
            while (pending_size_ > 0)
                broken(Broken::InputEnd);
            return Fill::End;
        }
        std::size_t from = 0;
        if (!started_) {
            // A byte order mark starts the text, not the first line's time stamp.
            started_ = true;
            if (without_bom(Bytes(chunk_.data(), got)).size() < got) from = kUtf8Bom.size();
        }
        for (std::size_t i = from; i < got; ++i)
            take(chunk_[i]);
        return Fill::Fed;
    }

    // A long stretch of text without a telegram (a forced text reading of a binary file, or of
    // /dev/zero) is noted as it grows, at 1 MiB, 2, 4 ... MiB, as a raw stream's run of skipped
    // bytes is (FramedSource::note_long_skip).
    void note_text_without_telegram() {
        next_text_note_ *= 2;
        defer_report(Severity::Warning, IssueKind::Other,
                     fmt::format("{}: {} {}: {} MiB of text read since {} {} without a {} "
                                 "telegram; still reading",
                                 name(), line_word_, line_, text_without_telegram_ >> 20,
                                 line_word_, text_start_line_, rules_.protocol_name()));
    }

    void take(std::uint8_t c) {
        if (++text_without_telegram_ >= next_text_note_) note_text_without_telegram();
        if (c == '\n') {
            while (pending_size_ > 0)
                broken(Broken::LineEnd);
            ++line_;
            column_ = 0;
            prefix_.clear();
            prefix_done_ = false;
            line_time_ = kNoTime;
            return;
        }
        ++column_;
        if (c == '\r' && pending_size_ > 0) {
            // CR LF: the line ends here for a telegram still open.
            while (pending_size_ > 0)
                broken(Broken::LineEnd);
        } else if (pending_size_ > 0) {
            append(c);
        } else if (c == kVlt2000Start) {
            start(column_);
        } else if (!prefix_done_ && prefix_.size() < kTextLogPrefixChars) {
            prefix_.push_back(static_cast<char>(c));
        }
    }

    void start(std::uint64_t column) {
        if (!prefix_done_) {
            prefix_done_ = true;
            line_time_ = parse_leading_timestamp(prefix_).value_or(kNoTime);
        }
        pending_[0] = kVlt2000Start;
        pending_size_ = 1;
        pending_column_ = column;
    }

    void append(std::uint8_t c) {
        pending_[pending_size_++] = c;
        if (!printable(c)) {
            broken(Broken::NotPrintable);
        } else if (pending_size_ == kVlt2000TelegramSize) {
            if (c == kVlt2000Stop)
                emit();
            else
                broken(Broken::NoStop);
        }
    }

    // A whole telegram: framed alone, so nothing continues across the text around it.
    void emit() {
        current_line_ = line_;
        current_column_ = pending_column_;
        current_start_ = stream_offset_;
        // The line's time stamp is its first telegram's: a later one on the same line came after
        // it by a time the log does not say, so it has no time of its own (no reply time is
        // measured from or to it; docs/decisions.md).
        current_time_ = line_time_;
        line_time_ = kNoTime;
        feed(Bytes(pending_.data(), pending_size_));
        stream_offset_ += pending_size_;
        pending_size_ = 0;
        mark_gap();
        // A new stretch of text starts after the telegram.
        text_without_telegram_ = 0;
        text_start_line_ = line_;
        next_text_note_ = kFirstLongSkipNote;
    }

    // The candidate in pending_ is no telegram: reported, and its characters after the '<'
    // looked at again (another '<' among them may start one).
    void broken(Broken why) {
        std::size_t next_start = 0;
        for (std::size_t i = 1; i < pending_size_ && next_start == 0; ++i)
            if (pending_[i] == kVlt2000Start) next_start = i;
        const std::size_t skipped = next_start != 0 ? next_start : pending_size_;
        if (hides(IssueKind::SkippedBytes))
            defer_report(Severity::Warning, IssueKind::SkippedBytes, {}, skipped);
        else
            report_broken(why, skipped, next_start);
        // The characters after the '<' again, from the next '<' on (none before it starts one).
        const std::size_t size = pending_size_;
        const std::uint64_t column = pending_column_;
        std::array<std::uint8_t, kVlt2000TelegramSize> rest{};
        std::copy(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(size),
                  rest.begin());
        pending_size_ = 0;
        if (next_start == 0) return;
        for (std::size_t i = next_start; i < size; ++i) {
            if (pending_size_ > 0)
                append(rest[i]);
            else if (rest[i] == kVlt2000Start)
                start(column + i);
        }
    }

    void report_broken(Broken why, std::size_t skipped, std::size_t next_start) {
        std::string shown;
        for (std::size_t i = 0; i < pending_size_; ++i) {
            const std::uint8_t c = pending_[i];
            if (printable(c) && c != '\'' && c != '\\')
                shown.push_back(static_cast<char>(c));
            else
                shown += fmt::format("\\x{:02X}", c);
        }
        std::string reason;
        switch (why) {
            case Broken::LineEnd:
                reason = fmt::format("the {} ends after {} of its {} characters", line_word_,
                                     pending_size_, kVlt2000TelegramSize);
                break;
            case Broken::InputEnd:
                reason = fmt::format("the input ends after {} of its {} characters", pending_size_,
                                     kVlt2000TelegramSize);
                break;
            case Broken::NotPrintable:
                reason = fmt::format("character {} is 0x{:02X}, not printable ASCII", pending_size_,
                                     pending_[pending_size_ - 1]);
                break;
            case Broken::NoStop:
                reason = fmt::format("its {}nd character is '{}', not '>'", kVlt2000TelegramSize,
                                     static_cast<char>(pending_[pending_size_ - 1]));
                break;
        }
        if (next_start != 0)
            reason += fmt::format("; another '<' at column {}", pending_column_ + next_start);
        defer_report(Severity::Warning, IssueKind::SkippedBytes,
                     fmt::format("{}: {} {}, column {}: skipped {} {}: '{}' is no {} telegram: {}",
                                 name(), line_word_, line_, pending_column_, skipped,
                                 skipped == 1 ? "character" : "characters", shown,
                                 rules_.protocol_name(), reason),
                     skipped);
    }

    std::int64_t time_at(std::uint64_t /*offset*/) override { return current_time_; }
    std::size_t reader_bytes() const override { return chunk_.capacity() + prefix_.capacity(); }

    std::string where(std::uint64_t offset) const override {
        return fmt::format("{} {}, column {}", line_word_, current_line_,
                           current_column_ + (offset - current_start_));
    }

    std::unique_ptr<std::string> text_;  // the buffer file_ reads, if the source holds it
    FILE* file_;
    const FramingRules& rules_;
    std::string line_word_;  // what messages call a line: "line", "argument"
    bool regular_ = false;
    bool started_ = false;  // the first chunk was read
    std::vector<std::uint8_t> chunk_ = std::vector<std::uint8_t>(1 << 16);
    std::uint64_t line_ = 1;
    std::uint64_t column_ = 0;  // of the last character taken, 1-based
    std::string prefix_;        // the line's text before its first '<' (bounded)
    bool prefix_done_ = false;
    std::int64_t line_time_ = kNoTime;
    std::array<std::uint8_t, kVlt2000TelegramSize> pending_{};
    std::size_t pending_size_ = 0;
    std::uint64_t pending_column_ = 0;
    std::uint64_t stream_offset_ = 0;  // telegram bytes fed so far
    // The telegram being framed: where it is in the text, its stream offset and time.
    std::uint64_t current_line_ = 0;
    std::uint64_t current_column_ = 0;
    std::uint64_t current_start_ = 0;
    std::int64_t current_time_ = kNoTime;
    // Characters read since the last telegram, from the line it ended on.
    std::uint64_t text_without_telegram_ = 0;
    std::uint64_t text_start_line_ = 1;
    std::uint64_t next_text_note_ = kFirstLongSkipNote;
};

}  // namespace

std::unique_ptr<TelegramSource> make_text_source(FILE* file, std::string name,
                                                 const FramingRules& rules) {
    return std::make_unique<TextLogSource>(file, std::move(name), rules, "line");
}

OpenResult make_memory_text_source(std::string name, std::string_view text,
                                   const FramingRules& rules, std::string line_word) {
    // A read-only stream over a copy the source holds (fmemopen takes no empty buffer: an empty
    // text reads as one empty line).
    auto copy = std::make_unique<std::string>(text.empty() ? std::string_view("\n") : text);
    FILE* file = fmemopen(copy->data(), copy->size(), "r");
    if (!file)
        return Error{fmt::format("{}: cannot set up reading: {}", name, std::strerror(errno))};
    return std::unique_ptr<TelegramSource>(std::make_unique<TextLogSource>(
        file, std::move(name), rules, std::move(line_word), std::move(copy)));
}

}  // namespace dpscope
