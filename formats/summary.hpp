// Counts kept while decoding (cheap enough for every telegram) and the summary `decode -q`
// prints: telegrams by frame type and service, problems by kind, findings by kind, and per
// slave the PPO layout in use; for an FC protocol capture telegrams by block and by AK, and per
// drive its commands (by outcome, from the FC tracker) and responses; for a VLT 2000 capture
// telegrams by letter, failures by reason, checksum errors and per address its commands (by
// outcome, from the VLT 2000 tracker) and replies.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>

#include "core/finding.hpp"
#include "core/protocol_lane.hpp"
#include "formats/output.hpp"
#include "protocols/fc/fc_tracker.hpp"
#include "protocols/profibus/bus_decoder.hpp"
#include "protocols/profibus/session_tracker.hpp"
#include "protocols/vlt2000/vlt2000_tracker.hpp"

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
        // What every bus has, then the bus's own counts.
        ++telegrams_;
        if (!t.problems().empty()) {
            ++with_problems_;
            for (const Problem& p : t.problems())
                ++problems_[static_cast<std::size_t>(p.kind)];
        }
        if (t.has_time()) {
            if (first_time_ == kNoTime) first_time_ = t.time_ns;
            last_time_ = t.time_ns;
        }
        if (t.protocol == Protocol::Fc) {
            add_fc(t);
            return;
        }
        if (t.protocol == Protocol::Vlt2000) {
            add_vlt2000(t);
            return;
        }
        if (t.protocol != Protocol::ProfibusDp) {
            add_other(t);
            return;
        }
        ++frame_types_[static_cast<std::size_t>(t.dp.fdl.type)];
        auto service = static_cast<std::size_t>(t.dp.service);
        if (t.direction == Direction::Request)
            ++requests_[service];
        else
            ++responses_[service];
        if (t.has_roles) slave_seen_[t.slave & 0x7F] = true;
        if (t.dp.service == Service::DataExchange && t.has_roles) {
            ++data_exchange_[t.slave & 0x7F];
            if (t.dp.ppo.has_pcv) pcv_seen_[t.slave & 0x7F] = true;
            dialects_[t.slave & 0x7F].add(t);
        } else if (t.has_roles &&
                   (t.dp.service == Service::SetPrm || t.dp.service == Service::SlaveDiag)) {
            dialects_[t.slave & 0x7F].add(t);  // the ident number
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
    // A drive's telegrams by direction, damaged ones too (the broadcasts are no drive's).
    std::uint64_t fc_drive_requests(std::uint8_t address) const noexcept {
        return fc_drive_requests_[address & 0x7F];
    }
    std::uint64_t fc_drive_responses(std::uint8_t address) const noexcept {
        return fc_drive_responses_[address & 0x7F];
    }
    std::uint64_t fc_responses(std::uint8_t ak) const noexcept { return fc_responses_[ak & 0x0F]; }

    // VLT 2000 telegrams counted (by letter and direction, failures, checksums, per address).
    struct Vlt2000AddressCounts {
        std::uint64_t commands = 0;
        std::uint64_t replies = 0;
        std::uint64_t failed = 0;
        std::uint64_t checksum_errors = 0;
        std::uint64_t checksum_disabled = 0;
    };
    std::uint64_t vlt2000_telegrams() const noexcept { return vlt2000_telegrams_; }
    std::uint64_t vlt2000_commands(Vlt2000Letter letter) const noexcept {
        return vlt2000_commands_[static_cast<std::size_t>(letter)];
    }
    std::uint64_t vlt2000_replies(Vlt2000Letter letter) const noexcept {
        return vlt2000_replies_[static_cast<std::size_t>(letter)];
    }
    std::uint64_t vlt2000_broadcasts() const noexcept { return vlt2000_broadcasts_; }
    std::uint64_t vlt2000_failed() const noexcept { return vlt2000_failed_; }
    // Failed replies by reason code (100: none given).
    std::uint64_t vlt2000_failed_by_reason(std::size_t reason) const noexcept {
        return reason < vlt2000_reasons_.size() ? vlt2000_reasons_[reason] : 0;
    }
    std::uint64_t vlt2000_checksum_errors() const noexcept { return vlt2000_checksum_errors_; }
    std::uint64_t vlt2000_checksum_disabled() const noexcept { return vlt2000_checksum_disabled_; }
    const Vlt2000AddressCounts& vlt2000_address(std::uint8_t address) const noexcept {
        return vlt2000_addresses_[address & 0x7F];
    }

    // The text summary: PROFIBUS frame types and services, or, for an FC capture, FC blocks,
    // AKs and drives, or, for a VLT 2000 capture, letters, failures, checksums and addresses;
    // for a bus it has no counts of its own for, what every bus has (telegrams, problems,
    // findings). `decoder`: the capture's (a PROFIBUS one names each slave's layout); `tracker`:
    // the capture's, whose per-drive commands by outcome the FC and VLT 2000 summaries name (the
    // same counts as the report's); null: the telegram counts alone (the --pnu selection).
    void render_text(Output& out, const InputSummary& input, const TelegramDecoder& decoder,
                     const TelegramTracker* tracker = nullptr) const;

  private:
    // A telegram of a bus without counts of its own here (add() counted what every bus has).
    void add_other(const DecodedTelegram& t) noexcept {
        ++other_telegrams_;
        if (t.has_roles) slave_seen_[t.slave & 0x7F] = true;
    }
    void add_fc(const DecodedTelegram& t) noexcept {
        ++fc_telegrams_;
        const FcTelegram& fc = t.fc;
        ++fc_blocks_[static_cast<std::size_t>(fc.block)];
        const bool request = t.direction == Direction::Request;
        ++(request ? fc_requests_ : fc_responses_total_);
        if (fc.has_pkw) ++(request ? fc_commands_ : fc_responses_)[fc.pkw.rc & 0x0F];
        if (fc.broadcast) ++fc_broadcasts_;
        if (t.has_roles && !fc.broadcast) {
            slave_seen_[t.slave & 0x7F] = true;
            ++(request ? fc_drive_requests_ : fc_drive_responses_)[t.slave & 0x7F];
        }
    }
    void add_vlt2000(const DecodedTelegram& t) noexcept {
        ++vlt2000_telegrams_;
        const Vlt2000Telegram& v = t.vlt2000;
        const bool request = t.direction == Direction::Request;
        if (t.has_roles) {
            const auto letter = static_cast<std::size_t>(v.letter);
            ++(request ? vlt2000_commands_ : vlt2000_replies_)[letter];
            if (request && v.broadcast) ++vlt2000_broadcasts_;
        }
        // What a reply says is read from intact ones only (as the report does): a damaged one
        // is counted, its content not trusted.
        bool intact = true;
        for (const Problem& p : v.problems)
            intact = intact && problem_severity(p.kind) != Severity::Error;
        const bool failed = v.failed && intact;
        if (failed) {
            ++vlt2000_failed_;
            ++vlt2000_reasons_[v.has_reason ? v.reason : kVlt2000NoReason];
        }
        // A wrong checksum judged so (not with --vlt2000-checksum ignore).
        bool checksum_error = false;
        for (const Problem& p : v.problems)
            checksum_error = checksum_error || p.kind == ProblemKind::Vlt2000ChecksumMismatch;
        if (checksum_error) ++vlt2000_checksum_errors_;
        if (v.checksum_disabled) ++vlt2000_checksum_disabled_;
        if (t.has_roles) {
            slave_seen_[t.slave & 0x7F] = true;
            Vlt2000AddressCounts& counts = vlt2000_addresses_[t.slave & 0x7F];
            ++(request ? counts.commands : counts.replies);
            if (failed) ++counts.failed;
            if (checksum_error) ++counts.checksum_errors;
            if (v.checksum_disabled) ++counts.checksum_disabled;
        }
    }
    void render_vlt2000_counts(fmt::memory_buffer& b) const;
    void render_vlt2000_addresses(fmt::memory_buffer& b, const Vlt2000Tracker* tracker) const;
    void render_dp_counts(fmt::memory_buffer& b) const;
    void render_fc_counts(fmt::memory_buffer& b) const;
    void render_fc_drives(fmt::memory_buffer& b, const FcTracker* tracker) const;

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
    std::array<bool, kStationCount> pcv_seen_{};    // a Data_Exchange layout with a PCV
    std::array<bool, kStationCount> slave_seen_{};  // a telegram to or from it was added
    std::array<DialectEvidence, kStationCount> dialects_{};
    std::int64_t first_time_ = kNoTime;
    std::int64_t last_time_ = kNoTime;
    std::uint64_t other_telegrams_ = 0;  // add_other()
    std::uint64_t fc_telegrams_ = 0;
    std::array<std::uint64_t, 4> fc_blocks_{};
    std::uint64_t fc_requests_ = 0;
    std::uint64_t fc_responses_total_ = 0;
    std::uint64_t fc_broadcasts_ = 0;
    std::array<std::uint64_t, 16> fc_commands_{};   // requests by AK
    std::array<std::uint64_t, 16> fc_responses_{};  // responses by AK
    std::array<std::uint64_t, kStationCount> fc_drive_requests_{};
    std::array<std::uint64_t, kStationCount> fc_drive_responses_{};
    static constexpr std::size_t kVlt2000NoReason = 100;
    static constexpr std::size_t kVlt2000Letters =
        static_cast<std::size_t>(Vlt2000Letter::Unknown) + 1;
    std::uint64_t vlt2000_telegrams_ = 0;
    std::array<std::uint64_t, kVlt2000Letters> vlt2000_commands_{};
    std::array<std::uint64_t, kVlt2000Letters> vlt2000_replies_{};
    std::uint64_t vlt2000_broadcasts_ = 0;
    std::uint64_t vlt2000_failed_ = 0;
    std::array<std::uint64_t, kVlt2000NoReason + 1> vlt2000_reasons_{};
    std::uint64_t vlt2000_checksum_errors_ = 0;
    std::uint64_t vlt2000_checksum_disabled_ = 0;
    std::array<Vlt2000AddressCounts, kStationCount> vlt2000_addresses_{};
};

}  // namespace dpscope
