#include "cli/parse_errors.hpp"

#include <fmt/format.h>

#include <regex>

namespace dpscope::cli {

namespace {

// "TEXT:{text,verbose}" -> "one of text, verbose"; "N:1 to 9 telegrams" -> "N, 1 to 9
// telegrams"; "ADDR=TYPE" as it is.
std::string value_description(const std::string& type) {
    const std::size_t colon = type.find(':');
    if (colon == std::string::npos) return type;
    std::string rest = type.substr(colon + 1);
    if (rest.size() >= 2 && rest.front() == '{' && rest.back() == '}') {
        std::string list = rest.substr(1, rest.size() - 2);
        std::string out = "one of ";
        for (char c : list)
            out += c == ',' ? std::string(", ") : std::string(1, c);
        return out;
    }
    return type.substr(0, colon) + ", " + rest;
}

std::string comma_list(const std::string& items) {
    std::string out;
    for (char c : items)
        out += c == ',' ? std::string(", ") : std::string(1, c);
    return out;
}

}  // namespace

std::string parse_error_text(std::string_view name, std::string_view text) {
    const std::string message(text);
    std::smatch m;
    // An ExtrasError of a subcommand is named after the subcommand: known by its words.
    {
        static const std::regex extras(
            R"(^The following arguments? (?:was|were) not expected: (.*)$)");
        if (std::regex_match(message, m, extras)) {
            const std::string items = m[1].str();
            const std::string first = items.substr(0, items.find(' '));
            if (first.size() > 1 && first[0] == '-' && first[1] != '=')
                return fmt::format("unknown option {}", items);
            return fmt::format(
                "unexpected argument{} '{}': give one input FILE, and repeat an option for each "
                "of its values (--station 3 --station 5)",
                items.find(' ') == std::string::npos ? "" : "s", items);
        }
    }
    if (name == "ArgumentMismatch") {
        static const std::regex at_most(R"(^(\S+): At Most (\d+) required but received (\d+)$)");
        static const std::regex missing(R"(^(\S+): (\d+) required (.*) missing$)");
        if (std::regex_match(message, m, at_most))
            return m[2] == "1"
                       ? fmt::format("{}: given {} times; give it once", m[1].str(), m[3].str())
                       : fmt::format("{}: at most {} values, not {}", m[1].str(), m[2].str(),
                                     m[3].str());
        if (std::regex_match(message, m, missing))
            return fmt::format("{} needs a value: {}", m[1].str(), value_description(m[3].str()));
    } else if (name == "ValidationError") {
        static const std::regex member(R"(^(\S+): (.*) not in \{(.*)\}$)");
        if (std::regex_match(message, m, member))
            return fmt::format("{}: '{}' is not one of {}", m[1].str(), m[2].str(),
                               comma_list(m[3].str()));
    } else if (name == "RequiredError") {
        if (message == "A subcommand is required")
            return "give a subcommand: decode, hex, report, simulate, sniff or stats";
    } else if (name == "ConversionError") {
        static const std::regex conversion(R"(^Could not convert: (\S+) = (.*)$)");
        if (std::regex_match(message, m, conversion))
            return fmt::format("{}: cannot read '{}'", m[1].str(), m[2].str());
    }
    return message;
}

std::string parse_error_text(const CLI::Error& error) {
    return parse_error_text(error.get_name(), error.what());
}

}  // namespace dpscope::cli
