// Reading the GSD files a run is given: --gsd FILE or ADDR=FILE (repeatable), --gsd-dir DIR
// (every *.gsd / *.gs? file in it, the language variants), the Wireshark plugin's folder.
// The text is parsed by protocols/profibus/gsd/gsd_file.hpp.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/result.hpp"
#include "protocols/profibus/gsd/gsd_library.hpp"

namespace dpscope {

// One --gsd: a file, and the address it is forced on (ADDR=FILE) or none (matched by ident).
struct GsdFileSpec {
    std::optional<std::uint8_t> station;
    std::string path;
};

// "FILE" or "ADDR=FILE" (ADDR 0 to 126); an error names the value.
Result<GsdFileSpec> parse_gsd_file_spec(const std::string& text);

// Whether a file name is a GSD's: it ends in ".gsd" or ".gs" and one more letter (".gse",
// ".gsg", ".gsf", ... the language variants), in any case.
bool is_gsd_file_name(std::string_view name) noexcept;

struct LoadedGsdFiles {
    std::shared_ptr<GsdLibrary> library;  // null when no file was given
    // A broken file ("FILE:LINE: what", left out), a second file with an ident already known, a
    // folder without GSD files: said on standard error, the run goes on.
    std::vector<std::string> warnings;
};

// Reads and parses the files and folders. A file or folder that cannot be read at all is an
// error (the command line names something that is not there); a file that does not parse is a
// warning and is left out. A folder's files are read in name order.
Result<LoadedGsdFiles> load_gsd_files(std::span<const GsdFileSpec> files,
                                      std::span<const std::string> folders);

}  // namespace dpscope
