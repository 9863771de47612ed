// The input bytes (after a first choice byte) as a whole capture file, read the way `dpscope
// decode` reads one: written to a temporary file (made once per process, rewritten for every
// input) and opened by name with dpscope's own reader path (capture/telegram_source.hpp
// open_source), with the format and bus the first byte chooses (bits 0-2: auto, pcap, pcapng,
// raw, hex, text, mod 6; bits 3-4: the bus chosen from the content as `decode` without --bus
// does, or PROFIBUS DP, FC, VLT 2000 forced; bit 5: choose_bus judges the bytes as complete or as
// a head still arriving, for a forced bus, which open_source does not choose). Every record is
// pulled, decoded with the bus's decoder and tracked by its tracker; input issues are formatted
// and dropped, as `decode` prints them. One reading a run, and no renderers (they have their own
// targets, fuzz_renderers and fuzz_reports), keep it fast; pcap and pcapng headers with a few
// records fit in the 1 KiB max_len. For the same reason a "*" line of a hex dump stands for at
// most 16 KiB here (SourceOptions), not the 64 MiB dpscope allows: with that, a 1 KiB dump of a
// few "*" lines is hundreds of MiB of telegrams, seconds of work that find nothing new.
//
// Invariants: every record's number follows the last one's, a record of a byte stream (raw, hex,
// text) holds no more bytes than the bus's longest telegram, a record of a raw or text stream or
// a pcap or pcapng file no more than the file (a hex dump's "*" lines may stand for more bytes
// than the dump has), and a source that read the input reports a format other than auto.
#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <span>
#include <string>

#include "capture/telegram_source.hpp"
#include "core/protocol_descriptor.hpp"
#include "core/protocol_lane.hpp"
#include "fuzz/support/fuzz_input.hpp"
#include "protocols/lane_options.hpp"

namespace {

// The temporary file every input is written to: a file in memory (memfd_create), opened by its
// /proc/self/fd name, so that a run costs no disk and leaves nothing behind (libFuzzer ends some
// runs without running destructors). Where memfd_create is missing, a file in /tmp, unlinked at
// once.
struct TempFile {
    std::string path;
    int fd = -1;
    TempFile() {
        fd = ::memfd_create("dpscope-fuzz-capture", 0);
        if (fd < 0) {
            char name[] = "/tmp/dpscope-fuzz-capture-XXXXXX";
            fd = mkstemp(name);
            if (fd < 0) {
                std::perror("fuzz_capture_file: mkstemp");
                std::abort();
            }
            ::unlink(name);
        }
        path = "/proc/self/fd/" + std::to_string(fd);
    }
    ~TempFile() { ::close(fd); }
    void write(const std::uint8_t* data, std::size_t size) const {
        if (::ftruncate(fd, 0) != 0) std::abort();
        std::size_t done = 0;
        while (done < size) {
            ssize_t n = ::pwrite(fd, data + done, size - done, static_cast<off_t>(done));
            if (n <= 0) std::abort();
            done += static_cast<std::size_t>(n);
        }
    }
};

const TempFile& temp_file() {
    static TempFile file;
    return file;
}

void check(bool ok) {
    if (!ok) __builtin_trap();
}

// Pulls every record of `source`, decoding and tracking it with the bus's decoder and tracker.
void read_records(dpscope::TelegramSource& source, const dpscope::ProtocolDescriptor& protocol,
                  std::size_t file_size) {
    using dpscope::InputFormat;
    const dpscope::LaneOptions options;
    std::unique_ptr<dpscope::TelegramDecoder> decoder = protocol.make_decoder(options);
    std::unique_ptr<dpscope::TelegramTracker> tracker = protocol.make_tracker(options);
    dpscope::Record record;
    std::uint64_t last = 0;
    while (source.next(record)) {
        check(record.number > last);
        const InputFormat format = source.format();
        const bool stream =
            format == InputFormat::Raw || format == InputFormat::Hex || format == InputFormat::Text;
        if (stream) check(record.bytes.size() <= protocol.max_telegram_bytes);
        if (format != InputFormat::Hex) check(record.bytes.size() <= file_size);
        last = record.number;
        (void)tracker->track(decoder->decode(record.bytes, record.time_ns, record.number));
    }
    (void)tracker->finish();
    check(source.format() != dpscope::InputFormat::Auto);
    (void)source.name().size();
    (void)source.bytes_skipped();
    (void)source.status();
}

void read_all(const std::string& path, dpscope::InputFormat format,
              const dpscope::ProtocolDescriptor* protocol, std::size_t file_size) {
    dpscope::BusChoice choice;
    dpscope::SourceOptions options;
    options.max_hex_repeat_bytes = 16 * 1024;
    dpscope::OpenResult opened = dpscope::open_source(path, format, protocol, choice, options);
    if (!opened) {
        (void)opened.error().size();
        return;
    }
    dpscope::TelegramSource& source = *opened.value();
    std::size_t issue_bytes = 0;
    source.on_issue(
        [&issue_bytes](const dpscope::InputIssue& issue) { issue_bytes += issue.message.size(); });
    read_records(source, *choice.protocol, file_size);
    (void)source.link_type();
    (void)source.unusable_reason();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using dpscope::InputFormat;
    static constexpr InputFormat kFormats[] = {InputFormat::Auto,   InputFormat::Pcap,
                                               InputFormat::Pcapng, InputFormat::Raw,
                                               InputFormat::Hex,    InputFormat::Text};
    dpscope::fuzz::FuzzInput in(data, size);
    const std::uint8_t choice = in.byte();
    const InputFormat format = kFormats[(choice & 7) % std::size(kFormats)];
    const dpscope::ProtocolDescriptor* protocols[] = {nullptr, &dpscope::profibus_protocol(),
                                                   &dpscope::fc_protocol(),
                                                   &dpscope::vlt2000_protocol()};
    const dpscope::ProtocolDescriptor* protocol = protocols[(choice >> 3) & 3];
    const std::span<const std::uint8_t> file = in.rest();
    const TempFile& temp = temp_file();
    temp.write(file.data(), file.size());
    const dpscope::Bytes bytes(file.data(), file.size());
    // open_source chooses the bus itself (as a head, then complete) unless the bus is forced.
    if (protocol != nullptr) {
        const InputFormat judged =
            format == InputFormat::Auto ? dpscope::detect_input_format(bytes) : format;
        if (judged != InputFormat::Auto)
            (void)dpscope::choose_bus(bytes, judged, (choice & 0x20) != 0).reason.size();
    }
    read_all(temp.path, format, protocol, file.size());
    return 0;
}
