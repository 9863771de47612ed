// "1 byte", "3 bytes": a count with its noun in the right number, for messages in every layer.
#pragma once

#include <fmt/format.h>

#include <cstdint>
#include <string>
#include <string_view>

namespace dpscope {

inline std::string counted(std::uint64_t n, std::string_view singular, std::string_view plural) {
    return fmt::format("{} {}", n, n == 1 ? singular : plural);
}

}  // namespace dpscope
