// Seeds of fuzz_renderers: event scripts (fuzz/seeds/script_seeds.hpp) of each bus, short (the
// target renders at most 6 telegrams): a clean session, one with faults, random mixes.
#include "script_seeds.hpp"
#include "seed_writer.hpp"

namespace dpscope::fuzz {

void make_seeds_fuzz_renderers(SeedWriter& writer) {
    for (const Seed& seed : telegram_script_seeds(40, 4))
        writer.add(seed.first, seed.second);
}

}  // namespace dpscope::fuzz
