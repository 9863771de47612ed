#include "protocols/fc/fc_decoder.hpp"

#include <algorithm>

#include "protocols/fc/fc_codes.hpp"
#include "protocols/fc/fc_framing_rules.hpp"

namespace dpscope {

std::string_view fc_block_name(FcBlock block) noexcept {
    switch (block) {
        case FcBlock::Process: return "process";
        case FcBlock::Parameter: return "parameter";
        case FcBlock::Text: return "text";
        case FcBlock::Unknown: break;
    }
    return "unknown";
}

std::string_view fc_address_format_name(FcAddressFormat format) noexcept {
    return format == FcAddressFormat::Short ? "1-31" : "1-126";
}

FcDecoder::FcDecoder(FcDecoderOptions options) noexcept
    : options_(options), layout_(options.pnu_bits == 11 ? kFcPkeLayout11 : kFcPkeLayout) {
    t_.protocol = Protocol::Fc;
    t_.naming = options_.naming.get();
}

namespace {

void read_address(std::uint8_t adr, FcTelegram& fc) noexcept {
    fc.adr = adr;
    if (adr & 0x80) {
        fc.address_format = FcAddressFormat::Long;
        fc.address = adr & 0x7F;
        fc.broadcast = fc.address == 0;
    } else {
        fc.address_format = FcAddressFormat::Short;
        fc.broadcast = (adr & 0x20) != 0;
        fc.address = fc.broadcast ? 0 : adr & 0x1F;
    }
}

}  // namespace

void FcDecoder::parse(Bytes bytes) {
    FcTelegram& fc = t_.fc;
    ByteReader reader(bytes);
    if (bytes.empty()) {
        fc.problems.add(ProblemKind::EmptyRecord, 0);
        return;
    }
    const std::uint8_t stx = *reader.u8();
    if (stx != kFcStx) {
        fc.problems.add(ProblemKind::BadStartDelimiter, 0, kFcStx, stx);
        return;
    }
    auto lge = reader.u8();
    if (!lge) {
        fc.problems.add(ProblemKind::Truncated, 1, 3, 1);
        return;
    }
    fc.lge = *lge;
    if (!fc_lge_valid(fc.lge)) fc.problems.add(ProblemKind::LgeInvalid, 1, 0, fc.lge);
    const std::size_t size = std::size_t{fc.lge} + 2;
    auto adr = reader.u8();
    if (!adr) {
        fc.problems.add(ProblemKind::Truncated, 2, static_cast<std::uint32_t>(size), 2);
        return;
    }
    read_address(*adr, fc);
    if (!fc_adr_valid(*adr)) fc.problems.add(ProblemKind::AdrInvalid, 2, 0, *adr);

    if (bytes.size() < size) {
        fc.problems.add(ProblemKind::Truncated, bytes.size(), static_cast<std::uint32_t>(size),
                        static_cast<std::uint32_t>(bytes.size()));
    } else {
        fc.complete = true;
        fc.bcc = bytes[size - 1];
        fc.bcc_computed = fc_bcc_of(bytes.first(size - 1));
        fc.bcc_ok = fc.bcc == fc.bcc_computed;
        if (!fc.bcc_ok)
            fc.problems.add(ProblemKind::BccMismatch, size - 1, fc.bcc_computed, fc.bcc);
        if (bytes.size() > size)
            fc.problems.add(ProblemKind::TrailingBytes, size, 0,
                            static_cast<std::uint32_t>(bytes.size() - size));
    }
    if (!fc_lge_valid(fc.lge)) return;

    // The data bytes: after ADR, up to the BCC (or what there is of them).
    const std::size_t data_end = std::min(bytes.size(), size - 1);
    ByteReader data(bytes.subspan(3, data_end - 3), 3);
    if (fc.lge == kFcLgeProcess) {
        fc.block = FcBlock::Process;
    } else {
        auto pke_high = data.peek_u8();
        const bool text_ak = pke_high && (*pke_high >> 4) == 15;
        fc.block = fc.lge == kFcLgeParameter && !text_ak ? FcBlock::Parameter : FcBlock::Text;
        if (data.remaining() < 4) return;
        ByteReader head = data.sub_reader(4);
        head.skip(2);
        fc.ind_high = *head.u8();
        if (fc.block == FcBlock::Parameter) {
            // PKE, IND and PWE as the FC layout splits them.
            ByteReader pkw(bytes.subspan(3, data_end - 3), 3);
            if (!read_pcv(pkw, layout_, fc.pkw)) return;
            data.skip(4);
        } else {
            ByteReader pke(bytes.subspan(3, 4), 3);
            const std::uint16_t pke_word = *pke.u16_be();
            fc.pkw.pca = pke_word;
            fc.pkw.rc = static_cast<std::uint8_t>(pke_word >> 12);
            fc.pkw.pnu = static_cast<std::uint16_t>(pke_word & ((1u << layout_.pnu_bits) - 1u));
            pke.skip(1);
            fc.pkw.ind_low = *pke.u8();
            fc.pkw.ind = fc.pkw.ind_low;
            const std::size_t chars = std::size_t{fc.lge} - kFcLgeTextBase;
            fc.text = *data.bytes(std::min(chars, data.remaining()));
            if (fc.text.size() < chars) return;
        }
        fc.has_pkw = true;
    }
    if (data.remaining() < 4) return;
    fc.pcd1 = *data.u16_be();
    fc.pcd2 = *data.u16_be();
    fc.has_pcd = true;
}

Direction FcDecoder::direction_of(const FcTelegram& fc) const noexcept {
    const bool has_ak = fc.has_pkw;
    if (has_ak && fc_response_only(fc.pkw.rc)) return Direction::Response;
    if (!pending_.valid) return Direction::Request;
    if (fc.adr != pending_.adr) return Direction::Request;
    if ((fc.block == FcBlock::Process) == pending_.pkw) return Direction::Request;
    if (has_ak && fc_command_only(fc.pkw.rc)) return Direction::Request;
    const Bytes bytes = t_.bytes;
    if (bytes.size() == pending_.size &&
        std::equal(bytes.begin(), bytes.end(), pending_.bytes.begin()))
        return Direction::Request;
    if (t_.time_ns != kNoTime && pending_.time_ns != kNoTime &&
        t_.time_ns - pending_.time_ns > options_.response_window_ns)
        return Direction::Request;
    return Direction::Response;
}

const DecodedTelegram& FcDecoder::decode(Bytes bytes, std::int64_t time_ns, std::uint64_t frame) {
    t_.frame = frame;
    t_.time_ns = time_ns;
    t_.bytes = bytes;
    t_.request_frame = 0;
    t_.fc.reset();
    parse(bytes);
    FcTelegram& fc = t_.fc;

    // Without an address byte the telegram takes no part in the handshake.
    const bool addressed = bytes.size() >= 3 && bytes[0] == kFcStx;
    t_.has_roles = addressed;
    t_.master = 0;
    t_.slave = fc.address;
    t_.direction = addressed ? direction_of(fc) : Direction::Request;
    if (!addressed) return t_;

    if (t_.direction == Direction::Response) {
        // A response from another address (AK 7 goes anywhere) answers nothing pending here: the
        // request still waits for its own drive.
        if (pending_.valid && fc.adr == pending_.adr) {
            t_.request_frame = pending_.frame;
            pending_.valid = false;
        }
    } else if (fc.broadcast || !fc.complete || !fc.bcc_ok) {
        // Nobody answers a broadcast, and a drive drops a damaged command: the master's next
        // telegram is then no answer to it.
        pending_.valid = false;
    } else {
        pending_.valid = true;
        pending_.frame = frame;
        pending_.time_ns = time_ns;
        pending_.adr = fc.adr;
        pending_.pkw = fc.block == FcBlock::Parameter || fc.block == FcBlock::Text;
        pending_.size = static_cast<std::uint16_t>(std::min(bytes.size(), pending_.bytes.size()));
        std::copy_n(bytes.begin(), pending_.size, pending_.bytes.begin());
    }
    return t_;
}

}  // namespace dpscope
