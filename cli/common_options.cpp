#include "cli/common_options.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cstdio>

#include "cli/pipeline.hpp"

namespace dpscope::cli {

void add_display_options(CLI::App& app, DecodeOptionValues& values,
                         std::string_view default_format) {
    values.format = std::string(default_format);
    app.add_option("-T,--format", values.format,
                   "Output format: text (one line a telegram), verbose (every field), jsonl (one "
                   "JSON object a telegram), csv")
        ->check(CLI::IsMember({"text", "verbose", "jsonl", "csv"}))
        ->default_str(std::string(default_format));
    app.add_flag("-V,--verbose", values.verbose, "Same as -T verbose: the whole field tree");
    app.add_flag("-q,--quiet", values.quiet,
                 "Decode everything but print only a summary: telegrams by frame type and "
                 "service, problems and findings by kind, and the PPO layout of each slave");
    app.add_option("--station", values.stations,
                   "Show only telegrams to or from station ADDR (0..127); repeat for more "
                   "stations. All telegrams are still decoded and tracked.")
        ->check(CLI::Range(0, 127))
        ->type_name("ADDR")
        ->allow_extra_args(false);
    app.add_option("--pnu", values.pnus,
                   "Show only Data_Exchange telegrams whose parameter channel carries parameter "
                   "number N; repeat for more")
        ->check(CLI::Range(0, 2047))
        ->type_name("N")
        ->allow_extra_args(false);
}

void add_tracking_options(CLI::App& app, DecodeOptionValues& values) {
    app.add_option("-c,--count", values.count, "Stop after reading N telegrams")->check(kPositive);
    app.add_option("--ppo", values.ppo,
                   "ADDR=TYPE: decode slave ADDR as PPO TYPE (1..5) instead of inferring the type "
                   "from Chk_Cfg, Get_Cfg or the Data_Exchange length; repeatable")
        ->type_name("ADDR=TYPE")
        ->allow_extra_args(false);
    app.add_option("--dialect", values.dialects,
                   "Parameter-channel code tables: vlt (Danfoss VLT 5000 / GE AF-600, the "
                   "default) or profidrive (PROFIdrive PKW with EEPROM variants). NAME sets it "
                   "for every slave, ADDR=NAME for one; repeatable")
        ->type_name("NAME|ADDR=NAME")
        ->allow_extra_args(false);
    app.add_option("--pcd-profile", values.pcd_profile,
                   "Control/status word profile: fc (Danfoss FC profile) or profidrive. Default: "
                   "fc for vlt slaves, profidrive for profidrive slaves")
        ->check(CLI::IsMember({"fc", "profidrive"}))
        ->type_name("NAME");
    app.add_option("--timeout-ms", values.timeout_ms,
                   "Session tracker: a parameter request unanswered (or a spontaneous message "
                   "unacknowledged) for longer than this is a finding")
        ->check(CLI::Range(1u, 3'600'000u))
        ->default_str("1000");
    app.add_flag("--strict", values.strict,
                 "Session tracker: RC 8 (no operating authority) after a read request is an "
                 "unexpected response type, not only unusual");
}

namespace {

bool parse_unsigned(std::string_view text, unsigned& value) {
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    return ec == std::errc() && end == text.data() + text.size() && !text.empty();
}

}  // namespace

std::optional<DecodeSettings> resolve_decode_options(const DecodeOptionValues& values,
                                                     std::string& error) {
    DecodeSettings settings;
    if (values.verbose && values.format != "text" && values.format != "verbose") {
        error = fmt::format("-V is the same as -T verbose; it cannot be combined with -T {}",
                            values.format);
        return std::nullopt;
    }
    settings.format = values.verbose
                          ? OutputFormat::Verbose
                          : output_format_from_name(values.format).value_or(OutputFormat::Text);
    settings.quiet = values.quiet;
    settings.count = values.count;
    settings.tracker.timeout_ns = static_cast<std::int64_t>(values.timeout_ms) * 1'000'000;
    settings.tracker.strict = values.strict;
    for (unsigned station : values.stations)
        settings.stations.push_back(static_cast<std::uint8_t>(station));
    for (unsigned pnu : values.pnus)
        settings.pnus.push_back(static_cast<std::uint16_t>(pnu));
    for (const std::string& item : values.ppo) {
        auto eq = item.find('=');
        unsigned address = 0, type = 0;
        if (eq == std::string::npos ||
            !parse_unsigned(std::string_view(item).substr(0, eq), address) ||
            !parse_unsigned(std::string_view(item).substr(eq + 1), type) || address > 126 ||
            type < 1 || type > 5) {
            error =
                fmt::format("--ppo {}: expected ADDR=TYPE with ADDR 0..126 and TYPE 1..5", item);
            return std::nullopt;
        }
        settings.decoder.station_ppo[address] = static_cast<std::uint8_t>(type);
    }
    for (const std::string& item : values.dialects) {
        auto eq = item.find('=');
        std::string_view name = eq == std::string::npos ? std::string_view(item)
                                                        : std::string_view(item).substr(eq + 1);
        auto dialect = dialect_from_name(name);
        if (!dialect) {
            error =
                fmt::format("--dialect {}: '{}' is not a dialect (vlt, profidrive)", item, name);
            return std::nullopt;
        }
        if (eq == std::string::npos) {
            settings.decoder.dialect = *dialect;
            continue;
        }
        unsigned address = 0;
        if (!parse_unsigned(std::string_view(item).substr(0, eq), address) || address > 126) {
            error = fmt::format("--dialect {}: '{}' is not a station address 0..126", item,
                                item.substr(0, eq));
            return std::nullopt;
        }
        settings.decoder.station_dialect[address] = *dialect;
    }
    if (!values.pcd_profile.empty())
        settings.decoder.pcd_profile = pcd_profile_from_name(values.pcd_profile);
    return settings;
}

bool passes_filter(const DecodeSettings& settings, const DecodedTelegram& t) noexcept {
    if (!settings.stations.empty()) {
        bool match =
            std::any_of(settings.stations.begin(), settings.stations.end(), [&](std::uint8_t a) {
                return (t.fdl.has_addresses && (t.fdl.da == a || t.fdl.sa == a)) ||
                       (t.has_roles && (t.master == a || t.slave == a));
            });
        if (!match) return false;
    }
    if (!settings.pnus.empty()) {
        if (!t.has_pcv) return false;
        if (std::find(settings.pnus.begin(), settings.pnus.end(), t.pcv.pnu) == settings.pnus.end())
            return false;
    }
    return true;
}

void report_input_issues(TelegramSource& source, Output& out) {
    source.on_issue([&out](const InputIssue& issue) {
        out.flush();
        print_diagnostic(issue.severity, issue.message);
    });
}

std::string nothing_found_error(const TelegramSource& source, std::uint64_t telegrams) {
    if (source.status() == InputStatus::Unusable) return source.unusable_reason();
    if (telegrams > 0 || source.status() == InputStatus::Damaged) return {};
    const std::uint64_t skipped = source.bytes_skipped();
    switch (source.format()) {
        case InputFormat::Raw:
            if (skipped == 0) return fmt::format("{}: the input is empty", source.name());
            return fmt::format(
                "{}: no PROFIBUS telegram in its {} bytes read as a raw byte stream; is it a "
                "capture?",
                source.name(), skipped);
        case InputFormat::Hex:
            if (skipped == 0 && source.issue_count(IssueKind::HexSyntax) > 0)
                return fmt::format("{}: no readable hex bytes in the text ({} with tokens that "
                                   "are no hex bytes, named above)",
                                   source.name(),
                                   source.issue_count(IssueKind::HexSyntax) == 1
                                       ? std::string("1 line")
                                       : fmt::format("{} lines",
                                                     source.issue_count(IssueKind::HexSyntax)));
            if (skipped == 0) return fmt::format("{}: no hex bytes in the text", source.name());
            return fmt::format("{}: no PROFIBUS telegram in its {} hex bytes", source.name(),
                               skipped);
        default: return {};
    }
}

void print_diagnostic(Severity severity, std::string_view message) {
    std::fflush(stdout);
    fmt::print(stderr, "dpscope: {}: {}\n", severity_name(severity), message);
}

void print_error(std::string_view message) { print_diagnostic(Severity::Error, message); }

void print_warning(std::string_view message) { print_diagnostic(Severity::Warning, message); }

}  // namespace dpscope::cli
