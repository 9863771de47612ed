// The Danfoss FC protocol payload of a decoded telegram (docs/protocol/fc-protocol.md):
//   STX 0x02 | LGE | ADR | data (LGE - 2 bytes, ADR and BCC counted in LGE) | BCC
// with a process block (LGE 6: PCD 1, PCD 2), a parameter block (LGE 14: PKE, IND, PWE high, PWE
// low, PCD 1, PCD 2) or a text block (LGE 10 + n: PKE, IND, n characters, PCD 1, PCD 2). Filled by
// FcDecoder (protocols/fc/fc_decoder.hpp).
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "core/byte_reader.hpp"
#include "core/code_tables.hpp"
#include "core/problem.hpp"

namespace dpscope {

inline constexpr std::uint8_t kFcStx = 0x02;
// LGE of the two fixed blocks, and of a text block without characters (10 + n).
inline constexpr std::uint8_t kFcLgeProcess = 6;
inline constexpr std::uint8_t kFcLgeParameter = 14;
inline constexpr std::uint8_t kFcLgeTextBase = 10;
// The FC PKE: AK in bits 15..12, PNU in bits 11..0, no SPM bit, the index in IND's low (second)
// byte [S001]. Older drives (VLT 2800, FCD 300) use PNU bits 10..0 (--fc-pnu-bits 11).
inline constexpr PkeLayout kFcPkeLayout{12, std::nullopt, IndexByte::Low};
inline constexpr PkeLayout kFcPkeLayout11{11, std::nullopt, IndexByte::Low};

enum class FcBlock : std::uint8_t {
    Process,    // LGE 6
    Parameter,  // LGE 14 (AK other than 15)
    Text,       // LGE 10 + n; also LGE 14 with AK 15 (its four PWE bytes are the characters)
    Unknown,    // LGE 7..9, or a record too short to tell
};
std::string_view fc_block_name(
    FcBlock block) noexcept;  // "process", "parameter", "text", "unknown"

// The two formats of the address byte [P:FC202-DG p153].
enum class FcAddressFormat : std::uint8_t {
    Short,  // bit 7 = 0: addresses 1..31 in bits 4..0, bit 5 = broadcast
    Long,   // bit 7 = 1: addresses 1..126 in bits 6..0, 0x80 = broadcast
};
std::string_view fc_address_format_name(FcAddressFormat format) noexcept;  // "1-31", "1-126"

// IND's high byte with AK 15: read or write the text [P:FC102-DG 8.4.10].
inline constexpr std::uint8_t kFcTextRead = 0x04;
inline constexpr std::uint8_t kFcTextWrite = 0x05;

// The fields a telegram decodes to; FcTelegram adds its problems. (Two parts so that reset() can
// renew the fields and empty the problem list in place: building a whole new telegram for every
// record zeroed and copied the list's storage each time; issue 31.)
struct FcTelegramFields {
    std::uint8_t lge = 0;
    std::uint8_t adr = 0;  // the address byte as sent
    FcAddressFormat address_format = FcAddressFormat::Short;
    std::uint8_t address = 0;  // 1..31 or 1..126; 0 for a broadcast
    bool broadcast = false;
    FcBlock block = FcBlock::Unknown;
    bool complete = false;  // every byte LGE announces is there (the BCC included)
    std::uint8_t bcc = 0;   // as sent (complete only)
    std::uint8_t bcc_computed = 0;
    bool bcc_ok = false;

    // Parameter and text blocks: PKE and IND read with the FC layout; PWE (bytes 5..8 of the
    // block) for a parameter block. pcv.rc is the AK, pcv.ind the index (IND's low byte).
    bool has_pkw = false;
    Pcv pkw;
    std::uint8_t ind_high = 0;  // AK 15: 0x04 read text, 0x05 write text
    Bytes text;                 // text blocks: the characters (a view into the telegram)

    // PCD 1 (control word to the drive, status word from it) and PCD 2 (reference / actual
    // value), the last four data bytes of every block.
    bool has_pcd = false;
    std::uint16_t pcd1 = 0;
    std::uint16_t pcd2 = 0;
};

struct FcTelegram : FcTelegramFields {
    ProblemList problems;

    void reset() noexcept {
        // Copied from a constant: a temporary built on the stack first cost a stalled load.
        static constexpr FcTelegramFields kFresh{};
        static_cast<FcTelegramFields&>(*this) = kFresh;
        problems.clear();
    }
};

// The parameter an FC telegram names: its PKW's PNU (a response echoes its request's); none
// without a PKW (--pnu, the filter's dpscope.pnu).
inline std::optional<std::uint16_t> fc_named_pnu(const FcTelegram& fc) noexcept {
    if (!fc.has_pkw) return std::nullopt;
    return fc.pkw.pnu;
}

// Every problem found in an FC telegram (DecodedTelegram::problems()).
inline const ProblemList& payload_problems(const FcTelegram& fc) noexcept { return fc.problems; }

}  // namespace dpscope
