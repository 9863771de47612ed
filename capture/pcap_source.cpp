#include "capture/pcap_source.hpp"

#include <fmt/format.h>
#include <pcap/pcap.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <limits>
#include <optional>
#include <vector>

#include "core/counted.hpp"

namespace dpscope {

std::string pcap_library_version() {
    std::string_view text = pcap_lib_version();
    constexpr std::string_view kPrefix = "libpcap version ";
    if (text.substr(0, kPrefix.size()) == kPrefix) text.remove_prefix(kPrefix.size());
    return std::string(text);
}

std::string link_type_name(int link_type) {
    for (const ProtocolDescriptor* protocol : protocol_table())
        for (const PcapLinkType& type : protocol->link_types)
            if (type.value == link_type) return std::string(type.name);
    const char* name = pcap_datalink_val_to_name(link_type);
    return name ? name : "unknown";
}

namespace {

// A classic pcap file read through libpcap. The records of a regular file in the usual layout
// (version 2.4, the micro- or nanosecond magic, 16-byte record headers) are read by this class
// itself, a block of 256 KiB at a time, instead of by pcap_next_ex's two freads a record: the
// reading was a quarter of decode -q (issue 31). Any record it does not take as it is (longer than
// the file's snapshot length, cut short by the end of the file, a read error) is handed back to
// libpcap at its byte offset, so what libpcap says and does about such a record is unchanged.
class PcapSource final : public TelegramSource {
  public:
    PcapSource(pcap_t* handle, std::string name, bool classic_pcap)
        : TelegramSource(std::move(name)), handle_(handle), classic_pcap_(classic_pcap) {
        link_type_ = pcap_datalink(handle_);
        if (classic_pcap_) start_block_reading();
    }
    ~PcapSource() override { pcap_close(handle_); }

    InputFormat format() const override {
        return classic_pcap_ ? InputFormat::Pcap : InputFormat::Pcapng;
    }
    int link_type() const override { return link_type_; }
    std::size_t buffered_bytes() const override { return block_.capacity(); }

  protected:
    bool read_next(Record& record) override {
        if (finished_) return false;
        if (block_reading_ && read_from_block(record)) return true;
        if (finished_) return false;
        pcap_pkthdr* header = nullptr;
        const u_char* data = nullptr;
        int rc = pcap_next_ex(handle_, &header, &data);
        if (rc == 1) {
            take(record, Bytes(data, header->caplen),
                 static_cast<std::int64_t>(header->ts.tv_sec) * 1'000'000'000 +
                     static_cast<std::int64_t>(header->ts.tv_usec),
                 header->len);
            return true;
        }
        finished_ = true;
        if (rc == PCAP_ERROR_BREAK) return false;  // end of file
        set_status(InputStatus::Damaged);
        report(Severity::Error,
               fmt::format("{}: {}: {}; decoding stopped after {}", name(), where(number_ + 1),
                           pcap_geterr(handle_), counted(number_, "record", "records")));
        return false;
    }

  private:
    static constexpr std::size_t kBlockBytes = 1 << 18;
    static constexpr std::uint32_t kMagicMicro = 0xA1B2C3D4;
    static constexpr std::uint32_t kMagicNano = 0xA1B23C4D;

    void take(Record& record, Bytes bytes, std::int64_t time_ns, std::uint32_t original_length) {
        ++number_;
        record.bytes = bytes;
        // Exactly 0 (1970-01-01T00:00:00Z) is how captures of untimed input (a raw dump written
        // with decode -w) say "no time".
        record.time_ns = time_ns == 0 ? kNoTime : time_ns;
        record.number = number_;
        record.offset = classic_pcap_ ? offset_ : 0;
        record.original_length = original_length;
        if (bytes.size() < original_length)
            report(Severity::Warning,
                   fmt::format("{}: {}: only {} of {} bytes captured (snapshot length)", name(),
                               where(number_), bytes.size(), original_length),
                   IssueKind::Snapshot);
        offset_ += kPcapRecordHeaderBytes + bytes.size();
    }

    // Whether the file is one this class reads itself: a regular file whose header (read again
    // with pread, libpcap has read it already) has the usual magic and version 2.4.
    void start_block_reading() {
        FILE* file = pcap_file(handle_);
        if (!file) return;
        const int fd = ::fileno(file);
        struct stat info {};
        if (fd < 0 || ::fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) return;
        unsigned char header[kPcapFileHeaderBytes];
        if (::pread(fd, header, sizeof header, 0) != static_cast<ssize_t>(sizeof header)) return;
        const std::uint32_t magic = read_u32(header, false);
        if (magic == kMagicMicro || magic == kMagicNano) {
            swapped_ = false;
        } else if (byte_swapped(magic) == kMagicMicro || byte_swapped(magic) == kMagicNano) {
            swapped_ = true;
        } else {
            return;
        }
        nanoseconds_ = (swapped_ ? byte_swapped(magic) : magic) == kMagicNano;
        if (pcap_major_version(handle_) != 2 || pcap_minor_version(handle_) != 4) return;
        if (pcap_snapshot(handle_) <= 0) return;
        snapshot_ = static_cast<std::uint32_t>(pcap_snapshot(handle_));
        if (snapshot_ > kBlockBytes - kPcapRecordHeaderBytes) return;
        file_ = file;
        block_.resize(kBlockBytes);
        block_reading_ = true;
    }

    static std::uint32_t byte_swapped(std::uint32_t v) noexcept { return __builtin_bswap32(v); }
    std::uint32_t read_u32(const unsigned char* p, bool swapped) const noexcept {
        std::uint32_t v;
        std::memcpy(&v, p, 4);
        return swapped ? byte_swapped(v) : v;
    }

    // At least `wanted` bytes from at_ in the block, reading more when it has fewer; false when the
    // file has no more.
    bool have(std::size_t wanted) {
        if (end_ - at_ >= wanted) return true;
        std::memmove(block_.data(), block_.data() + at_, end_ - at_);
        end_ -= at_;
        at_ = 0;
        while (end_ < wanted) {
            const std::size_t got =
                std::fread(block_.data() + end_, 1, block_.size() - end_, file_);
            if (got == 0) return false;
            end_ += got;
        }
        return true;
    }

    // The next record from the block; false at the end of the file (finished_ set) or when the
    // record goes to libpcap (block reading stopped).
    bool read_from_block(Record& record) {
        if (!have(kPcapRecordHeaderBytes)) {
            if (end_ == at_ && std::feof(file_) && !std::ferror(file_)) {
                finished_ = true;  // the end of the file, after a whole record
                return false;
            }
            return hand_to_libpcap();
        }
        const unsigned char* header = block_.data() + at_;
        const std::uint32_t seconds = read_u32(header, swapped_);
        const std::uint32_t fraction = read_u32(header + 4, swapped_);
        const std::uint32_t caplen = read_u32(header + 8, swapped_);
        const std::uint32_t length = read_u32(header + 12, swapped_);
        if (caplen > snapshot_ || !have(kPcapRecordHeaderBytes + caplen)) return hand_to_libpcap();
        // As libpcap reads them: both fields signed 32-bit, microseconds scaled to nanoseconds.
        const std::int64_t time_ns =
            static_cast<std::int64_t>(static_cast<std::int32_t>(seconds)) * 1'000'000'000 +
            static_cast<std::int64_t>(static_cast<std::int32_t>(fraction)) *
                (nanoseconds_ ? 1 : 1000);
        const Bytes bytes(block_.data() + at_ + kPcapRecordHeaderBytes, caplen);
        at_ += kPcapRecordHeaderBytes + caplen;
        take(record, bytes, time_ns, length);
        return true;
    }

    // libpcap reads on from the record at offset_: what it says about it is what dpscope says.
    bool hand_to_libpcap() {
        block_reading_ = false;
        if (std::fseek(file_, static_cast<long>(offset_), SEEK_SET) != 0) {
            finished_ = true;
            set_status(InputStatus::Damaged);
            report(Severity::Error,
                   fmt::format("{}: {}: cannot read on: {}; decoding stopped after {}", name(),
                               where(number_ + 1), std::strerror(errno),
                               counted(number_, "record", "records")));
        }
        block_ = {};
        return false;
    }

    std::string where(std::uint64_t record) const {
        if (classic_pcap_) return fmt::format("record {} (byte offset {})", record, offset_);
        return fmt::format("record {}", record);
    }

    pcap_t* handle_;
    bool classic_pcap_;
    int link_type_ = 0;
    bool finished_ = false;
    std::uint64_t number_ = 0;
    std::uint64_t offset_ = kPcapFileHeaderBytes;
    // Block reading (see the class comment).
    bool block_reading_ = false;
    FILE* file_ = nullptr;
    bool swapped_ = false;
    bool nanoseconds_ = false;
    std::uint32_t snapshot_ = 0;
    std::vector<unsigned char> block_;
    std::size_t at_ = 0;
    std::size_t end_ = 0;
};

// The protocol's link types as messages list them: "257 (PROFIBUS_DL) and 147 (USER0)", or
// without the parentheses "257 PROFIBUS_DL and 147 USER0".
std::string listed_link_types(const ProtocolDescriptor& protocol, bool name_in_parentheses) {
    std::string list;
    const std::size_t count = protocol.link_types.size();
    for (std::size_t i = 0; i < count; ++i) {
        const PcapLinkType& type = protocol.link_types[i];
        if (i > 0) list += i + 1 == count ? " and " : ", ";
        list += name_in_parentheses ? fmt::format("{} ({})", type.value, type.name)
                                    : fmt::format("{} {}", type.value, type.name);
    }
    return list;
}

std::string unsupported_link_type(const std::string& name, int link_type,
                                  const ProtocolDescriptor& protocol) {
    // A link type another bus is carried by (257 is PROFIBUS only): the capture is of that bus,
    // and the bus option chose another; name the real problem.
    for (const ProtocolDescriptor* other : protocol_table()) {
        if (other->protocol == protocol.protocol || !other->carried_by(link_type)) continue;
        return fmt::format(
            "{}: link type {} ({}) is a {} capture, but --bus {} reads {} telegrams from captures "
            "of link type {} only; leave --bus out (or give --bus {})",
            name, link_type, link_type_name(link_type), other->framing.protocol_name(),
            protocol_name(protocol.protocol), protocol.framing.protocol_name(),
            listed_link_types(protocol, true), protocol_name(other->protocol));
    }
    return fmt::format("{}: unsupported link type {} ({}); dpscope reads {}", name, link_type,
                       link_type_name(link_type), listed_link_types(protocol, true));
}

// pcapng (draft-ietf-opsawg-pcapng), read block by block without libpcap, whose reader refuses a
// second interface with another link type (as mergecap makes them). Every block's length is
// checked against the file and its copy at the block's end; messages name the byte offset.
class PcapngSource final : public TelegramSource {
  public:
    PcapngSource(FILE* file, std::string name, const ProtocolDescriptor& protocol)
        : TelegramSource(std::move(name)), protocol_(protocol), file_(file) {}
    ~PcapngSource() override { std::fclose(file_); }

    InputFormat format() const override { return InputFormat::Pcapng; }
    int link_type() const override { return link_type_; }
    std::size_t buffered_bytes() const override {
        std::size_t messages = 0;
        for (const Pending& p : pending_)
            messages += p.message.capacity();
        return block_.capacity() + interfaces_.capacity() * sizeof(Interface) +
               pending_.capacity() * sizeof(Pending) + messages;
    }

    // Reads up to the first packet dpscope decodes. An error when the file is no pcapng or none
    // of its interfaces has a link type of the protocol.
    Result<void> open();

  protected:
    bool read_next(Record& record) override;

  private:
    struct Interface {
        int link_type = 0;
        std::uint64_t block_offset = 0;
        std::uint32_t snap_length = 0;
        bool binary_resolution = false;  // if_tsresol: units of 2^-exponent s, else 10^-exponent
        unsigned exponent = 6;
        std::int64_t offset_s = 0;  // if_tsoffset
        bool resolution_usable = true;
    };
    enum class Read { Block, End, Damaged };
    struct Pending {
        Severity severity;
        IssueKind kind;
        std::string message;
    };

    // Interfaces kept per section: the packets of those described after them are skipped
    // (docs/decisions.md, "Memory of the readers"); a capture has a handful.
    static constexpr std::size_t kMaxInterfaces = 4096;
    static constexpr std::uint32_t kSectionHeader = 0x0A0D0D0A;
    static constexpr std::uint32_t kInterfaceDescription = 1;
    static constexpr std::uint32_t kObsoletePacket = 2;
    static constexpr std::uint32_t kSimplePacket = 3;
    static constexpr std::uint32_t kEnhancedPacket = 6;
    static constexpr std::uint32_t kMaxBlockBytes = 16 * 1024 * 1024;

    // Reads the next block into block_; Damaged after reporting why.
    Read read_block();
    // What a block means: false when it stops the reading (Damaged or Unusable).
    bool take_section_header();
    void take_interface();
    // A packet block: true and `record` filled when it is one of an interface dpscope decodes.
    bool take_packet(Record& record);

    bool fits(std::size_t position, std::size_t size) const {
        return position <= block_.size() && size <= block_.size() - position;
    }
    std::uint16_t u16(std::size_t at) const {
        std::uint16_t v = 0;
        std::memcpy(&v, block_.data() + at, 2);
        return swap_ ? static_cast<std::uint16_t>(v >> 8 | v << 8) : v;
    }
    std::uint32_t u32(std::size_t at) const {
        std::uint32_t v = 0;
        std::memcpy(&v, block_.data() + at, 4);
        return swap_ ? __builtin_bswap32(v) : v;
    }
    std::uint64_t u64(std::size_t at) const {
        std::uint64_t v = 0;
        std::memcpy(&v, block_.data() + at, 8);
        return swap_ ? __builtin_bswap64(v) : v;
    }
    std::optional<std::int64_t> time_of(const Interface& interface, std::uint64_t units) const;
    void issue(Severity severity, IssueKind kind, std::string message);
    void damaged(std::string message);
    bool packet_block() const {
        return block_type_ == kEnhancedPacket || block_type_ == kObsoletePacket ||
               block_type_ == kSimplePacket;
    }
    // "byte offset 1234", or "record 5 (byte offset 1234)" for a packet block.
    std::string at_block() const {
        if (packet_block())
            return fmt::format("record {} (byte offset {})", packets_ + 1, block_offset_);
        return fmt::format("byte offset {}", block_offset_);
    }

    const ProtocolDescriptor& protocol_;
    FILE* file_;
    std::vector<std::uint8_t> block_;  // the whole current block
    std::uint32_t block_type_ = 0;
    std::uint64_t block_offset_ = 0;
    std::uint64_t file_offset_ = 0;  // bytes read so far
    bool swap_ = false;              // the section's byte order is not the host's
    bool in_section_ = false;
    std::vector<Interface> interfaces_;
    std::uint64_t interfaces_beyond_ = 0;  // described after the first kMaxInterfaces
    int link_type_ = 0;                    // of the first interface of the protocol
    bool decodable_seen_ = false;
    int first_link_type_ = -1;
    std::uint64_t packets_ = 0;  // packet blocks, of every interface (Wireshark's frame numbers)
    bool opening_ = false;
    bool have_pending_packet_ = false;
    bool finished_ = false;
    std::vector<Pending> pending_;
    std::uint64_t pending_of_kind_[kIssueKinds] = {};  // issues met while opening, by kind
    std::string damage_;                               // what stopped the reading
    Record pending_record_;
};

void PcapngSource::issue(Severity severity, IssueKind kind, std::string message) {
    if (opening_) {
        // Those only counted keep no message: kept as a count (read_next() passes them on).
        const std::size_t k = static_cast<std::size_t>(kind);
        if (kind != IssueKind::Other && pending_of_kind_[k]++ >= kMaxIssuesShown) return;
        pending_.push_back(Pending{severity, kind, std::move(message)});
    } else
        report(severity, std::move(message), kind);
}

void PcapngSource::damaged(std::string message) {
    set_status(InputStatus::Damaged);
    damage_ = fmt::format("{}: {}", name(), message);
    issue(Severity::Error, IssueKind::Other,
          fmt::format("{}; decoding stopped after {}", damage_,
                      counted(packets_, "record", "records")));
}

PcapngSource::Read PcapngSource::read_block() {
    block_offset_ = file_offset_;
    block_type_ = 0;
    block_.resize(8);
    std::size_t got = std::fread(block_.data(), 1, 8, file_);
    file_offset_ += got;
    if (got == 0 && !std::ferror(file_)) return Read::End;
    if (got < 8) {
        damaged(std::ferror(file_)
                    ? fmt::format("{}: read error: {}", at_block(), std::strerror(errno))
                    : fmt::format("{}: the file ends inside a block header ({} of 8 bytes)",
                                  at_block(), got));
        return Read::Damaged;
    }
    std::uint32_t raw_type = 0;
    std::memcpy(&raw_type, block_.data(), 4);
    block_type_ = u32(0);
    std::size_t header = 8;
    if (raw_type == kSectionHeader) {  // the same in either byte order
        // The byte-order magic says how to read the length that comes before it.
        block_.resize(12);
        got = std::fread(block_.data() + 8, 1, 4, file_);
        file_offset_ += got;
        if (got < 4) {
            damaged(fmt::format("{}: the file ends inside a section header block", at_block()));
            return Read::Damaged;
        }
        std::uint32_t magic = 0;
        std::memcpy(&magic, block_.data() + 8, 4);
        if (magic == 0x1A2B3C4D) {
            swap_ = false;
        } else if (magic == 0x4D3C2B1A) {
            swap_ = true;
        } else {
            damaged(
                fmt::format("{}: section header block with byte-order magic 0x{:08X}, not "
                            "0x1A2B3C4D",
                            at_block(), magic));
            return Read::Damaged;
        }
        header = 12;
    } else if (!in_section_) {
        damaged(fmt::format("{}: block before the first section header block", at_block()));
        return Read::Damaged;
    }
    block_type_ = u32(0);
    const std::uint32_t length = u32(4);
    const std::uint32_t minimum = block_type_ == kSectionHeader ? 28 : 12;
    if (length < minimum || length % 4 != 0 || length > kMaxBlockBytes) {
        damaged(
            fmt::format("{}: block of type 0x{:08X} gives its length as {} bytes, not a "
                        "multiple of 4 from {} to {}",
                        at_block(), block_type_, length, minimum, kMaxBlockBytes));
        return Read::Damaged;
    }
    block_.resize(length);
    got = std::fread(block_.data() + header, 1, length - header, file_);
    file_offset_ += got;
    if (got < length - header) {
        damaged(std::ferror(file_)
                    ? fmt::format("{}: read error: {}", at_block(), std::strerror(errno))
                    : fmt::format("{}: block of type 0x{:08X} cut off: the file ends after {} "
                                  "of its {} bytes",
                                  at_block(), block_type_, header + got, length));
        return Read::Damaged;
    }
    if (u32(length - 4) != length) {
        damaged(
            fmt::format("{}: block of type 0x{:08X} gives its length as {} bytes at its "
                        "start and {} at its end",
                        at_block(), block_type_, length, u32(length - 4)));
        return Read::Damaged;
    }
    return Read::Block;
}

bool PcapngSource::take_section_header() {
    const std::uint16_t major = u16(12);
    if (major != 1) {
        damaged(
            fmt::format("{}: section header block of pcapng version {}.{}; dpscope reads "
                        "version 1",
                        at_block(), major, u16(14)));
        return false;
    }
    in_section_ = true;
    interfaces_.clear();  // interface ids count from 0 in each section
    interfaces_beyond_ = 0;
    return true;
}

void PcapngSource::take_interface() {
    if (interfaces_.size() >= kMaxInterfaces) {
        if (interfaces_beyond_++ == 0)
            issue(Severity::Warning, IssueKind::Interface,
                  fmt::format("{}: {}: the section describes more than {} interfaces; the "
                              "packets of those after the {}th are skipped",
                              name(), at_block(), kMaxInterfaces, kMaxInterfaces));
        return;
    }
    Interface interface;
    interface.block_offset = block_offset_;
    const std::size_t body_end = block_.size() - 4;
    if (block_.size() < 20) {
        issue(Severity::Warning, IssueKind::Interface,
              fmt::format("{}: {}: interface description block of {} bytes is too short (at "
                          "least 20); its packets are skipped",
                          name(), at_block(), block_.size()));
        interfaces_.push_back(Interface{-1, block_offset_, 0, false, 6, 0, false});
        return;
    }
    interface.link_type = u16(8);
    interface.snap_length = u32(12);
    // Options: code, length, value padded to 4 bytes; code 0 ends them.
    for (std::size_t at = 16; at + 4 <= body_end;) {
        const std::uint16_t code = u16(at);
        const std::uint16_t length = u16(at + 2);
        if (code == 0) break;
        const std::size_t padded = (static_cast<std::size_t>(length) + 3) / 4 * 4;
        if (!fits(at + 4, padded) || at + 4 + padded > body_end) {
            issue(Severity::Warning, IssueKind::Interface,
                  fmt::format("{}: byte offset {}: interface option {} runs past the end of its "
                              "block; the options after it are ignored",
                              name(), block_offset_ + at, code));
            break;
        }
        if (code == 9 && length == 1) {  // if_tsresol
            const std::uint8_t resolution = block_[at + 4];
            interface.binary_resolution = (resolution & 0x80) != 0;
            interface.exponent = resolution & 0x7F;
            interface.resolution_usable =
                interface.binary_resolution ? interface.exponent <= 63 : interface.exponent <= 18;
        } else if (code == 14 && length == 8) {  // if_tsoffset
            interface.offset_s = static_cast<std::int64_t>(u64(at + 4));
        }
        at += 4 + padded;
    }
    const std::size_t id = interfaces_.size();
    interfaces_.push_back(interface);
    if (first_link_type_ < 0) first_link_type_ = interface.link_type;
    if (protocol_.carried_by(interface.link_type)) {
        if (!decodable_seen_) link_type_ = interface.link_type;
        decodable_seen_ = true;
    } else {
        issue(
            Severity::Warning, IssueKind::Interface,
            fmt::format("{}: {}: interface {} has link type {} ({}), which dpscope does not "
                        "decode (it reads {}); its packets are skipped",
                        name(), at_block(), id, interface.link_type,
                        link_type_name(interface.link_type), listed_link_types(protocol_, false)));
    }
    if (!interface.resolution_usable)
        issue(Severity::Warning, IssueKind::Interface,
              fmt::format("{}: {}: interface {} has a timestamp resolution of {}^-{} s, finer "
                          "than dpscope can convert; its packets have no times",
                          name(), at_block(), id, interface.binary_resolution ? 2 : 10,
                          interface.exponent));
}

std::optional<std::int64_t> PcapngSource::time_of(const Interface& interface,
                                                  std::uint64_t units) const {
    if (!interface.resolution_usable) return std::nullopt;
    std::uint64_t seconds = 0, nanos = 0;
    if (interface.binary_resolution) {
        const unsigned e = interface.exponent;
        seconds = e == 0 ? units : units >> e;
        std::uint64_t fraction = e == 0 ? 0 : units & ((std::uint64_t{1} << e) - 1);
        unsigned shift = e;
        if (shift > 34) {  // keep fraction * 1e9 within 64 bits
            fraction >>= shift - 34;
            shift = 34;
        }
        nanos = (fraction * 1'000'000'000ULL) >> shift;
    } else {
        std::uint64_t scale = 1;
        for (unsigned i = 0; i < interface.exponent; ++i)
            scale *= 10;
        seconds = units / scale;
        std::uint64_t fraction = units % scale;
        if (interface.exponent <= 9) {
            std::uint64_t up = 1;
            for (unsigned i = interface.exponent; i < 9; ++i)
                up *= 10;
            nanos = fraction * up;
        } else {
            std::uint64_t down = 1;
            for (unsigned i = 9; i < interface.exponent; ++i)
                down *= 10;
            nanos = fraction / down;
        }
    }
    constexpr std::int64_t kMaxSeconds =
        std::numeric_limits<std::int64_t>::max() / 1'000'000'000 - 1;
    if (seconds > static_cast<std::uint64_t>(kMaxSeconds)) return std::nullopt;
    // if_tsoffset is any int64: the sum is checked, not assumed to fit.
    std::int64_t total = 0;
    if (__builtin_add_overflow(static_cast<std::int64_t>(seconds), interface.offset_s, &total) ||
        total > kMaxSeconds || total < -kMaxSeconds)
        return std::nullopt;
    return total * 1'000'000'000 + static_cast<std::int64_t>(nanos);
}

bool PcapngSource::take_packet(Record& record) {
    const std::string where = at_block();
    const std::size_t body_end = block_.size() - 4;
    std::uint32_t interface_id = 0;
    std::uint64_t units = 0;
    bool timed = true;
    std::size_t data_at = 0;
    std::uint32_t captured = 0, original = 0;
    if (block_type_ == kEnhancedPacket || block_type_ == kObsoletePacket) {
        if (body_end < 28) {
            damaged(fmt::format("{}: packet block of {} bytes is too short for its header", where,
                                block_.size()));
            return false;
        }
        interface_id = block_type_ == kEnhancedPacket ? u32(8) : u16(8);
        units = std::uint64_t{u32(12)} << 32 | u32(16);
        captured = u32(20);
        original = u32(24);
        data_at = 28;
    } else {  // simple packet block: interface 0, no time, captured as much as the block holds
        if (body_end < 12) {
            damaged(fmt::format("{}: simple packet block of {} bytes is too short", where,
                                block_.size()));
            return false;
        }
        timed = false;
        original = u32(8);
        data_at = 12;
        captured = static_cast<std::uint32_t>(std::min<std::size_t>(original, body_end - 12));
        if (!interfaces_.empty() && interfaces_[0].snap_length != 0)
            captured = std::min(captured, interfaces_[0].snap_length);
    }
    if (captured > body_end - data_at) {
        damaged(
            fmt::format("{}: captured length {} runs past the end of its block ({} bytes "
                        "of data)",
                        where, captured, body_end - data_at));
        return false;
    }
    ++packets_;
    if (interface_id >= interfaces_.size()) {
        if (interface_id - interfaces_.size() < interfaces_beyond_) return false;  // named
        issue(Severity::Warning, IssueKind::Interface,
              fmt::format("{}: {}: packet of interface {}, but the section describes {}; skipped",
                          name(), where, interface_id, interfaces_.size()));
        return false;
    }
    const Interface& interface = interfaces_[interface_id];
    if (!protocol_.carried_by(interface.link_type)) return false;  // named at its description
    record.bytes = Bytes(block_.data() + data_at, captured);
    record.time_ns = kNoTime;
    if (timed) {
        if (auto time = time_of(interface, units)) {
            record.time_ns = *time == 0 ? kNoTime : *time;  // 0: untimed, as in classic pcap
        } else if (interface.resolution_usable) {
            issue(Severity::Warning, IssueKind::BadTime,
                  fmt::format("{}: {}: timestamp outside 1677-09-21 to 2262-04-11; the record has "
                              "no time",
                              name(), where));
        }
    }
    record.number = packets_;
    record.offset = block_offset_;
    record.original_length = original;
    if (captured < original)
        issue(Severity::Warning, IssueKind::Snapshot,
              fmt::format("{}: {}: only {} of {} bytes captured (snapshot length)", name(), where,
                          captured, original));
    return true;
}

Result<void> PcapngSource::open() {
    opening_ = true;
    Read first = read_block();
    if (first != Read::Block || block_type_ != kSectionHeader)
        return Error{damage_.empty() ? fmt::format("{}: not a pcapng file", name()) : damage_};
    if (!take_section_header()) return Error{damage_};
    // Up to the first packet dpscope decodes, so that a file with none is refused here.
    for (;;) {
        Read read = read_block();
        if (read != Read::Block) {
            finished_ = true;
            break;
        }
        if (block_type_ == kSectionHeader) {
            if (!take_section_header()) {
                finished_ = true;
                break;
            }
        } else if (block_type_ == kInterfaceDescription) {
            take_interface();
        } else if (block_type_ == kEnhancedPacket || block_type_ == kObsoletePacket ||
                   block_type_ == kSimplePacket) {
            if (take_packet(pending_record_)) {
                have_pending_packet_ = true;
                break;
            }
            if (status() == InputStatus::Damaged) {
                finished_ = true;
                break;
            }
        }
    }
    opening_ = false;
    if (!decodable_seen_ && first_link_type_ >= 0 && status() != InputStatus::Damaged)
        return Error{unsupported_link_type(name(), first_link_type_, protocol_)};
    // No interface at all: an empty capture, of the protocol's first link type (none: a protocol
    // no pcap file carries, and the capture has no link type to pass on).
    if (!decodable_seen_)
        link_type_ = protocol_.link_types.empty() ? -1 : protocol_.link_types.front().value;
    return {};
}

bool PcapngSource::read_next(Record& record) {
    if (!pending_.empty()) {
        for (Pending& p : pending_)
            report(p.severity, std::move(p.message), p.kind);
        pending_.clear();
        pending_.shrink_to_fit();
        for (std::size_t k = 0; k < kIssueKinds; ++k)
            if (pending_of_kind_[k] > kMaxIssuesShown)
                count_hidden(static_cast<IssueKind>(k), pending_of_kind_[k] - kMaxIssuesShown, 0);
    }
    if (have_pending_packet_) {
        have_pending_packet_ = false;
        record = pending_record_;
        return true;
    }
    while (!finished_) {
        Read read = read_block();
        if (read != Read::Block) break;
        if (block_type_ == kSectionHeader) {
            if (!take_section_header()) break;
        } else if (block_type_ == kInterfaceDescription) {
            take_interface();
        } else if (block_type_ == kEnhancedPacket || block_type_ == kObsoletePacket ||
                   block_type_ == kSimplePacket) {
            if (take_packet(record)) return true;
            if (status() == InputStatus::Damaged) break;
        }
        // Other blocks (name resolution, statistics, secrets, custom) say nothing dpscope uses.
    }
    finished_ = true;
    return false;
}

}  // namespace

OpenResult open_pcapng_source(FILE* file, const std::string& name,
                              const ProtocolDescriptor& protocol) {
    auto source = std::make_unique<PcapngSource>(file, name, protocol);
    if (Result<void> opened = source->open(); !opened) return Error{opened.error()};
    return source;
}

OpenResult open_pcap_source(FILE* file, const std::string& name, bool classic_pcap,
                            const ProtocolDescriptor& protocol) {
    char errbuf[PCAP_ERRBUF_SIZE] = {};
    pcap_t* handle =
        pcap_fopen_offline_with_tstamp_precision(file, PCAP_TSTAMP_PRECISION_NANO, errbuf);
    if (!handle) {
        std::fclose(file);
        return Error{fmt::format("{}: not a readable pcap or pcapng file: {}", name, errbuf)};
    }
    int link_type = pcap_datalink(handle);
    if (!protocol.carried_by(link_type)) {
        pcap_close(handle);
        return Error{unsupported_link_type(name, link_type, protocol)};
    }
    return std::make_unique<PcapSource>(handle, name, classic_pcap);
}

}  // namespace dpscope
