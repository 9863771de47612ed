// Telegram builder: frame type chosen by data length, FCS, round trips through parse_fdl and
// the FDL framing rules, and the PCV byte layout.
#include "protocols/profibus/telegram_builder.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "protocols/profibus/fdl_framing_rules.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::hex;

TelegramSpec spec_of(std::uint8_t da, std::uint8_t sa, std::uint8_t fc,
                     std::optional<std::uint8_t> dsap, std::optional<std::uint8_t> ssap,
                     const std::vector<std::uint8_t>& du) {
    TelegramSpec spec;
    spec.da = da;
    spec.sa = sa;
    spec.fc = fc;
    spec.dsap = dsap;
    spec.ssap = ssap;
    spec.du = Bytes(du.data(), du.size());
    return spec;
}

FdlTelegram parse(const std::vector<std::uint8_t>& bytes) {
    FdlTelegram t;
    parse_fdl(Bytes(bytes.data(), bytes.size()), t);
    return t;
}

TEST(TelegramBuilderTest, FrameControlBytes) {
    EXPECT_EQ(request_fc(FdlFunction::SrdHigh), 0x4D);
    EXPECT_EQ(request_fc(FdlFunction::SrdHigh, true, true), 0x7D);
    EXPECT_EQ(request_fc(FdlFunction::SrdLow, false, true), 0x5C);
    EXPECT_EQ(request_fc(FdlFunction::FdlStatus), 0x49);
    EXPECT_EQ(request_fc(FdlFunction::SdnHigh, true, false), 0x66);
    EXPECT_EQ(response_fc(FdlStatus::DataLow), 0x08);
    EXPECT_EQ(response_fc(FdlStatus::DataHigh), 0x0A);
    EXPECT_EQ(response_fc(FdlStatus::Ok, 3), 0x30);
    EXPECT_EQ(response_fc(FdlStatus::DataLow, 7), 0x38);  // station type is 2 bits
    FrameControl fc{request_fc(FdlFunction::SrdHigh, true, false)};
    EXPECT_TRUE(fc.is_request());
    EXPECT_TRUE(fc.fcb());
    EXPECT_FALSE(fc.fcv());
}

TEST(TelegramBuilderTest, NoDataGivesSd1) {
    auto bytes = build_telegram(
        spec_of(3, 2, request_fc(FdlFunction::FdlStatus), std::nullopt, std::nullopt, {}));
    EXPECT_EQ(bytes, hex("10 03 02 49 4E 16"));
}

TEST(TelegramBuilderTest, EightOctetsIncludingSapsGiveSd3) {
    // Slave_Diag response: 2 SAP bytes + 6 diagnosis bytes.
    auto du = hex("02 05 00 FF 04 02");
    auto bytes = build_telegram(spec_of(2, 3, response_fc(FdlStatus::DataLow), 62, 60, du));
    EXPECT_EQ(bytes, hex("A2 82 83 08 3E 3C 02 05 00 FF 04 02 93 16"));
}

TEST(TelegramBuilderTest, EightOctetsWithoutSapsGiveSd3) {
    auto du = hex("01 02 03 04 05 06 07 08");
    auto bytes = build_telegram(
        spec_of(3, 2, request_fc(FdlFunction::SrdHigh), std::nullopt, std::nullopt, du));
    ASSERT_EQ(bytes.size(), 14u);
    EXPECT_EQ(bytes[0], kSd3);
    EXPECT_EQ(bytes[1], 0x03);
    EXPECT_EQ(bytes[2], 0x02);
    EXPECT_EQ(bytes[3], 0x4D);
    EXPECT_EQ(std::vector<std::uint8_t>(bytes.begin() + 4, bytes.begin() + 12), du);
    EXPECT_EQ(bytes[12], static_cast<std::uint8_t>(0x03 + 0x02 + 0x4D + 36));
    EXPECT_EQ(bytes[13], kEndDelimiter);
}

TEST(TelegramBuilderTest, OtherLengthsGiveSd2) {
    auto du = hex("F3 F1");
    auto bytes =
        build_telegram(spec_of(3, 2, request_fc(FdlFunction::SrdHigh, true, true), 62, 62, du));
    EXPECT_EQ(bytes, hex("68 07 07 68 83 82 7D 3E 3E F3 F1 E2 16"));
    // 7 and 9 octets: SD2 with LE = octets + 3.
    for (std::size_t n : {7u, 9u, 1u}) {
        SCOPED_TRACE("octets " + std::to_string(n));
        std::vector<std::uint8_t> data(n, 0x11);
        auto t = build_telegram(spec_of(5, 1, 0x6D, std::nullopt, std::nullopt, data));
        ASSERT_EQ(t.size(), n + 9);
        EXPECT_EQ(t[0], kSd2);
        EXPECT_EQ(t[1], n + 3);
        EXPECT_EQ(t[2], n + 3);
        EXPECT_EQ(t[3], kSd2);
    }
    // 6 data bytes + 2 SAP bytes = 8 octets -> SD3, but 7 + 2 = 9 -> SD2.
    std::vector<std::uint8_t> seven(7, 0);
    EXPECT_EQ(build_telegram(spec_of(3, 2, 0x7D, 62, 62, seven))[0], kSd2);
    // A single SAP with 7 data bytes is 8 octets.
    EXPECT_EQ(build_telegram(spec_of(3, 2, 0x7D, 62, std::nullopt, seven))[0], kSd3);
}

TEST(TelegramBuilderTest, FcsIsTheSumOfDaToDu) {
    auto du = hex("FF FF FF 80");
    auto bytes = build_telegram(spec_of(126, 125, 0x7D, 51, 51, du));
    // Summed: DA FE, SA FD, FC 7D, 33, 33, FF, FF, FF, 80.
    unsigned sum = 0xFE + 0xFD + 0x7D + 0x33 + 0x33 + 0xFF + 0xFF + 0xFF + 0x80;
    ASSERT_EQ(bytes.size(), 15u);
    EXPECT_EQ(bytes[13], static_cast<std::uint8_t>(sum));
    EXPECT_EQ(bytes[14], kEndDelimiter);
    EXPECT_EQ(bytes[13], fcs_of(Bytes(bytes.data() + 4, 9)));
}

TEST(TelegramBuilderTest, RoundTripThroughParseFdl) {
    for (std::size_t n = 0; n <= 246; ++n) {
        for (int saps = 0; saps < 3; ++saps) {
            std::size_t octets = n + static_cast<std::size_t>(saps);
            if (octets + 3 > 249) continue;
            SCOPED_TRACE("data " + std::to_string(n) + " saps " + std::to_string(saps));
            std::vector<std::uint8_t> data(n);
            for (std::size_t i = 0; i < n; ++i)
                data[i] = static_cast<std::uint8_t>(i * 7 + 1);
            std::optional<std::uint8_t> dsap, ssap;
            if (saps >= 1) dsap = 61;
            if (saps >= 2) ssap = 62;
            auto bytes = build_telegram(spec_of(
                9, 1, request_fc(FdlFunction::SrdHigh, n % 2 == 0, true), dsap, ssap, data));
            FdlTelegram t = parse(bytes);
            ASSERT_TRUE(t.problems.empty()) << problem_message(t.problems[0]);
            FrameType want = octets == 0   ? FrameType::Sd1
                             : octets == 8 ? FrameType::Sd3
                                           : FrameType::Sd2;
            EXPECT_EQ(t.type, want);
            EXPECT_EQ(t.size, bytes.size());
            EXPECT_EQ(t.da, 9);
            EXPECT_EQ(t.sa, 1);
            EXPECT_EQ(t.fc.function(), static_cast<std::uint8_t>(FdlFunction::SrdHigh));
            EXPECT_EQ(t.fc.fcb(), n % 2 == 0);
            EXPECT_EQ(t.has_dsap, saps >= 1);
            EXPECT_EQ(t.has_ssap, saps >= 2);
            if (saps >= 1) {
                EXPECT_EQ(t.dsap, 61);
            }
            if (saps >= 2) {
                EXPECT_EQ(t.ssap, 62);
            }
            EXPECT_TRUE(t.fcs_ok);
            ASSERT_EQ(t.du.size(), n);
            EXPECT_TRUE(std::equal(t.du.begin(), t.du.end(), data.begin()));
            FramingVerdict check =
                fdl_framing_rules().judge(Bytes(bytes.data(), bytes.size()), false);
            EXPECT_EQ(check.status, FramingStatus::Telegram);
            EXPECT_EQ(check.length, bytes.size());
        }
    }
}

TEST(TelegramBuilderTest, LargestSd2HasLe249) {
    std::vector<std::uint8_t> data(244, 0xAB);
    auto bytes = build_telegram(spec_of(3, 2, 0x7D, 62, 62, data));
    ASSERT_EQ(bytes.size(), kMaxTelegramSize);
    EXPECT_EQ(bytes[1], 249);
    EXPECT_TRUE(parse(bytes).problems.empty());
}

TEST(TelegramBuilderTest, CorruptedBuiltTelegramIsDetected) {
    auto bytes = build_telegram(spec_of(3, 2, 0x7D, 62, 62, hex("F3 F1")));
    bytes[10] ^= 0x01;
    FdlTelegram t = parse(bytes);
    EXPECT_FALSE(t.fcs_ok);
    ASSERT_EQ(t.problems.size(), 1u);
    EXPECT_EQ(t.problems[0].kind, ProblemKind::FcsMismatch);
    // Truncated: the builder's output cut short is reported.
    bytes.resize(8);
    EXPECT_TRUE(parse(bytes).problems.contains(ProblemKind::Truncated));
}

TEST(TelegramBuilderTest, AddressesAndSapsAreMasked) {
    // Bit 7 of an address is the extension flag: the builder owns it.
    auto bytes = build_telegram(spec_of(0x83, 0x82, 0x49, std::nullopt, std::nullopt, {}));
    EXPECT_EQ(bytes, hex("10 03 02 49 4E 16"));
    auto with_sap = build_telegram(spec_of(3, 2, 0x7D, 0xFE, 0x7E, hex("00")));
    FdlTelegram t = parse(with_sap);
    EXPECT_TRUE(t.problems.empty());
    EXPECT_EQ(with_sap[7], 0x3E);
    EXPECT_EQ(with_sap[8], 0x3E);
    EXPECT_EQ(t.dsap, 62);
    EXPECT_EQ(t.ssap, 62);
    EXPECT_FALSE(t.has_dest_segment);
}

TEST(TelegramBuilderTest, TokenAndShortAck) {
    std::vector<std::uint8_t> out;
    append_token(out, 5, 2);
    append_short_ack(out);
    append_token(out, 0x85, 0x82);  // bit 7 is not allowed in a token
    EXPECT_EQ(out, hex("DC 05 02 E5 DC 05 02"));
}

TEST(TelegramBuilderTest, AppendTelegramAppends) {
    std::vector<std::uint8_t> out = hex("E5");
    append_telegram(out, spec_of(3, 2, 0x49, std::nullopt, std::nullopt, {}));
    EXPECT_EQ(out, hex("E5 10 03 02 49 4E 16"));
}

TEST(TelegramBuilderTest, AppendPcvLayout) {
    std::vector<std::uint8_t> out;
    append_pcv(out, 3, false, 207, 0, 1000);
    EXPECT_EQ(out, hex("30 CF 00 00 00 00 03 E8"));

    out.clear();
    append_pcv(out, 10, true, 538, 0, 0x0A);  // as the bit layout wants it (contradictions.md #3)
    EXPECT_EQ(out, hex("AA 1A 00 00 00 00 00 0A"));

    out.clear();
    append_pcv(out, 6, false, 100, 5, 0x12345678);  // IND in byte 3, byte 4 zero
    EXPECT_EQ(out, hex("60 64 05 00 12 34 56 78"));

    out.clear();
    append_pcv(out, 7, false, 0, 0, 2);
    EXPECT_EQ(out, hex("70 00 00 00 00 00 00 02"));
}

TEST(TelegramBuilderTest, AppendPcvMasksOutOfRangeFields) {
    std::vector<std::uint8_t> out;
    append_pcv(out, 0x1F, false, 0xFFFF, 0, 0);  // RC 4 bits, PNU 11 bits, SPM untouched
    EXPECT_EQ(out, hex("F7 FF 00 00 00 00 00 00"));
}

TEST(TelegramBuilderTest, AppendU16BigEndian) {
    std::vector<std::uint8_t> out;
    append_u16_be(out, 0x047F);
    append_u16_be(out, 0x2000);
    EXPECT_EQ(out, hex("04 7F 20 00"));
}

}  // namespace
}  // namespace dpscope
