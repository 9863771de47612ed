// toybus, the toy protocol of issue 28: its framing rules (every proper prefix needs more bytes, a
// line broken into by the next telegram is invalid there), its decoder (valid, truncated and
// corrupted telegrams of each kind, request/response pairing) and its tracker on the
// parameter-channel engine (a transaction, a rejection, an orphan, a time-out).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "protocols/toybus/toybus_decoder.hpp"
#include "protocols/toybus/toybus_framing_rules.hpp"
#include "protocols/toybus/toybus_tracker.hpp"

namespace dpscope {
namespace {

using Telegram = std::vector<std::uint8_t>;
Telegram bytes_of(const std::string& text) { return Telegram(text.begin(), text.end()); }
Bytes span_of(const Telegram& t) { return Bytes(t.data(), t.size()); }

constexpr std::int64_t kMs = 1'000'000;

TEST(ToybusTest, EveryTelegramFramesWholeAndEveryPrefixNeedsMore) {
    for (const std::string text :
         {"?01 0100\r\n", "!02 0200 00500\r\n", "=02 0200 00500\n", "#03 0300 05\r\n"}) {
        const Telegram t = bytes_of(text);
        const FramingVerdict whole = toybus_framing_rules().judge(span_of(t), false);
        EXPECT_EQ(whole.status, FramingStatus::Telegram) << text;
        EXPECT_EQ(whole.length, t.size()) << text;
        for (std::size_t n = 1; n < t.size(); ++n)
            EXPECT_EQ(toybus_framing_rules().judge(span_of(t).first(n), false).status,
                      FramingStatus::NeedMore)
                << text << " prefix " << n;
    }
}

TEST(ToybusTest, ALineBrokenIntoByTheNextTelegramIsInvalidWhereItStarts) {
    const Telegram t = bytes_of("?05 0500=05 0500 00042\r\n");
    const FramingVerdict v = toybus_framing_rules().judge(span_of(t), false);
    EXPECT_EQ(v.status, FramingStatus::Invalid);
    EXPECT_EQ(v.reason, ProblemKind::BadEndDelimiter);
    EXPECT_EQ(v.reason_offset, 8u);
    const Telegram endless = bytes_of("?01 0100 0000000000");
    EXPECT_EQ(toybus_framing_rules().judge(span_of(endless), false).status, FramingStatus::Invalid);
}

TEST(ToybusTest, DecodesEachKind) {
    ToybusTelegram v;
    parse_toybus(span_of(bytes_of("!02 0200 00500\r\n")), v);
    EXPECT_TRUE(v.complete);
    EXPECT_EQ(v.kind, ToybusKind::Write);
    EXPECT_EQ(v.address, 2);
    EXPECT_EQ(v.parameter, 200);
    EXPECT_EQ(v.value, 500u);
    v.reset();
    parse_toybus(span_of(bytes_of("#03 0300 05\r\n")), v);
    EXPECT_TRUE(v.complete);
    EXPECT_EQ(v.kind, ToybusKind::Error);
    EXPECT_EQ(v.error, 5);
}

TEST(ToybusTest, TruncatedAndCorruptedTelegramsHaveProblems) {
    ToybusTelegram v;
    parse_toybus(span_of(bytes_of("?04 04\r\n")), v);
    EXPECT_TRUE(v.problems.contains(ProblemKind::Truncated));
    EXPECT_FALSE(v.has_parameter);
    v.reset();
    parse_toybus(span_of(bytes_of("?1x 0100\r\n")), v);
    EXPECT_TRUE(v.problems.contains(ProblemKind::Vlt2000FieldInvalid));
    EXPECT_FALSE(v.has_address);
    v.reset();
    parse_toybus(span_of(bytes_of("?40 0100\r\n")), v);
    EXPECT_TRUE(v.problems.contains(ProblemKind::AdrInvalid));
}

TEST(ToybusTest, TrackerPairsRejectsAndTimesOut) {
    ToybusDecoder decoder;
    ToybusTracker tracker;
    std::vector<FindingKind> kinds;
    std::uint64_t frame = 0;
    auto feed = [&](const std::string& text, std::int64_t ms) {
        const Telegram t = bytes_of(text);
        const DecodedTelegram& d = decoder.decode(span_of(t), ms * kMs, ++frame);
        for (const Finding& f : tracker.track(d))
            kinds.push_back(f.kind);
        return d.request_frame;
    };
    EXPECT_EQ(feed("?01 0100\r\n", 0), 0u);
    EXPECT_EQ(feed("=01 0100 01234\r\n", 10), 1u);
    EXPECT_EQ(tracker.completed().size(), 1u);
    feed("?03 0300\r\n", 20);
    feed("#03 0300 05\r\n", 30);
    feed("=05 0500 00042\r\n", 40);
    feed("?07 0700\r\n", 50);
    for (const Finding& f : tracker.finish(5000 * kMs))
        kinds.push_back(f.kind);
    EXPECT_EQ(kinds,
              (std::vector<FindingKind>{FindingKind::RequestRejected, FindingKind::OrphanResponse,
                                        FindingKind::ResponseTimeout}));
    EXPECT_EQ(tracker.transactions(), 2u);
}

}  // namespace
}  // namespace dpscope
