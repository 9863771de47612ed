// The bus simulator: reproducible sessions, the start-up sequence of each slave, clean cyclic
// traffic, fault injection, and the fault and slave specifications of the command line.
#include "simulator/simulator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "capture/telegram_source.hpp"
#include "core/protocol_descriptor.hpp"
#include "simulator/bus_model.hpp"
#include "protocols/profibus/bus_decoder.hpp"
#include "protocols/profibus/dp_payload.hpp"
#include "protocols/profibus/dpv1/profidrive.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::hex;

struct Telegram {
    std::vector<std::uint8_t> bytes;
    std::int64_t time_ns;
};

std::vector<Telegram> run(Simulator& simulator) {
    std::vector<Telegram> out;
    std::vector<std::uint8_t> bytes;
    std::int64_t time_ns = 0;
    while (simulator.next(bytes, time_ns))
        out.push_back({bytes, time_ns});
    return out;
}

std::vector<Telegram> run(const SimulatorOptions& options) {
    Simulator simulator(options);
    return run(simulator);
}

SimulatorOptions small_session(std::uint64_t seed = 1, std::uint64_t cycles = 50) {
    SimulatorOptions options;
    options.seed = seed;
    options.cycles = cycles;
    return options;
}

// What a decoded telegram says, copied out of the decoder's reused result.
struct Decoded {
    FrameType type;
    Service service;
    Direction direction;
    std::uint8_t master;
    std::uint8_t slave;
    std::vector<std::uint8_t> du;
    bool fcs_ok;
    std::vector<ProblemKind> problems;
};

std::vector<Decoded> decode_all(const std::vector<Telegram>& telegrams, BusDecoder& decoder) {
    std::vector<Decoded> out;
    for (std::size_t i = 0; i < telegrams.size(); ++i) {
        const Telegram& t = telegrams[i];
        const DecodedTelegram& d =
            decoder.decode(Bytes(t.bytes.data(), t.bytes.size()), t.time_ns, i + 1);
        Decoded copy{
            d.dp.fdl.type,   d.dp.service,
            d.direction,     d.master,
            d.slave,         std::vector<std::uint8_t>(d.dp.fdl.du.begin(), d.dp.fdl.du.end()),
            d.dp.fdl.fcs_ok, {}};
        for (const Problem& p : d.problems())
            copy.problems.push_back(p.kind);
        out.push_back(copy);
    }
    return out;
}

// ---- reproducibility and timing --------------------------------------------------------------

// The table of simulated buses (simulator/bus_model.hpp), made from the registration list: every
// protocol has a record of its own with what the session asks; PROFIBUS DP is the session's own
// traffic, every other bus a model whose drives get one fault entry each.
TEST(SimulatorTest, EveryProtocolHasItsSimulatedBus) {
    for (const ProtocolDescriptor* d : protocol_table()) {
        const SimulatedBus& bus = simulated_bus(d->protocol);
        EXPECT_EQ(bus.protocol, d->protocol) << d->name;
        EXPECT_NE(bus.check_faults, nullptr) << d->name;
        EXPECT_NE(bus.span_bound_ns, nullptr) << d->name;
        EXPECT_TRUE(bus.character_bits == 10 || bus.character_bits == 11) << d->name;
        EXPECT_EQ(bus.make_model == nullptr, d->protocol == Protocol::ProfibusDp) << d->name;
        if (bus.make_model) {
            EXPECT_NE(bus.fault_applies, nullptr) << d->name;
            SimulatorOptions options;
            options.bus = d->protocol;
            options.baud = 0;
            std::vector<std::uint8_t> drives;
            std::unique_ptr<BusModel> model = bus.make_model(options, drives);
            EXPECT_NE(model, nullptr) << d->name;
            EXPECT_FALSE(drives.empty()) << d->name;
            EXPECT_EQ(options.baud, d->default_baud) << d->name;  // what it left open, filled in
            EXPECT_TRUE(bus.check_faults(options)) << d->name;
            EXPECT_GT(bus.span_bound_ns(options), 0) << d->name;
        }
    }
}

TEST(SimulatorTest, SameSeedGivesIdenticalSessions) {
    std::vector<Telegram> a = run(small_session(7));
    std::vector<Telegram> b = run(small_session(7));
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        ASSERT_EQ(a[i].bytes, b[i].bytes) << i;
        ASSERT_EQ(a[i].time_ns, b[i].time_ns) << i;
    }
}

TEST(SimulatorTest, DifferentSeedGivesDifferentSessions) {
    std::vector<Telegram> a = run(small_session(7));
    std::vector<Telegram> b = run(small_session(8));
    bool differ = a.size() != b.size();
    for (std::size_t i = 0; !differ && i < a.size(); ++i)
        differ = a[i].bytes != b[i].bytes || a[i].time_ns != b[i].time_ns;
    EXPECT_TRUE(differ);
}

TEST(SimulatorTest, TimesStrictlyIncreaseFromTheStartTime) {
    SimulatorOptions options = small_session(3, 300);
    std::vector<Telegram> telegrams = run(options);
    ASSERT_FALSE(telegrams.empty());
    EXPECT_GT(telegrams[0].time_ns, options.start_time_ns);
    EXPECT_LT(telegrams[0].time_ns, options.start_time_ns + 1'000'000);
    for (std::size_t i = 1; i < telegrams.size(); ++i)
        ASSERT_GT(telegrams[i].time_ns, telegrams[i - 1].time_ns) << i;
    // 300 cycles of 2 ms at least.
    EXPECT_GE(telegrams.back().time_ns - telegrams[0].time_ns, 299 * 2'000'000LL);
}

TEST(SimulatorTest, MaxTelegramsIsHonoured) {
    SimulatorOptions options = small_session(1, 1000);
    options.max_telegrams = 57;
    Simulator simulator(options);
    std::vector<Telegram> telegrams = run(simulator);
    EXPECT_EQ(telegrams.size(), 57u);
    EXPECT_EQ(simulator.telegrams(), 57u);
    std::vector<std::uint8_t> bytes;
    std::int64_t time_ns = 0;
    EXPECT_FALSE(simulator.next(bytes, time_ns));
    // The limit also ends an endless session (cycles 0).
    options.cycles = 0;
    options.max_telegrams = 500;
    EXPECT_EQ(run(options).size(), 500u);
}

// Runs at most `limit` telegrams, so that a session that would not end fails instead of hanging.
std::vector<Telegram> run_at_most(Simulator& simulator, std::size_t limit) {
    std::vector<Telegram> out;
    std::vector<std::uint8_t> bytes;
    std::int64_t time_ns = 0;
    while (out.size() < limit && simulator.next(bytes, time_ns))
        out.push_back({bytes, time_ns});
    return out;
}

TEST(SimulatorTest, EndsAfterItsCyclesWhateverTheStartTime) {
    // Regression: a start time before 1970 ran on until 1970 (5 s of traffic for --start -5, 292
    // years for NaN), and one near the end of int64 wrapped round and never ended.
    constexpr std::int64_t kMax = std::numeric_limits<std::int64_t>::max();
    const std::size_t expected = run(small_session(3, 100)).size();
    for (std::int64_t start :
         {std::int64_t{0}, std::int64_t{-5'000'000'000}, std::numeric_limits<std::int64_t>::min(),
          std::int64_t{1'000'000'000'000'000'000}, kMax - 1'000'000, kMax}) {
        SCOPED_TRACE(start);
        SimulatorOptions options = small_session(3, 100);
        options.start_time_ns = start;
        Simulator simulator(options);
        std::vector<Telegram> telegrams = run_at_most(simulator, 10 * expected);
        EXPECT_EQ(telegrams.size(), expected);
        ASSERT_FALSE(telegrams.empty());
        EXPECT_GE(telegrams[0].time_ns, std::max<std::int64_t>(0, start));
        for (std::size_t i = 1; i < telegrams.size(); ++i)
            ASSERT_GE(telegrams[i].time_ns, telegrams[i - 1].time_ns) << i;  // never wraps
        if (start == kMax) {
            EXPECT_EQ(telegrams.back().time_ns, kMax);
        }
    }
}

TEST(SimulatorTest, WithoutCyclesOrCountTheSessionIsTheStartUp) {
    SimulatorOptions options = small_session(3, 0);
    Simulator simulator(options);
    // Three slaves: ten telegrams each, then Global_Control and the token.
    EXPECT_EQ(run_at_most(simulator, 10'000).size(), 3u * 10 + 2);
}

TEST(SimulatorTest, TimeOutFaultsAtARateStillEnd) {
    // Regression: each time-out injected while the session ran on for the previous one kept it
    // open again, for ever.
    SimulatorOptions options = small_session(3, 100);
    options.faults = {
        FaultSpec{FaultKind::ResponseTimeout, 1.0, std::nullopt, std::nullopt},
        FaultSpec{FaultKind::SpontaneousUnacknowledged, 1.0, std::nullopt, std::nullopt}};
    Simulator simulator(options);
    std::vector<Telegram> telegrams = run_at_most(simulator, 100'000);
    ASSERT_LT(telegrams.size(), 100'000u);
    for (const Injection& injection : simulator.injections())
        EXPECT_LT(injection.cycle, 100u);  // nothing is injected past the session's cycles
    // It ran on until the master gave up (1.5 s), not much longer.
    std::int64_t span = telegrams.back().time_ns - options.start_time_ns;
    EXPECT_GT(span, 1'500'000'000);
    EXPECT_LT(span, 2'000'000'000);
}

TEST(SimulatorTest, SessionSpanBoundHoldsWithEveryFault) {
    std::vector<FaultSpec> faults;
    for (std::size_t i = 0; i < static_cast<std::size_t>(FaultKind::Count); ++i)
        faults.push_back(FaultSpec{static_cast<FaultKind>(i), 0.05, std::nullopt, std::nullopt});
    struct Case {
        std::uint32_t baud;
        std::uint32_t cycle_us;
        std::uint64_t cycles;
        std::uint64_t max_telegrams;
    };
    for (const Case& c : {Case{9600, 100, 200, 0}, Case{1'500'000, 2000, 300, 0},
                          Case{12'000'000, 100, 0, 5000}, Case{19'200, 1000, 1000, 700}}) {
        SCOPED_TRACE(c.baud);
        SimulatorOptions options = small_session(5, c.cycles);
        options.baud = c.baud;
        options.cycle_us = c.cycle_us;
        options.max_telegrams = c.max_telegrams;
        options.faults = faults;
        options.slaves = {{3, 1, Dialect::Vlt},
                          {4, 5, Dialect::Vlt, true},
                          {6, 2, Dialect::Profidrive},
                          {7, 3, Dialect::Profidrive, true}};
        std::vector<Telegram> telegrams = run(options);
        ASSERT_FALSE(telegrams.empty());
        EXPECT_LE(telegrams.back().time_ns - options.start_time_ns, session_span_bound_ns(options));
    }
    SimulatorOptions endless = small_session(1, 0);
    endless.max_telegrams = std::numeric_limits<std::uint64_t>::max();
    EXPECT_EQ(session_span_bound_ns(endless), std::numeric_limits<std::int64_t>::max());
}

TEST(SimulatorTest, DefaultSlaves) {
    Simulator simulator(SimulatorOptions{});
    ASSERT_EQ(simulator.slaves().size(), 3u);
    EXPECT_EQ(simulator.slaves()[0].address, 3);
    EXPECT_EQ(simulator.slaves()[0].ppo_type, 1);
    EXPECT_EQ(simulator.slaves()[1].address, 4);
    EXPECT_EQ(simulator.slaves()[1].ppo_type, 2);
    EXPECT_EQ(simulator.slaves()[2].address, 5);
    EXPECT_EQ(simulator.slaves()[2].ppo_type, 5);
    EXPECT_EQ(simulator.slaves()[2].dialect, Dialect::Vlt);
}

// ---- start-up --------------------------------------------------------------------------------

struct StartUpCase {
    SimulatedSlave slave;
    std::vector<std::uint8_t> cfg;
    std::uint16_t ident;
};

TEST(SimulatorTest, StartUpSequencePerSlave) {
    const std::vector<StartUpCase> cases = {
        {{3, 1, Dialect::Vlt}, hex("F3 F1"), 0x0402},
        {{4, 2, Dialect::Vlt}, hex("F3 F5"), 0x0402},
        {{5, 3, Dialect::Vlt}, hex("F1"), 0x0402},
        {{6, 4, Dialect::Vlt}, hex("F5"), 0x0402},
        {{7, 5, Dialect::Profidrive}, hex("F3 F9"), 0x6001},
        {{8, 1, Dialect::Ge}, hex("F3 F1"), 0x6002},
    };
    SimulatorOptions options = small_session(2, 1);
    for (const StartUpCase& c : cases)
        options.slaves.push_back(c.slave);
    std::vector<Telegram> telegrams = run(options);
    BusDecoder decoder;
    std::vector<Decoded> decoded = decode_all(telegrams, decoder);
    ASSERT_GE(decoded.size(), cases.size() * 10 + 2);

    const Service kServices[] = {Service::FdlStatus, Service::FdlStatus, Service::SlaveDiag,
                                 Service::SlaveDiag, Service::SetPrm,    Service::SetPrm,
                                 Service::ChkCfg,    Service::ChkCfg,    Service::SlaveDiag,
                                 Service::SlaveDiag};
    for (std::size_t s = 0; s < cases.size(); ++s) {
        const StartUpCase& c = cases[s];
        SCOPED_TRACE(static_cast<int>(c.slave.address));
        for (std::size_t k = 0; k < 10; ++k) {
            const Decoded& d = decoded[s * 10 + k];
            SCOPED_TRACE(k);
            EXPECT_EQ(d.service, kServices[k]);
            EXPECT_EQ(d.direction, k % 2 == 0 ? Direction::Request : Direction::Response);
            EXPECT_EQ(d.master, 2);
            EXPECT_EQ(d.slave, c.slave.address);
            EXPECT_TRUE(d.problems.empty());
        }
        const Decoded* seq = &decoded[s * 10];
        EXPECT_EQ(seq[0].type, FrameType::Sd1);
        EXPECT_EQ(seq[5].type, FrameType::ShortAck);
        EXPECT_EQ(seq[7].type, FrameType::ShortAck);
        EXPECT_EQ(seq[6].du, c.cfg);
        // First diagnosis: not parameterised yet, no master; the last one: master 2, WD on.
        std::vector<std::uint8_t> first_diag = hex("02 05 00 FF");
        std::vector<std::uint8_t> last_diag = hex("00 0C 00 02");
        for (auto* diag : {&first_diag, &last_diag}) {
            diag->push_back(static_cast<std::uint8_t>(c.ident >> 8));
            diag->push_back(static_cast<std::uint8_t>(c.ident));
        }
        EXPECT_EQ(seq[3].du, first_diag);
        EXPECT_EQ(seq[9].du, last_diag);
        ASSERT_GE(seq[4].du.size(), 7u);
        EXPECT_EQ(seq[4].du[4], c.ident >> 8);
        EXPECT_EQ(seq[4].du[5], c.ident & 0xFF);
        EXPECT_EQ(seq[4].du.size(), c.slave.dialect == Dialect::Profidrive ? 10u : 7u);

        const StationConfig& station = decoder.station(c.slave.address);
        EXPECT_TRUE(station.has_ident);
        EXPECT_EQ(station.ident, c.ident);
        EXPECT_EQ(station.ppo.type, c.slave.ppo_type);
        EXPECT_EQ(station.ppo.source, PpoSource::ChkCfg);
        EXPECT_EQ(station.cfg_frame, s * 10 + 7);
    }
    const Decoded& gc = decoded[cases.size() * 10];
    EXPECT_EQ(gc.service, Service::GlobalControl);
    EXPECT_EQ(gc.du, hex("00 00"));
    EXPECT_EQ(decoded[cases.size() * 10 + 1].service, Service::Token);
    EXPECT_EQ(decoded[cases.size() * 10 + 2].service, Service::DataExchange);
}

TEST(SimulatorTest, CleanRunDecodesWithoutProblems) {
    std::vector<Telegram> telegrams = run(small_session(4, 600));
    BusDecoder decoder;
    std::vector<Decoded> decoded = decode_all(telegrams, decoder);
    std::size_t tokens = 0, data_exchange = 0, unknown = 0, gap_polls = 0, global_control = 0;
    for (std::size_t i = 0; i < decoded.size(); ++i) {
        const Decoded& d = decoded[i];
        ASSERT_TRUE(d.problems.empty()) << "telegram " << i + 1;
        ASSERT_TRUE(d.fcs_ok) << "telegram " << i + 1;
        if (d.service == Service::Token) ++tokens;
        if (d.service == Service::DataExchange) ++data_exchange;
        if (d.service == Service::Unknown) ++unknown;
        if (d.service == Service::FdlStatus && d.direction == Direction::Request &&
            (d.slave < 3 || d.slave > 5))
            ++gap_polls;
        if (d.service == Service::GlobalControl) ++global_control;
    }
    EXPECT_EQ(unknown, 0u);
    EXPECT_EQ(tokens, 601u);                 // one per cycle and one after start-up
    EXPECT_EQ(data_exchange, 600u * 3 * 2);  // request and response per slave and cycle
    EXPECT_EQ(gap_polls, 6u);                // every 100 cycles
    EXPECT_EQ(global_control, 1u + 2);       // start-up, then every 250 cycles
}

TEST(SimulatorTest, GapPollsNeverAddressAStationOnTheBus) {
    // Gap polls ask addresses where nobody is; they start above the highest station and wrap
    // around after 125, skipping the master and the slaves.
    SimulatorOptions options = small_session(1, 500);
    options.slaves = {{124, 3, Dialect::Vlt}, {4, 3, Dialect::Vlt}, {3, 3, Dialect::Vlt}};
    std::vector<Telegram> telegrams = run(options);
    BusDecoder decoder;
    std::vector<Decoded> decoded = decode_all(telegrams, decoder);
    std::vector<int> polled;
    for (std::size_t i = 3 * 10; i < decoded.size(); ++i)
        if (decoded[i].service == Service::FdlStatus && decoded[i].direction == Direction::Request)
            polled.push_back(decoded[i].slave);
    ASSERT_EQ(polled.size(), 5u);
    EXPECT_EQ(polled[0], 125);
    EXPECT_EQ(polled[1], 1);
    for (int address : polled) {
        EXPECT_TRUE(address != 2 && address != 3 && address != 4 && address != 124)
            << "gap poll sent to station " << address
            << ", which is on the bus (polled: " << ::testing::PrintToString(polled) << ")";
    }
    EXPECT_EQ(polled[2], 5);
}

TEST(SimulatorTest, WithoutStartUpTheCaptureBeginsWithTheFirstCycle) {
    SimulatorOptions options = small_session(6, 20);
    options.record_start_up = false;
    std::vector<Telegram> telegrams = run(options);
    BusDecoder decoder;
    std::vector<Decoded> decoded = decode_all(telegrams, decoder);
    ASSERT_FALSE(decoded.empty());
    EXPECT_EQ(decoded[0].service, Service::DataExchange);
    EXPECT_EQ(decoded[0].direction, Direction::Request);
    EXPECT_EQ(decoded[0].slave, 3);
    for (const Decoded& d : decoded) {
        EXPECT_NE(d.service, Service::SetPrm);
        EXPECT_NE(d.service, Service::ChkCfg);
        EXPECT_NE(d.service, Service::SlaveDiag);
        EXPECT_NE(d.service, Service::FdlStatus);
    }
    // The start-up still took its time on the bus.
    std::vector<Telegram> with_start_up = run(small_session(6, 20));
    EXPECT_EQ(telegrams.size(), with_start_up.size() - 32);
    EXPECT_EQ(telegrams[0].time_ns, with_start_up[32].time_ns);
    EXPECT_EQ(telegrams[0].bytes, with_start_up[32].bytes);
}

// ---- fault specifications --------------------------------------------------------------------

TEST(SimulatorTest, FaultKindNamesRoundTrip) {
    for (std::size_t i = 0; i < static_cast<std::size_t>(FaultKind::Count); ++i) {
        auto kind = static_cast<FaultKind>(i);
        std::string_view name = fault_kind_name(kind);
        EXPECT_NE(name, "unknown");
        EXPECT_EQ(fault_kind_from_name(name), kind) << name;
    }
    EXPECT_EQ(fault_kind_name(FaultKind::FcsError), "fcs_error");
    EXPECT_EQ(fault_kind_name(FaultKind::FdlNoResponse), "fdl_no_response");
    EXPECT_EQ(fault_kind_name(FaultKind::Count), "unknown");
    EXPECT_EQ(fault_kind_from_name("bad_fcs"), FaultKind::FcsError);
    EXPECT_FALSE(fault_kind_from_name("FCS_ERROR").has_value());
    EXPECT_FALSE(fault_kind_from_name("").has_value());
}

TEST(SimulatorTest, FaultNamesAreTheFindingNamesAndTheSimulatorsOwn) {
    // Every finding kind is a fault of the same name (the name comes from the finding catalogue).
    for (std::size_t i = 0; i < kFindingKindCount; ++i) {
        auto finding = static_cast<FindingKind>(i);
        auto kind = fault_kind_from_name(finding_kind_name(finding));
        ASSERT_TRUE(kind.has_value()) << finding_kind_name(finding);
        EXPECT_EQ(fault_finding_kind(*kind), finding) << finding_kind_name(finding);
    }
    // The simulator's own faults are named after no finding kind.
    std::size_t own = 0;
    for (std::size_t i = 0; i < kFaultKindCount; ++i) {
        auto kind = static_cast<FaultKind>(i);
        if (auto finding = fault_finding_kind(kind)) {
            EXPECT_EQ(fault_kind_name(kind), finding_kind_name(*finding));
        } else {
            ++own;
            EXPECT_FALSE(finding_kind_from_name(fault_kind_name(kind)).has_value())
                << fault_kind_name(kind);
        }
    }
    EXPECT_EQ(kFaultKindCount, kFindingKindCount + own);
    EXPECT_FALSE(fault_finding_kind(FaultKind::Garbage).has_value());
}

FaultSpec fault(std::string_view text) {
    Result<FaultSpec> spec = parse_fault_spec(text);
    EXPECT_TRUE(spec.has_value()) << text << ": " << spec.error();
    return spec ? *spec : FaultSpec{};
}

std::string fault_error(std::string_view text) {
    Result<FaultSpec> spec = parse_fault_spec(text);
    EXPECT_FALSE(spec.has_value()) << text;
    return spec.error();
}

TEST(SimulatorTest, ParseFaultSpecValid) {
    FaultSpec once = fault("garbage");
    EXPECT_EQ(once.kind, FaultKind::Garbage);
    EXPECT_EQ(once.rate, 0);
    EXPECT_FALSE(once.cycle.has_value());
    EXPECT_FALSE(once.slave.has_value());

    FaultSpec at = fault("fdl_retry@26:3");
    EXPECT_EQ(at.kind, FaultKind::FdlRetry);
    EXPECT_EQ(at.cycle, 26u);
    EXPECT_EQ(at.slave, 3);
    EXPECT_EQ(at.rate, 0);

    FaultSpec rate = fault("request_rejected=0.25");
    EXPECT_EQ(rate.kind, FaultKind::RequestRejected);
    EXPECT_DOUBLE_EQ(rate.rate, 0.25);
    EXPECT_FALSE(rate.cycle.has_value());

    FaultSpec rate_slave = fault("spm_violation=1:126");
    EXPECT_DOUBLE_EQ(rate_slave.rate, 1.0);
    EXPECT_EQ(rate_slave.slave, 126);

    FaultSpec alias = fault("bad_fcs@0:0");
    EXPECT_EQ(alias.kind, FaultKind::FcsError);
    EXPECT_EQ(alias.cycle, 0u);
    EXPECT_EQ(alias.slave, 0);

    EXPECT_EQ(fault("stacked_request:5").slave, 5);
}

TEST(SimulatorTest, ParseFaultSpecInvalid) {
    std::string unknown = fault_error("nonsense@3");
    // The kinds a PROFIBUS DP session takes (the default bus), and only those.
    EXPECT_EQ(unknown.rfind("nonsense@3: unknown kind 'nonsense' (known with --bus profibus: "
                            "fcs_error, garbage, ",
                            0),
              0u)
        << unknown;
    EXPECT_NE(unknown.find("fdl_no_response, dpv1_stacked_request, "), std::string::npos)
        << unknown;
    EXPECT_NE(unknown.find(
                  ", dpv1_error_pdu, dpv1_unknown_code, gsd_ident_mismatch, gsd_unknown_module, "
                  "gsd_config_limit, gsd_user_prm_length, gsd_user_prm_range, gsd_diag_too_long, "
                  "gsd_late_response, gsd_poll_interval, station_lost, resync, answer_not_asked, "
                  "answer_wrong_kind, answer_short_ack, diag_fault, repeats, refusal)"),
              std::string::npos)
        << unknown;
    EXPECT_EQ(unknown.find("fc_"), std::string::npos) << unknown;
    EXPECT_EQ(unknown.find("vlt2000_"), std::string::npos) << unknown;
    Result<FaultSpec> fc = parse_fault_spec("nonsense", Protocol::Fc);
    ASSERT_FALSE(fc);
    EXPECT_EQ(fc.error(),
              "nonsense: unknown kind 'nonsense' (known with --bus fc: garbage, "
              "malformed_telegram, fc_stacked_request, fc_no_response, fc_late_response, "
              "fc_mismatched_response, fc_unexpected_response_type, fc_command_rejected, "
              "fc_bcc_error)");
    Result<FaultSpec> vlt = parse_fault_spec("nonsense", Protocol::Vlt2000);
    ASSERT_FALSE(vlt);
    EXPECT_EQ(vlt.error(),
              "nonsense: unknown kind 'nonsense' (known with --bus vlt2000: garbage, "
              "malformed_telegram, vlt2000_stacked_request, vlt2000_no_response, "
              "vlt2000_unexpected_reply, vlt2000_mismatched_response, vlt2000_command_failed, "
              "vlt2000_checksum_error, vlt2000_checksum_disabled)");
    // A kind of another bus is parsed; check_simulator_faults names its bus.
    EXPECT_TRUE(parse_fault_spec("fc_bcc_error", Protocol::Vlt2000));
    EXPECT_EQ(fault_error("garbage@x"), "garbage@x: 'x' is not a cycle number");
    EXPECT_EQ(fault_error("garbage@-1"), "garbage@-1: '-1' is not a cycle number");
    EXPECT_EQ(fault_error("garbage@"), "garbage@: '' is not a cycle number");
    EXPECT_EQ(fault_error("garbage=0"), "garbage=0: rate '0' must be a number in (0, 1]");
    EXPECT_EQ(fault_error("garbage=1.5"), "garbage=1.5: rate '1.5' must be a number in (0, 1]");
    EXPECT_EQ(fault_error("garbage=abc"), "garbage=abc: rate 'abc' must be a number in (0, 1]");
    EXPECT_EQ(fault_error("garbage="), "garbage=: rate '' must be a number in (0, 1]");
    EXPECT_EQ(fault_error("garbage:127"),
              "garbage:127: '127' is not a station address from 0 to 126");
    EXPECT_EQ(fault_error("garbage@3:x"),
              "garbage@3:x: 'x' is not a station address from 0 to 126");
    EXPECT_EQ(fault_error("garbage:"), "garbage:: '' is not a station address from 0 to 126");
    EXPECT_NE(fault_error("").find("unknown kind ''"), std::string::npos);
}

SimulatedSlave slave(std::string_view text) {
    Result<SimulatedSlave> spec = parse_slave_spec(text);
    EXPECT_TRUE(spec.has_value()) << text << ": " << spec.error();
    return spec ? *spec : SimulatedSlave{};
}

std::string slave_error(std::string_view text) {
    Result<SimulatedSlave> spec = parse_slave_spec(text);
    EXPECT_FALSE(spec.has_value()) << text;
    return spec.error();
}

TEST(SimulatorTest, ParseSlaveSpecValid) {
    SimulatedSlave a = slave("5:2");
    EXPECT_EQ(a.address, 5);
    EXPECT_EQ(a.ppo_type, 2);
    EXPECT_EQ(a.dialect, Dialect::Vlt);
    SimulatedSlave b = slave("7:1:profidrive");
    EXPECT_EQ(b.address, 7);
    EXPECT_EQ(b.ppo_type, 1);
    EXPECT_EQ(b.dialect, Dialect::Profidrive);
    SimulatedSlave c = slave("125:5:vlt");
    EXPECT_EQ(c.address, 125);
    EXPECT_EQ(c.ppo_type, 5);
    EXPECT_EQ(c.dialect, Dialect::Vlt);
    EXPECT_EQ(slave("0:3").address, 0);
    EXPECT_FALSE(a.dpv1);
    SimulatedSlave d = slave("8:3:dpv1");
    EXPECT_EQ(d.address, 8);
    EXPECT_EQ(d.ppo_type, 3);
    EXPECT_EQ(d.dialect, Dialect::Vlt);
    EXPECT_TRUE(d.dpv1);
    SimulatedSlave e = slave("9:1:profidrive:dpv1");
    EXPECT_EQ(e.dialect, Dialect::Profidrive);
    EXPECT_TRUE(e.dpv1);
    EXPECT_TRUE(slave("10:5:vlt:dpv1").dpv1);
    SimulatedSlave f = slave("11:1:ge");
    EXPECT_EQ(f.dialect, Dialect::Ge);
    EXPECT_FALSE(f.dpv1);
    SimulatedSlave g = slave("12:5:ge:dpv1");
    EXPECT_EQ(g.dialect, Dialect::Ge);
    EXPECT_TRUE(g.dpv1);
}

TEST(SimulatorTest, ParseSlaveSpecInvalid) {
    EXPECT_EQ(slave_error("5"), "5: expected ADDR:PPO[:DIALECT][:dpv1]");
    EXPECT_EQ(slave_error("126:1"), "126:1: the address must be from 0 to 125");
    EXPECT_EQ(slave_error("x:1"), "x:1: the address must be from 0 to 125");
    EXPECT_EQ(slave_error(":1"), ":1: the address must be from 0 to 125");
    EXPECT_EQ(slave_error("5:0"), "5:0: the PPO type must be from 1 to 5");
    EXPECT_EQ(slave_error("5:6"), "5:6: the PPO type must be from 1 to 5");
    EXPECT_EQ(slave_error("5:"), "5:: the PPO type must be from 1 to 5");
    EXPECT_EQ(slave_error("5:1:foo"), "5:1:foo: dialect must be one of vlt, ge, profidrive");
    EXPECT_EQ(slave_error("5:1:"), "5:1:: dialect must be one of vlt, ge, profidrive");
    EXPECT_EQ(slave_error("5:1:vlt:x"), "5:1:vlt:x: only dpv1 may follow the dialect");
    EXPECT_EQ(slave_error("5:1:vlt:dpv1:x"), "5:1:vlt:dpv1:x: only dpv1 may follow the dialect");
    EXPECT_EQ(slave_error("5:1:dpv1:vlt"),
              "5:1:dpv1:vlt: dialect must be one of vlt, ge, profidrive");
    EXPECT_EQ(slave_error("5:1:vlt:"), "5:1:vlt:: only dpv1 may follow the dialect");
    EXPECT_EQ(slave_error("5:1:GE"), "5:1:GE: dialect must be one of vlt, ge, profidrive");
}

// ---- fault injection -------------------------------------------------------------------------

TEST(SimulatorTest, EveryFaultKindIsInjectedExactlyOnce) {
    for (std::size_t i = 0; i < static_cast<std::size_t>(FaultKind::Count); ++i) {
        auto kind = static_cast<FaultKind>(i);
        for (std::uint8_t address : std::initializer_list<std::uint8_t>{3, 4, 5}) {
            SCOPED_TRACE(std::string(fault_kind_name(kind)) + " on slave " +
                         std::to_string(address));
            SimulatorOptions options = small_session(9, 300);
            options.faults = {FaultSpec{kind, 0, 5, address}};
            if (fault_needs_dpv1(kind))
                options.slaves = {{3, 1, Dialect::Vlt, true},
                                  {4, 3, Dialect::Profidrive, true},
                                  {5, 5, Dialect::Vlt, true}};
            if (fault_bus(kind) == Protocol::Fc) {
                options.bus = Protocol::Fc;
                options.drives = {{3, FcAddressFormat::Long},
                                  {4, FcAddressFormat::Short},
                                  {5, FcAddressFormat::Long}};
            }
            if (fault_bus(kind) == Protocol::Vlt2000) {
                options.bus = Protocol::Vlt2000;
                options.baud = 0;
                options.vlt2000_drives = {3, 4, 5};
            }
            Simulator simulator(options);
            std::vector<Telegram> telegrams = run(simulator);
            ASSERT_EQ(simulator.injections().size(), 1u);
            const Injection& injection = simulator.injections()[0];
            EXPECT_EQ(injection.kind, kind);
            EXPECT_EQ(injection.slave, address);
            EXPECT_GE(injection.cycle, 5u);
            EXPECT_GE(injection.telegram, 1u);
            EXPECT_LE(injection.telegram, telegrams.size());
        }
    }
}

// station_lost: silent for kStationLostCycles cycles (a Data_Exchange and its repeat, then
// Slave_Diag and its repeat, unanswered), then Slave_Diag, Set_Prm, Chk_Cfg, Slave_Diag answered.
TEST(SimulatorTest, StationLostIsSilentThenParameterisedAnew) {
    SimulatorOptions options = small_session(3, 30);
    options.record_start_up = false;
    options.slaves = {{3, 3, Dialect::Vlt}};
    options.faults = {FaultSpec{FaultKind::StationLost, 0, 5, 3}};
    std::vector<Telegram> telegrams = run(options);
    // Per cycle: Data_Exchange request and response, the token.
    std::size_t first = 5 * 3;
    ASSERT_GT(telegrams.size(), first + 30);
    auto is_request_to_3 = [](const Telegram& t) {
        return t.bytes.size() > 6 && t.bytes[0] == 0x68 && (t.bytes[4] & 0x7F) == 0x03 &&
               (t.bytes[6] & 0x40) != 0;
    };
    auto is_token = [](const Telegram& t) { return t.bytes.size() == 3 && t.bytes[0] == 0xDC; };
    // Cycle 5: the Data_Exchange and its repeat (same bytes), then the token.
    EXPECT_TRUE(is_request_to_3(telegrams[first]));
    EXPECT_EQ(telegrams[first].bytes, telegrams[first + 1].bytes);
    EXPECT_TRUE(is_token(telegrams[first + 2]));
    // Cycles 6 to 9: Slave_Diag (DSAP 60) and its repeat, then the token.
    for (std::size_t cycle = 0; cycle < kStationLostCycles - 1; ++cycle) {
        const std::size_t at = first + 3 + 3 * cycle;
        ASSERT_TRUE(is_request_to_3(telegrams[at])) << cycle;
        EXPECT_EQ(telegrams[at].bytes[7], sap::kSlaveDiag);
        EXPECT_EQ(telegrams[at].bytes, telegrams[at + 1].bytes);
        EXPECT_TRUE(is_token(telegrams[at + 2]));
        if (cycle > 0) {  // FCB toggles from poll to poll
            EXPECT_NE(telegrams[at].bytes[6], telegrams[at - 3].bytes[6]);
        }
    }
    // Cycle 10: Slave_Diag answered, Set_Prm, Chk_Cfg (short acknowledges), Slave_Diag answered.
    const std::size_t back = first + 3 + 3 * (kStationLostCycles - 1);
    const std::uint8_t dsaps[] = {sap::kSlaveDiag, sap::kSetPrm, sap::kChkCfg, sap::kSlaveDiag};
    for (std::size_t i = 0; i < 4; ++i) {
        ASSERT_TRUE(is_request_to_3(telegrams[back + 2 * i])) << i;
        EXPECT_EQ(telegrams[back + 2 * i].bytes[7], dsaps[i]);
        if (i == 1 || i == 2) {
            EXPECT_EQ(telegrams[back + 2 * i + 1].bytes, std::vector<std::uint8_t>{0xE5});
        } else {
            EXPECT_EQ(telegrams[back + 2 * i + 1].bytes[0], 0xA2);  // SD3: 2 SAPs, 6 bytes
        }
    }
    // The first diagnosis: Station_Not_Ready, Prm_Req, no master.
    EXPECT_EQ(telegrams[back + 1].bytes[6], 0x02);
    EXPECT_EQ(telegrams[back + 1].bytes[7], 0x05);
    EXPECT_EQ(telegrams[back + 1].bytes[9], 0xFF);
    EXPECT_TRUE(is_token(telegrams[back + 8]));
    // Cycle 11: Data_Exchange again, answered.
    EXPECT_TRUE(is_request_to_3(telegrams[back + 9]));
    EXPECT_EQ(telegrams[back + 10].bytes[0], 0x68);
    EXPECT_EQ(telegrams[back + 10].bytes[5], 0x03);  // from slave 3
}

TEST(SimulatorTest, TokenRingPassesThroughEveryMaster) {
    SimulatorOptions options = small_session(3, 40);
    options.ring_masters = {1, 9};
    options.token_hold_us = 250;
    std::vector<Telegram> telegrams = run(options);
    std::vector<std::pair<std::uint8_t, std::uint8_t>> tokens;  // (to, from)
    for (const Telegram& t : telegrams)
        if (t.bytes.size() == 3 && t.bytes[0] == 0xDC) tokens.emplace_back(t.bytes[1], t.bytes[2]);
    ASSERT_EQ(tokens.size(), 3u * 41);  // start-up and every cycle
    for (std::size_t i = 0; i < tokens.size(); i += 3) {
        EXPECT_EQ(tokens[i], std::make_pair(std::uint8_t{1}, std::uint8_t{2}));
        EXPECT_EQ(tokens[i + 1], std::make_pair(std::uint8_t{9}, std::uint8_t{1}));
        EXPECT_EQ(tokens[i + 2], std::make_pair(std::uint8_t{2}, std::uint8_t{9}));
    }
    // The further masters' gap polls (cycle 10 and 30) ask free addresses only.
    std::size_t gap_polls = 0;
    for (const Telegram& t : telegrams) {
        if (t.bytes.size() != 6 || t.bytes[0] != 0x10) continue;
        if (t.bytes[2] != 1 && t.bytes[2] != 9) continue;  // from a further master
        ++gap_polls;
        EXPECT_TRUE(t.bytes[1] != 2 && t.bytes[1] != 1 && t.bytes[1] != 9 &&
                    (t.bytes[1] < 3 || t.bytes[1] > 5))
            << int{t.bytes[1]};
    }
    EXPECT_EQ(gap_polls, 4u);
    // Without a ring the session is the one of before: tokens to itself only.
    SimulatorOptions alone = small_session(3, 40);
    for (const Telegram& t : run(alone))
        if (t.bytes.size() == 3 && t.bytes[0] == 0xDC) {
            EXPECT_EQ(t.bytes[1], t.bytes[2]);
        }
}

TEST(SimulatorTest, FaultWithoutCycleHappensOnceAtASeededCycle) {
    SimulatorOptions options = small_session(9, 300);
    options.faults = {FaultSpec{FaultKind::Garbage, 0, std::nullopt, std::nullopt}};
    Simulator first(options);
    run(first);
    ASSERT_EQ(first.injections().size(), 1u);
    EXPECT_GE(first.injections()[0].cycle, 20u);
    EXPECT_LT(first.injections()[0].cycle, 20u + 150);
    Simulator second(options);
    run(second);
    ASSERT_EQ(second.injections().size(), 1u);
    EXPECT_EQ(second.injections()[0].cycle, first.injections()[0].cycle);
    EXPECT_EQ(second.injections()[0].slave, first.injections()[0].slave);
}

TEST(SimulatorTest, FaultRateInjectsEveryCycle) {
    SimulatorOptions options = small_session(9, 10);
    options.faults = {FaultSpec{FaultKind::FcsError, 1.0, std::nullopt, 5}};
    Simulator simulator(options);
    run(simulator);
    ASSERT_EQ(simulator.injections().size(), 10u);
    for (std::size_t i = 0; i < 10; ++i) {
        EXPECT_EQ(simulator.injections()[i].cycle, i);
        EXPECT_EQ(simulator.injections()[i].slave, 5);
    }
}

TEST(SimulatorTest, FaultOnASlaveWithoutPcvIsNotInjected) {
    SimulatorOptions options = small_session(9, 100);
    options.slaves = {{3, 3, Dialect::Vlt}};  // PPO 3: no parameter channel
    options.faults = {FaultSpec{FaultKind::RequestRejected, 0, 5, std::nullopt},
                      FaultSpec{FaultKind::ConfigMismatch, 0, 5, std::nullopt}};
    Simulator simulator(options);
    run(simulator);
    ASSERT_EQ(simulator.injections().size(), 1u);
    EXPECT_EQ(simulator.injections()[0].kind, FaultKind::ConfigMismatch);
}

// A GE slave (seed 002) rejects with its fault numbers 130 (a read) and 131 (a change), sends one
// of the unused RC 9..12 as its unknown code, and no spontaneous messages; the vlt slave beside
// it keeps error 2 and RC 13, and does send spontaneous messages.
TEST(SimulatorTest, GeSlaveUsesGeFaultNumbersAndUnusedCodes) {
    SimulatorOptions options = small_session(7, 600);
    options.slaves = {{3, 1, Dialect::Ge}, {4, 1, Dialect::Vlt}};
    options.faults = {FaultSpec{FaultKind::RequestRejected, 0.05, std::nullopt, std::nullopt},
                      FaultSpec{FaultKind::UnknownCode, 0.05, std::nullopt, std::nullopt},
                      FaultSpec{FaultKind::SpontaneousMessage, 0.05, std::nullopt, std::nullopt}};
    Simulator simulator(options);
    std::vector<Telegram> telegrams = run(simulator);
    std::map<std::uint8_t, std::map<FaultKind, int>> injected;
    for (const Injection& injection : simulator.injections())
        ++injected[injection.slave][injection.kind];
    EXPECT_EQ(injected[3][FaultKind::SpontaneousMessage], 0);
    EXPECT_GT(injected[4][FaultKind::SpontaneousMessage], 0);
    EXPECT_GT(injected[3][FaultKind::RequestRejected], 0);
    EXPECT_GT(injected[3][FaultKind::UnknownCode], 0);

    BusDecoder decoder;
    std::map<std::uint8_t, std::set<int>> errors, high_codes;
    std::map<std::uint8_t, int> last_request_rc;
    std::set<std::pair<int, int>> request_and_error;  // slave 3: the pending request's RC, error
    for (const Decoded& d : decode_all(telegrams, decoder)) {
        if (d.service != Service::DataExchange || d.du.size() < 8) continue;
        const int rc = d.du[0] >> 4;
        if (d.direction == Direction::Request) {
            if (rc != 0) last_request_rc[d.slave] = rc;
            continue;
        }
        const int pva_low = d.du[6] << 8 | d.du[7];
        if (rc == 7) {
            errors[d.slave].insert(pva_low);
            if (d.slave == 3) request_and_error.insert({last_request_rc[3], pva_low});
        }
        if (rc >= 9) high_codes[d.slave].insert(rc);
    }
    EXPECT_EQ(errors[3], (std::set<int>{130, 131}));
    EXPECT_EQ(errors[4], (std::set<int>{2}));
    for (const auto& [request, error] : request_and_error)
        EXPECT_EQ(error, request == 2 || request == 3 ? 131 : 130) << "request RC " << request;
    ASSERT_FALSE(high_codes[3].empty());
    for (int rc : high_codes[3]) {
        EXPECT_GE(rc, 9);
        EXPECT_LE(rc, 12);
    }
    EXPECT_TRUE(high_codes[4].count(13));  // the vlt slave's unknown code
    EXPECT_TRUE(high_codes[4].count(9));   // and its spontaneous messages

    // Named beforehand: a spontaneous fault aimed at the ge slave cannot happen.
    options.faults = {FaultSpec{FaultKind::SpontaneousUnacknowledged, 0, 5, 3}};
    EXPECT_EQ(check_simulator_faults(options).error(),
              "fault spontaneous_unacknowledged@5:3: slave 3 speaks the ge dialect, which has no "
              "spontaneous messages (RC 9 to 12 not used)");
    options.faults = {FaultSpec{FaultKind::SpontaneousMessage, 0, 5, std::nullopt}};
    EXPECT_TRUE(check_simulator_faults(options));  // slave 4 can take it
}

TEST(SimulatorTest, FaultsThatCannotBeInjectedAreNamedBeforehand) {
    SimulatorOptions options = small_session(9, 100);
    EXPECT_TRUE(check_simulator_faults(options));
    options.faults = {FaultSpec{FaultKind::StackedRequest, 0, 10, 9}};
    EXPECT_EQ(check_simulator_faults(options).error(),
              "fault stacked_request@10:9: slave 9 is not simulated");
    options.slaves = {{3, 3, Dialect::Vlt}, {4, 4, Dialect::Vlt}};
    options.faults = {FaultSpec{FaultKind::StackedRequest, 0, std::nullopt, 3}};
    EXPECT_EQ(check_simulator_faults(options).error(),
              "fault stacked_request:3: slave 3 has no parameter channel (PPO 3 and 4 carry no "
              "PCV)");
    options.faults = {FaultSpec{FaultKind::RequestRejected, 0.5, std::nullopt, std::nullopt}};
    EXPECT_EQ(check_simulator_faults(options).error(),
              "fault request_rejected=0.5: no simulated slave has a parameter channel (PPO 1, 2 "
              "or 5)");
    options.faults = {FaultSpec{FaultKind::FcsError, 0, std::nullopt, 3}};  // no PCV needed
    EXPECT_TRUE(check_simulator_faults(options));
    options = small_session(9, 100);
    options.faults = {FaultSpec{FaultKind::OrphanResponse, 0, 100, std::nullopt}};
    EXPECT_EQ(check_simulator_faults(options).error(),
              "fault orphan_response@100: cycle 100 is past the session's 100 cycles (0..99)");
    options.cycles = 0;  // until -c: any cycle may come
    EXPECT_TRUE(check_simulator_faults(options));
}

TEST(SimulatorTest, FaultsTheSessionEndedBeforeAreNamed) {
    SimulatorOptions options = small_session(9, 100);
    options.faults = {FaultSpec{FaultKind::StackedRequest, 0, 99, std::nullopt},
                      FaultSpec{FaultKind::FcsError, 0, 10, std::nullopt},
                      FaultSpec{FaultKind::Garbage, 1.0, std::nullopt, std::nullopt}};
    Simulator simulator(options);
    run(simulator);
    EXPECT_EQ(faults_not_injected(options, simulator.injections()),
              std::vector<std::string>{"stacked_request@99"});
}

TEST(SimulatorTest, FaultsNotInjectedAreKnownWithoutTheInjectionList) {
    SimulatorOptions options = small_session(9, 100);
    options.faults = {FaultSpec{FaultKind::StackedRequest, 0, 99, std::nullopt},
                      FaultSpec{FaultKind::Garbage, 0, std::nullopt, std::nullopt},
                      FaultSpec{FaultKind::Garbage, 0, 10, 4},
                      FaultSpec{FaultKind::FcsError, 0.5, std::nullopt, std::nullopt}};
    Simulator simulator(options);
    std::vector<Injection> seen;
    simulator.on_injection([&](const Injection& injection) { seen.push_back(injection); });
    run(simulator);
    EXPECT_EQ(simulator.faults_not_injected(), std::vector<std::string>{"stacked_request@99"});
    EXPECT_EQ(faults_not_injected(options, seen), simulator.faults_not_injected());
    EXPECT_EQ(seen.size(), simulator.injection_count());
}

TEST(SimulatorTest, InjectionsKeptAreBoundedAndAllAreSeen) {
    // Regression: every injection was kept, so memory grew with the session.
    SimulatorOptions options = small_session(9, 4000);
    options.faults = {FaultSpec{FaultKind::Garbage, 1.0, std::nullopt, std::nullopt},
                      FaultSpec{FaultKind::StackedRequest, 0, 3990, 3}};
    Simulator simulator(options);
    std::uint64_t seen = 0;
    std::uint64_t last_telegram = 0;
    simulator.on_injection([&](const Injection& injection) {
        ++seen;
        EXPECT_GT(injection.telegram, last_telegram);
        last_telegram = injection.telegram;
    });
    run(simulator);
    EXPECT_EQ(simulator.injections().size(), Simulator::kKeptInjections);
    EXPECT_EQ(simulator.injection_count(), seen);
    EXPECT_GE(seen, 3u * 4000);
    // The check of faults given once does not depend on the kept list.
    EXPECT_TRUE(simulator.faults_not_injected().empty());
}

TEST(SimulatorTest, TimeoutFaultKeepsTheSessionOpenUntilTheMasterGivesUp) {
    SimulatorOptions options = small_session(9, 100);
    options.faults = {FaultSpec{FaultKind::ResponseTimeout, 0, 95, std::nullopt}};
    Simulator simulator(options);
    std::vector<Telegram> telegrams = run(simulator);
    ASSERT_EQ(simulator.injections().size(), 1u);
    // 100 cycles of 2 ms would end 0.2 s in; the session runs past the 1.5 s give-up.
    std::int64_t span = telegrams.back().time_ns - options.start_time_ns;
    EXPECT_GT(span, 1'700'000'000);
    EXPECT_LT(span, 2'000'000'000);
}

TEST(SimulatorTest, FcsErrorProducesABadFcs) {
    SimulatorOptions options = small_session(9, 20);
    options.faults = {FaultSpec{FaultKind::FcsError, 0, 5, 3}};
    Simulator simulator(options);
    std::vector<Telegram> telegrams = run(simulator);
    ASSERT_EQ(simulator.injections().size(), 1u);
    const Injection& injection = simulator.injections()[0];
    EXPECT_EQ(injection.cycle, 5u);
    BusDecoder decoder;
    std::vector<Decoded> decoded = decode_all(telegrams, decoder);
    std::size_t bad = 0;
    for (std::size_t i = 0; i < decoded.size(); ++i) {
        if (decoded[i].fcs_ok) continue;
        ++bad;
        EXPECT_EQ(i + 1, injection.telegram);
        EXPECT_EQ(decoded[i].problems, std::vector<ProblemKind>{ProblemKind::FcsMismatch});
        EXPECT_EQ(decoded[i].service, Service::DataExchange);
        EXPECT_EQ(decoded[i].direction, Direction::Response);
    }
    EXPECT_EQ(bad, 1u);
    // The master repeats the request, and this time the answer arrives.
    ASSERT_GT(decoded.size(), injection.telegram + 1);
    EXPECT_EQ(telegrams[injection.telegram].bytes, telegrams[injection.telegram - 2].bytes);
    EXPECT_TRUE(decoded[injection.telegram + 1].fcs_ok);
}

TEST(SimulatorTest, GarbageProducesARecordThatIsNotATelegram) {
    SimulatorOptions options = small_session(9, 20);
    options.faults = {FaultSpec{FaultKind::Garbage, 0, 5, 4}};
    Simulator simulator(options);
    std::vector<Telegram> telegrams = run(simulator);
    ASSERT_EQ(simulator.injections().size(), 1u);
    std::uint64_t number = simulator.injections()[0].telegram;
    BusDecoder decoder;
    std::vector<Decoded> decoded = decode_all(telegrams, decoder);
    std::size_t invalid = 0;
    for (std::size_t i = 0; i < decoded.size(); ++i) {
        if (decoded[i].type != FrameType::Invalid) continue;
        ++invalid;
        EXPECT_EQ(i + 1, number);
        EXPECT_EQ(decoded[i].problems, std::vector<ProblemKind>{ProblemKind::BadStartDelimiter});
        EXPECT_GE(telegrams[i].bytes.size(), 3u);
        EXPECT_LE(telegrams[i].bytes.size(), 12u);
    }
    EXPECT_EQ(invalid, 1u);
}

TEST(SimulatorTest, MalformedTelegramIsCutShort) {
    SimulatorOptions options = small_session(9, 20);
    options.faults = {FaultSpec{FaultKind::MalformedTelegram, 0, 5, 3}};
    Simulator simulator(options);
    std::vector<Telegram> telegrams = run(simulator);
    ASSERT_EQ(simulator.injections().size(), 1u);
    BusDecoder decoder;
    std::vector<Decoded> decoded = decode_all(telegrams, decoder);
    const Decoded& cut = decoded[simulator.injections()[0].telegram - 1];
    EXPECT_EQ(cut.problems, std::vector<ProblemKind>{ProblemKind::Truncated});
    for (std::size_t i = 0; i < decoded.size(); ++i)
        if (i + 1 != simulator.injections()[0].telegram) {
            EXPECT_TRUE(decoded[i].problems.empty()) << i;
        }
}

TEST(SimulatorTest, ConfigMismatchLengthensOneRequest) {
    SimulatorOptions options = small_session(9, 20);
    options.slaves = {{3, 1, Dialect::Vlt}};
    options.faults = {FaultSpec{FaultKind::ConfigMismatch, 0, 5, 3}};
    Simulator simulator(options);
    std::vector<Telegram> telegrams = run(simulator);
    ASSERT_EQ(simulator.injections().size(), 1u);
    BusDecoder decoder;
    std::vector<Decoded> decoded = decode_all(telegrams, decoder);
    std::size_t long_requests = 0;
    for (std::size_t i = 0; i < decoded.size(); ++i) {
        const Decoded& d = decoded[i];
        if (d.service != Service::DataExchange || d.direction != Direction::Request) continue;
        if (d.du.size() == 14) {
            ++long_requests;
            EXPECT_EQ(i + 1, simulator.injections()[0].telegram);
        } else {
            EXPECT_EQ(d.du.size(), 12u);
        }
    }
    EXPECT_EQ(long_requests, 1u);
}

// ---- DP-V1 parameter access ------------------------------------------------------------------

SimulatorOptions dpv1_session(std::uint64_t seed, std::uint64_t cycles) {
    SimulatorOptions options = small_session(seed, cycles);
    options.slaves = {
        {3, 1, Dialect::Vlt, true}, {4, 3, Dialect::Profidrive, true}, {5, 5, Dialect::Vlt, false}};
    return options;
}

// What the checks below count in a session's DP-V1 traffic, read back through the decoder.
struct Dpv1Tally {
    std::size_t telegrams = 0;
    std::size_t writes = 0, responses = 0, polls = 0;
    std::size_t multi_reads = 0, arrays = 0, descriptions = 0, texts = 0, padded = 0;
    std::size_t change_02 = 0, change_42 = 0, floats = 0, strings = 0;
    std::size_t max_polls = 0, min_polls = 1000;
    // Negative responses: their IDs, the error numbers, 0x40 blocks, errors with a subindex.
    std::set<std::uint8_t> negative_ids;
    std::set<std::uint16_t> error_numbers;
    std::size_t zero_blocks = 0, error_infos = 0;
    // Anomalies, one per response at most (the first that applies), and the telegram (1-based)
    // of the last of each kind.
    std::map<FaultKind, std::size_t> anomalies;
    std::map<FaultKind, std::size_t> anomaly_at;
    std::map<FaultKind, std::uint8_t> anomaly_slave;
    std::size_t problems = 0;
    bool set_prm_enables_dpv1 = true;
};

struct Dpv1Pending {
    bool open = false;       // a request written and echoed, its response not read yet
    bool any_write = false;  // a request has been written
    std::uint8_t reference = 0, id = 0, axis = 0, count = 0;
    std::vector<ProfidriveAddress> addresses;
    std::int64_t write_time = 0;
    std::size_t polls = 0;
    bool awaiting_echo = false;
    bool unknown_attribute = false;  // dpv1_unknown_code: its refusal is part of that anomaly
};

Dpv1Tally tally_dpv1(const std::vector<Telegram>& telegrams) {
    Dpv1Tally tally;
    BusDecoder decoder;
    std::map<std::uint8_t, Dpv1Pending> pending;
    std::uint8_t slave = 0;
    auto anomaly = [&](FaultKind kind, std::size_t number) {
        ++tally.anomalies[kind];
        tally.anomaly_at[kind] = number;
        tally.anomaly_slave[kind] = slave;
    };
    for (std::size_t i = 0; i < telegrams.size(); ++i) {
        const Telegram& t = telegrams[i];
        const DecodedTelegram& d =
            decoder.decode(Bytes(t.bytes.data(), t.bytes.size()), t.time_ns, i + 1);
        if (d.dp.service == Service::SetPrm && d.direction == Direction::Request &&
            (d.slave == 3 || d.slave == 4)) {
            const SetPrm* prm = d.dp.service_data.set_prm();
            tally.set_prm_enables_dpv1 = tally.set_prm_enables_dpv1 && prm && prm->dpv1_enabled();
        }
        if (d.dp.service != Service::MsacC1) continue;
        slave = d.slave;
        ++tally.telegrams;
        if (!d.problems().empty()) ++tally.problems;
        const Dpv1Pdu* pdu = d.dp.service_data.dpv1();
        if (!pdu) {
            ++tally.problems;
            continue;
        }
        Dpv1Pending& p = pending[d.slave];
        const ProfidriveMessage* message = d.dp.service_data.profidrive();
        if (d.direction == Direction::Request) {
            if (pdu->is_write()) {
                ++tally.writes;
                if (!message || !message->has_header || message->is_response) {
                    ++tally.problems;
                    continue;
                }
                if (p.open) anomaly(FaultKind::Dpv1StackedRequest, i + 1);
                if (p.any_write &&
                    message->reference != (p.reference == 0xFF ? 1 : p.reference + 1))
                    ++tally.problems;  // the reference goes up by one per request
                p.any_write = true;
                p.reference = message->reference;
                p.id = message->id;
                p.axis = message->axis;
                p.count = message->count;
                p.addresses = message->addresses;
                p.write_time = d.time_ns;
                p.polls = 0;
                p.awaiting_echo = true;
                if (message->count >= 2 && !message->is_change_request()) ++tally.multi_reads;
                if (message->id == profidrive::kChangeValue) ++tally.change_02;
                if (message->id == profidrive::kChangeValueNonVolatile) ++tally.change_42;
                p.unknown_attribute = false;
                for (const ProfidriveAddress& a : message->addresses) {
                    if (profidrive_attribute_name(a.attribute).empty()) {
                        anomaly(FaultKind::Dpv1UnknownCode, i + 1);
                        p.unknown_attribute = true;
                    }
                    if (a.elements > 1) ++tally.arrays;
                    if (a.attribute == profidrive::kAttributeDescription) ++tally.descriptions;
                    if (a.attribute == profidrive::kAttributeText) ++tally.texts;
                }
            } else if (!pdu->is_read() || pdu->length != 240 || !pdu->data.empty()) {
                ++tally.problems;
            }
            continue;
        }
        // Responses.
        if (p.awaiting_echo) {
            p.awaiting_echo = false;
            if (pdu->layout == Dpv1Pdu::Layout::Error && pdu->function == 0xDF) {
                anomaly(FaultKind::Dpv1ErrorPdu, i + 1);
                p.open = false;
            } else if (pdu->is_write() && pdu->data.empty()) {
                p.open = true;
            } else {
                ++tally.problems;
            }
            continue;
        }
        if (pdu->is_state_conflict()) {
            ++tally.polls;
            ++p.polls;
            if (p.open && d.time_ns - p.write_time > 1'000'000'000 && p.polls > 0) {
                anomaly(FaultKind::Dpv1ResponseTimeout, i + 1);
                p.open = false;  // counted once
            }
            continue;
        }
        if (!message || !message->is_response || !message->has_header) {
            ++tally.problems;
            continue;
        }
        ++tally.responses;
        if (!p.open) {
            anomaly(FaultKind::Dpv1OrphanResponse, i + 1);
            continue;
        }
        p.open = false;
        tally.max_polls = std::max(tally.max_polls, p.polls);
        tally.min_polls = std::min(tally.min_polls, p.polls);
        // The decoder names the response from the request it answers.
        if (!message->has_request || message->addresses.size() != p.addresses.size()) {
            ++tally.problems;
        } else {
            for (std::size_t k = 0; k < p.addresses.size(); ++k)
                if (message->addresses[k].pnu != p.addresses[k].pnu) ++tally.problems;
        }
        for (const ProfidriveValueBlock& block : message->blocks) {
            if (block.padded) ++tally.padded;
            if (block.format == 0x08) ++tally.floats;
            if (block.format == 0x09 || block.format == 0x0A) ++tally.strings;
        }
        if (p.unknown_attribute) {
            // Refused with error 0x16 (illegal parameter address), and nothing else.
            if (!message->negative() || message->blocks.size() != 1 ||
                message->blocks[0].error_number() != 0x16)
                ++tally.problems;
        } else if (message->reference != p.reference) {
            anomaly(FaultKind::Dpv1ReferenceMismatch, i + 1);
        } else if (!profidrive_response_answers(message->id, p.id)) {
            anomaly(FaultKind::Dpv1UnexpectedResponseId, i + 1);
        } else if (message->count != p.count || message->axis != p.axis) {
            anomaly(FaultKind::Dpv1ParameterCountMismatch, i + 1);
        } else if (message->negative()) {
            anomaly(FaultKind::Dpv1NegativeResponse, i + 1);
            tally.negative_ids.insert(message->id);
            for (const ProfidriveValueBlock& block : message->blocks) {
                if (block.format == profidrive::kFormatZero) ++tally.zero_blocks;
                if (block.is_error()) tally.error_numbers.insert(block.error_number());
                if (block.has_error_info()) ++tally.error_infos;
            }
            for (const ProfidriveValueBlock& block : message->blocks)
                if (block.format != profidrive::kFormatZero && !block.is_error() &&
                    (message->id & 0x7F) == profidrive::kChangeValue)
                    ++tally.problems;  // a negative change response: 0x40 and 0x44 blocks only
        } else {
            bool consistent = message->trailing == 0;
            if (message->id == profidrive::kChangeValue) {
                consistent = consistent && message->blocks.empty();
            } else {
                consistent = consistent && message->blocks.size() == message->count;
                for (std::size_t k = 0; consistent && k < message->blocks.size(); ++k) {
                    const ProfidriveValueBlock& block = message->blocks[k];
                    const ProfidriveAddress& a = p.addresses[k];
                    consistent = block.complete && !block.is_error();
                    bool string = block.format == 0x09 || block.format == 0x0A;
                    if (a.attribute == profidrive::kAttributeValue && !string)
                        consistent = consistent && block.count == a.elements;
                }
            }
            if (!consistent) anomaly(FaultKind::Dpv1LengthError, i + 1);
        }
    }
    return tally;
}

TEST(SimulatorTest, Dpv1ParameterAccessDecodes) {
    for (std::uint64_t seed : {1u, 2u, 3u}) {
        SCOPED_TRACE(seed);
        Dpv1Tally tally = tally_dpv1(run(dpv1_session(seed, 600)));
        EXPECT_TRUE(tally.set_prm_enables_dpv1);
        EXPECT_EQ(tally.problems, 0u);
        EXPECT_TRUE(tally.anomalies.empty());  // a clean session
        EXPECT_GT(tally.writes, 100u);
        EXPECT_GT(tally.responses, 100u);
        EXPECT_LE(tally.writes - tally.responses, 2u);  // the last may still be open
        // Each response after one to three polls answered with state conflict.
        EXPECT_EQ(tally.min_polls, 1u);
        EXPECT_EQ(tally.max_polls, 3u);
        EXPECT_GE(tally.polls, tally.responses);
        // The mix.
        EXPECT_GT(tally.multi_reads, 0u);
        EXPECT_GT(tally.arrays, 0u);
        EXPECT_GT(tally.descriptions, 0u);
        EXPECT_GT(tally.texts, 0u);
        EXPECT_GT(tally.change_02, 0u);
        EXPECT_GT(tally.change_42, 0u);  // the vlt slave's non-volatile change
        EXPECT_GT(tally.padded, 0u);
        EXPECT_GT(tally.floats, 0u);
        EXPECT_GT(tally.strings, 0u);
    }
}

TEST(SimulatorTest, Dpv1SlaveStartsUpWithDpv1Enabled) {
    SimulatorOptions options = small_session(3, 5);
    options.slaves = {{3, 3, Dialect::Vlt, true}};
    std::vector<Telegram> telegrams = run(options);
    BusDecoder decoder;
    std::vector<Decoded> decoded = decode_all(telegrams, decoder);
    auto set_prm = std::find_if(decoded.begin(), decoded.end(), [](const Decoded& d) {
        return d.service == Service::SetPrm && d.direction == Direction::Request;
    });
    ASSERT_NE(set_prm, decoded.end());
    EXPECT_EQ(set_prm->du, hex("88 0A 0A 0B 04 02 00 80 00 00"));
    // A slave without DP-V1 keeps the DP-V0 Set_Prm.
    options.slaves = {{3, 3, Dialect::Vlt}};
    BusDecoder plain;
    decoded = decode_all(run(options), plain);
    set_prm = std::find_if(decoded.begin(), decoded.end(), [](const Decoded& d) {
        return d.service == Service::SetPrm && d.direction == Direction::Request;
    });
    ASSERT_NE(set_prm, decoded.end());
    EXPECT_EQ(set_prm->du, hex("88 0A 0A 0B 04 02 00"));
    EXPECT_EQ(std::count_if(decoded.begin(), decoded.end(),
                            [](const Decoded& d) { return d.service == Service::MsacC1; }),
              0);
}

TEST(SimulatorTest, Dpv1SessionsAreReproducible) {
    std::vector<Telegram> a = run(dpv1_session(5, 200));
    std::vector<Telegram> b = run(dpv1_session(5, 200));
    std::vector<Telegram> c = run(dpv1_session(6, 200));
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].bytes, b[i].bytes) << i;
        EXPECT_EQ(a[i].time_ns, b[i].time_ns) << i;
    }
    bool differs = a.size() != c.size();
    for (std::size_t i = 0; !differs && i < a.size(); ++i)
        differs = a[i].bytes != c[i].bytes;
    EXPECT_TRUE(differs);
}

TEST(SimulatorTest, EachDpv1FaultShowsOnceWhereAsked) {
    for (std::size_t i = 0; i < kFaultKindCount; ++i) {
        auto kind = static_cast<FaultKind>(i);
        if (!fault_needs_dpv1(kind)) continue;
        for (std::uint8_t address : {std::uint8_t{3}, std::uint8_t{4}}) {
            SCOPED_TRACE(std::string(fault_kind_name(kind)) + " on slave " +
                         std::to_string(address));
            SimulatorOptions options = dpv1_session(11, 150);
            options.faults = {FaultSpec{kind, 0, 20, address}};
            Simulator simulator(options);
            std::vector<Telegram> telegrams = run(simulator);
            ASSERT_EQ(simulator.injections().size(), 1u);
            const Injection& injection = simulator.injections()[0];
            EXPECT_EQ(injection.kind, kind);
            EXPECT_EQ(injection.slave, address);
            EXPECT_GE(injection.cycle, 20u);
            Dpv1Tally tally = tally_dpv1(telegrams);
            EXPECT_EQ(tally.problems, 0u);
            ASSERT_EQ(tally.anomalies.size(), 1u);
            EXPECT_EQ(tally.anomalies.begin()->first, kind);
            EXPECT_EQ(tally.anomalies.begin()->second, 1u);
            // The anomaly shows at the injected telegram or after it.
            EXPECT_GE(tally.anomaly_at[kind], injection.telegram);
            EXPECT_EQ(tally.anomaly_slave[kind], address);
        }
    }
}

TEST(SimulatorTest, Dpv1NegativeResponsesMixErrorsAndZeroBlocks) {
    SimulatorOptions options = dpv1_session(13, 600);
    options.faults = {FaultSpec{FaultKind::Dpv1NegativeResponse, 1.0, std::nullopt, std::nullopt}};
    Dpv1Tally tally = tally_dpv1(run(options));
    EXPECT_EQ(tally.problems, 0u);
    EXPECT_EQ(tally.anomalies.size(), 1u);
    EXPECT_GT(tally.anomalies[FaultKind::Dpv1NegativeResponse], 100u);
    EXPECT_EQ(tally.negative_ids, (std::set<std::uint8_t>{0x81, 0x82}));
    // Unknown parameter, read-only, limits, subindex, no texts.
    EXPECT_EQ(tally.error_numbers, (std::set<std::uint16_t>{0x00, 0x01, 0x02, 0x03, 0x0F}));
    EXPECT_GT(tally.zero_blocks, 0u);  // a multi-parameter change that wrote one of its values
    EXPECT_GT(tally.error_infos, 0u);  // the subindex after the error number
}

TEST(SimulatorTest, Dpv1ResponseTimeoutKeepsTheSessionOpenUntilTheMasterGivesUp) {
    SimulatorOptions options = dpv1_session(11, 100);
    options.faults = {FaultSpec{FaultKind::Dpv1ResponseTimeout, 0, 90, 3}};
    std::vector<Telegram> telegrams = run(options);
    ASSERT_FALSE(telegrams.empty());
    // The master gives up after 1.5 s; the session runs on past it.
    EXPECT_GT(telegrams.back().time_ns - options.start_time_ns, 1'500'000'000);
    EXPECT_EQ(tally_dpv1(telegrams).anomalies[FaultKind::Dpv1ResponseTimeout], 1u);
}

TEST(SimulatorTest, Dpv1FaultsNeedADpv1Slave) {
    SimulatorOptions options = small_session(9, 100);
    options.faults = {FaultSpec{FaultKind::Dpv1ErrorPdu, 0, std::nullopt, std::nullopt}};
    EXPECT_EQ(check_simulator_faults(options).error(),
              "fault dpv1_error_pdu: no simulated slave runs DP-V1 (add one with "
              "--slave ADDR:PPO[:DIALECT]:dpv1)");
    options.slaves = {{3, 1, Dialect::Vlt}, {4, 3, Dialect::Vlt, true}};
    options.faults = {FaultSpec{FaultKind::Dpv1NegativeResponse, 0, 5, 3}};
    EXPECT_EQ(check_simulator_faults(options).error(),
              "fault dpv1_negative_response@5:3: slave 3 does not run DP-V1 (give it as "
              "--slave ADDR:PPO[:DIALECT]:dpv1)");
    options.faults = {FaultSpec{FaultKind::Dpv1NegativeResponse, 0, 5, 4}};
    EXPECT_TRUE(check_simulator_faults(options));
    // A DP-V1 slave without a PCV takes no parameter-channel fault.
    options.faults = {FaultSpec{FaultKind::StackedRequest, 0, 5, 4}};
    EXPECT_FALSE(check_simulator_faults(options));
    // Armed at a rate, a dpv1 fault only goes to the DP-V1 slave.
    options.faults = {FaultSpec{FaultKind::Dpv1NegativeResponse, 0.5, std::nullopt, std::nullopt}};
    Simulator simulator(options);
    run(simulator);
    EXPECT_GT(simulator.injections().size(), 5u);
    for (const Injection& injection : simulator.injections())
        EXPECT_EQ(injection.slave, 4);
}

// Without a DP-V1 slave the simulator writes what it wrote before DP-V1 existed: the samples
// made by scripts/make-samples come out byte for byte.
TEST(SimulatorTest, SessionsWithoutDpv1AreUnchanged) {
    struct Case {
        std::string sample;
        SimulatorOptions options;
    };
    SimulatorOptions profidrive = small_session(16, 30);
    profidrive.slaves = {{8, 1, Dialect::Profidrive}, {9, 5, Dialect::Profidrive}};
    SimulatorOptions faults = small_session(19, 60);
    for (const char* text :
         {"fcs_error@4:3", "garbage@6:4", "malformed_telegram@8:5", "stacked_request@10:3",
          "request_rejected@12:4", "mismatched_response@14:5", "unknown_code@18:3",
          "config_mismatch@20:4", "orphan_response@22:5", "fdl_retry@26:3", "no_authority@28:4",
          "unexpected_response_type@30:5", "spontaneous_message@34:3", "spm_violation@40:4",
          "fdl_no_response@44:5"})
        faults.faults.push_back(*parse_fault_spec(text));
    for (Case& c : std::vector<Case>{{"samples/profidrive.pcap", profidrive},
                                     {"samples/faults.pcap", faults}}) {
        SCOPED_TRACE(c.sample);
        std::vector<Telegram> telegrams = run(c.options);
        OpenResult opened = open_source(test::source_dir() + "/" + c.sample, InputFormat::Auto,
                                        profibus_protocol());
        ASSERT_TRUE(opened) << opened.error();
        Record record;
        std::size_t n = 0;
        while (opened.value()->next(record)) {
            ASSERT_LT(n, telegrams.size());
            EXPECT_EQ(std::vector<std::uint8_t>(record.bytes.begin(), record.bytes.end()),
                      telegrams[n].bytes)
                << n;
            EXPECT_EQ(record.time_ns, telegrams[n].time_ns) << n;
            ++n;
        }
        EXPECT_EQ(n, telegrams.size());
    }
}

}  // namespace
}  // namespace dpscope
