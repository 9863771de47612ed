// Seeds of fuzz_hex_log: the hex logs and dumps among the samples, and the VLT 2000 text log.
#include "seed_writer.hpp"

namespace dpscope::fuzz {

void make_seeds_fuzz_hex_log(SeedWriter& writer) {
    for (const char* sample : {"serial.hexdump", "serial.xxd", "terminal.log", "fc-examples.hex",
                               "vlt2000-examples.txt"}) {
        const std::vector<std::uint8_t> bytes = writer.read(std::string("samples/") + sample);
        writer.add(sample, bytes);
    }
}

}  // namespace dpscope::fuzz
