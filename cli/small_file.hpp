// A settings file read whole: the health thresholds, parameter databases, sniff's config file
// and MQTT credentials are small regular files, and nothing else is read as one.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "core/result.hpp"

namespace dpscope::cli {

// The whole of a regular file of at most `max_bytes` (a device, FIFO or directory is refused
// before anything is read); the error is "OPTION FILE: why" (OPTION "--health-config"), naming
// `what` the file must be ("a parameter database").
Result<std::string> read_small_file(const std::string& path, std::size_t max_bytes,
                                    std::string_view option, std::string_view what);

}  // namespace dpscope::cli
