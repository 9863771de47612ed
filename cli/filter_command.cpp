// dpscope filter: the filter language (filter/display_filter.hpp, docs/filter.md) on its own:
// `dpscope filter --fields` lists the fields (as tshark -G fields lists Wireshark's), `dpscope
// filter EXPR` checks an expression (exit 2 with the column of what is wrong).
#include <fmt/format.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

#include "cli/commands.hpp"
#include "cli/common_options.hpp"
#include "core/protocol_descriptor.hpp"
#include "filter/display_filter.hpp"
#include "formats/json_writer.hpp"

namespace dpscope::cli {

namespace {

struct FilterCommand {
    std::string expression;
    bool fields = false;
    std::string format = "text";
};

// The buses a field is defined for: "all" for the common ones, else their names.
std::string buses_of(std::string_view name) {
    for (const FilterField& f : common_filter_fields())
        if (f.name == name && name != "dpscope.pnu") return "all";
    std::string buses;
    for (const ProtocolDescriptor* protocol : protocol_table())
        for (const FilterField& f : protocol->filter_fields)
            if (f.name == name)
                buses += fmt::format("{}{}", buses.empty() ? "" : ",", protocol->name);
    return buses;
}

int list_fields(const std::string& format) {
    fmt::memory_buffer out;
    if (format == "json") {
        JsonWriter w(out);
        w.begin_array();
        for (std::string_view name : filter_field_names()) {
            const std::vector<const FilterField*> fields = filter_fields_named(name);
            w.begin_object();
            w.key("name").string(name);
            w.key("type").string(fields.front()->type == FilterType::Text ? "text" : "integer");
            w.key("buses").string(buses_of(name));
            w.key("description").string(fields.front()->description);
            w.end_object();
        }
        w.end_array();
        out.push_back('\n');
    } else {
        for (std::string_view name : filter_field_names()) {
            const std::vector<const FilterField*> fields = filter_fields_named(name);
            fmt::format_to(std::back_inserter(out), "{:<30} {:<8} {:<17} {}\n", name,
                           fields.front()->type == FilterType::Text ? "text" : "integer",
                           buses_of(name), fields.front()->description);
        }
    }
    if (std::fwrite(out.data(), 1, out.size(), stdout) != out.size() || std::fflush(stdout) != 0) {
        print_error(
            fmt::format("cannot write the list to standard output: {}", std::strerror(errno)));
        return kExitOutputError;
    }
    return kExitOk;
}

int run_filter(const FilterCommand& command) {
    if (command.fields) return list_fields(command.format);
    if (command.expression.empty()) {
        print_error("dpscope filter: give an expression to check, or --fields");
        return kExitUsage;
    }
    Result<DisplayFilter> parsed = DisplayFilter::parse(command.expression);
    if (!parsed) {
        print_error(fmt::format("'{}': {}", command.expression, parsed.error()));
        return kExitUsage;
    }
    std::fputs("ok\n", stdout);
    return kExitOk;
}

}  // namespace

void add_filter_command(CLI::App& app, int& exit_code) {
    auto command = std::make_shared<FilterCommand>();
    CLI::App* sub = app.add_subcommand(
        "filter",
        "The filter language of -Y (docs/filter.md): --fields lists the fields a filter can "
        "read (the Wireshark plugin's names); an EXPR is checked, and an error names its "
        "column (exit 2).");
    sub->add_option("expression", command->expression, "A filter expression to check")
        ->type_name("EXPR");
    sub->add_flag("--fields", command->fields,
                  "List the fields: name, type (integer or text), the buses that have it, what "
                  "it holds");
    sub->add_option("-T,--format", command->format,
                    "Output format of --fields: text (a line a field) or json")
        ->check(CLI::IsMember({"text", "json"}))
        ->default_str("text");
    sub->footer(std::string(kExitCodeHelp));
    sub->callback([command, &exit_code] { exit_code = run_filter(*command); });
}

}  // namespace dpscope::cli
