// Seeds of fuzz_fc_decoder: single telegrams of every FC sample (pcap files, the hex
// examples) and of simulated FC sessions (one per FC fault), one of each kind (size and first 5
// bytes: address byte and PKE), behind headers choosing PNU bits, time and a context command.
#include <array>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "layer_seeds.hpp"

namespace dpscope::fuzz {

void make_seeds_fuzz_fc_decoder(SeedWriter& writer) {
    // Headers (the target's file says what each bit chooses).
    const std::vector<std::array<std::uint8_t, 2>> headers = {
        {0x00, 0x00}, {0x08, 0x10}, {0x09, 0x21}, {0x12, 0x03},
        {0x1C, 0x0F}, {0x22, 0x00}, {0x3C, 0x01}};
    std::set<std::vector<std::uint8_t>> seen;
    for (const char* sample : {"fc-clean.pcap", "fc.pcap", "fc-examples.hex"})
        add_single_telegrams(writer, sample, sample_telegrams(writer, sample, fc_protocol()),
                             headers, 5, seen);
    const std::vector<Telegrams> sessions = simulated_sessions(Protocol::Fc, {}, 200);
    for (std::size_t i = 0; i < sessions.size(); ++i)
        add_single_telegrams(writer, "simulated-" + std::to_string(i), sessions[i], headers, 5,
                             seen);
}

}  // namespace dpscope::fuzz
