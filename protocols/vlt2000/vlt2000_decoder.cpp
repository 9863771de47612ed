#include "protocols/vlt2000/vlt2000_decoder.hpp"

#include <algorithm>

#include "core/byte_word.hpp"
#include "protocols/vlt2000/vlt2000_codes.hpp"
#include "protocols/vlt2000/vlt2000_framing_rules.hpp"

namespace dpscope {

namespace {

constexpr bool is_digit(std::uint8_t c) noexcept { return c >= '0' && c <= '9'; }

// The first of bytes[from, to) that vlt2000_char_valid() refuses, or `to`: eight characters a
// step (core/byte_word.hpp: a byte below 0x20, 0x7F or above), then the step that holds one byte
// by byte.
std::size_t first_invalid_char(Bytes bytes, std::size_t from, std::size_t to) noexcept {
    using namespace byte_word;
    std::size_t i = from;
    for (; i + 8 <= to; i += 8) {
        const std::uint64_t w = load(bytes.data() + i);
        if ((any_high(w) | any_below(w, 0x20) | any_equal(w, 0x7F)) != 0) break;
    }
    for (; i < to; ++i)
        if (!vlt2000_char_valid(bytes[i])) return i;
    return to;
}

// The number `count` digits from `at` spell, or nullopt (with a problem at the first character
// that is no digit). Only the characters present are read.
std::optional<std::uint32_t> digits_at(Bytes bytes, std::size_t at, std::size_t count,
                                       ProblemList& problems) noexcept {
    std::uint32_t value = 0;
    for (std::size_t i = at; i < at + count; ++i) {
        if (!is_digit(bytes[i])) {
            problems.add(ProblemKind::Vlt2000FieldInvalid, i, 0, bytes[i]);
            return std::nullopt;
        }
        value = value * 10 + (bytes[i] - '0');
    }
    return value;
}

}  // namespace

void parse_vlt2000(Bytes bytes, Vlt2000Telegram& v, bool check_checksum) noexcept {
    ProblemList& problems = v.problems;
    if (bytes.empty()) {
        problems.add(ProblemKind::EmptyRecord, 0);
        return;
    }
    if (bytes[0] != kVlt2000Start) {
        problems.add(ProblemKind::BadStartDelimiter, 0, kVlt2000Start, bytes[0]);
        return;
    }
    const std::size_t size = std::min(bytes.size(), kVlt2000TelegramSize);
    v.complete = bytes.size() >= kVlt2000TelegramSize;
    if (!v.complete) {
        problems.add(ProblemKind::Truncated, bytes.size(), kVlt2000TelegramSize,
                     static_cast<std::uint32_t>(bytes.size()));
    }
    // Every character between '<' and '>' is printable ASCII: the framer takes no other (a
    // control character or a byte above 0x7E means the line broke), and neither does a record
    // from elsewhere (a capture file) pass unremarked. The first one that is not is reported; the
    // fields are still read.
    if (const std::size_t end = std::min(size, kVlt2000StopAt); end > 1) {
        if (const std::size_t i = first_invalid_char(bytes, 1, end); i < end)
            problems.add(ProblemKind::Vlt2000CharacterInvalid, i, 0, bytes[i]);
    }
    // Fields are read as far as the characters go; a field cut short is left unset.
    const auto has = [&](std::size_t at, std::size_t count) { return at + count <= size; };

    if (has(kVlt2000AddressAt, 2)) {
        if (auto address = digits_at(bytes, kVlt2000AddressAt, 2, problems)) {
            v.address = static_cast<std::uint8_t>(*address);
            v.broadcast = v.address == 0;
        }
    }
    if (has(kVlt2000LetterAt, 1)) {
        v.letter_char = bytes[kVlt2000LetterAt];
        v.letter = vlt2000_letter_of(v.letter_char);
        if (v.letter == Vlt2000Letter::Unknown)
            problems.add(ProblemKind::Vlt2000LetterUnknown, kVlt2000LetterAt, 0, v.letter_char);
    }
    if (has(kVlt2000WordAt, 4)) {
        // The low nibble of each character, byte 5 first (bits 3..0); the high nibble is
        // ignored, as the drive does. 'P' (0x50) keeps its group on the VLT 3000.
        for (unsigned group = 0; group < 4; ++group) {
            const std::uint8_t c = bytes[kVlt2000WordAt + group];
            v.word |= static_cast<std::uint16_t>((c & 0x0Fu) << (4 * group));
            if (c == 'P') v.word_keep |= static_cast<std::uint8_t>(1u << group);
        }
        v.has_word = true;
    }
    if (has(kVlt2000ParameterAt, 4)) {
        if (auto parameter = digits_at(bytes, kVlt2000ParameterAt, 4, problems)) {
            v.parameter = static_cast<std::uint16_t>(*parameter);
            v.has_parameter = true;
        }
    }
    if (has(kVlt2000SignAt, 1)) v.negative = bytes[kVlt2000SignAt] == '-';
    if (has(kVlt2000DecimalsAt, 1)) {
        const std::uint8_t d = bytes[kVlt2000DecimalsAt];
        if (is_digit(d)) {
            v.has_decimals = true;
            v.decimals = static_cast<std::uint8_t>(d - '0');
            v.failed = v.decimals == kVlt2000FailedDecimals;
        } else {
            problems.add(ProblemKind::Vlt2000FieldInvalid, kVlt2000DecimalsAt, 0, d);
        }
    }
    if (v.letter == Vlt2000Letter::ReadIndex && has(kVlt2000SignAt, 6)) {
        // Bytes 13-18 hold the index (a reply may carry the value there instead; VLT 3000: "x,y"
        // for a two-dimensional index). Shown as sent; a number when it is digits.
        v.index = bytes.subspan(kVlt2000SignAt, 6);
        std::uint32_t number = 0;
        bool digits = true;
        for (std::size_t i = 0; i < v.index.size(); ++i) {
            const std::uint8_t c = v.index[i];
            if (is_digit(c))
                number = number * 10 + (c - '0');
            else if (!(i == 0 && (c == '+' || c == ' ')))
                digits = false;
        }
        v.has_index_number = digits;
        v.index_number = number;
    }
    if (has(kVlt2000ValueAt, 5)) {
        if (v.failed) {
            // The value carries no value: bytes 17-18 may hold the reason code (VLT 3000).
            if (is_digit(bytes[kVlt2000ReasonAt]) && is_digit(bytes[kVlt2000ReasonAt + 1])) {
                v.has_reason = true;
                v.reason = static_cast<std::uint8_t>((bytes[kVlt2000ReasonAt] - '0') * 10 +
                                                     (bytes[kVlt2000ReasonAt + 1] - '0'));
            }
        } else if (v.letter == Vlt2000Letter::ReadIndex) {
            // The index ("x,y" on the VLT 3000), or in a reply perhaps the value: read as a value
            // where it is digits, no complaint where it is not.
            std::uint32_t digits = 0;
            bool all = true;
            for (std::size_t i = kVlt2000ValueAt; i < kVlt2000ValueAt + 5; ++i) {
                all = all && is_digit(bytes[i]);
                digits = digits * 10 + (is_digit(bytes[i]) ? bytes[i] - '0' : 0);
            }
            v.has_value = all;
            v.digits = all ? digits : 0;
        } else if (auto digits = digits_at(bytes, kVlt2000ValueAt, 5, problems)) {
            v.digits = *digits;
            v.has_value = true;
        }
    }
    if (has(kVlt2000ChecksumAt, 2)) {
        const std::uint8_t hi = bytes[kVlt2000ChecksumAt];
        const std::uint8_t lo = bytes[kVlt2000ChecksumAt + 1];
        v.checksum_computed = vlt2000_checksum_of(bytes);
        if (hi == '?' && lo == '?') {
            v.checksum_disabled = true;
        } else if (auto sent = digits_at(bytes, kVlt2000ChecksumAt, 2, problems)) {
            v.has_checksum = true;
            v.checksum = static_cast<std::uint8_t>(*sent);
            v.checksum_ok = v.checksum == v.checksum_computed;
            if (!v.checksum_ok && check_checksum)
                problems.add(ProblemKind::Vlt2000ChecksumMismatch, kVlt2000ChecksumAt,
                             v.checksum_computed, v.checksum);
        }
    }
    if (has(kVlt2000StopAt, 1) && bytes[kVlt2000StopAt] != kVlt2000Stop)
        problems.add(ProblemKind::BadEndDelimiter, kVlt2000StopAt, kVlt2000Stop,
                     bytes[kVlt2000StopAt]);
    if (bytes.size() > kVlt2000TelegramSize)
        problems.add(ProblemKind::TrailingBytes, kVlt2000TelegramSize, 0,
                     static_cast<std::uint32_t>(bytes.size() - kVlt2000TelegramSize));
}

Vlt2000Decoder::Vlt2000Decoder(Vlt2000DecoderOptions options) noexcept : options_(options) {
    t_.protocol = Protocol::Vlt2000;
    t_.naming = options_.naming.get();
}

Direction Vlt2000Decoder::direction_of(const Vlt2000Telegram& v) const noexcept {
    if (v.failed) return Direction::Response;
    if (!pending_.valid) return Direction::Request;
    if (v.address != pending_.address || v.letter_char != pending_.letter_char)
        return Direction::Request;
    const Bytes bytes = t_.bytes;
    if (bytes.size() == kVlt2000TelegramSize &&
        std::equal(bytes.begin(), bytes.end(), pending_.bytes.begin()))
        return Direction::Request;
    if (t_.time_ns != kNoTime && pending_.time_ns != kNoTime &&
        t_.time_ns - pending_.time_ns > options_.response_window_ns)
        return Direction::Request;
    return Direction::Response;
}

const DecodedTelegram& Vlt2000Decoder::decode(Bytes bytes, std::int64_t time_ns,
                                              std::uint64_t frame) {
    t_.frame = frame;
    t_.time_ns = time_ns;
    t_.bytes = bytes;
    t_.request_frame = 0;
    Vlt2000Telegram& v = t_.vlt2000;
    v.reset();
    parse_vlt2000(bytes, v, options_.check_checksum);

    // Without an address the telegram takes no part in the handshake.
    const bool addressed = bytes.size() >= 3 && bytes[0] == kVlt2000Start &&
                           is_digit(bytes[kVlt2000AddressAt]) &&
                           is_digit(bytes[kVlt2000AddressAt + 1]);
    t_.has_roles = addressed;
    t_.master = 0;
    t_.slave = v.address;
    t_.direction = addressed ? direction_of(v) : Direction::Request;
    if (!addressed) return t_;

    // A reply to I carries the element's value in bytes 13-19, as a reply to R does (dpscope's
    // reading: the VLT 2000's I reply is not documented): no index.
    if (t_.direction == Direction::Response && v.letter == Vlt2000Letter::ReadIndex) {
        v.index = Bytes();
        v.has_index_number = false;
        v.index_number = 0;
    }
    // A command that is whole and wrong only in its checksum may still be answered: the error
    // may be the tap's alone (docs/decisions.md). Cut short or with a field that is no number, a
    // drive drops it: the next telegram is no reply to it.
    const bool answerable =
        v.complete && v.letter != Vlt2000Letter::Unknown &&
        std::none_of(v.problems.begin(), v.problems.end(), [](const Problem& p) {
            return p.kind != ProblemKind::Vlt2000ChecksumMismatch &&
                   problem_severity(p.kind) == Severity::Error;
        });
    if (t_.direction == Direction::Response) {
        // A failed reply from another address answers nothing pending here.
        if (pending_.valid && v.address == pending_.address) {
            t_.request_frame = pending_.frame;
            pending_.valid = false;
        }
    } else if (!answerable) {
        pending_.valid = false;
    } else {
        pending_.valid = true;
        pending_.frame = frame;
        pending_.time_ns = time_ns;
        pending_.address = v.address;
        pending_.letter_char = v.letter_char;
        std::copy_n(bytes.begin(), kVlt2000TelegramSize, pending_.bytes.begin());
    }
    return t_;
}

}  // namespace dpscope
