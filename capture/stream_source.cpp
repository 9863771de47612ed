#include "capture/stream_source.hpp"

#include <fmt/format.h>
#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <deque>
#include <optional>
#include <string_view>
#include <vector>

#include "capture/framed_source.hpp"
#include "capture/hex_log.hpp"

namespace dpscope {

namespace {
// "a PROFIBUS", "an FC protocol": the article a protocol's name takes ("FC" is read "eff").
std::string article_for(std::string_view protocol) {
    const bool vowel_sound =
        !protocol.empty() && (protocol[0] == 'F' || protocol[0] == 'A' || protocol[0] == 'E' ||
                              protocol[0] == 'I' || protocol[0] == 'O' || protocol[0] == 'U');
    return fmt::format("{} {}", vowel_sound ? "an" : "a", protocol);
}
}  // namespace

bool FramedSource::read_next(Record& record) {
    for (;;) {
        Poll result = poll(record);
        if (result == Poll::Telegram) return true;
        if (result == Poll::End) return false;
    }
}

FramedSource::Poll FramedSource::poll(Record& record) {
    for (;;) {
        while (cursor_ == entries_.size() || !judged_) {
            if (cursor_ == entries_.size()) {
                entries_.clear();
                arena_.clear();
                issues_.clear();
                cursor_ = 0;
                if (finished_) {
                    finish_reporting();
                    return Poll::End;
                }
            }
            Fill fill_result = fill();
            if (fill_result == Fill::End) {
                framer_.finish(*this);
                finished_ = true;
            }
            if (!judged_ && (finished_ || framer_.bytes_fed() >= judge_window_ ||
                             entries_.size() >= kMaxHeldEntries)) {
                judged_ = true;
                if (!judge()) {
                    entries_.clear();
                    cursor_ = 0;
                    finished_ = true;
                    return Poll::End;
                }
            }
            if (fill_result == Fill::Idle && (cursor_ == entries_.size() || !judged_))
                return Poll::Idle;
        }
        const Entry& entry = entries_[cursor_++];
        if (entry.issue) {
            Issue& issue = issues_[entry.start];
            if (issue.kind == IssueKind::SkippedBytes) skipped_reported_ += issue.bytes;
            if (issue.message.empty())
                count_hidden(issue.kind, issue.count, issue.bytes);
            else
                report(issue.severity, std::move(issue.message), issue.kind, issue.bytes);
            continue;
        }
        record.bytes = Bytes(arena_.data() + entry.start, entry.length);
        record.time_ns = entry.time_ns;
        record.number = ++number_;
        record.offset = entry.offset;
        record.original_length = static_cast<std::uint32_t>(entry.length);
        return Poll::Telegram;
    }
}

bool FramedSource::judge() {
    const std::uint64_t decided = framer_.bytes_fed() - framer_.pending();
    const std::uint64_t skipped = framer_.bytes_skipped();
    if (decided < kMinJudgedBytes || skipped * 2 <= decided) return true;
    set_unusable(fmt::format(
        "{}: not {} {}: {} of {} {} bytes ({:.1f} %) form no telegram; {} decodes it anyway{}{}",
        name(), article_for(framer_.rules().protocol_name()), judged_what_, skipped,
        finished_ ? "its" : "its first", decided,
        100.0 * static_cast<double>(skipped) / static_cast<double>(decided), judged_forced_,
        looks_like_text() ? "; " : "", looks_like_text() ? text_input_hint() : ""));
    return false;
}

std::size_t FramedSource::buffered_bytes() const {
    std::size_t messages = 0;
    for (const Issue& issue : issues_)
        messages += issue.message.capacity();
    return framer_.buffer_capacity() + arena_.capacity() + entries_.capacity() * sizeof(Entry) +
           issues_.capacity() * sizeof(Issue) + messages + reader_bytes();
}

std::string FramedSource::where(std::uint64_t offset) const {
    return fmt::format("byte offset {}", offset);
}

void FramedSource::defer_report(Severity severity, IssueKind kind, std::string message,
                                std::uint64_t bytes) {
    if (kind != IssueKind::Other) {
        const bool hidden = hides(kind);
        ++deferred_[static_cast<std::size_t>(kind)];
        if (hidden) {
            // Only counted: one entry for a run of them.
            if (cursor_ < entries_.size() && entries_.back().issue) {
                Issue& last = issues_[entries_.back().start];
                if (last.kind == kind && last.message.empty()) {
                    ++last.count;
                    last.bytes += bytes;
                    return;
                }
            }
            message.clear();
        }
    }
    entries_.push_back(Entry{issues_.size(), 0, 0, kNoTime, true});
    issues_.push_back(Issue{severity, kind, bytes, std::move(message)});
}

std::uint64_t FramedSource::oldest_needed_offset() const noexcept {
    const std::uint64_t undecided = framer_.bytes_fed() - framer_.pending();
    const SkippedBytes& run = framer_.skipping();
    return run.count > 0 ? std::min(run.offset, undecided) : undecided;
}

void FramedSource::note_long_skip() {
    const SkippedBytes& run = framer_.skipping();
    if (run.count == 0) return;
    if (run.offset != long_skip_offset_) {  // another run than the one noted last
        long_skip_offset_ = run.offset;
        next_long_skip_note_ = kFirstLongSkipNote;
    }
    if (run.count < next_long_skip_note_) return;
    while (next_long_skip_note_ <= run.count)
        next_long_skip_note_ *= 2;
    defer_report(Severity::Warning, IssueKind::Other,
                 fmt::format("{}: {}: {} MiB read so far without {} telegram; still reading "
                             "(the run of skipped bytes is reported where it ends)",
                             name(), where(run.offset), run.count >> 20,
                             article_for(framer_.rules().protocol_name())));
}

void FramedSource::hand_out(Bytes record, std::uint64_t offset, std::int64_t time_ns) {
    entries_.push_back(Entry{arena_.size(), record.size(), offset, time_ns, false});
    arena_.insert(arena_.end(), record.begin(), record.end());
}

void FramedSource::on_telegram(Bytes telegram, std::uint64_t offset) {
    entries_.push_back(Entry{arena_.size(), telegram.size(), offset, time_at(offset), false});
    arena_.insert(arena_.end(), telegram.begin(), telegram.end());
}

void FramedSource::on_skipped(const SkippedBytes& skipped) {
    if (hides(IssueKind::SkippedBytes)) {
        defer_report(Severity::Warning, IssueKind::SkippedBytes, {}, skipped.count);
        return;
    }
    defer_report(Severity::Warning, IssueKind::SkippedBytes,
                 fmt::format("{}: {}: {}", name(), where(skipped.offset),
                             framer_.rules().describe_skip(skipped)),
                 skipped.count);
}

// One getc() waits for data; what the stream's buffer then holds is taken without waiting again.
std::size_t read_available(FILE* file, std::uint8_t* data, std::size_t size) {
    int c = std::getc(file);
    if (c == EOF || size == 0) return 0;
    data[0] = static_cast<std::uint8_t>(c);
    auto held = static_cast<std::size_t>(file->_IO_read_end - file->_IO_read_ptr);  // glibc
    return 1 + std::fread(data + 1, 1, std::min(size - 1, held), file);
}

namespace {

class RawSource final : public FramedSource {
  public:
    RawSource(FILE* file, std::string name, const FramingRules& rules)
        : FramedSource(std::move(name), rules), file_(file) {
        struct stat info {};
        regular_ = fileno(file) >= 0 && ::fstat(fileno(file), &info) == 0 && S_ISREG(info.st_mode);
    }
    ~RawSource() override { std::fclose(file_); }
    InputFormat format() const override { return InputFormat::Raw; }
    bool looks_like_text() const override { return text_like_; }

  private:
    Fill fill() override {
        std::size_t got = regular_ ? std::fread(chunk_.data(), 1, chunk_.size(), file_)
                                   : read_available(file_, chunk_.data(), chunk_.size());
        if (got > 0) {
            if (offset_ == 0) text_like_ = dpscope::looks_like_text(Bytes(chunk_.data(), got));
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

    std::size_t reader_bytes() const override { return chunk_.capacity(); }

    FILE* file_;
    bool regular_ = false;  // a plain file: read whole chunks
    std::vector<std::uint8_t> chunk_ = std::vector<std::uint8_t>(1 << 16);
    std::uint64_t offset_ = 0;
    bool text_like_ = false;  // the first chunk looked like text
};

// Reads a hex log a piece at a time (capture/hex_log.hpp, kHexLogPieceChars): a line that fits
// whole, else pieces of whole tokens cut after a separator, and a token longer than a piece in
// parts. It holds one buffer of two pieces, whatever the length of a line.
class HexPieceReader {
  public:
    struct Piece {
        std::string_view text;     // valid until the next call
        bool token_part = false;   // a part of a token longer than a piece (LongHexToken)
        bool first = false;        // the line's first piece
        bool last = false;         // the line ends with it
        bool token_start = false;  // token_part: the token's first part
        bool token_end = false;    // token_part: the token ends with it
        std::uint64_t column = 0;  // characters of the line before the piece
    };

    explicit HexPieceReader(FILE* file) : file_(file) {
        struct stat info {};
        regular_ = fileno(file) >= 0 && ::fstat(fileno(file), &info) == 0 && S_ISREG(info.st_mode);
    }

    // The next piece; nullopt at the end of the input (std::ferror tells a read error).
    std::optional<Piece> next() {
        for (;;) {
            const std::string_view held(buffer_.data() + begin_, end_ - begin_);
            const std::size_t look = std::min(held.size(), kHexLogPieceChars + 1);
            if (in_token_) {
                std::size_t stop = 0;
                while (stop < look && !separator(held[stop]))
                    ++stop;
                if (stop < look) return token_part(stop, true, false);  // stop > 0 (see below)
                // A part is cut only with more of the token after it, so that none is empty.
                if (held.size() > kHexLogPieceChars)
                    return token_part(kHexLogPieceChars, false, false);
                if (at_end_) return token_part(held.size(), true, true);
            } else {
                const std::size_t line_end = held.substr(0, look).find('\n');
                if (line_end != std::string_view::npos) return line_piece(line_end, 1, true);
                if (held.size() > kHexLogPieceChars) {
                    // A long line: its tokens up to the last separator, or a long token.
                    std::size_t cut = kHexLogPieceChars;
                    while (cut > 0 && !separator(held[cut - 1]))
                        --cut;
                    if (cut > 0) return line_piece(cut, 0, false);
                    in_token_ = true;
                    token_start_ = true;
                    continue;
                }
                if (at_end_) {
                    in_line_ = false;
                    if (held.empty()) return std::nullopt;
                    return line_piece(held.size(), 0, true);
                }
            }
            if (!read_more()) at_end_ = true;
        }
    }

    std::size_t capacity() const noexcept { return buffer_.capacity(); }

  private:
    static bool separator(char c) {
        return c == ' ' || c == '\t' || c == '\r' || c == ',' || c == ';' || c == '\n';
    }

    Piece line_piece(std::size_t length, std::size_t skip, bool last) {
        Piece piece;
        piece.text = std::string_view(buffer_.data() + begin_, length);
        piece.first = !in_line_;
        piece.last = last;
        piece.column = column_;
        advance(length + skip, last);
        return piece;
    }

    Piece token_part(std::size_t length, bool token_end, bool line_end) {
        Piece piece;
        piece.text = std::string_view(buffer_.data() + begin_, length);
        piece.token_part = true;
        piece.first = !in_line_;
        piece.last = line_end;
        piece.token_start = token_start_;
        piece.token_end = token_end;
        piece.column = column_;
        token_start_ = false;
        if (token_end) in_token_ = false;
        advance(length, line_end);
        return piece;
    }

    void advance(std::size_t length, bool line_end) {
        begin_ += length;
        column_ = line_end ? 0 : column_ + length;
        in_line_ = !line_end;
    }

    // Moves what is held to the buffer's start and reads more after it; false at the end.
    bool read_more() {
        if (begin_ > 0) {
            std::memmove(buffer_.data(), buffer_.data() + begin_, end_ - begin_);
            end_ -= begin_;
            begin_ = 0;
        }
        auto* room = reinterpret_cast<std::uint8_t*>(buffer_.data() + end_);
        const std::size_t size = buffer_.size() - end_;
        const std::size_t got =
            regular_ ? std::fread(room, 1, size, file_) : read_available(file_, room, size);
        end_ += got;
        return got > 0;
    }

    FILE* file_;
    bool regular_ = false;
    // Room for two pieces: a read is made only when at most one piece is held.
    std::vector<char> buffer_ = std::vector<char>(2 * kHexLogPieceChars + 1);
    std::size_t begin_ = 0;
    std::size_t end_ = 0;
    bool at_end_ = false;
    bool in_line_ = false;      // a line has begun and not ended
    bool in_token_ = false;     // inside a token longer than a piece
    bool token_start_ = false;  // its next part is its first
    std::uint64_t column_ = 0;
};

class HexSource final : public FramedSource {
  public:
    HexSource(FILE* file, std::string name, const FramingRules& rules,
              std::uint64_t max_repeat_bytes)
        : FramedSource(std::move(name), rules),
          file_(file),
          reader_(file),
          max_repeat_bytes_(std::clamp<std::uint64_t>(max_repeat_bytes, 1, kMaxHexRepeatBytes)) {}
    ~HexSource() override { std::fclose(file_); }
    InputFormat format() const override { return InputFormat::Hex; }

  private:
    struct Line {
        std::uint64_t start;   // stream offset of the line's first byte
        std::uint64_t number;  // 1-based line number in the file
        std::int64_t time_ns;
    };

    // One line (or piece of a long line) per call, so typed input is decoded as soon as a
    // telegram is complete; what a "*" line stands for, one chunk per call, so that the telegrams
    // framed from it are handed out before the next chunk is framed (a 1 KiB dump may stand for
    // many MiB).
    Fill fill() override {
        for (;;) {
            if (repeat_left_ > 0) {
                feed_repeat_chunk();
                return Fill::Fed;
            }
            if (held_) {
                held_ = false;
                if (held_line_.byte_count == 0 && !held_line_.error) continue;
                feed_line(held_line_);
                return Fill::Fed;
            }
            std::optional<HexPieceReader::Piece> piece = reader_.next();
            if (!piece) {
                if (std::ferror(file_)) {
                    set_status(InputStatus::Damaged);
                    report(Severity::Error, fmt::format("{}: line {}: read error: {}", name(),
                                                        line_number_ + 1, std::strerror(errno)));
                }
                return Fill::End;
            }
            if (piece->first) {
                ++line_number_;
                line_entered_ = false;
                line_time_ = kNoTime;
                text_without_bytes_ = 0;
                next_text_note_ = kFirstLongSkipNote;
            }
            bytes_.clear();
            HexLogLine parsed;
            std::string_view text = piece->text;
            // A byte order mark starts the text, not the first line's time stamp.
            if (line_number_ == 1 && piece->first && text.starts_with(kUtf8Bom))
                text.remove_prefix(kUtf8Bom.size());
            if (line_number_ == 1 && piece->first && is_hex_capture_header(text)) {
                // dpscope's own hex capture: one record a line, nothing to judge.
                records_ = true;
                stop_judging();
                continue;
            }
            if (piece->token_part) {
                parsed = long_token_.part(text, piece->token_start, piece->token_end, bytes_);
            } else if (piece->first && piece->last && !records_) {
                while (!text.empty() && text.back() == '\r')
                    text.remove_suffix(1);
                parsed = parse_hex_log_line(text, bytes_);
            } else {
                parsed = parse_hex_log_line(text, bytes_,
                                            piece->first ? LinePiece::First : LinePiece::Later);
            }
            if (parsed.error) parsed.error->column += piece->column;
            if (piece->first)
                line_time_ = parsed.time_ns ? *parsed.time_ns
                                            : parse_leading_timestamp(text).value_or(kNoTime);
            if (records_) {
                if (take_record_piece(parsed, piece->last)) return Fill::Fed;
                continue;
            }
            if (parsed.repeat_marker) {
                repeat_pending_ = true;
                continue;
            }
            if (parsed.dump_offset && start_repeat(*parsed.dump_offset)) {
                // The line's own bytes (in bytes_) come after the repeats.
                held_line_ = std::move(parsed);
                held_ = true;
                continue;
            }
            const bool noted = note_text_without_bytes(piece->text.size(), parsed.byte_count);
            if (parsed.byte_count == 0 && !parsed.error) {
                if (noted) return Fill::Fed;  // the note is handed out now
                continue;
            }
            feed_line(parsed);
            return Fill::Fed;
        }
    }

    // A piece of a line of a hex capture (records_): its bytes join the line's record, which is
    // handed out whole when the line ends (a line with no byte and no time is none). True when
    // something was handed out or reported.
    bool take_record_piece(const HexLogLine& parsed, bool line_end) {
        bool told = false;
        if (parsed.error) {
            report_bad_record(parsed);
            told = true;
        }
        const std::size_t room = kMaxHexRecordBytes - std::min(record_.size(), kMaxHexRecordBytes);
        if (bytes_.size() > room && !record_cut_) {
            record_cut_ = true;
            defer_report(Severity::Warning, IssueKind::Other,
                         fmt::format("{}: line {}: the record is longer than {} bytes; the rest "
                                     "of the line is left out",
                                     name(), line_number_, kMaxHexRecordBytes));
            told = true;
        }
        record_.insert(record_.end(), bytes_.begin(),
                       bytes_.begin() + static_cast<std::ptrdiff_t>(std::min(bytes_.size(), room)));
        record_error_ = record_error_ || parsed.error.has_value();
        if (!line_end) return told;
        if (!record_.empty() || record_error_ || line_time_ != kNoTime) {
            hand_out(Bytes(record_.data(), record_.size()), stream_offset_, line_time_);
            stream_offset_ += record_.size();
            told = true;
        }
        record_.clear();
        record_error_ = false;
        record_cut_ = false;
        return told;
    }

    void report_bad_record(const HexLogLine& parsed) {
        if (hides(IssueKind::HexSyntax)) {
            defer_report(Severity::Warning, IssueKind::HexSyntax, {});
            return;
        }
        defer_report(Severity::Warning, IssueKind::HexSyntax,
                     fmt::format("{}: line {}, column {}: '{}' {}; the line's record is read "
                                 "without it",
                                 name(), line_number_, parsed.error->column,
                                 shown_token(parsed.error->token), parsed.error->what));
    }

    // A long stretch of a line without a hex byte (a forced hex reading of a binary file, or of
    // /dev/zero) is noted as it grows, at 1 MiB, 2, 4 ... MiB; true when noted.
    bool note_text_without_bytes(std::size_t characters, std::size_t bytes) {
        if (bytes > 0) {
            text_without_bytes_ = 0;
            next_text_note_ = kFirstLongSkipNote;
            return false;
        }
        text_without_bytes_ += characters;
        if (text_without_bytes_ < next_text_note_) return false;
        while (next_text_note_ <= text_without_bytes_)
            next_text_note_ *= 2;
        defer_report(Severity::Warning, IssueKind::Other,
                     fmt::format("{}: line {}: {} MiB of text read so far without a hex byte; "
                                 "still reading",
                                 name(), line_number_, text_without_bytes_ >> 20));
        return true;
    }

    void feed_line(const HexLogLine& parsed) {
        if (!line_entered_) {
            // Lines before the oldest offset still to be placed are no longer needed.
            const std::uint64_t needed = oldest_needed_offset();
            while (lines_.size() > 1 && lines_[1].start <= needed)
                lines_.pop_front();
            lines_.push_back(Line{stream_offset_, line_number_, line_time_});
            line_entered_ = true;
        }
        // Bytes on either side of a bad token do not belong to one telegram.
        std::size_t from = 0;
        for (std::size_t at : parsed.breaks) {
            feed_line_bytes(from, at);
            from = at;
            if (at == parsed.breaks.front() && parsed.error) report_bad_line(parsed);
            mark_gap();
        }
        feed_line_bytes(from, bytes_.size());
        if (parsed.dump_offset) {
            last_dump_bytes_.assign(bytes_.begin(), bytes_.end());
            dump_next_ = *parsed.dump_offset + bytes_.size();
            have_dump_ = true;
        }
    }

    void feed_line_bytes(std::size_t from, std::size_t to) {
        if (to <= from) return;
        feed(Bytes(bytes_.data() + from, to - from));
        stream_offset_ += to - from;
    }

    void report_bad_line(const HexLogLine& parsed) {
        if (hides(IssueKind::HexSyntax)) {
            defer_report(Severity::Warning, IssueKind::HexSyntax, {});
            return;
        }
        std::string more;
        if (parsed.bad_tokens > 1)
            more = fmt::format("; {} more bad {} on the line", parsed.bad_tokens - 1,
                               parsed.bad_tokens == 2 ? "token" : "tokens");
        defer_report(Severity::Warning, IssueKind::HexSyntax,
                     fmt::format("{}: line {}, column {}: '{}' {}{}; the bytes before and after "
                                 "it are framed apart",
                                 name(), line_number_, parsed.error->column,
                                 shown_token(parsed.error->token), parsed.error->what, more));
    }

    // A dump line at `offset`: after a "*", the lines left out repeat the one before the "*" up
    // to this offset, and true says they are to be fed first (feed_repeat_chunk). An offset that
    // does not follow on is reported.
    bool start_repeat(std::uint64_t offset) {
        const bool repeat = repeat_pending_;
        repeat_pending_ = false;
        if (!have_dump_ || offset == dump_next_) return false;
        if (!repeat || last_dump_bytes_.empty() || offset < dump_next_ ||
            offset - dump_next_ > max_repeat_bytes_) {
            defer_report(Severity::Warning, IssueKind::HexSyntax,
                         fmt::format("{}: line {}: the dump's offset is 0x{:x}, but 0x{:x} bytes "
                                     "came before it{}; lines are missing or out of order",
                                     name(), line_number_, offset, dump_next_,
                                     repeat ? " (counting the lines \"*\" stands for)" : ""));
            mark_gap();
            return false;
        }
        repeat_left_ = offset - dump_next_;
        repeat_line_ = line_number_ - 1;
        dump_next_ = offset;
        return true;
    }

    // The next 64 KiB or so of what the "*" stands for: whole copies of the line before it (the
    // last copy cut short at the offset), so that every chunk starts where the line starts.
    void feed_repeat_chunk() {
        repeated_.clear();
        while (repeat_left_ > 0 && repeated_.size() < kRepeatChunkBytes) {
            std::size_t n = static_cast<std::size_t>(
                std::min<std::uint64_t>(repeat_left_, last_dump_bytes_.size()));
            repeated_.insert(repeated_.end(), last_dump_bytes_.begin(),
                             last_dump_bytes_.begin() + static_cast<std::ptrdiff_t>(n));
            repeat_left_ -= n;
        }
        lines_.push_back(Line{stream_offset_, repeat_line_, kNoTime});
        feed(Bytes(repeated_.data(), repeated_.size()));
        stream_offset_ += repeated_.size();
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

    std::size_t reader_bytes() const override {
        return reader_.capacity() + bytes_.capacity() + record_.capacity() +
               lines_.size() * sizeof(Line) + last_dump_bytes_.capacity() + repeated_.capacity() +
               held_line_.breaks.capacity() * sizeof(std::size_t);
    }

    std::string where(std::uint64_t offset) const override {
        const Line* line = line_of(offset);
        if (!line) return fmt::format("byte {}", offset);
        return fmt::format("line {} (byte {} of the decoded stream)", line->number, offset);
    }

    FILE* file_;
    HexPieceReader reader_;
    LongHexToken long_token_;
    std::uint64_t line_number_ = 0;
    bool line_entered_ = false;  // the line has its entry in lines_
    std::int64_t line_time_ = kNoTime;
    std::uint64_t text_without_bytes_ = 0;  // characters of the line since its last hex byte
    std::uint64_t next_text_note_ = kFirstLongSkipNote;
    // A hex capture written by dpscope: one record a line (hex_log.hpp, kHexCaptureHeader).
    static constexpr std::size_t kMaxHexRecordBytes = 65535;  // as a pcap's snapshot length
    bool records_ = false;
    std::vector<std::uint8_t> record_;  // the line's record so far
    bool record_error_ = false;         // the line has a bad token
    bool record_cut_ = false;           // the line's record was cut at kMaxHexRecordBytes
    std::uint64_t stream_offset_ = 0;
    std::vector<std::uint8_t> bytes_;
    std::deque<Line> lines_;
    // xxd and hexdump -C dumps: the last line's bytes, the offset expected next, a pending "*".
    std::vector<std::uint8_t> last_dump_bytes_;
    std::uint64_t dump_next_ = 0;
    bool have_dump_ = false;
    bool repeat_pending_ = false;
    // What a "*" stands for, fed a chunk a call: the bytes still to come, the "*" line's number,
    // the chunk, and the dump line after the "*", held until they are fed.
    static constexpr std::size_t kRepeatChunkBytes = 1 << 16;
    std::uint64_t max_repeat_bytes_;
    std::uint64_t repeat_left_ = 0;
    std::uint64_t repeat_line_ = 0;
    std::vector<std::uint8_t> repeated_;
    HexLogLine held_line_;
    bool held_ = false;
};

class MemorySource final : public FramedSource {
  public:
    MemorySource(std::string name, Bytes bytes, const FramingRules& rules)
        : FramedSource(std::move(name), rules), bytes_(bytes.begin(), bytes.end()) {}
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

std::unique_ptr<TelegramSource> make_raw_source(FILE* file, std::string name, bool judged,
                                                const FramingRules& rules) {
    auto source = std::make_unique<RawSource>(file, std::move(name), rules);
    if (judged) source->judge_input(kJudgedRawBytes, "byte stream", "--input-format raw");
    return source;
}

std::unique_ptr<TelegramSource> make_hex_source(FILE* file, std::string name, bool judged,
                                                const FramingRules& rules,
                                                std::uint64_t max_repeat_bytes) {
    auto source = std::make_unique<HexSource>(file, std::move(name), rules, max_repeat_bytes);
    if (judged) source->judge_input(kJudgedHexBytes, "hex log", "--input-format hex");
    return source;
}

std::unique_ptr<TelegramSource> make_memory_source(std::string name, Bytes bytes,
                                                   const FramingRules& rules) {
    return std::make_unique<MemorySource>(std::move(name), bytes, rules);
}

}  // namespace dpscope
