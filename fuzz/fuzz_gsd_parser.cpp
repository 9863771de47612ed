// Arbitrary text through the GSD parser (protocols/profibus/gsd/gsd_file.hpp). Invariants: a
// parse gives a device or an error that names the file and a line; every text of a device is
// valid UTF-8 (8-bit text is converted); every user parameter's bits lie in a byte and its range
// is ordered; what the lookups find is what the lists hold.
#include <cstdint>
#include <string_view>

#include "core/text_encoding.hpp"
#include "protocols/profibus/gsd/gsd_file.hpp"

namespace {

void check(bool ok) {
    if (!ok) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    dpscope::Result<dpscope::GsdDevice> parsed = dpscope::parse_gsd(text, "fuzz.gsd");
    if (!parsed) {
        check(parsed.error().rfind("fuzz.gsd:", 0) == 0);
        return 0;
    }
    const dpscope::GsdDevice& d = *parsed;
    check(dpscope::is_valid_utf8(d.vendor) && dpscope::is_valid_utf8(d.model) &&
          dpscope::is_valid_utf8(d.revision));
    for (const dpscope::GsdModule& m : d.modules)
        check(dpscope::is_valid_utf8(m.name));
    for (const dpscope::GsdUserPrm& p : d.user_prms) {
        check(dpscope::is_valid_utf8(p.name));
        check(p.first_bit <= p.last_bit && p.last_bit <= 7);
        check(p.min_value <= p.max_value);
        check(d.user_prm(p.reference) != nullptr);
    }
    for (const dpscope::GsdPrmText& t : d.prm_texts) {
        check(d.prm_text(t.reference) != nullptr);
        for (const dpscope::GsdValueText& v : t.texts)
            check(dpscope::is_valid_utf8(v.text));
    }
    for (const dpscope::GsdDiagArea& a : d.unit_diag_areas)
        check(a.first_bit <= a.last_bit);
    for (const dpscope::GsdMaxTsdr& t : d.max_tsdr)
        check(d.max_tsdr_at(t.rate).has_value());
    return 0;
}
