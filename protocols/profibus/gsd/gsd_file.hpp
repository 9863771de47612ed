// A PROFIBUS DP slave's device description (GSD file), as far as dpscope reads it (issue 29;
// the subset and its sources: docs/gsd.md). Pure text parsing, no I/O: the caller reads the
// file's bytes and names it for messages.
//
// The text is 8-bit (ISO 8859-1 / Windows-1252, as the language variants .gsd, .gse, .gsg, .gsf
// ... are written) unless it is valid UTF-8 throughout; names and texts are kept as UTF-8.
// Keywords are case-insensitive, ';' starts a comment outside a string, a '\' at the end of a
// line continues it on the next. A keyword dpscope does not read is skipped. A file that is
// broken (no "#Profibus_DP" line, a block without its end, a value that is no number where a
// number must be) is an error naming FILE:LINE and what is wrong.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"

namespace dpscope {

// A value of a parameter and its text (PrmText's Text(v), Unit_Diag_Area's Value(v)).
struct GsdValueText {
    std::int64_t value = 0;
    std::string text;
};

// PrmText = n ... EndPrmText: the texts of a user parameter's values.
struct GsdPrmText {
    std::uint32_t reference = 0;
    std::vector<GsdValueText> texts;
    std::uint32_t line = 0;
};

// The data types of an ExtUserPrmData.
enum class GsdDataType : std::uint8_t {
    Bit,      // Bit(n): one bit of the byte at the reference's offset
    BitArea,  // BitArea(first-last): bits first..last of that byte
    Unsigned8,
    Unsigned16,
    Unsigned32,
    Signed8,
    Signed16,
    Signed32,
};
std::string_view gsd_data_type_name(GsdDataType type) noexcept;

// ExtUserPrmData = n "name" ... EndExtUserPrmData: one user parameter's type, default and the
// values it may take (a range min-max, or a list of allowed values).
struct GsdUserPrm {
    std::uint32_t reference = 0;
    std::string name;
    GsdDataType type = GsdDataType::Unsigned8;
    std::uint8_t first_bit = 0;  // Bit, BitArea
    std::uint8_t last_bit = 0;
    std::int64_t default_value = 0;
    std::int64_t min_value = 0;
    std::int64_t max_value = 0;
    std::vector<std::int64_t> allowed;  // non-empty: only these values (instead of min-max)
    std::optional<std::uint32_t> text_reference;  // Prm_Text_Ref
    std::uint32_t line = 0;
};

// Ext_User_Prm_Data_Ref(offset) = reference: the user parameter at byte `offset` of the user
// parameter data; Ext_User_Prm_Data_Const(offset) = bytes: fixed bytes from `offset` on.
struct GsdPrmRef {
    std::uint32_t offset = 0;
    std::uint32_t reference = 0;
};
struct GsdPrmConst {
    std::uint32_t offset = 0;
    std::vector<std::uint8_t> bytes;
};

// Module = "name" identifier bytes ... EndModule.
struct GsdModule {
    std::string name;
    std::vector<std::uint8_t> config;     // the Chk_Cfg identifier bytes it stands for
    std::optional<std::uint32_t> number;  // the module's reference number (a line of its own)
    std::vector<GsdPrmRef> prm_refs;      // its user parameters
    std::vector<GsdPrmConst> prm_consts;
    std::uint32_t line = 0;
};

// Unit_Diag_Area = first-last ... Unit_Diag_Area_End: the texts of a field of bits of the
// device-related diagnosis.
struct GsdDiagArea {
    std::uint32_t first_bit = 0;
    std::uint32_t last_bit = 0;
    std::vector<GsdValueText> values;
};

// MaxTsdr_<rate>: the most bit times a slave takes to answer at that rate ("9.6", "1.5M").
struct GsdMaxTsdr {
    std::string rate;
    std::uint32_t bit_times = 0;
};

struct GsdDevice {
    std::string file;  // as the caller named it
    std::optional<std::uint32_t> gsd_revision;
    std::string vendor;    // Vendor_Name
    std::string model;     // Model_Name
    std::string revision;  // Revision
    std::optional<std::uint16_t> ident_number;
    std::optional<std::string> slave_family;  // as written: "1@Drives"
    bool dpv1_slave = false;
    bool modular_station = false;
    std::optional<std::uint32_t> max_module;
    std::optional<std::uint32_t> max_input_len;
    std::optional<std::uint32_t> max_output_len;
    std::optional<std::uint32_t> max_data_len;
    std::optional<std::uint32_t> user_prm_data_len;
    std::optional<std::uint32_t> max_user_prm_data_len;
    std::vector<std::uint8_t> user_prm_data;  // User_Prm_Data (the simple form)
    std::optional<std::uint32_t> max_diag_data_len;
    std::optional<std::uint32_t> min_slave_interval;  // Min_Slave_Intervall, in 100 us
    std::vector<GsdMaxTsdr> max_tsdr;
    std::vector<GsdPrmText> prm_texts;
    std::vector<GsdUserPrm> user_prms;
    std::vector<GsdPrmRef> prm_refs;  // the device's own (outside a module)
    std::vector<GsdPrmConst> prm_consts;
    std::vector<GsdModule> modules;
    std::vector<GsdValueText> unit_diag_bits;  // Unit_Diag_Bit(bit) = "text": value is the bit
    std::vector<GsdDiagArea> unit_diag_areas;
    std::optional<std::uint32_t> unit_diag_type;  // Unit_Diag_Type (channel diagnosis format)
    std::uint32_t keywords_skipped = 0;           // keywords dpscope does not read

    // MaxTsdr at `rate` as the GSD writes it ("1.5M"); nullopt when it gives none.
    std::optional<std::uint32_t> max_tsdr_at(std::string_view rate) const;
    const GsdPrmText* prm_text(std::uint32_t reference) const noexcept;
    const GsdUserPrm* user_prm(std::uint32_t reference) const noexcept;
};

// Parses the bytes of a GSD file named `file` (for messages). An error reads
// "FILE:LINE: what".
Result<GsdDevice> parse_gsd(std::string_view bytes, std::string_view file);

}  // namespace dpscope
