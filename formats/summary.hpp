// Counts kept while decoding (cheap enough for every telegram) and the summary `decode -q`
// prints: telegrams by frame type and service, problems by kind, findings by kind, and per
// slave the PPO layout in use; for an FC protocol capture telegrams by block and by AK, and per
// drive its requests and responses.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>

#include "decoder/bus_decoder.hpp"
#include "decoder/finding.hpp"
#include "decoder/session_tracker.hpp"
#include "formats/output.hpp"

namespace dpscope {

struct InputSummary {
    std::string name;
    std::string format;  // "pcap", "pcapng", "raw", "hex"
    std::uint64_t bytes_skipped = 0;
    bool damaged = false;  // reading stopped early
};

// The hint for a slave whose parameter-channel codes fit another dialect than the one it was
// decoded with ("" when there is none): "its parameter-channel codes fit the profidrive dialect
// (2041 telegrams carry codes vlt does not define); decode with --dialect 3=profidrive".
std::string dialect_hint_text(std::uint8_t slave, Dialect decoded, const DialectEvidence& evidence);

class Summary {
  public:
    void add(const DecodedTelegram& t) noexcept {
        if (t.protocol == Protocol::Fc) {
            add_fc(t);
            return;
        }
        ++telegrams_;
        ++frame_types_[static_cast<std::size_t>(t.dp.fdl.type)];
        auto service = static_cast<std::size_t>(t.dp.service);
        if (t.direction == Direction::Request)
            ++requests_[service];
        else
            ++responses_[service];
        if (!t.problems().empty()) {
            ++with_problems_;
            for (const Problem& p : t.problems())
                ++problems_[static_cast<std::size_t>(p.kind)];
        }
        if (t.has_time()) {
            if (first_time_ == kNoTime) first_time_ = t.time_ns;
            last_time_ = t.time_ns;
        }
        if (t.has_roles) slave_seen_[t.slave & 0x7F] = true;
        if (t.dp.service == Service::DataExchange && t.has_roles) {
            ++data_exchange_[t.slave & 0x7F];
            dialects_[t.slave & 0x7F].add(t);
        }
    }

    void add_findings(std::span<const Finding> findings) noexcept {
        for (const Finding& f : findings) {
            ++findings_[static_cast<std::size_t>(f.kind)];
            ++findings_by_severity_[static_cast<std::size_t>(f.kind)]
                                   [static_cast<std::size_t>(f.severity)];
        }
    }

    std::uint64_t telegrams() const noexcept { return telegrams_; }
    std::uint64_t with_problems() const noexcept { return with_problems_; }
    std::uint64_t problems(ProblemKind kind) const noexcept {
        return problems_[static_cast<std::size_t>(kind)];
    }
    std::uint64_t findings(FindingKind kind) const noexcept {
        return findings_[static_cast<std::size_t>(kind)];
    }
    std::uint64_t requests(Service s) const noexcept {
        return requests_[static_cast<std::size_t>(s)];
    }
    std::uint64_t responses(Service s) const noexcept {
        return responses_[static_cast<std::size_t>(s)];
    }
    std::int64_t first_time_ns() const noexcept { return first_time_; }
    std::int64_t last_time_ns() const noexcept { return last_time_; }
    std::uint64_t data_exchange(std::uint8_t slave) const noexcept {
        return data_exchange_[slave & 0x7F];
    }
    const DialectEvidence& dialect_evidence(std::uint8_t slave) const noexcept {
        return dialects_[slave & 0x7F];
    }

    // FC protocol telegrams counted (by block, by AK, per drive).
    std::uint64_t fc_telegrams() const noexcept { return fc_telegrams_; }
    std::uint64_t fc_blocks(FcBlock block) const noexcept {
        return fc_blocks_[static_cast<std::size_t>(block)];
    }
    std::uint64_t fc_commands(std::uint8_t ak) const noexcept { return fc_commands_[ak & 0x0F]; }
    std::uint64_t fc_responses(std::uint8_t ak) const noexcept { return fc_responses_[ak & 0x0F]; }

    // The text summary: PROFIBUS frame types and services, or, for an FC capture, FC blocks,
    // AKs and drives.
    void render_text(Output& out, const InputSummary& input, const BusDecoder& decoder) const;

  private:
    void add_fc(const DecodedTelegram& t) noexcept {
        ++telegrams_;
        ++fc_telegrams_;
        const FcTelegram& fc = t.fc;
        ++fc_blocks_[static_cast<std::size_t>(fc.block)];
        const bool request = t.direction == Direction::Request;
        ++(request ? fc_requests_ : fc_responses_total_);
        if (fc.has_pkw) ++(request ? fc_commands_ : fc_responses_)[fc.pkw.rc & 0x0F];
        if (fc.broadcast) ++fc_broadcasts_;
        if (!t.problems().empty()) {
            ++with_problems_;
            for (const Problem& p : t.problems())
                ++problems_[static_cast<std::size_t>(p.kind)];
        }
        if (t.has_time()) {
            if (first_time_ == kNoTime) first_time_ = t.time_ns;
            last_time_ = t.time_ns;
        }
        if (t.has_roles && !fc.broadcast) {
            slave_seen_[t.slave & 0x7F] = true;
            ++(request ? fc_drive_requests_ : fc_drive_responses_)[t.slave & 0x7F];
        }
    }
    void render_dp_counts(fmt::memory_buffer& b) const;
    void render_fc_counts(fmt::memory_buffer& b) const;
    void render_fc_drives(fmt::memory_buffer& b) const;

    std::uint64_t telegrams_ = 0;
    std::uint64_t with_problems_ = 0;
    std::array<std::uint64_t, 6> frame_types_{};
    std::array<std::uint64_t, kServiceCount> requests_{};
    std::array<std::uint64_t, kServiceCount> responses_{};
    std::array<std::uint64_t, kProblemKindCount> problems_{};
    std::array<std::uint64_t, kFindingKindCount> findings_{};
    // Per kind, by the severity each finding had (options and rules can change the default).
    std::array<std::array<std::uint64_t, 3>, kFindingKindCount> findings_by_severity_{};
    std::array<std::uint64_t, kStationCount> data_exchange_{};
    std::array<bool, kStationCount> slave_seen_{};  // a telegram to or from it was added
    std::array<DialectEvidence, kStationCount> dialects_{};
    std::int64_t first_time_ = kNoTime;
    std::int64_t last_time_ = kNoTime;
    std::uint64_t fc_telegrams_ = 0;
    std::array<std::uint64_t, 4> fc_blocks_{};
    std::uint64_t fc_requests_ = 0;
    std::uint64_t fc_responses_total_ = 0;
    std::uint64_t fc_broadcasts_ = 0;
    std::array<std::uint64_t, 16> fc_commands_{};   // requests by AK
    std::array<std::uint64_t, 16> fc_responses_{};  // responses by AK
    std::array<std::uint64_t, kStationCount> fc_drive_requests_{};
    std::array<std::uint64_t, kStationCount> fc_drive_responses_{};
};

}  // namespace dpscope
