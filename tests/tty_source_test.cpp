// Live tty input: the serial port set-up (on a pseudo-terminal) and the tty source (over pipes,
// so parity marks and hang-ups can be produced at will).
#include "capture/tty_source.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <termios.h>
#include <unistd.h>

#include <csignal>
#include <cstring>
#include <filesystem>
#include <vector>

#include "capture/serial_port.hpp"
#include "protocols/profibus/fdl_framing_rules.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::same_settings;
using test::settings_of;

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
    TtySource source(nullptr, pipe.read_end, "pipe", options(), fdl_framing_rules());
    source.on_issue([&](const InputIssue& issue) { c.issues.push_back(issue); });
    std::vector<std::uint8_t> three = kSd1;
    three.insert(three.end(), kToken.begin(), kToken.end());
    three.insert(three.end(), kSd1.begin(), kSd1.end());
    pipe.write(three);
    drain(source, c);
    ASSERT_EQ(c.telegrams.size(), 3u);
    EXPECT_EQ(c.telegrams[0], kSd1);
    EXPECT_EQ(c.telegrams[1], kToken);
    // One character is 11 bits: 7333.3 ns at 1.5 Mbit/s; 6 characters 44 us, 3 characters 22 us.
    EXPECT_EQ(c.times[1] - c.times[0], 44'000);
    EXPECT_EQ(c.times[2] - c.times[1], 22'000);
    EXPECT_EQ(source.reads(), 1u);
    EXPECT_EQ(source.bytes_read(), 15u);
    EXPECT_TRUE(c.issues.empty());
}

TEST(TtySourceTest, TimesNeverRepeatOrGoBackwards) {
    Pipe pipe;
    Collected c;
    TtySource source(nullptr, pipe.read_end, "pipe", options(), fdl_framing_rules());
    for (int i = 0; i < 50; ++i)
        pipe.write(hex("E5"));
    drain(source, c);
    ASSERT_EQ(c.telegrams.size(), 50u);
    for (std::size_t i = 1; i < c.times.size(); ++i)
        EXPECT_GT(c.times[i], c.times[i - 1]);
    EXPECT_GT(c.times[0], 1'700'000'000'000'000'000);  // wall-clock time
}

// A clock the test sets: the time each read() "returned".
std::int64_t g_fake_now = 0;
std::int64_t fake_clock() { return g_fake_now; }

// Writes `bytes` as one read whose return time is `now`, and collects what it completes.
void read_at(Pipe& pipe, TtySource& source, Collected& c, const std::vector<std::uint8_t>& bytes,
             std::int64_t now) {
    g_fake_now = now;
    pipe.write(bytes);
    drain(source, c, 2);
}

TEST(TtySourceTest, TelegramsAreNeverCloserThanTheirTimeOnTheWire) {
    Pipe pipe;
    Collected c;
    TtySourceOptions o = options(true, 0);
    o.clock = fake_clock;
    TtySource source(nullptr, pipe.read_end, "pipe", o, fdl_framing_rules());
    const std::int64_t character = 7333;  // 11 bits at 1.5 Mbit/s
    const std::vector<std::uint8_t> request = hex("68 05 05 68 83 82 7D 3A 3E 40 16");
    const std::vector<std::uint8_t> response = hex("68 05 05 68 82 83 08 3A 3E 45 16");
    const std::int64_t t0 = 1'700'000'000'000'000'000;
    // A request and the first bytes of its response in one read, the rest of the response in a
    // read that returned (by the clock) at the same moment: the response's first byte cannot
    // have arrived before the request's 11 bytes were sent.
    std::vector<std::uint8_t> first = request;
    first.insert(first.end(), response.begin(), response.begin() + 4);
    read_at(pipe, source, c, first, t0);
    read_at(pipe, source, c, std::vector<std::uint8_t>(response.begin() + 4, response.end()), t0);
    // A read returning earlier than the previous one (the clock was set back), ...
    read_at(pipe, source, c, kSd1, t0 - 1'000'000'000);
    // ... several reads returning at one moment, ...
    for (int i = 0; i < 5; ++i)
        read_at(pipe, source, c, kToken, t0);
    // ... and a telegram split byte by byte over reads that all returned at once.
    for (std::uint8_t byte : kSd1)
        read_at(pipe, source, c, {byte}, t0 + 10'000);
    ASSERT_EQ(c.telegrams.size(), 9u);
    // The first telegram keeps the time its read gives it: its first byte, 15 characters before
    // the read returned.
    EXPECT_EQ(c.times[0], t0 - 14 * character);
    for (std::size_t i = 1; i < c.times.size(); ++i)
        EXPECT_GE(c.times[i] - c.times[i - 1],
                  static_cast<std::int64_t>(c.telegrams[i - 1].size()) * character)
            << "telegram " << i + 1;
    // A read that returned when it should does not move its telegram.
    read_at(pipe, source, c, kToken, t0 + 1'000'000'000);
    EXPECT_EQ(c.times.back(), t0 + 1'000'000'000 - 2 * character);
}

TEST(TtySourceTest, ParityMarksAreCountedAndRemoved) {
    Pipe pipe;
    Collected c;
    TtySource source(nullptr, pipe.read_end, "pipe", options(), fdl_framing_rules());
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

// The bytes counted (sniff's "N telegrams, M bytes") are the line's, not the PARMRK escapes the
// driver adds: FF FF is one byte, FF 00 X one byte.
TEST(TtySourceTest, BytesReadCountsTheLineNotTheParityMarks) {
    Pipe pipe;
    Collected c;
    TtySource source(nullptr, pipe.read_end, "pipe", options(true, 0), fdl_framing_rules());
    source.on_issue([&](const InputIssue& issue) { c.issues.push_back(issue); });
    pipe.write(hex("10 03 FF 00 02 49 4E 16 FF FF E5"));  // 8 bytes on the line, 11 read
    drain(source, c);
    EXPECT_EQ(source.bytes_read(), 8u);
    pipe.write(hex("10 03 FF"));  // an escape split across reads
    drain(source, c, 2);
    pipe.write(hex("00 02 49 4E 16"));
    drain(source, c);
    EXPECT_EQ(source.bytes_read(), 14u);
    pipe.close_writer();
    drain(source, c);
    ASSERT_EQ(c.telegrams.size(), 3u);
    ASSERT_FALSE(c.issues.empty());
    EXPECT_NE(c.issues.back().message.find("the device went away (hang-up; unplugged?) after 14 "
                                           "bytes"),
              std::string::npos)
        << c.issues.back().message;
}

TEST(TtySourceTest, ParityMarkSplitAcrossReads) {
    Pipe pipe;
    Collected c;
    TtySource source(nullptr, pipe.read_end, "pipe", options(true, 0), fdl_framing_rules());
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
    TtySource source(nullptr, pipe.read_end, "pipe", options(false), fdl_framing_rules());
    pipe.write(hex("E5 FF FF E5"));
    drain(source, c);
    EXPECT_EQ(c.telegrams.size(), 2u);
    EXPECT_EQ(source.bytes_skipped(), 2u);
    EXPECT_EQ(source.parity_errors(), 0u);
}

// The silence is the clock's (the test's), not however long the scheduler keeps the test waiting.
TEST(TtySourceTest, IdleGapCutsOffAnIncompleteTelegram) {
    Pipe pipe;
    Collected c;
    TtySourceOptions o = options(true, 30);
    o.clock = fake_clock;
    TtySource source(nullptr, pipe.read_end, "pipe", o, fdl_framing_rules());
    source.on_issue([&](const InputIssue& issue) { c.issues.push_back(issue); });
    const std::int64_t t0 = 1'700'000'000'000'000'000;
    read_at(pipe, source, c, hex("68 07 07 68 83 82"), t0);  // half a telegram, then silence
    g_fake_now = t0 + 29'000'000;                            // not yet the gap
    drain(source, c, 2);
    EXPECT_EQ(source.idle_gaps(), 0u);
    g_fake_now = t0 + 60'000'000;
    drain(source, c, 2);
    read_at(pipe, source, c, kSd1, t0 + 61'000'000);
    ASSERT_EQ(c.telegrams.size(), 1u);
    EXPECT_EQ(c.telegrams[0], kSd1);
    EXPECT_EQ(source.idle_gaps(), 1u);
    EXPECT_EQ(source.bytes_skipped(), 6u);
    ASSERT_EQ(c.issues.size(), 1u);
    EXPECT_NE(c.issues[0].message.find("skipped 6 bytes: telegram cut off"), std::string::npos)
        << c.issues[0].message;
}

TEST(TtySourceTest, WithoutIdleGapATelegramMayPause) {
    Pipe pipe;
    Collected c;
    TtySourceOptions o = options(true, 0);
    o.clock = fake_clock;
    TtySource source(nullptr, pipe.read_end, "pipe", o, fdl_framing_rules());
    const std::int64_t t0 = 1'700'000'000'000'000'000;
    read_at(pipe, source, c, hex("10 03 02"), t0);
    read_at(pipe, source, c, hex("49 4E 16"), t0 + 40'000'000);  // after a pause of 40 ms
    ASSERT_EQ(c.telegrams.size(), 1u);
    EXPECT_EQ(c.telegrams[0], kSd1);
}

TEST(TtySourceTest, HangUpEndsTheSourceAsDamagedAfterDeliveringWhatCame) {
    Pipe pipe;
    Collected c;
    TtySource source(nullptr, pipe.read_end, "device", options(), fdl_framing_rules());
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
    TtySource source(nullptr, pipe.read_end, "pipe", options(), fdl_framing_rules());
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
        auto opened = SerialPort::open({pty.slave, baud, true, false});
        ASSERT_TRUE(opened) << opened.error();
        std::unique_ptr<SerialPort> port = std::move(opened).value();
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
    auto opened = SerialPort::open({pty.slave, 1'500'000, true, true});
    ASSERT_TRUE(opened) << opened.error();
    std::unique_ptr<SerialPort> port = std::move(opened).value();
    std::vector<std::uint8_t> all(256);
    for (int i = 0; i < 256; ++i)
        all[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(i);
    ASSERT_EQ(write(pty.master, all.data(), all.size()), 256);
    std::vector<std::uint8_t> got;
    test::wait_until([&] {
        std::uint8_t buffer[512];
        ssize_t n = read(port->fd(), buffer, sizeof buffer);  // the port is non-blocking
        if (n > 0) got.insert(got.end(), buffer, buffer + n);
        return got.size() >= all.size();
    });
    EXPECT_EQ(got, all);  // no CR/LF translation, no echo, no signals (for_writing: no PARMRK)
}

// Why opening the port was refused: "" when it was not (the port is then closed again).
std::string refusal(const SerialSettings& settings) { return SerialPort::open(settings).error(); }

TEST(SerialPortTest, ErrorsNameTheDevice) {
    std::string error = refusal({"/dev/does-not-exist", 1'500'000, true, false});
    EXPECT_NE(error.find("/dev/does-not-exist: cannot open"), std::string::npos) << error;
    error = refusal({"/dev/null", 1'500'000, true, false});
    EXPECT_NE(error.find("/dev/null: not a serial port"), std::string::npos) << error;
}

TEST(SerialPortTest, ClosingPutsTheSettingsBackAsFound) {
    PseudoTerminal pty;
    const termios before = settings_of(pty.slave);
    ASSERT_NE(before.c_lflag & ICANON, 0u);  // a fresh pty is a cooked terminal
    for (bool for_writing : {false, true}) {
        auto opened = SerialPort::open({pty.slave, 187'500, true, for_writing, ""});
        ASSERT_TRUE(opened) << opened.error();
        std::unique_ptr<SerialPort> port = std::move(opened).value();
        EXPECT_FALSE(same_settings(settings_of(pty.slave), before));  // raw while open
        port.reset();
        EXPECT_TRUE(same_settings(settings_of(pty.slave), before)) << for_writing;
    }
    // From a signal handler too (the process then ends without destructors).
    auto opened = SerialPort::open({pty.slave, 500'000, true, false, ""});
    ASSERT_TRUE(opened) << opened.error();
    std::unique_ptr<SerialPort> port = std::move(opened).value();
    SerialPort::restore_all_after_signal();
    EXPECT_TRUE(same_settings(settings_of(pty.slave), before));
}

std::string make_lock_dir() {
    std::string dir = test::temp_path("lock");
    std::filesystem::create_directories(dir);
    return dir;
}

std::string lock_path(const std::string& dir, const std::string& device) {
    return dir + "/LCK.." + device.substr(device.rfind('/') + 1);
}

TEST(SerialPortTest, TheLockFileKeepsASecondUserOut) {
    PseudoTerminal pty;
    const std::string dir = make_lock_dir();
    const std::string lock = lock_path(dir, pty.slave);
    auto opened = SerialPort::open({pty.slave, 1'500'000, true, false, dir});
    ASSERT_TRUE(opened) << opened.error();
    std::unique_ptr<SerialPort> port = std::move(opened).value();
    EXPECT_EQ(port->lock_file(), lock);
    char expected[32];
    std::snprintf(expected, sizeof expected, "%10d\n", static_cast<int>(getpid()));
    auto content = test::read_file(lock);
    EXPECT_EQ(std::string(content.begin(), content.end()), expected);  // UUCP (HDB) format
    const termios during = settings_of(pty.slave);
    std::string error = refusal({pty.slave, 9600, true, false, dir});
    EXPECT_NE(error.find(pty.slave + " is in use by process " + std::to_string(getpid())),
              std::string::npos)
        << error;
    EXPECT_NE(error.find("lock file " + lock), std::string::npos) << error;
    // The refused open changed nothing.
    EXPECT_TRUE(same_settings(settings_of(pty.slave), during));
    port.reset();
    EXPECT_FALSE(std::filesystem::exists(lock));
    std::filesystem::remove_all(dir);
}

TEST(SerialPortTest, WithoutALockFileTheDeviceLockKeepsASecondUserOut) {
    PseudoTerminal pty;
    auto opened = SerialPort::open({pty.slave, 1'500'000, true, false, ""});
    ASSERT_TRUE(opened) << opened.error();
    std::unique_ptr<SerialPort> port = std::move(opened).value();
    std::string error = refusal({pty.slave, 1'500'000, true, false, ""});
    EXPECT_NE(error.find(pty.slave + " is in use: another process holds a lock on the device"),
              std::string::npos)
        << error;
    port.reset();
    auto reopened = SerialPort::open({pty.slave, 1'500'000, true, false, ""});
    EXPECT_TRUE(reopened) << reopened.error();
}

TEST(SerialPortTest, AStaleLockFileIsReplacedAndALiveOneIsNot) {
    PseudoTerminal pty;
    const std::string dir = make_lock_dir();
    const std::string lock = lock_path(dir, pty.slave);
    // A process that has ended.
    pid_t gone = fork();
    if (gone == 0) _exit(0);
    waitpid(gone, nullptr, 0);
    test::write_text_file(lock, std::to_string(gone) + "\n");
    {
        auto opened = SerialPort::open({pty.slave, 1'500'000, true, false, dir});
        ASSERT_TRUE(opened) << opened.error();
        std::unique_ptr<SerialPort> port = std::move(opened).value();
        auto content = test::read_file(lock);
        EXPECT_EQ(std::stoi(std::string(content.begin(), content.end())), getpid());
    }
    // A process that is running (our parent): the port is not taken, the lock stays.
    std::string live = std::to_string(getppid());
    test::write_text_file(lock, std::string(10 - live.size(), ' ') + live + "\n");
    std::string error = refusal({pty.slave, 1'500'000, true, false, dir});
    EXPECT_NE(error.find("is in use by process " + live), std::string::npos) << error;
    EXPECT_TRUE(std::filesystem::exists(lock));
    std::filesystem::remove_all(dir);
}

// SerialPort::claim in a child process (a claim that blocks must not hang the test): what it
// said, or that it did not return within `seconds`. `prepare` runs in the child first.
struct ClaimOutcome {
    bool returned = false;
    bool claimed = false;
    std::string error;
};

ClaimOutcome claim_in_child(const SerialSettings& settings, const std::string& said,
                            void (*prepare)(const std::string& dir) = nullptr,
                            double seconds = test::kPatienceSeconds) {
    ClaimOutcome outcome;
    pid_t child = fork();
    if (child == 0) {
        if (prepare) prepare(settings.lock_dir);
        auto claimed = SerialPort::claim(settings);
        FILE* out = std::fopen(said.c_str(), "w");
        if (out) {
            std::fputs(claimed ? "" : claimed.error().c_str(), out);
            std::fclose(out);
        }
        _exit(claimed ? 0 : 1);
    }
    int status = 0;
    if (!test::wait_until([&] { return waitpid(child, &status, WNOHANG) == child; }, seconds)) {
        kill(child, SIGKILL);
        waitpid(child, &status, 0);
        return outcome;
    }
    outcome.returned = WIFEXITED(status);
    outcome.claimed = outcome.returned && WEXITSTATUS(status) == 0;
    outcome.error = test::slurp(said);
    return outcome;
}

// /run/lock is writable by everyone: what another user plants there (a FIFO, a symbolic link, a
// folder) is refused as a lock file, and never waited on, followed or removed.
TEST(SerialPortTest, ALockFileThatIsNoRegularFileIsRefusedWithoutWaiting) {
    PseudoTerminal pty;
    const std::string dir = make_lock_dir();
    const std::string lock = lock_path(dir, pty.slave);
    const std::string said = test::temp_path("said");
    // A FIFO: opening it for reading would wait for a writer forever.
    ASSERT_EQ(mkfifo(lock.c_str(), 0666), 0);
    ClaimOutcome fifo = claim_in_child({pty.slave, 9600, true, false, dir}, said);
    ASSERT_TRUE(fifo.returned) << "claim() blocked on a FIFO planted as the lock file";
    EXPECT_FALSE(fifo.claimed);
    EXPECT_NE(fifo.error.find("lock file " + lock + " is not a regular file (a FIFO)"),
              std::string::npos)
        << fifo.error;
    EXPECT_TRUE(std::filesystem::is_fifo(lock));  // not removed as stale
    std::filesystem::remove(lock);
    // A symbolic link to another file, holding a PID that is gone: not followed, the file
    // it points at is left as it was.
    const std::string target = test::temp_path("target");
    test::write_text_file(target, "         1\n");
    std::filesystem::create_symlink(target, lock);
    ClaimOutcome link = claim_in_child({pty.slave, 9600, true, false, dir}, said);
    ASSERT_TRUE(link.returned);
    EXPECT_FALSE(link.claimed);
    EXPECT_NE(link.error.find("lock file " + lock + " is not a regular file (a symbolic link)"),
              std::string::npos)
        << link.error;
    EXPECT_TRUE(std::filesystem::is_symlink(lock));
    EXPECT_EQ(test::slurp(target), "         1\n");
    std::filesystem::remove(lock);
    // A folder.
    std::filesystem::create_directory(lock);
    ClaimOutcome folder = claim_in_child({pty.slave, 9600, true, false, dir}, said);
    ASSERT_TRUE(folder.returned);
    EXPECT_FALSE(folder.claimed);
    EXPECT_NE(folder.error.find("is not a regular file (a folder)"), std::string::npos)
        << folder.error;
    std::filesystem::remove(lock);
    // A FIFO planted under the name of the temporary file the lock is written into first
    // (LTMP.PID, the PID is easy to guess): not opened, the lock is still taken.
    ClaimOutcome temp =
        claim_in_child({pty.slave, 9600, true, false, dir}, said, [](const std::string& in) {
            const std::string name = in + "/LTMP." + std::to_string(getpid());
            mkfifo(name.c_str(), 0666);
        });
    ASSERT_TRUE(temp.returned) << "claim() blocked on a FIFO planted as its temporary file";
    EXPECT_TRUE(temp.claimed) << temp.error;
    std::filesystem::remove_all(dir);
}

TEST(SerialPortTest, CharacterTimeIsElevenBits) {
    EXPECT_EQ(character_ns(1'500'000), 7333);
    EXPECT_EQ(character_ns(12'000'000), 916);
    EXPECT_EQ(character_ns(9600), 1'145'833);
}

}  // namespace
}  // namespace dpscope

namespace dpscope {
namespace {

TEST(SerialPortTest, ParityAndStopBitsAreSetAsAsked) {
    PseudoTerminal pty;
    SerialSettings odd{pty.slave, 9600, true, false, ""};
    odd.parity = SerialParity::Odd;
    odd.stop_bits = 2;
    {
        auto opened = SerialPort::open(odd);
        ASSERT_TRUE(opened) << opened.error();
        EXPECT_EQ((*opened)->frame(), "8O2");
        const termios tio = test::settings_of(pty.slave);
        EXPECT_NE(tio.c_cflag & CSTOPB, 0u);
        EXPECT_NE(tio.c_cflag & PARODD, 0u);
        EXPECT_NE(tio.c_iflag & INPCK, 0u);
        EXPECT_NE((*opened)->note().find("does not check odd parity"), std::string::npos)
            << (*opened)->note();
    }
    SerialSettings none{pty.slave, 115200, true, false, ""};
    none.parity = SerialParity::None;
    {
        auto opened = SerialPort::open(none);
        ASSERT_TRUE(opened) << opened.error();
        EXPECT_EQ((*opened)->frame(), "8N1");
        const termios tio = test::settings_of(pty.slave);
        EXPECT_EQ(tio.c_cflag & (PARENB | PARODD | CSTOPB), 0u);
        EXPECT_EQ(tio.c_iflag & (INPCK | PARMRK), 0u);  // no parity: nothing to mark
        EXPECT_FALSE((*opened)->parity_marked());
        EXPECT_EQ((*opened)->note(), "");
    }
    SerialSettings even{pty.slave, 9600, true, false, ""};
    auto opened = SerialPort::open(even);
    ASSERT_TRUE(opened) << opened.error();
    EXPECT_EQ((*opened)->frame(), "8E1");
    const termios tio = test::settings_of(pty.slave);
    EXPECT_EQ(tio.c_cflag & (PARODD | CSTOPB), 0u);
}

TEST(SerialPortTest, CharacterTimeCountsTheFrameBits) {
    EXPECT_EQ(character_bits(SerialParity::Even, 1), 11u);
    EXPECT_EQ(character_bits(SerialParity::None, 1), 10u);
    EXPECT_EQ(character_bits(SerialParity::None, 2), 11u);
    EXPECT_EQ(character_ns(9600), 1'145'833);
    EXPECT_EQ(character_ns(9600, 10), 1'041'666);
}

}  // namespace
}  // namespace dpscope
