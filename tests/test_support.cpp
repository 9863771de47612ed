#include "tests/test_support.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <thread>

#include "capture/hex_log.hpp"
#include "formats/output.hpp"

namespace dpscope::test {

namespace {

std::vector<std::uint8_t> fc_finish(std::vector<std::uint8_t> bytes) {
    bytes[1] = static_cast<std::uint8_t>(bytes.size() - 1);  // LGE: ADR .. BCC
    std::uint8_t bcc = 0;
    for (std::uint8_t b : bytes)
        bcc ^= b;
    bytes.push_back(bcc);
    return bytes;
}

void put_u16(std::vector<std::uint8_t>& bytes, std::uint16_t value) {
    bytes.push_back(static_cast<std::uint8_t>(value >> 8));
    bytes.push_back(static_cast<std::uint8_t>(value & 0xFF));
}

}  // namespace

std::vector<std::uint8_t> fc_process(std::uint8_t address, std::uint16_t pcd1, std::uint16_t pcd2) {
    std::vector<std::uint8_t> bytes{0x02, 0, static_cast<std::uint8_t>(0x80 | address)};
    put_u16(bytes, pcd1);
    put_u16(bytes, pcd2);
    return fc_finish(std::move(bytes));
}

std::vector<std::uint8_t> fc_parameter(std::uint8_t address, std::uint8_t ak, std::uint16_t pnu,
                                       std::uint8_t index, std::uint32_t pwe, std::uint16_t pcd1,
                                       std::uint16_t pcd2) {
    std::vector<std::uint8_t> bytes{0x02, 0, static_cast<std::uint8_t>(0x80 | address)};
    put_u16(bytes, static_cast<std::uint16_t>((ak & 0x0F) << 12 | (pnu & 0x0FFF)));
    put_u16(bytes, index);
    put_u16(bytes, static_cast<std::uint16_t>(pwe >> 16));
    put_u16(bytes, static_cast<std::uint16_t>(pwe & 0xFFFF));
    put_u16(bytes, pcd1);
    put_u16(bytes, pcd2);
    return fc_finish(std::move(bytes));
}

std::vector<std::uint8_t> joined(std::vector<std::uint8_t> header,
                                 const std::vector<std::uint8_t>& rest) {
    header.reserve(header.size() + rest.size());
    for (std::uint8_t b : rest)
        header.push_back(b);
    return header;
}

std::vector<std::uint8_t> hex(std::string_view text) {
    Result<std::vector<std::uint8_t>> bytes = parse_hex_bytes(text);
    EXPECT_TRUE(bytes) << bytes.error();
    return bytes ? std::move(bytes).value() : std::vector<std::uint8_t>{};
}

std::string source_dir() { return DPSCOPE_SOURCE_DIR; }
std::string dpscope_executable() { return DPSCOPE_EXECUTABLE; }

bool wait_until(const std::function<bool()>& done, double seconds) {
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                              std::chrono::duration<double>(seconds));
    while (!done()) {
        if (std::chrono::steady_clock::now() >= deadline) return done();
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return true;
}

std::string read_until(int fd, std::string_view want, double seconds) {
    std::string got;
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                              std::chrono::duration<double>(seconds));
    while (got.find(want) == std::string::npos) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
            deadline - std::chrono::steady_clock::now());
        pollfd p{fd, POLLIN, 0};
        if (left.count() <= 0 || ::poll(&p, 1, static_cast<int>(left.count())) <= 0) break;
        char buffer[4096];
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n <= 0) break;
        got.append(buffer, static_cast<std::size_t>(n));
    }
    return got;
}

namespace {

// The folder of each test that asked for a temporary path, removed with everything in it when
// the test process ends (set DPSCOPE_KEEP_TEST_FILES to keep them for a look after a failure).
// Each test has a folder of its own, made with mkdtemp, so that a test inspecting its folder
// (for staging files left behind, say) never sees another test's files, whether the other test
// runs in this process or in a parallel one.
struct TempFolders {
    std::string test;    // the test the current folder belongs to
    std::string folder;  // "" until the test asks
    std::vector<std::string> made;
    ~TempFolders() {
        if (std::getenv("DPSCOPE_KEEP_TEST_FILES")) return;
        for (const std::string& path : made) {
            std::error_code ignored;
            std::filesystem::remove_all(path, ignored);  // symbolic links themselves, not targets
        }
    }
};

TempFolders& temp_folders() {
    static TempFolders folders;
    return folders;
}

}  // namespace

std::string temp_folder() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string test = info ? std::string(info->test_suite_name()) + "." + info->name() : "test";
    std::replace(test.begin(), test.end(), '/', '_');  // parameterised tests: "Suite/Case.Test/0"
    TempFolders& folders = temp_folders();
    if (folders.folder.empty() || folders.test != test) {
        const char* base = std::getenv("TEST_TMPDIR");
        std::string pattern =
            std::string(base && *base ? base : "/tmp") + "/dpscope-" + test + "-XXXXXX";
        if (::mkdtemp(pattern.data()) == nullptr) {
            ADD_FAILURE() << "cannot make a temporary folder " << pattern << ": "
                          << std::strerror(errno);
            return "/nonexistent";
        }
        folders.test = test;
        folders.folder = pattern;
        folders.made.push_back(pattern);
    }
    return folders.folder;
}

std::string temp_path(std::string_view name) {
    static int counter = 0;
    return temp_folder() + "/" + std::to_string(counter++) + "-" + std::string(name);
}

void write_file(const std::string& path, const std::vector<std::uint8_t>& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()),
              static_cast<std::streamsize>(bytes.size()));
    ASSERT_TRUE(out.good()) << "cannot write " << path;
}

void write_text_file(const std::string& path, std::string_view text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
    ASSERT_TRUE(out.good()) << "cannot write " << path;
}

std::vector<std::uint8_t> read_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), {});
}

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream content;
    content << in.rdbuf();
    return content.str();
}

std::string output_text(const std::function<void(Output&)>& write) {
    char* data = nullptr;
    std::size_t size = 0;
    FILE* file = open_memstream(&data, &size);
    EXPECT_NE(file, nullptr);
    if (file == nullptr) return {};
    {
        Output out(file);
        write(out);
        EXPECT_TRUE(out.flush());
    }
    std::fclose(file);
    std::string text(data, size);
    std::free(data);
    return text;
}

namespace {

std::string shell_quote(const std::string& text) {
    std::string quoted = "'";
    for (char c : text) {
        if (c == '\'')
            quoted += "'\\''";
        else
            quoted += c;
    }
    return quoted + "'";
}

}  // namespace

CommandResult run_dpscope(const std::vector<std::string>& args, const std::string& input) {
    std::string out_path = temp_path("stdout");
    std::string err_path = temp_path("stderr");
    std::string in_path = "/dev/null";
    if (!input.empty()) {
        in_path = temp_path("stdin");
        write_text_file(in_path, input);
    }
    // Built with append(): GCC 12 warns falsely (-Wrestrict) on chains of operator+ at -O3.
    std::string command = "cd ";
    command.append(shell_quote(source_dir())).append(" && TZ=UTC LANG=C LC_ALL=C ");
    command.append(shell_quote(dpscope_executable()));
    for (const std::string& arg : args)
        command.append(" ").append(shell_quote(arg));
    command.append(" < ").append(shell_quote(in_path));
    command.append(" > ").append(shell_quote(out_path));
    command.append(" 2> ").append(shell_quote(err_path));
    int status = std::system(command.c_str());
    CommandResult result;
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    result.out = slurp(out_path);
    result.err = slurp(err_path);
    std::remove(out_path.c_str());
    std::remove(err_path.c_str());
    if (in_path != "/dev/null") std::remove(in_path.c_str());
    return result;
}

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        lines.push_back(line);
    return lines;
}

termios settings_of(const std::string& path) {
    termios tio;
    std::memset(&tio, 0, sizeof tio);
    int fd = open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK);
    EXPECT_GE(fd, 0) << path;
    EXPECT_EQ(tcgetattr(fd, &tio), 0);
    close(fd);
    return tio;
}

bool same_settings(const termios& a, const termios& b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

std::size_t live_processes_in_group(pid_t group) {
    std::size_t live = 0;
    for (const auto& entry : std::filesystem::directory_iterator("/proc")) {
        const std::string stat = slurp(entry.path().string() + "/stat");
        // pid (comm) state ppid pgrp ...: comm may hold spaces and parentheses.
        const std::size_t close = stat.rfind(')');
        if (close == std::string::npos) continue;
        std::istringstream rest(stat.substr(close + 1));
        char state = 0;
        long parent = 0;
        long pgrp = 0;
        if (rest >> state >> parent >> pgrp && pgrp == group && state != 'Z') ++live;
    }
    return live;
}

bool wait_for_processes_in_group(pid_t group, std::size_t count) {
    return wait_until([&] { return live_processes_in_group(group) == count; });
}

PseudoTerminal::PseudoTerminal() {
    int slave_fd = -1;
    char name[128] = {};
    EXPECT_EQ(openpty(&master, &slave_fd, name, nullptr, nullptr), 0);
    fcntl(master, F_SETFD, FD_CLOEXEC);
    slave = name;
    close(slave_fd);
}

void PseudoTerminal::close_master() {
    if (master >= 0) close(master);
    master = -1;
}

void PseudoTerminal::write(const std::vector<std::uint8_t>& bytes) const {
    ASSERT_EQ(::write(master, bytes.data(), bytes.size()), static_cast<ssize_t>(bytes.size()));
}

}  // namespace dpscope::test
