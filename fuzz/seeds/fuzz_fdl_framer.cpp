// Seeds of fuzz_fdl_framer: the PROFIBUS samples (every pcap/pcapng file, their telegrams
// back to back as one stream, and the raw serial stream) and simulated sessions (one per fault the
// simulator injects on PROFIBUS, DP-V1 and PROFIdrive slaves included), cut into pieces of at most
// 900 bytes behind chunk/gap headers.
#include <string>
#include <vector>

#include "layer_seeds.hpp"

namespace dpscope::fuzz {

void make_seeds_fuzz_fdl_framer(SeedWriter& writer) {
    for (const char* sample :
         {"bus-health.pcap", "dpv1.pcap", "faults.pcap", "ge.pcap", "midstream.pcap", "ppo1.pcap",
          "ppo2.pcap", "ppo3.pcap", "ppo4.pcap", "ppo5.pcapng", "profidrive.pcap", "timeouts.pcap",
          "truncated.pcap", "user0.pcap"}) {
        const Telegrams telegrams = sample_telegrams(writer, sample, profibus_protocol());
        add_stream_pieces(writer, std::string(sample), telegrams, 900);
    }
    // The raw serial stream as it is (garbage and cut telegrams included), in pieces.
    const std::vector<std::uint8_t> raw = writer.read("samples/serial.raw");
    add_stream_pieces(writer, "serial.raw", Telegrams{raw}, 900);
    const std::vector<Telegrams> sessions = simulated_sessions(
        Protocol::ProfibusDp, {"3:1", "4:2:profidrive:dpv1", "5:5:ge", "6:4:dpv1"}, 120);
    for (std::size_t i = 0; i < sessions.size(); ++i)
        add_stream_pieces(writer, "simulated-" + std::to_string(i), sessions[i], 900);
}

}  // namespace dpscope::fuzz
