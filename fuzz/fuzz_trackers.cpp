// The trackers, structure-aware: the input is an event script (fuzz/support/telegram_script.hpp)
// from which well-formed telegrams are built (bus, stations, RC/AK codes, PNU, IND, values, time
// steps with gaps past every time-out, a few damaged on purpose), so mutations reach the rules
// behind the checksums rather than the checksums. Each telegram is decoded by the bus's real
// decoder and tracked: PROFIBUS DP by a SessionTracker (DP link rules, parameter-channel engine,
// DP-V1 parameter access) and a BusHealthTracker (judged every few telegrams), Danfoss FC by an
// FcTracker, VLT 2000 by a Vlt2000Tracker; at the end the trackers are finished and the bus
// health judged. One target serves all three buses (the script's first byte chooses): they share
// the script and each run stays short (at most kMaxTelegrams telegrams).
//
// Invariants checked (a violation traps): every finding names a telegram that was seen (its frame,
// and its request's, at most the current one; the request not after the finding), every completed
// transaction's answer is a telegram seen, the trackers' per-severity counts equal the findings
// they returned, and the bus-health segment counted every telegram fed.
#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>

#include "fuzz/support/fuzz_input.hpp"
#include "fuzz/support/telegram_script.hpp"
#include "protocols/fc/fc_decoder.hpp"
#include "protocols/fc/fc_tracker.hpp"
#include "protocols/profibus/bus_decoder.hpp"
#include "protocols/profibus/health/bus_health.hpp"
#include "protocols/profibus/session_tracker.hpp"
#include "protocols/vlt2000/vlt2000_decoder.hpp"
#include "protocols/vlt2000/vlt2000_tracker.hpp"

namespace {

using namespace dpscope;

constexpr std::size_t kMaxTelegrams = 40;

void check(bool ok) {
    if (!ok) __builtin_trap();
}

struct Counts {
    std::uint64_t findings = 0;
};

void check_findings(std::span<const Finding> findings, std::uint64_t last_frame, Counts& counts) {
    for (const Finding& f : findings) {
        check(f.frame <= last_frame);
        check(f.request_frame <= last_frame);
        check(f.request_frame == 0 || f.frame == 0 || f.request_frame <= f.frame);
        ++counts.findings;
    }
}

void check_completed(std::span<const CompletedTransaction> done, std::uint64_t frame) {
    for (const CompletedTransaction& c : done)
        check(c.frame >= 1 && c.frame <= frame);
}

template <class Tracker>
void check_totals(const Tracker& tracker, const Counts& counts) {
    check(tracker.findings(Severity::Error) + tracker.findings(Severity::Warning) +
              tracker.findings(Severity::Note) ==
          counts.findings);
}

// Decodes and tracks every telegram of the script with the bus's decoder and tracker (and, on
// PROFIBUS, a BusHealthTracker).
template <class Decoder, class Tracker>
void run_lane(const fuzz::TelegramScript& script, Decoder& decoder, Tracker& tracker,
              BusHealthTracker* health) {
    Counts counts;
    std::uint64_t frame = 0;
    for (const fuzz::ScriptedTelegram& s : script.telegrams) {
        frame = s.frame;
        const DecodedTelegram& t = decoder.decode(script.telegram_bytes(s), s.time_ns, s.frame);
        check(t.frame == s.frame);
        check(t.request_frame < s.frame);
        check_findings(tracker.track(t), frame, counts);
        check_completed(tracker.completed(), frame);
        (void)tracker.subject_pnu();
        if (health) {
            (void)health->observe(t);
            if (s.frame % 32 == 0) (void)health->judge();
        }
    }
    check_findings(tracker.finish(), frame, counts);
    check_totals(tracker, counts);
    (void)tracker.transactions();
    if (health) {
        health->finish();
        const BusHealth& h = health->health();
        check(h.segment.telegrams == script.telegrams.size());
        for (std::size_t i = 1; i < h.stations.size(); ++i)
            check(h.stations[i - 1].address < h.stations[i].address);
        for (const StationHealth& st : h.stations) {
            check(st.timeline.size() <= BusHealthTracker::kMaxStateChanges);
            check(st.state_changes >= st.timeline.size());
            (void)st.judgement.verdict;
        }
        (void)health->judge();
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static fuzz::TelegramScript script;
    fuzz::FuzzInput in(data, size);
    fuzz::build_telegram_script(in, script, kMaxTelegrams);
    fuzz::with_script_bus(script, [&](auto& decoder, auto& tracker) {
        if constexpr (std::is_same_v<std::remove_cvref_t<decltype(decoder)>, BusDecoder>) {
            BusHealthOptions options;
            options.baud = script.baud;
            (void)options.thresholds.set(HealthThreshold::LostCycles,
                                         1 + (size > 0 ? data[0] >> 2 : 0) % 5);
            BusHealthTracker health(options);
            run_lane(script, decoder, tracker, &health);
        } else {
            run_lane(script, decoder, tracker, nullptr);
        }
    });
    return 0;
}
