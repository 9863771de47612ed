// dpscope decode: a capture file (or standard input) to decoded telegrams.
// dpscope hex:    telegrams typed as hex on the command line or piped in as a hex log.
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <bitset>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "capture/capture_writer.hpp"
#include "capture/hex_log.hpp"
#include "capture/output_file.hpp"
#include "capture/telegram_source.hpp"
#include "capture/text_log.hpp"
#include "cli/commands.hpp"
#include "cli/common_options.hpp"
#include "cli/pipeline.hpp"
#include "cli/progress.hpp"
#include "core/stream_framer.hpp"

namespace dpscope::cli {

namespace {

// The pcapng comment for a telegram's findings: "severity kind: message", one per line.
std::string findings_comment(std::span<const Finding> findings) {
    std::string comment;
    for (const Finding& f : findings) {
        if (!comment.empty()) comment.push_back('\n');
        fmt::format_to(std::back_inserter(comment), "{} {}: {}", severity_name(f.severity),
                       finding_kind_name(f.kind), f.message);
    }
    return comment;
}

// A raw stream keeps no record boundaries: a record that the protocol's framing, given it
// alone, does not find again as one telegram (a damaged one, or two in one record) is not read
// back as it was written, and the frames after it are numbered differently.
class RawRoundTrip final : private FramingSink {
  public:
    explicit RawRoundTrip(const FramingRules& rules) : framer_(rules) {}
    bool survives(Bytes record) {
        telegrams_ = 0;
        length_ = 0;
        skipped_ = false;
        framer_.feed(record, *this);
        framer_.finish(*this);
        return telegrams_ == 1 && length_ == record.size() && !skipped_;
    }

  private:
    void on_telegram(Bytes telegram, std::uint64_t) override {
        ++telegrams_;
        length_ = telegram.size();
    }
    void on_skipped(const SkippedBytes&) override { skipped_ = true; }

    StreamFramer framer_;
    std::size_t telegrams_ = 0;
    std::size_t length_ = 0;
    bool skipped_ = false;
};

// Decodes every telegram of `source`, renders those that pass the filters (and with -w writes
// them as a capture), and returns the exit code. Input problems are reported on standard error
// as they are met. `input_path` is the input as the user named it ("" for command-line bytes),
// so that -w never overwrites it.
int run_decoding(TelegramSource& source, const DecodeSettings& settings,
                 const std::string& input_path) {
    std::unique_ptr<PendingOutputFile> capture_file;
    std::unique_ptr<CaptureWriter> writer;
    // --trigger: -w names the folder of the windows' files, written as they close.
    std::unique_ptr<TriggerRecorder> triggers;
    if (settings.trigger) {
        Result<std::unique_ptr<TriggerRecorder>> made =
            make_trigger_recorder(settings, settings.write, "-w");
        if (!made) {
            print_error(made.error());
            return kExitUsage;
        }
        triggers = std::move(made).value();
    }
    if (!settings.write.empty() && !triggers) {
        if (Result<void> distinct = check_not_an_input({input_path}, settings.write, "-w");
            !distinct) {
            print_error(distinct.error());
            return kExitUsage;
        }
        Result<int> link_type = capture_link_type(
            *settings.protocol,
            settings.link_type_given ? std::optional<int>(settings.link_type) : std::nullopt);
        if (!link_type) {
            print_error(link_type.error());
            return kExitUsage;
        }
        Result<std::unique_ptr<PendingOutputFile>> file = PendingOutputFile::open(settings.write);
        if (!file) {
            print_error(file.error());
            return kExitOutputError;
        }
        capture_file = std::move(file).value();
        WriterResult opened = open_capture_writer(
            capture_file->file(), capture_file->name(), settings.write_format, *link_type,
            settings.protocol->protocol, settings.line, capture_file->is_staged());
        capture_file->release_file();  // the writer closes it
        if (!opened) {
            print_error(fmt::format("{}{}", opened.error(), capture_file->left_as_it_was()));
            return kExitOutputError;
        }
        writer = std::move(opened).value();
    }
    // --baud times the serial buses' commands on the line; a PROFIBUS decode has no use for it
    // (report and stats take it for the bus load), so it is said, as for the other options of
    // another bus. With -w it is not ignored: the capture written records the line; with GSD
    // files it times the slaves' answers against MaxTsdr (gsd_late_response).
    if (settings.baud_given && !settings.protocol->timed_by_line && settings.write.empty() &&
        !settings.lanes.decoder.gsd)
        print_warning(fmt::format(
            "{}: --baud applies to the FC protocol and VLT 2000 in decode (for PROFIBUS, report "
            "and stats use it for the bus load, and --gsd to time answers against MaxTsdr); "
            "this capture is PROFIBUS DP: ignored",
            source.name()));
    // With -w -, the capture owns standard output; text goes to standard error.
    FILE* text_stream = settings.write == "-" ? stderr : stdout;
    Output out(text_stream, settings.line_buffered || isatty(fileno(text_stream)) != 0);
    report_input_issues(source, out);
    Pipeline pipeline(settings);
    std::unique_ptr<TelegramRenderer> renderer;
    if (!settings.quiet && settings.print) {
        renderer = make_renderer(settings.format, out);
        renderer->begin();
    }
    // -q with --station/--pnu summarises the telegrams those select.
    Summary shown_summary;
    const bool with_comments = settings.write_format == CaptureFormat::Pcapng;
    bool write_failed = false;
    // What the capture holds of the --station and --pnu lists, to name filters that match nothing.
    std::bitset<kStationCount> stations_seen;
    PnuSet pnus_seen;
    Record record;
    std::uint64_t read = 0;
    std::span<const Finding> findings;
    // -F raw: the first record that a raw stream cannot keep is named (once).
    std::optional<RawRoundTrip> raw_round_trip;
    if (writer && settings.write_format == CaptureFormat::Raw)
        raw_round_trip.emplace(settings.protocol->framing);
    source.stop_after(settings.count);
    // Not over a decode printed on the same terminal (its lines would be overwritten).
    ProgressMeter progress =
        ProgressMeter::for_source(source, !renderer || isatty(fileno(text_stream)) == 0);
    // The health events of each telegram as the filter sees them (made once: zeroing it for
    // every telegram cost decode -q 5 %).
    std::array<FilterEvent, 8> event_buffer;
    while (source.next(record)) {
        ++read;
        progress.tick(source);
        const DecodedTelegram& t = pipeline.feed(record, findings);
        const std::int32_t subject_pnu = pipeline.subject_pnu();
        if (settings.filtering()) {
            mark_telegram_stations(FilterInput{t}, stations_seen);
            mark_telegram_pnus(FilterInput{t, {}, subject_pnu}, pnus_seen);
        }
        const std::span<const FilterEvent> events =
            filter_events(pipeline.health_events(), event_buffer);
        if (triggers) {
            const std::optional<TriggerHit> hit =
                trigger_hit(settings, t, findings, subject_pnu, events);
            if (Result<void> fed =
                    triggers->feed(record.bytes, record.time_ns, hit ? &*hit : nullptr);
                !fed) {
                print_error(fmt::format("--trigger: {}; no more windows are written", fed.error()));
                triggers.reset();
                write_failed = true;
            }
        }
        if (!show(renderer.get(), settings, t, findings, subject_pnu, events)) continue;
        if (settings.filtering()) {
            shown_summary.add(t);
            shown_summary.add_findings(findings);
        }
        if (writer && !write_failed) {
            Result<void> written =
                with_comments && !findings.empty()
                    ? writer->write(record.bytes, record.time_ns, findings_comment(findings))
                    : writer->write(record.bytes, record.time_ns);
            if (!written) {
                print_error(fmt::format("{}{}", written.error(), capture_file->left_as_it_was()));
                write_failed = true;
            }
            if (raw_round_trip && !raw_round_trip->survives(record.bytes)) {
                print_warning(fmt::format(
                    "{}: frame {} will not read back as it was written: a raw stream keeps no "
                    "record boundaries, so reading it back skips or splits a damaged telegram "
                    "(this one and any later) and numbers the frames after it differently (-F "
                    "hex or pcap keep every record)",
                    settings.write == "-" ? std::string("standard output") : settings.write,
                    record.number));
                raw_round_trip.reset();
            }
        }
    }
    progress.clear();
    std::span<const Finding> open_at_end = pipeline.finish();
    if (triggers) {
        if (Result<void> finished = triggers->finish(); !finished) {
            print_error(fmt::format("--trigger: {}", finished.error()));
            write_failed = true;
        }
        say_trigger_stats(triggers->stats(), settings.write);
    }
    warn_ppo_overrides(pipeline.decoder());
    if (renderer) {
        renderer->render_end_findings(open_at_end);
        renderer->end();
    }
    if (Result<void> found =
            check_telegrams_found(source, read, *settings.protocol, settings.bus_given);
        !found) {
        out.flush();
        print_error(found.error());
        return kExitUsage;  // an existing -w file stays as it was
    }
    out.flush();
    for (std::uint8_t station : settings.stations)
        if (!stations_seen.test(station))
            print_warning(fmt::format("--station {}: no telegram to or from station {} in {}",
                                      station, station, source.name()));
    for (std::uint16_t pnu : settings.pnus)
        if (!pnus_seen.test(pnu))
            print_warning(fmt::format("--pnu {}: no parameter request or answer about PNU {} in {}",
                                      pnu, pnu, source.name()));
    if (settings.quiet) {
        if (settings.filtering()) {
            shown_summary.add_findings(open_at_end);
            InputSummary input = describe_input(source);
            input.name += settings.stations.empty() ? "" : ", telegrams of the --station list";
            input.name += settings.pnus.empty() ? "" : ", telegrams about the --pnu list";
            input.name +=
                settings.display_filter.empty() ? "" : ", telegrams the -Y filter selects";
            // A drive's commands by outcome are its own, whatever --station selects; of the
            // telegrams about a --pnu, the counts alone.
            shown_summary.render_text(out, input, pipeline.decoder(),
                                      settings.pnus.empty() ? &pipeline.tracker() : nullptr);
        } else {
            pipeline.summary().render_text(out, describe_input(source), pipeline.decoder(),
                                           &pipeline.tracker());
        }
    }
    if (writer) {
        if (Result<void> closed = writer->close(); !closed && !write_failed) {
            print_error(fmt::format("{}{}", closed.error(), capture_file->left_as_it_was()));
            write_failed = true;
        }
    }
    int exit_code = source.status() == InputStatus::Damaged ? kExitDamagedInput : kExitOk;
    if (!out.flush()) {
        print_error(fmt::format("cannot write the output to {}: {}",
                                text_stream == stdout ? "standard output" : "standard error",
                                std::strerror(errno)));
        exit_code = kExitOutputError;
    }
    if (exit_code == kExitOk && read == 0)
        exit_code = empty_input_exit(source, settings.allow_empty);
    if (write_failed) exit_code = kExitOutputError;
    if (capture_file)
        // Replaced only by a run that succeeds; what a damaged input gave goes beside it.
        exit_code = finish_staged_output(
            *capture_file, exit_code,
            exit_code == kExitDamagedInput ? "the input ended in damage" : "", "-w", {input_path});
    return exit_code;
}

// `dpscope hex` with VLT 2000 telegrams typed as they are sent ('<01UOGD@0516+00080007>'), one
// or more an argument: read as a text log of one line an argument ("argument N, column C" in
// messages), and decoded as VLT 2000. Every argument must hold a telegram's '<'.
int decode_typed_vlt2000(const std::vector<std::string>& arguments, DecodeSettings& settings) {
    std::size_t first = 0;
    for (std::size_t i = 0; i < arguments.size(); ++i)
        if (arguments[i].find('<') != std::string::npos) {
            first = i;
            break;
        }
    for (std::size_t i = 0; i < arguments.size(); ++i)
        if (arguments[i].find('<') == std::string::npos) {
            print_error(fmt::format(
                "hex: argument {}: '{}' holds no VLT 2000 telegram ('<' ... '>') but argument {} "
                "does; give hex bytes or VLT 2000 telegrams",
                i + 1, arguments[i], first + 1));
            return kExitUsage;
        }
    if (settings.bus_given && settings.protocol != text_log_protocol()) {
        print_error(
            fmt::format("hex: argument {}: '{}' is a VLT 2000 telegram; --bus {} cannot "
                        "read it",
                        first + 1, arguments[first], protocol_name(settings.protocol->protocol)));
        return kExitUsage;
    }
    // The telegram's form names its bus: no note.
    settings.protocol = &vlt2000_protocol();
    std::string text;
    for (const std::string& argument : arguments)
        text += argument + "\n";
    OpenResult source =
        make_memory_text_source("<command line>", text, settings.protocol->framing, "argument");
    if (!source) {
        print_error(source.error());
        return kExitUsage;
    }
    return run_decoding(**source, settings, "");
}

struct DecodeCommand {
    DecodeOptionValues options;
    std::string file;
    std::string read_option;
    std::string input_format = "auto";
};

struct HexCommand {
    DecodeOptionValues options;
    std::vector<std::string> bytes;
};

}  // namespace

void add_decode_command(CLI::App& app, int& exit_code) {
    auto command = std::make_shared<DecodeCommand>();
    CLI::App* sub = app.add_subcommand(
        "decode",
        "Decode a capture: pcap or pcapng (link type 257 PROFIBUS_DL or 147 USER0), a raw serial "
        "byte stream, a hex text log, or a text log of VLT 2000 telegrams. The input kind is "
        "detected from the content.");
    sub->add_option("file", command->file, "Capture file to read; - reads standard input")
        ->type_name("FILE");
    sub->add_option("-r,--read", command->read_option,
                    "Capture file to read (as tshark -r); - "
                    "reads standard input")
        ->type_name("FILE");
    sub->add_option("--input-format", command->input_format,
                    "Input kind: auto (detect from the content), pcap, pcapng, raw (serial byte "
                    "stream, framed by structure), hex (text lines of hex bytes), text (a log of "
                    "VLT 2000 telegrams '<...>' as copied from a terminal; other text on a line "
                    "is ignored)")
        ->check(CLI::IsMember({"auto", "pcap", "pcapng", "raw", "hex", "text"}))
        ->default_str("auto");
    add_display_options(*sub, command->options, "text");
    add_write_options(*sub, command->options);
    add_trigger_options(*sub, command->options, false);
    add_allow_empty_option(*sub, command->options.allow_empty);
    add_tracking_options(*sub, command->options);
    add_line_options(*sub, command->options);
    sub->footer(std::string(kExitCodeHelp));
    sub->callback([command, &exit_code] {
        std::string path = !command->read_option.empty() ? command->read_option : command->file;
        if (path.empty()) {
            print_error("decode: no input; give a FILE or -r FILE (- for standard input)");
            exit_code = kExitUsage;
            return;
        }
        if (!command->read_option.empty() && !command->file.empty()) {
            print_error("decode: give the input once, either as FILE or with -r");
            exit_code = kExitUsage;
            return;
        }
        Result<DecodeSettings> settings = resolve_decode_options(command->options, "text");
        if (!settings) {
            print_error(settings.error());
            exit_code = kExitUsage;
            return;
        }
        OpenResult opened = open_input(
            path, input_format_from_name(command->input_format).value_or(InputFormat::Auto),
            *settings);
        if (!opened) {
            print_error(opened.error());
            exit_code = kExitUsage;
            return;
        }
        exit_code = run_decoding(*opened.value(), *settings, path);
    });
}

void add_hex_command(CLI::App& app, int& exit_code) {
    auto command = std::make_shared<HexCommand>();
    CLI::App* sub = app.add_subcommand(
        "hex",
        "Decode telegrams typed as hex bytes, e.g. 'dpscope hex 10 03 02 49 4E 16', or VLT 2000 "
        "telegrams as they are sent, e.g. 'dpscope hex \"<01UOGD@0516+00080007>\"'. Without "
        "BYTES, reads a hex log from standard input (one line at a time; leading text such as "
        "timestamps or TX/RX is ignored), or a VLT 2000 terminal log piped in. Telegrams are "
        "found by the same framer as raw input.");
    sub->add_option("bytes", command->bytes,
                    "Hex bytes: 68 or 0x68 or 680707 or 68:07:07, in one or more arguments; or "
                    "VLT 2000 telegrams '<...>' (quoted for the shell), one or more an argument")
        ->type_name("BYTES");
    add_display_options(*sub, command->options, "verbose");
    add_write_options(*sub, command->options);
    add_allow_empty_option(*sub, command->options.allow_empty);
    add_tracking_options(*sub, command->options);
    add_line_options(*sub, command->options);
    sub->footer(std::string(kExitCodeHelp));
    sub->callback([command, &exit_code] {
        Result<DecodeSettings> settings = resolve_decode_options(command->options, "verbose");
        if (!settings) {
            print_error(settings.error());
            exit_code = kExitUsage;
            return;
        }
        if (command->bytes.empty()) {
            // Typed at a terminal, nothing would happen until the user types: say so.
            if (isatty(STDIN_FILENO))
                std::fprintf(stderr,
                             "dpscope hex: reading a hex log from the terminal, one telegram or "
                             "more a line; end with Ctrl-D (or give BYTES as arguments)\n");
            // A log typed at a terminal is not held back to choose the bus: PROFIBUS unless
            // --bus says otherwise.
            // A log piped in may be a VLT 2000 terminal log ('<' ... '>'), read as one.
            SourceOptions piped;
            piped.hex_may_be_text = true;
            OpenResult opened = isatty(STDIN_FILENO)
                                    ? open_source("-", InputFormat::Hex, *settings->protocol)
                                    : open_input("-", InputFormat::Hex, *settings, piped);
            if (!opened) {
                print_error(opened.error());
                exit_code = kExitUsage;
                return;
            }
            exit_code = run_decoding(*opened.value(), *settings, "-");
            return;
        }
        if (std::any_of(command->bytes.begin(), command->bytes.end(),
                        [](const std::string& a) { return a.find('<') != std::string::npos; })) {
            exit_code = decode_typed_vlt2000(command->bytes, *settings);
            return;
        }
        std::vector<std::uint8_t> bytes;
        for (std::size_t i = 0; i < command->bytes.size(); ++i) {
            Result<std::vector<std::uint8_t>> parsed = parse_hex_bytes(command->bytes[i]);
            if (!parsed) {
                print_error(fmt::format("hex: argument {}: {}", i + 1, parsed.error()));
                exit_code = kExitUsage;
                return;
            }
            bytes.insert(bytes.end(), parsed->begin(), parsed->end());
        }
        if (!settings->bus_given) {
            BusChoice choice =
                choose_bus(Bytes(bytes.data(), bytes.size()), InputFormat::Raw, true);
            settings->protocol = choice.protocol;
            // Typed telegrams that only one bus frames need no note; one that several buses
            // could frame (or none) is said, with the option that chooses.
            if (!choice.unambiguous) say_bus_choice(*settings, choice, "<command line>");
        }
        auto source =
            memory_source("<command line>", Bytes(bytes.data(), bytes.size()), *settings->protocol);
        exit_code = run_decoding(*source, *settings, "");
    });
}

}  // namespace dpscope::cli
