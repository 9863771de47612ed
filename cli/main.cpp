// dpscope: a protocol analyzer for drive parameter channels on PROFIBUS DP.
#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <exception>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/common_options.hpp"
#include "cli/config_file.hpp"
#include "cli/parse_errors.hpp"
#include "cli/version_text.hpp"

namespace {

// Standard input, output or error closed when dpscope starts (`2>&-`): /dev/null takes its
// place, so that no file dpscope opens (a -w capture) gets descriptor 2 and messages written
// into it.
void open_missing_standard_streams() {
    for (int fd = 0; fd <= 2; ++fd) {
        if (::fcntl(fd, F_GETFD) != -1 || errno != EBADF) continue;
        const int null = ::open("/dev/null", fd == 0 ? O_RDONLY : O_WRONLY);
        if (null >= 0 && null != fd) {
            ::dup2(null, fd);
            ::close(null);
        }
    }
}

}  // namespace

int main(int argc, char** argv) {
    using namespace dpscope::cli;
    open_missing_standard_streams();
    // Wireshark runs dpscope as an extcap capture interface: its own options, not a subcommand.
    if (is_extcap_call(argc, argv)) return run_extcap(argc, argv);
    CLI::App app{
        "dpscope: decode PROFIBUS DP captures down to the drive parameter channel (PPO "
        "PCV/PKW: RC/AK, SPM, PNU, IND, PVA, PCD words), and the Danfoss FC protocol and VLT 2000 "
        "serial telegrams (--bus fc, --bus vlt2000).",
        "dpscope"};
    // The text ends with its own line end; CLI11 adds one after it.
    app.set_version_flag(
        "--version",
        [] {
            std::string text = dpscope::cli::version_text();
            text.pop_back();
            return text;
        },
        "Print the version, the commit, the buses, the libraries and the Wireshark version of "
        "the plugin, and exit");
    app.require_subcommand(1);
    // Command-line errors in dpscope's one error style; "Usage: dpscope ..." whatever argv[0].
    app.failure_message([](const CLI::App*, const CLI::Error& e) {
        return fmt::format(
            "dpscope: error: {}\nRun 'dpscope --help' or 'dpscope SUBCOMMAND "
            "--help' for the options.\n",
            parse_error_text(e));
    });
    app.footer(std::string(kExitCodeHelp) +
               "\nRun 'dpscope SUBCOMMAND --help' for the options of each subcommand."
               "\nWireshark runs dpscope as an extcap capture interface (--extcap-interfaces, "
               "--extcap-dlts, --extcap-config, --capture); 'dpscope --capture --help' explains "
               "those options.");
    // A file-size limit (ulimit -f) then fails a write like a full disk instead of killing us.
    std::signal(SIGXFSZ, SIG_IGN);
    int exit_code = kExitOk;
    add_completion_command(app, exit_code);
    add_decode_command(app, exit_code);
    add_filter_command(app, exit_code);
    add_hex_command(app, exit_code);
    add_params_command(app, exit_code);
    add_report_command(app, exit_code);
    add_simulate_command(app, exit_code);
    add_sniff_command(app, exit_code);
    add_stats_command(app, exit_code);
    // CLI11 would only say that a subcommand is required.
    if (argc > 1 && argv[1][0] != '-') {
        bool known = false;
        std::string names;
        for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
            known = known || sub->get_name() == argv[1];
            names += (names.empty() ? "" : ", ") + sub->get_name();
        }
        if (!known) {
            print_error(
                fmt::format("unknown subcommand '{}'; one of {} (see --help)", argv[1], names));
            return kExitUsage;
        }
    }
    // sniff --config FILE: the file's options go in before the command line's.
    std::vector<ConfigOrigin> origins;
    dpscope::Result<std::vector<std::string>> arguments =
        expand_config_option(std::vector<std::string>(argv, argv + argc), app, origins);
    if (!arguments) {
        print_error(arguments.error());
        return kExitUsage;
    }
    try {
        // CLI11 takes the arguments last first, without the program's name.
        std::vector<std::string> reversed(arguments->rbegin(), arguments->rend() - 1);
        app.parse(reversed);
    } catch (const CLI::ParseError& e) {
        // An option's value from the config file: the message names the file and line.
        const std::string text = parse_error_text(e);
        for (const ConfigOrigin& origin : origins) {
            const std::size_t at = text.find(origin.option);
            const std::size_t after = at + origin.option.size();
            if (e.get_exit_code() == 0 || at == std::string::npos ||
                (after < text.size() &&
                 (std::isalnum(static_cast<unsigned char>(text[after])) || text[after] == '-')))
                continue;
            print_error(fmt::format("{} (set in {})", text, origin.where));
            return kExitUsage;
        }
        int rc = app.exit(e);
        return rc == 0 ? kExitOk : kExitUsage;
    } catch (const std::exception& e) {
        print_error(e.what());
        return kExitUsage;
    }
    return exit_code;
}
