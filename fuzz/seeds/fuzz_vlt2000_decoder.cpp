// Seeds of fuzz_vlt2000_decoder: single telegrams of every VLT 2000 sample (pcap files, the
// text examples) and of simulated VLT 2000 sessions (one per VLT 2000 fault), one of each kind
// (size and first 12 characters), behind headers choosing the checksum check, time and a context
// command.
#include <array>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "layer_seeds.hpp"

namespace dpscope::fuzz {

void make_seeds_fuzz_vlt2000_decoder(SeedWriter& writer) {
    // Headers (the target's file says what each bit chooses).
    const std::vector<std::array<std::uint8_t, 2>> headers = {
        {0x00, 0x00}, {0x08, 0x00}, {0x11, 0x01}, {0x1A, 0x02},
        {0x20, 0x03}, {0x2D, 0x00}, {0x38, 0x04}};
    std::set<std::vector<std::uint8_t>> seen;
    for (const char* sample : {"vlt2000-clean.pcap", "vlt2000.pcap", "vlt2000-examples.txt"})
        add_single_telegrams(writer, sample, sample_telegrams(writer, sample, vlt2000_protocol()),
                             headers, 12, seen);
    const std::vector<Telegrams> sessions = simulated_sessions(Protocol::Vlt2000, {}, 200);
    for (std::size_t i = 0; i < sessions.size(); ++i)
        add_single_telegrams(writer, "simulated-" + std::to_string(i), sessions[i], headers, 12,
                             seen);
}

}  // namespace dpscope::fuzz
