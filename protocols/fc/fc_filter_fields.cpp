// The FC protocol's fields of the filter language (core/filter_field.hpp, docs/filter.md): the
// Wireshark plugin's names for the drive address, the PKW (AK, PNU, IND, PWE) and the BCC.
#include <array>
#include <span>

#include "core/code_tables.hpp"
#include "core/filter_field.hpp"
#include "protocols/fc/fc_telegram.hpp"

namespace dpscope {

namespace {

bool is_fc(const FilterInput& in) noexcept { return in.t.protocol == Protocol::Fc; }
const Pcv* pkw_of(const FilterInput& in) noexcept {
    return is_fc(in) && in.t.fc.has_pkw ? &in.t.fc.pkw : nullptr;
}

const std::array<FilterField, 9> kFields{{
    {"dpscope.pnu", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         const auto pnu = is_fc(in) ? fc_named_pnu(in.t.fc) : std::nullopt;
         return pnu && visit_integer(v, *pnu);
     },
     "the parameter the telegram is about (FC: the PKW's PNU)"},
    {"dpscope.fc.address", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         return is_fc(in) && in.t.fc.lge != 0 && visit_integer(v, in.t.fc.address);
     },
     "the drive's address (0: broadcast)"},
    {"dpscope.fc.broadcast", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         return is_fc(in) && in.t.fc.lge != 0 && visit_integer(v, in.t.fc.broadcast ? 1 : 0);
     },
     "1 (true) for a broadcast"},
    {"dpscope.fc.bcc_ok", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         return is_fc(in) && in.t.fc.complete && visit_integer(v, in.t.fc.bcc_ok ? 1 : 0);
     },
     "1 (true) when the BCC is right (complete telegrams)"},
    {"dpscope.fc.ak", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         const Pcv* p = pkw_of(in);
         return p && visit_integer(v, p->rc);
     },
     "command or response code (AK)"},
    {"dpscope.fc.pnu", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         const Pcv* p = pkw_of(in);
         return p && visit_integer(v, p->pnu);
     },
     "parameter number"},
    {"dpscope.fc.ind", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         const Pcv* p = pkw_of(in);
         return p && visit_integer(v, p->ind);
     },
     "subindex (IND)"},
    {"dpscope.fc.pwe", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         const Pcv* p = pkw_of(in);
         return p && visit_integer(v, p->pva);
     },
     "parameter value (PWE high and low) as a 32-bit number"},
    {"dpscope.fc.fault", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         const Pcv* p = pkw_of(in);
         return p && in.t.direction == Direction::Response &&
                response_code(Dialect::Fc, p->rc).kind == ResponseKind::Rejected &&
                visit_integer(v, p->pva & 0xFFFF);
     },
     "fault code of a command the drive cannot carry out (AK 7)"},
}};

}  // namespace

std::span<const FilterField> fc_filter_fields() noexcept { return kFields; }

}  // namespace dpscope
