// The VLT 2000 bus of the simulator (simulate --bus vlt2000): the traffic decodes with
// Vlt2000Decoder without problems and with the right directions, it holds every letter, broadcasts
// and failures the model promises at the timing of 9600 baud 8N1, and each fault gives the
// telegram shape it stands for.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/protocol_descriptor.hpp"
#include "capture/telegram_source.hpp"
#include "protocols/vlt2000/vlt2000_codes.hpp"
#include "protocols/vlt2000/vlt2000_decoder.hpp"
#include "simulator/simulator.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

// A decoded VLT 2000 telegram, copied out of the decoder's reused result.
struct Vlt {
    std::vector<std::uint8_t> bytes;
    std::int64_t time_ns = 0;
    Direction direction = Direction::Request;
    std::uint64_t request_frame = 0;
    Vlt2000Telegram v;  // its index view is not used (it points into the decoder's input)
    std::vector<ProblemKind> problems;

    std::string text() const { return std::string(bytes.begin(), bytes.end()); }
};

SimulatorOptions vlt_session(std::uint64_t seed, std::uint64_t cycles) {
    SimulatorOptions options;
    options.bus = Protocol::Vlt2000;
    options.seed = seed;
    options.cycles = cycles;
    options.baud = 0;
    return options;
}

std::vector<Vlt> decode_all(Simulator& simulator) {
    std::vector<Vlt> out;
    Vlt2000Decoder decoder;
    std::vector<std::uint8_t> bytes;
    std::int64_t time_ns = 0;
    while (simulator.next(bytes, time_ns)) {
        Vlt t;
        t.bytes = bytes;
        t.time_ns = time_ns;
        const DecodedTelegram& d = decoder.decode(Bytes(t.bytes), time_ns, out.size() + 1);
        t.direction = d.direction;
        t.request_frame = d.request_frame;
        t.v = d.vlt2000;
        t.v.index = {};
        for (const Problem& p : d.vlt2000.problems)
            t.problems.push_back(p.kind);
        out.push_back(std::move(t));
    }
    return out;
}

std::vector<Vlt> decode_all(const SimulatorOptions& options) {
    Simulator simulator(options);
    return decode_all(simulator);
}

// The time a telegram takes on the line at 9600 baud, 10 bits a character (22 characters:
// 22.9 ms).
std::int64_t line_ns(const Vlt& t) {
    return static_cast<std::int64_t>(t.bytes.size()) * 10 * 1'000'000'000 / 9600;
}

TEST(Vlt2000SimulatorTest, CleanSessionDecodesWithoutProblemsAndTheRightDirections) {
    std::vector<Vlt> telegrams = decode_all(vlt_session(3, 300));
    ASSERT_GT(telegrams.size(), 1500u);
    std::set<char> letters, reply_letters;
    std::set<std::uint8_t> addresses, decimals, reasons;
    std::set<std::uint16_t> words;
    int broadcasts = 0, broadcast_updates = 0, failed = 0, negative = 0, indexed = 0;
    for (std::size_t i = 0; i < telegrams.size(); ++i) {
        const Vlt& t = telegrams[i];
        SCOPED_TRACE("telegram " + std::to_string(i + 1) + " " + t.text());
        EXPECT_TRUE(t.problems.empty());
        ASSERT_TRUE(t.v.complete);
        ASSERT_EQ(t.bytes.size(), 22u);
        EXPECT_TRUE(t.v.checksum_ok);
        EXPECT_FALSE(t.v.checksum_disabled);
        ASSERT_NE(t.v.letter, Vlt2000Letter::Unknown);
        // Telegrams are whole characters apart: the next starts after this one ends.
        if (i + 1 < telegrams.size()) {
            EXPECT_EQ(line_ns(t), 22'916'666);
            EXPECT_GE(telegrams[i + 1].time_ns - t.time_ns, line_ns(t) + 500'000);
        }
        if (t.v.broadcast) {
            ++broadcasts;
            EXPECT_EQ(t.direction, Direction::Request);
            if (t.v.letter == Vlt2000Letter::Update) ++broadcast_updates;
            // Nobody replies: the next telegram is the master's.
            if (i + 1 < telegrams.size()) {
                EXPECT_EQ(telegrams[i + 1].direction, Direction::Request);
            }
            continue;
        }
        addresses.insert(t.v.address);
        if (t.direction == Direction::Request) {
            letters.insert(static_cast<char>(t.v.letter_char));
            words.insert(t.v.word);
            // Every command is answered by the next telegram, with its address and letter,
            // after the drive's response delay.
            ASSERT_LT(i + 1, telegrams.size());
            const Vlt& reply = telegrams[i + 1];
            EXPECT_EQ(reply.direction, Direction::Response);
            EXPECT_EQ(reply.request_frame, i + 1);
            EXPECT_EQ(reply.v.address, t.v.address);
            EXPECT_EQ(reply.v.letter_char, t.v.letter_char);
            const std::int64_t delay = reply.time_ns - t.time_ns - line_ns(t);
            EXPECT_GE(delay, Vlt2000BusModel::kResponseMinNs);
            EXPECT_LE(delay, Vlt2000BusModel::kResponseMaxNs + 1);
            if (t.v.letter == Vlt2000Letter::ReadIndex) {
                ++indexed;
                EXPECT_TRUE(t.v.has_index_number);
            }
            const std::optional<std::uint8_t> fails = vlt2000_simulated_failure(
                static_cast<char>(t.v.letter_char), t.v.parameter, t.v.index_number);
            EXPECT_EQ(reply.v.failed, fails.has_value());
            if (fails) {
                EXPECT_TRUE(reply.v.has_reason);
                EXPECT_EQ(reply.v.reason, *fails);
            } else if (t.v.letter == Vlt2000Letter::Update) {
                // The reply echoes the value.
                EXPECT_EQ(reply.v.signed_digits(), t.v.signed_digits());
                EXPECT_EQ(reply.v.decimals, t.v.decimals);
                EXPECT_EQ(reply.v.parameter, t.v.parameter);
            } else if (t.v.letter != Vlt2000Letter::Control) {
                EXPECT_EQ(reply.v.parameter, t.v.parameter);
            }
        } else {
            ASSERT_GT(i, 0u);
            EXPECT_EQ(telegrams[i - 1].direction, Direction::Request);
            reply_letters.insert(static_cast<char>(t.v.letter_char));
            // The status word: control and VLT ready.
            EXPECT_EQ(t.v.word & 0x0003, 0x0003);
            if (t.v.failed) {
                ++failed;
                reasons.insert(t.v.reason);
            } else {
                decimals.insert(t.v.decimals);
                negative += t.v.negative ? 1 : 0;
            }
        }
    }
    EXPECT_EQ(letters, (std::set<char>{'C', 'R', 'U', 'I'}));
    EXPECT_EQ(reply_letters, letters);
    EXPECT_EQ(addresses, (std::set<std::uint8_t>{1, 2, 5}));
    EXPECT_EQ(reasons, (std::set<std::uint8_t>{0, 1, 2, 3, 4}));
    EXPECT_EQ(decimals, (std::set<std::uint8_t>{0, 1, 2, 3}));
    EXPECT_TRUE(words.count(Vlt2000BusModel::kRunWord));
    EXPECT_TRUE(words.count(Vlt2000BusModel::kStopWord));
    EXPECT_EQ(broadcasts, 15);  // every 20th cycle
    EXPECT_GT(broadcast_updates, 0);
    EXPECT_LT(broadcast_updates, broadcasts);
    EXPECT_GT(failed, 10);
    EXPECT_GT(negative, 0);
    EXPECT_GT(indexed, 50);
}

TEST(Vlt2000SimulatorTest, TheWorkedExamplesTelegramsAndStatusWord) {
    // <01UOGD@0516+00080007>: U 0516 = 80 with control word 0x047F [P:VLT3000 p79].
    Vlt2000Fields update;
    update.address = 1;
    update.letter = 'U';
    update.word = 0x047F;
    update.parameter = 516;
    update.digits = 80;
    const std::vector<std::uint8_t> bytes = vlt2000_telegram(update);
    EXPECT_EQ(std::string(bytes.begin(), bytes.end()), "<01UOGD@0516+00080007>");
    // The reply's status word GHK@ = 0x0B87: running at the reference, outside the frequency
    // band (warning), under serial control.
    EXPECT_EQ(vlt2000_status_word(0x047F, true, true, false), 0x0B87);
    Vlt2000Fields reply = update;
    reply.word = 0x0B87;
    const std::vector<std::uint8_t> answer = vlt2000_telegram(reply);
    EXPECT_EQ(std::string(answer.begin() + 4, answer.begin() + 8), "GHK@");
    // Standing still: no warning, frequency range OK, not running.
    EXPECT_EQ(vlt2000_status_word(0x043F, false, true, true), 0x0707);
    // Coasting (ON2 off): not enabled.
    EXPECT_EQ(vlt2000_status_word(0x047D, false, true, true) & 0x0004, 0);
    // The seed's value example: 23.75 as +23750 with three decimals; and "??".
    Vlt2000Fields value;
    value.address = 2;
    value.letter = 'R';
    value.parameter = 520;
    value.digits = 23750;
    value.decimals = 3;
    value.checksum_disabled = true;
    const std::vector<std::uint8_t> read = vlt2000_telegram(value);
    ASSERT_EQ(read.size(), 22u);
    EXPECT_EQ(std::string(read.begin() + 12, read.end()), "+237503?\?>");
    Vlt2000Decoder decoder;
    const DecodedTelegram& d = decoder.decode(Bytes(read), 0, 1);
    EXPECT_TRUE(d.vlt2000.problems.empty());
    EXPECT_DOUBLE_EQ(d.vlt2000.value(), 23.75);
    // Letter I: the index in bytes 13-18.
    Vlt2000Fields index;
    index.address = 5;
    index.letter = 'I';
    index.parameter = 615;
    index.index = "000003";
    const std::vector<std::uint8_t> read_index = vlt2000_telegram(index);
    const DecodedTelegram& i = decoder.decode(Bytes(read_index), 0, 2);
    EXPECT_TRUE(i.vlt2000.problems.empty());
    EXPECT_TRUE(i.vlt2000.has_index_number);
    EXPECT_EQ(i.vlt2000.index_number, 3u);
}

TEST(Vlt2000SimulatorTest, ChecksumsFollowTheRule) {
    // The sum of the characters at offsets 1..18, its last two digits.
    for (const Vlt& t : decode_all(vlt_session(12, 20))) {
        unsigned sum = 0;
        for (std::size_t k = 1; k <= 18; ++k)
            sum += t.bytes[k];
        EXPECT_EQ(unsigned{t.bytes[19]}, '0' + (sum % 100) / 10) << t.text();
        EXPECT_EQ(unsigned{t.bytes[20]}, '0' + sum % 10) << t.text();
    }
}

TEST(Vlt2000SimulatorTest, FailuresOfTheSimulatedDrive) {
    EXPECT_EQ(vlt2000_simulated_failure('R', 999, 0), std::optional<std::uint8_t>(0));
    EXPECT_EQ(vlt2000_simulated_failure('U', 500, 0), std::optional<std::uint8_t>(1));
    EXPECT_EQ(vlt2000_simulated_failure('I', 615, 9), std::optional<std::uint8_t>(2));
    EXPECT_EQ(vlt2000_simulated_failure('I', 615, 0), std::optional<std::uint8_t>(2));
    EXPECT_EQ(vlt2000_simulated_failure('I', 205, 1), std::optional<std::uint8_t>(3));
    EXPECT_EQ(vlt2000_simulated_failure('U', 518, 0), std::optional<std::uint8_t>(4));
    EXPECT_EQ(vlt2000_simulated_failure('I', 615, 8), std::nullopt);
    EXPECT_EQ(vlt2000_simulated_failure('R', 500, 0), std::nullopt);
    EXPECT_EQ(vlt2000_simulated_failure('U', 516, 0), std::nullopt);
    EXPECT_EQ(vlt2000_simulated_failure('C', 999, 0), std::nullopt);  // parameter ignored
}

TEST(Vlt2000SimulatorTest, SameSeedSameBytesAndTheDefaultBaudIs9600) {
    std::vector<Vlt> a = decode_all(vlt_session(8, 50));
    std::vector<Vlt> b = decode_all(vlt_session(8, 50));
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].bytes, b[i].bytes);
        EXPECT_EQ(a[i].time_ns, b[i].time_ns);
    }
    std::vector<Vlt> other = decode_all(vlt_session(9, 50));
    bool differs = other.size() != a.size();
    for (std::size_t i = 0; !differs && i < a.size(); ++i)
        differs = a[i].bytes != other[i].bytes;
    EXPECT_TRUE(differs);
    SimulatorOptions fast = vlt_session(8, 50);
    fast.baud = 19200;
    std::vector<Vlt> c = decode_all(fast);
    ASSERT_EQ(c.size(), a.size());
    EXPECT_LT(c.back().time_ns, a.back().time_ns);
    // 9600 baud: a poll is two telegrams of 22.9 ms plus the gaps.
    EXPECT_GT(a.back().time_ns - a.front().time_ns, 50LL * 3 * 2 * 22'916'666);
}

TEST(Vlt2000SimulatorTest, DrivesAndCount) {
    SimulatorOptions options = vlt_session(4, 20);
    options.vlt2000_drives = {99, 31};
    std::set<std::uint8_t> addresses;
    for (const Vlt& t : decode_all(options))
        if (!t.v.broadcast) addresses.insert(t.v.address);
    EXPECT_EQ(addresses, (std::set<std::uint8_t>{31, 99}));
    SimulatorOptions counted = vlt_session(4, 0);
    counted.max_telegrams = 1234;
    EXPECT_EQ(decode_all(counted).size(), 1234u);
    EXPECT_EQ(parse_vlt2000_drive_spec("7").value(), 7);
    EXPECT_EQ(parse_vlt2000_drive_spec("99").value(), 99);
    EXPECT_EQ(parse_vlt2000_drive_spec("0").error(),
              "0: the address must be from 1 to 99 (two digits; 00 is the broadcast)");
    EXPECT_FALSE(parse_vlt2000_drive_spec("100"));
    EXPECT_FALSE(parse_vlt2000_drive_spec("x"));
    EXPECT_FALSE(parse_vlt2000_drive_spec(""));
}

// Runs a session with `kind` once on drive 2 from cycle 5 and returns the telegrams and the
// 0-based index of the telegram the injection names.
std::pair<std::vector<Vlt>, std::size_t> with_fault(FaultKind kind, bool one_drive = false) {
    SimulatorOptions options = vlt_session(21, 100);
    options.vlt2000_drives =
        one_drive ? std::vector<std::uint8_t>{2} : std::vector<std::uint8_t>{1, 2, 9};
    options.faults = {FaultSpec{kind, 0, 5, 2}};
    Simulator simulator(options);
    std::vector<Vlt> telegrams = decode_all(simulator);
    EXPECT_EQ(simulator.injections().size(), 1u);
    if (simulator.injections().empty()) return {telegrams, 0};
    const Injection& injection = simulator.injections()[0];
    EXPECT_EQ(injection.kind, kind);
    EXPECT_EQ(injection.slave, 2);
    EXPECT_GE(injection.cycle, 5u);
    EXPECT_GE(injection.telegram, 2u);
    EXPECT_LT(injection.telegram, telegrams.size());
    return {telegrams, static_cast<std::size_t>(injection.telegram - 1)};
}

TEST(Vlt2000SimulatorTest, StackedRequestIsASecondCommandWithAnotherLetter) {
    auto [t, n] = with_fault(FaultKind::Vlt2000StackedRequest);
    ASSERT_GT(n, 0u);
    EXPECT_EQ(t[n - 1].direction, Direction::Request);
    EXPECT_EQ(t[n].direction, Direction::Request);
    EXPECT_EQ(t[n].v.address, 2);
    EXPECT_EQ(t[n - 1].v.address, 2);
    EXPECT_NE(t[n].v.letter_char, t[n - 1].v.letter_char);
    // Sent before the drive's response delay was up.
    EXPECT_LT(t[n].time_ns - t[n - 1].time_ns - line_ns(t[n - 1]), Vlt2000BusModel::kResponseMinNs);
    EXPECT_EQ(t[n + 1].direction, Direction::Response);
    EXPECT_EQ(t[n + 1].request_frame, n + 1);
    EXPECT_EQ(t[n + 1].v.letter_char, t[n].v.letter_char);
}

TEST(Vlt2000SimulatorTest, NoResponseLeavesTheCommandUnanswered) {
    for (bool one_drive : {false, true}) {
        SCOPED_TRACE(one_drive ? "one drive" : "three drives");
        auto [t, n] = with_fault(FaultKind::Vlt2000NoResponse, one_drive);
        // The injection names the master's next telegram: another drive, or a broadcast.
        ASSERT_GT(n, 0u);
        EXPECT_EQ(t[n - 1].direction, Direction::Request);
        EXPECT_EQ(t[n - 1].v.address, 2);
        EXPECT_EQ(t[n].direction, Direction::Request);
        EXPECT_TRUE(t[n].v.broadcast || t[n].v.address != 2);
        EXPECT_GE(t[n].time_ns - t[n - 1].time_ns - line_ns(t[n - 1]),
                  Vlt2000BusModel::kMasterTimeoutNs);
    }
}

TEST(Vlt2000SimulatorTest, UnexpectedReplyAnswersABroadcast) {
    auto [t, n] = with_fault(FaultKind::Vlt2000UnexpectedReply);
    ASSERT_GT(n, 0u);
    EXPECT_TRUE(t[n - 1].v.broadcast);
    EXPECT_TRUE(t[n].v.broadcast);
    EXPECT_EQ(t[n].direction, Direction::Response);
    EXPECT_EQ(t[n].request_frame, n);
    EXPECT_EQ(t[n].v.letter_char, t[n - 1].v.letter_char);
    EXPECT_TRUE(t[n].problems.empty());
}

TEST(Vlt2000SimulatorTest, MismatchedResponseCarriesAnotherParameter) {
    auto [t, n] = with_fault(FaultKind::Vlt2000MismatchedResponse);
    ASSERT_GT(n, 0u);
    EXPECT_EQ(t[n].direction, Direction::Response);
    EXPECT_EQ(t[n].request_frame, n);
    EXPECT_NE(t[n].v.letter, Vlt2000Letter::Control);
    EXPECT_EQ(t[n].v.parameter, t[n - 1].v.parameter + 1);
    EXPECT_TRUE(t[n].problems.empty());
}

TEST(Vlt2000SimulatorTest, CommandFailedIsDecimalPosition9WithAReason) {
    auto [t, n] = with_fault(FaultKind::Vlt2000CommandFailed);
    ASSERT_GT(n, 0u);
    EXPECT_EQ(t[n].direction, Direction::Response);
    EXPECT_TRUE(t[n].v.failed);
    ASSERT_TRUE(t[n].v.has_reason);
    EXPECT_EQ(t[n].v.reason, t[n - 1].v.letter == Vlt2000Letter::Update ? 4 : 1);
    EXPECT_NE(vlt2000_reason_text(t[n].v.reason), "");
    // A command that works otherwise.
    EXPECT_FALSE(vlt2000_simulated_failure(static_cast<char>(t[n - 1].v.letter_char),
                                           t[n - 1].v.parameter, t[n - 1].v.index_number));
}

TEST(Vlt2000SimulatorTest, ChecksumErrorDamagesOneReply) {
    auto [t, n] = with_fault(FaultKind::Vlt2000ChecksumError);
    ASSERT_GT(n, 0u);
    EXPECT_EQ(t[n].direction, Direction::Response);
    EXPECT_EQ(t[n].problems, (std::vector<ProblemKind>{ProblemKind::Vlt2000ChecksumMismatch}));
    EXPECT_TRUE(t[n].v.has_checksum);
    for (std::size_t i = 0; i < t.size(); ++i)
        if (i != n) {
            EXPECT_TRUE(t[i].problems.empty()) << i;
        }
}

TEST(Vlt2000SimulatorTest, ChecksumDisabledFromTheInjectionOn) {
    auto [t, n] = with_fault(FaultKind::Vlt2000ChecksumDisabled);
    EXPECT_EQ(t[n].direction, Direction::Request);
    for (std::size_t i = 0; i < t.size(); ++i) {
        const bool drive_2 = !t[i].v.broadcast && t[i].v.address == 2;
        EXPECT_EQ(t[i].v.checksum_disabled, drive_2 && i >= n) << i;
        EXPECT_TRUE(t[i].problems.empty()) << i;
    }
}

TEST(Vlt2000SimulatorTest, MalformedTelegramIsAReplyCutShort) {
    auto [t, n] = with_fault(FaultKind::MalformedTelegram);
    ASSERT_GT(n, 0u);
    EXPECT_EQ(t[n].direction, Direction::Response);
    EXPECT_EQ(t[n].request_frame, n);
    EXPECT_EQ(t[n].problems, (std::vector<ProblemKind>{ProblemKind::Truncated}));
    EXPECT_FALSE(t[n].v.complete);
    EXPECT_GE(t[n].bytes.size(), 13u);
    EXPECT_LE(t[n].bytes.size(), 20u);
}

TEST(Vlt2000SimulatorTest, GarbageHasNoStartCharacter) {
    auto [t, n] = with_fault(FaultKind::Garbage);
    EXPECT_EQ(t[n].problems, (std::vector<ProblemKind>{ProblemKind::BadStartDelimiter}));
    for (std::uint8_t b : t[n].bytes)
        EXPECT_NE(b, '<');
    EXPECT_TRUE(t[n + 1].problems.empty());
    EXPECT_EQ(t[n + 1].direction, Direction::Request);
}

TEST(Vlt2000SimulatorTest, FaultRateOnEveryKindKeepsTheDecoderInStep) {
    SimulatorOptions options = vlt_session(5, 300);
    for (std::size_t i = 0; i < kFaultKindCount; ++i) {
        const auto kind = static_cast<FaultKind>(i);
        if (fault_applies_to_vlt2000(kind)) options.faults.push_back({kind, 0.01, {}, {}});
    }
    Simulator simulator(options);
    std::vector<Vlt> telegrams = decode_all(simulator);
    EXPECT_GT(simulator.injection_count(), 20u);
    // Every reply names the telegram before it as its command.
    for (std::size_t i = 0; i < telegrams.size(); ++i) {
        if (telegrams[i].direction != Direction::Response) continue;
        EXPECT_EQ(telegrams[i].request_frame, i) << i;
    }
}

TEST(Vlt2000SimulatorTest, FaultChecks) {
    SimulatorOptions options = vlt_session(1, 100);
    options.faults = {FaultSpec{FaultKind::FcsError, 0, 3, std::nullopt}};
    EXPECT_EQ(check_simulator_faults(options).error(),
              "fault fcs_error@3: a PROFIBUS DP fault; a VLT 2000 bus takes the vlt2000_* faults, "
              "garbage and malformed_telegram");
    options.faults = {FaultSpec{FaultKind::FcBccError, 0, 3, std::nullopt}};
    EXPECT_EQ(check_simulator_faults(options).error(),
              "fault fc_bcc_error@3: an FC protocol fault; a VLT 2000 bus takes the vlt2000_* "
              "faults, garbage and malformed_telegram");
    options.faults = {FaultSpec{FaultKind::Vlt2000ChecksumError, 0, 3, 7}};
    EXPECT_EQ(check_simulator_faults(options).error(),
              "fault vlt2000_checksum_error@3:7: drive 7 is not simulated");
    options.faults = {FaultSpec{FaultKind::Vlt2000NoResponse, 0, 300, 2}};
    EXPECT_EQ(check_simulator_faults(options).error(),
              "fault vlt2000_no_response@300:2: cycle 300 is past the session's 100 cycles "
              "(0..99)");
    options.faults = {FaultSpec{FaultKind::Garbage, 0, 3, 5}};
    EXPECT_TRUE(check_simulator_faults(options));
    SimulatorOptions profibus;
    profibus.faults = {FaultSpec{FaultKind::Vlt2000NoResponse, 0, 3, std::nullopt}};
    EXPECT_EQ(check_simulator_faults(profibus).error(),
              "fault vlt2000_no_response@3: a VLT 2000 fault; give --bus vlt2000");
    SimulatorOptions fc;
    fc.bus = Protocol::Fc;
    fc.faults = {FaultSpec{FaultKind::Vlt2000NoResponse, 0, 3, std::nullopt}};
    EXPECT_EQ(check_simulator_faults(fc).error(),
              "fault vlt2000_no_response@3: a VLT 2000 fault; an FC bus takes the fc_* faults, "
              "garbage and malformed_telegram");
}

TEST(Vlt2000SimulatorTest, FaultKindsPerBus) {
    EXPECT_EQ(fault_kind_names(Protocol::Vlt2000),
              "garbage, malformed_telegram, vlt2000_stacked_request, vlt2000_no_response, "
              "vlt2000_unexpected_reply, vlt2000_mismatched_response, vlt2000_command_failed, "
              "vlt2000_checksum_error, vlt2000_checksum_disabled");
    for (std::size_t i = 0; i < kFaultKindCount; ++i) {
        const auto kind = static_cast<FaultKind>(i);
        EXPECT_EQ(fault_applies_to_vlt2000(kind), fault_bus(kind) == Protocol::Vlt2000 ||
                                                      kind == FaultKind::Garbage ||
                                                      kind == FaultKind::MalformedTelegram)
            << fault_kind_name(kind);
    }
    const Result<FaultSpec> unknown = parse_fault_spec("nonsense", Protocol::Vlt2000);
    ASSERT_FALSE(unknown);
    EXPECT_EQ(unknown.error(), "nonsense: unknown kind 'nonsense' (known with --bus vlt2000: " +
                                   fault_kind_names(Protocol::Vlt2000) + ")");
}

// The VLT 2000 samples (scripts/make-samples): decoded as the simulator wrote them, the clean one
// without a problem, the faulty one with exactly the damage its faults make.
TEST(Vlt2000SimulatorTest, SamplesDecode) {
    for (const char* name : {"vlt2000-clean.pcap", "vlt2000.pcap"}) {
        SCOPED_TRACE(name);
        OpenResult opened = open_source(test::source_dir() + "/samples/" + name, InputFormat::Auto,
                                        protocol_descriptor(Protocol::Vlt2000));
        ASSERT_TRUE(opened) << opened.error();
        Vlt2000Decoder decoder;
        Record record;
        std::uint64_t frame = 0;
        std::map<ProblemKind, int> problems;
        std::set<char> letters;
        std::set<std::uint8_t> addresses;
        int broadcasts = 0, failed = 0, disabled = 0;
        while (opened.value()->next(record)) {
            const DecodedTelegram& t = decoder.decode(record.bytes, record.time_ns, ++frame);
            for (const Problem& p : t.vlt2000.problems)
                ++problems[p.kind];
            if (!t.has_roles) continue;
            letters.insert(static_cast<char>(t.vlt2000.letter_char));
            if (!t.vlt2000.broadcast) addresses.insert(t.vlt2000.address);
            broadcasts += t.vlt2000.broadcast && t.direction == Direction::Request ? 1 : 0;
            failed += t.vlt2000.failed ? 1 : 0;
            disabled += t.vlt2000.checksum_disabled ? 1 : 0;
        }
        EXPECT_GT(frame, 300u);
        EXPECT_EQ(letters, (std::set<char>{'C', 'R', 'U', 'I'}));
        EXPECT_GE(addresses.size(), 3u);
        EXPECT_GE(broadcasts, 2);
        EXPECT_GE(failed, 3);
        if (std::string(name) == "vlt2000-clean.pcap") {
            EXPECT_TRUE(problems.empty());
            EXPECT_EQ(disabled, 0);
        } else {
            EXPECT_EQ(problems,
                      (std::map<ProblemKind, int>{{ProblemKind::Vlt2000ChecksumMismatch, 2},
                                                  {ProblemKind::Truncated, 2},
                                                  {ProblemKind::BadStartDelimiter, 2}}));
            EXPECT_GT(disabled, 0);
        }
    }
}

}  // namespace
}  // namespace dpscope
