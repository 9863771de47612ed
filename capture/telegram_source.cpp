#include "capture/telegram_source.hpp"

#include <fmt/format.h>
#include <poll.h>
#include <stdio_ext.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <vector>

#include "capture/pcap_source.hpp"
#include "capture/stream_source.hpp"
#include "capture/text_log.hpp"
#include "core/counted.hpp"

namespace dpscope {

namespace {

// Time kinds are reported once: the first says what the problem is, the rest are counted.
std::uint64_t issues_shown(IssueKind kind) {
    return kind == IssueKind::TimeBackwards || kind == IssueKind::TimeJump ? 1 : kMaxIssuesShown;
}

// "2.500 s" for a time difference.
std::string seconds_text(std::uint64_t ns) {
    return fmt::format("{}.{:03} s", ns / 1'000'000'000, ns % 1'000'000'000 / 1'000'000);
}

}  // namespace

void TelegramSource::report(Severity severity, std::string message, IssueKind kind,
                            std::uint64_t bytes) {
    if (kind != IssueKind::Other) {
        Counted& counted = counted_[static_cast<std::size_t>(kind)];
        if (++counted.issues > issues_shown(kind)) {
            ++counted.hidden;
            counted.hidden_bytes += bytes;
            return;
        }
    }
    if (issue_handler_) issue_handler_(InputIssue{severity, std::move(message), kind});
}

void TelegramSource::count_hidden(IssueKind kind, std::uint64_t issues, std::uint64_t bytes) {
    Counted& counted = counted_[static_cast<std::size_t>(kind)];
    counted.issues += issues;
    counted.hidden += issues;
    counted.hidden_bytes += bytes;
}

void TelegramSource::finish_reporting() {
    if (reporting_finished_) return;
    reporting_finished_ = true;
    for (std::size_t i = 0; i < kIssueKinds; ++i) {
        const Counted& c = counted_[i];
        if (c.hidden == 0) continue;
        std::string what;
        switch (static_cast<IssueKind>(i)) {
            case IssueKind::SkippedBytes:
                what = fmt::format("{} of skipped bytes not shown ({})",
                                   counted(c.hidden, "more run", "more runs"),
                                   counted(c.hidden_bytes, "byte", "bytes"));
                break;
            case IssueKind::Snapshot:
                what = fmt::format("{} cut short by the snapshot length not shown",
                                   counted(c.hidden, "more record", "more records"));
                break;
            case IssueKind::HexSyntax:
                what = fmt::format("{} with tokens that are no hex bytes not shown",
                                   counted(c.hidden, "more line", "more lines"));
                break;
            case IssueKind::TimeBackwards:
                what = fmt::format("time went backwards {}",
                                   counted(c.hidden, "more time", "more times"));
                break;
            case IssueKind::TimeJump:
                what = fmt::format("time jumped forward by more than a minute {}",
                                   counted(c.hidden, "more time", "more times"));
                break;
            case IssueKind::Interface:
                what = fmt::format("{} about interfaces not shown",
                                   counted(c.hidden, "more warning", "more warnings"));
                break;
            case IssueKind::BadTime:
                what = fmt::format("{} with unusable timestamps not shown",
                                   counted(c.hidden, "more packet", "more packets"));
                break;
            case IssueKind::Other: continue;
        }
        if (issue_handler_)
            issue_handler_(InputIssue{Severity::Warning, fmt::format("{}: {}", name_, what),
                                      IssueKind::Other});
    }
}

std::uint64_t TelegramSource::bytes_read() const {
    if (position_stream_ == nullptr) return 0;
    const off_t position = ::ftello(position_stream_);
    return position < 0 ? 0 : static_cast<std::uint64_t>(position);
}

bool TelegramSource::next(Record& record) {
    if ((limit_ != 0 && handed_out_ >= limit_) || !read_next(record)) {
        finish_reporting();
        return false;
    }
    ++handed_out_;
    check_time(record);
    return true;
}

void TelegramSource::check_time(const Record& record) {
    if (record.time_ns == kNoTime) return;
    if (last_time_ns_ != kNoTime) {
        if (record.time_ns < last_time_ns_) {
            report(Severity::Warning,
                   fmt::format("{}: frame {}: time goes backwards by {} from frame {}; a capture "
                               "problem (merged or re-stamped capture?): latencies and time-outs "
                               "around it are unreliable",
                               name_, record.number,
                               seconds_text(static_cast<std::uint64_t>(last_time_ns_) -
                                            static_cast<std::uint64_t>(record.time_ns)),
                               last_number_),
                   IssueKind::TimeBackwards);
        } else if (static_cast<std::uint64_t>(record.time_ns) -
                       static_cast<std::uint64_t>(last_time_ns_) >
                   static_cast<std::uint64_t>(kTimeJumpNs)) {
            report(Severity::Warning,
                   fmt::format("{}: frame {}: time jumps forward by {} from frame {} (more than "
                               "a minute); a capture problem (a gap in the recording or a clock "
                               "step): latencies and time-outs across it are unreliable",
                               name_, record.number,
                               seconds_text(static_cast<std::uint64_t>(record.time_ns) -
                                            static_cast<std::uint64_t>(last_time_ns_)),
                               last_number_),
                   IssueKind::TimeJump);
        }
    }
    last_time_ns_ = record.time_ns;
    last_number_ = record.number;
}

namespace {

constexpr std::size_t kDetectBytes = 4096;
// How long a live input (pipe, terminal) is waited for after its first bytes to choose the bus.
constexpr int kBusChoiceWaitMs = 100;

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
// ends first, without waiting for more than has arrived after that. `name` is for the error.
Result<std::vector<std::uint8_t>> read_head(int fd, const std::string& name) {
    std::vector<std::uint8_t> head(kDetectBytes);
    std::size_t got = 0;
    while (got < 4) {
        ssize_t n = ::read(fd, head.data() + got, kDetectBytes - got);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return Error{fmt::format("{}: cannot read: {}", name, std::strerror(errno))};
        if (n == 0) break;
        got += static_cast<std::size_t>(n);
    }
    head.resize(got);
    return head;
}

}  // namespace

namespace {

// The input kind of `head`: `format` when forced; detected when Auto; with `hex_or_text`, Text
// when detected so and Hex otherwise (SourceOptions::hex_may_be_text).
InputFormat kind_of(Bytes head, InputFormat format, bool hex_or_text) {
    if (hex_or_text)
        return detect_input_format(head) == InputFormat::Text ? InputFormat::Text
                                                              : InputFormat::Hex;
    return format == InputFormat::Auto ? detect_input_format(head) : format;
}

// Reads the first bytes until they choose the bus (see choose_bus): the whole input or
// kBusChoiceBytes, or less of a stream still arriving once they decide. `format`: forced, or
// Auto (detected from the bytes), or Hex or Text (`hex_or_text`).
Result<std::vector<std::uint8_t>> read_head_for_bus(int fd, const std::string& name,
                                                    InputFormat format, bool hex_or_text,
                                                    BusChoice& choice, bool live) {
    // A regular file smaller than kBusChoiceBytes needs no more than its size (and one byte more,
    // so that the read that finds its end is the same as with a full-size buffer).
    std::size_t capacity = kBusChoiceBytes;
    struct stat info {};
    if (!live && ::fstat(fd, &info) == 0 && S_ISREG(info.st_mode)) {
        const off_t at = ::lseek(fd, 0, SEEK_CUR);
        if (at >= 0 && info.st_size >= at)
            capacity = std::min(capacity, static_cast<std::size_t>(info.st_size - at) + 1);
    }
    std::vector<std::uint8_t> head(capacity);
    std::size_t got = 0;
    bool end = false;
    for (;;) {
        // A pipe or terminal (live): once bytes have come, what arrives within kBusChoiceWaitMs
        // more is looked at, and the choice is made on that, so a live stream is not held back.
        if (live && got >= 4) {
            pollfd waiting{fd, POLLIN, 0};
            int ready = ::poll(&waiting, 1, kBusChoiceWaitMs);
            if (ready < 0 && errno == EINTR) continue;
            if (ready <= 0) {
                choice = choose_bus(Bytes(head.data(), got),
                                    kind_of(Bytes(head.data(), got), format, hex_or_text), true);
                break;
            }
        }
        ssize_t n = ::read(fd, head.data() + got, capacity - got);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return Error{fmt::format("{}: cannot read: {}", name, std::strerror(errno))};
        got += static_cast<std::size_t>(n);
        end = n == 0 || got == kBusChoiceBytes;
        if (got == capacity && !end) {  // the file grew: read on as with a full-size buffer
            capacity = kBusChoiceBytes;
            head.resize(capacity);
        }
        Bytes bytes(head.data(), got);
        if (got < 4 && !end) continue;
        choice = choose_bus(bytes, kind_of(bytes, format, hex_or_text), end);
        if (end || !choice.need_more) break;
    }
    head.resize(got);
    return head;
}

// The source of `format` reading `stream` (which it then owns).
OpenResult open_stream(FILE* stream, const std::string& name, InputFormat format, bool detected,
                       bool classic_pcap, bool pcapng, const ProtocolDescriptor& protocol,
                       const SourceOptions& options) {
    const FramingRules& rules = protocol.framing;
    switch (format) {
        case InputFormat::Pcap:
        case InputFormat::Pcapng:
            return pcapng ? open_pcapng_source(stream, name, protocol)
                          : open_pcap_source(stream, name, classic_pcap, protocol);
        case InputFormat::Hex:
            return make_hex_source(stream, name, detected, rules, options.max_hex_repeat_bytes);
        case InputFormat::Text: return make_text_source(stream, name, rules);
        case InputFormat::Raw:
        case InputFormat::Serial:
        case InputFormat::Auto: break;
    }
    return make_raw_source(stream, name, detected, rules);
}

OpenResult open_source_of(const std::string& path, InputFormat format,
                          const ProtocolDescriptor* chosen, BusChoice* choice,
                          const SourceOptions& options) {
    bool from_stdin = path == "-";
    std::string name = from_stdin ? std::string("<stdin>") : path;
    FILE* file = from_stdin ? stdin : std::fopen(path.c_str(), "rb");
    if (!file) return Error{fmt::format("{}: cannot open: {}", name, std::strerror(errno))};
    struct stat info {};
    if (fstat(fileno(file), &info) == 0 && S_ISDIR(info.st_mode)) {
        std::fclose(file);
        return Error{fmt::format("{}: is a directory, not a capture file", name)};
    }
    // `dpscope hex` on standard input: a hex log, or a VLT 2000 text log (SourceOptions).
    const bool hex_or_text = format == InputFormat::Hex && options.hex_may_be_text;
    if (hex_or_text) format = InputFormat::Auto;
    const bool detected = format == InputFormat::Auto && !hex_or_text;
    auto* replay = new ReplayCookie;
    replay->rest = file;
    // A forced format needs no look at the content (and a typed hex log must not wait for 4 KiB).
    bool classic_pcap = false;
    bool pcapng = false;
    if (!chosen) {
        // The bus is chosen from the first bytes, whatever the format.
        Result<std::vector<std::uint8_t>> head = read_head_for_bus(
            fileno(file), name, format, hex_or_text, *choice, !S_ISREG(info.st_mode));
        if (!head) {
            replay_close(replay);
            return Error{head.error()};
        }
        replay->head = std::move(head).value();
        chosen = choice->protocol;
        classic_pcap = detect_input_format(replay->head) == InputFormat::Pcap;
        pcapng = detect_input_format(replay->head) == InputFormat::Pcapng;
        format = kind_of(replay->head, format, hex_or_text);
    } else if (format == InputFormat::Auto || format == InputFormat::Pcap ||
               format == InputFormat::Pcapng) {
        Result<std::vector<std::uint8_t>> head = read_head(fileno(file), name);
        if (!head) {
            replay_close(replay);
            return Error{head.error()};
        }
        replay->head = std::move(head).value();
        classic_pcap = detect_input_format(replay->head) == InputFormat::Pcap;
        pcapng = detect_input_format(replay->head) == InputFormat::Pcapng;
        format = kind_of(replay->head, format, hex_or_text);
        if (choice) {
            const CaptureLabel label = read_capture_label(replay->head);
            choice->tagged = label.tagged;
            choice->line = label.line;
        }
    }
    // A text log holds VLT 2000 telegrams ('<' ... '>'): no other bus's framing reads it.
    if (const ProtocolDescriptor* owner = text_log_protocol();
        owner && format == InputFormat::Text && chosen != owner) {
        replay_close(replay);
        return Error{fmt::format(
            "{}: a text log of telegrams ({}{}) is {} traffic; --bus {} cannot read it "
            "(--input-format hex reads a log of hex bytes, raw a byte stream)",
            name, owner->text_log_shape, detected ? ", as detected from its content" : "",
            owner->traffic_name, chosen->name)};
    }
    const ProtocolDescriptor& protocol = *chosen;
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
        std::string error =
            fmt::format("{}: cannot set up reading: {}", name, std::strerror(errno));
        replay_close(replay);
        return Error{std::move(error)};
    }
    std::setvbuf(stream, nullptr, _IOFBF, 1 << 16);
    // Only this source's thread reads the stream: stdio need not lock it for each of libpcap's
    // two freads a record (a quarter of decode -q's time went to the locked fread; issue 31).
    __fsetlocking(stream, FSETLOCKING_BYCALLER);
    OpenResult opened =
        open_stream(stream, name, format, detected, classic_pcap, pcapng, protocol, options);
    // The position is read from a regular file's own stream (a cookie stream cannot tell it).
    if (opened && stream == file)
        (*opened)->watch_position(stream, static_cast<std::uint64_t>(info.st_size));
    return opened;
}

}  // namespace

OpenResult open_source(const std::string& path, InputFormat format, const ProtocolDescriptor& protocol,
                       const SourceOptions& options) {
    return open_source_of(path, format, &protocol, nullptr, options);
}

OpenResult open_source(const std::string& path, InputFormat format, const ProtocolDescriptor* protocol,
                       BusChoice& choice, const SourceOptions& options) {
    choice = BusChoice{};
    if (protocol) choice.protocol = protocol;
    return open_source_of(path, format, protocol, &choice, options);
}

std::unique_ptr<TelegramSource> memory_source(std::string display_name, Bytes bytes,
                                              const ProtocolDescriptor& protocol) {
    return make_memory_source(std::move(display_name), bytes, protocol.framing);
}

}  // namespace dpscope
