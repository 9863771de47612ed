// Drive parameter databases on the command line: dpscope params, --params (a broken or missing
// file is a warning and left out), --drive, and --pnu as a number, a group and number or a name.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::CommandResult;
using test::run_dpscope;

const std::string kTestDrive = "tests/params/testdrive.params";
const std::string kFcExamples = "samples/fc-examples.hex";

void expect_usage_error(const CommandResult& r, const std::string& message) {
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_NE(r.err.find(message), std::string::npos) << "expected '" << message << "' in:\n"
                                                      << r.err;
}

std::string write_database(const std::string& name, const std::string& text) {
    const std::string path = test::temp_path(name);
    test::write_text_file(path, text);
    return path;
}

TEST(ParamsCliTest, HelpNamesTheCommandAndItsOptions) {
    CommandResult app = run_dpscope({"--help"});
    EXPECT_NE(app.out.find("params"), std::string::npos) << app.out;
    CommandResult help = run_dpscope({"params", "--help"});
    EXPECT_EQ(help.exit_code, 0);
    for (const char* option : {"PATTERN", "--family", "-T,--format", "text,json,csv", "--params"})
        EXPECT_NE(help.out.find(option), std::string::npos) << option << "\n" << help.out;
    for (const char* command : {"decode", "hex", "report", "sniff"}) {
        CommandResult r = run_dpscope({command, "--help"});
        for (const char* option : {"--params", "--drive", "FAMILY|ADDR=FAMILY", "N|G-NN|NAME"}) {
            if (std::string(command) == "report" && std::string(option) == "N|G-NN|NAME") continue;
            EXPECT_NE(r.out.find(option), std::string::npos) << command << " " << option;
        }
    }
}

TEST(ParamsCliTest, ListsTheFamiliesAndSelectsByPattern) {
    CommandResult all = run_dpscope({"params"});
    EXPECT_EQ(all.exit_code, 0) << all.err;
    EXPECT_EQ(all.err, "");
    for (const char* family : {"af600: ", "fc: ", "vlt2000: ", "vlt5000: "})
        EXPECT_NE(all.out.find(family), std::string::npos) << family << "\n" << all.out;
    // A pattern is a part of the number as written, of the plain number, or of the name.
    CommandResult grouped = run_dpscope(
        {"params", "--params", kTestDrive, "--family", "testdrive", "-T", "csv", "16-1"});
    EXPECT_EQ(test::lines_of(grouped.out).size(), 1u + 4u) << grouped.out;  // 16-10 .. 16-18
    CommandResult plain = run_dpscope(
        {"params", "--params", kTestDrive, "--family", "testdrive", "-T", "csv", "1613"});
    ASSERT_EQ(test::lines_of(plain.out).size(), 2u) << plain.out;
    EXPECT_EQ(test::lines_of(plain.out)[1].rfind("testdrive,1613,16-13,\"Frequency\",", 0), 0u);
    CommandResult named = run_dpscope(
        {"params", "--params", kTestDrive, "--family", "testdrive", "-T", "csv", "RAMP"});
    EXPECT_EQ(test::lines_of(named.out).size(), 3u) << named.out;
    // Nothing matches: said, and an empty list.
    CommandResult none =
        run_dpscope({"params", "--params", kTestDrive, "--family", "testdrive", "nothing-like"});
    EXPECT_EQ(none.exit_code, 0);
    EXPECT_EQ(none.out, "");
    EXPECT_EQ(none.err,
              "dpscope: warning: no parameter matches 'nothing-like' in the family testdrive\n");
    expect_usage_error(run_dpscope({"params", "--family", "nope"}),
                       "dpscope: error: --family nope: no database of that family is loaded "
                       "(af600, fc, profidrive, vlt2000, vlt5000)");
    expect_usage_error(run_dpscope({"params", "-T", "xml"}),
                       "--format: 'xml' is not one of text, json, csv");
}

TEST(ParamsCliTest, ABrokenOrMissingFileIsAWarningAndLeftOut) {
    const std::string broken = write_database(
        "broken.params", "@family testdrive\n@source D = d\n1613 | Output | Hz | -1 | int16\n");
    CommandResult listed = run_dpscope({"params", "--params", broken, "--params", kTestDrive,
                                        "--family", "testdrive", "-T", "csv", "16-13"});
    EXPECT_EQ(listed.exit_code, 0) << listed.err;
    EXPECT_EQ(listed.err, "dpscope: warning: " + broken +
                              ":3: a row of 5 cells: a row has 7 (pnu | name | unit | conversion "
                              "| type | elements | source); is the line cut short?; dpscope goes "
                              "on without " +
                              broken + "\n");
    EXPECT_NE(listed.out.find("\"Frequency\""), std::string::npos) << listed.out;
    // decode goes on too: the exit code is the decode's.
    const std::string missing = test::temp_path("missing.params");
    CommandResult decoded = run_dpscope(
        {"decode", "--params", missing, "--params", broken, "--bus", "fc", "-q", kFcExamples});
    EXPECT_EQ(decoded.exit_code, 0) << decoded.err;
    EXPECT_NE(decoded.err.find("dpscope: warning: --params " + missing +
                               ": cannot read: No such file or directory; dpscope goes on "
                               "without it\n"),
              std::string::npos)
        << decoded.err;
    EXPECT_NE(decoded.err.find("dpscope: warning: " + broken + ":3: "), std::string::npos);
    EXPECT_EQ(decoded.out, run_dpscope({"decode", "--bus", "fc", "-q", kFcExamples}).out);
    CommandResult folder = run_dpscope({"params", "--params", test::source_dir(), "-T", "csv"});
    EXPECT_EQ(folder.exit_code, 0);
    EXPECT_NE(folder.err.find(": not a regular file; give a parameter database; dpscope goes on "
                              "without it"),
              std::string::npos)
        << folder.err;
}

TEST(ParamsCliTest, AnUnknownConversionIndexIsWarnedAtLoading) {
    const std::string odd = write_database(
        "odd.params", "@family odd\n@source D = d\n120 | Speed | RPM | 99 | uint16 | 1 | D\n");
    CommandResult r = run_dpscope({"params", "--params", odd, "--family", "odd"});
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_EQ(r.err, "dpscope: warning: " + odd +
                         ":3: conversion index 99 has no meaning dpscope knows: the values of PNU "
                         "120 are not scaled\n");
    EXPECT_NE(r.out.find("120  Speed  RPM"), std::string::npos) << r.out;
}

// --conversion-index gives a contested index the factor of the user's manual; a bad one is exit 2
// naming the option and what is wrong.
TEST(ParamsCliTest, ConversionIndexGivesAnIndexAFactorAndIsChecked) {
    const std::string hours = write_database(
        "hours.params",
        "@family fc\n@source D = d\n1500 | Operating hours | h | 74 | uint32 | 1 | D\n");
    // FC 15-00 written with PWE 0x7B = 123: hours as they are, or tenths with 74=0.1.
    const std::string telegram = write_database(
        "read-1500.hex", "02 0E 01 35 DC 00 00 00 00 00 7B 00 00 00 00 9F\n");
    CommandResult plain =
        run_dpscope({"decode", "--bus", "fc", "--params", hours, "-T", "jsonl", telegram});
    EXPECT_NE(plain.out.find("\"value_scaled\":123,"), std::string::npos) << plain.out << plain.err;
    CommandResult tenths = run_dpscope({"decode", "--bus", "fc", "--params", hours,
                                        "--conversion-index", "74=0.1", "-T", "jsonl", telegram});
    EXPECT_NE(tenths.out.find("\"value_scaled\":12.3,"), std::string::npos) << tenths.out;
    for (const char* bad : {"74", "74=0", "300=1", "74=x"}) {
        CommandResult r = run_dpscope({"decode", "--conversion-index", bad, telegram});
        EXPECT_EQ(r.exit_code, 2) << bad;
        EXPECT_NE(r.err.find("--conversion-index"), std::string::npos) << r.err;
    }
}

TEST(ParamsCliTest, PnuTakesANumberAGroupAndNumberOrAName) {
    const std::vector<std::string> base = {"decode", "--bus", "fc", "-T", "jsonl"};
    const auto decode = [&](std::vector<std::string> extra) {
        std::vector<std::string> args = base;
        args.insert(args.end(), extra.begin(), extra.end());
        args.push_back(kFcExamples);
        return run_dpscope(args);
    };
    CommandResult number = decode({"--pnu", "414"});
    ASSERT_EQ(number.exit_code, 0) << number.err;
    ASSERT_EQ(test::lines_of(number.out).size(), 2u) << number.out;
    EXPECT_EQ(decode({"--pnu", "4-14"}).out, number.out);
    // A name, unique in the families in play (--drive names the test database's family).
    CommandResult named =
        decode({"--params", kTestDrive, "--drive", "testdrive", "--pnu", "motor speed high"});
    EXPECT_EQ(named.exit_code, 0) << named.err;
    EXPECT_EQ(named.out, number.out);
    // Ambiguous, unknown, out of range, not a PNU: usage errors that say why.
    expect_usage_error(
        decode({"--params", kTestDrive, "--drive", "testdrive", "--pnu", "Ramp 1"}),
        "dpscope: error: --pnu Ramp 1: 'Ramp 1' is in the names of several parameters of the "
        "drive family testdrive (testdrive 3-41 Ramp 1 Ramp Up Time; testdrive 3-42 Ramp 1 Ramp "
        "Down Time); give its number or more of its name\n");
    expect_usage_error(
        decode({"--params", kTestDrive, "--drive", "testdrive", "--pnu", "Torque"}),
        "dpscope: error: --pnu Torque: no parameter of the drive family testdrive is named "
        "'Torque'\n");
    for (const char* bad : {"65536", "655-36", "16-130", "-1", "1-"})
        expect_usage_error(decode({"--pnu", bad}),
                           std::string("dpscope: error: --pnu ") + bad +
                               ": must be a whole number from 0 to 65535, a group and number from "
                               "0-00 to 655-35 (16-13), or a parameter's name\n");
    // The families in play follow --bus: without a name of the FC bus's family, none.
    expect_usage_error(decode({"--params", kTestDrive, "--pnu", "Motor Thermal"}),
                       "no parameter of the drive family fc is named 'Motor Thermal'");
}

TEST(ParamsCliTest, DriveIsCheckedLikeDialect) {
    expect_usage_error(run_dpscope({"decode", "--drive", "FC", kFcExamples}),
                       "dpscope: error: --drive FC: 'FC' is no drive family (lower-case letters, "
                       "digits, '-', '_'; dpscope params lists them)\n");
    expect_usage_error(run_dpscope({"decode", "--drive", "200=fc", kFcExamples}),
                       "dpscope: error: --drive 200=fc: '200' is not a station address from 0 "
                       "to 126\n");
    expect_usage_error(
        run_dpscope({"decode", "--drive", "3=fc", "--drive", "3=vlt5000", kFcExamples}),
        "dpscope: error: --drive 3=vlt5000: station 3 was already given the family fc; give "
        "one family a station (ADDR=FAMILY sets one station)\n");
    expect_usage_error(run_dpscope({"decode", "--drive", "fc", "--drive", "af600", kFcExamples}),
                       "--drive af600: every station was already given the family fc");
    CommandResult same = run_dpscope(
        {"decode", "--bus", "fc", "--drive", "3=fc", "--drive", "3=fc", "-q", kFcExamples});
    EXPECT_EQ(same.exit_code, 0) << same.err;
}

// ---- names and values in the outputs (issue 29, docs/parameters.md "In the outputs") ---------

// A family of the VLT 5000's plain numbers, for the PROFIBUS samples' PNUs.
const std::string kPlainFamily =
    "@family t5\n@source T = test sheet\n"
    "207 | Ramp-up time | s | -2 | uint32 | 1 | T p. 1\n"
    "518 | Frequency | Hz | -1 | int16 | 1 | T p. 2\n";

TEST(ParamsCliTest, PcvTelegramsShowNamesAndValuesInTheirUnits) {
    const std::string t5 = write_database("t5.params", kPlainFamily);
    const std::vector<std::string> base = {"decode", "--params", t5, "--drive", "t5"};
    auto run = [&](std::vector<std::string> extra) {
        std::vector<std::string> args = base;
        args.insert(args.end(), extra.begin(), extra.end());
        return run_dpscope(args);
    };
    CommandResult text = run({"samples/ppo1.pcap"});
    ASSERT_EQ(text.exit_code, 0) << text.err;
    // A read request: the name, no value; its answer: the value in its unit after the raw one.
    EXPECT_NE(text.out.find("RC=1 Request parameter value PNU=518 (Frequency) IND=0 PVA=0 |"),
              std::string::npos)
        << text.out;
    EXPECT_NE(text.out.find("RC=1 Transmit parameter value (word) PNU=518 (Frequency) IND=0 "
                            "PVA=500 (50.0 Hz) |"),
              std::string::npos);
    // Without the database, as before.
    EXPECT_NE(run_dpscope({"decode", "--drive", "t5", "samples/ppo1.pcap"})
                  .out.find("PNU=518 IND=0 PVA=500 |"),
              std::string::npos);
    CommandResult jsonl = run({"-T", "jsonl", "samples/ppo1.pcap"});
    EXPECT_NE(jsonl.out.find("\"pnu\":518,\"ind\":0,\"ind_low\":0,\"pva\":500,\"pva_raw\":500,"
                             "\"width\":\"word\",\"pnu_name\":\"Frequency\",\"value_scaled\":50.0,"
                             "\"unit\":\"Hz\","),
              std::string::npos);
    EXPECT_NE(jsonl.out.find("\"pnu\":518,\"ind\":0,\"ind_low\":0,\"pva\":0,\"pva_raw\":0,"
                             "\"width\":null,\"pnu_name\":\"Frequency\",\"value_scaled\":null,"
                             "\"unit\":\"Hz\","),
              std::string::npos);
    CommandResult csv = run({"-T", "csv", "samples/ppo1.pcap"});
    EXPECT_NE(csv.out.find(",\"Frequency\",50.0,\"Hz\"\n"), std::string::npos);
    EXPECT_NE(csv.out.find(",\"Frequency\",,\"Hz\"\n"), std::string::npos);
    CommandResult verbose = run({"-V", "-c", "60", "samples/ppo1.pcap"});
    EXPECT_NE(verbose.out.find("PNU: 518\n                name: Frequency (t5: unit Hz, conversion "
                               "index -1, int16, source T p. 2)\n"),
              std::string::npos)
        << verbose.out;
    EXPECT_NE(verbose.out.find("word value 500\n            in its unit: 50.0 Hz (conversion "
                               "index -1)\n"),
              std::string::npos);
    // The report names them in its tables.
    CommandResult report =
        run_dpscope({"report", "--params", t5, "--drive", "t5", "samples/ppo1.pcap"});
    EXPECT_NE(report.out.find("207 (Ramp-up time) ("), std::string::npos) << report.out;
    EXPECT_NE(report.out.find("518 (Frequency) ("), std::string::npos);
    CommandResult json =
        run_dpscope({"report", "-T", "json", "--params", t5, "--drive", "t5", "samples/ppo1.pcap"});
    EXPECT_NE(json.out.find("{\"pnu\":518,\"pnu_name\":\"Frequency\",\"requests\":"),
              std::string::npos);
}

TEST(ParamsCliTest, FcTelegramsShowNamesAndValuesInTheirUnits) {
    const std::vector<std::string> base = {"decode",   "--bus",   "fc",       "--params",
                                           kTestDrive, "--drive", "testdrive"};
    auto run = [&](std::vector<std::string> extra) {
        std::vector<std::string> args = base;
        args.insert(args.end(), extra.begin(), extra.end());
        args.push_back(kFcExamples);
        return run_dpscope(args);
    };
    CommandResult text = run({});
    ASSERT_EQ(text.exit_code, 0) << text.err;
    EXPECT_NE(text.out.find("AK=1 Parameter value transferred (word) PNU=414 (4-14 Motor Speed "
                            "High Limit [Hz]) IND=0 PWE=10 (1.0 Hz) |"),
              std::string::npos)
        << text.out;
    // No row: the FC series' number as before; a rejection: no value.
    EXPECT_NE(text.out.find("PNU=415 (4-15) IND=0 fault 17"), std::string::npos);
    CommandResult jsonl = run({"-T", "jsonl"});
    EXPECT_NE(jsonl.out.find("\"width\":\"word\",\"pnu_name\":\"Motor Speed High Limit [Hz]\","
                             "\"value_scaled\":1.0,\"unit\":\"Hz\""),
              std::string::npos)
        << jsonl.out;
    CommandResult csv = run({"-T", "csv"});
    EXPECT_NE(csv.out.find(",\"Motor Speed High Limit [Hz]\",1.0,\"Hz\"\n"), std::string::npos);
    CommandResult report = run_dpscope(
        {"report", "--bus", "fc", "--params", kTestDrive, "--drive", "testdrive", kFcExamples});
    EXPECT_NE(report.out.find("PNU 414 (4-14 Motor Speed High Limit [Hz]) (1 read, 0 writes)"),
              std::string::npos)
        << report.out;
}

TEST(ParamsCliTest, Vlt2000AndProfidriveShowNamesAndValuesInTheirUnits) {
    const std::string v2 = write_database(
        "v2.params",
        "@family v2\n@source T = t\n516 | Output frequency | Hz | - | int32 | 1 | T\n");
    CommandResult vlt = run_dpscope({"decode", "--bus", "vlt2000", "--params", v2, "--drive", "v2",
                                     "samples/vlt2000-examples.txt"});
    ASSERT_EQ(vlt.exit_code, 0) << vlt.err;
    // The value carries its own decimal point: the unit follows it.
    EXPECT_NE(vlt.out.find("parameter 516 (Output frequency) = 80 Hz"), std::string::npos)
        << vlt.out;
    CommandResult vlt_json = run_dpscope({"decode", "--bus", "vlt2000", "-T", "jsonl", "--params",
                                          v2, "--drive", "v2", "samples/vlt2000-examples.txt"});
    EXPECT_NE(vlt_json.out.find("\"pnu_name\":\"Output frequency\",\"value_scaled\":80,"
                                "\"unit\":\"Hz\""),
              std::string::npos);
    // DP-V1: each PROFIdrive parameter named, a whole value of the value attribute scaled.
    CommandResult dpv1 = run_dpscope({"decode", "--dialect", "4=profidrive", "--params", kTestDrive,
                                      "--drive", "3=testdrive", "samples/dpv1.pcap"});
    ASSERT_EQ(dpv1.exit_code, 0) << dpv1.err;
    EXPECT_NE(dpv1.out.find("PNU 342[0] (3-42 Ramp 1 Ramp Down Time) = 300 (3.00 s, "
                            "Unsigned32)"),
              std::string::npos)
        << dpv1.out;
    EXPECT_NE(dpv1.out.find("PNU 1540[0] (15-40 FC Type) = \"FC-302\" (VisibleString)"),
              std::string::npos);
    CommandResult dpv1_json =
        run_dpscope({"decode", "--dialect", "4=profidrive", "-T", "jsonl", "--params", kTestDrive,
                     "--drive", "3=testdrive", "samples/dpv1.pcap"});
    EXPECT_NE(dpv1_json.out.find("\"pnu_name\":\"Ramp 1 Ramp Down Time\",\"value_scaled\":3.00,"
                                 "\"unit\":\"s\""),
              std::string::npos);
}

}  // namespace
}  // namespace dpscope
