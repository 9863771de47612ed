#include "protocols/toybus/toybus_tracker.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>

#include "core/finding_list.hpp"

namespace dpscope {

namespace {

constexpr FindingKind kToybusKinds[] = {
    FindingKind::StackedRequest,     FindingKind::OrphanResponse,
    FindingKind::MismatchedResponse, FindingKind::UnexpectedResponseType,
    FindingKind::ResponseTimeout,    FindingKind::RequestRejected,
    FindingKind::MalformedTelegram,
};

constexpr std::uint8_t kMaster = 0;  // the master has no address
// The VLT dialect's codes the toy's telegrams are given (core/code_tables.hpp).
constexpr std::uint8_t kRcRead = 1;      // request parameter value
constexpr std::uint8_t kRcWrite = 2;     // change parameter value (word)
constexpr std::uint8_t kRcValue = 1;     // transfer parameter value (word): answers 1 and 2
constexpr std::uint8_t kRcRejected = 7;  // request rejected, with its error number

// Every request is new, every response an answer, answered in the same exchange; no SPM bit.
ParameterChannelPolicy toybus_policy(const ToybusTrackerOptions& options) {
    ParameterChannelPolicy policy;
    policy.has_spm_bit = false;
    policy.response_lags_one_cycle = false;
    policy.cyclic_requests = false;
    policy.timeout_ns = options.timeout_ns;
    return policy;
}

std::uint8_t code_of(const ToybusTelegram& v) {
    switch (v.kind) {
        case ToybusKind::Read: return kRcRead;
        case ToybusKind::Write: return kRcWrite;
        case ToybusKind::Value: return kRcValue;
        case ToybusKind::Error: return kRcRejected;
        case ToybusKind::Unknown: break;
    }
    return 0;
}

}  // namespace

std::span<const FindingKind> toybus_finding_kinds() noexcept { return kToybusKinds; }

bool is_toybus_finding_kind(FindingKind kind) noexcept {
    return std::find(std::begin(kToybusKinds), std::end(kToybusKinds), kind) !=
           std::end(kToybusKinds);
}

ToybusTracker::ToybusTracker(ToybusTrackerOptions options)
    : options_(options), engine_(toybus_policy(options)) {}

ToybusTracker::~ToybusTracker() = default;

ToybusStationStats& ToybusTracker::station(std::uint8_t address) {
    const std::size_t key = address & 0x7Fu;
    if (index_[key] == 0) {
        auto st = std::make_unique<ToybusStationStats>();
        st->address = static_cast<std::uint8_t>(key);
        engine_.add_channel(kMaster, st->address, st->channel);
        stations_.push_back(std::move(st));
        index_[key] = static_cast<std::int32_t>(stations_.size());
    }
    return *stations_[static_cast<std::size_t>(index_[key] - 1)];
}

std::vector<const ToybusStationStats*> ToybusTracker::stations() const {
    std::vector<const ToybusStationStats*> out;
    for (const auto& st : stations_)
        out.push_back(st.get());
    std::sort(out.begin(), out.end(),
              [](const auto* a, const auto* b) { return a->address < b->address; });
    return out;
}

std::uint64_t ToybusTracker::transactions() const noexcept {
    std::uint64_t total = 0;
    for (const auto& st : stations_)
        total += st->channel.transactions.total();
    return total;
}

void ToybusTracker::count() {
    for (const Finding& f : current_) {
        const auto kind = static_cast<std::size_t>(f.kind);
        const auto severity = static_cast<std::size_t>(f.severity);
        if (f.has_stations) {
            ToybusStationStats& st = station(f.slave);
            ++st.findings[kind];
            ++st.findings_by_severity[kind][severity];
        } else {
            ++bus_.findings[kind];
            ++bus_.findings_by_severity[kind][severity];
        }
    }
}

std::span<const Finding> ToybusTracker::track(const DecodedTelegram& t) {
    current_.clear();
    completed_.clear();
    last_frame_ = t.frame;
    const ToybusTelegram& v = t.toybus;
    subject_pnu_ = v.has_parameter ? v.parameter : -1;
    if (t.has_time()) {
        now_ns_ = t.time_ns;
        engine_.advance(t.time_ns, t.frame, current_);
    }
    for (const Problem& p : t.problems()) {
        if (problem_severity(p.kind) != Severity::Error) continue;
        add_finding(current_, FindingKind::MalformedTelegram, t.frame, t.time_ns, 0, t.has_roles,
                    kMaster, t.slave)
            .message = fmt::format("{}: {}", problem_kind_name(p.kind), problem_message(p));
        if (t.has_roles) ++station(t.slave).damaged;
        count();
        return current_;
    }
    if (!t.has_roles) {
        count();
        return current_;
    }
    ToybusStationStats& st = station(t.slave);
    ++st.telegrams;
    switch (v.kind) {
        case ToybusKind::Read: ++st.reads; break;
        case ToybusKind::Write: ++st.writes; break;
        case ToybusKind::Value: ++st.values; break;
        case ToybusKind::Error: ++st.errors; break;
        case ToybusKind::Unknown: break;
    }
    ParameterChannelSample s;
    s.frame = t.frame;
    s.time_ns = t.time_ns;
    s.direction = t.direction;
    s.master = kMaster;
    s.slave = t.slave;
    s.dialect = Dialect::Vlt;
    s.cycle = st.telegrams;
    s.pcv.rc = code_of(v);
    s.pcv.pnu = v.parameter;
    s.pcv.pva = v.kind == ToybusKind::Error ? v.error : v.value;
    s.pcv.pca = static_cast<std::uint16_t>(s.pcv.rc << 12);
    if (auto done = engine_.track(s, current_)) completed_.push_back(*done);
    count();
    return current_;
}

std::span<const Finding> ToybusTracker::finish(std::int64_t end_ns) {
    current_.clear();
    completed_.clear();
    if (end_ns != kNoTime && (now_ns_ == kNoTime || end_ns > now_ns_)) now_ns_ = end_ns;
    if (now_ns_ != kNoTime) engine_.advance(now_ns_, last_frame_, current_);
    count();
    return current_;
}

}  // namespace dpscope
