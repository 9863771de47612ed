// Options shared by the subcommands that decode (decode, hex), their validation, and the exit
// codes every subcommand uses.
#pragma once

#include <CLI/CLI.hpp>
#include <bitset>
#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "capture/capture_writer.hpp"
#include "capture/pcap_source.hpp"
#include "capture/trigger_recorder.hpp"
#include "cli/small_file.hpp"
#include "core/protocol_descriptor.hpp"
#include "core/result.hpp"
#include "drives/drive_family.hpp"
#include "drives/parameter_database.hpp"
#include "filter/display_filter.hpp"
#include "formats/renderer.hpp"
#include "protocols/lane_options.hpp"
#include "protocols/profibus/health/bus_health.hpp"

namespace dpscope::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFindings = 1;      // report: findings at or above --fail-on; no telegrams
inline constexpr int kExitUsage = 2;         // bad command line, or input unusable from the start
inline constexpr int kExitDamagedInput = 3;  // input stopped early; what came before was decoded
inline constexpr int kExitOutputError = 4;   // output could not be opened or written
inline constexpr int kExitDeviceError = 5;   // sniff: the capture device failed

inline constexpr std::string_view kExitCodeHelp =
    "Exit codes: 0 success; 1 report found something at or above --fail-on (stats: the verdict "
    "reached it), or the input holds no telegram (without --allow-empty); 2 bad usage or "
    "unusable input (cannot open, unknown format, unsupported link type); 3 the input ended in "
    "damage (truncated record, read error) after what was decoded; 4 output could not be "
    "opened or written (no such directory, disk full); 5 the capture device failed (sniff). "
    "Only a run that exits 0 or 1 writes or replaces a -w FILE of decode, hex, report, stats "
    "and simulate; on 3 the output goes to FILE.partial.";

// Decimal digits only (no sign, fraction, exponent or hex) that fit in T; false otherwise.
template <typename T>
bool parse_whole_number(std::string_view text, T& value) {
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    return !text.empty() && ec == std::errc() && end == text.data() + text.size();
}

// A finite decimal number (with a fraction or exponent; not hex, nan or inf) that is the whole
// of `text`; nullopt otherwise.
std::optional<double> parse_finite_number(const std::string& text);

// Every numeric option is checked on its text with one of these, and the error names the range:
// "--count: must be a whole number from 1 to 9223372036854775807, not '0'". CLI11's own
// conversions would take "-1" as the largest unsigned value and clamp a number too large.
// A whole number from `min` to `max` in decimal digits (no sign, fraction or exponent);
// `unit` (" ms", " baud") follows the range in the message.
CLI::Validator whole_number(std::uint64_t min, std::uint64_t max, std::string_view unit = "");
// A finite number from `min` to `max` (decimal, with a fraction or exponent; not hex, nan, inf).
CLI::Validator finite_number(double min, double max, std::string_view unit = "");

// A file name for an output (-w, --report-file): not empty ("-" is standard output).
CLI::Validator output_file_name();
// The values --bus takes: every protocol's name, in the order of the registration list.
std::vector<std::string> bus_names();

// -c N: one telegram up to 2^63 - 1 (more than any capture holds).
inline constexpr std::uint64_t kMaxCount = 9'223'372'036'854'775'807ULL;

// What the command line says, before validation.
struct DecodeOptionValues {
    std::string format = "text";
    bool verbose = false;
    bool quiet = false;
    std::uint64_t count = 0;
    std::vector<unsigned> stations;
    std::vector<std::string> pnus;  // --pnu: 1613, 16-13 or a parameter's name
    std::string display_filter;     // -Y EXPR (filter/display_filter.hpp)
    // --trigger EXPR (repeatable), --pre, --post, --trigger-limit, --trigger-dir (issue 30).
    std::vector<std::string> triggers;
    double pre_seconds = 10;
    double post_seconds = 10;
    unsigned trigger_limit = 60;
    std::string trigger_dir;
    std::vector<std::string> ppo;
    std::vector<std::string> dialects;
    std::vector<std::string> gsd_files;  // --gsd FILE or ADDR=FILE
    std::vector<std::string> gsd_dirs;   // --gsd-dir DIR
    std::vector<std::string> params;  // --params FILE: parameter databases beside the shipped
    std::vector<std::string> conversions;  // --conversion-index INDEX=FACTOR
    std::vector<std::string> drives;  // --drive [ADDR=]FAMILY
    std::string bus;  // --bus: "" = from the capture
    unsigned fc_pnu_bits = 12;
    std::string pcd_profile;
    std::uint32_t timeout_ms = 1000;
    std::uint32_t fc_response_ms = 20;
    std::string vlt2000_checksum = "check";  // check or ignore
    std::uint32_t baud = 0;                  // --baud (decode, hex, report): 0 = not given
    bool strict = false;
    bool line_buffered = false;
    // decode/hex -w: the telegrams shown, as a capture.
    std::string write;
    std::string write_format;  // -F; "" = pcap
    std::string link_type;     // "" = profibus
    bool print = false;        // -P: print the decode as well when writing a capture
    bool allow_empty = false;  // --allow-empty: an input without telegrams passes (exit 0)
};

// How to decode and track: -c, --bus, --ppo, --dialect, --fc-pnu-bits, --pcd-profile,
// --timeout-ms, --fc-response-ms, --strict; and how to name parameters: --params, --drive.
void add_tracking_options(CLI::App& app, DecodeOptionValues& values);
// --params FILE (repeatable): a parameter database read beside the shipped ones (decode, hex,
// report, sniff through add_tracking_options; params).
// --conversion-index INDEX=FACTOR (repeatable): the factor of a conversion index (checked when
// parsed: exit 2 on a bad one).
void add_params_option(CLI::App& app, std::vector<std::string>& files,
                       std::vector<std::string>& conversions);
// decode, hex and report: --baud, the line rate of a capture read from a file (sniff has its own
// --baud for the port and sets the same setting).
void add_line_options(CLI::App& app, DecodeOptionValues& values);
// What decode, hex and sniff print: -T, -V, -q, -l, --station, --pnu.
// -Y/--display-filter EXPR, its help beginning with `what` (what the filter does for the
// command); the fields and operators are the same for every command.
void add_display_filter_option(CLI::App& app, DecodeOptionValues& values, std::string_view what);

void add_display_options(CLI::App& app, DecodeOptionValues& values,
                         std::string_view default_format);
// decode and hex: -w FILE, -F, --linktype, -P.
void add_write_options(CLI::App& app, DecodeOptionValues& values);
// decode, hex and stats: --allow-empty (report and sniff word their own).
void add_allow_empty_option(CLI::App& app, bool& allow_empty);

struct DecodeSettings {
    // What the capture carries; every source of the command is opened with it. Chosen once:
    // by --bus, or (bus_given false) from the capture before it is decoded.
    const ProtocolDescriptor* protocol = &profibus_protocol();
    bool bus_given = false;
    // Every protocol's decoder and tracker options; the pipeline makes the capture's protocol's.
    LaneOptions lanes;
    // PROFIBUS bus health (protocols/profibus/health/bus_health.hpp): kept when track_health is set
    // (stats, report, sniff --stats); its baud rate is the line's when known.
    bool track_health = false;
    // Judge the verdicts every kJudgeEveryNs of capture time, so that a verdict turning bad is a
    // health event (health.verdict == "bad") offline as it is live. sniff judges itself, on the
    // wall clock (cli/live_health.hpp), and turns this off.
    bool judge_in_capture_time = true;
    BusHealthOptions health;
    OutputFormat format = OutputFormat::Text;
    bool quiet = false;
    bool line_buffered = false;  // -l: flush the output after every telegram
    std::uint64_t count = 0;     // 0: no limit
    std::vector<std::uint8_t> stations;
    std::vector<std::uint16_t> pnus;
    // The drive parameter databases (the shipped ones and --params files; never null) and the
    // families --drive names (docs/parameters.md).
    std::shared_ptr<const ParameterDatabase> parameters = std::make_shared<ParameterDatabase>();
    DriveHints drives;
    // -w: where the telegrams shown go as a capture ("" none), its format and link type.
    std::string write;
    CaptureFormat write_format = CaptureFormat::Pcap;
    int link_type = kLinkTypeProfibusDl;
    bool link_type_given = false;  // --linktype; otherwise the bus's default (capture_link_type)
    bool print = true;             // render the decode (false with -w unless -P)
    bool allow_empty = false;      // --allow-empty: an input without telegrams exits 0
    // The line the capture was made on, as far as it is known: --baud (baud_given, 0 none), or
    // what the capture records (open_input), or the port (sniff). -w records it in the capture
    // written.
    std::uint32_t baud_given = 0;
    LineSettings line;

    // -Y, --station and --pnu as one filter (the shorthands in the filter language, joined to
    // -Y with &&); null: every telegram is shown.
    std::shared_ptr<const DisplayFilter> filter;
    std::string display_filter;  // -Y as given ("" none)
    // --trigger (any of them; null: none), the window around it and the folder of its files.
    std::shared_ptr<const DisplayFilter> trigger;
    std::string trigger_text;  // the --trigger expressions joined with ||
    std::int64_t pre_ns = 0;
    std::int64_t post_ns = 0;
    unsigned trigger_limit = 60;
    std::string trigger_dir;

    bool filtering() const noexcept { return filter != nullptr; }
};

// The line the capture was made on: the time a telegram takes on it (the FC and VLT 2000
// trackers' response times), the bus load of the bus-health tracker, and what -w records. What
// `line` does not know (a baud rate of 0, an unknown frame) is left as it was.
void use_line(DecodeSettings& settings, const LineSettings& line);

// The link type a capture of `protocol` is written with: `given` (--linktype) or the bus's
// default (PROFIBUS 257 PROFIBUS_DL, FC protocol 147 USER0). An error when the link type is
// 257, which is PROFIBUS only, for another bus.
Result<int> capture_link_type(const ProtocolDescriptor& protocol, std::optional<int> given);

// The largest parameter database file read (--params): the shipped ones are a few dozen KiB.
inline constexpr std::size_t kMaxParameterFileBytes = 16 * 1024 * 1024;

// The shipped parameter databases, then each --params file in order (a family already loaded
// takes its rows: docs/parameters.md). A file that cannot be read or parsed is named in a
// warning ("FILE:LINE: what") and left out; dpscope goes on without it. So is a row's conversion
// index without a known meaning (its values are not scaled).
// Then each --conversion-index (already checked) gives its index its factor.
std::shared_ptr<const ParameterDatabase> load_parameter_databases(
    const std::vector<std::string>& files, const std::vector<std::string>& conversions = {});

// The families whose databases may name the PNUs of a capture decoded with `settings` (its
// --bus, else every bus; --drive, --dialect): what --pnu NAME is looked up in.
std::vector<std::string> families_in_play(const DecodeSettings& settings);

// --pnu TEXT: "1613", "16-13" or a parameter name unique in `families` of `database`; the error
// names the option, its value and why.
Result<std::uint16_t> resolve_pnu_option(std::string_view text, const ParameterDatabase& database,
                                         std::span<const std::string> families);

// What names the PNUs of a capture of the bus settings.protocol (chosen): each station's family
// by the family rule (--drive, the bus, the dialects) over settings.parameters.
std::shared_ptr<const ParameterNaming> parameter_naming(const DecodeSettings& settings);

// Validates the values; the error names the bad option.
// `default_format`: the -T default of the subcommand (-q conflicts with any other).
Result<DecodeSettings> resolve_decode_options(const DecodeOptionValues& values,
                                              std::string_view default_format);

// -Y, --station and --pnu (settings.filter): does the telegram pass? A telegram passes --station
// when it is to or from one of the stations (by address or DP role) or a finding at it concerns
// one; --pnu when its parameter channel is about one of the parameters (`subject_pnu`, from the
// tracker: a rejection without PNU is about the request it answers) or a finding at it concerns
// one; -Y when its expression holds (`events`: the health events the telegram caused).
bool passes_filter(const DecodeSettings& settings, const DecodedTelegram& t,
                   std::span<const Finding> findings, std::int32_t subject_pnu,
                   std::span<const FilterEvent> events = {}) noexcept;

// Does the telegram pass the filters (-Y, --station, --pnu) with its findings and the health
// events it caused? True when nothing filters.
class Pipeline;
bool selected_by_filter(const DecodeSettings& settings, const Pipeline& pipeline,
                        const DecodedTelegram& t, std::span<const Finding> findings);

// --trigger, --pre, --post, --trigger-limit and (sniff) --trigger-dir.
void add_trigger_options(CLI::App& app, DecodeOptionValues& values, bool with_dir);

// When a --trigger fires on the telegram: the event it is named after (the first health event,
// else the first finding's kind, else "match"), its station and the comment marking it.
std::optional<TriggerHit> trigger_hit(const DecodeSettings& settings, const DecodedTelegram& t,
                                      std::span<const Finding> findings, std::int32_t subject_pnu,
                                      std::span<const FilterEvent> events);

// The recorder of --trigger's windows, writing into `folder` (made if missing); the error names
// `option` (-w for decode, --trigger-dir for sniff): no folder, standard output, a file there.
Result<std::unique_ptr<TriggerRecorder>> make_trigger_recorder(const DecodeSettings& settings,
                                                               const std::string& folder,
                                                               std::string_view option);
// At the end, on standard error: the windows written and the triggers over the limit.
void say_trigger_stats(const TriggerStats& stats, const std::string& folder);

// The health events a telegram caused as the filter reads them (at most `out.size()`).
std::span<const FilterEvent> name_filter_events(std::span<const HealthEvent> events,
                                                std::span<FilterEvent> out) noexcept;
// The same, asked for every telegram: most have none, answered inline.
inline std::span<const FilterEvent> filter_events(std::span<const HealthEvent> events,
                                                  std::span<FilterEvent> out) noexcept {
    if (events.empty()) return {};
    return name_filter_events(events, out);
}

// Renders `t` when it passes the filters; otherwise lets `renderer` pass over it. Returns
// whether it passed.
inline bool show(TelegramRenderer* renderer, const DecodeSettings& settings,
                 const DecodedTelegram& t, std::span<const Finding> findings,
                 std::int32_t subject_pnu, std::span<const FilterEvent> events = {}) {
    bool shown = passes_filter(settings, t, findings, subject_pnu, events);
    if (renderer) {
        if (shown)
            renderer->render(t, findings);
        else
            renderer->pass_over(t);
    }
    return shown;
}

// Messages on standard error, one style for every subcommand: "dpscope: error: <message>",
// "dpscope: warning: <message>", or "dpscope: <severity>: <message>" for input issues.
// Messages name the file, record or byte offset and the option where they apply; callers
// never add the severity themselves.
void print_error(std::string_view message);
void print_warning(std::string_view message);
void print_diagnostic(Severity severity, std::string_view message);

// Writes `text` to standard error and never throws: a write that fails (standard error a pipe
// whose reader has gone, a full disk) drops the text and counts it. Every message goes through
// it (print_diagnostic too), so a closed standard error never ends a command early (sniff's
// capture runs on; docs/decisions.md, "A closed standard error"). False when dropped.
bool write_standard_error(std::string_view text) noexcept;
// Messages dropped so far because standard error could not be written.
std::uint64_t dropped_standard_error_messages() noexcept;
// Counts one more dropped message (output of the caller's own on standard error that failed).
void count_dropped_standard_error_message() noexcept;

// --- Bus health (issue 12): the thresholds of the verdict (stats, report, sniff --stats) -------
// The largest --health-config file read: the thresholds fit in 2 KiB with comments.
inline constexpr std::size_t kMaxHealthConfigBytes = 64 * 1024;
struct HealthOptionValues {
    std::string config;                   // --health-config FILE ("" none)
    std::vector<std::string> thresholds;  // --threshold NAME=VALUE, in the order given
};
// --health-config FILE and --threshold NAME=VALUE (repeatable); the help lists the thresholds
// with their defaults and ranges (protocols/profibus/health/health_thresholds.hpp).
void add_health_options(CLI::App& app, HealthOptionValues& values);
// The defaults, then the settings file, then each --threshold in order. The error names the file
// (and line), or the --threshold with its value and range; a file that cannot be read is named
// with the reason.
Result<HealthThresholds> resolve_health_options(const HealthOptionValues& values);
// The --fail-on of stats: exit code 1 when the segment's verdict reaches it.
enum class HealthFailOn { Bad, Weak, Never };
std::optional<HealthFailOn> health_fail_on_from_name(std::string_view name) noexcept;
bool verdict_fails(Verdict verdict, HealthFailOn fail_on) noexcept;

}  // namespace dpscope::cli
