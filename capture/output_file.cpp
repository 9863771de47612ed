#include "capture/output_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <system_error>

namespace dpscope {

namespace {

// The directory part of `path` ("." when it has none).
std::string directory_of(const std::string& path) {
    std::size_t slash = path.rfind('/');
    if (slash == std::string::npos) return ".";
    if (slash == 0) return "/";
    return path.substr(0, slash);
}

std::string base_name_of(const std::string& path) {
    std::size_t slash = path.rfind('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

mode_t creation_mode() {
    mode_t mask = umask(0);
    umask(mask);
    return static_cast<mode_t>(0666 & ~mask);
}

// The temporary files of the outputs not yet committed or discarded, where a signal handler can
// reach them: fixed storage, written before a slot is marked in use.
struct StagedSlot {
    std::atomic<int> state{0};  // 0 free, 1 being filled, 2 holds a path
    char path[PATH_MAX] = {};
};
constexpr int kStagedSlots = 16;
StagedSlot g_staged[kStagedSlots];
std::atomic<pid_t> g_staged_owner{0};  // a forked child (an --alarm command) removes nothing
static_assert(std::atomic<int>::is_always_lock_free && std::atomic<pid_t>::is_always_lock_free);

// A slot holding `path`, or -1 when all are taken (the file is then not removed on a signal).
int register_staged(const std::string& path) {
    if (path.size() >= PATH_MAX) return -1;
    for (int i = 0; i < kStagedSlots; ++i) {
        int expected = 0;
        if (!g_staged[i].state.compare_exchange_strong(expected, 1)) continue;
        std::memcpy(g_staged[i].path, path.c_str(), path.size() + 1);
        g_staged_owner.store(::getpid());
        g_staged[i].state.store(2);
        return i;
    }
    return -1;
}

void unregister_staged(int& slot) {
    if (slot >= 0) g_staged[slot].state.store(0);
    slot = -1;
}

constexpr int kEndingSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE};

extern "C" void remove_staged_and_end(int signal_number) {
    PendingOutputFile::remove_all_after_signal();
    ::signal(signal_number, SIG_DFL);
    ::raise(signal_number);  // delivered when the handler returns: the process ends by it
}

// Installs remove_staged_and_end for the ending signals whose action is the default one (not
// for one that is ignored, as nohup does, or handled).
void install_signal_cleanup() {
    static bool installed = false;
    if (installed) return;
    installed = true;
    for (int number : kEndingSignals) {
        struct sigaction current {};
        if (::sigaction(number, nullptr, &current) != 0) continue;
        if ((current.sa_flags & SA_SIGINFO) != 0 || current.sa_handler != SIG_DFL) continue;
        struct sigaction action {};
        action.sa_handler = remove_staged_and_end;
        sigemptyset(&action.sa_mask);
        action.sa_flags = 0;
        ::sigaction(number, &action, nullptr);
    }
}

// Blocks the ending signals while it lives: a temporary file is made and registered at once.
class EndingSignalsBlocked {
  public:
    EndingSignalsBlocked() {
        sigset_t blocked;
        sigemptyset(&blocked);
        for (int number : kEndingSignals)
            sigaddset(&blocked, number);
        ::sigprocmask(SIG_BLOCK, &blocked, &previous_);
    }
    ~EndingSignalsBlocked() { ::sigprocmask(SIG_SETMASK, &previous_, nullptr); }
    EndingSignalsBlocked(const EndingSignalsBlocked&) = delete;
    EndingSignalsBlocked& operator=(const EndingSignalsBlocked&) = delete;

  private:
    sigset_t previous_;
};

}  // namespace

void PendingOutputFile::remove_all_after_signal() noexcept {
    if (::getpid() != g_staged_owner.load()) return;
    for (StagedSlot& slot : g_staged)
        if (slot.state.load() == 2) ::unlink(slot.path);
}

Result<std::unique_ptr<PendingOutputFile>> PendingOutputFile::open(const std::string& path) {
    std::unique_ptr<PendingOutputFile> out(new PendingOutputFile());
    if (path == "-") {
        out->file_ = stdout;
        out->name_ = "<stdout>";
        out->to_stdout_ = true;
        return out;
    }
    out->name_ = path;
    // A symbolic link is followed: the file it names is replaced (or made), the link stays.
    std::string target = link_target(path);
    struct stat info {};
    bool exists = ::stat(path.c_str(), &info) == 0;
    if (exists) {
        if (char* real = ::realpath(path.c_str(), nullptr)) {
            target = real;
            std::free(real);
        }
    }
    if (exists && !S_ISREG(info.st_mode)) {
        // A device, FIFO or terminal: write to it as it is.
        out->file_ = std::fopen(path.c_str(), "wb");
        if (!out->file_) {
            return Error{
                fmt::format("{}: cannot open for writing: {}", path, std::strerror(errno))};
        }
        return out;
    }
    if (exists && ::access(target.c_str(), W_OK) != 0) {
        return Error{fmt::format("{}: cannot open for writing: {}", path, std::strerror(errno))};
    }
    std::string pattern = directory_of(target) + "/." + base_name_of(target) + ".dpscope-XXXXXX";
    install_signal_cleanup();
    int fd = -1;
    {
        EndingSignalsBlocked blocked;  // a signal now would find the file made but not registered
        fd = ::mkstemp(pattern.data());
        if (fd >= 0) out->slot_ = register_staged(pattern);
    }
    if (fd < 0) {
        return Error{fmt::format("{}: cannot open for writing: {}", path, std::strerror(errno))};
    }
    // The file replaced keeps its owner where that is permitted (root replacing a user's file;
    // a group the user is in), and mkstemp makes the file private: give it the mode the target
    // has (after the owner, which may clear set-ID bits), or a new file's mode.
    if (exists && (info.st_uid != ::geteuid() || info.st_gid != ::getegid())) {
        if (::fchown(fd, info.st_uid, info.st_gid) != 0) (void)::fchown(fd, -1, info.st_gid);
    }
    ::fchmod(fd, exists ? (info.st_mode & 07777) : creation_mode());
    out->file_ = ::fdopen(fd, "wb");
    if (!out->file_) {
        Error error{fmt::format("{}: cannot open for writing: {}", path, std::strerror(errno))};
        ::close(fd);
        ::unlink(pattern.c_str());
        unregister_staged(out->slot_);
        return error;
    }
    out->target_ = target;
    out->temporary_ = pattern;
    out->target_existed_ = exists;
    return out;
}

PendingOutputFile::~PendingOutputFile() {
    if (!done_) discard();
}

Result<void> PendingOutputFile::close_stream() {
    if (!file_) return {};
    const bool closed = to_stdout_ ? std::fflush(file_) == 0 : std::fclose(file_) == 0;
    file_ = nullptr;
    if (closed) return {};
    Error error{fmt::format("{}: write failed: {}", name_, std::strerror(errno))};
    if (!temporary_.empty()) ::unlink(temporary_.c_str());
    unregister_staged(slot_);
    return error;
}

Result<void> PendingOutputFile::commit() {
    done_ = true;
    if (Result<void> closed = close_stream(); !closed) return closed;
    if (temporary_.empty()) return {};
    const bool renamed = ::rename(temporary_.c_str(), target_.c_str()) == 0;
    Error error{fmt::format("{}: cannot replace the file: {}", name_, std::strerror(errno))};
    if (!renamed) ::unlink(temporary_.c_str());
    unregister_staged(slot_);
    if (!renamed) return error;
    return {};
}

Result<std::string> PendingOutputFile::keep_beside(const std::vector<std::string>& inputs) {
    if (temporary_.empty()) {
        if (Result<void> written = commit(); !written) return Error{written.error()};
        return std::string();
    }
    const std::string partial = target_ + ".partial";
    if (!check_not_an_input(inputs, partial, name_)) {
        discard();
        return Error{
            fmt::format("{}: cannot keep what was written: {} is the input", name_, partial)};
    }
    done_ = true;
    if (Result<void> closed = close_stream(); !closed) return Error{closed.error()};
    const bool renamed = ::rename(temporary_.c_str(), partial.c_str()) == 0;
    Error error{fmt::format("{}: cannot write {}: {}", name_, partial, std::strerror(errno))};
    if (!renamed) ::unlink(temporary_.c_str());
    unregister_staged(slot_);
    if (!renamed) return error;
    return partial;
}

void PendingOutputFile::discard() noexcept {
    done_ = true;
    if (file_ && !to_stdout_) std::fclose(file_);
    file_ = nullptr;
    if (!temporary_.empty()) ::unlink(temporary_.c_str());
    unregister_staged(slot_);
}

std::string link_target(const std::string& path) {
    std::string current = path;
    for (int hops = 0; hops < 40; ++hops) {
        struct stat info {};
        if (::lstat(current.c_str(), &info) != 0 || !S_ISLNK(info.st_mode)) break;
        std::string target(PATH_MAX, '\0');
        const ssize_t length = ::readlink(current.c_str(), target.data(), target.size());
        if (length <= 0 || static_cast<std::size_t>(length) >= target.size()) break;
        target.resize(static_cast<std::size_t>(length));
        current = target.front() == '/' || current.find('/') == std::string::npos
                      ? target
                      : directory_of(current) + "/" + target;
    }
    return current;
}

bool same_file(const std::string& a, const std::string& b) {
    struct stat info_a {};
    struct stat info_b {};
    const bool a_exists = ::stat(a.c_str(), &info_a) == 0;
    const bool b_exists = ::stat(b.c_str(), &info_b) == 0;
    if (a_exists && b_exists)
        return info_a.st_dev == info_b.st_dev && info_a.st_ino == info_b.st_ino;
    if (a_exists != b_exists) return false;
    // Neither exists yet: where each would be made, after the links that lead there.
    std::error_code error_a, error_b;
    auto canonical_a = std::filesystem::weakly_canonical(link_target(a), error_a);
    auto canonical_b = std::filesystem::weakly_canonical(link_target(b), error_b);
    if (error_a || error_b) return a == b;
    return canonical_a == canonical_b;
}

Result<void> check_not_an_input(const std::vector<std::string>& inputs, const std::string& output,
                                std::string_view output_option) {
    struct stat out_info {};
    bool out_known = output == "-" ? ::fstat(STDOUT_FILENO, &out_info) == 0
                                   : ::stat(output.c_str(), &out_info) == 0;
    // Only a file can be destroyed by writing to it; two opens of one device are no loss.
    if (!out_known || !S_ISREG(out_info.st_mode)) return {};
    for (const std::string& input : inputs) {
        if (input.empty()) continue;
        struct stat in_info {};
        bool in_known = input == "-" ? ::fstat(STDIN_FILENO, &in_info) == 0
                                     : ::stat(input.c_str(), &in_info) == 0;
        if (!in_known || in_info.st_dev != out_info.st_dev || in_info.st_ino != out_info.st_ino)
            continue;
        std::string out_name = output == "-" ? std::string("standard output") : output;
        std::string in_name = input == "-" ? std::string("standard input") : input;
        if (out_name == in_name)
            return Error{
                fmt::format("{} {}: that is the input; writing it would destroy the capture",
                            output_option, out_name)};
        return Error{fmt::format(
            "{} {}: that is the same file as the input {}; writing it would destroy the capture",
            output_option, out_name, in_name)};
    }
    return {};
}

}  // namespace dpscope
