// Time as every layer passes it: nanoseconds since the epoch in a std::int64_t, with kNoTime
// when a telegram's time is not known (raw byte streams, hex lines without a timestamp). Kept
// apart from the DP decoder so that capture sources and writers need no protocol knowledge.
#pragma once

#include <cstdint>
#include <limits>

namespace dpscope {

inline constexpr std::int64_t kNoTime = std::numeric_limits<std::int64_t>::min();

}  // namespace dpscope
