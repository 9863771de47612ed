// The toybus payload of a decoded telegram: a toy line protocol that proves CONTRIBUTING.md's
// "Adding a protocol" (issue 28). One ASCII telegram a line, ended by "\r\n" (or "\n"):
//   ?AA PPPP          read parameter PPPP of drive AA            (master -> drive)
//   !AA PPPP VVVVV    write VVVVV into parameter PPPP of drive AA (master -> drive)
//   =AA PPPP VVVVV    the parameter's value                      (drive -> master)
//   #AA PPPP EE       the command failed with error EE          (drive -> master)
// AA two digits 01..31, PPPP four digits, VVVVV five digits, EE two digits; the fields are
// separated by one space. Filled by ToybusDecoder (protocols/toybus/toybus_decoder.hpp).
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/byte_reader.hpp"
#include "core/problem.hpp"

namespace dpscope {

// The four lead characters, one per telegram kind.
inline constexpr std::uint8_t kToybusRead = '?';
inline constexpr std::uint8_t kToybusWrite = '!';
inline constexpr std::uint8_t kToybusValue = '=';
inline constexpr std::uint8_t kToybusError = '#';
// Byte offsets of the fields.
inline constexpr std::size_t kToybusAddressAt = 1;
inline constexpr std::size_t kToybusParameterAt = 4;
inline constexpr std::size_t kToybusValueAt = 9;  // the value, or the error number
// The longest telegram: "!AA PPPP VVVVV\r\n".
inline constexpr std::size_t kToybusMaxTelegram = 16;
inline constexpr std::uint8_t kToybusMaxAddress = 31;

enum class ToybusKind : std::uint8_t { Read, Write, Value, Error, Unknown };

constexpr ToybusKind toybus_kind_of(std::uint8_t lead) noexcept {
    switch (lead) {
        case kToybusRead: return ToybusKind::Read;
        case kToybusWrite: return ToybusKind::Write;
        case kToybusValue: return ToybusKind::Value;
        case kToybusError: return ToybusKind::Error;
        default: return ToybusKind::Unknown;
    }
}
constexpr bool toybus_is_lead(std::uint8_t c) noexcept {
    return toybus_kind_of(c) != ToybusKind::Unknown;
}
// The length of a kind's line without its line end: 8, 14, 14, 11 (0: unknown).
constexpr std::size_t toybus_body_size(ToybusKind kind) noexcept {
    switch (kind) {
        case ToybusKind::Read: return 8;
        case ToybusKind::Write:
        case ToybusKind::Value: return 14;
        case ToybusKind::Error: return 11;
        case ToybusKind::Unknown: break;
    }
    return 0;
}

struct ToybusTelegram {
    ToybusKind kind = ToybusKind::Unknown;
    bool complete = false;  // every field and the line end are there
    bool crlf = false;      // the line ended in "\r\n" (else "\n", or none)
    bool has_address = false;
    std::uint8_t address = 0;
    bool has_parameter = false;
    std::uint16_t parameter = 0;
    bool has_value = false;  // Write, Value
    std::uint32_t value = 0;
    bool has_error = false;  // Error
    std::uint8_t error = 0;

    ProblemList problems;

    void reset() noexcept { *this = ToybusTelegram{}; }
};

inline const ProblemList& payload_problems(const ToybusTelegram& v) noexcept { return v.problems; }

}  // namespace dpscope
