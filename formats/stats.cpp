#include "formats/stats.hpp"

namespace dpscope {

std::string_view stats_format_name(StatsFormat format) {
    switch (format) {
        case StatsFormat::Json: return "json";
        case StatsFormat::Markdown: return "markdown";
        case StatsFormat::Html: return "html";
        case StatsFormat::Csv: return "csv";
        case StatsFormat::Text: break;
    }
    return "text";
}

std::optional<StatsFormat> stats_format_from_name(std::string_view name) {
    for (StatsFormat f : {StatsFormat::Text, StatsFormat::Json, StatsFormat::Markdown,
                          StatsFormat::Html, StatsFormat::Csv})
        if (stats_format_name(f) == name) return f;
    return std::nullopt;
}

// Foundation only: formats are written by the formats work (issue 12).
void render_stats(StatsFormat, const StatsContext& context, Output& out) {
    if (context.health == nullptr) return;
    out.buffer().append(std::string_view("stats\n"));
}

void render_live_table(const BusHealth&, Output&, unsigned) {}

}  // namespace dpscope
