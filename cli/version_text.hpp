// What `dpscope --version` prints: the version and the commit, the buses it decodes, the libraries
// it was built with and runs with, and the Wireshark version its dissector plugin was built
// against.
#pragma once

#include <string>

namespace dpscope::cli {

std::string version_text();

}  // namespace dpscope::cli
