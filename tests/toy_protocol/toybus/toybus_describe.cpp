#include "protocols/toybus/toybus_describe.hpp"

#include <iterator>

namespace dpscope {

std::string_view toybus_kind_name(ToybusKind kind) noexcept {
    switch (kind) {
        case ToybusKind::Read: return "read";
        case ToybusKind::Write: return "write";
        case ToybusKind::Value: return "value";
        case ToybusKind::Error: return "error";
        case ToybusKind::Unknown: break;
    }
    return "unknown";
}

std::string toybus_kind_text(const ToybusTelegram& v) {
    constexpr char kLeads[] = {'?', '!', '=', '#', '-'};
    return fmt::format("{} {}", kLeads[static_cast<std::size_t>(v.kind)], toybus_kind_name(v.kind));
}

void append_toybus_detail(TextBuffer& out, const DecodedTelegram& t) {
    const ToybusTelegram& v = t.toybus;
    auto it = std::back_inserter(out);
    if (!v.has_parameter) {
        append(out, "-");
        return;
    }
    fmt::format_to(it, "parameter {:04}", v.parameter);
    if (v.has_value) fmt::format_to(it, " = {:05}", v.value);
    if (v.has_error) fmt::format_to(it, " error {:02}", v.error);
    if (t.request_frame != 0) fmt::format_to(it, " (answers frame {})", t.request_frame);
}

}  // namespace dpscope
