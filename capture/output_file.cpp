#include "capture/output_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

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

}  // namespace

Result<std::unique_ptr<PendingOutputFile>> PendingOutputFile::open(const std::string& path) {
    std::unique_ptr<PendingOutputFile> out(new PendingOutputFile());
    if (path == "-") {
        out->file_ = stdout;
        out->name_ = "<stdout>";
        out->to_stdout_ = true;
        return out;
    }
    out->name_ = path;
    // A symbolic link is followed: the file it names is replaced, the link stays.
    std::string target = path;
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
    int fd = ::mkstemp(pattern.data());
    if (fd < 0) {
        return Error{fmt::format("{}: cannot open for writing: {}", path, std::strerror(errno))};
    }
    // mkstemp makes the file private; give it the mode the target has, or a new file's mode.
    ::fchmod(fd, exists ? (info.st_mode & 07777) : creation_mode());
    out->file_ = ::fdopen(fd, "wb");
    if (!out->file_) {
        Error error{fmt::format("{}: cannot open for writing: {}", path, std::strerror(errno))};
        ::close(fd);
        ::unlink(pattern.c_str());
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
    return error;
}

Result<void> PendingOutputFile::commit() {
    done_ = true;
    if (Result<void> closed = close_stream(); !closed) return closed;
    if (temporary_.empty()) return {};
    if (::rename(temporary_.c_str(), target_.c_str()) != 0) {
        Error error{fmt::format("{}: cannot replace the file: {}", name_, std::strerror(errno))};
        ::unlink(temporary_.c_str());
        return error;
    }
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
    if (::rename(temporary_.c_str(), partial.c_str()) != 0) {
        Error error{fmt::format("{}: cannot write {}: {}", name_, partial, std::strerror(errno))};
        ::unlink(temporary_.c_str());
        return error;
    }
    return partial;
}

void PendingOutputFile::discard() noexcept {
    done_ = true;
    if (file_ && !to_stdout_) std::fclose(file_);
    file_ = nullptr;
    if (!temporary_.empty()) ::unlink(temporary_.c_str());
}

bool same_file(const std::string& a, const std::string& b) {
    struct stat info_a {};
    struct stat info_b {};
    if (::stat(a.c_str(), &info_a) == 0 && ::stat(b.c_str(), &info_b) == 0)
        return info_a.st_dev == info_b.st_dev && info_a.st_ino == info_b.st_ino;
    std::error_code error_a, error_b;
    auto canonical_a = std::filesystem::weakly_canonical(a, error_a);
    auto canonical_b = std::filesystem::weakly_canonical(b, error_b);
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
