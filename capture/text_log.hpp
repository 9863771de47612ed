// A text log of VLT 2000 telegrams: the 22-character ASCII telegrams ('<' ... '>',
// protocols/vlt2000/vlt2000_telegram.hpp) as engineers copy them from a terminal, one or more a
// line, or a raw dump of them without line breaks (one long line).
//
// Only the telegrams are data: on a line, a '<' starts a telegram that must be followed by 20
// printable ASCII characters and '>' on the same line; whatever else is on the line (a time
// stamp, "TX:"/"RX:", spaces, a CR) is ignored. A leading time stamp, before the line's first '<',
// gives the time of the line's first telegram (later ones on the line have none), in the forms a
// hex log takes (capture/hex_log.hpp): epoch seconds, a time of day, an ISO date and time,
// optionally in brackets; all UTC.
//
// A '<' that starts no telegram (the line or the input ends first, a character that is no
// printable ASCII, no '>' as the 22nd character) is reported with its line and column, its
// characters are skipped up to the next '<' among them, and the reading goes on. Each telegram
// found is handed to the protocol's framer alone (the framer still judges its checksum), so no
// telegram is made of characters from either side of ignored text.
//
// The reading is streamed: memory stays bounded (a telegram, and 64 characters of a line's
// leading text for the time stamp), whatever the length of a line.
#pragma once

#include <cstdio>
#include <memory>
#include <string>
#include <string_view>

#include "capture/telegram_source.hpp"
#include "core/framing_rules.hpp"

namespace dpscope {

// Leading text of a line kept to find its time stamp.
inline constexpr std::size_t kTextLogPrefixChars = 64;

// Takes ownership of `file`. `rules` (the VLT 2000 framing) must outlive the source.
std::unique_ptr<TelegramSource> make_text_source(FILE* file, std::string name,
                                                 const FramingRules& rules);

// The same over a copy of `text` (VLT 2000 telegrams typed on the command line, one argument a
// line); `line_word` is what messages call a line ("argument").
OpenResult make_memory_text_source(std::string name, std::string_view text,
                                   const FramingRules& rules, std::string line_word);

}  // namespace dpscope
