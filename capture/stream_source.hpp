// Byte-stream inputs framed by the StreamFramer with a protocol's framing rules: raw serial dumps,
// hex text logs, and bytes already in memory.
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>

#include "capture/telegram_source.hpp"
#include "core/framing_rules.hpp"

namespace dpscope {

// The input a detected raw or hex source judges before it hands out anything (see FramedSource):
// the first 64 KiB of a raw stream (one read), the first 4 KiB of bytes in a hex log (a hundred
// lines or so, so that a log piped in as it is written is not held back for long).
inline constexpr std::uint64_t kJudgedRawBytes = 64 * 1024;
inline constexpr std::uint64_t kJudgedHexBytes = 4 * 1024;

// Each takes ownership of `file`. `judged`: the kind was detected, not forced, so an input that
// is mostly no telegrams is refused (Unusable) instead of decoded. `rules` (the protocol's
// framing) must outlive the source.
std::unique_ptr<TelegramSource> make_raw_source(FILE* file, std::string name, bool judged,
                                                const FramingRules& rules);
// `max_repeat_bytes`: the most bytes one "*" line of a dump may stand for (SourceOptions).
std::unique_ptr<TelegramSource> make_hex_source(FILE* file, std::string name, bool judged,
                                                const FramingRules& rules,
                                                std::uint64_t max_repeat_bytes);
// Reads what has arrived into `data`, at least one byte unless the input ended: a pipe or
// terminal is decoded as it is written (fread would wait until the whole buffer is full).
std::size_t read_available(FILE* file, std::uint8_t* data, std::size_t size);

std::unique_ptr<TelegramSource> make_memory_source(std::string name, Bytes bytes,
                                                   const FramingRules& rules);

}  // namespace dpscope
