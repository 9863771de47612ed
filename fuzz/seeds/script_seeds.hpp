// Event scripts (fuzz/support/telegram_script.hpp) for the seed makers of the structure-aware
// targets (fuzz_trackers, fuzz_renderers, fuzz_reports): per bus a clean session as the simulator
// runs it (start-up, cyclic parameter access, DP-V1 parameter access, commands and answers), one
// with faults (retries, damaged and cut telegrams, negative answers, time-outs), and mixes of
// every event kind from a fixed pseudo-random sequence.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "fuzz/support/telegram_script.hpp"

namespace dpscope::fuzz {

using Seed = std::pair<std::string, std::vector<std::uint8_t>>;

namespace script_seeds_detail {

constexpr std::uint8_t k(DpEvent e) { return static_cast<std::uint8_t>(e); }
constexpr std::uint8_t k(FcEvent e) { return static_cast<std::uint8_t>(e); }
constexpr std::uint8_t k(VltEvent e) { return static_cast<std::uint8_t>(e); }

// The `who` byte of a PROFIBUS event: master index (0: 1, 1: 2), slave index (0..3: 3..6).
constexpr std::uint8_t who(std::uint8_t master, std::uint8_t slave) {
    return static_cast<std::uint8_t>(master | slave << 2);
}

// A PPO 1 Data_Exchange: request (code, PNU index, IND, value, PCD words) and response.
inline void dx(ScriptWriter& w, std::uint8_t step, std::uint8_t slave, std::uint8_t rc_request,
               std::uint8_t rc_response, std::uint8_t pnu_index, std::uint8_t ppo = 0) {
    w.event(step, k(DpEvent::DataExchange),
            {who(0, slave), ppo, rc_request, pnu_index, 0, 0x10, 0x04, 0x7F, 0x20, 0x00,
             rc_response, pnu_index, 0, 0x28, 0x0B, 0x87, 0x20, 0x00, 0x00});
}

inline Seed profibus_clean(bool dpv1) {
    ScriptWriter w(ScriptBus::Profibus, dpv1 ? 0x20 : 0x00, 3);
    for (std::uint8_t slave = 0; slave < 3; ++slave) {
        w.event(0x02, k(DpEvent::SlaveDiag), {who(0, slave), 0x02, 0x05});
        w.event(0x02, k(DpEvent::SetPrm),
                {who(0, slave), dpv1 ? std::uint8_t{0x0C} : std::uint8_t{0}});
        w.event(0x02, k(DpEvent::ChkCfg), {who(0, slave), slave});
        w.event(0x02, k(DpEvent::SlaveDiag), {who(0, slave), 0x00, 0x0C});
    }
    w.event(0x02, k(DpEvent::GlobalControl), {0, 0x00});
    w.event(0x02, k(DpEvent::Token), {0});
    for (std::uint8_t cycle = 0; cycle < 6; ++cycle)
        for (std::uint8_t slave = 0; slave < 3; ++slave) {
            // Read (AK 1) answered with a value (RC 1), write (AK 2) answered with RC 1, none.
            static constexpr std::uint8_t kRequest[] = {1, 2, 0, 6, 1, 0};
            static constexpr std::uint8_t kResponse[] = {1, 1, 0, 4, 7, 0};
            dx(w, 0x05, slave, kRequest[cycle], kResponse[cycle],
               static_cast<std::uint8_t>(cycle * 3 + slave), slave);
            if (dpv1 && slave == 0 && cycle % 2 == 0) {
                w.event(0x03, k(DpEvent::Dpv1Write),
                        {who(0, 0), 0x00, 0x01, 0x12, 0x10, 0x0A, 0x00});
                w.event(0x03, k(DpEvent::Dpv1Error), {who(0, 0), 0x00, 0x00});
                w.event(0x03, k(DpEvent::Dpv1Read),
                        {who(0, 0), 0x00, 0x01, 0x00, 0x42, 0x01, 0x00});
            }
        }
    w.event(0x03, k(DpEvent::Token), {0x21});
    return {dpv1 ? "profibus-dpv1-session" : "profibus-session", w.bytes()};
}

inline Seed profibus_faults() {
    ScriptWriter w(ScriptBus::Profibus, 0x01, 4);
    w.event(0x02, k(DpEvent::SetPrm), {who(0, 0), 0x0C});
    w.event(0x02, k(DpEvent::ChkCfg), {who(0, 0), 0x00});
    dx(w, 0x05, 0, 1, 1, 4);
    w.event(0x01, k(DpEvent::Retry), {0});
    w.event(0x01, k(DpEvent::Damaged), {0, 5, 0x40});
    w.event(0x01, k(DpEvent::Truncated), {0, 3});
    w.event(0x01, k(DpEvent::NegativeAnswer), {who(0, 1), 0x02});
    w.event(0x01, k(DpEvent::NegativeAnswer), {who(0, 1), 0x84});
    w.event(0x01, k(DpEvent::ShortAck), {0});
    w.event(0x01, k(DpEvent::DxRequest), {who(0, 2), 0x00, 0x01, 0x05, 0x00, 0x00, 0, 0, 0, 0});
    w.event(0xC2, k(DpEvent::DxResponse), {who(0, 2), 0x00, 0x01, 0x05, 0x00, 0x00, 0, 0, 0, 0, 0});
    w.event(0x01, k(DpEvent::Garbage), {0, 4, 0x68, 0x05, 0x05, 0x68});
    w.event(0x01, k(DpEvent::FdlStatus), {who(1, 3) | 0x40});
    w.event(0x01, k(DpEvent::Dpv1C2), {who(1, 1), 0x01});
    w.event(0x01, k(DpEvent::GetCfg), {who(0, 1), 0x05});
    w.event(0x01, k(DpEvent::SlaveDiag), {who(0, 1), 0x4E, 0x80, 0x01, 0x02, 0x03});
    w.event(0xFF, k(DpEvent::Token), {0x01});
    w.event(0x01, k(DpEvent::Token), {0x21});
    return {"profibus-faults", w.bytes()};
}

inline Seed fc_session(bool faults) {
    ScriptWriter w(ScriptBus::Fc, 0x00, 1);
    // who: drive index (bits 0-2), 1-31 format (bit 3); codes: AK (low), answer (high).
    static constexpr std::uint8_t kShapes[] = {0x00, 0x01, 0x01, 0x05, 0x02, 0x01};
    static constexpr std::uint8_t kCodes[] = {0x00, 0x11, 0x22, 0x3F, 0x2E, 0x12};
    for (std::uint8_t i = 0; i < 12; ++i) {
        const std::uint8_t shape = kShapes[i % 6];
        const std::uint8_t codes = kCodes[i % 6];
        w.event(0x04, k(FcEvent::Pair),
                {static_cast<std::uint8_t>(i % 3), codes, shape, i, 0x00, 0x20, 0x04, 0x7F, 0x20,
                 0x00, i, 0x00, 0x05, 0x06, 0x07, 0x08});
    }
    w.event(0x04, k(FcEvent::Broadcast), {0x00, 0x00, 0x04, 0x7F, 0x00, 0x00});
    if (faults) {
        w.event(0x01, k(FcEvent::Command), {0x01, 0x01, 0x01, 3, 0, 0x10, 0, 0, 0, 0});
        w.event(0x01, k(FcEvent::Command), {0x01, 0x02, 0x01, 3, 0, 0x10, 0, 0, 0, 0});
        w.event(0x42, k(FcEvent::Response), {0x02, 0x70, 0x01, 3, 0, 0x10, 0, 0, 0, 0});
        w.event(0x01, k(FcEvent::Damaged), {0x01, 3, 0x55});
        w.event(0x01, k(FcEvent::Truncated), {0x01, 5});
        w.event(0x01, k(FcEvent::Repeat), {0x01});
        w.event(0x01, k(FcEvent::Garbage), {0x00, 3, 0x02, 0x0E, 0x81});
        w.event(0xC3, k(FcEvent::Command), {0x00, 0x01, 0x01, 3, 0, 0x10, 0, 0, 0, 0});
    }
    return {faults ? "fc-faults" : "fc-session", w.bytes()};
}

inline Seed vlt2000_session(bool faults) {
    ScriptWriter w(ScriptBus::Vlt2000, 0x00, 1);
    // who: drive (bits 0-2), letter (bits 3-5: C R U I R C X r).
    for (std::uint8_t i = 0; i < 12; ++i) {
        const std::uint8_t who_byte = static_cast<std::uint8_t>((i % 3) | ((i % 4) << 3));
        w.event(0x04, k(VltEvent::Pair), {who_byte, 0x00, i, 0x10, 0x00, i, 0x14});
    }
    w.event(0x04, k(VltEvent::Broadcast), {0x00, 0x00, 0x00, 0x04});
    if (faults) {
        w.event(0x01, k(VltEvent::Pair), {0x09, 0x24, 0x05, 0x04, 0x05, 0x24});
        w.event(0x01, k(VltEvent::Command), {0x08, 0x00, 0x03, 0x00});
        w.event(0x01, k(VltEvent::Command), {0x08, 0x00, 0x03, 0x00});
        w.event(0x01, k(VltEvent::Reply), {0x49, 0x00, 0x03, 0x00});
        w.event(0x01, k(VltEvent::Damaged), {0x02, 12, 0x01});
        w.event(0x01, k(VltEvent::Truncated), {0x02, 10});
        w.event(0x01, k(VltEvent::Repeat), {0x02});
        w.event(0x01, k(VltEvent::Pair), {0x1A, 0xE0, 0x02, 0x00, 0xE0, 0x02, 0x00});
        w.event(0x01, k(VltEvent::Garbage), {0x00, 3, '<', '0', '1'});
        w.event(0xC3, k(VltEvent::Command), {0x08, 0x00, 0x03, 0x00});
    }
    return {faults ? "vlt2000-faults" : "vlt2000-session", w.bytes()};
}

// `count` events of random kinds with random fields, from a fixed sequence.
inline Seed mix(ScriptBus bus, std::uint32_t seed, std::size_t count) {
    std::uint32_t x = seed * 2654435761u + 1;
    auto next = [&x]() {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        return static_cast<std::uint8_t>(x);
    };
    std::vector<std::uint8_t> bytes = {static_cast<std::uint8_t>(bus), next(), next()};
    for (std::size_t i = 0; i < count * 8; ++i) {
        std::uint8_t b = next();
        // Time steps: mostly short.
        if (i % 8 == 0 && b >= 0x80 && (b & 7) != 0) b &= 0x3F;
        bytes.push_back(b);
    }
    static constexpr const char* kBus[] = {"profibus", "fc", "vlt2000"};
    return {std::string(kBus[static_cast<int>(bus)]) + "-mix-" + std::to_string(seed), bytes};
}

}  // namespace script_seeds_detail

// Every script seed: `mixes` random mixes per bus of `mix_events` events each.
inline std::vector<Seed> telegram_script_seeds(std::size_t mixes, std::size_t mix_events) {
    using namespace script_seeds_detail;
    std::vector<Seed> seeds = {profibus_clean(false), profibus_clean(true), profibus_faults(),
                               fc_session(false),     fc_session(true),     vlt2000_session(false),
                               vlt2000_session(true)};
    for (ScriptBus bus : {ScriptBus::Profibus, ScriptBus::Fc, ScriptBus::Vlt2000})
        for (std::uint32_t i = 0; i < mixes; ++i)
            seeds.push_back(mix(bus, i + 1, mix_events));
    return seeds;
}

}  // namespace dpscope::fuzz
