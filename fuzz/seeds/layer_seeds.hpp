// What the seed makers of the framer and decoder targets share: the telegrams of a sample capture
// (read through dpscope's own source, capture/telegram_source.hpp) and of a simulated session
// (simulator/simulator.hpp, faults included), and the seeds made of them: byte streams cut into
// pieces for a framer, single telegrams behind a header for a decoder.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/protocol_descriptor.hpp"
#include "capture/telegram_source.hpp"
#include "seed_writer.hpp"
#include "simulator/fault_kind.hpp"
#include "simulator/fault_spec.hpp"
#include "simulator/simulator.hpp"

namespace dpscope::fuzz {

using Telegrams = std::vector<std::vector<std::uint8_t>>;

// Every record of samples/NAME, read as a capture of `protocol`.
inline Telegrams sample_telegrams(const SeedWriter& writer, const std::string& name,
                                  const ProtocolDescriptor& protocol) {
    const std::string path = (writer.source_dir() / "samples" / name).string();
    OpenResult opened = open_source(path, InputFormat::Auto, protocol);
    if (!opened) throw std::runtime_error("cannot open " + path);
    std::unique_ptr<TelegramSource> source = std::move(opened.value());
    source->on_issue([](const InputIssue&) {});
    Telegrams out;
    Record record;
    while (source->next(record))
        out.emplace_back(record.bytes.begin(), record.bytes.end());
    return out;
}

// The telegrams of a simulated session of `options` (at most `max` of them).
inline Telegrams simulated_telegrams(SimulatorOptions options, std::uint64_t max) {
    options.max_telegrams = max;
    Simulator simulator(std::move(options));
    Telegrams out;
    std::vector<std::uint8_t> bytes;
    std::int64_t time_ns = 0;
    while (simulator.next(bytes, time_ns))
        out.push_back(bytes);
    return out;
}

// Simulated sessions on `bus` (slaves as `--slave` specs for PROFIBUS): one without faults, then
// one per fault kind the simulator can inject on that bus, injected at cycle 2 (a kind the
// session cannot take, e.g. a fault of another bus, is left out). Each at most `max` telegrams.
inline std::vector<Telegrams> simulated_sessions(Protocol bus,
                                                 const std::vector<std::string>& slaves,
                                                 std::uint64_t max) {
    SimulatorOptions base;
    base.bus = bus;
    base.cycles = 0;
    base.baud = 0;
    for (const std::string& text : slaves) {
        auto slave = parse_slave_spec(text);
        if (!slave) throw std::runtime_error("bad slave spec " + text);
        base.slaves.push_back(slave.value());
    }
    std::vector<Telegrams> sessions;
    sessions.push_back(simulated_telegrams(base, max));
    for (std::size_t k = 0; k < kFaultKindCount; ++k) {
        SimulatorOptions options = base;
        options.seed = k + 2;
        options.faults.push_back(FaultSpec{static_cast<FaultKind>(k), 0, 2, std::nullopt});
        if (!check_simulator_faults(options)) continue;
        sessions.push_back(simulated_telegrams(options, max));
    }
    return sessions;
}

// Framer seeds: the telegrams of `telegrams` as one byte stream, cut into pieces of at most
// `piece` bytes (at telegram boundaries where possible), each behind a 2-byte header of chunk
// and gap choices (fuzz/support/framer_check.hpp) that changes from piece to piece.
inline void add_stream_pieces(SeedWriter& writer, const std::string& name,
                              const Telegrams& telegrams, std::size_t piece) {
    static constexpr std::uint8_t kHeaders[][2] = {{0x00, 0x00}, {0xFF, 0x00}, {0x55, 0x3F},
                                                   {0xE4, 0x27}, {0xAA, 0x1A}, {0x1B, 0x85}};
    std::vector<std::uint8_t> current;
    std::size_t count = 0;
    auto flush = [&] {
        if (current.empty()) return;
        std::vector<std::uint8_t> seed(std::begin(kHeaders[count % 6]),
                                       std::end(kHeaders[count % 6]));
        seed.insert(seed.end(), current.begin(), current.end());
        writer.add(name + "-" + std::to_string(count++), seed);
        current.clear();
    };
    for (const auto& telegram : telegrams) {
        if (!current.empty() && current.size() + telegram.size() > piece) flush();
        current.insert(
            current.end(), telegram.begin(),
            telegram.begin() + static_cast<std::ptrdiff_t>(std::min(telegram.size(), piece)));
    }
    flush();
}

// Decoder seeds: each telegram of `telegrams` whose size and first `key_bytes` bytes no telegram
// before had (in `seen`: the kinds, not every value), once behind each of `headers` (2 bytes
// each: the target's options and context).
inline void add_single_telegrams(SeedWriter& writer, const std::string& name,
                                 const Telegrams& telegrams,
                                 const std::vector<std::array<std::uint8_t, 2>>& headers,
                                 std::size_t key_bytes, std::set<std::vector<std::uint8_t>>& seen) {
    std::size_t count = 0;
    for (const auto& telegram : telegrams) {
        std::vector<std::uint8_t> key(
            telegram.begin(),
            telegram.begin() + static_cast<std::ptrdiff_t>(std::min(key_bytes, telegram.size())));
        key.push_back(static_cast<std::uint8_t>(telegram.size()));
        if (!seen.insert(key).second) continue;
        for (const auto& header : headers) {
            std::vector<std::uint8_t> seed(header.begin(), header.end());
            seed.insert(seed.end(), telegram.begin(), telegram.end());
            writer.add(name + "-" + std::to_string(count++), seed);
        }
    }
}

}  // namespace dpscope::fuzz
