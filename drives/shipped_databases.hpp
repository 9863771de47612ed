// The parameter databases dpscope ships (drives/databases/<family>.params), compiled in: CMake
// writes their texts into a generated source (drives/embed_databases.cmake) and rebuilds it when
// a file changes. Parsed by parse_parameter_database() like a --params file.
#pragma once

#include <span>
#include <string_view>

namespace dpscope {

struct ShippedDatabase {
    std::string_view file;  // "drives/databases/fc.params": how messages name it
    std::string_view text;
};

// Every shipped database, by file name.
std::span<const ShippedDatabase> shipped_databases() noexcept;

}  // namespace dpscope
