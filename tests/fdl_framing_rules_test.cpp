// FDL framing rules: which bytes start a telegram, the verdict on every frame type (whole, cut off,
// malformed), the FCS rule for SD1/SD3 and the words for skipped bytes.
#include "protocols/profibus/fdl_framing_rules.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "protocols/profibus/fdl.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::hex;

// FDL status request from master 2 to station 3 (FCS 4E).
const std::vector<std::uint8_t> kSd1 = hex("10 03 02 49 4E 16");
// Chk_Cfg F3 F1 from 2 to 3 with SAPs 62/62.
const std::vector<std::uint8_t> kSd2 = hex("68 07 07 68 83 82 7D 3E 3E F3 F1 E2 16");

FramingVerdict check(const std::vector<std::uint8_t>& bytes, bool ended = false) {
    return fdl_framing_rules().judge(Bytes(bytes.data(), bytes.size()), ended);
}

TEST(FdlFramingRulesTest, JudgeDecidesStreamBoundaries) {
    EXPECT_EQ(check(kSd1).status, FramingStatus::Telegram);
    EXPECT_EQ(check(kSd1).length, 6);
    EXPECT_EQ(check(hex("10 03 02")).status, FramingStatus::NeedMore);
    EXPECT_EQ(check(kSd2).length, 13);
    EXPECT_EQ(check(hex("68 07 07 68 83")).status, FramingStatus::NeedMore);
    FramingVerdict bad_ler = check(hex("68 07 08 68"));
    EXPECT_EQ(bad_ler.status, FramingStatus::Invalid);
    EXPECT_EQ(bad_ler.reason, ProblemKind::LengthMismatch);
    EXPECT_EQ(check(hex("42")).reason, ProblemKind::BadStartDelimiter);
    EXPECT_EQ(check(hex("E5")).length, 1);
    EXPECT_EQ(check(hex("DC 02 02")).length, 3);
    // SD2 with a wrong FCS but intact structure is still a telegram.
    auto bad_fcs = kSd2;
    bad_fcs[11] ^= 1;
    EXPECT_EQ(check(bad_fcs).status, FramingStatus::Telegram);
    // SD1 with a wrong FCS: believed only when a telegram follows or the input ended.
    auto sd1_bad = hex("10 03 02 49 4F 16");
    EXPECT_EQ(check(sd1_bad).status, FramingStatus::NeedMore);
    EXPECT_EQ(check(sd1_bad, true).status, FramingStatus::Telegram);
    auto followed = sd1_bad;
    followed.push_back(0xE5);
    EXPECT_EQ(check(followed).status, FramingStatus::Telegram);
    auto garbage_after = sd1_bad;
    garbage_after.push_back(0x42);
    EXPECT_EQ(check(garbage_after).status, FramingStatus::Invalid);
    EXPECT_EQ(check(garbage_after).reason, ProblemKind::FcsMismatch);
}

TEST(FdlFramingRulesTest, StartBytesAreTheStartDelimiters) {
    for (int byte = 0; byte < 256; ++byte) {
        const auto b = static_cast<std::uint8_t>(byte);
        EXPECT_EQ(fdl_framing_rules().can_start(b), is_start_delimiter(b)) << byte;
    }
    EXPECT_TRUE(fdl_framing_rules().can_start(0x68));
    EXPECT_FALSE(fdl_framing_rules().can_start(kEndDelimiter));
}

TEST(FdlFramingRulesTest, ReasonsCarryTheFailingByte) {
    FramingVerdict le = check(hex("68 02"));
    EXPECT_EQ(le.reason, ProblemKind::LengthOutOfRange);
    EXPECT_EQ(le.reason_offset, 1);
    FramingVerdict sd = check(hex("68 07 07 10"));
    EXPECT_EQ(sd.reason, ProblemKind::StartDelimiterRepeat);
    EXPECT_EQ(sd.reason_offset, 3);
    FramingVerdict ed = check(hex("68 03 03 68 01 02 03 06 17"));
    EXPECT_EQ(ed.reason, ProblemKind::BadEndDelimiter);
    EXPECT_EQ(ed.reason_offset, 8);
    FramingVerdict token = check(hex("DC 02 82"));
    EXPECT_EQ(token.reason, ProblemKind::InvalidAddress);
    EXPECT_EQ(token.reason_offset, 2);
}

TEST(FdlFramingRulesTest, DescribesSkippedBytesInFdlWords) {
    const FramingRules& rules = fdl_framing_rules();
    EXPECT_EQ(rules.protocol_name(), "PROFIBUS");
    auto words = [&](ProblemKind reason, std::uint64_t count, std::uint16_t at) {
        return rules.describe_skip(SkippedBytes{100, count, reason, at});
    };
    EXPECT_EQ(words(ProblemKind::BadStartDelimiter, 1, 0), "skipped 1 byte: no start delimiter");
    EXPECT_EQ(words(ProblemKind::Truncated, 7, 0),
              "skipped 7 bytes: telegram cut off (gap or end of input)");
    EXPECT_EQ(words(ProblemKind::LengthOutOfRange, 2, 1),
              "skipped 2 bytes: LE outside 3..249 (byte 1 of the candidate telegram)");
    EXPECT_EQ(words(ProblemKind::LengthMismatch, 4, 2),
              "skipped 4 bytes: LEr differs from LE (byte 2 of the candidate telegram)");
    EXPECT_EQ(words(ProblemKind::StartDelimiterRepeat, 4, 3),
              "skipped 4 bytes: repeated start delimiter is not 0x68 (byte 3 of the candidate "
              "telegram)");
    EXPECT_EQ(words(ProblemKind::BadEndDelimiter, 9, 8),
              "skipped 9 bytes: no end delimiter where the length puts it (byte 8 of the "
              "candidate telegram)");
    EXPECT_EQ(words(ProblemKind::FcsMismatch, 7, 4),
              "skipped 7 bytes: FCS wrong and no telegram follows (byte 4 of the candidate "
              "telegram)");
    EXPECT_EQ(words(ProblemKind::InvalidAddress, 3, 2),
              "skipped 3 bytes: token address with bit 7 set (byte 2 of the candidate telegram)");
}

}  // namespace
}  // namespace dpscope
