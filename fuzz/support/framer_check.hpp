// What the three framer targets (fuzz_fdl_framer, fuzz_fc_framer, fuzz_vlt2000_framer) share:
// they feed a StreamFramer in chunks whose sizes the input's first two bytes choose, mark line
// gaps where those bytes say, finish, and check what the framer handed out against the stream:
//   - every telegram and every skipped run starts where the one before ended (offsets strictly
//     increasing and contiguous), and together they cover every byte fed, once;
//   - a telegram holds the stream's bytes at its offset, starts with a byte the rules accept as a
//     start, has a length the protocol allows, and the rules alone judge it (at the end of the
//     input) a telegram of the same length;
//   - the framer's counters agree (telegrams, bytes skipped, bytes fed) and nothing is pending
//     after a gap or the finish.
// A violation aborts with the check's text (libFuzzer reports it as a crash).
//
// Input layout: byte 0 holds four 2-bit chunk-size codes, used in turn (0: 1 byte, 1: 3 bytes,
// 2: 1 + byte 1's low 4 bits, 3: 64 bytes); byte 1's high 4 bits N (0: never) mark a line gap
// after every N-th chunk. The rest is the byte stream.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "core/framing_rules.hpp"
#include "core/stream_framer.hpp"
#include "fuzz/support/fuzz_input.hpp"

namespace dpscope::fuzz {

// Aborts with `what` when `ok` is false (in the replay build too, so a corpus test fails).
inline void framer_check(bool ok, const char* what) {
    if (ok) return;
    std::fprintf(stderr, "framer invariant violated: %s\n", what);
    std::abort();
}

class CheckingFramingSink final : public FramingSink {
  public:
    CheckingFramingSink(const FramingRules& rules, bool (*length_ok)(std::size_t),
                        Bytes stream) noexcept
        : rules_(rules), length_ok_(length_ok), stream_(stream) {}

    void on_telegram(Bytes telegram, std::uint64_t offset) override {
        framer_check(offset == next_, "a telegram starts where the last record ended");
        framer_check(!telegram.empty(), "a telegram has bytes");
        framer_check(offset + telegram.size() <= stream_.size(), "a telegram lies in the stream");
        framer_check(std::memcmp(telegram.data(), stream_.data() + offset, telegram.size()) == 0,
                     "a telegram holds the stream's bytes at its offset");
        framer_check(rules_.can_start(telegram[0]), "a telegram starts with a start byte");
        framer_check(length_ok_(telegram.size()), "a telegram's length is one the protocol has");
        const FramingVerdict verdict = rules_.judge(telegram, true);
        framer_check(verdict.status == FramingStatus::Telegram && verdict.length == telegram.size(),
                     "the rules alone judge a telegram a telegram of its length");
        next_ += telegram.size();
        ++telegrams_;
    }
    void on_skipped(const SkippedBytes& skipped) override {
        framer_check(skipped.offset == next_, "a skipped run starts where the last record ended");
        framer_check(skipped.count > 0, "a skipped run has bytes");
        framer_check(skipped.offset + skipped.count <= stream_.size(),
                     "a skipped run lies in the stream");
        (void)rules_.describe_skip(skipped);
        next_ += skipped.count;
        skipped_ += skipped.count;
    }

    std::uint64_t next() const noexcept { return next_; }
    std::uint64_t telegrams() const noexcept { return telegrams_; }
    std::uint64_t skipped() const noexcept { return skipped_; }

  private:
    const FramingRules& rules_;
    bool (*length_ok_)(std::size_t);
    Bytes stream_;
    std::uint64_t next_ = 0;
    std::uint64_t telegrams_ = 0;
    std::uint64_t skipped_ = 0;
};

// Runs one input through a framer over `rules` (layout above) and checks every invariant.
inline void run_framer_check(const std::uint8_t* data, std::size_t size, const FramingRules& rules,
                             bool (*length_ok)(std::size_t)) {
    FuzzInput in(data, size);
    const std::uint8_t codes = in.byte();
    const std::uint8_t choice = in.byte();
    const Bytes stream = in.rest();
    const std::size_t sizes[4] = {1, 3, 1u + (choice & 0x0Fu), 64};
    const unsigned gap_every = choice >> 4;

    StreamFramer framer(rules);
    CheckingFramingSink sink(rules, length_ok, stream);
    std::size_t at = 0;
    for (unsigned chunk = 0; at < stream.size(); ++chunk) {
        const std::size_t n = std::min(sizes[(codes >> (2 * (chunk % 4))) & 3], stream.size() - at);
        framer.feed(stream.subspan(at, n), sink);
        at += n;
        if (gap_every != 0 && (chunk + 1) % gap_every == 0) {
            framer.mark_gap(sink);
            framer_check(framer.pending() == 0, "nothing is pending after a gap");
            framer_check(sink.next() == at, "after a gap every byte fed is decided");
        }
        // Bytes skipped in the run not reported yet count as skipped already.
        framer_check(
            sink.next() + (framer.bytes_skipped() - sink.skipped()) + framer.pending() == at,
            "reported, skipped and pending bytes are the bytes fed");
    }
    framer.finish(sink);
    framer_check(framer.pending() == 0, "nothing is pending after finish");
    framer_check(sink.next() == stream.size(), "telegrams and skipped bytes cover the stream");
    framer_check(framer.bytes_fed() == stream.size(), "the framer counts the bytes fed");
    framer_check(framer.telegrams() == sink.telegrams(), "the framer counts its telegrams");
    framer_check(framer.bytes_skipped() == sink.skipped(), "the framer counts its skipped bytes");
}

}  // namespace dpscope::fuzz
