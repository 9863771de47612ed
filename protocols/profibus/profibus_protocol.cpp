// PROFIBUS DP as the shared code sees it (core/protocol_descriptor.hpp).
#include <algorithm>
#include <array>

#include "core/protocol_descriptor.hpp"
#include "protocols/lane_options.hpp"
#include "protocols/profibus/fdl_framing_rules.hpp"

namespace dpscope {

std::span<const FilterField> profibus_filter_fields() noexcept;  // profibus_filter_fields.cpp

namespace {

constexpr std::array<PcapLinkType, 2> kProfibusLinkTypes{{
    {kLinkTypeProfibusDl, "PROFIBUS_DL"},
    {kLinkTypeUser0, "USER0"},
}};

// The cyclic PCV's parameter (PNU 0 with RC 0 is the idle channel: none); a DP-V1 telegram's
// when its PROFIdrive request or response addresses one parameter (its values are not given:
// their format is the PROFIdrive message's).
std::optional<TelegramParameter> profibus_parameter_of(const DecodedTelegram& t) noexcept {
    if (t.dp.has_pcv) {
        const Pcv& pcv = t.dp.pcv;
        if (pcv.rc == 0 && pcv.pnu == 0) return std::nullopt;
        TelegramParameter p;
        p.pnu = pcv.pnu;
        if (carries_parameter_value(t.dp.dialect, t.direction == Direction::Request, pcv.rc)) {
            p.has_raw = true;
            p.raw = t.dp.pcv_value(t.direction);
        }
        return p;
    }
    if (const ProfidriveMessage* message = t.dp.service_data.profidrive();
        message && message->addresses.size() == 1) {
        TelegramParameter p;
        p.pnu = message->addresses.front().pnu;
        return p;
    }
    return std::nullopt;
}

std::unique_ptr<TelegramDecoder> profibus_decoder(const LaneOptions& options) {
    DecoderOptions decoder = options.decoder;
    decoder.naming = options.naming;
    return std::make_unique<BusDecoder>(std::move(decoder));
}

std::unique_ptr<TelegramTracker> profibus_tracker(const LaneOptions& options) {
    TrackerOptions tracker = options.tracker;
    tracker.timeout_ns = options.timeout_ns;
    tracker.line_baud = options.line_baud;
    return std::make_unique<SessionTracker>(tracker);
}

}  // namespace

const ProtocolDescriptor& profibus_protocol() noexcept {
    static const ProtocolDescriptor descriptor{
        .protocol = Protocol::ProfibusDp,
        .name = "profibus",
        .title = "PROFIBUS DP",
        .capture_noun = "a PROFIBUS DP",
        .framing = fdl_framing_rules(),
        .max_telegram_bytes = kMaxTelegramSize,  // SD2 with LE 249
        .link_types = kProfibusLinkTypes,
        .pcap_bus_number = 1,
        .lead_byte = std::nullopt,  // what an untagged USER0 capture is when no other bus fits
        .lead_byte_text = {},
        .text_log_shape = {},
        .traffic_name = "PROFIBUS DP",
        .has_bus_health = true,
        .timed_by_line = false,
        .masters_addressed = true,
        .drive_family = {},  // each slave's, by its dialect (drives/drive_family.hpp)
        .filter_fields = profibus_filter_fields(),
        .parameter_of = profibus_parameter_of,
        .make_decoder = profibus_decoder,
        .make_tracker = profibus_tracker,
    };
    return descriptor;
}

}  // namespace dpscope
