// The VLT 2000 telegram's fields of the filter language (core/filter_field.hpp, docs/filter.md):
// the Wireshark plugin's names for the address, the parameter, its value and a failed command.
#include <array>
#include <span>

#include "core/filter_field.hpp"
#include "protocols/vlt2000/vlt2000_telegram.hpp"

namespace dpscope {

namespace {

bool is_vlt2000(const FilterInput& in) noexcept { return in.t.protocol == Protocol::Vlt2000; }

const std::array<FilterField, 7> kFields{{
    {"dpscope.pnu", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         const auto pnu = is_vlt2000(in) ? vlt2000_named_pnu(in.t.vlt2000) : std::nullopt;
         return pnu && visit_integer(v, *pnu);
     },
     "the parameter the telegram is about (VLT 2000: its parameter, not a C telegram's)"},
    {"dpscope.vlt2000.address", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         return is_vlt2000(in) && visit_integer(v, in.t.vlt2000.address);
     },
     "the unit's address (0: every unit)"},
    {"dpscope.vlt2000.parameter", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         return is_vlt2000(in) && in.t.vlt2000.has_parameter &&
                visit_integer(v, in.t.vlt2000.parameter);
     },
     "parameter number"},
    {"dpscope.vlt2000.value", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         const Vlt2000Telegram& t = in.t.vlt2000;
         return is_vlt2000(in) && t.has_value && !t.failed &&
                visit_integer(v, t.negative ? -static_cast<std::int64_t>(t.digits) : t.digits);
     },
     "the value's digits without the decimal point, with its sign"},
    {"dpscope.vlt2000.failed", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         return is_vlt2000(in) && in.t.vlt2000.has_decimals &&
                visit_integer(v, in.t.vlt2000.failed ? 1 : 0);
     },
     "1 (true) when the drive says the command failed (decimal position 9)"},
    {"dpscope.vlt2000.reason", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         return is_vlt2000(in) && in.t.vlt2000.has_reason && visit_integer(v, in.t.vlt2000.reason);
     },
     "reason code of a failed command"},
    {"dpscope.vlt2000.checksum_ok", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         return is_vlt2000(in) && in.t.vlt2000.has_checksum &&
                visit_integer(v, in.t.vlt2000.checksum_ok ? 1 : 0);
     },
     "1 (true) when the checksum is right"},
}};

}  // namespace

std::span<const FilterField> vlt2000_filter_fields() noexcept { return kFields; }

}  // namespace dpscope
