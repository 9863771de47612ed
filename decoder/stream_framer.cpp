#include "decoder/stream_framer.hpp"

#include <fmt/format.h>

namespace dpscope {

std::string describe_skip(const SkippedBytes& skipped) {
    std::string_view what;
    switch (skipped.reason) {
        case ProblemKind::BadStartDelimiter: what = "no start delimiter"; break;
        case ProblemKind::LengthOutOfRange: what = "LE outside 3..249"; break;
        case ProblemKind::LengthMismatch: what = "LEr differs from LE"; break;
        case ProblemKind::StartDelimiterRepeat:
            what = "repeated start delimiter is not 0x68";
            break;
        case ProblemKind::BadEndDelimiter:
            what = "no end delimiter where the length puts it";
            break;
        case ProblemKind::FcsMismatch: what = "FCS wrong and no telegram follows"; break;
        case ProblemKind::InvalidAddress: what = "token address with bit 7 set"; break;
        case ProblemKind::Truncated: what = "telegram cut off (gap or end of input)"; break;
        default: what = problem_kind_name(skipped.reason); break;
    }
    if (skipped.reason == ProblemKind::BadStartDelimiter ||
        skipped.reason == ProblemKind::Truncated)
        return fmt::format("skipped {} {}: {}", skipped.count,
                           skipped.count == 1 ? "byte" : "bytes", what);
    return fmt::format("skipped {} {}: {} (byte {} of the candidate telegram)", skipped.count,
                       skipped.count == 1 ? "byte" : "bytes", what, skipped.reason_offset);
}

void StreamFramer::feed(Bytes chunk, Sink& sink) {
    bytes_fed_ += chunk.size();
    buffer_.insert(buffer_.end(), chunk.begin(), chunk.end());
    process(sink, false);
    compact();
}

void StreamFramer::mark_gap(Sink& sink) {
    process(sink, true);
    flush_skipped(sink);
    compact();
}

void StreamFramer::finish(Sink& sink) { mark_gap(sink); }

void StreamFramer::process(Sink& sink, bool input_ended) {
    while (start_ < buffer_.size()) {
        Bytes rest(buffer_.data() + start_, buffer_.size() - start_);
        FrameCheck check = check_frame(rest, input_ended);
        if (check.status == FrameStatus::NeedMore) {
            if (!input_ended) return;
            // Nothing more will come: this candidate is cut off. Later bytes may still hold
            // whole telegrams, so only this one byte is given up.
            check = FrameCheck{FrameStatus::Invalid, 0, ProblemKind::Truncated, 0};
        }
        if (check.status == FrameStatus::Complete) {
            flush_skipped(sink);
            sink.on_telegram(rest.first(check.length), buffer_offset_ + start_);
            ++telegrams_;
            start_ += check.length;
            continue;
        }
        // Invalid: skip this byte and everything up to the next possible start delimiter.
        std::size_t next = 1;
        while (next < rest.size() && !is_start_delimiter(rest[next]))
            ++next;
        skip(next, check.reason, check.reason_offset);
    }
}

void StreamFramer::skip(std::size_t count, ProblemKind reason, std::uint16_t reason_offset) {
    if (run_.count == 0) {
        run_.offset = buffer_offset_ + start_;
        run_.reason = reason;
        run_.reason_offset = reason_offset;
    }
    run_.count += count;
    bytes_skipped_ += count;
    start_ += count;
}

void StreamFramer::flush_skipped(Sink& sink) {
    if (run_.count == 0) return;
    sink.on_skipped(run_);
    run_ = SkippedBytes{};
}

void StreamFramer::compact() {
    if (start_ == 0) return;
    buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(start_));
    buffer_offset_ += start_;
    start_ = 0;
}

}  // namespace dpscope
