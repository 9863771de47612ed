// The windows around a trigger (capture/trigger_recorder.hpp, issue 30): the --pre seconds held
// in memory and the --post seconds after it in a pcapng file of their own, named after the time
// and the event, the triggering telegram commented; a trigger inside a window extends it; the
// limit per hour of capture time; the memory cap; names never over a file already there.
#include "capture/trigger_recorder.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "capture/pcap_source.hpp"
#include "capture/telegram_source.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

constexpr std::int64_t kT0 = 1'764'325'800'000'000'000;  // 2025-11-28T10:30:00Z
constexpr std::int64_t kSecond = 1'000'000'000;

// A folder of its own for each test.
struct Folder {
    explicit Folder(std::string_view name) : path(test::temp_path(name)) {
        std::filesystem::remove_all(path);
        std::filesystem::create_directories(path);
    }
    ~Folder() { std::filesystem::remove_all(path); }
    std::vector<std::string> files() const {
        std::vector<std::string> names;
        for (const auto& entry : std::filesystem::directory_iterator(path))
            names.push_back(entry.path().filename().string());
        std::sort(names.begin(), names.end());
        return names;
    }
    std::string path;
};

TriggerOptions options_in(const Folder& folder, double pre_s, double post_s) {
    TriggerOptions o;
    o.folder = folder.path;
    o.pre_ns = static_cast<std::int64_t>(pre_s * kSecond);
    o.post_ns = static_cast<std::int64_t>(post_s * kSecond);
    o.link_type = 257;
    return o;
}

// Telegram i (an SD1 FDL status request whose SA is i) at kT0 + i seconds.
std::vector<std::uint8_t> telegram(int i) {
    const auto sa = static_cast<std::uint8_t>(i & 0x7F);
    return {0x10, 0x03, sa, 0x49, static_cast<std::uint8_t>((0x03 + sa + 0x49) & 0xFF), 0x16};
}

// The source addresses (the telegram numbers) a capture file holds, in order.
std::vector<int> numbers_in(const std::string& path) {
    std::vector<int> numbers;
    OpenResult opened = open_source(path, InputFormat::Auto, profibus_protocol());
    EXPECT_TRUE(opened) << opened.error();
    if (!opened) return numbers;
    Record record;
    while (opened.value()->next(record))
        numbers.push_back(record.bytes.size() > 3 ? record.bytes[2] : -1);
    EXPECT_EQ(opened.value()->status(), InputStatus::Ok) << path;
    return numbers;
}

void feed_range(TriggerRecorder& r, int first, int last, int fire_at = -1, int fire_also = -1) {
    const TriggerHit hit{"station_lost", 7, "dpscope trigger: test"};
    for (int i = first; i <= last; ++i) {
        const std::vector<std::uint8_t> bytes = telegram(i);
        const bool fires = i == fire_at || i == fire_also;
        ASSERT_TRUE(
            r.feed(Bytes(bytes.data(), bytes.size()), kT0 + i * kSecond, fires ? &hit : nullptr));
    }
}

TEST(TriggerRecorderTest, TheWindowHoldsPreAndPostSecondsAroundTheTrigger) {
    Folder folder("trigger-window");
    TriggerRecorder r(options_in(folder, 3, 2));
    feed_range(r, 1, 20, 10);
    ASSERT_TRUE(r.finish());
    ASSERT_EQ(folder.files(),
              std::vector<std::string>{"trigger-20251128T103010Z-station_lost-7.pcapng"});
    // 7..9 before (3 s), 10, 11..12 after (2 s).
    EXPECT_EQ(numbers_in(folder.path + "/" + folder.files()[0]),
              (std::vector<int>{7, 8, 9, 10, 11, 12}));
    EXPECT_EQ(r.stats().windows, 1u);
    EXPECT_EQ(r.stats().hits, 1u);
    // The triggering telegram carries the comment.
    const std::vector<std::uint8_t> bytes = test::read_file(folder.path + "/" + folder.files()[0]);
    EXPECT_NE(std::string(bytes.begin(), bytes.end()).find("dpscope trigger: test"),
              std::string::npos);
}

TEST(TriggerRecorderTest, ATriggerInsideAWindowExtendsIt) {
    Folder folder("trigger-extend");
    TriggerRecorder r(options_in(folder, 1, 2));
    feed_range(r, 1, 20, 5, 7);  // 7 is inside 5's window (until 7): the window runs to 9
    ASSERT_TRUE(r.finish());
    ASSERT_EQ(folder.files().size(), 1u);
    EXPECT_EQ(numbers_in(folder.path + "/" + folder.files()[0]),
              (std::vector<int>{4, 5, 6, 7, 8, 9}));
    EXPECT_EQ(r.stats().hits, 2u);
    EXPECT_EQ(r.stats().windows, 1u);
}

TEST(TriggerRecorderTest, SeparateTriggersGetFilesOfTheirOwnNeverOverAFileThere) {
    Folder folder("trigger-two");
    // A file of an earlier run with the first window's name stays as it was.
    test::write_text_file(folder.path + "/trigger-20251128T103005Z-station_lost-7.pcapng",
                          "the user's\n");
    TriggerRecorder r(options_in(folder, 0, 1));
    feed_range(r, 1, 30, 5, 20);
    ASSERT_TRUE(r.finish());
    EXPECT_EQ(folder.files(),
              (std::vector<std::string>{"trigger-20251128T103005Z-station_lost-7-2.pcapng",
                                        "trigger-20251128T103005Z-station_lost-7.pcapng",
                                        "trigger-20251128T103020Z-station_lost-7.pcapng"}));
    const std::vector<std::uint8_t> kept =
        test::read_file(folder.path + "/trigger-20251128T103005Z-station_lost-7.pcapng");
    EXPECT_EQ(std::string(kept.begin(), kept.end()), "the user's\n");
    EXPECT_EQ(numbers_in(folder.path + "/trigger-20251128T103005Z-station_lost-7-2.pcapng"),
              (std::vector<int>{5, 6}));
}

TEST(TriggerRecorderTest, TheLimitPerHourCountsWhatItSuppresses) {
    Folder folder("trigger-limit");
    TriggerOptions o = options_in(folder, 0, 0);
    o.limit_per_hour = 2;
    TriggerRecorder r(o);
    const TriggerHit hit{"match", -1, "c"};
    for (int i = 0; i < 5; ++i) {
        const std::vector<std::uint8_t> bytes = telegram(i);
        ASSERT_TRUE(r.feed(Bytes(bytes.data(), bytes.size()), kT0 + i * 10 * kSecond, &hit));
    }
    // An hour later the limit starts again.
    const std::vector<std::uint8_t> late = telegram(9);
    ASSERT_TRUE(r.feed(Bytes(late.data(), late.size()), kT0 + 3601 * kSecond, &hit));
    ASSERT_TRUE(r.finish());
    EXPECT_EQ(r.stats().windows, 3u);
    EXPECT_EQ(r.stats().suppressed, 3u);
    EXPECT_EQ(folder.files().size(), 3u);
    EXPECT_EQ(folder.files()[0], "trigger-20251128T103000Z-match.pcapng");
}

TEST(TriggerRecorderTest, TheMemoryCapLetsTheOldestGoAndCountsThem) {
    Folder folder("trigger-cap");
    TriggerOptions o = options_in(folder, 1000, 0);
    o.max_pre_bytes = 5 * (6 + 32);  // five held telegrams
    TriggerRecorder r(o);
    feed_range(r, 1, 20, 20);
    ASSERT_TRUE(r.finish());
    ASSERT_EQ(folder.files().size(), 1u);
    EXPECT_EQ(numbers_in(folder.path + "/" + folder.files()[0]),
              (std::vector<int>{15, 16, 17, 18, 19, 20}));
    EXPECT_EQ(r.stats().pre_dropped, 14u);
}

TEST(TriggerRecorderTest, FileNamesKeepOnlySafeCharacters) {
    EXPECT_EQ(TriggerRecorder::file_name("cuts", kT0, TriggerHit{"station lost/../x", 3, ""}),
              "cuts/trigger-20251128T103000Z-station_lost____x-3.pcapng");
    EXPECT_EQ(TriggerRecorder::file_name("cuts/", kNoTime, TriggerHit{"", -1, ""}),
              "cuts/trigger-notime-match.pcapng");
}

}  // namespace
}  // namespace dpscope
