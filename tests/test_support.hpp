// Helpers shared by the test files.
#pragma once

#include <sys/types.h>
#include <termios.h>

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "core/byte_reader.hpp"

namespace dpscope {
class Output;
}

namespace dpscope::test {

// "68 07 07 68" (or "6807 0768", "0x68,0x07") -> bytes; a malformed string fails the test.
std::vector<std::uint8_t> hex(std::string_view text);

// A header and what follows it, appended byte by byte (GCC 12's -Warray-bounds misreads
// vector::insert after a short initializer list in a release build).
std::vector<std::uint8_t> joined(std::vector<std::uint8_t> header,
                                 const std::vector<std::uint8_t>& rest);

// The repository's root directory and the dpscope executable built with the tests.
// Danfoss FC protocol telegrams, built by hand with their BCC (protocols/fc/fc_framing_rules.hpp):
// the address byte in the 1-126 format (0x80 | address; address 0: the broadcast 0x80).
std::vector<std::uint8_t> fc_process(std::uint8_t address, std::uint16_t pcd1 = 0x047F,
                                     std::uint16_t pcd2 = 0x2000);
// A parameter block: PKE = AK << 12 | PNU (12 bits), IND = index, PWE, PCD 1 and 2.
std::vector<std::uint8_t> fc_parameter(std::uint8_t address, std::uint8_t ak, std::uint16_t pnu,
                                       std::uint8_t index = 0, std::uint32_t pwe = 0,
                                       std::uint16_t pcd1 = 0x047F, std::uint16_t pcd2 = 0x2000);

std::string source_dir();
std::string dpscope_executable();

// How long a test waits for what takes milliseconds on an idle machine: a child process saying
// it is ready, a file growing, a line arriving. It only bounds a hang; on a loaded machine all of
// it takes longer, and no test decides pass or fail by how long something took.
constexpr double kPatienceSeconds = 120;

// Checks `done` every 10 ms until it holds or `seconds` have passed; whether it holds.
bool wait_until(const std::function<bool()>& done, double seconds = kPatienceSeconds);

// What arrives on the descriptor `fd` (a child's pipe) until `want` is in it, the pipe ends, or
// `seconds` have passed; all that arrived. Waits on the descriptor, not on a clock.
std::string read_until(int fd, std::string_view want, double seconds = kPatienceSeconds);

// The current test's own temporary folder (made on first use under $TEST_TMPDIR, else /tmp;
// no other test, in this process or another, writes there). It and everything in it are removed
// when the test process ends, unless DPSCOPE_KEEP_TEST_FILES is set.
std::string temp_folder();
// A fresh path in the test's temporary folder (the file does not exist yet).
std::string temp_path(std::string_view name);
void write_file(const std::string& path, const std::vector<std::uint8_t>& bytes);
void write_text_file(const std::string& path, std::string_view text);
std::vector<std::uint8_t> read_file(const std::string& path);
std::string slurp(const std::string& path);  // the file's content as text ("" if unreadable)

// The text `write` writes to an Output (over an open_memstream); the test fails if the stream
// cannot be opened or the Output does not flush.
std::string output_text(const std::function<void(Output&)>& write);

struct CommandResult {
    int exit_code = -1;
    std::string out;  // standard output
    std::string err;  // standard error
};

// Runs dpscope with `args` (each element one argument), standard input from `input` (or
// /dev/null when empty), in the source directory, with TZ=UTC LANG=C.
CommandResult run_dpscope(const std::vector<std::string>& args, const std::string& input = {});

// The lines of `text`, without their line ends.
std::vector<std::string> lines_of(const std::string& text);

// The terminal settings of `path` as another program sees them (opened afresh, non-blocking).
termios settings_of(const std::string& path);
bool same_settings(const termios& a, const termios& b);

// Processes of the process group `group` that are alive (zombies not counted), from /proc.
std::size_t live_processes_in_group(pid_t group);
// Waits (at most the patience) until process group `group` has `count` live processes: a
// process sent SIGKILL, or a shell's child about to start, takes a moment. Whether it did.
bool wait_for_processes_in_group(pid_t group, std::size_t count);

// A pseudo-terminal pair: tests write into `master`; the code under test opens `slave` (a path)
// as its serial port. The master is close-on-exec, so a child process (dpscope sniff) does not
// inherit it and closing it here hangs the line up.
struct PseudoTerminal {
    int master = -1;
    std::string slave;
    PseudoTerminal();
    ~PseudoTerminal() { close_master(); }
    PseudoTerminal(const PseudoTerminal&) = delete;
    PseudoTerminal& operator=(const PseudoTerminal&) = delete;
    void close_master();
    void write(const std::vector<std::uint8_t>& bytes) const;  // all of them, or the test fails
};

// A pcapng file built block by block, in either byte order.
class PcapngBuilder {
  public:
    explicit PcapngBuilder(bool big_endian = false) : big_endian_(big_endian) { section(); }

    PcapngBuilder& section() {
        std::vector<std::uint8_t> body;
        put32(body, 0x1A2B3C4D);
        put16(body, 1);
        put16(body, 0);
        put32(body, 0xFFFFFFFF);  // section length -1: not given
        put32(body, 0xFFFFFFFF);
        return block(0x0A0D0D0A, body);
    }
    // `resolution`: the if_tsresol byte (0: none, microseconds); `offset_s`: if_tsoffset.
    PcapngBuilder& interface(std::uint16_t link_type, std::uint8_t resolution = 0,
                             std::int64_t offset_s = 0) {
        std::vector<std::uint8_t> body;
        put16(body, link_type);
        put16(body, 0);
        put32(body, 0);
        if (resolution != 0) {
            put16(body, 9);
            put16(body, 1);
            body.insert(body.end(), {resolution, 0, 0, 0});
        }
        if (offset_s != 0) {
            put16(body, 14);
            put16(body, 8);
            put32(body, static_cast<std::uint32_t>(static_cast<std::uint64_t>(offset_s) >>
                                                   (big_endian_ ? 32 : 0)));
            put32(body, static_cast<std::uint32_t>(static_cast<std::uint64_t>(offset_s) >>
                                                   (big_endian_ ? 0 : 32)));
        }
        put32(body, 0);  // opt_endofopt
        return block(1, body);
    }
    PcapngBuilder& packet(std::uint32_t interface, std::uint64_t units,
                          const std::vector<std::uint8_t>& data) {
        std::vector<std::uint8_t> body;
        put32(body, interface);
        put32(body, static_cast<std::uint32_t>(units >> 32));
        put32(body, static_cast<std::uint32_t>(units));
        put32(body, static_cast<std::uint32_t>(data.size()));
        put32(body, static_cast<std::uint32_t>(data.size()));
        body.insert(body.end(), data.begin(), data.end());
        return block(6, body);
    }
    PcapngBuilder& simple_packet(const std::vector<std::uint8_t>& data) {
        std::vector<std::uint8_t> body;
        put32(body, static_cast<std::uint32_t>(data.size()));
        body.insert(body.end(), data.begin(), data.end());
        return block(3, body);
    }
    PcapngBuilder& block(std::uint32_t type, std::vector<std::uint8_t> body) {
        while (body.size() % 4 != 0)
            body.push_back(0);
        std::uint32_t length = static_cast<std::uint32_t>(body.size() + 12);
        put32(bytes_, type);
        put32(bytes_, length);
        bytes_.insert(bytes_.end(), body.begin(), body.end());
        put32(bytes_, length);
        return *this;
    }
    std::vector<std::uint8_t>& bytes() { return bytes_; }

  private:
    void put16(std::vector<std::uint8_t>& out, std::uint16_t v) const {
        if (big_endian_)
            out.insert(out.end(),
                       {static_cast<std::uint8_t>(v >> 8), static_cast<std::uint8_t>(v)});
        else
            out.insert(out.end(),
                       {static_cast<std::uint8_t>(v), static_cast<std::uint8_t>(v >> 8)});
    }
    void put32(std::vector<std::uint8_t>& out, std::uint32_t v) const {
        if (big_endian_) {
            put16(out, static_cast<std::uint16_t>(v >> 16));
            put16(out, static_cast<std::uint16_t>(v));
        } else {
            put16(out, static_cast<std::uint16_t>(v));
            put16(out, static_cast<std::uint16_t>(v >> 16));
        }
    }

    bool big_endian_;
    std::vector<std::uint8_t> bytes_;
};

}  // namespace dpscope::test
