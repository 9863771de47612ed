// What a drive says about its own parameters (drives/described_parameters.hpp, issue 29): a
// PROFIdrive description (attribute 0x20) read in the capture names and scales the station's
// parameter from then on, before the databases; element 4 (variable attribute), 6 (name), 1, 2
// and 0 (the whole description); cut-short and damaged answers teach nothing; a decoder's clone
// keeps its own descriptions.
#include "drives/described_parameters.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "drives/parameter_naming.hpp"
#include "formats/describe.hpp"
#include "protocols/profibus/bus_decoder.hpp"
#include "protocols/profibus/gsd/gsd_library.hpp"
#include "protocols/profibus/telegram_builder.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using ByteVector = std::vector<std::uint8_t>;

constexpr std::uint8_t kMaster = 1;
constexpr std::uint8_t kSlave = 5;
constexpr std::uint8_t kSap = 51;

// A database of one family "t" (plain numbers): PNU 100 "Speed" with no conversion, and the
// profile family's 922.
std::shared_ptr<const ParameterDatabase> test_database() {
    auto db = std::make_shared<ParameterDatabase>();
    Result<ParameterFile> t = parse_parameter_database(
        "@family t\n@source D = d\n100 | Speed | - | - | int16 | 1 | D\n", "t.params");
    EXPECT_TRUE(t) << t.error();
    db->add(std::move(t->family));
    return db;
}

void put16(ByteVector& out, std::uint16_t v) { append_u16_be(out, v); }
using test::joined;

// The DP-V1 Write of a PROFIdrive request reading `attribute` element `subindex` of `pnu`.
ByteVector read_request(std::uint8_t reference, std::uint8_t attribute, std::uint16_t pnu,
                        std::uint16_t subindex) {
    ByteVector p{reference, 0x01, 0x00, 0x01, attribute, 0x01};
    put16(p, pnu);
    put16(p, subindex);
    return joined({0x5F, 0, 47, static_cast<std::uint8_t>(p.size())}, p);
}

// The DP-V1 Read response carrying one PROFIdrive value block.
ByteVector block_response(std::uint8_t reference, std::uint8_t format, std::uint8_t count,
                          const ByteVector& values) {
    ByteVector p = joined({reference, 0x01, 0x00, 0x01, format, count}, values);
    if (p.size() % 2) p.push_back(0);
    return joined({0x5E, 0, 47, static_cast<std::uint8_t>(p.size())}, p);
}

class DescribingBus {
  public:
    DescribingBus() {
        DecoderOptions options;
        options.station_dialect[kSlave] = Dialect::Profidrive;
        DriveHints hints;
        hints.station[kSlave] = "t";
        std::array<Dialect, kStationCount> dialects{};
        dialects[kSlave] = Dialect::Profidrive;
        options.naming = std::make_shared<ParameterNaming>(test_database(), Protocol::ProfibusDp,
                                                           dialects, hints);
        decoder_ = std::make_unique<BusDecoder>(options);
    }

    // The request, then its answer; the answer as decoded.
    const DecodedTelegram& exchange(const ByteVector& request, const ByteVector& answer,
                                    bool damage = false) {
        decode(build_telegram({kSlave, kMaster, request_fc(FdlFunction::SrdHigh, fcb_, true), kSap,
                               kSap, Bytes(request)}));
        fcb_ = !fcb_;
        ByteVector bytes = build_telegram(
            {kMaster, kSlave, response_fc(FdlStatus::DataLow), kSap, kSap, Bytes(answer)});
        if (damage) bytes[bytes.size() - 2] ^= 0xFF;  // the FCS
        return decode(bytes);
    }
    // A read of PNU `pnu`'s value answered with Integer16 `value`: its value in its unit.
    std::string value_in_unit(std::uint16_t pnu, std::uint16_t value) {
        ByteVector v;
        put16(v, value);
        const std::uint8_t reference = ++reference_;
        const DecodedTelegram& t =
            exchange(read_request(reference, 0x10, pnu, 0), block_response(reference, 0x03, 1, v));
        const ProfidriveMessage* m = t.dp.service_data.profidrive();
        if (!m) return "no message";
        const std::optional<ScaledValue> scaled = profidrive_value_in_unit(t, *m, 0);
        const NamedParameter named = profidrive_parameter(t, *m, 0);
        if (!scaled || !named.row) return "none";
        return format_scaled(*scaled) + (named.row->unit.empty() ? "" : " " + named.row->unit);
    }
    std::string name_of(std::uint16_t pnu) {
        const NamedParameter named = decoder_->decode({}, 0, 0).naming
                                         ? decoder_->decode({}, 0, 0).naming->parameter(kSlave, pnu)
                                         : NamedParameter{};
        return named.row ? named.row->name : "";
    }
    const DecodedTelegram& describe(std::uint16_t pnu, std::uint16_t element, std::uint8_t format,
                                    const ByteVector& values, bool damage = false) {
        const std::uint8_t reference = ++reference_;
        return exchange(
            read_request(reference, 0x20, pnu, element),
            block_response(reference, format, static_cast<std::uint8_t>(values.size()), values),
            damage);
    }
    BusDecoder& decoder() { return *decoder_; }

  private:
    const DecodedTelegram& decode(const ByteVector& bytes) {
        held_.push_back(bytes);
        ++frame_;
        return decoder_->decode(Bytes(held_.back()), static_cast<std::int64_t>(frame_) * 1'000'000,
                                frame_);
    }
    std::unique_ptr<BusDecoder> decoder_;
    std::vector<ByteVector> held_;
    std::uint64_t frame_ = 0;
    std::uint8_t reference_ = 0;
    bool fcb_ = false;
};

TEST(DescribedParametersTest, TheVariableAttributeScalesTheStationsParameterFromThenOn) {
    DescribingBus bus;
    EXPECT_EQ(bus.value_in_unit(100, 500), "none");  // the row has no conversion
    // Element 4: variable index 28 (frequency), conversion index -1.
    bus.describe(100, 4, 0x0A, {28, 0xFF});
    EXPECT_EQ(bus.value_in_unit(100, 500), "50.0 Hz");
    EXPECT_EQ(bus.value_in_unit(100, 0xFFF6), "-1.0 Hz");  // Integer16, signed
    // The name stays the database's; the row says where it came from.
    EXPECT_EQ(bus.name_of(100), "Speed");
}

TEST(DescribedParametersTest, AParameterNoDatabaseHasIsNamedOnceTheDriveGivesItsName) {
    DescribingBus bus;
    bus.describe(2000, 4, 0x0A, {22, 0xFE});  // current, 0.01 A: no name yet
    EXPECT_EQ(bus.value_in_unit(2000, 1234), "none");
    bus.describe(2000, 6, 0x09,
                 {'M', 'o', 't', 'o', 'r', ' ', 'c', 'u', 'r', 'r', 'e', 'n', 't', ' ', ' ', ' '});
    EXPECT_EQ(bus.name_of(2000), "Motor current");
    EXPECT_EQ(bus.value_in_unit(2000, 1234), "12.34 A");
}

TEST(DescribedParametersTest, TheWholeDescriptionGivesTypeElementsUnitAndName) {
    DescribingBus bus;
    ByteVector whole(46, 0);
    whole[0] = 0x00;
    whole[1] = 0x06;  // identifier: Unsigned16
    whole[3] = 0x01;  // one element
    whole[8] = 4;     // time
    whole[9] = 74;    // hours
    const char name[] = "Running hours";
    for (std::size_t i = 0; i + 1 < sizeof name; ++i)
        whole[14 + i] = static_cast<std::uint8_t>(name[i]);
    bus.describe(3000, 0, 0x0A, whole);
    EXPECT_EQ(bus.name_of(3000), "Running hours");
    EXPECT_EQ(bus.value_in_unit(3000, 42), "42 h");
}

TEST(DescribedParametersTest, DamagedOrCutShortAnswersTeachNothing) {
    DescribingBus bus;
    bus.describe(100, 4, 0x0A, {28, 0xFF}, /*damage=*/true);
    EXPECT_EQ(bus.value_in_unit(100, 500), "none");
    bus.describe(100, 4, 0x0A, {28});  // one byte of two
    EXPECT_EQ(bus.value_in_unit(100, 500), "none");
    bus.describe(100, 0, 0x0A, ByteVector(20, 0));  // a whole description cut short
    EXPECT_EQ(bus.value_in_unit(100, 500), "none");
}

TEST(DescribedParametersTest, AClonedDecoderKeepsItsOwnDescriptions) {
    DescribingBus bus;
    std::unique_ptr<TelegramDecoder> before = bus.decoder().clone();
    bus.describe(100, 4, 0x0A, {28, 0xFF});
    std::unique_ptr<TelegramDecoder> after = bus.decoder().clone();
    const ParameterNaming* old_naming = before->decode({}, 0, 0).naming;
    const ParameterNaming* new_naming = after->decode({}, 0, 0).naming;
    ASSERT_NE(old_naming, nullptr);
    ASSERT_NE(new_naming, nullptr);
    EXPECT_NE(old_naming, new_naming);
    EXPECT_EQ(old_naming->parameter(kSlave, 100).family->id, "t");
    EXPECT_EQ(new_naming->parameter(kSlave, 100).family->id, "drive");
    EXPECT_EQ(new_naming->parameter(kSlave, 100).row->unit, "Hz");
}

TEST(DescribedParametersTest, UnitsOfTheVariableIndex) {
    EXPECT_EQ(described_unit(28, -1), "Hz");
    EXPECT_EQ(described_unit(4, 74), "h");
    EXPECT_EQ(described_unit(4, 70), "min");
    EXPECT_EQ(described_unit(4, 77), "d");
    EXPECT_EQ(described_unit(4, -2), "s");
    EXPECT_EQ(described_unit(11, 67), "RPM");
    EXPECT_EQ(described_unit(17, 100), "°C");
    EXPECT_EQ(described_unit(99, 0), "");
}

TEST(DescribedParametersTest, WhatIsKeptIsBounded) {
    DescribedParameters described;
    const std::uint8_t attribute[] = {28, 0xFF};
    ParameterRow listed;
    listed.name = "x";
    for (std::uint32_t i = 0; i < kMaxDescribedParameters + 10; ++i)
        described.learn(static_cast<std::uint8_t>(i >> 16), static_cast<std::uint16_t>(i), 4,
                        attribute, i, &listed);
    EXPECT_EQ(described.size(), kMaxDescribedParameters);
    EXPECT_NE(described.find(0, 0), nullptr);
    EXPECT_EQ(described.find(0, static_cast<std::uint16_t>(kMaxDescribedParameters + 5)), nullptr);
}

// ---- the family a slave's GSD file names (family_of_device) ------------------------------------

TEST(DeviceFamilyTest, VendorAndModelNameAFamily) {
    EXPECT_EQ(family_of_device("Danfoss", "VLT 5000"), "vlt5000");
    EXPECT_EQ(family_of_device("Danfoss A/S", "VLT5000 PROFIBUS"), "vlt5000");
    EXPECT_EQ(family_of_device("DANFOSS", "FC 302"), "fc");
    EXPECT_EQ(family_of_device("Danfoss", "VLT AutomationDrive FC-301"), "fc");
    EXPECT_EQ(family_of_device("Danfoss", "VLT HVAC Drive"), "fc");
    EXPECT_EQ(family_of_device("GE", "AF-600 FP"), "af600");
    EXPECT_EQ(family_of_device("GE Industrial Solutions", "AF-650 GP"), "af600");
    EXPECT_EQ(family_of_device("Danfoss", "MCD 500"), std::nullopt);
    EXPECT_EQ(family_of_device("dpscope", "PROFIdrive sample drive"), std::nullopt);
    EXPECT_EQ(family_of_device("Siemens", "FC 302"), std::nullopt);
    EXPECT_EQ(family_of_device("Geberit", "AF-600"), std::nullopt);  // "ge" only as a word
}

// A slave described by a GSD file of an FC series drive is named by the fc family from its
// Set_Prm on (the forced one from the start); --drive for the station wins.
TEST(DeviceFamilyTest, TheGsdNamesTheFamilyUnlessDriveDoes) {
    auto db = std::make_shared<ParameterDatabase>();
    for (const char* id : {"fc", "profidrive"}) {
        Result<ParameterFile> f = parse_parameter_database(
            std::string("@family ") + id + "\n@source D = d\n100 | P | - | - | uint16 | 1 | D\n",
            "x.params");
        ASSERT_TRUE(f) << f.error();
        db->add(std::move(f->family));
    }
    auto library = std::make_shared<GsdLibrary>();
    GsdDevice fc;
    fc.vendor = "Danfoss";
    fc.model = "FC 302";
    fc.ident_number = 0x0A3B;
    library->add(fc);
    const auto decoder_for = [&](const DriveHints& hints) {
        DecoderOptions options;
        options.station_dialect[kSlave] = Dialect::Profidrive;
        options.station_dialect[6] = Dialect::Profidrive;
        std::array<Dialect, kStationCount> dialects{};
        dialects[kSlave] = dialects[6] = Dialect::Profidrive;
        options.naming =
            std::make_shared<ParameterNaming>(db, Protocol::ProfibusDp, dialects, hints);
        options.gsd = library;
        return std::make_unique<BusDecoder>(options);
    };
    const auto set_prm = [](std::uint8_t slave) {
        const std::uint8_t prm[] = {0x88, 10, 10, 11, 0x0A, 0x3B, 0x00};
        return build_telegram({slave, kMaster, request_fc(FdlFunction::SrdHigh, false, true),
                               sap::kSetPrm, sap::kMaster, Bytes(prm)});
    };
    {
        std::unique_ptr<BusDecoder> decoder = decoder_for({});
        ASSERT_NE(decoder->naming(), nullptr);
        EXPECT_EQ(decoder->naming()->family(kSlave)->id, "profidrive");
        const std::vector<std::uint8_t> bytes = set_prm(kSlave);
        decoder->decode(Bytes(bytes), 0, 1);
        EXPECT_EQ(decoder->naming()->family(kSlave)->id, "fc");
        EXPECT_EQ(decoder->naming()->family(6)->id, "profidrive");  // another slave: no GSD seen
    }
    {
        DriveHints hints;
        hints.station[kSlave] = "profidrive";
        std::unique_ptr<BusDecoder> decoder = decoder_for(hints);
        const std::vector<std::uint8_t> bytes = set_prm(kSlave);
        decoder->decode(Bytes(bytes), 0, 1);
        EXPECT_EQ(decoder->naming()->family(kSlave)->id, "profidrive");
    }
}

}  // namespace
}  // namespace dpscope
