// One line a telegram:
//   frame  time(s, relative to the first)  source → destination  frame type  service  req|rsp
//   detail  [problem kinds] [severity finding-kind ...]
// An FC protocol telegram: source and destination are the master "M" and the drive's address
// ("all" for a broadcast), the frame type "FC" and the service column the block. A VLT 2000
// telegram: the master "M" and the drive's two-digit address ("all" for address 00), the frame
// type "VLT" and the service column the control letter with its name ("U update").
#include <fmt/compile.h>

#include <algorithm>
#include <iterator>

#include "formats/describe.hpp"
#include "formats/protocol_rendering.hpp"
#include "formats/renderer.hpp"

namespace dpscope {

namespace {

constexpr int kTimeColumn = 12;

// Seconds since the first telegram in at most 12 characters: microseconds up to 99,999 s (and
// down to -9,999 s), then one decimal fewer for each further digit of the seconds, so the
// columns after it stay aligned however long the capture.
void append_relative_time(TextBuffer& b, std::int64_t relative_ns) {
    const bool negative = relative_ns < 0;
    const std::uint64_t magnitude = negative ? 0 - static_cast<std::uint64_t>(relative_ns)
                                             : static_cast<std::uint64_t>(relative_ns);
    const std::uint64_t seconds = magnitude / 1'000'000'000;
    int integer_digits = negative ? 2 : 1;
    for (std::uint64_t rest = seconds; rest >= 10; rest /= 10)
        ++integer_digits;
    const int decimals = std::clamp(kTimeColumn - 1 - integer_digits, 0, 6);
    // Written backwards into a small buffer, then right-aligned in the column.
    char text[32];
    char* end = text + sizeof text;
    char* start = end;
    if (decimals > 0) {
        std::uint64_t fraction = magnitude % 1'000'000'000;
        for (int i = decimals; i < 9; ++i)
            fraction /= 10;
        start = text_detail::write_decimal_backwards(end, fraction);
        while (end - start < decimals)
            *--start = '0';
        *--start = '.';
    }
    start = text_detail::write_decimal_backwards(start, seconds);
    if (negative) *--start = '-';
    append_right(b, std::string_view(start, static_cast<std::size_t>(end - start)), kTimeColumn);
    b.push_back(' ');
}

}  // namespace

void append_telegram_columns(TextBuffer& b, const DecodedTelegram& t,
                             std::span<const Finding> findings) {
    render_text_columns(b, t);
    if (!t.problems().empty()) {
        append(b, " [");
        bool first = true;
        for (const Problem& p : t.problems()) {
            if (!first) b.push_back(',');
            append(b, problem_kind_name(p.kind));
            first = false;
        }
        append(b, "]");
    }
    for (const Finding& f : findings)
        put(b, " [", severity_name(f.severity), ' ', finding_kind_name(f.kind), ']');
}

namespace {

class TextRenderer final : public TelegramRenderer {
  public:
    using TelegramRenderer::TelegramRenderer;

    void pass_over(const DecodedTelegram& t) override {
        if (first_time_ == kNoTime && t.has_time()) first_time_ = t.time_ns;
    }

    void render(const DecodedTelegram& t, std::span<const Finding> findings) override {
        TextBuffer& b = out_.buffer();
        append_decimal_right(b, t.frame, 6);
        b.push_back(' ');
        if (t.has_time()) {
            if (first_time_ == kNoTime) first_time_ = t.time_ns;
            append_relative_time(b, t.time_ns - first_time_);
        } else {
            append(b, "           - ");
        }
        append_telegram_columns(b, t, findings);
        b.push_back('\n');
        out_.end_record();
    }

    void render_end_findings(std::span<const Finding> findings) override {
        for (const Finding& f : findings)
            fmt::format_to(fmt::appender(out_.buffer()),
                           FMT_COMPILE("     - end of capture [{} {}] {}\n"),
                           severity_name(f.severity), finding_kind_name(f.kind), f.message);
        out_.end_record();
    }

  private:
    std::int64_t first_time_ = kNoTime;
};

}  // namespace

std::unique_ptr<TelegramRenderer> make_text_renderer(Output& out) {
    return std::make_unique<TextRenderer>(out);
}

}  // namespace dpscope
