#include "formats/renderer.hpp"

namespace dpscope {

std::string_view output_format_name(OutputFormat format) {
    switch (format) {
        case OutputFormat::Text: return "text";
        case OutputFormat::Verbose: return "verbose";
        case OutputFormat::Jsonl: return "jsonl";
        case OutputFormat::Csv: return "csv";
    }
    return "text";
}

std::optional<OutputFormat> output_format_from_name(std::string_view name) {
    for (OutputFormat format :
         {OutputFormat::Text, OutputFormat::Verbose, OutputFormat::Jsonl, OutputFormat::Csv})
        if (output_format_name(format) == name) return format;
    return std::nullopt;
}

std::unique_ptr<TelegramRenderer> make_renderer(OutputFormat format, Output& out) {
    switch (format) {
        case OutputFormat::Text: return make_text_renderer(out);
        case OutputFormat::Verbose: return make_verbose_renderer(out);
        case OutputFormat::Jsonl: return make_jsonl_renderer(out);
        case OutputFormat::Csv: return make_csv_renderer(out);
    }
    return make_text_renderer(out);
}

}  // namespace dpscope
