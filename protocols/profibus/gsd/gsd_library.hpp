// The GSD files a run was given (--gsd, --gsd-dir, the plugin's folder), and what a slave's GSD
// says about the data of its management telegrams: which module each Chk_Cfg / Get_Cfg
// identifier stands for, what each user parameter of a Set_Prm is, and what the bits of a
// diagnosis mean. Pure: the files are read by the caller (capture/gsd_files.hpp); the decoder
// matches a slave to its GSD (BusDecoder, by Ident_Number or forced per address) and stores what
// these functions find on the telegram, for the renderers to show and the tracker to judge.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "core/byte_reader.hpp"
#include "protocols/profibus/gsd/gsd_file.hpp"

namespace dpscope {

class GsdLibrary {
  public:
    // Adds a device and returns its index. A second device with an Ident_Number already known
    // is kept (it can still be forced on an address) but not matched by the number: the one
    // added first is. `shadowed` then names the one that keeps the number.
    std::size_t add(GsdDevice device, const GsdDevice** shadowed = nullptr);
    // --gsd ADDR=FILE: `station` is described by the device at `index`, whatever its ident.
    void force(std::uint8_t station, std::size_t index) noexcept;

    const GsdDevice* by_ident(std::uint16_t ident) const noexcept;
    const GsdDevice* forced(std::uint8_t station) const noexcept;
    std::size_t size() const noexcept { return devices_.size(); }
    bool empty() const noexcept { return devices_.empty(); }
    const GsdDevice& device(std::size_t index) const noexcept { return devices_[index]; }

  private:
    std::deque<GsdDevice> devices_;  // a deque: the decoder keeps pointers to the devices
    std::unordered_map<std::uint16_t, std::size_t> by_ident_;
    std::array<std::int16_t, 128> forced_{[] {
        std::array<std::int16_t, 128> none{};
        none.fill(-1);
        return none;
    }()};
};

// "Vendor Model" (or the file's name when the GSD names neither).
std::string gsd_device_title(const GsdDevice& device);

// ---- Chk_Cfg / Get_Cfg -------------------------------------------------------------------

// A run of identifier bytes and the GSD module they stand for (null: no module of the GSD has
// these bytes; the run is then one identifier).
struct GsdModuleMatch {
    std::uint16_t offset = 0;            // telegram offset of its first identifier byte
    std::uint16_t length = 0;            // identifier bytes
    std::uint16_t first_identifier = 0;  // the index of its first identifier (slot, from 0)
    std::uint16_t identifiers = 0;       // how many identifiers it covers
    const GsdModule* module = nullptr;
};

// Matches configuration bytes (`config`, whose first byte is at telegram offset `offset`) to the
// device's modules: at each identifier the longest module whose bytes come next and end on an
// identifier boundary (`identifier_offsets`: the telegram offset of each identifier, as
// parse_cfg found them). Appends to `out`.
void match_gsd_modules(const GsdDevice& device, Bytes config, std::uint16_t offset,
                       std::span<const std::uint16_t> identifier_offsets,
                       std::vector<GsdModuleMatch>& out);

// ---- Set_Prm -----------------------------------------------------------------------------

// One user parameter of a Set_Prm, read by the GSD's ExtUserPrmData.
struct GsdPrmValue {
    const GsdUserPrm* prm = nullptr;
    const GsdModule* module = nullptr;  // whose parameter it is (null: the device's)
    std::uint16_t offset = 0;           // telegram offset of its byte(s)
    std::int64_t value = 0;
    const GsdValueText* text = nullptr;  // its PrmText text, when the GSD gives one
    bool in_range = true;                // within min-max, or one of the allowed values
};

// What a Set_Prm's user parameter data holds by the GSD.
struct GsdPrmReading {
    std::vector<GsdPrmValue> values;
    // The bytes the GSD's parameter blocks take (device, then the modules'): the length the
    // slave expects when User_Prm_Data_Len gives none. 0: the GSD describes no bytes.
    std::uint32_t described_length = 0;
    bool modules_known = false;  // the slave's modules were known (a Chk_Cfg before)
};

// Reads `user_prm` (the User_Prm_Data: every byte after the seven fixed ones, DP-V1 status bytes
// included; the first at telegram offset `offset`) by the device's Ext_User_Prm_Data_Ref of the
// device and, when `modules` is given (the slave's configuration, in slot order), of each
// module's part after it. A parameter whose bytes are not all there is left out.
void read_gsd_user_prm(const GsdDevice& device, std::span<const GsdModule* const> modules,
                       bool modules_known, Bytes user_prm, std::uint16_t offset,
                       GsdPrmReading& out);

// ---- Slave_Diag --------------------------------------------------------------------------

// A text the GSD gives to part of an extended diagnosis.
struct GsdDiagText {
    enum class Source : std::uint8_t { Bit, Area, Slot };
    Source source = Source::Bit;
    std::uint16_t offset = 0;  // telegram offset of the byte (the first byte of an area)
    std::uint32_t bit = 0;     // Unit_Diag_Bit's number, the area's first bit, or the slot
    std::int64_t value = 0;    // an area's value
    std::string_view text;     // the GSD's text, or the module's name for a slot
};

// Names what the GSD describes in a device-related diagnosis block (`data`, after its header
// byte, the first at telegram offset `offset`): each set bit Unit_Diag_Bit names, and the value
// of each Unit_Diag_Area that has a text for it. Bit b is bit b % 8 of data byte b / 8 (counted
// from the byte after the header; docs/gsd.md).
void name_gsd_diag_bits(const GsdDevice& device, Bytes data, std::uint16_t offset,
                        std::vector<GsdDiagText>& out);

}  // namespace dpscope
