// Feeds a Danfoss FC protocol byte stream to a StreamFramer over fc_framing_rules() in chunks
// whose sizes the input chooses, with line gaps where it says, then finishes, and checks every
// record the framer hands out (fuzz/support/framer_check.hpp: offsets contiguous, telegrams +
// skipped bytes == bytes fed, each telegram judged again by the rules alone, lengths FC has).
// Nothing is decoded (the decoder has its own target, fuzz_fc_decoder), so a run costs little
// more than the framing itself. Input: 2 bytes of chunk and gap choices, then the stream.
#include <cstddef>
#include <cstdint>

#include "fuzz/support/framer_check.hpp"
#include "protocols/fc/fc_framing_rules.hpp"

namespace {

// LGE + 2 bytes: a process block (LGE 6) or a parameter/text block (LGE 10..255).
bool fc_length_ok(std::size_t length) { return length == 8 || (length >= 12 && length <= 257); }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    dpscope::fuzz::run_framer_check(data, size, dpscope::fc_framing_rules(), &fc_length_ok);
    return 0;
}
