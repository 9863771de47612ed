// Arbitrary text through the hex-log line parser, the strict hex parser and the timestamp parser.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "capture/hex_log.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::string_view text(reinterpret_cast<const char*>(data), size);
    std::vector<std::uint8_t> bytes;
    std::size_t start = 0;
    while (start <= text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string_view::npos) end = text.size();
        dpscope::parse_hex_log_line(text.substr(start, end - start), bytes);
        start = end + 1;
    }
    (void)dpscope::parse_hex_bytes(text);
    std::size_t space = text.find(' ');
    dpscope::parse_timestamp(text.substr(0, space), space == std::string_view::npos
                                                        ? std::string_view{}
                                                        : text.substr(space + 1));
    return 0;
}
