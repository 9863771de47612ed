// The subcommands. Each add_* function registers a subcommand on `app`; when the subcommand is
// chosen, its callback runs the command and stores the exit code in `exit_code`.
#pragma once

#include <CLI/CLI.hpp>

namespace dpscope::cli {

// dpscope completion bash|zsh (cli/completion_command.cpp): a script made from `app` itself (the
// subcommands registered when it runs).
void add_completion_command(CLI::App& app, int& exit_code);
void add_decode_command(CLI::App& app, int& exit_code);
void add_filter_command(CLI::App& app, int& exit_code);
void add_hex_command(CLI::App& app, int& exit_code);
void add_params_command(CLI::App& app, int& exit_code);
void add_report_command(CLI::App& app, int& exit_code);
void add_simulate_command(CLI::App& app, int& exit_code);
void add_sniff_command(CLI::App& app, int& exit_code);
void add_stats_command(CLI::App& app, int& exit_code);

// Wireshark extcap (cli/extcap_command.cpp): argv starts with an extcap option
// (--extcap-interfaces, --extcap-dlts, --extcap-config, --extcap-version..., --capture), as
// Wireshark runs the dpscope in its extcap folder; run_extcap answers and returns the exit code.
bool is_extcap_call(int argc, char** argv);
int run_extcap(int argc, char** argv);

}  // namespace dpscope::cli
