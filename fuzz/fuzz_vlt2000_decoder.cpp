// Feeds ONE VLT 2000 telegram to a Vlt2000Decoder, after a context the input's 2-byte header
// chooses, built with the simulator's vlt2000_telegram for the address and control letter the
// telegram carries: a command it may answer (its parameter copied), a broadcast, the telegram
// itself, a command with a wrong or a "??" checksum, an index read, or a command answered already.
// So a mutated telegram is judged as a reply (letter pairing, parameter compared, decimal position
// 9 and its reason) as well as a command. A custom mutator repairs '<', '>', the length (22) and
// the checksum (fuzz/support/checksum_repair.hpp) after libFuzzer's mutation, except one mutation
// in 16, so mutations reach the fields behind those checks. Nothing is rendered; the decoded
// telegram is walked (problems and their messages, letter, word bits, reason texts, the value)
// and checked (fuzz/support/decoded_check.hpp: problem offsets and the index lie in the telegram).
//
// Input: byte 0: bit 0 checksum not checked (--vlt2000-checksum ignore), bit 1 no times, bit 2 a
// response window shorter than the 1 ms between telegrams, bits 3-5 the context (0 none, 1 a
// command, 2 a broadcast, 3 the telegram itself, 4 a command with a wrong checksum, 5 a command
// with "??", 6 an index read, 7 a command and its reply). Byte 1: bits 0-1 the context's letter
// (the telegram's, U, R, C), bit 2 its value negative. Then the telegram (22 characters; more
// or fewer are reported).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fuzz/support/checksum_repair.hpp"
#include "fuzz/support/decoded_check.hpp"
#include "fuzz/support/fuzz_input.hpp"
#include "protocols/vlt2000/vlt2000_bus_model.hpp"
#include "protocols/vlt2000/vlt2000_codes.hpp"
#include "protocols/vlt2000/vlt2000_decoder.hpp"
#include "protocols/vlt2000/vlt2000_framing_rules.hpp"
#include "protocols/vlt2000/vlt2000_telegram.hpp"

namespace {

using dpscope::Bytes;
using dpscope::fuzz::decoded_check;

constexpr std::size_t kHeader = 2;

std::size_t repair(std::uint8_t* data, std::size_t size, std::size_t max_size, unsigned) {
    if (size <= kHeader || max_size <= kHeader) return size;
    return kHeader + dpscope::fuzz::repair_vlt2000_telegram(data + kHeader, size - kHeader,
                                                            max_size - kHeader);
}

using Run = dpscope::fuzz::DecoderRun<dpscope::Vlt2000Decoder>;

// The decimal number in `count` characters at `at`, or `otherwise` when they are no digits.
unsigned digits_at(Bytes t, std::size_t at, std::size_t count, unsigned otherwise) {
    if (t.size() < at + count) return otherwise;
    unsigned value = 0;
    for (std::size_t i = at; i < at + count; ++i) {
        if (t[i] < '0' || t[i] > '9') return otherwise;
        value = value * 10 + (t[i] - '0');
    }
    return value;
}

void decode_context(Run& run, Bytes telegram, std::uint8_t h0, std::uint8_t h1) {
    dpscope::Vlt2000Fields fields;
    fields.address =
        static_cast<std::uint8_t>(digits_at(telegram, dpscope::kVlt2000AddressAt, 2, 1));
    static constexpr char kLetters[] = {0, 'U', 'R', 'C'};
    fields.letter = kLetters[h1 & 0x03];
    if (fields.letter == 0)
        fields.letter = telegram.size() > dpscope::kVlt2000LetterAt
                            ? static_cast<char>(telegram[dpscope::kVlt2000LetterAt])
                            : 'R';
    fields.word = 0x047F;
    fields.parameter =
        static_cast<std::uint16_t>(digits_at(telegram, dpscope::kVlt2000ParameterAt, 4, 102));
    fields.negative = (h1 & 0x04) != 0;
    fields.digits = 1500;
    fields.decimals = 1;
    const unsigned context = (h0 >> 3) & 0x07;
    switch (context) {
        case 0: return;
        case 2: fields.address = 0; break;
        case 3: (void)run.decode(telegram); return;
        case 5: fields.checksum_disabled = true; break;
        case 6:
            fields.letter = 'I';
            fields.index = "000003";
            break;
        default: break;
    }
    std::vector<std::uint8_t> command = dpscope::vlt2000_telegram(fields);
    if (context == 4) command[dpscope::kVlt2000ChecksumAt + 1] ^= 0x01;
    (void)run.decode(Bytes(command));
    if (context == 7) {
        fields.word = 0x0B87;
        const std::vector<std::uint8_t> reply = dpscope::vlt2000_telegram(fields);
        (void)run.decode(Bytes(reply));
    }
}

std::size_t walk(const dpscope::DecodedTelegram& t) {
    using namespace dpscope;
    std::size_t total = fuzz::walk_problems(t);
    const Vlt2000Telegram& v = t.vlt2000;
    decoded_check(fuzz::lies_in(v.index, t.bytes), "the index lies in the telegram");
    decoded_check(!v.checksum_ok || v.has_checksum, "a checksum checked is one sent");
    decoded_check(!v.complete || t.bytes.size() >= kVlt2000TelegramSize,
                  "a complete telegram has 22 characters");
    total += vlt2000_letter_name(v.letter).size() +
             static_cast<std::size_t>(vlt2000_letter_char(v.letter));
    const std::uint8_t code = vlt2000_code(v.letter);
    total += t.direction == Direction::Request ? vlt2000_request_code(code).meaning.size()
                                               : vlt2000_response_code(code).meaning.size();
    if (v.has_word) {
        for (unsigned bit = 0; bit < 16; ++bit) {
            const Vlt2000Bit& meaning = t.direction == Direction::Request ? vlt2000_control_bit(bit)
                                                                          : vlt2000_status_bit(bit);
            total += ((v.word >> bit) & 1) != 0 ? meaning.when_1.size() : meaning.when_0.size();
        }
    }
    if (v.has_reason) total += vlt2000_reason_text(v.reason).size();
    if (v.has_value) total += v.value() > 0 ? 1 : 0;
    total += static_cast<std::size_t>(v.signed_digits() & 0xFF);
    return total;
}

}  // namespace

DPSCOPE_FUZZ_REPAIRING_MUTATOR(repair, 16)

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    dpscope::fuzz::FuzzInput in(data, size);
    const std::uint8_t h0 = in.byte();
    const std::uint8_t h1 = in.byte();
    const Bytes telegram = in.rest();

    dpscope::Vlt2000DecoderOptions options;
    options.check_checksum = (h0 & 0x01) == 0;
    if (h0 & 0x04) options.response_window_ns = 500'000;
    Run run(options);
    run.timed = (h0 & 0x02) == 0;
    decode_context(run, telegram, h0, h1);
    dpscope::fuzz::decode_and_check(run, telegram, dpscope::Protocol::Vlt2000,
                                    dpscope::vlt2000_framing_rules(), options.check_checksum, walk);
    return 0;
}
