// Where telegrams come from: a pcap/pcapng file (libpcap), a raw serial byte stream, or a hex
// text log. Every source hands out one telegram per call, numbered from 1, and reports what is
// wrong with the input as messages that name the file and the record or byte offset.
#pragma once

#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>

#include "capture/input_format.hpp"
#include "decoder/bus_decoder.hpp"
#include "decoder/problem.hpp"

namespace dpscope {

struct Record {
    Bytes bytes;                     // valid until the next call to next()
    std::int64_t time_ns = kNoTime;  // nanoseconds since the epoch, kNoTime when unknown
    std::uint64_t number = 0;        // 1-based
    std::uint64_t offset = 0;        // where the record starts: byte offset in a pcap file, stream
                                     // offset for raw/hex input; 0 for pcapng (not known)
    std::uint32_t original_length = 0;  // pcap: the length on the wire (> bytes.size() if cut)
};

struct InputIssue {
    Severity severity = Severity::Warning;
    std::string message;  // names the input and the record or byte offset
};

enum class InputStatus {
    Ok,        // read to the end
    Damaged,   // stopped early (truncated record, read error); what came before was handed out
    Unusable,  // nothing could be read (cannot open, bad magic, unsupported link type)
};

class TelegramSource {
  public:
    using IssueHandler = std::function<void(const InputIssue&)>;

    explicit TelegramSource(std::string display_name) : name_(std::move(display_name)) {}
    virtual ~TelegramSource() = default;
    TelegramSource(const TelegramSource&) = delete;
    TelegramSource& operator=(const TelegramSource&) = delete;

    // The next telegram; false at the end of the input or when damage stops the reading.
    virtual bool next(Record& record) = 0;
    virtual InputFormat format() const = 0;
    // The pcap link type, 0 for inputs without one.
    virtual int link_type() const { return 0; }
    // Bytes skipped by the stream framer (raw and hex inputs).
    virtual std::uint64_t bytes_skipped() const { return 0; }

    InputStatus status() const noexcept { return status_; }
    const std::string& name() const noexcept { return name_; }
    void on_issue(IssueHandler handler) { issue_handler_ = std::move(handler); }

  protected:
    void report(Severity severity, std::string message);
    void set_status(InputStatus status) noexcept { status_ = status; }

  private:
    std::string name_;
    InputStatus status_ = InputStatus::Ok;
    IssueHandler issue_handler_;
};

struct OpenResult {
    std::unique_ptr<TelegramSource> source;  // null when the input is unusable
    std::string error;                       // why, naming the file
};

// Opens `path` ("-" for standard input), detecting the format from the content unless `format`
// forces one.
OpenResult open_source(const std::string& path, InputFormat format);

// A source over bytes already in memory (e.g. `dpscope hex` arguments), framed as a raw stream.
std::unique_ptr<TelegramSource> memory_source(std::string display_name, Bytes bytes);

}  // namespace dpscope
