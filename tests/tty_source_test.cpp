// Live tty input: the serial port set-up (on a pseudo-terminal) and the tty source (over pipes,
// so parity marks and hang-ups can be produced at will).
#include "capture/tty_source.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <thread>
#include <vector>

#include "capture/serial_port.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::hex;

struct Pipe {
    int read_end = -1;
    int write_end = -1;
    Pipe() {
        int fds[2];
        EXPECT_EQ(pipe2(fds, O_NONBLOCK | O_CLOEXEC), 0);
        read_end = fds[0];
        write_end = fds[1];
    }
    ~Pipe() {
        if (read_end >= 0) close(read_end);
        close_writer();
    }
    void write(const std::vector<std::uint8_t>& bytes) const {
        ASSERT_EQ(::write(write_end, bytes.data(), bytes.size()),
                  static_cast<ssize_t>(bytes.size()));
    }
    void close_writer() {
        if (write_end >= 0) close(write_end);
        write_end = -1;
    }
};

struct Collected {
    std::vector<std::vector<std::uint8_t>> telegrams;
    std::vector<std::int64_t> times;
    std::vector<InputIssue> issues;
};

TtySourceOptions options(bool parity_marked = true, std::int64_t gap_ms = 50) {
    TtySourceOptions o;
    o.baud = 1'500'000;
    o.parity_marked = parity_marked;
    o.idle_gap_ns = gap_ms * 1'000'000;
    o.poll_ms = 5;
    return o;
}

// Polls until `idle_polls` consecutive Idle results or the end.
void drain(TtySource& source, Collected& c, int idle_polls = 3) {
    Record record;
    int idle = 0;
    while (idle < idle_polls) {
        FramedSource::Poll p = source.poll(record);
        if (p == FramedSource::Poll::End) return;
        if (p == FramedSource::Poll::Idle) {
            ++idle;
            continue;
        }
        idle = 0;
        c.telegrams.emplace_back(record.bytes.begin(), record.bytes.end());
        c.times.push_back(record.time_ns);
    }
}

const std::vector<std::uint8_t> kSd1 = hex("10 03 02 49 4E 16");
const std::vector<std::uint8_t> kToken = hex("DC 02 02");

TEST(TtySourceTest, TelegramsInOneReadGetTimesSpacedByTheirLength) {
    Pipe pipe;
    Collected c;
    TtySource source(nullptr, pipe.read_end, "pipe", options());
    source.on_issue([&](const InputIssue& issue) { c.issues.push_back(issue); });
    std::vector<std::uint8_t> three = kSd1;
    three.insert(three.end(), kToken.begin(), kToken.end());
    three.insert(three.end(), kSd1.begin(), kSd1.end());
    pipe.write(three);
    drain(source, c);
    ASSERT_EQ(c.telegrams.size(), 3u);
    EXPECT_EQ(c.telegrams[0], kSd1);
    EXPECT_EQ(c.telegrams[1], kToken);
    // One character is 11 bits: 7333 ns at 1.5 Mbit/s.
    EXPECT_EQ(c.times[1] - c.times[0], 6 * 7333);
    EXPECT_EQ(c.times[2] - c.times[1], 3 * 7333);
    EXPECT_EQ(source.reads(), 1u);
    EXPECT_EQ(source.bytes_read(), 15u);
    EXPECT_TRUE(c.issues.empty());
}

TEST(TtySourceTest, TimesNeverRepeatOrGoBackwards) {
    Pipe pipe;
    Collected c;
    TtySource source(nullptr, pipe.read_end, "pipe", options());
    for (int i = 0; i < 50; ++i)
        pipe.write(hex("E5"));
    drain(source, c);
    ASSERT_EQ(c.telegrams.size(), 50u);
    for (std::size_t i = 1; i < c.times.size(); ++i)
        EXPECT_GT(c.times[i], c.times[i - 1]);
    EXPECT_GT(c.times[0], 1'700'000'000'000'000'000);  // wall-clock time
}

TEST(TtySourceTest, ParityMarksAreCountedAndRemoved) {
    Pipe pipe;
    Collected c;
    TtySource source(nullptr, pipe.read_end, "pipe", options());
    source.on_issue([&](const InputIssue& issue) { c.issues.push_back(issue); });
    // 02 arrived with a parity error (FF 00 02); a real FF byte is escaped as FF FF.
    pipe.write(hex("10 03 FF 00 02 49 4E 16 FF FF E5"));
    drain(source, c);
    ASSERT_EQ(c.telegrams.size(), 2u);
    EXPECT_EQ(c.telegrams[0], kSd1);
    EXPECT_EQ(c.telegrams[1], hex("E5"));
    EXPECT_EQ(source.parity_errors(), 1u);
    EXPECT_EQ(source.bytes_skipped(), 1u);  // the FF between the two telegrams
    ASSERT_FALSE(c.issues.empty());
    EXPECT_NE(c.issues[0].message.find("pipe: byte offset 2 of the stream: parity or framing error "
                                       "(byte 0x02)"),
              std::string::npos)
        << c.issues[0].message;
}

TEST(TtySourceTest, ParityMarkSplitAcrossReads) {
    Pipe pipe;
    Collected c;
    TtySource source(nullptr, pipe.read_end, "pipe", options(true, 0));
    pipe.write(hex("10 03 FF"));
    drain(source, c, 2);
    pipe.write(hex("00 02 49 4E 16"));
    drain(source, c);
    ASSERT_EQ(c.telegrams.size(), 1u);
    EXPECT_EQ(c.telegrams[0], kSd1);
    EXPECT_EQ(source.parity_errors(), 1u);
}

TEST(TtySourceTest, WithoutParityMarkingBytesPassUnchanged) {
    Pipe pipe;
    Collected c;
    TtySource source(nullptr, pipe.read_end, "pipe", options(false));
    pipe.write(hex("E5 FF FF E5"));
    drain(source, c);
    EXPECT_EQ(c.telegrams.size(), 2u);
    EXPECT_EQ(source.bytes_skipped(), 2u);
    EXPECT_EQ(source.parity_errors(), 0u);
}

TEST(TtySourceTest, IdleGapCutsOffAnIncompleteTelegram) {
    Pipe pipe;
    Collected c;
    TtySource source(nullptr, pipe.read_end, "pipe", options(true, 30));
    source.on_issue([&](const InputIssue& issue) { c.issues.push_back(issue); });
    pipe.write(hex("68 07 07 68 83 82"));  // half a telegram, then silence
    drain(source, c, 2);
    std::this_thread::sleep_for(std::chrono::milliseconds(60));
    drain(source, c, 2);
    pipe.write(kSd1);
    drain(source, c);
    ASSERT_EQ(c.telegrams.size(), 1u);
    EXPECT_EQ(c.telegrams[0], kSd1);
    EXPECT_EQ(source.idle_gaps(), 1u);
    EXPECT_EQ(source.bytes_skipped(), 6u);
    ASSERT_EQ(c.issues.size(), 1u);
    EXPECT_NE(c.issues[0].message.find("skipped 6 byte(s): telegram cut off"), std::string::npos)
        << c.issues[0].message;
}

TEST(TtySourceTest, WithoutIdleGapATelegramMayPause) {
    Pipe pipe;
    Collected c;
    TtySource source(nullptr, pipe.read_end, "pipe", options(true, 0));
    pipe.write(hex("10 03 02"));
    drain(source, c, 2);
    std::this_thread::sleep_for(std::chrono::milliseconds(40));
    pipe.write(hex("49 4E 16"));
    drain(source, c);
    ASSERT_EQ(c.telegrams.size(), 1u);
    EXPECT_EQ(c.telegrams[0], kSd1);
}

TEST(TtySourceTest, HangUpEndsTheSourceAsDamagedAfterDeliveringWhatCame) {
    Pipe pipe;
    Collected c;
    TtySource source(nullptr, pipe.read_end, "device", options());
    source.on_issue([&](const InputIssue& issue) { c.issues.push_back(issue); });
    pipe.write(kSd1);
    pipe.write(hex("68 07"));  // and then the device goes away mid-telegram
    pipe.close_writer();
    drain(source, c, 1000);
    ASSERT_EQ(c.telegrams.size(), 1u);
    EXPECT_EQ(source.status(), InputStatus::Damaged);
    bool named = false;
    for (const InputIssue& issue : c.issues)
        named |= issue.message.find("device: the device went away") != std::string::npos;
    EXPECT_TRUE(named);
}

TEST(TtySourceTest, StopRequestReadsWhatIsBufferedThenEnds) {
    Pipe pipe;
    Collected c;
    TtySource source(nullptr, pipe.read_end, "pipe", options());
    pipe.write(kSd1);
    pipe.write(kToken);
    pipe.write(hex("10 03"));  // cut off by the stop
    source.request_stop();
    drain(source, c, 1000);
    ASSERT_EQ(c.telegrams.size(), 2u);
    EXPECT_EQ(source.status(), InputStatus::Ok);
    EXPECT_EQ(source.bytes_skipped(), 2u);
}

// ---- serial port --------------------------------------------------------------------------------

using test::PseudoTerminal;

TEST(SerialPortTest, EveryProfibusBaudRateIsSetAndReadBack) {
    PseudoTerminal pty;
    for (std::uint32_t baud : {9600u, 19200u, 45450u, 93750u, 187500u, 500000u, 1500000u, 3000000u,
                               6000000u, 12000000u}) {
        std::string error;
        auto port = SerialPort::open({pty.slave, baud, true, false}, error);
        ASSERT_TRUE(port) << error;
        EXPECT_EQ(port->baud(), baud);
        // A pseudo-terminal takes no parity and has no low-latency flag; the port says so.
        EXPECT_FALSE(port->parity_checked());
        EXPECT_TRUE(port->parity_marked());
        EXPECT_FALSE(port->low_latency());
        EXPECT_NE(port->note().find("does not check even parity"), std::string::npos);
    }
}

TEST(SerialPortTest, RawModeCarriesEveryByteUnchanged) {
    PseudoTerminal pty;
    std::string error;
    auto port = SerialPort::open({pty.slave, 1'500'000, true, true}, error);
    ASSERT_TRUE(port) << error;
    std::vector<std::uint8_t> all(256);
    for (int i = 0; i < 256; ++i)
        all[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(i);
    ASSERT_EQ(write(pty.master, all.data(), all.size()), 256);
    std::vector<std::uint8_t> got;
    for (int tries = 0; tries < 100 && got.size() < 256; ++tries) {
        std::uint8_t buffer[512];
        ssize_t n = read(port->fd(), buffer, sizeof buffer);
        if (n > 0)
            got.insert(got.end(), buffer, buffer + n);
        else
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    EXPECT_EQ(got, all);  // no CR/LF translation, no echo, no signals (for_writing: no PARMRK)
}

TEST(SerialPortTest, ErrorsNameTheDevice) {
    std::string error;
    EXPECT_FALSE(SerialPort::open({"/dev/does-not-exist", 1'500'000, true, false}, error));
    EXPECT_NE(error.find("/dev/does-not-exist: cannot open"), std::string::npos) << error;
    EXPECT_FALSE(SerialPort::open({"/dev/null", 1'500'000, true, false}, error));
    EXPECT_NE(error.find("/dev/null: not a serial port"), std::string::npos) << error;
}

TEST(SerialPortTest, CharacterTimeIsElevenBits) {
    EXPECT_EQ(character_ns(1'500'000), 7333);
    EXPECT_EQ(character_ns(12'000'000), 916);
    EXPECT_EQ(character_ns(9600), 1'145'833);
}

}  // namespace
}  // namespace dpscope
