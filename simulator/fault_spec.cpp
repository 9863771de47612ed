#include "simulator/fault_spec.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cstdlib>

#include "core/protocol_descriptor.hpp"
#include "protocols/profibus/ppo.hpp"

namespace dpscope {

namespace {

template <typename T>
bool parse_number(std::string_view text, T& value) {
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    return ec == std::errc() && end == text.data() + text.size();
}

}  // namespace

Result<FaultSpec> parse_fault_spec(std::string_view text, Protocol bus) {
    FaultSpec spec;
    std::string_view rest = text;
    if (auto colon = rest.rfind(':'); colon != std::string_view::npos) {
        unsigned address = 0;
        if (!parse_number(rest.substr(colon + 1), address) || address > 126) {
            return Error{fmt::format("{}: '{}' is not a station address from 0 to 126", text,
                                     rest.substr(colon + 1))};
        }
        spec.slave = static_cast<std::uint8_t>(address);
        rest = rest.substr(0, colon);
    }
    std::string_view name = rest;
    if (auto at = rest.find('@'); at != std::string_view::npos) {
        std::uint64_t cycle = 0;
        if (!parse_number(rest.substr(at + 1), cycle)) {
            return Error{fmt::format("{}: '{}' is not a cycle number", text, rest.substr(at + 1))};
        }
        spec.cycle = cycle;
        name = rest.substr(0, at);
    } else if (auto eq = rest.find('='); eq != std::string_view::npos) {
        std::string number(rest.substr(eq + 1));
        char* end = nullptr;
        double rate = std::strtod(number.c_str(), &end);
        if (number.empty() || *end != '\0' || !(rate > 0) || rate > 1) {
            return Error{fmt::format("{}: rate '{}' must be a number in (0, 1]", text, number)};
        }
        spec.rate = rate;
        name = rest.substr(0, eq);
    }
    auto kind = fault_kind_from_name(name);
    if (!kind)
        return Error{fmt::format("{}: unknown kind '{}' (known with --bus {}: {})", text, name,
                                 protocol_name(bus), fault_kind_names(bus))};
    spec.kind = *kind;
    return spec;
}

std::string describe_fault(const FaultSpec& spec) {
    std::string text(fault_kind_name(spec.kind));
    if (spec.rate > 0) text += fmt::format("={}", spec.rate);
    if (spec.cycle) text += fmt::format("@{}", *spec.cycle);
    if (spec.slave) text += fmt::format(":{}", *spec.slave);
    return text;
}

Result<SimulatedSlave> parse_slave_spec(std::string_view text) {
    SimulatedSlave slave;
    auto first = text.find(':');
    if (first == std::string_view::npos) {
        return Error{fmt::format("{}: expected ADDR:PPO[:DIALECT][:dpv1]", text)};
    }
    unsigned address = 0, ppo = 0;
    auto second = text.find(':', first + 1);
    std::string_view ppo_text = text.substr(
        first + 1, second == std::string_view::npos ? std::string_view::npos : second - first - 1);
    if (!parse_number(text.substr(0, first), address) || address > 125) {
        return Error{fmt::format("{}: the address must be from 0 to 125", text)};
    }
    if (!parse_number(ppo_text, ppo) || ppo < 1 || ppo > 5) {
        return Error{fmt::format("{}: the PPO type must be from 1 to 5", text)};
    }
    slave.address = static_cast<std::uint8_t>(address);
    slave.ppo_type = static_cast<std::uint8_t>(ppo);
    if (second == std::string_view::npos) return slave;
    // Then a dialect, a dpv1 flag, or both in that order.
    std::string_view rest = text.substr(second + 1);
    auto third = rest.find(':');
    std::string_view dialect_text = rest.substr(0, third);
    if (third == std::string_view::npos && dialect_text == "dpv1") {
        slave.dpv1 = true;
        return slave;
    }
    auto dialect = dialect_from_name(dialect_text);
    if (!dialect) {
        return Error{fmt::format("{}: dialect must be one of {}", text, kDialectNameList)};
    }
    slave.dialect = *dialect;
    if (third != std::string_view::npos) {
        if (rest.substr(third + 1) != "dpv1")
            return Error{fmt::format("{}: only dpv1 may follow the dialect", text)};
        slave.dpv1 = true;
    }
    return slave;
}

bool has_parameter_channel(const SimulatedSlave& slave) {
    return ppo_layout_of_type(slave.ppo_type, PpoSource::Option).has_pcv;
}

Result<void> check_faults(const std::vector<FaultSpec>& faults,
                          const std::vector<SimulatedSlave>& slaves, std::uint64_t cycles) {
    for (const FaultSpec& spec : faults) {
        // A fault of another bus names the --bus that takes it.
        if (const ProtocolDescriptor& bus = protocol_descriptor(fault_bus(spec.kind));
            bus.protocol != Protocol::ProfibusDp)
            return Error{fmt::format("fault {}: {} fault; give --bus {}", describe_fault(spec),
                                     bus.capture_noun, bus.name)};
        const bool needs_pcv = fault_needs_parameter_channel(spec.kind);
        const bool needs_dpv1 = fault_needs_dpv1(spec.kind);
        const bool needs_spontaneous = fault_needs_spontaneous_messages(spec.kind);
        auto fits = [&](const SimulatedSlave& slave) {
            return (!needs_pcv || has_parameter_channel(slave)) && (!needs_dpv1 || slave.dpv1) &&
                   (!needs_spontaneous || has_spontaneous_messages(slave.dialect));
        };
        bool target = false;
        for (const SimulatedSlave& slave : slaves) {
            if (spec.slave && slave.address != *spec.slave) continue;
            if (fits(slave)) target = true;
        }
        if (!target) {
            if (spec.slave) {
                bool simulated = false;
                for (const SimulatedSlave& slave : slaves)
                    simulated = simulated || slave.address == *spec.slave;
                if (!simulated)
                    return Error{fmt::format("fault {}: slave {} is not simulated",
                                             describe_fault(spec), *spec.slave)};
                if (needs_dpv1)
                    return Error{
                        fmt::format("fault {}: slave {} does not run DP-V1 (give it as "
                                    "--slave ADDR:PPO[:DIALECT]:dpv1)",
                                    describe_fault(spec), *spec.slave)};
                const SimulatedSlave* slave = nullptr;
                for (const SimulatedSlave& s : slaves)
                    if (s.address == *spec.slave) slave = &s;
                if (needs_spontaneous && has_parameter_channel(*slave))
                    return Error{fmt::format(
                        "fault {}: slave {} speaks the {} dialect, which has no spontaneous "
                        "messages (RC 9 to 12 not used)",
                        describe_fault(spec), *spec.slave, dialect_name(slave->dialect))};
                return Error{fmt::format(
                    "fault {}: slave {} has no parameter channel (PPO 3 and 4 carry no PCV)",
                    describe_fault(spec), *spec.slave)};
            }
            if (needs_dpv1)
                return Error{
                    fmt::format("fault {}: no simulated slave runs DP-V1 (add one with "
                                "--slave ADDR:PPO[:DIALECT]:dpv1)",
                                describe_fault(spec))};
            if (needs_spontaneous &&
                std::any_of(slaves.begin(), slaves.end(),
                            [](const SimulatedSlave& s) { return has_parameter_channel(s); }))
                return Error{fmt::format(
                    "fault {}: no simulated slave with a parameter channel has spontaneous "
                    "messages (the ge dialect has none)",
                    describe_fault(spec))};
            return Error{
                fmt::format("fault {}: no simulated slave has a parameter channel (PPO 1, 2 "
                            "or 5)",
                            describe_fault(spec))};
        }
        if (spec.cycle && cycles != 0 && *spec.cycle >= cycles)
            return Error{fmt::format("fault {}: cycle {} is past the session's {} cycles (0..{})",
                                     describe_fault(spec), *spec.cycle, cycles, cycles - 1)};
    }
    return {};
}

OnceFaultCheck::OnceFaultCheck(const std::vector<FaultSpec>& faults) {
    for (const FaultSpec& spec : faults)
        if (spec.rate == 0) once_.push_back(spec);
    found_.assign(once_.size(), false);
}

void OnceFaultCheck::record(const Injection& injection) {
    for (std::size_t i = 0; i < once_.size(); ++i) {
        const FaultSpec& spec = once_[i];
        if (found_[i] || injection.kind != spec.kind) continue;
        if (spec.slave && injection.slave != *spec.slave) continue;
        if (spec.cycle && injection.cycle < *spec.cycle) continue;
        found_[i] = true;
        return;
    }
}

std::vector<std::string> OnceFaultCheck::missing() const {
    std::vector<std::string> missing;
    for (std::size_t i = 0; i < once_.size(); ++i)
        if (!found_[i]) missing.push_back(describe_fault(once_[i]));
    return missing;
}

}  // namespace dpscope
