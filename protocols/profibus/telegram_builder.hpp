// Builds FDL telegrams: the encoder the simulator and the tests use. The frame type follows the
// data length as a PROFIBUS controller chooses it: SD1 for no data, SD3 for exactly 8 octets
// (address-extension bytes included), SD2 otherwise.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "core/byte_reader.hpp"
#include "protocols/profibus/fdl.hpp"

namespace dpscope {

struct TelegramSpec {
    std::uint8_t da = 0;
    std::uint8_t sa = 0;
    std::uint8_t fc = 0;
    std::optional<std::uint8_t> dsap;
    std::optional<std::uint8_t> ssap;
    Bytes du;
};

std::uint8_t request_fc(FdlFunction function, bool fcb = false, bool fcv = false) noexcept;
std::uint8_t response_fc(FdlStatus status, std::uint8_t station_type = 0) noexcept;

// Appends the encoded telegram to `out`.
void append_telegram(std::vector<std::uint8_t>& out, const TelegramSpec& spec);
void append_token(std::vector<std::uint8_t>& out, std::uint8_t da, std::uint8_t sa);
void append_short_ack(std::vector<std::uint8_t>& out);

std::vector<std::uint8_t> build_telegram(const TelegramSpec& spec);

// The 8 PCV bytes: PCA (RC, SPM, PNU), IND, IND low byte, PVA.
void append_pcv(std::vector<std::uint8_t>& out, std::uint8_t rc, bool spm, std::uint16_t pnu,
                std::uint8_t ind, std::uint32_t pva);
void append_u16_be(std::vector<std::uint8_t>& out, std::uint16_t value);

}  // namespace dpscope
