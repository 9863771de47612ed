// Helpers shared by the test files.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "decoder/byte_reader.hpp"

namespace dpscope::test {

// "68 07 07 68" (or "6807 0768", "0x68,0x07") -> bytes; a malformed string fails the test.
std::vector<std::uint8_t> hex(std::string_view text);

// The repository's root directory and the dpscope executable built with the tests.
std::string source_dir();
std::string dpscope_executable();

// A fresh path under the test's temporary directory (the file does not exist yet).
std::string temp_path(std::string_view name);
void write_file(const std::string& path, const std::vector<std::uint8_t>& bytes);
void write_text_file(const std::string& path, std::string_view text);
std::vector<std::uint8_t> read_file(const std::string& path);

struct CommandResult {
    int exit_code = -1;
    std::string out;  // standard output
    std::string err;  // standard error
};

// Runs dpscope with `args` (each element one argument), standard input from `input` (or
// /dev/null when empty), in the source directory, with TZ=UTC LANG=C.
CommandResult run_dpscope(const std::vector<std::string>& args, const std::string& input = {});

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

}  // namespace dpscope::test
