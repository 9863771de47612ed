#include "core/protocol_lane.hpp"

#include <fmt/format.h>

#include "core/counted.hpp"

namespace dpscope {

std::vector<std::string> early_response_warning(std::uint64_t early, std::uint32_t baud,
                                                std::uint32_t bits) {
    if (early == 0) return {};
    return {fmt::format(
        "{} began before {} command could have ended at {} baud ({} bits a byte): the "
        "line was faster; the drives' response times are counted from the commands' last "
        "bytes at that rate (0 for these); give the line's rate with --baud",
        counted(early, "response", "responses"), early == 1 ? "its" : "their", baud, bits)};
}

}  // namespace dpscope
