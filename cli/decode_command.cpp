// dpscope decode: a capture file (or standard input) to decoded telegrams.
// dpscope hex:    telegrams typed as hex on the command line or piped in as a hex log.
#include <fmt/format.h>
#include <unistd.h>

#include <memory>
#include <string>
#include <vector>

#include "capture/hex_log.hpp"
#include "capture/telegram_source.hpp"
#include "cli/commands.hpp"
#include "cli/common_options.hpp"
#include "cli/pipeline.hpp"

namespace dpscope::cli {

namespace {

// Decodes every telegram of `source`, renders those that pass the filters, and returns the exit
// code. Input problems are reported on standard error as they are met.
int run_decoding(TelegramSource& source, const DecodeSettings& settings) {
    Output out(stdout, isatty(STDOUT_FILENO) != 0);
    report_input_issues(source, out);
    Pipeline pipeline(settings);
    std::unique_ptr<TelegramRenderer> renderer;
    if (!settings.quiet) {
        renderer = make_renderer(settings.format, out);
        renderer->begin();
    }
    Record record;
    std::uint64_t read = 0;
    std::span<const Finding> findings;
    source.stop_after(settings.count);
    while (source.next(record)) {
        ++read;
        const DecodedTelegram& t = pipeline.feed(record, findings);
        if (renderer) show(*renderer, settings, t, findings);
    }
    std::span<const Finding> open_at_end = pipeline.finish();
    if (renderer) {
        renderer->render_end_findings(open_at_end);
        renderer->end();
    }
    if (std::string nothing = nothing_found_error(source, read); !nothing.empty()) {
        out.flush();
        print_error(nothing);
        return kExitUsage;
    }
    if (settings.quiet)
        pipeline.summary().render_text(out, describe_input(source), pipeline.decoder());
    if (!out.flush()) {
        print_error("cannot write the output");
        return kExitOutputError;
    }
    return source.status() == InputStatus::Damaged ? kExitDamagedInput : kExitOk;
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
        "byte stream, or a hex text log. The input kind is detected from the content.");
    sub->add_option("file", command->file, "Capture file to read; - reads standard input")
        ->type_name("FILE");
    sub->add_option("-r,--read", command->read_option,
                    "Capture file to read (as tshark -r); - "
                    "reads standard input")
        ->type_name("FILE");
    sub->add_option("--input-format", command->input_format,
                    "Input kind: auto (detect from the content), pcap, pcapng, raw (serial byte "
                    "stream, framed by structure), hex (text lines of hex bytes)")
        ->check(CLI::IsMember({"auto", "pcap", "pcapng", "raw", "hex"}))
        ->default_str("auto");
    add_display_options(*sub, command->options, "text");
    add_tracking_options(*sub, command->options);
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
        std::string error;
        auto settings = resolve_decode_options(command->options, error);
        if (!settings) {
            print_error(error);
            exit_code = kExitUsage;
            return;
        }
        OpenResult opened = open_source(
            path, input_format_from_name(command->input_format).value_or(InputFormat::Auto));
        if (!opened.source) {
            print_error(opened.error);
            exit_code = kExitUsage;
            return;
        }
        exit_code = run_decoding(*opened.source, *settings);
    });
}

void add_hex_command(CLI::App& app, int& exit_code) {
    auto command = std::make_shared<HexCommand>();
    CLI::App* sub = app.add_subcommand(
        "hex",
        "Decode telegrams typed as hex bytes, e.g. 'dpscope hex 10 03 02 49 4E 16'. Without "
        "BYTES, reads a hex log from standard input (one line at a time; leading text such as "
        "timestamps or TX/RX is ignored). Telegrams are found by the same framer as raw input.");
    sub->add_option("bytes", command->bytes,
                    "Hex bytes: 68 or 0x68 or 680707 or 68:07:07, in one or more arguments")
        ->type_name("BYTES");
    add_display_options(*sub, command->options, "verbose");
    add_tracking_options(*sub, command->options);
    sub->footer(std::string(kExitCodeHelp));
    sub->callback([command, &exit_code] {
        std::string error;
        auto settings = resolve_decode_options(command->options, error);
        if (!settings) {
            print_error(error);
            exit_code = kExitUsage;
            return;
        }
        if (command->bytes.empty()) {
            OpenResult opened = open_source("-", InputFormat::Hex);
            if (!opened.source) {
                print_error(opened.error);
                exit_code = kExitUsage;
                return;
            }
            exit_code = run_decoding(*opened.source, *settings);
            return;
        }
        std::vector<std::uint8_t> bytes;
        for (std::size_t i = 0; i < command->bytes.size(); ++i) {
            if (!parse_hex_bytes(command->bytes[i], bytes, error)) {
                print_error(fmt::format("hex: argument {}: {}", i + 1, error));
                exit_code = kExitUsage;
                return;
            }
        }
        auto source = memory_source("<command line>", Bytes(bytes.data(), bytes.size()));
        exit_code = run_decoding(*source, *settings);
    });
}

}  // namespace dpscope::cli
