// Byte-stream inputs framed by the StreamFramer: raw serial dumps, hex text logs, and bytes
// already in memory.
#pragma once

#include <cstdio>
#include <memory>
#include <string>

#include "capture/telegram_source.hpp"

namespace dpscope {

// Each takes ownership of `file`.
std::unique_ptr<TelegramSource> make_raw_source(FILE* file, std::string name);
std::unique_ptr<TelegramSource> make_hex_source(FILE* file, std::string name);
std::unique_ptr<TelegramSource> make_memory_source(std::string name, Bytes bytes);

}  // namespace dpscope
