// Where telegrams come from: a pcap/pcapng file (libpcap), a raw serial byte stream, or a hex
// text log. Every source hands out one telegram per call, numbered from 1, and reports what is
// wrong with the input as messages that name the file and the record or byte offset.
#pragma once

#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>

#include "capture/bus_tag.hpp"
#include "core/protocol_descriptor.hpp"
#include "capture/input_format.hpp"
#include "core/byte_reader.hpp"
#include "core/problem.hpp"
#include "core/result.hpp"
#include "core/time.hpp"

namespace dpscope {

struct Record {
    Bytes bytes;                     // valid until the next call to next()
    std::int64_t time_ns = kNoTime;  // nanoseconds since the epoch, kNoTime when unknown
    std::uint64_t number = 0;        // 1-based
    std::uint64_t offset = 0;        // where the record starts: byte offset in a pcap file, stream
                                     // offset for raw/hex input; 0 for pcapng (not known)
    std::uint32_t original_length = 0;  // pcap: the length on the wire (> bytes.size() if cut)
};

// Kinds of input issue that can repeat: the first few of each are reported, the rest counted and
// summed up in one message when the reading ends (kMaxIssuesShown).
enum class IssueKind : std::uint8_t {
    Other,          // never capped (errors, one-off notes)
    SkippedBytes,   // a run of bytes that forms no telegram
    Snapshot,       // a record cut short by the snapshot length
    HexSyntax,      // a hex-log line with a token that is no hex byte
    TimeBackwards,  // a telegram earlier than the one before
    TimeJump,       // a telegram more than kTimeJumpNs after the one before
    Interface,      // pcapng: a packet of an interface dpscope does not decode, or a bad one
    BadTime,        // pcapng: a timestamp outside what dpscope can represent
};
inline constexpr std::size_t kIssueKinds = 8;
// Repeated issues of one kind reported before the rest are only counted.
inline constexpr std::uint64_t kMaxIssuesShown = 10;
// Times that step forward by more than this are a capture problem (a gap or a clock step).
inline constexpr std::int64_t kTimeJumpNs = 60'000'000'000;

struct InputIssue {
    Severity severity = Severity::Warning;
    std::string message;  // names the input and the record or byte offset
    IssueKind kind = IssueKind::Other;
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

    // The next telegram; false at the end of the input, when damage stops the reading, or after
    // the number of telegrams set by stop_after(). When it returns false the first time, the
    // issues that were only counted are summed up.
    bool next(Record& record);
    // Hand out at most `telegrams` telegrams (0: no limit): the input after the last of them is
    // not read further, and nothing is reported about it.
    void stop_after(std::uint64_t telegrams) noexcept { limit_ = telegrams; }
    virtual InputFormat format() const = 0;
    // The pcap link type, 0 for inputs without one.
    virtual int link_type() const { return 0; }
    // Bytes skipped by the stream framer (raw and hex inputs).
    virtual std::uint64_t bytes_skipped() const { return 0; }
    // Did the input's first bytes look like text (capture/input_format.hpp, looks_like_text)?
    // Raw inputs only: messages then name the input formats for text.
    virtual bool looks_like_text() const { return false; }
    // Memory the source holds for its input now, in bytes: read buffers, bytes not framed yet,
    // telegrams and messages framed and not handed out yet (capacities, not sizes). Bounded by a
    // constant whatever the input (tests check it; docs/decisions.md, "Memory of the readers").
    virtual std::size_t buffered_bytes() const { return 0; }
    // How far the reading has got: bytes of the input consumed so far (what the source has
    // buffered ahead of the telegram handed out last is not counted). 0 when not known (standard
    // input, bytes in memory). Costs a library call: ask now and then, not per telegram.
    std::uint64_t bytes_read() const;
    // The input's size in bytes when it is a regular file opened by name; 0 otherwise.
    std::uint64_t input_size() const noexcept { return input_size_; }
    // Set by open_source: the stream the source reads (which it owns) and the file's size.
    void watch_position(std::FILE* stream, std::uint64_t size) noexcept {
        position_stream_ = stream;
        input_size_ = size;
    }

    InputStatus status() const noexcept { return status_; }
    // Why the input is Unusable when that was found out while reading (e.g. a byte stream that is
    // no PROFIBUS stream); "" otherwise.
    const std::string& unusable_reason() const noexcept { return unusable_reason_; }
    const std::string& name() const noexcept { return name_; }
    void on_issue(IssueHandler handler) { issue_handler_ = std::move(handler); }
    // Issues of a repeating kind met so far, shown or only counted.
    std::uint64_t issue_count(IssueKind kind) const noexcept {
        return counted_[static_cast<std::size_t>(kind)].issues;
    }

  protected:
    // The next telegram from the input itself.
    virtual bool read_next(Record& record) = 0;

    // Reports an issue; issues of a repeating kind beyond kMaxIssuesShown (one for the time
    // kinds) are counted, with `bytes` summed, and summed up by finish_reporting().
    void report(Severity severity, std::string message, IssueKind kind = IssueKind::Other,
                std::uint64_t bytes = 0);
    // `issues` issues of a repeating kind, with `bytes` summed, that come after the first
    // kMaxIssuesShown of their kind: counted as report() counts them, without a message.
    void count_hidden(IssueKind kind, std::uint64_t issues, std::uint64_t bytes);
    // The counted issues, one message per kind; once.
    void finish_reporting();
    void set_status(InputStatus status) noexcept { status_ = status; }
    void set_unusable(std::string reason) {
        status_ = InputStatus::Unusable;
        unusable_reason_ = std::move(reason);
    }

  private:
    struct Counted {
        std::uint64_t issues = 0;
        std::uint64_t hidden = 0;
        std::uint64_t hidden_bytes = 0;
    };
    void check_time(const Record& record);

    std::string name_;
    InputStatus status_ = InputStatus::Ok;
    std::string unusable_reason_;
    IssueHandler issue_handler_;
    std::uint64_t limit_ = 0;
    std::uint64_t handed_out_ = 0;
    std::int64_t last_time_ns_ = kNoTime;
    std::uint64_t last_number_ = 0;
    Counted counted_[kIssueKinds];
    bool reporting_finished_ = false;
    std::FILE* position_stream_ = nullptr;
    std::uint64_t input_size_ = 0;
};

// A source, or why the input is unusable (naming the file).
using OpenResult = Result<std::unique_ptr<TelegramSource>>;

// The most bytes one "*" line of a hexdump -C or xxd -a dump may stand for (docs/decisions.md,
// "Hex dumps: what a '*' line stands for"): a dump of a real capture repeats idle or identical
// traffic for far less, and a gap wider than this is reported as missing lines.
inline constexpr std::uint64_t kMaxHexRepeatBytes = 64 * 1024 * 1024;

// How a source reads, beyond format and bus.
struct SourceOptions {
    // The most bytes one "*" line of a hex dump may stand for; 1 to kMaxHexRepeatBytes (the
    // fuzz target fuzz_capture_file lowers it, so that a run stays short).
    std::uint64_t max_hex_repeat_bytes = kMaxHexRepeatBytes;
    // A forced hex input whose first bytes are a text log of VLT 2000 telegrams is read as that
    // text log (`dpscope hex` on standard input).
    bool hex_may_be_text = false;
};

// Opens `path` ("-" for standard input), detecting the format from the content unless `format`
// forces one. `protocol` is what the capture carries: a byte stream is framed by its rules, and
// a pcap or pcapng file must have one of its link types.
OpenResult open_source(const std::string& path, InputFormat format, const ProtocolDescriptor& protocol,
                       const SourceOptions& options = {});

// The same, where the bus may be left to the capture: `protocol` null chooses it from the first
// bytes (choose_bus in capture/bus_tag.hpp: up to 64 KiB of a byte stream, the header and first
// record of a pcap or pcapng file; a stream still arriving is read only until they decide), and
// `choice` says which bus and why. With a `protocol`, the source is of that bus and
// choice.tagged is what a pcap or pcapng file's tag names, if it has one. Either way
// choice.line is the line the file records, if it records one.
OpenResult open_source(const std::string& path, InputFormat format, const ProtocolDescriptor* protocol,
                       BusChoice& choice, const SourceOptions& options = {});

// A source over bytes already in memory (e.g. `dpscope hex` arguments), framed as a raw stream
// of `protocol`.
std::unique_ptr<TelegramSource> memory_source(std::string display_name, Bytes bytes,
                                              const ProtocolDescriptor& protocol);

}  // namespace dpscope
