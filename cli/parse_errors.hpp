// CLI11's command-line errors in dpscope's words. dpscope's own checks say what is wrong and how
// to mend it ("--count: must be a whole number from 1 to ..."); CLI11's words for the errors it
// finds itself ("--read: At Most 1 required but received 2") are rewritten in the same style.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <string_view>

namespace dpscope::cli {

// The message for `error` (without "dpscope: error: "): CLI11's own wording rewritten where it
// is known, else its text as it is (dpscope's validators word theirs).
std::string parse_error_text(const CLI::Error& error);

// The same for an error's name (CLI::Error::get_name()) and text, for the tests.
std::string parse_error_text(std::string_view name, std::string_view text);

}  // namespace dpscope::cli
