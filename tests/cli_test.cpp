// The dpscope executable: help and version, decode from a file and from standard input, exit
// codes and error messages, filters, the hex and simulate subcommands.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <pcap/pcap.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "capture/telegram_source.hpp"
#include "simulator/simulator.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::CommandResult;
using test::lines_of;
using test::run_dpscope;

const std::string kPpo1 = "samples/ppo1.pcap";
const std::string kTruncated = "samples/truncated.pcap";

struct TempFile {
    explicit TempFile(std::string_view name) : path(test::temp_path(name)) {}
    ~TempFile() { std::remove(path.c_str()); }
    std::string path;
};

// The whole file as a string, for standard input (binary safe).
std::string file_content(const std::string& path) {
    std::vector<std::uint8_t> bytes = test::read_file(path);
    return std::string(bytes.begin(), bytes.end());
}

std::size_t records_in(const std::string& path) {
    OpenResult opened = open_source(path, InputFormat::Auto, profibus_protocol());
    EXPECT_TRUE(opened) << opened.error();
    if (!opened) return 0;
    Record record;
    std::size_t n = 0;
    while (opened.value()->next(record))
        ++n;
    return n;
}

std::string sample(const std::string& relative) { return test::source_dir() + "/" + relative; }

void expect_mentions(const std::string& help, const std::vector<std::string>& options) {
    for (const std::string& option : options)
        EXPECT_NE(help.find(option), std::string::npos) << option << " missing from:\n" << help;
}

// ---- version and help ------------------------------------------------------------------------

TEST(CliTest, Version) {
    CommandResult r = run_dpscope({"--version"});
    EXPECT_EQ(r.exit_code, 0);
    // The version and the commit, the buses, the libraries, the plugin's Wireshark (issue 32).
    EXPECT_TRUE(std::regex_search(
        r.out, std::regex("^dpscope [0-9]+\\.[0-9]+\\.[0-9]+ \\(commit [0-9a-z.-]+\\)\n")))
        << r.out;
    expect_mentions(r.out,
                    {"buses (--bus): profibus = PROFIBUS DP, fc = ", "vlt2000 = ", "libpcap 1.",
                     "libmosquitto ", "fmt 9.", "CLI11 2.", "Wireshark plugin: "});
    EXPECT_EQ(r.out.back(), '\n');
    EXPECT_EQ(r.out.find("\n\n"), std::string::npos) << r.out;
}

TEST(CliTest, AppHelpListsSubcommandsAndExitCodes) {
    CommandResult r = run_dpscope({"--help"});
    EXPECT_EQ(r.exit_code, 0);
    expect_mentions(r.out, {"--help", "--version", "decode", "hex", "simulate",
                            "Exit codes:", "2 bad usage", "3 the input ended in damage"});
}

const std::vector<std::string> kDecodeOptions = {
    "-T,--format", "-V,--verbose", "-q,--quiet",      "-c,--count",    "--station",
    "--pnu",       "--ppo",        "--dialect",       "--pcd-profile", "--timeout-ms",
    "--strict",    "-h,--help",    "--fc-response-ms"};

TEST(CliTest, DecodeHelpMentionsEveryOption) {
    CommandResult r = run_dpscope({"decode", "--help"});
    EXPECT_EQ(r.exit_code, 0);
    expect_mentions(r.out, kDecodeOptions);
    expect_mentions(r.out, {"file", "-r,--read", "--input-format", "auto,pcap,pcapng,raw,hex",
                            "text,verbose,jsonl,csv", "Exit codes:"});
}

TEST(CliTest, HexHelpMentionsEveryOption) {
    CommandResult r = run_dpscope({"hex", "--help"});
    EXPECT_EQ(r.exit_code, 0);
    expect_mentions(r.out, kDecodeOptions);
    expect_mentions(r.out, {"bytes", "BYTES", "Exit codes:"});
}

TEST(CliTest, SimulateHelpMentionsEveryOption) {
    CommandResult r = run_dpscope({"simulate", "--help"});
    EXPECT_EQ(r.exit_code, 0);
    // -F has one name in every subcommand; simulate's old --output-format is still read.
    EXPECT_EQ(r.out.find("--output-format"), std::string::npos);
    for (const char* command : {"decode", "hex"})
        EXPECT_NE(run_dpscope({command, "--help"}).out.find("-F,--write-format"), std::string::npos)
            << command;
    CommandResult old_name =
        run_dpscope({"simulate", "-c", "2", "--output-format", "hex", "-w", "-"});
    EXPECT_EQ(old_name.exit_code, 0) << old_name.err;
    EXPECT_EQ(old_name.out, run_dpscope({"simulate", "-c", "2", "-F", "hex", "-w", "-"}).out);
    expect_mentions(r.out, {"-w,--write",    "-F,--write-format",
                            "--linktype",    "--seed",
                            "--baud",        "--master",
                            "--slave",       "--cycles",
                            "-c,--count",    "--cycle-us",
                            "--start",       "--fault",
                            "--no-start-up", "-v,--list-injections",
                            "-h,--help",     "Exit codes:",
                            "--bus",         "--drive",
                            "1-31",          "1-126"});
    // Every fault kind is listed.
    for (std::size_t i = 0; i < static_cast<std::size_t>(FaultKind::Count); ++i)
        expect_mentions(r.out, {std::string(fault_kind_name(static_cast<FaultKind>(i)))});
}

TEST(CliTest, MissingSubcommandIsUsageError) {
    CommandResult r = run_dpscope({});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(r.out.empty());
    CommandResult unknown = run_dpscope({"frob", kPpo1});
    EXPECT_EQ(unknown.exit_code, 2);
    EXPECT_EQ(unknown.err,
              "dpscope: error: unknown subcommand 'frob'; one of completion, decode, filter, hex, "
              "params, "
              "report, simulate, sniff, stats (see --help)\n");
}

// ---- decode ----------------------------------------------------------------------------------

TEST(CliTest, DecodeFileReadOptionAndStandardInputAgree) {
    CommandResult positional = run_dpscope({"decode", kPpo1});
    EXPECT_EQ(positional.exit_code, 0) << positional.err;
    EXPECT_TRUE(positional.err.empty()) << positional.err;
    std::vector<std::string> lines = lines_of(positional.out);
    ASSERT_EQ(lines.size(), records_in(sample(kPpo1)));
    EXPECT_EQ(lines[0].rfind("     1     0.000000   2 → 3   SD1 FDL_Status     req FDL status", 0),
              0u)
        << lines[0];
    EXPECT_EQ(lines[6].rfind("     7     0.000", 0), 0u) << lines[6];
    EXPECT_NE(lines[6].find("SD2 Chk_Cfg        req F3 F1 = PPO1"), std::string::npos) << lines[6];

    CommandResult read = run_dpscope({"decode", "-r", kPpo1});
    EXPECT_EQ(read.exit_code, 0) << read.err;
    EXPECT_EQ(read.out, positional.out);

    CommandResult stdin_read = run_dpscope({"decode", "-r", "-"}, file_content(sample(kPpo1)));
    EXPECT_EQ(stdin_read.exit_code, 0) << stdin_read.err;
    EXPECT_EQ(stdin_read.out, positional.out);

    CommandResult stdin_positional = run_dpscope({"decode", "-"}, file_content(sample(kPpo1)));
    EXPECT_EQ(stdin_positional.exit_code, 0) << stdin_positional.err;
    EXPECT_EQ(stdin_positional.out, positional.out);
}

TEST(CliTest, DecodeWithoutInputOrWithTwoInputsIsUsageError) {
    CommandResult none = run_dpscope({"decode"});
    EXPECT_EQ(none.exit_code, 2);
    EXPECT_NE(none.err.find("decode: no input"), std::string::npos) << none.err;
    CommandResult both = run_dpscope({"decode", "-r", kPpo1, kPpo1});
    EXPECT_EQ(both.exit_code, 2);
    EXPECT_NE(both.err.find("give the input once"), std::string::npos) << both.err;
    EXPECT_TRUE(both.out.empty());
}

TEST(CliTest, MissingFileIsUsageErrorNamingIt) {
    CommandResult r = run_dpscope({"decode", "samples/does-not-exist.pcap"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(r.out.empty());
    EXPECT_EQ(
        r.err,
        "dpscope: error: samples/does-not-exist.pcap: cannot open: No such file or directory\n");
}

TEST(CliTest, UnsupportedLinkTypeIsUsageErrorNamingFileAndLinkType) {
    TempFile file("ethernet.pcap");
    pcap_t* dead = pcap_open_dead(DLT_EN10MB, 65535);
    ASSERT_NE(dead, nullptr);
    pcap_dumper_t* dumper = pcap_dump_open(dead, file.path.c_str());
    ASSERT_NE(dumper, nullptr) << pcap_geterr(dead);
    std::vector<std::uint8_t> frame(60, 0x00);
    pcap_pkthdr header{};
    header.caplen = header.len = static_cast<bpf_u_int32>(frame.size());
    pcap_dump(reinterpret_cast<u_char*>(dumper), &header, frame.data());
    pcap_dump_close(dumper);
    pcap_close(dead);

    CommandResult r = run_dpscope({"decode", file.path});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(r.out.empty());
    EXPECT_NE(r.err.find("dpscope: error: " + file.path + ": unsupported link type 1 (EN10MB)"),
              std::string::npos)
        << r.err;
}

TEST(CliTest, ForcedPcapOnTextIsUsageError) {
    TempFile file("log.txt");
    test::write_text_file(file.path, "10 03 02 49 4E 16\n");
    CommandResult r = run_dpscope({"decode", "--input-format", "pcap", file.path});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find(file.path + ": not a readable pcap or pcapng file"), std::string::npos)
        << r.err;
    // Detected as hex it decodes.
    CommandResult detected = run_dpscope({"decode", file.path});
    EXPECT_EQ(detected.exit_code, 0);
    EXPECT_EQ(detected.out, "     1            -   2 → 3   SD1 FDL_Status     req FDL status\n");
}

TEST(CliTest, InputWithoutAnyTelegramIsUsageError) {
    TempFile empty("empty.raw");
    test::write_file(empty.path, {});
    for (const char* command : {"decode", "report"}) {
        CommandResult r = run_dpscope({command, empty.path});
        EXPECT_EQ(r.exit_code, 2) << command;
        EXPECT_TRUE(r.out.empty()) << command;
        EXPECT_EQ(r.err, "dpscope: error: " + empty.path + ": the input is empty\n") << command;
    }
    TempFile prose("notes.raw");
    test::write_file(prose.path, {0xE2, 0x86, 0x92, 'n', 'o', ' ', 'b', 'u', 's'});
    CommandResult r = run_dpscope({"decode", prose.path});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find(prose.path + ": no PROFIBUS telegram in its 9 bytes read as a raw byte "
                                      "stream"),
              std::string::npos)
        << r.err;
    // One byte is "1 byte" (#27 point 15).
    TempFile one("one.raw");
    test::write_file(one.path, {'x'});
    CommandResult single = run_dpscope({"decode", "--input-format", "raw", one.path});
    EXPECT_EQ(single.exit_code, 2);
    EXPECT_NE(single.err.find(one.path + ": no PROFIBUS telegram in its 1 byte read as a raw byte "
                                         "stream"),
              std::string::npos)
        << single.err;
    CommandResult forced = run_dpscope({"decode", "--input-format", "hex", kPpo1});
    EXPECT_EQ(forced.exit_code, 2);
    EXPECT_NE(forced.err.find("no hex bytes in the text"), std::string::npos) << forced.err;
    // A pcap may rightly hold no telegram: an empty capture is no error.
    TempFile no_records("none.pcap");
    std::vector<std::uint8_t> header;
    {
        CommandResult first = run_dpscope({"simulate", "-w", "-", "-c", "1"});
        ASSERT_GT(first.out.size(), 24u);
        header.assign(first.out.begin(), first.out.begin() + 24);  // the file header alone
    }
    test::write_file(no_records.path, header);
    // ... but the report of it is no pass: nothing was checked (exit 1), unless --allow-empty.
    CommandResult report = run_dpscope({"report", no_records.path});
    EXPECT_EQ(report.exit_code, 1) << report.err;
    EXPECT_NE(report.out.find("Result:  FAIL: nothing checked (no telegrams); 0 errors"),
              std::string::npos)
        << report.out;
    CommandResult allowed = run_dpscope({"report", "--allow-empty", "-T", "json", no_records.path});
    EXPECT_EQ(allowed.exit_code, 0) << allowed.err;
    EXPECT_NE(allowed.out.find("\"result\":\"pass\",\"nothing_checked\":true"), std::string::npos)
        << allowed.out;
    EXPECT_NE(run_dpscope({"report", "--help"}).out.find("--allow-empty"), std::string::npos);
}

// A capture without telegrams (a pcap or pcapng file without records) is no pass for any command
// that reads one: decode and stats say "no telegrams" and exit 1, as report says "nothing
// checked"; --allow-empty lets each pass (exit 0, a note). (An empty byte stream is no capture:
// InputWithoutAnyTelegramIsUsageError.)
TEST(CliTest, AnEmptyInputFailsUnlessAllowed) {
    TempFile no_records("none.pcap");
    {
        CommandResult first = run_dpscope({"simulate", "-w", "-", "-c", "1"});
        ASSERT_GT(first.out.size(), 24u);
        test::write_file(no_records.path,
                         std::vector<std::uint8_t>(first.out.begin(), first.out.begin() + 24));
    }
    TempFile no_packets("none.pcapng");
    {
        CommandResult first = run_dpscope({"simulate", "-F", "pcapng", "-w", "-", "-c", "1"});
        ASSERT_GT(first.out.size(), 64u);
        // The section header and the interface description, without the packet.
        std::vector<std::uint8_t> head(first.out.begin(), first.out.end());
        const std::uint32_t shb = head[4] | head[5] << 8 | head[6] << 16 | head[7] << 24;
        const std::uint32_t idb =
            head[shb + 4] | head[shb + 5] << 8 | head[shb + 6] << 16 | head[shb + 7] << 24;
        head.resize(shb + idb);
        test::write_file(no_packets.path, head);
    }
    for (const std::string& input : {no_records.path, no_packets.path}) {
        for (const std::vector<std::string>& command :
             std::vector<std::vector<std::string>>{{"decode"}, {"decode", "-q"}, {"stats"}}) {
            std::vector<std::string> args = command;
            args.push_back(input);
            CommandResult failed = run_dpscope(args);
            EXPECT_EQ(failed.exit_code, 1) << args[0] << " " << input;
            EXPECT_EQ(failed.err, "dpscope: error: " + input +
                                      ": no telegrams: the capture is empty (--allow-empty accepts "
                                      "it)\n")
                << args[0];
            args.insert(args.begin() + 1, "--allow-empty");
            CommandResult allowed = run_dpscope(args);
            EXPECT_EQ(allowed.exit_code, 0) << args[0] << " " << input;
            EXPECT_EQ(allowed.err, "dpscope: note: " + input + ": no telegrams\n") << args[0];
        }
        CommandResult report = run_dpscope({"report", input});
        EXPECT_EQ(report.exit_code, 1) << input << report.err;
        EXPECT_NE(report.out.find("FAIL: nothing checked (no telegrams)"), std::string::npos)
            << report.out;
        EXPECT_EQ(run_dpscope({"report", "--allow-empty", input}).exit_code, 0) << input;
    }
    // The segment of an empty capture is not judged, in every stats format.
    CommandResult text = run_dpscope({"stats", "--allow-empty", no_records.path});
    EXPECT_NE(text.out.find("Segment:   not judged (no telegrams)\n"), std::string::npos)
        << text.out;
    EXPECT_EQ(text.out.find("good"), std::string::npos) << text.out;
    CommandResult json = run_dpscope({"stats", "--allow-empty", "-T", "json", no_records.path});
    EXPECT_NE(json.out.find("\"verdict\":null,\"reasons\":[]}"), std::string::npos) << json.out;
    for (const char* format : {"markdown", "html"}) {
        CommandResult other =
            run_dpscope({"stats", "--allow-empty", "-T", format, no_records.path});
        EXPECT_NE(other.out.find("not judged"), std::string::npos) << format << other.out;
        EXPECT_EQ(other.out.find("good"), std::string::npos) << format;
    }
    for (const char* command : {"decode", "hex", "stats"})
        EXPECT_NE(run_dpscope({command, "--help"}).out.find("--allow-empty"), std::string::npos)
            << command;
}

// The report's filter line names what the bus has: slaves on PROFIBUS, drives on the serial
// buses (as their sections and the --station warning do).
TEST(CliTest, ReportFilterLineNamesSlavesOrDrives) {
    EXPECT_NE(run_dpscope({"report", "--station", "2", "samples/vlt2000.pcap"})
                  .out.find("\nFilter:  drive 2 (telegram counts cover the whole capture)\n"),
              std::string::npos);
    EXPECT_NE(run_dpscope({"report", "--station", "1", "--station", "2", "samples/fc.pcap"})
                  .out.find("\nFilter:  drives 1, 2 ("),
              std::string::npos);
    CommandResult markdown =
        run_dpscope({"report", "-T", "markdown", "--station", "2", "samples/vlt2000.pcap"});
    EXPECT_NE(markdown.out.find("- Filter: drive 2 ("), std::string::npos) << markdown.out;
    EXPECT_NE(run_dpscope({"report", "--station", "3", "--station", "5", "samples/faults.pcap"})
                  .out.find("\nFilter:  slaves 3, 5 ("),
              std::string::npos);
}

// The errors CLI11 finds itself are worded as dpscope words its own: what was wrong, how to
// mend it; never CLI11's "At Most 1 required but received 2".
TEST(CliTest, CommandLineErrorsAreInDpscopesWords) {
    const std::string help =
        "\nRun 'dpscope --help' or 'dpscope SUBCOMMAND --help' for the options.\n";
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases{
        {{"decode", "-r", kPpo1, "-r", kPpo1}, "--read: given 2 times; give it once"},
        {{"decode", "--bogus", kPpo1}, "unknown option --bogus"},
        {{"decode", "-T", "foo", kPpo1}, "--format: 'foo' is not one of text, verbose, jsonl, csv"},
        {{"decode", kPpo1, "-c"}, "--count needs a value: N, 1 to 9223372036854775807 telegrams"},
        {{"decode", "--ppo"}, "--ppo needs a value: ADDR=TYPE"},
        {{"decode", kPpo1, "extra"},
         "unexpected argument 'extra': give one input FILE, and repeat an option for each of its "
         "values (--station 3 --station 5)"},
        {{}, "give a subcommand: decode, hex, report, simulate, sniff or stats"},
    };
    for (const auto& [args, message] : cases) {
        CommandResult r = run_dpscope(args);
        EXPECT_EQ(r.exit_code, 2) << message;
        EXPECT_EQ(r.err, "dpscope: error: " + message + help);
    }
}

TEST(CliTest, BadOptionValuesAreUsageErrors) {
    CommandResult ppo = run_dpscope({"decode", "--ppo", "3=9", kPpo1});
    EXPECT_EQ(ppo.exit_code, 2);
    EXPECT_TRUE(ppo.out.empty());
    EXPECT_EQ(ppo.err,
              "dpscope: error: --ppo 3=9: expected ADDR=TYPE with ADDR from 0 to 126 and TYPE from "
              "1 to 5\n");

    CommandResult dialect = run_dpscope({"decode", "--dialect", "foo", kPpo1});
    EXPECT_EQ(dialect.exit_code, 2);
    EXPECT_TRUE(dialect.out.empty());
    EXPECT_EQ(dialect.err,
              "dpscope: error: --dialect foo: 'foo' is not a dialect (vlt, ge, profidrive)\n");
    CommandResult upper = run_dpscope({"decode", "--dialect", "3=GE", kPpo1});
    EXPECT_EQ(upper.exit_code, 2);
    EXPECT_EQ(upper.err,
              "dpscope: error: --dialect 3=GE: 'GE' is not a dialect (vlt, ge, profidrive)\n");
    // fc is the FC carrier's code tables, no dialect of a PROFIBUS slave.
    CommandResult fc = run_dpscope({"decode", "--dialect", "3=fc", kPpo1});
    EXPECT_EQ(fc.exit_code, 2);
    EXPECT_EQ(fc.err,
              "dpscope: error: --dialect 3=fc: 'fc' is not a dialect (vlt, ge, profidrive)\n");
    for (const char* bad : {"0", "60001", "-1", "2.5", "x"}) {
        CommandResult response = run_dpscope({"report", "--fc-response-ms", bad, kPpo1});
        EXPECT_EQ(response.exit_code, 2) << bad;
        EXPECT_NE(response.err.find("must be a whole number from 1 to 60000 ms"), std::string::npos)
            << response.err;
    }
    CommandResult twice = run_dpscope({"decode", "--dialect", "ge", "--dialect", "vlt", kPpo1});
    EXPECT_EQ(twice.exit_code, 2);
    EXPECT_NE(twice.err.find("the dialect for every slave was already given as ge"),
              std::string::npos)
        << twice.err;

    CommandResult count = run_dpscope({"decode", "-c", "0", kPpo1});
    EXPECT_EQ(count.exit_code, 2);
    EXPECT_NE(count.err.find("--count: must be a whole number from 1 to 9223372036854775807 "
                             "telegrams, not '0'"),
              std::string::npos)
        << count.err;

    CommandResult verbose_jsonl = run_dpscope({"decode", "-V", "-T", "jsonl", kPpo1});
    EXPECT_EQ(verbose_jsonl.exit_code, 2);
    EXPECT_TRUE(verbose_jsonl.out.empty());
    EXPECT_EQ(
        verbose_jsonl.err,
        "dpscope: error: -V is the same as -T verbose; it cannot be combined with -T jsonl\n");

    CommandResult station_dialect = run_dpscope({"decode", "--dialect", "200=vlt", kPpo1});
    EXPECT_EQ(station_dialect.exit_code, 2);
    EXPECT_NE(station_dialect.err.find("'200' is not a station address"), std::string::npos);

    for (std::vector<std::string> args : {std::vector<std::string>{"decode", "-T", "json", kPpo1},
                                          {"decode", "--station", "128", kPpo1},
                                          {"decode", "--pnu", "65536", kPpo1},
                                          {"decode", "-c", "0", kPpo1},
                                          {"decode", "--input-format", "pcapng2", kPpo1},
                                          {"decode", "--no-such-option", kPpo1}}) {
        CommandResult r = run_dpscope(args);
        EXPECT_EQ(r.exit_code, 2) << args[1];
        EXPECT_TRUE(r.out.empty()) << args[1];
        EXPECT_FALSE(r.err.empty()) << args[1];
    }
}

TEST(CliTest, TruncatedCaptureExitsThreeAfterPrintingWhatCameBefore) {
    CommandResult r = run_dpscope({"decode", kTruncated});
    EXPECT_EQ(r.exit_code, 3);
    EXPECT_NE(r.err.find("dpscope: error: " + kTruncated + ": record 102 (byte offset 3098): "),
              std::string::npos)
        << r.err;
    std::vector<std::string> lines = lines_of(r.out);
    ASSERT_EQ(lines.size(), 101u);
    EXPECT_EQ(lines.back().rfind("   101 ", 0), 0u) << lines.back();
    // The same telegrams as the intact capture.
    std::vector<std::string> intact = lines_of(run_dpscope({"decode", kPpo1}).out);
    ASSERT_GE(intact.size(), 101u);
    EXPECT_EQ(lines.front(), intact.front());
}

TEST(CliTest, TruncatedCaptureInSummaryMode) {
    CommandResult r = run_dpscope({"decode", "-q", kTruncated});
    EXPECT_EQ(r.exit_code, 3);
    EXPECT_NE(r.out.find("  telegrams: 101, "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("  input: reading stopped early"), std::string::npos) << r.out;
}

TEST(CliTest, CountStopsAfterNTelegrams) {
    CommandResult r = run_dpscope({"decode", "-c", "5", kPpo1});
    EXPECT_EQ(r.exit_code, 0);
    std::vector<std::string> lines = lines_of(r.out);
    ASSERT_EQ(lines.size(), 5u);
    EXPECT_EQ(lines[4].rfind("     5 ", 0), 0u);
    CommandResult jsonl = run_dpscope({"decode", "--count", "3", "-T", "jsonl", kPpo1});
    EXPECT_EQ(lines_of(jsonl.out).size(), 3u);
}

std::vector<std::uint8_t> random_bytes(std::size_t n) {
    std::mt19937 generator(11);
    std::vector<std::uint8_t> bytes(n);
    for (std::uint8_t& b : bytes)
        b = static_cast<std::uint8_t>(generator());
    return bytes;
}

TEST(CliTest, RandomBytesAreNoProfibusStreamUnlessRawIsForced) {
    TempFile file("random.bin");
    test::write_file(file.path, random_bytes(1'000'000));
    for (const char* command : {"decode", "report"}) {
        CommandResult r = run_dpscope({command, file.path});
        EXPECT_EQ(r.exit_code, 2) << command;
        EXPECT_TRUE(r.out.empty()) << command << r.out.substr(0, 200);
        // One line: the verdict with the share skipped, and how to decode it anyway.
        EXPECT_EQ(lines_of(r.err).size(), 1u) << r.err.substr(0, 2000);
        EXPECT_NE(r.err.find("dpscope: error: " + file.path + ": not a PROFIBUS byte stream: "),
                  std::string::npos)
            << r.err;
        EXPECT_NE(r.err.find("of its first 65536 bytes (99."), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("--input-format raw decodes it anyway"), std::string::npos) << r.err;
    }
    // Forced: decoded, and the warnings about skipped bytes are capped, also with -q.
    for (bool quiet : {false, true}) {
        std::vector<std::string> args = {"decode", "--input-format", "raw", file.path};
        if (quiet) args.push_back("-q");
        CommandResult r = run_dpscope(args);
        EXPECT_EQ(r.exit_code, 0) << quiet;
        std::vector<std::string> warnings = lines_of(r.err);
        ASSERT_EQ(warnings.size(), kMaxIssuesShown + 1) << r.err.substr(0, 2000);
        EXPECT_TRUE(std::regex_search(warnings.back(),
                                      std::regex(": [0-9]+ more runs of skipped bytes not shown "
                                                 "\\([0-9]+ bytes\\)$")))
            << warnings.back();
    }
}

TEST(CliTest, CountStopsReadingRawInputAtTheLastTelegram) {
    // Two telegrams, then garbage: -c 2 says nothing about the garbage.
    TempFile file("count.raw");
    std::vector<std::uint8_t> bytes = test::hex("10 03 02 49 4E 16 DC 02 02");
    std::vector<std::uint8_t> garbage = random_bytes(5000);
    for (std::uint8_t& b : garbage)
        b &= 0x0F;  // no start delimiter
    bytes.insert(bytes.end(), garbage.begin(), garbage.end());
    bytes.push_back(0xE5);
    test::write_file(file.path, bytes);
    for (const char* command : {"decode", "report"}) {
        // --allow-empty: two telegrams without a parameter channel are "nothing checked".
        std::vector<std::string> args = {command, "--input-format", "raw", "-c", "2", file.path};
        if (std::string(command) == "report") args.push_back("--allow-empty");
        CommandResult r = run_dpscope(args);
        EXPECT_EQ(r.exit_code, 0) << command << r.err;
        EXPECT_EQ(r.err, "") << command;
    }
    CommandResult all = run_dpscope({"decode", "--input-format", "raw", file.path});
    EXPECT_NE(all.err.find("skipped 5000 byte"), std::string::npos) << all.err;
}

TEST(CliTest, MergedPcapngWithTwoLinkTypesIsDecoded) {
    // mergecap of a 257 and a 147 capture: two interfaces with different link types.
    TempFile file("merged.pcapng");
    test::PcapngBuilder b;
    b.interface(257).interface(147).interface(1);
    const std::uint64_t t0 = 1'704'067'200'000'000;
    b.packet(0, t0, test::hex("10 03 02 49 4E 16")).packet(1, t0 + 100, test::hex("E5"));
    b.packet(2, t0 + 150, std::vector<std::uint8_t>(60, 0xFF));
    b.packet(1, t0 + 200, test::hex("DC 02 02"));
    test::write_file(file.path, b.bytes());
    CommandResult r = run_dpscope({"decode", file.path});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    std::vector<std::string> lines = lines_of(r.out);
    ASSERT_EQ(lines.size(), 3u) << r.out;
    EXPECT_EQ(lines[2].rfind("     4     0.000200 ", 0), 0u) << lines[2];
    EXPECT_EQ(r.err, "dpscope: warning: " + file.path +
                         ": byte offset 76: interface 2 has link type 1 (EN10MB), which dpscope "
                         "does not decode (it reads 257 PROFIBUS_DL and 147 USER0); its packets "
                         "are skipped\n");
}

TEST(CliTest, HexLogTypoNamesLineAndColumn) {
    CommandResult r = run_dpscope({"decode", "-"}, "10 03 02 49 4E 16\n10 03 02 49 0G 16\n");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(lines_of(r.out).size(), 1u);
    EXPECT_NE(r.err.find("dpscope: warning: <stdin>: line 2, column 13: '0G' is not a hex byte"),
              std::string::npos)
        << r.err;
    CommandResult odd = run_dpscope({"decode", "-"}, "100302494E1\n");
    EXPECT_EQ(odd.exit_code, 2);
    EXPECT_NE(odd.err.find("<stdin>: line 1, column 1: '100302494E1' is no run of hex bytes (an "
                           "odd number of hex digits: 11)"),
              std::string::npos)
        << odd.err;
    EXPECT_NE(odd.err.find("dpscope: error: <stdin>: no readable hex bytes in the text (1 line "
                           "with tokens that are no hex bytes, named above)"),
              std::string::npos)
        << odd.err;
}

// Source and destination of a text line: "frame time SRC → DST ...".
std::pair<std::string, std::string> ends_of(const std::string& line) {
    std::istringstream in(line);
    std::string frame, time, source, arrow, destination;
    in >> frame >> time >> source >> arrow >> destination;
    EXPECT_EQ(arrow, "→") << line;
    return {source, destination};
}

TEST(CliTest, StationFilter) {
    CommandResult all = run_dpscope({"decode", "samples/faults.pcap"});
    CommandResult r = run_dpscope({"decode", "--station", "5", "samples/faults.pcap"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    std::vector<std::string> lines = lines_of(r.out);
    ASSERT_FALSE(lines.empty());
    EXPECT_LT(lines.size(), lines_of(all.out).size());
    // A telegram of other stations is shown only for a finding about station 5 found at it
    // (fdl_no_response is found at the master's next telegram).
    std::size_t by_finding = 0;
    for (const std::string& line : lines) {
        auto [source, destination] = ends_of(line);
        if (source == "5" || destination == "5") continue;
        EXPECT_NE(line.find("fdl_no_response]"), std::string::npos) << line;
        ++by_finding;
    }
    CommandResult jsonl =
        run_dpscope({"decode", "-T", "jsonl", "--station", "5", "samples/faults.pcap"});
    std::size_t about_five = 0;
    for (const std::string& line : lines_of(jsonl.out)) {
        if (line.find("\"da\":5,") != std::string::npos ||
            line.find("\"sa\":5,") != std::string::npos ||
            line.find("\"master\":2,\"slave\":5,\"request_frame\"") != std::string::npos)
            continue;  // to or from 5, or a short acknowledge of 5 (by its roles)
        EXPECT_NE(line.find("\"slave\":5,\"pnu\""), std::string::npos) << line;
        ++about_five;
    }
    EXPECT_EQ(about_five, by_finding);
    // Two stations: the union.
    CommandResult two =
        run_dpscope({"decode", "--station", "5", "--station", "4", "samples/faults.pcap"});
    std::size_t fours = 0;
    for (const std::string& line : lines_of(two.out)) {
        auto [source, destination] = ends_of(line);
        EXPECT_TRUE(source == "5" || destination == "5" || source == "4" || destination == "4" ||
                    line.find("fdl_no_response]") != std::string::npos)
            << line;
        if (source == "4" || destination == "4") ++fours;
    }
    EXPECT_GT(fours, 0u);
}

TEST(CliTest, FilteredTimesStayRelativeToTheCapturesFirstTelegram) {
    // "frame time" of each line, as in the unfiltered output.
    auto frame_and_time = [](const std::string& line) { return line.substr(0, 19); };
    std::set<std::string> all;
    for (const std::string& line : lines_of(run_dpscope({"decode", "samples/faults.pcap"}).out))
        all.insert(frame_and_time(line));
    for (std::vector<std::string> filter :
         {std::vector<std::string>{"--station", "4"}, std::vector<std::string>{"--pnu", "207"}}) {
        filter.insert(filter.begin(), "decode");
        filter.push_back("samples/faults.pcap");
        std::vector<std::string> lines = lines_of(run_dpscope(filter).out);
        ASSERT_FALSE(lines.empty());
        EXPECT_NE(lines[0].substr(6, 13), "     0.000000") << lines[0];
        for (const std::string& line : lines)
            EXPECT_TRUE(all.count(frame_and_time(line))) << line;
    }
}

TEST(CliTest, ProfidriveSlaveDecodedAsVltGetsADialectHintInSummaryAndReport) {
    TempFile capture("profidrive-slave.pcap");
    CommandResult made = run_dpscope(
        {"simulate", "-w", capture.path, "--slave", "3:1:profidrive", "--cycles", "2000"});
    ASSERT_EQ(made.exit_code, 0) << made.err;
    const std::string option = "decode with --dialect 3=profidrive";
    CommandResult summary = run_dpscope({"decode", "-q", capture.path});
    EXPECT_NE(summary.out.find("         hint: its parameter-channel codes fit the profidrive "
                               "dialect ("),
              std::string::npos)
        << summary.out;
    EXPECT_NE(summary.out.find(option), std::string::npos);
    CommandResult report = run_dpscope({"report", capture.path});
    EXPECT_NE(report.out.find("  dialect hint   its parameter-channel codes fit the profidrive"),
              std::string::npos)
        << report.out;
    // Decoded as profidrive: no unknown codes, no hint.
    CommandResult right = run_dpscope({"decode", "-q", "--dialect", "3=profidrive", capture.path});
    EXPECT_EQ(right.out.find("hint"), std::string::npos) << right.out;
    // Decoded as ge: AK 13/14 only profidrive defines.
    CommandResult ge = run_dpscope({"decode", "-q", "--dialect", "ge", capture.path});
    EXPECT_NE(ge.out.find("fit the profidrive dialect"), std::string::npos) << ge.out;
    EXPECT_NE(ge.out.find("codes ge does not define"), std::string::npos) << ge.out;
}

TEST(CliTest, VltSlaveWithSpontaneousMessagesDecodedAsGeGetsAVltHint) {
    TempFile capture("vlt-spontaneous.pcap");
    CommandResult made = run_dpscope({"simulate", "-w", capture.path, "--slave", "3:1", "--cycles",
                                      "400", "--fault", "spontaneous_message=0.2"});
    ASSERT_EQ(made.exit_code, 0) << made.err;
    // The simulated vlt slave's ident number, 0x0402, is the VLT 5000/6000's, which is the
    // evidence named first (its RC 9..12, not used in ge, would point to vlt as well).
    CommandResult ge = run_dpscope({"decode", "-q", "--dialect", "3=ge", capture.path});
    EXPECT_NE(ge.out.find("hint: its ident number 0x0402 is the Danfoss VLT 5000/6000's (the vlt "
                          "dialect)"),
              std::string::npos)
        << ge.out;
    EXPECT_NE(ge.out.find("decode with --dialect 3=vlt"), std::string::npos) << ge.out;
    CommandResult vlt = run_dpscope({"decode", "-q", capture.path});
    EXPECT_EQ(vlt.out.find("hint"), std::string::npos) << vlt.out;
}

// A simulated GE slave (seed 002): its rejection carries fault number 130 or 131, which only the
// ge dialect names; its unknown code is one of the unused RC 9..12.
TEST(CliTest, GeSlaveDecodedWithTheGeDialect) {
    TempFile capture("ge-slave.pcap");
    CommandResult made =
        run_dpscope({"simulate", "-w", capture.path, "--seed", "5", "--slave", "3:1:ge", "--cycles",
                     "40", "--fault", "request_rejected@5:3", "--fault", "unknown_code@20:3"});
    ASSERT_EQ(made.exit_code, 0) << made.err;
    auto ge_text = [](const std::string& out) {
        return out.find("(There is no network access to the parameter called)") !=
                   std::string::npos ||
               out.find(
                   "(Data change is not possible because factory setup has been "
                   "selected)") != std::string::npos;
    };
    for (const char* dialect : {"ge", "3=ge"}) {
        CommandResult ge = run_dpscope({"decode", "--dialect", dialect, capture.path});
        EXPECT_EQ(ge.exit_code, 0) << ge.err;
        EXPECT_TRUE(ge_text(ge.out)) << dialect << "\n" << ge.out;
        EXPECT_EQ(ge.out.find("unknown error number"), std::string::npos) << ge.out;
        EXPECT_NE(ge.out.find("unknown_code"), std::string::npos) << ge.out;
        EXPECT_EQ(ge.out.find("spontaneous"), std::string::npos) << ge.out;
        CommandResult verbose = run_dpscope({"decode", "-V", "--dialect", dialect, capture.path});
        EXPECT_NE(verbose.out.find("Dialect: ge;"), std::string::npos);
    }
    // vlt knows neither 130 nor 131, and reads RC 9..12 as spontaneous messages.
    CommandResult vlt = run_dpscope({"decode", capture.path});
    EXPECT_EQ(vlt.exit_code, 0) << vlt.err;
    EXPECT_FALSE(ge_text(vlt.out)) << vlt.out;
    EXPECT_NE(vlt.out.find("(unknown error number)"), std::string::npos) << vlt.out;
    EXPECT_NE(vlt.out.find("spontaneous"), std::string::npos) << vlt.out;
    CommandResult report = run_dpscope({"report", "--dialect", "3=ge", capture.path});
    EXPECT_NE(report.out.find("PPO 1"), std::string::npos) << report.out;
    EXPECT_NE(report.out.find("dialect ge"), std::string::npos) << report.out;
    CommandResult vlt_report = run_dpscope({"report", capture.path});
    EXPECT_NE(vlt_report.out.find("(unknown error number)"), std::string::npos) << vlt_report.out;
    for (const char* format : {"json", "markdown", "html"}) {
        CommandResult other = run_dpscope({"report", "-T", format, capture.path});
        EXPECT_NE(other.out.find("unknown error number"), std::string::npos) << format;
        EXPECT_EQ(other.out.find("network access"), std::string::npos) << format;
    }
    CommandResult csv = run_dpscope({"decode", "-T", "csv", capture.path});
    EXPECT_NE(csv.out.find("\"unknown error number\""), std::string::npos);
    CommandResult jsonl = run_dpscope({"decode", "-T", "jsonl", capture.path});
    EXPECT_NE(jsonl.out.find("\"error_text\":\"unknown error number\""), std::string::npos);

    // A ge slave sends no spontaneous messages: the fault cannot be injected there.
    CommandResult spontaneous = run_dpscope(
        {"simulate", "-w", "-", "--slave", "3:1:ge", "--fault", "spontaneous_message:3"});
    EXPECT_EQ(spontaneous.exit_code, 2);
    EXPECT_EQ(spontaneous.err,
              "dpscope: error: --fault spontaneous_message:3: slave 3 speaks the ge dialect, "
              "which has no spontaneous messages (RC 9 to 12 not used)\n");
    CommandResult nobody = run_dpscope(
        {"simulate", "-w", "-", "--slave", "3:1:ge", "--fault", "spontaneous_unacknowledged"});
    EXPECT_EQ(nobody.exit_code, 2);
    EXPECT_NE(nobody.err.find("no simulated slave with a parameter channel has spontaneous "
                              "messages"),
              std::string::npos)
        << nobody.err;
}

TEST(CliTest, ReportWarnsOfAStationNotInTheCapture) {
    CommandResult r = run_dpscope({"report", "--station", "9", "samples/ppo2.pcap"});
    EXPECT_EQ(r.exit_code, 1) << "nothing checked";
    EXPECT_NE(r.err.find("warning: --station 9: no slave 9 in the capture"), std::string::npos)
        << r.err;
    CommandResult present = run_dpscope({"report", "--station", "4", "samples/faults.pcap"});
    EXPECT_EQ(present.err.find("warning"), std::string::npos) << present.err;
}

TEST(CliTest, PnuFilter) {
    CommandResult r = run_dpscope({"decode", "--pnu", "207", "-T", "jsonl", kPpo1});
    EXPECT_EQ(r.exit_code, 0);
    std::vector<std::string> lines = lines_of(r.out);
    ASSERT_FALSE(lines.empty());
    for (const std::string& line : lines) {
        EXPECT_NE(line.find("\"service\":\"Data_Exchange\""), std::string::npos) << line;
        EXPECT_NE(line.find("\"pcv\":{\"pca\":"), std::string::npos) << line;
        EXPECT_NE(line.find(",\"pnu\":207,"), std::string::npos) << line;
    }
    CommandResult none = run_dpscope({"decode", "--pnu", "2000", kPpo1});
    EXPECT_EQ(none.exit_code, 0);
    EXPECT_TRUE(none.out.empty());
}

TEST(CliTest, PnuFilterSelectsDpv1RequestsAndTheResponsesNamedAfterThem) {
    // samples/dpv1.pcap: PNU 1543 is read from slave 3 (one negative response) and slave 5.
    CommandResult r = run_dpscope({"decode", "--pnu", "1543", "-T", "jsonl", "samples/dpv1.pcap"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(r.err.empty()) << r.err;
    std::vector<std::string> lines = lines_of(r.out);
    ASSERT_GE(lines.size(), 4u);
    std::size_t requests = 0, responses = 0;
    for (const std::string& line : lines) {
        EXPECT_NE(line.find("\"service\":\"MSAC_C1\""), std::string::npos) << line;
        EXPECT_NE(line.find("\"pnu\":1543,"), std::string::npos) << line;
        requests += line.find("\"response\":false") != std::string::npos;
        responses += line.find("\"response\":true") != std::string::npos;
    }
    EXPECT_EQ(requests, responses);
    // Above the cyclic PCV's 2047: only DP-V1 can match; nothing here does, which is said.
    CommandResult none = run_dpscope({"decode", "--pnu", "60000", "samples/dpv1.pcap"});
    EXPECT_EQ(none.exit_code, 0);
    EXPECT_TRUE(none.out.empty());
    EXPECT_NE(none.err.find("--pnu 60000: no parameter request or answer about PNU 60000"),
              std::string::npos)
        << none.err;
}

TEST(CliTest, QuietPrintsOnlyTheSummary) {
    CommandResult r = run_dpscope({"decode", "-q", kPpo1});
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_EQ(r.out.rfind("Summary of samples/ppo1.pcap (pcap)\n", 0), 0u) << r.out;
    EXPECT_NE(r.out.find("  telegrams: " + std::to_string(records_in(sample(kPpo1))) +
                         ", from 2024-01-01T00:00:00."),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("    Data_Exchange            60  (30 requests, 30 responses)\n"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("      3: PPO 1 (PCV + 2 PCD words, 12 bytes each way) from Chk_Cfg; "
                         "dialect vlt; ident 0x0402; 60 Data_Exchange telegrams\n"),
              std::string::npos)
        << r.out;
    EXPECT_EQ(r.out.find("FDL_Status     req"), std::string::npos);
}

TEST(CliTest, OutputFormatsFromTheCommandLine) {
    CommandResult csv = run_dpscope({"decode", "-T", "csv", "-c", "2", kPpo1});
    std::vector<std::string> lines = lines_of(csv.out);
    ASSERT_EQ(lines.size(), 3u);
    EXPECT_EQ(lines[0].rfind("frame,time,len,sd,", 0), 0u);
    CommandResult verbose = run_dpscope({"decode", "-V", "-c", "1", kPpo1});
    EXPECT_EQ(verbose.out.rfind("Frame 1: 6 bytes, 2024-01-01T00:00:00.", 0), 0u) << verbose.out;
    EXPECT_NE(verbose.out.find("    Start delimiter: SD1 (0x10)\n"), std::string::npos);
}

// ---- hex -------------------------------------------------------------------------------------

TEST(CliTest, HexFromArguments) {
    CommandResult r = run_dpscope({"hex", "10", "03", "02", "49", "4E", "16"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out.rfind("Frame 1: 6 bytes\n", 0), 0u) << r.out;
    EXPECT_NE(r.out.find("    Start delimiter: SD1 (0x10)\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("    Frame control: 0x49 (request, FCB 0, FCV 0, FDL status)\n"),
              std::string::npos)
        << r.out;
    // One typed telegram only one bus frames: no note about the bus.
    EXPECT_EQ(r.err, "");

    // Every documented spelling, split over arguments; two telegrams.
    CommandResult text = run_dpscope({"hex", "-T", "text", "0x10", "0302", "49:4E", "16,E5"});
    EXPECT_EQ(text.exit_code, 0) << text.err;
    EXPECT_EQ(text.out,
              "     1            -   2 → 3   SD1 FDL_Status     req FDL status\n"
              "     2            -   3 → 2   SC  FDL_Status     rsp short acknowledge\n");
    EXPECT_EQ(text.err, "");
    // Bytes that two buses could frame: the choice is said, with the option that makes it.
    CommandResult mixed = run_dpscope({"hex", "-T", "text", "10 03 02 49 4E 16",
                                       "02 0E 81 24 22 00 00 00 00 02 30 04 7F 20 00 FE"});
    EXPECT_NE(mixed.err.find("dpscope: note: <command line>: read as the FC protocol"),
              std::string::npos)
        << mixed.err;
    // --baud is no option of a PROFIBUS decode: said, as for the other buses' options.
    CommandResult baud = run_dpscope({"hex", "--baud", "19200", "10 03 02 49 4E 16"});
    EXPECT_EQ(baud.err,
              "dpscope: warning: <command line>: --baud applies to the FC protocol and VLT 2000 "
              "in decode (for PROFIBUS, report and stats use it for the bus load, and --gsd to "
              "time answers against MaxTsdr); this capture is PROFIBUS DP: ignored\n");
    EXPECT_EQ(run_dpscope({"decode", "--baud", "19200", "samples/fc.pcap"}).err, "");
}

TEST(CliTest, HexFromStandardInput) {
    CommandResult r = run_dpscope({"hex", "-T", "text"},
                                  "12:00:00.000 TX: 10 03 02 49 4E 16\n"
                                  "12:00:00.001 RX: 10 02 03 00 05 16\n");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out,
              "     1     0.000000   2 → 3   SD1 FDL_Status     req FDL status\n"
              "     2     0.001000   3 → 2   SD1 FDL_Status     rsp OK slave\n");
}

TEST(CliTest, HexSkippedBytesAreReported) {
    CommandResult r = run_dpscope({"hex", "-T", "text", "01 02", "E5"});
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_EQ(lines_of(r.out).size(), 1u);
    EXPECT_NE(r.err.find("<command line>: byte 0: skipped 2 bytes: no start delimiter"),
              std::string::npos)
        << r.err;
}

TEST(CliTest, HexTakesTypedVlt2000Telegrams) {
    // Issue #27 point 9: `dpscope hex '<01UOGD@0516+00080007>'` said the argument is not hex
    // bytes. A typed VLT 2000 telegram is decoded as one, without --bus and without a note.
    CommandResult one = run_dpscope({"hex", "-T", "jsonl", "<01UOGD@0516+00080007>"});
    EXPECT_EQ(one.exit_code, 0) << one.err;
    EXPECT_TRUE(one.err.empty()) << one.err;
    ASSERT_EQ(lines_of(one.out).size(), 1u) << one.out;
    EXPECT_NE(one.out.find("\"vlt2000\":{\"complete\":true,\"address\":1,"), std::string::npos)
        << one.out;
    // A command and its reply, as two arguments or on one with text around them.
    for (std::vector<std::string> args :
         {std::vector<std::string>{"<01UOGD@0516+00080007>", "<01UGHK@0516+00080007>"},
          std::vector<std::string>{"TX <01UOGD@0516+00080007> RX <01UGHK@0516+00080007>"}}) {
        std::vector<std::string> full = {"hex", "-T", "jsonl"};
        full.insert(full.end(), args.begin(), args.end());
        CommandResult two = run_dpscope(full);
        EXPECT_EQ(two.exit_code, 0) << two.err;
        std::vector<std::string> lines = lines_of(two.out);
        ASSERT_EQ(lines.size(), 2u) << two.out;
        EXPECT_NE(lines[1].find("\"request_frame\":1,"), std::string::npos) << lines[1];
    }
    // With --bus vlt2000 the same; with another bus, or mixed with hex bytes, a usage error.
    EXPECT_EQ(run_dpscope({"hex", "--bus", "vlt2000", "<01UOGD@0516+00080007>"}).exit_code, 0);
    CommandResult fc = run_dpscope({"hex", "--bus", "fc", "<01UOGD@0516+00080007>"});
    EXPECT_EQ(fc.exit_code, 2);
    EXPECT_NE(fc.err.find("dpscope: error: hex: argument 1: '<01UOGD@0516+00080007>' is a VLT "
                          "2000 telegram; --bus fc cannot read it"),
              std::string::npos)
        << fc.err;
    CommandResult mixed = run_dpscope({"hex", "<01UOGD@0516+00080007>", "10 03 02 49 4E 16"});
    EXPECT_EQ(mixed.exit_code, 2);
    EXPECT_NE(mixed.err.find("dpscope: error: hex: argument 2: '10 03 02 49 4E 16' holds no VLT "
                             "2000 telegram ('<' ... '>') but argument 1 does; give hex bytes or "
                             "VLT 2000 telegrams"),
              std::string::npos)
        << mixed.err;
    // A broken telegram is named by its argument and column.
    CommandResult broken = run_dpscope({"hex", "<01UOGD@0516+0008>"});
    EXPECT_EQ(broken.exit_code, 2);
    EXPECT_NE(broken.err.find("dpscope: warning: <command line>: argument 1, column 1: skipped 18 "
                              "characters: '<01UOGD@0516+0008>' is no VLT 2000 telegram: the "
                              "argument ends after 18 of its 22 characters"),
              std::string::npos)
        << broken.err;
    EXPECT_NE(broken.err.find("dpscope: error: <command line>: no VLT 2000 telegram in the text, "
                              "only 18 characters of broken ones (named above)"),
              std::string::npos)
        << broken.err;
    // Next to a good one, in a later argument, at the column where it starts.
    CommandResult later = run_dpscope({"hex", "-T", "jsonl", "<01UOGD@0516+00080007>",
                                       "RX <01UGHK@0516+0008\x07"
                                       "007>"});
    EXPECT_EQ(later.exit_code, 0) << later.err;
    EXPECT_EQ(lines_of(later.out).size(), 1u) << later.out;
    EXPECT_NE(later.err.find("dpscope: warning: <command line>: argument 2, column 4: skipped 18 "
                             "characters: '<01UGHK@0516+0008\\x07' is no VLT 2000 telegram: "
                             "character 18 is 0x07, not printable ASCII"),
              std::string::npos)
        << later.err;
}

TEST(CliTest, HexReadsAVlt2000LogPipedIn) {
    // A VLT 2000 terminal log piped into `dpscope hex` is read as the text log it is.
    CommandResult r = run_dpscope({"hex", "-T", "jsonl"},
                                  "12:00:00.5 TX <01UOGD@0516+00080007>\n"
                                  "12:00:00.75 RX <01UGHK@0516+00080007>\n");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    std::vector<std::string> lines = lines_of(r.out);
    ASSERT_EQ(lines.size(), 2u) << r.out << r.err;
    EXPECT_NE(lines[0].find("\"time\":43200.500000000,"), std::string::npos) << lines[0];
    EXPECT_NE(lines[1].find("\"request_frame\":1,"), std::string::npos) << lines[1];
    // A hex log piped in stays a hex log, also when its bytes are VLT 2000 characters.
    CommandResult bytes = run_dpscope({"hex", "-T", "text"}, "10 03 02 49 4E 16\n");
    EXPECT_EQ(bytes.exit_code, 0) << bytes.err;
    EXPECT_EQ(lines_of(bytes.out).size(), 1u) << bytes.out;
}

TEST(CliTest, BadHexArgumentIsUsageErrorNamingIt) {
    CommandResult r = run_dpscope({"hex", "10", "zz", "02"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(r.out.empty());
    EXPECT_EQ(r.err.rfind("dpscope: error: hex: argument 2: 'zz' is not hex bytes", 0), 0u)
        << r.err;
    CommandResult odd = run_dpscope({"hex", "680"});
    EXPECT_EQ(odd.exit_code, 2);
    EXPECT_NE(odd.err.find("argument 1: '680'"), std::string::npos) << odd.err;
}

// ---- simulate
// --------------------------------------------------------------------------------

TEST(CliTest, SimulateThenDecodeRoundTrip) {
    TempFile file("sim.pcap");
    CommandResult sim = run_dpscope(
        {"simulate", "-w", file.path, "--seed", "11", "--slave", "3:1", "--cycles", "30"});
    EXPECT_EQ(sim.exit_code, 0) << sim.err;
    EXPECT_TRUE(sim.out.empty());
    // The same options as samples/ppo1.pcap: the same bytes.
    EXPECT_EQ(test::read_file(file.path), test::read_file(sample(kPpo1)));

    // The file matches the simulator run in-process.
    SimulatorOptions options;
    options.seed = 11;
    options.slaves = {{3, 1, Dialect::Vlt}};
    options.cycles = 30;
    Simulator simulator(options);
    OpenResult opened = open_source(file.path, InputFormat::Auto, profibus_protocol());
    ASSERT_TRUE(opened) << opened.error();
    Record record;
    std::vector<std::uint8_t> bytes;
    std::int64_t time_ns = 0;
    std::size_t n = 0;
    while (simulator.next(bytes, time_ns)) {
        ASSERT_TRUE(opened.value()->next(record)) << n;
        EXPECT_EQ(std::vector<std::uint8_t>(record.bytes.begin(), record.bytes.end()), bytes);
        EXPECT_EQ(record.time_ns, time_ns);
        ++n;
    }
    EXPECT_FALSE(opened.value()->next(record));
}

TEST(CliTest, SimulateToStandardOutputThenDecodeFromStandardInput) {
    for (std::string format : {"pcap", "pcapng", "raw", "hex"}) {
        SCOPED_TRACE(format);
        CommandResult sim =
            run_dpscope({"simulate", "-w", "-", "-F", format, "--seed", "4", "--cycles", "12"});
        ASSERT_EQ(sim.exit_code, 0) << sim.err;
        ASSERT_FALSE(sim.out.empty());
        TempFile file("sim.cap");
        test::write_text_file(file.path, sim.out);
        CommandResult from_file = run_dpscope({"decode", "-T", "jsonl", file.path});
        CommandResult from_stdin = run_dpscope({"decode", "-T", "jsonl", "-r", "-"}, sim.out);
        EXPECT_EQ(from_file.exit_code, 0) << from_file.err;
        EXPECT_EQ(from_stdin.exit_code, 0) << from_stdin.err;
        EXPECT_EQ(from_stdin.out, from_file.out);
        // Start-up of three slaves (32 telegrams) plus 12 cycles of at least 7 telegrams.
        EXPECT_GE(lines_of(from_stdin.out).size(), 32u + 12 * 7);
    }
}

TEST(CliTest, SimulateListsInjections) {
    TempFile file("faults.pcap");
    CommandResult r = run_dpscope({"simulate", "-w", file.path, "--cycles", "10", "--fault",
                                   "fcs_error@3:3", "--fault", "garbage@5:4", "-v"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("injected fcs_error on slave 3 in cycle 3 at telegram "),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("injected garbage on slave 4 in cycle 5 at telegram "), std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("\nwrote " + std::to_string(records_in(file.path)) + " telegrams\n"),
              std::string::npos)
        << r.err;
}

TEST(CliTest, SimulateCountLimitsTheTelegrams) {
    TempFile file("count.pcap");
    CommandResult r = run_dpscope({"simulate", "-w", file.path, "-c", "40"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(records_in(file.path), 40u);
}

TEST(CliTest, SimulateTokenRing) {
    TempFile file("ring.pcap");
    CommandResult r = run_dpscope({"simulate", "-w", file.path, "--cycles", "10", "--masters",
                                   "1,9", "--token-hold-us", "300"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    // Per cycle two tokens more than with one master (3 passes instead of 1), also at start-up.
    CommandResult alone = run_dpscope({"simulate", "-w", "-", "-F", "hex", "--cycles", "10"});
    CommandResult ring =
        run_dpscope({"simulate", "-w", "-", "-F", "hex", "--cycles", "10", "--masters", "1,9"});
    ASSERT_EQ(alone.exit_code, 0) << alone.err;
    ASSERT_EQ(ring.exit_code, 0) << ring.err;
    auto lines = [](const std::string& text) {
        return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
    };
    EXPECT_EQ(lines(ring.out), lines(alone.out) + 2 * 11);

    auto error_of = [](std::vector<std::string> args) {
        std::vector<std::string> full = {"simulate", "-w", "-"};
        full.insert(full.end(), args.begin(), args.end());
        CommandResult result = run_dpscope(full);
        EXPECT_EQ(result.exit_code, 2) << result.err;
        EXPECT_TRUE(result.out.empty());
        return result.err;
    };
    EXPECT_EQ(error_of({"--masters", "2"}),
              "dpscope: error: --masters: 2 is the DP master (--master)\n");
    EXPECT_EQ(error_of({"--masters", "4"}), "dpscope: error: --masters: 4 is a slave's address\n");
    EXPECT_EQ(error_of({"--slave", "9:1", "--masters", "9"}),
              "dpscope: error: --masters: 9 is a slave's address\n");
    EXPECT_EQ(error_of({"--masters", "1,7,1"}), "dpscope: error: --masters: 1 is given twice\n");
    EXPECT_EQ(error_of({"--token-hold-us", "50"}),
              "dpscope: error: --token-hold-us: only with --masters (the masters that hold the "
              "token)\n");
    EXPECT_EQ(error_of({"--bus", "fc", "--masters", "1"}),
              "dpscope: error: --masters: a token ring is PROFIBUS; leave --masters out with --bus "
              "fc\n");
    EXPECT_NE(error_of({"--masters", "127"}).find("--masters"), std::string::npos);
    EXPECT_NE(error_of({"--masters", "1", "--token-hold-us", "1000001"}).find("--token-hold-us"),
              std::string::npos);
}

TEST(CliTest, SimulateUsageErrors) {
    CommandResult slave = run_dpscope({"simulate", "-w", "-", "--slave", "3"});
    EXPECT_EQ(slave.exit_code, 2);
    EXPECT_TRUE(slave.out.empty());
    EXPECT_EQ(slave.err, "dpscope: error: --slave 3: expected ADDR:PPO[:DIALECT][:dpv1]\n");
    CommandResult master = run_dpscope({"simulate", "-w", "-", "--slave", "2:1"});
    EXPECT_EQ(master.exit_code, 2);
    EXPECT_NE(master.err.find("the master has address 2"), std::string::npos) << master.err;
    CommandResult fault = run_dpscope({"simulate", "-w", "-", "--fault", "nonsense"});
    EXPECT_EQ(fault.exit_code, 2);
    EXPECT_NE(fault.err.find("dpscope: error: --fault nonsense: unknown kind 'nonsense'"),
              std::string::npos)
        << fault.err;
    CommandResult dpv1 = run_dpscope({"simulate", "-w", "-", "--fault", "dpv1_error_pdu"});
    EXPECT_EQ(dpv1.exit_code, 2);
    EXPECT_EQ(dpv1.err,
              "dpscope: error: --fault dpv1_error_pdu: no simulated slave runs DP-V1 (add one "
              "with --slave ADDR:PPO[:DIALECT]:dpv1)\n");
    CommandResult endless = run_dpscope({"simulate", "-w", "-", "--cycles", "0"});
    EXPECT_EQ(endless.exit_code, 2);
    EXPECT_TRUE(endless.out.empty());
    CommandResult no_output = run_dpscope({"simulate"});
    EXPECT_EQ(no_output.exit_code, 2);
    CommandResult format = run_dpscope({"simulate", "-w", "-", "-F", "json"});
    EXPECT_EQ(format.exit_code, 2);
    CommandResult nobody = run_dpscope({"simulate", "-w", "-", "--fault", "stacked_request:9"});
    EXPECT_EQ(nobody.exit_code, 2);
    EXPECT_TRUE(nobody.out.empty());
    EXPECT_EQ(nobody.err, "dpscope: error: --fault stacked_request:9: slave 9 is not simulated\n");
    CommandResult late = run_dpscope({"simulate", "-w", "-", "--fault", "stacked_request@999"});
    EXPECT_EQ(late.exit_code, 2);
    EXPECT_FALSE(late.out.empty());  // the session is written all the same
    EXPECT_NE(late.err.find("--fault stacked_request@999 was not injected"), std::string::npos)
        << late.err;
}

// simulate --bus fc: a pcap of link type USER0 with FC telegrams; hex and raw as for PROFIBUS.
TEST(CliTest, SimulateFcWritesUser0CapturesOfFcTelegrams) {
    TempFile file("fc.pcap");
    CommandResult r =
        run_dpscope({"simulate", "--bus", "fc", "-w", file.path, "--seed", "3", "--cycles", "20",
                     "--drive", "4", "--drive", "7:1-31", "-v", "--fault", "fc_bcc_error@2:7"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("injected fc_bcc_error on slave 7 in cycle 2"), std::string::npos)
        << r.err;
    std::vector<std::uint8_t> bytes = test::read_file(file.path);
    ASSERT_GT(bytes.size(), 24u);
    EXPECT_EQ(bytes[20] | bytes[21] << 8, 147);  // LINKTYPE_USER0
    EXPECT_EQ(records_in(file.path), 80u);       // 20 cycles of two polls, no broadcast yet
    CommandResult hex = run_dpscope({"simulate", "--bus", "fc", "-w", "-", "-F", "hex", "--seed",
                                     "3", "--cycles", "1", "--drive", "4"});
    EXPECT_EQ(hex.exit_code, 0) << hex.err;
    std::vector<std::string> lines = lines_of(hex.out);
    ASSERT_EQ(lines.size(), 3u) << hex.out;  // the header line, then one record a line
    EXPECT_EQ(lines[0], "# dpscope hex capture: bus=fc, one record a line");
    EXPECT_NE(lines[1].find(" 02 06 84 04 7F 20 00 DB"), std::string::npos) << lines[1];
    CommandResult raw = run_dpscope(
        {"simulate", "--bus", "fc", "-w", "-", "-F", "raw", "--cycles", "1", "--drive", "4"});
    EXPECT_EQ(raw.exit_code, 0) << raw.err;
    EXPECT_EQ(raw.out.substr(0, 3), std::string("\x02\x06\x84", 3));
}

TEST(CliTest, SimulateFcUsageErrors) {
    auto error_of = [](std::vector<std::string> args) {
        CommandResult r = run_dpscope(args);
        EXPECT_EQ(r.exit_code, 2);
        EXPECT_TRUE(r.out.empty());
        return r.err;
    };
    EXPECT_EQ(error_of({"simulate", "--bus", "fc", "-w", "-", "--slave", "3:1"}),
              "dpscope: error: --slave 3:1: slaves are PROFIBUS DP stations; an FC bus has drives "
              "(--drive ADDR[:1-31|1-126])\n");
    EXPECT_EQ(error_of({"simulate", "-w", "-", "--drive", "3"}),
              "dpscope: error: --drive 3: drives are for --bus fc and --bus vlt2000; a PROFIBUS "
              "DP bus has slaves (--slave ADDR:PPO)\n");
    EXPECT_EQ(error_of({"simulate", "--bus", "fc", "-w", "-", "--drive", "40:1-31"}),
              "dpscope: error: --drive 40:1-31: the address must be from 1 to 31 in the 1-31 "
              "format\n");
    EXPECT_EQ(error_of({"simulate", "--bus", "fc", "-w", "-", "--drive", "4", "--drive", "4:1-31"}),
              "dpscope: error: --drive 4 and --drive 4:1-31 both give address 4: one drive per "
              "address\n");
    EXPECT_EQ(error_of({"simulate", "--bus", "fc", "-w", "-", "--fault", "fcs_error"}),
              "dpscope: error: --fault fcs_error: a PROFIBUS DP fault; an FC bus takes the fc_* "
              "faults, garbage and malformed_telegram\n");
    EXPECT_EQ(error_of({"simulate", "-w", "-", "--fault", "fc_late_response"}),
              "dpscope: error: --fault fc_late_response: an FC protocol fault; give --bus fc\n");
    EXPECT_EQ(error_of({"simulate", "--bus", "fc", "-w", "-", "--fault", "fc_no_response:9"}),
              "dpscope: error: --fault fc_no_response:9: drive 9 is not simulated\n");
    EXPECT_EQ(error_of({"simulate", "--bus", "fc", "-w", "-", "--master", "3"}),
              "dpscope: error: --master: the FC master has no address; leave --master out with "
              "--bus fc\n");
    EXPECT_EQ(error_of({"simulate", "--bus", "fc", "-w", "-", "--linktype", "profibus"}),
              "dpscope: error: --linktype profibus: an FC capture has link type user0 (147)\n");
}

// simulate --bus vlt2000: a pcap of link type USER0 with VLT 2000 telegrams; hex and raw too.
TEST(CliTest, SimulateVlt2000WritesUser0CapturesOfVlt2000Telegrams) {
    TempFile file("vlt2000.pcap");
    CommandResult r = run_dpscope({"simulate", "--bus", "vlt2000", "-w", file.path, "--seed", "3",
                                   "--cycles", "19", "--drive", "4", "--drive", "99", "-v",
                                   "--fault", "vlt2000_checksum_error@2:99"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("injected vlt2000_checksum_error on slave 99 in cycle 2"),
              std::string::npos)
        << r.err;
    std::vector<std::uint8_t> bytes = test::read_file(file.path);
    ASSERT_GT(bytes.size(), 24u);
    EXPECT_EQ(bytes[20] | bytes[21] << 8, 147);  // LINKTYPE_USER0
    EXPECT_EQ(records_in(file.path), 76u);       // 19 cycles of two polls, no broadcast yet
    // decode finds the bus in the capture: the drive's reply names the command it answers.
    CommandResult decoded = run_dpscope({"decode", "-T", "jsonl", file.path});
    EXPECT_EQ(decoded.exit_code, 0) << decoded.err;
    std::vector<std::string> records = lines_of(decoded.out);
    ASSERT_EQ(records.size(), 76u);
    EXPECT_NE(records[1].find("\"direction\":\"response\""), std::string::npos) << records[1];
    EXPECT_NE(records[1].find("\"request_frame\":1,"), std::string::npos) << records[1];
    CommandResult hex = run_dpscope({"simulate", "--bus", "vlt2000", "-w", "-", "-F", "hex",
                                     "--seed", "3", "--cycles", "1", "--drive", "4"});
    EXPECT_EQ(hex.exit_code, 0) << hex.err;
    std::vector<std::string> lines = lines_of(hex.out);
    ASSERT_EQ(lines.size(), 3u) << hex.out;  // the header line, then one record a line
    EXPECT_EQ(lines[0], "# dpscope hex capture: bus=vlt2000, one record a line");
    EXPECT_NE(lines[1].find(" 3C 30 34 "), std::string::npos) << lines[1];  // "<04"
    CommandResult raw = run_dpscope(
        {"simulate", "--bus", "vlt2000", "-w", "-", "-F", "raw", "--cycles", "1", "--drive", "4"});
    EXPECT_EQ(raw.exit_code, 0) << raw.err;
    ASSERT_EQ(raw.out.size(), 44u);
    EXPECT_EQ(raw.out.substr(0, 3), "<04");
    EXPECT_EQ(raw.out.substr(21, 4), "><04");
    EXPECT_EQ(raw.out.back(), '>');
}

TEST(CliTest, SimulateVlt2000UsageErrors) {
    auto error_of = [](std::vector<std::string> args) {
        CommandResult r = run_dpscope(args);
        EXPECT_EQ(r.exit_code, 2);
        EXPECT_TRUE(r.out.empty());
        return r.err;
    };
    EXPECT_EQ(error_of({"simulate", "--bus", "vlt2000", "-w", "-", "--slave", "3:1"}),
              "dpscope: error: --slave 3:1: slaves are PROFIBUS DP stations; a VLT 2000 bus has "
              "drives (--drive ADDR)\n");
    EXPECT_EQ(error_of({"simulate", "--bus", "vlt2000", "-w", "-", "--drive", "100"}),
              "dpscope: error: --drive 100: the address must be from 1 to 99 (two digits; 00 is "
              "the broadcast)\n");
    EXPECT_EQ(
        error_of({"simulate", "--bus", "vlt2000", "-w", "-", "--drive", "4", "--drive", "04"}),
        "dpscope: error: --drive 4 and --drive 04 both give address 4: one drive per "
        "address\n");
    EXPECT_EQ(error_of({"simulate", "--bus", "vlt2000", "-w", "-", "--fault", "fc_bcc_error"}),
              "dpscope: error: --fault fc_bcc_error: an FC protocol fault; a VLT 2000 bus takes "
              "the vlt2000_* faults, garbage and malformed_telegram\n");
    EXPECT_EQ(error_of({"simulate", "-w", "-", "--fault", "vlt2000_no_response"}),
              "dpscope: error: --fault vlt2000_no_response: a VLT 2000 fault; give --bus "
              "vlt2000\n");
    EXPECT_EQ(
        error_of({"simulate", "--bus", "vlt2000", "-w", "-", "--fault", "vlt2000_no_response:9"}),
        "dpscope: error: --fault vlt2000_no_response:9: drive 9 is not simulated\n");
    EXPECT_NE(error_of({"simulate", "--bus", "vlt2000", "-w", "-", "--fault", "nonsense"})
                  .find("(known with --bus vlt2000: garbage, malformed_telegram, "
                        "vlt2000_stacked_request, "),
              std::string::npos);
    EXPECT_EQ(error_of({"simulate", "--bus", "vlt2000", "-w", "-", "--master", "3"}),
              "dpscope: error: --master: the VLT 2000 master has no address; leave --master out "
              "with --bus vlt2000\n");
    EXPECT_EQ(error_of({"simulate", "--bus", "vlt2000", "-w", "-", "--linktype", "profibus"}),
              "dpscope: error: --linktype profibus: a VLT 2000 capture has link type user0 "
              "(147)\n");
    EXPECT_EQ(error_of({"simulate", "--bus", "vlt2000", "-w", "-", "--baud", "230400"}),
              "dpscope: error: --baud: must be a whole number from 2400 to 115200 baud for the "
              "VLT 2000, not '230400'\n");
}

TEST(CliTest, SimulateNumbersOutOfRangeAreUsageErrors) {
    // Regression: --start in milliseconds, 1e18, nan or inf wrote until the disk was full;
    // --start 5e9 dated the capture 1992; --start -5 wrote 5 s of traffic instead of 2.
    const std::string start_range =
        "must be seconds since the epoch from 0 to 2147483647 (1970-01-01T00:00:00Z to "
        "2038-01-19T03:14:07Z, the last time a capture's timestamps hold)\n";
    for (std::string start :
         {"1704067200000", "1e18", "nan", "inf", "-inf", "5e9", "-5", "2147483648", "abc", ""}) {
        SCOPED_TRACE(start);
        CommandResult r = run_dpscope({"simulate", "-w", "-", "--start", start});
        EXPECT_EQ(r.exit_code, 2);
        EXPECT_TRUE(r.out.empty());
        EXPECT_EQ(r.err, "dpscope: error: --start " + start + ": " + start_range);
    }
    struct Case {
        std::vector<std::string> args;
        std::string message;
    };
    const std::string whole = "must be a whole number from ";
    const std::vector<Case> cases = {
        {{"--cycles", "-1"}, "--cycles: " + whole + "0 to 18446744073709551615, not '-1'"},
        {{"--cycles", "99999999999999999999999"},
         "--cycles: " + whole + "0 to 18446744073709551615, not '99999999999999999999999'"},
        {{"-c", "1.5"}, "--count: " + whole + "0 to 18446744073709551615, not '1.5'"},
        {{"--seed", "-1"}, "--seed: " + whole + "0 to 18446744073709551615, not '-1'"},
        {{"--baud", "-5"}, "--baud: " + whole + "2400 to 12000000 baud, not '-5'"},
        {{"--baud", "12000001"}, "--baud: " + whole + "2400 to 12000000 baud, not '12000001'"},
        {{"--baud", "4800"}, "--baud: " + whole + "9600 to 12000000 baud for PROFIBUS, not '4800'"},
        {{"--master", "127"}, "--master: " + whole + "0 to 126, not '127'"},
        {{"--cycle-us", "99"}, "--cycle-us: " + whole + "100 to 1000000, not '99'"},
        {{"--fault", "garbage=nan"}, "--fault garbage=nan: rate 'nan' must be a number in (0, 1]"},
        {{"--fault", "garbage=inf"}, "--fault garbage=inf: rate 'inf' must be a number in (0, 1]"},
        {{"--fault", "garbage@-1"}, "--fault garbage@-1: '-1' is not a cycle number"},
        // The session's end must fit as well as its start.
        {{"--cycles", "100000000000000"},
         "--cycles 100000000000000: the session could last longer than the 2147483647 s a "
         "capture's timestamps span (1970-01-01T00:00:00Z to 2038-01-19T03:14:07Z); give fewer "
         "--cycles"},
        {{"--cycles", "0", "-c", "1000000000000000"},
         "-c 1000000000000000: the session could last longer than the 2147483647 s a capture's "
         "timestamps span (1970-01-01T00:00:00Z to 2038-01-19T03:14:07Z); give a smaller -c"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.args[1]);
        std::vector<std::string> args = {"simulate", "-w", "-"};
        args.insert(args.end(), c.args.begin(), c.args.end());
        CommandResult r = run_dpscope(args);
        EXPECT_EQ(r.exit_code, 2);
        EXPECT_TRUE(r.out.empty());
        EXPECT_EQ(r.err.rfind("dpscope: error: " + c.message + "\n", 0), 0u) << r.err;
    }
    // A start so late that the session would end past 2038: the latest start is named.
    CommandResult late = run_dpscope({"simulate", "-w", "-", "--start", "2147483640"});
    EXPECT_EQ(late.exit_code, 2);
    EXPECT_TRUE(late.out.empty());
    std::smatch latest;
    ASSERT_TRUE(std::regex_search(
        late.err, latest,
        std::regex("^dpscope: error: --start 2147483640: the session lasts up to ([0-9]+) s and "
                   "would end after 2038-01-19T03:14:07Z, the last time a capture's timestamps "
                   "hold; give --start from 0 to ([0-9]+)\n$")))
        << late.err;
    CommandResult fits = run_dpscope({"simulate", "-w", "-", "--start", latest[2].str()});
    EXPECT_EQ(fits.exit_code, 0) << fits.err;
}

TEST(CliTest, SimulateStartDatesTheCapture) {
    TempFile file("start.pcap");
    CommandResult r =
        run_dpscope({"simulate", "-w", file.path, "--start", "2000000000.5", "--cycles", "5"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    OpenResult opened = open_source(file.path, InputFormat::Auto, profibus_protocol());
    ASSERT_TRUE(opened) << opened.error();
    Record record;
    ASSERT_TRUE(opened.value()->next(record));
    EXPECT_GE(record.time_ns, 2'000'000'000'500'000'000);
    EXPECT_LT(record.time_ns, 2'000'000'001'000'000'000);
}

TEST(CliTest, SimulateTwoSlavesAtOneAddressIsAUsageError) {
    CommandResult r =
        run_dpscope({"simulate", "-w", "-", "--slave", "3:1", "--slave", "4:2", "--slave", "3:2"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(r.out.empty());
    EXPECT_EQ(r.err,
              "dpscope: error: --slave 3:1 and --slave 3:2 both give address 3: one slave per "
              "address\n");
}

TEST(CliTest, SimulateUnwritableOutputNamesIt) {
    TempFile blocker("plain-file");
    test::write_file(blocker.path, {0x00});
    const std::string path = blocker.path + "/out.pcap";
    CommandResult r = run_dpscope({"simulate", "-w", path, "--cycles", "1"});
    EXPECT_EQ(r.exit_code, 4);
    EXPECT_NE(r.err.find("dpscope: error: " + path + ": cannot open for writing"),
              std::string::npos)
        << r.err;
    CommandResult report = run_dpscope({"report", "-w", path, "samples/ppo2.pcap"});
    EXPECT_EQ(report.exit_code, 4);
    EXPECT_NE(report.err.find("dpscope: error: " + path + ": cannot open for writing"),
              std::string::npos)
        << report.err;
}

TEST(CliTest, SimulateWriteErrorExitsFour) {
    CommandResult r = run_dpscope({"simulate", "-w", "/dev/full", "--cycles", "5"});
    EXPECT_EQ(r.exit_code, 4);
    EXPECT_NE(r.err.find("dpscope: error: /dev/full: write failed"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace dpscope

namespace dpscope {
namespace {

// The FC protocol through the whole pipeline: FcDecoder, FcTracker, the report's FC sections.
TEST(CliTest, FcCaptureIsTrackedAndReported) {
    std::vector<std::uint8_t> bytes;
    for (const std::vector<std::uint8_t>& telegram :
         {test::fc_parameter(1, 1, 414), test::fc_parameter(1, 1, 414, 0, 1500, 0x0607),
          test::fc_parameter(1, 14, 302, 0, 60000), test::fc_parameter(1, 7, 302, 0, 2, 0x0607),
          test::fc_parameter(1, 1, 415), test::fc_process(2), test::fc_process(2, 0x0607)})
        bytes.insert(bytes.end(), telegram.begin(), telegram.end());
    const std::string path = test::temp_path("fc_capture.raw");
    test::write_file(path, bytes);

    CommandResult decode = run_dpscope({"decode", "--bus", "fc", path});
    EXPECT_EQ(decode.exit_code, 0) << decode.err;
    EXPECT_NE(decode.out.find("[note fc_command_rejected]"), std::string::npos) << decode.out;
    EXPECT_NE(decode.out.find("[error fc_no_response]"), std::string::npos) << decode.out;

    CommandResult report = run_dpscope({"report", "--bus", "fc", "-T", "json", path});
    EXPECT_EQ(report.exit_code, 1) << report.err;  // fc_no_response is an error
    EXPECT_NE(report.out.find("\"bus\":\"fc\""), std::string::npos) << report.out;
    EXPECT_NE(report.out.find("\"fault_text\":\"Upper or lower limit is exceeded\""),
              std::string::npos);
    EXPECT_NE(report.out.find("\"fc_stacked_request\""), std::string::npos);
    EXPECT_EQ(report.out.find("\"stacked_request\""), std::string::npos)
        << "only the FC kinds are listed";

    CommandResult filtered = run_dpscope({"report", "--bus", "fc", "--station", "9", path});
    EXPECT_NE(filtered.err.find("--station 9: no drive 9 in the capture"), std::string::npos)
        << filtered.err;
}

TEST(CliTest, Vlt2000CaptureIsReportedPerDrive) {
    // Drive 01: a read answered, a read unanswered; drive 02: a control telegram answered. Each
    // telegram's first 19 characters, then its checksum (the sum of offsets 1..18, mod 100).
    std::string capture;
    for (const std::string head :
         {"<01R@@@@0102+000000", "<01RGH@@0102+001501", "<01R@@@@0999+000000",
          "<02COGD@0000+000000", "<02CGHK@0000+000000"}) {
        unsigned sum = 0;
        for (std::size_t i = 1; i < head.size(); ++i)
            sum += static_cast<unsigned char>(head[i]);
        capture += fmt::format("{}{:02}>", head, sum % 100);
    }
    const std::string path = test::temp_path("vlt2000_capture.raw");
    test::write_file(path, std::vector<std::uint8_t>(capture.begin(), capture.end()));

    CommandResult report =
        run_dpscope({"report", "--input-format", "raw", "--bus", "vlt2000", path});
    EXPECT_EQ(report.exit_code, 1) << report.err;  // vlt2000_no_response is an error
    EXPECT_NE(report.out.find("\nDrive 01 (VLT 2000)\n"), std::string::npos) << report.out;
    EXPECT_NE(report.out.find("\nDrive 02 (VLT 2000)\n"), std::string::npos) << report.out;
    EXPECT_NE(report.out.find("Checks:  time-outs not judged (no timestamps), checksums checked"),
              std::string::npos)
        << report.out;

    CommandResult json =
        run_dpscope({"report", "--input-format", "raw", "--bus", "vlt2000", "--vlt2000-checksum",
                     "ignore", "--station", "2", "--station", "7", "-T", "json", path});
    EXPECT_EQ(json.exit_code, 0) << json.err;  // drive 02 is clean
    EXPECT_NE(json.out.find("\"vlt2000_checksum\":\"ignore\""), std::string::npos) << json.out;
    EXPECT_NE(json.out.find("\"address\":2,"), std::string::npos) << json.out;
    EXPECT_EQ(json.out.find("\"address\":1,"), std::string::npos) << json.out;
    EXPECT_NE(json.err.find("--station 7: no drive 7 in the capture"), std::string::npos)
        << json.err;
    EXPECT_EQ(json.err.find("--station 2"), std::string::npos) << json.err;
}

}  // namespace
}  // namespace dpscope
