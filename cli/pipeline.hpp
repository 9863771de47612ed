// The decode -> track -> count chain every subcommand that reads telegrams runs.
#pragma once

#include <span>

#include "capture/telegram_source.hpp"
#include "cli/common_options.hpp"
#include "decoder/session_tracker.hpp"
#include "formats/summary.hpp"

namespace dpscope::cli {

class Pipeline {
  public:
    explicit Pipeline(const DecodeSettings& settings)
        : decoder_(settings.decoder), tracker_(decoder_, settings.tracker) {}

    // Decodes and tracks one record; `findings` receives what the tracker found at it.
    const DecodedTelegram& feed(const Record& record, std::span<const Finding>& findings) {
        const DecodedTelegram& t = decoder_.decode(record.bytes, record.time_ns, record.number);
        findings = tracker_.track(t);
        summary_.add(t);
        summary_.add_findings(findings);
        return t;
    }
    // The end of the input: findings still open past the time-out.
    std::span<const Finding> finish() {
        std::span<const Finding> findings = tracker_.finish();
        summary_.add_findings(findings);
        return findings;
    }

    const BusDecoder& decoder() const noexcept { return decoder_; }
    const SessionTracker& tracker() const noexcept { return tracker_; }
    const Summary& summary() const noexcept { return summary_; }

  private:
    BusDecoder decoder_;
    SessionTracker tracker_;
    Summary summary_;
};

// What the summary and the report say about the input itself.
inline InputSummary describe_input(const TelegramSource& source) {
    return InputSummary{source.name(), std::string(input_format_name(source.format())),
                        source.bytes_skipped(), source.status() == InputStatus::Damaged};
}

// Reports input problems on standard error (after flushing `out`, so messages and output keep
// their order on a terminal).
void report_input_issues(TelegramSource& source, Output& out);

}  // namespace dpscope::cli
