// Telegram renderers: text (one summary line a telegram, like tshark), verbose (the whole field
// tree), jsonl (one JSON object a telegram; schema in docs/formats.md) and csv.
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <string_view>

#include "core/finding.hpp"
#include "formats/output.hpp"
#include "protocols/profibus/bus_decoder.hpp"

namespace dpscope {

enum class OutputFormat { Text, Verbose, Jsonl, Csv };

std::string_view output_format_name(OutputFormat format);  // "text", "verbose", "jsonl", "csv"
std::optional<OutputFormat> output_format_from_name(std::string_view name);

class TelegramRenderer {
  public:
    explicit TelegramRenderer(Output& out) : out_(out) {}
    virtual ~TelegramRenderer() = default;
    TelegramRenderer(const TelegramRenderer&) = delete;
    TelegramRenderer& operator=(const TelegramRenderer&) = delete;

    virtual void begin() {}
    // `findings`: what the session tracker found on this telegram (may be empty).
    virtual void render(const DecodedTelegram& telegram, std::span<const Finding> findings) = 0;
    // A telegram filtered out: not shown, but times stay relative to the capture's first.
    virtual void pass_over(const DecodedTelegram& /*telegram*/) {}
    // Findings only known at the end of the capture (time-outs still open then).
    virtual void render_end_findings(std::span<const Finding> /*findings*/) {}
    virtual void end() {}

  protected:
    Output& out_;
};

std::unique_ptr<TelegramRenderer> make_renderer(OutputFormat format, Output& out);

std::unique_ptr<TelegramRenderer> make_text_renderer(Output& out);
std::unique_ptr<TelegramRenderer> make_verbose_renderer(Output& out);
std::unique_ptr<TelegramRenderer> make_jsonl_renderer(Output& out);
std::unique_ptr<TelegramRenderer> make_csv_renderer(Output& out);

}  // namespace dpscope
