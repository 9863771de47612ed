#include "filter/display_filter.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <limits>
#include <optional>

#include "core/protocol_descriptor.hpp"

namespace dpscope {

// ---- the fields every bus has ----------------------------------------------------------------

namespace {

bool masters_addressed(const FilterInput& in) noexcept {
    return protocol_descriptor(in.t.protocol).masters_addressed;
}

const std::array<FilterField, 14> kCommonFields{{
    {"frame.number", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) { return visit_integer(v, in.t.frame); },
     "the record's number in the capture (1-based)"},
    {"dpscope.bus", FilterType::Text,
     [](const FilterInput& in, const FilterVisitor& v) {
         return visit_text(v, protocol_name(in.t.protocol));
     },
     "\"profibus\", \"fc\" or \"vlt2000\""},
    {"dpscope.direction", FilterType::Text,
     [](const FilterInput& in, const FilterVisitor& v) {
         return visit_text(v, in.t.direction == Direction::Request ? "request" : "response");
     },
     "\"request\" or \"response\""},
    {"dpscope.master", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         return in.t.has_roles && masters_addressed(in) && visit_integer(v, in.t.master);
     },
     "the master's address (PROFIBUS)"},
    {"dpscope.slave", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         return in.t.has_roles && visit_integer(v, in.t.slave);
     },
     "the slave's (drive's) address"},
    {"dpscope.station", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         const bool masters = masters_addressed(in);
         if (in.t.has_roles) {
             if (masters && visit_integer(v, in.t.master & 0x7F)) return true;
             if (visit_integer(v, in.t.slave & 0x7F)) return true;
         }
         // A finding about a station (the FC and VLT 2000 masters have no address: a finding
         // is about its drive).
         for (const Finding& f : in.findings)
             if (f.has_stations &&
                 ((masters && visit_integer(v, f.master)) || visit_integer(v, f.slave)))
                 return true;
         return false;
     },
     "each station the telegram is to or from, and each one a finding on it is about"},
    {"dpscope.finding", FilterType::Text,
     [](const FilterInput& in, const FilterVisitor& v) {
         for (const Finding& f : in.findings)
             if (visit_text(v, finding_kind_name(f.kind))) return true;
         return false;
     },
     "each finding's kind: \"stacked_request\", \"orphan_response\", ... (docs/findings)"},
    {"dpscope.finding.severity", FilterType::Text,
     [](const FilterInput& in, const FilterVisitor& v) {
         for (const Finding& f : in.findings)
             if (visit_text(v, severity_name(f.severity))) return true;
         return false;
     },
     "each finding's severity: \"error\", \"warning\", \"note\""},
    {"dpscope.finding.pnu", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         for (const Finding& f : in.findings)
             if (f.pnu && visit_integer(v, *f.pnu)) return true;
         return false;
     },
     "each PNU a finding on the telegram is about"},
    {"dpscope.problem", FilterType::Text,
     [](const FilterInput& in, const FilterVisitor& v) {
         for (const Problem& p : in.t.problems())
             if (visit_text(v, problem_kind_name(p.kind))) return true;
         return false;
     },
     "each problem the decoder found in the telegram: \"fcs_mismatch\", \"truncated\", ..."},
    {"dpscope.pnu", FilterType::Integer,
     [](const FilterInput&, const FilterVisitor&) { return false; },  // each bus's own
     "the parameters the telegram is about (each bus says which; see the bus's fields)"},
    {"health.event", FilterType::Text,
     [](const FilterInput& in, const FilterVisitor& v) {
         for (const FilterEvent& e : in.events)
             if (visit_text(v, e.event)) return true;
         return false;
     },
     "each bus-health event the telegram caused: \"station_lost\", \"station_returned\", "
     "\"verdict_bad\" (PROFIBUS)"},
    {"health.verdict", FilterType::Text,
     [](const FilterInput& in, const FilterVisitor& v) {
         for (const FilterEvent& e : in.events)
             if (!e.verdict.empty() && visit_text(v, e.verdict)) return true;
         return false;
     },
     "the verdict a health event the telegram caused gave: \"bad\""},
    {"health.station", FilterType::Integer,
     [](const FilterInput& in, const FilterVisitor& v) {
         for (const FilterEvent& e : in.events)
             if (visit_integer(v, e.station)) return true;
         return false;
     },
     "the station of each health event the telegram caused (255: the segment)"},
}};

}  // namespace

std::span<const FilterField> common_filter_fields() noexcept { return kCommonFields; }

std::vector<const FilterField*> filter_fields_named(std::string_view name) {
    std::vector<const FilterField*> found;
    for (const FilterField& f : common_filter_fields())
        if (f.name == name) found.push_back(&f);
    for (const ProtocolDescriptor* protocol : protocol_table())
        for (const FilterField& f : protocol->filter_fields)
            if (f.name == name) found.push_back(&f);
    return found;
}

std::vector<std::string_view> filter_field_names() {
    std::vector<std::string_view> names;
    for (const FilterField& f : common_filter_fields())
        names.push_back(f.name);
    for (const ProtocolDescriptor* protocol : protocol_table())
        for (const FilterField& f : protocol->filter_fields)
            names.push_back(f.name);
    std::sort(names.begin(), names.end());
    names.erase(std::unique(names.begin(), names.end()), names.end());
    return names;
}

// ---- the tree ----------------------------------------------------------------------------------

// ---- the parser --------------------------------------------------------------------------------

class FilterParser {
  public:
    explicit FilterParser(std::string_view text) : text_(text) {
        filter_.text_ = std::string(text);
    }

    Result<DisplayFilter> parse() {
        skip_blanks();
        if (at_ == text_.size()) return fail("an empty filter: write a field and a comparison");
        Result<std::size_t> root = parse_or();
        if (!root) return Error{root.error()};
        skip_blanks();
        if (at_ != text_.size())
            return fail(
                fmt::format("'{}' after a whole expression: join with && or ||", word_here()));
        filter_.root_ = *root;
        return std::move(filter_);
    }

  private:
    using Node = DisplayFilter::Node;
    using Literal = DisplayFilter::Literal;

    Error fail(std::string_view what, std::size_t column_at) const {
        return Error{fmt::format("column {}: {}", column_at + 1, what)};
    }
    Error fail(std::string_view what) const { return fail(what, at_); }

    void skip_blanks() {
        while (at_ < text_.size() && (text_[at_] == ' ' || text_[at_] == '\t' ||
                                      text_[at_] == '\n' || text_[at_] == '\r'))
            ++at_;
    }
    bool starts(std::string_view s) const { return text_.substr(at_).starts_with(s); }
    static bool word_char(char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
               c == '_' || c == '.' || c == '-';
    }
    // A keyword (`and`, `in`) here, followed by no word character.
    bool keyword(std::string_view k) const {
        return starts(k) && (at_ + k.size() == text_.size() || !word_char(text_[at_ + k.size()]));
    }
    std::string word_here() const {
        std::size_t end = at_;
        while (end < text_.size() && end - at_ < 20 && text_[end] != ' ')
            ++end;
        return std::string(text_.substr(at_, std::max<std::size_t>(1, end - at_)));
    }

    std::size_t add(Node node) {
        filter_.nodes_.push_back(node);
        return filter_.nodes_.size() - 1;
    }

    Result<std::size_t> parse_or() {
        Result<std::size_t> left = parse_and();
        if (!left) return left;
        for (;;) {
            skip_blanks();
            if (starts("||"))
                at_ += 2;
            else if (keyword("or"))
                at_ += 2;
            else
                return left;
            Result<std::size_t> right = parse_and();
            if (!right) return right;
            Node n;
            n.kind = Node::Kind::Or;
            n.left = *left;
            n.right = *right;
            left = add(n);
        }
    }

    Result<std::size_t> parse_and() {
        Result<std::size_t> left = parse_unary();
        if (!left) return left;
        for (;;) {
            skip_blanks();
            if (starts("&&"))
                at_ += 2;
            else if (keyword("and"))
                at_ += 3;
            else
                return left;
            Result<std::size_t> right = parse_unary();
            if (!right) return right;
            Node n;
            n.kind = Node::Kind::And;
            n.left = *left;
            n.right = *right;
            left = add(n);
        }
    }

    Result<std::size_t> parse_unary() {
        if (++depth_ > kMaxDepth) return fail("nested too deep (at most 64 levels)");
        skip_blanks();
        Result<std::size_t> result = [&]() -> Result<std::size_t> {
            if (starts("!") && !starts("!=")) {
                ++at_;
            } else if (keyword("not")) {
                at_ += 3;
            } else {
                return parse_primary();
            }
            Result<std::size_t> operand = parse_unary();
            if (!operand) return operand;
            Node n;
            n.kind = Node::Kind::Not;
            n.left = *operand;
            return add(n);
        }();
        --depth_;
        return result;
    }

    Result<std::size_t> parse_primary() {
        skip_blanks();
        if (at_ == text_.size()) return fail("the expression ends where a field was expected");
        if (text_[at_] == '(') {
            const std::size_t open = at_;
            ++at_;
            Result<std::size_t> inner = parse_or();
            if (!inner) return inner;
            skip_blanks();
            if (at_ == text_.size() || text_[at_] != ')') return fail("'(' is not closed", open);
            ++at_;
            return inner;
        }
        return parse_test();
    }

    Result<std::size_t> parse_test() {
        const std::size_t field_at = at_;
        std::size_t end = at_;
        while (end < text_.size() && word_char(text_[end]))
            ++end;
        if (end == at_)
            return fail(
                fmt::format("'{}' where a field was expected (a name such as "
                            "dpscope.pcv.rc)",
                            word_here()));
        const std::string_view name = text_.substr(at_, end - at_);
        std::vector<const FilterField*> fields = filter_fields_named(name);
        if (fields.empty())
            return fail(fmt::format("no field '{}' (dpscope filter --fields lists them)", name),
                        field_at);
        at_ = end;
        Node n;
        n.kind = Node::Kind::Test;
        n.type = fields.front()->type;
        n.field_first = filter_.fields_.size();
        n.field_count = fields.size();
        filter_.fields_.insert(filter_.fields_.end(), fields.begin(), fields.end());
        skip_blanks();
        static constexpr std::pair<std::string_view, FilterOp> kOps[] = {
            {"==", FilterOp::Eq}, {"!=", FilterOp::Ne}, {"<=", FilterOp::Le},
            {">=", FilterOp::Ge}, {"<", FilterOp::Lt},  {">", FilterOp::Gt},
        };
        static constexpr std::pair<std::string_view, FilterOp> kWords[] = {
            {"eq", FilterOp::Eq},
            {"ne", FilterOp::Ne},
            {"le", FilterOp::Le},
            {"ge", FilterOp::Ge},
            {"lt", FilterOp::Lt},
            {"gt", FilterOp::Gt},
            {"contains", FilterOp::Contains},
            {"in", FilterOp::In},
        };
        n.op = FilterOp::Exists;
        for (const auto& [symbol, op] : kOps)
            if (starts(symbol)) {
                n.op = op;
                at_ += symbol.size();
                break;
            }
        if (n.op == FilterOp::Exists)
            for (const auto& [word, op] : kWords)
                if (keyword(word)) {
                    n.op = op;
                    at_ += word.size();
                    break;
                }
        if (n.op == FilterOp::Exists) return add(n);  // a field alone: present
        if (n.op == FilterOp::Contains && n.type != FilterType::Text)
            return fail(fmt::format("'contains' compares text; {} is a number", name), field_at);
        skip_blanks();
        n.literal_first = filter_.literals_.size();
        if (n.op == FilterOp::In) {
            Result<std::size_t> count = parse_set(n.type, name);
            if (!count) return Error{count.error()};
            n.literal_count = *count;
        } else {
            Result<Literal> value = parse_literal(n.type, name, false);
            if (!value) return Error{value.error()};
            filter_.literals_.push_back(std::move(*value));
            n.literal_count = 1;
        }
        return add(n);
    }

    Result<std::size_t> parse_set(FilterType type, std::string_view field) {
        if (at_ == text_.size() || text_[at_] != '{')
            return fail("'in' takes a set: {1 2 3}, {\"a\", \"b\"}, {1..5}");
        const std::size_t open = at_;
        ++at_;
        std::size_t count = 0;
        for (;;) {
            skip_blanks();
            if (at_ == text_.size()) return fail("'{' is not closed", open);
            if (text_[at_] == '}') {
                ++at_;
                break;
            }
            if (text_[at_] == ',' && count > 0) {
                ++at_;
                continue;
            }
            if (count == kMaxSetItems) return fail("a set of more than 1024 items");
            Result<Literal> item = parse_literal(type, field, true);
            if (!item) return Error{item.error()};
            filter_.literals_.push_back(std::move(*item));
            ++count;
        }
        if (count == 0) return fail("an empty set", open);
        return count;
    }

    Result<Literal> parse_literal(FilterType type, std::string_view field, bool in_set) {
        if (at_ == text_.size())
            return fail(
                fmt::format("the expression ends where a value for {} was expected", field));
        const std::size_t value_at = at_;
        Literal literal;
        if (text_[at_] == '"') {
            ++at_;
            std::string value;
            for (;;) {
                if (at_ == text_.size()) return fail("a string is not closed", value_at);
                const char c = text_[at_++];
                if (c == '"') break;
                if (c == '\\') {
                    if (at_ == text_.size()) return fail("a string is not closed", value_at);
                    value.push_back(text_[at_++]);
                    continue;
                }
                value.push_back(c);
            }
            if (type != FilterType::Text)
                return fail(fmt::format("{} is a number, not text", field), value_at);
            literal.is_text = true;
            literal.text = std::move(value);
            return literal;
        }
        std::size_t end = at_;
        while (end < text_.size() && (word_char(text_[end]) || text_[end] == '+'))
            ++end;
        std::string_view word = text_.substr(at_, end - at_);
        if (word.empty())
            return fail(fmt::format("'{}' where a value for {} was expected", word_here(), field));
        if (type == FilterType::Text) {
            // A bare word is text (stacked_request), as Wireshark reads one.
            at_ = end;
            literal.is_text = true;
            literal.text = std::string(word);
            return literal;
        }
        if (word == "true" || word == "false") {
            at_ = end;
            literal.low = literal.high = word == "true" ? 1 : 0;
            return literal;
        }
        const std::size_t dots = in_set ? word.find("..") : std::string_view::npos;
        const std::string_view first = word.substr(0, dots);
        std::optional<std::int64_t> low = number(first);
        if (!low) return fail(fmt::format("'{}' is no number for {}", first, field), value_at);
        literal.low = literal.high = *low;
        if (dots != std::string_view::npos) {
            const std::string_view last = word.substr(dots + 2);
            std::optional<std::int64_t> high = number(last);
            if (!high)
                return fail(fmt::format("'{}' is no number for {}", last, field),
                            value_at + dots + 2);
            if (*high < *low)
                return fail(fmt::format("the range {} ends before it starts", word), value_at);
            literal.high = *high;
        }
        at_ = end;
        return literal;
    }

    // A whole number: decimal (a sign allowed) or 0x hexadecimal.
    static std::optional<std::int64_t> number(std::string_view s) {
        bool negative = false;
        if (!s.empty() && (s.front() == '-' || s.front() == '+')) {
            negative = s.front() == '-';
            s.remove_prefix(1);
        }
        int base = 10;
        if (s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X')) {
            base = 16;
            s.remove_prefix(2);
        }
        if (s.empty()) return std::nullopt;
        std::uint64_t value = 0;
        const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), value, base);
        if (error != std::errc{} || end != s.data() + s.size() ||
            value > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
            return std::nullopt;
        const auto v = static_cast<std::int64_t>(value);
        return negative ? -v : v;
    }

    static constexpr int kMaxDepth = 64;
    static constexpr std::size_t kMaxSetItems = 1024;
    std::string_view text_;
    std::size_t at_ = 0;
    int depth_ = 0;
    DisplayFilter filter_;
};

Result<DisplayFilter> DisplayFilter::parse(std::string_view text) {
    if (text.size() > 65536) return Error{"column 1: a filter of more than 64 KiB"};
    return FilterParser(text).parse();
}

// ---- evaluation --------------------------------------------------------------------------------

namespace {

bool compare(FilterOp op, FilterType type, const FilterValue& value,
             const DisplayFilter::Literal& literal) noexcept {
    if (type == FilterType::Text) {
        const std::string_view l = literal.text;
        switch (op) {
            case FilterOp::Eq:
            case FilterOp::In: return value.text == l;
            case FilterOp::Ne: return value.text != l;
            case FilterOp::Lt: return value.text < l;
            case FilterOp::Le: return value.text <= l;
            case FilterOp::Gt: return value.text > l;
            case FilterOp::Ge: return value.text >= l;
            case FilterOp::Contains: return value.text.find(l) != std::string_view::npos;
            case FilterOp::Exists: return true;
        }
        return false;
    }
    const std::int64_t v = value.integer;
    switch (op) {
        case FilterOp::Eq: return v == literal.low;
        case FilterOp::In: return v >= literal.low && v <= literal.high;
        case FilterOp::Ne: return v != literal.low;
        case FilterOp::Lt: return v < literal.low;
        case FilterOp::Le: return v <= literal.low;
        case FilterOp::Gt: return v > literal.low;
        case FilterOp::Ge: return v >= literal.low;
        case FilterOp::Contains: return false;
        case FilterOp::Exists: return true;
    }
    return false;
}

// Stops at the first value that satisfies the test (for != : the first that equals, which
// makes the test fail).
class TestVisitor final : public FilterVisitor {
  public:
    TestVisitor(FilterOp op, FilterType type, std::span<const DisplayFilter::Literal> literals)
        : op_(op), type_(type), literals_(literals) {}
    bool visit(const FilterValue& value) const override {
        seen_ = true;
        if (op_ == FilterOp::Exists) return true;
        if (op_ == FilterOp::Ne) return !compare(op_, type_, value, literals_.front());
        for (const DisplayFilter::Literal& l : literals_)
            if (compare(op_, type_, value, l)) return true;
        return false;
    }
    bool seen() const noexcept { return seen_; }

  private:
    FilterOp op_;
    FilterType type_;
    std::span<const DisplayFilter::Literal> literals_;
    mutable bool seen_ = false;
};

}  // namespace

bool DisplayFilter::evaluate(std::size_t index, const FilterInput& in) const noexcept {
    const Node& n = nodes_[index];
    switch (n.kind) {
        case Node::Kind::Or: return evaluate(n.left, in) || evaluate(n.right, in);
        case Node::Kind::And: return evaluate(n.left, in) && evaluate(n.right, in);
        case Node::Kind::Not: return !evaluate(n.left, in);
        case Node::Kind::Test: break;
    }
    const std::span<const Literal> literals{literals_.data() + n.literal_first, n.literal_count};
    TestVisitor visitor(n.op, n.type, literals);
    bool stopped = false;
    for (std::size_t f = n.field_first; f < n.field_first + n.field_count && !stopped; ++f)
        stopped = fields_[f]->values(in, visitor);
    // != holds when the field has a value and none of them equals the literal.
    if (n.op == FilterOp::Ne) return visitor.seen() && !stopped;
    return stopped;
}

bool DisplayFilter::reads(std::string_view prefix) const noexcept {
    return std::any_of(fields_.begin(), fields_.end(),
                       [&](const FilterField* f) { return f->name.starts_with(prefix); });
}

bool DisplayFilter::matches(const FilterInput& in) const noexcept {
    return nodes_.empty() || evaluate(root_, in);
}

namespace {

// Sets the bit of every value of `fields` on the input that is a bit of `seen`.
template <std::size_t Bits>
void mark_values(std::span<const FilterField* const> fields, const FilterInput& in,
                 std::bitset<Bits>& seen) {
    class Marker final : public FilterVisitor {
      public:
        explicit Marker(std::bitset<Bits>& seen) : seen_(seen) {}
        bool visit(const FilterValue& value) const override {
            if (value.integer >= 0 && value.integer < static_cast<std::int64_t>(Bits))
                seen_.set(static_cast<std::size_t>(value.integer));
            return false;  // every value
        }

      private:
        std::bitset<Bits>& seen_;
    };
    const Marker marker(seen);
    for (const FilterField* field : fields)
        field->values(in, marker);
}

}  // namespace

void mark_telegram_pnus(const FilterInput& in, PnuSet& seen) {
    static const std::vector<const FilterField*> fields = filter_fields_named("dpscope.pnu");
    mark_values(fields, in, seen);
}

void mark_telegram_stations(const FilterInput& in, std::bitset<kStationCount>& seen) {
    static const std::vector<const FilterField*> fields = filter_fields_named("dpscope.station");
    mark_values(fields, in, seen);
}

std::string station_filter_text(std::span<const std::uint8_t> stations) {
    if (stations.empty()) return {};
    std::string set;
    for (std::uint8_t s : stations)
        set += fmt::format("{}{}", set.empty() ? "" : " ", s);
    return fmt::format("dpscope.station in {{{}}}", set);
}

std::string pnu_filter_text(std::span<const std::uint16_t> pnus) {
    if (pnus.empty()) return {};
    std::string set;
    for (std::uint16_t p : pnus)
        set += fmt::format("{}{}", set.empty() ? "" : " ", p);
    return fmt::format("dpscope.pnu in {{{0}}} || dpscope.finding.pnu in {{{0}}}", set);
}

}  // namespace dpscope
