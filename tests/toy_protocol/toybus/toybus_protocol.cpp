// toybus as the shared code sees it (core/protocol_descriptor.hpp).
#include <array>
#include <optional>

#include "core/protocol_descriptor.hpp"
#include "core/protocol_lane.hpp"
#include "protocols/lane_options.hpp"
#include "protocols/toybus/toybus_decoder.hpp"
#include "protocols/toybus/toybus_framing_rules.hpp"
#include "protocols/toybus/toybus_tracker.hpp"

namespace dpscope {

namespace {

// No link type of its own: dpscope writes it as USER0 and records the bus in the file (bus 4).
constexpr std::array<PcapLinkType, 1> kToybusLinkTypes{{{kLinkTypeUser0, "USER0"}}};

std::optional<std::uint16_t> toybus_named_pnu(const DecodedTelegram& t) noexcept {
    if (!t.toybus.has_parameter) return std::nullopt;
    return t.toybus.parameter;
}

// What --pnu selects: the parameter a toybus telegram names (the filter field dpscope.pnu).
const std::array<FilterField, 1> kToybusFilterFields{{
    {"dpscope.pnu", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         const auto pnu = in.t.protocol == Protocol::Toybus ? toybus_named_pnu(in.t) : std::nullopt;
         return pnu && visit_integer(v, *pnu);
     },
     "the parameter the telegram is about (toybus: its parameter)"},
}};

// Its decoder and tracker: it has no options of its own, only the shared time-out.
std::unique_ptr<TelegramDecoder> toybus_decoder(const LaneOptions& options) {
    ToybusDecoderOptions decoder;
    decoder.response_window_ns = options.timeout_ns;
    return std::make_unique<ToybusDecoder>(decoder);
}

std::unique_ptr<TelegramTracker> toybus_tracker(const LaneOptions& options) {
    ToybusTrackerOptions tracker;
    tracker.timeout_ns = options.timeout_ns;
    return std::make_unique<ToybusTracker>(tracker);
}

}  // namespace

const ProtocolDescriptor& toybus_protocol() noexcept {
    static const ProtocolDescriptor descriptor{
        .protocol = Protocol::Toybus,
        .name = "toybus",
        .title = "the toybus line protocol",
        .capture_noun = "a toybus",
        .framing = toybus_framing_rules(),
        .max_telegram_bytes = kToybusMaxTelegram,
        .link_types = kToybusLinkTypes,
        .pcap_bus_number = 4,
        .lead_byte = kToybusRead,
        .lead_byte_text = "'?'",
        .text_log_shape = "",
        .traffic_name = "toybus",
        .has_bus_health = false,
        .timed_by_line = false,
        .default_baud = 9600,
        .min_baud = 0,
        .max_baud = 0,
        .default_parity = "none",
        .masters_addressed = false,
        .filter_fields = kToybusFilterFields,
        .make_decoder = toybus_decoder,
        .make_tracker = toybus_tracker,
    };
    return descriptor;
}

}  // namespace dpscope
