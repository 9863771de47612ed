// The serial ports of the machine, as a live capture can use them: found in sysfs
// (/sys/class/tty/NAME/device), with their /dev/serial/by-id names where udev made them.
#pragma once

#include <string>
#include <vector>

namespace dpscope {

struct SerialPortEntry {
    std::string name;    // ttyUSB0
    std::string device;  // /dev/ttyUSB0 (under the device root given)
    std::string by_id;   // usb-FTDI_FT232R_USB_UART_A1B2C3-if00-port0; "" when udev made none
};

// Every tty under `sys_root`/class/tty that has a device behind it (`device` link) and a node
// under `dev_root`, sorted by name (ttyUSB2 before ttyUSB10). The 8250 driver's placeholder
// ports (ttyS1..ttyS31 on most PCs, linked to the platform device serial8250) have no hardware
// and are left out. A root that cannot be read gives no ports; nothing here fails.
std::vector<SerialPortEntry> list_serial_ports(const std::string& sys_root = "/sys",
                                               const std::string& dev_root = "/dev");

}  // namespace dpscope
