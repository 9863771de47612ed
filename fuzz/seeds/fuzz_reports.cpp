// Seeds of fuzz_reports: the event scripts of fuzz/seeds/script_seeds.hpp behind the three choice
// bytes (report format, --fail-on, --allow-empty, --station, statistics instead of the report;
// stats format; live-table width), each script once per report format and once per stats format.
#include <string>

#include "script_seeds.hpp"
#include "seed_writer.hpp"

namespace dpscope::fuzz {

void make_seeds_fuzz_reports(SeedWriter& writer) {
    static constexpr const char* kReport[] = {"text", "json", "markdown", "html", "junit"};
    static constexpr const char* kStats[] = {"text", "json", "markdown", "html", "csv"};
    for (const Seed& seed : telegram_script_seeds(12, 8))
        for (std::uint8_t format = 0; format < 5; ++format) {
            // fail-on cycles with the format; every other seed filters station 3 or 4.
            const std::uint8_t report = static_cast<std::uint8_t>(
                format | (format % 3) << 3 | (format & 1) << 5 | (format == 2) << 6);
            const std::uint8_t stats = static_cast<std::uint8_t>(format << 5 | (3 + format % 2));
            const std::uint8_t width = static_cast<std::uint8_t>(format * 30);
            std::vector<std::uint8_t> bytes = {report, stats, width};
            bytes.insert(bytes.end(), seed.second.begin(), seed.second.end());
            writer.add(seed.first + "-" + kReport[format], bytes);
            // The same with the statistics instead of the report (PROFIBUS scripts only use it).
            bytes[0] = static_cast<std::uint8_t>(report | 0x80);
            writer.add(seed.first + "-stats-" + kStats[format], bytes);
        }
}

}  // namespace dpscope::fuzz
