// dpscope params: what the drive parameter databases hold (the shipped ones and --params files),
// family by family: each parameter's number as the family writes it, name, unit, conversion
// index, type, elements and source.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/common_options.hpp"
#include "formats/field_writers.hpp"
#include "formats/json_writer.hpp"
#include "formats/output.hpp"

namespace dpscope::cli {

namespace {

struct ParamsCommand {
    std::string family;
    std::string pattern;
    std::string format = "text";
    std::vector<std::string> params;
    std::vector<std::string> conversions;
};

// The rows of a family that PATTERN selects.
std::vector<const ParameterRow*> selected_rows(const ParameterFamily& family,
                                               std::string_view pattern) {
    std::vector<const ParameterRow*> rows;
    for (const ParameterRow& row : family.rows)
        if (matches_pattern(family, row, pattern)) rows.push_back(&row);
    return rows;
}

std::string conversion_text(const ParameterRow& row) {
    return row.conversion ? std::to_string(*row.conversion) : std::string("-");
}

struct Listed {
    const ParameterFamily* family;
    std::vector<const ParameterRow*> rows;
};

// Text: a heading per family, then a table with aligned columns and the documents cited.
void write_text(Output& out, const std::vector<Listed>& listed) {
    auto& b = out.buffer();
    bool first = true;
    for (const Listed& l : listed) {
        const ParameterFamily& family = *l.family;
        if (!first) b.push_back('\n');
        first = false;
        fmt::format_to(std::back_inserter(b), "{}: {}: {} of {} parameters{}\n", family.id,
                       family.title, l.rows.size(), family.rows.size(),
                       family.numbering == PnuNumbering::Group
                           ? ", numbered by group (16-13 is PNU 1613)"
                           : "");
        std::size_t pnu_width = 3, name_width = 4, unit_width = 4, type_width = 4;
        for (const ParameterRow* row : l.rows) {
            pnu_width = std::max(pnu_width, family.format_pnu(row->pnu).size());
            name_width = std::max(name_width, row->name.size());
            unit_width = std::max(unit_width, row->unit.empty() ? 1 : row->unit.size());
            type_width = std::max(type_width, parameter_type_name(row->type).size());
        }
        fmt::format_to(std::back_inserter(b),
                       "  {:<{}}  {:<{}}  {:<{}}  {:>10}  {:<{}}  {:>8}  {}\n", "PNU", pnu_width,
                       "name", name_width, "unit", unit_width, "conversion", "type", type_width,
                       "elements", "source");
        std::vector<std::uint32_t> cited;
        for (const ParameterRow* row : l.rows) {
            // Names and units are UTF-8: pad by the bytes they lack, which is right for ASCII and
            // close for the rest (a unit such as "°C").
            fmt::format_to(std::back_inserter(b),
                           "  {:<{}}  {:<{}}  {:<{}}  {:>10}  {:<{}}  {:>8}  {}\n",
                           family.format_pnu(row->pnu), pnu_width, row->name, name_width,
                           row->unit.empty() ? "-" : row->unit, unit_width, conversion_text(*row),
                           parameter_type_name(row->type), type_width, row->elements, row->source);
            if (std::find(cited.begin(), cited.end(), row->source_index) == cited.end())
                cited.push_back(row->source_index);
        }
        std::sort(cited.begin(), cited.end());
        if (!cited.empty()) b.append(std::string_view("  sources:\n"));
        for (std::uint32_t index : cited) {
            const ParameterSource& source = family.sources[index];
            fmt::format_to(std::back_inserter(b), "    {} = {}\n", source.key, source.text);
        }
    }
}

void write_json(Output& out, const std::vector<Listed>& listed) {
    JsonWriter w(out.buffer());
    w.begin_object();
    w.key("families").begin_array();
    for (const Listed& l : listed) {
        const ParameterFamily& family = *l.family;
        w.begin_object();
        w.key("family").string(family.id);
        w.key("title").string(family.title);
        w.key("numbering").string(family.numbering == PnuNumbering::Group ? "group" : "plain");
        w.key("parameters").begin_array();
        for (const ParameterRow* row : l.rows) {
            w.begin_object();
            w.key("pnu").integer(row->pnu);
            w.key("pnu_shown").string(family.format_pnu(row->pnu));
            w.key("name").string(row->name);
            w.key("unit");
            optional_string(w, row->unit);
            w.key("conversion")
                .optional_integer(row->conversion.has_value(), row->conversion.value_or(0));
            w.key("type").string(parameter_type_name(row->type));
            w.key("elements").integer(row->elements);
            w.key("source").string(row->source);
            w.key("source_document").string(family.sources[row->source_index].text);
            w.end_object();
        }
        w.end_array();
        w.end_object();
    }
    w.end_array();
    w.end_object();
    out.put('\n');
}

void write_csv(Output& out, const std::vector<Listed>& listed) {
    auto& b = out.buffer();
    b.append(std::string_view(
        "family,pnu,pnu_shown,name,unit,conversion,type,elements,source,source_document\n"));
    for (const Listed& l : listed) {
        const ParameterFamily& family = *l.family;
        for (const ParameterRow* row : l.rows) {
            fmt::format_to(std::back_inserter(b), "{},{},{},", family.id, row->pnu,
                           family.format_pnu(row->pnu));
            csv_quoted(b, row->name);
            b.push_back(',');
            csv_quoted(b, row->unit);
            fmt::format_to(std::back_inserter(b), ",{},{},{},",
                           row->conversion ? std::to_string(*row->conversion) : std::string(),
                           parameter_type_name(row->type), row->elements);
            csv_quoted(b, row->source);
            b.push_back(',');
            csv_quoted(b, family.sources[row->source_index].text);
            b.push_back('\n');
        }
    }
}

int run_params(const ParamsCommand& command) {
    std::shared_ptr<const ParameterDatabase> database = load_parameter_databases(command.params, command.conversions);
    std::vector<std::string> ids;
    for (const ParameterFamily& family : database->families())
        ids.push_back(family.id);
    std::sort(ids.begin(), ids.end());
    if (!command.family.empty() && !database->family(command.family)) {
        print_error(fmt::format(
            "--family {}: no database of that family is loaded ({})", command.family,
            ids.empty() ? std::string("none is") : fmt::format("{}", fmt::join(ids, ", "))));
        return kExitUsage;
    }
    std::vector<Listed> listed;
    for (const std::string& id : ids) {
        if (!command.family.empty() && id != command.family) continue;
        const ParameterFamily& family = *database->family(id);
        std::vector<const ParameterRow*> rows = selected_rows(family, command.pattern);
        if (!rows.empty() || command.pattern.empty()) listed.push_back({&family, std::move(rows)});
    }
    if (listed.empty() && !command.pattern.empty())
        print_warning(fmt::format("no parameter matches '{}'{}", command.pattern,
                                  command.family.empty()
                                      ? std::string()
                                      : fmt::format(" in the family {}", command.family)));
    Output out(stdout);
    if (command.format == "json")
        write_json(out, listed);
    else if (command.format == "csv")
        write_csv(out, listed);
    else
        write_text(out, listed);
    if (!out.flush()) {
        print_error(
            fmt::format("cannot write the list to standard output: {}", std::strerror(errno)));
        return kExitOutputError;
    }
    return kExitOk;
}

}  // namespace

void add_params_command(CLI::App& app, int& exit_code) {
    auto command = std::make_shared<ParamsCommand>();
    CLI::App* sub = app.add_subcommand(
        "params",
        "List what the drive parameter databases hold (docs/parameters.md): per family, each "
        "parameter's number as the family writes it (16-13 for PNU 1613 of the FC series), name, "
        "unit, conversion index, type, elements and source. The shipped databases are compiled "
        "in; --params adds files.");
    sub->add_option("pattern", command->pattern,
                    "List only parameters whose number (16-13 or 1613) or name holds PATTERN, "
                    "without regard to case")
        ->type_name("PATTERN");
    sub->add_option("--family", command->family,
                    "List only this family (fc, vlt5000, vlt2000, af600, profidrive, or one a --params file "
                    "defines)")
        ->type_name("NAME");
    sub->add_option("-T,--format", command->format,
                    "Output format: text (a table per family, with the documents cited), json, "
                    "csv (one row a parameter)")
        ->check(CLI::IsMember({"text", "json", "csv"}))
        ->default_str("text");
    add_params_option(*sub, command->params, command->conversions);
    sub->footer(std::string(kExitCodeHelp));
    sub->callback([command, &exit_code] { exit_code = run_params(*command); });
}

}  // namespace dpscope::cli
