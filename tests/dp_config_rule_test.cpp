// The PROFIBUS DP configuration rule on decoded telegrams, apart from the session tracker: the
// Data_Exchange lengths against the layout Chk_Cfg or Get_Cfg announced (config_mismatch).
#include "protocols/profibus/dp_config_rule.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "protocols/profibus/bus_decoder.hpp"
#include "protocols/profibus/telegram_builder.hpp"

namespace dpscope {
namespace {

class DpConfigRuleTest : public ::testing::Test {
  protected:
    explicit DpConfigRuleTest(DecoderOptions options = {}) : decoder_(options) {}

    const DecodedTelegram& decode(const std::vector<std::uint8_t>& bytes) {
        bytes_.push_back(bytes);
        const std::vector<std::uint8_t>& kept = bytes_.back();
        return decoder_.decode(Bytes(kept.data(), kept.size()), kNoTime, ++frame_);
    }
    // Slave 3's Chk_Cfg: PPO 1 (12 bytes each way), then its short acknowledgement.
    void configure() {
        std::vector<std::uint8_t> cfg = {0xF3, 0xF1};
        decode(build_telegram(
            {3, 2, request_fc(FdlFunction::SrdHigh, true, true), 62, 62, Bytes(cfg)}));
        decode({kShortAck});
    }
    const DecodedTelegram& outputs(std::size_t length) {
        std::vector<std::uint8_t> du(length, 0);
        fcb_ = !fcb_;
        return decode(build_telegram(
            {3, 2, request_fc(FdlFunction::SrdHigh, fcb_, true), {}, {}, Bytes(du)}));
    }
    const DecodedTelegram& inputs(std::size_t length) {
        std::vector<std::uint8_t> du(length, 0);
        return decode(build_telegram({2, 3, response_fc(FdlStatus::DataLow), {}, {}, Bytes(du)}));
    }

    std::vector<Finding> findings;
    ConfigCheckState state;

  private:
    BusDecoder decoder_;
    std::vector<std::vector<std::uint8_t>> bytes_;
    std::uint64_t frame_ = 0;
    bool fcb_ = true;
};

TEST_F(DpConfigRuleTest, TheDecoderNamesTheConfigurationFrame) {
    configure();
    const DecodedTelegram& t = outputs(12);
    EXPECT_EQ(t.dp.ppo.source, PpoSource::ChkCfg);
    EXPECT_EQ(t.dp.ppo_cfg_frame, 1u);
    check_config(state, t, findings);
    EXPECT_TRUE(findings.empty());
}

TEST_F(DpConfigRuleTest, WrongLengthIsReportedOncePerLength) {
    configure();
    check_config(state, outputs(14), findings);  // frame 3
    check_config(state, inputs(12), findings);
    check_config(state, outputs(14), findings);  // the same length again
    check_config(state, outputs(12), findings);  // agrees again
    check_config(state, outputs(14), findings);  // frame 7: reported again
    check_config(state, inputs(10), findings);   // frame 8: the inputs disagree
    ASSERT_EQ(findings.size(), 3u);
    EXPECT_EQ(findings[0].kind, FindingKind::ConfigMismatch);
    EXPECT_EQ(findings[0].frame, 3u);
    EXPECT_EQ(findings[0].message,
              "Data_Exchange request carries 14 bytes; the Chk_Cfg in frame 1 announced 12");
    EXPECT_EQ(findings[1].frame, 7u);
    EXPECT_EQ(findings[2].frame, 8u);
    EXPECT_EQ(findings[2].message,
              "Data_Exchange response carries 10 bytes; the Chk_Cfg in frame 1 announced 12");
}

TEST_F(DpConfigRuleTest, ResponseWithoutDataIsNotMeasured) {
    configure();
    check_config(state, outputs(12), findings);
    check_config(state,
                 decode(build_telegram({2, 3, response_fc(FdlStatus::NoService), {}, {}, {}})),
                 findings);
    EXPECT_TRUE(findings.empty());
}

TEST_F(DpConfigRuleTest, WithoutAConfigurationNothingIsChecked) {
    const DecodedTelegram& t = outputs(14);
    EXPECT_EQ(t.dp.ppo.source, PpoSource::Length);
    EXPECT_EQ(t.dp.ppo_cfg_frame, 0u);
    check_config(state, t, findings);
    EXPECT_TRUE(findings.empty());
}

}  // namespace
}  // namespace dpscope
