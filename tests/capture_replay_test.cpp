// CaptureReplay, the Wireshark dissector's per-capture state (wireshark/capture_replay.hpp): a
// telegram decoded again, in any order, is what it was on the first pass, and the first pass is
// what `dpscope decode` decodes and finds. Runs without Wireshark.
#include "wireshark/capture_replay.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "capture/bus_tag.hpp"
#include "capture/telegram_source.hpp"
#include "formats/output.hpp"
#include "formats/renderer.hpp"
#include "test_support.hpp"

namespace dpscope {
namespace {

struct Telegram {
    std::uint64_t frame;
    std::int64_t time_ns;
    std::vector<std::uint8_t> bytes;
};

struct Capture {
    Protocol protocol = Protocol::ProfibusDp;
    std::vector<Telegram> telegrams;
};

Capture read_sample(const std::string& name) {
    Capture capture;
    BusChoice choice;
    auto source =
        open_source(test::source_dir() + "/samples/" + name, InputFormat::Auto, nullptr, choice);
    EXPECT_TRUE(source.has_value()) << name;
    if (!source.has_value()) return capture;
    capture.protocol = choice.protocol->protocol;
    Record record;
    while ((*source)->next(record))
        capture.telegrams.push_back(
            {record.number, record.time_ns, {record.bytes.begin(), record.bytes.end()}});
    return capture;
}

// One telegram as `dpscope decode -T jsonl` writes it, with the findings given.
std::string jsonl(const DecodedTelegram& t, std::span<const Finding> findings) {
    return test::output_text([&](Output& out) { make_jsonl_renderer(out)->render(t, findings); });
}

// The decode of every sample of each bus, once on the first pass and again in a shuffled order.
class CaptureReplaySample : public ::testing::TestWithParam<const char*> {};

TEST_P(CaptureReplaySample, DecodingAgainInAnyOrderGivesTheFirstPassDecode) {
    const Capture capture = read_sample(GetParam());
    ASSERT_FALSE(capture.telegrams.empty());
    CaptureReplay replay(capture.protocol, default_replay_options());
    std::vector<std::string> first;
    for (const Telegram& t : capture.telegrams) {
        const DecodedTelegram& decoded =
            replay.first_pass(t.frame, Bytes(t.bytes.data(), t.bytes.size()), t.time_ns);
        first.push_back(jsonl(decoded, replay.findings(t.frame)));
    }
    std::vector<std::size_t> order(capture.telegrams.size());
    for (std::size_t i = 0; i < order.size(); ++i)
        order[i] = i;
    std::mt19937 random(13);
    std::shuffle(order.begin(), order.end(), random);
    for (std::size_t i : order) {
        const Telegram& t = capture.telegrams[i];
        ASSERT_TRUE(replay.seen(t.frame));
        const DecodedTelegram& again =
            replay.decode_again(t.frame, Bytes(t.bytes.data(), t.bytes.size()), t.time_ns);
        ASSERT_EQ(jsonl(again, replay.findings(t.frame)), first[i]) << "frame " << t.frame;
    }
    // In order (tshark's second pass) each telegram is one more decode.
    const std::uint64_t before = replay.replayed_decodes();
    for (const Telegram& t : capture.telegrams)
        replay.decode_again(t.frame, Bytes(t.bytes.data(), t.bytes.size()), t.time_ns);
    EXPECT_LE(replay.replayed_decodes() - before,
              capture.telegrams.size() + CaptureReplay::kCheckpointInterval);
}

INSTANTIATE_TEST_SUITE_P(
    Samples, CaptureReplaySample,
    ::testing::Values("faults.pcap", "dpv1.pcap", "profidrive.pcap", "bus-health.pcap", "fc.pcap",
                      "vlt2000.pcap", "serial.raw", "timeouts.pcap"),
    [](const auto& param_info) {
        std::string name = param_info.param;
        std::replace_if(
            name.begin(), name.end(),
            [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
        return name;
    });

// The first pass finds what `dpscope decode` finds at each telegram (jsonl lines equal).
TEST(CaptureReplay, FirstPassEqualsDpscopeDecode) {
    for (const char* name : {"faults.pcap", "fc.pcap", "vlt2000.pcap", "dpv1.pcap"}) {
        const Capture capture = read_sample(name);
        CaptureReplay replay(capture.protocol, default_replay_options());
        std::string ours;
        for (const Telegram& t : capture.telegrams) {
            const DecodedTelegram& decoded =
                replay.first_pass(t.frame, Bytes(t.bytes.data(), t.bytes.size()), t.time_ns);
            ours += jsonl(decoded, replay.findings(t.frame));
        }
        const test::CommandResult decode =
            test::run_dpscope({"decode", "-T", "jsonl", test::source_dir() + "/samples/" + name});
        ASSERT_EQ(decode.exit_code, 0) << name;
        // dpscope decode adds the findings still open at the end (no telegram is left for them
        // in Wireshark); compare the telegrams' lines.
        std::string telegram_lines;
        std::size_t at = 0;
        while (at < decode.out.size()) {
            const std::size_t end = decode.out.find('\n', at);
            const std::string line = decode.out.substr(at, end - at + 1);
            if (line.starts_with("{\"frame\"")) telegram_lines += line;
            at = end == std::string::npos ? decode.out.size() : end + 1;
        }
        EXPECT_EQ(ours, telegram_lines) << name;
    }
}

TEST(CaptureReplay, LinksResponsesToRequests) {
    const Capture capture = read_sample("ppo2.pcap");
    CaptureReplay replay(capture.protocol, default_replay_options());
    for (const Telegram& t : capture.telegrams)
        replay.first_pass(t.frame, Bytes(t.bytes.data(), t.bytes.size()), t.time_ns);
    // Frame 2 (FDL_Status response) answers frame 1.
    EXPECT_EQ(replay.response_frame(1), 2u);
    EXPECT_EQ(replay.response_frame(2), 0u);
    EXPECT_EQ(replay.time_of(1), capture.telegrams[0].time_ns);
    EXPECT_EQ(replay.time_of(100000), kNoTime);
}

TEST(CaptureReplay, AFrameNeverFedIsDecodedOnItsOwn) {
    CaptureReplay replay(Protocol::ProfibusDp, default_replay_options());
    const std::vector<std::uint8_t> status = {0x10, 0x04, 0x02, 0x49, 0x4F, 0x16};
    const DecodedTelegram& t = replay.decode_again(7, Bytes(status.data(), status.size()), kNoTime);
    EXPECT_EQ(t.frame, 7u);
    EXPECT_EQ(t.dp.service, Service::FdlStatus);
    EXPECT_FALSE(replay.seen(7));
    EXPECT_TRUE(replay.findings(7).empty());
}

TEST(CaptureReplay, EmptyAndDamagedRecordsAreKeptAndDecodedAgain) {
    CaptureReplay replay(Protocol::ProfibusDp, default_replay_options());
    const std::vector<std::uint8_t> garbage = {0x2A, 0x68, 0x03};
    replay.first_pass(1, Bytes(), kNoTime);
    replay.first_pass(2, Bytes(garbage.data(), garbage.size()), kNoTime);
    EXPECT_EQ(replay.decode_again(1, Bytes(), kNoTime).problems().size(), 1u);
    EXPECT_FALSE(replay.decode_again(2, Bytes(), kNoTime).problems().empty());
}

TEST(CaptureReplay, UntaggedUser0ByFirstByte) {
    EXPECT_EQ(protocol_of_untagged_user0(0x02), Protocol::Fc);
    EXPECT_EQ(protocol_of_untagged_user0('<'), Protocol::Vlt2000);
    EXPECT_EQ(protocol_of_untagged_user0(0x68), Protocol::ProfibusDp);
    EXPECT_EQ(protocol_of_untagged_user0(0xE5), Protocol::ProfibusDp);
}

}  // namespace
}  // namespace dpscope
