#include "capture/serial_ports.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <system_error>

namespace dpscope {

namespace {

namespace fs = std::filesystem;

// "ttyUSB10" against "ttyUSB2": digit runs compare as numbers.
bool natural_less(const std::string& a, const std::string& b) {
    std::size_t i = 0;
    std::size_t j = 0;
    auto digit = [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; };
    while (i < a.size() && j < b.size()) {
        if (digit(a[i]) && digit(b[j])) {
            std::size_t ei = i;
            std::size_t ej = j;
            while (ei < a.size() && digit(a[ei]))
                ++ei;
            while (ej < b.size() && digit(b[ej]))
                ++ej;
            std::string na = a.substr(i, ei - i);
            std::string nb = b.substr(j, ej - j);
            na.erase(0, std::min(na.find_first_not_of('0'), na.size()));
            nb.erase(0, std::min(nb.find_first_not_of('0'), nb.size()));
            if (na.size() != nb.size()) return na.size() < nb.size();
            if (na != nb) return na < nb;
            i = ei;
            j = ej;
        } else {
            if (a[i] != b[j]) return a[i] < b[j];
            ++i;
            ++j;
        }
    }
    return a.size() - i < b.size() - j;
}

// The by-id link names, by the tty they point to: ttyUSB0 -> usb-FTDI_...-if00-port0.
std::map<std::string, std::string> by_id_names(const std::string& dev_root) {
    std::map<std::string, std::string> names;
    std::error_code error;
    fs::directory_iterator it(fs::path(dev_root) / "serial" / "by-id", error);
    if (error) return names;
    // increment(error), not a range-for: a failing step must not throw (never a crash).
    for (; it != fs::directory_iterator(); it.increment(error)) {
        const fs::directory_entry& entry = *it;
        std::error_code link_error;
        if (!entry.is_symlink(link_error)) continue;
        fs::path target = fs::read_symlink(entry.path(), link_error);
        if (link_error) continue;
        std::string tty = target.filename().string();
        std::string name = entry.path().filename().string();
        // Two links to one port (rare): the first by name, so the choice is stable.
        auto [at, inserted] = names.emplace(tty, name);
        if (!inserted && name < at->second) at->second = name;
    }
    return names;
}

}  // namespace

std::vector<SerialPortEntry> list_serial_ports(const std::string& sys_root,
                                               const std::string& dev_root) {
    std::vector<SerialPortEntry> ports;
    std::error_code error;
    fs::directory_iterator it(fs::path(sys_root) / "class" / "tty", error);
    if (error) return ports;
    const std::map<std::string, std::string> by_id = by_id_names(dev_root);
    for (; it != fs::directory_iterator(); it.increment(error)) {
        const fs::directory_entry& entry = *it;
        const std::string name = entry.path().filename().string();
        std::error_code entry_error;
        const fs::path device_link = entry.path() / "device";
        if (!fs::exists(device_link, entry_error)) continue;  // virtual: tty1, console, ptmx
        // The 8250 driver's placeholders: all linked to the platform device "serial8250".
        fs::path target = fs::read_symlink(device_link, entry_error);
        if (!entry_error && target.filename() == "serial8250") continue;
        const fs::path node = fs::path(dev_root) / name;
        if (!fs::exists(node, entry_error)) continue;
        auto id = by_id.find(name);
        ports.push_back({name, node.string(), id == by_id.end() ? std::string() : id->second});
    }
    std::sort(ports.begin(), ports.end(), [](const SerialPortEntry& a, const SerialPortEntry& b) {
        return natural_less(a.name, b.name);
    });
    return ports;
}

}  // namespace dpscope
