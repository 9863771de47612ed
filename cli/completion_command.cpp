// dpscope completion bash|zsh: a shell completion script made from the command-line definition
// itself (issue 32), so that it cannot drift from the options: the subcommands, each one's
// options, and the values of an option that takes one of a set. The sets are those the options
// check (CLI11's IsMember, as --help shows them: -T, --bus, --input-format, ...) and, for the
// options that check their values otherwise, the catalogues they check against: --dialect (the
// dialects), --fault (the simulator's fault kinds), --drive (the shipped databases' families).
// Any other option's value, and a positional, completes as a file name.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "cli/commands.hpp"
#include "cli/common_options.hpp"
#include "core/code_tables.hpp"
#include "drives/shipped_databases.hpp"
#include "simulator/fault_kind.hpp"

namespace dpscope::cli {
namespace {

struct CompletedOption {
    std::vector<std::string> names;   // "-T", "--format"
    bool takes_value = false;         // a flag takes none
    std::vector<std::string> values;  // empty: a file name
};

struct CompletedCommand {
    std::string name;
    std::vector<CompletedOption> options;
};

// The values inside "{a,b,c}" of an option's type name ("TEXT:{text,json}=text"), as CLI11's
// IsMember describes its set; none when there is no set.
std::vector<std::string> set_values(const std::string& type_name) {
    std::vector<std::string> values;
    const std::size_t open = type_name.find('{');
    const std::size_t close = type_name.find('}', open);
    if (open == std::string::npos || close == std::string::npos) return values;
    const std::string_view inside(type_name.data() + open + 1, close - open - 1);
    std::size_t start = 0;
    while (start <= inside.size()) {
        const std::size_t comma = std::min(inside.find(',', start), inside.size());
        if (comma > start) values.emplace_back(inside.substr(start, comma - start));
        start = comma + 1;
    }
    return values;
}

// The catalogue an option checks its values against where that is not a CLI11 set.
std::vector<std::string> catalogue_values(const std::string& long_name) {
    std::vector<std::string> values;
    if (long_name == "dialect") {
        for (Dialect dialect : kDialects)
            values.emplace_back(dialect_name(dialect));
    } else if (long_name == "fault") {
        for (std::size_t i = 0; i < kFaultKindCount; ++i)
            values.emplace_back(fault_kind_name(static_cast<FaultKind>(i)));
    } else if (long_name == "drive") {
        for (const ShippedDatabase& database : shipped_databases()) {
            std::string_view file = database.file;  // "drives/databases/fc.params"
            file.remove_prefix(file.rfind('/') + 1);
            values.emplace_back(file.substr(0, file.find('.')));
        }
    }
    return values;
}

CompletedCommand command_of(const CLI::App& app, std::string name) {
    CompletedCommand command{std::move(name), {}};
    for (const CLI::Option* option : app.get_options()) {
        if (option->get_positional() && option->get_lnames().empty() &&
            option->get_snames().empty())
            continue;  // a positional: a file name
        CompletedOption completed;
        for (const std::string& s : option->get_snames())
            completed.names.push_back("-" + s);
        for (const std::string& l : option->get_lnames())
            completed.names.push_back("--" + l);
        if (completed.names.empty()) continue;
        completed.takes_value = option->get_items_expected_max() != 0;  // a flag: 0
        if (completed.takes_value) {
            completed.values = set_values(option->get_type_name());
            if (completed.values.empty() && !option->get_lnames().empty())
                completed.values = catalogue_values(option->get_lnames().front());
        }
        command.options.push_back(std::move(completed));
    }
    return command;
}

std::vector<CompletedCommand> commands_of(const CLI::App& app) {
    std::vector<CompletedCommand> commands;
    commands.push_back(command_of(app, ""));
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
        commands.push_back(command_of(*sub, sub->get_name()));
    return commands;
}

std::string joined(const std::vector<std::string>& words) {
    std::string text;
    for (const std::string& word : words) {
        if (!text.empty()) text += ' ';
        text += word;
    }
    return text;
}

// The bash script: the first word that is not an option is the subcommand (dpscope's own options
// take no value); in a subcommand, the word after an option that takes a value completes from the
// option's set, or as a file; a word starting with '-' from the options; any other as a file.
std::string bash_script(const std::vector<CompletedCommand>& commands) {
    std::vector<std::string> subcommands;
    for (const CompletedCommand& command : commands)
        if (!command.name.empty()) subcommands.push_back(command.name);
    const auto alternatives = [](const std::vector<std::string>& names) {
        std::string text;
        for (const std::string& n : names)
            text += (text.empty() ? "" : "|") + n;
        return text;
    };
    std::string cases;
    for (const CompletedCommand& command : commands) {
        std::vector<std::string> option_words;
        std::string value_cases;
        std::vector<std::string> file_options;
        for (const CompletedOption& option : command.options) {
            option_words.insert(option_words.end(), option.names.begin(), option.names.end());
            if (!option.takes_value) continue;
            if (option.values.empty())
                file_options.push_back(alternatives(option.names));
            else
                value_cases += fmt::format(
                    "            {}) COMPREPLY=($(compgen -W '{}' -- \"$cur\")); return ;;\n",
                    alternatives(option.names), joined(option.values));
        }
        if (!file_options.empty())
            value_cases += fmt::format("            {}) _dpscope_files; return ;;\n",
                                       alternatives(file_options));
        if (command.name.empty()) {  // dpscope's own options and the subcommands
            cases +=
                fmt::format("    '')\n        COMPREPLY=($(compgen -W '{} {}' -- \"$cur\")) ;;\n",
                            joined(option_words), joined(subcommands));
            continue;
        }
        cases += fmt::format(
            "    {})\n        case $prev in\n{}        esac\n"
            "        if [[ $cur == -* ]]; then\n"
            "            COMPREPLY=($(compgen -W '{}' -- \"$cur\"))\n"
            "        else\n            _dpscope_files\n        fi ;;\n",
            command.name, value_cases, joined(option_words));
    }
    return fmt::format(
        "# bash completion for dpscope. Written by `dpscope completion bash` from dpscope's own\n"
        "# command-line definition: subcommands, options, and the values of -T, --bus, --dialect,\n"
        "# --fault and the other options that take one of a set.\n"
        "_dpscope_files() {{\n"
        "    compopt -o filenames 2>/dev/null\n"
        "    COMPREPLY=($(compgen -f -- \"$cur\"))\n"
        "}}\n"
        "_dpscope() {{\n"
        "    local cur=${{COMP_WORDS[COMP_CWORD]}} prev=${{COMP_WORDS[COMP_CWORD-1]}}\n"
        "    local sub='' i\n"
        "    for ((i = 1; i < COMP_CWORD; i++)); do\n"
        "        case ${{COMP_WORDS[i]}} in\n"
        "            -*) ;;\n"
        "            *) sub=${{COMP_WORDS[i]}}; break ;;\n"
        "        esac\n"
        "    done\n"
        "    case $sub in\n"
        "{}"
        "    esac\n"
        "}}\n"
        "complete -F _dpscope dpscope\n",
        cases);
}

// zsh runs the bash script through its bash-completion layer (bashcompinit): the same words.
// zsh loads the file as the body of the function _dpscope on the first Tab, so the bash function
// gets another name, the body registers it for later Tabs, and completes this first one itself.
std::string zsh_script(const std::vector<CompletedCommand>& commands) {
    std::string bash = bash_script(commands);
    const auto rename = [&bash](std::string_view from, std::string_view to) {
        for (std::size_t at = bash.find(from); at != std::string::npos;
             at = bash.find(from, at + to.size()))
            bash.replace(at, from.size(), to);
    };
    rename("_dpscope() {", "_dpscope_bash() {");
    rename("complete -F _dpscope dpscope", "complete -F _dpscope_bash dpscope");
    return "#compdef dpscope\n"
           "# zsh completion for dpscope, written by `dpscope completion zsh`: the bash script of\n"
           "# `dpscope completion bash` through zsh's bashcompinit.\n"
           "autoload -U +X bashcompinit && bashcompinit\n" +
           bash +
           "# Loaded by the first Tab: complete it now (later ones go to _dpscope_bash directly).\n"
           "(( $+functions[_bash_complete] )) && [[ -n ${words-} ]] && "
           "_bash_complete -F _dpscope_bash\n";
}

}  // namespace

void add_completion_command(CLI::App& app, int& exit_code) {
    auto shell = std::make_shared<std::string>();
    CLI::App* sub = app.add_subcommand(
        "completion",
        "Print a shell completion script for bash or zsh, made from dpscope's own options: "
        "subcommands, options, and the values of -T, --bus, --dialect, --fault and the other "
        "options that take one of a set. The package installs both; by hand: "
        "'source <(dpscope completion bash)'.");
    sub->add_option("shell", *shell, "The shell: bash or zsh")
        ->required()
        ->check(CLI::IsMember({"bash", "zsh"}));
    sub->footer(std::string(kExitCodeHelp));
    sub->callback([shell, &app, &exit_code] {
        const std::vector<CompletedCommand> commands = commands_of(app);
        const std::string script = *shell == "zsh" ? zsh_script(commands) : bash_script(commands);
        if (std::fwrite(script.data(), 1, script.size(), stdout) != script.size() ||
            std::fflush(stdout) != 0) {
            print_error(fmt::format("cannot write the completion script to standard output: {}",
                                    std::strerror(errno)));
            exit_code = kExitOutputError;
            return;
        }
        exit_code = kExitOk;
    });
}

}  // namespace dpscope::cli
