// StreamFramer: chunked input of every size, resynchronisation after garbage, the FCS rules for
// SD1/SD2/SD3, gaps, the end of input and the counters; framing by another protocol's rules.
#include "core/stream_framer.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "protocols/profibus/fdl_framing_rules.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::hex;

struct Event {
    bool telegram = false;
    std::vector<std::uint8_t> bytes;  // telegram bytes
    std::uint64_t offset = 0;         // telegram offset or skipped offset
    SkippedBytes skipped{};
};

class RecordingSink : public StreamFramer::Sink {
  public:
    void on_telegram(Bytes telegram, std::uint64_t offset) override {
        events.push_back(Event{true, {telegram.begin(), telegram.end()}, offset, {}});
    }
    void on_skipped(const SkippedBytes& skipped) override {
        events.push_back(Event{false, {}, skipped.offset, skipped});
    }

    std::vector<Event> telegrams() const {
        std::vector<Event> out;
        for (const Event& e : events)
            if (e.telegram) out.push_back(e);
        return out;
    }
    std::vector<SkippedBytes> skips() const {
        std::vector<SkippedBytes> out;
        for (const Event& e : events)
            if (!e.telegram) out.push_back(e.skipped);
        return out;
    }

    std::vector<Event> events;
};

Bytes span_of(const std::vector<std::uint8_t>& bytes) { return Bytes(bytes.data(), bytes.size()); }

std::vector<std::uint8_t> concat(std::initializer_list<std::vector<std::uint8_t>> parts) {
    std::vector<std::uint8_t> out;
    for (const auto& part : parts)
        out.insert(out.end(), part.begin(), part.end());
    return out;
}

// FDL status request 2 -> 3 (FCS 4E), and the same with a wrong FCS.
const std::vector<std::uint8_t> kSd1 = hex("10 03 02 49 4E 16");
const std::vector<std::uint8_t> kSd1BadFcs = hex("10 03 02 49 4F 16");
// Chk_Cfg F3 F1 from 2 to 3 with SAPs 62/62 (FCS E2), and the same with a wrong FCS.
const std::vector<std::uint8_t> kSd2 = hex("68 07 07 68 83 82 7D 3E 3E F3 F1 E2 16");
const std::vector<std::uint8_t> kSd2BadFcs = hex("68 07 07 68 83 82 7D 3E 3E F3 F1 E3 16");
// Slave_Diag response (FCS 93), and the same with a wrong FCS.
const std::vector<std::uint8_t> kSd3 = hex("A2 82 83 08 3E 3C 02 05 00 FF 04 02 93 16");
const std::vector<std::uint8_t> kSd3BadFcs = hex("A2 82 83 08 3E 3C 02 05 00 FF 04 02 94 16");
const std::vector<std::uint8_t> kToken = hex("DC 02 02");
const std::vector<std::uint8_t> kShortAck = hex("E5");

void feed_all(StreamFramer& framer, const std::vector<std::uint8_t>& bytes, RecordingSink& sink) {
    framer.feed(span_of(bytes), sink);
}

TEST(StreamFramerTest, SplitsEveryFrameTypeInOneChunk) {
    auto stream = concat({kSd1, kSd2, kSd3, kToken, kShortAck});
    StreamFramer framer(fdl_framing_rules());
    RecordingSink sink;
    feed_all(framer, stream, sink);
    framer.finish(sink);
    auto telegrams = sink.telegrams();
    ASSERT_EQ(telegrams.size(), 5u);
    EXPECT_EQ(telegrams[0].bytes, kSd1);
    EXPECT_EQ(telegrams[0].offset, 0u);
    EXPECT_EQ(telegrams[1].bytes, kSd2);
    EXPECT_EQ(telegrams[1].offset, 6u);
    EXPECT_EQ(telegrams[2].bytes, kSd3);
    EXPECT_EQ(telegrams[2].offset, 19u);
    EXPECT_EQ(telegrams[3].bytes, kToken);
    EXPECT_EQ(telegrams[3].offset, 33u);
    EXPECT_EQ(telegrams[4].bytes, kShortAck);
    EXPECT_EQ(telegrams[4].offset, 36u);
    EXPECT_TRUE(sink.skips().empty());
    EXPECT_EQ(framer.telegrams(), 5u);
    EXPECT_EQ(framer.bytes_fed(), 37u);
    EXPECT_EQ(framer.bytes_skipped(), 0u);
    EXPECT_EQ(framer.pending(), 0u);
}

// A stream with garbage, damaged telegrams and every frame type gives the same telegrams and
// skipped runs whatever the chunk size, down to single bytes.
TEST(StreamFramerTest, ChunkSizeDoesNotChangeTheResult) {
    auto stream = concat({hex("00 42"), kSd1, kSd2, kSd1BadFcs, kSd3, kToken, hex("68 FF 33"),
                          kShortAck, kSd2BadFcs, kSd3BadFcs, kSd1});
    StreamFramer whole(fdl_framing_rules());
    RecordingSink expected;
    feed_all(whole, stream, expected);
    whole.finish(expected);

    // The reference run, checked by hand.
    auto telegrams = expected.telegrams();
    ASSERT_EQ(telegrams.size(), 9u);
    EXPECT_EQ(telegrams[0].offset, 2u);
    EXPECT_EQ(telegrams[2].bytes, kSd1BadFcs);
    EXPECT_EQ(telegrams[2].offset, 21u);
    EXPECT_EQ(telegrams[5].bytes, kShortAck);
    EXPECT_EQ(telegrams[5].offset, 47u);
    EXPECT_EQ(telegrams[6].bytes, kSd2BadFcs);
    EXPECT_EQ(telegrams[7].bytes, kSd3BadFcs);
    EXPECT_EQ(telegrams[8].offset, 75u);
    auto skips = expected.skips();
    ASSERT_EQ(skips.size(), 2u);
    EXPECT_EQ(skips[0].offset, 0u);
    EXPECT_EQ(skips[0].count, 2u);
    EXPECT_EQ(skips[0].reason, ProblemKind::BadStartDelimiter);
    EXPECT_EQ(skips[1].offset, 44u);
    EXPECT_EQ(skips[1].count, 3u);
    EXPECT_EQ(skips[1].reason, ProblemKind::LengthOutOfRange);
    EXPECT_EQ(skips[1].reason_offset, 1);
    EXPECT_EQ(whole.bytes_skipped(), 5u);
    EXPECT_EQ(whole.telegrams(), 9u);

    for (std::size_t chunk = 1; chunk <= stream.size(); ++chunk) {
        SCOPED_TRACE("chunk size " + std::to_string(chunk));
        StreamFramer framer(fdl_framing_rules());
        RecordingSink sink;
        for (std::size_t at = 0; at < stream.size(); at += chunk) {
            std::size_t n = std::min(chunk, stream.size() - at);
            framer.feed(Bytes(stream.data() + at, n), sink);
        }
        framer.finish(sink);
        ASSERT_EQ(sink.events.size(), expected.events.size());
        for (std::size_t i = 0; i < sink.events.size(); ++i) {
            const Event& got = sink.events[i];
            const Event& want = expected.events[i];
            EXPECT_EQ(got.telegram, want.telegram) << "event " << i;
            EXPECT_EQ(got.bytes, want.bytes) << "event " << i;
            EXPECT_EQ(got.offset, want.offset) << "event " << i;
            EXPECT_EQ(got.skipped.count, want.skipped.count) << "event " << i;
            EXPECT_EQ(got.skipped.reason, want.skipped.reason) << "event " << i;
            EXPECT_EQ(got.skipped.reason_offset, want.skipped.reason_offset) << "event " << i;
        }
        EXPECT_EQ(framer.bytes_fed(), stream.size());
        EXPECT_EQ(framer.bytes_skipped(), 5u);
        EXPECT_EQ(framer.telegrams(), 9u);
        EXPECT_EQ(framer.pending(), 0u);
    }
}

TEST(StreamFramerTest, ResyncsAfterGarbageAndReportsTheRunOnce) {
    StreamFramer framer(fdl_framing_rules());
    RecordingSink sink;
    feed_all(framer, concat({hex("00 42 FF"), kSd1}), sink);
    ASSERT_EQ(sink.events.size(), 2u);
    ASSERT_FALSE(sink.events[0].telegram);  // the skipped run comes before the telegram
    const SkippedBytes& skipped = sink.events[0].skipped;
    EXPECT_EQ(skipped.offset, 0u);
    EXPECT_EQ(skipped.count, 3u);
    EXPECT_EQ(skipped.reason, ProblemKind::BadStartDelimiter);
    EXPECT_EQ(skipped.reason_offset, 0);
    EXPECT_EQ(fdl_framing_rules().describe_skip(skipped), "skipped 3 bytes: no start delimiter");
    SkippedBytes one = skipped;
    one.count = 1;
    EXPECT_EQ(fdl_framing_rules().describe_skip(one), "skipped 1 byte: no start delimiter");
    ASSERT_TRUE(sink.events[1].telegram);
    EXPECT_EQ(sink.events[1].offset, 3u);
    EXPECT_EQ(sink.events[1].bytes, kSd1);
    EXPECT_EQ(framer.bytes_skipped(), 3u);
}

TEST(StreamFramerTest, GarbageBetweenTelegramsIsSkippedAtItsOffset) {
    StreamFramer framer(fdl_framing_rules());
    RecordingSink sink;
    feed_all(framer, concat({kSd1, hex("00 00"), kSd2}), sink);
    ASSERT_EQ(sink.events.size(), 3u);
    EXPECT_TRUE(sink.events[0].telegram);
    ASSERT_FALSE(sink.events[1].telegram);
    EXPECT_EQ(sink.events[1].skipped.offset, 6u);
    EXPECT_EQ(sink.events[1].skipped.count, 2u);
    EXPECT_TRUE(sink.events[2].telegram);
    EXPECT_EQ(sink.events[2].offset, 8u);
}

TEST(StreamFramerTest, SkippedRunSpanningFeedsIsReportedOnceWithFirstReason) {
    StreamFramer framer(fdl_framing_rules());
    RecordingSink sink;
    feed_all(framer, hex("68 FF"), sink);  // LE out of range at byte 1
    feed_all(framer, hex("42 43"), sink);
    EXPECT_TRUE(sink.events.empty());  // the run is open until something ends it
    EXPECT_EQ(framer.bytes_skipped(), 4u);
    feed_all(framer, kToken, sink);
    ASSERT_EQ(sink.events.size(), 2u);
    const SkippedBytes& skipped = sink.events[0].skipped;
    EXPECT_EQ(skipped.offset, 0u);
    EXPECT_EQ(skipped.count, 4u);
    EXPECT_EQ(skipped.reason, ProblemKind::LengthOutOfRange);
    EXPECT_EQ(skipped.reason_offset, 1);
    EXPECT_EQ(fdl_framing_rules().describe_skip(skipped),
              "skipped 4 bytes: LE outside 3..249 (byte 1 of the candidate telegram)");
    EXPECT_EQ(sink.events[1].offset, 4u);
}

TEST(StreamFramerTest, LengthRepeatMismatchIsSkipped) {
    StreamFramer framer(fdl_framing_rules());
    RecordingSink sink;
    feed_all(framer, concat({hex("68 07 08 68 83 82 7D 3E 3E F3 F1 E2 16"), kShortAck}), sink);
    auto skips = sink.skips();
    ASSERT_EQ(skips.size(), 1u);
    EXPECT_EQ(skips[0].reason, ProblemKind::LengthMismatch);
    EXPECT_EQ(skips[0].reason_offset, 2);
    EXPECT_EQ(skips[0].count, 13u);
    auto telegrams = sink.telegrams();
    ASSERT_EQ(telegrams.size(), 1u);
    EXPECT_EQ(telegrams[0].offset, 13u);
    EXPECT_EQ(telegrams[0].bytes, kShortAck);
}

TEST(StreamFramerTest, Sd2WithBadEndDelimiterIsSkipped) {
    auto bad = kSd2;
    bad.pop_back();  // replace the end delimiter
    bad.push_back(0x17);
    StreamFramer framer(fdl_framing_rules());
    RecordingSink sink;
    feed_all(framer, concat({bad, kShortAck}), sink);
    auto skips = sink.skips();
    ASSERT_EQ(skips.size(), 1u);
    EXPECT_EQ(skips[0].offset, 0u);
    EXPECT_EQ(skips[0].count, 13u);
    EXPECT_EQ(skips[0].reason, ProblemKind::BadEndDelimiter);
    EXPECT_EQ(skips[0].reason_offset, 12);
    EXPECT_EQ(fdl_framing_rules().describe_skip(skips[0]),
              "skipped 13 bytes: no end delimiter where the length puts it (byte 12 of the "
              "candidate telegram)");
    ASSERT_EQ(sink.telegrams().size(), 1u);
    EXPECT_EQ(sink.telegrams()[0].offset, 13u);
}

TEST(StreamFramerTest, TokenWithBit7AddressIsSkipped) {
    StreamFramer framer(fdl_framing_rules());
    RecordingSink sink;
    feed_all(framer, concat({hex("DC 82 02"), kShortAck}), sink);
    auto skips = sink.skips();
    ASSERT_EQ(skips.size(), 1u);
    EXPECT_EQ(skips[0].count, 3u);
    EXPECT_EQ(skips[0].reason, ProblemKind::InvalidAddress);
    EXPECT_EQ(skips[0].reason_offset, 1);
    ASSERT_EQ(sink.telegrams().size(), 1u);
    EXPECT_EQ(sink.telegrams()[0].offset, 3u);
}

TEST(StreamFramerTest, Sd1BadFcsAcceptedWhenAStartDelimiterFollows) {
    StreamFramer framer(fdl_framing_rules());
    RecordingSink sink;
    feed_all(framer, concat({kSd1BadFcs, kShortAck}), sink);
    auto telegrams = sink.telegrams();
    ASSERT_EQ(telegrams.size(), 2u);
    EXPECT_EQ(telegrams[0].bytes, kSd1BadFcs);
    EXPECT_EQ(telegrams[0].offset, 0u);
    EXPECT_EQ(telegrams[1].offset, 6u);
    EXPECT_TRUE(sink.skips().empty());
}

TEST(StreamFramerTest, Sd1BadFcsWaitsForTheNextByte) {
    StreamFramer framer(fdl_framing_rules());
    RecordingSink sink;
    feed_all(framer, kSd1BadFcs, sink);
    EXPECT_TRUE(sink.events.empty());
    EXPECT_EQ(framer.pending(), 6u);
    feed_all(framer, kSd2, sink);
    auto telegrams = sink.telegrams();
    ASSERT_EQ(telegrams.size(), 2u);
    EXPECT_EQ(telegrams[0].bytes, kSd1BadFcs);
    EXPECT_EQ(telegrams[1].bytes, kSd2);
    EXPECT_EQ(telegrams[1].offset, 6u);
    EXPECT_EQ(framer.pending(), 0u);
}

TEST(StreamFramerTest, Sd1BadFcsRejectedWhenGarbageFollows) {
    StreamFramer framer(fdl_framing_rules());
    RecordingSink sink;
    feed_all(framer, concat({kSd1BadFcs, hex("42"), kSd2}), sink);
    auto skips = sink.skips();
    ASSERT_EQ(skips.size(), 1u);
    EXPECT_EQ(skips[0].offset, 0u);
    EXPECT_EQ(skips[0].count, 7u);
    EXPECT_EQ(skips[0].reason, ProblemKind::FcsMismatch);
    EXPECT_EQ(skips[0].reason_offset, 4);
    EXPECT_EQ(fdl_framing_rules().describe_skip(skips[0]),
              "skipped 7 bytes: FCS wrong and no telegram follows (byte 4 of the candidate "
              "telegram)");
    auto telegrams = sink.telegrams();
    ASSERT_EQ(telegrams.size(), 1u);
    EXPECT_EQ(telegrams[0].bytes, kSd2);
    EXPECT_EQ(telegrams[0].offset, 7u);
}

TEST(StreamFramerTest, Sd1BadFcsAcceptedAtFinish) {
    StreamFramer framer(fdl_framing_rules());
    RecordingSink sink;
    feed_all(framer, kSd1BadFcs, sink);
    EXPECT_TRUE(sink.events.empty());
    framer.finish(sink);
    auto telegrams = sink.telegrams();
    ASSERT_EQ(telegrams.size(), 1u);
    EXPECT_EQ(telegrams[0].bytes, kSd1BadFcs);
    EXPECT_TRUE(sink.skips().empty());
    EXPECT_EQ(framer.telegrams(), 1u);
    EXPECT_EQ(framer.pending(), 0u);
}

TEST(StreamFramerTest, Sd3BadFcsAcceptedOnlyBeforeAStartDelimiterOrAtFinish) {
    {
        StreamFramer framer(fdl_framing_rules());
        RecordingSink sink;
        feed_all(framer, concat({kSd3BadFcs, kToken}), sink);
        ASSERT_EQ(sink.telegrams().size(), 2u);
        EXPECT_EQ(sink.telegrams()[0].bytes, kSd3BadFcs);
        EXPECT_EQ(sink.telegrams()[1].offset, 14u);
    }
    {
        StreamFramer framer(fdl_framing_rules());
        RecordingSink sink;
        feed_all(framer, concat({kSd3BadFcs, hex("00"), kShortAck}), sink);
        auto skips = sink.skips();
        ASSERT_EQ(skips.size(), 1u);
        EXPECT_EQ(skips[0].reason, ProblemKind::FcsMismatch);
        EXPECT_EQ(skips[0].reason_offset, 12);
        EXPECT_EQ(skips[0].count, 15u);
        ASSERT_EQ(sink.telegrams().size(), 1u);
        EXPECT_EQ(sink.telegrams()[0].offset, 15u);
    }
    {
        StreamFramer framer(fdl_framing_rules());
        RecordingSink sink;
        feed_all(framer, kSd3BadFcs, sink);
        EXPECT_TRUE(sink.events.empty());
        framer.finish(sink);
        ASSERT_EQ(sink.telegrams().size(), 1u);
        EXPECT_EQ(sink.telegrams()[0].bytes, kSd3BadFcs);
    }
}

TEST(StreamFramerTest, Sd2BadFcsAcceptedWhateverFollows) {
    StreamFramer framer(fdl_framing_rules());
    RecordingSink sink;
    feed_all(framer, concat({kSd2BadFcs, hex("42")}), sink);
    auto telegrams = sink.telegrams();
    ASSERT_EQ(telegrams.size(), 1u);
    EXPECT_EQ(telegrams[0].bytes, kSd2BadFcs);
    EXPECT_EQ(telegrams[0].offset, 0u);
    framer.finish(sink);
    auto skips = sink.skips();
    ASSERT_EQ(skips.size(), 1u);
    EXPECT_EQ(skips[0].offset, 13u);
    EXPECT_EQ(skips[0].count, 1u);
    EXPECT_EQ(skips[0].reason, ProblemKind::BadStartDelimiter);
}

TEST(StreamFramerTest, MarkGapDecidesACutOffTelegram) {
    StreamFramer framer(fdl_framing_rules());
    RecordingSink sink;
    feed_all(framer, std::vector<std::uint8_t>(kSd2.begin(), kSd2.begin() + 7), sink);
    EXPECT_TRUE(sink.events.empty());
    EXPECT_EQ(framer.pending(), 7u);
    framer.mark_gap(sink);
    EXPECT_EQ(framer.pending(), 0u);
    auto skips = sink.skips();
    ASSERT_EQ(skips.size(), 1u);
    EXPECT_EQ(skips[0].offset, 0u);
    EXPECT_EQ(skips[0].count, 7u);
    EXPECT_EQ(skips[0].reason, ProblemKind::Truncated);
    EXPECT_EQ(fdl_framing_rules().describe_skip(skips[0]),
              "skipped 7 bytes: telegram cut off (gap or end of input)");
    EXPECT_TRUE(sink.telegrams().empty());

    // The rest of the telegram after the gap cannot complete it.
    feed_all(framer, std::vector<std::uint8_t>(kSd2.begin() + 7, kSd2.end()), sink);
    feed_all(framer, kSd1, sink);
    auto telegrams = sink.telegrams();
    ASSERT_EQ(telegrams.size(), 1u);
    EXPECT_EQ(telegrams[0].bytes, kSd1);
    EXPECT_EQ(telegrams[0].offset, 13u);
    skips = sink.skips();
    ASSERT_EQ(skips.size(), 2u);
    EXPECT_EQ(skips[1].offset, 7u);
    EXPECT_EQ(skips[1].count, 6u);
    EXPECT_EQ(skips[1].reason, ProblemKind::BadStartDelimiter);
    EXPECT_EQ(framer.bytes_skipped(), 13u);
}

TEST(StreamFramerTest, MarkGapDeliversACompleteTelegramWaitingForItsSuccessor) {
    StreamFramer framer(fdl_framing_rules());
    RecordingSink sink;
    feed_all(framer, kSd1BadFcs, sink);
    framer.mark_gap(sink);
    ASSERT_EQ(sink.telegrams().size(), 1u);
    EXPECT_EQ(sink.telegrams()[0].bytes, kSd1BadFcs);
    EXPECT_TRUE(sink.skips().empty());
    // Framing goes on normally after the gap.
    feed_all(framer, kShortAck, sink);
    ASSERT_EQ(sink.telegrams().size(), 2u);
    EXPECT_EQ(sink.telegrams()[1].offset, 6u);
}

TEST(StreamFramerTest, MarkGapWithNothingPendingDoesNothing) {
    StreamFramer framer(fdl_framing_rules());
    RecordingSink sink;
    framer.mark_gap(sink);
    feed_all(framer, kToken, sink);
    framer.mark_gap(sink);
    ASSERT_EQ(sink.events.size(), 1u);
    EXPECT_TRUE(sink.events[0].telegram);
}

TEST(StreamFramerTest, FinishReportsACutOffTelegramAfterAWholeOne) {
    StreamFramer framer(fdl_framing_rules());
    RecordingSink sink;
    feed_all(framer, concat({kSd1, std::vector<std::uint8_t>(kSd2.begin(), kSd2.begin() + 9)}),
             sink);
    ASSERT_EQ(sink.telegrams().size(), 1u);
    EXPECT_EQ(framer.pending(), 9u);
    framer.finish(sink);
    auto skips = sink.skips();
    ASSERT_EQ(skips.size(), 1u);
    EXPECT_EQ(skips[0].offset, 6u);
    EXPECT_EQ(skips[0].count, 9u);
    EXPECT_EQ(skips[0].reason, ProblemKind::Truncated);
    EXPECT_EQ(framer.bytes_fed(), 15u);
    EXPECT_EQ(framer.bytes_skipped(), 9u);
    EXPECT_EQ(framer.telegrams(), 1u);
    EXPECT_EQ(framer.pending(), 0u);
}

TEST(StreamFramerTest, FinishRecoversWholeTelegramsBehindACutOffOne) {
    // An SD2 header that never completes, with a short acknowledge inside its length.
    StreamFramer framer(fdl_framing_rules());
    RecordingSink sink;
    feed_all(framer, hex("68 07 07 68 83 E5"), sink);
    EXPECT_TRUE(sink.events.empty());
    framer.finish(sink);
    ASSERT_EQ(sink.events.size(), 2u);
    ASSERT_FALSE(sink.events[0].telegram);
    EXPECT_EQ(sink.events[0].skipped.offset, 0u);
    EXPECT_EQ(sink.events[0].skipped.count, 5u);
    EXPECT_EQ(sink.events[0].skipped.reason, ProblemKind::Truncated);
    ASSERT_TRUE(sink.events[1].telegram);
    EXPECT_EQ(sink.events[1].offset, 5u);
    EXPECT_EQ(sink.events[1].bytes, kShortAck);
}

TEST(StreamFramerTest, CountersTrackFedSkippedAndPending) {
    StreamFramer framer(fdl_framing_rules());
    RecordingSink sink;
    EXPECT_EQ(framer.bytes_fed(), 0u);
    EXPECT_EQ(framer.pending(), 0u);
    feed_all(framer, hex("01 02"), sink);
    EXPECT_EQ(framer.bytes_fed(), 2u);
    EXPECT_EQ(framer.bytes_skipped(), 2u);
    EXPECT_EQ(framer.pending(), 0u);
    feed_all(framer, hex("68 07 07"), sink);
    EXPECT_EQ(framer.bytes_fed(), 5u);
    EXPECT_EQ(framer.pending(), 3u);
    EXPECT_EQ(framer.telegrams(), 0u);
    feed_all(framer, std::vector<std::uint8_t>(kSd2.begin() + 3, kSd2.end()), sink);
    EXPECT_EQ(framer.bytes_fed(), 15u);
    EXPECT_EQ(framer.pending(), 0u);
    EXPECT_EQ(framer.telegrams(), 1u);
    ASSERT_EQ(sink.telegrams().size(), 1u);
    EXPECT_EQ(sink.telegrams()[0].offset, 2u);
    EXPECT_EQ(sink.telegrams()[0].bytes, kSd2);
}

TEST(StreamFramerTest, EmptyFeedAndFinishProduceNothing) {
    StreamFramer framer(fdl_framing_rules());
    RecordingSink sink;
    framer.feed(Bytes{}, sink);
    framer.finish(sink);
    EXPECT_TRUE(sink.events.empty());
    EXPECT_EQ(framer.bytes_fed(), 0u);
    EXPECT_EQ(framer.telegrams(), 0u);
}

// A toy protocol: STX (0x02), a length byte (1..8), that many bytes. Nothing of FDL applies.
bool toy_can_start(std::uint8_t byte) { return byte == 0x02; }

class ToyRules final : public FramingRules {
  public:
    ToyRules() : FramingRules(toy_can_start) {}
    FramingVerdict judge(Bytes candidate, bool) const noexcept override {
        if (candidate.size() < 2) return FramingVerdict::need_more();
        if (candidate[1] == 0 || candidate[1] > 8)
            return FramingVerdict::invalid(ProblemKind::LengthOutOfRange, 1);
        const std::size_t size = std::size_t{2} + candidate[1];
        return candidate.size() < size ? FramingVerdict::need_more()
                                       : FramingVerdict::telegram(size);
    }
    std::string_view protocol_name() const noexcept override { return "toy"; }

  protected:
    std::string_view reason_text(ProblemKind reason) const override {
        return reason == ProblemKind::LengthOutOfRange ? "length outside 1..8"
                                                       : FramingRules::reason_text(reason);
    }
};

TEST(StreamFramerTest, FramesByAnotherProtocolsRules) {
    const ToyRules rules;
    StreamFramer framer(rules);
    RecordingSink sink;
    // 0x10 and 0x68 start FDL telegrams, not toy ones; 02 09 has a bad length; 02 01 is cut off.
    feed_all(framer, hex("10 68 02 02 AA BB 02 09 E5 02 01 CC 02 01"), sink);
    framer.finish(sink);
    ASSERT_EQ(sink.events.size(), 5u);
    EXPECT_FALSE(sink.events[0].telegram);
    EXPECT_EQ(sink.events[0].skipped.count, 2u);
    EXPECT_EQ(rules.describe_skip(sink.events[0].skipped), "skipped 2 bytes: no start delimiter");
    EXPECT_TRUE(sink.events[1].telegram);
    EXPECT_EQ(sink.events[1].bytes, hex("02 02 AA BB"));
    EXPECT_EQ(sink.events[1].offset, 2u);
    EXPECT_FALSE(sink.events[2].telegram);
    EXPECT_EQ(sink.events[2].skipped.offset, 6u);
    EXPECT_EQ(sink.events[2].skipped.count, 3u);
    EXPECT_EQ(rules.describe_skip(sink.events[2].skipped),
              "skipped 3 bytes: length outside 1..8 (byte 1 of the candidate telegram)");
    EXPECT_TRUE(sink.events[3].telegram);
    EXPECT_EQ(sink.events[3].bytes, hex("02 01 CC"));
    EXPECT_FALSE(sink.events[4].telegram);
    EXPECT_EQ(sink.events[4].skipped.reason, ProblemKind::Truncated);
    EXPECT_EQ(sink.events[4].skipped.count, 2u);
    EXPECT_EQ(framer.telegrams(), 2u);
    EXPECT_EQ(framer.bytes_skipped(), 7u);
}

}  // namespace
}  // namespace dpscope
