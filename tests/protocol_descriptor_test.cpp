// The table of protocol descriptors (core/protocol_descriptor.hpp) and the per-layer tables made
// from the same registration list (protocols/protocol_list.hpp): PROFIBUS DP's framing rules and
// pcap link types, every protocol listed once in the enum's order, names that round-trip, link
// types, lead bytes and bus numbers that tell the protocols apart, and a record in every layer.
#include "core/protocol_descriptor.hpp"

#include <gtest/gtest.h>

#include <set>

#include "capture/bus_tag.hpp"
#include "capture/pcap_source.hpp"
#include "formats/report_model.hpp"
#include "protocols/profibus/fdl_framing_rules.hpp"

namespace dpscope {
namespace {

TEST(ProtocolDescriptorTest, ProfibusDpIsFramedByFdlAndCarriedByLinkTypes257And147) {
    const ProtocolDescriptor& dp = profibus_protocol();
    EXPECT_EQ(dp.protocol, Protocol::ProfibusDp);
    EXPECT_EQ(dp.framing.protocol_name(), "PROFIBUS");
    EXPECT_EQ(&dp.framing, &fdl_framing_rules());
    ASSERT_EQ(dp.link_types.size(), 2u);
    EXPECT_EQ(dp.link_types[0].value, kLinkTypeProfibusDl);
    EXPECT_EQ(dp.link_types[0].name, "PROFIBUS_DL");
    EXPECT_EQ(dp.link_types[1].value, kLinkTypeUser0);
    EXPECT_EQ(dp.link_types[1].name, "USER0");
}

TEST(ProtocolDescriptorTest, CarriedByOnlyItsOwnLinkTypes) {
    const ProtocolDescriptor& dp = profibus_protocol();
    EXPECT_TRUE(dp.carried_by(257));
    EXPECT_TRUE(dp.carried_by(147));
    for (int other : {0, 1, 148, 256, 258, -1})
        EXPECT_FALSE(dp.carried_by(other)) << other;
}

TEST(ProtocolDescriptorTest, EveryProtocolIsListedOnceWithLinkTypesNoOtherClaims) {
    auto protocols = protocol_table();
    ASSERT_FALSE(protocols.empty());
    EXPECT_EQ(protocols[0], &profibus_protocol());
    std::set<Protocol> seen_protocols;
    // USER0 is the link type of every bus without one of its own (the bus is recorded in the
    // file); every other link type belongs to one protocol.
    std::set<int> seen_link_types;
    for (const ProtocolDescriptor* protocol : protocols) {
        EXPECT_TRUE(seen_protocols.insert(protocol->protocol).second)
            << protocol->framing.protocol_name();
        EXPECT_FALSE(protocol->link_types.empty()) << protocol->framing.protocol_name();
        for (const PcapLinkType& type : protocol->link_types) {
            EXPECT_TRUE(seen_link_types.insert(type.value).second || type.value == kLinkTypeUser0)
                << type.value;
            // link_type_name() names a protocol's link types as the protocol does.
            EXPECT_EQ(link_type_name(type.value), type.name);
        }
    }
}

TEST(ProtocolDescriptorTest, TheTableIsInTheEnumsOrderAndNamesRoundTrip) {
    const auto table = protocol_table();
    ASSERT_EQ(table.size(), kProtocolCount);
    std::set<std::string_view> names;
    for (std::size_t i = 0; i < table.size(); ++i) {
        const ProtocolDescriptor& d = *table[i];
        EXPECT_EQ(static_cast<std::size_t>(d.protocol), i) << d.name;
        EXPECT_EQ(&protocol_descriptor(d.protocol), &d) << d.name;
        EXPECT_EQ(protocol_by_name(d.name), &d) << d.name;
        EXPECT_EQ(protocol_name(d.protocol), d.name);
        EXPECT_EQ(protocol_from_name(d.name), d.protocol) << d.name;
        EXPECT_TRUE(names.insert(d.name).second) << d.name;
    }
    EXPECT_EQ(protocol_by_name("modbus"), nullptr);
    EXPECT_EQ(protocol_by_name(""), nullptr);
    EXPECT_FALSE(protocol_from_name("PROFIBUS").has_value());  // names are exact
}

TEST(ProtocolDescriptorTest, EveryProtocolIsDescribedWhole) {
    for (const ProtocolDescriptor* d : protocol_table()) {
        EXPECT_FALSE(d->name.empty());
        EXPECT_FALSE(d->title.empty()) << d->name;
        EXPECT_FALSE(d->capture_noun.empty()) << d->name;
        EXPECT_FALSE(d->traffic_name.empty()) << d->name;
        EXPECT_NE(d->pcap_bus_number, 0u) << d->name;
        EXPECT_NE(d->addresses_pnu, nullptr) << d->name;
        EXPECT_NE(d->mark_pnus, nullptr) << d->name;
        EXPECT_EQ(d->lead_byte.has_value(), !d->lead_byte_text.empty()) << d->name;
    }
}

TEST(ProtocolDescriptorTest, BusNumbersLeadBytesAndTextLogsTellTheProtocolsApart) {
    std::set<std::uint32_t> numbers;
    std::set<std::uint8_t> lead_bytes;
    int text_logs = 0;
    for (const ProtocolDescriptor* d : protocol_table()) {
        EXPECT_TRUE(numbers.insert(d->pcap_bus_number).second) << d->name;
        EXPECT_EQ(protocol_of_pcap_bus_number(d->pcap_bus_number), d->protocol) << d->name;
        if (d->lead_byte) {
            EXPECT_TRUE(lead_bytes.insert(*d->lead_byte).second) << d->name;
            EXPECT_EQ(protocol_of_untagged_user0(*d->lead_byte), d->protocol) << d->name;
        }
        if (!d->text_log_shape.empty()) ++text_logs;
    }
    EXPECT_FALSE(protocol_of_pcap_bus_number(0).has_value());
    // The first protocol is what an untagged USER0 capture is when no lead byte fits.
    EXPECT_EQ(protocol_of_untagged_user0(0x68), protocol_table().front()->protocol);
    ASSERT_EQ(text_logs, 1);
    EXPECT_EQ(text_log_protocol(), &vlt2000_protocol());
}

TEST(ProtocolDescriptorTest, ALinkTypeOfOneProtocolNamesItAndASharedOneNone) {
    EXPECT_EQ(only_protocol_of_link_type(kLinkTypeProfibusDl), &profibus_protocol());
    EXPECT_EQ(only_protocol_of_link_type(kLinkTypeUser0), nullptr);  // every bus writes USER0
    EXPECT_EQ(only_protocol_of_link_type(1), nullptr);
    for (const ProtocolDescriptor* d : protocol_table())
        EXPECT_TRUE(d->carried_by(d->written_link_type().value)) << d->name;
}

TEST(ProtocolDescriptorTest, EveryProtocolHasARecordInEveryLayersTable) {
    const auto reports = report::bus_report_table();
    ASSERT_EQ(reports.size(), kProtocolCount);
    for (const ProtocolDescriptor* d : protocol_table()) {
        EXPECT_EQ(reports[static_cast<std::size_t>(d->protocol)]->protocol, d->protocol)
            << d->name;
    }
}

}  // namespace
}  // namespace dpscope
