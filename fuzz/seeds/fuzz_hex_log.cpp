// Seeds of fuzz_hex_log: the hex logs and dumps among the samples and the VLT 2000 text log (cut
// to the target's max_len), and one line of each shape capture/hex_log.hpp reads: hexdump -C and
// xxd lines with their offset and ASCII columns, the repeat and closing-offset lines, "0x" and
// comma-separated bytes, a compact hex string, and every timestamp form (epoch seconds, time of
// day, ISO date and time with "T" or a space, bracketed), with errors (a bad token, an odd
// compact string).
#include <algorithm>
#include <string>

#include "seed_writer.hpp"

namespace dpscope::fuzz {

void make_seeds_fuzz_hex_log(SeedWriter& writer) {
    constexpr std::size_t kMaxLen = 4096;  // fuzz/CMakeLists.txt
    for (const char* sample : {"serial.hexdump", "serial.xxd", "terminal.log", "fc-examples.hex",
                               "vlt2000-examples.txt"}) {
        std::vector<std::uint8_t> bytes = writer.read(std::string("samples/") + sample);
        bytes.resize(std::min(bytes.size(), kMaxLen));
        writer.add(sample, bytes);
    }
    const char* const lines[][2] = {
        {"hexdump-line",
         "00000000  68 05 05 68 83 02 7d 3c  3e 46 16 e5 10 02 01 49  "
         "|h..h..}<>F.....I|\n*\n00000020\n"},
        {"xxd-line", "00000010: 6805 0568 8302 7d3c 3e46 16e5  h..h..}<>F..\n"},
        {"od-line", "0000000 68 05 05 68 83 02 7d 3c\n"},
        {"prefixed", "TX: 0x68, 0x05, 0x05, 0x68, 0x83, 0x02, 0x7D, 0x3C, 0x3E, 0x46, 0x16\n"},
        {"compact", "RX 680505688302 7d3c3e4616\n6805056883027d3c3e4616\n"},
        {"epoch", "1700000000.000125 68 05 05 68 83 02 7d 3c 3e 46 16\n"},
        {"time-of-day", "12:00:01.5 10 02 01 49 4c 16\n[12:00:01.500] E5\n"},
        {"iso-t", "2024-01-02T12:00:01.5Z 02 0e 81 10 05 00 00 00 00 00 00 04 7f 20 00 b2\n"},
        {"iso-space", "2024-01-02 12:00:01.123456789 02 06 81 04 7f 20 00 7e\n"},
        {"iso-offset", "[2024-01-02T12:00:01+02:00] 68 05 05 68\n"},
        {"errors", "68 0G 05 68 680 7\n6805056883027\n68050568830z\n"},
        {"crlf", "10 02 01 49 4c 16\r\n10 01 02 6d 70 16\r\n"},
        {"vlt2000", "<01C0000000+00000000?\?>\n<01R04I7000200+0000102056>\n"},
    };
    for (const auto& [name, text] : lines)
        writer.add(name, std::string_view(text));
}

}  // namespace dpscope::fuzz
