// Properties of the FDL framing rules and the stream framer over every telegram kind the telegram
// builder makes (SD1, SD2 of many lengths, SD3, each with and without SAPs; SD4; SC):
//   - builder -> framer -> parser round-trips: the same bytes come out, the parser finds no
//     problem and reads back what was built;
//   - every proper prefix of a valid telegram is "need more";
//   - a single-bit error in a valid telegram never crashes, every byte is still accounted for
//     (framed or skipped, once), no framed telegram passes the FCS unless its checksum really
//     matches, and the damaged telegram is never taken for an intact one.
// Seeded (std::mt19937 with fixed seeds, used without distributions), so every run is the same.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "core/stream_framer.hpp"
#include "protocols/profibus/fdl.hpp"
#include "protocols/profibus/fdl_framing_rules.hpp"
#include "protocols/profibus/telegram_builder.hpp"

namespace dpscope {
namespace {

struct Case {
    std::string name;  // for failure messages: "SD2 du 9 dsap ssap"
    FrameType type = FrameType::Invalid;
    TelegramSpec spec;                // addresses, FC and SAPs (SD4: addresses)
    std::vector<std::uint8_t> du;     // the data unit
    std::vector<std::uint8_t> bytes;  // the encoded telegram
};

class Generator {
  public:
    explicit Generator(std::uint32_t seed) : rng_(seed) {}

    std::uint32_t below(std::uint32_t n) { return static_cast<std::uint32_t>(rng_() % n); }
    std::uint8_t byte() { return static_cast<std::uint8_t>(rng_()); }

    // A telegram with `du_size` data bytes and the SAPs `saps` says (bit 0 DSAP, bit 1 SSAP).
    Case fdl(std::size_t du_size, unsigned saps) {
        Case c;
        c.spec.da = static_cast<std::uint8_t>(below(128));
        c.spec.sa = static_cast<std::uint8_t>(below(127));
        c.spec.fc = static_cast<std::uint8_t>(byte() & 0x7F);  // bit 7 is reserved
        if (saps & 1) c.spec.dsap = static_cast<std::uint8_t>(below(64));
        if (saps & 2) c.spec.ssap = static_cast<std::uint8_t>(below(64));
        for (std::size_t i = 0; i < du_size; ++i)
            c.du.push_back(byte());
        const std::size_t octets = du_size + std::size_t{(saps & 1) != 0} + ((saps & 2) != 0);
        c.type = octets == 0 ? FrameType::Sd1 : octets == 8 ? FrameType::Sd3 : FrameType::Sd2;
        c.name = std::string(frame_type_name(c.type)) + " du " + std::to_string(du_size) +
                 ((saps & 1) ? " dsap" : "") + ((saps & 2) ? " ssap" : "");
        c.spec.du = Bytes(c.du.data(), c.du.size());
        append_telegram(c.bytes, c.spec);
        c.spec.du = {};  // would dangle once the case moves; c.du holds the data
        return c;
    }
    Case token() {
        Case c;
        c.type = FrameType::Sd4;
        c.name = "SD4";
        c.spec.da = static_cast<std::uint8_t>(below(128));
        c.spec.sa = static_cast<std::uint8_t>(below(127));
        append_token(c.bytes, c.spec.da, c.spec.sa);
        return c;
    }
    static Case short_ack() {
        Case c;
        c.type = FrameType::ShortAck;
        c.name = "SC";
        append_short_ack(c.bytes);
        return c;
    }
    // Any kind, SD2 of any length.
    Case any() {
        switch (below(8)) {
            case 0: return token();
            case 1: return short_ack();
            case 2: return fdl(0, 0);  // SD1
            case 3: {                  // SD3
                const unsigned saps = below(4);
                return fdl(8 - ((saps & 1) != 0) - ((saps & 2) != 0), saps);
            }
            default: {  // SD2
                const unsigned saps = below(4);
                const std::size_t taken = ((saps & 1) != 0) + ((saps & 2) != 0);
                std::size_t octets = 0;
                while (octets == 0 || octets == 8)
                    octets = std::max<std::size_t>(taken, 1 + below(246));
                return fdl(octets - taken, saps);
            }
        }
    }

  private:
    std::mt19937 rng_;
};

// Every kind with every SAP combination, SD2 at its shortest, longest and lengths in between.
std::vector<Case> every_kind(Generator& gen) {
    std::vector<Case> cases;
    cases.push_back(Generator::short_ack());
    cases.push_back(gen.token());
    cases.push_back(gen.fdl(0, 0));  // SD1 (no data, so no SAPs)
    for (unsigned saps = 0; saps < 4; ++saps) {
        const std::size_t taken = ((saps & 1) != 0) + ((saps & 2) != 0);
        cases.push_back(gen.fdl(8 - taken, saps));  // SD3
        for (std::size_t octets : {1u, 2u, 3u, 4u, 7u, 9u, 10u, 16u, 33u, 100u, 200u, 245u, 246u}) {
            if (octets < taken) continue;
            cases.push_back(gen.fdl(octets - taken, saps));  // SD2
        }
    }
    return cases;
}

Bytes span_of(const std::vector<std::uint8_t>& bytes) { return Bytes(bytes.data(), bytes.size()); }

struct Framed {
    std::vector<std::uint8_t> bytes;
    std::uint64_t offset = 0;
};

class CollectingSink final : public StreamFramer::Sink {
  public:
    void on_telegram(Bytes telegram, std::uint64_t offset) override {
        check_contiguous(offset, telegram.size());
        telegrams.push_back(Framed{{telegram.begin(), telegram.end()}, offset});
    }
    void on_skipped(const SkippedBytes& skipped) override {
        check_contiguous(skipped.offset, skipped.count);
        skipped_bytes += skipped.count;
        EXPECT_FALSE(fdl_framing_rules().describe_skip(skipped).empty());
    }
    // Every byte so far was framed or skipped, each once, in stream order.
    std::uint64_t accounted = 0;
    std::uint64_t skipped_bytes = 0;
    std::vector<Framed> telegrams;

  private:
    void check_contiguous(std::uint64_t offset, std::uint64_t count) {
        EXPECT_EQ(offset, accounted);
        accounted = offset + count;
    }
};

// The FCS computed here, independently of the decoder: the sum of DA..DU modulo 256, or nothing
// for SD4, SC and anything that is not a whole SD1..SD3.
std::optional<bool> checksum_matches(const std::vector<std::uint8_t>& t) {
    std::size_t from = 0;
    std::size_t fcs_at = 0;
    if (t.size() == 6 && t[0] == kSd1) {
        from = 1;
        fcs_at = 4;
    } else if (t.size() == 14 && t[0] == kSd3) {
        from = 1;
        fcs_at = 12;
    } else if (t.size() >= 9 && t[0] == kSd2 && t.size() == std::size_t{t[1]} + 6) {
        from = 4;
        fcs_at = t.size() - 2;
    } else {
        return std::nullopt;
    }
    unsigned sum = 0;
    for (std::size_t i = from; i < fcs_at; ++i)
        sum += t[i];
    return static_cast<std::uint8_t>(sum) == t[fcs_at];
}

void expect_parses_as_built(const Case& c, const std::vector<std::uint8_t>& bytes) {
    FdlTelegram t;
    parse_fdl(span_of(bytes), t);
    EXPECT_TRUE(t.problems.empty()) << problem_message(t.problems[0]);
    EXPECT_EQ(t.type, c.type);
    EXPECT_EQ(t.size, c.bytes.size());
    EXPECT_TRUE(t.fcs_ok);
    if (c.type == FrameType::ShortAck) return;
    EXPECT_EQ(t.da, c.spec.da);
    EXPECT_EQ(t.sa, c.spec.sa);
    if (c.type == FrameType::Sd4) return;
    EXPECT_TRUE(t.has_fcs);
    EXPECT_EQ(t.fc.raw, c.spec.fc);
    EXPECT_EQ(t.has_dsap, c.spec.dsap.has_value());
    EXPECT_EQ(t.has_ssap, c.spec.ssap.has_value());
    EXPECT_EQ(t.dsap, c.spec.dsap.value_or(0));
    EXPECT_EQ(t.ssap, c.spec.ssap.value_or(0));
    EXPECT_EQ(std::vector<std::uint8_t>(t.du.begin(), t.du.end()), c.du);
}

TEST(FramingPropertyTest, EveryKindRoundTripsThroughFramerAndParser) {
    Generator gen(8001);
    for (const Case& c : every_kind(gen)) {
        SCOPED_TRACE(c.name);
        FramingVerdict verdict = fdl_framing_rules().judge(span_of(c.bytes), false);
        EXPECT_EQ(verdict.status, FramingStatus::Telegram);
        EXPECT_EQ(verdict.length, c.bytes.size());
        StreamFramer framer(fdl_framing_rules());
        CollectingSink sink;
        framer.feed(span_of(c.bytes), sink);
        // Whole as soon as its last byte is in: no look-ahead needed for an intact telegram.
        ASSERT_EQ(sink.telegrams.size(), 1u);
        EXPECT_EQ(sink.telegrams[0].bytes, c.bytes);
        EXPECT_EQ(framer.pending(), 0u);
        framer.finish(sink);
        EXPECT_EQ(sink.telegrams.size(), 1u);
        EXPECT_EQ(sink.skipped_bytes, 0u);
        expect_parses_as_built(c, sink.telegrams[0].bytes);
    }
}

TEST(FramingPropertyTest, StreamOfRandomTelegramsRoundTripsInAnyChunks) {
    Generator gen(8002);
    std::vector<Case> cases;
    std::vector<std::uint8_t> stream;
    for (int i = 0; i < 3000; ++i) {
        cases.push_back(gen.any());
        stream.insert(stream.end(), cases.back().bytes.begin(), cases.back().bytes.end());
    }
    StreamFramer framer(fdl_framing_rules());
    CollectingSink sink;
    for (std::size_t at = 0; at < stream.size();) {
        const std::size_t n = std::min<std::size_t>(1 + gen.below(300), stream.size() - at);
        framer.feed(Bytes(stream.data() + at, n), sink);
        at += n;
    }
    framer.finish(sink);
    EXPECT_EQ(sink.skipped_bytes, 0u);
    EXPECT_EQ(sink.accounted, stream.size());
    ASSERT_EQ(sink.telegrams.size(), cases.size());
    std::uint64_t offset = 0;
    for (std::size_t i = 0; i < cases.size(); ++i) {
        SCOPED_TRACE(cases[i].name + " #" + std::to_string(i));
        EXPECT_EQ(sink.telegrams[i].offset, offset);
        EXPECT_EQ(sink.telegrams[i].bytes, cases[i].bytes);
        expect_parses_as_built(cases[i], sink.telegrams[i].bytes);
        offset += cases[i].bytes.size();
    }
}

TEST(FramingPropertyTest, EveryProperPrefixNeedsMore) {
    Generator gen(8003);
    for (const Case& c : every_kind(gen)) {
        SCOPED_TRACE(c.name);
        for (std::size_t n = 0; n < c.bytes.size(); ++n) {
            Bytes prefix(c.bytes.data(), n);
            EXPECT_EQ(fdl_framing_rules().judge(prefix, false).status, FramingStatus::NeedMore)
                << n << " bytes";
            // The framer holds the prefix back, deciding nothing yet.
            StreamFramer framer(fdl_framing_rules());
            CollectingSink sink;
            framer.feed(prefix, sink);
            EXPECT_TRUE(sink.telegrams.empty()) << n << " bytes";
            EXPECT_EQ(sink.accounted, 0u) << n << " bytes";
            EXPECT_EQ(framer.pending(), n);
        }
    }
}

// Frames `bytes` whole and checks what may be believed of every telegram framed.
CollectingSink frame_damaged(const std::vector<std::uint8_t>& bytes) {
    StreamFramer framer(fdl_framing_rules());
    CollectingSink sink;
    framer.feed(span_of(bytes), sink);
    framer.finish(sink);
    EXPECT_EQ(sink.accounted, bytes.size());
    EXPECT_EQ(framer.pending(), 0u);
    for (const Framed& f : sink.telegrams) {
        FdlTelegram t;
        parse_fdl(span_of(f.bytes), t);
        if (!t.has_fcs) continue;
        // The parser's FCS verdict is the checksum's truth, and the framer framed no more and no
        // less than one whole telegram.
        std::optional<bool> matches = checksum_matches(f.bytes);
        EXPECT_TRUE(matches.has_value()) << "framed " << f.bytes.size() << " bytes at " << f.offset;
        if (matches) {
            EXPECT_EQ(t.fcs_ok, *matches) << "at " << f.offset;
        }
    }
    return sink;
}

TEST(FramingPropertyTest, SingleBitErrorsAreNeverTakenForAnIntactTelegram) {
    Generator gen(8004);
    for (const Case& c : every_kind(gen)) {
        SCOPED_TRACE(c.name);
        for (std::size_t bit = 0; bit < c.bytes.size() * 8; ++bit) {
            std::vector<std::uint8_t> damaged = c.bytes;
            damaged[bit / 8] ^= static_cast<std::uint8_t>(1u << (bit % 8));
            CollectingSink sink = frame_damaged(damaged);
            if (c.type == FrameType::Sd4 || c.type == FrameType::ShortAck) continue;  // no FCS
            // A telegram with an FCS framed where the damaged one was is never intact: a single
            // bit error changes its sum, its structure or the frame control.
            for (const Framed& f : sink.telegrams) {
                if (f.offset != 0 || f.bytes.size() != c.bytes.size()) continue;
                FdlTelegram t;
                parse_fdl(span_of(f.bytes), t);
                EXPECT_FALSE(t.problems.empty()) << "bit " << bit;
                EXPECT_FALSE(t.fcs_ok && t.has_fcs && t.type == c.type) << "bit " << bit;
            }
        }
    }
}

TEST(FramingPropertyTest, BitErrorsInAStreamKeepEveryByteAccountedFor) {
    Generator gen(8005);
    for (int round = 0; round < 200; ++round) {
        std::vector<std::uint8_t> stream;
        for (int i = 0; i < 8; ++i) {
            Case c = gen.any();
            stream.insert(stream.end(), c.bytes.begin(), c.bytes.end());
        }
        for (std::uint32_t flips = 1 + gen.below(4); flips > 0; --flips) {
            const std::uint32_t bit = gen.below(static_cast<std::uint32_t>(stream.size() * 8));
            stream[bit / 8] ^= static_cast<std::uint8_t>(1u << (bit % 8));
        }
        SCOPED_TRACE("round " + std::to_string(round));
        frame_damaged(stream);
    }
}

}  // namespace
}  // namespace dpscope
