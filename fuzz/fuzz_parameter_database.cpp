// Arbitrary text through the drive parameter database parser (drives/parameter_database.hpp).
// Invariants: a parse gives a family or an error that names the file and a line; a family's rows
// are sorted by PNU without repeats, each found by its PNU, with a name and source of valid UTF-8
// and a source index into the family's sources; a PNU written as the family writes it reads back
// as the same PNU; scaling any value of any row neither crashes nor gives a non-finite number;
// a family added twice to a database keeps one row a PNU.
#include <cmath>
#include <cstdint>
#include <string_view>

#include "core/text_encoding.hpp"
#include "drives/parameter_database.hpp"

namespace {

void check(bool ok) {
    if (!ok) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    dpscope::Result<dpscope::ParameterFile> parsed =
        dpscope::parse_parameter_database(text, "fuzz.params");
    if (!parsed) {
        check(parsed.error().rfind("fuzz.params:", 0) == 0);
        return 0;
    }
    const dpscope::ParameterFamily& family = parsed->family;
    check(!family.id.empty() && !family.title.empty());
    for (const std::string& warning : parsed->warnings)
        check(warning.rfind("fuzz.params:", 0) == 0);
    for (std::size_t i = 0; i < family.rows.size(); ++i) {
        const dpscope::ParameterRow& row = family.rows[i];
        if (i > 0) check(family.rows[i - 1].pnu < row.pnu);
        check(family.find(row.pnu) == &row);
        check(!row.name.empty() && dpscope::is_valid_utf8(row.name));
        check(dpscope::is_valid_utf8(row.unit) && dpscope::is_valid_utf8(row.source));
        check(row.source_index < family.sources.size());
        check(row.elements >= 1);
        check(dpscope::parse_pnu_text(family.format_pnu(row.pnu)) == row.pnu);
        for (std::uint32_t bits : {0u, 1u, 0x7FFFu, 0x8000u, 0xFFFFu, 0x80000000u, 0xFFFFFFFFu}) {
            const std::int64_t raw = dpscope::raw_value_of_type(row.type, bits);
            if (const auto scaled = dpscope::scale_value(row, raw)) {
                check(std::isfinite(scaled->value));
                check(scaled->decimals >= 0 && scaled->decimals <= 7);
                check(!dpscope::format_scaled(*scaled).empty());
            }
        }
    }
    dpscope::ParameterDatabase database;
    database.add(family);
    database.add(family);
    check(database.families().size() == 1);
    check(database.families().front().rows.size() == family.rows.size());
    return 0;
}
