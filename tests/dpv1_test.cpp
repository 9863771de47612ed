// DP-V1 PDUs: function numbers and their names, Read/Write requests and responses, negative
// responses split into Error_Decode, class, code and Error_Code_2, Initiate, Abort, Alarm_Ack,
// Idle, Data_Transport; cut-short PDUs give problems at their offsets and never crash.
#include "protocols/profibus/dpv1/dpv1.hpp"

#include <gtest/gtest.h>

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::hex;

// The PDU of `bytes`, as if the data unit started at byte 9 of its telegram (SD2 with SAPs).
constexpr std::size_t kDuOffset = 9;

struct Parsed {
    std::vector<std::uint8_t> bytes;
    Dpv1Pdu pdu;
    ProblemList problems;
};

Parsed parse(std::string_view text, bool request = true) {
    Parsed p;
    p.bytes = hex(text);
    parse_dpv1_pdu(ByteReader(Bytes(p.bytes.data(), p.bytes.size()), kDuOffset), request, p.pdu,
                   p.problems);
    return p;
}

TEST(Dpv1Test, EveryFunctionNumberAndItsNegativeFormHasItsName) {
    struct Case {
        std::uint8_t function;
        std::string_view name;
    };
    for (const Case& c :
         {Case{0x48, "Idle"}, Case{0x51, "Data_Transport"}, Case{0x56, "Resource_Manager"},
          Case{0x57, "Initiate"}, Case{0x58, "Abort"}, Case{0x5C, "Alarm_Ack"}, Case{0x5E, "Read"},
          Case{0x5F, "Write"}}) {
        EXPECT_EQ(dpv1_function_name(c.function), c.name);
        EXPECT_EQ(dpv1_function_name(c.function | 0x80), std::string(c.name) + " negative");
    }
    EXPECT_EQ(dpv1_function_name(0x00), "");
    EXPECT_EQ(dpv1_function_name(0x5D), "");
    EXPECT_EQ(dpv1_function_name(0xFF), "");
}

TEST(Dpv1Test, ErrorDecodeClassAndCodeNames) {
    EXPECT_EQ(dpv1_error_decode_name(0x80), "DP-V1");
    EXPECT_EQ(dpv1_error_decode_name(0xFE), "FMS");
    EXPECT_EQ(dpv1_error_decode_name(0xFF), "HART");
    EXPECT_EQ(dpv1_error_decode_name(0x81), "PNIO");
    EXPECT_EQ(dpv1_error_decode_name(0x00), "");

    EXPECT_EQ(dpv1_error_class_name(0xA0), "application");
    EXPECT_EQ(dpv1_error_class_name(0xB5), "access");
    EXPECT_EQ(dpv1_error_class_name(0xC2), "resource");
    EXPECT_EQ(dpv1_error_class_name(0xD0), "user specific");
    EXPECT_EQ(dpv1_error_class_name(0xFF), "user specific");
    EXPECT_EQ(dpv1_error_class_name(0x95), "");

    struct Case {
        std::uint8_t code;
        std::string_view name;
    };
    for (const Case& c : {Case{0xA0, "read error"},
                          Case{0xA1, "write error"},
                          Case{0xA2, "module failure"},
                          Case{0xA8, "version conflict"},
                          Case{0xA9, "feature not supported"},
                          Case{0xAA, "user specific"},
                          Case{0xAF, "user specific"},
                          Case{0xA3, "reserved"},
                          Case{0xB0, "invalid index"},
                          Case{0xB1, "write length error"},
                          Case{0xB2, "invalid slot"},
                          Case{0xB3, "type conflict"},
                          Case{0xB4, "invalid area"},
                          Case{0xB5, "state conflict"},
                          Case{0xB6, "access denied"},
                          Case{0xB7, "invalid range"},
                          Case{0xB8, "invalid parameter"},
                          Case{0xB9, "invalid type"},
                          Case{0xBA, "user specific"},
                          Case{0xC0, "read constraint conflict"},
                          Case{0xC1, "write constraint conflict"},
                          Case{0xC2, "resource busy"},
                          Case{0xC3, "resource unavailable"},
                          Case{0xC4, "reserved"},
                          Case{0xC8, "user specific"},
                          Case{0xD3, "user specific"},
                          Case{0x10, "reserved"}})
        EXPECT_EQ(dpv1_error_code_name(c.code), c.name) << int(c.code);
}

TEST(Dpv1Test, ReadRequestCarriesTheMostTheMasterAccepts) {
    Parsed p = parse("5E 00 2F F0");
    EXPECT_EQ(p.pdu.layout, Dpv1Pdu::Layout::Addressed);
    EXPECT_TRUE(p.pdu.is_read());
    EXPECT_FALSE(p.pdu.negative());
    EXPECT_EQ(p.pdu.slot, 0);
    EXPECT_EQ(p.pdu.index, 47);
    EXPECT_EQ(p.pdu.length, 240);
    EXPECT_TRUE(p.pdu.data.empty());
    EXPECT_EQ(p.pdu.data_offset, kDuOffset + 4);
    EXPECT_TRUE(p.pdu.on_parameter_channel());
    EXPECT_TRUE(p.pdu.complete);
    EXPECT_TRUE(p.problems.empty());
}

TEST(Dpv1Test, WriteRequestAndItsEchoedResponse) {
    Parsed req = parse("5F 01 2F 0A 05 01 01 01 10 01 00 0C 00 04");
    EXPECT_TRUE(req.pdu.is_write());
    EXPECT_EQ(req.pdu.slot, 1);
    EXPECT_EQ(req.pdu.length, 10);
    ASSERT_EQ(req.pdu.data.size(), 10u);
    EXPECT_EQ(req.pdu.data[0], 0x05);
    EXPECT_EQ(req.pdu.data_offset, kDuOffset + 4);

    Parsed res = parse("5F 01 2F 0A", false);
    EXPECT_EQ(res.pdu.layout, Dpv1Pdu::Layout::Addressed);
    EXPECT_EQ(res.pdu.length, 10);
    EXPECT_TRUE(res.pdu.data.empty());
    EXPECT_TRUE(res.problems.empty());
}

TEST(Dpv1Test, IndexOtherThan47IsNoParameterChannel) {
    Parsed p = parse("5E 00 03 04 01 02 03 04", false);
    EXPECT_FALSE(p.pdu.on_parameter_channel());
    EXPECT_EQ(p.pdu.data.size(), 4u);
}

TEST(Dpv1Test, NegativeResponseSplitsErrorCode1IntoClassAndCode) {
    Parsed p = parse("DE 80 B5 00", false);
    EXPECT_EQ(p.pdu.layout, Dpv1Pdu::Layout::Error);
    EXPECT_TRUE(p.pdu.negative());
    EXPECT_TRUE(p.pdu.is_read());
    EXPECT_EQ(p.pdu.error_decode, 0x80);
    EXPECT_EQ(p.pdu.error_code_1, 0xB5);
    EXPECT_EQ(p.pdu.error_code_2, 0x00);
    EXPECT_TRUE(p.pdu.is_state_conflict());
    EXPECT_FALSE(p.pdu.on_parameter_channel());
    EXPECT_EQ(dpv1_error_class_name(p.pdu.error_code_1), "access");
    EXPECT_EQ(dpv1_error_code_name(p.pdu.error_code_1), "state conflict");

    Parsed w = parse("DF 80 A1 07", false);
    EXPECT_TRUE(w.pdu.is_write());
    EXPECT_FALSE(w.pdu.is_state_conflict());
    EXPECT_EQ(w.pdu.error_code_2, 0x07);

    for (std::string_view text : {"D1 80 B0 00", "D7 80 C3 00", "DC 80 A9 00"}) {
        Parsed other = parse(text, false);
        EXPECT_EQ(other.pdu.layout, Dpv1Pdu::Layout::Error) << text;
        EXPECT_TRUE(other.problems.empty()) << text;
    }
}

TEST(Dpv1Test, NegativeResponseCutShortKeepsWhatWasRead) {
    Parsed p = parse("DE 80", false);
    EXPECT_EQ(p.pdu.layout, Dpv1Pdu::Layout::Error);
    EXPECT_EQ(p.pdu.error_decode, 0x80);
    EXPECT_EQ(p.pdu.error_code_1, 0);
    EXPECT_FALSE(p.pdu.complete);
    ASSERT_EQ(p.problems.size(), 1u);
    EXPECT_EQ(p.problems[0].kind, ProblemKind::ServiceDataShort);
    EXPECT_EQ(p.problems[0].offset, kDuOffset + 1);
    EXPECT_EQ(p.problems[0].expected, 3u);
    EXPECT_EQ(p.problems[0].actual, 1u);
}

TEST(Dpv1Test, AddressedHeaderCutShort) {
    Parsed p = parse("5E 00");
    EXPECT_EQ(p.pdu.layout, Dpv1Pdu::Layout::Addressed);
    EXPECT_EQ(p.pdu.slot, 0);
    EXPECT_FALSE(p.pdu.complete);
    ASSERT_EQ(p.problems.size(), 1u);
    EXPECT_EQ(p.problems[0].kind, ProblemKind::ServiceDataShort);
    EXPECT_EQ(p.problems[0].offset, kDuOffset + 1);
    EXPECT_FALSE(p.pdu.on_parameter_channel() && !p.pdu.data.empty());
}

TEST(Dpv1Test, EmptyDataUnitIsNoPdu) {
    Parsed p = parse("");
    EXPECT_EQ(p.pdu.layout, Dpv1Pdu::Layout::None);
    EXPECT_TRUE(p.problems.empty());
}

TEST(Dpv1Test, InitiateRequestFields) {
    // Send_Timeout 1000 (10 s), Features_Supported 0x0100, profile features 0x0000, ident
    // 0x1234; S_Type 0, S_Len 2, D_Type 1, D_Len 2 and the addresses.
    Parsed p = parse("57 00 00 00 03 E8 01 00 00 00 12 34 00 02 01 02 AA BB CC DD");
    EXPECT_EQ(p.pdu.layout, Dpv1Pdu::Layout::Initiate);
    const Dpv1Initiate& i = p.pdu.initiate;
    EXPECT_EQ(i.send_timeout, 1000);
    EXPECT_EQ(i.features_supported, 0x0100);
    EXPECT_EQ(i.profile_features_supported, 0);
    EXPECT_EQ(i.profile_ident_number, 0x1234);
    EXPECT_TRUE(i.has_addresses);
    EXPECT_EQ(i.s_type, 0);
    EXPECT_EQ(i.s_len, 2);
    EXPECT_EQ(i.d_type, 1);
    EXPECT_EQ(i.d_len, 2);
    EXPECT_EQ(std::vector<std::uint8_t>(i.s_addr.begin(), i.s_addr.end()), hex("AA BB"));
    EXPECT_EQ(std::vector<std::uint8_t>(i.d_addr.begin(), i.d_addr.end()), hex("CC DD"));
    EXPECT_TRUE(p.problems.empty());
}

TEST(Dpv1Test, InitiateResponseFields) {
    Parsed p = parse("57 F0 01 00 00 00 12 34 00 00 00 00", false);
    EXPECT_EQ(p.pdu.layout, Dpv1Pdu::Layout::Initiate);
    const Dpv1Initiate& i = p.pdu.initiate;
    EXPECT_EQ(i.max_len_data_unit, 240);
    EXPECT_EQ(i.send_timeout, 0);
    EXPECT_EQ(i.features_supported, 0x0100);
    EXPECT_EQ(i.profile_ident_number, 0x1234);
    EXPECT_TRUE(i.has_addresses);
    EXPECT_TRUE(i.s_addr.empty());
    EXPECT_TRUE(p.problems.empty());
}

TEST(Dpv1Test, InitiateCutShort) {
    Parsed fixed = parse("57 00 00 00 03");
    EXPECT_EQ(fixed.pdu.layout, Dpv1Pdu::Layout::Initiate);
    EXPECT_FALSE(fixed.pdu.initiate.has_addresses);
    EXPECT_FALSE(fixed.pdu.complete);
    ASSERT_EQ(fixed.problems.size(), 1u);
    EXPECT_EQ(fixed.problems[0].offset, kDuOffset + 1);
    EXPECT_EQ(fixed.problems[0].expected, 11u);

    Parsed no_addresses = parse("57 F0 01 00 00 00 12 34 00", false);
    EXPECT_EQ(no_addresses.pdu.initiate.profile_ident_number, 0x1234);
    EXPECT_FALSE(no_addresses.pdu.initiate.has_addresses);
    EXPECT_TRUE(no_addresses.pdu.complete);
    ASSERT_EQ(no_addresses.problems.size(), 1u);
    EXPECT_EQ(no_addresses.problems[0].offset, kDuOffset + 8);

    // S_Len 4 announced, 1 byte there.
    Parsed address = parse("57 F0 01 00 00 00 12 34 00 04 00 00 AA", false);
    EXPECT_TRUE(address.pdu.initiate.has_addresses);
    EXPECT_EQ(address.pdu.initiate.s_addr.size(), 1u);
    ASSERT_EQ(address.problems.size(), 1u);
    EXPECT_EQ(address.problems[0].kind, ProblemKind::ServiceDataShort);
    EXPECT_EQ(address.problems[0].offset, kDuOffset + 13);
}

TEST(Dpv1Test, AbortFields) {
    Parsed p = parse("58 00 13");
    EXPECT_EQ(p.pdu.layout, Dpv1Pdu::Layout::Abort);
    EXPECT_EQ(p.pdu.abort.subnet, 0);
    EXPECT_EQ(p.pdu.abort.instance(), 1);
    EXPECT_EQ(p.pdu.abort.reason(), 3);
    EXPECT_EQ(dpv1_abort_instance_name(p.pdu.abort.instance_reason), "MSAC_C2");
    EXPECT_EQ(dpv1_abort_reason_name(p.pdu.abort.instance_reason), "connection timeout (ABT_TO)");
    EXPECT_EQ(dpv1_abort_instance_name(0x09), "FDL");
    EXPECT_EQ(dpv1_abort_reason_name(0x09), "no response (NR)");
    EXPECT_EQ(dpv1_abort_instance_name(0x25), "user");
    EXPECT_EQ(dpv1_abort_reason_name(0x25), "user specific");
    EXPECT_EQ(dpv1_abort_instance_name(0x30), "reserved");
    EXPECT_EQ(dpv1_abort_reason_name(0x1F), "reserved");

    // Every reason the FDL and MSAC_C2 instances name (dpscope's reading of IEC 61158-6-3).
    const std::pair<std::uint8_t, std::string_view> named[] = {
        {0x01, "user error (UE)"},
        {0x02, "no resource (RR)"},
        {0x03, "service not activated (RS)"},
        {0x0A, "data high (DH)"},
        {0x0B, "local resource error (LR)"},
        {0x0C, "no response data (RDL)"},
        {0x0D, "response data high (RDH)"},
        {0x0E, "not in the logical ring (DS)"},
        {0x0F, "no reaction (NA)"},
        {0x04, "reserved"},
        {0x11, "sequence error (ABT_SE)"},
        {0x12, "invalid request PDU (ABT_FE)"},
        {0x14, "invalid response PDU (ABT_RE)"},
        {0x15, "invalid service from the user (ABT_IV)"},
        {0x16, "Send_Timeout too small (ABT_STO)"},
        {0x17, "invalid additional address information (ABT_IA)"},
        {0x18, "waiting for FDL_DATA_REPLY.con (ABT_OC)"},
    };
    for (const auto& [instance_reason, name] : named)
        EXPECT_EQ(dpv1_abort_reason_name(instance_reason), name) << int{instance_reason};

    Parsed cut = parse("58 02");
    EXPECT_EQ(cut.pdu.layout, Dpv1Pdu::Layout::Abort);
    EXPECT_EQ(cut.pdu.abort.subnet, 2);
    ASSERT_EQ(cut.problems.size(), 1u);
    EXPECT_EQ(cut.problems[0].offset, kDuOffset + 1);
}

TEST(Dpv1Test, AlarmAckSlotTypeAndSpecifier) {
    Parsed p = parse("5C 02 01 0A");
    EXPECT_EQ(p.pdu.layout, Dpv1Pdu::Layout::Addressed);
    EXPECT_EQ(p.pdu.slot, 2);
    EXPECT_EQ(p.pdu.index, 1);    // Alarm_Type
    EXPECT_EQ(p.pdu.length, 10);  // Specifier
    EXPECT_FALSE(p.pdu.on_parameter_channel());
    EXPECT_TRUE(p.problems.empty());
}

TEST(Dpv1Test, IdleIsTheFunctionAlone) {
    Parsed p = parse("48");
    EXPECT_EQ(p.pdu.layout, Dpv1Pdu::Layout::Idle);
    EXPECT_EQ(p.pdu.function, 0x48);
    EXPECT_TRUE(p.problems.empty());
}

TEST(Dpv1Test, DataTransportCarriesData) {
    Parsed p = parse("51 00 2F 03 01 02 03");
    EXPECT_EQ(p.pdu.layout, Dpv1Pdu::Layout::Addressed);
    EXPECT_EQ(p.pdu.base_function(), 0x51);
    EXPECT_EQ(p.pdu.data.size(), 3u);
    EXPECT_FALSE(p.pdu.on_parameter_channel());  // only Read and Write carry PROFIdrive
}

TEST(Dpv1Test, UnknownFunctionKeepsTheRest) {
    Parsed p = parse("33 01 02");
    EXPECT_EQ(p.pdu.layout, Dpv1Pdu::Layout::Unknown);
    EXPECT_EQ(p.pdu.data.size(), 2u);
    EXPECT_EQ(p.pdu.data_offset, kDuOffset + 1);
    Parsed rm = parse("56 00");
    EXPECT_EQ(rm.pdu.layout, Dpv1Pdu::Layout::Unknown);
}

TEST(Dpv1Test, EveryPrefixOfEveryPduParsesWithoutCrashing) {
    for (std::string_view text : {"5F 01 2F 0A 05 01 01 01 10 01 00 0C 00 04", "DE 80 B5 00",
                                  "57 00 00 00 03 E8 01 00 00 00 12 34 00 02 01 02 AA BB CC DD",
                                  "57 F0 01 00 00 00 12 34 00 00 00 00", "58 00 13", "5C 02 01 0A",
                                  "48", "51 00 2F 01 01"}) {
        std::vector<std::uint8_t> bytes = hex(text);
        for (std::size_t n = 0; n <= bytes.size(); ++n) {
            Dpv1Pdu pdu;
            ProblemList problems;
            parse_dpv1_pdu(ByteReader(Bytes(bytes.data(), n), kDuOffset), true, pdu, problems);
            parse_dpv1_pdu(ByteReader(Bytes(bytes.data(), n), kDuOffset), false, pdu, problems);
            for (const Problem& problem : problems)
                EXPECT_LE(problem.offset, kDuOffset + n) << text << " cut at " << n;
        }
    }
}

}  // namespace
}  // namespace dpscope
