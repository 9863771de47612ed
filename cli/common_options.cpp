#include "cli/common_options.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "capture/gsd_files.hpp"
#include "cli/pipeline.hpp"
#include "cli/progress.hpp"
#include "drives/shipped_databases.hpp"

namespace dpscope::cli {

CLI::Validator whole_number(std::uint64_t min, std::uint64_t max, std::string_view unit) {
    std::string range = fmt::format("{} to {}{}", min, max, unit);
    return CLI::Validator(
        [min, max, range](std::string& text) -> std::string {
            std::uint64_t value = 0;
            if (parse_whole_number(text, value) && value >= min && value <= max) return {};
            return fmt::format("must be a whole number from {}, not '{}'", range, text);
        },
        range, "whole number");
}

std::optional<double> parse_finite_number(const std::string& text) {
    if (text.empty() || text.find_first_of("xX") != std::string::npos)  // strtod reads hex too
        return std::nullopt;
    char* end = nullptr;
    double value = std::strtod(text.c_str(), &end);
    if (end != text.c_str() + text.size() || !std::isfinite(value)) return std::nullopt;
    return value;
}

CLI::Validator finite_number(double min, double max, std::string_view unit) {
    std::string range = fmt::format("{} to {}{}", min, max, unit);
    return CLI::Validator(
        [min, max, range](std::string& text) -> std::string {
            std::optional<double> value = parse_finite_number(text);
            if (value && *value >= min && *value <= max) return {};
            return fmt::format("must be a number from {}, not '{}'", range, text);
        },
        range, "number");
}

std::vector<std::string> bus_names() {
    std::vector<std::string> names;
    for (const ProtocolDescriptor* descriptor : protocol_table())
        names.emplace_back(descriptor->name);
    return names;
}

CLI::Validator output_file_name() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            return text.empty() ? "must be a file name, or - for standard output, not ''"
                                : std::string();
        },
        "", "file name");  // no description: the help shows the option's type name alone
}

void add_display_filter_option(CLI::App& app, DecodeOptionValues& values, std::string_view what) {
    app.add_option("-Y,--display-filter", values.display_filter,
                   fmt::format("{} Fields by the Wireshark plugin's names (dpscope.pcv.rc == 7, "
                               "dpscope.station == 5, dpscope.finding == \"stacked_request\", "
                               "health.event == \"station_lost\"), == != < <= > >=, contains, "
                               "in {{...}}, && || ! and parentheses; dpscope filter --fields "
                               "lists the fields",
                               what))
        ->type_name("EXPR");
}

bool selected_by_filter(const DecodeSettings& settings, const Pipeline& pipeline,
                        const DecodedTelegram& t, std::span<const Finding> findings) {
    if (!settings.filtering()) return true;
    std::array<FilterEvent, 8> event_buffer;
    return passes_filter(settings, t, findings, pipeline.subject_pnu(),
                         filter_events(pipeline.health_events(), event_buffer));
}

void add_display_options(CLI::App& app, DecodeOptionValues& values,
                         std::string_view default_format) {
    values.format.clear();  // "" until -T is given: the subcommand's default
    app.add_option("-T,--format", values.format,
                   "Output format: text (one line a telegram), verbose (every field), jsonl (one "
                   "JSON object a telegram), csv")
        ->check(CLI::IsMember({"text", "verbose", "jsonl", "csv"}))
        ->default_str(std::string(default_format));
    app.add_flag("-V,--verbose", values.verbose, "Same as -T verbose: the whole field tree");
    app.add_flag("-q,--quiet", values.quiet,
                 "Decode everything but print only a summary: telegrams by frame type and "
                 "service, problems and findings by kind, and the PPO layout of each slave; "
                 "FC and VLT 2000: each drive's commands by outcome (answered, unanswered, "
                 "abandoned, damaged, not judged), as the report counts them, and its responses "
                 "(with --station/--pnu: of the telegrams those select; with --pnu no outcomes). "
                 "Not with -T/-V");
    app.add_flag("-l,--line-buffered", values.line_buffered,
                 "Write each telegram's output as soon as it is decoded, also into a pipe (as "
                 "tcpdump -l); on a terminal that is always done");
    add_display_filter_option(
        app, values,
        "Show only telegrams the filter EXPR selects (docs/filter.md). With --station and --pnu, "
        "all must hold. All telegrams are still decoded and tracked");
    app.add_option("--station", values.stations,
                   "Show only telegrams to or from station ADDR (0 to 127), and those carrying a "
                   "finding about it; repeat for more stations. All telegrams are still decoded "
                   "and tracked.")
        ->check(whole_number(0, 127))
        ->type_name("ADDR")
        ->allow_extra_args(false);
    app.add_option("--pnu", values.pnus,
                   "Show only telegrams about parameter number N: Data_Exchange telegrams whose "
                   "parameter channel is about N (a request for N and its answer, also a "
                   "rejection that leaves the PNU out; PNUs 0-2047), DP-V1 telegrams whose "
                   "PROFIdrive request or response addresses N (0-65535), and those carrying a "
                   "finding about N; repeat for more. N is a number (1613), a group and number "
                   "(16-13, the same PNU) or a parameter's name (Frequency: the whole name, "
                   "else a part of one, without regard to case) that names one PNU in the "
                   "parameter databases of the drives in play (--bus, --drive, --dialect; "
                   "dpscope params lists them)")
        ->type_name("N|G-NN|NAME")
        ->allow_extra_args(false);
}

void add_write_options(CLI::App& app, DecodeOptionValues& values) {
    app.add_option("-w,--write", values.write,
                   "Write the telegrams shown (after -c, --station, --pnu) to FILE as a capture "
                   "instead of printing them (- is standard output); with pcapng, telegrams with "
                   "findings carry them as packet comments. FILE is written (an existing one "
                   "replaced) only by a run that exits 0; a damaged input (exit code 3) writes "
                   "what was read to FILE.partial and leaves FILE as it was; an unusable input "
                   "or a write error writes nothing; never when FILE is the input")
        ->check(output_file_name())
        ->type_name("FILE");
    app.add_option("-F,--write-format", values.write_format,
                   "Capture format for -w: pcap (default), pcapng, raw (bytes only; a damaged "
                   "telegram does not read back as it was, which is warned), hex (one record a "
                   "line with its timestamp, read back record by record)")
        ->check(CLI::IsMember({"pcap", "pcapng", "raw", "hex"}))
        ->type_name("FORMAT");
    app.add_option("--linktype", values.link_type,
                   "Link type for -w pcap/pcapng: profibus (257, PROFIBUS_DL, the default for "
                   "PROFIBUS; PROFIBUS only) or user0 (147, for tools that cannot open 257, and "
                   "the default for the FC protocol and the VLT 2000); 257 and 147 are accepted "
                   "too. A USER0 "
                   "capture records its bus in the file, so that decode reads it without --bus")
        ->check(CLI::IsMember({"profibus", "user0", "257", "147"}))
        ->type_name("TYPE")
        ->default_str("by --bus");
    app.add_flag("-P,--print", values.print,
                 "With -w FILE: print the decode on standard output as well (as tshark -P)");
}

void add_allow_empty_option(CLI::App& app, bool& allow_empty) {
    app.add_flag("--allow-empty", allow_empty,
                 "Pass a capture that holds no telegram (a pcap or pcapng file without records): "
                 "by default that is said on standard error and the exit code is 1, so that a "
                 "failed recording does not pass a check");
}

void add_line_options(CLI::App& app, DecodeOptionValues& values) {
    app.add_option("--baud", values.baud,
                   "The line's baud rate when the capture was made. FC protocol and VLT 2000: a "
                   "telegram's time is when its first byte came, so the time a command takes on "
                   "the line (11 bits a byte for FC, 10 for VLT 2000) is not counted in the "
                   "drive's response time; default 9600. PROFIBUS (report): the bus load and idle "
                   "time of the bus-health section need it; without it they are unknown. Default: "
                   "the line the capture records (sniff -w); a --baud given wins, with a warning "
                   "when they differ")
        ->check(whole_number(300, 12'000'000, " baud"))
        ->type_name("BAUD");
}

void add_tracking_options(CLI::App& app, DecodeOptionValues& values) {
    app.add_option("-c,--count", values.count, "Stop after reading N telegrams")
        ->check(whole_number(1, kMaxCount, " telegrams"))
        ->type_name("N");
    app.add_option("--bus", values.bus,
                   "The bus the capture carries: profibus (PROFIBUS DP), fc (Danfoss FC "
                   "protocol on RS-485) or vlt2000 (VLT 2000/3000/3500 ASCII telegram). Default: "
                   "from the capture (a pcap of link type 257 is "
                   "PROFIBUS; a USER0 pcap written by dpscope names its bus; a raw or hex byte "
                   "stream is tried with each bus's framing, and the choice is said on standard "
                   "error)")
        ->check(CLI::IsMember(bus_names()))
        ->type_name("BUS");
    app.add_option("--fc-pnu-bits", values.fc_pnu_bits,
                   "FC protocol: PKE bits holding the PNU: 12 (FC series, the default) or 11 "
                   "(VLT 2800, FCD 300)")
        ->check(CLI::IsMember({11u, 12u}))
        ->type_name("BITS")
        ->default_str("12");
    app.add_option("--ppo", values.ppo,
                   "ADDR=TYPE: decode slave ADDR (0 to 126) as PPO TYPE (1 to 5) instead of "
                   "inferring the type "
                   "from Chk_Cfg, Get_Cfg or the Data_Exchange length; repeatable")
        ->type_name("ADDR=TYPE")
        ->allow_extra_args(false);
    app.add_option("--dialect", values.dialects,
                   "Parameter-channel code tables: vlt (Danfoss VLT 5000, the default), ge (GE "
                   "AF-600/AF-650: RC 9-12 not used, errors 130/131) or profidrive (PROFIdrive "
                   "PKW with EEPROM variants); for DP-V1 parameter access vlt and ge also take "
                   "Danfoss's request IDs 0x42/0x51/0x52 and axis 0 only. NAME sets it for every "
                   "slave, ADDR=NAME for one; repeatable")
        ->type_name("NAME|ADDR=NAME")
        ->allow_extra_args(false);
    app.add_option("--gsd", values.gsd_files,
                   "PROFIBUS: a slave's GSD file (device description). FILE describes the slaves "
                   "whose Ident_Number (in Set_Prm or Slave_Diag) is the file's; ADDR=FILE "
                   "describes slave ADDR (0 to 126) whatever its ident. Adds vendor, model, "
                   "module names, user parameters and diagnosis texts to the decode, and the "
                   "GSD checks to the tracker (docs/gsd.md); repeatable")
        ->type_name("FILE|ADDR=FILE")
        ->allow_extra_args(false);
    app.add_option("--gsd-dir", values.gsd_dirs,
                   "PROFIBUS: read every GSD file in DIR (*.gsd and the language variants "
                   "*.gse, *.gsg, *.gsf, ...), matched to slaves by Ident_Number; repeatable")
        ->type_name("DIR")
        ->allow_extra_args(false);
    app.add_option("--pcd-profile", values.pcd_profile,
                   "Control/status word profile: fc (Danfoss FC profile) or profidrive. Default: "
                   "fc for vlt and ge slaves, profidrive for profidrive slaves")
        ->check(CLI::IsMember({"fc", "profidrive"}))
        ->type_name("NAME");
    app.add_option("--timeout-ms", values.timeout_ms,
                   "Session tracker: a parameter request unanswered (or a spontaneous message "
                   "unacknowledged) for longer than this is a finding; FC protocol: a command "
                   "unanswered for longer (fc_no_response); VLT 2000: a command unanswered for "
                   "longer (vlt2000_no_response)")
        ->check(whole_number(1, 3'600'000, " ms"))
        ->type_name("MS")
        ->default_str("1000");
    app.add_option("--fc-response-ms", values.fc_response_ms,
                   "FC protocol: a drive answering a command later than this is a finding "
                   "(fc_late_response; a warning). Default 20; the VLT 2800 documents at most 50 "
                   "ms. Unanswered for longer than --timeout-ms is fc_no_response")
        ->check(whole_number(1, 60'000, " ms"))
        ->type_name("MS")
        ->default_str("20");
    app.add_option("--vlt2000-checksum", values.vlt2000_checksum,
                   "VLT 2000: check the telegrams' checksum (sum of the 18 characters after '<', "
                   "last two decimal "
                   "digits, the VLT 3000/3500 rule) or ignore it, for a drive that computes it "
                   "otherwise. Default: check")
        ->check(CLI::IsMember({"check", "ignore"}))
        ->type_name("check|ignore")
        ->default_str("check");
    app.add_flag("--strict", values.strict,
                 "Session tracker: RC 8 (no operating authority) after a read request is an "
                 "unexpected response type, not only unusual");
    add_params_option(app, values.params, values.conversions);
    app.add_option("--drive", values.drives,
                   "The drive family whose parameter database names the PNUs (docs/"
                   "parameters.md; dpscope params lists the families): FAMILY for every station, "
                   "ADDR=FAMILY for one (0 to 126); repeatable. Default: the FC protocol's drives "
                   "fc, VLT 2000's vlt2000, a PROFIBUS slave's by its --dialect (vlt: vlt5000, "
                   "ge: af600, profidrive: profidrive, the PROFIdrive profile's parameters); on "
                   "PROFIBUS the profile's parameters (PNU 900-999, 60000 and up) a family has no "
                   "row for are named by the profidrive family")
        ->type_name("FAMILY|ADDR=FAMILY")
        ->allow_extra_args(false);
}

void add_params_option(CLI::App& app, std::vector<std::string>& files,
                       std::vector<std::string>& conversions) {
    app.add_option("--params", files,
                   "Read a drive parameter database from FILE beside the shipped ones "
                   "(docs/parameters.md: one row a parameter); a family already known takes its "
                   "rows, replacing those of the same PNU. A file that cannot be read or has an "
                   "error is named with its line in a warning, and dpscope goes on without it; "
                   "repeatable")
        ->type_name("FILE")
        ->allow_extra_args(false);
    app.add_option("--conversion-index", conversions,
                   "Give conversion index INDEX (-128 to 127) the factor FACTOR (a decimal "
                   "number above 0, at most 1e9; its decimals are those shown): the value in the "
                   "row's unit is the raw number times FACTOR. Default: the powers of ten, and "
                   "factor 1 for 67, 70, 74, 75, 77 and 100, the indices that name their unit "
                   "(docs/parameters.md, Scaling: older manuals give 74 as 0.1 or 3.6); "
                   "repeatable")
        ->type_name("INDEX=FACTOR")
        ->allow_extra_args(false)
        ->check([](const std::string& text) -> std::string {
            Result<ConversionOverride> parsed = parse_conversion_override(text);
            return parsed ? std::string{} : parsed.error();
        });
}

namespace {

// "USER0" -> "user0": a link type as --linktype names it.
std::string lower_case(std::string_view text) {
    std::string lower(text);
    for (char& c : lower)
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    return lower;
}

}  // namespace

Result<int> capture_link_type(const ProtocolDescriptor& protocol, std::optional<int> given) {
    if (!given) return protocol.written_link_type().value;
    if (const ProtocolDescriptor* owner = only_protocol_of_link_type(*given);
        owner && owner != &protocol)
        return Error{fmt::format(
            "--linktype {}: link type {} ({}) is {} only; a capture of {} is written as {} ({}), "
            "which records its bus",
            owner->name, *given, owner->written_link_type().name,
            owner->framing.protocol_name(), protocol.framing.protocol_name(),
            lower_case(protocol.written_link_type().name), protocol.written_link_type().value)};
    return *given;
}

namespace {

// --drive FAMILY and --drive ADDR=FAMILY into `hints`; a family no database holds is accepted
// (its PNUs are then shown without names) but must be an id a database could have.
Result<void> resolve_drive_options(const std::vector<std::string>& items, DriveHints& hints) {
    for (const std::string& item : items) {
        const std::size_t eq = item.find('=');
        const std::string family = eq == std::string::npos ? item : item.substr(eq + 1);
        if (!is_family_id(family))
            return Error{fmt::format(
                "--drive {}: '{}' is no drive family (lower-case letters, digits, '-', '_'; "
                "dpscope params lists them)",
                item, family)};
        std::string* slot = &hints.all;
        std::string whom = "every station";
        if (eq != std::string::npos) {
            unsigned address = 0;
            if (!parse_whole_number(std::string_view(item).substr(0, eq), address) || address > 126)
                return Error{fmt::format("--drive {}: '{}' is not a station address from 0 to 126",
                                         item, item.substr(0, eq))};
            slot = &hints.station[address];
            whom = fmt::format("station {}", address);
        }
        if (!slot->empty() && *slot != family)
            return Error{
                fmt::format("--drive {}: {} was already given the family {}; give one "
                            "family a station (ADDR=FAMILY sets one station)",
                            item, whom, *slot)};
        *slot = family;
    }
    return {};
}

}  // namespace

std::shared_ptr<const ParameterDatabase> load_parameter_databases(
    const std::vector<std::string>& files, const std::vector<std::string>& conversions) {
    auto database = std::make_shared<ParameterDatabase>();
    const auto load = [&](std::string_view text, std::string_view name) {
        Result<ParameterFile> parsed = parse_parameter_database(text, name);
        if (!parsed) {
            print_warning(fmt::format("{}; dpscope goes on without {}", parsed.error(), name));
            return;
        }
        for (const std::string& warning : parsed->warnings)
            print_warning(warning);
        database->add(std::move(parsed->family));
    };
    for (const ShippedDatabase& shipped : shipped_databases())
        load(shipped.text, shipped.file);
    for (const std::string& file : files) {
        Result<std::string> text =
            read_small_file(file, kMaxParameterFileBytes, "--params", "a parameter database");
        if (!text) {
            print_warning(fmt::format("{}; dpscope goes on without it", text.error()));
            continue;
        }
        load(*text, file);
    }
    for (const std::string& text : conversions)
        if (Result<ConversionOverride> parsed = parse_conversion_override(text))
            database->override_conversion(*parsed);
    return database;
}

std::vector<std::string> families_in_play(const DecodeSettings& settings) {
    std::vector<std::string> families;
    const auto add = [&](std::string_view family) {
        if (std::find(families.begin(), families.end(), family) == families.end())
            families.emplace_back(family);
    };
    for (const ProtocolDescriptor* bus : protocol_table()) {
        if (settings.bus_given && bus != settings.protocol) continue;
        for (std::size_t address = 0; address <= 126; ++address) {
            const auto station = static_cast<std::uint8_t>(address);
            add(drive_family(bus->protocol, settings.lanes.decoder.dialect_of(station),
                             settings.drives.of(station)));
        }
    }
    return families;
}

std::shared_ptr<const ParameterNaming> parameter_naming(const DecodeSettings& settings) {
    return std::make_shared<ParameterNaming>(settings.parameters, settings.protocol->protocol,
                                             settings.lanes.decoder.station_dialects(),
                                             settings.drives);
}

Result<std::uint16_t> resolve_pnu_option(std::string_view text, const ParameterDatabase& database,
                                         std::span<const std::string> families) {
    const bool numeric = !text.empty() && std::all_of(text.begin(), text.end(), [](char c) {
        return (c >= '0' && c <= '9') || c == '-';
    });
    if (numeric) {
        if (std::optional<std::uint16_t> pnu = parse_pnu_text(text)) return *pnu;
        return Error{fmt::format(
            "--pnu {}: must be a whole number from 0 to 65535, a group and number from 0-00 to "
            "655-35 (16-13), or a parameter's name",
            text)};
    }
    Result<std::vector<NamedParameter>> found = database.find_by_name(text, families);
    if (!found) return Error{fmt::format("--pnu {}: {}", text, found.error())};
    return found->front().row->pnu;
}

Result<DecodeSettings> resolve_decode_options(const DecodeOptionValues& values,
                                              std::string_view default_format) {
    DecodeSettings settings;
    const bool format_given = !values.format.empty();
    const std::string format = format_given ? values.format : std::string(default_format);
    if (values.verbose && format != "text" && format != "verbose") {
        return Error{
            fmt::format("-V is the same as -T verbose; it cannot be combined with -T {}", format)};
    }
    settings.format = values.verbose ? OutputFormat::Verbose
                                     : output_format_from_name(format).value_or(OutputFormat::Text);
    if (values.quiet && (values.verbose || format_given)) {
        return Error{fmt::format(
            "-q prints only the text summary; it cannot be combined with {} (drop one of them)",
            values.verbose ? std::string("-V") : "-T " + format)};
    }
    settings.quiet = values.quiet;
    settings.line_buffered = values.line_buffered;
    settings.allow_empty = values.allow_empty;
    settings.count = values.count;
    settings.lanes.timeout_ns = static_cast<std::int64_t>(values.timeout_ms) * 1'000'000;
    settings.lanes.tracker.strict = values.strict;
    settings.lanes.fc_tracker.response_ns =
        static_cast<std::int64_t>(values.fc_response_ms) * 1'000'000;
    settings.baud_given = values.baud;
    use_line(settings, LineSettings{values.baud, std::nullopt, 0});
    if (!values.bus.empty()) {
        settings.protocol = &protocol_descriptor(*protocol_from_name(values.bus));
        settings.bus_given = true;
    }
    settings.lanes.fc_decoder.pnu_bits = static_cast<std::uint8_t>(values.fc_pnu_bits);
    settings.lanes.vlt2000_decoder.check_checksum = values.vlt2000_checksum != "ignore";
    for (unsigned station : values.stations)
        settings.stations.push_back(static_cast<std::uint8_t>(station));
    for (const std::string& item : values.ppo) {
        auto eq = item.find('=');
        unsigned address = 0, type = 0;
        if (eq == std::string::npos ||
            !parse_whole_number(std::string_view(item).substr(0, eq), address) ||
            !parse_whole_number(std::string_view(item).substr(eq + 1), type) || address > 126 ||
            type < 1 || type > 5) {
            return Error{fmt::format(
                "--ppo {}: expected ADDR=TYPE with ADDR from 0 to 126 and TYPE from 1 to 5", item)};
        }
        std::uint8_t& ppo = settings.lanes.decoder.station_ppo[address];
        if (ppo != 0 && ppo != type) {
            return Error{
                fmt::format("--ppo {}: slave {} was already given PPO {}; give one type a slave",
                            item, address, ppo)};
        }
        ppo = static_cast<std::uint8_t>(type);
    }
    bool dialect_for_all = false;
    for (const std::string& item : values.dialects) {
        auto eq = item.find('=');
        std::string_view name = eq == std::string::npos ? std::string_view(item)
                                                        : std::string_view(item).substr(eq + 1);
        auto dialect = dialect_from_name(name);
        if (!dialect) {
            return Error{fmt::format("--dialect {}: '{}' is not a dialect ({})", item, name,
                                     kDialectNameList)};
        }
        if (eq == std::string::npos) {
            if (dialect_for_all && settings.lanes.decoder.dialect != *dialect) {
                return Error{
                    fmt::format("--dialect {}: the dialect for every slave was already given "
                                "as {}; give it once (ADDR=NAME sets one slave)",
                                item, dialect_name(settings.lanes.decoder.dialect))};
            }
            dialect_for_all = true;
            settings.lanes.decoder.dialect = *dialect;
            continue;
        }
        unsigned address = 0;
        if (!parse_whole_number(std::string_view(item).substr(0, eq), address) || address > 126) {
            return Error{fmt::format("--dialect {}: '{}' is not a station address from 0 to 126",
                                     item, item.substr(0, eq))};
        }
        std::optional<Dialect>& station = settings.lanes.decoder.station_dialect[address];
        if (station && *station != *dialect) {
            return Error{
                fmt::format("--dialect {}: slave {} was already given the {} dialect; give "
                            "one dialect a slave",
                            item, address, dialect_name(*station))};
        }
        station = *dialect;
    }
    if (!values.pcd_profile.empty())
        settings.lanes.decoder.pcd_profile = pcd_profile_from_name(values.pcd_profile);
    if (!values.gsd_files.empty() || !values.gsd_dirs.empty()) {
        std::vector<GsdFileSpec> specs;
        for (const std::string& item : values.gsd_files) {
            Result<GsdFileSpec> spec = parse_gsd_file_spec(item);
            if (!spec) return Error{spec.error()};
            specs.push_back(std::move(*spec));
        }
        Result<LoadedGsdFiles> loaded = load_gsd_files(specs, values.gsd_dirs);
        if (!loaded) return Error{loaded.error()};
        for (const std::string& warning : loaded->warnings)
            print_warning(warning);
        settings.lanes.decoder.gsd = std::move(loaded->library);
    }
    if (Result<void> drives = resolve_drive_options(values.drives, settings.drives); !drives)
        return Error{drives.error()};
    settings.parameters = load_parameter_databases(values.params, values.conversions);
    if (!values.pnus.empty()) {
        const std::vector<std::string> families = families_in_play(settings);
        for (const std::string& text : values.pnus) {
            Result<std::uint16_t> pnu = resolve_pnu_option(text, *settings.parameters, families);
            if (!pnu) return Error{pnu.error()};
            settings.pnus.push_back(*pnu);
        }
    }
    // -Y, with --station and --pnu as its shorthands: one filter.
    std::vector<std::string> parts;
    if (!values.display_filter.empty()) {
        Result<DisplayFilter> parsed = DisplayFilter::parse(values.display_filter);
        if (!parsed)
            return Error{fmt::format("-Y '{}': {}", values.display_filter, parsed.error())};
        parts.push_back("(" + values.display_filter + ")");
        settings.display_filter = values.display_filter;
    }
    if (!values.triggers.empty()) {
        std::string joined;
        for (const std::string& text : values.triggers) {
            Result<DisplayFilter> parsed = DisplayFilter::parse(text);
            if (!parsed) return Error{fmt::format("--trigger '{}': {}", text, parsed.error())};
            joined += (joined.empty() ? "(" : " || (") + text + ")";
        }
        Result<DisplayFilter> parsed = DisplayFilter::parse(joined);
        if (!parsed) return Error{fmt::format("--trigger '{}': {}", joined, parsed.error())};
        settings.trigger = std::make_shared<const DisplayFilter>(std::move(*parsed));
        settings.trigger_text =
            values.triggers.size() == 1 ? values.triggers.front() : std::move(joined);
        settings.pre_ns = static_cast<std::int64_t>(values.pre_seconds * 1e9);
        settings.post_ns = static_cast<std::int64_t>(values.post_seconds * 1e9);
        settings.trigger_limit = values.trigger_limit;
        settings.trigger_dir = values.trigger_dir;
        if (settings.trigger->reads("health.")) settings.track_health = true;
    }
    if (!settings.stations.empty()) parts.push_back(station_filter_text(settings.stations));
    if (!settings.pnus.empty()) parts.push_back("(" + pnu_filter_text(settings.pnus) + ")");
    if (!parts.empty()) {
        std::string joined;
        for (const std::string& part : parts)
            joined += (joined.empty() ? "" : " && ") + part;
        Result<DisplayFilter> parsed = DisplayFilter::parse(joined);
        if (!parsed) return Error{fmt::format("-Y '{}': {}", joined, parsed.error())};
        settings.filter = std::make_shared<const DisplayFilter>(std::move(*parsed));
        // health.* fields: the events come from the bus-health tracker.
        if (settings.filter->reads("health.")) settings.track_health = true;
    }
    settings.write = values.write;
    settings.write_format =
        capture_format_from_name(values.write_format).value_or(CaptureFormat::Pcap);
    settings.link_type = values.link_type == "user0" || values.link_type == "147"
                             ? kLinkTypeUser0
                             : kLinkTypeProfibusDl;
    settings.link_type_given = !values.link_type.empty();
    settings.print = values.write.empty() || values.print;
    if (values.write.empty()) {
        const char* unused = values.print                   ? "-P"
                             : !values.write_format.empty() ? "-F"
                             : !values.link_type.empty()    ? "--linktype"
                                                            : nullptr;
        if (unused) {
            return Error{fmt::format("{} goes with -w FILE, which is not given", unused)};
        }
    } else if ((format_given || values.verbose) && !values.print) {
        return Error{
            fmt::format("{}: with -w the decode is not printed; add -P to print it as well",
                        values.verbose ? std::string("-V") : "-T " + format)};
    } else if (values.print && values.write == "-") {
        return Error{
            "-P prints the decode on standard output, where -w - writes the capture; write "
            "the capture to a file"};
    } else if (values.quiet && values.write == "-") {
        return Error{
            "-q prints its summary on standard output, where -w - writes the capture; write "
            "the capture to a file"};
    }
    return settings;
}

bool passes_filter(const DecodeSettings& settings, const DecodedTelegram& t,
                   std::span<const Finding> findings, std::int32_t subject_pnu,
                   std::span<const FilterEvent> events) noexcept {
    if (!settings.filter) return true;
    return settings.filter->matches(FilterInput{t, findings, subject_pnu, events});
}

void add_trigger_options(CLI::App& app, DecodeOptionValues& values, bool with_dir) {
    app.add_option("--trigger", values.triggers,
                   "Keep the telegrams around each telegram the filter EXPR selects (the filter "
                   "language of -Y, docs/filter.md; e.g. 'health.event == \"station_lost\"', "
                   "'dpscope.finding == \"stacked_request\"'): the --pre seconds before it and "
                   "the --post seconds after it go to their own pcapng file, "
                   "trigger-<UTC time>-<event>-<station>.pcapng, the triggering telegram marked "
                   "with a comment; a trigger inside a window extends it. Repeatable (any fires). "
                   "decode: -w names the folder of the files")
        ->type_name("EXPR")
        ->allow_extra_args(false);
    app.add_option("--pre", values.pre_seconds,
                   "With --trigger: the seconds of telegrams before a trigger kept in its file "
                   "(0 to 3600; default 10), held in memory (at most 64 MiB)")
        ->check(finite_number(0, 3600, " seconds"))
        ->type_name("SECONDS");
    app.add_option("--post", values.post_seconds,
                   "With --trigger: the seconds of telegrams after the last trigger of a window "
                   "(0 to 3600; default 10)")
        ->check(finite_number(0, 3600, " seconds"))
        ->type_name("SECONDS");
    app.add_option("--trigger-limit", values.trigger_limit,
                   "With --trigger: at most N windows start in an hour of capture time (1 to "
                   "100000; default 60); the triggers over it are counted, not written")
        ->check(whole_number(1, 100000))
        ->type_name("N");
    if (with_dir)
        app.add_option("--trigger-dir", values.trigger_dir,
                       "With --trigger: the folder of the trigger files (made if missing; default: "
                       "the folder of -w, else the current one)")
            ->type_name("DIR");
}

std::optional<TriggerHit> trigger_hit(const DecodeSettings& settings, const DecodedTelegram& t,
                                      std::span<const Finding> findings, std::int32_t subject_pnu,
                                      std::span<const FilterEvent> events) {
    if (!settings.trigger ||
        !settings.trigger->matches(FilterInput{t, findings, subject_pnu, events}))
        return std::nullopt;
    TriggerHit hit;
    if (!events.empty()) {
        hit.event = std::string(events.front().event);
        if (events.front().station != kSegmentAddress) hit.station = events.front().station;
    } else if (!findings.empty()) {
        hit.event = std::string(finding_kind_name(findings.front().kind));
        if (findings.front().has_stations) hit.station = findings.front().slave;
    } else {
        hit.event = "match";
        if (t.has_roles) hit.station = t.slave;
    }
    hit.comment = fmt::format("dpscope trigger: {} (frame {})", settings.trigger_text, t.frame);
    return hit;
}

Result<std::unique_ptr<TriggerRecorder>> make_trigger_recorder(const DecodeSettings& settings,
                                                               const std::string& folder,
                                                               std::string_view option) {
    if (folder.empty())
        return Error{
            fmt::format("--trigger writes each window to a file of its own: give {} "
                        "FOLDER",
                        option)};
    if (folder == "-")
        return Error{
            fmt::format("--trigger writes files, not standard output: give {} a folder", option)};
    std::error_code error;
    if (std::filesystem::exists(folder, error)) {
        if (!std::filesystem::is_directory(folder, error))
            return Error{
                fmt::format("{} {}: not a folder (with --trigger, {} names the folder "
                            "of the trigger files)",
                            option, folder, option)};
    } else if (!std::filesystem::create_directories(folder, error) && error) {
        return Error{
            fmt::format("{} {}: cannot make the folder: {}", option, folder, error.message())};
    }
    Result<int> link_type = capture_link_type(
        *settings.protocol,
        settings.link_type_given ? std::optional<int>(settings.link_type) : std::nullopt);
    if (!link_type) return Error{link_type.error()};
    TriggerOptions options;
    options.folder = folder;
    options.pre_ns = settings.pre_ns;
    options.post_ns = settings.post_ns;
    options.limit_per_hour = settings.trigger_limit;
    options.link_type = *link_type;
    options.bus = settings.protocol->protocol;
    options.line = settings.line;
    return std::make_unique<TriggerRecorder>(std::move(options));
}

void say_trigger_stats(const TriggerStats& stats, const std::string& folder) {
    std::string text = fmt::format("dpscope: --trigger: {} written in {} ({} fired)",
                                   counted(stats.windows, "window", "windows"), folder,
                                   counted(stats.hits, "telegram", "telegrams"));
    if (stats.suppressed > 0)
        text += fmt::format("; {} started no window: over --trigger-limit", stats.suppressed);
    if (stats.pre_dropped > 0)
        text += fmt::format("; {} let go before --pre ended: the memory cap (64 MiB)",
                            counted(stats.pre_dropped, "telegram", "telegrams"));
    write_standard_error(text + "\n");
}

std::span<const FilterEvent> name_filter_events(std::span<const HealthEvent> events,
                                                std::span<FilterEvent> out) noexcept {
    std::size_t n = 0;
    for (const HealthEvent& e : events) {
        if (n == out.size()) break;
        out[n++] = FilterEvent{health_event_name(e.kind),
                               e.kind == HealthEventKind::VerdictBad ? "bad" : "", e.address};
    }
    return out.first(n);
}

int finish_staged_output(PendingOutputFile& file, int exit_code, std::string_view partial_why,
                         std::string_view option, const std::vector<std::string>& inputs) {
    if (exit_code == kExitOk || exit_code == kExitFindings) {
        if (Result<void> committed = file.commit(); !committed) {
            print_error(committed.error());
            return kExitOutputError;
        }
        return exit_code;
    }
    if (partial_why.empty()) {
        file.discard();
        return exit_code;
    }
    Result<std::string> kept = file.keep_beside(inputs);
    if (!kept) {
        print_error(kept.error());
        return kExitOutputError;
    }
    if (kept->empty()) return exit_code;  // standard output or a device: written as it came
    print_warning(fmt::format("{} {}: {} (exit code {}), so {} is {}; what was written is in {}",
                              option, file.name(), partial_why, exit_code, file.name(),
                              file.target_existed() ? "left as it was" : "not made", *kept));
    return exit_code;
}

void report_input_issues(TelegramSource& source, Output& out) {
    source.on_issue([&out](const InputIssue& issue) {
        out.flush();
        print_diagnostic(issue.severity, issue.message);
    });
}

void warn_ppo_overrides(const TelegramDecoder& capture_decoder) {
    const auto* profibus = dynamic_cast<const BusDecoder*>(&capture_decoder);
    if (profibus == nullptr) return;  // --ppo is PROFIBUS's
    const BusDecoder& decoder = *profibus;
    for (unsigned address = 0; address < kStationCount; ++address) {
        const StationConfig& station = decoder.station(static_cast<std::uint8_t>(address));
        if (station.overridden_cfg_frame == 0) continue;
        const PpoLayout& announced = station.overridden_ppo;
        std::string layout = announced.type != 0
                                 ? fmt::format("PPO {}", announced.type)
                                 : fmt::format("a layout of {} output and {} input bytes",
                                               announced.output_bytes, announced.input_bytes);
        unsigned forced = decoder.options().station_ppo[address];
        print_warning(fmt::format(
            "--ppo {}={}: the {} in frame {} announces {} for slave {}; decoded as PPO {}, as the "
            "option says",
            address, forced, announced.source == PpoSource::GetCfg ? "Get_Cfg response" : "Chk_Cfg",
            station.overridden_cfg_frame, layout, address, forced));
    }
}

namespace {

// The bus as messages name it: "the FC protocol (RS-485)", "PROFIBUS DP".
std::string bus_title(Protocol protocol) { return std::string(protocol_descriptor(protocol).title); }

}  // namespace

void say_bus_choice(const DecodeSettings& settings, const BusChoice& choice,
                    const std::string& input) {
    if (settings.bus_given) {
        if (choice.tagged && *choice.tagged != settings.protocol->protocol)
            print_warning(fmt::format(
                "{}: the capture records its bus as {}, but --bus {} says {}; decoded as --bus "
                "says",
                input, bus_title(*choice.tagged), protocol_name(settings.protocol->protocol),
                bus_title(settings.protocol->protocol)));
        return;
    }
    if (choice.say)
        print_diagnostic(Severity::Note,
                         fmt::format("{}: read as {}: {}; --bus chooses", input,
                                     bus_title(choice.protocol->protocol), choice.reason));
}

void warn_profibus_options(const DecodeSettings& settings, const std::string& input) {
    const Protocol bus = settings.protocol->protocol;
    // The options given (not at their defaults) that belong to each bus.
    std::array<std::vector<std::string_view>, kProtocolCount> given_for;
    const auto given = [&](Protocol owner, std::string_view option) {
        given_for[static_cast<std::size_t>(owner)].push_back(option);
    };
    const DecoderOptions& dp = settings.lanes.decoder;
    if (std::any_of(dp.station_ppo.begin(), dp.station_ppo.end(),
                    [](std::uint8_t ppo) { return ppo != 0; }))
        given(Protocol::ProfibusDp, "--ppo");
    if (dp.dialect != Dialect::Vlt ||
        std::any_of(dp.station_dialect.begin(), dp.station_dialect.end(),
                    [](const std::optional<Dialect>& d) { return d.has_value(); }))
        given(Protocol::ProfibusDp, "--dialect");
    if (dp.pcd_profile) given(Protocol::ProfibusDp, "--pcd-profile");
    if (dp.gsd) given(Protocol::ProfibusDp, "--gsd/--gsd-dir");
    if (settings.lanes.tracker.strict) given(Protocol::ProfibusDp, "--strict");
    if (settings.lanes.fc_decoder.pnu_bits != FcDecoderOptions{}.pnu_bits)
        given(Protocol::Fc, "--fc-pnu-bits");
    if (settings.lanes.fc_tracker.response_ns != FcTrackerOptions{}.response_ns)
        given(Protocol::Fc, "--fc-response-ms");
    if (!settings.lanes.vlt2000_decoder.check_checksum)
        given(Protocol::Vlt2000, "--vlt2000-checksum");
    for (const ProtocolDescriptor* owner : protocol_table()) {
        const auto& options = given_for[static_cast<std::size_t>(owner->protocol)];
        if (owner->protocol == bus || options.empty()) continue;
        print_warning(fmt::format("{}: {} {} to {}; this capture is {}: ignored", input,
                                  fmt::join(options, ", "),
                                  options.size() == 1 ? "applies" : "apply", owner->title,
                                  bus_title(bus)));
    }
}

void use_line(DecodeSettings& settings, const LineSettings& line) {
    if (line.known()) {
        settings.line.baud = line.baud;
        settings.lanes.line_baud = line.baud;
        settings.health.baud = line.baud;
    }
    if (line.frame_known()) {
        settings.line.parity = line.parity;
        settings.line.stop_bits = line.stop_bits;
        const unsigned bits = character_bits(*line.parity, line.stop_bits);
        settings.lanes.character_bits = bits;
        settings.health.character_bits = bits;
    }
}

namespace {

// The line a capture records (sniff -w), used where --baud does not say otherwise.
void use_recorded_line(DecodeSettings& settings, const LineSettings& recorded,
                       const std::string& input) {
    LineSettings line = recorded;
    if (settings.baud_given != 0) {
        if (recorded.known() && recorded.baud != settings.baud_given)
            print_warning(fmt::format(
                "{}: the capture records its line as {}, but --baud says {}; timed at {} baud, "
                "as --baud says",
                input, describe_line(recorded), settings.baud_given, settings.baud_given));
        line.baud = settings.baud_given;
    }
    use_line(settings, line);
}

}  // namespace

OpenResult open_input(const std::string& path, InputFormat format, DecodeSettings& settings,
                      const SourceOptions& options) {
    BusChoice choice;
    OpenResult opened = open_source(path, format, settings.bus_given ? settings.protocol : nullptr,
                                    choice, options);
    if (!opened) return opened;
    settings.protocol = choice.protocol;
    say_bus_choice(settings, choice, (*opened)->name());
    warn_profibus_options(settings, (*opened)->name());
    use_recorded_line(settings, choice.line, (*opened)->name());
    return opened;
}

Result<void> check_telegrams_found(const TelegramSource& source, std::uint64_t telegrams,
                                   const ProtocolDescriptor& protocol, bool bus_given) {
    if (source.status() == InputStatus::Unusable) return Error{source.unusable_reason()};
    if (telegrams > 0 || source.status() == InputStatus::Damaged) return {};
    // Without --bus: the bus was chosen by the capture; name the option that chooses it.
    const std::string hint = bus_given ? std::string()
                                       : fmt::format(" (read as {}; --bus chooses the bus)",
                                                     bus_title(protocol.protocol));
    const std::uint64_t skipped = source.bytes_skipped();
    switch (source.format()) {
        case InputFormat::Raw:
            if (skipped == 0) return Error{fmt::format("{}: the input is empty", source.name())};
            return Error{
                fmt::format("{}: no {} telegram in its {} read as a raw byte stream; is it a "
                            "capture?{}{}{}",
                            source.name(), protocol.framing.protocol_name(),
                            counted(skipped, "byte", "bytes"), source.looks_like_text() ? " I" : "",
                            source.looks_like_text() ? text_input_hint().substr(1) : "", hint)};
        case InputFormat::Hex:
            if (skipped == 0 && source.issue_count(IssueKind::HexSyntax) > 0)
                return Error{fmt::format(
                    "{}: no readable hex bytes in the text ({} with tokens that "
                    "are no hex bytes, named above)",
                    source.name(),
                    source.issue_count(IssueKind::HexSyntax) == 1
                        ? std::string("1 line")
                        : fmt::format("{} lines", source.issue_count(IssueKind::HexSyntax)))};
            if (skipped == 0)
                return Error{fmt::format("{}: no hex bytes in the text", source.name())};
            return Error{fmt::format("{}: no {} telegram in its {} hex bytes{}", source.name(),
                                     protocol.framing.protocol_name(), skipped, hint)};
        case InputFormat::Text:
            if (skipped == 0)
                return Error{fmt::format("{}: no {} telegram ('<' ... '>') in the text",
                                         source.name(), protocol.framing.protocol_name())};
            return Error{fmt::format(
                "{}: no {} telegram in the text, only {} {} of broken ones (named above)",
                source.name(), protocol.framing.protocol_name(), skipped,
                skipped == 1 ? "character" : "characters")};
        default: return {};
    }
}

int empty_input_exit(const TelegramSource& source, bool allow_empty) {
    if (allow_empty) {
        print_diagnostic(Severity::Note, fmt::format("{}: no telegrams", source.name()));
        return kExitOk;
    }
    print_error(fmt::format("{}: no telegrams: the capture is empty (--allow-empty accepts it)",
                            source.name()));
    return kExitFindings;
}

namespace {

std::atomic<std::uint64_t> g_dropped_standard_error{0};

}  // namespace

bool write_standard_error(std::string_view text) noexcept {
    if (std::fwrite(text.data(), 1, text.size(), stderr) == text.size() && std::fflush(stderr) == 0)
        return true;
    std::clearerr(stderr);  // the next message is tried again (a disk may have room by then)
    count_dropped_standard_error_message();
    return false;
}

std::uint64_t dropped_standard_error_messages() noexcept {
    return g_dropped_standard_error.load(std::memory_order_relaxed);
}

void count_dropped_standard_error_message() noexcept {
    g_dropped_standard_error.fetch_add(1, std::memory_order_relaxed);
}

void print_diagnostic(Severity severity, std::string_view message) {
    clear_progress_line();
    std::fflush(stdout);
    // fmt::print would throw std::system_error on a failed write: a closed standard error must
    // never end a command.
    write_standard_error(fmt::format("dpscope: {}: {}\n", severity_name(severity), message));
}

void print_error(std::string_view message) { print_diagnostic(Severity::Error, message); }

void print_warning(std::string_view message) { print_diagnostic(Severity::Warning, message); }

// --- Bus health (issue 12) ----------------------------------------------------------------------

namespace {

// A threshold's value as the help writes it: "3", "0.1", "1000000000".
std::string limit_text(double value) {
    return value == std::floor(value) ? fmt::format("{:.0f}", value) : fmt::format("{:g}", value);
}

// "lost_cycles (default 3, 1 to 1000)", "repeat_percent_bad (default 5, 0 to 100 %)" for each
// threshold, for --threshold's help.
std::string threshold_list() {
    std::string list;
    for (const HealthThresholdRow& row : health_threshold_catalogue()) {
        if (!list.empty()) list += "; ";
        list += fmt::format("{} (default {}, {} to {}{}{})", row.name,
                            limit_text(row.default_value), limit_text(row.minimum),
                            limit_text(row.maximum), row.unit.empty() ? "" : " ", row.unit);
    }
    return list;
}

}  // namespace

void add_health_options(CLI::App& app, HealthOptionValues& values) {
    app.add_option("--health-config", values.config,
                   "Read the bus-health thresholds from FILE: 'name = value' lines, '#' or ';' "
                   "comments, optionally under a [thresholds] header (TOML or INI); an error "
                   "names FILE:LINE. A regular file of at most 64 KiB. --threshold options "
                   "apply after it")
        ->type_name("FILE");
    app.add_option("--threshold", values.thresholds,
                   "Set one bus-health threshold, NAME=VALUE (repeatable; after --health-config). "
                   "The thresholds (docs/bus-health.md): " +
                       threshold_list())
        ->type_name("NAME=VALUE")
        ->allow_extra_args(false);
}

Result<HealthThresholds> resolve_health_options(const HealthOptionValues& values) {
    HealthThresholds thresholds;
    if (!values.config.empty()) {
        Result<std::string> text =
            read_small_file(values.config, kMaxHealthConfigBytes, "--health-config",
                            "a settings file of 'name = value' lines");
        if (!text) return Error{text.error()};
        if (Result<void> loaded = thresholds.load(*text, values.config); !loaded)
            return Error{fmt::format("--health-config {}", loaded.error())};
    }
    for (const std::string& assignment : values.thresholds)
        if (Result<void> set = thresholds.set_from_text(assignment); !set)
            return Error{fmt::format("--threshold {}: {}", assignment, set.error())};
    return thresholds;
}

std::optional<HealthFailOn> health_fail_on_from_name(std::string_view name) noexcept {
    if (name == "bad") return HealthFailOn::Bad;
    if (name == "weak") return HealthFailOn::Weak;
    if (name == "never") return HealthFailOn::Never;
    return std::nullopt;
}

bool verdict_fails(Verdict verdict, HealthFailOn fail_on) noexcept {
    switch (fail_on) {
        case HealthFailOn::Bad: return verdict == Verdict::Bad;
        case HealthFailOn::Weak: return verdict != Verdict::Good;
        case HealthFailOn::Never: break;
    }
    return false;
}

}  // namespace dpscope::cli
