// dpscope_fuzz_seeds TARGET SOURCE_DIR OUT_DIR: writes the seeds of fuzz target TARGET (made by
// fuzz/seeds/TARGET.cpp from samples/ and the simulator) into OUT_DIR, which must be empty or
// absent. scripts/fuzz-seeds minimises them into fuzz/corpus/TARGET/.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>

#include "seed_targets.hpp"
#include "seed_writer.hpp"

namespace dpscope::fuzz {

std::vector<std::uint8_t> SeedWriter::read(std::string_view relative_path) const {
    const std::filesystem::path path = source_dir_ / std::filesystem::path(relative_path);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot read " + path.string());
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void SeedWriter::add(std::string_view name, std::span<const std::uint8_t> bytes) {
    const bool plain = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
               c == '-' || c == '_' || c == '.';
    });
    if (!plain) throw std::runtime_error("bad seed name '" + std::string(name) + "'");
    const std::filesystem::path path = out_dir_ / std::filesystem::path(name);
    if (std::filesystem::exists(path))
        throw std::runtime_error("seed name used twice: " + std::string(name));
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()),
              static_cast<std::streamsize>(bytes.size()));
    if (!out.flush()) throw std::runtime_error("cannot write " + path.string());
    ++written_;
}

void SeedWriter::add(std::string_view name, std::string_view text) {
    add(name, std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

}  // namespace dpscope::fuzz

int main(int argc, char** argv) {
    using dpscope::fuzz::kSeedTargetCount;
    using dpscope::fuzz::kSeedTargets;
    if (argc != 4) {
        std::fprintf(stderr, "usage: dpscope_fuzz_seeds TARGET SOURCE_DIR OUT_DIR\ntargets:");
        for (std::size_t i = 0; i < kSeedTargetCount; ++i)
            std::fprintf(stderr, " %s", kSeedTargets[i].name);
        std::fprintf(stderr, "\n");
        return 2;
    }
    const std::string_view name = argv[1];
    const auto* target =
        std::find_if(kSeedTargets, kSeedTargets + kSeedTargetCount,
                     [&](const dpscope::fuzz::SeedTarget& t) { return name == t.name; });
    if (target == kSeedTargets + kSeedTargetCount) {
        std::fprintf(stderr, "dpscope_fuzz_seeds: no seed maker for %s\n", argv[1]);
        return 2;
    }
    std::error_code error;
    std::filesystem::create_directories(argv[3], error);
    if (error || !std::filesystem::is_empty(argv[3], error)) {
        std::fprintf(stderr, "dpscope_fuzz_seeds: %s must be an empty directory\n", argv[3]);
        return 2;
    }
    try {
        dpscope::fuzz::SeedWriter writer(argv[2], argv[3]);
        target->make(writer);
        std::printf("%s: wrote %zu seeds to %s\n", target->name, writer.written(), argv[3]);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "dpscope_fuzz_seeds: %s: %s\n", argv[1], e.what());
        return 1;
    }
    return 0;
}
