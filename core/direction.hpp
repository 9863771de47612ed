// Which way a telegram goes: a request from the master, or a response from the slave. Shared by
// every protocol and by the parameter-channel engine, which knows no protocol.
#pragma once

#include <cstdint>
#include <string_view>

namespace dpscope {

enum class Direction : std::uint8_t { Request, Response };
// "request", "response"
constexpr std::string_view direction_name(Direction direction) noexcept {
    return direction == Direction::Request ? "request" : "response";
}

}  // namespace dpscope
