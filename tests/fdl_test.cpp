// FDL layer: every frame type valid, truncated and corrupted; frame control; address extension.
#include "protocols/profibus/fdl.hpp"

#include <gtest/gtest.h>

#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::hex;

FdlTelegram parse(const std::vector<std::uint8_t>& bytes) {
    FdlTelegram t;
    parse_fdl(Bytes(bytes.data(), bytes.size()), t);
    return t;
}

// FDL status request from master 2 to station 3: 10 03 02 49 FCS 16, FCS = 03+02+49 = 4E.
const std::vector<std::uint8_t> kSd1 = hex("10 03 02 49 4E 16");
// Chk_Cfg F3 F1 from 2 to 3 with SAPs 62/62.
const std::vector<std::uint8_t> kSd2 = hex("68 07 07 68 83 82 7D 3E 3E F3 F1 E2 16");
// Slave_Diag response, 8 data octets including the two SAP bytes.
const std::vector<std::uint8_t> kSd3 = hex("A2 82 83 08 3E 3C 02 05 00 FF 04 02 93 16");

TEST(FdlTest, Sd1Valid) {
    FdlTelegram t = parse(kSd1);
    EXPECT_EQ(t.type, FrameType::Sd1);
    EXPECT_EQ(t.size, 6);
    EXPECT_TRUE(t.has_addresses);
    EXPECT_EQ(t.da, 3);
    EXPECT_EQ(t.sa, 2);
    ASSERT_TRUE(t.has_fc);
    EXPECT_TRUE(t.fc.is_request());
    EXPECT_EQ(t.fc.function(), static_cast<std::uint8_t>(FdlFunction::FdlStatus));
    EXPECT_TRUE(t.has_fcs);
    EXPECT_TRUE(t.fcs_ok);
    EXPECT_TRUE(t.du.empty());
    EXPECT_TRUE(t.problems.empty());
}

TEST(FdlTest, Sd1Truncated) {
    FdlTelegram t = parse(hex("10 03 02 49"));
    EXPECT_EQ(t.type, FrameType::Sd1);
    EXPECT_EQ(t.da, 3);
    EXPECT_FALSE(t.has_fcs);
    ASSERT_EQ(t.problems.size(), 1u);
    EXPECT_EQ(t.problems[0].kind, ProblemKind::Truncated);
    EXPECT_EQ(t.problems[0].expected, 6u);
    EXPECT_EQ(t.problems[0].actual, 4u);
}

TEST(FdlTest, Sd1CorruptedFcsAndEndDelimiter) {
    FdlTelegram t = parse(hex("10 03 02 49 4F 17"));
    EXPECT_FALSE(t.fcs_ok);
    ASSERT_EQ(t.problems.size(), 2u);
    EXPECT_EQ(t.problems[0].kind, ProblemKind::FcsMismatch);
    EXPECT_EQ(t.problems[0].offset, 4);
    EXPECT_EQ(t.problems[0].expected, 0x4Eu);
    EXPECT_EQ(t.problems[0].actual, 0x4Fu);
    EXPECT_EQ(t.problems[1].kind, ProblemKind::BadEndDelimiter);
    EXPECT_EQ(t.problems[1].offset, 5);
    EXPECT_EQ(problem_message(t.problems[0]),
              "byte 4: FCS 0x4F wrong, checksum of the data is 0x4E");
}

TEST(FdlTest, Sd2ValidWithSaps) {
    FdlTelegram t = parse(kSd2);
    EXPECT_EQ(t.type, FrameType::Sd2);
    EXPECT_EQ(t.length_field, 7);
    EXPECT_EQ(t.size, 13);
    EXPECT_EQ(t.da, 3);
    EXPECT_EQ(t.sa, 2);
    EXPECT_TRUE(t.has_dsap);
    EXPECT_TRUE(t.has_ssap);
    EXPECT_EQ(t.dsap, 62);
    EXPECT_EQ(t.ssap, 62);
    EXPECT_TRUE(t.fc.fcb());
    EXPECT_TRUE(t.fc.fcv());
    EXPECT_EQ(t.fc.function(), static_cast<std::uint8_t>(FdlFunction::SrdHigh));
    ASSERT_EQ(t.du.size(), 2u);
    EXPECT_EQ(t.du[0], 0xF3);
    EXPECT_EQ(t.du_offset, 9);
    EXPECT_TRUE(t.fcs_ok);
    EXPECT_TRUE(t.problems.empty());
}

TEST(FdlTest, Sd2Truncated) {
    auto bytes = kSd2;
    bytes.resize(9);
    FdlTelegram t = parse(bytes);
    EXPECT_EQ(t.type, FrameType::Sd2);
    EXPECT_EQ(t.dsap, 62);
    EXPECT_FALSE(t.has_fcs);
    ASSERT_EQ(t.problems.size(), 1u);
    EXPECT_EQ(t.problems[0].kind, ProblemKind::Truncated);
    EXPECT_EQ(t.problems[0].expected, 13u);
}

TEST(FdlTest, Sd2CutAfterLeHasNoLengthRepeat) {
    FdlTelegram t = parse(hex("68 07"));
    EXPECT_EQ(t.length_field, 7u);
    EXPECT_FALSE(t.has_length_repeat);
}

TEST(FdlTest, Sd2LengthFieldsDisagree) {
    FdlTelegram t = parse(hex("68 07 08 68 83 82 7D 3E 3E F3 F1 E2 16"));
    EXPECT_EQ(t.length_field, 7u);
    EXPECT_TRUE(t.has_length_repeat);
    EXPECT_EQ(t.length_repeat, 8u);  // kept for the views, which show both
    ASSERT_FALSE(t.problems.empty());
    EXPECT_EQ(t.problems[0].kind, ProblemKind::LengthMismatch);
    EXPECT_EQ(t.problems[0].offset, 2);
}

TEST(FdlTest, Sd2RepeatedStartDelimiterWrong) {
    FdlTelegram t = parse(hex("68 07 07 69 83 82 7D 3E 3E F3 F1 E2 16"));
    EXPECT_TRUE(t.problems.contains(ProblemKind::StartDelimiterRepeat));
}

TEST(FdlTest, Sd2LengthOutOfRange) {
    FdlTelegram t = parse(hex("68 02 02 68 03 02 49 4E 16"));
    EXPECT_TRUE(t.problems.contains(ProblemKind::LengthOutOfRange));
}

TEST(FdlTest, Sd2CorruptedFcs) {
    auto bytes = kSd2;
    bytes[11] ^= 0x5A;
    FdlTelegram t = parse(bytes);
    EXPECT_FALSE(t.fcs_ok);
    ASSERT_EQ(t.problems.size(), 1u);
    EXPECT_EQ(t.problems[0].kind, ProblemKind::FcsMismatch);
    EXPECT_EQ(t.problems[0].offset, 11);
}

TEST(FdlTest, Sd2TrailingBytes) {
    auto bytes = kSd2;
    bytes.push_back(0x00);
    bytes.push_back(0x00);
    FdlTelegram t = parse(bytes);
    ASSERT_EQ(t.problems.size(), 1u);
    EXPECT_EQ(t.problems[0].kind, ProblemKind::TrailingBytes);
    EXPECT_EQ(t.problems[0].offset, 13);
    EXPECT_EQ(t.problems[0].actual, 2u);
    EXPECT_EQ(problem_message(t.problems[0]), "byte 13: 2 bytes after the end of the telegram");
    EXPECT_EQ(problem_severity(ProblemKind::TrailingBytes), Severity::Warning);
    bytes.pop_back();
    EXPECT_EQ(problem_message(parse(bytes).problems[0]),
              "byte 13: 1 byte after the end of the telegram");
}

TEST(FdlTest, Sd3Valid) {
    FdlTelegram t = parse(kSd3);
    EXPECT_EQ(t.type, FrameType::Sd3);
    EXPECT_EQ(t.size, 14);
    EXPECT_FALSE(t.fc.is_request());
    EXPECT_EQ(t.fc.function(), static_cast<std::uint8_t>(FdlStatus::DataLow));
    EXPECT_EQ(t.dsap, 62);
    EXPECT_EQ(t.ssap, 60);
    EXPECT_EQ(t.du.size(), 6u);
    EXPECT_TRUE(t.problems.empty());
}

TEST(FdlTest, Sd3TruncatedAndCorrupted) {
    auto cut = kSd3;
    cut.resize(10);
    EXPECT_TRUE(parse(cut).problems.contains(ProblemKind::Truncated));
    auto bad = kSd3;
    bad[7] ^= 0x01;
    EXPECT_TRUE(parse(bad).problems.contains(ProblemKind::FcsMismatch));
}

TEST(FdlTest, Sd4TokenValidTruncatedCorrupted) {
    FdlTelegram t = parse(hex("DC 02 02"));
    EXPECT_EQ(t.type, FrameType::Sd4);
    EXPECT_EQ(t.da, 2);
    EXPECT_EQ(t.sa, 2);
    EXPECT_TRUE(t.is_request());
    EXPECT_FALSE(t.has_fc);
    EXPECT_TRUE(t.fcs_ok);
    EXPECT_TRUE(t.problems.empty());
    EXPECT_TRUE(parse(hex("DC 02")).problems.contains(ProblemKind::Truncated));
    EXPECT_TRUE(parse(hex("DC 82 02")).problems.contains(ProblemKind::InvalidAddress));
}

TEST(FdlTest, ShortAcknowledge) {
    FdlTelegram t = parse(hex("E5"));
    EXPECT_EQ(t.type, FrameType::ShortAck);
    EXPECT_EQ(t.size, 1);
    EXPECT_FALSE(t.is_request());
    EXPECT_TRUE(t.problems.empty());
    EXPECT_TRUE(parse(hex("E5 E5")).problems.contains(ProblemKind::TrailingBytes));
}

TEST(FdlTest, EmptyAndUnknownStartDelimiter) {
    EXPECT_TRUE(parse({}).problems.contains(ProblemKind::EmptyRecord));
    FdlTelegram t = parse(hex("2A 3F 9F"));
    EXPECT_EQ(t.type, FrameType::Invalid);
    ASSERT_EQ(t.problems.size(), 1u);
    EXPECT_EQ(t.problems[0].kind, ProblemKind::BadStartDelimiter);
    EXPECT_EQ(t.problems[0].actual, 0x2Au);
}

TEST(FdlTest, AddressExtensionAnnouncedButMissing) {
    // DA with bit 7 set, but no data unit for the DSAP byte (SD1).
    FdlTelegram t = parse(hex("10 83 02 49 CE 16"));
    EXPECT_TRUE(t.problems.contains(ProblemKind::AddressExtensionShort));
}

TEST(FdlTest, SegmentAddressExtension) {
    // DAE chain: 0xC5 = another follows (bit 7) + segment (bit 6) 5, then 0x3C = SAP 60.
    std::vector<std::uint8_t> manual = hex("68 06 06 68 83 02 7D C5 3C 00");
    manual.push_back(fcs_of(Bytes(manual.data() + 4, manual.size() - 4)));
    manual.push_back(0x16);
    FdlTelegram t = parse(manual);
    EXPECT_TRUE(t.has_dest_segment);
    EXPECT_EQ(t.dest_segment, 5);
    EXPECT_TRUE(t.has_dsap);
    EXPECT_EQ(t.dsap, 60);
    EXPECT_EQ(t.du.size(), 1u);
    EXPECT_TRUE(t.problems.empty());
}

// FC bit 7: only the clock value request 0xC0 sets it; anything else is a reserved code.
TEST(FdlTest, FrameControlBit7) {
    FdlTelegram clock = parse(hex("10 7F 02 C0 41 16"));
    EXPECT_TRUE(clock.problems.empty());
    EXPECT_TRUE(clock.fc.is_clock_value());
    EXPECT_FALSE(clock.fc.is_reserved());
    EXPECT_EQ(request_function_name(clock.fc), "clock value");
    FdlTelegram time_event = parse(hex("10 7F 02 40 C1 16"));
    EXPECT_TRUE(time_event.problems.empty());
    EXPECT_EQ(request_function_name(time_event.fc), "time event");
    EXPECT_EQ(request_function_name(FrameControl{0x7D}), "SRD high");
    EXPECT_EQ(request_function_name(FrameControl{0x4E}), "ident");
    EXPECT_EQ(request_function_name(FrameControl{0x4F}), "LSAP status");

    // Bit 7 with SRD high (request), and with DL (response): reserved, a problem at the FC byte.
    for (std::uint8_t fc : {std::uint8_t{0xCD}, std::uint8_t{0x88}, std::uint8_t{0xF0}}) {
        SCOPED_TRACE(fc);
        std::vector<std::uint8_t> bytes = {0x10, 0x03, 0x02, fc, 0x00, 0x16};
        bytes[4] = fcs_of(Bytes(bytes.data() + 1, 3));
        FdlTelegram t = parse(bytes);
        bool clock_with_fcb = (fc & 0xCF) == 0xC0;
        if (clock_with_fcb) {
            EXPECT_TRUE(t.problems.empty());
            continue;
        }
        ASSERT_EQ(t.problems.size(), 1u);
        EXPECT_EQ(t.problems[0].kind, ProblemKind::ReservedFrameControl);
        EXPECT_EQ(t.problems[0].offset, 3);
        EXPECT_EQ(t.problems[0].actual, fc);
        EXPECT_TRUE(t.fc.is_reserved());
        if (t.fc.is_request()) {
            EXPECT_EQ(request_function_name(t.fc), "reserved");
        }
        EXPECT_EQ(problem_kind_name(t.problems[0].kind), "reserved_frame_control");
        EXPECT_EQ(problem_severity(t.problems[0].kind), Severity::Error);
    }
    // SD2 with SAPs: FC at byte 6; a truncated telegram cut right after it still reports it.
    FdlTelegram cut = parse(hex("68 05 05 68 83 02 CD"));
    EXPECT_TRUE(cut.problems.contains(ProblemKind::ReservedFrameControl));
    EXPECT_EQ(cut.problems[0].offset, 6);
    EXPECT_TRUE(cut.problems.contains(ProblemKind::Truncated));
}

TEST(FdlTest, FrameControlNames) {
    EXPECT_EQ(request_function_name(0x0C), "SRD low");
    EXPECT_EQ(request_function_name(0x0D), "SRD high");
    EXPECT_EQ(request_function_name(0x04), "SDN low");
    EXPECT_EQ(request_function_name(0x05), "SDA high");
    EXPECT_EQ(request_function_name(0x09), "FDL status");
    EXPECT_EQ(request_function_name(0x08), "reserved");
    for (auto [code, name] : std::vector<std::pair<int, std::string>>{{0, "OK"},
                                                                      {1, "UE"},
                                                                      {2, "RR"},
                                                                      {3, "RS"},
                                                                      {8, "DL"},
                                                                      {9, "NR"},
                                                                      {10, "DH"},
                                                                      {12, "RDL"},
                                                                      {13, "RDH"},
                                                                      {5, "reserved"}})
        EXPECT_EQ(response_status_name(static_cast<std::uint8_t>(code)), name);
    EXPECT_EQ(station_type_name(0), "slave");
    EXPECT_EQ(station_type_name(3), "master in the token ring");
    FrameControl response{0x08};
    EXPECT_FALSE(response.is_request());
    EXPECT_EQ(response.station_type(), 0);
    FrameControl master_in_ring{0x30};
    EXPECT_EQ(master_in_ring.station_type(), 3);
    EXPECT_TRUE(function_expects_reply(0x0D));
    EXPECT_TRUE(function_expects_reply(0x09));
    EXPECT_FALSE(function_expects_reply(0x06));
}

}  // namespace
}  // namespace dpscope
