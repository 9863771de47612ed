#include "cli/config_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <optional>

#include "cli/small_file.hpp"

namespace dpscope::cli {

namespace {

// A config file is a few dozen lines; a larger one is no config file.
constexpr std::size_t kMaxConfigFileBytes = 1024 * 1024;

bool is_key_character(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-';
}

// true/false for a flag's value; nullopt for anything else.
std::optional<bool> truth_value(std::string_view text) {
    std::string lower;
    for (char c : text)
        lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (lower == "true" || lower == "yes" || lower == "on" || lower == "1") return true;
    if (lower == "false" || lower == "no" || lower == "off" || lower == "0") return false;
    return std::nullopt;
}

// The option of `command` that `argument` (an argument of the command line) names, or null.
const CLI::Option* option_named(const CLI::App& command, std::string_view argument) {
    if (argument.size() < 2 || argument[0] != '-' || argument == "--") return nullptr;
    std::string name(argument);
    if (const std::size_t equals = name.find('='); equals != std::string::npos) name.resize(equals);
    // -w5 style: a short option with its value attached.
    if (name[1] != '-' && name.size() > 2) name.resize(2);
    return command.get_option_no_throw(name);
}

}  // namespace

Result<std::vector<ConfigEntry>> parse_config_text(std::string_view text, std::string_view file) {
    std::vector<ConfigEntry> entries;
    unsigned number = 0;
    for (const std::string_view line : settings_lines(text)) {
        ++number;
        if (line.empty() || line.front() == '#') continue;
        ConfigEntry entry;
        entry.line = number;
        std::size_t key_end = 0;
        while (key_end < line.size() && is_key_character(line[key_end]))
            ++key_end;
        entry.key = std::string(line.substr(0, key_end));
        std::string_view rest = trimmed(line.substr(key_end));
        if (entry.key.empty() || entry.key.front() == '-' || (!rest.empty() && rest.front() != '='))
            return Error{fmt::format(
                "{}:{}: expected KEY = VALUE, KEY being an option's long name without \"--\" "
                "(as in baud = 1500000), not '{}'",
                file, number, line)};
        if (!rest.empty()) {
            entry.has_value = true;
            std::string_view value = trimmed(rest.substr(1));
            if (!value.empty() && value.front() == '"') {
                std::string unquoted;
                std::size_t i = 1;
                bool closed = false;
                for (; i < value.size(); ++i) {
                    if (value[i] == '\\' && i + 1 < value.size() &&
                        (value[i + 1] == '"' || value[i + 1] == '\\')) {
                        unquoted += value[++i];
                    } else if (value[i] == '"') {
                        closed = true;
                        break;
                    } else {
                        unquoted += value[i];
                    }
                }
                if (!closed || i + 1 != value.size())
                    return Error{fmt::format(
                        "{}:{}: the value of {} {}", file, number, entry.key,
                        closed ? "goes on after its closing quote" : "has no closing quote")};
                entry.value = std::move(unquoted);
            } else {
                entry.value = std::string(value);
            }
        }
        entries.push_back(std::move(entry));
    }
    return entries;
}

Result<std::vector<std::string>> config_arguments(const std::vector<ConfigEntry>& entries,
                                                  const CLI::App& command,
                                                  const std::vector<std::string>& command_line,
                                                  std::string_view file) {
    std::vector<const CLI::Option*> given;
    for (const std::string& argument : command_line)
        if (const CLI::Option* option = option_named(command, argument)) given.push_back(option);
    std::vector<std::string> arguments;
    for (const ConfigEntry& entry : entries) {
        const std::string name = "--" + entry.key;
        const CLI::Option* option = command.get_option_no_throw(name);
        if (entry.key == "config")
            return Error{fmt::format("{}:{}: a config file cannot name another", file, entry.line)};
        if (!option || option->get_lnames().empty() ||
            std::find(option->get_lnames().begin(), option->get_lnames().end(), entry.key) ==
                option->get_lnames().end())
            return Error{fmt::format("{}:{}: {} has no option {} (see dpscope {} --help)", file,
                                     entry.line, command.get_name(), name, command.get_name())};
        const bool flag = option->get_expected_max() == 0;  // add_flag: expected(0)
        const bool repeatable = option->get_expected_max() > 1;
        if (!repeatable && std::find(given.begin(), given.end(), option) != given.end())
            continue;  // the command line says it
        if (flag) {
            std::optional<bool> on = entry.has_value ? truth_value(entry.value) : true;
            if (!on)
                return Error{fmt::format(
                    "{}:{}: {} is a flag: give true or false (yes/no, on/off, 1/0), not '{}'", file,
                    entry.line, entry.key, entry.value)};
            if (*on) arguments.push_back(name);
            continue;
        }
        if (!entry.has_value)
            return Error{fmt::format("{}:{}: {} needs a value ({} = VALUE)", file, entry.line,
                                     entry.key, entry.key)};
        arguments.push_back(name + "=" + entry.value);
    }
    return arguments;
}

Result<std::vector<std::string>> expand_config_option(const std::vector<std::string>& argv,
                                                      const CLI::App& app,
                                                      std::vector<ConfigOrigin>& origins) {
    if (argv.size() < 2) return argv;
    const CLI::App* command = nullptr;
    try {
        command = app.get_subcommand(argv[1]);
    } catch (const CLI::OptionNotFound&) {
        return argv;
    }
    if (!command || !command->get_option_no_throw("--config")) return argv;
    std::vector<std::string> rest;
    std::string file;
    bool found = false;
    for (std::size_t i = 2; i < argv.size(); ++i) {
        const std::string& a = argv[i];
        if (a == "--") {
            rest.insert(rest.end(), argv.begin() + static_cast<std::ptrdiff_t>(i), argv.end());
            break;
        }
        if (a == "--config" || a.starts_with("--config=")) {
            if (found) return Error{"--config: given 2 times; give it once"};
            found = true;
            if (a == "--config") {
                if (i + 1 >= argv.size()) return Error{"--config: give the config FILE"};
                file = argv[++i];
            } else {
                file = a.substr(9);
            }
            continue;
        }
        rest.push_back(a);
    }
    if (!found) return argv;
    Result<std::string> text =
        read_small_file(file, kMaxConfigFileBytes, "--config", "a file of KEY = VALUE lines");
    if (!text) return Error{text.error()};
    Result<std::vector<ConfigEntry>> entries = parse_config_text(*text, file);
    if (!entries) return Error{entries.error()};
    Result<std::vector<std::string>> arguments = config_arguments(*entries, *command, rest, file);
    if (!arguments) return Error{arguments.error()};
    for (const ConfigEntry& entry : *entries)
        origins.push_back({"--" + entry.key, fmt::format("{}:{}", file, entry.line)});
    std::vector<std::string> expanded = {argv[0], argv[1]};
    expanded.insert(expanded.end(), arguments->begin(), arguments->end());
    expanded.insert(expanded.end(), rest.begin(), rest.end());
    return expanded;
}

}  // namespace dpscope::cli
