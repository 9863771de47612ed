// Seeds of fuzz_capture_file: every sample capture (pcap, pcapng, raw, hex dumps, terminal and
// VLT 2000 text logs) behind the choice byte, cut to the target's max_len, once with the format
// and bus found from the content (choice 0x00) and once with both forced as `--input-format` and
// `--bus` would. The special inputs (a truncated pcap, pcapng files with two interfaces or an
// overflowing if_tsoffset, timestamp overflows in logs) stay in fuzz/corpus/fuzz_capture_file/ as
// regression-* files, which merging never removes.
#include <algorithm>
#include <string>
#include <string_view>

#include "seed_writer.hpp"

namespace dpscope::fuzz {

namespace {

constexpr std::size_t kMaxLen = 1024;  // fuzz/CMakeLists.txt

// The choice byte (fuzz/fuzz_capture_file.cpp): format in bits 0-2, bus in bits 3-4.
std::uint8_t forced_choice(std::string_view name) {
    std::uint8_t format = 3;  // raw
    if (name.ends_with(".pcap")) format = 1;
    if (name.ends_with(".pcapng")) format = 2;
    if (name.ends_with(".hex") || name.ends_with(".hexdump") || name.ends_with(".xxd") ||
        name.ends_with(".log"))
        format = 4;
    std::uint8_t bus = 1;  // PROFIBUS DP
    if (name.starts_with("fc")) bus = 2;
    if (name.starts_with("vlt2000")) bus = 3;
    if (name.ends_with(".txt")) format = 5;
    return static_cast<std::uint8_t>(format | bus << 3);
}

}  // namespace

void make_seeds_fuzz_capture_file(SeedWriter& writer) {
    for (const char* sample : {"bus-health.pcap",
                               "dpv1.pcap",
                               "faults.pcap",
                               "fc-clean.pcap",
                               "fc-examples.hex",
                               "fc.pcap",
                               "ge.pcap",
                               "midstream.pcap",
                               "ppo1.pcap",
                               "ppo2.pcap",
                               "ppo3.pcap",
                               "ppo4.pcap",
                               "ppo5.pcapng",
                               "profidrive.pcap",
                               "serial.hexdump",
                               "serial.raw",
                               "serial.xxd",
                               "terminal.log",
                               "timeouts.pcap",
                               "truncated.pcap",
                               "user0.pcap",
                               "vlt2000-clean.pcap",
                               "vlt2000-examples.txt",
                               "vlt2000.pcap"}) {
        const std::vector<std::uint8_t> bytes = writer.read(std::string("samples/") + sample);
        for (std::uint8_t choice : {std::uint8_t{0}, forced_choice(sample)}) {
            std::vector<std::uint8_t> seed = {choice};
            seed.insert(
                seed.end(), bytes.begin(),
                bytes.begin() + static_cast<std::ptrdiff_t>(std::min(bytes.size(), kMaxLen - 1)));
            writer.add(std::string(choice == 0 ? "auto-" : "forced-") + sample, seed);
        }
    }
}

}  // namespace dpscope::fuzz
