// PROFIBUS FDL (layer 2) telegrams: SD1, SD2, SD3, SD4 and the short acknowledge SC.
//
//   SD1  10 DA SA FC FCS 16                      no data
//   SD2  68 LE LEr 68 DA SA FC [DAE][SAE] DU FCS 16   LE = DA..DU, 4..249
//   SD3  A2 DA SA FC [DAE][SAE] DU(8) FCS 16      8 data octets (SAP bytes included)
//   SD4  DC DA SA                                 token
//   SC   E5                                       short acknowledge
//
// FCS is the arithmetic sum of DA..DU modulo 256. Bit 7 of DA/SA announces an address-extension
// byte at the start of the data unit: bit 7 = another extension follows, bit 6 = segment address,
// bits 5..0 = SAP (or segment number).
#pragma once

#include <cstdint>
#include <string_view>

#include "core/byte_reader.hpp"
#include "core/problem.hpp"

namespace dpscope {

inline constexpr std::uint8_t kSd1 = 0x10;
inline constexpr std::uint8_t kSd2 = 0x68;
inline constexpr std::uint8_t kSd3 = 0xA2;
inline constexpr std::uint8_t kSd4 = 0xDC;
inline constexpr std::uint8_t kShortAck = 0xE5;
inline constexpr std::uint8_t kEndDelimiter = 0x16;
inline constexpr std::uint8_t kBroadcastAddress = 127;
inline constexpr std::size_t kMaxTelegramSize = 255;  // SD2 with LE 249

enum class FrameType : std::uint8_t { Sd1, Sd2, Sd3, Sd4, ShortAck, Invalid };

// "SD1", "SD2", "SD3", "SD4", "SC" (and "invalid").
std::string_view frame_type_name(FrameType type);
bool is_start_delimiter(std::uint8_t byte) noexcept;

// Request function codes (FC bit 6 set, low nibble). FC bit 7 is reserved (0) except in the
// clock value request 0xC0 (function 0 with bit 7 set); function 0 without it is a time event.
enum class FdlFunction : std::uint8_t {
    TimeEvent = 0x0,
    SdaLow = 0x3,
    SdnLow = 0x4,
    SdaHigh = 0x5,
    SdnHigh = 0x6,
    Msrd = 0x7,
    FdlStatus = 0x9,
    TimeEventActual = 0xA,
    CounterEventActual = 0xB,
    SrdLow = 0xC,
    SrdHigh = 0xD,
    Ident = 0xE,
    LsapStatus = 0xF,
};

// Response status codes (FC bit 6 clear, low nibble).
enum class FdlStatus : std::uint8_t {
    Ok = 0x0,
    UserError = 0x1,
    NoResource = 0x2,
    NoService = 0x3,
    DataLow = 0x8,
    NoResponseData = 0x9,
    DataHigh = 0xA,
    NotReceivedDataLow = 0xC,
    NotReceivedDataHigh = 0xD,
};

struct FrameControl {
    std::uint8_t raw = 0;

    bool is_request() const noexcept { return (raw & 0x40) != 0; }
    bool fcb() const noexcept { return (raw & 0x20) != 0; }
    bool fcv() const noexcept { return (raw & 0x10) != 0; }
    std::uint8_t function() const noexcept { return raw & 0x0F; }
    std::uint8_t station_type() const noexcept { return (raw >> 4) & 0x03; }
    // A clock value request: bit 7 and bit 6 set, function 0 (0xC0, with FCB/FCV as sent).
    bool is_clock_value() const noexcept { return (raw & 0xCF) == 0xC0; }
    // Bit 7 set in any other frame control byte: a reserved code (a ReservedFrameControl problem).
    bool is_reserved() const noexcept { return (raw & 0x80) != 0 && !is_clock_value(); }
};

// "SRD high", "SDN low", "FDL status", ... ; "reserved" for unassigned codes.
std::string_view request_function_name(std::uint8_t function);
// The function of a request's whole frame control byte: "clock value" for 0xC0, "reserved" when
// bit 7 is set otherwise, else request_function_name() of the low nibble.
std::string_view request_function_name(FrameControl fc);
// "OK", "UE", "RR", "RS", "DL", "NR", "DH", "RDL", "RDH"; "reserved" otherwise.
std::string_view response_status_name(std::uint8_t status);
// The longer wording, e.g. "data low", "no resources".
std::string_view response_status_text(std::uint8_t status);
// "slave", "master not ready", "master ready for the token ring", "master in the token ring".
std::string_view station_type_name(std::uint8_t station_type);
// SRD, SDA, MSRD, FDL status, ident and LSAP status requests wait for a reply; SDN does not.
bool function_expects_reply(std::uint8_t function) noexcept;
bool function_is_srd(std::uint8_t function) noexcept;
bool function_is_sda(std::uint8_t function) noexcept;

std::uint8_t fcs_of(Bytes bytes) noexcept;

struct FdlTelegram {
    FrameType type = FrameType::Invalid;
    std::uint16_t size = 0;          // bytes the telegram occupies, at most the record size
    std::uint8_t length_field = 0;   // SD2: LE
    bool has_length_repeat = false;  // SD2 long enough to carry LEr
    std::uint8_t length_repeat = 0;  // SD2: LEr
    bool has_addresses = false;      // SD1..SD4
    std::uint8_t da = 0;             // 7-bit destination address
    std::uint8_t sa = 0;             // 7-bit source address
    bool has_fc = false;             // SD1..SD3
    FrameControl fc{};
    bool has_dsap = false;
    bool has_ssap = false;
    std::uint8_t dsap = 0;
    std::uint8_t ssap = 0;
    bool has_dest_segment = false;
    bool has_source_segment = false;
    std::uint8_t dest_segment = 0;
    std::uint8_t source_segment = 0;
    Bytes du{};                   // data unit after the address-extension bytes
    std::uint16_t du_offset = 0;  // where du starts in the telegram
    bool has_fcs = false;         // SD1..SD3 that were long enough to carry one
    std::uint8_t fcs = 0;
    bool fcs_ok = true;  // true when there is no FCS to check (SD4, SC)
    ProblemList problems;

    bool is_request() const noexcept {
        return type == FrameType::Sd4 || (has_fc && fc.is_request());
    }
};

// Decodes one telegram from the start of `bytes` as far as the bytes allow. Every failed check
// lands in out.problems with the byte offset; nothing throws. Bytes past the telegram's end are
// reported as TrailingBytes.
void parse_fdl(Bytes bytes, FdlTelegram& out) noexcept;

}  // namespace dpscope
