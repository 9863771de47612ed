// Where telegrams go: pcap (through libpcap, nanosecond timestamps), pcapng, a raw byte stream,
// or a hex text log that `dpscope decode` reads back with its timestamps.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "decoder/byte_reader.hpp"

namespace dpscope {

enum class CaptureFormat { Pcap, Pcapng, Raw, Hex };

std::string_view capture_format_name(CaptureFormat format);  // "pcap", "pcapng", "raw", "hex"
std::optional<CaptureFormat> capture_format_from_name(std::string_view name);

class CaptureWriter {
  public:
    virtual ~CaptureWriter() = default;
    // Each returns false after a write error; error() says what happened.
    virtual bool write(Bytes telegram, std::int64_t time_ns) = 0;
    virtual bool flush() = 0;
    virtual bool close() = 0;
    const std::string& error() const noexcept { return error_; }

  protected:
    std::string error_;
};

struct WriterResult {
    std::unique_ptr<CaptureWriter> writer;  // null on failure
    std::string error;
};

// `path` "-" writes to standard output. `link_type` is used by pcap and pcapng.
WriterResult open_capture_writer(const std::string& path, CaptureFormat format, int link_type);

}  // namespace dpscope
