#include "capture/gsd_files.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "core/text_encoding.hpp"

namespace dpscope {

Result<GsdFileSpec> parse_gsd_file_spec(const std::string& text) {
    GsdFileSpec spec;
    const std::size_t eq = text.find('=');
    if (eq != std::string::npos && eq > 0 &&
        std::all_of(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(eq),
                    [](char c) { return c >= '0' && c <= '9'; })) {
        unsigned station = 0;
        auto [end, ec] = std::from_chars(text.data(), text.data() + eq, station);
        if (ec != std::errc() || end != text.data() + eq || station > 126)
            return Error{fmt::format("--gsd {}: the address must be from 0 to 126", text)};
        spec.station = static_cast<std::uint8_t>(station);
        spec.path = text.substr(eq + 1);
    } else {
        spec.path = text;
    }
    if (spec.path.empty()) return Error{fmt::format("--gsd {}: no file named", text)};
    return spec;
}

bool is_gsd_file_name(std::string_view name) noexcept {
    if (name.size() < 5) return false;
    std::string_view ext = name.substr(name.size() - 4);
    if (ext[0] != '.' || ascii_lower(ext[1]) != 'g' || ascii_lower(ext[2]) != 's') return false;
    const char last = ascii_lower(ext[3]);
    return last >= 'a' && last <= 'z';
}

namespace {

Result<std::string> read_whole_file(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        return Error{
            fmt::format("{}: is a folder, not a GSD file (--gsd-dir reads a folder)", path)};
    std::ifstream in(path, std::ios::binary);
    if (!in) return Error{fmt::format("{}: cannot open: {}", path, std::strerror(errno))};
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) return Error{fmt::format("{}: read error", path)};
    return bytes;
}

// Parses one file into the library; a file that does not parse is a warning.
void add_file(const std::string& path, std::optional<std::uint8_t> station,
              const std::string& bytes, LoadedGsdFiles& loaded) {
    Result<GsdDevice> device = parse_gsd(bytes, path);
    if (!device) {
        loaded.warnings.push_back(fmt::format("{} (GSD file left out)", device.error()));
        return;
    }
    const GsdDevice* shadowed = nullptr;
    const std::optional<std::uint16_t> ident = device->ident_number;
    const std::size_t index = loaded.library->add(std::move(*device), &shadowed);
    if (shadowed)
        loaded.warnings.push_back(fmt::format(
            "{}: Ident_Number 0x{:04X} is also {}'s, which describes the slaves with it{}", path,
            *ident, shadowed->file, station ? "" : " (give ADDR=FILE to use this one)"));
    if (station) loaded.library->force(*station, index);
}

}  // namespace

Result<LoadedGsdFiles> load_gsd_files(std::span<const GsdFileSpec> files,
                                      std::span<const std::string> folders) {
    LoadedGsdFiles loaded;
    if (files.empty() && folders.empty()) return loaded;
    loaded.library = std::make_shared<GsdLibrary>();
    // Files forced on an address first: a file named twice keeps its first role.
    for (const GsdFileSpec& spec : files) {
        Result<std::string> bytes = read_whole_file(spec.path);
        if (!bytes) return Error{fmt::format("--gsd {}", bytes.error())};
        add_file(spec.path, spec.station, *bytes, loaded);
    }
    for (const std::string& folder : folders) {
        std::error_code ec;
        std::filesystem::directory_iterator it(folder, ec);
        if (ec)
            return Error{
                fmt::format("--gsd-dir {}: cannot read the folder: {}", folder, ec.message())};
        std::vector<std::string> names;
        for (; it != std::filesystem::directory_iterator(); it.increment(ec)) {
            if (ec) break;
            std::error_code type_ec;
            if (!it->is_regular_file(type_ec)) continue;
            if (is_gsd_file_name(it->path().filename().string()))
                names.push_back(it->path().string());
        }
        if (ec)
            return Error{
                fmt::format("--gsd-dir {}: cannot read the folder: {}", folder, ec.message())};
        std::sort(names.begin(), names.end());
        if (names.empty())
            loaded.warnings.push_back(
                fmt::format("--gsd-dir {}: no GSD file (*.gsd, *.gse, *.gsg, ...) in it", folder));
        for (const std::string& name : names) {
            Result<std::string> bytes = read_whole_file(name);
            if (!bytes) {
                loaded.warnings.push_back(fmt::format("{} (GSD file left out)", bytes.error()));
                continue;
            }
            add_file(name, std::nullopt, *bytes, loaded);
        }
    }
    return loaded;
}

}  // namespace dpscope
