#include "protocols/toybus/toybus_decoder.hpp"

#include <optional>

namespace dpscope {

namespace {

constexpr bool is_digit(std::uint8_t c) noexcept { return c >= '0' && c <= '9'; }

// The number `count` digits from `at` spell, or nullopt (a problem at the first that is none).
std::optional<std::uint32_t> digits_at(Bytes body, std::size_t at, std::size_t count,
                                       ProblemList& problems) noexcept {
    std::uint32_t value = 0;
    for (std::size_t i = at; i < at + count; ++i) {
        if (!is_digit(body[i])) {
            problems.add(ProblemKind::Vlt2000FieldInvalid, i, 0, body[i]);
            return std::nullopt;
        }
        value = value * 10 + (body[i] - '0');
    }
    return value;
}

}  // namespace

void parse_toybus(Bytes bytes, ToybusTelegram& v) noexcept {
    ProblemList& problems = v.problems;
    if (bytes.empty()) {
        problems.add(ProblemKind::EmptyRecord, 0);
        return;
    }
    v.kind = toybus_kind_of(bytes[0]);
    if (v.kind == ToybusKind::Unknown) {
        problems.add(ProblemKind::BadStartDelimiter, 0, kToybusRead, bytes[0]);
        return;
    }
    // The line without its line end.
    Bytes body = bytes;
    const bool ended = body.back() == '\n';
    if (ended) body = body.first(body.size() - 1);
    if (ended && !body.empty() && body.back() == '\r') {
        body = body.first(body.size() - 1);
        v.crlf = true;
    }
    const std::size_t want = toybus_body_size(v.kind);
    if (body.size() < want || !ended)
        problems.add(ProblemKind::Truncated, bytes.size(), static_cast<std::uint32_t>(want + 2),
                     static_cast<std::uint32_t>(bytes.size()));
    else if (body.size() > want)
        problems.add(ProblemKind::TrailingBytes, want, 0,
                     static_cast<std::uint32_t>(body.size() - want));
    for (std::size_t i = 1; i < body.size(); ++i)
        if (body[i] < 0x20 || body[i] > 0x7E) {
            problems.add(ProblemKind::Vlt2000CharacterInvalid, i, 0, body[i]);
            break;
        }
    const auto has = [&](std::size_t at, std::size_t count) { return at + count <= body.size(); };
    // A separator that is not a space is reported as a field that is no digit: no problem kind
    // says "not a space" (dpscope's catalogue is not extended for the toy).
    const auto space_at = [&](std::size_t at) {
        if (has(at, 1) && body[at] != ' ')
            problems.add(ProblemKind::Vlt2000FieldInvalid, at, ' ', body[at]);
    };
    if (has(kToybusAddressAt, 2)) {
        if (auto address = digits_at(body, kToybusAddressAt, 2, problems)) {
            v.address = static_cast<std::uint8_t>(*address);
            v.has_address = true;
            if (v.address == 0 || v.address > kToybusMaxAddress)
                problems.add(ProblemKind::AdrInvalid, kToybusAddressAt, 0, v.address);
        }
    }
    space_at(kToybusParameterAt - 1);
    if (has(kToybusParameterAt, 4)) {
        if (auto parameter = digits_at(body, kToybusParameterAt, 4, problems)) {
            v.parameter = static_cast<std::uint16_t>(*parameter);
            v.has_parameter = true;
        }
    }
    if (v.kind == ToybusKind::Read) {
        v.complete = problems.empty();
        return;
    }
    space_at(kToybusValueAt - 1);
    if (v.kind == ToybusKind::Error) {
        if (has(kToybusValueAt, 2))
            if (auto error = digits_at(body, kToybusValueAt, 2, problems)) {
                v.error = static_cast<std::uint8_t>(*error);
                v.has_error = true;
            }
    } else if (has(kToybusValueAt, 5)) {
        if (auto value = digits_at(body, kToybusValueAt, 5, problems)) {
            v.value = *value;
            v.has_value = true;
        }
    }
    v.complete = problems.empty();
}

ToybusDecoder::ToybusDecoder(ToybusDecoderOptions options) noexcept : options_(options) {
    t_.protocol = Protocol::Toybus;
}

const DecodedTelegram& ToybusDecoder::decode(Bytes bytes, std::int64_t time_ns,
                                             std::uint64_t frame) {
    t_.frame = frame;
    t_.time_ns = time_ns;
    t_.bytes = bytes;
    t_.request_frame = 0;
    ToybusTelegram& v = t_.toybus;
    v.reset();
    parse_toybus(bytes, v);

    const bool request = v.kind == ToybusKind::Read || v.kind == ToybusKind::Write;
    t_.direction =
        request || v.kind == ToybusKind::Unknown ? Direction::Request : Direction::Response;
    t_.has_roles = v.has_address;
    t_.master = 0;
    t_.slave = v.address;
    if (!v.has_address) return t_;
    if (request) {
        pending_ = Pending{v.has_parameter, frame, time_ns, v.address, v.parameter};
        return t_;
    }
    const bool in_window = time_ns == kNoTime || pending_.time_ns == kNoTime ||
                           time_ns - pending_.time_ns <= options_.response_window_ns;
    if (pending_.valid && in_window && v.address == pending_.address &&
        (!v.has_parameter || v.parameter == pending_.parameter)) {
        t_.request_frame = pending_.frame;
        pending_.valid = false;
    }
    return t_;
}

}  // namespace dpscope
