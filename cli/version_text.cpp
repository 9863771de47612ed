#include "cli/version_text.hpp"

#include <fmt/format.h>

#include <CLI/Version.hpp>

#include "capture/pcap_source.hpp"
#include "cli/build_info.hpp"
#include "cli/version.hpp"
#include "core/protocol_descriptor.hpp"
#include "monitor/mqtt_publisher.hpp"

namespace dpscope::cli {

std::string version_text() {
    std::string text = fmt::format("dpscope {} (commit {})\n", kVersion, kBuildCommit);
    text += "buses (--bus):";
    const char* separator = " ";
    for (const ProtocolDescriptor* protocol : protocol_table()) {
        text += fmt::format("{}{} = {}", separator, protocol->name, protocol->title);
        separator = ", ";
    }
    text += fmt::format(
        "\nlibraries: libpcap {}, libmosquitto {} (as loaded); fmt {}.{}.{}, CLI11 {} (as "
        "built)\n",
        pcap_library_version(), monitor::mqtt_library_version(), FMT_VERSION / 10000,
        FMT_VERSION / 100 % 100, FMT_VERSION % 100, CLI11_VERSION);
    if (*kWiresharkPluginVersion != '\0')
        text +=
            fmt::format("Wireshark plugin: built against Wireshark {}\n", kWiresharkPluginVersion);
    else
        text += "Wireshark plugin: not built in this build\n";
    return text;
}

}  // namespace dpscope::cli
