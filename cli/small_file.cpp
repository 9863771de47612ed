#include "cli/small_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace dpscope::cli {

Result<std::string> read_small_file(const std::string& path, std::size_t max_bytes,
                                    std::string_view option, std::string_view what) {
    // A settings file is a regular file of a few lines: a device (/dev/zero), FIFO or directory
    // is refused before anything is read (opened without waiting, as a FIFO would wait for a
    // writer), and a file is read up to max_bytes.
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        return Error{fmt::format("{} {}: cannot read: {}", option, path, std::strerror(errno))};
    struct stat info {};
    if (::fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) {
        ::close(fd);
        return Error{fmt::format("{} {}: not a regular file; give {}", option, path, what)};
    }
    std::FILE* file = ::fdopen(fd, "rb");
    if (file == nullptr) {
        const int error = errno;
        ::close(fd);
        return Error{fmt::format("{} {}: cannot read: {}", option, path, std::strerror(error))};
    }
    std::string text;
    char buffer[4096];
    std::size_t n = 0;
    while ((n = std::fread(buffer, 1, sizeof buffer, file)) > 0) {
        text.append(buffer, n);
        if (text.size() > max_bytes) {
            std::fclose(file);
            return Error{fmt::format("{} {}: larger than {} KiB, too large for {}", option, path,
                                     max_bytes / 1024, what)};
        }
    }
    const bool failed = std::ferror(file) != 0;
    const int error = errno;
    std::fclose(file);
    if (failed)
        return Error{fmt::format("{} {}: cannot read: {}", option, path, std::strerror(error))};
    return text;
}

std::string_view trimmed(std::string_view text) noexcept {
    const std::size_t first = text.find_first_not_of(" \t\r");
    if (first == std::string_view::npos) return {};
    const std::size_t last = text.find_last_not_of(" \t\r");
    return text.substr(first, last - first + 1);
}

std::vector<std::string_view> settings_lines(std::string_view text) {
    std::vector<std::string_view> lines;
    for (std::size_t at = 0; at < text.size();) {
        std::size_t end = text.find('\n', at);
        if (end == std::string_view::npos) end = text.size();
        lines.push_back(trimmed(text.substr(at, end - at)));
        at = end + 1;
    }
    return lines;
}

}  // namespace dpscope::cli
