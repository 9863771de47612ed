// The VLT 2000 serial telegram as the shared code sees it (core/protocol_descriptor.hpp).
#include <array>
#include <optional>

#include "core/protocol_descriptor.hpp"
#include "protocols/lane_options.hpp"
#include "protocols/vlt2000/vlt2000_framing_rules.hpp"

namespace dpscope {

std::span<const FilterField> vlt2000_filter_fields() noexcept;  // vlt2000_filter_fields.cpp

namespace {

// Its line unless --baud says otherwise: 9600 baud 8N1 (its manual: 8 data bits, no parity, 1
// stop bit; the values of its parameter 501 were not found, so the rate is dpscope's choice,
// docs/decisions.md).
constexpr std::uint32_t kVlt2000DefaultLineBaud = 9600;

// No link type of its own: dpscope writes it as USER0 and records the bus in the file.
constexpr std::array<PcapLinkType, 1> kVlt2000LinkTypes{{{kLinkTypeUser0, "USER0"}}};

// Its parameter and the value it carries with its own decimal point: not a C telegram's, a failed
// one's, an I telegram's index or a read command's (the drive fills that in).
std::optional<TelegramParameter> vlt2000_parameter_of(const DecodedTelegram& t) noexcept {
    const std::optional<std::uint16_t> pnu = vlt2000_named_pnu(t.vlt2000);
    if (!pnu || !t.has_roles) return std::nullopt;
    const Vlt2000Telegram& v = t.vlt2000;
    TelegramParameter p;
    p.pnu = *pnu;
    const bool index = v.letter == Vlt2000Letter::ReadIndex && !v.index.empty();
    const bool read_command = t.direction == Direction::Request && v.letter == Vlt2000Letter::Read;
    if (v.has_value && !v.failed && !index && !read_command) {
        p.has_decimal = true;
        p.decimal = v.value();
        p.decimals = v.has_decimals && v.decimals <= 5 ? v.decimals : 0;
    }
    return p;
}

std::unique_ptr<TelegramDecoder> vlt2000_decoder(const LaneOptions& options) {
    Vlt2000DecoderOptions decoder = options.vlt2000_decoder;
    decoder.response_window_ns = options.timeout_ns;
    decoder.naming = options.naming;
    return std::make_unique<Vlt2000Decoder>(decoder);
}

std::unique_ptr<TelegramTracker> vlt2000_tracker(const LaneOptions& options) {
    return std::make_unique<Vlt2000Tracker>(
        on_the_line(options.vlt2000_tracker, options, kVlt2000DefaultLineBaud));
}

}  // namespace

const ProtocolDescriptor& vlt2000_protocol() noexcept {
    static const ProtocolDescriptor descriptor{
        .protocol = Protocol::Vlt2000,
        .name = "vlt2000",
        .title = "the VLT 2000 telegram",
        .capture_noun = "a VLT 2000",
        .framing = vlt2000_framing_rules(),
        .max_telegram_bytes = kVlt2000TelegramSize,
        .link_types = kVlt2000LinkTypes,
        .pcap_bus_number = 3,
        .lead_byte = kVlt2000Start,
        .lead_byte_text = "'<'",
        .text_log_shape = "'<' ... '>'",
        .traffic_name = "VLT 2000",
        .has_bus_health = false,
        .timed_by_line = true,
        .default_baud = kVlt2000DefaultLineBaud,
        .default_parity = "none",
        .masters_addressed = false,
        .drive_family = "vlt2000",
        .filter_fields = vlt2000_filter_fields(),
        .parameter_of = vlt2000_parameter_of,
        .make_decoder = vlt2000_decoder,
        .make_tracker = vlt2000_tracker,
    };
    return descriptor;
}

}  // namespace dpscope
