// Seeds of fuzz_trackers: event scripts (fuzz/seeds/script_seeds.hpp) of each bus: a clean
// session, one with faults, and random mixes of every event kind.
#include "script_seeds.hpp"
#include "seed_writer.hpp"

namespace dpscope::fuzz {

void make_seeds_fuzz_trackers(SeedWriter& writer) {
    for (const Seed& seed : telegram_script_seeds(40, 60))
        writer.add(seed.first, seed.second);
}

}  // namespace dpscope::fuzz
