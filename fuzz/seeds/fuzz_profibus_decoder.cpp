// Seeds of fuzz_profibus_decoder: single telegrams of every PROFIBUS sample (pcap, pcapng, the
// raw stream) and of simulated sessions (one per fault the simulator injects on PROFIBUS, with
// PPO 1, 2, 4, 5, ge, profidrive and DP-V1 slaves), one of each kind (size and first 12 bytes),
// behind headers choosing dialects and contexts (Chk_Cfg, Set_Prm DP-V1, PROFIdrive Write, the
// request before: none, Data_Exchange, DP-V1 Read, Slave_Diag, Get_Cfg, Set_Prm, itself).
#include <array>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "layer_seeds.hpp"

namespace dpscope::fuzz {

void make_seeds_fuzz_profibus_decoder(SeedWriter& writer) {
    // Headers (the target's file says what each bit chooses).
    const std::vector<std::array<std::uint8_t, 2>> headers = {
        {0x00, 0x00}, {0x3C, 0x01}, {0x5E, 0x22}, {0x61, 0x15},
        {0x85, 0x02}, {0xD9, 0x2D}, {0xF2, 0x43}};
    std::set<std::vector<std::uint8_t>> seen;
    for (const char* sample :
         {"bus-health.pcap", "dpv1.pcap", "faults.pcap", "ge.pcap", "midstream.pcap", "ppo1.pcap",
          "ppo2.pcap", "ppo3.pcap", "ppo4.pcap", "ppo5.pcapng", "profidrive.pcap", "timeouts.pcap",
          "truncated.pcap", "user0.pcap", "serial.raw"})
        add_single_telegrams(writer, sample,
                             sample_telegrams(writer, sample, profibus_protocol()), headers, 12,
                             seen);
    const std::vector<Telegrams> sessions = simulated_sessions(
        Protocol::ProfibusDp, {"3:1", "4:2:profidrive:dpv1", "5:5:ge", "6:4:dpv1"}, 200);
    for (std::size_t i = 0; i < sessions.size(); ++i)
        add_single_telegrams(writer, "simulated-" + std::to_string(i), sessions[i], headers, 12,
                             seen);
}

}  // namespace dpscope::fuzz
