// The decode -> track -> count chain every subcommand that reads telegrams runs.
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "capture/output_file.hpp"
#include "capture/telegram_source.hpp"
#include "cli/common_options.hpp"
#include "cli/version.hpp"
#include "core/counted.hpp"
#include "core/protocol_lane.hpp"
#include "core/text_encoding.hpp"
#include "formats/finding_log.hpp"
#include "formats/report.hpp"
#include "formats/report_timeline.hpp"
#include "formats/summary.hpp"
#include "protocols/profibus/health/bus_health.hpp"

namespace dpscope::cli {

// What a command needs of the pipeline beyond the decode and the summary.
struct PipelineParts {
    // The per-channel timelines (only the HTML report shows them; the hot path of every other
    // command skips them).
    bool timelines = false;
    // The protocol's tracker judging the parameter channel (its findings and the PNU a telegram
    // is about). `dpscope stats` shows bus health only and needs it only for a -Y filter.
    bool parameter_findings = true;
    // Each telegram's health events are read (by a filter or a trigger): the verdicts are then
    // judged every quarter second of capture time, and one that turns bad is such an event.
    // report and stats read them only for -Y; their figures are judged at the end either way.
    bool health_events = true;
};

class Pipeline {
  public:
    // The protocol is chosen once, from settings.protocol: its descriptor makes the decoder and
    // the tracker that are fed (core/protocol_lane.hpp). Without parts.parameter_findings the
    // tracker is made but not fed: no findings, subject_pnu() -1.
    explicit Pipeline(const DecodeSettings& settings, PipelineParts parts = {})
        : protocol_(settings.protocol->protocol),
          naming_(parameter_naming(settings)),
          decoder_(settings.protocol->make_decoder(lanes_with(settings.lanes, naming_))),
          tracker_(settings.protocol->make_tracker(settings.lanes)),
          track_parameters_(parts.parameter_findings),
          keep_timelines_(parts.timelines) {
        if (settings.track_health && settings.protocol->has_bus_health) {
            health_.emplace(settings.health);
            judge_ = settings.judge_in_capture_time && parts.health_events;
        }
    }

    // Offline, the verdicts are judged as often as sniff judges them live: every quarter second
    // of capture time (every kJudgeEveryTelegrams telegrams without times).
    static constexpr std::int64_t kJudgeEveryNs = 250'000'000;
    static constexpr std::uint64_t kJudgeEveryTelegrams = 1000;

    // Decodes and tracks one record; `findings` receives what the tracker found at it.
    const DecodedTelegram& feed(const Record& record, std::span<const Finding>& findings) {
        const DecodedTelegram& t = decoder_->decode(record.bytes, record.time_ns, record.number);
        findings = track_parameters_ ? tracker_->track(t) : std::span<const Finding>{};
        if (health_) {
            health_events_ = health_->observe(t);
            if (judge_ && judge_due(record)) judge_at(record);
        }
        summary_.add(t);
        summary_.add_findings(findings);
        if (keep_timelines_ && track_parameters_) timelines_.add(findings, tracker_->completed());
        return t;
    }
    // The end of the input: findings still open past the time-out.
    // `end_ns`: when the capture ended, if later than its last telegram (a live capture's stop).
    std::span<const Finding> finish(std::int64_t end_ns = kNoTime) {
        std::span<const Finding> findings;
        if (track_parameters_) {
            findings = tracker_->finish(end_ns);
            for (const std::string& warning : tracker_->end_warnings(summary_.telegrams()))
                print_warning(warning);
        }
        // Bus health ends with the last telegram, not at a live capture's stop: sniff's figures
        // then equal those of `dpscope stats` on the capture it wrote.
        if (health_) {
            health_->finish();
            warn_line_rate(health_->health().segment);
        }
        summary_.add_findings(findings);
        if (keep_timelines_) timelines_.add(findings, {});
        return findings;
    }

    Protocol protocol() const noexcept { return protocol_; }
    // The capture's decoder and tracker (those of its protocol).
    const TelegramDecoder& decoder() const noexcept { return *decoder_; }
    const TelegramTracker& tracker() const noexcept { return *tracker_; }
    // The parameter number the last telegram's parameter channel is about (-1: none), from the
    // protocol's tracker.
    std::int32_t subject_pnu() const noexcept {
        return track_parameters_ ? tracker_->subject_pnu() : -1;
    }
    const Summary& summary() const noexcept { return summary_; }
    // The bus-health statistics (PROFIBUS, with settings.track_health); null otherwise.
    const BusHealthTracker* health() const noexcept { return health_ ? &*health_ : nullptr; }
    BusHealthTracker* health() noexcept { return health_ ? &*health_ : nullptr; }
    // The health events (station lost, returned) the last feed() caused.
    std::span<const HealthEvent> health_events() const noexcept { return health_events_; }
    const ChannelTimelines& timelines() const noexcept { return timelines_; }
    // What names the capture's PNUs (drives/parameter_naming.hpp): the decoder's as of now when
    // it keeps its own (what the drives described, the families their GSD files name), so the
    // report written after the decode names as the last telegram was named.
    const ParameterNaming& naming() const noexcept {
        const ParameterNaming* own = decoder_->naming();
        return own ? *own : *naming_;
    }

  private:
    // Whether a quarter second of capture time (or kJudgeEveryTelegrams) has passed since the
    // last judgement (asked for every telegram: inline, the judging is not).
    bool judge_due(const Record& record) {
        return record.time_ns != kNoTime
                   ? last_judged_ns_ == kNoTime || record.time_ns - last_judged_ns_ >= kJudgeEveryNs
                   : ++unjudged_ >= kJudgeEveryTelegrams;
    }
    // Judges the verdicts (judge_due() said it is time); a verdict that turned bad joins the
    // telegram's health events.
    [[gnu::noinline]] void judge_at(const Record& record) {
        last_judged_ns_ = record.time_ns;
        unjudged_ = 0;
        events_.assign(health_events_.begin(), health_events_.end());
        const std::span<const HealthEvent> turned_bad = health_->judge_verdicts();
        if (turned_bad.empty()) return;
        events_.insert(events_.end(), turned_bad.begin(), turned_bad.end());
        health_events_ = events_;
    }

    // The telegrams need more time at the baud rate given than the capture lasts: the line was
    // faster (the bus load would read over 100 %, shown as 100).
    static void warn_line_rate(const SegmentHealth& segment) {
        const double duration_ns = segment.duration_s() * 1e9;
        if (segment.baud == 0 || duration_ns <= 0 || segment.busy_ns <= duration_ns * 1.01) return;
        print_warning(fmt::format(
            "the telegrams take {:.0f} % of the capture's time at {} baud: the line was faster "
            "than --baud says (the bus load shows as 100 %); give the rate the capture was made at",
            segment.busy_ns / duration_ns * 100.0, segment.baud));
    }

    static LaneOptions lanes_with(LaneOptions lanes,
                                  std::shared_ptr<const ParameterNaming> naming) {
        lanes.naming = std::move(naming);
        return lanes;
    }

    Protocol protocol_;
    std::shared_ptr<const ParameterNaming> naming_;  // what names the PNUs (drives/)
    std::unique_ptr<TelegramDecoder> decoder_;
    std::unique_ptr<TelegramTracker> tracker_;
    bool track_parameters_ = true;
    std::optional<BusHealthTracker> health_;
    std::span<const HealthEvent> health_events_;
    bool judge_ = false;
    std::int64_t last_judged_ns_ = kNoTime;
    std::uint64_t unjudged_ = 0;
    std::vector<HealthEvent> events_;  // the observed events and the verdicts turned bad
    Summary summary_;
    ChannelTimelines timelines_;
    bool keep_timelines_ = false;
};

// What the summary and the report say about the input itself. The name is shown as valid UTF-8
// without control characters (display_text()): a file name can be any bytes, and every output
// format is UTF-8.
inline InputSummary describe_input(const TelegramSource& source) {
    return InputSummary{display_text(source.name()),
                        std::string(input_format_name(source.format())), source.bytes_skipped(),
                        source.status() == InputStatus::Damaged};
}

// The conformance report over what `pipeline` decoded from `source`, findings from `log`.
inline ReportContext report_context(const Pipeline& pipeline, const TelegramSource& source,
                                    const FindingLog& log, FailOn fail_on) {
    ReportContext context;
    context.input = describe_input(source);
    context.summary = &pipeline.summary();
    context.decoder = &pipeline.decoder();
    context.naming = &pipeline.naming();
    context.protocol = pipeline.protocol();
    context.tracker = &pipeline.tracker();
    context.timelines = &pipeline.timelines();  // empty unless the pipeline kept them
    context.health = pipeline.health() ? &pipeline.health()->health() : nullptr;
    context.findings = &log;
    context.fail_on = fail_on;
    context.version = kVersion;
    return context;
}

// Ends a staged output by the run's exit code: 0 and 1 (the result asked for) move it into
// place. Any other code leaves an existing file as it was: an output written whole (`partial_why`
// says why the run did not succeed, "the input ended in damage") goes beside it as FILE.partial,
// with a warning naming both; one that is not (`partial_why` empty: an unusable input, a write
// error) is discarded. `option` names the output in messages ("-w"), `inputs` are the run's
// inputs (a FILE.partial that is one of them is not written). Returns the exit code, or
// kExitOutputError when the file cannot be moved.
int finish_staged_output(PendingOutputFile& file, int exit_code, std::string_view partial_why,
                         std::string_view option, const std::vector<std::string>& inputs);

// Runs `write(out, partial_why)` with `out` on PATH (- is standard output) staged as a
// PendingOutputFile and ends it with finish_staged_output: an existing file is replaced only when
// `write` returns 0 or 1; `write` sets `partial_why` when its output is whole though it returns
// another code (3, damaged input, needs none: it is set for it). Returns write's exit code, or
// kExitOutputError when the file cannot be opened or moved into place.
template <class Write>
int write_staged_output(const std::string& path, const std::string& input, Write&& write) {
    Result<std::unique_ptr<PendingOutputFile>> opened = PendingOutputFile::open(path);
    if (!opened) {
        print_error(opened.error());
        return kExitOutputError;
    }
    std::unique_ptr<PendingOutputFile> file = std::move(opened).value();
    int exit_code = kExitOk;
    std::string partial_why;
    {
        Output out(file->file());
        exit_code = write(out, partial_why);
    }
    if (exit_code == kExitDamagedInput && partial_why.empty())
        partial_why = "the input ended in damage";
    return finish_staged_output(*file, exit_code, partial_why, "-w", {input});
}

// Reports input problems on standard error (after flushing `out`, so messages and output keep
// their order on a terminal).
void report_input_issues(TelegramSource& source, Output& out);

// A warning for each slave whose --ppo contradicts the configuration (Chk_Cfg or Get_Cfg) in the
// capture: the option wins, the warning says so.
// (A capture of another bus has none.)
void warn_ppo_overrides(const TelegramDecoder& decoder);

// A byte stream (raw or hex) in which no telegram of `protocol` was found is no capture dpscope
// reads: an error saying so, unless `telegrams` were found or the input is a pcap/pcapng file
// (which may rightly hold none: empty_input_exit()). An unusable input gives its reason.
// `bus_given` false: the bus was chosen from the capture, and the error suggests --bus.
Result<void> check_telegrams_found(const TelegramSource& source, std::uint64_t telegrams,
                                   const ProtocolDescriptor& protocol, bool bus_given = true);

// The exit code of a decode, hex or stats run that read no telegram from a capture without
// records (check_telegrams_found() passed; a byte stream without telegrams is no capture):
// an error naming the input and exit code 1 (as report's "nothing checked"), or with
// --allow-empty a note and 0 (docs/decisions.md, "An empty input").
int empty_input_exit(const TelegramSource& source, bool allow_empty);

// Says on standard error how the bus of `input` was chosen when that is worth saying (a note,
// without --bus), or that the capture's tag names another bus than --bus (a warning).
void say_bus_choice(const DecodeSettings& settings, const BusChoice& choice,
                    const std::string& input);

// Opens `path` for decode and report: with --bus as it says, without it choosing the bus from
// the capture and setting settings.protocol; says the choice (say_bus_choice). The line the
// capture records (sniff -w) is used unless --baud was given, which wins, with a warning when
// they differ (use_line).
OpenResult open_input(const std::string& path, InputFormat format, DecodeSettings& settings,
                      const SourceOptions& options = {});

}  // namespace dpscope::cli
