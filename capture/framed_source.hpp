// A telegram source over a byte stream split by the StreamFramer: raw dumps, hex logs, bytes in
// memory and serial ports share it. Subclasses feed bytes (fill); this class hands the framed
// telegrams out one by one with their stream offsets and times, and reports skipped bytes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "capture/telegram_source.hpp"
#include "decoder/stream_framer.hpp"

namespace dpscope {

class FramedSource : public TelegramSource, private StreamFramer::Sink {
  public:
    using TelegramSource::TelegramSource;

    // Blocks until a telegram is framed or the input ends.
    bool next(Record& record) override;

    enum class Poll { Telegram, Idle, End };
    // Like next(), but returns Idle when the input has nothing for now (live sources).
    Poll poll(Record& record);

    std::uint64_t bytes_skipped() const override { return framer_.bytes_skipped(); }

  protected:
    enum class Fill { Fed, Idle, End };
    // Feeds more input through feed(): Fed, Idle (nothing yet, a live source), End.
    virtual Fill fill() = 0;
    // The time of the telegram starting at stream offset `offset`.
    virtual std::int64_t time_at(std::uint64_t /*offset*/) { return kNoTime; }
    // Where `offset` is, in words a person can find in the input.
    virtual std::string where(std::uint64_t offset) const;

    void feed(Bytes bytes) { framer_.feed(bytes, *this); }
    // The line was idle: a telegram cannot continue across the gap.
    void mark_gap() { framer_.mark_gap(*this); }
    std::size_t pending_bytes() const noexcept { return framer_.pending(); }

  private:
    struct Entry {
        std::size_t start;
        std::size_t length;
        std::uint64_t offset;
        std::int64_t time_ns;
    };

    void on_telegram(Bytes telegram, std::uint64_t offset) override;
    void on_skipped(const SkippedBytes& skipped) override;

    StreamFramer framer_;
    std::vector<std::uint8_t> arena_;
    std::vector<Entry> entries_;
    std::size_t cursor_ = 0;
    bool finished_ = false;
    std::uint64_t number_ = 0;
};

}  // namespace dpscope
