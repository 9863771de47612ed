// The table of protocol descriptors (core/protocol_descriptor.hpp) and the per-layer tables made
// from the same registration list (protocols/protocol_list.hpp): PROFIBUS DP's framing rules and
// pcap link types, every protocol listed once in the enum's order, names that round-trip, link
// types, lead bytes and bus numbers that tell the protocols apart, and a record in every layer.
#include "core/protocol_descriptor.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "capture/bus_tag.hpp"
#include "capture/pcap_source.hpp"
#include "core/protocol_lane.hpp"
#include "formats/report_model.hpp"
#include "protocols/fc/fc_tracker.hpp"
#include "protocols/lane_options.hpp"
#include "protocols/profibus/fdl_framing_rules.hpp"
#include "test_support.hpp"

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
        // What --pnu selects: the bus's dpscope.pnu filter field.
        EXPECT_TRUE(std::any_of(d->filter_fields.begin(), d->filter_fields.end(),
                                [](const FilterField& f) { return f.name == "dpscope.pnu"; }))
            << d->name;
        EXPECT_EQ(d->lead_byte.has_value(), !d->lead_byte_text.empty()) << d->name;
        EXPECT_GT(d->max_telegram_bytes, 0u) << d->name;
        EXPECT_NE(d->make_decoder, nullptr) << d->name;
        EXPECT_NE(d->make_tracker, nullptr) << d->name;
        EXPECT_EQ(d->min_baud == 0, d->max_baud == 0) << d->name;
        EXPECT_LE(d->min_baud, d->max_baud) << d->name;
        EXPECT_TRUE(d->default_parity == "even" || d->default_parity == "none") << d->name;
    }
}

// The lanes (core/protocol_lane.hpp): each protocol's factories make a decoder whose telegrams
// are of that protocol and a tracker with the shared time-out; a telegram it cannot frame is
// decoded with problems, tracked, and no station is made up from it.
TEST(ProtocolDescriptorTest, EveryProtocolMakesItsDecoderAndTrackerFromTheSharedOptions) {
    LaneOptions options;
    options.timeout_ns = 250'000'000;
    const std::vector<std::uint8_t> junk = test::hex("00 01 02 03");
    for (const ProtocolDescriptor* d : protocol_table()) {
        std::unique_ptr<TelegramDecoder> decoder = d->make_decoder(options);
        std::unique_ptr<TelegramTracker> tracker = d->make_tracker(options);
        ASSERT_NE(decoder, nullptr) << d->name;
        ASSERT_NE(tracker, nullptr) << d->name;
        EXPECT_EQ(tracker->timeout_ns(), 250'000'000) << d->name;
        const DecodedTelegram& t = decoder->decode(Bytes(junk.data(), junk.size()), 1'000, 1);
        EXPECT_EQ(t.protocol, d->protocol) << d->name;
        EXPECT_FALSE(t.problems().empty()) << d->name;
        (void)tracker->track(t);
        (void)tracker->finish();
        EXPECT_FALSE(tracker->has_station(0)) << d->name;
        EXPECT_TRUE(tracker->end_warnings(1).empty()) << d->name;
    }
}

// A decoder's clone decodes on exactly as the original: an FC response cloned after its request
// is still decoded against it.
TEST(ProtocolDescriptorTest, ACloneDecodesOnAsTheOriginal) {
    std::unique_ptr<TelegramDecoder> original = fc_protocol().make_decoder(LaneOptions{});
    const std::vector<std::uint8_t> request = test::fc_parameter(3, 1, 414);
    const std::vector<std::uint8_t> response = test::fc_parameter(3, 1, 414, 0, 1500, 0x0607);
    (void)original->decode(Bytes(request.data(), request.size()), 1'000'000, 1);
    std::unique_ptr<TelegramDecoder> copy = original->clone();
    const DecodedTelegram& a =
        original->decode(Bytes(response.data(), response.size()), 5'000'000, 2);
    const Direction direction = a.direction;
    const std::uint64_t request_frame = a.request_frame;
    const DecodedTelegram& b = copy->decode(Bytes(response.data(), response.size()), 5'000'000, 2);
    EXPECT_EQ(direction, Direction::Response);
    EXPECT_EQ(request_frame, 1u);
    EXPECT_EQ(b.direction, direction);
    EXPECT_EQ(b.request_frame, request_frame);
}

// The serial buses' trackers take the line from the shared options, or their own default; a
// drive seen is a station of the capture, and a response earlier than the line allows is named
// at the end.
TEST(ProtocolDescriptorTest, TheLineComesFromTheSharedOptionsOrTheBussDefault) {
    LaneOptions options;
    std::unique_ptr<TelegramTracker> by_default = fc_protocol().make_tracker(options);
    EXPECT_EQ(static_cast<const FcTracker&>(*by_default).options().line_baud,
              fc_protocol().default_baud);
    options.line_baud = 2400;
    options.character_bits = 10;
    std::unique_ptr<TelegramTracker> tracker = fc_protocol().make_tracker(options);
    const auto& fc = static_cast<const FcTracker&>(*tracker);
    EXPECT_EQ(fc.options().line_baud, 2400u);
    EXPECT_EQ(fc.options().character_bits, 10u);

    std::unique_ptr<TelegramDecoder> decoder = fc_protocol().make_decoder(options);
    const std::vector<std::uint8_t> request = test::fc_parameter(3, 1, 414);
    const std::vector<std::uint8_t> response = test::fc_parameter(3, 1, 414, 0, 1500, 0x0607);
    // 16 bytes at 2400 baud take 67 ms: a response 1 ms after the request began is early.
    (void)tracker->track(decoder->decode(Bytes(request.data(), request.size()), 1'000'000, 1));
    (void)tracker->track(decoder->decode(Bytes(response.data(), response.size()), 2'000'000, 2));
    (void)tracker->finish();
    EXPECT_TRUE(tracker->has_station(3));
    EXPECT_FALSE(tracker->has_station(4));
    const std::vector<std::string> warnings = tracker->end_warnings(2);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("1 response began before its command could have ended at 2400 "
                               "baud (10 bits a byte)"),
              std::string::npos)
        << warnings[0];
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
