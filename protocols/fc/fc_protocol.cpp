// The Danfoss FC protocol as the shared code sees it (core/protocol_descriptor.hpp).
#include <array>
#include <optional>

#include "core/protocol_descriptor.hpp"
#include "protocols/fc/fc_framing_rules.hpp"
#include "protocols/lane_options.hpp"

namespace dpscope {

std::span<const FilterField> fc_filter_fields() noexcept;  // fc_filter_fields.cpp

namespace {

// The FC protocol has no link type of its own: dpscope writes it as USER0 and records the bus in
// the file (capture/bus_tag.hpp).
constexpr std::array<PcapLinkType, 1> kFcLinkTypes{{{kLinkTypeUser0, "USER0"}}};

// Its line unless --baud says otherwise (docs/protocol/fc-protocol.md): 9600 baud 8E1; the FC
// series' baud rates (par. 8-32) are 2400 to 115200.
constexpr std::uint32_t kFcDefaultLineBaud = 9600;
constexpr std::uint32_t kFcMinBaud = 2400;
constexpr std::uint32_t kFcMaxBaud = 115'200;

std::optional<TelegramParameter> fc_parameter_of(const DecodedTelegram& t) noexcept {
    const FcTelegram& fc = t.fc;
    if (!t.has_roles || !fc.has_pkw) return std::nullopt;
    TelegramParameter p;
    p.pnu = fc.pkw.pnu;
    const bool request = t.direction == Direction::Request;
    if (fc.block == FcBlock::Parameter &&
        carries_parameter_value(Dialect::Fc, request, fc.pkw.rc)) {
        const ValueWidth width = request ? request_code(Dialect::Fc, fc.pkw.rc).width
                                         : response_code(Dialect::Fc, fc.pkw.rc).width;
        p.has_raw = true;
        p.raw = pcv_value(fc.pkw, width);
    }
    return p;
}

std::unique_ptr<TelegramDecoder> fc_decoder(const LaneOptions& options) {
    FcDecoderOptions decoder = options.fc_decoder;
    decoder.response_window_ns = options.timeout_ns;
    decoder.naming = options.naming;
    return std::make_unique<FcDecoder>(decoder);
}

std::unique_ptr<TelegramTracker> fc_tracker(const LaneOptions& options) {
    return std::make_unique<FcTracker>(
        on_the_line(options.fc_tracker, options, kFcDefaultLineBaud));
}

}  // namespace

const ProtocolDescriptor& fc_protocol() noexcept {
    static const ProtocolDescriptor descriptor{
        .protocol = Protocol::Fc,
        .name = "fc",
        .title = "the FC protocol (RS-485)",
        .capture_noun = "an FC protocol",
        .framing = fc_framing_rules(),
        .max_telegram_bytes = 2 + 255,  // STX, LGE and the 255 bytes LGE counts at most
        .link_types = kFcLinkTypes,
        .pcap_bus_number = 2,
        .lead_byte = kFcStx,
        .lead_byte_text = "STX (0x02)",
        .text_log_shape = {},
        .traffic_name = "FC protocol",
        .has_bus_health = false,
        .timed_by_line = true,
        .default_baud = kFcDefaultLineBaud,
        .min_baud = kFcMinBaud,
        .max_baud = kFcMaxBaud,
        .default_parity = "even",
        .masters_addressed = false,
        .drive_family = "fc",
        .filter_fields = fc_filter_fields(),
        .parameter_of = fc_parameter_of,
        .make_decoder = fc_decoder,
        .make_tracker = fc_tracker,
    };
    return descriptor;
}

}  // namespace dpscope
