// PROFIdrive parameter requests and responses (the data of DP-V1 index 47): request IDs,
// addresses, change requests with value blocks and pad bytes, positive and negative responses
// with 0x44 error blocks and 0x40 zero blocks, every value format as text and as numbers, error
// texts of both dialects, the worked examples of the protocol notes, cut-short and corrupted data.
#include "protocols/profibus/dpv1/profidrive.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::hex;

// The data starts at byte 13 of the telegram (SD2 header, SAPs, DP-V1 header).
constexpr std::size_t kDataOffset = 13;

struct Parsed {
    std::vector<std::uint8_t> bytes;
    ProfidriveMessage message;
    ProblemList problems;
};

Parsed request(std::string_view text) {
    Parsed p;
    p.bytes = hex(text);
    parse_profidrive_request(ByteReader(Bytes(p.bytes.data(), p.bytes.size()), kDataOffset),
                             p.message, p.problems);
    return p;
}

Parsed response(std::string_view text) {
    Parsed p;
    p.bytes = hex(text);
    parse_profidrive_response(ByteReader(Bytes(p.bytes.data(), p.bytes.size()), kDataOffset),
                              p.message, p.problems);
    return p;
}

// The text of one block built from `format`, `count` and the value bytes.
std::string values_text(std::uint8_t format, std::string_view value_bytes, std::uint8_t count = 1) {
    std::vector<std::uint8_t> bytes = hex(value_bytes);
    ProfidriveValueBlock block;
    block.format = format;
    block.count = count;
    block.values = Bytes(bytes.data(), bytes.size());
    block.complete = true;
    std::string out;
    append_profidrive_values(block, out);
    return out;
}

TEST(ProfidriveTest, RequestIdNames) {
    EXPECT_EQ(profidrive_request_id_name(0x01), "request parameter value");
    EXPECT_EQ(profidrive_request_id_name(0x02), "change parameter value");
    EXPECT_EQ(profidrive_request_id_name(0x42), "change parameter value (non-volatile)");
    EXPECT_EQ(profidrive_request_id_name(0x51), "request parameter value (double word)");
    EXPECT_EQ(profidrive_request_id_name(0x52), "change parameter value (double word)");
    EXPECT_EQ(profidrive_request_id_name(0x03), "");
    EXPECT_EQ(profidrive_response_id_name(0x01), "request parameter (+)");
    EXPECT_EQ(profidrive_response_id_name(0x02), "change parameter (+)");
    EXPECT_EQ(profidrive_response_id_name(0x81), "request parameter (-)");
    EXPECT_EQ(profidrive_response_id_name(0x82), "change parameter (-)");
    EXPECT_EQ(profidrive_response_id_name(0x42), "");
    EXPECT_EQ(profidrive_attribute_name(0x10), "value");
    EXPECT_EQ(profidrive_attribute_name(0x20), "description");
    EXPECT_EQ(profidrive_attribute_name(0x30), "text");
    EXPECT_EQ(profidrive_attribute_name(0x40), "");
}

TEST(ProfidriveTest, ResponseIdsAnswerTheirRequests) {
    EXPECT_TRUE(profidrive_response_answers(0x01, 0x01));
    EXPECT_TRUE(profidrive_response_answers(0x81, 0x01));
    EXPECT_FALSE(profidrive_response_answers(0x02, 0x01));
    EXPECT_TRUE(profidrive_response_answers(0x82, 0x02));
    EXPECT_FALSE(profidrive_response_answers(0x81, 0x02));
    EXPECT_TRUE(profidrive_response_answers(0x01, 0x51));
    EXPECT_TRUE(profidrive_response_answers(0xD1, 0x51));
    EXPECT_TRUE(profidrive_response_answers(0x02, 0x42));
    EXPECT_TRUE(profidrive_response_answers(0x82, 0x52));
    EXPECT_FALSE(profidrive_response_answers(0x01, 0x52));
    EXPECT_FALSE(profidrive_response_answers(0x01, 0x07));
}

TEST(ProfidriveTest, EachRequestIdParsesItsLayout) {
    for (int id : {0x01, 0x51}) {
        std::string text = fmt::format("07 {:02X} 00 01 10 01 00 0C 00 04", id);
        Parsed p = request(text);
        EXPECT_TRUE(p.message.has_header);
        EXPECT_EQ(p.message.id, id);
        EXPECT_FALSE(p.message.is_change_request());
        ASSERT_EQ(p.message.addresses.size(), 1u);
        EXPECT_TRUE(p.message.blocks.empty());
        EXPECT_TRUE(p.problems.empty()) << text;
    }
    for (int id : {0x02, 0x42, 0x52}) {
        std::string text = fmt::format("07 {:02X} 00 01 10 01 00 0C 00 04 42 01 00 03", id);
        Parsed p = request(text);
        EXPECT_TRUE(p.message.is_change_request());
        ASSERT_EQ(p.message.blocks.size(), 1u) << text;
        EXPECT_EQ(p.message.blocks[0].format, 0x42);
        EXPECT_TRUE(p.problems.empty()) << text;
        EXPECT_EQ(p.message.trailing, 0);
    }
}

TEST(ProfidriveTest, RequestAddressFields) {
    Parsed p = request("11 01 02 02 20 00 01 F4 00 00 30 05 FF FF 00 03");
    const ProfidriveMessage& m = p.message;
    EXPECT_FALSE(m.is_response);
    EXPECT_EQ(m.reference, 0x11);
    EXPECT_EQ(m.axis, 2);
    EXPECT_EQ(m.count, 2);
    ASSERT_EQ(m.addresses.size(), 2u);
    EXPECT_EQ(m.addresses[0].attribute, 0x20);
    EXPECT_EQ(m.addresses[0].elements, 0);
    EXPECT_EQ(m.addresses[0].pnu, 500);
    EXPECT_EQ(m.addresses[0].subindex, 0);
    EXPECT_EQ(m.addresses[1].attribute, 0x30);
    EXPECT_EQ(m.addresses[1].elements, 5);
    EXPECT_EQ(m.addresses[1].pnu, 65535);
    EXPECT_EQ(m.addresses[1].subindex, 3);
}

TEST(ProfidriveTest, ChangeRequestWithOddValueBlockHasAPadByte) {
    // Two parameters: Unsigned8 x1 (one byte, padded) and Integer16 x2.
    Parsed p = request(
        "21 02 00 02 10 01 00 64 00 00 10 02 00 65 00 00 05 01 7F 00 03 02 FF FE "
        "00 02");
    const ProfidriveMessage& m = p.message;
    ASSERT_EQ(m.blocks.size(), 2u);
    EXPECT_EQ(m.blocks[0].format, 0x05);
    EXPECT_EQ(m.blocks[0].count, 1);
    EXPECT_TRUE(m.blocks[0].padded);
    EXPECT_TRUE(m.blocks[0].complete);
    EXPECT_EQ(m.blocks[0].values_offset, kDataOffset + 18);
    EXPECT_EQ(m.blocks[1].format, 0x03);
    EXPECT_FALSE(m.blocks[1].padded);
    EXPECT_EQ(m.blocks[1].values_offset, kDataOffset + 22);
    std::string text;
    append_profidrive_values(m.blocks[1], text);
    EXPECT_EQ(text, "-2, 2");
    EXPECT_TRUE(p.problems.empty());
    EXPECT_EQ(m.trailing, 0);
}

TEST(ProfidriveTest, LastOddBlockMayEndWithoutPad) {
    Parsed p = request("21 02 00 01 10 01 00 64 00 00 05 01 7F");
    ASSERT_EQ(p.message.blocks.size(), 1u);
    EXPECT_FALSE(p.message.blocks[0].padded);
    EXPECT_TRUE(p.message.blocks[0].complete);
    EXPECT_TRUE(p.problems.empty());
}

TEST(ProfidriveTest, PositiveReadResponse) {
    Parsed p = response("09 01 01 02 06 02 00 01 00 02 09 03 41 42 43 00");
    const ProfidriveMessage& m = p.message;
    EXPECT_TRUE(m.is_response);
    EXPECT_FALSE(m.negative());
    ASSERT_EQ(m.blocks.size(), 2u);
    EXPECT_EQ(m.blocks[0].format, 0x06);
    EXPECT_EQ(m.blocks[1].format, 0x09);
    EXPECT_TRUE(m.blocks[1].padded);
    std::string text;
    append_profidrive_values(m.blocks[1], text);
    EXPECT_EQ(text, "\"ABC\"");
    EXPECT_TRUE(p.problems.empty());
    EXPECT_EQ(m.trailing, 0);
}

TEST(ProfidriveTest, NegativeReadResponseWithErrorBlocks) {
    // Parameter 1 fine (Word 5), parameter 2 error 0x00, parameter 3 error 0x03 with subindex 7.
    Parsed p = response("0A 81 00 03 42 01 00 05 44 01 00 00 44 02 00 03 00 07");
    const ProfidriveMessage& m = p.message;
    EXPECT_TRUE(m.negative());
    ASSERT_EQ(m.blocks.size(), 3u);
    EXPECT_FALSE(m.blocks[0].is_error());
    EXPECT_TRUE(m.blocks[1].is_error());
    EXPECT_EQ(m.blocks[1].error_number(), 0x00);
    EXPECT_FALSE(m.blocks[1].has_error_info());
    EXPECT_TRUE(m.blocks[2].is_error());
    EXPECT_EQ(m.blocks[2].error_number(), 0x03);
    EXPECT_TRUE(m.blocks[2].has_error_info());
    EXPECT_EQ(m.blocks[2].error_info(), 7);
    std::string text;
    append_profidrive_values(m.blocks[2], text);
    EXPECT_EQ(text, "error 0x03, info 7");
    EXPECT_TRUE(p.problems.empty());
}

TEST(ProfidriveTest, ChangeResponses) {
    Parsed positive = response("0B 02 00 02");
    EXPECT_TRUE(positive.message.blocks.empty());
    EXPECT_TRUE(positive.problems.empty());  // a positive change response is the header alone

    Parsed negative = response("0B 82 00 02 40 00 44 01 00 02");
    ASSERT_EQ(negative.message.blocks.size(), 2u);
    EXPECT_EQ(negative.message.blocks[0].format, profidrive::kFormatZero);
    EXPECT_TRUE(negative.message.blocks[0].complete);
    EXPECT_TRUE(negative.message.blocks[0].values.empty());
    EXPECT_EQ(negative.message.blocks[1].error_number(), 0x02);
    EXPECT_TRUE(negative.problems.empty());
}

TEST(ProfidriveTest, ReadResponseMissingBlocksIsAProblem) {
    Parsed p = response("0C 01 00 02 42 01 00 05");
    EXPECT_EQ(p.message.blocks.size(), 1u);
    ASSERT_EQ(p.problems.size(), 1u);
    EXPECT_EQ(p.problems[0].kind, ProblemKind::ServiceDataShort);
    EXPECT_EQ(p.problems[0].offset, kDataOffset + 8);
}

TEST(ProfidriveTest, FormatNamesAndSizes) {
    EXPECT_EQ(profidrive_format_name(0x03), "Integer16");
    EXPECT_EQ(profidrive_format_name(0x21), "N2");
    EXPECT_EQ(profidrive_format_name(0x22), "N4");
    EXPECT_EQ(profidrive_format_name(0x23), "V2");
    EXPECT_EQ(profidrive_format_name(0x36), "TimeDifference without date");
    EXPECT_EQ(profidrive_format_name(0x40), "Zero");
    EXPECT_EQ(profidrive_format_name(0x44), "Error");
    EXPECT_EQ(profidrive_format_name(0x37), "reserved");
    EXPECT_EQ(profidrive_format_size(0x22), 4);
    EXPECT_EQ(profidrive_format_size(0x40), 0);
    EXPECT_EQ(profidrive_format_size(0x45), -1);
    EXPECT_EQ(profidrive_format_size(0x00), -1);
}

TEST(ProfidriveTest, EveryFormatIsRendered) {
    EXPECT_EQ(values_text(0x01, "01 00", 2), "true, false");
    EXPECT_EQ(values_text(0x02, "FF"), "-1");
    EXPECT_EQ(values_text(0x03, "80 00"), "-32768");
    EXPECT_EQ(values_text(0x04, "FF FF FF FE"), "-2");
    EXPECT_EQ(values_text(0x05, "FF"), "255");
    EXPECT_EQ(values_text(0x06, "FF FF"), "65535");
    EXPECT_EQ(values_text(0x07, "FF FF FF FF"), "4294967295");
    EXPECT_EQ(values_text(0x08, "3F C0 00 00"), "1.5");
    EXPECT_EQ(values_text(0x09, "48 22 5C 01", 4), "\"H\\\"\\\\\\x01\"");
    EXPECT_EQ(values_text(0x0A, "01 AB", 2), "01 AB");
    EXPECT_EQ(values_text(0x21, "40 00"), "100.000 %");
    EXPECT_EQ(values_text(0x21, "E0 00"), "-50.000 %");
    EXPECT_EQ(values_text(0x22, "20 00 00 00"), "50.000 %");
    EXPECT_EQ(values_text(0x23, "80 01"), "1000000000000001");
    EXPECT_EQ(values_text(0x0C, "03 6E E8 00 00 0A"), "16:00:00.000 day 10");
    EXPECT_EQ(values_text(0x0D, "00 00 03 E8 00 02"), "2 d 1000 ms");
    EXPECT_EQ(values_text(0x35, "00 00 00 05 00 00"), "0 d 5 ms");
    EXPECT_EQ(values_text(0x34, "00 00 EA 60"), "00:01:00.000");
    EXPECT_EQ(values_text(0x36, "00 01 00 00"), "65536 ms");
    EXPECT_EQ(values_text(0x32, "EA 5F 3B 17 1F 0C 18"), "2024-12-31 23:59:59.999");
    EXPECT_EQ(values_text(0x32, "00 00 00 00 01 01 63"), "1999-01-01 00:00:00.000");
    EXPECT_EQ(values_text(0x41, "0F"), "15");
    EXPECT_EQ(values_text(0x42, "FF FF"), "65535");
    EXPECT_EQ(values_text(0x43, "12 34 56 78"), "305419896");
    EXPECT_EQ(values_text(0x42, "00 01 00 02", 2), "1, 2");
    EXPECT_EQ(values_text(0x40, "", 0), "");
    EXPECT_EQ(values_text(0x44, "00 65"), "error 0x65");
    EXPECT_EQ(values_text(0x44, "00"), "error (number cut short)");
    EXPECT_EQ(values_text(0x50, "01 02"), "01 02");  // reserved: the bytes

    std::vector<std::uint8_t> one = hex("07");
    ProfidriveValueBlock cut;
    cut.format = 0x06;
    cut.count = 1;
    cut.values = Bytes(one.data(), one.size());
    std::string text;
    append_profidrive_values(cut, text);
    EXPECT_EQ(text, "(cut short)");
    cut.format = 0x09;
    cut.count = 3;
    text.clear();
    append_profidrive_values(cut, text);
    EXPECT_EQ(text, "\"\\x07\" (cut short)");
}

TEST(ProfidriveTest, NumericValues) {
    std::vector<std::uint8_t> bytes = hex("FF FE 00 02");
    ProfidriveValueBlock block;
    block.format = 0x03;
    block.count = 2;
    block.values = Bytes(bytes.data(), bytes.size());
    ASSERT_EQ(profidrive_value_count(block), 2u);
    auto first = profidrive_number(block, 0);
    ASSERT_TRUE(first);
    EXPECT_FALSE(first->is_real);
    EXPECT_EQ(first->integer, -2);
    EXPECT_EQ(profidrive_number(block, 1)->integer, 2);
    EXPECT_FALSE(profidrive_number(block, 2));

    block.format = 0x21;  // N2: 0xFFFE, a little under 0 %
    auto n2 = profidrive_number(block, 1);
    ASSERT_TRUE(n2);
    EXPECT_TRUE(n2->is_real);
    EXPECT_DOUBLE_EQ(n2->real, 2 * 100.0 / 0x4000);

    block.format = 0x43;
    ASSERT_EQ(profidrive_value_count(block), 1u);
    EXPECT_EQ(profidrive_number(block, 0)->integer, 0xFFFE0002);

    block.format = 0x08;  // 0xFFFE0002 is a NaN: no number
    EXPECT_FALSE(profidrive_number(block, 0));

    block.format = 0x09;  // strings have no numbers
    EXPECT_EQ(profidrive_value_count(block), 4u);
    EXPECT_FALSE(profidrive_number(block, 0));
    block.format = 0x44;
    EXPECT_EQ(profidrive_value_count(block), 0u);
    EXPECT_FALSE(profidrive_number(block, 0));
}

TEST(ProfidriveTest, ErrorTextsOfBothDialects) {
    EXPECT_EQ(profidrive_error_text(0x00, Dialect::Profidrive),
              "illegal or unknown parameter number");
    EXPECT_EQ(profidrive_error_text(0x03, Dialect::Vlt), "invalid subindex");
    EXPECT_EQ(profidrive_error_text(0x15, Dialect::Profidrive),
              "response too long (over 240 bytes)");
    EXPECT_EQ(profidrive_error_text(0x08, Dialect::Profidrive), "reserved");
    EXPECT_EQ(profidrive_error_text(0x64, Dialect::Vlt), "reserved");
    EXPECT_EQ(profidrive_error_text(0x65, Dialect::Vlt), "wrong axis");
    EXPECT_EQ(profidrive_error_text(0x66, Dialect::Vlt), "unknown service request");
    EXPECT_EQ(profidrive_error_text(0x67, Dialect::Vlt),
              "service not possible with multi-parameter access");
    EXPECT_EQ(profidrive_error_text(0x68, Dialect::Vlt), "value cannot be read from the bus");
    EXPECT_EQ(profidrive_error_text(0x69, Dialect::Vlt), "manufacturer-specific");
    EXPECT_EQ(profidrive_error_text(0x65, Dialect::Profidrive), "manufacturer-specific");
    EXPECT_EQ(profidrive_error_text(0x1234, Dialect::Profidrive), "manufacturer-specific");
}

// ../shared/protocol.md section 6.6: the ABB FPBA-01 examples. The DP-V1 header is checked in
// dpv1_test and bus_decoder_test; here the PROFIdrive part after it.
TEST(ProfidriveTest, WorkedExampleSingleRead) {
    Parsed p = request("05 01 01 01 10 01 00 0C 00 04");
    EXPECT_EQ(p.message.reference, 5);
    EXPECT_EQ(p.message.id, profidrive::kRequestValue);
    EXPECT_EQ(p.message.axis, 1);
    EXPECT_EQ(p.message.count, 1);
    ASSERT_EQ(p.message.addresses.size(), 1u);
    EXPECT_EQ(p.message.addresses[0].attribute, profidrive::kAttributeValue);
    EXPECT_EQ(p.message.addresses[0].elements, 1);
    EXPECT_EQ(p.message.addresses[0].pnu, 12);
    EXPECT_EQ(p.message.addresses[0].subindex, 4);
    EXPECT_TRUE(p.problems.empty());
}

TEST(ProfidriveTest, WorkedExampleThreeParameterRead) {
    Parsed p = request("06 01 01 03 10 01 00 0C 00 04 10 01 00 14 00 08 10 01 00 1E 00 13");
    EXPECT_EQ(p.bytes.size(), 22u);  // 4 + 3 x 6
    ASSERT_EQ(p.message.addresses.size(), 3u);
    EXPECT_EQ(p.message.addresses[0].pnu, 12);
    EXPECT_EQ(p.message.addresses[0].subindex, 4);
    EXPECT_EQ(p.message.addresses[1].pnu, 20);
    EXPECT_EQ(p.message.addresses[1].subindex, 8);
    EXPECT_EQ(p.message.addresses[2].pnu, 30);
    EXPECT_EQ(p.message.addresses[2].subindex, 19);
    EXPECT_TRUE(p.problems.empty());
}

TEST(ProfidriveTest, WorkedExampleReadPnu918) {
    Parsed p = request("09 01 01 01 10 00 03 96 00 00");
    ASSERT_EQ(p.message.addresses.size(), 1u);
    EXPECT_EQ(p.message.addresses[0].elements, 0);
    EXPECT_EQ(p.message.addresses[0].pnu, 918);
    EXPECT_EQ(p.message.addresses[0].subindex, 0);
}

TEST(ProfidriveTest, WorkedExampleReadResponse) {
    Parsed p = response("09 01 01 01 42 01 00 03");
    EXPECT_EQ(p.message.reference, 9);
    EXPECT_EQ(p.message.id, 0x01);
    EXPECT_EQ(p.message.axis, 1);
    EXPECT_EQ(p.message.count, 1);
    ASSERT_EQ(p.message.blocks.size(), 1u);
    EXPECT_EQ(p.message.blocks[0].format, 0x42);
    EXPECT_EQ(p.message.blocks[0].count, 1);
    std::string text;
    append_profidrive_values(p.message.blocks[0], text);
    EXPECT_EQ(text, "3");
    EXPECT_EQ(profidrive_number(p.message.blocks[0], 0)->integer, 3);
    EXPECT_TRUE(p.problems.empty());
}

TEST(ProfidriveTest, HeaderCutShort) {
    Parsed p = request("05 01 01");
    EXPECT_FALSE(p.message.has_header);
    ASSERT_EQ(p.problems.size(), 1u);
    EXPECT_EQ(p.problems[0].kind, ProblemKind::ServiceDataShort);
    EXPECT_EQ(p.problems[0].offset, kDataOffset);
    EXPECT_EQ(p.problems[0].expected, 4u);
    EXPECT_EQ(p.problems[0].actual, 3u);
}

TEST(ProfidriveTest, AddressesCutShort) {
    Parsed p = request("05 01 01 02 10 01 00 0C 00 04 10 01");
    EXPECT_EQ(p.message.addresses.size(), 1u);
    ASSERT_EQ(p.problems.size(), 1u);
    EXPECT_EQ(p.problems[0].offset, kDataOffset + 10);
    EXPECT_EQ(p.problems[0].expected, 6u);
}

TEST(ProfidriveTest, ValueBlockCutShort) {
    Parsed p = response("09 01 01 01 43 02 00 00 00 01 00");
    ASSERT_EQ(p.message.blocks.size(), 1u);
    EXPECT_FALSE(p.message.blocks[0].complete);
    EXPECT_EQ(p.message.blocks[0].values.size(), 5u);
    ASSERT_EQ(p.problems.size(), 1u);
    EXPECT_EQ(p.problems[0].offset, kDataOffset + 6);
    EXPECT_EQ(p.problems[0].expected, 8u);
    EXPECT_EQ(p.problems[0].actual, 5u);
    std::string text;
    append_profidrive_values(p.message.blocks[0], text);
    EXPECT_EQ(text, "1 (cut short)");
}

TEST(ProfidriveTest, ReservedFormatTakesTheRest) {
    Parsed p = response("09 01 01 02 50 01 AA BB CC");
    ASSERT_EQ(p.message.blocks.size(), 1u);
    EXPECT_EQ(p.message.blocks[0].values.size(), 3u);
    EXPECT_FALSE(p.message.blocks[0].complete);
    EXPECT_EQ(p.message.trailing, 0);
}

TEST(ProfidriveTest, BytesAfterTheMessageAreCounted) {
    Parsed p = request("05 01 01 01 10 01 00 0C 00 04 00 00 00");
    EXPECT_EQ(p.message.trailing, 3);
    // A positive change response with a block it should not have: the block is read.
    Parsed r = response("0B 02 00 01 44 01 00 00");
    EXPECT_EQ(r.message.blocks.size(), 1u);
    EXPECT_TRUE(r.problems.empty());
}

TEST(ProfidriveTest, CorruptedBytesNeverCrash) {
    // Every prefix and every single-byte corruption of a few messages, both ways.
    for (std::string_view text :
         {"21 02 00 02 10 01 00 64 00 00 10 02 00 65 00 00 05 01 7F 00 03 02 FF FE 00 02",
          "0A 81 00 03 42 01 00 05 44 01 00 00 44 02 00 03 00 07",
          "09 01 01 02 06 02 00 01 00 02 09 03 41 42 43 00"}) {
        std::vector<std::uint8_t> bytes = hex(text);
        for (std::size_t n = 0; n <= bytes.size(); ++n) {
            for (std::size_t at = 0; at < n; ++at) {
                for (int value : {0x00, 0x44, 0xFF}) {
                    std::vector<std::uint8_t> copy(bytes.begin(), bytes.begin() + n);
                    copy[at] = static_cast<std::uint8_t>(value);
                    for (bool is_response : {false, true}) {
                        ProfidriveMessage m;
                        ProblemList problems;
                        ByteReader reader(Bytes(copy.data(), copy.size()), kDataOffset);
                        if (is_response)
                            parse_profidrive_response(reader, m, problems);
                        else
                            parse_profidrive_request(reader, m, problems);
                        for (const ProfidriveValueBlock& block : m.blocks) {
                            std::string out;
                            append_profidrive_values(block, out);
                            for (std::size_t i = 0; i < profidrive_value_count(block); ++i)
                                (void)profidrive_number(block, i);
                        }
                        for (const Problem& problem : problems)
                            EXPECT_LE(problem.offset, kDataOffset + copy.size());
                    }
                }
            }
        }
    }
}

}  // namespace
}  // namespace dpscope

namespace dpscope {
namespace {

// The numeric formats NumericValues leaves out (scripts/coverage found them unreached): Boolean,
// Integer8 and Integer32 as signed integers, N4 as a percentage (0x40000000 = 100 %).
TEST(ProfidriveTest, NumbersOfBooleanIntegerAndN4Values) {
    std::vector<std::uint8_t> bytes = hex("FE 00 00 02");
    ProfidriveValueBlock block;
    block.values = Bytes(bytes.data(), bytes.size());

    block.format = 0x01;  // Boolean: any byte but 0 is 1
    ASSERT_EQ(profidrive_value_count(block), 4u);
    EXPECT_EQ(profidrive_number(block, 0)->integer, 1);
    EXPECT_EQ(profidrive_number(block, 1)->integer, 0);

    block.format = 0x02;  // Integer8
    EXPECT_EQ(profidrive_number(block, 0)->integer, -2);
    EXPECT_EQ(profidrive_number(block, 3)->integer, 2);

    block.format = 0x04;  // Integer32
    ASSERT_EQ(profidrive_value_count(block), 1u);
    EXPECT_EQ(profidrive_number(block, 0)->integer, -33554430);

    std::vector<std::uint8_t> half = hex("20 00 00 00");
    block.values = Bytes(half.data(), half.size());
    block.format = 0x22;  // N4: 0x20000000 is 50 %
    auto n4 = profidrive_number(block, 0);
    ASSERT_TRUE(n4);
    EXPECT_TRUE(n4->is_real);
    EXPECT_DOUBLE_EQ(n4->real, 50.0);
}

}  // namespace
}  // namespace dpscope
