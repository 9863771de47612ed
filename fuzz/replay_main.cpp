// dpscope_fuzz_replay TARGET PATH...: runs the fuzz target TARGET on every file named, and on every
// file of every directory named (sorted by name), without libFuzzer, the way libFuzzer runs a
// corpus. The test fuzz_corpus.TARGET runs it on fuzz/corpus/TARGET/, so every seed and every
// input that once found a defect is run in each test tree (ASan + UBSan included); the coverage
// preset uses it to count what the corpora reach.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "replay_targets.hpp"

// The custom mutators call libFuzzer's own mutator; without libFuzzer nothing mutates.
extern "C" std::size_t LLVMFuzzerMutate(std::uint8_t*, std::size_t size, std::size_t) {
    return size;
}

namespace {

namespace fs = std::filesystem;

bool read_file(const fs::path& path, std::vector<std::uint8_t>& bytes) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return false;
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    return !in.bad();
}

}  // namespace

int main(int argc, char** argv) {
    using dpscope::fuzz::kReplayTargetCount;
    using dpscope::fuzz::kReplayTargets;
    if (argc < 3) {
        std::fprintf(stderr, "usage: dpscope_fuzz_replay TARGET FILE_OR_DIRECTORY...\ntargets:");
        for (std::size_t i = 0; i < kReplayTargetCount; ++i)
            std::fprintf(stderr, " %s", kReplayTargets[i].name);
        std::fprintf(stderr, "\n");
        return 2;
    }
    const std::string_view name = argv[1];
    const auto* target =
        std::find_if(kReplayTargets, kReplayTargets + kReplayTargetCount,
                     [&](const dpscope::fuzz::ReplayTarget& t) { return name == t.name; });
    if (target == kReplayTargets + kReplayTargetCount) {
        std::fprintf(stderr, "dpscope_fuzz_replay: no fuzz target named %s\n", argv[1]);
        return 2;
    }
    std::vector<fs::path> files;
    for (int i = 2; i < argc; ++i) {
        std::error_code error;
        const fs::path path = argv[i];
        if (fs::is_directory(path, error)) {
            for (const auto& entry : fs::directory_iterator(path, error))
                if (entry.is_regular_file(error)) files.push_back(entry.path());
            if (error) {
                std::fprintf(stderr, "dpscope_fuzz_replay: %s: %s\n", argv[i],
                             error.message().c_str());
                return 2;
            }
        } else {
            files.push_back(path);
        }
    }
    std::sort(files.begin(), files.end());
    if (files.empty()) {
        std::fprintf(stderr, "dpscope_fuzz_replay: no input files\n");
        return 2;
    }
    std::vector<std::uint8_t> bytes;
    for (const auto& file : files) {
        if (!read_file(file, bytes)) {
            std::fprintf(stderr, "dpscope_fuzz_replay: cannot read %s\n", file.c_str());
            return 2;
        }
        target->one_input(bytes.data(), bytes.size());
    }
    std::printf("%s: ran %zu inputs\n", target->name, files.size());
    return 0;
}
