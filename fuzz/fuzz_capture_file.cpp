// The input bytes as a whole capture file, read the way `dpscope decode` reads one: written to a
// temporary file (made once per process, rewritten for every input), opened with the format
// detected from the content and then with each forced format (pcap, pcapng, raw, hex), then
// with the bus chosen from the content and as a forced text log of VLT 2000 telegrams, every
// record pulled, decoded with one BusDecoder, tracked with a SessionTracker, counted in a Summary
// and rendered into an Output that is thrown away by one of the four renderers in turn (the
// others pass over it). Input issues are formatted and dropped, as `decode` prints them.
#include <fcntl.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "capture/telegram_source.hpp"
#include "decoder/bus_decoder.hpp"
#include "decoder/session_tracker.hpp"
#include "formats/output.hpp"
#include "formats/renderer.hpp"
#include "formats/summary.hpp"

namespace {

dpscope::Output& output() {
    static FILE* sink = std::fopen("/dev/null", "w");
    static dpscope::Output out{sink};
    return out;
}

// The temporary file every input is written to. It is unlinked at once and opened by its
// /proc/self/fd name: libFuzzer ends some runs without running destructors, and no run may
// leave a file behind.
struct TempFile {
    std::string path;
    int fd = -1;
    TempFile() {
        char name[] = "/tmp/dpscope-fuzz-capture-XXXXXX";
        fd = mkstemp(name);
        if (fd < 0) {
            std::perror("fuzz_capture_file: mkstemp");
            std::abort();
        }
        ::unlink(name);
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

// `protocol` null: the bus is chosen from the input, as `decode` without --bus does.
void read_all(const std::string& path, dpscope::InputFormat format,
              const dpscope::CaptureProtocol* protocol, std::size_t turn) {
    dpscope::BusChoice choice;
    dpscope::OpenResult opened = dpscope::open_source(path, format, protocol, choice);
    if (!opened) {
        (void)opened.error().size();
        return;
    }
    dpscope::TelegramSource& source = *opened.value();
    std::size_t issue_bytes = 0;
    source.on_issue(
        [&issue_bytes](const dpscope::InputIssue& issue) { issue_bytes += issue.message.size(); });
    dpscope::Output& out = output();
    dpscope::BusDecoder decoder;
    dpscope::SessionTracker tracker;
    dpscope::Summary summary;
    std::vector<std::unique_ptr<dpscope::TelegramRenderer>> renderers;
    for (auto kind : {dpscope::OutputFormat::Text, dpscope::OutputFormat::Verbose,
                      dpscope::OutputFormat::Jsonl, dpscope::OutputFormat::Csv}) {
        renderers.push_back(dpscope::make_renderer(kind, out));
        renderers.back()->begin();
    }
    dpscope::Record record;
    while (source.next(record)) {
        const dpscope::DecodedTelegram& t =
            decoder.decode(record.bytes, record.time_ns, record.number);
        std::span<const dpscope::Finding> findings = tracker.track(t);
        summary.add(t);
        summary.add_findings(findings);
        // Renderers take turns, as in fuzz_framer_decoder (rendering is most of the time spent);
        // the others pass over the telegram as `decode` does with one it filters out. `turn`
        // differs between the readings of one input, so each renderer sees every record.
        const std::size_t shown = (record.number + turn) % renderers.size();
        for (std::size_t i = 0; i < renderers.size(); ++i) {
            if (i == shown)
                renderers[i]->render(t, findings);
            else
                renderers[i]->pass_over(t);
        }
        out.buffer().clear();
    }
    std::span<const dpscope::Finding> open_at_end = tracker.finish();
    summary.add_findings(open_at_end);
    for (auto& renderer : renderers) {
        renderer->render_end_findings(open_at_end);
        renderer->end();
    }
    summary.render_text(
        out,
        dpscope::InputSummary{source.name(), std::string(input_format_name(source.format())),
                              source.bytes_skipped(),
                              source.status() == dpscope::InputStatus::Damaged},
        decoder);
    (void)source.link_type();
    (void)source.unusable_reason();
    out.buffer().clear();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const TempFile& file = temp_file();
    file.write(data, size);
    // The choice of the bus reads the same bytes: a pcap or pcapng header, its tag and first
    // record, and every bus's framing over a byte stream or a hex log's bytes.
    const dpscope::Bytes bytes(data, size);
    for (auto format :
         {dpscope::InputFormat::Pcap, dpscope::InputFormat::Pcapng, dpscope::InputFormat::Raw,
          dpscope::InputFormat::Hex, dpscope::InputFormat::Text})
        for (bool complete : {false, true})
            (void)dpscope::choose_bus(bytes, format, complete).reason.size();
    std::size_t turn = 0;
    const dpscope::CaptureProtocol* profibus = &dpscope::profibus_dp_protocol();
    for (auto format :
         {dpscope::InputFormat::Auto, dpscope::InputFormat::Pcap, dpscope::InputFormat::Pcapng,
          dpscope::InputFormat::Raw, dpscope::InputFormat::Hex})
        read_all(file.path, format, profibus, turn++);
    // The bus chosen from the content (a text log: VLT 2000), and the text-log reader forced.
    read_all(file.path, dpscope::InputFormat::Auto, nullptr, turn++);
    read_all(file.path, dpscope::InputFormat::Text, &dpscope::vlt2000_protocol(), turn++);
    return 0;
}
