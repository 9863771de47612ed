// The PROFIBUS link rules on decoded telegrams, apart from the session tracker: fcs_error,
// malformed_telegram, fdl_retry (the frame count bit) and fdl_no_response.
#include "protocols/profibus/dp_link_rules.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "protocols/profibus/bus_decoder.hpp"
#include "protocols/profibus/telegram_builder.hpp"

namespace dpscope {
namespace {

// Master 2 asking slave 3 (SRD to DSAP 60, the Slave_Diag service).
std::vector<std::uint8_t> srd(bool fcb, bool fcv = true) {
    return build_telegram({3, 2, request_fc(FdlFunction::SrdHigh, fcb, fcv), 60, 62, {}});
}

std::vector<std::uint8_t> damaged(std::vector<std::uint8_t> bytes) {
    bytes[bytes.size() - 2] ^= 0x01;  // the FCS
    return bytes;
}

class DpLinkRulesTest : public ::testing::Test {
  protected:
    const DecodedTelegram& decode(const std::vector<std::uint8_t>& bytes) {
        bytes_.push_back(bytes);
        const std::vector<std::uint8_t>& kept = bytes_.back();
        ++frame_;
        const std::int64_t time_ns = 1'000'000'000 + static_cast<std::int64_t>(frame_);
        return decoder_.decode(Bytes(kept.data(), kept.size()), time_ns, frame_);
    }

    std::vector<Finding> findings;
    FrameCountState frame_count;

  private:
    BusDecoder decoder_;
    std::vector<std::vector<std::uint8_t>> bytes_;
    std::uint64_t frame_ = 0;
};

TEST_F(DpLinkRulesTest, IntactTelegramHasNoFinding) {
    EXPECT_TRUE(check_intact(decode(srd(true)), findings));
    EXPECT_TRUE(findings.empty());
}

// A byte after the end delimiter is a problem of warning severity only (trailing_bytes): the
// telegram is still intact, so no malformed_telegram is reported and it is read further.
TEST_F(DpLinkRulesTest, TrailingBytesAloneLeaveTheTelegramIntact) {
    std::vector<std::uint8_t> bytes = srd(true);
    bytes.push_back(0x00);
    const DecodedTelegram& t = decode(bytes);
    ASSERT_EQ(t.problems().size(), 1u);
    EXPECT_EQ(t.problems()[0].kind, ProblemKind::TrailingBytes);
    EXPECT_TRUE(t.dp.fdl.fcs_ok);
    EXPECT_TRUE(check_intact(t, findings));
    EXPECT_TRUE(findings.empty());
}

TEST_F(DpLinkRulesTest, BadFcsIsAnFcsError) {
    const DecodedTelegram& t = decode(damaged(srd(true)));
    EXPECT_FALSE(check_intact(t, findings));
    ASSERT_EQ(findings.size(), 1u);
    EXPECT_EQ(findings[0].kind, FindingKind::FcsError);
    EXPECT_EQ(findings[0].frame, 1u);
    EXPECT_TRUE(findings[0].has_stations);
    EXPECT_EQ(findings[0].slave, 3);
    EXPECT_FALSE(findings[0].message.empty());
}

TEST_F(DpLinkRulesTest, MalformedTelegramWithoutStations) {
    EXPECT_FALSE(check_intact(decode({0x2A, 0x3F, 0x9F}), findings));
    ASSERT_EQ(findings.size(), 1u);
    EXPECT_EQ(findings[0].kind, FindingKind::MalformedTelegram);
    EXPECT_FALSE(findings[0].has_stations);
}

TEST_F(DpLinkRulesTest, SameFcbAgainIsARetry) {
    EXPECT_FALSE(check_frame_count(frame_count, decode(srd(true)), findings));
    EXPECT_FALSE(check_frame_count(frame_count, decode(srd(false)), findings));
    EXPECT_TRUE(check_frame_count(frame_count, decode(srd(false)), findings));
    ASSERT_EQ(findings.size(), 1u);
    EXPECT_EQ(findings[0].kind, FindingKind::FdlRetry);
    EXPECT_EQ(findings[0].frame, 3u);
    EXPECT_EQ(findings[0].message, "SRD high request to station 3 repeated with the same FCB 0");
}

TEST_F(DpLinkRulesTest, FdlStatusAndAnInvalidFcbRestartTheCount) {
    check_frame_count(frame_count, decode(srd(true)), findings);
    check_frame_count(
        frame_count, decode(build_telegram({3, 2, request_fc(FdlFunction::FdlStatus), {}, {}, {}})),
        findings);
    EXPECT_FALSE(check_frame_count(frame_count, decode(srd(true)), findings));
    check_frame_count(frame_count, decode(srd(true, false)), findings);  // FCV 0
    EXPECT_FALSE(check_frame_count(frame_count, decode(srd(true)), findings));
    EXPECT_TRUE(findings.empty());
}

TEST_F(DpLinkRulesTest, DroppedRequestKeepsItsFcb) {
    check_frame_count(frame_count, decode(srd(true)), findings);
    // The next request is damaged: the slave drops it, the master repeats it with FCB 0.
    const DecodedTelegram& lost = decode(damaged(srd(false)));
    EXPECT_TRUE(note_dropped_request(frame_count, lost));
    EXPECT_TRUE(check_frame_count(frame_count, decode(srd(false)), findings));
    // A damaged response is no dropped request.
    EXPECT_FALSE(note_dropped_request(
        frame_count,
        decode(damaged(build_telegram({2, 3, response_fc(FdlStatus::Ok), {}, {}, {}})))));
}

TEST_F(DpLinkRulesTest, RequestWithoutReplyIsReportedAtTheNextTelegram) {
    check_reply_missing(decode(srd(true)), findings);
    EXPECT_TRUE(findings.empty());
    check_reply_missing(decode(srd(false)), findings);  // no reply came to frame 1
    ASSERT_EQ(findings.size(), 1u);
    const Finding& f = findings[0];
    EXPECT_EQ(f.kind, FindingKind::FdlNoResponse);
    EXPECT_EQ(f.frame, 2u);
    EXPECT_EQ(f.request_frame, 1u);
    EXPECT_EQ(f.master, 2);
    EXPECT_EQ(f.slave, 3);
    EXPECT_NE(f.message.find("got no reply before the master's next telegram"), std::string::npos);
}

}  // namespace
}  // namespace dpscope
