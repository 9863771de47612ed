// The PROFIBUS DP fields of the filter language (core/filter_field.hpp, docs/filter.md): the
// Wireshark plugin's names for the FDL header, the DP service, the PPO's parameter channel and
// process data, DP-V1 and PROFIdrive parameter access.
#include <array>
#include <span>

#include "core/code_tables.hpp"
#include "core/filter_field.hpp"
#include "protocols/profibus/dp_service.hpp"
#include "protocols/profibus/dp_telegram.hpp"
#include "protocols/profibus/dpv1/dpv1.hpp"
#include "protocols/profibus/dpv1/profidrive.hpp"
#include "protocols/profibus/fdl.hpp"

namespace dpscope {

namespace {

bool is_dp(const FilterInput& in) noexcept { return in.t.protocol == Protocol::ProfibusDp; }

// The cyclic parameter channel's PCV, when the telegram carries one.
const Pcv* pcv_of(const FilterInput& in) noexcept {
    return is_dp(in) && in.t.dp.has_pcv ? &in.t.dp.pcv : nullptr;
}

// Process data word `index` (0: CTW or STW, 1: the reference or actual value).
bool pcd_word(const FilterInput& in, std::size_t index, std::uint16_t& word) noexcept {
    if (!is_dp(in)) return false;
    const Bytes pcd = in.t.dp.pcd;
    if (pcd.size() < 2 * (index + 1)) return false;
    word = static_cast<std::uint16_t>(pcd[2 * index] << 8 | pcd[2 * index + 1]);
    return true;
}

const Dpv1Pdu* dpv1_of(const FilterInput& in) noexcept {
    return is_dp(in) ? in.t.dp.service_data.dpv1() : nullptr;
}
const ProfidriveMessage* profidrive_of(const FilterInput& in) noexcept {
    return is_dp(in) ? in.t.dp.service_data.profidrive() : nullptr;
}

const std::array<FilterField, 27> kFields{{
    {"dpscope.pnu", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         if (!is_dp(in)) return false;
         // The cyclic channel's as the tracker pairs it (a rejection that leaves the PNU out
         // is about its request's), then each one a PROFIdrive message addresses.
         if (in.t.dp.has_pcv && in.subject_pnu >= 0 && visit_integer(v, in.subject_pnu))
             return true;
         if (const ProfidriveMessage* m = profidrive_of(in))
             for (const ProfidriveAddress& a : m->addresses)
                 if (visit_integer(v, a.pnu)) return true;
         return false;
     },
     "the parameters the telegram is about: a PCV request and its answer (also a rejection "
     "that leaves the PNU out), each PNU a PROFIdrive message addresses"},
    {"dpscope.station", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         return is_dp(in) && in.t.dp.fdl.has_addresses &&
                (visit_integer(v, in.t.dp.fdl.da & 0x7F) ||
                 visit_integer(v, in.t.dp.fdl.sa & 0x7F));
     },
     "each station the telegram is to or from (with the findings about a station)"},
    {"dpscope.fdl.sa", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         return is_dp(in) && in.t.dp.fdl.has_addresses && visit_integer(v, in.t.dp.fdl.sa);
     },
     "source address (7 bits)"},
    {"dpscope.fdl.da", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         return is_dp(in) && in.t.dp.fdl.has_addresses && visit_integer(v, in.t.dp.fdl.da);
     },
     "destination address (7 bits)"},
    {"dpscope.fdl.sd", FilterType::Text,
     [](const FilterInput& in, const FilterVisitor& v) {
         return is_dp(in) && in.t.dp.fdl.type != FrameType::Invalid &&
                visit_text(v, frame_type_name(in.t.dp.fdl.type));
     },
     "frame type: \"SD1\", \"SD2\", \"SD3\", \"SD4\", \"SC\""},
    {"dpscope.fdl.fcs_ok", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         return is_dp(in) && visit_integer(v, in.t.dp.fdl.fcs_ok ? 1 : 0);
     },
     "1 (true) unless the FCS was read and is wrong"},
    {"dpscope.dp.service", FilterType::Text,
     [](const FilterInput& in, const FilterVisitor& v) {
         return is_dp(in) && in.t.dp.service != Service::Unknown &&
                visit_text(v, service_name(in.t.dp.service));
     },
     "DP service: \"Data_Exchange\", \"Slave_Diag\", \"Set_Prm\", \"MSAC_C1\", ..."},
    {"dpscope.ppo.type", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         return pcv_of(in) && in.t.dp.ppo.type != 0 && visit_integer(v, in.t.dp.ppo.type);
     },
     "PPO type (1 to 5) of a Data_Exchange telegram with a parameter channel"},
    {"dpscope.pcv", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         const Pcv* p = pcv_of(in);
         return p && visit_integer(v, p->pca);
     },
     "the parameter channel (its PCA word): present on Data_Exchange telegrams with a PCV"},
    {"dpscope.pcv.rc", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         const Pcv* p = pcv_of(in);
         return p && visit_integer(v, p->rc);
     },
     "request or response code (RC, AK)"},
    {"dpscope.pcv.spm", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         const Pcv* p = pcv_of(in);
         return p && visit_integer(v, p->spm ? 1 : 0);
     },
     "the spontaneous-message toggle bit"},
    {"dpscope.pcv.pnu", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         const Pcv* p = pcv_of(in);
         return p && visit_integer(v, p->pnu);
     },
     "parameter number as sent"},
    {"dpscope.pcv.ind", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         const Pcv* p = pcv_of(in);
         return p && visit_integer(v, p->ind);
     },
     "subindex (IND)"},
    {"dpscope.pcv.pva", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         const Pcv* p = pcv_of(in);
         return p && visit_integer(v, p->pva);
     },
     "parameter value bytes 5-8 (PVA, PWE) as a 32-bit number"},
    {"dpscope.pcv.error", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         const Pcv* p = pcv_of(in);
         return p && in.t.direction == Direction::Response &&
                response_code(in.t.dp.dialect, p->rc).kind == ResponseKind::Rejected &&
                visit_integer(v, p->pva & 0xFFFF);
     },
     "error number of a rejected request (RC 7)"},
    {"dpscope.pcv.dialect", FilterType::Text,
     [](const FilterInput& in, const FilterVisitor& v) {
         return pcv_of(in) && visit_text(v, dialect_name(in.t.dp.dialect));
     },
     "the channel's dialect: \"vlt\", \"ge\", \"profidrive\""},
    {"dpscope.pcd.ctw", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         std::uint16_t w = 0;
         return in.t.direction == Direction::Request && pcd_word(in, 0, w) && visit_integer(v, w);
     },
     "control word (process data word 1 of a request)"},
    {"dpscope.pcd.stw", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         std::uint16_t w = 0;
         return in.t.direction == Direction::Response && pcd_word(in, 0, w) && visit_integer(v, w);
     },
     "status word (process data word 1 of a response)"},
    {"dpscope.pcd.ref", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         std::uint16_t w = 0;
         return pcd_word(in, 1, w) && visit_integer(v, w);
     },
     "process data word 2: the reference (MRV) or the actual value (MAV)"},
    {"dpscope.dpv1.function", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         const Dpv1Pdu* p = dpv1_of(in);
         return p && visit_integer(v, p->function);
     },
     "DP-V1 function number as sent (0x5E Read, 0x5F Write; bit 7: negative)"},
    {"dpscope.dpv1.slot", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         const Dpv1Pdu* p = dpv1_of(in);
         return p && visit_integer(v, p->slot);
     },
     "DP-V1 slot"},
    {"dpscope.dpv1.index", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         const Dpv1Pdu* p = dpv1_of(in);
         return p && visit_integer(v, p->index);
     },
     "DP-V1 index (47: PROFIdrive parameter access)"},
    {"dpscope.profidrive.pnu", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         if (const ProfidriveMessage* m = profidrive_of(in))
             for (const ProfidriveAddress& a : m->addresses)
                 if (visit_integer(v, a.pnu)) return true;
         return false;
     },
     "each parameter number a PROFIdrive request or response addresses"},
    {"dpscope.profidrive.id", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         const ProfidriveMessage* m = profidrive_of(in);
         return m && m->has_header && visit_integer(v, m->id);
     },
     "PROFIdrive request or response ID"},
    {"dpscope.profidrive.reference", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         const ProfidriveMessage* m = profidrive_of(in);
         return m && m->has_header && visit_integer(v, m->reference);
     },
     "PROFIdrive request reference"},
    {"dpscope.profidrive.attribute", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         if (const ProfidriveMessage* m = profidrive_of(in))
             for (const ProfidriveAddress& a : m->addresses)
                 if (visit_integer(v, a.attribute)) return true;
         return false;
     },
     "each attribute addressed (0x10 value, 0x20 description, 0x30 text)"},
    {"dpscope.profidrive.error", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         if (const ProfidriveMessage* m = profidrive_of(in))
             for (const ProfidriveValueBlock& b : m->blocks)
                 if (b.is_error() && b.values.size() >= 2 && visit_integer(v, b.error_number()))
                     return true;
         return false;
     },
     "each error number in a PROFIdrive response"},
}};

}  // namespace

std::span<const FilterField> profibus_filter_fields() noexcept { return kFields; }

}  // namespace dpscope
