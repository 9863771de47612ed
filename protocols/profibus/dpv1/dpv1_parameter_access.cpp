#include "protocols/profibus/dpv1/dpv1_parameter_access.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>
#include <optional>
#include <string>

#include "core/counted.hpp"

namespace dpscope {

namespace {

constexpr std::int64_t kNever = std::numeric_limits<std::int64_t>::max();
// A message names at most this many parameters.
constexpr std::size_t kNamedPnus = 8;
// A Danfoss parameter request names at most 0x25 parameters [S003].
constexpr std::uint8_t kMaxDanfossParameters = 0x25;

std::string function_text(std::uint8_t function) {
    std::string_view name = dpv1_function_name(function);
    return name.empty() ? fmt::format("function 0x{:02X}", function) : std::string(name);
}

// "PNU 12" or "PNUs 12, 20, 30"; "" without addresses.
std::string pnus_text(const std::vector<ProfidriveAddress>& addresses) {
    if (addresses.empty()) return {};
    std::string text = addresses.size() == 1 ? "PNU " : "PNUs ";
    for (std::size_t i = 0; i < addresses.size() && i < kNamedPnus; ++i)
        fmt::format_to(std::back_inserter(text), "{}{}", i ? ", " : "", addresses[i].pnu);
    if (addresses.size() > kNamedPnus) text += ", ...";
    return text;
}

// "reference 5, request parameter value, PNU 12".
std::string request_text(std::uint8_t reference, std::uint8_t id,
                         const std::vector<ProfidriveAddress>& addresses) {
    std::string_view name = profidrive_request_id_name(id);
    std::string text =
        fmt::format("reference {}, {}", reference,
                    name.empty() ? fmt::format("request ID 0x{:02X}", id) : std::string(name));
    std::string pnus = pnus_text(addresses);
    if (!pnus.empty()) text += ", " + pnus;
    return text;
}

std::string response_id_text(std::uint8_t id) {
    std::string_view name = profidrive_response_id_name(id);
    return name.empty() ? fmt::format("0x{:02X}", id) : fmt::format("0x{:02X} ({})", id, name);
}

// Formats whose number of values is a length in bytes, not a number of array elements.
bool counts_bytes(std::uint8_t format) { return format == 0x09 || format == 0x0A; }

// Collects the inconsistencies of one telegram into one message.
struct Inconsistencies {
    std::string text;
    template <typename... Args>
    void add(fmt::format_string<Args...> format, Args&&... args) {
        if (!text.empty()) text += "; ";
        fmt::format_to(std::back_inserter(text), format, std::forward<Args>(args)...);
    }
};

// The DP-V1 length byte against the data that follows it.
void check_dpv1_length(const Dpv1Pdu& pdu, Inconsistencies& found) {
    if (pdu.length != pdu.data.size())
        found.add("DP-V1 length {} but {}", pdu.length,
                  counted(pdu.data.size(), "data byte", "data bytes"));
}

}  // namespace

struct Dpv1ParameterAccessTracker::Transaction {
    enum class State : std::uint8_t { Written, Reading };
    bool active = false;
    std::uint8_t slot = 0;
    std::uint8_t index = 0;
    State state = State::Written;
    bool timed_out = false;
    bool change = false;
    std::uint64_t frame = 0;  // the Write
    std::int64_t time_ns = kNoTime;
    std::uint8_t dpv1_length = 0;
    std::uint8_t reference = 0;
    std::uint8_t id = 0;
    std::uint8_t axis = 0;
    std::uint8_t count = 0;
    std::vector<ProfidriveAddress> addresses;
    std::uint64_t polls = 0;

    std::optional<std::uint16_t> first_pnu() const {
        if (addresses.empty()) return std::nullopt;
        return addresses.front().pnu;
    }
};

struct Dpv1ParameterAccessTracker::Channel {
    std::uint8_t master = 0;
    std::uint8_t slave = 0;
    Dpv1Stats* stats = nullptr;
    // One per slot and index while active; closed ones are reused (their vectors keep their
    // capacity, so tracking stops allocating).
    std::vector<Transaction> open;
    // The last DP-V1 request still waiting for its DP-V1 response.
    bool awaiting = false;
    std::uint8_t function = 0;
    std::uint8_t slot = 0;
    std::uint8_t index = 0;
    std::uint8_t length = 0;  // a Read's: the most the master accepts
    std::uint64_t frame = 0;
    // A parameter request was written on the channel: before the first, a parameter response
    // may answer a request made before the capture, and is no orphan.
    bool written = false;

    Transaction* find(std::uint8_t slot_number, std::uint8_t index_number) {
        for (Transaction& tx : open)
            if (tx.active && tx.slot == slot_number && tx.index == index_number) return &tx;
        return nullptr;
    }
    Transaction& start() {
        for (Transaction& tx : open)
            if (!tx.active) {
                tx.active = true;
                return tx;
            }
        Transaction& tx = open.emplace_back();
        tx.active = true;
        return tx;
    }
    // Ends `tx`. One that timed out was counted then; any other is no longer open.
    void close(Transaction* tx) const {
        if (!tx->timed_out) --stats->open;
        tx->active = false;
    }
    Finding& add(FindingList& out, FindingKind kind, const DecodedTelegram& t,
                 std::uint64_t request_frame) const {
        return add_finding(out, kind, t.frame, t.time_ns, request_frame, true, master, slave);
    }
};

Dpv1ParameterAccessTracker::Dpv1ParameterAccessTracker(std::int64_t timeout_ns)
    : timeout_ns_(timeout_ns) {}

Dpv1ParameterAccessTracker::~Dpv1ParameterAccessTracker() = default;

void Dpv1ParameterAccessTracker::add_channel(std::uint8_t master, std::uint8_t slave,
                                             Dpv1Stats& stats) {
    if (index_.find(master, slave) != ChannelIndex::kNone) return;
    index_.set(master, slave, static_cast<std::int32_t>(channels_.size()));
    auto ch = std::make_unique<Channel>();
    ch->master = master & 0x7F;
    ch->slave = slave & 0x7F;
    ch->stats = &stats;
    channels_.push_back(std::move(ch));
}

void Dpv1ParameterAccessTracker::track(const DecodedTelegram& t, FindingList& out) {
    const Dpv1Pdu* pdu = t.dp.service_data.dpv1();
    if (!pdu || !t.has_roles) return;
    std::int32_t at = index_.find(t.master, t.slave);
    if (at < 0) return;
    Channel& ch = *channels_[static_cast<std::size_t>(at)];
    // An empty data unit is a poll at the link layer: no DP-V1 PDU, nothing to pair.
    if (pdu->layout == Dpv1Pdu::Layout::None) return;
    Dpv1Stats& stats = *ch.stats;
    ++stats.telegrams;
    stats.dialect = t.dp.dialect;
    if (t.has_time()) {
        if (stats.first_time_ns == kNoTime) stats.first_time_ns = t.time_ns;
        stats.last_time_ns = t.time_ns;
    }
    if (t.direction == Direction::Request)
        request(ch, t, *pdu, out);
    else
        response(ch, t, *pdu, out);
}

void Dpv1ParameterAccessTracker::request(Channel& ch, const DecodedTelegram& t, const Dpv1Pdu& pdu,
                                         FindingList& out) {
    if (pdu.layout != Dpv1Pdu::Layout::Addressed || !(pdu.is_read() || pdu.is_write())) return;
    ch.awaiting = true;
    ch.function = pdu.base_function();
    ch.slot = pdu.slot;
    ch.index = pdu.index;
    ch.length = pdu.length;
    ch.frame = t.frame;
    if (!pdu.is_write()) return;
    const ProfidriveMessage* request = t.dp.service_data.profidrive();
    if (request && request->has_header) write_request(ch, t, pdu, *request, out);
}

void Dpv1ParameterAccessTracker::write_request(Channel& ch, const DecodedTelegram& t,
                                               const Dpv1Pdu& pdu, const ProfidriveMessage& m,
                                               FindingList& out) {
    Dpv1Stats& stats = *ch.stats;
    ch.written = true;
    if (Transaction* open = ch.find(pdu.slot, pdu.index)) {
        // The same Write again before its Write response: a repeat, not a new request.
        if (open->state == Transaction::State::Written && !open->timed_out &&
            open->reference == m.reference && open->id == m.id && open->count == m.count)
            return;
        if (open->timed_out) {
            // Reported as a time-out already: the master gave up on it.
            ch.close(open);
        } else {
            Finding& f = ch.add(out, FindingKind::Dpv1StackedRequest, t, open->frame);
            if (!m.addresses.empty()) f.pnu = m.addresses.front().pnu;
            f.message = fmt::format(
                "new parameter request ({}) written to slot {} index {} while the response to "
                "the request of frame {} ({}) was not read",
                request_text(m.reference, m.id, m.addresses), pdu.slot, pdu.index, open->frame,
                request_text(open->reference, open->id, open->addresses));
            ++stats.abandoned;
            ch.close(open);
        }
    }

    Transaction& tx = ch.start();
    tx.state = Transaction::State::Written;
    tx.timed_out = false;
    tx.polls = 0;
    tx.slot = pdu.slot;
    tx.index = pdu.index;
    tx.frame = t.frame;
    tx.time_ns = t.time_ns;
    tx.dpv1_length = pdu.length;
    tx.reference = m.reference;
    tx.id = m.id;
    tx.axis = m.axis;
    tx.count = m.count;
    tx.change = m.is_change_request();
    tx.addresses.assign(m.addresses.begin(), m.addresses.end());
    ++stats.started;
    ++stats.open;
    for (const ProfidriveAddress& address : m.addresses) {
        auto it = stats.parameters.find(address.pnu);
        if (it == stats.parameters.end()) {
            if (stats.parameters.size() >= Dpv1Stats::kMaxParameters) {
                ++stats.parameters_not_counted;
                continue;
            }
            it = stats.parameters.emplace(address.pnu, Dpv1Stats::ParameterUse{}).first;
        }
        ++(tx.change ? it->second.writes : it->second.reads);
    }
    if (t.has_time() && t.time_ns + timeout_ns_ < next_deadline_ns_)
        next_deadline_ns_ = t.time_ns + timeout_ns_;

    // The request ID and the attributes: codes of the dialect's table [S003].
    const bool danfoss = danfoss_family(t.dp.dialect);
    Inconsistencies unknown;
    if (!profidrive_request_id_defined(m.id, t.dp.dialect)) {
        if (profidrive_request_id_defined(m.id, Dialect::Vlt))
            unknown.add(
                "request ID 0x{:02X} is a Danfoss one, none of 0x01, 0x02 ({}; a Danfoss drive is "
                "decoded with --dialect {}=vlt)",
                m.id, dialect_name(t.dp.dialect), ch.slave);
        else
            unknown.add("request ID 0x{:02X} is none of {} ({})", m.id,
                        danfoss ? "0x01, 0x02, 0x42, 0x51, 0x52" : "0x01, 0x02",
                        dialect_name(t.dp.dialect));
    }
    for (const ProfidriveAddress& address : m.addresses)
        if (profidrive_attribute_name(address.attribute).empty())
            unknown.add(
                "PNU {}: attribute 0x{:02X} is none of 0x10 (value), 0x20 (description), 0x30 "
                "(text)",
                address.pnu, address.attribute);
    if (!unknown.text.empty()) {
        Finding& f = ch.add(out, FindingKind::Dpv1UnknownCode, t, 0);
        f.pnu = tx.first_pnu();
        f.message = fmt::format("parameter request ({}): {}",
                                request_text(m.reference, m.id, m.addresses), unknown.text);
    }

    // The request's own lengths.
    Inconsistencies found;
    check_dpv1_length(pdu, found);
    // The header's ranges [S003]: reference 0x01..0xFF, 0x01..0x25 parameters (Danfoss).
    if (m.reference == 0) found.add("request reference 0 (0x01 to 0xFF allowed)");
    if (m.count == 0)
        found.add("0 parameters (at least 1)");
    else if (m.count > kMaxDanfossParameters && danfoss)
        found.add("{} parameters, more than the {} Danfoss allows", m.count, kMaxDanfossParameters);
    if (m.addresses.size() < m.count)
        found.add("{} parameters announced, {} addresses present", m.count, m.addresses.size());
    // A Danfoss drive has axis 0 only ("always 0") [S003]; a PROFIdrive drive any.
    if (danfoss && m.axis != 0)
        found.add(
            "axis {} (a Danfoss drive has axis 0 only; another drive is decoded with --dialect "
            "{}=profidrive)",
            m.axis, ch.slave);
    // No value block of a response holds more than 234 elements [S003], on any drive.
    for (const ProfidriveAddress& address : m.addresses)
        if (address.elements > profidrive::kMaxElements)
            found.add("PNU {}: {} elements, more than the {} a DP-V1 telegram carries", address.pnu,
                      address.elements, profidrive::kMaxElements);
    if (tx.change && m.addresses.size() == m.count) {
        if (m.blocks.size() < m.count)
            found.add("{} value blocks for {} parameters", m.blocks.size(), m.count);
        for (std::size_t k = 0; k < m.blocks.size() && k < m.addresses.size(); ++k) {
            const ProfidriveValueBlock& block = m.blocks[k];
            const ProfidriveAddress& address = m.addresses[k];
            if (!block.complete) {
                found.add("PNU {}: value block cut short", address.pnu);
                continue;
            }
            if (address.attribute == profidrive::kAttributeValue && !counts_bytes(block.format) &&
                block.count != std::max<std::uint8_t>(address.elements, 1))
                found.add("PNU {}: {} values for {} elements", address.pnu, block.count,
                          std::max<std::uint8_t>(address.elements, 1));
            // Danfoss 0x52 sends every value as a double word, whatever its type [S003].
            if (m.id == profidrive::kChangeValueDoubleWord &&
                profidrive_format_size(block.format) != 4)
                found.add(
                    "PNU {}: format 0x{:02X} in a double-word change (4-byte values, "
                    "such as format 0x43, expected)",
                    address.pnu, block.format);
        }
    }
    if (m.trailing > 0) found.add("{} after the request", counted(m.trailing, "byte", "bytes"));
    if (!found.text.empty()) {
        Finding& f = ch.add(out, FindingKind::Dpv1LengthError, t, 0);
        f.pnu = tx.first_pnu();
        f.message = fmt::format("parameter request ({}): {}",
                                request_text(m.reference, m.id, m.addresses), found.text);
    }
}

void Dpv1ParameterAccessTracker::response(Channel& ch, const DecodedTelegram& t, const Dpv1Pdu& pdu,
                                          FindingList& out) {
    if (pdu.layout == Dpv1Pdu::Layout::Error) {
        error_pdu(ch, t, pdu, out);
        return;
    }
    if (pdu.layout != Dpv1Pdu::Layout::Addressed || !(pdu.is_read() || pdu.is_write())) return;
    // The most the paired Read accepts, when this answers one.
    int read_max = -1;
    if (ch.awaiting && ch.function == pdu.base_function() && ch.slot == pdu.slot &&
        ch.index == pdu.index) {
        ch.awaiting = false;
        if (pdu.is_read()) read_max = ch.length;
    }
    if (pdu.is_write()) {
        Transaction* tx = ch.find(pdu.slot, pdu.index);
        if (!tx || tx->state != Transaction::State::Written) return;
        tx->state = Transaction::State::Reading;
        Inconsistencies found;
        if (pdu.length != tx->dpv1_length)
            found.add("Write response echoes length {}, the request had {}", pdu.length,
                      tx->dpv1_length);
        if (!pdu.data.empty())
            found.add("Write response carries {}",
                      counted(pdu.data.size(), "data byte", "data bytes"));
        if (!found.text.empty()) {
            Finding& f = ch.add(out, FindingKind::Dpv1LengthError, t, tx->frame);
            f.pnu = tx->first_pnu();
            f.message = found.text;
        }
        return;
    }
    if (t.dp.service_data.profidrive()) parameter_response(ch, t, pdu, read_max, out);
}

void Dpv1ParameterAccessTracker::error_pdu(Channel& ch, const DecodedTelegram& t,
                                           const Dpv1Pdu& pdu, FindingList& out) {
    // An error PDU names no slot or index: it answers the request waiting for a response.
    const bool paired = ch.awaiting && ch.function == pdu.base_function();
    ch.awaiting = false;
    Transaction* tx = paired ? ch.find(ch.slot, ch.index) : nullptr;
    Dpv1Stats& stats = *ch.stats;
    if (pdu.is_state_conflict() && pdu.is_read()) {  // not ready yet: the master reads again
        ++stats.polls;
        // Counted as the polls come, so a transaction that times out or stays open counts too.
        if (tx) stats.max_polls = std::max(stats.max_polls, ++tx->polls);
        return;
    }
    ++stats.error_pdus;
    Finding& f = ch.add(out, FindingKind::Dpv1ErrorPdu, t, paired ? ch.frame : 0);
    if (!pdu.complete) {
        // The decoder reports the missing bytes; the codes it did not read are no error class.
        f.severity = Severity::Note;
        f.message = fmt::format("{}: error PDU cut short (its error codes missing)",
                                function_text(pdu.function));
    } else {
        const std::uint8_t error_class = pdu.error_code_1 >> 4;
        // Access (0xB) and resource (0xC) errors are the slave refusing a request it understood.
        f.severity =
            error_class == 0x0B || error_class == 0x0C ? Severity::Note : Severity::Warning;
        std::string_view decode = dpv1_error_decode_name(pdu.error_decode);
        std::string_view class_name = dpv1_error_class_name(pdu.error_code_1);
        f.message = fmt::format(
            "{}: Error_Decode 0x{:02X}{}, Error_Code_1 0x{:02X} ({}{}), Error_Code_2 0x{:02X}",
            function_text(pdu.function), pdu.error_decode,
            decode.empty() ? std::string() : fmt::format(" ({})", decode), pdu.error_code_1,
            class_name.empty() ? std::string("reserved class") : std::string(class_name),
            class_name.empty() ? std::string()
                               : fmt::format(": {}", dpv1_error_code_name(pdu.error_code_1)),
            pdu.error_code_2);
    }
    if (paired)
        fmt::format_to(std::back_inserter(f.message), " to the {} of slot {} index {}",
                       function_text(ch.function), ch.slot, ch.index);
    if (tx) {
        f.pnu = tx->first_pnu();
        fmt::format_to(std::back_inserter(f.message), " (parameter request of frame {}: {})",
                       tx->frame, request_text(tx->reference, tx->id, tx->addresses));
        if (tx->timed_out) {
            ++stats.late;
            f.message += ", after its time-out";
        } else {
            ++stats.refused;
        }
        ch.close(tx);
    }
}

void Dpv1ParameterAccessTracker::parameter_response(Channel& ch, const DecodedTelegram& t,
                                                    const Dpv1Pdu& pdu, int read_max,
                                                    FindingList& out) {
    const ProfidriveMessage& m = *t.dp.service_data.profidrive();
    Dpv1Stats& stats = *ch.stats;
    Transaction* tx = ch.find(pdu.slot, pdu.index);
    if (!tx) {
        if (!ch.written) return;  // its request may have come before the capture: not judged
        Finding& f = ch.add(out, FindingKind::Dpv1OrphanResponse, t, 0);
        if (!m.addresses.empty()) f.pnu = m.addresses.front().pnu;
        f.message = m.has_header ? fmt::format(
                                       "parameter response (reference {}, response ID {}) on slot "
                                       "{} index {} answers no open request",
                                       m.reference, response_id_text(m.id), pdu.slot, pdu.index)
                                 : fmt::format(
                                       "parameter response on slot {} index {} answers no open "
                                       "request",
                                       pdu.slot, pdu.index);
        return;
    }
    // The transaction is complete, or late when it timed out (counted as a time-out then).
    if (tx->timed_out) {
        ++stats.late;
    } else {
        ++stats.completed;
        if (tx->time_ns != kNoTime && t.has_time() && t.time_ns >= tx->time_ns) {
            auto latency = static_cast<std::uint64_t>(t.time_ns - tx->time_ns);
            stats.latency_ns.add(latency);
            stats.latency_sum_ns += latency;
        }
    }
    // The request as findings name it: written only for a finding (most responses have none).
    const auto about = [&tx] { return request_text(tx->reference, tx->id, tx->addresses); };
    auto add = [&](FindingKind kind) -> Finding& {
        Finding& f = ch.add(out, kind, t, tx->frame);
        f.pnu = tx->first_pnu();
        return f;
    };

    if (!m.has_header) {
        add(FindingKind::Dpv1LengthError).message = fmt::format(
            "parameter response of {} has no complete header (request of frame {}: {})",
            counted(std::min<std::size_t>(pdu.length, pdu.data.size()), "byte", "bytes"), tx->frame,
            about());
        ch.close(tx);
        return;
    }
    if (m.reference != tx->reference)
        add(FindingKind::Dpv1ReferenceMismatch).message =
            fmt::format("response reference {} to the request of frame {} ({})", m.reference,
                        tx->frame, about());
    // The answer to a request ID no table has cannot be judged (dpv1_unknown_code named it).
    const bool id_known = !profidrive_request_id_name(tx->id).empty();
    if (id_known && !profidrive_response_answers(m.id, tx->id))
        add(FindingKind::Dpv1UnexpectedResponseId).message =
            fmt::format("response ID {} does not answer the request of frame {} ({})",
                        response_id_text(m.id), tx->frame, about());
    const bool count_mirrored = m.count == tx->count;
    if (!count_mirrored || m.axis != tx->axis) {
        Inconsistencies differ;
        if (m.axis != tx->axis) differ.add("axis {} (request: {})", m.axis, tx->axis);
        if (!count_mirrored) differ.add("{} parameters (request: {})", m.count, tx->count);
        add(FindingKind::Dpv1ParameterCountMismatch).message = fmt::format(
            "response with {} to the request of frame {} ({})", differ.text, tx->frame, about());
    }

    const bool negative = m.negative();
    if (negative) {
        ++stats.negative_responses;
        std::string errors;
        for (std::size_t k = 0; k < m.blocks.size(); ++k) {
            const ProfidriveValueBlock& block = m.blocks[k];
            if (!block.is_error() || block.values.size() < 2) continue;
            if (auto it = stats.negative_errors.find(block.error_number());
                it != stats.negative_errors.end())
                ++it->second;
            else if (stats.negative_errors.size() < Dpv1Stats::kMaxNegativeErrors)
                stats.negative_errors.emplace(block.error_number(), 1);
            else
                ++stats.negative_errors_not_listed;
            if (!errors.empty()) errors += "; ";
            if (k < tx->addresses.size())
                fmt::format_to(std::back_inserter(errors), "PNU {}: ", tx->addresses[k].pnu);
            fmt::format_to(std::back_inserter(errors), "error 0x{:02X} ({})", block.error_number(),
                           profidrive_error_text(block.error_number(), stats.dialect));
            if (block.has_error_info())
                fmt::format_to(std::back_inserter(errors), ", subindex {}", block.error_info());
        }
        add(FindingKind::Dpv1NegativeResponse).message = fmt::format(
            "negative response {} to the request of frame {} ({}): {}", response_id_text(m.id),
            tx->frame, about(), errors.empty() ? std::string("no error number") : errors);
    }

    // Lengths and value blocks against the request.
    Inconsistencies found;
    check_dpv1_length(pdu, found);
    // The response's size: no more than the Read asked for, nor than 240 bytes (a longer one is
    // refused with error 0x15 [P:MCA101 p30]).
    const std::size_t size = std::max<std::size_t>(pdu.length, pdu.data.size());
    if (read_max >= 0 && size > static_cast<std::size_t>(read_max))
        found.add("response of {}, more than the {} its Read accepts",
                  counted(size, "byte", "bytes"), read_max);
    if (size > profidrive::kMaxData)
        found.add("response of {} bytes, more than the {} a parameter response may have", size,
                  profidrive::kMaxData);
    if (!id_known || !profidrive_response_answers(m.id, tx->id)) {
        // Not an answer to this request: its blocks cannot be judged against it.
    } else if (tx->change && !negative) {
        std::size_t length = std::min<std::size_t>(pdu.length, pdu.data.size());
        if (length > 4) found.add("positive change response of {} bytes (4 expected)", length);
    } else if (count_mirrored) {
        if (m.blocks.size() != tx->count)
            found.add("{} value blocks for {} parameters", m.blocks.size(), tx->count);
        for (std::size_t k = 0; k < m.blocks.size() && k < tx->addresses.size(); ++k) {
            const ProfidriveValueBlock& block = m.blocks[k];
            const ProfidriveAddress& address = tx->addresses[k];
            if (!block.complete) {
                found.add("PNU {}: value block cut short", address.pnu);
            } else if (tx->change) {
                if (block.format != profidrive::kFormatZero &&
                    block.format != profidrive::kFormatError)
                    found.add(
                        "PNU {}: format 0x{:02X} in a negative change response (0x40 or "
                        "0x44 expected)",
                        address.pnu, block.format);
                else if (block.format == profidrive::kFormatZero && block.count != 0)
                    found.add("PNU {}: {} values in a format 0x40 block", address.pnu, block.count);
            } else if (block.is_error()) {
                if (block.count != 1 && block.count != 2)
                    found.add("PNU {}: error block with {} values", address.pnu, block.count);
            } else if (address.attribute == profidrive::kAttributeValue &&
                       !counts_bytes(block.format) &&
                       block.count != std::max<std::uint8_t>(address.elements, 1)) {
                found.add("PNU {}: {} values for {} elements", address.pnu, block.count,
                          std::max<std::uint8_t>(address.elements, 1));
            }
            // Danfoss 0x51 answers every value as a double word, whatever its type [S003].
            if (block.complete && !tx->change && tx->id == profidrive::kRequestValueDoubleWord &&
                !block.is_error() && address.attribute == profidrive::kAttributeValue &&
                profidrive_format_size(block.format) != 4)
                found.add(
                    "PNU {}: format 0x{:02X} in the answer to a double-word read (4-byte values, "
                    "such as format 0x43, expected)",
                    address.pnu, block.format);
        }
        if (m.trailing > 0)
            found.add("{} after the last value block", counted(m.trailing, "byte", "bytes"));
    }
    if (!found.text.empty())
        add(FindingKind::Dpv1LengthError).message =
            fmt::format("parameter response to the request of frame {} ({}): {}", tx->frame,
                        about(), found.text);
    ch.close(tx);
}

void Dpv1ParameterAccessTracker::check_deadlines(std::int64_t now_ns, std::uint64_t frame,
                                                 FindingList& out) {
    std::int64_t next = kNever;
    for (auto& owned : channels_) {
        Channel& ch = *owned;
        for (Transaction& tx : ch.open) {
            if (!tx.active || tx.timed_out || tx.time_ns == kNoTime) continue;
            std::int64_t deadline = tx.time_ns + timeout_ns_;
            if (now_ns > deadline) {
                tx.timed_out = true;
                ++ch.stats->timeouts;
                --ch.stats->open;
                Finding& f = add_finding(out, FindingKind::Dpv1ResponseTimeout, frame, now_ns,
                                         tx.frame, true, ch.master, ch.slave);
                f.pnu = tx.first_pnu();
                f.message = fmt::format(
                    "no parameter response to the request of frame {} ({}) within {} ms{}",
                    tx.frame, request_text(tx.reference, tx.id, tx.addresses),
                    timeout_ns_ / 1'000'000,
                    tx.polls ? fmt::format(", {}", counted(tx.polls, "poll", "polls"))
                             : std::string());
            } else {
                next = std::min(next, deadline);
            }
        }
    }
    next_deadline_ns_ = next;
}

}  // namespace dpscope
