// A settings file read whole: the health thresholds, parameter databases, sniff's config file
// and MQTT credentials are small regular files, and nothing else is read as one.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"

namespace dpscope::cli {

// The whole of a regular file of at most `max_bytes` (a device, FIFO or directory is refused
// before anything is read); the error is "OPTION FILE: why" (OPTION "--health-config"), naming
// `what` the file must be ("a parameter database").
Result<std::string> read_small_file(const std::string& path, std::size_t max_bytes,
                                    std::string_view option, std::string_view what);

// A settings file's lines, each without its line end and trimmed (spaces, tabs and a CR at either
// end); line N of the file is element N - 1, so messages can number it.
std::vector<std::string_view> settings_lines(std::string_view text);
// `text` without spaces, tabs and CRs at either end.
std::string_view trimmed(std::string_view text) noexcept;

}  // namespace dpscope::cli
