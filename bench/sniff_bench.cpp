// Sniffer throughput over a pseudo-terminal: plays a simulated 12 Mbit/s session into one end
// while `dpscope sniff` captures on the other, writing pcap and printing -T text (to /dev/null).
// Reports bytes/s at full speed and when paced at the bus rate, lost telegrams, and the sniffer's
// CPU time per second of bus traffic.
// --stats: `sniff --stats -w FILE` with its standard output on a second pseudo-terminal (the live
// station table, read as fast as it comes), played as fast as the pty takes it and paced at
// 1.1 MB/s (a saturated 12 Mbit/s bus); exit code 1 when a telegram was lost.
// Usage: dpscope_sniff_bench [--stats] DPSCOPE [TELEGRAMS]
#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "capture/telegram_source.hpp"
#include "capture/tty_player.hpp"
#include "simulator/simulator.hpp"

namespace {

constexpr std::uint32_t kBaud = 12'000'000;

struct Result {
    double seconds = 0;
    std::uint64_t bytes = 0;
    std::uint64_t sent = 0;
    std::uint64_t captured = 0;
    double cpu_seconds = 0;
};

std::string slurp(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// How the telegrams are played: as fast as the pty takes them, at the simulated bus timing
// (12 Mbit/s with the protocol's idle gaps), or back to back at a fixed byte rate.
enum class Pace { FullSpeed, BusTiming, ByteRate };

Result run(const std::string& dpscope, std::uint64_t telegrams, Pace pace, bool stats = false) {
    int master = -1, slave_fd = -1;
    char name[128] = {};
    if (openpty(&master, &slave_fd, name, nullptr, nullptr) != 0) std::exit(1);
    fcntl(master, F_SETFD, FD_CLOEXEC);
    close(slave_fd);
    // --stats: standard output on a terminal of its own, drained by a thread.
    int screen = -1, screen_slave = -1;
    std::atomic<bool> drained{false};
    std::thread drain;
    if (stats) {
        winsize size{};
        size.ws_col = 160;
        size.ws_row = 50;
        if (openpty(&screen, &screen_slave, nullptr, nullptr, &size) != 0) std::exit(1);
        fcntl(screen, F_SETFD, FD_CLOEXEC);
        drain = std::thread([&] {
            char buffer[65536];
            while (!drained) {
                pollfd p{screen, POLLIN, 0};
                if (poll(&p, 1, 20) > 0 && read(screen, buffer, sizeof buffer) <= 0) break;
            }
        });
    }
    const std::string pcap = "/tmp/dpscope-sniff-bench.pcap";
    const std::string err = "/tmp/dpscope-sniff-bench.err";
    pid_t pid = fork();
    if (pid == 0) {
        int null = open("/dev/null", O_WRONLY);
        int errfd = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        dup2(stats ? screen_slave : null, STDOUT_FILENO);
        dup2(errfd, STDERR_FILENO);
        if (stats)
            execl(dpscope.c_str(), dpscope.c_str(), "sniff", "-i", name, "--baud", "12000000", "-w",
                  pcap.c_str(), "--stats", static_cast<char*>(nullptr));
        else
            execl(dpscope.c_str(), dpscope.c_str(), "sniff", "-i", name, "--baud", "12000000", "-w",
                  pcap.c_str(), "-T", "text", static_cast<char*>(nullptr));
        _exit(127);
    }
    for (int i = 0; i < 500 && slurp(err).find("capturing on") == std::string::npos; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));

    dpscope::SimulatorOptions options;
    options.baud = kBaud;
    options.cycle_us = 0;  // back to back: the bus is as busy as the protocol lets it be
    options.cycles = 0;
    options.max_telegrams = telegrams;
    options.slaves = {{3, 1, dpscope::Dialect::Vlt},
                      {4, 2, dpscope::Dialect::Vlt},
                      {5, 5, dpscope::Dialect::Vlt},
                      {6, 3, dpscope::Dialect::Vlt}};
    dpscope::Simulator simulator(options);
    auto start = std::chrono::steady_clock::now();
    std::uint64_t played_bytes = 0;
    auto next = [&](std::vector<std::uint8_t>& b, std::int64_t& t) {
        if (!simulator.next(b, t)) return false;
        if (pace == Pace::ByteRate) {  // 1.1 MB/s, no idle time at all
            t = static_cast<std::int64_t>(static_cast<double>(played_bytes) / 1.1e6 * 1e9);
            played_bytes += b.size();
        }
        return true;
    };
    dpscope::Result<dpscope::PlayStats> played =
        dpscope::play_telegrams(master, next, pace == Pace::FullSpeed, nullptr);
    if (!played) {
        std::fprintf(stderr, "%s\n", played.error().c_str());
        std::exit(1);
    }
    // Wait until the sniffer has taken everything the pty holds.
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() - 0.3;
    kill(pid, SIGINT);
    int status = 0;
    rusage usage{};
    wait4(pid, &status, 0, &usage);
    close(master);
    if (stats) {
        drained = true;
        drain.join();
        close(screen);
        close(screen_slave);
    }
    Result r;
    r.seconds = seconds;
    r.bytes = played->bytes;
    r.sent = played->telegrams;
    r.cpu_seconds = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                    static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) / 1e6;
    dpscope::OpenResult opened =
        dpscope::open_source(pcap, dpscope::InputFormat::Auto, dpscope::profibus_protocol());
    dpscope::Record record;
    while (opened && opened.value()->next(record))
        ++r.captured;
    std::remove(pcap.c_str());
    std::remove(err.c_str());
    return r;
}

void print(const char* label, const Result& r) {
    double bus_seconds = static_cast<double>(r.bytes) * 11.0 / kBaud;
    std::printf("| %s | %llu | %.2f MB/s | %llu | %.3f s per bus second |\n", label,
                static_cast<unsigned long long>(r.sent),
                static_cast<double>(r.bytes) / r.seconds / 1e6,
                static_cast<unsigned long long>(r.sent - r.captured), r.cpu_seconds / bus_seconds);
}

}  // namespace

int main(int argc, char** argv) {
    const bool stats = argc > 1 && std::string(argv[1]) == "--stats";
    if (stats) {
        --argc;
        ++argv;
    }
    if (argc < 2) {
        std::fprintf(stderr, "usage: dpscope_sniff_bench [--stats] DPSCOPE [TELEGRAMS]\n");
        return 2;
    }
    std::uint64_t telegrams = argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 500'000;
    if (stats) {
        std::printf(
            "| playback | telegrams | throughput | lost | sniffer CPU "
            "|\n|---|---:|---:|---:|---:|\n");
        Result fast = run(argv[1], telegrams, Pace::FullSpeed, true);
        print("sniff --stats -w FILE (table on a terminal), as fast as the pty takes it", fast);
        Result paced = run(argv[1], telegrams, Pace::ByteRate, true);
        print("sniff --stats -w FILE (table on a terminal), paced at 1.1 MB/s, no idle time",
              paced);
        return fast.captured == fast.sent && paced.captured == paced.sent ? 0 : 1;
    }
    std::printf(
        "| playback | telegrams | throughput | lost | sniffer CPU |\n|---|---:|---:|---:|---:|\n");
    print("as fast as the pty takes it", run(argv[1], telegrams, Pace::FullSpeed));
    print("paced at 1.1 MB/s, no idle time", run(argv[1], telegrams, Pace::ByteRate));
    print("paced at the simulated 12 Mbit/s bus timing", run(argv[1], telegrams, Pace::BusTiming));
    return 0;
}
