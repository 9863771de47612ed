// The PROFIdrive parameter request (data of a DP-V1 Write to index 47) and parameter response
// (data of the DP-V1 Read response that fetches it). Facts and sources:
// docs/protocol/dpv1-parameter-access.md. Pure decoding; the decoder (bus_decoder.cpp) keeps
// the last request per master, slave, slot and index so a response, which carries no parameter
// numbers, is named after the request it answers.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/byte_reader.hpp"
#include "core/code_tables.hpp"
#include "core/problem.hpp"
#include "protocols/profibus/fdl.hpp"

namespace dpscope {

namespace profidrive {
// Request IDs.
inline constexpr std::uint8_t kRequestValue = 0x01;
inline constexpr std::uint8_t kChangeValue = 0x02;
inline constexpr std::uint8_t kChangeValueNonVolatile = 0x42;  // Danfoss
inline constexpr std::uint8_t kRequestValueDoubleWord = 0x51;  // Danfoss
inline constexpr std::uint8_t kChangeValueDoubleWord = 0x52;   // Danfoss
// Response IDs: the request ID (0x01 or 0x02), bit 7 set when negative.
inline constexpr std::uint8_t kNegative = 0x80;
// Attributes.
inline constexpr std::uint8_t kAttributeValue = 0x10;
inline constexpr std::uint8_t kAttributeDescription = 0x20;
inline constexpr std::uint8_t kAttributeText = 0x30;
// Formats with a meaning of their own in a value block.
inline constexpr std::uint8_t kFormatZero = 0x40;
inline constexpr std::uint8_t kFormatError = 0x44;
// The most data a parameter request or response carries (error 0x15 beyond).
inline constexpr std::size_t kMaxData = 240;
// The most elements one parameter address asks for: "quantity 1-234" [S003], what one value
// block of a response holds (240 - 4 header - 2 block header bytes of one-byte values).
inline constexpr std::uint8_t kMaxElements = 234;
}  // namespace profidrive

// "request parameter value", "change parameter value", "change parameter value
// (non-volatile)", "request parameter value (double word)", "change parameter value (double
// word)"; "" for others.
std::string_view profidrive_request_id_name(std::uint8_t request_id);
// "request parameter (+)", "change parameter (+)", "request parameter (-)", "change parameter
// (-)"; "" for others.
std::string_view profidrive_response_id_name(std::uint8_t response_id);
// Whether a request ID is one the dialect defines [S003]: 0x01 and 0x02 everywhere, Danfoss's
// 0x42, 0x51 and 0x52 on the Danfoss-built dialects (vlt, ge) only.
bool profidrive_request_id_defined(std::uint8_t request_id, Dialect dialect) noexcept;
// "value", "description", "text"; "" for others.
std::string_view profidrive_attribute_name(std::uint8_t attribute);
// "Integer16", "Unsigned32", "FloatingPoint32", "VisibleString", "N2", "V2", "Zero", "Error",
// ...; "reserved" for reserved codes.
std::string_view profidrive_format_name(std::uint8_t format);
// Bytes per value for a format; 0 for Zero, -1 where the size is unknown (reserved formats).
int profidrive_format_size(std::uint8_t format) noexcept;
// The text of an error number in a format-0x44 block. The manufacturer-specific numbers
// (0x65 and up) read per dialect: the Danfoss FC texts for vlt and ge (danfoss_family),
// "manufacturer-specific" for profidrive.
std::string_view profidrive_error_text(std::uint16_t error, Dialect dialect);
// Whether a response ID is a valid answer to a request ID (the standard IDs mirrored, bit 7 set
// when negative; for the Danfoss IDs 0x42/0x51/0x52 also 0x01/0x02/0x81/0x82, whose use the
// sources do not document).
bool profidrive_response_answers(std::uint8_t response_id, std::uint8_t request_id) noexcept;

// One parameter address of a request (6 bytes).
struct ProfidriveAddress {
    std::uint8_t attribute = 0;
    std::uint8_t elements = 0;
    std::uint16_t pnu = 0;
    std::uint16_t subindex = 0;
};

// One value block: format, number of values, values (or error values), padded to even length.
struct ProfidriveValueBlock {
    std::uint8_t format = 0;
    std::uint8_t count = 0;           // number of values as sent
    Bytes values{};                   // the value bytes read (fewer than announced when cut short)
    std::uint16_t values_offset = 0;  // their offset in the telegram
    bool padded = false;              // a pad byte followed the values
    bool complete = false;            // every announced value byte was there
    // Format 0x44: the error number and, when a second value is given, the additional
    // information (e.g. the first failing subindex).
    bool is_error() const noexcept { return format == profidrive::kFormatError; }
    std::uint16_t error_number() const noexcept;
    bool has_error_info() const noexcept { return is_error() && values.size() >= 4; }
    std::uint16_t error_info() const noexcept;
};

// A parameter request or response. The decoder reuses one per telegram; the vectors keep their
// capacity.
struct ProfidriveMessage {
    bool is_response = false;
    bool has_header = false;  // the 4 header bytes were there
    std::uint8_t reference = 0;
    std::uint8_t id = 0;  // request ID or response ID
    std::uint8_t axis = 0;
    std::uint8_t count = 0;  // number of parameters as sent
    // Request: the addresses read (up to `count`). Response: the addresses of the request it
    // answers, copied by the decoder when it has that request (`has_request`).
    std::vector<ProfidriveAddress> addresses;
    // Change request: the value blocks after the addresses. Response: its value blocks.
    std::vector<ProfidriveValueBlock> blocks;
    // Response only: the request it answers, as the decoder kept it.
    bool has_request = false;
    std::uint64_t request_frame = 0;
    std::uint8_t request_id = 0;
    std::uint8_t request_reference = 0;
    // Bytes after the last block the message accounts for (a length inconsistency).
    std::uint16_t trailing = 0;

    bool negative() const noexcept { return is_response && (id & profidrive::kNegative); }
    bool is_change_request() const noexcept {
        return !is_response &&
               (id == profidrive::kChangeValue || id == profidrive::kChangeValueNonVolatile ||
                id == profidrive::kChangeValueDoubleWord);
    }
    void clear() noexcept {
        is_response = has_header = has_request = false;
        reference = id = axis = count = request_id = request_reference = 0;
        request_frame = 0;
        trailing = 0;
        addresses.clear();
        blocks.clear();
    }
};

// Reads a parameter request from the data of a DP-V1 Write (index 47). Header, then `count`
// addresses, then for a change request `count` value blocks. What is missing is a
// ServiceDataShort problem at its offset; what was read stays.
void parse_profidrive_request(ByteReader reader, ProfidriveMessage& out,
                              ProblemList& problems) noexcept;
// Reads a parameter response from the data of a DP-V1 Read response (index 47): header, then
// value blocks until the data ends or `count` blocks were read.
void parse_profidrive_response(ByteReader reader, ProfidriveMessage& out,
                               ProblemList& problems) noexcept;

// A value block's values as text, by format: integers, unsigned and Byte / Word / Double word in
// decimal, float32, VisibleString quoted, OctetString in hex, N2/N4 as a percentage
// (N2: 0x4000 = 100 %), V2 as 16 bits, time differences in ms; several values separated by
// ", ". Error blocks give "error 0xNN" (renderers add the text). Appends to `out`.
// A block cut short ends in " (cut short)".
void append_profidrive_values(const ProfidriveValueBlock& block, std::string& out);

// A value as a number: integers, unsigned, Boolean (0/1), V2, Byte, Word, Double word and
// TimeDifference without date (ms) as integers; float32 and N2/N4 (in percent) as reals.
struct ProfidriveNumber {
    bool is_real = false;
    bool single = false;  // a float32: write it with float precision ("0.1", not 0.100000001...)
    std::int64_t integer = 0;
    double real = 0;
};
// How many whole values a block holds (each character of a string counts; 0 for Zero, Error
// and reserved formats).
std::size_t profidrive_value_count(const ProfidriveValueBlock& block) noexcept;
// Value `index` of a block as a number; nullopt where the format is not numeric (strings, dates,
// times of day, Zero, Error, reserved), the value is missing, or a float is not finite.
std::optional<ProfidriveNumber> profidrive_number(const ProfidriveValueBlock& block,
                                                  std::size_t index) noexcept;

}  // namespace dpscope
