// Feeds a PROFIBUS FDL byte stream to a StreamFramer over fdl_framing_rules() in chunks whose sizes
// the input chooses, with line gaps where it says, then finishes, and checks every record the
// framer hands out (fuzz/support/framer_check.hpp: offsets contiguous, telegrams + skipped bytes
// == bytes fed, each telegram judged again by the rules alone, lengths FDL has). Nothing is
// decoded (the decoder has its own target, fuzz_profibus_decoder), so a run costs little more
// than the framing itself. Input: 2 bytes of chunk and gap choices, then the stream.
#include <cstddef>
#include <cstdint>

#include "fuzz/support/framer_check.hpp"
#include "protocols/profibus/fdl_framing_rules.hpp"

namespace {

// SC (1), SD4 (3), SD1 (6), SD3 (14), SD2 (LE 3..249 + 6).
bool fdl_length_ok(std::size_t length) {
    return length == 1 || length == 3 || length == 6 || length == 14 ||
           (length >= 9 && length <= 255);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    dpscope::fuzz::run_framer_check(data, size, dpscope::fdl_framing_rules(), &fdl_length_ok);
    return 0;
}
