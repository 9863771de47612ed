// Seeds of fuzz_fc_framer: the FC samples (fc.pcap, fc-clean.pcap, fc-examples.hex, their
// telegrams back to back as one stream) and simulated FC sessions (one per FC fault), cut into
// pieces of at most 900 bytes behind chunk/gap headers.
#include <string>
#include <vector>

#include "layer_seeds.hpp"

namespace dpscope::fuzz {

void make_seeds_fuzz_fc_framer(SeedWriter& writer) {
    for (const char* sample : {"fc-clean.pcap", "fc.pcap"}) {
        const Telegrams telegrams = sample_telegrams(writer, sample, fc_protocol());
        add_stream_pieces(writer, std::string(sample), telegrams, 900);
    }
    // The hex examples, framed by dpscope's hex-log reader.
    add_stream_pieces(writer, "fc-examples.hex",
                      sample_telegrams(writer, "fc-examples.hex", fc_protocol()), 900);
    const std::vector<Telegrams> sessions = simulated_sessions(Protocol::Fc, {}, 120);
    for (std::size_t i = 0; i < sessions.size(); ++i)
        add_stream_pieces(writer, "simulated-" + std::to_string(i), sessions[i], 900);
}

}  // namespace dpscope::fuzz
