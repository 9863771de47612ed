#include "formats/finding_log.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <span>

namespace dpscope {

namespace {

// Fixed part of a spilled finding, followed by the message bytes.
struct SpilledFinding {
    std::uint64_t frame;
    std::uint64_t request_frame;
    std::int64_t time_ns;
    std::uint32_t message_length;
    std::uint16_t pnu;
    std::uint8_t kind;
    std::uint8_t severity;
    std::uint8_t master;
    std::uint8_t slave;
    std::uint8_t flags;  // bit 0: has_stations, bit 1: has pnu
};

// Kind, severity and stations in one key: kind << 19 | severity << 17 | has_stations << 16 |
// master << 8 | slave.
std::uint32_t tally_key(const Finding& f) {
    const std::uint32_t stations =
        f.has_stations ? (1u << 16 | static_cast<std::uint32_t>(f.master) << 8 | f.slave) : 0u;
    return static_cast<std::uint32_t>(f.kind) << 19 | static_cast<std::uint32_t>(f.severity) << 17 |
           stations;
}

// Appends `f` to `records` as a SpilledFinding and its message's bytes.
void add_record(std::vector<char>& records, const Finding& f) {
    SpilledFinding s;
    std::memset(&s, 0, sizeof s);  // the padding too: the file holds no uninitialised bytes
    s.frame = f.frame;
    s.request_frame = f.request_frame;
    s.time_ns = f.time_ns;
    s.message_length = static_cast<std::uint32_t>(f.message.size());
    s.pnu = f.pnu.value_or(0);
    s.kind = static_cast<std::uint8_t>(f.kind);
    s.severity = static_cast<std::uint8_t>(f.severity);
    s.master = f.master;
    s.slave = f.slave;
    s.flags = static_cast<std::uint8_t>((f.has_stations ? 1 : 0) | (f.pnu ? 2 : 0));
    const std::size_t at = records.size();
    records.resize(at + sizeof s + f.message.size());
    std::memcpy(records.data() + at, &s, sizeof s);
    if (!f.message.empty())
        std::memcpy(records.data() + at + sizeof s, f.message.data(), f.message.size());
}

// Calls f for each whole record at the start of `bytes` (into `finding`, reused); returns the
// bytes they took (a record cut off at the end is left).
template <class F>
std::size_t read_records(std::span<const char> bytes, Finding& finding, std::uint64_t& given,
                         const F& f) {
    std::size_t at = 0;
    while (bytes.size() - at >= sizeof(SpilledFinding)) {
        SpilledFinding s{};
        std::memcpy(&s, bytes.data() + at, sizeof s);
        if (bytes.size() - at - sizeof s < s.message_length) break;
        finding.frame = s.frame;
        finding.request_frame = s.request_frame;
        finding.time_ns = s.time_ns;
        finding.kind = static_cast<FindingKind>(s.kind);
        finding.severity = static_cast<Severity>(s.severity);
        finding.master = s.master;
        finding.slave = s.slave;
        finding.has_stations = (s.flags & 1) != 0;
        finding.pnu = (s.flags & 2) ? std::optional<std::uint16_t>(s.pnu) : std::nullopt;
        finding.message.assign(bytes.data() + at + sizeof s, s.message_length);
        at += sizeof s + s.message_length;
        ++given;
        f(finding);
    }
    return at;
}

// Writes all of `bytes` at the file's end; false (errno set) when a write failed.
bool write_all(int fd, const std::vector<char>& bytes) {
    std::size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            if (n == 0) errno = ENOSPC;
            return false;
        }
        done += static_cast<std::size_t>(n);
    }
    return true;
}

}  // namespace

std::string default_spill_folder() {
    const char* folder = std::getenv("TMPDIR");
    return folder && *folder ? std::string(folder) : std::string("/tmp");
}

FindingLog::FindingLog(std::string spill_folder) : spill_folder_(std::move(spill_folder)) {}

FindingLog::~FindingLog() {
    if (spill_fd_ >= 0) ::close(spill_fd_);
}

void FindingLog::append(std::span<const Finding> findings) {
    for (const Finding& f : findings) {
        ++count_;
        // Findings come in runs of one kind at one station: the last tally is tried first.
        const std::uint32_t key = tally_key(f);
        if (last_tally_ == nullptr || key != last_tally_key_) [[unlikely]] {
            last_tally_ = &tallies_[key];
            last_tally_key_ = key;
        }
        ++*last_tally_;
        if (spill_failed_ && in_memory_ >= kKeepInMemory) {
            ++unlisted_;
            continue;
        }
        // Room for a batch up front (spilled at kKeepInMemory findings): no growing copies.
        if (records_.capacity() == 0) [[unlikely]]
            records_.reserve(kKeepInMemory * kRecordBytesGuess);
        add_record(records_, f);
        ++in_memory_;
        if (in_memory_ >= kKeepInMemory && !spill_failed_) spill();
    }
}

void FindingLog::spill() {
    if (spill_fd_ < 0) {
        // An anonymous file: made, then unlinked at once, so nothing is left behind.
        std::string pattern = spill_folder_ + "/dpscope-findings-XXXXXX";
        spill_fd_ = ::mkostemp(pattern.data(), O_CLOEXEC);
        if (spill_fd_ < 0) {
            lost_ = fmt::format("cannot make a temporary file in {}: {}", spill_folder_,
                                std::strerror(errno));
            spill_failed_ = true;
            return;
        }
        ::unlink(pattern.c_str());
    }
    if (!write_all(spill_fd_, records_)) {
        // Cut the file back to its whole records; the findings of this batch stay in memory
        // (after those in the file: capture order), later ones are only counted.
        lost_ = fmt::format("cannot write the temporary file in {}: {}", spill_folder_,
                            std::strerror(errno));
        spill_failed_ = true;
        if (::ftruncate(spill_fd_, static_cast<off_t>(spilled_bytes_)) != 0) {
            // The file cannot be cut back: its records are read up to spilled_bytes_ only.
        }
        return;
    }
    spilled_bytes_ += records_.size();
    spilled_ += in_memory_;
    records_.clear();
    in_memory_ = 0;
}

void FindingLog::for_each(const std::function<void(const Finding&)>& f) const {
    Finding finding;          // each record read into it in turn
    std::uint64_t given = 0;  // of the spilled findings
    if (spilled_bytes_ > 0) {
        // Read back in chunks of 64 KiB into one buffer; a record that spans two chunks (its
        // start left over, `held` bytes) is moved to the buffer's front and completed there.
        constexpr std::size_t kChunk = std::size_t{1} << 16;
        std::vector<char> buffer(kChunk);
        std::size_t held = 0;
        std::uint64_t offset = 0;
        while (offset < spilled_bytes_) {
            if (buffer.size() - held < kChunk) buffer.resize(held + kChunk);  // a long record
            const std::size_t want =
                static_cast<std::size_t>(std::min<std::uint64_t>(kChunk, spilled_bytes_ - offset));
            const ssize_t got =
                ::pread(spill_fd_, buffer.data() + held, want, static_cast<off_t>(offset));
            if (got <= 0) {
                if (got < 0 && errno == EINTR) continue;
                lost_ = fmt::format("cannot read the temporary file of findings back: {}",
                                    got < 0 ? std::strerror(errno) : "it is shorter than written");
                unreadable_ = spilled_ - given;
                return;
            }
            offset += static_cast<std::uint64_t>(got);
            const std::size_t filled = held + static_cast<std::size_t>(got);
            const std::size_t at =
                read_records(std::span<const char>(buffer.data(), filled), finding, given, f);
            held = filled - at;
            if (held > 0) std::memmove(buffer.data(), buffer.data() + at, held);
        }
        unreadable_ = 0;
    }
    std::uint64_t kept = 0;
    read_records(records_, finding, kept, f);
}

void FindingLog::for_each_tally(const std::function<void(const FindingTally&)>& f) const {
    for (const auto& [key, count] : tallies_) {
        FindingTally tally;
        tally.kind = static_cast<FindingKind>(key >> 19);
        tally.severity = static_cast<Severity>((key >> 17) & 3);
        tally.has_stations = (key >> 16 & 1) != 0;
        tally.master = static_cast<std::uint8_t>(key >> 8);
        tally.slave = static_cast<std::uint8_t>(key);
        tally.count = count;
        f(tally);
    }
}

}  // namespace dpscope
