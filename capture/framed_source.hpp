// A telegram source over a byte stream split by the StreamFramer with a protocol's framing rules
// (core/framing_rules.hpp): raw dumps, hex logs, bytes in memory and serial ports share it.
// Subclasses feed bytes (fill); this class hands the framed telegrams out one by one with their
// stream offsets and times, and reports skipped bytes in stream order with them (so nothing is
// reported about bytes after the last telegram handed out).
//
// A source that judges its input (judge_input) holds its telegrams back until it has decided
// `window` bytes of the stream, or the whole of a shorter input (or holds kMaxHeldEntries
// telegrams and messages): when more than half of at least kMinJudgedBytes of them form no
// telegram, the input is no stream of the rules' protocol and the source is Unusable, without
// handing anything out.
//
// Memory stays bounded whatever the input (buffered_bytes()): what one fill() feeds is framed and
// handed out before the next, and the messages of repeating issues that would only be counted
// (beyond kMaxIssuesShown of their kind) are never made: a run of them is one counted entry.
// A run of skipped bytes that goes on is noted as it grows (at 1 MiB, then 2, 4, 8 ... MiB), so
// that an input without telegrams (a forced --input-format raw on /dev/zero) is not read in
// silence.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "capture/telegram_source.hpp"
#include "core/stream_framer.hpp"

namespace dpscope {

class FramedSource : public TelegramSource, private StreamFramer::Sink {
  public:
    // `rules` must outlive the source (the protocols' rules are static: fdl_framing_rules()).
    FramedSource(std::string display_name, const FramingRules& rules)
        : TelegramSource(std::move(display_name)), framer_(rules) {}

    enum class Poll { Telegram, Idle, End };
    // Like next(), but returns Idle when the input has nothing for now (live sources).
    Poll poll(Record& record);

    // Skipped bytes reported so far (those before the last telegram handed out, or all at the end).
    std::uint64_t bytes_skipped() const override { return skipped_reported_; }
    // Telegrams framed from what fill() fed last and not yet handed out: what the source holds in
    // memory, bounded by what one fill() feeds.
    std::size_t telegrams_waiting() const noexcept { return entries_.size() - cursor_; }
    std::size_t buffered_bytes() const override;

    // A judged input needs at least this many bytes for a verdict.
    static constexpr std::uint64_t kMinJudgedBytes = 512;
    // A judged input is judged at the latest when this many telegrams and messages are held.
    static constexpr std::size_t kMaxHeldEntries = 16384;
    // The first note on a run of skipped bytes that goes on; the next at twice as many bytes.
    static constexpr std::uint64_t kFirstLongSkipNote = 1 << 20;
    // Judge the input over its first `window` bytes; `what` names it in the verdict ("byte
    // stream"), `forced` the option that reads it anyway ("--input-format raw").
    void judge_input(std::uint64_t window, std::string what, std::string forced) {
        judge_window_ = window;
        judged_ = window == 0;
        judged_what_ = std::move(what);
        judged_forced_ = std::move(forced);
    }

  protected:
    // Blocks until a telegram is framed or the input ends.
    bool read_next(Record& record) override;

    enum class Fill { Fed, Idle, End };
    // Feeds more input through feed(): Fed, Idle (nothing yet, a live source), End.
    virtual Fill fill() = 0;
    // The time of the telegram starting at stream offset `offset`.
    virtual std::int64_t time_at(std::uint64_t /*offset*/) { return kNoTime; }
    // Where `offset` is, in words a person can find in the input.
    virtual std::string where(std::uint64_t offset) const;
    // The memory of the subclass's own buffers (see buffered_bytes()).
    virtual std::size_t reader_bytes() const { return 0; }

    void feed(Bytes bytes) {
        framer_.feed(bytes, *this);
        note_long_skip();
    }
    // An issue reported in stream order with the telegrams framed so far; `bytes`: input bytes it
    // skipped (IssueKind::SkippedBytes, counted in bytes_skipped()).
    void defer_report(Severity severity, IssueKind kind, std::string message,
                      std::uint64_t bytes = 0);
    // Will the next issue of `kind` only be counted? Then its message is not needed: pass "".
    bool hides(IssueKind kind) const noexcept {
        return kind != IssueKind::Other &&
               deferred_[static_cast<std::size_t>(kind)] >= kMaxIssuesShown;
    }
    // The stream offset from which on the subclass still needs to place offsets (time_at, where):
    // the first byte not decided yet, or the start of the run of skipped bytes still going on.
    std::uint64_t oldest_needed_offset() const noexcept;
    // The line was idle: a telegram cannot continue across the gap.
    void mark_gap() { framer_.mark_gap(*this); }
    // A record the input delimits itself (a line of a hex capture), handed out as it is, in
    // stream order with the telegrams framed so far; not framed.
    void hand_out(Bytes record, std::uint64_t offset, std::int64_t time_ns);
    // The input is of a kind that is not judged (dpscope's own hex capture).
    void stop_judging() noexcept { judged_ = true; }
    std::size_t pending_bytes() const noexcept { return framer_.pending(); }

  private:
    struct Issue {
        Severity severity;
        IssueKind kind;
        std::uint64_t bytes;      // skipped bytes
        std::string message;      // "" for issues that are only counted
        std::uint64_t count = 1;  // issues only counted, coalesced into one entry
    };
    // A telegram (arena_[start, start + length)) or, when `issue` is set, issues_[start].
    struct Entry {
        std::size_t start;
        std::size_t length;
        std::uint64_t offset;
        std::int64_t time_ns;
        bool issue;
    };

    void on_telegram(Bytes telegram, std::uint64_t offset) override;
    void on_skipped(const SkippedBytes& skipped) override;
    // The verdict on a judged input once enough of it is decided; false: not a stream of the
    // protocol.
    bool judge();
    // Notes the run of skipped bytes still going on when it has grown past the next threshold.
    void note_long_skip();

    StreamFramer framer_;
    std::vector<std::uint8_t> arena_;
    std::vector<Issue> issues_;
    std::vector<Entry> entries_;
    std::size_t cursor_ = 0;
    bool finished_ = false;
    std::uint64_t number_ = 0;
    std::uint64_t skipped_reported_ = 0;
    std::uint64_t judge_window_ = 0;
    bool judged_ = true;
    std::string judged_what_;
    std::string judged_forced_;
    // Issues of each repeating kind deferred so far (to know which only count).
    std::uint64_t deferred_[kIssueKinds] = {};
    // The run of skipped bytes last noted, and the size at which it is noted next.
    std::uint64_t long_skip_offset_ = 0;
    std::uint64_t next_long_skip_note_ = kFirstLongSkipNote;
};

}  // namespace dpscope
