// Drive parameter databases (drives/parameter_database.hpp): the file format, its errors, the
// lookups by number and name, PNUs written as groups, and the scaling by conversion index; the
// family rule (drives/drive_family.hpp).
#include "drives/parameter_database.hpp"

#include <dirent.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "capture/telegram_source.hpp"
#include "core/protocol_descriptor.hpp"
#include "drives/drive_family.hpp"
#include "drives/shipped_databases.hpp"
#include "filter/display_filter.hpp"
#include "protocols/lane_options.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

const std::string kHeader =
    "@family demo\n"
    "@title Demo drive\n"
    "@numbering group\n"
    "@source D = demo sheet\n";

// The test database (tests/params/testdrive.params), parsed.
ParameterFile test_drive() {
    const std::string path = test::source_dir() + "/tests/params/testdrive.params";
    Result<ParameterFile> parsed = parse_parameter_database(test::slurp(path), "testdrive.params");
    EXPECT_TRUE(parsed) << parsed.error();
    return parsed ? *parsed : ParameterFile{};
}

// The error of a text that must not parse (file name "t.params").
std::string error_of(const std::string& text) {
    Result<ParameterFile> parsed = parse_parameter_database(text, "t.params");
    EXPECT_FALSE(parsed) << text;
    return parsed ? std::string() : parsed.error();
}

ParameterRow row_of(ParameterType type, std::optional<std::int16_t> conversion) {
    ParameterRow row;
    row.type = type;
    row.conversion = conversion;
    if (conversion) row.scaling = conversion_of_index(*conversion);
    return row;
}

std::string scaled(const ParameterRow& row, std::int64_t raw) {
    std::optional<ScaledValue> value = scale_value(row, raw);
    return value ? format_scaled(*value) : "none";
}

TEST(ParameterDatabaseTest, ReadsTheTestDatabase) {
    ParameterFile file = test_drive();
    const ParameterFamily& family = file.family;
    EXPECT_TRUE(file.warnings.empty());
    EXPECT_EQ(family.id, "testdrive");
    EXPECT_EQ(family.title, "Test drive (made up for the tests)");
    EXPECT_EQ(family.numbering, PnuNumbering::Group);
    ASSERT_EQ(family.sources.size(), 2u);
    EXPECT_EQ(family.sources[1].key, "TDX");
    EXPECT_EQ(family.sources[1].text, "dpscope test drive, second sheet");
    ASSERT_EQ(family.rows.size(), 28u);
    // Sorted by PNU whatever the order of the file.
    for (std::size_t i = 1; i < family.rows.size(); ++i)
        EXPECT_LT(family.rows[i - 1].pnu, family.rows[i].pnu);
    const ParameterRow* frequency = family.find(1613);
    ASSERT_NE(frequency, nullptr);
    EXPECT_EQ(frequency->name, "Frequency");
    EXPECT_EQ(frequency->unit, "Hz");
    EXPECT_EQ(frequency->conversion, -1);
    EXPECT_EQ(frequency->type, ParameterType::Uint16);
    EXPECT_EQ(frequency->elements, 1u);
    EXPECT_EQ(frequency->source, "TD p. 5");
    EXPECT_EQ(family.sources[frequency->source_index].key, "TD");
    const ParameterRow* log = family.find(1530);
    ASSERT_NE(log, nullptr);
    EXPECT_EQ(log->elements, 10u);
    EXPECT_EQ(log->unit, "");  // '-'
    EXPECT_EQ(family.sources[log->source_index].key, "TDX");
    const ParameterRow* type = family.find(1540);
    ASSERT_NE(type, nullptr);
    EXPECT_EQ(type->conversion, std::nullopt);
    EXPECT_EQ(type->type, ParameterType::String);
    EXPECT_EQ(family.find(1612), nullptr);
    EXPECT_EQ(family.find(65535), nullptr);
    EXPECT_EQ(family.find(0), nullptr);
}

TEST(ParameterDatabaseTest, AcceptsPlainNumbersCommentsBlankLinesCrLfAndABom) {
    Result<ParameterFile> parsed = parse_parameter_database(
        "\xEF\xBB\xBF# a comment\r\n\r\n@family vlt-old_2\r\n@source S = sheet\r\n"
        "   # indented comment\r\n 518 |  Frequency  | Hz | -1 | int16 | 1 | S p. 9 \r\n"
        "65535 | Last | - | - | uint32 | 65535 | S\r\n0 | Zero | - | 0 | uint8 | 1 | S",
        "p.params");
    ASSERT_TRUE(parsed) << parsed.error();
    const ParameterFamily& family = parsed->family;
    EXPECT_EQ(family.id, "vlt-old_2");
    EXPECT_EQ(family.title, "vlt-old_2");  // no @title: the id
    EXPECT_EQ(family.numbering, PnuNumbering::Plain);
    ASSERT_EQ(family.rows.size(), 3u);
    EXPECT_EQ(family.find(518)->name, "Frequency");
    EXPECT_EQ(family.find(518)->source, "S p. 9");
    EXPECT_EQ(family.find(518)->line, 6u);
    EXPECT_EQ(family.find(65535)->elements, 65535u);
    EXPECT_EQ(family.find(0)->name, "Zero");
    EXPECT_EQ(family.format_pnu(518), "518");
}

TEST(ParameterDatabaseTest, EveryTypeIsReadByItsName) {
    for (const char* name : {"int8", "int16", "int32", "uint8", "uint16", "uint32", "n2", "v2",
                             "string", "time", "date"}) {
        std::optional<ParameterType> type = parameter_type_from_name(name);
        ASSERT_TRUE(type) << name;
        EXPECT_EQ(parameter_type_name(*type), name);
        Result<ParameterFile> parsed = parse_parameter_database(
            kHeader + "1-00 | P | - | - | " + name + " | 1 | D", "t.params");
        ASSERT_TRUE(parsed) << parsed.error();
        EXPECT_EQ(parsed->family.rows.front().type, *type);
    }
    EXPECT_FALSE(parameter_type_from_name("INT8"));
    EXPECT_FALSE(parameter_type_from_name("float"));
}

TEST(ParameterDatabaseTest, BrokenFilesNameTheFileAndLine) {
    // A row cut short, and one with a cell too many.
    EXPECT_EQ(error_of(kHeader + "1-00 | Name | Hz | -1 | int16"),
              "t.params:5: a row of 5 cells: a row has 7 (pnu | name | unit | conversion | type | "
              "elements | source); is the line cut short?");
    EXPECT_EQ(error_of(kHeader + "1-00"),
              "t.params:5: a row of 1 cell: a row has 7 (pnu | name | unit | conversion | type | "
              "elements | source); is the line cut short?");
    EXPECT_EQ(error_of(kHeader + "1-00 | A | B | - | 0 | int16 | 1 | D"),
              "t.params:5: a row of 8 cells: a row has 7 (pnu | name | unit | conversion | type | "
              "elements | source); a name holds no '|'");
    // Numbers that are none or out of their range.
    EXPECT_EQ(error_of(kHeader + "x | N | - | 0 | int16 | 1 | D"),
              "t.params:5: PNU 'x': a whole number from 0 to 65535 or GROUP-NN (16-13)");
    EXPECT_EQ(error_of(kHeader + "65536 | N | - | 0 | int16 | 1 | D"),
              "t.params:5: PNU '65536': a whole number from 0 to 65535 or GROUP-NN (16-13)");
    EXPECT_EQ(error_of(kHeader + "16-130 | N | - | 0 | int16 | 1 | D"),
              "t.params:5: PNU '16-130': a whole number from 0 to 65535 or GROUP-NN (16-13)");
    EXPECT_EQ(error_of(kHeader + "-5 | N | - | 0 | int16 | 1 | D"),
              "t.params:5: PNU '-5': a whole number from 0 to 65535 or GROUP-NN (16-13)");
    EXPECT_EQ(error_of(kHeader + "1-00 | N | - | 1.5 | int16 | 1 | D"),
              "t.params:5: conversion '1.5': a conversion index is a whole number from -128 to "
              "127, or '-' for none");
    EXPECT_EQ(error_of(kHeader + "1-00 | N | - | 128 | int16 | 1 | D"),
              "t.params:5: conversion '128': a conversion index is a whole number from -128 to "
              "127, or '-' for none");
    EXPECT_EQ(error_of(kHeader + "1-00 | N | - | +1 | int16 | 1 | D"),
              "t.params:5: conversion '+1': a conversion index is a whole number from -128 to "
              "127, or '-' for none");
    EXPECT_EQ(error_of(kHeader + "1-00 | N | - | 0 | int16 | 0 | D"),
              "t.params:5: elements '0': a whole number from 1 to 65535");
    EXPECT_EQ(error_of(kHeader + "1-00 | N | - | 0 | int16 | two | D"),
              "t.params:5: elements 'two': a whole number from 1 to 65535");
    // An unknown type; an unknown source key; no name; no source.
    EXPECT_EQ(error_of(kHeader + "1-00 | N | - | 0 | float | 1 | D"),
              "t.params:5: type 'float' is none of int8, int16, int32, uint8, uint16, uint32, n2, "
              "v2, string, time, date");
    EXPECT_EQ(error_of(kHeader + "1-00 | N | - | 0 | int16 | 1 | PG99 p. 3"),
              "t.params:5: source 'PG99' is no @source key defined above the row");
    EXPECT_EQ(error_of(kHeader + "1-00 |  | - | 0 | int16 | 1 | D"),
              "t.params:5: a row without a name");
    EXPECT_EQ(error_of(kHeader + "1-00 | N | - | 0 | int16 | 1 | "),
              "t.params:5: a row without a source: cite a @source key");
    EXPECT_EQ(error_of(kHeader + "1-00 | N |  | 0 | int16 | 1 | D"),
              "t.params:5: an empty unit; write '-' for none");
    // The same PNU twice: both lines are named.
    EXPECT_EQ(error_of(kHeader + "16-13 | A | - | 0 | int16 | 1 | D\n# between\n"
                                 "1613 | B | - | 0 | int16 | 1 | D"),
              "t.params:7: PNU 16-13 is given twice, on line 5 and on line 7");
    // No @family: an empty file, a file of comments, a row or directive before it.
    EXPECT_EQ(error_of(""), "t.params:1: no @family line: a database begins with '@family ID'");
    EXPECT_EQ(error_of("# only a comment\n"),
              "t.params:1: no @family line: a database begins with '@family ID'");
    EXPECT_EQ(error_of("@source D = x\n@family f\n"),
              "t.params:1: @source before '@family ID': a database begins with its @family line");
    EXPECT_EQ(error_of("1 | N | - | 0 | int16 | 1 | D\n"),
              "t.params:1: a row before '@family ID': a database begins with its @family line");
    // The directives' own errors.
    EXPECT_EQ(error_of("@family FC\n"),
              "t.params:1: @family 'FC': an id is 1 to 32 lower-case letters, digits, '-' or '_'");
    EXPECT_EQ(error_of("@family fc\n@family vlt\n"),
              "t.params:2: a second @family ('vlt'); a file holds one family, 'fc'");
    EXPECT_EQ(error_of("@family fc\n@numbering decimal\n"),
              "t.params:2: @numbering 'decimal': group (PNU 1613 written 16-13) or plain");
    EXPECT_EQ(error_of("@family fc\n@source D\n"),
              "t.params:2: @source without '=': write '@source KEY = document'");
    EXPECT_EQ(error_of("@family fc\n@source D = a\n@source D = b\n"),
              "t.params:3: @source D is defined twice");
    EXPECT_EQ(error_of("@family fc\n@source D =\n"), "t.params:2: @source D names no document");
    EXPECT_EQ(error_of("@family fc\n@units x\n"),
              "t.params:2: unknown directive @units (@family, @title, @numbering, @source)");
    EXPECT_EQ(error_of("@family fc\n@title\n"), "t.params:2: @title without a title");
    EXPECT_EQ(error_of(kHeader + "1-00 | N | - | 0 | int16 | 1 | D\n@numbering plain\n"),
              "t.params:6: @numbering after the first row: it says how the rows write their PNUs");
    // A group-written PNU in a plain file.
    EXPECT_EQ(error_of("@family f\n@source D = d\n16-13 | N | - | 0 | int16 | 1 | D\n"),
              "t.params:3: PNU '16-13' is written as a group; this file's @numbering is plain "
              "(write the number, or '@numbering group' above the rows)");
    // Text that is no UTF-8, or holds a control character.
    EXPECT_EQ(error_of(kHeader + "1-00 | N\xE9 | - | 0 | int16 | 1 | D"),
              "t.params:5: the line is no valid UTF-8 text");
    EXPECT_EQ(error_of(kHeader + "1-00 | N\x01 | - | 0 | int16 | 1 | D"),
              "t.params:5: a control character in the row");
}

TEST(ParameterDatabaseTest, AnUnknownConversionIndexIsAWarningAndScalesNothing) {
    Result<ParameterFile> parsed = parse_parameter_database(
        kHeader + "1-00 | Odd | - | 99 | uint16 | 1 | D\n1-01 | Tiny | - | -8 | uint32 | 1 | D",
        "t.params");
    ASSERT_TRUE(parsed) << parsed.error();
    ASSERT_EQ(parsed->warnings.size(), 2u);
    EXPECT_EQ(parsed->warnings[0],
              "t.params:5: conversion index 99 has no meaning dpscope knows: the values of PNU "
              "1-00 are not scaled");
    EXPECT_EQ(parsed->warnings[1].rfind("t.params:6: conversion index -8", 0), 0u);
    EXPECT_EQ(scaled(parsed->family.rows[0], 1500), "none");
    EXPECT_EQ(scaled(parsed->family.rows[1], 12), "none");
}

// The indices that name a unit which is no power of ten of its base unit (67 RPM, 70 minutes,
// 74 hours, 75, 77 days): the raw number counts that unit, so it is shown as it is; no warning.
TEST(ParameterDatabaseTest, TheIndicesThatNameTheirUnitShowTheNumberInIt) {
    Result<ParameterFile> parsed = parse_parameter_database(
        kHeader +
            "1-00 | Speed | RPM | 67 | uint16 | 1 | D\n1-01 | Hours | h | 74 | uint32 | 1 | D\n"
            "1-02 | Minutes | min | 70 | uint32 | 1 | D\n1-03 | Days | d | 77 | uint32 | 1 | D\n"
            "1-04 | Odd | - | 75 | uint32 | 1 | D",
        "t.params");
    ASSERT_TRUE(parsed) << parsed.error();
    EXPECT_TRUE(parsed->warnings.empty());
    EXPECT_EQ(scaled(parsed->family.rows[0], 1500), "1500");
    EXPECT_EQ(scaled(parsed->family.rows[1], 12), "12");
    EXPECT_EQ(scaled(parsed->family.rows[2], 90), "90");
    EXPECT_EQ(scaled(parsed->family.rows[3], 3), "3");
    EXPECT_EQ(scaled(parsed->family.rows[4], 7), "7");
}

// --conversion-index INDEX=FACTOR: the contested meaning of an index, as the user's manual gives
// it, for the rows held and those added later; the decimals shown are the factor's.
TEST(ParameterDatabaseTest, AConversionOverrideGivesAnIndexItsFactor) {
    Result<ConversionOverride> tenth = parse_conversion_override("74=0.1");
    ASSERT_TRUE(tenth) << tenth.error();
    EXPECT_EQ(tenth->index, 74);
    EXPECT_EQ(tenth->conversion.decimals, 1);
    ParameterDatabase db;
    Result<ParameterFile> first =
        parse_parameter_database(kHeader + "1-01 | Hours | h | 74 | uint32 | 1 | D", "a.params");
    ASSERT_TRUE(first) << first.error();
    db.add(std::move(first->family));
    db.override_conversion(*tenth);
    const ParameterRow* hours = db.lookup("demo", 101);
    ASSERT_NE(hours, nullptr);
    EXPECT_EQ(scaled(*hours, 123), "12.3");
    Result<ConversionOverride> three = parse_conversion_override("74=3.6");
    ASSERT_TRUE(three);
    db.override_conversion(*three);  // the later one wins
    EXPECT_EQ(scaled(*db.lookup("demo", 101), 10), "36.0");
    Result<ParameterFile> second =
        parse_parameter_database(kHeader + "1-02 | More | h | 74 | uint32 | 1 | D", "b.params");
    ASSERT_TRUE(second);
    db.add(std::move(second->family));
    const ParameterRow* more = db.lookup("demo", 102);
    ASSERT_NE(more, nullptr);
    EXPECT_EQ(scaled(*more, 10), "36.0");
    Result<ConversionOverride> whole = parse_conversion_override("-1=3600");
    ASSERT_TRUE(whole);
    EXPECT_EQ(whole->index, -1);
    EXPECT_EQ(whole->conversion.decimals, 0);
    for (const char* bad : {"74", "74=", "=0.1", "128=1", "-129=1", "74=0", "74=-1", "74=1e3",
                            "74=0.0000000001", "74=2000000000", "74=1/60", "x=1", "74=.", "74=1."})
        EXPECT_FALSE(parse_conversion_override(bad)) << bad;
}

TEST(ParameterDatabaseTest, ScalesByEveryConversionIndex) {
    // Powers of ten from -7 to 7, 100 and the unit-naming indices (factor 1); others have none.
    EXPECT_EQ(scaled(row_of(ParameterType::Int32, 0), 500), "500");
    EXPECT_EQ(scaled(row_of(ParameterType::Int32, -1), 500), "50.0");
    EXPECT_EQ(scaled(row_of(ParameterType::Int32, -2), 1234), "12.34");
    EXPECT_EQ(scaled(row_of(ParameterType::Int32, -3), 1), "0.001");
    EXPECT_EQ(scaled(row_of(ParameterType::Int32, -4), 123456), "12.3456");
    EXPECT_EQ(scaled(row_of(ParameterType::Int32, -5), 100000), "1.00000");
    EXPECT_EQ(scaled(row_of(ParameterType::Int32, -6), 3), "0.000003");
    EXPECT_EQ(scaled(row_of(ParameterType::Int32, -7), 2147483647), "214.7483647");
    EXPECT_EQ(scaled(row_of(ParameterType::Int32, 1), 75), "750");
    EXPECT_EQ(scaled(row_of(ParameterType::Int32, 2), 23), "2300");
    EXPECT_EQ(scaled(row_of(ParameterType::Int32, 3), 7), "7000");
    EXPECT_EQ(scaled(row_of(ParameterType::Uint32, 7), 4294967295), "42949672950000000");
    EXPECT_EQ(scaled(row_of(ParameterType::Uint8, 100), 45), "45");
    for (int index : {-8, 8, 66, 68, 71, 76, 78, 99, 101, -128, 127})
        EXPECT_FALSE(conversion_of_index(index)) << index;
    // Negative values, sign-extended by the type.
    EXPECT_EQ(scaled(row_of(ParameterType::Int32, -1), -500), "-50.0");
    EXPECT_EQ(
        scaled(row_of(ParameterType::Int16, -2), raw_value_of_type(ParameterType::Int16, 0xFFFF)),
        "-0.01");
    EXPECT_EQ(scaled(row_of(ParameterType::Int8, 0), raw_value_of_type(ParameterType::Int8, 0x80)),
              "-128");
    EXPECT_EQ(scaled(row_of(ParameterType::Int32, -1),
                     raw_value_of_type(ParameterType::Int32, 0xFFFFFE0C)),
              "-50.0");
    EXPECT_EQ(scaled(row_of(ParameterType::Uint16, -1),
                     raw_value_of_type(ParameterType::Uint16, 0xFFFFFE0C)),
              "6503.6");  // 0xFE0C
    EXPECT_EQ(raw_value_of_type(ParameterType::Uint32, 0xFFFFFFFF), 4294967295);
    EXPECT_EQ(raw_value_of_type(ParameterType::Uint8, 0x1FF), 255);
    EXPECT_EQ(raw_value_of_type(ParameterType::N2, 0xC000), -16384);
    // Exact decimals: 3 * 10^-1 is 0.3, not 0.30000000000000004.
    std::optional<ScaledValue> three = scale_value(row_of(ParameterType::Int32, -1), 3);
    ASSERT_TRUE(three);
    EXPECT_EQ(three->value, 0.3);
    EXPECT_EQ(three->decimals, 1);
    // No conversion, or a type that is no number: not scaled.
    EXPECT_EQ(scaled(row_of(ParameterType::Int32, std::nullopt), 5), "none");
    for (ParameterType type :
         {ParameterType::V2, ParameterType::String, ParameterType::Time, ParameterType::Date})
        EXPECT_EQ(scaled(row_of(type, 0), 5), "none") << parameter_type_name(type);
    EXPECT_EQ(scaled(row_of(ParameterType::N2, -2), 1234), "12.34");
}

TEST(ParameterDatabaseTest, PnusAreWrittenAndReadAsGroups) {
    ParameterFamily group;
    group.numbering = PnuNumbering::Group;
    EXPECT_EQ(group.format_pnu(1613), "16-13");
    EXPECT_EQ(group.format_pnu(1), "0-01");
    EXPECT_EQ(group.format_pnu(100), "1-00");
    EXPECT_EQ(group.format_pnu(65535), "655-35");
    ParameterFamily plain;
    EXPECT_EQ(plain.format_pnu(518), "518");
    EXPECT_EQ(parse_pnu_text("16-13"), 1613);
    EXPECT_EQ(parse_pnu_text("0-01"), 1);
    EXPECT_EQ(parse_pnu_text("1613"), 1613);
    EXPECT_EQ(parse_pnu_text("655-35"), 65535);
    EXPECT_EQ(parse_pnu_text("65535"), 65535);
    EXPECT_EQ(parse_pnu_text("0"), 0);
    for (const char* bad : {"655-36", "65536", "16-1", "16-134", "-13", "16-", "1a", "16-1x", "",
                            "+5", "1-2-3", "1000-00", " 16"})
        EXPECT_FALSE(parse_pnu_text(bad)) << bad;
}

TEST(ParameterDatabaseTest, FindsParametersByName) {
    ParameterDatabase db;
    db.add(test_drive().family);
    Result<ParameterFile> other = parse_parameter_database(
        "@family other\n@source O = o\n"
        "1613 | Frequency | Hz | -1 | int16 | 1 | O\n"
        "1614 | Frequency [%] | % | -2 | int16 | 1 | O\n",
        "o.params");
    ASSERT_TRUE(other) << other.error();
    db.add(other->family);
    // The exact name first, whatever its case; here in two families, with one PNU.
    Result<std::vector<NamedParameter>> frequency = db.find_by_name("FREQUENCY");
    ASSERT_TRUE(frequency) << frequency.error();
    ASSERT_EQ(frequency->size(), 2u);
    EXPECT_EQ((*frequency)[0].family->id, "testdrive");
    EXPECT_EQ((*frequency)[0].row->pnu, 1613);
    EXPECT_EQ((*frequency)[1].family->id, "other");
    // A unique part of a name.
    Result<std::vector<NamedParameter>> heatsink = db.find_by_name("heatsink");
    ASSERT_TRUE(heatsink) << heatsink.error();
    ASSERT_EQ(heatsink->size(), 1u);
    EXPECT_EQ(heatsink->front().row->pnu, 1634);
    // A part of several names: an error naming the candidates.
    Result<std::vector<NamedParameter>> ramp = db.find_by_name("ramp 1");
    ASSERT_FALSE(ramp);
    EXPECT_EQ(ramp.error(),
              "'ramp 1' is in the names of several parameters of any drive family (testdrive "
              "3-41 Ramp 1 Ramp Up Time; testdrive 3-42 Ramp 1 Ramp Down Time); give its number "
              "or more of its name");
    // Only the families asked: "Frequency [%]" is in `other` alone.
    const std::vector<std::string> only_test = {"testdrive"};
    EXPECT_FALSE(db.find_by_name("Frequency [%]", only_test));
    Result<std::vector<NamedParameter>> percent = db.find_by_name("frequency [%]");
    ASSERT_TRUE(percent) << percent.error();
    EXPECT_EQ(percent->front().row->pnu, 1614);
    // "Frequency [%]" holds "Frequency", which is exact: the exact name wins over parts.
    Result<std::vector<NamedParameter>> exact = db.find_by_name("Frequency", only_test);
    ASSERT_TRUE(exact) << exact.error();
    EXPECT_EQ(exact->front().row->pnu, 1613);
    // Two exact names, two PNUs: ambiguous too.
    Result<std::vector<NamedParameter>> motor_current = db.find_by_name("motor current");
    ASSERT_FALSE(motor_current);
    EXPECT_EQ(motor_current.error(),
              "'motor current' names several parameters of any drive family (testdrive 1-24 "
              "Motor Current; testdrive 16-14 Motor current); give its number or more of its "
              "name");
    Result<std::vector<NamedParameter>> none = db.find_by_name("torque", only_test);
    ASSERT_FALSE(none);
    EXPECT_EQ(none.error(), "no parameter of the drive family testdrive is named 'torque'");
    EXPECT_FALSE(db.find_by_name("  "));
}

TEST(ParameterDatabaseTest, APatternMatchesANumberAsWrittenOrPlainOrAPartOfAName) {
    const ParameterFamily family = test_drive().family;
    const ParameterRow& frequency = *family.find(1613);
    for (const char* pattern : {"", "16-13", "16-1", "1613", "161", "FREQ", "quen", "3"})
        EXPECT_TRUE(matches_pattern(family, frequency, pattern)) << pattern;
    for (const char* pattern : {"16-14", "1614", "frequency [", "16 13", "-130"})
        EXPECT_FALSE(matches_pattern(family, frequency, pattern)) << pattern;
}

TEST(ParameterDatabaseTest, ManyCandidatesAreListedUpToEight) {
    ParameterDatabase db;
    db.add(test_drive().family);
    Result<std::vector<NamedParameter>> motor = db.find_by_name("o");
    ASSERT_FALSE(motor);
    EXPECT_NE(motor.error().find("; and "), std::string::npos) << motor.error();
    EXPECT_NE(motor.error().find(" more); give its number"), std::string::npos) << motor.error();
}

TEST(ParameterDatabaseTest, AUserFileAddsAndOverridesRowsOfAFamily) {
    ParameterDatabase db;
    db.add(test_drive().family);
    Result<ParameterFile> user = parse_parameter_database(
        "@family testdrive\n@title Ignored title\n@numbering plain\n@source U = my notes\n"
        "1613 | Output Frequency | Hz | -2 | int32 | 1 | U\n"
        "9999 | Custom | - | 0 | uint16 | 1 | U p. 2\n",
        "user.params");
    ASSERT_TRUE(user) << user.error();
    db.add(user->family);
    ASSERT_EQ(db.families().size(), 1u);
    const ParameterFamily* family = db.family("testdrive");
    ASSERT_NE(family, nullptr);
    EXPECT_EQ(family->title, "Test drive (made up for the tests)");  // the first file's
    EXPECT_EQ(family->numbering, PnuNumbering::Group);
    EXPECT_EQ(family->rows.size(), 29u);
    const ParameterRow* replaced = db.lookup("testdrive", 1613);
    ASSERT_NE(replaced, nullptr);
    EXPECT_EQ(replaced->name, "Output Frequency");
    EXPECT_EQ(replaced->conversion, -2);
    EXPECT_EQ(family->sources[replaced->source_index].text, "my notes");
    EXPECT_EQ(family->sources[replaced->source_index].file, "user.params");
    const ParameterRow* added = db.lookup("testdrive", 9999);
    ASSERT_NE(added, nullptr);
    EXPECT_EQ(added->name, "Custom");
    // The rows it did not name are kept, with their own sources.
    const ParameterRow* kept = db.lookup("testdrive", 1530);
    ASSERT_NE(kept, nullptr);
    EXPECT_EQ(family->sources[kept->source_index].key, "TDX");
    for (std::size_t i = 1; i < family->rows.size(); ++i)
        EXPECT_LT(family->rows[i - 1].pnu, family->rows[i].pnu);
    EXPECT_EQ(db.lookup("nothing", 1613), nullptr);
    EXPECT_EQ(db.family("nothing"), nullptr);
}

TEST(ParameterDatabaseTest, TheFamilyComesFromTheHintTheBusOrTheDialect) {
    EXPECT_EQ(drive_family(Protocol::Fc, Dialect::Vlt), "fc");
    EXPECT_EQ(drive_family(Protocol::Vlt2000, Dialect::Ge), "vlt2000");
    EXPECT_EQ(drive_family(Protocol::ProfibusDp, Dialect::Vlt), "vlt5000");
    EXPECT_EQ(drive_family(Protocol::ProfibusDp, Dialect::Ge), "af600");
    EXPECT_EQ(drive_family(Protocol::ProfibusDp, Dialect::Profidrive), "profidrive");
    EXPECT_EQ(drive_family(Protocol::ProfibusDp, Dialect::Vlt, "fc"), "fc");
    EXPECT_EQ(drive_family(Protocol::Fc, Dialect::Vlt, "vlt5000"), "vlt5000");
    EXPECT_EQ(drive_family(Protocol::ProfibusDp, Dialect::Ge, ""), "af600");
}

// ---- the shipped databases (drives/databases/*.params) ------------------------------------------

// Every shipped database parses, without a warning, and is named after its family.
TEST(ParameterDatabaseTest, EveryShippedDatabaseParses) {
    ASSERT_FALSE(shipped_databases().empty());
    std::set<std::string> families;
    for (const ShippedDatabase& shipped : shipped_databases()) {
        Result<ParameterFile> parsed = parse_parameter_database(shipped.text, shipped.file);
        ASSERT_TRUE(parsed) << parsed.error();
        EXPECT_TRUE(parsed->warnings.empty()) << shipped.file << ": " << parsed->warnings.front();
        EXPECT_EQ(std::string(shipped.file), "drives/databases/" + parsed->family.id + ".params");
        EXPECT_TRUE(families.insert(parsed->family.id).second) << shipped.file;
        // The compiled-in text is the file's.
        EXPECT_EQ(test::slurp(test::source_dir() + "/" + std::string(shipped.file)), shipped.text);
    }
    // The families the family rule names (drives/drive_family.hpp).
    for (const char* family : {"fc", "vlt5000", "vlt2000", "af600"})
        EXPECT_TRUE(families.count(family)) << family;
}

// How a sample's drives are to be named: the dialects the golden cases decode it with
// (tests/golden_cases.cmake; every other slave is vlt, the default), and the family of the
// slaves of samples/dpv1.pcap that access parameters through DP-V1 in the Danfoss dialect: FC
// series drives (the simulator's DP-V1 parameter table is the FC series', four-digit PNUs such as
// 1530; docs/cli.md, "simulate"), which `--drive 3=fc --drive 5=fc` names.
void configure(const std::string& sample, DecoderOptions& options, DriveHints& drives) {
    if (sample == "ge.pcap") options.dialect = Dialect::Ge;
    if (sample == "profidrive.pcap") options.dialect = Dialect::Profidrive;
    if (sample == "dpv1.pcap") {
        options.station_dialect[4] = Dialect::Profidrive;
        drives.station[3] = drives.station[5] = "fc";
    }
    if (sample == "gsd.pcap") options.station_dialect[4] = Dialect::Profidrive;
}

// The PNUs each sample's telegrams name, by the family the family rule gives their station:
// decoded, not listed by hand. Left out: PNU 0 in a PROFIBUS PCV, the idle parameter channel
// (a PKW of zeros) and the PNU a rejection (RC 7) leaves out, which names no parameter.
// `on_profibus`: the (family, PNU) a PROFIBUS telegram names, which the profile family may name.
std::map<std::string, std::map<std::uint16_t, std::set<std::string>>> pnus_of_the_samples(
    std::set<std::pair<std::string, std::uint16_t>>& on_profibus) {
    std::map<std::string, std::map<std::uint16_t, std::set<std::string>>> used;
    DIR* folder = ::opendir((test::source_dir() + "/samples").c_str());
    EXPECT_NE(folder, nullptr);
    if (!folder) return used;
    std::vector<std::string> samples;
    while (const dirent* entry = ::readdir(folder))
        if (entry->d_type == DT_REG) samples.emplace_back(entry->d_name);
    ::closedir(folder);
    std::sort(samples.begin(), samples.end());
    for (const std::string& sample : samples) {
        BusChoice choice;
        OpenResult source = open_source(test::source_dir() + "/samples/" + sample,
                                        InputFormat::Auto, nullptr, choice);
        EXPECT_TRUE(source) << sample << ": " << source.error();
        if (!source) continue;
        LaneOptions options;
        DriveHints drives;
        configure(sample, options.decoder, drives);
        std::unique_ptr<TelegramDecoder> decoder = choice.protocol->make_decoder(options);
        Record record;
        PnuSet named;
        while ((*source)->next(record)) {
            const DecodedTelegram& t = decoder->decode(record.bytes, record.time_ns, record.number);
            const std::string family(
                drive_family(t.protocol, options.decoder.dialect_of(t.slave), drives.of(t.slave)));
            named.reset();
            mark_telegram_pnus(FilterInput{t}, named);
            if (t.dp.has_pcv && t.dp.pcv.pnu != 0) named.set(t.dp.pcv.pnu);
            for (std::size_t pnu = 0; pnu < named.size(); ++pnu)
                if (named.test(pnu)) {
                    used[family][static_cast<std::uint16_t>(pnu)].insert(sample);
                    if (t.protocol == Protocol::ProfibusDp)
                        on_profibus.emplace(family, static_cast<std::uint16_t>(pnu));
                }
        }
    }
    return used;
}

// drives/databases/unsourced.txt: the PNUs the samples use that a shipped database has no row
// for, because no source for the row was found ("FAMILY PNU" a line, '#' comments).
std::set<std::pair<std::string, std::uint16_t>> unsourced_pnus() {
    std::set<std::pair<std::string, std::uint16_t>> listed;
    std::istringstream lines(test::slurp(test::source_dir() + "/drives/databases/unsourced.txt"));
    std::string line;
    while (std::getline(lines, line)) {
        line = line.substr(0, line.find('#'));
        std::istringstream fields(line);
        std::string family;
        unsigned pnu = 0;
        if (!(fields >> family)) continue;
        EXPECT_TRUE(fields >> pnu) << line;
        EXPECT_TRUE(listed.emplace(family, static_cast<std::uint16_t>(pnu)).second) << line;
    }
    return listed;
}

// Every PNU a sample names has a row in the family of its station, or is listed as unsourced;
// and every PNU listed as unsourced is used by a sample and has no row (a row written since, or
// a sample changed, makes the list say so).
TEST(ParameterDatabaseTest, EveryPnuTheSamplesUseHasARowInItsFamily) {
    ParameterDatabase shipped;
    for (const ShippedDatabase& database : shipped_databases()) {
        Result<ParameterFile> parsed = parse_parameter_database(database.text, database.file);
        ASSERT_TRUE(parsed) << parsed.error();
        shipped.add(std::move(parsed->family));
    }
    std::set<std::pair<std::string, std::uint16_t>> profibus;
    const auto used = pnus_of_the_samples(profibus);
    const auto unsourced = unsourced_pnus();
    std::size_t checked = 0;
    for (const auto& [family, pnus] : used) {
        for (const auto& [pnu, samples] : pnus) {
            ++checked;
            std::string where;
            for (const std::string& sample : samples)
                where += (where.empty() ? "" : ", ") + sample;
            // A drive known only by its profile: its maker's PNUs are no family's.
            if (family == kProfileFamily && !is_profile_pnu(pnu)) continue;
            // On PROFIBUS the profile's family names the profile PNUs (ParameterNaming).
            const bool has_row = shipped.lookup(family, pnu) != nullptr ||
                                 (is_profile_pnu(pnu) && profibus.count({family, pnu}) &&
                                  shipped.lookup(kProfileFamily, pnu) != nullptr);
            const bool listed = unsourced.count({family, pnu}) > 0;
            EXPECT_TRUE(has_row || listed)
                << "PNU " << pnu << " (" << where << ") has no row in " << family;
            EXPECT_FALSE(has_row && listed)
                << family << " " << pnu << " has a row now: drop it from unsourced.txt";
        }
    }
    for (const auto& [family, pnu] : unsourced) {
        const auto in_family = used.find(family);
        EXPECT_TRUE(in_family != used.end() && in_family->second.count(pnu))
            << family << " " << pnu << " is in unsourced.txt but no sample uses it";
    }
    // The samples name parameters of every family (samples/ge.pcap: two GE AF-600 slaves).
    for (const char* family : {"fc", "vlt5000", "vlt2000", "af600", "profidrive"})
        EXPECT_TRUE(used.count(family)) << family;
    EXPECT_GT(checked, 10u);
}

}  // namespace
}  // namespace dpscope
