// Session tracker: simulator scenarios for every finding kind (exact findings asserted), a clean
// multi-slave session with none, and hand-built telegram sequences for the cyclic rules: the
// one-cycle lag, stale repeats, RC 7 with PNU 0, identical consecutive requests, spontaneous
// messages, time-outs and latency.
#include "protocols/profibus/session_tracker.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <vector>

#include "capture/gsd_files.hpp"
#include "protocols/fc/fc_decoder.hpp"
#include "protocols/fc/fc_tracker.hpp"
#include "protocols/profibus/bus_decoder.hpp"
#include "protocols/profibus/telegram_builder.hpp"
#include "protocols/vlt2000/vlt2000_decoder.hpp"
#include "protocols/vlt2000/vlt2000_tracker.hpp"
#include "simulator/simulator.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using Counts = std::map<std::string, int>;

Counts count_kinds(const std::vector<Finding>& findings) {
    Counts counts;
    for (const Finding& f : findings)
        ++counts[std::string(finding_kind_name(f.kind))];
    return counts;
}

// ---- simulator scenarios ------------------------------------------------------------------------

struct SimulatedRun {
    std::vector<Finding> findings;
    std::vector<Injection> injections;
    std::vector<ChannelStats> channels;
    // Each channel's GSD checks (ChannelStats::gsd points into the tracker, gone after the run).
    std::vector<std::optional<GsdCheckStats>> gsd;
    std::uint64_t transactions = 0;
};

SimulatedRun simulate(SimulatorOptions options, DecoderOptions decoder_options = {},
                      TrackerOptions tracker_options = {}) {
    Simulator simulator(options);
    BusDecoder decoder(decoder_options);
    SessionTracker tracker(tracker_options);
    SimulatedRun run;
    std::vector<std::uint8_t> bytes;
    std::int64_t time = 0;
    std::uint64_t frame = 0;
    while (simulator.next(bytes, time)) {
        const DecodedTelegram& t = decoder.decode(Bytes(bytes.data(), bytes.size()), time, ++frame);
        for (const Finding& f : tracker.track(t))
            run.findings.push_back(f);
    }
    for (const Finding& f : tracker.finish())
        run.findings.push_back(f);
    run.injections = simulator.injections();
    for (const ChannelStats* stats : tracker.channels()) {
        run.channels.push_back(*stats);
        run.channels.back().gsd = nullptr;
        run.gsd.push_back(stats->gsd ? std::optional<GsdCheckStats>(*stats->gsd) : std::nullopt);
    }
    run.transactions = tracker.transactions();
    return run;
}

// The sample GSD files (samples/gsd/): the VLT 5000 (0x0402) and the PROFIdrive drive (0x6001).
std::shared_ptr<const GsdLibrary> sample_gsd_library() {
    Result<LoadedGsdFiles> loaded = load_gsd_files(
        {}, std::vector<std::string>{std::string(DPSCOPE_SOURCE_DIR) + "/samples/gsd"});
    EXPECT_TRUE(loaded) << loaded.error();
    EXPECT_TRUE(loaded && loaded->warnings.empty());
    return loaded ? loaded->library : nullptr;
}

SimulatorOptions three_slaves(std::uint64_t cycles) {
    SimulatorOptions options;
    options.seed = 42;
    options.cycles = cycles;
    options.slaves = {{3, 1, Dialect::Vlt}, {4, 2, Dialect::Vlt}, {5, 5, Dialect::Vlt}};
    return options;
}

TEST(SessionTrackerTest, CleanMultiSlaveSessionHasNoFindings) {
    SimulatorOptions options;
    options.seed = 7;
    options.cycles = 3000;
    options.cycle_us = 5000;  // seven slaves need more than the default 2 ms
    options.slaves = {{3, 1, Dialect::Vlt},       {4, 2, Dialect::Vlt}, {5, 5, Dialect::Vlt},
                      {6, 3, Dialect::Vlt},       {7, 4, Dialect::Vlt}, {8, 1, Dialect::Profidrive},
                      {9, 5, Dialect::Profidrive}};
    DecoderOptions decoder;
    decoder.station_dialect[8] = Dialect::Profidrive;
    decoder.station_dialect[9] = Dialect::Profidrive;
    SimulatedRun run = simulate(options, decoder);
    EXPECT_TRUE(run.findings.empty()) << finding_kind_name(run.findings[0].kind) << " in frame "
                                      << run.findings[0].frame << ": " << run.findings[0].message;
    EXPECT_GT(run.transactions, 1000u);
    for (const ChannelStats& s : run.channels) {
        bool with_pcv = s.slave != 6 && s.slave != 7;
        EXPECT_EQ(s.transactions.total() > 0, with_pcv) << "slave " << int(s.slave);
        if (!with_pcv) continue;
        EXPECT_EQ(s.transactions.total(), s.transactions.positive) << "slave " << int(s.slave);
        EXPECT_EQ(s.timeouts, 0u);
        EXPECT_EQ(s.abandoned, 0u);
        // Answers come one to three cycles after the request.
        EXPECT_GE(s.latency_cycles.min(), 1u);
        EXPECT_LE(s.latency_cycles.max(), 3u);
        EXPECT_GT(s.latency_ns.min(), 5'000'000u);
        EXPECT_LT(s.latency_ns.max(), 3 * 5'000'000u + 1'000'000u);
    }
}

struct FaultScenario {
    const char* fault;
    std::uint64_t cycles;
    Counts expected;
};

class FaultScenarioTest : public ::testing::TestWithParam<FaultScenario> {};

TEST_P(FaultScenarioTest, ExactlyTheExpectedFindings) {
    const FaultScenario& scenario = GetParam();
    Result<FaultSpec> fault = parse_fault_spec(std::string(scenario.fault) + "@40:4");
    ASSERT_TRUE(fault) << fault.error();
    SimulatorOptions options = three_slaves(scenario.cycles);
    if (std::optional<FindingKind> provokes = fault_finding_kind(fault->kind);
        provokes && finding_component(*provokes) == FindingComponent::Dpv1ParameterAccess) {
        // The DP-V1 faults need slave 4 to talk DP-V1.
        Result<SimulatedSlave> dpv1_slave = parse_slave_spec("4:2:vlt:dpv1");
        ASSERT_TRUE(dpv1_slave) << dpv1_slave.error();
        options.slaves[1] = *dpv1_slave;
    }
    DecoderOptions decoder;
    TrackerOptions tracker;
    if (std::optional<FindingKind> provokes = fault_finding_kind(fault->kind);
        provokes && finding_component(*provokes) == FindingComponent::DeviceDescription) {
        // The GSD faults: the slaves described by the sample GSD files, the line's rate known.
        decoder.gsd = sample_gsd_library();
        tracker.line_baud = options.baud;
        if (fault->kind == FaultKind::GsdUserPrmRange) {
            // The user parameters are the DP-V1 status bytes of the PROFIdrive sample drive.
            Result<SimulatedSlave> dpv1_slave = parse_slave_spec("4:2:profidrive:dpv1");
            ASSERT_TRUE(dpv1_slave) << dpv1_slave.error();
            options.slaves[1] = *dpv1_slave;
            decoder.station_dialect[4] = Dialect::Profidrive;
        }
    }
    options.faults.push_back(*fault);
    SimulatedRun run = simulate(options, decoder, tracker);
    ASSERT_EQ(run.injections.size(), 1u) << "the fault was not injected";
    EXPECT_EQ(count_kinds(run.findings), scenario.expected);
    for (const Finding& f : run.findings) {
        EXPECT_FALSE(f.message.empty());
        EXPECT_GE(f.frame, run.injections[0].telegram) << f.message;
        EXPECT_EQ(f.severity, default_severity(f.kind));
        if (f.has_stations) {
            EXPECT_EQ(f.master, 2);
            EXPECT_EQ(f.slave, 4);
        }
    }
}

// One scenario per simulator fault: the fault injected once, on slave 4 at cycle 40, and the
// findings it must yield. The coverage tests below read this table.
const FaultScenario kFaultScenarios[] = {
    // The simulated master retries once (same FCB) after a damaged or missing response.
    FaultScenario{"fcs_error", 120, {{"fcs_error", 1}, {"fdl_retry", 1}}},
    FaultScenario{"garbage", 120, {{"malformed_telegram", 1}}},
    FaultScenario{"malformed_telegram", 120, {{"malformed_telegram", 1}, {"fdl_retry", 1}}},
    FaultScenario{"stacked_request", 120, {{"stacked_request", 1}}},
    FaultScenario{"orphan_response", 120, {{"orphan_response", 1}}},
    FaultScenario{"mismatched_response", 120, {{"mismatched_response", 1}}},
    FaultScenario{"unexpected_response_type", 120, {{"unexpected_response_type", 1}}},
    FaultScenario{"response_timeout", 1200, {{"response_timeout", 1}}},
    FaultScenario{"request_rejected", 120, {{"request_rejected", 1}}},
    FaultScenario{"no_authority", 300, {{"no_authority", 1}}},
    FaultScenario{"spontaneous_message", 120, {{"spontaneous_message", 1}}},
    FaultScenario{"spontaneous_unacknowledged",
                  1200,
                  {{"spontaneous_message", 1}, {"spontaneous_unacknowledged", 1}}},
    FaultScenario{"spm_violation", 120, {{"spm_violation", 1}}},
    FaultScenario{"config_mismatch", 120, {{"config_mismatch", 1}}},
    FaultScenario{"unknown_code", 120, {{"unknown_code", 1}}},
    FaultScenario{"fdl_retry", 120, {{"fdl_no_response", 1}, {"fdl_retry", 1}}},
    // No reply to the request nor to its retry; the next telegram also finds one missing.
    FaultScenario{"fdl_no_response", 120, {{"fdl_no_response", 2}, {"fdl_retry", 1}}},
    // Bus-health faults (docs/bus-health.md), judged by the BusHealthTracker: the session tracker
    // sees only their missing responses. station_lost: five polls and their repeats unanswered.
    FaultScenario{"station_lost", 120, {{"fdl_no_response", 10}, {"fdl_retry", 5}}},
    FaultScenario{"resync", 120, {}},
    FaultScenario{"answer_not_asked", 120, {}},
    FaultScenario{"answer_wrong_kind", 120, {}},
    FaultScenario{"answer_short_ack", 120, {}},
    FaultScenario{"diag_fault", 120, {}},
    // Two responses lost: each repeat is an fdl_retry, each loss an fdl_no_response.
    FaultScenario{"repeats", 120, {{"fdl_no_response", 2}, {"fdl_retry", 2}}},
    FaultScenario{"refusal", 120, {}},
    // DP-V1 parameter access (the simulator's DP-V1 traffic): each fault yields its own finding.
    FaultScenario{"dpv1_stacked_request", 120, {{"dpv1_stacked_request", 1}}},
    FaultScenario{"dpv1_reference_mismatch", 120, {{"dpv1_reference_mismatch", 1}}},
    FaultScenario{"dpv1_unexpected_response_id", 120, {{"dpv1_unexpected_response_id", 1}}},
    FaultScenario{"dpv1_parameter_count_mismatch", 120, {{"dpv1_parameter_count_mismatch", 1}}},
    FaultScenario{"dpv1_orphan_response", 120, {{"dpv1_orphan_response", 1}}},
    FaultScenario{"dpv1_response_timeout", 1200, {{"dpv1_response_timeout", 1}}},
    FaultScenario{"dpv1_negative_response", 120, {{"dpv1_negative_response", 1}}},
    FaultScenario{"dpv1_length_error", 120, {{"dpv1_length_error", 1}}},
    FaultScenario{"dpv1_error_pdu", 120, {{"dpv1_error_pdu", 1}}},
    // A read with an attribute no table has, refused by the drive (error 0x16).
    FaultScenario{
        "dpv1_unknown_code", 120, {{"dpv1_unknown_code", 1}, {"dpv1_negative_response", 1}}},
    // GSD faults, the slaves checked against the sample GSD files (samples/gsd/).
    FaultScenario{"gsd_ident_mismatch", 120, {{"gsd_ident_mismatch", 1}}},
    FaultScenario{"gsd_unknown_module", 120, {{"gsd_unknown_module", 1}}},
    // Two PPO modules: the Data_Exchange lengths then disagree with the configuration, both ways.
    FaultScenario{"gsd_config_limit", 120, {{"gsd_config_limit", 1}, {"config_mismatch", 2}}},
    FaultScenario{"gsd_user_prm_length", 120, {{"gsd_user_prm_length", 1}}},
    FaultScenario{"gsd_user_prm_range", 120, {{"gsd_user_prm_range", 1}}},
    FaultScenario{"gsd_diag_too_long", 120, {{"gsd_diag_too_long", 1}}},
    FaultScenario{"gsd_late_response", 120, {{"gsd_late_response", 1}}},
    FaultScenario{"gsd_poll_interval", 120, {{"gsd_poll_interval", 1}}},
};

TEST(SessionTrackerTest, GsdKindsAreTheDeviceDescriptionComponent) {
    std::vector<FindingKind> component = finding_kinds_of(FindingComponent::DeviceDescription);
    EXPECT_EQ(component, std::vector<FindingKind>(kGsdKinds.begin(), kGsdKinds.end()));
}

TEST(SessionTrackerTest, CleanSessionKeepsToItsGsdFiles) {
    SimulatorOptions options = three_slaves(200);
    Result<SimulatedSlave> dpv1_slave = parse_slave_spec("4:2:profidrive:dpv1");
    ASSERT_TRUE(dpv1_slave) << dpv1_slave.error();
    options.slaves[1] = *dpv1_slave;
    DecoderOptions decoder;
    decoder.gsd = sample_gsd_library();
    decoder.station_dialect[4] = Dialect::Profidrive;
    TrackerOptions tracker;
    tracker.line_baud = options.baud;
    SimulatedRun run = simulate(options, decoder, tracker);
    EXPECT_EQ(count_kinds(run.findings), Counts{});
    ASSERT_EQ(run.gsd.size(), 3u);
    for (const std::optional<GsdCheckStats>& gsd : run.gsd) {
        ASSERT_TRUE(gsd);
        ASSERT_NE(gsd->device, nullptr);
        EXPECT_GE(gsd->judged_by(FindingKind::GsdIdentMismatch), 3u);  // Diag, Set_Prm, Diag
        for (std::uint64_t broken : gsd->broken)
            EXPECT_EQ(broken, 0u);
        EXPECT_GT(gsd->response_ns.count(), 200u);
        EXPECT_GT(gsd->max_tsdr_ns, 0u);
    }
}

INSTANTIATE_TEST_SUITE_P(SessionTrackerTest, FaultScenarioTest,
                         ::testing::ValuesIn(kFaultScenarios),
                         [](const ::testing::TestParamInfo<FaultScenario>& param) {
                             return std::string(param.param.fault);
                         });

// ---- FC protocol scenarios ----------------------------------------------------------------------
// The FC faults on hand-made FC telegrams, decoded by FcDecoder and judged by FcTracker (the FC
// tracker's detailed tests are in fc_tracker_test.cpp): a clean exchange with drives 1 and 2 (a
// command every 10 ms, answered after 5 ms), with the fault at the fourth exchange.

struct FcStep {
    std::vector<std::uint8_t> bytes;
    std::int64_t time_ms;
};

struct FcScenario {
    const char* fault;
    std::vector<FcStep> steps;
    Counts expected;
};

// Exchanges with drives 1 and 2 from `t0_ms`: read PNU 414 from drive 1, a process block to drive
// 2, each answered after 5 ms.
void fc_clean(std::vector<FcStep>& steps, std::int64_t t0_ms, int exchanges) {
    for (int i = 0; i < exchanges; ++i) {
        const std::int64_t t = t0_ms + 10 * i;
        if (i % 2 == 0) {
            steps.push_back({test::fc_parameter(1, 1, 414), t});
            steps.push_back({test::fc_parameter(1, 1, 414, 0, 1500, 0x0607, 0x2000), t + 5});
        } else {
            steps.push_back({test::fc_process(2), t});
            steps.push_back({test::fc_process(2, 0x0607, 0x2000), t + 5});
        }
    }
}

std::vector<FcScenario> fc_scenarios() {
    auto with = [](std::vector<FcStep> fault) {
        std::vector<FcStep> steps;
        fc_clean(steps, 0, 3);
        for (FcStep& step : fault)
            steps.push_back(std::move(step));
        fc_clean(steps, 100, 3);
        return steps;
    };
    std::vector<std::uint8_t> bad_bcc = test::fc_parameter(1, 1, 414, 0, 1500, 0x0607, 0x2000);
    bad_bcc.back() ^= 0x01;
    return {
        // A second command to drive 1 before it answered the first (a write: AK 14 is a command
        // only, so the decoder cannot take it for the answer).
        {"fc_stacked_request",
         with({{test::fc_parameter(1, 1, 414), 30},
               {test::fc_parameter(1, 14, 415, 0, 7), 35},
               {test::fc_parameter(1, 1, 415, 0, 7, 0x0607, 0x2000), 40}}),
         {{"fc_stacked_request", 1}}},
        // Drive 1 does not answer; the master moves on to drive 2.
        {"fc_no_response",
         with({{test::fc_parameter(1, 1, 414), 30},
               {test::fc_process(2), 50},
               {test::fc_process(2, 0x0607, 0x2000), 55}}),
         {{"fc_no_response", 1}}},
        // Drive 1 answers after 30 ms (more than 20).
        {"fc_late_response",
         with({{test::fc_parameter(1, 1, 414), 30},
               {test::fc_parameter(1, 1, 414, 0, 1500, 0x0607, 0x2000), 60}}),
         {{"fc_late_response", 1}}},
        // The answer carries PNU 415 for a read of PNU 414.
        {"fc_mismatched_response",
         with({{test::fc_parameter(1, 1, 414), 30},
               {test::fc_parameter(1, 1, 415, 0, 1500, 0x0607, 0x2000), 35}}),
         {{"fc_mismatched_response", 1}}},
        // A word write answered with a double word value.
        {"fc_unexpected_response_type",
         with({{test::fc_parameter(1, 2, 414, 0, 1500), 30},
               {test::fc_parameter(1, 2, 414, 0, 1500, 0x0607, 0x2000), 35}}),
         {{"fc_unexpected_response_type", 1}}},
        // AK 7 with fault code 2 (limit exceeded).
        {"fc_command_rejected",
         with({{test::fc_parameter(1, 14, 414, 0, 60000), 30},
               {test::fc_parameter(1, 7, 414, 0, 2, 0x0607, 0x2000), 35}}),
         {{"fc_command_rejected", 1}}},
        // One answer with a wrong BCC.
        {"fc_bcc_error",
         with({{test::fc_parameter(1, 1, 414), 30}, {bad_bcc, 35}}),
         {{"fc_bcc_error", 1}}},
    };
}

std::vector<Finding> run_fc(const std::vector<FcStep>& steps) {
    FcDecoder decoder;
    FcTracker tracker;
    std::vector<Finding> findings;
    std::uint64_t frame = 0;
    for (const FcStep& step : steps) {
        const DecodedTelegram& t = decoder.decode(step.bytes, step.time_ms * 1'000'000, ++frame);
        for (const Finding& f : tracker.track(t))
            findings.push_back(f);
    }
    for (const Finding& f : tracker.finish())
        findings.push_back(f);
    return findings;
}

TEST(SessionTrackerTest, FcScenariosGiveExactlyTheExpectedFindings) {
    std::vector<FcStep> clean;
    fc_clean(clean, 0, 8);
    EXPECT_TRUE(run_fc(clean).empty());
    for (const FcScenario& scenario : fc_scenarios()) {
        SCOPED_TRACE(scenario.fault);
        std::vector<Finding> findings = run_fc(scenario.steps);
        EXPECT_EQ(count_kinds(findings), scenario.expected);
        for (const Finding& f : findings) {
            EXPECT_FALSE(f.message.empty());
            EXPECT_EQ(f.severity, default_severity(f.kind));
            EXPECT_TRUE(f.has_stations);
            EXPECT_EQ(f.master, 0);
            EXPECT_EQ(f.slave, 1) << f.message;
        }
    }
}

// ---- VLT 2000 scenarios ------------------------------------------------------------------------
// The VLT 2000 faults simulated (simulate --bus vlt2000), decoded by Vlt2000Decoder and judged by
// Vlt2000Tracker: drives 1, 2 and 5, the fault once on drive 2 from cycle 40 of 120. The simulated
// drives also fail some commands by design (vlt2000_simulated_failure: the background of
// vlt2000_command_failed notes, counted apart); beyond those, exactly the expected findings.

struct Vlt2000Scenario {
    const char* fault;
    Counts expected;
};

const Vlt2000Scenario kVlt2000Scenarios[] = {
    // A second command (another letter) to drive 2 before its reply.
    {"vlt2000_stacked_request", {{"vlt2000_stacked_request", 1}}},
    // Drive 2 does not reply; the master moves on to the next drive.
    {"vlt2000_no_response", {{"vlt2000_no_response", 1}}},
    // Drive 2 replies to the next broadcast.
    {"vlt2000_unexpected_reply", {{"vlt2000_unexpected_reply", 1}}},
    // The reply carries the next parameter number.
    {"vlt2000_mismatched_response", {{"vlt2000_mismatched_response", 1}}},
    // A command that works otherwise fails: decimal position 9, reason 01 or 04.
    {"vlt2000_command_failed", {{"vlt2000_command_failed", 1}}},
    // One reply with two digits that are not the sum's.
    {"vlt2000_checksum_error", {{"vlt2000_checksum_error", 1}}},
    // From then on "??" to and from drive 2: one note.
    {"vlt2000_checksum_disabled", {{"vlt2000_checksum_disabled", 1}}},
    // The shared faults on a VLT 2000 bus: junk between telegrams, a reply cut short.
    {"garbage", {{"malformed_telegram", 1}}},
    {"malformed_telegram", {{"malformed_telegram", 1}}},
};

struct Vlt2000Run {
    std::vector<Finding> findings;  // beyond the background
    std::uint64_t background = 0;   // command_failed notes of commands that fail by design
    std::vector<Injection> injections;
    std::uint64_t transactions = 0;
};

Vlt2000Run simulate_vlt2000(std::vector<FaultSpec> faults, std::uint64_t seed = 42,
                            std::uint64_t cycles = 120) {
    SimulatorOptions options;
    options.bus = Protocol::Vlt2000;
    options.baud = 0;
    options.seed = seed;
    options.cycles = cycles;
    options.vlt2000_drives = {1, 2, 5};
    options.faults = std::move(faults);
    Simulator simulator(options);
    Vlt2000Decoder decoder;
    Vlt2000Tracker tracker;
    Vlt2000Run run;
    // The commands, by frame: whether the simulated drive fails them by design.
    std::map<std::uint64_t, bool> fails_by_design;
    auto keep = [&](const Finding& f) {
        if (f.kind == FindingKind::Vlt2000CommandFailed && fails_by_design[f.request_frame])
            ++run.background;
        else
            run.findings.push_back(f);
    };
    std::vector<std::uint8_t> bytes;
    std::int64_t time = 0;
    std::uint64_t frame = 0;
    while (simulator.next(bytes, time)) {
        const DecodedTelegram& t = decoder.decode(Bytes(bytes.data(), bytes.size()), time, ++frame);
        if (t.has_roles && t.direction == Direction::Request)
            fails_by_design[frame] =
                vlt2000_simulated_failure(static_cast<char>(t.vlt2000.letter_char),
                                          t.vlt2000.parameter, t.vlt2000.index_number)
                    .has_value();
        for (const Finding& f : tracker.track(t))
            keep(f);
    }
    for (const Finding& f : tracker.finish())
        keep(f);
    run.injections = simulator.injections();
    run.transactions = tracker.transactions();
    return run;
}

TEST(SessionTrackerTest, CleanVlt2000SessionHasOnlyTheDrivesOwnFailures) {
    Vlt2000Run run = simulate_vlt2000({}, 7, 600);
    EXPECT_TRUE(run.findings.empty()) << finding_kind_name(run.findings[0].kind) << " in frame "
                                      << run.findings[0].frame << ": " << run.findings[0].message;
    EXPECT_GT(run.background, 10u);
    EXPECT_GT(run.transactions, 1500u);
}

TEST(SessionTrackerTest, Vlt2000ScenariosGiveExactlyTheExpectedFindings) {
    for (const Vlt2000Scenario& scenario : kVlt2000Scenarios) {
        SCOPED_TRACE(scenario.fault);
        Result<FaultSpec> fault =
            parse_fault_spec(std::string(scenario.fault) + "@40:2", Protocol::Vlt2000);
        ASSERT_TRUE(fault) << fault.error();
        Vlt2000Run run = simulate_vlt2000({*fault});
        ASSERT_EQ(run.injections.size(), 1u) << "the fault was not injected";
        EXPECT_EQ(count_kinds(run.findings), scenario.expected);
        for (const Finding& f : run.findings) {
            EXPECT_FALSE(f.message.empty());
            EXPECT_GE(f.frame, run.injections[0].telegram) << f.message;
            EXPECT_EQ(f.severity, default_severity(f.kind));
            if (f.has_stations) {
                EXPECT_EQ(f.master, 0);
                // A reply to a broadcast comes with address 00.
                EXPECT_EQ(f.slave, f.kind == FindingKind::Vlt2000UnexpectedReply ? 0 : 2)
                    << f.message;
            }
        }
    }
}

// Every injection of a VLT 2000 kind, at a rate over a long session, yields exactly its finding
// and nothing else (the kinds judged once per address or per broadcast left out).
TEST(SessionTrackerTest, Vlt2000FaultsAtARateAreAllFoundAndNothingElse) {
    for (const Vlt2000Scenario& scenario : kVlt2000Scenarios) {
        const std::string name = scenario.fault;
        if (name == "vlt2000_checksum_disabled" || name == "vlt2000_unexpected_reply") continue;
        SCOPED_TRACE(name);
        Result<FaultSpec> fault = parse_fault_spec(name + "=0.01", Protocol::Vlt2000);
        ASSERT_TRUE(fault) << fault.error();
        Vlt2000Run run = simulate_vlt2000({*fault}, 3, 1500);
        const int injected = static_cast<int>(run.injections.size());
        ASSERT_GT(injected, 10);
        Counts want;
        for (const auto& [kind, n] : scenario.expected)
            want[kind] = n * injected;
        EXPECT_EQ(count_kinds(run.findings), want);
    }
}

TEST(SessionTrackerTest, EveryKindIsCoveredByAScenario) {
    // Some scenario of kFaultScenarios (PROFIBUS DP, simulated), of the FC scenarios or of the
    // VLT 2000 scenarios expects each finding kind.
    std::set<std::string> covered;
    for (const FaultScenario& scenario : kFaultScenarios)
        for (const auto& [kind, count] : scenario.expected)
            covered.insert(kind);
    for (const FcScenario& scenario : fc_scenarios())
        for (const auto& [kind, count] : scenario.expected)
            covered.insert(kind);
    for (const Vlt2000Scenario& scenario : kVlt2000Scenarios)
        for (const auto& [kind, count] : scenario.expected)
            covered.insert(kind);
    for (std::size_t i = 0; i < kFindingKindCount; ++i)
        EXPECT_TRUE(covered.count(std::string(finding_kind_name(static_cast<FindingKind>(i)))))
            << finding_kind_name(static_cast<FindingKind>(i));
    // ... and names only finding kinds.
    for (const std::string& kind : covered)
        EXPECT_TRUE(finding_kind_from_name(kind).has_value()) << kind;
}

TEST(SessionTrackerTest, EverySimulatorFaultHasAScenario) {
    // Every fault has a scenario on its own bus; garbage and malformed_telegram (PROFIBUS DP
    // faults the VLT 2000 bus takes too) also one on the VLT 2000 bus.
    std::map<Protocol, std::set<std::string>> faults;
    for (const FaultScenario& scenario : kFaultScenarios)
        faults[Protocol::ProfibusDp].insert(scenario.fault);
    const std::vector<FcScenario> fc = fc_scenarios();
    for (const FcScenario& scenario : fc)
        faults[Protocol::Fc].insert(scenario.fault);
    for (const Vlt2000Scenario& scenario : kVlt2000Scenarios)
        faults[Protocol::Vlt2000].insert(scenario.fault);
    for (const auto& [bus, names] : faults) {
        for (const std::string& name : names) {
            auto kind = fault_kind_from_name(name);
            ASSERT_TRUE(kind) << name;
            EXPECT_TRUE(fault_applies_to_bus(*kind, bus)) << name;
        }
    }
    for (std::size_t i = 0; i < kFaultKindCount; ++i) {
        const auto kind = static_cast<FaultKind>(i);
        EXPECT_TRUE(faults[fault_bus(kind)].count(std::string(fault_kind_name(kind))))
            << fault_kind_name(kind);
        if (fault_applies_to_bus(kind, Protocol::Vlt2000)) {
            EXPECT_TRUE(faults[Protocol::Vlt2000].count(std::string(fault_kind_name(kind))))
                << fault_kind_name(kind);
        }
    }
    EXPECT_EQ(faults[Protocol::ProfibusDp].size(), std::size(kFaultScenarios))
        << "a fault with two scenarios";
    EXPECT_EQ(faults[Protocol::Fc].size(), fc.size()) << "a fault with two scenarios";
    EXPECT_EQ(faults[Protocol::Vlt2000].size(), std::size(kVlt2000Scenarios))
        << "a fault with two scenarios";
}

TEST(SessionTrackerTest, TimeoutFindingNamesTheRequestAndItsDeadline) {
    SimulatorOptions options = three_slaves(1200);
    options.faults.push_back(FaultSpec{FaultKind::ResponseTimeout, 0, 40, 3});
    SimulatedRun run = simulate(options);
    ASSERT_EQ(run.findings.size(), 1u);
    const Finding& f = run.findings[0];
    EXPECT_EQ(f.kind, FindingKind::ResponseTimeout);
    EXPECT_NE(f.request_frame, 0u);
    EXPECT_GT(f.frame, f.request_frame);
    EXPECT_TRUE(f.pnu.has_value());
    EXPECT_NE(f.message.find("within 1000 ms"), std::string::npos) << f.message;
    // With a time-out longer than the master waits, there is no finding at all: the master gives
    // up (after 1500 ms) and the request counts as abandoned.
    TrackerOptions patient;
    patient.timeout_ns = 2'000'000'000;
    SimulatedRun long_wait = simulate(options, {}, patient);
    EXPECT_TRUE(long_wait.findings.empty());
    std::uint64_t abandoned = 0;
    for (const ChannelStats& s : long_wait.channels)
        abandoned += s.abandoned;
    EXPECT_EQ(abandoned, 1u);
}

// Every injection of a kind, at a rate over a long session and several seeds, yields exactly its
// findings and nothing else. (Left out: time-outs, which cannot be seen when injected in the last
// second of a capture, and kinds whose back-to-back injections are one repeated telegram.)
TEST(SessionTrackerTest, FaultsAtARateAreAllFoundAndNothingElse) {
    struct Expected {
        FaultKind kind;
        Counts per_injection;
    };
    const std::vector<Expected> table = {
        {FaultKind::FcsError, {{"fcs_error", 1}, {"fdl_retry", 1}}},
        {FaultKind::Garbage, {{"malformed_telegram", 1}}},
        {FaultKind::MalformedTelegram, {{"malformed_telegram", 1}, {"fdl_retry", 1}}},
        {FaultKind::StackedRequest, {{"stacked_request", 1}}},
        {FaultKind::OrphanResponse, {{"orphan_response", 1}}},
        {FaultKind::MismatchedResponse, {{"mismatched_response", 1}}},
        {FaultKind::UnexpectedResponseType, {{"unexpected_response_type", 1}}},
        {FaultKind::RequestRejected, {{"request_rejected", 1}}},
        {FaultKind::NoAuthority, {{"no_authority", 1}}},
        {FaultKind::SpontaneousMessage, {{"spontaneous_message", 1}}},
        {FaultKind::SpmViolation, {{"spm_violation", 1}}},
        {FaultKind::FdlRetry, {{"fdl_no_response", 1}, {"fdl_retry", 1}}},
        {FaultKind::FdlNoResponse, {{"fdl_no_response", 2}, {"fdl_retry", 1}}},
    };
    for (const Expected& expected : table) {
        for (std::uint64_t seed : {1, 2, 3}) {
            SimulatorOptions options = three_slaves(2500);
            options.seed = seed;
            options.faults.push_back(FaultSpec{expected.kind, 0.004, {}, {}});
            SimulatedRun run = simulate(options);
            int injected = static_cast<int>(run.injections.size());
            ASSERT_GT(injected, 5) << fault_kind_name(expected.kind);
            Counts want;
            for (const auto& [kind, n] : expected.per_injection)
                want[kind] = n * injected;
            EXPECT_EQ(count_kinds(run.findings), want)
                << fault_kind_name(expected.kind) << ", seed " << seed;
        }
    }
}

// ---- hand-built sequences -----------------------------------------------------------------------

struct Word {
    std::uint8_t rc = 0;
    std::uint16_t pnu = 0;
    std::uint8_t ind = 0;
    std::uint32_t pva = 0;
    bool spm = false;
};

// Master 2 and slave 3 (PPO 1) exchanging Data_Exchange telegrams, 2 ms per cycle.
class Channel {
  public:
    explicit Channel(TrackerOptions tracker_options = {}, Dialect dialect = Dialect::Vlt)
        : decoder_(options(dialect)), tracker_(tracker_options) {}

    // One cycle: the master's request, then the slave's response.
    void cycle(Word master, Word slave) {
        request(master);
        response(slave);
        now_ += 2'000'000 - 200'000;
    }
    // A damaged request (bad FCS) gets no reply; the master sends it again with the same FCB.
    void request(Word w, bool bad_fcs = false) {
        std::vector<std::uint8_t> bytes =
            build(3, 2, request_fc(FdlFunction::SrdHigh, fcb_, true), w, 0x047F);
        if (bad_fcs) bytes[bytes.size() - 2] ^= 0x01;
        feed(bytes);
        if (!bad_fcs) fcb_ = !fcb_;
        now_ += 200'000;
    }
    void response(Word w, bool bad_fcs = false) {
        std::vector<std::uint8_t> bytes = build(2, 3, response_fc(FdlStatus::DataLow), w, 0x0F07);
        if (bad_fcs) bytes[bytes.size() - 2] ^= 0x01;
        feed(bytes);
    }
    // The end of the capture, `later_ms` after the last telegram (a live capture's stop).
    void finish(std::int64_t later_ms = 0) {
        for (const Finding& f : tracker_.finish(later_ms ? now_ + later_ms * 1'000'000 : kNoTime))
            findings.push_back(f);
    }
    const ChannelStats& stats() const { return *tracker_.channels().at(0); }
    void advance_ms(std::int64_t ms) { now_ += ms * 1'000'000; }
    std::uint64_t frame() const { return frame_; }
    // The PNU the last telegram fed is about (SessionTracker::subject_pnu).
    std::int32_t subject_pnu() const { return tracker_.subject_pnu(); }

    std::vector<Finding> findings;

  private:
    static DecoderOptions options(Dialect dialect) {
        DecoderOptions o;
        o.station_ppo[3] = 1;
        o.dialect = dialect;
        return o;
    }
    static std::vector<std::uint8_t> build(std::uint8_t da, std::uint8_t sa, std::uint8_t fc,
                                           Word w, std::uint16_t word1) {
        std::vector<std::uint8_t> du;
        append_pcv(du, w.rc, w.spm, w.pnu, w.ind, w.pva);
        append_u16_be(du, word1);
        append_u16_be(du, 0x2000);
        return build_telegram({da, sa, fc, {}, {}, Bytes(du)});
    }
    void feed(const std::vector<std::uint8_t>& bytes) {
        const DecodedTelegram& t =
            decoder_.decode(Bytes(bytes.data(), bytes.size()), now_, ++frame_);
        for (const Finding& f : tracker_.track(t))
            findings.push_back(f);
    }

    BusDecoder decoder_;
    SessionTracker tracker_;
    std::int64_t now_ = 1'704'067'200'000'000'000;
    std::uint64_t frame_ = 0;
    bool fcb_ = true;
};

const Word kIdle{};
const Word kRead520{1, 520};
const Word kValue520{1, 520, 0, 240};
const Word kRead518{1, 518};
const Word kValue518{1, 518, 0, 500};

TEST(SessionTrackerTest, OneCycleLagIsNoOrphan) {
    Channel ch;
    ch.cycle(kRead520, kIdle);      // the slave sees the request a cycle late
    ch.cycle(kRead520, kValue520);  // answered
    ch.cycle(kIdle, kValue520);     // the master moved on; the answer still arrives
    ch.cycle(kIdle, kIdle);
    EXPECT_TRUE(ch.findings.empty());
    EXPECT_EQ(ch.stats().transactions.positive, 1u);
    EXPECT_EQ(ch.stats().latency_cycles.max(), 1u);
    // From the first request telegram to the answer: one cycle (2 ms) plus the 0.2 ms between
    // request and response.
    EXPECT_EQ(ch.stats().latency_ns.max(), 2'200'000u);
}

TEST(SessionTrackerTest, LaggingAnswerWithAFreshValueIsNoOrphan) {
    Channel ch;
    ch.cycle(kRead520, kValue520);
    ch.cycle(kIdle, Word{1, 520, 0, 241});  // the live value moved on in the lag cycle
    ch.cycle(kIdle, kIdle);
    EXPECT_TRUE(ch.findings.empty());
}

TEST(SessionTrackerTest, AnswerTwoCyclesAfterTheMasterMovedOnIsAnOrphan) {
    Channel ch;
    ch.cycle(kRead520, kValue520);
    ch.cycle(kIdle, kValue520);
    ch.cycle(kIdle, kIdle);
    ch.cycle(kIdle, kValue520);  // fresh again, nothing asked
    ASSERT_EQ(ch.findings.size(), 1u);
    EXPECT_EQ(ch.findings[0].kind, FindingKind::OrphanResponse);
    EXPECT_EQ(ch.findings[0].pnu, 520);
    EXPECT_EQ(ch.findings[0].frame, ch.frame());
}

TEST(SessionTrackerTest, StaleRepeatsWhileTheNextRequestIsWorkedOn) {
    Channel ch;
    ch.cycle(kRead520, kIdle);
    ch.cycle(kRead520, kValue520);
    ch.cycle(kRead518, kValue520);  // the master goes straight to the next request
    ch.cycle(kRead518, kValue520);  // the slave still shows the old answer
    ch.cycle(kRead518, kValue518);
    ch.cycle(kIdle, kValue518);
    EXPECT_TRUE(ch.findings.empty()) << ch.findings[0].message;
    EXPECT_EQ(ch.stats().transactions.positive, 2u);
    EXPECT_EQ(ch.stats().latency_cycles.max(), 2u);
}

TEST(SessionTrackerTest, RepeatedIdenticalRequestCountsOnce) {
    Channel ch;
    for (int i = 0; i < 5; ++i)
        ch.cycle(kRead520, kIdle);
    ch.cycle(kRead520, kValue520);
    for (int i = 0; i < 5; ++i)
        ch.cycle(kRead520, kValue520);
    EXPECT_TRUE(ch.findings.empty());
    EXPECT_EQ(ch.stats().requests, 1u);
    EXPECT_EQ(ch.stats().transactions.total(), 1u);
    EXPECT_EQ(ch.stats().latency_cycles.max(), 5u);
}

TEST(SessionTrackerTest, IdenticalConsecutiveRequestsSeparatedByRc0) {
    Channel ch;
    ch.cycle(kRead520, kIdle);
    ch.cycle(kRead520, kValue520);
    ch.cycle(kIdle, kValue520);
    ch.cycle(kRead520, kIdle);  // the same request again after one RC 0 cycle
    ch.cycle(kRead520, kValue520);
    ch.cycle(kIdle, kValue520);
    EXPECT_TRUE(ch.findings.empty());
    EXPECT_EQ(ch.stats().requests, 2u);
    EXPECT_EQ(ch.stats().transactions.positive, 2u);
    EXPECT_EQ(ch.stats().pnu_requests.at(520), 2u);
}

TEST(SessionTrackerTest, IdenticalRequestsAnsweredByASlaveThatNeverClears) {
    Channel ch;
    ch.cycle(kRead520, kIdle);
    ch.cycle(kRead520, kValue520);
    ch.cycle(kIdle, kValue520);
    ch.cycle(kRead520, kValue520);  // lags: still the old answer
    ch.cycle(kRead520, kValue520);  // the same answer, now for the new request
    ch.cycle(kIdle, kValue520);
    EXPECT_TRUE(ch.findings.empty()) << ch.findings[0].message;
    EXPECT_EQ(ch.stats().transactions.positive, 2u);
}

TEST(SessionTrackerTest, ReadBackOfTheValueJustWrittenIsAnswered) {
    Channel ch;
    const Word write{2, 100, 0, 50};
    const Word written{1, 100, 0, 50};
    const Word read{1, 100};
    ch.cycle(write, kIdle);
    ch.cycle(write, written);
    ch.cycle(read, written);  // lag: still the write's answer
    ch.cycle(read, written);  // the same bytes, now answering the read
    ch.cycle(Word{1, 200}, written);
    ch.cycle(Word{1, 200}, Word{1, 200, 0, 7});
    ch.cycle(kIdle, Word{1, 200, 0, 7});
    ch.cycle(kIdle, kIdle);
    EXPECT_TRUE(ch.findings.empty()) << ch.findings[0].message;
    EXPECT_EQ(ch.stats().requests, 3u);
    EXPECT_EQ(ch.stats().transactions.positive, 3u);
    EXPECT_EQ(ch.stats().latency_cycles.max(), 1u);
}

TEST(SessionTrackerTest, RefreshedAnswerWhileTheRequestStandsIsNoOrphan) {
    Channel ch;
    ch.cycle(kRead520, kIdle);
    ch.cycle(kRead520, kValue520);
    ch.cycle(kRead520, Word{1, 520, 0, 241});  // the master still asks; the value moves on
    ch.cycle(kRead520, Word{1, 520, 0, 242});
    ch.cycle(kIdle, Word{1, 520, 0, 242});
    ch.cycle(kIdle, kIdle);
    EXPECT_TRUE(ch.findings.empty()) << ch.findings[0].message;
    EXPECT_EQ(ch.stats().transactions.positive, 1u);
}

TEST(SessionTrackerTest, ResponseInTheRequestsFirstCycleDoesNotAnswerIt) {
    // The slave answers from the data it had before this exchange: a response in the cycle a
    // request first appears cannot be its answer.
    Channel ch;
    ch.cycle(kRead520, kIdle);
    ch.cycle(kRead520, kValue520);
    ch.cycle(kIdle, kValue520);
    ch.cycle(kRead518, Word{1, 518, 0, 500});  // a stale answer for 518 from nowhere
    ch.cycle(kRead518, Word{1, 518, 0, 500});
    EXPECT_EQ(count_kinds(ch.findings), (Counts{{"orphan_response", 1}}));
    EXPECT_EQ(ch.findings[0].frame, 8u);
    // The repeat a cycle later answers the request.
    EXPECT_EQ(ch.stats().transactions.positive, 2u);
}

TEST(SessionTrackerTest, CaptureStartingInTheLagCycleHasNoOrphan) {
    Channel moved_on;  // the master just moved on to PNU 200; the slave still shows PNU 100
    moved_on.cycle(Word{1, 200}, Word{1, 100, 0, 55});
    moved_on.cycle(Word{1, 200}, Word{1, 200, 0, 7});
    moved_on.cycle(kIdle, Word{1, 200, 0, 7});
    moved_on.cycle(kIdle, kIdle);
    EXPECT_TRUE(moved_on.findings.empty()) << moved_on.findings[0].message;
    EXPECT_EQ(moved_on.stats().transactions.positive, 1u);

    Channel idle;  // the master went back to RC 0; the slave still shows its answer
    idle.cycle(kIdle, Word{1, 100, 0, 55});
    idle.cycle(kIdle, kIdle);
    EXPECT_TRUE(idle.findings.empty()) << idle.findings[0].message;
}

TEST(SessionTrackerTest, CaptureStartingAfterTheAnswerHasNoTimeout) {
    // The request was issued and answered before the capture began; it stands for 1.4 s.
    Channel ch;
    for (int i = 0; i < 700; ++i)
        ch.cycle(kRead520, kValue520);
    ch.cycle(kIdle, kValue520);
    ch.cycle(kIdle, kIdle);
    ch.finish();
    EXPECT_TRUE(ch.findings.empty()) << ch.findings[0].message;
    EXPECT_EQ(ch.stats().requests, 0u);  // not captured from its start: no transaction
    EXPECT_EQ(ch.stats().transactions.total(), 0u);
    EXPECT_EQ(ch.stats().abandoned, 0u);
    EXPECT_EQ(ch.stats().timeouts, 0u);
    EXPECT_TRUE(ch.stats().pnu_requests.empty());

    // Only a request standing when the capture began: later, the same bytes shown since before
    // are a slave that does not clear its answer, and the repeat a cycle on answers.
    Channel later;
    for (int i = 0; i < 5; ++i)
        later.cycle(kIdle, kValue520);
    later.cycle(kRead520, kValue520);
    later.cycle(kRead520, kValue520);
    later.cycle(kIdle, kValue520);
    EXPECT_TRUE(later.findings.empty()) << later.findings[0].message;
    EXPECT_EQ(later.stats().requests, 1u);
    EXPECT_EQ(later.stats().transactions.positive, 1u);
    EXPECT_EQ(later.stats().latency_cycles.max(), 1u);
}

TEST(SessionTrackerTest, LateRejectionOfAnAbandonedRequestIsNoMismatch) {
    Channel ch;
    ch.cycle(Word{2, 100, 0, 9999}, kIdle);
    ch.cycle(kIdle, kIdle);  // the master gives up on the write
    ch.cycle(Word{1, 200}, kIdle);
    ch.cycle(Word{1, 200}, Word{7, 100, 0, 2});  // the write's rejection, late
    ch.cycle(Word{1, 200}, Word{1, 200, 0, 7});
    ch.cycle(kIdle, Word{1, 200, 0, 7});
    EXPECT_TRUE(ch.findings.empty()) << ch.findings[0].message;
    EXPECT_EQ(ch.stats().abandoned, 1u);
    EXPECT_EQ(ch.stats().transactions.positive, 1u);
}

TEST(SessionTrackerTest, RejectionNamingAnotherPnuIsMismatched) {
    Channel ch;
    ch.cycle(Word{1, 200}, kIdle);
    ch.cycle(Word{1, 200}, Word{7, 300, 0, 2});  // only PNU 0 may stand for the request's
    ch.cycle(kIdle, Word{7, 300, 0, 2});
    ASSERT_EQ(count_kinds(ch.findings), (Counts{{"mismatched_response", 1}}));
    EXPECT_NE(ch.findings[0].message.find("answer RC 7 for PNU 300"), std::string::npos)
        << ch.findings[0].message;
    EXPECT_EQ(ch.stats().transactions.mismatched, 1u);
}

TEST(SessionTrackerTest, StaleValueIsNoAnswerToAChangeRequestForAnotherValue) {
    const Word write9{2, 100, 0, 9};
    const Word rejected{7, 100, 0, 2};
    Channel after_read;
    after_read.cycle(Word{1, 100}, kIdle);
    after_read.cycle(Word{1, 100}, Word{1, 100, 0, 5});
    after_read.cycle(write9, Word{1, 100, 0, 5});
    after_read.cycle(write9, Word{1, 100, 0, 5});  // value 5 is not the 9 written
    after_read.cycle(write9, rejected);
    after_read.cycle(kIdle, rejected);
    EXPECT_EQ(count_kinds(after_read.findings), (Counts{{"request_rejected", 1}}));
    EXPECT_EQ(after_read.stats().transactions.positive, 1u);
    EXPECT_EQ(after_read.stats().transactions.rejected, 1u);

    Channel after_rejection;  // a rejection is no answer to another write
    after_rejection.cycle(Word{2, 100, 0, 9999}, kIdle);
    after_rejection.cycle(Word{2, 100, 0, 9999}, rejected);
    after_rejection.cycle(Word{2, 100, 0, 50}, rejected);
    after_rejection.cycle(Word{2, 100, 0, 50}, rejected);
    after_rejection.cycle(Word{2, 100, 0, 50}, Word{1, 100, 0, 50});
    after_rejection.cycle(kIdle, Word{1, 100, 0, 50});
    EXPECT_EQ(count_kinds(after_rejection.findings), (Counts{{"request_rejected", 1}}));
    EXPECT_EQ(after_rejection.stats().transactions.positive, 1u);
    EXPECT_EQ(after_rejection.stats().latency_cycles.max(), 2u);

    Channel capture_start;  // the value shown at the start is not the 9 being written
    capture_start.cycle(write9, Word{1, 100, 0, 5});
    capture_start.cycle(write9, rejected);
    capture_start.cycle(kIdle, rejected);
    EXPECT_EQ(count_kinds(capture_start.findings), (Counts{{"request_rejected", 1}}));
}

TEST(SessionTrackerTest, StackedRequestDoesNotTakeItsPredecessorsRejection) {
    Channel ch;
    ch.cycle(Word{2, 100, 0, 9999}, kIdle);
    ch.cycle(Word{1, 100}, Word{7, 100, 0, 2});  // stacked; the write's rejection, late
    ch.cycle(Word{1, 100}, Word{7, 100, 0, 2});
    ch.cycle(Word{1, 100}, Word{1, 100, 0, 5});
    ch.cycle(kIdle, Word{1, 100, 0, 5});
    EXPECT_EQ(count_kinds(ch.findings), (Counts{{"stacked_request", 1}}));
    EXPECT_EQ(ch.stats().transactions.positive, 1u);
    EXPECT_EQ(ch.stats().transactions.rejected, 0u);
}

TEST(SessionTrackerTest, RejectionWithPnu0CanBeARepeatOrStandAtTheCaptureStart) {
    const Word write{2, 100, 0, 9999};
    const Word rejected{7, 0, 0, 2};  // PCA 70 00
    Channel start;
    for (int i = 0; i < 700; ++i)
        start.cycle(write, rejected);
    start.finish();
    EXPECT_TRUE(start.findings.empty()) << start.findings[0].message;
    EXPECT_EQ(start.stats().requests, 0u);

    Channel again;  // a slave that does not clear its answer; the same write after RC 0
    again.cycle(write, kIdle);
    again.cycle(write, rejected);
    again.cycle(kIdle, rejected);
    again.cycle(kIdle, rejected);
    for (int i = 0; i < 600; ++i)
        again.cycle(write, rejected);
    again.finish();
    EXPECT_EQ(count_kinds(again.findings), (Counts{{"request_rejected", 2}}));
    EXPECT_EQ(again.stats().transactions.rejected, 2u);
}

TEST(SessionTrackerTest, OtherCodesWhileTheMasterHoldsAnAnsweredRequestAreOrphans) {
    Channel ch;
    ch.cycle(Word{1, 100}, kIdle);
    ch.cycle(Word{1, 100}, Word{1, 100, 0, 5});
    ch.cycle(Word{1, 100}, Word{7, 100, 0, 17});  // only a refreshed value is no orphan
    ch.cycle(Word{1, 100}, Word{3, 100, 0, 1});
    ch.cycle(kIdle, kIdle);
    EXPECT_EQ(count_kinds(ch.findings), (Counts{{"orphan_response", 2}}));
}

TEST(SessionTrackerTest, OrphanBeyondTheFirstCycleIsReported) {
    Channel ch;
    for (int i = 0; i < 5; ++i)
        ch.cycle(kIdle, kIdle);
    ch.cycle(Word{1, 100}, Word{1, 300, 0, 9});  // PNU 300 answers nothing
    ch.cycle(Word{1, 100}, kIdle);
    ch.cycle(Word{1, 100}, Word{1, 100, 0, 5});
    EXPECT_EQ(count_kinds(ch.findings), (Counts{{"orphan_response", 1}}));
    EXPECT_EQ(ch.findings[0].pnu, 300);
}

TEST(SessionTrackerTest, RefreshedOrphanIsReportedOnce) {
    Channel ch;
    ch.cycle(Word{1, 100}, kIdle);
    ch.cycle(Word{1, 100}, Word{1, 100, 0, 5});
    ch.cycle(kIdle, Word{1, 100, 0, 5});
    ch.cycle(kIdle, Word{1, 100, 0, 5});
    ch.cycle(kIdle, Word{1, 100, 0, 6});  // the slave keeps refreshing after RC 0
    ch.cycle(kIdle, Word{1, 100, 0, 7});
    ch.cycle(kIdle, kIdle);
    ch.cycle(kIdle, Word{1, 100, 0, 8});  // again after it showed something else
    EXPECT_EQ(count_kinds(ch.findings), (Counts{{"orphan_response", 2}}));
}

TEST(SessionTrackerTest, RejectionWithPnu0IsARejectionNotAMismatch) {
    Channel ch;
    const Word write{2, 215, 0, 999};
    ch.cycle(write, kIdle);
    ch.cycle(write, Word{7, 0, 0, 2});  // PCA 70 00, error 2, as in the Danfoss FCM 300 example
    ch.cycle(kIdle, Word{7, 0, 0, 2});
    ASSERT_EQ(ch.findings.size(), 1u);
    const Finding& f = ch.findings[0];
    EXPECT_EQ(f.kind, FindingKind::RequestRejected);
    EXPECT_EQ(f.severity, Severity::Note);
    EXPECT_EQ(f.pnu, 215);
    EXPECT_EQ(f.request_frame, 1u);
    EXPECT_NE(f.message.find("error 2 (Upper or lower value passed)"), std::string::npos)
        << f.message;
    EXPECT_EQ(ch.stats().transactions.rejected, 1u);
    EXPECT_EQ(ch.stats().rejection_errors.at(2), 1u);
    EXPECT_EQ(ch.stats().rejections.at({215, 2}), 1u);
}

TEST(SessionTrackerTest, RejectionWithPnu0IsAboutTheRequestItAnswers) {
    Channel ch;
    const Word write{2, 215, 0, 999};
    ch.request(write);
    EXPECT_EQ(ch.subject_pnu(), 215);
    ch.response(kIdle);  // the cycle the request appears in: the slave has not seen it
    EXPECT_EQ(ch.subject_pnu(), 0);
    ch.request(write);
    ch.response(Word{7, 0, 0, 2});  // the rejection leaves the PNU out
    EXPECT_EQ(ch.subject_pnu(), 215);
    ch.request(kIdle);
    ch.response(Word{7, 0, 0, 2});  // repeated while the master moves on: still about 215
    EXPECT_EQ(ch.subject_pnu(), 215);
    ch.request(kRead520);
    EXPECT_EQ(ch.subject_pnu(), 520);
    ch.response(Word{7, 0, 0, 2});  // lagging one cycle behind the new request: still 215
    EXPECT_EQ(ch.subject_pnu(), 215);
    ch.request(kRead520);
    ch.response(Word{2, 520, 0, 5});  // an answer naming its PNU is about that PNU
    EXPECT_EQ(ch.subject_pnu(), 520);
}

TEST(SessionTrackerTest, ArrayAnswerForAnotherIndexIsMismatched) {
    Channel ch;
    const Word read_element{6, 615, 3};
    ch.cycle(read_element, kIdle);
    ch.cycle(read_element, Word{4, 615, 4, 7});
    ASSERT_EQ(ch.findings.size(), 1u);
    EXPECT_EQ(ch.findings[0].kind, FindingKind::MismatchedResponse);
    EXPECT_NE(ch.findings[0].message.find("IND 4"), std::string::npos) << ch.findings[0].message;
}

TEST(SessionTrackerTest, Rc8AfterAReadIsAWarningUnlessStrict) {
    {
        Channel lenient;
        lenient.cycle(kRead520, kIdle);
        lenient.cycle(kRead520, Word{8, 520});
        ASSERT_EQ(lenient.findings.size(), 1u);
        EXPECT_EQ(lenient.findings[0].kind, FindingKind::NoAuthority);
        EXPECT_EQ(lenient.findings[0].severity, Severity::Warning);
        EXPECT_NE(lenient.findings[0].message.find("after a read"), std::string::npos);
    }
    {
        TrackerOptions strict;
        strict.strict = true;
        Channel ch(strict);
        ch.cycle(kRead520, kIdle);
        ch.cycle(kRead520, Word{8, 520});
        ASSERT_EQ(ch.findings.size(), 1u);
        EXPECT_EQ(ch.findings[0].kind, FindingKind::UnexpectedResponseType);
    }
    {
        Channel write;  // RC 8 after a change request is a listed answer: no_authority only
        write.cycle(Word{2, 215, 0, 5}, kIdle);
        write.cycle(Word{2, 215, 0, 5}, Word{8, 215});
        ASSERT_EQ(write.findings.size(), 1u);
        EXPECT_EQ(write.findings[0].kind, FindingKind::NoAuthority);
        EXPECT_EQ(write.findings[0].message.find("after a read"), std::string::npos);
    }
}

TEST(SessionTrackerTest, WrongResponseCodeIsUnexpected) {
    Channel ch;
    ch.cycle(kRead520, kIdle);
    ch.cycle(kRead520, Word{3, 520, 0, 1});  // a description element answering a value read
    ASSERT_EQ(ch.findings.size(), 1u);
    EXPECT_EQ(ch.findings[0].kind, FindingKind::UnexpectedResponseType);
    EXPECT_EQ(ch.stats().transactions.unexpected, 1u);
}

TEST(SessionTrackerTest, StackedRequestIsReportedOnceAndItsLateAnswerIsNoMismatch) {
    Channel ch;
    ch.cycle(kRead520, kIdle);
    ch.cycle(kRead518, kIdle);      // changed before an answer
    ch.cycle(kRead518, kValue520);  // the abandoned request's answer arrives late
    ch.cycle(kRead518, kValue518);
    ASSERT_EQ(ch.findings.size(), 1u);
    EXPECT_EQ(ch.findings[0].kind, FindingKind::StackedRequest);
    EXPECT_EQ(ch.findings[0].request_frame, 1u);
    EXPECT_EQ(ch.findings[0].frame, 3u);
    EXPECT_EQ(ch.findings[0].pnu, 520);
    EXPECT_EQ(ch.stats().abandoned, 0u);  // a stacked request is a finding, not "abandoned"
    EXPECT_EQ(ch.stats().transactions.positive, 1u);
}

TEST(SessionTrackerTest, TimedOutRequestIsNotAlsoStacked) {
    Channel ch;
    ch.cycle(kRead520, kIdle);
    for (int i = 0; i < 600; ++i)
        ch.cycle(kRead520, kIdle);  // 1.2 s without an answer
    ch.cycle(kRead518, kIdle);
    ch.cycle(kRead518, kValue518);
    ASSERT_EQ(ch.findings.size(), 1u);
    EXPECT_EQ(ch.findings[0].kind, FindingKind::ResponseTimeout);
    EXPECT_EQ(ch.findings[0].request_frame, 1u);
    EXPECT_EQ(ch.stats().timeouts, 1u);
}

TEST(SessionTrackerTest, OpenRequestsAtTheEndAreJudgedByTheirAge) {
    Channel young;
    young.cycle(kRead520, kIdle);
    young.finish();
    EXPECT_TRUE(young.findings.empty());

    Channel old;
    old.cycle(kRead520, kIdle);
    old.advance_ms(1500);
    old.cycle(kIdle, kIdle);  // a later telegram moves the clock; the master gave up silently
    EXPECT_EQ(count_kinds(old.findings), (Counts{{"response_timeout", 1}}));

    // A live capture stopped 1.5 s after the last telegram: judged at the stop.
    Channel stopped;
    stopped.cycle(kRead520, kIdle);
    stopped.finish(1500);
    ASSERT_EQ(count_kinds(stopped.findings), (Counts{{"response_timeout", 1}}));
    EXPECT_EQ(stopped.findings[0].request_frame, 1u);
    EXPECT_EQ(stopped.findings[0].frame, 2u);  // the last telegram read
    Channel soon;
    soon.cycle(kRead520, kIdle);
    soon.finish(500);
    EXPECT_TRUE(soon.findings.empty());
}

TEST(SessionTrackerTest, TimeoutIsConfigurable) {
    TrackerOptions quick;
    quick.timeout_ns = 5'000'000;
    Channel ch(quick);
    for (int i = 0; i < 4; ++i)
        ch.cycle(kRead520, kIdle);  // 8 ms
    ch.cycle(kRead520, kValue520);
    ASSERT_EQ(ch.findings.size(), 1u);
    EXPECT_EQ(ch.findings[0].kind, FindingKind::ResponseTimeout);
    EXPECT_NE(ch.findings[0].message.find("within 5 ms"), std::string::npos);
    // The late answer still completes the transaction.
    EXPECT_EQ(ch.stats().transactions.positive, 1u);
}

TEST(SessionTrackerTest, SpontaneousMessageKeepsTheRequestPending) {
    Channel ch;
    const Word message{10, 538, 0, 0x000A, true};  // RC 10, slave SPM toggled to 1
    ch.cycle(kRead520, kIdle);
    ch.cycle(kRead520, message);
    ch.cycle(Word{1, 520, 0, 0, true}, message);  // master acknowledges: SPM 1
    ch.cycle(Word{1, 520, 0, 0, true}, Word{1, 520, 0, 240, true});
    ASSERT_EQ(ch.findings.size(), 1u);
    EXPECT_EQ(ch.findings[0].kind, FindingKind::SpontaneousMessage);
    EXPECT_EQ(ch.findings[0].pnu, 538);
    EXPECT_EQ(ch.stats().spontaneous, 1u);
    EXPECT_EQ(ch.stats().transactions.positive, 1u);
    EXPECT_EQ(ch.stats().latency_cycles.max(), 3u);
}

TEST(SessionTrackerTest, UnacknowledgedSpontaneousMessage) {
    Channel ch;
    const Word message{9, 538, 0, 1, true};
    ch.cycle(kIdle, message);
    for (int i = 0; i < 550; ++i)
        ch.cycle(kIdle, message);  // 1.1 s, no SPM toggle
    EXPECT_EQ(count_kinds(ch.findings),
              (Counts{{"spontaneous_message", 1}, {"spontaneous_unacknowledged", 1}}));
    ch.cycle(Word{0, 0, 0, 0, true}, message);  // a late acknowledgement is no violation
    ch.cycle(Word{0, 0, 0, 0, true}, Word{0, 0, 0, 0, true});
    EXPECT_EQ(ch.findings.size(), 2u);
}

TEST(SessionTrackerTest, MessageAcknowledgedBeforeTheCaptureIsNotPending) {
    // The capture begins after the master acknowledged: its SPM already equals the slave's.
    Channel ch;
    const Word read{1, 520, 0, 0, true};
    ch.cycle(read, Word{10, 538, 0, 0x0A, true});
    for (int i = 0; i < 700; ++i)
        ch.cycle(read, Word{1, 520, 0, 240, true});
    ch.cycle(Word{0, 0, 0, 0, true}, Word{1, 520, 0, 240, true});
    ch.finish();
    ASSERT_EQ(count_kinds(ch.findings), (Counts{{"spontaneous_message", 1}}));
    EXPECT_NE(ch.findings[0].message.find("(already acknowledged)"), std::string::npos)
        << ch.findings[0].message;
    EXPECT_EQ(ch.stats().transactions.positive, 1u);

    Channel waiting;  // the same start, but the master's SPM differs: pending
    waiting.cycle(kRead520, Word{10, 538, 0, 0x0A, true});
    waiting.cycle(Word{1, 520, 0, 0, true}, Word{10, 538, 0, 0x0A, true});
    ASSERT_EQ(count_kinds(waiting.findings), (Counts{{"spontaneous_message", 1}}));
    EXPECT_EQ(waiting.findings[0].message.find("already"), std::string::npos);
}

TEST(SessionTrackerTest, MessageStillShownIsNotAcknowledgedAfterAll) {
    // First seen with the master's SPM, but still repeated long after: never acknowledged.
    Channel ch;
    const Word message{9, 538, 0, 1, false};
    for (int i = 0; i < 700; ++i)
        ch.cycle(kIdle, message);
    EXPECT_EQ(count_kinds(ch.findings),
              (Counts{{"spontaneous_message", 1}, {"spontaneous_unacknowledged", 1}}));
    ch.cycle(Word{0, 0, 0, 0, true}, message);  // the acknowledgement, late: no violation
    ch.cycle(Word{0, 0, 0, 0, true}, Word{0, 0, 0, 0, false});
    EXPECT_EQ(ch.findings.size(), 2u);
}

TEST(SessionTrackerTest, SecondMessageTogglesSpmAgain) {
    Channel ch;
    ch.cycle(kIdle, Word{9, 538, 0, 1, true});
    ch.cycle(Word{0, 0, 0, 0, true}, Word{9, 538, 0, 1, true});
    ch.cycle(Word{0, 0, 0, 0, true}, Word{9, 538, 0, 0, false});  // a new message: SPM back to 0
    ch.cycle(Word{0, 0, 0, 0, false}, Word{0, 0, 0, 0, false});
    EXPECT_EQ(count_kinds(ch.findings), (Counts{{"spontaneous_message", 2}}));
}

TEST(SessionTrackerTest, SpmToggleWithNothingPendingIsAViolation) {
    Channel ch;
    ch.cycle(kIdle, kIdle);
    ch.cycle(Word{0, 0, 0, 0, true}, kIdle);
    ASSERT_EQ(ch.findings.size(), 1u);
    EXPECT_EQ(ch.findings[0].kind, FindingKind::SpmViolation);
    EXPECT_EQ(ch.findings[0].frame, 3u);
}

TEST(SessionTrackerTest, UndefinedCodesAreUnknownAndDoNotAnswer) {
    Channel ch;
    ch.cycle(Word{11, 520}, kIdle);  // RC 11 is no vlt request code
    EXPECT_EQ(count_kinds(ch.findings), (Counts{{"unknown_code", 1}}));
    ch.cycle(Word{11, 520}, Word{1, 520, 0, 5});  // any answer with its PNU closes it
    ch.cycle(kIdle, Word{1, 520, 0, 5});
    EXPECT_EQ(ch.findings.size(), 1u);
    EXPECT_EQ(ch.stats().transactions.positive, 1u);
    ch.findings.clear();
    ch.cycle(kRead520, kIdle);
    ch.cycle(kRead520, Word{14, 520});  // RC 14 is no vlt response code
    ch.cycle(kRead520, Word{14, 520});  // repeated: reported once
    ch.cycle(kRead520, kValue520);
    EXPECT_EQ(count_kinds(ch.findings), (Counts{{"unknown_code", 1}}));
    EXPECT_EQ(ch.stats().transactions.positive, 2u);
}

// Seed 002: a GE AF-600 marks RC 9..12 "not used". In the ge dialect they are unknown codes,
// no spontaneous messages; the pending request stays open until the real answer.
TEST(SessionTrackerTest, GeResponseCodesNineToTwelveAreUnknownCodes) {
    for (std::uint8_t rc = 9; rc <= 12; ++rc) {
        SCOPED_TRACE("RC " + std::to_string(rc));
        Channel ge({}, Dialect::Ge);
        ge.cycle(kRead520, kIdle);
        ge.cycle(kRead520, Word{rc, 520, 0, 10, true});  // SPM toggled, as a VLT message would
        ge.cycle(kRead520, kValue520);
        ge.cycle(kIdle, kValue520);
        EXPECT_EQ(count_kinds(ge.findings), (Counts{{"unknown_code", 1}}));
        EXPECT_EQ(ge.stats().spontaneous, 0u);
        EXPECT_EQ(ge.stats().transactions.positive, 1u);
        EXPECT_EQ(ge.findings[0].message,
                  fmt::format("response code RC {} is not defined in the ge dialect", rc));

        Channel vlt;  // the same telegrams in the vlt dialect: a spontaneous message
        vlt.cycle(kRead520, kIdle);
        vlt.cycle(kRead520, Word{rc, 520, 0, 10, true});
        EXPECT_EQ(count_kinds(vlt.findings), (Counts{{"spontaneous_message", 1}}));
    }
}

// The ge dialect names 130 and 131 (seed 002); vlt reports them as unknown error numbers.
TEST(SessionTrackerTest, GeRejectionNamesFaultNumbers130And131) {
    for (std::uint16_t error : {std::uint16_t{130}, std::uint16_t{131}}) {
        Channel ge({}, Dialect::Ge);
        ge.cycle(kRead520, kIdle);
        ge.cycle(kRead520, Word{7, 520, 0, error});
        ASSERT_EQ(count_kinds(ge.findings), (Counts{{"request_rejected", 1}}));
        EXPECT_NE(ge.findings[0].message.find(fmt::format("rejected with error {} ({})", error,
                                                          error_text(Dialect::Ge, error))),
                  std::string::npos)
            << ge.findings[0].message;
        EXPECT_FALSE(error_text(Dialect::Ge, error).empty());

        Channel vlt;
        vlt.cycle(kRead520, kIdle);
        vlt.cycle(kRead520, Word{7, 520, 0, error});
        ASSERT_EQ(vlt.findings.size(), 1u);
        EXPECT_NE(vlt.findings[0].message.find(
                      fmt::format("rejected with error {} (unknown error number)", error)),
                  std::string::npos)
            << vlt.findings[0].message;
    }
}

TEST(SessionTrackerTest, UndefinedRequestIsTrackedUntilAnswered) {
    Channel rejected;
    rejected.cycle(Word{13, 100}, kIdle);  // RC 13 is no vlt request code
    rejected.cycle(Word{13, 100}, Word{7, 100, 0, 18});
    rejected.cycle(kIdle, Word{7, 100, 0, 18});
    ASSERT_EQ(count_kinds(rejected.findings),
              (Counts{{"unknown_code", 1}, {"request_rejected", 1}}));
    EXPECT_EQ(rejected.findings[1].request_frame, 1u);
    EXPECT_NE(
        rejected.findings[1].message.find("RC 13 (Not assigned) PNU 100 rejected with error 18"),
        std::string::npos)
        << rejected.findings[1].message;
    EXPECT_EQ(rejected.stats().transactions.rejected, 1u);

    Channel replaced;  // left unanswered for another request: stacked, as any request
    replaced.cycle(Word{13, 100}, kIdle);
    replaced.cycle(kRead520, kIdle);
    EXPECT_EQ(count_kinds(replaced.findings),
              (Counts{{"unknown_code", 1}, {"stacked_request", 1}}));
}

TEST(SessionTrackerTest, UndefinedRequestAnsweredNegativelyIsCountedAsSuch) {
    Channel authority;
    authority.cycle(Word{12, 100}, kIdle);
    authority.cycle(Word{12, 100}, Word{8, 100});
    authority.cycle(kIdle, Word{8, 100});
    EXPECT_EQ(count_kinds(authority.findings), (Counts{{"unknown_code", 1}, {"no_authority", 1}}));
    EXPECT_EQ(authority.stats().transactions.no_authority, 1u);
    EXPECT_EQ(authority.stats().transactions.positive, 0u);

    Channel rejected;
    rejected.cycle(Word{12, 100}, kIdle);
    rejected.cycle(Word{12, 100}, Word{7, 100, 0, 2});
    EXPECT_EQ(rejected.stats().transactions.rejected, 1u);
    EXPECT_EQ(rejected.stats().rejection_errors.at(2), 1u);
    EXPECT_EQ(rejected.stats().rejections.at({100, 2}), 1u);
}

TEST(SessionTrackerTest, ProfidriveCodesAreKnownInTheProfidriveDialect) {
    Channel ch({}, Dialect::Profidrive);
    const Word eeprom_write{14, 215, 0, 7};  // change word, RAM + EEPROM
    ch.cycle(eeprom_write, kIdle);
    ch.cycle(eeprom_write, Word{1, 215, 0, 7});
    EXPECT_TRUE(ch.findings.empty());
    EXPECT_EQ(ch.stats().transactions.positive, 1u);
}

TEST(SessionTrackerTest, BadFcsTelegramIsReportedAndOtherwiseIgnored) {
    Channel ch;
    ch.cycle(kRead520, kIdle);
    ch.request(kRead520);
    ch.response(kValue520, true);  // the answer, damaged
    ch.cycle(kRead520, kValue520);
    EXPECT_EQ(count_kinds(ch.findings), (Counts{{"fcs_error", 1}}));
    EXPECT_EQ(ch.stats().transactions.positive, 1u);
    // Latency counts from the request to the first intact answer.
    EXPECT_EQ(ch.stats().latency_cycles.max(), 2u);
}

TEST(SessionTrackerTest, LatencyStatistics) {
    Channel ch;
    for (int delay = 1; delay <= 4; ++delay) {
        Word request{1, static_cast<std::uint16_t>(500 + delay)};
        Word answer{1, request.pnu, 0, 1};
        ch.cycle(request, kIdle);
        for (int i = 1; i < delay; ++i)
            ch.cycle(request, kIdle);
        ch.cycle(request, answer);
        ch.cycle(kIdle, answer);
        ch.cycle(kIdle, kIdle);
    }
    const ChannelStats& s = ch.stats();
    EXPECT_EQ(s.transactions.positive, 4u);
    EXPECT_EQ(s.latency_cycles.min(), 1u);
    EXPECT_EQ(s.latency_cycles.max(), 4u);
    EXPECT_EQ(s.latency_cycles.percentile(50), 2u);
    EXPECT_EQ(s.latency_ns.min(), 2'200'000u);
    EXPECT_EQ(s.latency_ns.max(), 8'200'000u);
    EXPECT_EQ(s.requests, 4u);
    // Each round: the request cycle, delay - 1 waiting cycles, the answer cycle, two idle ones.
    EXPECT_EQ(s.cycles, (1 + 3) + (2 + 3) + (3 + 3) + (4 + 3));
}

TEST(SessionTrackerTest, ConfigMismatchReportedOncePerLength) {
    // Slave 3 announced PPO 1 (12 bytes) in its Chk_Cfg; the master sends 14.
    BusDecoder decoder;
    SessionTracker tracker;
    std::vector<Finding> findings;
    std::uint64_t frame = 0;
    std::int64_t now = 1'000'000'000;
    auto feed = [&](const std::vector<std::uint8_t>& bytes) {
        now += 1'000'000;
        for (const Finding& f :
             tracker.track(decoder.decode(Bytes(bytes.data(), bytes.size()), now, ++frame)))
            findings.push_back(f);
    };
    std::vector<std::uint8_t> cfg = {0xF3, 0xF1};
    feed(build_telegram({3, 2, request_fc(FdlFunction::SrdHigh, true, true), 62, 62, Bytes(cfg)}));
    feed({kShortAck});
    bool fcb = false;
    auto exchange = [&](std::size_t length) {
        std::vector<std::uint8_t> du(length, 0);
        feed(
            build_telegram({3, 2, request_fc(FdlFunction::SrdHigh, fcb, true), {}, {}, Bytes(du)}));
        fcb = !fcb;
        std::vector<std::uint8_t> in(12, 0);
        feed(build_telegram({2, 3, response_fc(FdlStatus::DataLow), {}, {}, Bytes(in)}));
    };
    exchange(12);
    exchange(14);
    exchange(14);
    exchange(12);
    exchange(14);
    ASSERT_EQ(count_kinds(findings), (Counts{{"config_mismatch", 2}}));
    EXPECT_NE(findings[0].message.find("carries 14 bytes; the Chk_Cfg in frame 1 announced 12"),
              std::string::npos)
        << findings[0].message;
}

TEST(SessionTrackerTest, FdlRetryAndMissingReply) {
    BusDecoder decoder;
    SessionTracker tracker;
    std::vector<Finding> findings;
    std::uint64_t frame = 0;
    auto feed = [&](const std::vector<std::uint8_t>& bytes) {
        for (const Finding& f :
             tracker.track(decoder.decode(Bytes(bytes.data(), bytes.size()), kNoTime, ++frame)))
            findings.push_back(f);
    };
    auto srd = [](bool fcb) {
        return build_telegram({3, 2, request_fc(FdlFunction::SrdHigh, fcb, true), 60, 62, {}});
    };
    const std::vector<std::uint8_t> ack = {kShortAck};
    feed(build_telegram({3, 2, request_fc(FdlFunction::FdlStatus), {}, {}, {}}));
    feed(build_telegram({2, 3, response_fc(FdlStatus::Ok), {}, {}, {}}));
    feed(srd(true));
    feed(ack);
    feed(srd(false));  // no reply
    feed(srd(false));  // the retry, same FCB
    feed(ack);
    EXPECT_EQ(count_kinds(findings), (Counts{{"fdl_no_response", 1}, {"fdl_retry", 1}}));
    EXPECT_EQ(findings[0].request_frame, 5u);
    // After FDL_Status the frame count starts over: the same FCB is no retry.
    findings.clear();
    feed(build_telegram({3, 2, request_fc(FdlFunction::FdlStatus), {}, {}, {}}));
    feed(build_telegram({2, 3, response_fc(FdlStatus::Ok), {}, {}, {}}));
    feed(srd(true));
    feed(ack);
    feed(srd(true));  // answered, yet sent with the same FCB as the request before: a retry
    feed(ack);
    EXPECT_EQ(count_kinds(findings), (Counts{{"fdl_retry", 1}}));
    // SDN (Global_Control to everyone) expects no reply.
    findings.clear();
    std::vector<std::uint8_t> operate = {0, 0};
    feed(build_telegram({127, 2, request_fc(FdlFunction::SdnHigh), 58, 62, Bytes(operate)}));
    feed(build_telegram({3, 2, request_fc(FdlFunction::FdlStatus), {}, {}, {}}));
    EXPECT_TRUE(findings.empty());
}

TEST(SessionTrackerTest, DamagedRequestGetsNoReplyAndItsRetryIsCounted) {
    Channel ch;
    ch.cycle(kRead520, kIdle);
    ch.request(kRead520, true);  // damaged on the line: the slave stays silent, rightly
    ch.cycle(kRead520, kIdle);   // the master sends it again with the same FCB
    ch.cycle(kRead520, kValue520);
    EXPECT_EQ(count_kinds(ch.findings), (Counts{{"fcs_error", 1}, {"fdl_retry", 1}}));
    EXPECT_EQ(ch.stats().transactions.positive, 1u);
}

TEST(SessionTrackerTest, RetryOfADamagedRequestIsTheCycle) {
    Channel ch;
    ch.cycle(Word{1, 200}, kIdle);
    ch.cycle(Word{1, 200}, Word{1, 200, 0, 7});
    ch.cycle(Word{1, 100}, Word{1, 200, 0, 7});
    ch.request(Word{1, 100}, true);              // dropped by the slave
    ch.cycle(Word{1, 100}, Word{1, 100, 0, 5});  // the retry: the request's second cycle
    ch.cycle(Word{1, 100}, Word{1, 100, 0, 5});
    ch.cycle(kIdle, kIdle);
    EXPECT_EQ(count_kinds(ch.findings), (Counts{{"fcs_error", 1}, {"fdl_retry", 1}}));
    EXPECT_EQ(ch.stats().cycles, 6u);
    EXPECT_EQ(ch.stats().transactions.positive, 2u);
}

TEST(SessionTrackerTest, StatusResponseWithoutDataIsNoConfigMismatch) {
    BusDecoder decoder;
    SessionTracker tracker;
    std::vector<Finding> findings;
    std::uint64_t frame = 0;
    auto feed = [&](const std::vector<std::uint8_t>& bytes) {
        for (const Finding& f :
             tracker.track(decoder.decode(Bytes(bytes.data(), bytes.size()), kNoTime, ++frame)))
            findings.push_back(f);
    };
    std::vector<std::uint8_t> cfg = {0xF3, 0xF1};
    feed(build_telegram({3, 2, request_fc(FdlFunction::SrdHigh, true, true), 62, 62, Bytes(cfg)}));
    feed({kShortAck});
    std::vector<std::uint8_t> outputs(12, 0);
    feed(build_telegram(
        {3, 2, request_fc(FdlFunction::SrdHigh, false, true), {}, {}, Bytes(outputs)}));
    // The slave restarted: RS (SAP not activated), an SD1 without data.
    feed(build_telegram({2, 3, response_fc(FdlStatus::NoService), {}, {}, {}}));
    EXPECT_TRUE(findings.empty()) << findings[0].message;
}

TEST(SessionTrackerTest, MalformedTelegramWithoutStationsCountsForTheBus) {
    BusDecoder decoder;
    SessionTracker tracker;
    std::vector<std::uint8_t> junk = {0x2A, 0x3F, 0x9F};
    auto findings = tracker.track(decoder.decode(Bytes(junk.data(), junk.size()), kNoTime, 1));
    ASSERT_EQ(findings.size(), 1u);
    EXPECT_EQ(findings[0].kind, FindingKind::MalformedTelegram);
    EXPECT_FALSE(findings[0].has_stations);
    EXPECT_EQ(tracker.bus().findings[static_cast<std::size_t>(FindingKind::MalformedTelegram)], 1u);
    EXPECT_TRUE(tracker.channels().empty());
}

}  // namespace
}  // namespace dpscope
