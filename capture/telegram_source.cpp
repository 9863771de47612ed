#include "capture/telegram_source.hpp"

#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <vector>

#include "capture/pcap_source.hpp"
#include "capture/stream_source.hpp"

namespace dpscope {

void TelegramSource::report(Severity severity, std::string message) {
    if (issue_handler_) issue_handler_(InputIssue{severity, std::move(message)});
}

namespace {

constexpr std::size_t kDetectBytes = 4096;

// A FILE* that first replays the bytes read for format detection and then continues with the
// underlying stream, so pipes (standard input) need no seeking.
struct ReplayCookie {
    std::vector<std::uint8_t> head;
    std::size_t position = 0;
    FILE* rest = nullptr;
};

ssize_t replay_read(void* cookie, char* buffer, std::size_t size) {
    auto* replay = static_cast<ReplayCookie*>(cookie);
    if (replay->position < replay->head.size()) {
        std::size_t n = std::min(size, replay->head.size() - replay->position);
        std::memcpy(buffer, replay->head.data() + replay->position, n);
        replay->position += n;
        return static_cast<ssize_t>(n);
    }
    // read(2), not fread: hand over what has arrived, so a pipe or a terminal is decoded as it
    // is written instead of when a buffer is full.
    for (;;) {
        ssize_t n = ::read(fileno(replay->rest), buffer, size);
        if (n >= 0 || errno != EINTR) return n;
    }
}

int replay_close(void* cookie) {
    auto* replay = static_cast<ReplayCookie*>(cookie);
    int rc = replay->rest == stdin ? 0 : std::fclose(replay->rest);
    delete replay;
    return rc;
}

// Reads the first bytes for format detection: at least a pcap magic's worth unless the input
// ends first, without waiting for more than has arrived after that.
bool read_head(int fd, std::vector<std::uint8_t>& head) {
    head.resize(kDetectBytes);
    std::size_t got = 0;
    while (got < 4) {
        ssize_t n = ::read(fd, head.data() + got, kDetectBytes - got);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return false;
        if (n == 0) break;
        got += static_cast<std::size_t>(n);
    }
    head.resize(got);
    return true;
}

}  // namespace

OpenResult open_source(const std::string& path, InputFormat format) {
    OpenResult result;
    bool from_stdin = path == "-";
    std::string name = from_stdin ? std::string("<stdin>") : path;
    FILE* file = from_stdin ? stdin : std::fopen(path.c_str(), "rb");
    if (!file) {
        result.error = fmt::format("{}: cannot open: {}", name, std::strerror(errno));
        return result;
    }
    struct stat info {};
    if (fstat(fileno(file), &info) == 0 && S_ISDIR(info.st_mode)) {
        std::fclose(file);
        result.error = fmt::format("{}: is a directory, not a capture file", name);
        return result;
    }
    auto* replay = new ReplayCookie;
    replay->rest = file;
    // A forced format needs no look at the content (and a typed hex log must not wait for 4 KiB).
    bool classic_pcap = false;
    if (format == InputFormat::Auto || format == InputFormat::Pcap ||
        format == InputFormat::Pcapng) {
        if (!read_head(fileno(file), replay->head)) {
            result.error = fmt::format("{}: cannot read: {}", name, std::strerror(errno));
            replay_close(replay);
            return result;
        }
        classic_pcap = detect_input_format(replay->head) == InputFormat::Pcap;
        if (format == InputFormat::Auto) format = detect_input_format(replay->head);
    }
    // A regular file goes back to its start and is read as it is: glibc reads a plain file's
    // small records (libpcap's 16-byte headers) much faster than through a cookie stream.
    FILE* stream = nullptr;
    if (!from_stdin && S_ISREG(info.st_mode) && ::lseek(fileno(file), 0, SEEK_SET) == 0) {
        delete replay;
        stream = file;
    } else {
        stream = fopencookie(replay, "rb",
                             cookie_io_functions_t{replay_read, nullptr, nullptr, replay_close});
    }
    if (!stream) {
        result.error = fmt::format("{}: cannot set up reading: {}", name, std::strerror(errno));
        replay_close(replay);
        return result;
    }
    std::setvbuf(stream, nullptr, _IOFBF, 1 << 16);
    switch (format) {
        case InputFormat::Pcap:
        case InputFormat::Pcapng:
            result.source = open_pcap_source(stream, name, classic_pcap, result.error);
            break;
        case InputFormat::Hex: result.source = make_hex_source(stream, name); break;
        case InputFormat::Raw:
        case InputFormat::Serial:
        case InputFormat::Auto: result.source = make_raw_source(stream, name); break;
    }
    return result;
}

std::unique_ptr<TelegramSource> memory_source(std::string display_name, Bytes bytes) {
    return make_memory_source(std::move(display_name), bytes);
}

}  // namespace dpscope
