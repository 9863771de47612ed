#include "formats/summary.hpp"

#include <algorithm>
#include <iterator>
#include <optional>
#include <string>
#include <type_traits>

#include "formats/describe.hpp"
#include "protocols/fc/fc_codes.hpp"
#include "protocols/vlt2000/vlt2000_codes.hpp"

namespace dpscope {

namespace {

// "note", or "1 warning, 1 note" when the findings of a kind had several severities.
std::string severities_text(const std::array<std::uint64_t, 3>& by_severity) {
    std::string text;
    int seen = 0;
    std::string_view only;
    for (std::size_t s = by_severity.size(); s-- > 0;) {
        if (!by_severity[s]) continue;
        auto severity = static_cast<Severity>(s);
        only = severity_name(severity);
        fmt::format_to(std::back_inserter(text), "{}{} {}{}", seen++ ? ", " : "", by_severity[s],
                       severity_name(severity), by_severity[s] == 1 ? "" : "s");
    }
    return seen == 1 ? std::string(only) : text;
}

}  // namespace

std::string dialect_hint_text(std::uint8_t slave, Dialect decoded,
                              const DialectEvidence& evidence) {
    std::optional<Dialect> hint = evidence.hint();
    if (!hint) return {};
    const std::string option =
        fmt::format("decode with --dialect {}={}", slave, dialect_name(*hint));
    switch (evidence.basis()) {
        case DialectEvidence::Basis::Ident:
            return fmt::format("its ident number 0x{:04X} is the {}'s (the {} dialect); {}",
                               evidence.ident(), drive_of_ident(evidence.ident()),
                               dialect_name(*hint), option);
        case DialectEvidence::Basis::Errors: {
            std::span<const std::uint16_t> numbers = evidence.undefined_error_numbers();
            std::string list;
            for (std::size_t i = 0; i < numbers.size(); ++i)
                list += fmt::format("{}{}",
                                    i == 0 ? ""
                                    : i + 1 == numbers.size() && !evidence.more_error_numbers()
                                        ? " and "
                                        : ", ",
                                    numbers[i]);
            if (evidence.more_error_numbers()) list += ", ...";
            return fmt::format(
                "its error numbers fit the {} dialect ({} {}, which {} does not define, in {}); {}",
                dialect_name(*hint), numbers.size() == 1 ? "error" : "errors", list,
                dialect_name(decoded),
                counted(evidence.undefined_errors(), "rejection telegram", "rejection telegrams"),
                option);
        }
        case DialectEvidence::Basis::Codes:
        case DialectEvidence::Basis::None: break;
    }
    return fmt::format(
        "its parameter-channel codes fit the {} dialect ({} carry codes {} does not define); {}",
        dialect_name(*hint), counted(evidence.undefined(), "telegram", "telegrams"),
        dialect_name(decoded), option);
}

void Summary::render_text(Output& out, const InputSummary& input,
                          const TelegramDecoder& capture_decoder,
                          const TelegramTracker* tracker) const {
    TextBuffer& b = out.buffer();
    auto it = std::back_inserter(b);
    fmt::format_to(it, "Summary of {} ({})\n", input.name, input.format);
    fmt::format_to(it, "  telegrams: {}", telegrams_);
    if (first_time_ != kNoTime) {
        append(b, ", from ");
        append_iso_time(b, first_time_);
        append(b, " to ");
        append_iso_time(b, last_time_);
        append(b, " (");
        append_epoch_seconds(b, last_time_ - first_time_);
        append(b, " s)");
    }
    b.push_back('\n');
    if (input.damaged) append(b, "  input: reading stopped early (see the message above)\n");
    if (input.bytes_skipped > 0)
        fmt::format_to(it, "  bytes skipped between telegrams: {}\n", input.bytes_skipped);

    if (fc_telegrams_ > 0) {
        render_fc_counts(b);
    } else if (vlt2000_telegrams_ > 0) {
        render_vlt2000_counts(b);
    } else if (other_telegrams_ == 0) {
        render_dp_counts(b);
    }
    fmt::format_to(it, "  telegrams with problems: {}\n", with_problems_);
    for (std::size_t k = 0; k < kProblemKindCount; ++k)
        if (problems_[k])
            fmt::format_to(it, "    {:<26} {:>10}\n",
                           problem_kind_name(static_cast<ProblemKind>(k)), problems_[k]);

    std::uint64_t total_findings = 0;
    for (std::uint64_t n : findings_)
        total_findings += n;
    fmt::format_to(it, "  findings: {}\n", total_findings);
    const std::size_t kind_width = std::max<std::size_t>(26, longest_finding_kind_name());
    for (std::size_t k = 0; k < kFindingKindCount; ++k)
        if (findings_[k]) {
            auto kind = static_cast<FindingKind>(k);
            // Kind and count span 37 columns; the kind column is as wide as the longest name.
            fmt::format_to(it, "    {:<{}} {:>{}}  ({})\n", finding_kind_name(kind), kind_width,
                           findings_[k], 36 - kind_width,
                           severities_text(findings_by_severity_[k]));
        }

    if (fc_telegrams_ > 0) {
        render_fc_drives(b, dynamic_cast<const FcTracker*>(tracker));
        out.end_record();
        return;
    }
    if (vlt2000_telegrams_ > 0) {
        render_vlt2000_addresses(b, dynamic_cast<const Vlt2000Tracker*>(tracker));
        out.end_record();
        return;
    }
    const auto* profibus = dynamic_cast<const BusDecoder*>(&capture_decoder);
    if (other_telegrams_ > 0 || profibus == nullptr) {
        out.end_record();
        return;
    }
    const BusDecoder& decoder = *profibus;
    bool header = false;
    for (std::size_t a = 0; a < kStationCount; ++a) {
        const StationConfig& station = decoder.station(static_cast<std::uint8_t>(a));
        // Slaves of the telegrams summarised (with --station, only those).
        if (!slave_seen_[a] || (data_exchange_[a] == 0 && !station.ppo.known())) continue;
        if (!header) {
            append(b, "  slaves:\n");
            header = true;
        }
        fmt::format_to(it, "    {:>3}: ", a);
        const bool layout_known = station.ppo.known() || decoder.options().station_ppo[a] != 0;
        const PpoLayout layout = decoder.layout_for(static_cast<std::uint8_t>(a), 0);
        if (layout_known)
            append_ppo_long(b, layout);
        else
            append(b, "PPO guessed from each Data_Exchange length");
        const Dialect dialect = decoder.options().dialect_of(static_cast<std::uint8_t>(a));
        // The dialect names the parameter channel's code tables: none without a PCV.
        if (pcv_seen_[a] || (layout_known && layout.has_pcv))
            fmt::format_to(it, "; dialect {}", dialect_name(dialect));
        else
            append(b, "; no parameter channel");
        if (station.has_ident) fmt::format_to(it, "; ident 0x{:04X}", station.ident);
        fmt::format_to(
            it, "; {}\n",
            counted(data_exchange_[a], "Data_Exchange telegram", "Data_Exchange telegrams"));
        std::string hint = dialect_hint_text(static_cast<std::uint8_t>(a), dialect, dialects_[a]);
        if (!hint.empty()) fmt::format_to(it, "         hint: {}\n", hint);
    }
    out.end_record();
}

void Summary::render_dp_counts(TextBuffer& b) const {
    auto it = std::back_inserter(b);
    append(b, "  by frame type:");
    for (FrameType type : {FrameType::Sd1, FrameType::Sd2, FrameType::Sd3, FrameType::Sd4,
                           FrameType::ShortAck, FrameType::Invalid}) {
        std::uint64_t n = frame_types_[static_cast<std::size_t>(type)];
        if (n) fmt::format_to(it, " {} {}", frame_type_name(type), n);
    }
    b.push_back('\n');

    append(b, "  by service:\n");
    for (std::size_t s = 0; s < kServiceCount; ++s) {
        std::uint64_t total = requests_[s] + responses_[s];
        if (total == 0) continue;
        fmt::format_to(it, "    {:<16} {:>10}  ({}, {})\n", service_name(static_cast<Service>(s)),
                       total, counted(requests_[s], "request", "requests"),
                       counted(responses_[s], "response", "responses"));
    }
}

void Summary::render_fc_counts(TextBuffer& b) const {
    auto it = std::back_inserter(b);
    append(b, "  bus: FC protocol\n");
    append(b, "  by block:");
    for (FcBlock block : {FcBlock::Process, FcBlock::Parameter, FcBlock::Text, FcBlock::Unknown})
        if (std::uint64_t n = fc_blocks_[static_cast<std::size_t>(block)])
            fmt::format_to(it, " {} {}", fc_block_name(block), n);
    b.push_back('\n');
    fmt::format_to(it, "  by direction: {}, {}", counted(fc_requests_, "request", "requests"),
                   counted(fc_responses_total_, "response", "responses"));
    if (fc_broadcasts_) fmt::format_to(it, " ({} broadcast)", fc_broadcasts_);
    b.push_back('\n');
    auto by_ak = [&](std::string_view title, const std::array<std::uint64_t, 16>& counts,
                     bool request) {
        bool any = false;
        for (std::size_t ak = 0; ak < counts.size(); ++ak) {
            if (!counts[ak]) continue;
            if (!any) fmt::format_to(it, "  {}:\n", title);
            any = true;
            const auto code = static_cast<std::uint8_t>(ak);
            std::string name = fmt::format(
                "AK {:>2} {}", ak, request ? fc_command(code).meaning : fc_response(code).meaning);
            fmt::format_to(it, "    {:<60} {:>10}\n", name, counts[ak]);
        }
    };
    by_ak("parameter commands", fc_commands_, true);
    by_ak("parameter responses", fc_responses_, false);
}

namespace {

// The tracker's counts of drive `address`, or null.
template <class Tracker>
auto drive_stats(const Tracker* tracker, std::size_t address) {
    using Stats = std::remove_pointer_t<typename decltype(tracker->stations())::value_type>;
    const Stats* found = nullptr;
    if (tracker)
        for (const Stats* s : tracker->stations())
            if (s->address == address) found = s;
    return found;
}

// " (119 answered, 0 unanswered, 1 abandoned, 1 damaged)" from the tracker's counts, or "".
template <class Stats>
std::string outcomes_of(const Stats* s) {
    if (!s) return {};
    return fmt::format(" ({})", command_outcomes_text(s->answered, s->no_responses, s->abandoned,
                                                      s->damaged, s->not_judged_total()));
}

// " (1 damaged)" or "".
std::string damaged_of(std::uint64_t damaged) {
    return damaged ? fmt::format(" ({} damaged)", damaged) : std::string();
}

}  // namespace

void Summary::render_fc_drives(TextBuffer& b, const FcTracker* tracker) const {
    auto it = std::back_inserter(b);
    bool header = false;
    for (std::size_t a = 0; a < kStationCount; ++a) {
        if (!slave_seen_[a]) continue;
        if (!header) {
            append(b, "  drives:\n");
            header = true;
        }
        const FcStationStats* s = drive_stats(tracker, a);
        fmt::format_to(it, "    {:>3}: {}{}, {}{}\n", a,
                       counted(fc_drive_requests_[a], "command", "commands"), outcomes_of(s),
                       counted(fc_drive_responses_[a], "response", "responses"),
                       damaged_of(s ? s->damaged_responses : 0));
    }
}

// "  bus: VLT 2000", telegrams by letter (commands and replies), by direction, failed replies by
// reason code, and the checksums found wrong or switched off ("??").
void Summary::render_vlt2000_counts(TextBuffer& b) const {
    auto it = std::back_inserter(b);
    append(b, "  bus: VLT 2000\n");
    std::uint64_t commands = 0;
    std::uint64_t replies = 0;
    for (std::size_t l = 0; l < kVlt2000Letters; ++l) {
        commands += vlt2000_commands_[l];
        replies += vlt2000_replies_[l];
    }
    fmt::format_to(it, "  by direction: {}, {}", counted(commands, "command", "commands"),
                   counted(replies, "reply", "replies"));
    if (vlt2000_broadcasts_) fmt::format_to(it, " ({} broadcast)", vlt2000_broadcasts_);
    b.push_back('\n');
    if (commands + replies > 0) append(b, "  by letter:\n");
    for (Vlt2000Letter letter : {Vlt2000Letter::Update, Vlt2000Letter::Read, Vlt2000Letter::Control,
                                 Vlt2000Letter::ReadIndex, Vlt2000Letter::Unknown}) {
        const auto l = static_cast<std::size_t>(letter);
        const std::uint64_t total = vlt2000_commands_[l] + vlt2000_replies_[l];
        if (total == 0) continue;
        const std::string name =
            letter == Vlt2000Letter::Unknown
                ? std::string("unknown letter")
                : fmt::format("{} {}", vlt2000_letter_char(letter), vlt2000_letter_name(letter));
        fmt::format_to(it, "    {:<16} {:>10}  ({}, {})\n", name, total,
                       counted(vlt2000_commands_[l], "command", "commands"),
                       counted(vlt2000_replies_[l], "reply", "replies"));
    }
    fmt::format_to(it, "  failed replies (decimal position 9): {}\n", vlt2000_failed_);
    for (std::size_t reason = 0; reason < vlt2000_reasons_.size(); ++reason) {
        if (!vlt2000_reasons_[reason]) continue;
        std::string name;
        if (reason == kVlt2000NoReason) {
            name = "no reason code given";
        } else {
            const std::string_view text = vlt2000_reason_text(static_cast<std::uint32_t>(reason));
            name =
                fmt::format("reason {:02} {}", reason, text.empty() ? "unknown reason code" : text);
        }
        fmt::format_to(it, "    {:<60} {:>10}\n", name, vlt2000_reasons_[reason]);
    }
    fmt::format_to(it, "  checksums: {} wrong, {} not checked (\"??\")\n", vlt2000_checksum_errors_,
                   vlt2000_checksum_disabled_);
}

// Per address (00: broadcasts) its commands (by outcome, with the tracker) and replies, failures
// and checksums.
void Summary::render_vlt2000_addresses(TextBuffer& b, const Vlt2000Tracker* tracker) const {
    auto it = std::back_inserter(b);
    bool header = false;
    for (std::size_t a = 0; a < kStationCount; ++a) {
        if (!slave_seen_[a]) continue;
        if (!header) {
            append(b, "  addresses:\n");
            header = true;
        }
        const Vlt2000AddressCounts& counts = vlt2000_addresses_[a];
        const Vlt2000StationStats* s = a == 0 ? nullptr : drive_stats(tracker, a);
        fmt::format_to(it, "    {:02}{}: {}{}, {}{}", a, a == 0 ? " (broadcast)" : "",
                       counted(counts.commands, "command", "commands"), outcomes_of(s),
                       counted(counts.replies, "reply", "replies"),
                       damaged_of(s ? s->damaged_replies : 0));
        if (counts.failed) fmt::format_to(it, ", {} failed", counts.failed);
        if (counts.checksum_errors)
            fmt::format_to(it, ", {}",
                           counted(counts.checksum_errors, "checksum error", "checksum errors"));
        if (counts.checksum_disabled)
            fmt::format_to(it, ", {} without checksum (\"??\")", counts.checksum_disabled);
        b.push_back('\n');
    }
}

}  // namespace dpscope
