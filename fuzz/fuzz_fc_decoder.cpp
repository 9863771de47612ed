// Feeds ONE Danfoss FC protocol telegram to an FcDecoder, after a context the input's 2-byte
// header chooses, built with the simulator's build_fc_telegram for the address byte the telegram
// carries: a command it may answer (the same kind of block, with an AK the header chooses, the
// telegram's PNU and index), a broadcast, a command with a wrong BCC, the telegram itself, or a
// command answered already. So a mutated telegram is judged as a response (AK pairing, PNU and
// index compared) as well as a command. A custom mutator repairs STX, LGE and the BCC
// (fuzz/support/checksum_repair.hpp) after libFuzzer's mutation, except one mutation in 16, so
// mutations reach the fields behind those checks. Nothing is rendered; the decoded telegram is
// walked (problems and their messages, the AK meanings, fault texts) and checked
// (fuzz/support/decoded_check.hpp: problem offsets and the text lie in the telegram).
//
// Input: byte 0: bit 0 PNU bits 11 (else 12), bit 1 no times, bit 2 a response window shorter
// than the 1 ms between telegrams, bits 3-5 the context (0 none, 1 a command of the telegram's
// block, 2 the same as a broadcast, 3 the same with a wrong BCC, 4 the telegram itself, 5 a
// process-block command, 6 a text command (AK 15), 7 a command of the telegram's block and its
// response). Byte 1: bits 0-3 the context command's AK, bits 4-7 its index. Then the telegram (at
// most 257 bytes).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fuzz/support/checksum_repair.hpp"
#include "fuzz/support/decoded_check.hpp"
#include "fuzz/support/fuzz_input.hpp"
#include "protocols/fc/fc_bus_model.hpp"
#include "protocols/fc/fc_codes.hpp"
#include "protocols/fc/fc_decoder.hpp"
#include "protocols/fc/fc_framing_rules.hpp"
#include "protocols/fc/fc_telegram.hpp"

namespace {

using dpscope::Bytes;
using dpscope::fuzz::decoded_check;

constexpr std::size_t kHeader = 2;

std::size_t repair(std::uint8_t* data, std::size_t size, std::size_t max_size, unsigned) {
    if (size <= kHeader || max_size <= kHeader) return size;
    return kHeader +
           dpscope::fuzz::repair_fc_telegram(data + kHeader, size - kHeader, max_size - kHeader);
}

using Run = dpscope::fuzz::DecoderRun<dpscope::FcDecoder>;

// The data of a command like `telegram` (its block's length, PNU and index) with AK `ak` and
// index `ind`; a process block's data when the telegram has none to copy.
std::vector<std::uint8_t> command_data(Bytes telegram, std::uint8_t ak, std::uint8_t ind) {
    std::vector<std::uint8_t> data;
    if (telegram.size() >= 4) data.assign(telegram.begin() + 3, telegram.end() - 1);
    if (data.size() != 4 && data.size() < 8) data.assign(4, 0);
    if (data.size() >= 8) {
        data[0] = static_cast<std::uint8_t>((ak << 4) | (data[0] & 0x0F));
        data[3] = ind;
    }
    data[data.size() - 4] = 0x04;  // control word: data valid
    return data;
}

void decode_context(Run& run, Bytes telegram, std::uint8_t h0, std::uint8_t h1) {
    const std::uint8_t adr = telegram.size() >= 3 ? telegram[2] : 0x01;
    const std::uint8_t ak = h1 & 0x0F;
    const auto ind = static_cast<std::uint8_t>(h1 >> 4);
    switch ((h0 >> 3) & 0x07) {
        case 1:
        case 7: {
            const std::vector<std::uint8_t> command =
                dpscope::build_fc_telegram(adr, command_data(telegram, ak, ind));
            (void)run.decode(Bytes(command));
            if (((h0 >> 3) & 0x07) == 7) {
                std::vector<std::uint8_t> data = command_data(telegram, 1, ind);
                const std::vector<std::uint8_t> reply = dpscope::build_fc_telegram(adr, data);
                (void)run.decode(Bytes(reply));
            }
            break;
        }
        case 2: {
            const auto broadcast = static_cast<std::uint8_t>(adr & 0x80 ? 0x80 : 0x20);
            const std::vector<std::uint8_t> command =
                dpscope::build_fc_telegram(broadcast, command_data(telegram, ak, ind));
            (void)run.decode(Bytes(command));
            break;
        }
        case 3: {
            std::vector<std::uint8_t> command =
                dpscope::build_fc_telegram(adr, command_data(telegram, ak, ind));
            command.back() ^= 0x5A;
            (void)run.decode(Bytes(command));
            break;
        }
        case 4: (void)run.decode(telegram); break;
        case 5: {
            const std::vector<std::uint8_t> command =
                dpscope::build_fc_telegram(adr, {0x04, 0x7C, 0x20, 0x00});
            (void)run.decode(Bytes(command));
            break;
        }
        case 6: {
            std::vector<std::uint8_t> data = {
                0xF0, 0x01, dpscope::kFcTextRead, ind, 0, 0, 0, 0, 0x04, 0x7C, 0x00, 0x00};
            const std::vector<std::uint8_t> command = dpscope::build_fc_telegram(adr, data);
            (void)run.decode(Bytes(command));
            break;
        }
        default: break;
    }
}

std::size_t walk(const dpscope::DecodedTelegram& t) {
    using namespace dpscope;
    std::size_t total = fuzz::walk_problems(t);
    const FcTelegram& fc = t.fc;
    decoded_check(fuzz::lies_in(fc.text, t.bytes), "the text lies in the telegram");
    decoded_check(!fc.bcc_ok || fc.complete, "a BCC checked is a BCC there");
    decoded_check(!fc.complete || std::size_t{fc.lge} + 2 <= t.bytes.size(),
                  "a complete telegram has every byte LGE announces");
    total += fc_block_name(fc.block).size() + fc_address_format_name(fc.address_format).size();
    if (fc.has_pkw) {
        const std::uint8_t ak = fc.pkw.rc;
        if (t.direction == Direction::Request) {
            total += fc_command(ak).meaning.size();
        } else {
            const FcResponse& response = fc_response(ak);
            total += response.meaning.size();
            if (response.kind == ResponseKind::Rejected) total += fc_fault_text(fc.pkw.pva).size();
            total += pcv_value(fc.pkw, response.width);
        }
        total += fc_command_only(ak) + fc_response_only(ak);
    }
    if (fc.has_pcd) {
        const WordBits& bits = t.direction == Direction::Request
                                   ? control_word_bits(PcdProfile::Fc, true)
                                   : status_word_bits(PcdProfile::Fc, true);
        for (unsigned bit = 0; bit < 16; ++bit)
            total +=
                ((fc.pcd1 >> bit) & 1) != 0 ? bits[bit].when_1.size() : bits[bit].when_0.size();
        total += reference_percent(fc.pcd2) > 0 ? 1 : 0;
    }
    return total;
}

}  // namespace

DPSCOPE_FUZZ_REPAIRING_MUTATOR(repair, 16)

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    dpscope::fuzz::FuzzInput in(data, size);
    const std::uint8_t h0 = in.byte();
    const std::uint8_t h1 = in.byte();
    const Bytes telegram = in.rest();

    dpscope::FcDecoderOptions options;
    options.pnu_bits = (h0 & 0x01) != 0 ? 11 : 12;
    if (h0 & 0x04) options.response_window_ns = 500'000;
    Run run(options);
    run.timed = (h0 & 0x02) == 0;
    decode_context(run, telegram, h0, h1);
    dpscope::fuzz::decode_and_check(run, telegram, dpscope::Protocol::Fc,
                                    dpscope::fc_framing_rules(), true, walk);
    return 0;
}
