// ByteReader: big-endian reads, bounds checks that leave the cursor alone, offsets and
// sub-readers.
#include "core/byte_reader.hpp"

#include <gtest/gtest.h>

#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::hex;

Bytes span_of(const std::vector<std::uint8_t>& bytes) { return Bytes(bytes.data(), bytes.size()); }

TEST(ByteReaderTest, ReadsBigEndianValuesInOrder) {
    auto bytes = hex("12 34 56 78 9A BC DE F0 01");
    ByteReader reader(span_of(bytes));
    EXPECT_EQ(reader.size(), 9u);
    EXPECT_EQ(reader.u8(), std::optional<std::uint8_t>(0x12));
    EXPECT_EQ(reader.u16_be(), std::optional<std::uint16_t>(0x3456));
    EXPECT_EQ(reader.u32_be(), std::optional<std::uint32_t>(0x789ABCDEu));
    EXPECT_EQ(reader.position(), 7u);
    EXPECT_EQ(reader.remaining(), 2u);
    EXPECT_EQ(reader.u16_be(), std::optional<std::uint16_t>(0xF001));
    EXPECT_TRUE(reader.empty());
    EXPECT_EQ(reader.remaining(), 0u);
}

TEST(ByteReaderTest, U32HighBitDoesNotSignExtend) {
    auto bytes = hex("FF FF FF FE");
    ByteReader reader(span_of(bytes));
    EXPECT_EQ(reader.u32_be(), std::optional<std::uint32_t>(0xFFFFFFFEu));
}

TEST(ByteReaderTest, ReadPastEndReturnsNulloptAndKeepsCursor) {
    auto bytes = hex("01 02 03");
    ByteReader reader(span_of(bytes));
    EXPECT_EQ(reader.u32_be(), std::nullopt);
    EXPECT_EQ(reader.position(), 0u);
    EXPECT_EQ(reader.bytes(4), std::nullopt);
    EXPECT_EQ(reader.position(), 0u);
    EXPECT_FALSE(reader.skip(4));
    EXPECT_EQ(reader.position(), 0u);
    ASSERT_TRUE(reader.skip(2));
    EXPECT_EQ(reader.u16_be(), std::nullopt);
    EXPECT_EQ(reader.position(), 2u);
    EXPECT_EQ(reader.u8(), std::optional<std::uint8_t>(0x03));
    EXPECT_EQ(reader.u8(), std::nullopt);
    EXPECT_EQ(reader.position(), 3u);
}

TEST(ByteReaderTest, EmptySpanHasNothingToRead) {
    ByteReader reader(Bytes{});
    EXPECT_TRUE(reader.empty());
    EXPECT_EQ(reader.size(), 0u);
    EXPECT_EQ(reader.u8(), std::nullopt);
    EXPECT_EQ(reader.peek_u8(), std::nullopt);
    EXPECT_EQ(reader.u16_be(), std::nullopt);
    EXPECT_TRUE(reader.rest().empty());
    EXPECT_TRUE(reader.skip(0));
    EXPECT_EQ(reader.bytes(0).value().size(), 0u);
}

TEST(ByteReaderTest, PeekLooksAheadWithoutMoving) {
    auto bytes = hex("A0 A1 A2");
    ByteReader reader(span_of(bytes));
    reader.u8();
    EXPECT_EQ(reader.peek_u8(), std::optional<std::uint8_t>(0xA1));
    EXPECT_EQ(reader.peek_u8(1), std::optional<std::uint8_t>(0xA2));
    EXPECT_EQ(reader.peek_u8(2), std::nullopt);
    EXPECT_EQ(reader.position(), 1u);
}

TEST(ByteReaderTest, OffsetAddsTheBaseOffset) {
    auto bytes = hex("3E 3C 02 05");
    ByteReader reader(span_of(bytes), 7);
    EXPECT_EQ(reader.offset(), 7u);
    reader.u16_be();
    EXPECT_EQ(reader.position(), 2u);
    EXPECT_EQ(reader.offset(), 9u);
}

TEST(ByteReaderTest, BytesAndRestReturnSubSpans) {
    auto bytes = hex("10 20 30 40 50");
    ByteReader reader(span_of(bytes));
    auto first = reader.bytes(2);
    ASSERT_TRUE(first);
    ASSERT_EQ(first->size(), 2u);
    EXPECT_EQ((*first)[0], 0x10);
    EXPECT_EQ((*first)[1], 0x20);
    EXPECT_EQ(first->data(), bytes.data());  // a view, not a copy
    Bytes rest = reader.rest();
    ASSERT_EQ(rest.size(), 3u);
    EXPECT_EQ(rest[0], 0x30);
    EXPECT_EQ(rest[2], 0x50);
    EXPECT_TRUE(reader.empty());
    EXPECT_TRUE(reader.rest().empty());
}

TEST(ByteReaderTest, SubReaderContinuesOffsetsAndAdvancesParent) {
    auto bytes = hex("01 02 03 04 05 06");
    ByteReader reader(span_of(bytes), 10);
    reader.u8();
    ByteReader sub = reader.sub_reader(3);
    EXPECT_EQ(sub.size(), 3u);
    EXPECT_EQ(sub.offset(), 11u);
    EXPECT_EQ(reader.position(), 4u);
    EXPECT_EQ(reader.offset(), 14u);
    EXPECT_EQ(sub.u16_be(), std::optional<std::uint16_t>(0x0203));
    EXPECT_EQ(sub.offset(), 13u);
    EXPECT_EQ(sub.u16_be(), std::nullopt);  // the sub-reader ends where it was cut
    EXPECT_EQ(sub.u8(), std::optional<std::uint8_t>(0x04));
    EXPECT_EQ(reader.u8(), std::optional<std::uint8_t>(0x05));
}

TEST(ByteReaderTest, SubReaderLongerThanRemainingIsClamped) {
    auto bytes = hex("01 02 03");
    ByteReader reader(span_of(bytes));
    reader.u8();
    ByteReader sub = reader.sub_reader(10);
    EXPECT_EQ(sub.size(), 2u);
    EXPECT_EQ(sub.offset(), 1u);
    EXPECT_TRUE(reader.empty());
    EXPECT_EQ(reader.position(), 3u);
}

}  // namespace
}  // namespace dpscope
