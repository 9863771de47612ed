#include "capture/capture_writer.hpp"

#include <fmt/format.h>
#include <pcap/pcap.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <vector>

#include "decoder/bus_decoder.hpp"

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

std::int64_t time_or_zero(std::int64_t time_ns) { return time_ns == kNoTime ? 0 : time_ns; }

// Writers over a stdio stream: raw bytes, hex lines, pcapng blocks.
class StdioWriter : public CaptureWriter {
  public:
    StdioWriter(FILE* file, std::string name) : file_(file), name_(std::move(name)) {}
    ~StdioWriter() override { close(); }

    bool flush() override {
        if (!file_) return false;
        if (std::fflush(file_) != 0) return fail();
        return check();
    }
    bool close() override {
        if (!file_) return error_.empty();
        bool ok = check();
        if (std::fflush(file_) != 0) ok = fail();
        if (file_ != stdout && std::fclose(file_) != 0) ok = fail();
        file_ = nullptr;
        return ok;
    }

  protected:
    bool put(const void* data, std::size_t size) {
        if (!file_) return false;
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
    bool write(Bytes telegram, std::int64_t) override {
        return put(telegram.data(), telegram.size());
    }
};

class HexWriter final : public StdioWriter {
  public:
    using StdioWriter::StdioWriter;
    bool write(Bytes telegram, std::int64_t time_ns) override {
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

class PcapngWriter final : public StdioWriter {
  public:
    PcapngWriter(FILE* file, std::string name, int link_type) : StdioWriter(file, std::move(name)) {
        // Section header block: type, length, byte-order magic, version 1.0, unknown length.
        for (std::uint32_t word : {0x0A0D0D0Au, 28u, 0x1A2B3C4Du, 0x00000001u})
            u32(word);
        u64(~0ULL);
        u32(28);
        // Interface description block: link type, snapshot length, if_tsresol = 9 (ns).
        u32(1);
        u32(32);
        u16(static_cast<std::uint16_t>(link_type));
        u16(0);
        u32(65535);
        u16(9);  // option if_tsresol
        u16(1);  // option length
        u32(9);  // value 9 and three padding bytes
        u32(0);  // opt_endofopt
        u32(32);
        put(block_.data(), block_.size());
        block_.clear();
    }

    bool write(Bytes telegram, std::int64_t time_ns) override {
        auto ts = static_cast<std::uint64_t>(time_or_zero(time_ns));
        std::size_t padded = (telegram.size() + 3) & ~std::size_t{3};
        auto total = static_cast<std::uint32_t>(32 + padded);
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
        u32(total);
        return put(block_.data(), block_.size());
    }

  private:
    void u16(std::uint16_t v) {
        block_.push_back(static_cast<std::uint8_t>(v));
        block_.push_back(static_cast<std::uint8_t>(v >> 8));
    }
    void u32(std::uint32_t v) {
        u16(static_cast<std::uint16_t>(v));
        u16(static_cast<std::uint16_t>(v >> 16));
    }
    void u64(std::uint64_t v) {
        u32(static_cast<std::uint32_t>(v));
        u32(static_cast<std::uint32_t>(v >> 32));
    }

    std::vector<std::uint8_t> block_;
};

// pcap through libpcap's dump API, nanosecond magic.
class PcapWriter final : public CaptureWriter {
  public:
    PcapWriter(pcap_t* dead, pcap_dumper_t* dumper, std::string name)
        : dead_(dead), dumper_(dumper), name_(std::move(name)) {}
    ~PcapWriter() override {
        close();
        pcap_close(dead_);
    }

    bool write(Bytes telegram, std::int64_t time_ns) override {
        if (!dumper_) return false;
        std::int64_t t = time_or_zero(time_ns);
        pcap_pkthdr header{};
        header.ts.tv_sec = static_cast<time_t>(t / kNanosPerSecond);
        header.ts.tv_usec = static_cast<suseconds_t>(t % kNanosPerSecond);  // nanoseconds here
        header.caplen = header.len = static_cast<bpf_u_int32>(telegram.size());
        pcap_dump(reinterpret_cast<u_char*>(dumper_), &header, telegram.data());
        return check();
    }
    bool flush() override {
        if (!dumper_) return false;
        if (pcap_dump_flush(dumper_) != 0) return fail();
        return check();
    }
    bool close() override {
        if (!dumper_) return error_.empty();
        bool ok = flush();
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
    bool fail() {
        if (error_.empty())
            error_ = fmt::format("{}: write failed: {}", name_, std::strerror(errno));
        return false;
    }

    pcap_t* dead_;
    pcap_dumper_t* dumper_;
    std::string name_;
};

}  // namespace

WriterResult open_capture_writer(const std::string& path, CaptureFormat format, int link_type) {
    WriterResult result;
    bool to_stdout = path == "-";
    std::string name = to_stdout ? std::string("<stdout>") : path;
    if (format == CaptureFormat::Pcap) {
        pcap_t* dead =
            pcap_open_dead_with_tstamp_precision(link_type, 65535, PCAP_TSTAMP_PRECISION_NANO);
        if (!dead) {
            result.error = fmt::format("{}: libpcap cannot create a writer", name);
            return result;
        }
        pcap_dumper_t* dumper =
            to_stdout ? pcap_dump_fopen(dead, stdout) : pcap_dump_open(dead, path.c_str());
        if (!dumper) {
            result.error = fmt::format("{}: cannot open for writing: {}", name, pcap_geterr(dead));
            pcap_close(dead);
            return result;
        }
        result.writer = std::make_unique<PcapWriter>(dead, dumper, name);
        return result;
    }
    FILE* file = to_stdout ? stdout : std::fopen(path.c_str(), "wb");
    if (!file) {
        result.error = fmt::format("{}: cannot open for writing: {}", name, std::strerror(errno));
        return result;
    }
    switch (format) {
        case CaptureFormat::Pcapng:
            result.writer = std::make_unique<PcapngWriter>(file, name, link_type);
            break;
        case CaptureFormat::Raw: result.writer = std::make_unique<RawWriter>(file, name); break;
        case CaptureFormat::Hex: result.writer = std::make_unique<HexWriter>(file, name); break;
        case CaptureFormat::Pcap: break;
    }
    return result;
}

}  // namespace dpscope
