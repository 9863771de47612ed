#include "formats/report_markup.hpp"

#include <iterator>

namespace dpscope::report {

std::string md_escape(std::string_view text) {
    std::string out;
    for (char ch : text) {
        if (ch == '\\' || ch == '|' || ch == '*' || ch == '_' || ch == '`' || ch == '<' ||
            ch == '>')
            out += '\\';
        out += ch;
    }
    return out;
}

void escape_xml(TextBuffer& b, std::string_view text) {
    for (char ch : text) {
        switch (ch) {
            case '&': append(b, "&amp;"); break;
            case '<': append(b, "&lt;"); break;
            case '>': append(b, "&gt;"); break;
            case '"': append(b, "&quot;"); break;
            case '\'': append(b, "&#39;"); break;
            default: b.push_back(ch);
        }
    }
}

std::string xml(std::string_view text) {
    TextBuffer b;
    escape_xml(b, text);
    return fmt::to_string(b);
}

void html_kv(TextBuffer& b, std::string_view key, std::string_view value) {
    append(b, "<tr><th>");
    escape_xml(b, key);
    append(b, "</th><td>");
    escape_xml(b, value);
    append(b, "</td></tr>\n");
}

std::array<std::uint64_t, 3> severity_totals(const FindingCounts& findings,
                                             const FindingSeverityCounts& by_severity) {
    std::array<std::uint64_t, 3> totals{};
    for (FindingKind kind : kAllKinds)
        if (findings[static_cast<std::size_t>(kind)])
            for (std::size_t level = 0; level < totals.size(); ++level)
                totals[level] += by_severity[static_cast<std::size_t>(kind)][level];
    return totals;
}

void html_findings_by_kind(TextBuffer& b, const FindingCounts& findings,
                           const FindingSeverityCounts& by_severity) {
    append(b, "<h3>Findings by kind</h3>\n");
    bool any = false;
    for (FindingKind kind : kAllKinds)
        any |= findings[static_cast<std::size_t>(kind)] > 0;
    if (!any) {
        append(b, "<p class=\"meta\">None.</p>\n");
        return;
    }
    append(b,
           "<table class=\"kinds\"><tr><th>kind</th><th>severity</th><th "
           "class=\"n\">count</th></tr>\n");
    for (FindingKind kind : kAllKinds) {
        if (!findings[static_cast<std::size_t>(kind)]) continue;
        for (Severity level : {Severity::Error, Severity::Warning, Severity::Note}) {
            std::uint64_t n =
                by_severity[static_cast<std::size_t>(kind)][static_cast<std::size_t>(level)];
            if (!n) continue;
            std::string_view severity = severity_name(level);
            fmt::format_to(std::back_inserter(b),
                           "<tr class=\"{}\"><td>{}</td><td class=\"{}\">{}</td><td "
                           "class=\"n\">{}</td></tr>\n",
                           severity, finding_kind_name(kind), severity, severity, n);
        }
    }
    append(b, "</table>\n");
}

}  // namespace dpscope::report
