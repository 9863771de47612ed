// sniff --config FILE (cli/config_file.hpp): the format, the expansion into arguments, which
// side wins, and every error naming the file and line; and the CLI end to end.
#include "cli/config_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/test_support.hpp"

namespace dpscope::cli {
namespace {

// A command shaped like sniff: a required option, flags, a repeatable option.
struct Command {
    CLI::App app{"test"};
    CLI::App* sniff = app.add_subcommand("sniff");
    std::string interface, write, config;
    unsigned baud = 0;
    bool stats = false;
    std::vector<std::string> triggers;
    Command() {
        sniff->add_option("-i,--interface", interface);
        sniff->add_option("--baud", baud);
        sniff->add_option("-w,--write", write);
        sniff->add_flag("--stats", stats);
        sniff->add_option("--trigger", triggers);
        sniff->add_option("--config", config);
    }
};

TEST(ConfigFileTest, LinesAreKeysWithValuesCommentsAndQuotes) {
    auto entries = parse_config_text(
        "# a service's capture\n"
        "\n"
        "  interface = /dev/ttyUSB0  \n"
        "stats\n"
        "trigger = dpscope.finding == \"stacked_request\" # not a comment\n"
        "write = \"  blanks kept \\\" and \\\\ \"\n"
        "baud=1500000",
        "x.conf");
    ASSERT_TRUE(entries) << entries.error();
    ASSERT_EQ(entries->size(), 5u);
    EXPECT_EQ((*entries)[0].key, "interface");
    EXPECT_EQ((*entries)[0].value, "/dev/ttyUSB0");
    EXPECT_EQ((*entries)[0].line, 3u);
    EXPECT_FALSE((*entries)[1].has_value);
    EXPECT_EQ((*entries)[2].value, "dpscope.finding == \"stacked_request\" # not a comment");
    EXPECT_EQ((*entries)[3].value, "  blanks kept \" and \\ ");
    EXPECT_EQ((*entries)[4].value, "1500000");
    EXPECT_EQ((*entries)[4].line, 7u);
}

TEST(ConfigFileTest, MalformedLinesAreNamedByFileAndLine) {
    for (const auto& [text, says] : std::vector<std::pair<std::string, std::string>>{
             {"baud 1500000", "x.conf:1: expected KEY = VALUE"},
             {"\n--baud = 5", "x.conf:2: expected KEY = VALUE"},
             {"= 5", "x.conf:1: expected KEY = VALUE"},
             {"write = \"open", "x.conf:1: the value of write has no closing quote"},
             {"write = \"a\" b", "x.conf:1: the value of write goes on after its closing quote"}}) {
        auto entries = parse_config_text(text, "x.conf");
        ASSERT_FALSE(entries) << text;
        EXPECT_NE(entries.error().find(says), std::string::npos) << entries.error();
    }
}

TEST(ConfigFileTest, TheCommandLineWinsAndRepeatableOptionsAddUp) {
    Command c;
    auto entries = parse_config_text(
        "interface = /dev/ttyUSB0\nbaud = 1500000\nstats = yes\ntrigger = a\ntrigger = b\n",
        "x.conf");
    ASSERT_TRUE(entries);
    auto arguments =
        config_arguments(*entries, *c.sniff, {"--baud=500000", "--trigger", "c"}, "x.conf");
    ASSERT_TRUE(arguments) << arguments.error();
    EXPECT_EQ(*arguments, (std::vector<std::string>{"--interface=/dev/ttyUSB0", "--stats",
                                                    "--trigger=a", "--trigger=b"}));
    // A short name on the command line is the same option.
    arguments = config_arguments(*entries, *c.sniff, {"-i", "/dev/ttyS0"}, "x.conf");
    ASSERT_TRUE(arguments);
    EXPECT_EQ(arguments->front(), "--baud=1500000");
    // A flag set false is left out.
    entries = parse_config_text("stats = off\n", "x.conf");
    arguments = config_arguments(*entries, *c.sniff, {}, "x.conf");
    ASSERT_TRUE(arguments);
    EXPECT_TRUE(arguments->empty());
}

TEST(ConfigFileTest, UnknownKeysBadFlagsAndMissingValuesAreErrors) {
    Command c;
    for (const auto& [text, says] : std::vector<std::pair<std::string, std::string>>{
             {"bauds = 5", "x.conf:1: sniff has no option --bauds (see dpscope sniff --help)"},
             {"i = /dev/ttyUSB0", "x.conf:1: sniff has no option --i"},
             {"\nstats = maybe", "x.conf:2: stats is a flag: give true or false"},
             {"baud", "x.conf:1: baud needs a value (baud = VALUE)"},
             {"config = other.conf", "x.conf:1: a config file cannot name another"}}) {
        auto entries = parse_config_text(text, "x.conf");
        ASSERT_TRUE(entries) << text;
        auto arguments = config_arguments(*entries, *c.sniff, {}, "x.conf");
        ASSERT_FALSE(arguments) << text;
        EXPECT_NE(arguments.error().find(says), std::string::npos) << arguments.error();
    }
}

TEST(ConfigFileTest, ExpansionPutsTheFileFirstAndLeavesOtherCommandsAlone) {
    Command c;
    const std::string file = test::temp_path("expand.conf");
    {
        std::ofstream out(file);
        out << "interface = /dev/ttyUSB0\nbaud = 1500000\n";
    }
    std::vector<ConfigOrigin> origins;
    auto expanded = expand_config_option({"dpscope", "sniff", "--config", file, "--baud", "9600"},
                                         c.app, origins);
    ASSERT_TRUE(expanded) << expanded.error();
    EXPECT_EQ(*expanded, (std::vector<std::string>{"dpscope", "sniff", "--interface=/dev/ttyUSB0",
                                                   "--baud", "9600"}));
    ASSERT_EQ(origins.size(), 2u);
    EXPECT_EQ(origins[1].option, "--baud");
    EXPECT_EQ(origins[1].where, file + ":2");
    expanded = expand_config_option({"dpscope", "sniff", "--config=" + file}, c.app, origins);
    ASSERT_TRUE(expanded);
    EXPECT_EQ(expanded->size(), 4u);
    // Without --config, or for a command without it: as it was.
    EXPECT_EQ(*expand_config_option({"dpscope", "sniff", "-i", "x"}, c.app, origins),
              (std::vector<std::string>{"dpscope", "sniff", "-i", "x"}));
    EXPECT_EQ(*expand_config_option({"dpscope", "--help"}, c.app, origins),
              (std::vector<std::string>{"dpscope", "--help"}));
    auto missing =
        expand_config_option({"dpscope", "sniff", "--config", file + ".none"}, c.app, origins);
    ASSERT_FALSE(missing);
    EXPECT_NE(missing.error().find("--config " + file + ".none: cannot read"), std::string::npos);
    // Only a small regular file is read: not a device that never ends, not a folder.
    for (const std::string& not_a_file : {std::string("/dev/zero"), test::source_dir()}) {
        auto refused =
            expand_config_option({"dpscope", "sniff", "--config", not_a_file}, c.app, origins);
        ASSERT_FALSE(refused) << not_a_file;
        EXPECT_NE(refused.error().find("not a regular file"), std::string::npos) << refused.error();
    }
    auto twice = expand_config_option({"dpscope", "sniff", "--config", file, "--config", file},
                                      c.app, origins);
    ASSERT_FALSE(twice);
    std::filesystem::remove(file);
}

// The real command: a value the file got wrong is named with the file and line; a good file
// gets as far as the port.
TEST(ConfigFileTest, SniffReadsItsOptionsFromTheFile) {
    const std::string file = test::temp_path("sniff.conf");
    const auto write = [&](const std::string& text) {
        std::ofstream out(file);
        out << text;
    };
    write("interface = /dev/dpscope-no-such-tty\nbaud = 1500000\nstats = true\n");
    auto run = test::run_dpscope({"sniff", "--config", file});
    EXPECT_EQ(run.exit_code, 2) << run.err;
    EXPECT_NE(run.err.find("/dev/dpscope-no-such-tty"), std::string::npos) << run.err;
    // The command line's --baud wins over the file's (which would be out of range).
    write("interface = /dev/dpscope-no-such-tty\nbaud = 1\n");
    run = test::run_dpscope({"sniff", "--config", file, "--baud", "9600"});
    EXPECT_NE(run.err.find("/dev/dpscope-no-such-tty"), std::string::npos) << run.err;
    run = test::run_dpscope({"sniff", "--config", file});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_NE(run.err.find("--baud: must be a whole number from 300 to 16000000 baud, not '1' "
                           "(set in " +
                           file + ":2)"),
              std::string::npos)
        << run.err;
    write("interface = /dev/ttyUSB0\nbaud = 1500000\nstatistics = on\n");
    run = test::run_dpscope({"sniff", "--config", file});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_NE(run.err.find(file + ":3: sniff has no option --statistics"), std::string::npos)
        << run.err;
    std::filesystem::remove(file);
}

}  // namespace
}  // namespace dpscope::cli
