// The GSD library: matching a slave's telegrams to its GSD file (modules, user parameters,
// diagnosis texts), and reading GSD files from the command line's files and folders.
#include "protocols/profibus/gsd/gsd_library.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "capture/gsd_files.hpp"

namespace dpscope {
namespace {

// A modular device written for these tests: two modules of one identifier and one of two, two
// user parameters of the device and one of a module, two diagnosis bits and an area.
constexpr std::string_view kDevice = R"(#Profibus_DP
Vendor_Name = "Test vendor"
Model_Name = "Modular test device"
Ident_Number = 0x1234
Max_Module = 3
User_Prm_Data_Len = 2
PrmText = 1
Text(0) = "slow"
Text(1) = "fast"
EndPrmText
ExtUserPrmData = 1 "Speed"
Bit(0) 0 0-1
Prm_Text_Ref = 1
EndExtUserPrmData
ExtUserPrmData = 2 "Filter"
Unsigned8 3 1-10
EndExtUserPrmData
ExtUserPrmData = 3 "Gain"
Signed16 0 -100-100
EndExtUserPrmData
Ext_User_Prm_Data_Ref(0) = 1
Ext_User_Prm_Data_Ref(1) = 2
Unit_Diag_Bit(0) = "Power low"
Unit_Diag_Bit(9) = "Sensor open"
Unit_Diag_Area = 4-5
Value(2) = "Mode two"
Unit_Diag_Area_End
Module = "In 1 byte" 0x10
EndModule
Module = "Out 1 byte" 0x20
EndModule
Module = "Drive PPO 1" 0xF3,0xF1
Ext_User_Prm_Data_Ref(0) = 3
EndModule
)";

GsdDevice device() {
    Result<GsdDevice> d = parse_gsd(kDevice, "test.gsd");
    EXPECT_TRUE(d) << d.error();
    return d ? *d : GsdDevice{};
}

TEST(GsdLibraryTest, MatchesTheLongestModuleOnIdentifierBoundaries) {
    const GsdDevice d = device();
    const std::uint8_t config[] = {0xF3, 0xF1, 0x10, 0x30, 0x20};
    const std::uint16_t identifiers[] = {9, 10, 11, 12, 13};  // telegram offsets, from 9
    std::vector<GsdModuleMatch> matches;
    match_gsd_modules(d, Bytes(config), 9, identifiers, matches);
    ASSERT_EQ(matches.size(), 4u);
    EXPECT_EQ(matches[0].module->name, "Drive PPO 1");
    EXPECT_EQ(matches[0].identifiers, 2);
    EXPECT_EQ(matches[1].module->name, "In 1 byte");
    EXPECT_EQ(matches[1].first_identifier, 2);
    EXPECT_EQ(matches[2].module, nullptr);  // 0x30: no module has it
    EXPECT_EQ(matches[2].offset, 12);
    EXPECT_EQ(matches[3].module->name, "Out 1 byte");
}

TEST(GsdLibraryTest, ModuleMayNotEndInsideAnIdentifier) {
    const GsdDevice d = device();
    // One special identifier of two bytes F3 F1 would be the module's bytes, but it is one
    // identifier starting at 9 that runs to 11: no match ends on a boundary inside it.
    const std::uint8_t config[] = {0xF3, 0xF1, 0x10};
    const std::uint16_t identifiers[] = {9};
    std::vector<GsdModuleMatch> matches;
    match_gsd_modules(d, Bytes(config), 9, identifiers, matches);
    ASSERT_EQ(matches.size(), 1u);
    EXPECT_EQ(matches[0].module, nullptr);
    EXPECT_EQ(matches[0].length, 3);
}

TEST(GsdLibraryTest, ReadsUserParametersOfDeviceAndModules) {
    const GsdDevice d = device();
    const GsdModule* ppo = &d.modules[2];
    const std::uint8_t user[] = {0x01, 0x0B, 0xFF, 0x9C};  // fast, 11 (over 10), gain -100
    GsdPrmReading reading;
    const GsdModule* modules[] = {ppo};
    read_gsd_user_prm(d, modules, true, Bytes(user), 7, reading);
    ASSERT_EQ(reading.values.size(), 3u);
    EXPECT_EQ(reading.values[0].prm->name, "Speed");
    ASSERT_NE(reading.values[0].text, nullptr);
    EXPECT_EQ(reading.values[0].text->text, "fast");
    EXPECT_EQ(reading.values[0].offset, 7);
    EXPECT_EQ(reading.values[1].value, 11);
    EXPECT_FALSE(reading.values[1].in_range);
    EXPECT_EQ(reading.values[2].module, ppo);
    EXPECT_EQ(reading.values[2].value, -100);
    EXPECT_TRUE(reading.values[2].in_range);
    EXPECT_EQ(reading.described_length, 4u);
    // Cut short: the parameters whose bytes are missing are left out.
    read_gsd_user_prm(d, modules, true, Bytes(user).first(3), 7, reading);
    EXPECT_EQ(reading.values.size(), 2u);
    // Modules not known: only the device's block.
    read_gsd_user_prm(d, {}, false, Bytes(user), 7, reading);
    EXPECT_EQ(reading.values.size(), 2u);
    EXPECT_EQ(reading.described_length, 2u);
}

TEST(GsdLibraryTest, NamesDiagnosisBitsAndAreas) {
    const GsdDevice d = device();
    const std::uint8_t block[] = {0x21, 0x02};  // bit 0, bits 4-5 = 2, bit 9
    std::vector<GsdDiagText> texts;
    name_gsd_diag_bits(d, Bytes(block), 20, texts);
    ASSERT_EQ(texts.size(), 3u);
    EXPECT_EQ(texts[0].text, "Power low");
    EXPECT_EQ(texts[0].offset, 20);
    EXPECT_EQ(texts[1].text, "Sensor open");
    EXPECT_EQ(texts[1].offset, 21);
    EXPECT_EQ(texts[2].text, "Mode two");
    EXPECT_EQ(texts[2].value, 2);
    texts.clear();
    name_gsd_diag_bits(d, Bytes(block).first(0), 20, texts);  // no data: nothing named
    EXPECT_TRUE(texts.empty());
}

TEST(GsdLibraryTest, MatchesByIdentFirstFileWinsAndForcesPerAddress) {
    GsdLibrary library;
    GsdDevice a = device();
    GsdDevice b = device();
    b.file = "second.gsd";
    const GsdDevice* shadowed = nullptr;
    library.add(a, &shadowed);
    EXPECT_EQ(shadowed, nullptr);
    const std::size_t second = library.add(b, &shadowed);
    ASSERT_NE(shadowed, nullptr);
    EXPECT_EQ(shadowed->file, "test.gsd");
    EXPECT_EQ(library.by_ident(0x1234)->file, "test.gsd");
    EXPECT_EQ(library.by_ident(0x4321), nullptr);
    library.force(7, second);
    EXPECT_EQ(library.forced(7)->file, "second.gsd");
    EXPECT_EQ(library.forced(8), nullptr);
    EXPECT_EQ(gsd_device_title(*library.forced(7)), "Test vendor Modular test device");
}

TEST(GsdFilesTest, ParsesFileSpecs) {
    Result<GsdFileSpec> plain = parse_gsd_file_spec("a.gsd");
    ASSERT_TRUE(plain);
    EXPECT_FALSE(plain->station);
    Result<GsdFileSpec> forced = parse_gsd_file_spec("12=dir/a.gsd");
    ASSERT_TRUE(forced);
    EXPECT_EQ(*forced->station, 12);
    EXPECT_EQ(forced->path, "dir/a.gsd");
    EXPECT_EQ(parse_gsd_file_spec("127=a.gsd").error(),
              "--gsd 127=a.gsd: the address must be from 0 to 126");
    EXPECT_EQ(parse_gsd_file_spec("5=").error(), "--gsd 5=: no file named");
    EXPECT_TRUE(is_gsd_file_name("X.GSD"));
    EXPECT_TRUE(is_gsd_file_name("x.gse"));
    EXPECT_FALSE(is_gsd_file_name("x.gs1"));
    EXPECT_FALSE(is_gsd_file_name("x.gsdml"));
}

TEST(GsdFilesTest, ReadsAFolderWarnsOfBrokenFilesAndFailsOnMissingOnes) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("dpscope-gsd-test-" + std::to_string(getpid()));
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "good.gsd") << kDevice;
    std::ofstream(dir / "broken.gse") << "#Profibus_DP\nModule = \"x\" 0x10\n";  // no EndModule
    std::ofstream(dir / "notes.txt") << "not a GSD";
    Result<LoadedGsdFiles> loaded = load_gsd_files({}, std::vector<std::string>{dir.string()});
    ASSERT_TRUE(loaded) << loaded.error();
    ASSERT_NE(loaded->library, nullptr);
    EXPECT_EQ(loaded->library->size(), 1u);
    ASSERT_EQ(loaded->warnings.size(), 1u);
    EXPECT_NE(loaded->warnings[0].find("broken.gse:"), std::string::npos) << loaded->warnings[0];
    const GsdFileSpec missing{std::nullopt, (dir / "none.gsd").string()};
    Result<LoadedGsdFiles> failed = load_gsd_files(std::span(&missing, 1), {});
    ASSERT_FALSE(failed);
    EXPECT_NE(failed.error().find("none.gsd: cannot open"), std::string::npos) << failed.error();
    Result<LoadedGsdFiles> no_folder =
        load_gsd_files({}, std::vector<std::string>{(dir / "nope").string()});
    EXPECT_FALSE(no_folder);
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace dpscope
