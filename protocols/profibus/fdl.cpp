#include "protocols/profibus/fdl.hpp"

#include <cstring>

namespace dpscope {

std::string_view frame_type_name(FrameType type) {
    switch (type) {
        case FrameType::Sd1: return "SD1";
        case FrameType::Sd2: return "SD2";
        case FrameType::Sd3: return "SD3";
        case FrameType::Sd4: return "SD4";
        case FrameType::ShortAck: return "SC";
        case FrameType::Invalid: break;
    }
    return "invalid";
}

bool is_start_delimiter(std::uint8_t byte) noexcept {
    return byte == kSd1 || byte == kSd2 || byte == kSd3 || byte == kSd4 || byte == kShortAck;
}

std::string_view request_function_name(std::uint8_t function) {
    switch (static_cast<FdlFunction>(function)) {
        case FdlFunction::TimeEvent: return "time event";
        case FdlFunction::SdaLow: return "SDA low";
        case FdlFunction::SdnLow: return "SDN low";
        case FdlFunction::SdaHigh: return "SDA high";
        case FdlFunction::SdnHigh: return "SDN high";
        case FdlFunction::Msrd: return "MSRD";
        case FdlFunction::FdlStatus: return "FDL status";
        case FdlFunction::TimeEventActual: return "time event (actual)";
        case FdlFunction::CounterEventActual: return "counter event (actual)";
        case FdlFunction::SrdLow: return "SRD low";
        case FdlFunction::SrdHigh: return "SRD high";
        case FdlFunction::Ident: return "ident";
        case FdlFunction::LsapStatus: return "LSAP status";
    }
    return "reserved";
}

std::string_view request_function_name(FrameControl fc) {
    if (fc.is_clock_value()) return "clock value";
    if (fc.is_reserved()) return "reserved";
    return request_function_name(fc.function());
}

std::string_view response_status_name(std::uint8_t status) {
    switch (static_cast<FdlStatus>(status)) {
        case FdlStatus::Ok: return "OK";
        case FdlStatus::UserError: return "UE";
        case FdlStatus::NoResource: return "RR";
        case FdlStatus::NoService: return "RS";
        case FdlStatus::DataLow: return "DL";
        case FdlStatus::NoResponseData: return "NR";
        case FdlStatus::DataHigh: return "DH";
        case FdlStatus::NotReceivedDataLow: return "RDL";
        case FdlStatus::NotReceivedDataHigh: return "RDH";
    }
    return "reserved";
}

std::string_view response_status_text(std::uint8_t status) {
    switch (static_cast<FdlStatus>(status)) {
        case FdlStatus::Ok: return "positive acknowledgement";
        case FdlStatus::UserError: return "user error";
        case FdlStatus::NoResource: return "no resources";
        case FdlStatus::NoService: return "SAP not activated";
        case FdlStatus::DataLow: return "response data low";
        case FdlStatus::NoResponseData: return "no response data";
        case FdlStatus::DataHigh: return "response data high (diagnosis pending)";
        case FdlStatus::NotReceivedDataLow: return "data not received, response data low";
        case FdlStatus::NotReceivedDataHigh: return "data not received, response data high";
    }
    return "reserved";
}

std::string_view station_type_name(std::uint8_t station_type) {
    switch (station_type & 0x03) {
        case 0: return "slave";
        case 1: return "master not ready";
        case 2: return "master ready for the token ring";
        default: return "master in the token ring";
    }
}

bool function_is_srd(std::uint8_t function) noexcept {
    return function == static_cast<std::uint8_t>(FdlFunction::SrdLow) ||
           function == static_cast<std::uint8_t>(FdlFunction::SrdHigh);
}

bool function_is_sda(std::uint8_t function) noexcept {
    return function == static_cast<std::uint8_t>(FdlFunction::SdaLow) ||
           function == static_cast<std::uint8_t>(FdlFunction::SdaHigh);
}

bool function_expects_reply(std::uint8_t function) noexcept {
    switch (static_cast<FdlFunction>(function)) {
        case FdlFunction::SdaLow:
        case FdlFunction::SdaHigh:
        case FdlFunction::Msrd:
        case FdlFunction::FdlStatus:
        case FdlFunction::SrdLow:
        case FdlFunction::SrdHigh:
        case FdlFunction::Ident:
        case FdlFunction::LsapStatus: return true;
        default: return false;
    }
}

std::uint8_t fcs_of(Bytes bytes) noexcept {
    // Eight bytes at a time: the even and odd bytes of a word summed in 16-bit lanes, which
    // cannot overflow for a telegram (at most 255 bytes, 32 words, 510 per lane and word).
    constexpr std::uint64_t kLowBytes = 0x00FF00FF00FF00FFULL;
    std::uint64_t lanes = 0;
    std::size_t i = 0;
    for (; i + 8 <= bytes.size(); i += 8) {
        std::uint64_t word;
        std::memcpy(&word, bytes.data() + i, sizeof word);
        lanes += (word & kLowBytes) + ((word >> 8) & kLowBytes);
    }
    unsigned sum = static_cast<unsigned>((lanes * 0x0001000100010001ULL) >> 48);
    for (; i < bytes.size(); ++i)
        sum += bytes[i];
    return static_cast<std::uint8_t>(sum);
}

namespace {

// Reads the address-extension chain for one address. Returns false if the chain runs past the
// data unit. A byte with bit 6 set names a segment, a byte without it names the SAP.
bool read_extension(ByteReader& reader, bool& has_sap, std::uint8_t& sap, bool& has_segment,
                    std::uint8_t& segment) noexcept {
    for (;;) {
        auto byte = reader.u8();
        if (!byte) return false;
        if (*byte & 0x40) {
            has_segment = true;
            segment = *byte & 0x3F;
        } else {
            has_sap = true;
            sap = *byte & 0x3F;
        }
        if (!(*byte & 0x80)) return true;
    }
}

// DA SA FC [extensions] DU from a reader positioned on DA, for SD1/SD2/SD3.
// `reader` by reference: a copy made on the call path costs a store-forwarding stall.
void parse_header_and_data(ByteReader&& reader, FdlTelegram& out) noexcept {
    auto da = reader.u8();
    auto sa = reader.u8();
    if (!da || !sa) return;
    out.has_addresses = true;
    out.da = *da & 0x7F;
    out.sa = *sa & 0x7F;
    std::size_t fc_at = reader.offset();
    auto fc = reader.u8();
    if (!fc) return;
    out.has_fc = true;
    out.fc.raw = *fc;
    if (out.fc.is_reserved()) out.problems.add(ProblemKind::ReservedFrameControl, fc_at, 0, *fc);
    if (*da & 0x80) {
        std::size_t at = reader.offset();
        if (!read_extension(reader, out.has_dsap, out.dsap, out.has_dest_segment, out.dest_segment))
            out.problems.add(ProblemKind::AddressExtensionShort, at);
    }
    if (*sa & 0x80) {
        std::size_t at = reader.offset();
        if (!read_extension(reader, out.has_ssap, out.ssap, out.has_source_segment,
                            out.source_segment))
            out.problems.add(ProblemKind::AddressExtensionShort, at);
    }
    out.du_offset = static_cast<std::uint16_t>(reader.offset());
    out.du = reader.rest();
}

// The FCS byte at `fcs_at` and the end delimiter after it, for a telegram of `size` bytes whose
// checksummed bytes are bytes[sum_from, fcs_at).
void check_trailer(Bytes bytes, std::size_t sum_from, std::size_t fcs_at, FdlTelegram& out) {
    ByteReader reader(bytes);
    if (!reader.skip(sum_from)) return;  // cut off before the data: reported by the caller
    auto summed = reader.bytes(fcs_at - sum_from);
    if (!summed) return;  // truncated before the FCS: reported by the caller
    auto fcs = reader.u8();
    if (!fcs) return;
    out.has_fcs = true;
    out.fcs = *fcs;
    std::uint8_t want = fcs_of(*summed);
    out.fcs_ok = want == *fcs;
    if (!out.fcs_ok) out.problems.add(ProblemKind::FcsMismatch, fcs_at, want, *fcs);
    auto ed = reader.u8();
    if (ed && *ed != kEndDelimiter)
        out.problems.add(ProblemKind::BadEndDelimiter, fcs_at + 1, kEndDelimiter, *ed);
}

}  // namespace

void parse_fdl(Bytes bytes, FdlTelegram& out) noexcept {
    // Field by field rather than `out = FdlTelegram{}`: the problem list's storage need not be
    // zeroed for every telegram.
    out.type = FrameType::Invalid;
    out.size = 0;
    out.length_field = 0;
    out.has_length_repeat = false;
    out.length_repeat = 0;
    out.has_addresses = out.has_fc = out.has_dsap = out.has_ssap = false;
    out.has_dest_segment = out.has_source_segment = false;
    out.da = out.sa = out.dsap = out.ssap = out.dest_segment = out.source_segment = 0;
    out.fc = FrameControl{};
    out.du = {};
    out.du_offset = 0;
    out.has_fcs = false;
    out.fcs = 0;
    out.fcs_ok = true;
    out.problems.clear();
    ByteReader reader(bytes);
    auto sd = reader.u8();
    if (!sd) {
        out.problems.add(ProblemKind::EmptyRecord, 0);
        return;
    }
    std::size_t size = 0;
    switch (*sd) {
        case kShortAck:
            out.type = FrameType::ShortAck;
            size = 1;
            break;
        case kSd4: {
            out.type = FrameType::Sd4;
            size = 3;
            auto da = reader.u8();
            auto sa = reader.u8();
            if (da && sa) {
                out.has_addresses = true;
                out.da = *da & 0x7F;
                out.sa = *sa & 0x7F;
                if (*da & 0x80) out.problems.add(ProblemKind::InvalidAddress, 1, 0, *da);
                if (*sa & 0x80) out.problems.add(ProblemKind::InvalidAddress, 2, 0, *sa);
            }
            break;
        }
        case kSd1:
            out.type = FrameType::Sd1;
            size = 6;
            parse_header_and_data(
                ByteReader(bytes.first(bytes.size() < 4 ? bytes.size() : 4).subspan(1), 1), out);
            check_trailer(bytes, 1, 4, out);
            break;
        case kSd3:
            out.type = FrameType::Sd3;
            size = 14;
            parse_header_and_data(
                ByteReader(bytes.first(bytes.size() < 12 ? bytes.size() : 12).subspan(1), 1), out);
            check_trailer(bytes, 1, 12, out);
            break;
        case kSd2: {
            out.type = FrameType::Sd2;
            auto le = reader.u8();
            auto ler = reader.u8();
            auto sd_repeat = reader.u8();
            if (!le) {
                size = 6;  // the shortest header we could have checked
                break;
            }
            out.length_field = *le;
            if (ler) {
                out.has_length_repeat = true;
                out.length_repeat = *ler;
            }
            if (ler && *ler != *le) out.problems.add(ProblemKind::LengthMismatch, 2, *le, *ler);
            if (*le < 4 || *le > 249) out.problems.add(ProblemKind::LengthOutOfRange, 1, 0, *le);
            if (sd_repeat && *sd_repeat != kSd2)
                out.problems.add(ProblemKind::StartDelimiterRepeat, 3, kSd2, *sd_repeat);
            size = std::size_t{*le} + 6;
            std::size_t fcs_at = 4 + std::size_t{*le};
            if (bytes.size() > 4) {
                std::size_t body_end = bytes.size() < fcs_at ? bytes.size() : fcs_at;
                parse_header_and_data(ByteReader(bytes.subspan(4, body_end - 4), 4), out);
            }
            check_trailer(bytes, 4, fcs_at, out);
            break;
        }
        default:
            out.problems.add(ProblemKind::BadStartDelimiter, 0, 0, *sd);
            out.size = static_cast<std::uint16_t>(bytes.size() > 0xFFFF ? 0xFFFF : bytes.size());
            return;
    }
    if (bytes.size() < size) {
        out.problems.add(ProblemKind::Truncated, bytes.size(), static_cast<std::uint32_t>(size),
                         static_cast<std::uint32_t>(bytes.size()));
        out.size = static_cast<std::uint16_t>(bytes.size());
    } else {
        out.size = static_cast<std::uint16_t>(size);
        if (bytes.size() > size)
            out.problems.add(ProblemKind::TrailingBytes, size, 0,
                             static_cast<std::uint32_t>(bytes.size() - size));
    }
}

}  // namespace dpscope
