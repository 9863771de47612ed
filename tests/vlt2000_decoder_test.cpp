// The VLT 2000 serial telegram: the decoder's fields (address, letter, control/status word,
// parameter, value with its decimal point, index, failure with reason code, checksum), its
// command/reply inference, the code tables, truncated and corrupted telegrams, and the framing
// rules in a byte stream. The worked examples are those of ../shared/protocol.md §7.5 and the
// seed's value example (docs/protocol/vlt2000.md).
#include "protocols/vlt2000/vlt2000_decoder.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/stream_framer.hpp"
#include "protocols/vlt2000/vlt2000_codes.hpp"
#include "protocols/vlt2000/vlt2000_framing_rules.hpp"

namespace dpscope {
namespace {

using Telegram = std::vector<std::uint8_t>;

Telegram bytes_of(const std::string& text) { return Telegram(text.begin(), text.end()); }
Bytes span_of(const Telegram& bytes) { return Bytes(bytes.data(), bytes.size()); }

// '<' + the 18 characters of bytes 2-19 + their checksum + '>'.
std::string vlt(const std::string& body) {
    EXPECT_EQ(body.size(), 18u) << body;
    unsigned sum = 0;
    for (char c : body)
        sum += static_cast<unsigned char>(c);
    const unsigned checksum = sum % 100;
    std::string out = "<" + body;
    out.push_back(static_cast<char>('0' + checksum / 10));
    out.push_back(static_cast<char>('0' + checksum % 10));
    out.push_back('>');
    return out;
}

constexpr std::int64_t kMs = 1'000'000;

// --- Worked examples ------------------------------------------------------------------------

TEST(Vlt2000DecoderTest, WorkedExampleOfTheVlt3000Manual) {
    // §7.5: "<01UOGD@0516+000800" sums to 1007 over bytes 2-19: checksum 07.
    EXPECT_EQ(vlt("01UOGD@0516+000800"), "<01UOGD@0516+00080007>");
    const Telegram bytes = bytes_of("<01UOGD@0516+00080007>");
    EXPECT_EQ(vlt2000_checksum_of(span_of(bytes)), 7);
    Vlt2000Decoder decoder;
    const DecodedTelegram& t = decoder.decode(span_of(bytes), 0, 1);
    EXPECT_EQ(t.protocol, Protocol::Vlt2000);
    EXPECT_TRUE(t.problems().empty());
    const Vlt2000Telegram& v = t.vlt2000;
    EXPECT_TRUE(v.complete);
    EXPECT_EQ(v.address, 1);
    EXPECT_FALSE(v.broadcast);
    EXPECT_EQ(v.letter, Vlt2000Letter::Update);
    EXPECT_EQ(v.letter_char, 'U');
    ASSERT_TRUE(v.has_word);
    EXPECT_EQ(v.word, 0x047F);  // O G D @: bits 3-0 = F, 7-4 = 7, 11-8 = 4, 15-12 = 0
    EXPECT_EQ(v.word_keep, 0);
    ASSERT_TRUE(v.has_parameter);
    EXPECT_EQ(v.parameter, 516);
    EXPECT_FALSE(v.negative);
    ASSERT_TRUE(v.has_value);
    EXPECT_EQ(v.digits, 80u);  // "00080"
    ASSERT_TRUE(v.has_decimals);
    EXPECT_EQ(v.decimals, 0);
    EXPECT_DOUBLE_EQ(v.value(), 80.0);
    EXPECT_FALSE(v.failed);
    EXPECT_TRUE(v.has_checksum);
    EXPECT_EQ(v.checksum, 7);
    EXPECT_EQ(v.checksum_computed, 7);
    EXPECT_TRUE(v.checksum_ok);
    EXPECT_FALSE(v.checksum_disabled);
    EXPECT_TRUE(t.has_roles);
    EXPECT_EQ(t.master, 0);
    EXPECT_EQ(t.slave, 1);
    EXPECT_EQ(t.direction, Direction::Request);

    // The reply: the same letter, status word G H K @ = 0x0B87.
    const Telegram reply = bytes_of("<01UGHK@0516+00080007>");
    const DecodedTelegram& r = decoder.decode(span_of(reply), 5 * kMs, 2);
    EXPECT_TRUE(r.problems().empty());
    EXPECT_EQ(r.direction, Direction::Response);
    EXPECT_EQ(r.request_frame, 1u);
    EXPECT_EQ(r.vlt2000.word, 0x0B87);
}

TEST(Vlt2000DecoderTest, StatusWordOfTheExampleReadsAsTheManualSays) {
    // 0x0B87: bits 0, 1, 2, 7, 8, 9, 11 set: ready, running at the reference, a warning; bit
    // 10 clear: out of the frequency range [P:VLT3000 p80].
    EXPECT_EQ(vlt2000_status_bit(0).when_1, "control ready");
    EXPECT_EQ(vlt2000_status_bit(1).when_1, "VLT ready");
    EXPECT_EQ(vlt2000_status_bit(7).when_1, "warning");
    EXPECT_EQ(vlt2000_status_bit(8).when_1, "speed at reference");
    EXPECT_EQ(vlt2000_status_bit(10).when_0, "out of frequency range");
    EXPECT_EQ(vlt2000_status_bit(11).when_1, "running");
    // Control word bit 10 must be 1 for any command to act [P:VLT2010 p36]; bits 0-2 are OFF1-3.
    EXPECT_EQ(vlt2000_control_bit(10).when_1, "data valid");
    EXPECT_EQ(vlt2000_control_bit(0).when_1, "ON1");
    EXPECT_EQ(vlt2000_control_bit(2).when_0, "OFF3 (quick stop, relay off)");
    EXPECT_EQ(vlt2000_control_bit(16).when_1, "");
}

TEST(Vlt2000DecoderTest, SeedValueExampleAppliesTheDecimalPoint) {
    // [S004]: 23.75 is sent as "+23750" with byte 19 = 3.
    const Telegram bytes = bytes_of(vlt("07U@@@@0205+237503"));
    Vlt2000Decoder decoder;
    const Vlt2000Telegram& v = decoder.decode(span_of(bytes), 0, 1).vlt2000;
    EXPECT_TRUE(v.problems.empty());
    EXPECT_EQ(v.address, 7);
    EXPECT_EQ(v.digits, 23750u);
    EXPECT_EQ(v.decimals, 3);
    EXPECT_DOUBLE_EQ(v.value(), 23.75);
    EXPECT_EQ(v.signed_digits(), 23750);

    // Any character but '-' is '+' [S004].
    const Telegram minus = bytes_of(vlt("07U@@@@0205-002501"));
    const Telegram space = bytes_of(vlt("07U@@@@0205 002501"));
    EXPECT_DOUBLE_EQ(decoder.decode(span_of(minus), 0, 2).vlt2000.value(), -25.0);
    EXPECT_DOUBLE_EQ(decoder.decode(span_of(space), 0, 3).vlt2000.value(), 25.0);
}

TEST(Vlt2000DecoderTest, EveryLetterAndItsEngineCode) {
    struct Case {
        char c;
        Vlt2000Letter letter;
        std::uint8_t code;
    };
    for (const Case& c : {Case{'U', Vlt2000Letter::Update, kVlt2000CodeUpdate},
                          Case{'R', Vlt2000Letter::Read, kVlt2000CodeRead},
                          Case{'C', Vlt2000Letter::Control, kVlt2000CodeControl},
                          Case{'I', Vlt2000Letter::ReadIndex, kVlt2000CodeReadIndex}}) {
        EXPECT_EQ(vlt2000_letter_of(static_cast<std::uint8_t>(c.c)), c.letter) << c.c;
        EXPECT_EQ(vlt2000_letter_char(c.letter), c.c);
        EXPECT_EQ(vlt2000_code(c.letter), c.code);
        EXPECT_EQ(vlt2000_letter_of_code(c.code), c.letter);
        EXPECT_EQ(vlt2000_judge_answer(c.code, c.code), AnswerVerdict::Positive);
        EXPECT_EQ(vlt2000_judge_answer(c.code, kVlt2000CodeFailed), AnswerVerdict::Negative);
        EXPECT_EQ(judge_answer(Dialect::Vlt2000, c.code, c.code, false), AnswerVerdict::Positive);
        EXPECT_TRUE(request_code(Dialect::Vlt2000, c.code).defined);
    }
    EXPECT_EQ(vlt2000_judge_answer(kVlt2000CodeRead, kVlt2000CodeUpdate), AnswerVerdict::Invalid);
    EXPECT_EQ(vlt2000_judge_answer(0, kVlt2000CodeRead), AnswerVerdict::Invalid);
    EXPECT_TRUE(request_code(Dialect::Vlt2000, kVlt2000CodeUpdate).is_change);
    EXPECT_EQ(response_code(Dialect::Vlt2000, kVlt2000CodeFailed).kind, ResponseKind::Rejected);
    EXPECT_EQ(vlt2000_letter_name(Vlt2000Letter::ReadIndex), "read index");
    EXPECT_EQ(dialect_name(Dialect::Vlt2000), "vlt2000");
    EXPECT_FALSE(dialect_from_name("vlt2000"));  // not a PROFIBUS slave's dialect
}

TEST(Vlt2000DecoderTest, ReadIndexCarriesTheIndexInBytes13To18) {
    const Telegram bytes = bytes_of(vlt("03I@@D@0600+000120"));
    Vlt2000Decoder decoder;
    const Vlt2000Telegram& v = decoder.decode(span_of(bytes), 0, 1).vlt2000;
    EXPECT_TRUE(v.problems.empty());
    EXPECT_EQ(v.letter, Vlt2000Letter::ReadIndex);
    EXPECT_EQ(v.parameter, 600);
    ASSERT_EQ(v.index.size(), 6u);
    EXPECT_TRUE(v.has_index_number);
    EXPECT_EQ(v.index_number, 12u);
    // The VLT 3000's two-dimensional index "x,y" is shown as sent, without a number.
    const Telegram two = bytes_of(vlt("03I@@D@0600003,012"));
    Vlt2000Decoder other;  // a second I to drive 03 would be taken for the first one's reply
    const Vlt2000Telegram& w = other.decode(span_of(two), 0, 2).vlt2000;
    EXPECT_TRUE(w.problems.empty());
    EXPECT_FALSE(w.has_index_number);
    EXPECT_EQ(std::string(w.index.begin(), w.index.end()), "003,01");
    // The reply carries the element's value where the command had the index.
    Vlt2000Decoder paired;
    paired.decode(span_of(bytes), 0, 1);
    const Telegram reply = bytes_of(vlt("03IGHK@0600+004501"));
    const DecodedTelegram& r = paired.decode(span_of(reply), kMs, 2);
    EXPECT_EQ(r.direction, Direction::Response);
    EXPECT_TRUE(r.vlt2000.index.empty());
    EXPECT_FALSE(r.vlt2000.has_index_number);
    ASSERT_TRUE(r.vlt2000.has_value);
    EXPECT_DOUBLE_EQ(r.vlt2000.value(), 45.0);  // "00450" with 1 decimal
}

TEST(Vlt2000DecoderTest, FailedReplyCarriesItsReasonCode) {
    Vlt2000Decoder decoder;
    const Telegram command = bytes_of(vlt("02R@@D@0999+000000"));
    EXPECT_EQ(decoder.decode(span_of(command), 0, 1).direction, Direction::Request);
    // Decimal position 9, reason 00 in bytes 17-18: parameter does not exist [P:VLT3000 p80].
    const Telegram failed = bytes_of(vlt("02RGH@@0999+000009"));
    const DecodedTelegram& t = decoder.decode(span_of(failed), 3 * kMs, 2);
    EXPECT_TRUE(t.problems().empty());
    EXPECT_EQ(t.direction, Direction::Response);
    EXPECT_EQ(t.request_frame, 1u);
    EXPECT_TRUE(t.vlt2000.failed);
    ASSERT_TRUE(t.vlt2000.has_reason);
    EXPECT_EQ(t.vlt2000.reason, 0);
    EXPECT_EQ(vlt2000_reason_text(0), "parameter does not exist");
    EXPECT_EQ(vlt2000_reason_text(4), "read only, e.g. factory set-up selected");
    EXPECT_EQ(error_text_or_unknown(Dialect::Vlt2000, 42), kUnknownReasonCode);
    // Without digits in bytes 17-18 there is no reason code (the VLT 2000: "unknown parameter").
    const Telegram plain = bytes_of(vlt("02RGH@@0999+000xx9"));
    const Vlt2000Telegram& p = decoder.decode(span_of(plain), 4 * kMs, 3).vlt2000;
    EXPECT_TRUE(p.failed);
    EXPECT_FALSE(p.has_reason);
    EXPECT_TRUE(p.problems.empty());
}

// Every reason code the VLT 3000 and VLT 3500 manuals list has its text: 00-04 [P:VLT3000 p80],
// 05-08 and 99 [P:VLT3500 p92]; any other number has none.
TEST(Vlt2000DecoderTest, EveryDocumentedReasonCodeHasItsText) {
    EXPECT_EQ(vlt2000_reason_text(5), "cannot be changed while the motor is running");
    EXPECT_EQ(vlt2000_reason_text(6), "value outside the parameter's range");
    EXPECT_EQ(vlt2000_reason_text(7), "illegal value in byte 19, the decimal position");
    EXPECT_EQ(vlt2000_reason_text(8), "value read is above 99999");
    EXPECT_EQ(vlt2000_reason_text(99), "other fault");
    for (std::uint32_t reason : {9u, 10u, 42u, 98u, 100u})
        EXPECT_EQ(vlt2000_reason_text(reason), "");
    EXPECT_EQ(error_text_or_unknown(Dialect::Vlt2000, 99), "other fault");
    EXPECT_EQ(error_text_or_unknown(Dialect::Vlt2000, 9), kUnknownReasonCode);
}

TEST(Vlt2000DecoderTest, QuestionMarksSwitchTheChecksumOff) {
    const Telegram bytes = bytes_of("<01C@@D@0000+000000?\?>");
    Vlt2000Decoder decoder;
    const Vlt2000Telegram& v = decoder.decode(span_of(bytes), 0, 1).vlt2000;
    EXPECT_TRUE(v.problems.empty());
    EXPECT_TRUE(v.checksum_disabled);
    EXPECT_FALSE(v.has_checksum);
    EXPECT_FALSE(v.checksum_ok);
    EXPECT_EQ(v.word, 0x0400);
}

TEST(Vlt2000DecoderTest, WrongChecksumIsAProblemUnlessIgnored) {
    const Telegram bytes = bytes_of("<01UOGD@0516+00080008>");
    Vlt2000Decoder decoder;
    const DecodedTelegram& t = decoder.decode(span_of(bytes), 0, 1);
    ASSERT_EQ(t.problems().size(), 1u);
    const Problem& p = t.problems()[0];
    EXPECT_EQ(p.kind, ProblemKind::Vlt2000ChecksumMismatch);
    EXPECT_EQ(p.offset, kVlt2000ChecksumAt);
    EXPECT_EQ(p.expected, 7u);
    EXPECT_EQ(p.actual, 8u);
    EXPECT_EQ(problem_message(p), "byte 20: checksum 08 wrong, the sum of bytes 2-19 ends in 07");
    EXPECT_FALSE(t.vlt2000.checksum_ok);

    Vlt2000DecoderOptions options;
    options.check_checksum = false;
    Vlt2000Decoder lenient(options);
    const DecodedTelegram& u = lenient.decode(span_of(bytes), 0, 1);
    EXPECT_TRUE(u.problems().empty());
    EXPECT_EQ(u.vlt2000.checksum_computed, 7);
    EXPECT_FALSE(u.vlt2000.checksum_ok);
}

TEST(Vlt2000DecoderTest, BroadcastIsAddress00AndExpectsNoReply) {
    Vlt2000Decoder decoder;
    const Telegram broadcast = bytes_of(vlt("00C@@D@0000+000000"));
    const DecodedTelegram& t = decoder.decode(span_of(broadcast), 0, 1);
    EXPECT_TRUE(t.vlt2000.broadcast);
    EXPECT_EQ(t.slave, 0);
    EXPECT_EQ(t.direction, Direction::Request);
    // A telegram from address 00 with the letter right after it is taken for a reply (the
    // tracker reports it: nobody replies to a broadcast).
    const Telegram answer = bytes_of(vlt("00CGH@@0000+000000"));
    const DecodedTelegram& r = decoder.decode(span_of(answer), 2 * kMs, 2);
    EXPECT_EQ(r.direction, Direction::Response);
    EXPECT_EQ(r.request_frame, 1u);
}

TEST(Vlt2000DecoderTest, DirectionByAddressLetterRepeatAndWindow) {
    Vlt2000Decoder decoder;
    const Telegram read1 = bytes_of(vlt("01R@@D@0516+000000"));
    const Telegram reply1 = bytes_of(vlt("01RGH@@0516+001002"));
    const Telegram read2 = bytes_of(vlt("02R@@D@0516+000000"));
    const Telegram other_letter = bytes_of(vlt("02UGH@@0516+001002"));
    EXPECT_EQ(decoder.decode(span_of(read1), 0, 1).direction, Direction::Request);
    // The same characters again: the master repeating itself, not a reply.
    EXPECT_EQ(decoder.decode(span_of(read1), 1 * kMs, 2).direction, Direction::Request);
    EXPECT_EQ(decoder.decode(span_of(reply1), 2 * kMs, 3).direction, Direction::Response);
    // Nothing pending: a command.
    EXPECT_EQ(decoder.decode(span_of(reply1), 3 * kMs, 4).direction, Direction::Request);
    EXPECT_EQ(decoder.decode(span_of(read2), 4 * kMs, 5).direction, Direction::Request);
    // Another letter than the command's: a command of its own.
    EXPECT_EQ(decoder.decode(span_of(other_letter), 5 * kMs, 6).direction, Direction::Request);
    // Later than the window: a command.
    Vlt2000DecoderOptions options;
    options.response_window_ns = 100 * kMs;
    Vlt2000Decoder windowed(options);
    EXPECT_EQ(windowed.decode(span_of(read1), 0, 1).direction, Direction::Request);
    EXPECT_EQ(windowed.decode(span_of(reply1), 200 * kMs, 2).direction, Direction::Request);
    // A command wrong only in its checksum may still be answered (the error may be the tap's);
    // one cut short or with a field that is no number expects no reply.
    Vlt2000Decoder fresh;
    const Telegram damaged = bytes_of("<01R@@D@0516+00000000>");
    ASSERT_FALSE(fresh.decode(span_of(damaged), 0, 1).problems().empty());
    const DecodedTelegram& answer = fresh.decode(span_of(reply1), kMs, 2);
    EXPECT_EQ(answer.direction, Direction::Response);
    EXPECT_EQ(answer.request_frame, 1u);
    const Telegram cut = bytes_of("<01R@@D@0516+0000");
    EXPECT_EQ(fresh.decode(span_of(cut), 2 * kMs, 3).direction, Direction::Request);
    EXPECT_EQ(fresh.decode(span_of(reply1), 3 * kMs, 4).direction, Direction::Request);
    // A trailing byte (a warning) does not keep the reply from being recognised.
    Telegram trailing = read1;
    trailing.push_back('\r');
    Vlt2000Decoder lenient;
    lenient.decode(span_of(trailing), 0, 1);
    EXPECT_EQ(lenient.decode(span_of(reply1), kMs, 2).direction, Direction::Response);
}

TEST(Vlt2000DecoderTest, PGroupsAreKeptGroupsOfTheVlt3000) {
    const Telegram bytes = bytes_of(vlt("01CPPD@0000+000000"));
    Vlt2000Decoder decoder;
    const Vlt2000Telegram& v = decoder.decode(span_of(bytes), 0, 1).vlt2000;
    EXPECT_EQ(v.word_keep, 0b0011);
    EXPECT_EQ(v.word, 0x0400);
}

TEST(Vlt2000DecoderTest, NonDigitsUnknownLetterAndEndDelimiterAreProblems) {
    Vlt2000Decoder decoder;
    const Telegram address = bytes_of(vlt("0xU@@@@0516+000000"));
    const DecodedTelegram& a = decoder.decode(span_of(address), 0, 1);
    ASSERT_FALSE(a.problems().empty());
    EXPECT_EQ(a.problems()[0].kind, ProblemKind::Vlt2000FieldInvalid);
    EXPECT_EQ(a.problems()[0].offset, 2);
    EXPECT_EQ(problem_message(a.problems()[0]), "byte 3: 'x' is not a digit (address)");
    EXPECT_FALSE(a.has_roles);

    const Telegram letter = bytes_of(vlt("01X@@@@0516+000000"));
    const DecodedTelegram& l = decoder.decode(span_of(letter), 0, 2);
    ASSERT_EQ(l.problems().size(), 1u);
    EXPECT_EQ(l.problems()[0].kind, ProblemKind::Vlt2000LetterUnknown);
    EXPECT_EQ(problem_message(l.problems()[0]), "byte 4: control letter 'X' is none of U, R, C, I");

    const Telegram parameter = bytes_of(vlt("01R@@@@05a6+000000"));
    EXPECT_EQ(decoder.decode(span_of(parameter), 0, 3).problems()[0].offset, 10);
    const Telegram value = bytes_of(vlt("01U@@@@0516+0#0000"));
    EXPECT_EQ(decoder.decode(span_of(value), 0, 4).problems()[0].offset, 14);
    const Telegram decimals = bytes_of(vlt("01U@@@@0516+00000x"));
    EXPECT_EQ(decoder.decode(span_of(decimals), 0, 5).problems()[0].offset, 18);

    Telegram end = bytes_of(vlt("01U@@@@0516+000000"));
    end[21] = '!';
    const DecodedTelegram& e = decoder.decode(span_of(end), 0, 6);
    ASSERT_EQ(e.problems().size(), 1u);
    EXPECT_EQ(e.problems()[0].kind, ProblemKind::BadEndDelimiter);
    EXPECT_EQ(problem_message(e.problems()[0]),
              "byte 22: end delimiter is '!', expected '>' (0x3E)");
}

// Found by fuzz_vlt2000_decoder (fuzz/corpus/fuzz_vlt2000_decoder/regression-control-character):
// a control character or a byte above 0x7E where no digit is checked (the word, the sign, an
// index) decoded without any problem, although the framer never takes such a telegram.
TEST(Vlt2000DecoderTest, CharacterOutsidePrintableAsciiIsAProblem) {
    Vlt2000Decoder decoder;
    Telegram word = bytes_of(vlt("01C@@@@0000+000000"));
    word[5] = 0x07;
    Telegram sign = bytes_of(vlt("01I@@@@0615+000003"));
    sign[12] = 0xA2;
    sign[19] = sign[20] = '?';  // no checksum: only the character is wrong
    for (const Telegram& bytes : {word, sign}) {
        const DecodedTelegram& t = decoder.decode(span_of(bytes), kNoTime, 1);
        ASSERT_TRUE(t.problems().contains(ProblemKind::Vlt2000CharacterInvalid));
    }
    const DecodedTelegram& s = decoder.decode(span_of(sign), kNoTime, 2);
    ASSERT_EQ(s.problems().size(), 1u);
    EXPECT_EQ(s.problems()[0].offset, 12);
    EXPECT_EQ(problem_message(s.problems()[0]), "byte 13: 0xA2 is not printable ASCII");
    // The framing rules reject the same bytes.
    EXPECT_EQ(vlt2000_framing_rules().judge(span_of(sign), true).status, FramingStatus::Invalid);
}

// The characters are checked eight at a time: the first one outside printable ASCII is found at
// every place between '<' and '>', whichever kind it is, and a later one is not reported.
TEST(Vlt2000DecoderTest, TheFirstCharacterOutsidePrintableAsciiIsNamedWhereverItIs) {
    Vlt2000Decoder decoder;
    const Telegram whole = bytes_of("<01UOGD@0516+00080007>");
    for (std::size_t at = 1; at + 1 < whole.size(); ++at) {
        for (const std::uint8_t bad :
             std::initializer_list<std::uint8_t>{0x00, 0x1F, 0x7F, 0x80, 0xFF}) {
            Telegram bytes = whole;
            bytes[at] = bad;
            if (at + 2 < whole.size()) bytes[at + 1] = 0x01;  // a second one, after it
            const DecodedTelegram& t = decoder.decode(span_of(bytes), kNoTime, 1);
            std::size_t found = 0;
            for (const Problem& p : t.problems())
                if (p.kind == ProblemKind::Vlt2000CharacterInvalid) {
                    ++found;
                    EXPECT_EQ(p.offset, at) << int{bad};
                }
            EXPECT_EQ(found, 1u) << at << " " << int{bad};
        }
    }
    // Every printable character passes.
    Telegram printable = whole;
    for (std::uint8_t c = 0x20; c <= 0x7E; ++c) {
        printable[1 + (c % 20)] = c;
        EXPECT_FALSE(decoder.decode(span_of(printable), kNoTime, 1)
                         .problems()
                         .contains(ProblemKind::Vlt2000CharacterInvalid))
            << int{c};
    }
}

TEST(Vlt2000DecoderTest, EveryPrefixIsTruncatedAndNeverCrashes) {
    const Telegram whole = bytes_of("<01UOGD@0516+00080007>");
    Vlt2000Decoder decoder;
    EXPECT_TRUE(decoder.decode(Bytes(), 0, 1).problems().contains(ProblemKind::EmptyRecord));
    for (std::size_t n = 1; n < whole.size(); ++n) {
        const DecodedTelegram& t = decoder.decode(Bytes(whole.data(), n), 0, n + 1);
        ASSERT_FALSE(t.problems().empty()) << n;
        EXPECT_EQ(t.problems()[0].kind, ProblemKind::Truncated) << n;
        EXPECT_FALSE(t.vlt2000.complete);
        EXPECT_EQ(t.problems()[0].expected, kVlt2000TelegramSize);
    }
    // Fields before the cut are read: the address and letter after 4 characters.
    const DecodedTelegram& t = decoder.decode(Bytes(whole.data(), 4), 0, 99);
    EXPECT_EQ(t.vlt2000.address, 1);
    EXPECT_EQ(t.vlt2000.letter, Vlt2000Letter::Update);
    EXPECT_FALSE(t.vlt2000.has_word);
}

TEST(Vlt2000DecoderTest, WrongStartAndTrailingBytes) {
    Vlt2000Decoder decoder;
    const Telegram start = bytes_of("(01UOGD@0516+00080007>");
    const DecodedTelegram& s = decoder.decode(span_of(start), 0, 1);
    ASSERT_EQ(s.problems().size(), 1u);
    EXPECT_EQ(s.problems()[0].kind, ProblemKind::BadStartDelimiter);
    EXPECT_EQ(problem_message(s.problems()[0]), "byte 1: '(' is not '<' (0x3C)");
    Telegram longer = bytes_of("<01UOGD@0516+00080007>");
    longer.push_back('\r');
    const DecodedTelegram& l = decoder.decode(span_of(longer), 0, 2);
    ASSERT_EQ(l.problems().size(), 1u);
    EXPECT_EQ(l.problems()[0].kind, ProblemKind::TrailingBytes);
    EXPECT_EQ(l.problems()[0].offset, kVlt2000TelegramSize);
    EXPECT_EQ(problem_message(l.problems()[0]), "byte 23: 1 byte after the end of the telegram");
}

// Messages number a telegram's bytes 1-22 as the VLT 2000 manual does [S004] (byte 19 is the
// decimal position, bytes 20-21 the checksum); a problem's offset stays the 0-based position in
// the record, as for every bus.
TEST(Vlt2000DecoderTest, MessagesNumberTheBytesAsTheManual) {
    Vlt2000Decoder decoder;
    const Telegram decimals = bytes_of(vlt("01U@@@@0516+00000x"));
    const Problem p = decoder.decode(span_of(decimals), 0, 1).problems()[0];
    EXPECT_EQ(p.offset, kVlt2000DecimalsAt);
    EXPECT_EQ(problem_message(p), "byte 19: 'x' is not a digit (decimal position)");
    const Telegram checksum = bytes_of("<01UOGD@0516+0008000x>");
    EXPECT_EQ(problem_message(decoder.decode(span_of(checksum), 0, 2).problems()[0]),
              "byte 21: 'x' is not a digit (checksum)");
    const Telegram parameter = bytes_of(vlt("01R@@@@05a6+000000"));
    EXPECT_EQ(problem_message(decoder.decode(span_of(parameter), 0, 3).problems()[0]),
              "byte 11: 'a' is not a digit (parameter number)");
    // Other buses keep 0-based byte numbers.
    EXPECT_EQ(problem_message(Problem{ProblemKind::TrailingBytes, 13, 0, 2}),
              "byte 13: 2 bytes after the end of the telegram");
    // The framer's words for a candidate it skips count the same way.
    const Telegram no_stop = bytes_of("<01UOGD@0516+00080007!<");
    const FramingVerdict verdict = vlt2000_framing_rules().judge(span_of(no_stop), true);
    ASSERT_EQ(verdict.status, FramingStatus::Invalid);
    EXPECT_EQ(vlt2000_framing_rules().describe_skip(
                  SkippedBytes{0, 22, verdict.reason, verdict.reason_offset}),
              "skipped 22 bytes: no '>' at the telegram's end (byte 22 of the candidate telegram)");
}

TEST(Vlt2000DecoderTest, SingleBitErrorsAreAlwaysNoticed) {
    // The checksum is a decimal sum: flipping bit k of one character changes the sum by 2^k
    // (1..128), never a multiple of 100. The delimiters and checksum digits are checked as such.
    const Telegram whole = bytes_of("<01UOGD@0516+00080007>");
    Vlt2000Decoder decoder;
    for (std::size_t i = 0; i < whole.size() * 8; ++i) {
        Telegram bytes = whole;
        bytes[i / 8] ^= static_cast<std::uint8_t>(1u << (i % 8));
        const DecodedTelegram& t = decoder.decode(span_of(bytes), 0, i + 1);
        // A control-word character's high nibble is ignored by the drive, but the checksum
        // still covers it.
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

TEST(Vlt2000FramingTest, SplitsTelegramsInAnyChunking) {
    const std::vector<std::string> telegrams = {"<01UOGD@0516+00080007>", "<01UGHK@0516+00080007>",
                                                vlt("00C@@D@0000+000000"),
                                                "<02R@@D@0205+000000?\?>"};
    std::string stream;
    for (const std::string& t : telegrams)
        stream += t;
    const Telegram bytes = bytes_of(stream);
    for (std::size_t chunk = 1; chunk <= bytes.size(); ++chunk) {
        StreamFramer framer(vlt2000_framing_rules());
        Collect sink;
        for (std::size_t at = 0; at < bytes.size(); at += chunk)
            framer.feed(Bytes(bytes.data() + at, std::min(chunk, bytes.size() - at)), sink);
        framer.finish(sink);
        ASSERT_EQ(sink.telegrams.size(), telegrams.size()) << chunk;
        for (std::size_t i = 0; i < telegrams.size(); ++i)
            EXPECT_EQ(sink.telegrams[i], bytes_of(telegrams[i])) << chunk;
        EXPECT_TRUE(sink.skipped.empty());
    }
}

TEST(Vlt2000FramingTest, ResynchronisesOnTheNextStartAfterGarbageAndABrokenTelegram) {
    // Garbage, a telegram cut off by the next '<' (its 22nd character is no '>'), a control
    // character inside a candidate, then a good telegram.
    const std::string good = "<01UOGD@0516+00080007>";
    const std::string stream = "xyz<01UOGD@05" + good + "<01U\x01" + "GD@0516+00080007>" + good;
    const Telegram bytes = bytes_of(stream);
    StreamFramer framer(vlt2000_framing_rules());
    Collect sink;
    framer.feed(span_of(bytes), sink);
    framer.finish(sink);
    ASSERT_EQ(sink.telegrams.size(), 2u);
    EXPECT_EQ(sink.telegrams[0], bytes_of(good));
    EXPECT_EQ(sink.telegrams[1], bytes_of(good));
    std::uint64_t skipped = 0;
    for (const SkippedBytes& s : sink.skipped)
        skipped += s.count;
    EXPECT_EQ(skipped, bytes.size() - 2 * good.size());
}

TEST(Vlt2000FramingTest, WrongChecksumIsADamagedTelegramUnlessAStartIsInside) {
    const Telegram bad = bytes_of("<01UOGD@0516+00080008>");
    EXPECT_EQ(vlt2000_framing_rules().judge(span_of(bad), false).status, FramingStatus::Telegram);
    // A '<' inside: where a telegram may begin that a broken one ran into.
    const Telegram inner = bytes_of("<01UOGD@<516+00080008>");
    const FramingVerdict v = vlt2000_framing_rules().judge(span_of(inner), false);
    EXPECT_EQ(v.status, FramingStatus::Invalid);
    EXPECT_EQ(v.reason, ProblemKind::Vlt2000ChecksumMismatch);
    // "??" needs no sum.
    EXPECT_EQ(
        vlt2000_framing_rules().judge(span_of(bytes_of("<01UOGD@<516+000800?\?>")), false).status,
        FramingStatus::Telegram);
}

TEST(Vlt2000FramingTest, EveryProperPrefixNeedsMore) {
    const Telegram whole = bytes_of("<01UOGD@0516+00080007>");
    for (std::size_t n = 1; n < whole.size(); ++n) {
        EXPECT_EQ(vlt2000_framing_rules().judge(Bytes(whole.data(), n), false).status,
                  FramingStatus::NeedMore)
            << n;
        EXPECT_EQ(vlt2000_framing_rules().judge(Bytes(whole.data(), n), true).status,
                  FramingStatus::NeedMore)
            << n;
    }
    const FramingVerdict v = vlt2000_framing_rules().judge(span_of(whole), false);
    EXPECT_EQ(v.status, FramingStatus::Telegram);
    EXPECT_EQ(v.length, whole.size());
    EXPECT_EQ(vlt2000_framing_rules().protocol_name(), "VLT 2000");
    EXPECT_TRUE(vlt2000_framing_rules().can_start('<'));
    EXPECT_FALSE(vlt2000_framing_rules().can_start('>'));
}

}  // namespace
}  // namespace dpscope
