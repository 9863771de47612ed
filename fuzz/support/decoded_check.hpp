// What the three decoder targets (fuzz_profibus_decoder, fuzz_fc_decoder, fuzz_vlt2000_decoder)
// share: a decoder fed telegrams 1 ms apart (DecoderRun), checks on a DecodedTelegram that hold
// whatever the bytes are (every problem lies in the telegram, every view into the telegram lies in
// it, the framing rules and the decoder agree), the problem list walked so that each problem's
// message (built only when asked for) is built once, and the end of every run
// (decode_and_check).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>

#include "core/framing_rules.hpp"
#include "core/problem.hpp"
#include "core/telegram.hpp"
#include "core/time.hpp"

namespace dpscope::fuzz {

// Aborts with `what` when `ok` is false (in the replay build too, so a corpus test fails).
inline void decoded_check(bool ok, const char* what) {
    if (ok) return;
    std::fprintf(stderr, "decoder invariant violated: %s\n", what);
    std::abort();
}

// `part` is empty or lies inside `whole` (a view the decoder handed out into the telegram).
inline bool lies_in(Bytes part, Bytes whole) noexcept {
    if (part.empty()) return true;
    const std::less_equal<const std::uint8_t*> le;
    return le(whole.data(), part.data()) &&
           le(part.data() + part.size(), whole.data() + whole.size());
}

// `part` lies in `whole` at `offset`.
inline bool lies_at(Bytes part, std::size_t offset, Bytes whole) noexcept {
    if (part.empty()) return offset <= whole.size();
    return lies_in(part, whole) && part.data() == whole.data() + offset;
}

// A problem says where its check failed: inside the telegram, or just past its last byte for a
// check that wanted more bytes than there are (cut short, data unit short, ...).
inline bool problem_offset_ok(const Problem& problem, std::size_t size) noexcept {
    switch (problem.kind) {
        case ProblemKind::EmptyRecord:
        case ProblemKind::Truncated:
        case ProblemKind::AddressExtensionShort:
        case ProblemKind::ServiceDataShort:
        case ProblemKind::CfgIdentifierTruncated:
        case ProblemKind::DiagBlockTruncated: return problem.offset <= size;
        default: return problem.offset < size;
    }
}

// Walks the problems: each offset checked, each message built, each catalogue entry read.
// Returns the sum of the message sizes (so that nothing is optimised away).
inline std::size_t walk_problems(const DecodedTelegram& t) {
    std::size_t total = 0;
    const ProblemList& problems = t.problems();
    decoded_check(problems.size() <= ProblemList::kCapacity, "the problem list holds its capacity");
    for (const Problem& problem : problems) {
        decoded_check(problem_offset_ok(problem, t.bytes.size()),
                      "a problem's offset lies in the telegram");
        const ProblemKindInfo& info = problem_kind_info(problem.kind);
        decoded_check(info.kind == problem.kind, "the catalogue row names its kind");
        total += problem_message(problem).size() + info.name.size();
    }
    return total;
}

// The protocol's framing rules and its decoder agree on the record: when the rules alone (at the
// end of the input) take all of it for one telegram, the decoder finds no framing problem in it;
// and when the decoder finds no problem at all, the rules take it for one telegram of its length
// (`decoder_checks_all`: false where an option turns a check of the decoder off). `documented`
// (may be null) names the framing problems where the two differ by design.
inline void check_rules_agree(const DecodedTelegram& t, const FramingRules& rules,
                              bool decoder_checks_all,
                              bool (*documented)(const Problem&, Bytes) = nullptr) {
    if (t.bytes.empty()) return;
    const FramingVerdict verdict = rules.can_start(t.bytes[0])
                                       ? rules.judge(t.bytes, true)
                                       : FramingVerdict::invalid(ProblemKind::BadStartDelimiter, 0);
    const bool taken =
        verdict.status == FramingStatus::Telegram && verdict.length == t.bytes.size();
    if (taken) {
        for (const Problem& problem : t.problems())
            decoded_check(problem_component(problem.kind) != ProblemComponent::Framing ||
                              (documented != nullptr && documented(problem, t.bytes)),
                          "a record the framing rules take has no framing problem");
    }
    if (decoder_checks_all && t.problems().empty() && t.problems().dropped() == 0)
        decoded_check(taken, "a record the decoder finds nothing wrong with, the rules take");
}

// A decoder of the target's protocol fed one telegram after another, 1 ms apart (or without
// times), each with the next frame number.
template <class Decoder>
struct DecoderRun {
    Decoder decoder;
    bool timed = true;
    std::uint64_t frame = 0;
    std::int64_t time_ns = 1'700'000'000'000'000'000;

    template <class Options>
    explicit DecoderRun(const Options& options) : decoder(options) {}

    const DecodedTelegram& decode(Bytes bytes) {
        time_ns += 1'000'000;
        return decoder.decode(bytes, timed ? time_ns : kNoTime, ++frame);
    }
};

// The end of a decoder target's run: decodes `telegram` (after the context the target fed), checks
// that the decoded telegram is the record and of `protocol`, that the framing rules agree
// (check_rules_agree) and walks it with the target's `walk`, which checks its own fields.
template <class Decoder, class Walk>
void decode_and_check(DecoderRun<Decoder>& run, Bytes telegram, Protocol protocol,
                      const FramingRules& rules, bool decoder_checks_all, Walk walk,
                      bool (*documented)(const Problem&, Bytes) = nullptr) {
    const DecodedTelegram& t = run.decode(telegram);
    decoded_check(t.bytes.data() == telegram.data() && t.bytes.size() == telegram.size(),
                  "the decoded telegram is the record");
    decoded_check(t.protocol == protocol, "a telegram of the target's protocol");
    check_rules_agree(t, rules, decoder_checks_all, documented);
    volatile std::size_t sink = walk(t);
    (void)sink;
}

}  // namespace dpscope::fuzz
