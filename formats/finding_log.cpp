#include "formats/finding_log.hpp"

#include <cerrno>
#include <cstring>

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

}  // namespace

FindingLog::~FindingLog() {
    if (spill_) std::fclose(spill_);
}

void FindingLog::append(std::span<const Finding> findings) {
    for (const Finding& f : findings) {
        memory_.push_back(f);
        ++count_;
    }
    if (memory_.size() >= kKeepInMemory) spill();
}

void FindingLog::spill() {
    if (!spill_ && lost_.empty()) {
        spill_ = std::tmpfile();
        if (!spill_) lost_ = std::string("cannot create a temporary file: ") + std::strerror(errno);
    }
    if (!spill_) {
        // Keep what fits; the rest is counted but cannot be listed.
        memory_.resize(kKeepInMemory);
        return;
    }
    for (const Finding& f : memory_) {
        SpilledFinding s{f.frame,
                         f.request_frame,
                         f.time_ns,
                         static_cast<std::uint32_t>(f.message.size()),
                         f.pnu.value_or(0),
                         static_cast<std::uint8_t>(f.kind),
                         static_cast<std::uint8_t>(f.severity),
                         f.master,
                         f.slave,
                         static_cast<std::uint8_t>((f.has_stations ? 1 : 0) | (f.pnu ? 2 : 0))};
        if (std::fwrite(&s, sizeof s, 1, spill_) != 1 ||
            std::fwrite(f.message.data(), 1, f.message.size(), spill_) != f.message.size()) {
            lost_ = std::string("cannot write the temporary file: ") + std::strerror(errno);
            break;
        }
    }
    memory_.clear();
}

void FindingLog::for_each(const std::function<void(const Finding&)>& f) const {
    if (spill_) {
        std::fflush(spill_);
        std::rewind(spill_);
        SpilledFinding s{};
        Finding finding;
        while (std::fread(&s, sizeof s, 1, spill_) == 1) {
            finding.frame = s.frame;
            finding.request_frame = s.request_frame;
            finding.time_ns = s.time_ns;
            finding.kind = static_cast<FindingKind>(s.kind);
            finding.severity = static_cast<Severity>(s.severity);
            finding.master = s.master;
            finding.slave = s.slave;
            finding.has_stations = (s.flags & 1) != 0;
            finding.pnu = (s.flags & 2) ? std::optional<std::uint16_t>(s.pnu) : std::nullopt;
            finding.message.resize(s.message_length);
            if (std::fread(finding.message.data(), 1, s.message_length, spill_) !=
                s.message_length) {
                if (lost_.empty()) lost_ = "cannot read the temporary file of findings back";
                std::fseek(spill_, 0, SEEK_END);
                return;
            }
            f(finding);
        }
        std::fseek(spill_, 0, SEEK_END);
    }
    for (const Finding& finding : memory_)
        f(finding);
}

}  // namespace dpscope
