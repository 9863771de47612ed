// Where telegrams go: pcap (through libpcap, nanosecond timestamps), pcapng, a raw byte stream,
// or a hex text log that `dpscope decode` reads back with its timestamps.
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "capture/bus_tag.hpp"
#include "core/byte_reader.hpp"
#include "core/result.hpp"
#include "core/telegram.hpp"

namespace dpscope {

enum class CaptureFormat { Pcap, Pcapng, Raw, Hex };

std::string_view capture_format_name(CaptureFormat format);  // "pcap", "pcapng", "raw", "hex"
std::optional<CaptureFormat> capture_format_from_name(std::string_view name);

// What a rotating writer did with its files (the ring: sniff --ring, --max-disk).
struct RotationStats {
    unsigned files_written = 0;         // stem-00001 ... the current one
    unsigned files_removed = 0;         // the oldest, removed by the ring or the disk cap
    std::uint64_t records_removed = 0;  // the telegrams those held
    std::uint64_t bytes_kept = 0;       // what the files left on disk hold
};

class CaptureWriter {
  public:
    virtual ~CaptureWriter() = default;
    // A rotating writer's account of its files; null for one that writes one file.
    virtual const RotationStats* rotation_stats() const noexcept { return nullptr; }
    // A rotating writer: closes the current file (complete) and starts the next one now, as
    // sniff does on SIGHUP; nothing when the current file holds no telegram yet. Returns the new
    // file's name ("" when none was started). An error for a writer that does not rotate.
    virtual Result<std::string> start_next_file() {
        return Error{"this capture writer writes one file; it has no next one"};
    }
    // Each fails from the first write error on, saying what happened (naming the file).
    Result<void> write(Bytes telegram, std::int64_t time_ns) {
        return outcome(write_record(telegram, time_ns, {}));
    }
    // The same with a comment on the record where the format has them (pcapng: opt_comment);
    // other formats drop the comment.
    Result<void> write(Bytes telegram, std::int64_t time_ns, std::string_view comment) {
        return outcome(write_record(telegram, time_ns, comment));
    }
    Result<void> flush() { return outcome(flush_records()); }
    Result<void> close() { return outcome(close_file()); }

  protected:
    // What each format does; false after a write error, with error_ set.
    virtual bool write_record(Bytes telegram, std::int64_t time_ns, std::string_view comment) = 0;
    virtual bool flush_records() = 0;
    virtual bool close_file() = 0;

    // The first write error: it stays, and every later call fails with it.
    std::string error_;

  private:
    Result<void> outcome(bool ok) const {
        if (ok) return {};
        // A call after close() fails without a write error of its own.
        return Error{error_.empty() ? std::string("the capture file is already closed") : error_};
    }
};

// A writer, or why none could be opened (naming the file).
using WriterResult = Result<std::unique_ptr<CaptureWriter>>;

// `path` "-" writes to standard output. `link_type` is used by pcap and pcapng. A pcap file whose
// header cannot be written (disk full) is an error here, not at the first record. A pcap writer
// whose write fails (disk full) cuts the file back to the last flushed record, so it stays a
// valid capture of what came before. A pcap or pcapng capture of link type USER0, which several
// buses share, records `bus` in its header (capture/bus_tag.hpp), also on standard output; a
// pcap or pcapng capture of any link type records `line` when its baud rate is known (pcap: in
// the same tag, pcapng: if_speed and a comment naming the frame).
WriterResult open_capture_writer(const std::string& path, CaptureFormat format, int link_type,
                                 Protocol bus = Protocol::ProfibusDp,
                                 const LineSettings& line = {});
// The same into an open stream, which the writer then owns and closes (standard output is
// flushed, not closed). `name` is what messages call it. `staged`: the stream is a staged file
// that a write error throws away (capture/output_file.hpp), so a failed write neither cuts it
// back nor says what it keeps.
WriterResult open_capture_writer(FILE* file, std::string name, CaptureFormat format, int link_type,
                                 Protocol bus = Protocol::ProfibusDp,
                                 const LineSettings& line = {}, bool staged = false);

struct RotationOptions {
    std::uint64_t max_bytes = 0;  // start a new file before one grows past this (0: no limit)
    std::int64_t max_ns = 0;      // ... or once its first telegram is this old (0: no limit)
    // The ring (as dumpcap -b files:N): keep at most this many files, the current one included,
    // removing the oldest once the file before the current one is complete (0: keep all).
    unsigned ring_files = 0;
    // And at most this many bytes in the files kept, removing the oldest complete files (never
    // the current one) when the set grows past it (0: no cap).
    std::uint64_t max_disk = 0;
};

// With rotation, FILE is written as stem-00001.ext, stem-00002.ext, ... (see
// rotated_file_name); without, this is open_capture_writer. `first`: the first file already open
// (FILE itself, or stem-00001.ext when rotating; the writer owns it), as a caller that stages it
// opens it; nullptr opens it here.
WriterResult open_rotating_writer(const std::string& path, CaptureFormat format, int link_type,
                                  RotationOptions rotation, Protocol bus = Protocol::ProfibusDp,
                                  const LineSettings& line = {}, FILE* first = nullptr);
std::string rotated_file_name(const std::string& path, unsigned index);

}  // namespace dpscope
