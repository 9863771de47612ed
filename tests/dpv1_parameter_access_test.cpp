// DP-V1 parameter access: telegrams built byte by byte (SD2, DSAP/SSAP 51, the DP-V1 PDU and the
// PROFIdrive request or response as in docs/protocol/dpv1-parameter-access.md), decoded by
// BusDecoder and tracked by SessionTracker. A clean session with single and multi-parameter
// reads, a change, arrays with subindices, state-conflict polls and link-level polls has no
// finding; each dpv1_* rule is shown with its exact findings.
#include "protocols/profibus/dpv1/dpv1_parameter_access.hpp"

#include <gtest/gtest.h>

#include <initializer_list>
#include <vector>

#include "protocols/profibus/bus_decoder.hpp"
#include "protocols/profibus/session_tracker.hpp"
#include "protocols/profibus/telegram_builder.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using ByteVector = std::vector<std::uint8_t>;

constexpr std::uint8_t kMaster = 1;
constexpr std::uint8_t kSlave = 5;
constexpr std::uint8_t kSap = 51;

// A PROFIdrive parameter address: attribute value, elements, PNU, subindex.
struct Address {
    std::uint16_t pnu = 0;
    std::uint8_t elements = 0;
    std::uint16_t subindex = 0;
    std::uint8_t attribute = 0x10;
};

void put16(ByteVector& out, std::uint16_t v) { append_u16_be(out, v); }

using test::joined;

// The parameter request: header, addresses, then the value blocks given as raw bytes.
ByteVector parameter_request(std::uint8_t reference, std::uint8_t id,
                             std::initializer_list<Address> addresses, ByteVector blocks = {},
                             std::uint8_t axis = 0) {
    ByteVector out{reference, id, axis, static_cast<std::uint8_t>(addresses.size())};
    for (const Address& a : addresses) {
        out.push_back(a.attribute);
        out.push_back(a.elements);
        put16(out, a.pnu);
        put16(out, a.subindex);
    }
    out.insert(out.end(), blocks.begin(), blocks.end());
    return out;
}

// The parameter response: header, then the value blocks as raw bytes.
ByteVector parameter_response(std::uint8_t reference, std::uint8_t id, std::uint8_t count,
                              ByteVector blocks = {}, std::uint8_t axis = 0) {
    return joined({reference, id, axis, count}, blocks);
}

// A DP-V1 PDU: function, slot 0, index 47, length (the data's unless given), data.
ByteVector pdu(std::uint8_t function, const ByteVector& data, int length = -1) {
    return joined({function, 0, 47,
                   static_cast<std::uint8_t>(length < 0 ? data.size() : std::size_t(length))},
                  data);
}
ByteVector read_request() { return {0x5E, 0, 47, 240}; }
ByteVector write_response(std::uint8_t length) { return {0x5F, 0, 47, length}; }
ByteVector error_pdu(std::uint8_t function, std::uint8_t code_1) {
    return {function, 0x80, code_1, 0x00};
}

// Master 1 and slave 5 talking DP-V1 on SAP 51, 1 ms between telegrams.
class Dpv1Bus {
  public:
    explicit Dpv1Bus(TrackerOptions options = {}, DecoderOptions decoder = {})
        : decoder_(decoder), tracker_(options) {}
    // Slave 5 decoded with `dialect` (--dialect 5=NAME).
    static DecoderOptions dialect(Dialect d) {
        DecoderOptions options;
        options.station_dialect[kSlave] = d;
        return options;
    }

    std::uint64_t request(const ByteVector& du) {
        send(build_telegram({kSlave, kMaster, request_fc(FdlFunction::SrdHigh, fcb_, true), kSap,
                             kSap, Bytes(du)}));
        fcb_ = !fcb_;
        return frame_;
    }
    // The same request again with the same FCB (an FDL retry).
    std::uint64_t repeat(const ByteVector& du) {
        fcb_ = !fcb_;
        return request(du);
    }
    std::uint64_t response(const ByteVector& du) {
        send(build_telegram(
            {kMaster, kSlave, response_fc(FdlStatus::DataLow), kSap, kSap, Bytes(du)}));
        return frame_;
    }
    std::uint64_t short_ack() {
        ByteVector bytes;
        append_short_ack(bytes);
        send(bytes);
        return frame_;
    }
    // A link-level poll: the master asks with an empty data unit, the slave has nothing yet.
    void link_poll() {
        request({});
        short_ack();
    }
    // Write, Write response, Reads answered "state conflict" `polls` times, then the response.
    std::uint64_t transaction(const ByteVector& request_data, const ByteVector& response_data,
                              int polls = 0) {
        request(pdu(0x5F, request_data));
        response(write_response(static_cast<std::uint8_t>(request_data.size())));
        for (int i = 0; i < polls; ++i) {
            request(read_request());
            response(error_pdu(0xDE, 0xB5));
        }
        request(read_request());
        return response(pdu(0x5E, response_data));
    }
    void advance_ms(std::int64_t ms) { now_ += ms * 1'000'000; }
    // The end of the capture, `later_ms` after the last telegram (a live capture's stop).
    void finish(std::int64_t later_ms = 0) {
        for (const Finding& f : tracker_.finish(later_ms ? now_ + later_ms * 1'000'000 : kNoTime))
            findings.push_back(f);
    }
    const Dpv1Stats& stats() const {
        for (const ChannelStats* s : tracker_.channels())
            if (s->slave == kSlave && s->master == kMaster) return s->dpv1;
        static const Dpv1Stats kNone;
        ADD_FAILURE() << "no channel";
        return kNone;
    }
    const SessionTracker& tracker() const { return tracker_; }

    std::vector<Finding> findings;

  private:
    void send(const ByteVector& bytes) {
        const DecodedTelegram& t =
            decoder_.decode(Bytes(bytes.data(), bytes.size()), now_, ++frame_);
        for (const Finding& f : tracker_.track(t))
            findings.push_back(f);
        now_ += 1'000'000;
    }

    BusDecoder decoder_;
    SessionTracker tracker_;
    std::int64_t now_ = 1'704'067'200'000'000'000;
    std::uint64_t frame_ = 0;
    bool fcb_ = true;
};

struct Expected {
    FindingKind kind;
    std::uint64_t frame;
    Severity severity;
};

void expect_findings(const std::vector<Finding>& findings,
                     std::initializer_list<Expected> expected) {
    ASSERT_EQ(findings.size(), expected.size());
    std::size_t i = 0;
    for (const Expected& e : expected) {
        const Finding& f = findings[i++];
        SCOPED_TRACE(f.message);
        EXPECT_EQ(f.kind, e.kind) << finding_kind_name(f.kind);
        EXPECT_EQ(f.frame, e.frame);
        EXPECT_EQ(f.severity, e.severity);
        EXPECT_TRUE(f.has_stations);
        EXPECT_EQ(f.master, kMaster);
        EXPECT_EQ(f.slave, kSlave);
        EXPECT_FALSE(f.message.empty());
    }
}

std::string messages(const std::vector<Finding>& findings) {
    std::string text;
    for (const Finding& f : findings)
        text += std::string(finding_kind_name(f.kind)) + ": " + f.message + "\n";
    return text;
}

// ---- a clean session ----------------------------------------------------------------------------

TEST(Dpv1ParameterAccessTest, CleanSessionHasNoFindings) {
    Dpv1Bus bus;
    // The worked example (ABB's, with axis 0 as a Danfoss drive has it): reference 5, read PNU 12
    // subindex 4; Word 3.
    bus.transaction(parameter_request(5, 0x01, {{12, 1, 4}}),
                    parameter_response(5, 0x01, 1, {0x42, 0x01, 0x00, 0x03}), 2);
    // Three parameters in one request, a value, a string and an array read (subindex 2..4).
    bus.transaction(
        parameter_request(6, 0x01, {{20, 0, 8}, {30, 0, 0}, {40, 3, 2}}),
        parameter_response(6, 0x01, 3,
                           {0x06, 0x01, 0x01, 0xF4,                             // Unsigned16 500
                            0x09, 0x03, 'a', 'b', 'c', 0x00,                    // "abc", padded
                            0x03, 0x03, 0x00, 0x01, 0x00, 0x02, 0x00, 0x03}));  // 3 x Integer16
    // A change of one array element, answered with the header only, after link-level polls.
    bus.request(pdu(0x5F, parameter_request(7, 0x02, {{40, 1, 3}}, {0x03, 0x01, 0x00, 0x07})));
    bus.short_ack();
    bus.link_poll();
    bus.response(write_response(14));
    bus.request(read_request());
    bus.short_ack();
    bus.link_poll();
    bus.response(error_pdu(0xDE, 0xB5));
    bus.request(read_request());
    bus.short_ack();
    bus.link_poll();
    bus.request({});
    bus.response(pdu(0x5E, parameter_response(7, 0x02, 1)));
    // A Danfoss double-word read answered as a standard read.
    bus.transaction(parameter_request(8, 0x51, {{100, 0, 0}}),
                    parameter_response(8, 0x01, 1, {0x43, 0x01, 0, 0, 0x01, 0x00}));
    bus.finish();
    EXPECT_TRUE(bus.findings.empty()) << messages(bus.findings);

    const Dpv1Stats& s = bus.stats();
    EXPECT_EQ(s.started, 4u);
    EXPECT_EQ(s.completed, 4u);
    EXPECT_EQ(s.abandoned + s.timeouts + s.refused, 0u);
    EXPECT_EQ(s.polls, 3u);
    EXPECT_EQ(s.max_polls, 2u);
    EXPECT_EQ(s.latency_ns.count(), 4u);
    EXPECT_EQ(s.latency_ns.min(), 3'000'000u);   // Write, its response, Read, the response
    EXPECT_EQ(s.latency_ns.max(), 15'000'000u);  // the change, with its link-level polls
    EXPECT_EQ(s.parameters.size(), 5u);
    EXPECT_EQ(s.parameters.at(40).reads, 1u);
    EXPECT_EQ(s.parameters.at(40).writes, 1u);
    EXPECT_EQ(s.parameters.at(12).reads, 1u);
    EXPECT_EQ(s.negative_responses, 0u);
    EXPECT_EQ(bus.tracker().transactions(), 4u);
}

TEST(Dpv1ParameterAccessTest, RepeatedWriteBeforeItsResponseIsOneRequest) {
    Dpv1Bus bus;
    ByteVector request = pdu(0x5F, parameter_request(9, 0x01, {{918, 0, 0}}));
    bus.request(request);
    std::uint64_t retry = bus.repeat(request);  // no reply: an FDL retry, same FCB and request
    bus.response(write_response(10));
    bus.request(read_request());
    bus.response(pdu(0x5E, parameter_response(9, 0x01, 1, {0x42, 0x01, 0x00, 0x03})));
    bus.finish();
    // The link rules see the retry; the DP-V1 rules see one request.
    ASSERT_EQ(bus.findings.size(), 2u) << messages(bus.findings);
    EXPECT_EQ(bus.findings[0].kind, FindingKind::FdlNoResponse);
    EXPECT_EQ(bus.findings[1].kind, FindingKind::FdlRetry);
    EXPECT_EQ(bus.findings[1].frame, retry);
    EXPECT_EQ(bus.stats().started, 1u);
    EXPECT_EQ(bus.stats().completed, 1u);
}

// ---- one scenario per rule ----------------------------------------------------------------------

TEST(Dpv1ParameterAccessTest, StackedRequest) {
    Dpv1Bus bus;
    std::uint64_t first = bus.request(pdu(0x5F, parameter_request(1, 0x01, {{12}})));
    bus.response(write_response(10));
    std::uint64_t second = bus.request(pdu(0x5F, parameter_request(2, 0x01, {{13}})));
    bus.response(write_response(10));
    bus.request(read_request());
    bus.response(pdu(0x5E, parameter_response(2, 0x01, 1, {0x06, 0x01, 0x00, 0x01})));
    bus.finish();
    expect_findings(bus.findings, {{FindingKind::Dpv1StackedRequest, second, Severity::Error}});
    EXPECT_EQ(bus.findings[0].request_frame, first);
    EXPECT_EQ(bus.findings[0].pnu, 13);
    EXPECT_NE(bus.findings[0].message.find("PNU 12"), std::string::npos);
    EXPECT_EQ(bus.stats().abandoned, 1u);
    EXPECT_EQ(bus.stats().completed, 1u);
}

TEST(Dpv1ParameterAccessTest, ReferenceMismatch) {
    Dpv1Bus bus;
    std::uint64_t at = bus.transaction(parameter_request(3, 0x01, {{12}}),
                                       parameter_response(4, 0x01, 1, {0x06, 0x01, 0x00, 0x01}));
    bus.finish();
    expect_findings(bus.findings, {{FindingKind::Dpv1ReferenceMismatch, at, Severity::Error}});
    EXPECT_EQ(bus.findings[0].pnu, 12);
    EXPECT_EQ(bus.findings[0].request_frame, 1u);
}

TEST(Dpv1ParameterAccessTest, ChangeAnsweredAsAReadIsAnUnexpectedResponseId) {
    Dpv1Bus bus;
    std::uint64_t at = bus.transaction(parameter_request(3, 0x02, {{12}}, {0x06, 0x01, 0x00, 0x05}),
                                       parameter_response(3, 0x01, 1, {0x06, 0x01, 0x00, 0x05}));
    bus.finish();
    expect_findings(bus.findings, {{FindingKind::Dpv1UnexpectedResponseId, at, Severity::Error}});
    EXPECT_NE(bus.findings[0].message.find("change parameter value"), std::string::npos);
}

TEST(Dpv1ParameterAccessTest, ParameterCountOrAxisNotMirrored) {
    // A PROFIdrive drive, which may have another axis than 0.
    Dpv1Bus bus({}, Dpv1Bus::dialect(Dialect::Profidrive));
    std::uint64_t count = bus.transaction(
        parameter_request(3, 0x01, {{12}}),
        parameter_response(3, 0x01, 2, {0x06, 0x01, 0x00, 0x05, 0x06, 0x01, 0x00, 0x06}));
    std::uint64_t axis = bus.transaction(parameter_request(4, 0x01, {{12}}, {}, 1),
                                         parameter_response(4, 0x01, 1, {0x06, 0x01, 0x00, 0x05}));
    bus.finish();
    expect_findings(bus.findings,
                    {{FindingKind::Dpv1ParameterCountMismatch, count, Severity::Error},
                     {FindingKind::Dpv1ParameterCountMismatch, axis, Severity::Error}});
    EXPECT_NE(bus.findings[1].message.find("axis 0 (request: 1)"), std::string::npos);
}

TEST(Dpv1ParameterAccessTest, ResponseWithoutARequestIsAnOrphan) {
    Dpv1Bus bus;
    bus.transaction(parameter_request(2, 0x01, {{12}}),
                    parameter_response(2, 0x01, 1, {0x06, 0x01, 0, 1}));
    bus.request(read_request());
    std::uint64_t at = bus.response(pdu(0x5E, parameter_response(3, 0x01, 1, {0x06, 0x01, 0, 1})));
    bus.finish();
    expect_findings(bus.findings, {{FindingKind::Dpv1OrphanResponse, at, Severity::Warning}});
}

// A capture that begins while a parameter request is under way (a tap clipped onto a running
// bus): its Write came before the capture, so the Reads polling for the response and the
// response are no orphans. Nothing before the first parameter request seen from the master to
// the slave is judged an orphan (docs/decisions.md, "Counts and verdicts that add up").
TEST(Dpv1ParameterAccessTest, ResponseBeforeTheFirstRequestSeenIsNoOrphan) {
    Dpv1Bus bus;
    bus.request(read_request());
    bus.response(error_pdu(0xDE, 0xB5));  // state conflict: not ready yet
    bus.request(read_request());
    bus.response(pdu(0x5E, parameter_response(3, 0x01, 1, {0x06, 0x01, 0, 1})));
    bus.transaction(parameter_request(4, 0x01, {{12}}),
                    parameter_response(4, 0x01, 1, {0x06, 0x01, 0, 1}));
    bus.finish();
    EXPECT_TRUE(bus.findings.empty()) << messages(bus.findings);
    EXPECT_EQ(bus.stats().started, 1u);
    EXPECT_EQ(bus.stats().completed, 1u);
}

TEST(Dpv1ParameterAccessTest, TimeoutAsTimePassesAndAtTheEndOfTheCapture) {
    TrackerOptions options;
    options.timeout_ns = 100'000'000;
    Dpv1Bus bus(options);
    std::uint64_t first = bus.request(pdu(0x5F, parameter_request(1, 0x01, {{12}})));
    bus.response(write_response(10));
    bus.request(read_request());
    bus.response(error_pdu(0xDE, 0xB5));
    bus.advance_ms(200);
    std::uint64_t poll = bus.request(read_request());  // the next telegram sees the deadline past
    bus.response(error_pdu(0xDE, 0xB5));
    // A second request on another slot, left open at the end of the capture.
    ByteVector second = pdu(0x5F, parameter_request(2, 0x01, {{13}}));
    second[1] = 1;
    std::uint64_t open = bus.request(second);
    bus.short_ack();
    bus.advance_ms(150);
    bus.link_poll();
    bus.finish();
    ASSERT_EQ(bus.findings.size(), 2u) << messages(bus.findings);
    expect_findings(bus.findings,
                    {{FindingKind::Dpv1ResponseTimeout, poll, Severity::Error},
                     {FindingKind::Dpv1ResponseTimeout, bus.findings[1].frame, Severity::Error}});
    EXPECT_EQ(bus.findings[0].request_frame, first);
    EXPECT_EQ(bus.findings[1].request_frame, open);
    EXPECT_GT(bus.findings[1].frame, open);
    EXPECT_NE(bus.findings[0].message.find("within 100 ms, 1 poll"), std::string::npos)
        << bus.findings[0].message;
    EXPECT_EQ(bus.stats().timeouts, 2u);
}

TEST(Dpv1ParameterAccessTest, TimedOutRequestIsNotAlsoStackedAndItsLateResponseNoOrphan) {
    TrackerOptions options;
    options.timeout_ns = 100'000'000;
    Dpv1Bus bus(options);
    bus.request(pdu(0x5F, parameter_request(1, 0x01, {{12}})));
    bus.response(write_response(10));
    bus.advance_ms(200);
    std::uint64_t late = bus.request(read_request());
    // The late response completes the timed-out request: no orphan.
    bus.response(pdu(0x5E, parameter_response(1, 0x01, 1, {0x06, 0x01, 0, 1})));
    // Timed out again; the master gives up and writes the next request: no stacked request.
    bus.request(pdu(0x5F, parameter_request(2, 0x01, {{13}})));
    bus.response(write_response(10));
    bus.advance_ms(200);
    std::uint64_t next = bus.request(pdu(0x5F, parameter_request(3, 0x01, {{14}})));
    bus.response(write_response(10));
    bus.request(read_request());
    bus.response(pdu(0x5E, parameter_response(3, 0x01, 1, {0x06, 0x01, 0, 1})));
    bus.finish();
    expect_findings(bus.findings, {{FindingKind::Dpv1ResponseTimeout, late, Severity::Error},
                                   {FindingKind::Dpv1ResponseTimeout, next, Severity::Error}});
    const Dpv1Stats& s = bus.stats();
    EXPECT_EQ(s.started, 3u);
    // The late response ends the first as late (one of the time-outs): not completed, no latency.
    EXPECT_EQ(s.completed, 1u);
    EXPECT_EQ(s.timeouts, 2u);
    EXPECT_EQ(s.late, 1u);
    EXPECT_EQ(s.abandoned, 0u);
    EXPECT_EQ(s.open, 0u);
    EXPECT_EQ(s.latency_ns.count(), 1u);
    EXPECT_LT(s.latency_ns.max(), 100'000'000u);
}

// Every transaction started is completed, refused, abandoned, timed out or still open.
void expect_every_transaction_accounted(const Dpv1Stats& s) {
    EXPECT_EQ(s.started, s.completed + s.refused + s.abandoned + s.timeouts + s.open)
        << s.started << " started, " << s.completed << " completed, " << s.refused << " refused, "
        << s.abandoned << " abandoned, " << s.timeouts << " timed out, " << s.open << " open";
}

TEST(Dpv1ParameterAccessTest, EveryTransactionStartedEndsOnceOrIsOpen) {
    TrackerOptions options;
    options.timeout_ns = 100'000'000;
    Dpv1Bus bus(options);
    // Completed.
    bus.transaction(parameter_request(1, 0x01, {{12}}),
                    parameter_response(1, 0x01, 1, {0x06, 0x01, 0, 1}));
    // Refused.
    bus.request(pdu(0x5F, parameter_request(2, 0x01, {{13}})));
    bus.response(error_pdu(0xDF, 0xB0));
    // Abandoned.
    bus.request(pdu(0x5F, parameter_request(3, 0x01, {{14}})));
    bus.response(write_response(10));
    bus.request(pdu(0x5F, parameter_request(4, 0x01, {{15}})));
    bus.response(write_response(10));
    // ... that one times out after 3 polls and is answered late, after 2 more.
    for (int i = 0; i < 3; ++i) {
        bus.request(read_request());
        bus.response(error_pdu(0xDE, 0xB5));
        bus.advance_ms(40);
    }
    for (int i = 0; i < 2; ++i) {
        bus.request(read_request());
        bus.response(error_pdu(0xDE, 0xB5));
    }
    bus.request(read_request());
    bus.response(pdu(0x5E, parameter_response(4, 0x01, 1, {0x06, 0x01, 0, 1})));
    // Timed out, then refused late.
    bus.request(pdu(0x5F, parameter_request(5, 0x01, {{16}})));
    bus.response(write_response(10));
    bus.advance_ms(200);
    bus.request(read_request());
    bus.response(error_pdu(0xDE, 0xA0));
    // Timed out, then given up by a new Write, which is still open at the end.
    bus.request(pdu(0x5F, parameter_request(6, 0x01, {{17}})));
    bus.response(write_response(10));
    bus.advance_ms(200);
    bus.request(pdu(0x5F, parameter_request(7, 0x01, {{18}})));
    bus.response(write_response(10));
    bus.finish();
    const Dpv1Stats& s = bus.stats();
    EXPECT_EQ(s.started, 7u);
    EXPECT_EQ(s.completed, 1u);
    EXPECT_EQ(s.refused, 1u);
    EXPECT_EQ(s.abandoned, 1u);
    EXPECT_EQ(s.timeouts, 3u) << messages(bus.findings);
    EXPECT_EQ(s.late, 2u);
    EXPECT_EQ(s.open, 1u);
    expect_every_transaction_accounted(s);
    // The polls of the transaction that timed out count, before and after its time-out.
    EXPECT_EQ(s.polls, 5u);
    EXPECT_EQ(s.max_polls, 5u);
    EXPECT_EQ(s.latency_ns.count(), 1u);
    // The late refusal says so; the late response is no orphan.
    bool late_refusal = false;
    for (const Finding& f : bus.findings) {
        EXPECT_NE(f.kind, FindingKind::Dpv1OrphanResponse) << f.message;
        if (f.kind == FindingKind::Dpv1ErrorPdu)
            late_refusal |= f.message.find("after its time-out") != std::string::npos;
    }
    EXPECT_TRUE(late_refusal) << messages(bus.findings);
}

TEST(Dpv1ParameterAccessTest, PollsOfATransactionStillOpenCountInTheMost) {
    Dpv1Bus bus;
    bus.transaction(parameter_request(1, 0x01, {{12}}),
                    parameter_response(1, 0x01, 1, {0x06, 0x01, 0, 1}), 1);
    bus.request(pdu(0x5F, parameter_request(2, 0x01, {{13}})));
    bus.response(write_response(10));
    for (int i = 0; i < 4; ++i) {
        bus.request(read_request());
        bus.response(error_pdu(0xDE, 0xB5));
    }
    bus.finish();
    const Dpv1Stats& s = bus.stats();
    EXPECT_EQ(s.max_polls, 4u);
    EXPECT_EQ(s.open, 1u);
    EXPECT_EQ(s.timeouts, 0u);
    expect_every_transaction_accounted(s);
}

TEST(Dpv1ParameterAccessTest, OpenRequestAtTheEndOfTheCaptureTimesOut) {
    Dpv1Bus bus;
    std::uint64_t write = bus.request(pdu(0x5F, parameter_request(1, 0x01, {{12}})));
    bus.response(write_response(10));
    bus.request(read_request());
    std::uint64_t last = bus.response(error_pdu(0xDE, 0xB5));
    EXPECT_TRUE(bus.findings.empty());
    bus.finish(1000);  // a live capture stopped a second later
    expect_findings(bus.findings, {{FindingKind::Dpv1ResponseTimeout, last, Severity::Error}});
    EXPECT_EQ(bus.findings[0].request_frame, write);
}

TEST(Dpv1ParameterAccessTest, NegativeResponseListsEveryErrorWithItsText) {
    Dpv1Bus bus;
    std::uint64_t at = bus.transaction(
        parameter_request(3, 0x01, {{12}, {20}, {30, 4, 1}}),
        parameter_response(3, 0x81, 3,
                           {0x06, 0x01, 0x00, 0x05,                 // PNU 12: a value
                            0x44, 0x01, 0x00, 0x00,                 // PNU 20: unknown
                            0x44, 0x02, 0x00, 0x03, 0x00, 0x07}));  // PNU 30: subindex 7
    bus.finish();
    expect_findings(bus.findings, {{FindingKind::Dpv1NegativeResponse, at, Severity::Note}});
    EXPECT_EQ(bus.findings[0].pnu, 12);
    EXPECT_NE(bus.findings[0].message.find(
                  "PNU 20: error 0x00 (illegal or unknown parameter number); PNU 30: error 0x03 "
                  "(invalid subindex), subindex 7"),
              std::string::npos)
        << bus.findings[0].message;
    const Dpv1Stats& s = bus.stats();
    EXPECT_EQ(s.negative_responses, 1u);
    EXPECT_EQ(s.negative_errors.at(0x00), 1u);
    EXPECT_EQ(s.negative_errors.at(0x03), 1u);
}

TEST(Dpv1ParameterAccessTest, NegativeChangeResponseWithZeroAndErrorBlocksIsConsistent) {
    Dpv1Bus bus;
    std::uint64_t at = bus.transaction(
        parameter_request(3, 0x02, {{12}, {13}}, {0x06, 0x01, 0x00, 0x05, 0x06, 0x01, 0x00, 0x06}),
        parameter_response(3, 0x82, 2, {0x40, 0x00, 0x44, 0x01, 0x00, 0x02}));
    bus.finish();
    expect_findings(bus.findings, {{FindingKind::Dpv1NegativeResponse, at, Severity::Note}});
    EXPECT_NE(bus.findings[0].message.find("PNU 13: error 0x02 (lower or upper limit exceeded)"),
              std::string::npos);
}

TEST(Dpv1ParameterAccessTest, LengthErrors) {
    Dpv1Bus bus;
    // The DP-V1 length byte says 10, 8 data bytes follow.
    std::uint64_t dpv1_length = [&] {
        bus.request(pdu(0x5F, parameter_request(1, 0x01, {{12}})));
        bus.response(write_response(10));
        bus.request(read_request());
        return bus.response(pdu(0x5E, parameter_response(1, 0x01, 1, {0x06, 0x01, 0, 1}), 10));
    }();
    // Two values for an array access of three elements.
    std::uint64_t values =
        bus.transaction(parameter_request(2, 0x01, {{40, 3, 0}}),
                        parameter_response(2, 0x01, 1, {0x06, 0x02, 0, 1, 0, 2}));
    // A positive change response with a value block.
    std::uint64_t change =
        bus.transaction(parameter_request(3, 0x02, {{12}}, {0x06, 0x01, 0x00, 0x05}),
                        parameter_response(3, 0x02, 1, {0x06, 0x01, 0x00, 0x05}));
    // A negative change response with a value where 0x40 or 0x44 belongs.
    std::uint64_t negative_change = bus.transaction(
        parameter_request(4, 0x02, {{12}, {13}}, {0x06, 0x01, 0, 5, 0x06, 0x01, 0, 6}),
        parameter_response(4, 0x82, 2, {0x06, 0x01, 0, 5, 0x44, 0x01, 0x00, 0x02}));
    // One value block for two parameters, then trailing bytes.
    std::uint64_t blocks = bus.transaction(parameter_request(5, 0x01, {{12}, {13}}),
                                           parameter_response(5, 0x01, 2, {0x06, 0x01, 0, 5}));
    std::uint64_t trailing =
        bus.transaction(parameter_request(6, 0x01, {{12}}),
                        parameter_response(6, 0x01, 1, {0x06, 0x01, 0, 5, 0xEE, 0xEE}));
    bus.finish();
    expect_findings(bus.findings,
                    {{FindingKind::Dpv1LengthError, dpv1_length, Severity::Error},
                     {FindingKind::Dpv1LengthError, values, Severity::Error},
                     {FindingKind::Dpv1LengthError, change, Severity::Error},
                     {FindingKind::Dpv1NegativeResponse, negative_change, Severity::Note},
                     {FindingKind::Dpv1LengthError, negative_change, Severity::Error},
                     // The data short of the second block is this one finding, not also
                     // malformed_telegram (the decoder's service_data_short).
                     {FindingKind::Dpv1LengthError, blocks, Severity::Error},
                     {FindingKind::Dpv1LengthError, trailing, Severity::Error}});
    EXPECT_NE(bus.findings[0].message.find("DP-V1 length 10 but 8 data bytes"), std::string::npos);
    EXPECT_NE(bus.findings[1].message.find("PNU 40: 2 values for 3 elements"), std::string::npos);
    EXPECT_NE(bus.findings[2].message.find("positive change response of 8 bytes"),
              std::string::npos);
    EXPECT_NE(bus.findings[4].message.find("PNU 12: format 0x06 in a negative change response"),
              std::string::npos);
    EXPECT_NE(bus.findings[5].message.find("1 value blocks for 2 parameters"), std::string::npos);
    EXPECT_NE(bus.findings[6].message.find("2 bytes after the last value block"),
              std::string::npos);
}

TEST(Dpv1ParameterAccessTest, ChangeRequestWithTooFewValuesIsALengthError) {
    Dpv1Bus bus;
    std::uint64_t at =
        bus.request(pdu(0x5F, parameter_request(1, 0x02, {{40, 2, 0}}, {0x06, 0x01, 0x00, 0x05})));
    bus.response(write_response(14));
    bus.request(read_request());
    bus.response(pdu(0x5E, parameter_response(1, 0x02, 1)));
    bus.finish();
    expect_findings(bus.findings, {{FindingKind::Dpv1LengthError, at, Severity::Error}});
    EXPECT_NE(bus.findings[0].message.find("PNU 40: 1 values for 2 elements"), std::string::npos);
}

TEST(Dpv1ParameterAccessTest, ErrorPdusAreNotesForAccessAndResourceWarningsOtherwise) {
    Dpv1Bus bus;
    // The Write refused: invalid index (access class): the transaction ends.
    bus.request(pdu(0x5F, parameter_request(1, 0x01, {{12}})));
    std::uint64_t refused = bus.response(error_pdu(0xDF, 0xB0));
    // A Read answered with an application error.
    bus.request(pdu(0x5F, parameter_request(2, 0x01, {{13}})));
    bus.response(write_response(10));
    bus.request(read_request());
    std::uint64_t application = bus.response(error_pdu(0xDE, 0xA0));
    // Resource busy on a write to another index: no transaction, still a note.
    bus.request({0x5F, 0, 3, 2, 0x00, 0x01});
    std::uint64_t busy = bus.response(error_pdu(0xDF, 0xC2));
    bus.finish();
    expect_findings(bus.findings, {{FindingKind::Dpv1ErrorPdu, refused, Severity::Note},
                                   {FindingKind::Dpv1ErrorPdu, application, Severity::Warning},
                                   {FindingKind::Dpv1ErrorPdu, busy, Severity::Note}});
    EXPECT_NE(bus.findings[0].message.find("Error_Code_1 0xB0 (access: invalid index)"),
              std::string::npos)
        << bus.findings[0].message;
    EXPECT_EQ(bus.findings[0].pnu, 12);
    EXPECT_EQ(bus.findings[1].pnu, 13);
    EXPECT_FALSE(bus.findings[2].pnu);
    EXPECT_EQ(bus.stats().refused, 2u);
    EXPECT_EQ(bus.stats().error_pdus, 3u);
    EXPECT_EQ(bus.stats().polls, 0u);
}

TEST(Dpv1ParameterAccessTest, RequestHeaderOutOfTheSeedsRangesIsALengthError) {
    Dpv1Bus bus;
    std::uint64_t zero_reference = bus.request(pdu(0x5F, parameter_request(0, 0x01, {{12}})));
    bus.response(write_response(10));
    bus.request(read_request());
    bus.response(pdu(0x5E, parameter_response(0, 0x01, 1, {0x06, 0x01, 0, 1})));
    std::uint64_t no_parameters = bus.request(pdu(0x5F, parameter_request(2, 0x01, {})));
    bus.response(write_response(4));
    bus.request(read_request());
    bus.response(pdu(0x5E, parameter_response(2, 0x01, 0)));
    bus.finish();
    expect_findings(bus.findings, {{FindingKind::Dpv1LengthError, zero_reference, Severity::Error},
                                   {FindingKind::Dpv1LengthError, no_parameters, Severity::Error}});
    EXPECT_NE(bus.findings[0].message.find("request reference 0 (0x01 to 0xFF allowed)"),
              std::string::npos)
        << bus.findings[0].message;
    EXPECT_NE(bus.findings[1].message.find("0 parameters (at least 1)"), std::string::npos)
        << bus.findings[1].message;
}

TEST(Dpv1ParameterAccessTest, DoubleWordChangeWithOtherThanFourByteValuesIsALengthError) {
    Dpv1Bus bus;
    // 0x52 with a double word: fine.
    bus.transaction(parameter_request(1, 0x52, {{12}}, {0x43, 0x01, 0, 0, 0, 5}),
                    parameter_response(1, 0x02, 1));
    // 0x52 with a Word: not a double word.
    std::uint64_t word =
        bus.request(pdu(0x5F, parameter_request(2, 0x52, {{13}}, {0x42, 0x01, 0, 5})));
    bus.response(write_response(14));
    bus.request(read_request());
    bus.response(pdu(0x5E, parameter_response(2, 0x02, 1)));
    bus.finish();
    expect_findings(bus.findings, {{FindingKind::Dpv1LengthError, word, Severity::Error}});
    EXPECT_NE(bus.findings[0].message.find("PNU 13: format 0x42 in a double-word change"),
              std::string::npos)
        << bus.findings[0].message;
}

TEST(Dpv1ParameterAccessTest, ReadResponseLongerThanItsReadAcceptsIsALengthError) {
    Dpv1Bus bus;
    bus.request(pdu(0x5F, parameter_request(1, 0x01, {{12}})));
    bus.response(write_response(10));
    bus.request({0x5E, 0, 47, 6});  // accepts at most 6 bytes
    std::uint64_t response =
        bus.response(pdu(0x5E, parameter_response(1, 0x01, 1, {0x06, 0x01, 0, 1})));
    bus.finish();
    expect_findings(bus.findings, {{FindingKind::Dpv1LengthError, response, Severity::Error}});
    EXPECT_NE(bus.findings[0].message.find("response of 8 bytes, more than the 6 its Read accepts"),
              std::string::npos)
        << bus.findings[0].message;
}

TEST(Dpv1ParameterAccessTest, ErrorPduCutShortIsANoteWithoutAClass) {
    Dpv1Bus bus;
    bus.request(pdu(0x5F, parameter_request(1, 0x01, {{12}})));
    std::uint64_t cut = bus.response({0xDF, 0x80});  // Error_Code_1 and _2 missing
    bus.finish();
    // The decoder reports the missing bytes; the tracker does not judge codes it never saw.
    ASSERT_EQ(bus.findings.size(), 2u) << messages(bus.findings);
    EXPECT_EQ(bus.findings[0].kind, FindingKind::MalformedTelegram);
    const Finding& f = bus.findings[1];
    EXPECT_EQ(f.kind, FindingKind::Dpv1ErrorPdu);
    EXPECT_EQ(f.frame, cut);
    EXPECT_EQ(f.severity, Severity::Note);
    const std::string& message = f.message;
    EXPECT_NE(message.find("cut short"), std::string::npos) << message;
    EXPECT_EQ(message.find("Error_Code_1"), std::string::npos) << message;
    EXPECT_EQ(message.find("reserved class"), std::string::npos) << message;
    EXPECT_EQ(bus.stats().refused, 1u);
}

TEST(Dpv1ParameterAccessTest, ResponseLaterThanTheFdlReplyToItsRequestIsPaired) {
    Dpv1Bus bus;
    bus.request(pdu(0x5F, parameter_request(1, 0x01, {{12}})));
    bus.short_ack();  // the Write taken, its response not ready at the link layer
    bus.link_poll();
    bus.response(write_response(10));  // the Write response, in answer to a later poll
    bus.request(read_request());
    bus.short_ack();
    bus.request({});
    bus.response(error_pdu(0xDE, 0xB5));  // the state conflict, also late
    bus.request(read_request());
    bus.short_ack();
    bus.link_poll();
    bus.request({});
    bus.response(pdu(0x5E, parameter_response(1, 0x01, 1, {0x06, 0x01, 0, 1})));
    bus.finish();
    EXPECT_TRUE(bus.findings.empty()) << messages(bus.findings);
    EXPECT_EQ(bus.stats().completed, 1u);
    EXPECT_EQ(bus.stats().polls, 1u);
}

TEST(Dpv1ParameterAccessTest, ParametersAccessedAreBounded) {
    Dpv1Bus bus;
    for (std::uint16_t pnu = 1; pnu <= Dpv1Stats::kMaxParameters + 10; ++pnu)
        bus.transaction(parameter_request(static_cast<std::uint8_t>(pnu % 255 + 1), 0x01, {{pnu}}),
                        parameter_response(static_cast<std::uint8_t>(pnu % 255 + 1), 0x01, 1,
                                           {0x06, 0x01, 0, 1}));
    bus.finish();
    EXPECT_TRUE(bus.findings.empty()) << messages(bus.findings);
    EXPECT_EQ(bus.stats().parameters.size(), Dpv1Stats::kMaxParameters);
    EXPECT_EQ(bus.stats().parameters_not_counted, 10u);
}

TEST(Dpv1ParameterAccessTest, NegativeErrorNumbersListedAreBounded) {
    Dpv1Bus bus;
    const std::uint16_t numbers = Dpv1Stats::kMaxNegativeErrors + 10;
    for (std::uint16_t error = 0; error < numbers; ++error) {
        auto reference = static_cast<std::uint8_t>(error % 255 + 1);
        bus.transaction(parameter_request(reference, 0x01, {{12}}),
                        parameter_response(reference, 0x81, 1,
                                           {0x44, 0x01, static_cast<std::uint8_t>(error >> 8),
                                            static_cast<std::uint8_t>(error & 0xFF)}));
    }
    // A number already listed is still counted.
    bus.transaction(parameter_request(1, 0x01, {{12}}),
                    parameter_response(1, 0x81, 1, {0x44, 0x01, 0x00, 0x02}));
    bus.finish();
    const Dpv1Stats& s = bus.stats();
    EXPECT_EQ(s.negative_responses, numbers + 1u);
    EXPECT_EQ(s.negative_errors.size(), Dpv1Stats::kMaxNegativeErrors);
    EXPECT_EQ(s.negative_errors_not_listed, 10u);
    EXPECT_EQ(s.negative_errors.at(2), 2u);
}

// Danfoss allows at most 0x25 (37) parameters in one request [S003]; the default dialect (vlt)
// is a Danfoss one, so a request naming 38 is a length error, even when answered in full.
TEST(Dpv1ParameterAccessTest, MoreParametersThanDanfossAllowsIsALengthError) {
    constexpr std::uint8_t kParameters = 38;  // one more than the Danfoss limit
    Dpv1Bus bus;
    // Reference 1 reads PNUs 1..38; each is answered with the value block Unsigned16 1.
    ByteVector request{1, 0x01, 0, kParameters};
    const ByteVector value{0x06, 0x01, 0x00, 0x01};
    ByteVector blocks;
    for (std::uint16_t pnu = 1; pnu <= kParameters; ++pnu) {
        request.push_back(0x10);  // attribute value
        request.push_back(0);     // no elements: a simple parameter
        put16(request, pnu);
        put16(request, 0);  // subindex
        for (std::uint8_t b : value)
            blocks.push_back(b);
    }
    bus.transaction(request, parameter_response(1, 0x01, kParameters, blocks));
    bus.finish();
    const std::uint64_t write = 1;  // the Write, the transaction's first telegram
    expect_findings(bus.findings, {{FindingKind::Dpv1LengthError, write, Severity::Error}});
    EXPECT_EQ(bus.findings[0].pnu, 1);
    EXPECT_EQ(bus.findings[0].message,
              "parameter request (reference 1, request parameter value, PNUs 1, 2, 3, 4, 5, 6, 7, "
              "8, ...): 38 parameters, more than the 37 Danfoss allows");
    EXPECT_EQ(bus.stats().completed, 1u);
}

// The Write response echoes the Write's length and carries no data; an echo of another length
// (and one with data) is a length error on the Write response, naming the Write.
TEST(Dpv1ParameterAccessTest, WriteResponseEchoingAnotherLengthIsALengthError) {
    Dpv1Bus bus;
    std::uint64_t first = bus.request(pdu(0x5F, parameter_request(1, 0x01, {{12}})));  // length 10
    std::uint64_t longer = bus.response(write_response(12));
    bus.request(read_request());
    bus.response(pdu(0x5E, parameter_response(1, 0x01, 1, {0x06, 0x01, 0, 1})));
    std::uint64_t second = bus.request(pdu(0x5F, parameter_request(2, 0x01, {{13}})));
    std::uint64_t with_data = bus.response(pdu(0x5F, {0xEE, 0xEE, 0xEE}));  // length 3, 3 bytes
    bus.request(read_request());
    bus.response(pdu(0x5E, parameter_response(2, 0x01, 1, {0x06, 0x01, 0, 1})));
    bus.finish();
    expect_findings(bus.findings, {{FindingKind::Dpv1LengthError, longer, Severity::Error},
                                   {FindingKind::Dpv1LengthError, with_data, Severity::Error}});
    EXPECT_EQ(bus.findings[0].request_frame, first);
    EXPECT_EQ(bus.findings[0].pnu, 12);
    EXPECT_EQ(bus.findings[0].message, "Write response echoes length 12, the request had 10");
    EXPECT_EQ(bus.findings[1].request_frame, second);
    EXPECT_EQ(bus.findings[1].pnu, 13);
    EXPECT_EQ(bus.findings[1].message,
              "Write response echoes length 3, the request had 10; Write response carries 3 data "
              "bytes");
    // The transactions go on to their responses.
    EXPECT_EQ(bus.stats().completed, 2u);
}

// A Read response of 3 bytes has no PROFIdrive header (4 bytes), so no reference to quote: the
// orphan is named by its slot and index alone. The decoder reports the short data, too.
TEST(Dpv1ParameterAccessTest, OrphanResponseWithoutAHeaderIsNamedBySlotAndIndex) {
    Dpv1Bus bus;
    bus.transaction(parameter_request(2, 0x01, {{12}}),
                    parameter_response(2, 0x01, 1, {0x06, 0x01, 0, 1}));
    bus.request(read_request());
    std::uint64_t at = bus.response(pdu(0x5E, {0x03, 0x01, 0x00}));
    bus.finish();
    expect_findings(bus.findings, {{FindingKind::MalformedTelegram, at, Severity::Error},
                                   {FindingKind::Dpv1OrphanResponse, at, Severity::Warning}});
    EXPECT_FALSE(bus.findings[1].pnu);
    EXPECT_EQ(bus.findings[1].message,
              "parameter response on slot 0 index 47 answers no open request");
}

// A parameter response without its complete header ends the transaction with a length error
// naming the request; its size is what the data holds, or less when the DP-V1 length says so.
TEST(Dpv1ParameterAccessTest, ResponseWithoutACompleteHeaderIsALengthError) {
    Dpv1Bus bus;
    std::uint64_t cut = bus.transaction(parameter_request(1, 0x01, {{12}}), {0x01, 0x01, 0x00});
    // The whole response sent, but the length byte announces only 2 of its 8 bytes.
    std::uint64_t write = bus.request(pdu(0x5F, parameter_request(2, 0x01, {{13}})));
    bus.response(write_response(10));
    bus.request(read_request());
    std::uint64_t announced =
        bus.response(pdu(0x5E, parameter_response(2, 0x01, 1, {0x06, 0x01, 0, 1}), 2));
    bus.finish();
    // One finding each, the DP-V1 one: not also malformed_telegram for the same short data.
    expect_findings(bus.findings, {{FindingKind::Dpv1LengthError, cut, Severity::Error},
                                   {FindingKind::Dpv1LengthError, announced, Severity::Error}});
    EXPECT_EQ(bus.findings[0].request_frame, 1u);
    EXPECT_EQ(bus.findings[0].pnu, 12);
    EXPECT_EQ(bus.findings[0].message,
              "parameter response of 3 bytes has no complete header (request of frame 1: "
              "reference 1, request parameter value, PNU 12)");
    EXPECT_EQ(bus.findings[1].request_frame, write);
    EXPECT_EQ(bus.findings[1].message,
              "parameter response of 2 bytes has no complete header (request of frame 5: "
              "reference 2, request parameter value, PNU 13)");
    // Both transactions end there: none is left open to time out.
    EXPECT_EQ(bus.stats().started, 2u);
    EXPECT_EQ(bus.stats().completed, 2u);
    EXPECT_EQ(bus.stats().open, 0u);
}

// No parameter response is longer than 240 bytes [P:MCA101 p30]. One FDL telegram carries at
// most 240 bytes of DP-V1 data (LE 249), so only the DP-V1 length byte can announce more.
TEST(Dpv1ParameterAccessTest, ResponseAnnouncingMoreThan240BytesIsALengthError) {
    Dpv1Bus bus;
    bus.request(pdu(0x5F, parameter_request(1, 0x01, {{12}})));
    bus.response(write_response(10));
    // A Read accepting up to 255 bytes (not judged), so only the 240-byte limit is passed.
    bus.request({0x5E, 0, 47, 255});
    std::uint64_t at =
        bus.response(pdu(0x5E, parameter_response(1, 0x01, 1, {0x06, 0x01, 0, 1}), 250));
    bus.finish();
    expect_findings(bus.findings, {{FindingKind::Dpv1LengthError, at, Severity::Error}});
    EXPECT_EQ(bus.findings[0].message,
              "parameter response to the request of frame 1 (reference 1, request parameter "
              "value, PNU 12): DP-V1 length 250 but 8 data bytes; response of 250 bytes, more "
              "than the 240 a parameter response may have");
}

// A value block whose values stop short of the count it announces (2 Unsigned16, 2 bytes), in a
// telegram with a correct FCS: one defect, one finding, the DP-V1 one (not also
// malformed_telegram for the decoder's service_data_short), counted once.
TEST(Dpv1ParameterAccessTest, ResponseValueBlockCutShortIsALengthError) {
    Dpv1Bus bus;
    std::uint64_t at = bus.transaction(parameter_request(1, 0x01, {{12}}),
                                       parameter_response(1, 0x01, 1, {0x06, 0x02, 0x00, 0x01}));
    bus.finish();
    expect_findings(bus.findings, {{FindingKind::Dpv1LengthError, at, Severity::Error}});
    EXPECT_EQ(bus.findings[0].message,
              "parameter response to the request of frame 1 (reference 1, request parameter "
              "value, PNU 12): PNU 12: value block cut short");
    EXPECT_EQ(bus.tracker().findings(Severity::Error), 1u);
    const ChannelStats& channel = *bus.tracker().channels().front();
    EXPECT_EQ(channel.findings[static_cast<std::size_t>(FindingKind::MalformedTelegram)], 0u);
    EXPECT_EQ(channel.findings[static_cast<std::size_t>(FindingKind::Dpv1LengthError)], 1u);
}

// The same in a Write request: its value block cut short is the DP-V1 length error alone.
TEST(Dpv1ParameterAccessTest, RequestValueBlockCutShortIsOneLengthError) {
    Dpv1Bus bus;
    std::uint64_t at =
        bus.request(pdu(0x5F, parameter_request(1, 0x02, {{12}}, {0x06, 0x02, 0, 5})));
    bus.finish();
    ASSERT_EQ(bus.findings.size(), 1u) << messages(bus.findings);
    EXPECT_EQ(bus.findings[0].kind, FindingKind::Dpv1LengthError);
    EXPECT_EQ(bus.findings[0].frame, at);
    EXPECT_NE(bus.findings[0].message.find("PNU 12: value block cut short"), std::string::npos)
        << bus.findings[0].message;
}

// In a negative change response a parameter that was changed has a Zero block (0x40), which
// holds no values: one announcing 2 is a length error.
TEST(Dpv1ParameterAccessTest, ZeroBlockWithValuesInANegativeChangeResponseIsALengthError) {
    Dpv1Bus bus;
    std::uint64_t at = bus.transaction(
        parameter_request(3, 0x02, {{12}, {13}}, {0x06, 0x01, 0x00, 0x05, 0x06, 0x01, 0x00, 0x06}),
        parameter_response(3, 0x82, 2, {0x40, 0x02, 0x44, 0x01, 0x00, 0x02}));
    bus.finish();
    expect_findings(bus.findings, {{FindingKind::Dpv1NegativeResponse, at, Severity::Note},
                                   {FindingKind::Dpv1LengthError, at, Severity::Error}});
    EXPECT_EQ(bus.findings[0].message,
              "negative response 0x82 (change parameter (-)) to the request of frame 1 "
              "(reference 3, change parameter value, PNUs 12, 13): PNU 13: error 0x02 (lower or "
              "upper limit exceeded)");
    EXPECT_EQ(bus.findings[1].message,
              "parameter response to the request of frame 1 (reference 3, change parameter "
              "value, PNUs 12, 13): PNU 12: 2 values in a format 0x40 block");
}

// An error block (0x44) holds the error number and perhaps one more value (1 or 2 values);
// none, or three, is a length error.
TEST(Dpv1ParameterAccessTest, ErrorBlockWithOtherThanOneOrTwoValuesIsALengthError) {
    Dpv1Bus bus;
    std::uint64_t none = bus.transaction(parameter_request(1, 0x01, {{12}}),
                                         parameter_response(1, 0x81, 1, {0x44, 0x00}));
    std::uint64_t three = bus.transaction(
        parameter_request(2, 0x01, {{13}}),
        parameter_response(2, 0x81, 1, {0x44, 0x03, 0x00, 0x00, 0x00, 0x03, 0x00, 0x07}));
    bus.finish();
    expect_findings(bus.findings, {{FindingKind::Dpv1NegativeResponse, none, Severity::Note},
                                   {FindingKind::Dpv1LengthError, none, Severity::Error},
                                   {FindingKind::Dpv1NegativeResponse, three, Severity::Note},
                                   {FindingKind::Dpv1LengthError, three, Severity::Error}});
    EXPECT_EQ(bus.findings[0].message,
              "negative response 0x81 (request parameter (-)) to the request of frame 1 "
              "(reference 1, request parameter value, PNU 12): no error number");
    EXPECT_EQ(bus.findings[1].message,
              "parameter response to the request of frame 1 (reference 1, request parameter "
              "value, PNU 12): PNU 12: error block with 0 values");
    EXPECT_EQ(bus.findings[2].message,
              "negative response 0x81 (request parameter (-)) to the request of frame 5 "
              "(reference 2, request parameter value, PNU 13): PNU 13: error 0x00 (illegal or "
              "unknown parameter number), subindex 3");
    EXPECT_EQ(bus.findings[3].message,
              "parameter response to the request of frame 5 (reference 2, request parameter "
              "value, PNU 13): PNU 13: error block with 3 values");
}

// ---- the ranges and codes of seed 003 (#27 point 18) -------------------------------------------

// A Danfoss 0x51 read answers every value as a double word, whatever its type [S003], as 0x52
// sends them: a value block of another size is a length error; an error block is not.
TEST(Dpv1ParameterAccessTest, DoubleWordReadAnsweredWithOtherThanFourByteValuesIsALengthError) {
    Dpv1Bus bus;
    bus.transaction(parameter_request(1, 0x51, {{12}}),
                    parameter_response(1, 0x01, 1, {0x43, 0x01, 0, 0, 0, 5}));
    bus.transaction(parameter_request(2, 0x51, {{13, 2, 0}}),
                    parameter_response(2, 0x01, 1, {0x07, 0x02, 0, 0, 0, 5, 0, 0, 0, 6}));
    std::uint64_t refused = bus.transaction(parameter_request(3, 0x51, {{9999}}),
                                            parameter_response(3, 0x81, 1, {0x44, 0x01, 0, 0}));
    std::uint64_t word = bus.transaction(parameter_request(4, 0x51, {{14}, {15}}),
                                         parameter_response(4, 0x01, 2,
                                                            {0x42, 0x01, 0x00, 0x05,  // Word
                                                             0x43, 0x01, 0, 0, 0, 6}));
    bus.finish();
    expect_findings(bus.findings, {{FindingKind::Dpv1NegativeResponse, refused, Severity::Note},
                                   {FindingKind::Dpv1LengthError, word, Severity::Error}});
    ASSERT_EQ(bus.findings.size(), 2u);
    EXPECT_EQ(bus.findings[1].message,
              "parameter response to the request of frame 13 (reference 4, request parameter "
              "value (double word), PNUs 14, 15): PNU 14: format 0x42 in the answer to a "
              "double-word read (4-byte values, such as format 0x43, expected)");
    EXPECT_EQ(bus.findings[1].pnu, 14);
}

// The number of elements: at most 234, what one value block of a DP-V1 telegram holds [S003]
// (which prints the range as 0x01-0xFA, but the quantity as 1-234: 0xEA). On every dialect.
TEST(Dpv1ParameterAccessTest, RequestForMoreThan234ElementsIsALengthError) {
    for (Dialect dialect : {Dialect::Vlt, Dialect::Ge, Dialect::Profidrive}) {
        SCOPED_TRACE(dialect_name(dialect));
        const std::uint8_t axis = dialect == Dialect::Profidrive ? 1 : 0;
        Dpv1Bus bus({}, Dpv1Bus::dialect(dialect));
        // 234 one-byte elements fill the 240 bytes of the response: fine.
        ByteVector values{0x05, 234};
        for (int i = 0; i < 234; ++i)
            values.push_back(static_cast<std::uint8_t>(i));
        bus.transaction(parameter_request(1, 0x01, {{12, 234, 0}}, {}, axis),
                        parameter_response(1, 0x01, 1, values, axis));
        // 235: no response can carry them; refused with error 0x16 (illegal parameter address).
        std::uint64_t more = bus.request(
            pdu(0x5F, parameter_request(2, 0x01, {{13, 235, 0}, {14, 0xFA, 0}}, {}, axis)));
        bus.response(write_response(16));
        bus.request(read_request());
        std::uint64_t refused = bus.response(
            pdu(0x5E,
                parameter_response(2, 0x81, 2, {0x44, 0x01, 0, 0x16, 0x44, 0x01, 0, 0x16}, axis)));
        bus.finish();
        expect_findings(bus.findings,
                        {{FindingKind::Dpv1LengthError, more, Severity::Error},
                         {FindingKind::Dpv1NegativeResponse, refused, Severity::Note}});
        ASSERT_EQ(bus.findings.size(), 2u);
        EXPECT_EQ(bus.findings[0].message,
                  "parameter request (reference 2, request parameter value, PNUs 13, 14): PNU 13: "
                  "235 elements, more than the 234 a DP-V1 telegram carries; PNU 14: 250 "
                  "elements, more than the 234 a DP-V1 telegram carries");
    }
}

// A Danfoss drive (vlt, and ge, built on the same option) has axis 0 only [S003]; the PROFIdrive
// dialect takes any axis (ABB's drive object 1 [P:FPBA p110]).
TEST(Dpv1ParameterAccessTest, AxisOtherThanZeroOnADanfossDriveIsALengthError) {
    for (Dialect dialect : {Dialect::Vlt, Dialect::Ge}) {
        SCOPED_TRACE(dialect_name(dialect));
        Dpv1Bus bus({}, Dpv1Bus::dialect(dialect));
        std::uint64_t write =
            bus.request(pdu(0x5F, parameter_request(5, 0x01, {{12, 1, 4}}, {}, 1)));
        bus.response(write_response(10));
        bus.request(read_request());
        bus.response(pdu(0x5E, parameter_response(5, 0x01, 1, {0x42, 0x01, 0x00, 0x03}, 1)));
        bus.finish();
        expect_findings(bus.findings, {{FindingKind::Dpv1LengthError, write, Severity::Error}});
        ASSERT_EQ(bus.findings.size(), 1u);
        EXPECT_EQ(bus.findings[0].message,
                  "parameter request (reference 5, request parameter value, PNU 12): axis 1 (a "
                  "Danfoss drive has axis 0 only; another drive is decoded with --dialect "
                  "5=profidrive)");
    }
    // ABB's worked example [P:FPBA p110], decoded as PROFIdrive: clean.
    Dpv1Bus abb({}, Dpv1Bus::dialect(Dialect::Profidrive));
    abb.transaction(parameter_request(5, 0x01, {{12, 1, 4}}, {}, 1),
                    parameter_response(5, 0x01, 1, {0x42, 0x01, 0x00, 0x03}, 1));
    abb.finish();
    EXPECT_TRUE(abb.findings.empty()) << messages(abb.findings);
}

// Request IDs and attributes are those of seed 003's table: 0x01, 0x02 and Danfoss's 0x42, 0x51,
// 0x52 (vlt, ge; the PROFIdrive dialect knows only 0x01 and 0x02); attributes 0x10, 0x20, 0x30.
// Another is a dpv1_unknown_code on the Write; its response is not judged against it.
TEST(Dpv1ParameterAccessTest, RequestIdOrAttributeOutsideTheTablesIsAnUnknownCode) {
    Dpv1Bus bus;
    std::uint64_t id = bus.transaction(parameter_request(1, 0x03, {{12}}),
                                       parameter_response(1, 0x81, 1, {0x44, 0x01, 0x00, 0x66}));
    std::uint64_t attribute =
        bus.transaction(parameter_request(2, 0x01, {{13, 0, 0, 0x40}}),
                        parameter_response(2, 0x81, 1, {0x44, 0x01, 0x00, 0x16}));
    bus.transaction(parameter_request(3, 0x42, {{14}}, {0x43, 0x01, 0, 0, 0, 1}),
                    parameter_response(3, 0x02, 1));
    bus.finish();
    expect_findings(bus.findings, {{FindingKind::Dpv1UnknownCode, id - 3, Severity::Warning},
                                   {FindingKind::Dpv1NegativeResponse, id, Severity::Note},
                                   {FindingKind::Dpv1UnknownCode, attribute - 3, Severity::Warning},
                                   {FindingKind::Dpv1NegativeResponse, attribute, Severity::Note}});
    ASSERT_EQ(bus.findings.size(), 4u);
    EXPECT_EQ(bus.findings[0].message,
              "parameter request (reference 1, request ID 0x03, PNU 12): request ID 0x03 is none "
              "of 0x01, 0x02, 0x42, 0x51, 0x52 (vlt)");
    EXPECT_EQ(bus.findings[2].message,
              "parameter request (reference 2, request parameter value, PNU 13): PNU 13: "
              "attribute 0x40 is none of 0x10 (value), 0x20 (description), 0x30 (text)");
    EXPECT_EQ(bus.findings[0].pnu, 12);

    // The Danfoss IDs on a PROFIdrive drive.
    Dpv1Bus profidrive({}, Dpv1Bus::dialect(Dialect::Profidrive));
    std::uint64_t danfoss =
        profidrive.transaction(parameter_request(1, 0x51, {{12}}, {}, 1),
                               parameter_response(1, 0x01, 1, {0x43, 0x01, 0, 0, 0, 5}, 1));
    profidrive.transaction(parameter_request(2, 0x02, {{13}}, {0x42, 0x01, 0, 1}, 1),
                           parameter_response(2, 0x02, 1, {}, 1));
    profidrive.finish();
    expect_findings(profidrive.findings,
                    {{FindingKind::Dpv1UnknownCode, danfoss - 3, Severity::Warning}});
    ASSERT_EQ(profidrive.findings.size(), 1u);
    EXPECT_EQ(profidrive.findings[0].message,
              "parameter request (reference 1, request parameter value (double word), PNU 12): "
              "request ID 0x51 is a Danfoss one, none of 0x01, 0x02 (profidrive; a Danfoss drive "
              "is decoded with --dialect 5=vlt)");
}

}  // namespace
}  // namespace dpscope
