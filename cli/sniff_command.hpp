// dpscope sniff: what its command line says, and the capture it runs. The Wireshark extcap
// interface (cli/extcap_command.cpp) runs its captures through the same run_sniff.
#pragma once

#include <cstdint>
#include <string>

#include "cli/common_options.hpp"
#include "cli/live_mqtt.hpp"
#include "core/protocol_descriptor.hpp"
#include "core/result.hpp"

namespace dpscope::cli {

struct SniffCommand {
    DecodeOptionValues options;
    std::string device;
    std::uint32_t baud = 0;  // 0: not given (the FC protocol's default, 9600)
    std::string parity;      // "": the bus's default (even; none for the VLT 2000)
    unsigned stop_bits = 1;
    std::string output;
    std::string link_type;  // "" = profibus
    std::uint64_t rotate_size = 0;
    double rotate_seconds = 0;
    double status_interval = 0;  // --status-interval SECONDS (0: none)
    std::string status_file;     // --status-file FILE: the status line, replaced each time
    unsigned ring = 0;           // --ring N: keep the last N files
    std::uint64_t max_disk = 0;  // --max-disk SIZE: and at most SIZE bytes in them
    double duration = 0;
    bool report = false;
    std::string report_format = "text";
    std::string report_file;
    std::string fail_on = "error";
    bool allow_empty = false;
    std::uint32_t idle_gap_ms = 50;
    bool no_low_latency = false;
    // Bus health (PROFIBUS): --stats, --stats-file, --stats-format, --alarm.
    bool stats = false;
    std::string stats_file;
    std::string stats_format = "text";
    std::string alarm;
    HealthOptionValues health;  // --health-config, --threshold (the verdicts of --stats, --alarm)
    MqttOptions mqtt;           // --mqtt and its options (cli/live_mqtt.hpp)
    std::string config_file;    // --config FILE (expanded before parsing: cli/config_file.hpp)
    // SIGHUP: "stop" (the terminal hung up), "reopen" (logrotate: the -w file anew, or the next
    // file of a rotation), "auto" (stop with a controlling terminal, reopen without: a service).
    std::string sighup = "auto";
    // The Wireshark extcap capture (cli/extcap_command.cpp): -w is Wireshark's fifo. Every
    // telegram is flushed into it at once; nothing is printed but errors (Wireshark shows
    // anything on standard error as an error); the fifo's reader going away (Wireshark stopped
    // or closed) ends the capture with exit code 0, as a signal does.
    bool extcap = false;
};

// Checks what the options say together (cli/sniff_options.cpp): a message naming the options
// that cannot work, for exit code 2.
Result<void> check_sniff_usage(const SniffCommand& command, const ProtocolDescriptor& bus);

// Checks the options, captures until stopped (-c, --duration, a signal, the device or the
// output failing) and returns the exit code.
int run_sniff(const SniffCommand& command);

}  // namespace dpscope::cli
