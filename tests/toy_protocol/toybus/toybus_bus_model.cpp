// The toybus in `dpscope simulate --bus toybus` (simulator/bus_model.hpp): one master reads
// parameter 100 + the cycle's number modulo 10 from each of drives 1 and 2 in turn; each drive
// answers within 2 to 8 ms. No faults are injected (the toy checks the seam, not the tracker).
#include <fmt/format.h>

#include <algorithm>
#include <memory>

#include "core/protocol_descriptor.hpp"
#include "simulator/bus_model.hpp"
#include "simulator/fault_spec.hpp"
#include "simulator/simulator.hpp"

namespace dpscope {

namespace {

constexpr std::uint8_t kToybusDrives[] = {1, 2};
constexpr std::int64_t kResponseMinNs = 2'000'000;
constexpr std::int64_t kResponseMaxNs = 8'000'000;

std::vector<std::uint8_t> toybus_line(std::string text) {
    text += "\r\n";
    return std::vector<std::uint8_t>(text.begin(), text.end());
}

class ToybusBusModel final : public BusModel {
  public:
    void cycle(BusEnvironment& env, std::uint64_t number) override {
        const unsigned parameter = 100 + static_cast<unsigned>(number % 10);
        for (std::uint8_t drive : kToybusDrives) {
            env.send(toybus_line(fmt::format("?{:02} {:04}", drive, parameter)), 1'000'000);
            const auto wait = static_cast<std::int64_t>(
                env.random(static_cast<std::uint64_t>(kResponseMaxNs - kResponseMinNs)));
            env.send(toybus_line(fmt::format("={:02} {:04} {:05}", drive, parameter,
                                             (number * 7 + drive) % 100'000)),
                     kResponseMinNs + wait);
        }
    }
};

std::unique_ptr<BusModel> make_toybus_model(SimulatorOptions& options,
                                            std::vector<std::uint8_t>& drives) {
    if (options.baud == 0) options.baud = toybus_protocol().default_baud;
    drives.assign(std::begin(kToybusDrives), std::end(kToybusDrives));
    return std::make_unique<ToybusBusModel>();
}

Result<void> check_toybus_faults(const SimulatorOptions& options) {
    if (!options.faults.empty())
        return Error{fmt::format("fault {}: the toybus simulation injects no faults",
                                 describe_fault(options.faults.front()))};
    return {};
}

bool toybus_fault_applies(FaultKind) noexcept { return false; }

std::int64_t toybus_span_bound_ns(const SimulatorOptions& options) {
    const double baud =
        options.baud == 0 ? toybus_protocol().default_baud : static_cast<double>(options.baud);
    const double telegram_ns = 16 * 10 * 1e9 / baud;
    const double poll_ns = 1e6 + telegram_ns + static_cast<double>(kResponseMaxNs) + telegram_ns;
    const double cycle_ns = std::max(static_cast<double>(options.cycle_us) * 1e3,
                                     static_cast<double>(std::size(kToybusDrives)) * poll_ns);
    const double cycles = session_cycles_bound(options);
    const double span = cycles * cycle_ns;
    return span_bound_of(span);
}

}  // namespace

const SimulatedBus& toybus_simulated_bus() noexcept {
    static const SimulatedBus bus{
        .protocol = Protocol::Toybus,
        .make_model = make_toybus_model,
        .check_faults = check_toybus_faults,
        .span_bound_ns = toybus_span_bound_ns,
        .fault_applies = toybus_fault_applies,
        .runs_on_ns = nullptr,
        .character_bits = 10,  // 8N1
    };
    return bus;
}

}  // namespace dpscope
