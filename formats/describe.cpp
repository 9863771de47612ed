#include "formats/describe.hpp"

#include <fmt/compile.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <ctime>
#include <iterator>
#include <vector>

#include "formats/parameter_names.hpp"

namespace dpscope {

namespace {

constexpr std::int64_t kNanos = 1'000'000'000;

void split_time(std::int64_t time_ns, std::int64_t& seconds, std::int64_t& nanos) {
    seconds = time_ns / kNanos;
    nanos = time_ns % kNanos;
    if (nanos < 0) {
        nanos += kNanos;
        --seconds;
    }
}

}  // namespace

void append_iso_time(TextBuffer& out, std::int64_t time_ns) {
    std::int64_t seconds = 0, nanos = 0;
    split_time(time_ns, seconds, nanos);
    // The civil date of a day count (days since 1970-01-01), in whole-number arithmetic (the
    // proleptic Gregorian calendar gmtime uses): eras of 400 years, March-based years.
    const std::int64_t days = seconds >= 0 ? seconds / 86400 : (seconds - 86399) / 86400;
    const std::int64_t second_of_day = seconds - days * 86400;
    const std::int64_t z = days + 719468;
    const std::int64_t era = (z >= 0 ? z : z - 146096) / 146097;
    const std::int64_t day_of_era = z - era * 146097;
    const std::int64_t year_of_era =
        (day_of_era - day_of_era / 1460 + day_of_era / 36524 - day_of_era / 146096) / 365;
    const std::int64_t day_of_year =
        day_of_era - (365 * year_of_era + year_of_era / 4 - year_of_era / 100);
    const std::int64_t month_index = (5 * day_of_year + 2) / 153;  // 0 = March
    const std::int64_t day = day_of_year - (153 * month_index + 2) / 5 + 1;
    const std::int64_t month = month_index < 10 ? month_index + 3 : month_index - 9;
    const std::int64_t year = year_of_era + era * 400 + (month <= 2 ? 1 : 0);
    if (year < 0 || year > 9999) {  // out of the four digits: as fmt writes "{:04}"
        fmt::format_to(fmt::appender(out), FMT_COMPILE("{:04}-"), year);
    } else {
        append_decimal_padded(out, static_cast<std::uint64_t>(year), 4);
        out.push_back('-');
    }
    char* p = append_room(out, 25);  // MM-DDTHH:MM:SS.NNNNNNNNNZ
    auto two = [&p](std::int64_t value) {
        std::memcpy(p, text_detail::kDigitPairs + value * 2, 2);
        p += 2;
    };
    two(month);
    *p++ = '-';
    two(day);
    *p++ = 'T';
    two(second_of_day / 3600);
    *p++ = ':';
    two(second_of_day / 60 % 60);
    *p++ = ':';
    two(second_of_day % 60);
    *p++ = '.';
    std::memset(p, '0', 9);
    text_detail::write_decimal_backwards(p + 9, static_cast<std::uint64_t>(nanos));
    p[9] = 'Z';
}

std::string relative_seconds_text(std::int64_t relative_ns) {
    const bool negative = relative_ns < 0;
    const std::uint64_t magnitude = negative ? 0 - static_cast<std::uint64_t>(relative_ns)
                                             : static_cast<std::uint64_t>(relative_ns);
    return fmt::format(FMT_COMPILE("{}{}.{:06}"), negative ? "-" : "", magnitude / 1'000'000'000,
                       (magnitude % 1'000'000'000) / 1000);
}

void append_epoch_seconds(TextBuffer& out, std::int64_t time_ns) {
    const std::size_t at = out.size();
    char* end =
        text_detail::write_epoch_seconds(append_room(out, text_detail::kEpochSecondsMax), time_ns);
    out.try_resize(at + static_cast<std::size_t>(end - (out.data() + at)));
}

bool append_flags(TextBuffer& out, std::uint8_t value, std::span<const FlagBit> flags,
                  std::string_view none, std::uint8_t ignore_mask) {
    bool any = false;
    for (const FlagBit& flag : flags) {
        if (!(value & flag.mask) || (flag.mask & ignore_mask)) continue;
        if (any) out.push_back(' ');
        append(out, flag.name);
        any = true;
    }
    if (!any) append(out, none);
    return any;
}

namespace {

// "00" "01" ... "FF": a byte's two hex digits a step.
constexpr std::array<char, 512> kHexPairs = [] {
    constexpr char kDigits[] = "0123456789ABCDEF";
    std::array<char, 512> pairs{};
    for (std::size_t byte = 0; byte < 256; ++byte) {
        pairs[2 * byte] = kDigits[byte >> 4];
        pairs[2 * byte + 1] = kDigits[byte & 0x0F];
    }
    return pairs;
}();

}  // namespace

void append_hex(TextBuffer& out, Bytes bytes, std::string_view separator) {
    if (bytes.empty()) return;
    // Room for all of it at once: two digits a byte, a separator between bytes.
    const std::size_t step = 2 + separator.size();
    char* p = append_room(out, bytes.size() * step - separator.size());
    if (separator.empty()) {  // jsonl's and csv's data: the bytes' digits only
        for (const std::uint8_t byte : bytes) {
            std::memcpy(p, kHexPairs.data() + 2 * byte, 2);
            p += 2;
        }
        return;
    }
    for (std::size_t i = 0; i < bytes.size(); ++i) {
        if (i > 0) {
            std::memcpy(p, separator.data(), separator.size());
            p += separator.size();
        }
        std::memcpy(p, kHexPairs.data() + 2 * bytes[i], 2);
        p += 2;
    }
}

void append_frame_control(TextBuffer& out, FrameControl fc) {
    if (fc.is_request()) {
        put(out, "request, FCB ", fc.fcb() ? '1' : '0', ", FCV ", fc.fcv() ? '1' : '0', ", ",
            request_function_name(fc));
    } else {
        put(out, "response, ", station_type_name(fc.station_type()), ", ",
            response_status_name(fc.function()), " (", response_status_text(fc.function()), ')');
    }
}

void append_ppo_short(TextBuffer& out, const PpoLayout& layout) {
    const char* guess = layout.source == PpoSource::Length ? "?" : "";
    if (layout.type != 0) {
        if (layout.alternative != 0)
            put(out, "PPO", layout.type, '/', layout.alternative, guess);
        else
            put(out, "PPO", layout.type, guess);
        return;
    }
    if (layout.has_pcv)
        put(out, "PCV+", (layout.output_bytes - kPcvBytes) / 2, 'w');
    else
        put(out, layout.output_bytes / 2, 'w');
}

std::string command_outcomes_text(std::uint64_t answered, std::uint64_t unanswered,
                                  std::uint64_t abandoned, std::uint64_t damaged,
                                  std::uint64_t not_judged) {
    std::string text =
        fmt::format(FMT_COMPILE("{} answered, {} unanswered, {} abandoned, {} damaged"), answered,
                    unanswered, abandoned, damaged);
    if (not_judged) text += fmt::format(FMT_COMPILE(", {} not judged"), not_judged);
    return text;
}

std::string cfg_units(std::uint64_t units, bool words) {
    return words ? counted(units, "word", "words") : counted(units, "byte", "bytes");
}

void append_ppo_long(TextBuffer& out, const PpoLayout& layout) {
    auto words = [&](std::uint16_t bytes) {
        return (bytes - (layout.has_pcv ? kPcvBytes : 0)) / 2;
    };
    if (layout.type != 0) {
        fmt::format_to(fmt::appender(out), FMT_COMPILE("PPO {}"), layout.type);
        if (layout.alternative != 0)
            fmt::format_to(fmt::appender(out), FMT_COMPILE(" or PPO {}"), layout.alternative);
        append(out, " (");
    } else {
        append(out, "no standard PPO (");
    }
    if (layout.has_pcv) append(out, "PCV + ");
    if (layout.output_bytes == layout.input_bytes)
        fmt::format_to(fmt::appender(out), FMT_COMPILE("{}, {} each way)"),
                       counted(words(layout.output_bytes), "PCD word", "PCD words"),
                       counted(layout.output_bytes, "byte", "bytes"));
    else
        fmt::format_to(fmt::appender(out), FMT_COMPILE("{} out, {} in; {} out, {} in)"),
                       counted(words(layout.output_bytes), "PCD word", "PCD words"),
                       words(layout.input_bytes), counted(layout.output_bytes, "byte", "bytes"),
                       layout.input_bytes);
    switch (layout.source) {
        case PpoSource::ChkCfg: append(out, " from Chk_Cfg"); break;
        case PpoSource::GetCfg: append(out, " from Get_Cfg"); break;
        case PpoSource::Length: append(out, " guessed from the length"); break;
        case PpoSource::Option: append(out, " given by --ppo"); break;
        case PpoSource::None: break;
    }
}

void append_pcv_summary(TextBuffer& out, const DecodedTelegram& t) {
    const Pcv& pcv = t.dp.pcv;
    bool request = t.direction == Direction::Request;
    put(out, "RC=", pcv.rc, ' ', t.dp.pcv_meaning(t.direction));
    if (pcv.spm) append(out, " SPM=1");
    // The parameter's name and the value in its unit from its drive's database (issue 29).
    const TelegramParameterView view = parameter_view(t);
    put(out, " PNU=", pcv.pnu);
    append_parameter_name(out, view.named);
    put(out, " IND=", pcv.ind);
    if (!request && response_code(t.dp.dialect, pcv.rc).kind == ResponseKind::Rejected) {
        std::uint16_t error = static_cast<std::uint16_t>(pcv.pva & 0xFFFF);
        put(out, " error ", error, " (", error_text_or_unknown(t.dp.dialect, error), ')');
        return;
    }
    put(out, " PVA=", t.dp.pcv_value(t.direction));
    append_view_value(out, view);
}

std::string_view pcd_word_name(Direction direction, std::size_t index) {
    if (index == 0) return direction == Direction::Request ? "CTW" : "STW";
    if (index == 1) return direction == Direction::Request ? "MRV" : "MAV";
    return "";
}

void append_pcd_summary(TextBuffer& out, const DecodedTelegram& t) {
    ByteReader reader(t.dp.pcd);
    auto first = reader.u16_be();
    if (!first) {
        append(out, "no PCD");
        return;
    }
    put(out, pcd_word_name(t.direction, 0), "=0x", hex(*first, 4));
    if (auto second = reader.u16_be()) {
        put(out, ' ', pcd_word_name(t.direction, 1), '=');
        append_hundredths(out, reference_percent_hundredths(*second));
        out.push_back('%');
    }
    if (std::size_t more = reader.remaining() / 2; more > 0) put(out, " +", more, 'w');
}

void append_cfg_summary(TextBuffer& out, Bytes identifiers, std::span<const CfgModule> modules) {
    append_hex(out, identifiers);
    append(out, " = ");
    append_ppo_short(out, ppo_from_cfg(modules, PpoSource::ChkCfg));
}

void append_gsd_device(TextBuffer& out, const DecodedTelegram& t) {
    if (!t.dp.device) return;
    append(out, " (");
    append(out, gsd_device_title(*t.dp.device));
    out.push_back(')');
}

void append_gsd_modules(TextBuffer& out, std::span<const GsdModuleMatch> matches) {
    if (matches.empty()) return;
    append(out, " [GSD ");
    bool first = true;
    for (const GsdModuleMatch& m : matches) {
        if (!first) append(out, " + ");
        first = false;
        if (m.module)
            fmt::format_to(fmt::appender(out), FMT_COMPILE("\"{}\""), m.module->name);
        else
            append(out, "no module");
    }
    out.push_back(']');
}

void append_gsd_value(TextBuffer& out, const GsdPrmValue& v) {
    auto it = fmt::appender(out);
    if (v.text)
        fmt::format_to(it, FMT_COMPILE("{}={}"), v.prm->name, v.text->text);
    else
        fmt::format_to(it, FMT_COMPILE("{}={}"), v.prm->name, v.value);
    if (!v.in_range) append(out, " (not allowed)");
}

void append_gsd_diag_text(TextBuffer& out, const GsdDiagText& d) {
    if (d.source == GsdDiagText::Source::Slot)
        fmt::format_to(fmt::appender(out), FMT_COMPILE("slot {} \"{}\""), d.bit, d.text);
    else
        fmt::format_to(fmt::appender(out), FMT_COMPILE("\"{}\""), d.text);
}

namespace {

// "PNU 12[4]", "PNU 12[4..7]" (several elements); "param 2" when the address is not known.
// `subindex` false: "PNU 918" (an error, whose information names the failing subindex).
// With `t`, the parameter's name after it (issue 29): "PNU 1613[0] (16-13 Frequency)".
void append_parameter_address(TextBuffer& out, const ProfidriveMessage& m, std::size_t k,
                              bool subindex = true, const DecodedTelegram* t = nullptr) {
    auto it = fmt::appender(out);
    if (k >= m.addresses.size()) {
        fmt::format_to(it, FMT_COMPILE("param {}"), k + 1);
        return;
    }
    const ProfidriveAddress& a = m.addresses[k];
    if (!subindex)
        fmt::format_to(it, FMT_COMPILE("PNU {}"), a.pnu);
    else if (a.elements > 1)
        fmt::format_to(it, FMT_COMPILE("PNU {}[{}..{}]"), a.pnu, a.subindex,
                       std::min(0xFFFF, a.subindex + a.elements - 1));  // subindexes end there
    else
        fmt::format_to(it, FMT_COMPILE("PNU {}[{}]"), a.pnu, a.subindex);
    if (t) append_parameter_name(out, profidrive_parameter(*t, m, k));
}

// "500 (Integer16)"; with `t`, the value in its parameter's unit first: "500 (50.0 Hz,
// Integer16)".
void append_block_values(TextBuffer& out, const ProfidriveValueBlock& block,
                         const DecodedTelegram* t = nullptr, const ProfidriveMessage* m = nullptr,
                         std::size_t k = 0) {
    std::string values;
    append_profidrive_values(block, values);
    append(out, values.empty() ? std::string_view("(no values)") : std::string_view(values));
    append(out, " (");
    if (t && m) {
        const NamedParameter named = profidrive_parameter(*t, *m, k);
        if (const std::optional<ScaledValue> value = profidrive_value_in_unit(*t, *m, k)) {
            append_scaled(out, *named.row, *value);
            append(out, ", ");
        }
    }
    if (profidrive_format_size(block.format) < 0)  // a reserved format: name its number
        fmt::format_to(fmt::appender(out), FMT_COMPILE("format 0x{:02X}, reserved)"), block.format);
    else
        fmt::format_to(fmt::appender(out), FMT_COMPILE("{})"),
                       profidrive_format_name(block.format));
}

}  // namespace

NamedParameter profidrive_parameter(const DecodedTelegram& t, const ProfidriveMessage& m,
                                    std::size_t k) noexcept {
    if (k >= m.addresses.size()) return {};
    return named_parameter(t, m.addresses[k].pnu);
}

std::optional<ScaledValue> profidrive_value_in_unit(const DecodedTelegram& t,
                                                    const ProfidriveMessage& m,
                                                    std::size_t k) noexcept {
    if (k >= m.addresses.size() || k >= m.blocks.size()) return std::nullopt;
    if (m.addresses[k].attribute != profidrive::kAttributeValue) return std::nullopt;
    const ProfidriveValueBlock& block = m.blocks[k];
    if (block.is_error() || block.format == profidrive::kFormatZero ||
        profidrive_value_count(block) != 1)
        return std::nullopt;
    const std::optional<ProfidriveNumber> number = profidrive_number(block, 0);
    if (!number || number->is_real) return std::nullopt;
    const NamedParameter named = named_parameter(t, m.addresses[k].pnu);
    if (!named.row) return std::nullopt;
    return scale_value(*named.row, number->integer);
}

void append_profidrive_block(TextBuffer& out, const ProfidriveValueBlock& block, Dialect dialect) {
    auto it = fmt::appender(out);
    if (block.is_error()) {
        if (block.values.size() < 2) {
            append(out, "error (number cut short)");
            return;
        }
        fmt::format_to(it, FMT_COMPILE("error 0x{:02X} {}"), block.error_number(),
                       profidrive_error_text(block.error_number(), dialect));
        if (block.has_error_info())
            fmt::format_to(it, FMT_COMPILE(" (subindex {})"), block.error_info());
        return;
    }
    if (block.format == profidrive::kFormatZero) {
        append(out, "done (Zero)");
        return;
    }
    append_block_values(out, block);
}

void append_profidrive_summary(TextBuffer& out, const ProfidriveMessage& m, Dialect dialect,
                               const DecodedTelegram* t) {
    auto it = fmt::appender(out);
    if (!m.has_header) {
        append(out, "PROFIdrive header cut short");
        return;
    }
    std::string_view id_name =
        m.is_response ? profidrive_response_id_name(m.id) : profidrive_request_id_name(m.id);
    fmt::format_to(it, FMT_COMPILE("PROFIdrive {} ref {} "), m.is_response ? "rsp" : "req",
                   m.reference);
    if (id_name.empty())
        fmt::format_to(it, FMT_COMPILE("ID 0x{:02X}"), m.id);
    else
        append(out, id_name);
    fmt::format_to(it, FMT_COMPILE(" axis {}, {} param{}"), m.axis, m.count,
                   m.count == 1 ? "" : "s");
    if (m.is_response) {
        if (!m.blocks.empty()) append(out, ":");
        for (std::size_t k = 0; k < m.blocks.size(); ++k) {
            append(out, k ? ", " : " ");
            const ProfidriveValueBlock& block = m.blocks[k];
            append_parameter_address(out, m, k, !block.is_error(), t);
            if (block.is_error() || block.format == profidrive::kFormatZero) {
                append(out, ": ");
                append_profidrive_block(out, block, dialect);
            } else {
                append(out, " = ");
                append_block_values(out, block, t, &m, k);
            }
        }
    } else {
        if (!m.addresses.empty()) append(out, ":");
        for (std::size_t k = 0; k < m.addresses.size(); ++k) {
            append(out, k ? ", " : " ");
            append_parameter_address(out, m, k, true, t);
            std::string_view attribute = profidrive_attribute_name(m.addresses[k].attribute);
            if (attribute.empty())
                fmt::format_to(it, FMT_COMPILE(" attribute 0x{:02X}"), m.addresses[k].attribute);
            else
                fmt::format_to(it, FMT_COMPILE(" {}"), attribute);
            if (k < m.blocks.size()) {
                append(out, " = ");
                append_block_values(out, m.blocks[k], t, &m, k);
            }
        }
    }
    if (m.trailing > 0)
        fmt::format_to(it, FMT_COMPILE(" +{} after the message"),
                       counted(m.trailing, "byte", "bytes"));
}

void append_dpv1_summary(TextBuffer& out, const DecodedTelegram& t) {
    const FdlTelegram& f = t.dp.fdl;
    const Dpv1Pdu* pdu = t.dp.service_data.dpv1();
    auto it = fmt::appender(out);
    if (!pdu || pdu->layout == Dpv1Pdu::Layout::None) {
        if (t.direction == Direction::Request)
            append(out, "no PDU (link-level poll)");
        else if (f.has_fc)
            fmt::format_to(it, FMT_COMPILE("no PDU: {} ({})"),
                           response_status_name(f.fc.function()),
                           response_status_text(f.fc.function()));
        else
            append(out, "no PDU");
        return;
    }
    std::string_view name = dpv1_function_name(pdu->function);
    if (name.empty())
        fmt::format_to(it, FMT_COMPILE("function 0x{:02X}"), pdu->function);
    else
        append(out, name);
    if (!pdu->complete && pdu->layout != Dpv1Pdu::Layout::Initiate) {
        append(out, " (header cut short)");
        return;
    }
    switch (pdu->layout) {
        case Dpv1Pdu::Layout::Error: {
            std::string_view decode = dpv1_error_decode_name(pdu->error_decode);
            if (decode.empty())
                fmt::format_to(it, FMT_COMPILE(" Error_Decode 0x{:02X}"), pdu->error_decode);
            else
                fmt::format_to(it, FMT_COMPILE(" {}"), decode);
            std::string_view error_class = dpv1_error_class_name(pdu->error_code_1);
            if (pdu->error_decode == kDpv1ErrorDecodeDpv1)
                fmt::format_to(it, FMT_COMPILE(" {}{}{} (0x{:02X})"), error_class,
                               error_class.empty() ? "" : ": ",
                               dpv1_error_code_name(pdu->error_code_1), pdu->error_code_1);
            else
                fmt::format_to(it, FMT_COMPILE(" Error_Code_1 0x{:02X}"), pdu->error_code_1);
            if (pdu->error_code_2 != 0)
                fmt::format_to(it, FMT_COMPILE(" Error_Code_2 0x{:02X}"), pdu->error_code_2);
            return;
        }
        case Dpv1Pdu::Layout::Addressed:
            if (pdu->base_function() == dpv1_function::kAlarmAck) {
                fmt::format_to(it, FMT_COMPILE(" slot {} alarm type {} specifier 0x{:02X}"),
                               pdu->slot, pdu->index, pdu->length);
                return;
            }
            fmt::format_to(it, FMT_COMPILE(" slot {} idx {} len {}"), pdu->slot, pdu->index,
                           pdu->length);
            if (const ProfidriveMessage* m = t.dp.service_data.profidrive()) {
                append(out, " | ");
                append_profidrive_summary(out, *m, t.dp.dialect, &t);
            } else if (!pdu->data.empty()) {
                append(out, " data ");
                append_hex(out, pdu->data.first(std::min<std::size_t>(pdu->data.size(), 16)));
                if (pdu->data.size() > 16) append(out, " ...");
            }
            return;
        case Dpv1Pdu::Layout::Initiate: {
            const Dpv1Initiate& i = pdu->initiate;
            if (!pdu->complete) {
                append(out, " (cut short)");
                return;
            }
            if (t.direction == Direction::Request)
                fmt::format_to(it, FMT_COMPILE(" send timeout {} ms"), i.send_timeout * 10);
            else
                fmt::format_to(it, FMT_COMPILE(" max data unit {}"), i.max_len_data_unit);
            fmt::format_to(
                it,
                FMT_COMPILE(" features 0x{:04X} profile features 0x{:04X} profile ident 0x{:04X}"),
                i.features_supported, i.profile_features_supported, i.profile_ident_number);
            if (i.has_addresses)
                fmt::format_to(it, FMT_COMPILE(" S_Type {} S_Len {} D_Type {} D_Len {}"), i.s_type,
                               i.s_len, i.d_type, i.d_len);
            return;
        }
        case Dpv1Pdu::Layout::Abort:
            fmt::format_to(it, FMT_COMPILE(" subnet {} {}: {}"), pdu->abort.subnet,
                           dpv1_abort_instance_name(pdu->abort.instance_reason),
                           dpv1_abort_reason_name(pdu->abort.instance_reason));
            return;
        case Dpv1Pdu::Layout::Idle:
        case Dpv1Pdu::Layout::None: return;
        case Dpv1Pdu::Layout::Unknown:
            if (!pdu->data.empty()) {
                append(out, " data ");
                append_hex(out, pdu->data.first(std::min<std::size_t>(pdu->data.size(), 16)));
                if (pdu->data.size() > 16) append(out, " ...");
            }
            return;
    }
}

void append_service_detail(TextBuffer& out, const DecodedTelegram& t) {
    const FdlTelegram& f = t.dp.fdl;
    const DpServiceData& data = t.dp.service_data;
    bool request = t.direction == Direction::Request;
    if (f.type == FrameType::ShortAck) {
        append(out, "short acknowledge");
        return;
    }
    switch (t.dp.service) {
        case Service::Token: append(out, "token"); return;
        case Service::DataExchange:
            if (f.du.empty() && f.has_fc && !f.fc.is_request()) {  // RS, RR, ...: no inputs
                put(out, "no data: ", response_status_name(f.fc.function()), " (",
                    response_status_text(f.fc.function()), ')');
                return;
            }
            append_ppo_short(out, t.dp.ppo);
            out.push_back(' ');
            if (t.dp.has_pcv) {
                append_pcv_summary(out, t);
                append(out, " | ");
            }
            append_pcd_summary(out, t);
            return;
        case Service::SlaveDiag:
            if (request) {
                append(out, "diagnosis request");
                return;
            }
            if (const SlaveDiag* diag = data.slave_diag()) {
                fmt::format_to(fmt::appender(out), FMT_COMPILE("ident 0x{:04X}"), diag->ident);
                append_gsd_device(out, t);
                append(out, " master ");
                if (diag->master_address == kNoMasterAddress)
                    append(out, "none");
                else
                    fmt::format_to(fmt::appender(out), FMT_COMPILE("{}"), diag->master_address);
                append(out, " [");
                TextBuffer second;
                bool first_any =
                    append_flags(out, diag->station_status_1, station_status_1_flags(), "");
                bool second_any = append_flags(second, diag->station_status_2,
                                               station_status_2_flags(), "", kDiagAlwaysOne);
                if (first_any && second_any) out.push_back(' ');
                out.append(second.data(), second.data() + second.size());
                if (!first_any && !second_any) append(out, "OK");
                append(out, "]");
                if (!diag->extended.empty())
                    fmt::format_to(fmt::appender(out), FMT_COMPILE(" +{}"),
                                   counted(diag->extended.size(), "ext byte", "ext bytes"));
                const char* separator = ": ";
                for (const GsdDiagText& d : data.gsd_diag()) {
                    append(out, separator);
                    separator = ", ";
                    append_gsd_diag_text(out, d);
                }
                return;
            }
            break;
        case Service::SetPrm:
            if (const SetPrm* prm = data.set_prm()) {
                fmt::format_to(fmt::appender(out), FMT_COMPILE("ident 0x{:04X}"), prm->ident);
                append_gsd_device(out, t);
                out.push_back(' ');
                if (prm->watchdog_on() && prm->watchdog_base_uncertain())
                    fmt::format_to(fmt::appender(out),
                                   FMT_COMPILE("WD {} ms (1 ms base) or {} ms (10 ms base) "),
                                   prm->watchdog_ms(), prm->watchdog_ms_10ms_base());
                else if (prm->watchdog_on())
                    fmt::format_to(fmt::appender(out), FMT_COMPILE("WD {} ms "),
                                   prm->watchdog_ms());
                append(out, "[");
                append_flags(out, prm->station_status, set_prm_station_flags());
                fmt::format_to(fmt::appender(out), FMT_COMPILE("] group 0x{:02X}"),
                               prm->group_ident);
                // "DP-V1" only when DPV1_Enable is set; status bytes without it are DP-V0 mode.
                if (prm->dpv1_enabled()) append(out, " DP-V1");
                if (!prm->user_prm.empty())
                    fmt::format_to(fmt::appender(out), FMT_COMPILE(" user {}"),
                                   counted(prm->user_prm.size(), "byte", "bytes"));
                if (const GsdPrmReading* reading = data.gsd_prm()) {
                    const char* separator = ": ";
                    for (const GsdPrmValue& v : reading->values) {
                        append(out, separator);
                        separator = ", ";
                        append_gsd_value(out, v);
                    }
                }
                return;
            }
            break;
        case Service::ChkCfg:
            if (const std::vector<CfgModule>* modules = data.cfg_modules()) {
                append_cfg_summary(out, f.du, *modules);
                append_gsd_modules(out, data.gsd_modules());
                return;
            }
            break;
        case Service::GetCfg:
            if (request) {
                append(out, "configuration request");
                return;
            }
            // An empty Get_Cfg response reads as its FDL status, like any response without data.
            if (const std::vector<CfgModule>* modules = data.cfg_modules();
                modules && !f.du.empty()) {
                append_cfg_summary(out, f.du, *modules);
                append_gsd_modules(out, data.gsd_modules());
                return;
            }
            break;
        case Service::RdInp:
        case Service::RdOutp:
            if (request) {
                append(out, t.dp.service == Service::RdInp ? "read inputs" : "read outputs");
                return;
            }
            break;
        case Service::GlobalControl:
            if (const GlobalControl* gc = data.global_control()) {
                append_flags(out, gc->command, global_control_flags(), "operate");
                fmt::format_to(fmt::appender(out), FMT_COMPILE(" group 0x{:02X}"),
                               gc->group_select);
                return;
            }
            break;
        case Service::MsacC1:
        case Service::MsacC2:
            if (data.dpv1() || f.du.empty()) {
                append_dpv1_summary(out, t);
                return;
            }
            break;
        case Service::SetSlaveAdd:
            if (const SetSlaveAdd* ssa = data.set_slave_add()) {
                fmt::format_to(fmt::appender(out), FMT_COMPILE("new address {} ident 0x{:04X}"),
                               ssa->new_address, ssa->ident);
                return;
            }
            break;
        default: break;
    }
    // Generic: the FDL function or status, and the data when there is any.
    if (f.has_fc) {
        if (f.fc.is_request())
            append(out, request_function_name(f.fc));
        else
            fmt::format_to(fmt::appender(out), FMT_COMPILE("{} {}"),
                           response_status_name(f.fc.function()),
                           station_type_name(f.fc.station_type()));
    }
    if (f.has_dsap || f.has_ssap) {
        append(out, " SAP ");
        if (f.has_ssap) fmt::format_to(fmt::appender(out), FMT_COMPILE("{}"), f.ssap);
        append(out, "->");
        if (f.has_dsap) fmt::format_to(fmt::appender(out), FMT_COMPILE("{}"), f.dsap);
    }
    if (!f.du.empty()) {
        append(out, " data ");
        append_hex(out, f.du.first(std::min<std::size_t>(f.du.size(), 16)));
        if (f.du.size() > 16) append(out, " ...");
    }
}

}  // namespace dpscope
