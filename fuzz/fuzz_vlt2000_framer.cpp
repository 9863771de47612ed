// Feeds a VLT 2000 serial byte stream to a StreamFramer over vlt2000_framing_rules() in chunks
// whose sizes the input chooses, with line gaps where it says, then finishes, and checks every
// record the framer hands out (fuzz/support/framer_check.hpp: offsets contiguous, telegrams +
// skipped bytes == bytes fed, each telegram judged again by the rules alone, 22 characters each).
// Nothing is decoded (the decoder has its own target, fuzz_vlt2000_decoder), so a run costs
// little more than the framing itself. Input: 2 bytes of chunk and gap choices, then the stream.
#include <cstddef>
#include <cstdint>

#include "fuzz/support/framer_check.hpp"
#include "protocols/vlt2000/vlt2000_framing_rules.hpp"

namespace {

bool vlt2000_length_ok(std::size_t length) { return length == dpscope::kVlt2000TelegramSize; }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    dpscope::fuzz::run_framer_check(data, size, dpscope::vlt2000_framing_rules(),
                                    &vlt2000_length_ok);
    return 0;
}
