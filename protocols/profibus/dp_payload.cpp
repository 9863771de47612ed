#include "protocols/profibus/dp_payload.hpp"

namespace dpscope {

namespace {

constexpr FlagBit kStationStatus1[] = {
    {0x01, "Station_Non_Existent"},
    {0x02, "Station_Not_Ready"},
    {0x04, "Cfg_Fault"},
    {0x08, "Ext_Diag"},
    {0x10, "Not_Supported"},
    {0x20, "Invalid_Slave_Response"},
    {0x40, "Prm_Fault"},
    {0x80, "Master_Lock"},
};
constexpr FlagBit kStationStatus2[] = {
    {0x01, "Prm_Req"},     {0x02, "Stat_Diag"}, {0x04, "always_1"}, {0x08, "WD_On"},
    {0x10, "Freeze_Mode"}, {0x20, "Sync_Mode"}, {0x40, "reserved"}, {0x80, "Deactivated"},
};
constexpr FlagBit kStationStatus3[] = {{0x80, "Ext_Diag_Overflow"}};

constexpr FlagBit kSetPrmStation[] = {
    {0x08, "WD_On"},      {0x10, "Freeze_Req"}, {0x20, "Sync_Req"},
    {0x40, "Unlock_Req"}, {0x80, "Lock_Req"},
};
constexpr FlagBit kDpv1Status1[] = {
    {0x04, "WD_Base_1ms"},
    {0x20, "Publisher_Enable"},
    {0x40, "Fail_Safe"},
    {0x80, "DPV1_Enable"},
};
constexpr FlagBit kDpv1Status2[] = {
    {0x01, "Chk_Cfg_Mode"},
    {0x04, "Enable_Update_Alarm"},
    {0x08, "Enable_Status_Alarm"},
    {0x10, "Enable_Manufacturer_Specific_Alarm"},
    {0x20, "Enable_Diagnostic_Alarm"},
    {0x40, "Enable_Process_Alarm"},
    {0x80, "Enable_Pull_Plug_Alarm"},
};
constexpr FlagBit kDpv1Status3[] = {{0x08, "Prm_Structure"}, {0x10, "IsoM_Req"}, {0x80, "PrmCmd"}};

constexpr FlagBit kGlobalControl[] = {
    {0x02, "Clear_Data"}, {0x04, "Unfreeze"}, {0x08, "Freeze"}, {0x10, "Unsync"}, {0x20, "Sync"},
};

// Reserved bits of the DP-V1 status bytes; all clear is how a DP-V1 Set_Prm is recognised.
constexpr std::uint8_t kDpv1Status1Reserved = 0x1B;
constexpr std::uint8_t kDpv1Status2Reserved = 0x02;
constexpr std::uint8_t kDpv1Status3Reserved = 0x60;

}  // namespace

void report_service_data_short(const ByteReader& reader, std::size_t wanted,
                               ProblemList& problems) noexcept {
    problems.add(ProblemKind::ServiceDataShort, reader.offset(), static_cast<std::uint32_t>(wanted),
                 static_cast<std::uint32_t>(reader.remaining()));
}

bool need_service_data(const ByteReader& reader, std::size_t bytes,
                       ProblemList& problems) noexcept {
    if (reader.remaining() >= bytes) return true;
    report_service_data_short(reader, bytes, problems);
    return false;
}

std::span<const FlagBit> station_status_1_flags() { return kStationStatus1; }
std::span<const FlagBit> station_status_2_flags() { return kStationStatus2; }
std::span<const FlagBit> station_status_3_flags() { return kStationStatus3; }
std::span<const FlagBit> set_prm_station_flags() { return kSetPrmStation; }
std::span<const FlagBit> dpv1_status_1_flags() { return kDpv1Status1; }
std::span<const FlagBit> dpv1_status_2_flags() { return kDpv1Status2; }
std::span<const FlagBit> dpv1_status_3_flags() { return kDpv1Status3; }
std::span<const FlagBit> global_control_flags() { return kGlobalControl; }

std::string_view diag_block_type_name(DiagBlockType type) {
    switch (type) {
        case DiagBlockType::Device: return "device-related";
        case DiagBlockType::Identifier: return "identifier-related";
        case DiagBlockType::Channel: return "channel-related";
        case DiagBlockType::Revision: return "revision";
    }
    return "device-related";
}

std::string_view channel_error_text(std::uint8_t error_type) {
    switch (error_type) {
        case 1: return "short circuit";
        case 2: return "undervoltage";
        case 3: return "overvoltage";
        case 4: return "overload";
        case 5: return "overtemperature";
        case 6: return "line break";
        case 7: return "upper limit value exceeded";
        case 8: return "lower limit value exceeded";
        case 9: return "error";
        default: return error_type >= 16 ? "manufacturer-specific" : "reserved";
    }
}

std::string_view channel_type_text(std::uint8_t channel_type) {
    switch (channel_type) {
        case 1: return "bit";
        case 2: return "2 bits";
        case 3: return "4 bits";
        case 4: return "byte";
        case 5: return "word";
        case 6: return "2 words";
        default: return "reserved";
    }
}

std::string_view channel_io_text(std::uint8_t io) {
    switch (io) {
        case 1: return "input";
        case 2: return "output";
        case 3: return "input/output";
        default: return "reserved I/O type";
    }
}

std::string_view dpv1_alarm_or_status_text(std::uint8_t type_byte) {
    std::uint8_t code = type_byte & 0x7F;
    bool manufacturer = code >= 32 && code <= 126;
    if (type_byte & 0x80) {
        switch (code) {
            case 1: return "status message";
            case 2: return "module status";
            case 3: return "DXB_Link_Status";
            case 30: return "PrmCmdAck";
            case 31: return "Red_State";
            default: return manufacturer ? "manufacturer-specific status" : "reserved status";
        }
    }
    switch (code) {
        case 1: return "diagnostic alarm";
        case 2: return "process alarm";
        case 3: return "pull alarm";
        case 4: return "plug alarm";
        case 5: return "status alarm";
        case 6: return "update alarm";
        default: return manufacturer ? "manufacturer-specific alarm" : "reserved alarm";
    }
}

std::string_view dpv1_alarm_mode_text(std::uint8_t status_3) {
    static constexpr std::string_view kModes[] = {
        "1 alarm of each type", "2 alarms in total",  "4 alarms in total",  "8 alarms in total",
        "12 alarms in total",   "16 alarms in total", "24 alarms in total", "32 alarms in total",
    };
    return kModes[status_3 & 0x07];
}

std::optional<SlaveDiag> parse_slave_diag(ByteReader reader, ProblemList& problems) {
    if (!need_service_data(reader, 6, problems)) return std::nullopt;
    SlaveDiag diag;
    diag.station_status_1 = *reader.u8();
    diag.station_status_2 = *reader.u8();
    diag.station_status_3 = *reader.u8();
    diag.master_address = *reader.u8();
    diag.ident = *reader.u16_be();
    diag.extended_offset = static_cast<std::uint16_t>(reader.offset());
    diag.extended = reader.rest();
    return diag;
}

void parse_extended_diag(ByteReader reader, std::vector<DiagBlock>& blocks, ProblemList& problems) {
    while (!reader.empty()) {
        DiagBlock block;
        block.offset = static_cast<std::uint16_t>(reader.offset());
        std::uint8_t header = *reader.u8();
        switch (header >> 6) {
            case 0:
            case 1: {
                block.type = (header >> 6) == 0 ? DiagBlockType::Device : DiagBlockType::Identifier;
                std::size_t length = header & 0x3F;  // includes the header byte
                std::size_t body = length > 0 ? length - 1 : 0;
                if (body > reader.remaining()) {
                    problems.add(ProblemKind::DiagBlockTruncated, block.offset,
                                 static_cast<std::uint32_t>(length),
                                 static_cast<std::uint32_t>(reader.remaining() + 1));
                    block.data = reader.rest();
                    blocks.push_back(block);
                    return;
                }
                block.data = *reader.bytes(body);
                break;
            }
            case 2: {
                block.type = DiagBlockType::Channel;
                block.module = header & 0x3F;
                auto channel = reader.u8();
                auto type = reader.u8();
                if (!channel || !type) {
                    problems.add(ProblemKind::DiagBlockTruncated, block.offset, 3,
                                 static_cast<std::uint32_t>(1 + (channel ? 1 : 0)));
                    return;
                }
                block.io = *channel >> 6;
                block.channel = *channel & 0x3F;
                block.channel_type = *type >> 5;
                block.error_type = *type & 0x1F;
                break;
            }
            default:
                block.type = DiagBlockType::Revision;
                block.revision = header & 0x3F;
                break;
        }
        blocks.push_back(block);
    }
}

std::uint32_t SetPrm::watchdog_ms() const noexcept {
    std::uint32_t base = (has_dpv1_status && (dpv1_status[0] & 0x04)) ? 1 : 10;
    return base * wd_fact_1 * wd_fact_2;
}

std::optional<SetPrm> parse_set_prm(ByteReader reader, ProblemList& problems) {
    if (!need_service_data(reader, 7, problems)) return std::nullopt;
    SetPrm prm;
    prm.station_status = *reader.u8();
    prm.wd_fact_1 = *reader.u8();
    prm.wd_fact_2 = *reader.u8();
    prm.min_tsdr = *reader.u8();
    prm.ident = *reader.u16_be();
    prm.group_ident = *reader.u8();
    if (reader.remaining() >= 3) {
        std::uint8_t s1 = *reader.peek_u8(0);
        std::uint8_t s2 = *reader.peek_u8(1);
        std::uint8_t s3 = *reader.peek_u8(2);
        if (!(s1 & kDpv1Status1Reserved) && !(s2 & kDpv1Status2Reserved) &&
            !(s3 & kDpv1Status3Reserved)) {
            prm.has_dpv1_status = true;
            prm.dpv1_status = {s1, s2, s3};
            reader.skip(3);
        }
    }
    prm.user_prm_offset = static_cast<std::uint16_t>(reader.offset());
    prm.user_prm = reader.rest();
    return prm;
}

std::string_view cfg_direction_name(CfgDirection direction) {
    switch (direction) {
        case CfgDirection::None: return "-";
        case CfgDirection::Input: return "in";
        case CfgDirection::Output: return "out";
        case CfgDirection::InputOutput: return "in/out";
    }
    return "-";
}

bool parse_cfg(ByteReader reader, std::vector<CfgModule>& modules, ProblemList& problems) {
    while (!reader.empty()) {
        CfgModule module;
        module.offset = static_cast<std::uint16_t>(reader.offset());
        module.identifier = *reader.u8();
        std::uint8_t id = module.identifier;
        std::uint8_t direction_bits = (id >> 4) & 0x03;
        if (direction_bits != 0) {
            // Compact format: bits 3..0 length-1, 5..4 direction, 6 words, 7 consistency.
            std::uint8_t units = static_cast<std::uint8_t>((id & 0x0F) + 1);
            bool words = (id & 0x40) != 0;
            bool consistent = (id & 0x80) != 0;
            module.direction = static_cast<CfgDirection>(direction_bits);
            if (direction_bits & 0x01) {
                module.input_units = units;
                module.input_words = words;
                module.input_consistent = consistent;
            }
            if (direction_bits & 0x02) {
                module.output_units = units;
                module.output_words = words;
                module.output_consistent = consistent;
            }
            modules.push_back(module);
            continue;
        }
        // Special format: bits 7..6 say which length bytes follow (output first), bits 3..0 how
        // many manufacturer-specific bytes follow them.
        module.special = true;
        std::uint8_t which = id >> 6;
        module.manufacturer_bytes = id & 0x0F;
        if (id == 0x00) module.free_place = true;
        std::size_t wanted =
            ((which & 0x02) ? 1u : 0u) + ((which & 0x01) ? 1u : 0u) + module.manufacturer_bytes;
        if (reader.remaining() < wanted) {
            problems.add(ProblemKind::CfgIdentifierTruncated, module.offset,
                         static_cast<std::uint32_t>(wanted),
                         static_cast<std::uint32_t>(reader.remaining()));
            return false;
        }
        auto apply = [](std::uint8_t length_byte, std::uint8_t& units, bool& words,
                        bool& consistent) {
            units = static_cast<std::uint8_t>((length_byte & 0x3F) + 1);
            words = (length_byte & 0x40) != 0;
            consistent = (length_byte & 0x80) != 0;
        };
        if (which & 0x02)
            apply(*reader.u8(), module.output_units, module.output_words, module.output_consistent);
        if (which & 0x01)
            apply(*reader.u8(), module.input_units, module.input_words, module.input_consistent);
        module.direction = static_cast<CfgDirection>(((which & 0x02) ? 2 : 0) | (which & 0x01));
        reader.skip(module.manufacturer_bytes);
        modules.push_back(module);
    }
    return true;
}

std::optional<GlobalControl> parse_global_control(ByteReader reader, ProblemList& problems) {
    if (!need_service_data(reader, 2, problems)) return std::nullopt;
    GlobalControl gc;
    gc.command = *reader.u8();
    gc.group_select = *reader.u8();
    return gc;
}

std::optional<SetSlaveAdd> parse_set_slave_add(ByteReader reader, ProblemList& problems) {
    if (!need_service_data(reader, 4, problems)) return std::nullopt;
    SetSlaveAdd ssa;
    ssa.new_address = *reader.u8();
    ssa.ident = *reader.u16_be();
    ssa.no_add_chg = *reader.u8();
    ssa.rem_slave_data = reader.rest();
    return ssa;
}

}  // namespace dpscope
