// Data units of the DP management services: Slave_Diag, Set_Prm, Chk_Cfg/Get_Cfg identifiers,
// Global_Control and Set_Slave_Add. Every parser reads through ByteReader and reports what does
// not fit as Problems; what could be read is still returned.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "core/byte_reader.hpp"
#include "core/problem.hpp"

namespace dpscope {

struct FlagBit {
    std::uint8_t mask;
    std::string_view name;
};

// ---- Slave_Diag ------------------------------------------------------------------------------

inline constexpr std::uint8_t kDiagCfgFault = 0x04;    // Station_Status_1
inline constexpr std::uint8_t kDiagExtDiag = 0x08;     // Station_Status_1
inline constexpr std::uint8_t kDiagPrmFault = 0x40;    // Station_Status_1
inline constexpr std::uint8_t kDiagPrmReq = 0x01;      // Station_Status_2
inline constexpr std::uint8_t kDiagAlwaysOne = 0x04;   // Station_Status_2
inline constexpr std::uint8_t kDiagWatchdogOn = 0x08;  // Station_Status_2
inline constexpr std::uint8_t kNoMasterAddress = 255;

std::span<const FlagBit> station_status_1_flags();
std::span<const FlagBit> station_status_2_flags();
std::span<const FlagBit> station_status_3_flags();

enum class DiagBlockType : std::uint8_t { Device, Identifier, Channel, Revision };
std::string_view diag_block_type_name(DiagBlockType type);

struct DiagBlock {
    DiagBlockType type = DiagBlockType::Device;
    std::uint16_t offset = 0;  // header byte offset in the telegram
    Bytes data;                // the block without its header byte
    // Channel-related blocks:
    std::uint8_t module = 0;  // identifier (slot) number
    std::uint8_t channel = 0;
    std::uint8_t io = 0;            // 0 reserved, 1 input, 2 output, 3 input/output
    std::uint8_t channel_type = 0;  // 1 bit, 2 2-bit, 3 4-bit, 4 byte, 5 word, 6 2 words
    std::uint8_t error_type = 0;
    // Revision blocks:
    std::uint8_t revision = 0;
};

struct SlaveDiag {
    std::uint8_t station_status_1 = 0;
    std::uint8_t station_status_2 = 0;
    std::uint8_t station_status_3 = 0;
    std::uint8_t master_address = kNoMasterAddress;
    std::uint16_t ident = 0;
    Bytes extended;  // extended diagnosis, after the six fixed bytes
    std::uint16_t extended_offset = 0;
};

// `reader` spans the data unit; its offsets are telegram offsets.
std::optional<SlaveDiag> parse_slave_diag(ByteReader reader, ProblemList& problems);
// Appends the blocks of an extended diagnosis to `blocks` (so a caller can reuse the vector). A
// block that runs past the end is reported; a device- or identifier-related one is kept with the
// bytes there are, a channel-related one is dropped.
void parse_extended_diag(ByteReader reader, std::vector<DiagBlock>& blocks, ProblemList& problems);
std::string_view channel_error_text(std::uint8_t error_type);
std::string_view channel_type_text(std::uint8_t channel_type);
// The I/O type of a channel-related block (bits 7..6 of its second byte): 01 "input",
// 10 "output", 11 "input/output"; 00 is "reserved I/O type".
std::string_view channel_io_text(std::uint8_t io);
// DP-V1 device-related blocks: byte 1 names an alarm (bit 7 clear) or a status (bit 7 set).
// Alarms 1..6, statuses 1..3, 30, 31; 32..126 manufacturer-specific; 0, 127 and the gaps reserved.
std::string_view dpv1_alarm_or_status_text(std::uint8_t type_byte);

// ServiceDataShort at the reader's position: `wanted` bytes of a service's data unit were due
// and fewer are left. need_service_data() reports it when fewer than `bytes` remain.
void report_service_data_short(const ByteReader& reader, std::size_t wanted,
                               ProblemList& problems) noexcept;
bool need_service_data(const ByteReader& reader, std::size_t bytes, ProblemList& problems) noexcept;

// Whether a slave runs in DP-V1 mode, as its last Set_Prm said (DPV1_Status_1 bit 7,
// DPV1_Enable). A device-related diagnosis block is a DP-V1 alarm or status only in DP-V1 mode;
// otherwise it is manufacturer-specific data. Unknown: no Set_Prm to the slave in the capture.
enum class SlaveDpv1 : std::uint8_t { Unknown, Enabled, Disabled };

// ---- Set_Prm ---------------------------------------------------------------------------------

std::span<const FlagBit> set_prm_station_flags();
std::span<const FlagBit> dpv1_status_1_flags();
std::span<const FlagBit> dpv1_status_2_flags();
std::span<const FlagBit> dpv1_status_3_flags();  // bit 7 PrmCmd; Alarm_Mode is bits 2..0
// DPV1_Status_3 bits 2..0: "1 alarm of each type" (0), else "N alarms in total" (2, 4, 8, 12,
// 16, 24, 32).
std::string_view dpv1_alarm_mode_text(std::uint8_t status_3);

struct SetPrm {
    std::uint8_t station_status = 0;
    std::uint8_t wd_fact_1 = 0;
    std::uint8_t wd_fact_2 = 0;
    std::uint8_t min_tsdr = 0;
    std::uint16_t ident = 0;
    std::uint8_t group_ident = 0;
    bool has_dpv1_status = false;  // the first three user bytes fit the DP-V1 layout
    std::array<std::uint8_t, 3> dpv1_status{};
    Bytes user_prm;  // User_Prm_Data after the DP-V1 status bytes
    std::uint16_t user_prm_offset = 0;

    bool watchdog_on() const noexcept { return (station_status & 0x08) != 0; }
    // DPV1_Enable in DPV1_Status_1 (the first three user bytes read as DP-V1 status).
    bool dpv1_enabled() const noexcept { return has_dpv1_status && (dpv1_status[0] & 0x80); }
    // WD_Fact_1 x WD_Fact_2 x 10 ms (x 1 ms with the DP-V1 WD_Base_1ms bit).
    std::uint32_t watchdog_ms() const noexcept;
    // True when the watchdog has two readings: the bytes read as DPV1_Status_1..3 set
    // WD_Base_1ms, but a DP-V0 slave's User_Prm_Data can look the same, so the base may as well
    // be 10 ms. watchdog_ms() is then the 1 ms reading and watchdog_ms_10ms_base() the other.
    bool watchdog_base_uncertain() const noexcept {
        return has_dpv1_status && (dpv1_status[0] & 0x04);
    }
    std::uint32_t watchdog_ms_10ms_base() const noexcept {
        return std::uint32_t{10} * wd_fact_1 * wd_fact_2;
    }
};

std::optional<SetPrm> parse_set_prm(ByteReader reader, ProblemList& problems);

// ---- Chk_Cfg / Get_Cfg -----------------------------------------------------------------------

enum class CfgDirection : std::uint8_t { None, Input, Output, InputOutput };
std::string_view cfg_direction_name(CfgDirection direction);  // "-", "in", "out", "in/out"

struct CfgModule {
    std::uint16_t offset = 0;  // identifier byte offset in the telegram
    std::uint8_t identifier = 0;
    bool special = false;     // special identifier format (bits 5..4 = 00)
    bool free_place = false;  // 0x00
    CfgDirection direction = CfgDirection::None;
    std::uint8_t input_units = 0;  // length in units (bytes or words)
    std::uint8_t output_units = 0;
    bool input_words = false;
    bool output_words = false;
    bool input_consistent = false;
    bool output_consistent = false;
    std::uint8_t manufacturer_bytes = 0;

    std::uint16_t input_bytes() const noexcept {
        return static_cast<std::uint16_t>(input_units * (input_words ? 2 : 1));
    }
    std::uint16_t output_bytes() const noexcept {
        return static_cast<std::uint16_t>(output_units * (output_words ? 2 : 1));
    }
};

// Decodes identifier bytes into modules; returns false (with a Problem) when a special
// identifier announces more bytes than there are; the modules read before it are kept.
bool parse_cfg(ByteReader reader, std::vector<CfgModule>& modules, ProblemList& problems);

// ---- Global_Control and Set_Slave_Add --------------------------------------------------------

std::span<const FlagBit> global_control_flags();

struct GlobalControl {
    std::uint8_t command = 0;
    std::uint8_t group_select = 0;
};
std::optional<GlobalControl> parse_global_control(ByteReader reader, ProblemList& problems);

struct SetSlaveAdd {
    std::uint8_t new_address = 0;
    std::uint16_t ident = 0;
    std::uint8_t no_add_chg = 0;
    Bytes rem_slave_data;
};
std::optional<SetSlaveAdd> parse_set_slave_add(ByteReader reader, ProblemList& problems);

}  // namespace dpscope
