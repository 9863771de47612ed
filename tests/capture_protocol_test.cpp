// The protocol a capture carries, as the capture layer sees it: PROFIBUS DP's framing rules and
// pcap link types, and the list of every protocol dpscope reads.
#include "core/protocol_descriptor.hpp"

#include <gtest/gtest.h>

#include <set>

#include "capture/pcap_source.hpp"
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

}  // namespace
}  // namespace dpscope
