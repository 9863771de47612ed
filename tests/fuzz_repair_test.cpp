// The repair functions of the decoder fuzz targets' custom mutators (fuzz/support/
// checksum_repair.hpp): a telegram mutated at random and then repaired decodes with no checksum,
// length or delimiter problem, and one left broken still reports it.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "fuzz/support/checksum_repair.hpp"
#include "protocols/fc/fc_bus_model.hpp"
#include "protocols/fc/fc_decoder.hpp"
#include "protocols/fc/fc_framing_rules.hpp"
#include "protocols/profibus/fdl.hpp"
#include "protocols/profibus/fdl_framing_rules.hpp"
#include "protocols/profibus/telegram_builder.hpp"
#include "protocols/vlt2000/vlt2000_bus_model.hpp"
#include "protocols/vlt2000/vlt2000_decoder.hpp"
#include "protocols/vlt2000/vlt2000_framing_rules.hpp"

namespace dpscope {
namespace {

constexpr std::size_t kMaxSize = 300;

// Mutates `bytes` the way libFuzzer might: a few bytes changed, and now and then bytes added or
// removed at the end. Byte 0 keeps one of `starts`.
void mutate(std::vector<std::uint8_t>& bytes, std::mt19937& random,
            const std::vector<std::uint8_t>& starts) {
    std::uniform_int_distribution<int> byte(0, 255);
    const int changes = 1 + static_cast<int>(random() % 4);
    for (int i = 0; i < changes && !bytes.empty(); ++i)
        bytes[random() % bytes.size()] = static_cast<std::uint8_t>(byte(random));
    switch (random() % 4) {
        case 0: bytes.resize(bytes.size() + random() % 20, 0x33); break;
        case 1:
            bytes.resize(bytes.size() - std::min<std::size_t>(bytes.size() - 1, random() % 8));
            break;
        default: break;
    }
    bytes[0] = starts[random() % starts.size()];
}

std::size_t repair(std::vector<std::uint8_t>& bytes,
                   std::size_t (*fn)(std::uint8_t*, std::size_t, std::size_t)) {
    const std::size_t size = bytes.size();
    bytes.resize(kMaxSize);
    bytes.resize(fn(bytes.data(), size, kMaxSize));
    return bytes.size();
}

bool has_any(const ProblemList& problems, std::initializer_list<ProblemKind> kinds) {
    for (ProblemKind kind : kinds)
        if (problems.contains(kind)) return true;
    return false;
}

TEST(FuzzRepairTest, RepairedFdlTelegramsHaveNoFramingOrFcsProblem) {
    std::mt19937 random(14);
    for (int round = 0; round < 2000; ++round) {
        std::vector<std::uint8_t> du(random() % 3 == 0 ? 8 : random() % 60);
        for (auto& b : du)
            b = static_cast<std::uint8_t>(random());
        std::vector<std::uint8_t> bytes = build_telegram(
            {static_cast<std::uint8_t>(random() % 126), static_cast<std::uint8_t>(random() % 126),
             request_fc(FdlFunction::SrdHigh), std::nullopt, std::nullopt, Bytes(du)});
        mutate(bytes, random, {kSd1, kSd2, kSd3});
        repair(bytes, &fuzz::repair_fdl_telegram);
        FdlTelegram fdl;
        parse_fdl(Bytes(bytes), fdl);
        SCOPED_TRACE(round);
        EXPECT_FALSE(has_any(
            fdl.problems,
            {ProblemKind::FcsMismatch, ProblemKind::LengthMismatch, ProblemKind::LengthOutOfRange,
             ProblemKind::StartDelimiterRepeat, ProblemKind::BadEndDelimiter,
             ProblemKind::Truncated, ProblemKind::TrailingBytes}));
        EXPECT_TRUE(fdl.fcs_ok);
        const FramingVerdict verdict = fdl_framing_rules().judge(Bytes(bytes), true);
        EXPECT_EQ(verdict.status, FramingStatus::Telegram);
        EXPECT_EQ(verdict.length, bytes.size());
    }
}

TEST(FuzzRepairTest, BrokenFdlTelegramsStillReportTheirProblem) {
    const std::uint8_t du[] = {1, 2, 3, 4, 5};
    std::vector<std::uint8_t> bytes =
        build_telegram({5, 2, request_fc(FdlFunction::SrdHigh), 61, 62, Bytes(du)});
    std::vector<std::uint8_t> fcs = bytes;
    fcs[fcs.size() - 2] ^= 0x01;
    std::vector<std::uint8_t> ler = bytes;
    ler[2] ^= 0x01;
    FdlTelegram fdl;
    parse_fdl(Bytes(fcs), fdl);
    EXPECT_TRUE(fdl.problems.contains(ProblemKind::FcsMismatch));
    parse_fdl(Bytes(ler), fdl);
    EXPECT_TRUE(fdl.problems.contains(ProblemKind::LengthMismatch));
    // Repaired, both are whole again.
    repair(fcs, &fuzz::repair_fdl_telegram);
    repair(ler, &fuzz::repair_fdl_telegram);
    EXPECT_EQ(fcs, bytes);
    EXPECT_EQ(ler, bytes);
}

TEST(FuzzRepairTest, FdlRepairLeavesTokensAndAcknowledgementsAndStaysInMaxSize) {
    std::vector<std::uint8_t> token = {kSd4, 0x83, 0x02};
    EXPECT_EQ(fuzz::repair_fdl_telegram(token.data(), token.size(), token.size()), 3u);
    EXPECT_EQ(token, (std::vector<std::uint8_t>{kSd4, 0x83, 0x02}));
    // An SD2 too short to be one, with no room to grow: left as it is.
    std::vector<std::uint8_t> cut = {kSd2, 0x05, 0x05};
    EXPECT_EQ(fuzz::repair_fdl_telegram(cut.data(), cut.size(), cut.size()), 3u);
    EXPECT_EQ(cut, (std::vector<std::uint8_t>{kSd2, 0x05, 0x05}));
    // An SD2 longer than 255 bytes is cut to 255 (LE 249).
    std::vector<std::uint8_t> longest(270, 0x11);
    longest[0] = kSd2;
    EXPECT_EQ(fuzz::repair_fdl_telegram(longest.data(), longest.size(), longest.size()), 255u);
    EXPECT_EQ(longest[1], 249);
}

TEST(FuzzRepairTest, RepairedFcTelegramsHaveNoFramingOrBccProblem) {
    std::mt19937 random(15);
    for (int round = 0; round < 2000; ++round) {
        std::vector<std::uint8_t> data(random() % 3 == 0   ? 4
                                       : random() % 3 == 0 ? 12
                                                           : 8 + random() % 40);
        for (auto& b : data)
            b = static_cast<std::uint8_t>(random());
        std::vector<std::uint8_t> bytes =
            build_fc_telegram(static_cast<std::uint8_t>(1 + random() % 31), data);
        mutate(bytes, random, {kFcStx, 0x00, 0x7F});
        repair(bytes, &fuzz::repair_fc_telegram);
        FcDecoder decoder;
        const DecodedTelegram& t = decoder.decode(Bytes(bytes), kNoTime, 1);
        SCOPED_TRACE(round);
        EXPECT_FALSE(has_any(t.fc.problems, {ProblemKind::BccMismatch, ProblemKind::LgeInvalid,
                                             ProblemKind::Truncated, ProblemKind::TrailingBytes,
                                             ProblemKind::BadStartDelimiter}));
        EXPECT_TRUE(t.fc.bcc_ok);
        EXPECT_TRUE(t.fc.complete);
    }
}

TEST(FuzzRepairTest, BrokenFcTelegramsStillReportTheirProblem) {
    std::vector<std::uint8_t> bytes = build_fc_telegram(
        0x05, {0x10, 0x64, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x04, 0x7C, 0x00, 0x00});
    std::vector<std::uint8_t> bcc = bytes;
    bcc.back() ^= 0x01;
    std::vector<std::uint8_t> lge = bytes;
    lge[1] = 8;  // no block length
    FcDecoder decoder;
    EXPECT_TRUE(
        decoder.decode(Bytes(bcc), kNoTime, 1).fc.problems.contains(ProblemKind::BccMismatch));
    EXPECT_TRUE(
        decoder.decode(Bytes(lge), kNoTime, 2).fc.problems.contains(ProblemKind::LgeInvalid));
    repair(bcc, &fuzz::repair_fc_telegram);
    repair(lge, &fuzz::repair_fc_telegram);
    EXPECT_EQ(bcc, bytes);
    EXPECT_EQ(lge, bytes);
}

TEST(FuzzRepairTest, RepairedVlt2000TelegramsHaveNoFramingOrChecksumProblem) {
    std::mt19937 random(16);
    std::uniform_int_distribution<int> printable(0x20, 0x7E);
    for (int round = 0; round < 2000; ++round) {
        Vlt2000Fields fields;
        fields.address = static_cast<std::uint8_t>(random() % 100);
        fields.letter = "URCI"[random() % 4];
        fields.parameter = static_cast<std::uint16_t>(random() % 10000);
        fields.digits = static_cast<std::uint32_t>(random() % 100000);
        fields.checksum_disabled = random() % 8 == 0;
        std::vector<std::uint8_t> bytes = vlt2000_telegram(fields);
        const int changes = 1 + static_cast<int>(random() % 4);
        for (int i = 0; i < changes; ++i)
            bytes[random() % bytes.size()] = static_cast<std::uint8_t>(printable(random));
        if (random() % 4 == 0) bytes.resize(random() % 40, '0');
        if (bytes.empty()) bytes.push_back('<');
        repair(bytes, &fuzz::repair_vlt2000_telegram);
        Vlt2000Telegram v;
        parse_vlt2000(Bytes(bytes), v);
        SCOPED_TRACE(round);
        EXPECT_FALSE(has_any(
            v.problems,
            {ProblemKind::Vlt2000ChecksumMismatch, ProblemKind::BadStartDelimiter,
             ProblemKind::BadEndDelimiter, ProblemKind::Truncated, ProblemKind::TrailingBytes}));
        EXPECT_TRUE(v.complete);
        EXPECT_TRUE(v.checksum_ok || v.checksum_disabled);
        const FramingVerdict verdict = vlt2000_framing_rules().judge(Bytes(bytes), true);
        EXPECT_EQ(verdict.status, FramingStatus::Telegram);
    }
}

TEST(FuzzRepairTest, BrokenVlt2000TelegramsStillReportTheirProblem) {
    Vlt2000Fields fields;
    fields.address = 7;
    fields.letter = 'R';
    fields.parameter = 102;
    std::vector<std::uint8_t> bytes = vlt2000_telegram(fields);
    std::vector<std::uint8_t> broken = bytes;
    broken[kVlt2000ChecksumAt + 1] = broken[kVlt2000ChecksumAt + 1] == '0' ? '1' : '0';
    Vlt2000Telegram v;
    parse_vlt2000(Bytes(broken), v);
    EXPECT_TRUE(v.problems.contains(ProblemKind::Vlt2000ChecksumMismatch));
    repair(broken, &fuzz::repair_vlt2000_telegram);
    EXPECT_EQ(broken, bytes);
    // "??" is left as it is: the checksum is not checked.
    fields.checksum_disabled = true;
    std::vector<std::uint8_t> unchecked = vlt2000_telegram(fields);
    const std::vector<std::uint8_t> before = unchecked;
    repair(unchecked, &fuzz::repair_vlt2000_telegram);
    EXPECT_EQ(unchecked, before);
}

}  // namespace
}  // namespace dpscope
