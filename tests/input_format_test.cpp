// Input format names and detection from a file's first bytes: pcap (both byte orders, microsecond
// and nanosecond magic), pcapng, hex text and raw bytes.
#include "capture/input_format.hpp"

#include <gtest/gtest.h>

#include <string>
#include <string_view>
#include <vector>

#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::hex;

InputFormat detect(const std::vector<std::uint8_t>& head) {
    return detect_input_format(Bytes(head.data(), head.size()));
}

InputFormat detect_text(std::string_view text) {
    std::vector<std::uint8_t> bytes(text.begin(), text.end());
    return detect(bytes);
}

TEST(InputFormatTest, NamesRoundTrip) {
    EXPECT_EQ(input_format_name(InputFormat::Auto), "auto");
    EXPECT_EQ(input_format_name(InputFormat::Pcap), "pcap");
    EXPECT_EQ(input_format_name(InputFormat::Pcapng), "pcapng");
    EXPECT_EQ(input_format_name(InputFormat::Raw), "raw");
    EXPECT_EQ(input_format_name(InputFormat::Hex), "hex");
    for (InputFormat format : {InputFormat::Auto, InputFormat::Pcap, InputFormat::Pcapng,
                               InputFormat::Raw, InputFormat::Hex}) {
        auto back = input_format_from_name(input_format_name(format));
        ASSERT_TRUE(back.has_value()) << input_format_name(format);
        EXPECT_EQ(*back, format);
    }
}

TEST(InputFormatTest, UnknownNamesAreRejected) {
    EXPECT_FALSE(input_format_from_name("").has_value());
    EXPECT_FALSE(input_format_from_name("PCAP").has_value());
    EXPECT_FALSE(input_format_from_name("pcap-ng").has_value());
    EXPECT_FALSE(input_format_from_name("TEXT").has_value());
}

TEST(InputFormatTest, PcapMicrosecondMagicBothByteOrders) {
    // Little-endian file: magic written as D4 C3 B2 A1, followed by version 2.4.
    EXPECT_EQ(detect(hex("D4 C3 B2 A1 02 00 04 00")), InputFormat::Pcap);
    // Big-endian file.
    EXPECT_EQ(detect(hex("A1 B2 C3 D4 00 02 00 04")), InputFormat::Pcap);
}

TEST(InputFormatTest, PcapNanosecondMagicBothByteOrders) {
    EXPECT_EQ(detect(hex("4D 3C B2 A1 02 00 04 00")), InputFormat::Pcap);
    EXPECT_EQ(detect(hex("A1 B2 3C 4D 00 02 00 04")), InputFormat::Pcap);
}

TEST(InputFormatTest, PcapngSectionHeaderBlock) {
    EXPECT_EQ(detect(hex("0A 0D 0D 0A 1C 00 00 00 4D 3C 2B 1A")), InputFormat::Pcapng);
    // The magic alone is enough.
    EXPECT_EQ(detect(hex("0A 0D 0D 0A")), InputFormat::Pcapng);
}

TEST(InputFormatTest, CorruptedMagicIsNotPcap) {
    // One bit off in each magic: binary content, so raw.
    EXPECT_EQ(detect(hex("D4 C3 B2 A0 02 00 04 00")), InputFormat::Raw);
    EXPECT_EQ(detect(hex("0A 0D 0D 0B 1C 00 00 00")), InputFormat::Raw);
}

TEST(InputFormatTest, TruncatedMagicIsNotPcap) {
    // Fewer than four bytes cannot carry a magic.
    EXPECT_EQ(detect(hex("D4 C3 B2")), InputFormat::Raw);
    EXPECT_EQ(detect(hex("0A 0D 0D")), InputFormat::Raw);
}

TEST(InputFormatTest, HexTextIsDetected) {
    EXPECT_EQ(detect_text("10 03 02 49 4E 16\n"), InputFormat::Hex);
    EXPECT_EQ(detect_text("12:00:01.5 TX: 68 07 07 68\r\n\tE5\n"), InputFormat::Hex);
    EXPECT_EQ(detect_text("6807076883827D3E3EF3F1E216"), InputFormat::Hex);
    // Two characters are enough for one pair.
    EXPECT_EQ(detect_text("E5"), InputFormat::Hex);
}

TEST(InputFormatTest, TextWithoutHexPairIsRaw) {
    EXPECT_EQ(detect_text("hello world\n"), InputFormat::Raw);
    EXPECT_EQ(detect_text("1 2 3 4\n"), InputFormat::Raw);
}

TEST(InputFormatTest, NonPrintableByteMakesItRaw) {
    // A raw PROFIBUS stream: SD1 telegram.
    EXPECT_EQ(detect(hex("10 03 02 49 4E 16")), InputFormat::Raw);
    // Hex text with a single control byte in it.
    std::string text = "10 03 02 49 4E 16\n";
    text[5] = '\x01';
    EXPECT_EQ(detect_text(text), InputFormat::Raw);
    // A byte above 0x7E.
    EXPECT_EQ(detect_text("68 07 \xE5"), InputFormat::Raw);
}

TEST(InputFormatTest, AByteOrderMarkAndNonAsciiTextOutsideTheBytesAreText) {
    // Issue #27 point 5: a UTF-8 BOM (as Windows editors write it), a UTF-8 header ("Log µs"),
    // or one Latin-1 byte in a longer log do not make a hex log or VLT 2000 log a raw stream.
    EXPECT_EQ(detect_text("\xEF\xBB\xBF"
                          "12:00:01.5 10 03 02 49 4E 16\n"),
              InputFormat::Hex);
    EXPECT_EQ(detect_text("Log \xC2\xB5s\n12:00:01.5 10 03 02 49 4E 16\n"), InputFormat::Hex);
    EXPECT_EQ(detect_text("Log \xB5s (Latin-1)\n12:00:01.5 10 03 02 49 4E 16\n"), InputFormat::Hex);
    EXPECT_EQ(detect_text("\xEF\xBB\xBF"
                          "12:00:01.5 <01UOGD@0516+00080007>\n"),
              InputFormat::Text);
    EXPECT_EQ(detect_text("Log \xC2\xB5s\n<01UOGD@0516+00080007>\n"), InputFormat::Text);
    EXPECT_EQ(detect_text("Protokoll \xFC"
                          "ber RS-485\n<01UOGD@0516+00080007>\n"),
              InputFormat::Text);
    // A UTF-8 character cut off by the end of a longer head is still text.
    EXPECT_EQ(detect_text("12:00:01.5 10 03 02 49 4E 16 TX 10 03 02 49 4E 16 \xC2"),
              InputFormat::Hex);
}

TEST(InputFormatTest, BinaryWithBytesAboveAsciiStaysRaw) {
    // PROFIBUS tokens between masters 0x31 and 0x32 carry no control byte, but 0xDC starts no
    // UTF-8 sequence there: one byte in three is no text.
    std::vector<std::uint8_t> tokens;
    for (int i = 0; i < 100; ++i)
        tokens.insert(tokens.end(), {0xDC, 0x31, 0x32, 0xDC, 0x32, 0x31});
    EXPECT_EQ(detect(tokens), InputFormat::Raw);
    EXPECT_FALSE(looks_like_text(Bytes(tokens.data(), tokens.size())));
}

TEST(InputFormatTest, TextWithControlCharactersLooksLikeText) {
    // A terminal log with colour escapes is no hex log to detection (ESC is a control byte), but
    // it looks like text, so that messages can point to --input-format hex.
    const std::string log = "\x1B[32m12:00:01.5 10 03 02 49 4E 16\x1B[0m\n";
    const Bytes bytes(reinterpret_cast<const std::uint8_t*>(log.data()), log.size());
    EXPECT_EQ(detect_input_format(bytes), InputFormat::Raw);
    EXPECT_TRUE(looks_like_text(bytes));
    EXPECT_FALSE(looks_like_text(hex("68 07 07 68 83 82 7D 3E 3E F3 F1 E2 16")));
}

TEST(InputFormatTest, EmptyHeadIsRaw) { EXPECT_EQ(detect({}), InputFormat::Raw); }

}  // namespace
}  // namespace dpscope
