// The Danfoss FC protocol: framing rules in a byte stream, the decoder's fields (both address
// formats, every block, the FC PKE layout, text blocks, fault codes), its request/response
// inference, the code tables, and truncated and corrupted telegrams. The worked examples are
// those of ../shared/protocol.md §4.6 and §5.5 (docs/protocol/fc-protocol.md).
#include "protocols/fc/fc_decoder.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/stream_framer.hpp"
#include "protocols/fc/fc_codes.hpp"
#include "protocols/fc/fc_framing_rules.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::hex;
using Telegram = std::vector<std::uint8_t>;

Bytes span_of(const Telegram& bytes) { return Bytes(bytes.data(), bytes.size()); }

// STX, LGE (data + 2), ADR, the data and the BCC.
Telegram fc(std::uint8_t adr, const Telegram& data) {
    // push_back only: GCC 12's -Warray-bounds misreads insert after a short initializer list.
    Telegram out;
    out.reserve(data.size() + 4);
    out.push_back(kFcStx);
    out.push_back(static_cast<std::uint8_t>(data.size() + 2));
    out.push_back(adr);
    for (std::uint8_t b : data)
        out.push_back(b);
    out.push_back(fc_bcc_of(span_of(out)));
    return out;
}

constexpr std::int64_t kMs = 1'000'000;

// --- Worked examples ------------------------------------------------------------------------

TEST(FcDecoderTest, ProcessBlockExampleWithItsBcc) {
    // §5.4: process block to address 1 (1-126 format), CTW 047F, reference 2000: BCC 0xDE.
    const Telegram bytes = hex("02 06 81 04 7F 20 00 DE");
    EXPECT_EQ(fc(0x81, hex("04 7F 20 00")), bytes);
    FcDecoder decoder;
    const DecodedTelegram& t = decoder.decode(span_of(bytes), 0, 1);
    EXPECT_EQ(t.protocol, Protocol::Fc);
    EXPECT_TRUE(t.problems().empty());
    EXPECT_EQ(t.fc.block, FcBlock::Process);
    EXPECT_EQ(t.fc.address_format, FcAddressFormat::Long);
    EXPECT_EQ(t.fc.address, 1);
    EXPECT_FALSE(t.fc.broadcast);
    EXPECT_TRUE(t.fc.bcc_ok);
    EXPECT_FALSE(t.fc.has_pkw);
    ASSERT_TRUE(t.fc.has_pcd);
    EXPECT_EQ(t.fc.pcd1, 0x047F);
    EXPECT_EQ(t.fc.pcd2, 0x2000);
    EXPECT_EQ(t.direction, Direction::Request);
    EXPECT_EQ(t.slave, 1);
}

TEST(FcDecoderTest, ParameterBlockReadOf4Dash14) {
    // §5.5: read par. 4-14 (PKE 119E: AK 1, PNU 414) at address 1 with CTW and reference.
    const Telegram bytes = hex("02 0E 81 11 9E 00 00 00 00 00 00 04 7F 20 00 59");
    FcDecoder decoder;
    const DecodedTelegram& t = decoder.decode(span_of(bytes), 0, 1);
    EXPECT_TRUE(t.problems().empty());
    EXPECT_EQ(t.fc.block, FcBlock::Parameter);
    ASSERT_TRUE(t.fc.has_pkw);
    EXPECT_EQ(t.fc.pkw.rc, 1);
    EXPECT_EQ(t.fc.pkw.pnu, 414);
    EXPECT_FALSE(t.fc.pkw.spm);
    EXPECT_EQ(t.fc.pkw.ind, 0);
    EXPECT_EQ(t.fc.pkw.pva, 0u);
    EXPECT_EQ(t.fc.pcd1, 0x047F);
    EXPECT_EQ(fc_command(t.fc.pkw.rc).meaning, "Read parameter value");
}

TEST(FcDecoderTest, PkeExamplesSplitAsTheSourcesSay) {
    struct Case {
        std::uint16_t pke;
        std::uint8_t ak;
        std::uint16_t pnu;
    };
    // §4.6: E0CA write 202 RAM+EEPROM word; E19F write 415; 10CE read 206; 1267 read 615.
    for (const Case& c : {Case{0xE0CA, 14, 202}, Case{0xE19F, 14, 415}, Case{0x10CE, 1, 206},
                          Case{0x1267, 1, 615}}) {
        const Telegram bytes =
            fc(0x01, {static_cast<std::uint8_t>(c.pke >> 8), static_cast<std::uint8_t>(c.pke), 0, 1,
                      0, 0, 0, 7, 0, 0, 0, 0});
        FcDecoder decoder;
        const DecodedTelegram& t = decoder.decode(span_of(bytes), 0, 1);
        EXPECT_EQ(t.fc.pkw.rc, c.ak) << std::hex << c.pke;
        EXPECT_EQ(t.fc.pkw.pnu, c.pnu) << std::hex << c.pke;
        EXPECT_EQ(t.fc.pkw.ind, 1) << "the index is IND's low byte";
        EXPECT_EQ(t.fc.pkw.pva, 7u);
    }
}

TEST(FcDecoderTest, DescriptionExampleOfEarlyFc300AndItsAnswer) {
    // §5.5: AK 4 read description of 0-01, element 1, address 1 in the 1-31 format; reply AK 3
    // with PWE low 0405.
    FcDecoder decoder;
    const Telegram request = fc(0x01, hex("40 01 00 01 00 00 00 00 00 00 00 00"));
    const Telegram reply = fc(0x01, hex("30 01 00 01 00 00 04 05 00 00 00 00"));
    const DecodedTelegram& q = decoder.decode(span_of(request), 10 * kMs, 1);
    EXPECT_EQ(q.fc.address_format, FcAddressFormat::Short);
    EXPECT_EQ(q.fc.address, 1);
    EXPECT_EQ(q.fc.pkw.rc, 4);
    EXPECT_EQ(q.fc.pkw.pnu, 1);
    EXPECT_EQ(q.fc.pkw.ind, 1);
    EXPECT_EQ(q.direction, Direction::Request);
    const DecodedTelegram& r = decoder.decode(span_of(reply), 15 * kMs, 2);
    EXPECT_EQ(r.direction, Direction::Response);
    EXPECT_EQ(r.request_frame, 1u);
    EXPECT_EQ(r.fc.pkw.rc, 3);
    EXPECT_EQ(r.fc.pkw.pva & 0xFFFF, 0x0405u);
    EXPECT_EQ(fc_judge_answer(4, 3), AnswerVerdict::Positive);
}

// --- Address byte ---------------------------------------------------------------------------

TEST(FcDecoderTest, BothAddressFormatsAndTheirBroadcasts) {
    struct Case {
        std::uint8_t adr;
        FcAddressFormat format;
        std::uint8_t address;
        bool broadcast;
    };
    for (const Case& c :
         {Case{0x01, FcAddressFormat::Short, 1, false},
          Case{0x1F, FcAddressFormat::Short, 31, false},
          Case{0x20, FcAddressFormat::Short, 0, true}, Case{0x3F, FcAddressFormat::Short, 0, true},
          Case{0x81, FcAddressFormat::Long, 1, false},
          Case{0xFE, FcAddressFormat::Long, 126, false},
          Case{0x80, FcAddressFormat::Long, 0, true}}) {
        FcDecoder decoder;
        const Telegram bytes = fc(c.adr, hex("04 7F 20 00"));
        const DecodedTelegram& t = decoder.decode(span_of(bytes), 0, 1);
        EXPECT_TRUE(t.problems().empty()) << int(c.adr);
        EXPECT_EQ(t.fc.address_format, c.format) << int(c.adr);
        EXPECT_EQ(t.fc.address, c.address) << int(c.adr);
        EXPECT_EQ(t.fc.broadcast, c.broadcast) << int(c.adr);
        EXPECT_TRUE(fc_adr_valid(c.adr));
    }
    EXPECT_FALSE(fc_adr_valid(0x00));
    EXPECT_FALSE(fc_adr_valid(0xFF));
    FcDecoder decoder;
    const Telegram bad = fc(0xFF, hex("04 7F 20 00"));
    EXPECT_TRUE(decoder.decode(span_of(bad), 0, 1).problems().contains(ProblemKind::AdrInvalid));
}

// --- Text blocks and fault codes ------------------------------------------------------------

TEST(FcDecoderTest, TextBlockCarriesItsCharactersAndTheTextFlag) {
    FcDecoder decoder;
    const Telegram request = fc(0x02, hex("F0 01 04 00 00 00 00 00 04 7F 00 00"));
    const DecodedTelegram& q = decoder.decode(span_of(request), 0, 1);
    EXPECT_EQ(q.fc.block, FcBlock::Text) << "LGE 14 with AK 15 is a text block of 4 characters";
    EXPECT_EQ(q.fc.ind_high, kFcTextRead);
    EXPECT_EQ(q.fc.pkw.pnu, 1);
    Telegram data = hex("F0 01 04 00");
    for (char c : std::string("Language"))
        data.push_back(static_cast<std::uint8_t>(c));
    const Telegram reply_data = [&] {
        Telegram d = data;
        for (std::uint8_t b : hex("06 07 00 00"))
            d.push_back(b);
        return d;
    }();
    const Telegram reply = fc(0x02, reply_data);
    EXPECT_EQ(reply[1], kFcLgeTextBase + 8);
    const DecodedTelegram& r = decoder.decode(span_of(reply), 1 * kMs, 2);
    EXPECT_TRUE(r.problems().empty());
    EXPECT_EQ(r.direction, Direction::Response);
    EXPECT_EQ(r.fc.block, FcBlock::Text);
    EXPECT_EQ(std::string(r.fc.text.begin(), r.fc.text.end()), "Language");
    EXPECT_EQ(r.fc.pcd1, 0x0607);
    EXPECT_EQ(fc_response(r.fc.pkw.rc).kind, ResponseKind::Text);
}

TEST(FcDecoderTest, FaultCodesHaveTheSeedsTexts) {
    EXPECT_EQ(fc_fault_text(0), "Illegal parameter number");
    EXPECT_EQ(fc_fault_text(6), "Not used");
    EXPECT_EQ(fc_fault_text(17), "Not applicable while running");
    EXPECT_EQ(fc_fault_text(130), "No bus access for this parameter");
    EXPECT_EQ(fc_fault_text(131), "Write to factory set-up is not possible");
    EXPECT_EQ(fc_fault_text(132), "No LCP access");
    EXPECT_EQ(fc_fault_text(255), "No error");
    EXPECT_EQ(fc_fault_text(8), "");
    EXPECT_EQ(fc_fault_text(100), "");
}

TEST(FcDecoderTest, CommandAndResponseTablesAndPairing) {
    for (int ak : {0, 1, 2, 3, 4, 13, 14, 15})
        EXPECT_TRUE(fc_command(static_cast<std::uint8_t>(ak)).defined) << int(ak);
    for (int ak : {5, 6, 7, 8, 9, 10, 11, 12})
        EXPECT_FALSE(fc_command(static_cast<std::uint8_t>(ak)).defined) << int(ak);
    for (int ak : {4, 5, 6, 8, 9, 10, 11, 12, 13, 14})
        EXPECT_EQ(fc_response(static_cast<std::uint8_t>(ak)).kind, ResponseKind::Undefined)
            << int(ak);
    EXPECT_EQ(fc_response(7).kind, ResponseKind::Rejected);
    EXPECT_EQ(fc_judge_answer(1, 1), AnswerVerdict::Positive);
    EXPECT_EQ(fc_judge_answer(1, 2), AnswerVerdict::Positive);
    EXPECT_EQ(fc_judge_answer(2, 1), AnswerVerdict::Positive);
    EXPECT_EQ(fc_judge_answer(2, 2), AnswerVerdict::Invalid);
    EXPECT_EQ(fc_judge_answer(3, 2), AnswerVerdict::Positive);
    EXPECT_EQ(fc_judge_answer(13, 2), AnswerVerdict::Positive);
    EXPECT_EQ(fc_judge_answer(14, 1), AnswerVerdict::Positive);
    EXPECT_EQ(fc_judge_answer(15, 15), AnswerVerdict::Positive);
    EXPECT_EQ(fc_judge_answer(15, 1), AnswerVerdict::Invalid);
    EXPECT_EQ(fc_judge_answer(14, 7), AnswerVerdict::Negative);
    EXPECT_EQ(fc_judge_answer(0, 0), AnswerVerdict::Positive);
    EXPECT_EQ(fc_judge_answer(0, 7), AnswerVerdict::Invalid);
}

TEST(FcDecoderTest, ElevenBitPnuOfOlderDrives) {
    const Telegram bytes = fc(0x01, hex("1F FF 00 00 00 00 00 00 00 00 00 00"));
    FcDecoder twelve;
    EXPECT_EQ(twelve.decode(span_of(bytes), 0, 1).fc.pkw.pnu, 0xFFF);
    FcDecoder eleven(FcDecoderOptions{11, 1'000'000'000});
    EXPECT_EQ(eleven.decode(span_of(bytes), 0, 1).fc.pkw.pnu, 0x7FF);
}

// --- Request or response --------------------------------------------------------------------

TEST(FcDecoderTest, DirectionByOrderAddressAndCodes) {
    FcDecoder decoder;
    const Telegram read1 = fc(0x01, hex("11 9E 00 00 00 00 00 00 04 7F 20 00"));
    const Telegram answer1 = fc(0x01, hex("11 9E 00 00 00 00 00 32 06 07 20 00"));
    const Telegram read2 = fc(0x02, hex("11 9E 00 00 00 00 00 00 04 7F 20 00"));
    const Telegram other = fc(0x03, hex("11 9E 00 00 00 00 00 00 04 7F 20 00"));
    const Telegram reject = fc(0x03, hex("71 9E 00 00 00 00 00 02 06 07 20 00"));
    const Telegram broadcast = fc(0x80, hex("04 7F 20 00"));
    const Telegram write = fc(0x02, hex("E1 9F 00 00 00 00 00 05 04 7F 20 00"));

    auto decode = [&](const Telegram& bytes, std::int64_t ms, std::uint64_t frame) {
        const DecodedTelegram& t = decoder.decode(span_of(bytes), ms * kMs, frame);
        return std::pair{t.direction, t.request_frame};
    };
    EXPECT_EQ(decode(read1, 0, 1), std::pair(Direction::Request, std::uint64_t{0}));
    EXPECT_EQ(decode(answer1, 5, 2), std::pair(Direction::Response, std::uint64_t{1}));
    EXPECT_EQ(decode(read2, 10, 3), std::pair(Direction::Request, std::uint64_t{0}));
    // Another address: the master moved on (address 2 left unanswered).
    EXPECT_EQ(decode(other, 15, 4), std::pair(Direction::Request, std::uint64_t{0}));
    // AK 7 only a response has.
    EXPECT_EQ(decode(reject, 20, 5), std::pair(Direction::Response, std::uint64_t{4}));
    // A broadcast is answered by nobody: what follows is a request.
    EXPECT_EQ(decode(broadcast, 25, 6), std::pair(Direction::Request, std::uint64_t{0}));
    EXPECT_EQ(decode(read2, 30, 7), std::pair(Direction::Request, std::uint64_t{0}));
    // The same bytes again are the request repeated; AK 14 only a command has.
    EXPECT_EQ(decode(read2, 35, 8), std::pair(Direction::Request, std::uint64_t{0}));
    EXPECT_EQ(decode(write, 40, 9), std::pair(Direction::Request, std::uint64_t{0}));
    // Past the response window a telegram is no answer.
    EXPECT_EQ(decode(read1, 50, 10), std::pair(Direction::Request, std::uint64_t{0}));
    EXPECT_EQ(decode(answer1, 5000, 11), std::pair(Direction::Request, std::uint64_t{0}));
}

TEST(FcDecoderTest, AProcessBlockDoesNotAnswerAParameterBlock) {
    FcDecoder decoder;
    const Telegram read = fc(0x01, hex("11 9E 00 00 00 00 00 00 04 7F 20 00"));
    const Telegram process = fc(0x01, hex("04 7F 20 00"));
    const Telegram status = fc(0x01, hex("06 07 20 00"));
    EXPECT_EQ(decoder.decode(span_of(read), 0, 1).direction, Direction::Request);
    EXPECT_EQ(decoder.decode(span_of(process), kMs, 2).direction, Direction::Request);
    EXPECT_EQ(decoder.decode(span_of(status), 2 * kMs, 3).direction, Direction::Response);
}

// --- Truncated and corrupted ----------------------------------------------------------------

TEST(FcDecoderTest, BccErrorIsAProblemWithBothValues) {
    Telegram bytes = hex("02 06 81 04 7F 20 00 DE");
    bytes.back() = 0xDF;
    FcDecoder decoder;
    const DecodedTelegram& t = decoder.decode(span_of(bytes), 0, 1);
    ASSERT_EQ(t.problems().size(), 1u);
    EXPECT_EQ(t.problems()[0].kind, ProblemKind::BccMismatch);
    EXPECT_EQ(t.problems()[0].offset, 7);
    EXPECT_EQ(t.problems()[0].expected, 0xDEu);
    EXPECT_EQ(t.problems()[0].actual, 0xDFu);
    EXPECT_FALSE(t.fc.bcc_ok);
    EXPECT_EQ(t.fc.pcd1, 0x047F) << "the fields are still read";
    EXPECT_NE(problem_message(t.problems()[0]).find("BCC"), std::string::npos);
}

TEST(FcDecoderTest, EveryPrefixIsTruncatedAndNeverCrashes) {
    const Telegram whole = hex("02 0E 81 11 9E 00 00 00 00 00 00 04 7F 20 00 59");
    for (std::size_t n = 0; n < whole.size(); ++n) {
        const Telegram part(whole.begin(), whole.begin() + static_cast<std::ptrdiff_t>(n));
        FcDecoder decoder;
        const DecodedTelegram& t = decoder.decode(span_of(part), 0, 1);
        ASSERT_FALSE(t.problems().empty()) << n;
        EXPECT_EQ(t.problems()[0].kind, n == 0 ? ProblemKind::EmptyRecord : ProblemKind::Truncated)
            << n;
        EXPECT_FALSE(t.fc.complete);
        // Only the BCC missing: every field is there to read.
        EXPECT_EQ(t.fc.has_pcd, n == whole.size() - 1) << n;
    }
}

TEST(FcDecoderTest, WrongStartLengthAndTrailingBytes) {
    FcDecoder decoder;
    const Telegram no_stx = hex("03 06 81 04 7F 20 00 DE");
    const DecodedTelegram& a = decoder.decode(span_of(no_stx), 0, 1);
    ASSERT_FALSE(a.problems().empty());
    EXPECT_EQ(a.problems()[0].kind, ProblemKind::BadStartDelimiter);
    EXPECT_NE(problem_message(a.problems()[0]).find("STX"), std::string::npos);
    const Telegram bad_lge = hex("02 08 81 04 7F 20 00 00 00 00");
    EXPECT_TRUE(
        decoder.decode(span_of(bad_lge), 0, 2).problems().contains(ProblemKind::LgeInvalid));
    Telegram trailing = hex("02 06 81 04 7F 20 00 DE");
    trailing.push_back(0x55);
    const DecodedTelegram& c = decoder.decode(span_of(trailing), 0, 3);
    EXPECT_TRUE(c.problems().contains(ProblemKind::TrailingBytes));
    EXPECT_TRUE(c.fc.bcc_ok);
}

TEST(FcDecoderTest, SingleBitErrorsNeverCrash) {
    const Telegram whole = hex("02 0E 81 11 9E 00 00 00 00 00 00 04 7F 20 00 59");
    FcDecoder decoder;
    for (std::size_t i = 0; i < whole.size() * 8; ++i) {
        Telegram bytes = whole;
        bytes[i / 8] ^= static_cast<std::uint8_t>(1u << (i % 8));
        const DecodedTelegram& t = decoder.decode(span_of(bytes), 0, i + 1);
        EXPECT_FALSE(t.problems().empty()) << "bit " << i << " must be noticed";
    }
}

// --- Framing --------------------------------------------------------------------------------

struct Collect final : StreamFramer::Sink {
    std::vector<Telegram> telegrams;
    std::vector<SkippedBytes> skipped;
    void on_telegram(Bytes telegram, std::uint64_t) override {
        telegrams.emplace_back(telegram.begin(), telegram.end());
    }
    void on_skipped(const SkippedBytes& s) override { skipped.push_back(s); }
};

TEST(FcFramingTest, SplitsEveryBlockInAnyChunking) {
    const Telegram process = hex("02 06 81 04 7F 20 00 DE");
    const Telegram parameter = hex("02 0E 81 11 9E 00 00 00 00 00 00 04 7F 20 00 59");
    Telegram text_data = hex("F0 01 04 00");
    for (char c : std::string("Hello"))
        text_data.push_back(static_cast<std::uint8_t>(c));
    for (std::uint8_t b : hex("06 07 00 00"))
        text_data.push_back(b);
    const Telegram text = fc(0x81, text_data);
    Telegram stream;
    for (const Telegram* t : {&process, &parameter, &text, &process})
        stream.insert(stream.end(), t->begin(), t->end());
    for (std::size_t chunk = 1; chunk <= stream.size(); ++chunk) {
        StreamFramer framer(fc_framing_rules());
        Collect sink;
        for (std::size_t at = 0; at < stream.size(); at += chunk)
            framer.feed(Bytes(stream.data() + at, std::min(chunk, stream.size() - at)), sink);
        framer.finish(sink);
        ASSERT_EQ(sink.telegrams.size(), 4u) << chunk;
        EXPECT_EQ(sink.telegrams[1], parameter);
        EXPECT_EQ(sink.telegrams[2], text);
        EXPECT_TRUE(sink.skipped.empty());
    }
}

TEST(FcFramingTest, ResynchronisesByteByByteAfterGarbageAndBadLengths) {
    const Telegram process = hex("02 06 81 04 7F 20 00 DE");
    // Garbage, an STX with an LGE of 8 (no block), an STX with LGE 6 whose BCC fails while no
    // telegram follows it, then a good telegram.
    Telegram stream = hex("55 AA 02 08 02 06 81 04 7F 20 00 00 11");
    stream.insert(stream.end(), process.begin(), process.end());
    StreamFramer framer(fc_framing_rules());
    Collect sink;
    framer.feed(Bytes(stream.data(), stream.size()), sink);
    framer.finish(sink);
    ASSERT_EQ(sink.telegrams.size(), 1u);
    EXPECT_EQ(sink.telegrams[0], process);
    ASSERT_FALSE(sink.skipped.empty());
    std::uint64_t skipped = 0;
    for (const SkippedBytes& s : sink.skipped)
        skipped += s.count;
    EXPECT_EQ(skipped, stream.size() - process.size());
}

TEST(FcFramingTest, WrongBccAcceptedOnlyBeforeAnotherTelegramOrTheEnd) {
    const Telegram good = hex("02 06 81 04 7F 20 00 DE");
    const Telegram bad = hex("02 06 81 04 7F 20 00 00");
    const Telegram stream =
        hex("02 06 81 04 7F 20 00 00 02 06 81 04 7F 20 00 DE 02 06 81 04 7F 20 00 00");
    StreamFramer framer(fc_framing_rules());
    Collect sink;
    framer.feed(Bytes(stream.data(), stream.size()), sink);
    framer.finish(sink);
    ASSERT_EQ(sink.telegrams.size(), 3u);
    EXPECT_EQ(sink.telegrams[0], bad);
    EXPECT_EQ(sink.telegrams[2], bad);
}

TEST(FcFramingTest, EveryProperPrefixNeedsMore) {
    const Telegram whole = hex("02 0E 81 11 9E 00 00 00 00 00 00 04 7F 20 00 59");
    for (std::size_t n = 1; n < whole.size(); ++n)
        EXPECT_EQ(fc_framing_rules().judge(Bytes(whole.data(), n), false).status,
                  FramingStatus::NeedMore)
            << n;
    EXPECT_EQ(fc_framing_rules().judge(span_of(whole), false).status, FramingStatus::Telegram);
    EXPECT_EQ(fc_framing_rules().judge(span_of(whole), false).length, whole.size());
    EXPECT_EQ(fc_framing_rules().protocol_name(), "FC protocol");
}

}  // namespace
}  // namespace dpscope
