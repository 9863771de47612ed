#include "protocols/profibus/dpv1/profidrive.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

#include "protocols/profibus/dp_payload.hpp"

namespace dpscope {

namespace {

bool read_header(ByteReader& reader, ProfidriveMessage& out, ProblemList& problems) {
    if (reader.remaining() < 4) {
        report_service_data_short(reader, 4, problems);
        return false;
    }
    out.has_header = true;
    out.reference = *reader.u8();
    out.id = *reader.u8();
    out.axis = *reader.u8();
    out.count = *reader.u8();
    return true;
}

// One value block at the reader. Returns false when the block broke off (a problem is
// recorded); a block whose format has no known size takes the rest of the data.
bool read_block(ByteReader& reader, ProfidriveMessage& out, ProblemList& problems) {
    if (reader.remaining() < 2) {
        report_service_data_short(reader, 2, problems);
        return false;
    }
    ProfidriveValueBlock& block = out.blocks.emplace_back();
    block.format = *reader.u8();
    block.count = *reader.u8();
    int size = profidrive_format_size(block.format);
    block.values_offset = static_cast<std::uint16_t>(reader.offset());
    if (size < 0) {  // a reserved format: how long its values are cannot be known
        block.values = reader.rest();
        return false;
    }
    std::size_t wanted = static_cast<std::size_t>(size) * block.count;
    if (reader.remaining() < wanted) {
        report_service_data_short(reader, wanted, problems);
        block.values = reader.rest();
        return false;
    }
    block.values = *reader.bytes(wanted);
    block.complete = true;
    // Odd value byte counts are padded to keep the next block word-aligned; the last block may
    // end the data without one.
    if (wanted % 2 != 0 && reader.remaining() > 0) {
        reader.skip(1);
        block.padded = true;
    }
    return true;
}

std::uint16_t be16(Bytes b, std::size_t at) {
    return static_cast<std::uint16_t>((b[at] << 8) | b[at + 1]);
}
std::uint32_t be32(Bytes b, std::size_t at) {
    return (std::uint32_t{b[at]} << 24) | (std::uint32_t{b[at + 1]} << 16) |
           (std::uint32_t{b[at + 2]} << 8) | b[at + 3];
}

void append_string(Bytes values, std::string& out) {
    out += '"';
    for (std::uint8_t c : values) {
        if (c == '"' || c == '\\') {
            out += '\\';
            out += static_cast<char>(c);
        } else if (c >= 0x20 && c < 0x7F) {
            out += static_cast<char>(c);
        } else {
            fmt::format_to(std::back_inserter(out), "\\x{:02X}", c);
        }
    }
    out += '"';
}

// Milliseconds as h:mm:ss.mmm.
void append_clock(std::uint32_t ms, std::string& out) {
    fmt::format_to(std::back_inserter(out), "{:02}:{:02}:{:02}.{:03}", ms / 3'600'000,
                   ms / 60'000 % 60, ms / 1000 % 60, ms % 1000);
}

void append_one(std::uint8_t format, Bytes v, std::string& out) {
    auto it = std::back_inserter(out);
    switch (format) {
        case 0x01: out += v[0] ? "true" : "false"; return;
        case 0x02: fmt::format_to(it, "{}", static_cast<std::int8_t>(v[0])); return;
        case 0x03: fmt::format_to(it, "{}", static_cast<std::int16_t>(be16(v, 0))); return;
        case 0x04: fmt::format_to(it, "{}", static_cast<std::int32_t>(be32(v, 0))); return;
        case 0x05:
        case 0x41: fmt::format_to(it, "{}", v[0]); return;  // Byte, Word, Double word: unsigned
        case 0x06:
        case 0x42: fmt::format_to(it, "{}", be16(v, 0)); return;
        case 0x07:
        case 0x43: fmt::format_to(it, "{}", be32(v, 0)); return;
        case 0x08: fmt::format_to(it, "{}", std::bit_cast<float>(be32(v, 0))); return;
        case 0x21:  // N2: 0x4000 = 100 %
            fmt::format_to(it, "{:.3f} %", static_cast<std::int16_t>(be16(v, 0)) * 100.0 / 0x4000);
            return;
        case 0x22:  // N4: 0x40000000 = 100 %
            fmt::format_to(it, "{:.3f} %",
                           static_cast<std::int32_t>(be32(v, 0)) * 100.0 / 0x40000000);
            return;
        case 0x23: fmt::format_to(it, "{:016b}", be16(v, 0)); return;  // V2: bit 15 first
        case 0x0C:  // TimeOfDay: ms since midnight, days since 1984-01-01
            append_clock(be32(v, 0) & 0x0FFFFFFF, out);
            fmt::format_to(it, " day {}", be16(v, 4));
            return;
        case 0x0D:
        case 0x35:  // TimeDifference: ms, days
            fmt::format_to(it, "{} d {} ms", be16(v, 4), be32(v, 0) & 0x0FFFFFFF);
            return;
        case 0x34: append_clock(be32(v, 0) & 0x0FFFFFFF, out); return;  // time of day, no date
        case 0x36: fmt::format_to(it, "{} ms", be32(v, 0)); return;     // difference, no date
        case 0x32:  // Date: ms (2), minute, hour, day, month, year
            // Years 0-49 are 2000-2049, 50-99 are 1950-1999.
            fmt::format_to(it, "{:04}-{:02}-{:02} {:02}:{:02}:{:02}.{:03}",
                           (v[6] & 0x7F) < 50 ? 2000 + (v[6] & 0x7F) : 1900 + (v[6] & 0x7F),
                           v[5] & 0x0F, v[4] & 0x1F, v[3] & 0x1F, v[2] & 0x3F, be16(v, 0) / 1000,
                           be16(v, 0) % 1000);
            return;
        default: break;
    }
    // Any other format of known size: hex, as wide as the value.
    out += "0x";
    for (std::uint8_t b : v)
        fmt::format_to(it, "{:02X}", b);
}

}  // namespace

std::string_view profidrive_request_id_name(std::uint8_t request_id) {
    switch (request_id) {
        case profidrive::kRequestValue: return "request parameter value";
        case profidrive::kChangeValue: return "change parameter value";
        case profidrive::kChangeValueNonVolatile: return "change parameter value (non-volatile)";
        case profidrive::kRequestValueDoubleWord: return "request parameter value (double word)";
        case profidrive::kChangeValueDoubleWord: return "change parameter value (double word)";
        default: return "";
    }
}

bool profidrive_request_id_defined(std::uint8_t request_id, Dialect dialect) noexcept {
    switch (request_id) {
        case profidrive::kRequestValue:
        case profidrive::kChangeValue: return true;
        case profidrive::kChangeValueNonVolatile:
        case profidrive::kRequestValueDoubleWord:
        case profidrive::kChangeValueDoubleWord: return danfoss_family(dialect);
        default: return false;
    }
}

std::string_view profidrive_response_id_name(std::uint8_t response_id) {
    switch (response_id) {
        case 0x01: return "request parameter (+)";
        case 0x02: return "change parameter (+)";
        case 0x81: return "request parameter (-)";
        case 0x82: return "change parameter (-)";
        default: return "";
    }
}

std::string_view profidrive_attribute_name(std::uint8_t attribute) {
    switch (attribute) {
        case profidrive::kAttributeValue: return "value";
        case profidrive::kAttributeDescription: return "description";
        case profidrive::kAttributeText: return "text";
        default: return "";
    }
}

std::string_view profidrive_format_name(std::uint8_t format) {
    switch (format) {
        case 0x01: return "Boolean";
        case 0x02: return "Integer8";
        case 0x03: return "Integer16";
        case 0x04: return "Integer32";
        case 0x05: return "Unsigned8";
        case 0x06: return "Unsigned16";
        case 0x07: return "Unsigned32";
        case 0x08: return "FloatingPoint32";
        case 0x09: return "VisibleString";
        case 0x0A: return "OctetString";
        case 0x0C: return "TimeOfDay";
        case 0x0D: return "TimeDifference";
        case 0x21: return "N2";
        case 0x22: return "N4";
        case 0x23: return "V2";
        case 0x32: return "Date";
        case 0x34: return "TimeOfDay without date";
        case 0x35: return "TimeDifference with date";
        case 0x36: return "TimeDifference without date";
        case profidrive::kFormatZero: return "Zero";
        case 0x41: return "Byte";
        case 0x42: return "Word";
        case 0x43: return "Double word";
        case profidrive::kFormatError: return "Error";
        default: return "reserved";
    }
}

int profidrive_format_size(std::uint8_t format) noexcept {
    switch (format) {
        case 0x01:
        case 0x02:
        case 0x05:
        case 0x09:
        case 0x0A:
        case 0x41: return 1;
        case 0x03:
        case 0x06:
        case 0x21:
        case 0x23:
        case 0x42:
        case 0x44: return 2;
        case 0x04:
        case 0x07:
        case 0x08:
        case 0x22:
        case 0x34:
        case 0x36:
        case 0x43: return 4;
        case 0x0C:
        case 0x0D:
        case 0x35: return 6;
        case 0x32: return 7;
        case profidrive::kFormatZero: return 0;
        default: return -1;
    }
}

std::string_view profidrive_error_text(std::uint16_t error, Dialect dialect) {
    switch (error) {
        case 0x00: return "illegal or unknown parameter number";
        case 0x01: return "value cannot be changed (read-only)";
        case 0x02: return "lower or upper limit exceeded";
        case 0x03: return "invalid subindex";
        case 0x04: return "no array";
        case 0x05: return "wrong data type (wrong length)";
        case 0x06: return "only reset allowed";
        case 0x07: return "description element cannot be changed";
        case 0x09: return "no description data";
        case 0x0B: return "no operating priority (change rights)";
        case 0x0F: return "no text array";
        case 0x11: return "request not possible in the current operating state";
        case 0x14: return "illegal value (within the limits)";
        case 0x15: return "response too long (over 240 bytes)";
        case 0x16: return "illegal parameter address";
        case 0x17: return "illegal format (change)";
        case 0x18: return "number of values inconsistent (change)";
        case 0x19: return "drive object does not exist";
        default: break;
    }
    if (error < 0x65) return "reserved";
    if (danfoss_family(dialect)) {
        switch (error) {
            case 0x65: return "wrong axis";
            case 0x66: return "unknown service request";
            case 0x67: return "service not possible with multi-parameter access";
            case 0x68: return "value cannot be read from the bus";
            default: break;
        }
    }
    return "manufacturer-specific";
}

bool profidrive_response_answers(std::uint8_t response_id, std::uint8_t request_id) noexcept {
    std::uint8_t base = response_id & 0x7F;
    switch (request_id) {
        case profidrive::kRequestValue:
        case profidrive::kChangeValue: return base == request_id;
        case profidrive::kRequestValueDoubleWord:
            return base == profidrive::kRequestValue || base == request_id;
        case profidrive::kChangeValueNonVolatile:
        case profidrive::kChangeValueDoubleWord:
            return base == profidrive::kChangeValue || base == request_id;
        default: return false;
    }
}

std::uint16_t ProfidriveValueBlock::error_number() const noexcept {
    return values.size() >= 2 ? be16(values, 0) : 0;
}

std::uint16_t ProfidriveValueBlock::error_info() const noexcept {
    return values.size() >= 4 ? be16(values, 2) : 0;
}

void parse_profidrive_request(ByteReader reader, ProfidriveMessage& out,
                              ProblemList& problems) noexcept {
    out.is_response = false;
    if (!read_header(reader, out, problems)) return;
    for (std::uint8_t k = 0; k < out.count; ++k) {
        if (reader.remaining() < 6) {
            report_service_data_short(reader, 6, problems);
            return;
        }
        ProfidriveAddress& address = out.addresses.emplace_back();
        address.attribute = *reader.u8();
        address.elements = *reader.u8();
        address.pnu = *reader.u16_be();
        address.subindex = *reader.u16_be();
    }
    if (out.is_change_request()) {
        for (std::uint8_t k = 0; k < out.count; ++k)
            if (!read_block(reader, out, problems)) return;
    }
    out.trailing = static_cast<std::uint16_t>(reader.remaining());
}

void parse_profidrive_response(ByteReader reader, ProfidriveMessage& out,
                               ProblemList& problems) noexcept {
    out.is_response = true;
    if (!read_header(reader, out, problems)) return;
    for (std::uint8_t k = 0; k < out.count && !reader.empty(); ++k)
        if (!read_block(reader, out, problems)) return;
    // A positive change response is the header alone; every other response has one block per
    // parameter (a read's values, a negative response's 0x40 and 0x44 blocks).
    bool header_only = out.id == profidrive::kChangeValue ||
                       out.id == profidrive::kChangeValueNonVolatile ||
                       out.id == profidrive::kChangeValueDoubleWord;
    if (!header_only && out.blocks.size() < out.count)
        report_service_data_short(reader, 2, problems);
    out.trailing = static_cast<std::uint16_t>(reader.remaining());
}

void append_profidrive_values(const ProfidriveValueBlock& block, std::string& out) {
    int size = profidrive_format_size(block.format);
    const std::size_t start = out.size();
    auto cut_short = [&] { out += out.size() == start ? "(cut short)" : " (cut short)"; };
    if (block.is_error()) {
        if (block.values.size() < 2) {
            out += "error (number cut short)";
            return;
        }
        fmt::format_to(std::back_inserter(out), "error 0x{:02X}", block.error_number());
        if (block.has_error_info())
            fmt::format_to(std::back_inserter(out), ", info {}", block.error_info());
        return;
    }
    if (size <= 0 || block.format == 0x09 || block.format == 0x0A) {
        if (block.format == 0x09) {
            append_string(block.values, out);
        } else if (!block.values.empty()) {  // octet string, or a reserved format: the bytes
            for (std::size_t i = 0; i < block.values.size(); ++i)
                fmt::format_to(std::back_inserter(out), "{}{:02X}", i ? " " : "", block.values[i]);
        }
        if (size > 0 && !block.complete) cut_short();
        return;
    }
    auto step = static_cast<std::size_t>(size);
    for (std::size_t at = 0; at + step <= block.values.size(); at += step) {
        if (at) out += ", ";
        append_one(block.format, block.values.subspan(at, step), out);
    }
    if (!block.complete) cut_short();
}

std::size_t profidrive_value_count(const ProfidriveValueBlock& block) noexcept {
    int size = profidrive_format_size(block.format);
    if (size <= 0 || block.is_error()) return 0;
    return block.values.size() / static_cast<std::size_t>(size);
}

std::optional<ProfidriveNumber> profidrive_number(const ProfidriveValueBlock& block,
                                                  std::size_t index) noexcept {
    int size = profidrive_format_size(block.format);
    if (size <= 0 || block.is_error()) return std::nullopt;
    std::size_t at = index * static_cast<std::size_t>(size);
    if (at + static_cast<std::size_t>(size) > block.values.size()) return std::nullopt;
    Bytes v = block.values.subspan(at, static_cast<std::size_t>(size));
    ProfidriveNumber n;
    switch (block.format) {
        case 0x01: n.integer = v[0] ? 1 : 0; return n;
        case 0x02: n.integer = static_cast<std::int8_t>(v[0]); return n;
        case 0x03: n.integer = static_cast<std::int16_t>(be16(v, 0)); return n;
        case 0x04: n.integer = static_cast<std::int32_t>(be32(v, 0)); return n;
        case 0x05:
        case 0x41: n.integer = v[0]; return n;
        case 0x06:
        case 0x23:
        case 0x42: n.integer = be16(v, 0); return n;
        case 0x07:
        case 0x43: n.integer = be32(v, 0); return n;
        case 0x08: {
            auto f = std::bit_cast<float>(be32(v, 0));
            if (!std::isfinite(f)) return std::nullopt;
            n.is_real = true;
            n.single = true;
            n.real = f;
            return n;
        }
        case 0x21:
            n.is_real = true;
            n.real = static_cast<std::int16_t>(be16(v, 0)) * 100.0 / 0x4000;
            return n;
        case 0x22:
            n.is_real = true;
            n.real = static_cast<std::int32_t>(be32(v, 0)) * 100.0 / 0x40000000;
            return n;
        case 0x36: n.integer = be32(v, 0); return n;  // milliseconds
        default: return std::nullopt;
    }
}

}  // namespace dpscope
