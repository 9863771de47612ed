#include "formats/report.hpp"

#include "formats/report_model.hpp"

namespace dpscope {

std::string_view report_format_name(ReportFormat format) {
    switch (format) {
        case ReportFormat::Text: return "text";
        case ReportFormat::Json: return "json";
        case ReportFormat::Markdown: return "markdown";
        case ReportFormat::Html: return "html";
        case ReportFormat::Junit: return "junit";
    }
    return "text";
}

std::optional<ReportFormat> report_format_from_name(std::string_view name) {
    for (ReportFormat format : {ReportFormat::Text, ReportFormat::Json, ReportFormat::Markdown,
                                ReportFormat::Html, ReportFormat::Junit})
        if (report_format_name(format) == name) return format;
    return std::nullopt;
}

std::string_view fail_on_name(FailOn fail_on) {
    switch (fail_on) {
        case FailOn::Error: return "error";
        case FailOn::Warning: return "warning";
        case FailOn::Never: return "never";
    }
    return "error";
}

std::optional<FailOn> fail_on_from_name(std::string_view name) {
    for (FailOn f : {FailOn::Error, FailOn::Warning, FailOn::Never})
        if (fail_on_name(f) == name) return f;
    return std::nullopt;
}

bool severity_fails(Severity severity, FailOn fail_on) noexcept {
    switch (fail_on) {
        case FailOn::Error: return severity == Severity::Error;
        case FailOn::Warning: return severity != Severity::Note;
        case FailOn::Never: return false;
    }
    return false;
}

bool report_fails(const ReportContext& context) {
    return report::build_report_model(context).fails;
}

bool render_report(ReportFormat format, const ReportContext& context, Output& out) {
    const report::ReportModel model = report::build_report_model(context);
    switch (format) {
        case ReportFormat::Text: report::write_text(context, model, out); break;
        case ReportFormat::Json: report::write_json(context, model, out); break;
        case ReportFormat::Markdown: report::write_markdown(context, model, out); break;
        case ReportFormat::Html: report::write_html(context, model, out); break;
        case ReportFormat::Junit: report::write_junit(context, model, out); break;
    }
    return model.fails;
}

}  // namespace dpscope
