// Arbitrary text through the filter language's parser (filter/display_filter.hpp), and what
// parses evaluated on a few telegrams of each bus, with findings and a health event.
// Invariants: a parse gives a filter or an error "column N: what" with N within the text (+1);
// evaluation neither crashes nor depends on anything but its input (the same input, the same
// answer); a filter and its negation never both select one telegram. The negation "!(text)" is
// three levels deeper than the text, so a text near the 64-level limit may parse while its
// negation is refused as nested too deep: that is the only refusal allowed.
#include <cstdint>
#include <string>
#include <string_view>

#include "filter/display_filter.hpp"

namespace {

void check(bool ok) {
    if (!ok) __builtin_trap();
}

dpscope::DecodedTelegram telegram(dpscope::Protocol protocol, bool response) {
    dpscope::DecodedTelegram t;
    t.protocol = protocol;
    t.frame = 7;
    t.direction = response ? dpscope::Direction::Response : dpscope::Direction::Request;
    t.has_roles = true;
    t.master = 2;
    t.slave = 5;
    t.dp.fdl.has_addresses = protocol == dpscope::Protocol::ProfibusDp;
    t.dp.fdl.sa = response ? 5 : 2;
    t.dp.fdl.da = response ? 2 : 5;
    t.dp.has_pcv = protocol == dpscope::Protocol::ProfibusDp;
    t.dp.pcv.rc = response ? 7 : 1;
    t.dp.pcv.pnu = 516;
    t.fc.has_pkw = protocol == dpscope::Protocol::Fc;
    t.fc.lge = 14;
    t.fc.pkw.rc = 1;
    t.fc.pkw.pnu = 1613;
    t.vlt2000.has_parameter = protocol == dpscope::Protocol::Vlt2000;
    t.vlt2000.parameter = 518;
    return t;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    dpscope::Result<dpscope::DisplayFilter> parsed = dpscope::DisplayFilter::parse(text);
    if (!parsed) {
        const std::string& error = parsed.error();
        check(error.rfind("column ", 0) == 0);
        const std::size_t column = std::stoul(error.substr(7));
        check(column >= 1 && column <= text.size() + 1);
        return 0;
    }
    dpscope::Result<dpscope::DisplayFilter> negated =
        dpscope::DisplayFilter::parse("!(" + std::string(text) + ")");
    if (!negated) check(negated.error().find("nested too deep") != std::string::npos);
    dpscope::Finding finding;
    finding.has_stations = true;
    finding.master = 2;
    finding.slave = 9;
    finding.pnu = 1613;
    const dpscope::Finding findings[] = {finding};
    const dpscope::FilterEvent events[] = {{"station_lost", "", 9}};
    for (dpscope::Protocol protocol :
         {dpscope::Protocol::ProfibusDp, dpscope::Protocol::Fc, dpscope::Protocol::Vlt2000})
        for (bool response : {false, true}) {
            const dpscope::DecodedTelegram t = telegram(protocol, response);
            const dpscope::FilterInput in{t, findings, 516, events};
            const bool selected = parsed->matches(in);
            check(selected == parsed->matches(in));
            if (negated) check(!(selected && negated->matches(in)));
        }
    return 0;
}
