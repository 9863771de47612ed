// `dpscope sniff --config FILE`: the options of a command from a file, for a service
// (dpscope-sniff@.service reads /etc/dpscope/NAME.conf). The format (docs/service.md):
//
//   # comment lines and blank lines are skipped
//   interface = /dev/ttyUSB0        # not a comment: a value is the rest of its line
//   baud = 1500000
//   stats = true                    # a flag: true/false, yes/no, on/off, 1/0; or the key alone
//   trigger = health.event == "station_lost"
//   trigger = dpscope.finding == "stacked_request"   # a repeatable option, once per line
//   mqtt-segment = "line 3"         # double quotes keep blanks; \" and \\ inside them
//
// A key is an option's long name without "--". The file's options come before the command
// line's: an option the command line gives too is taken from the command line (a repeatable one
// gets both).
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"

namespace dpscope::cli {

struct ConfigEntry {
    std::string key;
    std::string value;
    bool has_value = false;  // "key = value"; false for "key" alone
    unsigned line = 0;
};

// The entries of a config file's text; `file` names it in messages ("FILE:LINE: ...").
Result<std::vector<ConfigEntry>> parse_config_text(std::string_view text, std::string_view file);

// The arguments the entries stand for, for `command` (a subcommand): "--key=value" or "--key",
// leaving out what `command_line` (the arguments after the subcommand's name) gives itself.
// Unknown keys, a flag with a value that is no truth value and an option without its value are
// errors naming the file and line.
Result<std::vector<std::string>> config_arguments(const std::vector<ConfigEntry>& entries,
                                                  const CLI::App& command,
                                                  const std::vector<std::string>& command_line,
                                                  std::string_view file);

// Where an option came from, for a message about its value: "--baud" -> "FILE:LINE".
struct ConfigOrigin {
    std::string option;  // "--baud"
    std::string where;   // "/etc/dpscope/line3.conf:4"
};

// argv with `SUBCOMMAND ... --config FILE ...` expanded: the file's arguments right after the
// subcommand's name, `--config FILE` left out. `origins` gets where each option came from.
// Unchanged when no --config is given.
Result<std::vector<std::string>> expand_config_option(const std::vector<std::string>& argv,
                                                      const CLI::App& app,
                                                      std::vector<ConfigOrigin>& origins);

}  // namespace dpscope::cli
