// Options shared by the subcommands that decode (decode, hex), their validation, and the exit
// codes every subcommand uses.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "decoder/bus_decoder.hpp"
#include "decoder/session_tracker.hpp"
#include "formats/renderer.hpp"

namespace dpscope::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFindings = 1;      // report: findings at or above --fail-on
inline constexpr int kExitUsage = 2;         // bad command line, or input unusable from the start
inline constexpr int kExitDamagedInput = 3;  // input stopped early; what came before was decoded
inline constexpr int kExitOutputError = 4;   // output could not be opened or written
inline constexpr int kExitDeviceError = 5;   // sniff: the capture device failed

inline constexpr std::string_view kExitCodeHelp =
    "Exit codes: 0 success; 1 report found something at or above --fail-on; 2 bad usage or "
    "unusable input (cannot open, unknown format, unsupported link type); 3 the input ended in "
    "damage (truncated record, read error) after what was decoded; 4 output could not be "
    "opened or written (no such directory, disk full); 5 the capture device failed (sniff).";

// A number greater than 0 (CLI11's PositiveNumber names its range as 0 to 1.8e308).
inline const CLI::Validator kPositive(
    [](std::string& text) -> std::string {
        char* end = nullptr;
        double value = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0') return "'" + text + "' is not a number";
        return value > 0 ? std::string() : "must be greater than 0, not " + text;
    },
    "> 0", "positive");

// What the command line says, before validation.
struct DecodeOptionValues {
    std::string format = "text";
    bool verbose = false;
    bool quiet = false;
    std::uint64_t count = 0;
    std::vector<unsigned> stations;
    std::vector<unsigned> pnus;
    std::vector<std::string> ppo;
    std::vector<std::string> dialects;
    std::string pcd_profile;
    std::uint32_t timeout_ms = 1000;
    bool strict = false;
};

// How to decode and track: -c, --ppo, --dialect, --pcd-profile, --timeout-ms, --strict.
void add_tracking_options(CLI::App& app, DecodeOptionValues& values);
// What decode and hex print: -T, -V, -q, --station, --pnu.
void add_display_options(CLI::App& app, DecodeOptionValues& values,
                         std::string_view default_format);

struct DecodeSettings {
    DecoderOptions decoder;
    TrackerOptions tracker;
    OutputFormat format = OutputFormat::Text;
    bool quiet = false;
    std::uint64_t count = 0;  // 0: no limit
    std::vector<std::uint8_t> stations;
    std::vector<std::uint16_t> pnus;
};

// Validates the values; nullopt with `error` naming the bad option otherwise.
std::optional<DecodeSettings> resolve_decode_options(const DecodeOptionValues& values,
                                                     std::string& error);

// --station and --pnu: does the telegram pass?
bool passes_filter(const DecodeSettings& settings, const DecodedTelegram& t) noexcept;

// Renders `t` when it passes the filters; otherwise lets `renderer` pass over it.
inline void show(TelegramRenderer& renderer, const DecodeSettings& settings,
                 const DecodedTelegram& t, std::span<const Finding> findings) {
    if (passes_filter(settings, t))
        renderer.render(t, findings);
    else
        renderer.pass_over(t);
}

// Messages on standard error, one style for every subcommand: "dpscope: error: <message>",
// "dpscope: warning: <message>", or "dpscope: <severity>: <message>" for input issues.
// Messages name the file, record or byte offset and the option where they apply; callers
// never add the severity themselves.
void print_error(std::string_view message);
void print_warning(std::string_view message);
void print_diagnostic(Severity severity, std::string_view message);

}  // namespace dpscope::cli
