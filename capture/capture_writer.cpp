#include "capture/capture_writer.hpp"

#include <fmt/format.h>
#include <pcap/pcap.h>
#include <stdio_ext.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <utility>
#include <vector>

#include "capture/bus_tag.hpp"
#include "capture/hex_log.hpp"
#include "capture/pcap_source.hpp"
#include "core/counted.hpp"
#include "core/time.hpp"

namespace dpscope {

std::string_view capture_format_name(CaptureFormat format) {
    switch (format) {
        case CaptureFormat::Pcap: return "pcap";
        case CaptureFormat::Pcapng: return "pcapng";
        case CaptureFormat::Raw: return "raw";
        case CaptureFormat::Hex: return "hex";
    }
    return "pcap";
}

std::optional<CaptureFormat> capture_format_from_name(std::string_view name) {
    for (CaptureFormat format :
         {CaptureFormat::Pcap, CaptureFormat::Pcapng, CaptureFormat::Raw, CaptureFormat::Hex})
        if (capture_format_name(format) == name) return format;
    return std::nullopt;
}

namespace {

constexpr std::int64_t kNanosPerSecond = 1'000'000'000;

bool is_regular(FILE* file) {
    struct stat info {};
    return fstat(fileno(file), &info) == 0 && S_ISREG(info.st_mode);
}

std::int64_t time_or_zero(std::int64_t time_ns) { return time_ns == kNoTime ? 0 : time_ns; }

// Writers over a stdio stream: raw bytes, hex lines, pcapng blocks.
class StdioWriter : public CaptureWriter {
  public:
    StdioWriter(FILE* file, std::string name) : file_(file), name_(std::move(name)) {}
    ~StdioWriter() override { close_file(); }

  protected:
    bool flush_records() override {
        if (!file_) return false;
        if (std::fflush(file_) != 0) return fail();
        return check();
    }
    bool close_file() override {
        if (!file_) return error_.empty();
        bool ok = check();
        if (std::fflush(file_) != 0) ok = fail();
        if (file_ != stdout && std::fclose(file_) != 0) ok = fail();
        file_ = nullptr;
        return ok;
    }

    bool put(const void* data, std::size_t size) {
        if (!file_ || !error_.empty()) return false;  // the first write error stays
        if (std::fwrite(data, 1, size, file_) != size) return fail();
        return true;
    }
    bool check() { return std::ferror(file_) ? fail() : error_.empty(); }
    bool fail() {
        if (error_.empty())
            error_ = fmt::format("{}: write failed: {}", name_, std::strerror(errno));
        return false;
    }

    FILE* file_;
    std::string name_;
};

class RawWriter final : public StdioWriter {
  public:
    using StdioWriter::StdioWriter;

  protected:
    bool write_record(Bytes telegram, std::int64_t, std::string_view) override {
        return put(telegram.data(), telegram.size());
    }
};

class HexWriter final : public StdioWriter {
  public:
    // The first line says that the capture is read one record a line, and names its bus.
    HexWriter(FILE* file, std::string name, Protocol bus) : StdioWriter(file, std::move(name)) {
        const std::string header = hex_capture_header(bus);
        put(header.data(), header.size());
    }

  protected:
    bool write_record(Bytes telegram, std::int64_t time_ns, std::string_view) override {
        line_.clear();
        if (time_ns != kNoTime) {
            fmt::format_to(std::back_inserter(line_), "{}.{:09} ", time_ns / kNanosPerSecond,
                           time_ns % kNanosPerSecond);
        }
        for (std::size_t i = 0; i < telegram.size(); ++i) {
            if (i > 0) line_.push_back(' ');
            fmt::format_to(std::back_inserter(line_), "{:02X}", telegram[i]);
        }
        line_.push_back('\n');
        return put(line_.data(), line_.size());
    }

  private:
    std::string line_;
};

// Little-endian words appended to a block.
void put16(std::vector<std::uint8_t>& block, std::uint16_t v) {
    block.push_back(static_cast<std::uint8_t>(v));
    block.push_back(static_cast<std::uint8_t>(v >> 8));
}
void put32(std::vector<std::uint8_t>& block, std::uint32_t v) {
    put16(block, static_cast<std::uint16_t>(v));
    put16(block, static_cast<std::uint16_t>(v >> 16));
}
void put64(std::vector<std::uint8_t>& block, std::uint64_t v) {
    put32(block, static_cast<std::uint32_t>(v));
    put32(block, static_cast<std::uint32_t>(v >> 32));
}
// An option with a text value, padded to 32 bits.
void put_text_option(std::vector<std::uint8_t>& block, std::uint16_t code, std::string_view text) {
    put16(block, code);
    put16(block, static_cast<std::uint16_t>(text.size()));
    block.insert(block.end(), text.begin(), text.end());
    block.resize(block.size() + (((text.size() + 3) & ~std::size_t{3}) - text.size()), 0);
}

// The section header and interface description blocks a pcapng capture starts with: link type,
// snapshot length, if_tsresol = 9 (ns); for USER0 the bus as if_description; a known line as
// if_speed (the baud rate, bits per second) and, its frame known, the comment "dpscope
// frame=8E1".
std::vector<std::uint8_t> pcapng_header(int link_type, Protocol bus, const LineSettings& line) {
    std::vector<std::uint8_t> header;
    // Section header block: type, length, byte-order magic, version 1.0, unknown length.
    for (std::uint32_t word : {0x0A0D0D0Au, 28u, 0x1A2B3C4Du, 0x00000001u})
        put32(header, word);
    put64(header, ~0ULL);
    put32(header, 28);
    std::vector<std::uint8_t> options;
    put16(options, 9);  // option if_tsresol
    put16(options, 1);  // option length
    put32(options, 9);  // value 9 and three padding bytes
    if (link_type == kLinkTypeUser0) put_text_option(options, 3, pcapng_bus_description(bus));
    if (line.known()) {
        put16(options, 8);  // option if_speed
        put16(options, 8);
        put64(options, line.baud);
        if (line.frame_known())
            put_text_option(options, 1,
                            fmt::format("{}{}", kPcapngFramePrefix,
                                        serial_frame_name(*line.parity, line.stop_bits)));
    }
    put32(options, 0);  // opt_endofopt
    const auto length = static_cast<std::uint32_t>(20 + options.size());
    put32(header, 1);
    put32(header, length);
    put16(header, static_cast<std::uint16_t>(link_type));
    put16(header, 0);
    put32(header, 65535);
    header.insert(header.end(), options.begin(), options.end());
    put32(header, length);
    return header;
}

class PcapngWriter final : public StdioWriter {
  public:
    PcapngWriter(FILE* file, std::string name, int link_type, Protocol bus,
                 const LineSettings& line)
        : StdioWriter(file, std::move(name)) {
        const std::vector<std::uint8_t> header = pcapng_header(link_type, bus, line);
        put(header.data(), header.size());
        header_bytes_ = header.size();
    }

    std::size_t header_bytes() const noexcept { return header_bytes_; }

  protected:
    // An enhanced packet block; a comment becomes its opt_comment option (UTF-8, at most
    // 65535 bytes).
    bool write_record(Bytes telegram, std::int64_t time_ns, std::string_view comment) override {
        auto ts = static_cast<std::uint64_t>(time_or_zero(time_ns));
        std::size_t padded = (telegram.size() + 3) & ~std::size_t{3};
        if (comment.size() > 0xFFFF) comment = comment.substr(0, 0xFFFF);
        std::size_t comment_padded = (comment.size() + 3) & ~std::size_t{3};
        std::size_t options = comment.empty() ? 0 : 4 + comment_padded + 4;
        auto total = static_cast<std::uint32_t>(32 + padded + options);
        block_.clear();
        u32(6);  // enhanced packet block
        u32(total);
        u32(0);  // interface 0
        u32(static_cast<std::uint32_t>(ts >> 32));
        u32(static_cast<std::uint32_t>(ts));
        u32(static_cast<std::uint32_t>(telegram.size()));
        u32(static_cast<std::uint32_t>(telegram.size()));
        block_.insert(block_.end(), telegram.begin(), telegram.end());
        block_.resize(block_.size() + (padded - telegram.size()), 0);
        if (!comment.empty()) {
            u16(1);  // opt_comment
            u16(static_cast<std::uint16_t>(comment.size()));
            block_.insert(block_.end(), comment.begin(), comment.end());
            block_.resize(block_.size() + (comment_padded - comment.size()), 0);
            u32(0);  // opt_endofopt
        }
        u32(total);
        return put(block_.data(), block_.size());
    }

  private:
    void u16(std::uint16_t v) { put16(block_, v); }
    void u32(std::uint32_t v) { put32(block_, v); }

    std::vector<std::uint8_t> block_;
    std::size_t header_bytes_ = 0;
};

// A stream over a stream that cannot seek (standard output into a pipe) that sets the bus tag in
// the pcap file header libpcap writes through it (bytes 8 to 15, capture/bus_tag.hpp), and
// passes everything else on unchanged. Closing it flushes the stream below, and closes it unless
// it is standard output.
struct TagCookie {
    FILE* below = nullptr;
    std::uint64_t position = 0;
    std::uint8_t header[kPcapFileHeaderBytes] = {};
    Protocol bus = Protocol::ProfibusDp;
    LineSettings line;
};

ssize_t tag_write(void* cookie, const char* data, std::size_t size) {
    auto* tag = static_cast<TagCookie*>(cookie);
    const char* out = data;
    std::vector<char> patched;
    if (tag->position < kPcapFileHeaderBytes) {
        // The header arrives in one piece or several; keep it until it is whole, then tag it.
        patched.assign(data, data + size);
        for (std::size_t i = 0; i < size && tag->position + i < kPcapFileHeaderBytes; ++i)
            tag->header[tag->position + i] = static_cast<std::uint8_t>(data[i]);
        std::uint8_t tagged[kPcapFileHeaderBytes];
        std::memcpy(tagged, tag->header, sizeof tagged);
        put_pcap_bus_tag(tagged, tag->bus, tag->line);
        for (std::size_t i = 0; i < size && tag->position + i < kPcapFileHeaderBytes; ++i) {
            const std::size_t at = tag->position + i;
            if (at >= 8 && at < 16) patched[i] = static_cast<char>(tagged[at]);
        }
        out = patched.data();
    }
    if (std::fwrite(out, 1, size, tag->below) != size || std::fflush(tag->below) != 0) return -1;
    tag->position += size;
    return static_cast<ssize_t>(size);
}

int tag_close(void* cookie) {
    auto* tag = static_cast<TagCookie*>(cookie);
    int rc = std::fflush(tag->below);
    if (tag->below != stdout && std::fclose(tag->below) != 0) rc = EOF;
    delete tag;
    return rc;
}

// pcap through libpcap's dump API, nanosecond magic.
class PcapWriter final : public CaptureWriter {
    // The record's seconds field has 32 bits, which libpcap (and so tcpdump and dpscope) reads
    // as signed: 2038-01-19T03:14:07Z is the last second every reader dates right.
    static constexpr std::int64_t kLastPcapSecond = 0x7FFF'FFFF;
    static constexpr std::size_t kMaxUnflushedRecords = 4096;

  public:
    // `tag_at`: where the file header starts in a seekable file whose header gets the tag of
    // `bus` and `line` written over it (-1: none, or a tag stream does it).
    // `staged`: a write error throws the file away; nothing is cut back or said of it.
    PcapWriter(pcap_t* dead, pcap_dumper_t* dumper, std::string name, long tag_at, Protocol bus,
               const LineSettings& line, bool staged)
        : dead_(dead), dumper_(dumper), name_(std::move(name)) {
        // The file header is written at once, so that a full disk is named with its reason now
        // (errno is gone by the time a later record finds the stream's error flag set).
        FILE* file = pcap_dump_file(dumper_);
        if (std::fflush(file) != 0) {
            error_ = fmt::format("{}: write failed: {}", name_, std::strerror(errno));
            committed_ = -1;
            return;
        }
        if (!is_regular(file) || staged) committed_ = -1;
        if (tag_at >= 0) {
            // libpcap writes the header in the host's byte order (the file may be write-only,
            // so it is not read back).
            std::uint8_t header[kPcapFileHeaderBytes] = {};
            const std::uint32_t magic = 0xA1B23C4D;  // nanosecond magic
            std::memcpy(header, &magic, sizeof magic);
            put_pcap_bus_tag(header, bus, line);
            if (::pwrite(fileno(file), header + 8, 8, tag_at + 8) != 8)
                error_ = fmt::format("{}: write failed: {}", name_, std::strerror(errno));
        }
    }
    ~PcapWriter() override {
        close_file();
        pcap_close(dead_);
    }

    // The file header could not be written (a full disk): no capture file to write into.
    const std::string& header_error() const noexcept { return error_; }

  protected:
    bool write_record(Bytes telegram, std::int64_t time_ns, std::string_view) override {
        if (!dumper_ || !error_.empty()) return false;
        std::int64_t t = time_or_zero(time_ns);
        if (t < 0 || t / kNanosPerSecond > kLastPcapSecond) {
            error_ = fmt::format(
                "{}: telegram time {}{}.{:09} s is outside what a pcap file holds (0 to {} s "
                "since the epoch, until 2038-01-19T03:14:07Z)",
                name_, t < 0 ? "-" : "", std::abs(t / kNanosPerSecond),
                std::abs(t % kNanosPerSecond), kLastPcapSecond);
            return false;
        }
        // Bounded memory in long writes without flushes: flush (and forget the boundaries)
        // every kMaxUnflushedRecords records.
        if (boundaries_.size() >= kMaxUnflushedRecords && !flush_records()) return false;
        pcap_pkthdr header{};
        header.ts.tv_sec = static_cast<time_t>(t / kNanosPerSecond);
        header.ts.tv_usec = static_cast<suseconds_t>(t % kNanosPerSecond);  // nanoseconds here
        header.caplen = header.len = static_cast<bpf_u_int32>(telegram.size());
        pcap_dump(reinterpret_cast<u_char*>(dumper_), &header, telegram.data());
        if (committed_ >= 0) {
            position_ += static_cast<long>(kPcapRecordHeaderBytes + telegram.size());
            boundaries_.push_back(position_);
        }
        return check();
    }
    bool flush_records() override {
        if (!dumper_) return false;
        if (pcap_dump_flush(dumper_) != 0) return fail();
        if (!check()) return false;
        // Everything up to here is on disk as whole records.
        if (committed_ >= 0) committed_ = position_;
        boundaries_.clear();
        return true;
    }
    bool close_file() override {
        if (!dumper_) return error_.empty();
        bool ok = error_.empty() && flush_records();
        FILE* file = pcap_dump_file(dumper_);
        if (file == stdout) {
            // pcap_dump_close would close standard output; it is flushed, the process owns it.
            dumper_ = nullptr;
            return ok;
        }
        pcap_dump_close(dumper_);
        dumper_ = nullptr;
        return ok;
    }

  private:
    bool check() {
        if (std::ferror(pcap_dump_file(dumper_))) return fail();
        return true;
    }
    // A write failed (disk full, file size limit): keep the file a valid capture by dropping
    // what stdio still holds and cutting the file back to the last flushed record boundary.
    bool fail() {
        if (!error_.empty()) return false;
        error_ = fmt::format("{}: write failed: {}", name_, std::strerror(errno));
        FILE* file = pcap_dump_file(dumper_);
        __fpurge(file);
        if (committed_ < 0) return false;
        // Keep every record that reached the file whole: the last record boundary at or below
        // what the file holds.
        long keep = committed_;
        struct stat info {};
        if (fstat(fileno(file), &info) == 0)
            for (long boundary : boundaries_)
                if (boundary <= info.st_size) keep = boundary;
        if (::ftruncate(fileno(file), keep) == 0)
            error_ += fmt::format("; the file keeps the {} of whole records written before",
                                  counted(static_cast<std::uint64_t>(keep), "byte", "bytes"));
        return false;
    }

    pcap_t* dead_;
    // Bytes flushed as whole records; -1 for pipes (cannot be cut back) and staged files.
    long committed_ = static_cast<long>(kPcapFileHeaderBytes);
    long position_ = static_cast<long>(kPcapFileHeaderBytes);  // where the next record starts
    std::vector<long> boundaries_;                             // record ends since the last flush
    pcap_dumper_t* dumper_;
    std::string name_;
};

// Rotation: FILE becomes stem-00001.ext, stem-00002.ext, ...; a new file is started before a
// telegram that would exceed the size, or that comes after the time span; no telegram is split or
// lost at the seam.
class RotatingWriter final : public CaptureWriter {
  public:
    RotatingWriter(std::string path, CaptureFormat format, int link_type, RotationOptions rotation,
                   Protocol bus, const LineSettings& line, FILE* first)
        : path_(std::move(path)),
          format_(format),
          link_type_(link_type),
          rotation_(rotation),
          bus_(bus),
          line_(line),
          first_(first) {}

    const RotationStats* rotation_stats() const noexcept override { return &stats_; }

    Result<std::string> start_next_file() override {
        if (!current_ || !error_.empty()) return Error{error_.empty() ? "closed" : error_};
        if (records_ == 0) return std::string();
        if (Result<void> next = open_next(); !next) {
            error_ = next.error();
            return Error{error_};
        }
        return rotated_file_name(path_, index_);
    }

    // Closes the current file (if any) and starts the next one; then the ring removes what it
    // keeps no more (the file just closed is complete by then).
    Result<void> open_next() {
        if (current_) {
            if (Result<void> closed = current_->close(); !closed) return closed;
            kept_.push_back(KeptFile{index_, bytes_, records_});
            kept_bytes_ += bytes_;
        }
        ++index_;
        std::string name = rotated_file_name(path_, index_);
        FILE* first = std::exchange(first_, nullptr);
        WriterResult opened =
            first ? open_capture_writer(first, name, format_, link_type_, bus_, line_)
                  : open_capture_writer(name, format_, link_type_, bus_, line_);
        if (!opened) return Error{opened.error()};
        current_ = std::move(opened).value();
        // pcapng: the section and interface blocks (with the bus tag and the line).
        bytes_ = format_ == CaptureFormat::Pcap     ? kPcapFileHeaderBytes
                 : format_ == CaptureFormat::Pcapng ? pcapng_header(link_type_, bus_, line_).size()
                                                    : 0;
        file_start_ns_ = kNoTime;
        records_ = 0;
        stats_.files_written = index_;
        if (rotation_.ring_files > 0)
            while (!kept_.empty() && kept_.size() + 1 > rotation_.ring_files)
                if (Result<void> removed = remove_oldest(); !removed) return removed;
        return keep_under_cap();
    }

  protected:
    // Comments are dropped: rotation writes pcap (sniff -w).
    bool write_record(Bytes telegram, std::int64_t time_ns, std::string_view) override {
        if (!current_) return false;
        std::uint64_t record_bytes = telegram.size() + kPcapRecordHeaderBytes;
        bool full =
            rotation_.max_bytes > 0 && records_ > 0 && bytes_ + record_bytes > rotation_.max_bytes;
        bool old = rotation_.max_ns > 0 && records_ > 0 && time_ns != kNoTime &&
                   time_ns - file_start_ns_ >= rotation_.max_ns;
        if (full || old) {
            if (Result<void> next = open_next(); !next) {
                error_ = next.error();
                return false;
            }
        }
        if (file_start_ns_ == kNoTime) file_start_ns_ = time_ns;
        bytes_ += record_bytes;
        ++records_;
        stats_.bytes_kept = kept_bytes_ + bytes_;
        if (rotation_.max_disk > 0 && stats_.bytes_kept > rotation_.max_disk)
            if (Result<void> capped = keep_under_cap(); !capped) {
                error_ = capped.error();
                return false;
            }
        if (Result<void> written = current_->write(telegram, time_ns); !written) {
            error_ = written.error();
            return false;
        }
        return true;
    }
    bool flush_records() override {
        if (!current_) return false;
        if (Result<void> flushed = current_->flush(); !flushed) {
            error_ = flushed.error();
            return false;
        }
        return true;
    }
    bool close_file() override {
        if (!current_) return error_.empty();
        Result<void> closed = current_->close();
        if (!closed) error_ = closed.error();
        current_.reset();
        return closed && error_.empty();
    }

  private:
    struct KeptFile {
        unsigned index = 0;
        std::uint64_t bytes = 0;
        std::uint64_t records = 0;
    };

    Result<void> remove_oldest() {
        const KeptFile oldest = kept_.front();
        const std::string name = rotated_file_name(path_, oldest.index);
        if (std::remove(name.c_str()) != 0 && errno != ENOENT)
            return Error{fmt::format("{}: cannot remove the oldest file of the ring: {}", name,
                                     std::strerror(errno))};
        kept_.pop_front();
        kept_bytes_ -= oldest.bytes;
        ++stats_.files_removed;
        stats_.records_removed += oldest.records;
        stats_.bytes_kept = kept_bytes_ + bytes_;
        return {};
    }
    // --max-disk: the oldest complete files go while the set is over the cap.
    Result<void> keep_under_cap() {
        stats_.bytes_kept = kept_bytes_ + bytes_;
        if (rotation_.max_disk == 0) return {};
        while (!kept_.empty() && kept_bytes_ + bytes_ > rotation_.max_disk)
            if (Result<void> removed = remove_oldest(); !removed) return removed;
        return {};
    }

    std::string path_;
    CaptureFormat format_;
    int link_type_;
    RotationOptions rotation_;
    Protocol bus_;
    LineSettings line_;
    FILE* first_;  // the first file, opened by the caller (nullptr: opened here)
    std::unique_ptr<CaptureWriter> current_;
    std::uint64_t bytes_ = 0;
    std::uint64_t records_ = 0;
    std::int64_t file_start_ns_ = kNoTime;
    unsigned index_ = 0;
    std::deque<KeptFile> kept_;  // the complete files on disk, oldest first
    std::uint64_t kept_bytes_ = 0;
    RotationStats stats_;
};

}  // namespace

std::string rotated_file_name(const std::string& path, unsigned index) {
    std::size_t slash = path.rfind('/');
    std::size_t dot = path.rfind('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash) ||
        dot == (slash == std::string::npos ? 0 : slash + 1))
        return fmt::format("{}-{:05}", path, index);
    return fmt::format("{}-{:05}{}", path.substr(0, dot), index, path.substr(dot));
}

WriterResult open_rotating_writer(const std::string& path, CaptureFormat format, int link_type,
                                  RotationOptions rotation, Protocol bus, const LineSettings& line,
                                  FILE* first) {
    if (rotation.max_bytes == 0 && rotation.max_ns == 0)
        return first ? open_capture_writer(first, path == "-" ? "<stdout>" : path, format,
                                           link_type, bus, line)
                     : open_capture_writer(path, format, link_type, bus, line);
    if (path == "-") return Error{"cannot rotate standard output: give -w a file name"};
    auto writer =
        std::make_unique<RotatingWriter>(path, format, link_type, rotation, bus, line, first);
    if (Result<void> opened = writer->open_next(); !opened) return Error{opened.error()};
    return writer;
}

WriterResult open_capture_writer(const std::string& path, CaptureFormat format, int link_type,
                                 Protocol bus, const LineSettings& line) {
    if (path == "-") return open_capture_writer(stdout, "<stdout>", format, link_type, bus, line);
    FILE* file = std::fopen(path.c_str(), "wb");
    if (!file)
        return Error{fmt::format("{}: cannot open for writing: {}", path, std::strerror(errno))};
    return open_capture_writer(file, path, format, link_type, bus, line);
}

WriterResult open_capture_writer(FILE* file, std::string name, CaptureFormat format, int link_type,
                                 Protocol bus, const LineSettings& line, bool staged) {
    switch (format) {
        case CaptureFormat::Pcap: {
            // USER0 is shared by the buses: the header records which (capture/bus_tag.hpp), and
            // the line where it is known, for any link type. A seekable file gets the tag
            // written over libpcap's header; anything else is written through a stream that
            // sets it on the way.
            const bool tagged = link_type == kLinkTypeUser0 || line.known();
            // A link type of one bus (257: PROFIBUS) is that bus whatever the caller's.
            if (const ProtocolDescriptor* owner = only_protocol_of_link_type(link_type))
                bus = owner->protocol;
            long tag_at = -1;
            FILE* target = file;
            if (tagged) {
                std::fflush(file);
                tag_at = is_regular(file) ? ::lseek(fileno(file), 0, SEEK_CUR) : -1;
                if (tag_at < 0) {
                    auto* cookie = new TagCookie{file, 0, {}, bus, line};
                    target =
                        fopencookie(cookie, "wb",
                                    cookie_io_functions_t{nullptr, tag_write, nullptr, tag_close});
                    if (!target) {
                        delete cookie;
                        if (file != stdout) std::fclose(file);
                        return Error{fmt::format("{}: cannot set up writing: {}", name,
                                                 std::strerror(errno))};
                    }
                }
            }
            pcap_t* dead =
                pcap_open_dead_with_tstamp_precision(link_type, 65535, PCAP_TSTAMP_PRECISION_NANO);
            pcap_dumper_t* dumper = dead ? pcap_dump_fopen(dead, target) : nullptr;
            if (!dumper) {
                std::string error = fmt::format("{}: cannot write a pcap file: {}", name,
                                                dead ? pcap_geterr(dead) : "libpcap has no writer");
                if (dead) pcap_close(dead);
                if (target != stdout) std::fclose(target);
                return Error{std::move(error)};
            }
            auto writer = std::make_unique<PcapWriter>(dead, dumper, std::move(name), tag_at, bus,
                                                       line, staged);
            if (!writer->header_error().empty()) return Error{writer->header_error()};
            return writer;
        }
        case CaptureFormat::Pcapng:
            return std::make_unique<PcapngWriter>(file, std::move(name), link_type, bus, line);
        case CaptureFormat::Raw: return std::make_unique<RawWriter>(file, std::move(name));
        case CaptureFormat::Hex: return std::make_unique<HexWriter>(file, std::move(name), bus);
    }
    return Error{fmt::format("{}: no writer for this capture format", name)};
}

}  // namespace dpscope
