// The framing rules of PROFIBUS FDL (protocols/profibus/fdl.hpp) in a byte stream: a telegram
// starts with SD1, SD2, SD3, SD4 or SC, and a candidate is accepted when its start delimiter, LE =
// LEr (3..249), repeated SD and end delimiter are right. A wrong FCS alone does not reject an SD2
// (the length redundancy makes a false match unlikely; the decoder reports the FCS error); an SD1
// or SD3 with a wrong FCS is accepted only when the next byte starts another telegram or nothing
// follows.
#pragma once

#include "core/framing_rules.hpp"
#include "protocols/profibus/fdl.hpp"

namespace dpscope {

class FdlFramingRules final : public FramingRules {
  public:
    FdlFramingRules() noexcept;

    FramingVerdict judge(Bytes candidate, bool at_end) const noexcept override;
    std::string_view protocol_name() const noexcept override { return "PROFIBUS"; }
    std::unique_ptr<FramerCore> make_framer_core() const override;

  protected:
    std::string_view reason_text(ProblemKind reason) const override;

  private:
    // SD1 and SD3: fixed `size`, FCS at size - 2, ED at size - 1.
    FramingVerdict judge_fixed(Bytes candidate, std::size_t size, bool at_end) const noexcept;
};

// The one instance every FDL byte-stream source shares (the rules hold no state).
const FdlFramingRules& fdl_framing_rules() noexcept;

// judge() is defined here and always inlined, so that the framing loop FramerFor<FdlFramingRules>
// has it inline: a call per candidate would cost the stream framer about a third of its speed
// (BM_StreamFramer in bench/decode_bench.cpp).
[[gnu::always_inline]] inline FramingVerdict FdlFramingRules::judge(Bytes candidate,
                                                                    bool at_end) const noexcept {
    if (candidate.empty()) return FramingVerdict::need_more();
    switch (candidate[0]) {
        case kShortAck: return FramingVerdict::telegram(1);
        case kSd4:
            if (candidate.size() < 3) return FramingVerdict::need_more();
            if (candidate[1] & 0x80) return FramingVerdict::invalid(ProblemKind::InvalidAddress, 1);
            if (candidate[2] & 0x80) return FramingVerdict::invalid(ProblemKind::InvalidAddress, 2);
            return FramingVerdict::telegram(3);
        case kSd1: return judge_fixed(candidate, 6, at_end);
        case kSd3: return judge_fixed(candidate, 14, at_end);
        case kSd2: {
            if (candidate.size() < 2) return FramingVerdict::need_more();
            std::uint8_t le = candidate[1];
            if (le < 3 || le > 249)
                return FramingVerdict::invalid(ProblemKind::LengthOutOfRange, 1);
            if (candidate.size() < 3) return FramingVerdict::need_more();
            if (candidate[2] != le) return FramingVerdict::invalid(ProblemKind::LengthMismatch, 2);
            if (candidate.size() < 4) return FramingVerdict::need_more();
            if (candidate[3] != kSd2)
                return FramingVerdict::invalid(ProblemKind::StartDelimiterRepeat, 3);
            std::size_t size = std::size_t{le} + 6;
            if (candidate.size() < size) return FramingVerdict::need_more();
            if (candidate[size - 1] != kEndDelimiter)
                return FramingVerdict::invalid(ProblemKind::BadEndDelimiter, size - 1);
            return FramingVerdict::telegram(size);
        }
        default: return FramingVerdict::invalid(ProblemKind::BadStartDelimiter, 0);
    }
}

}  // namespace dpscope
