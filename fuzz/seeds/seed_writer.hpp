// The seed makers: fuzz/seeds/TARGET.cpp defines `void make_seeds_TARGET(SeedWriter&)`, which
// writes the inputs that start TARGET's corpus, made from samples/ and the simulator.
// `dpscope_fuzz_seeds TARGET SOURCE_DIR OUT_DIR` runs it; scripts/fuzz-seeds minimises what it
// writes into fuzz/corpus/TARGET/.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace dpscope::fuzz {

class SeedWriter {
  public:
    SeedWriter(std::filesystem::path source_dir, std::filesystem::path out_dir)
        : source_dir_(std::move(source_dir)), out_dir_(std::move(out_dir)) {}

    // The repository's root (samples/ is below it).
    const std::filesystem::path& source_dir() const noexcept { return source_dir_; }
    // The bytes of a file below the repository's root, e.g. "samples/faults.pcap" (the run fails
    // when it cannot be read).
    std::vector<std::uint8_t> read(std::string_view relative_path) const;

    // Writes one seed as OUT_DIR/NAME (letters, digits, '-', '_', '.'); a name used twice fails.
    void add(std::string_view name, std::span<const std::uint8_t> bytes);
    void add(std::string_view name, std::string_view text);

    std::size_t written() const noexcept { return written_; }

  private:
    std::filesystem::path source_dir_;
    std::filesystem::path out_dir_;
    std::size_t written_ = 0;
};

}  // namespace dpscope::fuzz
