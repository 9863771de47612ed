#include "protocols/profibus/telegram_builder.hpp"

namespace dpscope {

std::uint8_t request_fc(FdlFunction function, bool fcb, bool fcv) noexcept {
    return static_cast<std::uint8_t>(0x40 | (fcb ? 0x20 : 0) | (fcv ? 0x10 : 0) |
                                     static_cast<std::uint8_t>(function));
}

std::uint8_t response_fc(FdlStatus status, std::uint8_t station_type) noexcept {
    return static_cast<std::uint8_t>(((station_type & 0x03) << 4) |
                                     static_cast<std::uint8_t>(status));
}

void append_u16_be(std::vector<std::uint8_t>& out, std::uint16_t value) {
    out.push_back(static_cast<std::uint8_t>(value >> 8));
    out.push_back(static_cast<std::uint8_t>(value));
}

void append_pcv(std::vector<std::uint8_t>& out, std::uint8_t rc, bool spm, std::uint16_t pnu,
                std::uint8_t ind, std::uint32_t pva) {
    append_u16_be(
        out, static_cast<std::uint16_t>(((rc & 0x0F) << 12) | (spm ? 0x0800 : 0) | (pnu & 0x07FF)));
    out.push_back(ind);
    out.push_back(0);
    append_u16_be(out, static_cast<std::uint16_t>(pva >> 16));
    append_u16_be(out, static_cast<std::uint16_t>(pva));
}

void append_telegram(std::vector<std::uint8_t>& out, const TelegramSpec& spec) {
    std::size_t data_length = spec.du.size() + (spec.dsap ? 1 : 0) + (spec.ssap ? 1 : 0);
    std::uint8_t da = static_cast<std::uint8_t>((spec.da & 0x7F) | (spec.dsap ? 0x80 : 0));
    std::uint8_t sa = static_cast<std::uint8_t>((spec.sa & 0x7F) | (spec.ssap ? 0x80 : 0));
    std::size_t sum_from;
    if (data_length == 0) {
        out.push_back(kSd1);
    } else if (data_length == 8) {
        out.push_back(kSd3);
    } else {
        auto le = static_cast<std::uint8_t>(data_length + 3);
        // One byte at a time: GCC 12 with LTO warns falsely (-Wstringop-overflow) about
        // inserting the four as a list.
        for (std::uint8_t byte : {kSd2, le, le, kSd2})
            out.push_back(byte);
    }
    sum_from = out.size();
    out.push_back(da);
    out.push_back(sa);
    out.push_back(spec.fc);
    if (spec.dsap) out.push_back(*spec.dsap & 0x3F);
    if (spec.ssap) out.push_back(*spec.ssap & 0x3F);
    out.insert(out.end(), spec.du.begin(), spec.du.end());
    out.push_back(fcs_of(Bytes(out.data() + sum_from, out.size() - sum_from)));
    out.push_back(kEndDelimiter);
}

void append_token(std::vector<std::uint8_t>& out, std::uint8_t da, std::uint8_t sa) {
    out.insert(out.end(),
               {kSd4, static_cast<std::uint8_t>(da & 0x7F), static_cast<std::uint8_t>(sa & 0x7F)});
}

void append_short_ack(std::vector<std::uint8_t>& out) { out.push_back(kShortAck); }

std::vector<std::uint8_t> build_telegram(const TelegramSpec& spec) {
    std::vector<std::uint8_t> out;
    append_telegram(out, spec);
    return out;
}

}  // namespace dpscope
