#include "protocols/profibus/ppo.hpp"

namespace dpscope {

std::string_view ppo_source_name(PpoSource source) {
    switch (source) {
        case PpoSource::None: return "none";
        case PpoSource::ChkCfg: return "chk_cfg";
        case PpoSource::GetCfg: return "get_cfg";
        case PpoSource::Length: return "length";
        case PpoSource::Option: return "option";
    }
    return "none";
}

namespace {

struct StandardPpo {
    std::uint8_t type;
    bool has_pcv;
    std::uint16_t bytes;
};

constexpr StandardPpo kStandardPpos[] = {
    {1, true, 12}, {2, true, 20}, {3, false, 4}, {4, false, 12}, {5, true, 28},
};

std::uint8_t standard_type(bool has_pcv, std::uint16_t bytes) {
    for (const StandardPpo& ppo : kStandardPpos)
        if (ppo.has_pcv == has_pcv && ppo.bytes == bytes) return ppo.type;
    return 0;
}

}  // namespace

PpoLayout ppo_layout_of_type(std::uint8_t type, PpoSource source) {
    PpoLayout layout;
    layout.source = source;
    for (const StandardPpo& ppo : kStandardPpos) {
        if (ppo.type != type) continue;
        layout.type = type;
        layout.has_pcv = ppo.has_pcv;
        layout.output_bytes = layout.input_bytes = ppo.bytes;
    }
    return layout;
}

PpoLayout ppo_from_cfg(std::span<const CfgModule> modules, PpoSource source) {
    PpoLayout layout;
    layout.source = source;
    const CfgModule* io[2] = {nullptr, nullptr};  // the first two modules that carry I/O
    std::size_t io_count = 0;
    unsigned output = 0;
    unsigned input = 0;
    for (const CfgModule& module : modules) {
        if (module.input_bytes() == 0 && module.output_bytes() == 0) continue;
        if (io_count < 2) io[io_count] = &module;
        ++io_count;
        output += module.output_bytes();
        input += module.input_bytes();
    }
    layout.output_bytes = static_cast<std::uint16_t>(output);
    layout.input_bytes = static_cast<std::uint16_t>(input);
    if (io_count == 0) return layout;
    // The PKW is 8 bytes each way: one in/out module, or an output and an input module.
    bool pkw_together = io[0]->output_bytes() == kPcvBytes && io[0]->input_bytes() == kPcvBytes;
    bool pkw_split = io_count >= 2 && io[0]->output_bytes() + io[1]->output_bytes() == kPcvBytes &&
                     io[0]->input_bytes() + io[1]->input_bytes() == kPcvBytes &&
                     (io[0]->input_bytes() == 0 || io[0]->output_bytes() == 0);
    std::size_t pkw_modules = pkw_together ? 1 : (pkw_split ? 2 : 0);
    layout.has_pcv = pkw_modules > 0 && io_count > pkw_modules;
    if (output == input) layout.type = standard_type(layout.has_pcv, layout.output_bytes);
    return layout;
}

PpoLayout ppo_from_length(std::size_t length) {
    PpoLayout layout;
    layout.source = PpoSource::Length;
    layout.output_bytes = layout.input_bytes = static_cast<std::uint16_t>(length);
    switch (length) {
        case 4: layout.type = 3; break;
        case 12:
            layout.type = 1;
            layout.alternative = 4;
            layout.has_pcv = true;
            break;
        case 20:
            layout.type = 2;
            layout.has_pcv = true;
            break;
        case 28:
            layout.type = 5;
            layout.has_pcv = true;
            break;
        default: break;
    }
    return layout;
}

}  // namespace dpscope
