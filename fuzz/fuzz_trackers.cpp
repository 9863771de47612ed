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
// they returned, and the bus-health segment counted every telegram fed. A second bus-health
// tracker without the steady path (BusHealthOptions::steady_path) is fed the same telegrams: its
// events, telegram by telegram, and its figures at every judgement must be the first one's.
#include <fmt/format.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <type_traits>

#include "formats/json_writer.hpp"
#include "fuzz/support/fuzz_input.hpp"
#include "fuzz/support/telegram_script.hpp"
#include "protocols/fc/fc_decoder.hpp"
#include "protocols/fc/fc_tracker.hpp"
#include "protocols/profibus/bus_decoder.hpp"
#include "protocols/profibus/health/bus_health.hpp"
#include "protocols/profibus/health/health_render.hpp"
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

// Every figure of the bus health as the stats JSON writes it.
std::string health_json(const BusHealth& h) {
    fmt::memory_buffer out;
    {
        JsonWriter w(out);
        w.begin_object();
        health::write_json_members(w, h);
        w.end_object();
    }
    return fmt::to_string(out);
}

bool same_events(std::span<const HealthEvent> a, std::span<const HealthEvent> b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (a[i].kind != b[i].kind || a[i].address != b[i].address ||
            a[i].time_ns != b[i].time_ns || a[i].frame != b[i].frame || a[i].role != b[i].role)
            return false;
    return true;
}

// Decodes and tracks every telegram of the script with the bus's decoder and tracker (and, on
// PROFIBUS, a BusHealthTracker and `full`, one without the steady path, compared with it).
template <class Decoder, class Tracker>
void run_lane(const fuzz::TelegramScript& script, Decoder& decoder, Tracker& tracker,
              BusHealthTracker* health, BusHealthTracker* full = nullptr) {
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
            const std::span<const HealthEvent> events = health->observe(t);
            check(same_events(events, full->observe(t)));
            if (s.frame % 32 == 0) {
                check(same_events(health->judge(), full->judge()));
                check(health_json(health->health()) == health_json(full->health()));
            }
        }
    }
    check_findings(tracker.finish(), frame, counts);
    check_totals(tracker, counts);
    (void)tracker.transactions();
    if (health) {
        health->finish();
        full->finish();
        check(health_json(health->health()) == health_json(full->health()));
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
            BusHealthOptions full_options = options;
            full_options.steady_path = false;
            BusHealthTracker full(full_options);
            run_lane(script, decoder, tracker, &health, &full);
        } else {
            run_lane(script, decoder, tracker, nullptr);
        }
    });
    return 0;
}
