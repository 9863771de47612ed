// Seeds of fuzz_vlt2000_framer: the VLT 2000 samples (vlt2000.pcap, vlt2000-clean.pcap,
// vlt2000-examples.txt, their telegrams back to back as one stream) and simulated VLT 2000
// sessions (one per VLT 2000 fault), cut into pieces of at most 900 bytes behind chunk/gap
// headers.
#include <string>
#include <vector>

#include "layer_seeds.hpp"

namespace dpscope::fuzz {

void make_seeds_fuzz_vlt2000_framer(SeedWriter& writer) {
    for (const char* sample : {"vlt2000-clean.pcap", "vlt2000.pcap"}) {
        const Telegrams telegrams = sample_telegrams(writer, sample, vlt2000_protocol());
        add_stream_pieces(writer, std::string(sample), telegrams, 900);
    }
    // The text examples, read by dpscope's text-log reader.
    add_stream_pieces(writer, "vlt2000-examples.txt",
                      sample_telegrams(writer, "vlt2000-examples.txt", vlt2000_protocol()), 900);
    const std::vector<Telegrams> sessions = simulated_sessions(Protocol::Vlt2000, {}, 120);
    for (std::size_t i = 0; i < sessions.size(); ++i)
        add_stream_pieces(writer, "simulated-" + std::to_string(i), sessions[i], 900);
}

}  // namespace dpscope::fuzz
