// PPO types from configuration identifiers, from the Data_Exchange length and by number
// (docs/protocol/ppo.md, "Identifier bytes per PPO", "Inferring the PPO type").
#include "protocols/profibus/ppo.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::hex;

PpoLayout from_cfg(const std::string& identifiers, PpoSource source = PpoSource::ChkCfg) {
    auto bytes = hex(identifiers);
    std::vector<CfgModule> modules;
    ProblemList problems;
    EXPECT_TRUE(parse_cfg(ByteReader(Bytes(bytes.data(), bytes.size())), modules, problems));
    EXPECT_TRUE(problems.empty());
    return ppo_from_cfg(modules, source);
}

struct CfgCase {
    const char* identifiers;
    std::uint8_t type;
    bool has_pcv;
    std::uint16_t bytes;
};

// Every row of docs/protocol/ppo.md's identifier table (standard PPOs) and the other legal
// encodings listed there.
TEST(PpoTest, IdentifierTableRows) {
    const std::vector<CfgCase> cases = {
        // Module-consistent PCD (Danfoss GSD, ABB).
        {"F3 F1", 1, true, 12},
        {"F3 F5", 2, true, 20},
        {"F1", 3, false, 4},
        {"F5", 4, false, 12},
        {"F3 F9", 5, true, 28},
        // Word-consistent PCD.
        {"F3 71", 1, true, 12},
        {"F3 75", 2, true, 20},
        {"71", 3, false, 4},
        {"75", 4, false, 12},
        {"F3 79", 5, true, 28},
    };
    for (const CfgCase& c : cases) {
        SCOPED_TRACE(c.identifiers);
        PpoLayout layout = from_cfg(c.identifiers);
        EXPECT_EQ(layout.type, c.type);
        EXPECT_EQ(layout.has_pcv, c.has_pcv);
        EXPECT_EQ(layout.output_bytes, c.bytes);
        EXPECT_EQ(layout.input_bytes, c.bytes);
        EXPECT_EQ(layout.alternative, 0);
        EXPECT_EQ(layout.source, PpoSource::ChkCfg);
        EXPECT_TRUE(layout.known());
    }
}

TEST(PpoTest, OtherLegalEncodings) {
    const std::vector<CfgCase> cases = {
        // Separate output and input identifiers for the PKW, in either order.
        {"E3 D3 F1", 1, true, 12},
        {"D3 E3 F5", 2, true, 20},
        // Separate output and input identifiers for the PCD.
        {"E1 D1", 3, false, 4},
        {"F3 E1 D1", 1, true, 12},
        // Byte-unit PKW.
        {"B7 F1", 1, true, 12},
        {"B7 F9", 5, true, 28},
        // Free places as padding.
        {"00 F3 00 F1", 1, true, 12},
        {"00 F1", 3, false, 4},
        // PKW in special format.
        {"C0 C3 C3 F1", 1, true, 12},
        {"C0 C3 C3 F5", 2, true, 20},
        // PKW and PCD in special format.
        {"C0 C3 C3 C0 41 41", 1, true, 12},
        // Manufacturer bytes carry no I/O.
        {"03 AA BB CC F3 F1", 1, true, 12},
        {"F3 02 AA BB F1", 1, true, 12},
    };
    for (const CfgCase& c : cases) {
        SCOPED_TRACE(c.identifiers);
        PpoLayout layout = from_cfg(c.identifiers);
        EXPECT_EQ(layout.type, c.type);
        EXPECT_EQ(layout.has_pcv, c.has_pcv);
        EXPECT_EQ(layout.output_bytes, c.bytes);
        EXPECT_EQ(layout.input_bytes, c.bytes);
    }
}

TEST(PpoTest, SourceIsKept) {
    PpoLayout layout = from_cfg("F3 F1", PpoSource::GetCfg);
    EXPECT_EQ(layout.source, PpoSource::GetCfg);
    EXPECT_EQ(layout.type, 1);
}

TEST(PpoTest, NonStandardConfigurationsHaveNoType) {
    // One 8-byte module: Danfoss PPO 6 or a PKW-only module; not a PCV followed by PCD.
    PpoLayout pkw_only = from_cfg("F3");
    EXPECT_EQ(pkw_only.type, 0);
    EXPECT_FALSE(pkw_only.has_pcv);
    EXPECT_EQ(pkw_only.output_bytes, 8);
    EXPECT_EQ(pkw_only.input_bytes, 8);
    EXPECT_TRUE(pkw_only.known());

    // One module of 10 words (ABB PPO 6): 20 bytes without a PCV is not PPO 2.
    PpoLayout abb6 = from_cfg("F9");
    EXPECT_EQ(abb6.type, 0);
    EXPECT_FALSE(abb6.has_pcv);
    EXPECT_EQ(abb6.output_bytes, 20);

    // One module of 28 bytes: not a PPO (docs/protocol/ppo.md).
    PpoLayout one28 = from_cfg("C0 4D 4D");
    EXPECT_EQ(one28.type, 0);
    EXPECT_FALSE(one28.has_pcv);
    EXPECT_EQ(one28.output_bytes, 28);

    // ABB PPO 7: PKW + 12 words = 32 bytes.
    PpoLayout abb7 = from_cfg("F3 FB");
    EXPECT_EQ(abb7.type, 0);
    EXPECT_TRUE(abb7.has_pcv);
    EXPECT_EQ(abb7.output_bytes, 32);
}

TEST(PpoTest, DifferentInputAndOutputLengthsHaveNoType) {
    PpoLayout layout = from_cfg("F3 E1");  // PKW + 2 output words only
    EXPECT_EQ(layout.type, 0);
    EXPECT_TRUE(layout.has_pcv);
    EXPECT_EQ(layout.output_bytes, 12);
    EXPECT_EQ(layout.input_bytes, 8);
}

TEST(PpoTest, EmptyOrFreePlaceOnlyConfigurationHasNoIo) {
    for (const char* identifiers : {"", "00 00"}) {
        SCOPED_TRACE(identifiers);
        PpoLayout layout = from_cfg(identifiers);
        EXPECT_EQ(layout.type, 0);
        EXPECT_FALSE(layout.has_pcv);
        EXPECT_EQ(layout.output_bytes, 0);
        EXPECT_EQ(layout.input_bytes, 0);
    }
}

TEST(PpoTest, TruncatedConfigurationUsesTheModulesRead) {
    // The special-format PCD identifier is cut off: only the PKW module survives.
    auto bytes = hex("F3 C0 41");
    std::vector<CfgModule> modules;
    ProblemList problems;
    EXPECT_FALSE(parse_cfg(ByteReader(Bytes(bytes.data(), bytes.size())), modules, problems));
    PpoLayout layout = ppo_from_cfg(modules, PpoSource::ChkCfg);
    EXPECT_EQ(layout.type, 0);
    EXPECT_FALSE(layout.has_pcv);
    EXPECT_EQ(layout.output_bytes, 8);
}

TEST(PpoTest, CorruptedConfigurationIsNotAStandardPpo) {
    PpoLayout layout = from_cfg("F3 F1 F1");  // PKW + 4 words: 16 bytes
    EXPECT_EQ(layout.type, 0);
    EXPECT_TRUE(layout.has_pcv);
    EXPECT_EQ(layout.output_bytes, 16);
}

TEST(PpoTest, LengthTable) {
    struct LengthCase {
        std::size_t length;
        std::uint8_t type;
        std::uint8_t alternative;
        bool has_pcv;
    };
    const std::vector<LengthCase> cases = {
        {4, 3, 0, false}, {12, 1, 4, true},  {20, 2, 0, true},  {28, 5, 0, true},
        {8, 0, 0, false}, {16, 0, 0, false}, {24, 0, 0, false}, {32, 0, 0, false},
        {0, 0, 0, false}, {2, 0, 0, false},  {13, 0, 0, false},
    };
    for (const LengthCase& c : cases) {
        SCOPED_TRACE("length " + std::to_string(c.length));
        PpoLayout layout = ppo_from_length(c.length);
        EXPECT_EQ(layout.type, c.type);
        EXPECT_EQ(layout.alternative, c.alternative);
        EXPECT_EQ(layout.has_pcv, c.has_pcv);
        EXPECT_EQ(layout.output_bytes, c.length);
        EXPECT_EQ(layout.input_bytes, c.length);
        EXPECT_EQ(layout.source, PpoSource::Length);
        EXPECT_TRUE(layout.known());
    }
}

TEST(PpoTest, TwelveBytesAreAmbiguousBetweenPpo1AndPpo4) {
    PpoLayout layout = ppo_from_length(12);
    EXPECT_EQ(layout.type, 1);
    EXPECT_EQ(layout.alternative, 4);
    EXPECT_TRUE(layout.has_pcv);
}

TEST(PpoTest, LayoutOfEveryStandardType) {
    struct TypeCase {
        std::uint8_t type;
        bool has_pcv;
        std::uint16_t bytes;
    };
    for (const TypeCase& c : std::vector<TypeCase>{
             {1, true, 12}, {2, true, 20}, {3, false, 4}, {4, false, 12}, {5, true, 28}}) {
        SCOPED_TRACE("PPO " + std::to_string(c.type));
        PpoLayout layout = ppo_layout_of_type(c.type, PpoSource::Option);
        EXPECT_EQ(layout.type, c.type);
        EXPECT_EQ(layout.has_pcv, c.has_pcv);
        EXPECT_EQ(layout.output_bytes, c.bytes);
        EXPECT_EQ(layout.input_bytes, c.bytes);
        EXPECT_EQ(layout.alternative, 0);
        EXPECT_EQ(layout.source, PpoSource::Option);
    }
}

TEST(PpoTest, LayoutOfUnknownTypeIsEmpty) {
    for (int type : {0, 6, 7, 8, 255}) {
        SCOPED_TRACE(std::to_string(type));
        PpoLayout layout = ppo_layout_of_type(static_cast<std::uint8_t>(type), PpoSource::Option);
        EXPECT_EQ(layout.type, 0);
        EXPECT_FALSE(layout.has_pcv);
        EXPECT_EQ(layout.output_bytes, 0);
        EXPECT_EQ(layout.input_bytes, 0);
    }
    EXPECT_FALSE(ppo_layout_of_type(1, PpoSource::None).known());
}

TEST(PpoTest, SourceNamesAndConstants) {
    EXPECT_EQ(ppo_source_name(PpoSource::None), "none");
    EXPECT_EQ(ppo_source_name(PpoSource::ChkCfg), "chk_cfg");
    EXPECT_EQ(ppo_source_name(PpoSource::GetCfg), "get_cfg");
    EXPECT_EQ(ppo_source_name(PpoSource::Length), "length");
    EXPECT_EQ(ppo_source_name(PpoSource::Option), "option");
    EXPECT_EQ(kPcvBytes, 8u);
    EXPECT_FALSE(PpoLayout{}.known());
}

}  // namespace
}  // namespace dpscope
