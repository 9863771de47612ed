// Renderers and summary on Danfoss FC protocol telegrams decoded by FcDecoder from hand-made
// bytes (docs/protocol/fc-protocol.md; the worked examples of protocol.md §4.6 and §5.5): text,
// verbose, jsonl and csv, the decode -q summary, and the --pnu / --station filters.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "formats/renderer.hpp"
#include "formats/summary.hpp"
#include "protocols/fc/fc_decoder.hpp"
#include "protocols/fc/fc_framing_rules.hpp"
#include "tests/json_parser.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::Json;
using test::parse_json;

constexpr std::int64_t kT0 = 1'704'067'200'000'000'000;  // 2024-01-01T00:00:00Z
constexpr std::int64_t kMs = 1'000'000;

// STX LGE ADR data BCC, with the BCC computed.
std::vector<std::uint8_t> telegram(std::uint8_t adr, const std::vector<std::uint8_t>& data) {
    std::vector<std::uint8_t> bytes{kFcStx, static_cast<std::uint8_t>(data.size() + 2), adr};
    for (std::uint8_t b : data)
        bytes.push_back(b);
    bytes.push_back(fc_bcc_of(Bytes(bytes.data(), bytes.size())));
    return bytes;
}

void put16(std::vector<std::uint8_t>& out, std::uint16_t word) {
    out.push_back(static_cast<std::uint8_t>(word >> 8));
    out.push_back(static_cast<std::uint8_t>(word & 0xFF));
}

// PKE IND PWE PCD1 PCD2 of a parameter block.
std::vector<std::uint8_t> parameter(std::uint8_t ak, std::uint16_t pnu, std::uint8_t index,
                                    std::uint32_t pwe, std::uint16_t pcd1, std::uint16_t pcd2) {
    std::vector<std::uint8_t> data;
    put16(data, static_cast<std::uint16_t>((ak << 12) | pnu));
    data.push_back(0);
    data.push_back(index);
    put16(data, static_cast<std::uint16_t>(pwe >> 16));
    put16(data, static_cast<std::uint16_t>(pwe & 0xFFFF));
    put16(data, pcd1);
    put16(data, pcd2);
    return data;
}

// PKE IND characters PCD1 PCD2 of a text block (AK 15).
std::vector<std::uint8_t> text_block(std::uint16_t pnu, std::uint8_t ind_high,
                                     std::string_view text, std::uint16_t pcd1,
                                     std::uint16_t pcd2) {
    std::vector<std::uint8_t> data;
    put16(data, static_cast<std::uint16_t>(0xF000 | pnu));
    data.push_back(ind_high);
    data.push_back(0);
    for (char c : text)
        data.push_back(static_cast<std::uint8_t>(c));
    put16(data, pcd1);
    put16(data, pcd2);
    return data;
}

std::vector<std::uint8_t> process(std::uint16_t pcd1, std::uint16_t pcd2) {
    std::vector<std::uint8_t> data;
    put16(data, pcd1);
    put16(data, pcd2);
    return data;
}

// A session of drive 1 (1-126 format), one telegram every 10 ms:
//   1/2 process block and status; 3/4 read 4-14 and its word; 5/6 write 2-02 (AK 14) and its
//   echo; 7/8 write 4-15 rejected with fault 17; 9/10 read 6-15 index 1 rejected with fault 100
//   (no text); 11/12 read the text of 0-01 and the text; 13 a broadcast; 14 a BCC error;
//   15 a parameter block cut short.
std::vector<std::vector<std::uint8_t>> session() {
    std::vector<std::vector<std::uint8_t>> in;
    in.push_back(telegram(0x81, process(0x047F, 0x2000)));
    in.push_back(telegram(0x81, process(0x0F07, 0x2000)));
    in.push_back(telegram(0x81, parameter(1, 414, 0, 0, 0x047F, 0x2000)));
    in.push_back(telegram(0x81, parameter(1, 414, 0, 10, 0x0F07, 0x2000)));
    in.push_back(telegram(0x81, parameter(14, 202, 0, 1500, 0x047F, 0x2000)));
    in.push_back(telegram(0x81, parameter(1, 202, 0, 1500, 0x0F07, 0x2000)));
    in.push_back(telegram(0x81, parameter(3, 415, 0, 100000, 0x047F, 0x2000)));
    in.push_back(telegram(0x81, parameter(7, 415, 0, 17, 0x0F07, 0x2000)));
    in.push_back(telegram(0x81, parameter(1, 615, 1, 0, 0x047F, 0x2000)));
    in.push_back(telegram(0x81, parameter(7, 615, 1, 100, 0x0F07, 0x2000)));
    in.push_back(telegram(0x81, text_block(1, kFcTextRead, "", 0x047F, 0x2000)));
    in.push_back(telegram(0x81, text_block(1, kFcTextRead, "Eng\"\x01", 0x0F07, 0x2000)));
    in.push_back(telegram(0x20, process(0x0443, 0x0000)));
    std::vector<std::uint8_t> bad = telegram(0x81, process(0x047F, 0x2000));
    bad.back() ^= 0x01;
    in.push_back(bad);
    std::vector<std::uint8_t> cut = telegram(0x81, parameter(1, 414, 0, 0, 0x047F, 0x2000));
    cut.resize(9);
    in.push_back(cut);
    return in;
}

std::string render(OutputFormat format, const std::vector<std::vector<std::uint8_t>>& inputs) {
    return test::output_text([&](Output& out) {
        auto renderer = make_renderer(format, out);
        FcDecoder decoder;
        renderer->begin();
        for (std::size_t i = 0; i < inputs.size(); ++i) {
            const DecodedTelegram& t =
                decoder.decode(Bytes(inputs[i].data(), inputs[i].size()),
                               kT0 + static_cast<std::int64_t>(i) * 10 * kMs, i + 1);
            renderer->render(t, {});
        }
        renderer->render_end_findings({});
        renderer->end();
    });
}

std::vector<std::string> lines(OutputFormat format) {
    return test::lines_of(render(format, session()));
}

TEST(FcRendererTest, TextOneLinePerTelegram) {
    std::vector<std::string> l = lines(OutputFormat::Text);
    ASSERT_EQ(l.size(), 15u);
    EXPECT_EQ(l[0],
              "     1     0.000000   M → 1   FC  process        req ADR 0x81 (1-126) | "
              "CTW=0x047F MRV=50.00%");
    EXPECT_EQ(l[1],
              "     2     0.010000   1 → M   FC  process        rsp ADR 0x81 (1-126) | "
              "STW=0x0F07 MAV=50.00%");
    EXPECT_EQ(l[2],
              "     3     0.020000   M → 1   FC  parameter      req ADR 0x81 (1-126) AK=1 Read "
              "parameter value PNU=414 (4-14) IND=0 PWE=0 | CTW=0x047F MRV=50.00%");
    EXPECT_NE(l[3].find("rsp ADR 0x81 (1-126) AK=1 Parameter value transferred (word) PNU=414 "
                        "(4-14) IND=0 PWE=10 | STW=0x0F07"),
              std::string::npos)
        << l[3];
    EXPECT_NE(l[4].find("AK=14 Write parameter value in RAM and EEPROM (word) PNU=202 (2-02) "
                        "IND=0 PWE=1500"),
              std::string::npos)
        << l[4];
    EXPECT_NE(l[6].find("AK=3 Write parameter value in RAM (double word) PNU=415 (4-15) IND=0 "
                        "PWE=100000"),
              std::string::npos)
        << l[6];
    EXPECT_NE(l[7].find("AK=7 Command cannot be performed PNU=415 (4-15) IND=0 fault 17 (Not "
                        "applicable while running) |"),
              std::string::npos)
        << l[7];
    EXPECT_NE(l[8].find("PNU=615 (6-15) IND=1 PWE=0"), std::string::npos) << l[8];
    EXPECT_NE(l[9].find("fault 100 (unknown fault code)"), std::string::npos) << l[9];
    EXPECT_NE(l[10].find("FC  text           req ADR 0x81 (1-126) AK=15 Read text PNU=1 (0-01) "
                         "IND=0 read text \"\" | CTW"),
              std::string::npos)
        << l[10];
    EXPECT_NE(l[11].find("rsp ADR 0x81 (1-126) AK=15 Text transferred PNU=1 (0-01) IND=0 read "
                         "text \"Eng\\\"\\x01\" | STW"),
              std::string::npos)
        << l[11];
    EXPECT_NE(l[12].find("M → all FC  process        req ADR 0x20 (1-31, broadcast) | "
                         "CTW=0x0443 MRV=0.00%"),
              std::string::npos)
        << l[12];
    EXPECT_NE(l[13].find("| CTW=0x047F MRV=50.00% [bcc_mismatch]"), std::string::npos) << l[13];
    EXPECT_NE(l[14].find("FC  parameter      req ADR 0x81 (1-126) data 11 9E 00 00 00 00 "
                         "[truncated]"),
              std::string::npos)
        << l[14];
}

TEST(FcRendererTest, TextWithoutAddressByteShowsTheBytes) {
    std::string text = render(OutputFormat::Text, {{0x10, 0x02}, {0x02}});
    std::vector<std::string> l = test::lines_of(text);
    ASSERT_EQ(l.size(), 2u);
    EXPECT_NE(l[0].find("  ? → ?   bad unknown        req 10 02 [bad_start_delimiter]"),
              std::string::npos)
        << l[0];
    EXPECT_NE(l[1].find("bad unknown        req 02 [truncated]"), std::string::npos) << l[1];
}

// LGE 7 names no block: the data bytes are shown; the long-format broadcast 0x80.
TEST(FcRendererTest, UnknownBlockAndLongBroadcast) {
    std::vector<std::vector<std::uint8_t>> in = {
        telegram(0x81, {0x04, 0x7F, 0x20, 0x00, 0x00}),
        telegram(0x80, process(0x047F, 0x2000)),
    };
    std::vector<std::string> l = test::lines_of(render(OutputFormat::Text, in));
    ASSERT_EQ(l.size(), 2u);
    EXPECT_NE(l[0].find("M → 1   FC  unknown        req ADR 0x81 (1-126) data 04 7F 20 00 00 "
                        "DF [lge_invalid]"),
              std::string::npos)
        << l[0];
    EXPECT_NE(l[1].find("M → all FC  process        req ADR 0x80 (1-126, broadcast) | "),
              std::string::npos)
        << l[1];
    std::string verbose = render(OutputFormat::Verbose, in);
    EXPECT_NE(verbose.find("    LGE: 7 (no block has this length; telegram 9 bytes)\n"
                           "    ADR: 0x81 (1-126 format, address 1)\n    BCC: 0xDF (correct)\n"),
              std::string::npos)
        << verbose;
    EXPECT_NE(verbose.find("    ADR: 0x80 (1-126 format, broadcast)\n"), std::string::npos)
        << verbose;
    std::vector<std::string> j = test::lines_of(render(OutputFormat::Jsonl, in));
    ASSERT_EQ(j.size(), 2u);
    auto unknown = parse_json(j[0]);
    ASSERT_TRUE(unknown);
    EXPECT_EQ((*unknown)["fc_protocol"]["block"].string(), "unknown");
    EXPECT_EQ((*unknown)["fc_protocol"]["lge"].integer(), 7);
    EXPECT_TRUE((*unknown)["fc_protocol"]["pcd1"].is_null());
    EXPECT_EQ((*unknown)["problems"][0]["kind"].string(), "lge_invalid");
    auto broadcast = parse_json(j[1]);
    ASSERT_TRUE(broadcast);
    EXPECT_TRUE((*broadcast)["fc_protocol"]["broadcast"].boolean);
    EXPECT_EQ((*broadcast)["fc_protocol"]["address"].integer(), 0);
    EXPECT_EQ((*broadcast)["slave"].integer(), 0);
}

const std::vector<std::string> kFcJsonKeys = {"frame",    "time",    "len",           "direction",
                                              "master",   "slave",   "request_frame", "fc_protocol",
                                              "problems", "findings"};

const std::vector<std::string> kFcProtocolKeys = {
    "lge",          "adr",        "address",      "address_format", "broadcast",    "block",
    "complete",     "pke",        "ak",           "ak_name",        "ak_known",     "pnu",
    "parameter",    "index",      "ind_high",     "text_mode",      "text",         "text_hex",
    "pwe",          "pwe_raw",    "width",        "pnu_name",       "value_scaled", "unit",
    "fault_code",   "fault_text", "pcd1",         "pcd1_word",      "pcd1_bits",    "pcd2",
    "pcd2_percent", "bcc",        "bcc_computed", "bcc_ok"};

std::vector<Json> jsonl() {
    std::vector<Json> out;
    for (const std::string& line : lines(OutputFormat::Jsonl)) {
        auto parsed = parse_json(line);
        EXPECT_TRUE(parsed) << line;
        if (!parsed) continue;
        EXPECT_EQ(parsed->keys(), kFcJsonKeys) << line;
        EXPECT_EQ((*parsed)["fc_protocol"].keys(), kFcProtocolKeys) << line;
        // No FDL or DP key on an FC line.
        for (std::string_view key : {"sd", "da", "sa", "dsap", "ssap", "fc", "fcs_ok", "service",
                                     "ppo", "pcv", "pcd", "diag", "prm", "cfg", "data"})
            EXPECT_EQ(parsed->find(key), nullptr) << key << " in " << line;
        out.push_back(std::move(*parsed));
    }
    return out;
}

TEST(FcRendererTest, JsonlCommonKeysAndTheFcProtocolObject) {
    std::vector<Json> j = jsonl();
    ASSERT_EQ(j.size(), 15u);
    const Json& read = j[2];
    EXPECT_EQ(read["frame"].integer(), 3);
    EXPECT_EQ(read["time"].text, "1704067200.020000000");
    EXPECT_EQ(read["len"].integer(), 16);
    EXPECT_EQ(read["direction"].string(), "request");
    EXPECT_EQ(read["master"].integer(), 0);
    EXPECT_EQ(read["slave"].integer(), 1);
    EXPECT_TRUE(read["request_frame"].is_null());
    const Json& p = read["fc_protocol"];
    EXPECT_EQ(p["lge"].integer(), 14);
    EXPECT_EQ(p["adr"].integer(), 0x81);
    EXPECT_EQ(p["address"].integer(), 1);
    EXPECT_EQ(p["address_format"].string(), "1-126");
    EXPECT_FALSE(p["broadcast"].boolean);
    EXPECT_EQ(p["block"].string(), "parameter");
    EXPECT_TRUE(p["complete"].boolean);
    EXPECT_EQ(p["pke"].integer(), 0x119E);
    EXPECT_EQ(p["ak"].integer(), 1);
    EXPECT_EQ(p["ak_name"].string(), "Read parameter value");
    EXPECT_TRUE(p["ak_known"].boolean);
    EXPECT_EQ(p["pnu"].integer(), 414);
    EXPECT_EQ(p["parameter"].string(), "4-14");
    EXPECT_EQ(p["index"].integer(), 0);
    EXPECT_TRUE(p["text_mode"].is_null());
    EXPECT_TRUE(p["text"].is_null());
    EXPECT_EQ(p["pwe"].integer(), 0);
    EXPECT_TRUE(p["width"].is_null());
    EXPECT_TRUE(p["fault_code"].is_null());
    EXPECT_EQ(p["pcd1"].integer(), 0x047F);
    EXPECT_EQ(p["pcd1_word"].string(), "control");
    ASSERT_EQ(p["pcd1_bits"].items.size(), 16u);
    EXPECT_EQ(p["pcd2"].integer(), 0x2000);
    EXPECT_EQ(p["pcd2_percent"].text, "50.00");
    EXPECT_EQ(p["bcc"].integer(), 0x59);
    EXPECT_TRUE(p["bcc_ok"].boolean);

    const Json& answer = j[3];
    EXPECT_EQ(answer["direction"].string(), "response");
    EXPECT_EQ(answer["request_frame"].integer(), 3);
    EXPECT_EQ(answer["fc_protocol"]["ak_name"].string(), "Parameter value transferred (word)");
    EXPECT_EQ(answer["fc_protocol"]["pwe"].integer(), 10);
    EXPECT_EQ(answer["fc_protocol"]["width"].string(), "word");
    EXPECT_EQ(answer["fc_protocol"]["pcd1_word"].string(), "status");

    EXPECT_EQ(j[6]["fc_protocol"]["width"].string(), "dword");
    EXPECT_EQ(j[6]["fc_protocol"]["pwe"].integer(), 100000);
    const Json& rejected = j[7]["fc_protocol"];
    EXPECT_EQ(rejected["fault_code"].integer(), 17);
    EXPECT_EQ(rejected["fault_text"].string(), "Not applicable while running");
    EXPECT_TRUE(rejected["pwe"].is_null());
    EXPECT_EQ(rejected["pwe_raw"].integer(), 17);
    EXPECT_EQ(j[9]["fc_protocol"]["fault_code"].integer(), 100);
    EXPECT_EQ(j[9]["fc_protocol"]["fault_text"].string(), "unknown fault code");
    EXPECT_EQ(j[9]["fc_protocol"]["index"].integer(), 1);

    const Json& text_request = j[10]["fc_protocol"];
    EXPECT_EQ(text_request["block"].string(), "text");
    EXPECT_EQ(text_request["ind_high"].integer(), 4);
    EXPECT_EQ(text_request["text_mode"].string(), "read");
    EXPECT_EQ(text_request["text"].string(), "");
    EXPECT_TRUE(text_request["pwe"].is_null());
    const Json& text = j[11]["fc_protocol"];
    EXPECT_EQ(text["ak_name"].string(), "Text transferred");
    EXPECT_EQ(text["text"].string(), "Eng\\\"\\x01");
    EXPECT_EQ(text["text_hex"].string(), "456E672201");

    const Json& broadcast = j[12];
    EXPECT_EQ(broadcast["slave"].integer(), 0);
    EXPECT_TRUE(broadcast["fc_protocol"]["broadcast"].boolean);
    EXPECT_EQ(broadcast["fc_protocol"]["address_format"].string(), "1-31");
    EXPECT_TRUE(broadcast["fc_protocol"]["ak"].is_null());

    const Json& bad = j[13];
    EXPECT_FALSE(bad["fc_protocol"]["bcc_ok"].boolean);
    EXPECT_EQ(bad["fc_protocol"]["bcc_computed"].integer(), 0xDE);
    ASSERT_EQ(bad["problems"].items.size(), 1u);
    EXPECT_EQ(bad["problems"][0]["kind"].string(), "bcc_mismatch");

    const Json& cut = j[14]["fc_protocol"];
    EXPECT_FALSE(cut["complete"].boolean);
    EXPECT_TRUE(cut["bcc"].is_null());
    EXPECT_TRUE(cut["bcc_ok"].is_null());
    EXPECT_TRUE(cut["pcd1"].is_null());
    EXPECT_EQ(j[14]["problems"][0]["kind"].string(), "truncated");
}

TEST(FcRendererTest, VerboseFieldsOnePerLine) {
    std::string text = render(OutputFormat::Verbose, session());
    for (std::string_view expected : {
             "Frame 3: 16 bytes, 2024-01-01T00:00:00.020000000Z\n"
             "    Bytes: 02 0E 81 11 9E 00 00 00 00 00 00 04 7F 20 00 59\n"
             "FC protocol: parameter block request to drive 1\n"
             "    STX: 0x02\n"
             "    LGE: 14 (parameter block, telegram 16 bytes)\n"
             "    ADR: 0x81 (1-126 format, address 1)\n"
             "    PKE: 0x119E\n"
             "        AK: 1 = Read parameter value\n"
             "        PNU: 414 (parameter 4-14)\n"
             "    IND: 0x0000\n"
             "        high byte: 0x00\n"
             "        index (low byte): 0\n"
             "    PWE: 0x00000000 (the AK carries no value)\n"
             "    PCD 1 CTW: 0x047F (control word, FC profile)\n"
             "        bit  0 = 1: ",
             "    PCD 2 MRV: 0x2000 = 50.00 %\n    BCC: 0x59 (correct)\n\n",
             "FC protocol: parameter block response from drive 1, answers frame 3\n",
             "    PWE: 0x0000000A, word value 10\n",
             "    PCD 1 STW: 0x0F07 (status word, FC profile)\n",
             "        Fault code: 17 = Not applicable while running\n",
             "        Fault code: 100 = unknown fault code\n",
             "        high byte: 0x04 (read text)\n",
             "    Text: 0 characters \"\"\n",
             "    Text: 5 characters \"Eng\\\"\\x01\"\n",
             "FC protocol: process block request to every drive (broadcast)\n",
             "    ADR: 0x20 (1-31 format, broadcast)\n",
             "    BCC: 0xDF (wrong: computed 0xDE)\nProblems\n    bcc_mismatch (error): ",
             "    BCC: missing (telegram cut short)\nProblems\n    truncated (error): ",
         })
        EXPECT_NE(text.find(expected), std::string::npos) << expected << "\n---\n" << text;
    // The FDL tree is a PROFIBUS thing.
    EXPECT_EQ(text.find("PROFIBUS"), std::string::npos);
}

TEST(FcRendererTest, CsvRowsHaveTheHeaderColumns) {
    std::vector<std::string> l = lines(OutputFormat::Csv);
    ASSERT_EQ(l.size(), 16u);
    auto columns = [](const std::string& row) {
        std::size_t n = 1;
        bool quoted = false;
        for (char c : row) {
            if (c == '"') quoted = !quoted;
            if (c == ',' && !quoted) ++n;
        }
        return n;
    };
    for (const std::string& row : l)
        EXPECT_EQ(columns(row), columns(l[0])) << row;
    EXPECT_EQ(l[3],
              "3,1704067200.020000000,16,,,,,,,parameter,request,0,1,,true,,1,,414,0,0,"
              "\"Read parameter value\",,,047F 2000,\"ADR 0x81 (1-126) AK=1 Read parameter value "
              "PNU=414 (4-14) IND=0 PWE=0 | CTW=0x047F MRV=50.00%\",,,,,");
    EXPECT_NE(l[8].find(",response,0,1,7,true,,7,,415,0,,\"Command cannot be performed\",17,"
                        "\"Not applicable while running\",0F07 2000,"),
              std::string::npos)
        << l[8];
    EXPECT_NE(l[10].find(",\"Command cannot be performed\",100,\"unknown fault code\","),
              std::string::npos)
        << l[10];
    EXPECT_NE(l[1].find(",process,request,0,1,,true,,,,,,,,,,047F 2000,"), std::string::npos)
        << l[1];
    EXPECT_NE(l[14].find(",false,,,,,,,,,,047F 2000,"), std::string::npos) << l[14];
    EXPECT_NE(l[14].find(",bcc_mismatch@7,"), std::string::npos) << l[14];
    EXPECT_NE(l[15].find(",truncated@9,"), std::string::npos) << l[15];
}

std::string summary_text(const Summary& summary) {
    return test::output_text([&](Output& out) {
        BusDecoder decoder;
        summary.render_text(out, InputSummary{"fc.hex", "hex", 0, false}, decoder);
    });
}

TEST(FcRendererTest, SummaryCountsBlocksAndAks) {
    Summary summary;
    FcDecoder decoder;
    std::vector<std::vector<std::uint8_t>> in = session();
    for (std::size_t i = 0; i < in.size(); ++i)
        summary.add(decoder.decode(Bytes(in[i].data(), in[i].size()),
                                   kT0 + static_cast<std::int64_t>(i) * 10 * kMs, i + 1));
    EXPECT_EQ(summary.telegrams(), 15u);
    EXPECT_EQ(summary.fc_telegrams(), 15u);
    EXPECT_EQ(summary.fc_blocks(FcBlock::Process), 4u);
    EXPECT_EQ(summary.fc_blocks(FcBlock::Parameter), 9u);
    EXPECT_EQ(summary.fc_blocks(FcBlock::Text), 2u);
    EXPECT_EQ(summary.fc_commands(1), 2u);  // the cut-short read carries no PKW
    EXPECT_EQ(summary.fc_responses(7), 2u);
    EXPECT_EQ(summary.with_problems(), 2u);
    std::string text = summary_text(summary);
    EXPECT_EQ(text.find("by frame type"), std::string::npos) << text;
    EXPECT_EQ(text.find("invalid"), std::string::npos) << text;
    EXPECT_EQ(text.find("by service"), std::string::npos) << text;
    for (std::string_view expected :
         {"  telegrams: 15, from 2024-01-01T00:00:00.000000000Z",
          "  bus: FC protocol\n  by block: process 4 parameter 9 text 2\n",
          "  by direction: 9 requests, 6 responses (1 broadcast)\n",
          "  parameter commands:\n    AK  1 Read parameter value",
          "    AK 14 Write parameter value in RAM and EEPROM (word)",
          "  parameter responses:\n    AK  1 Parameter value transferred (word)",
          "    AK  7 Command cannot be performed                                     2\n",
          "    bcc_mismatch", "  drives:\n      1: 8 commands, 6 responses\n"})
        EXPECT_NE(text.find(expected), std::string::npos) << expected << "\n---\n" << text;
}

// --pnu selects FC telegrams by their PKW's PNU (requests and the answers that echo it); --station
// by the drive's address.
TEST(FcRendererTest, PnuAndStationFiltersSelectFcTelegrams) {
    test::CommandResult r = test::run_dpscope(
        {"decode", "--bus", "fc", "--pnu", "414", "-T", "jsonl", "samples/fc-examples.hex"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    std::vector<std::string> l = test::lines_of(r.out);
    ASSERT_EQ(l.size(), 2u) << r.out;
    for (const std::string& line : l)
        EXPECT_NE(line.find("\"pnu\":414,"), std::string::npos) << line;
    EXPECT_EQ(r.err, "");

    test::CommandResult none =
        test::run_dpscope({"decode", "--bus", "fc", "--pnu", "999", "samples/fc-examples.hex"});
    EXPECT_EQ(none.out, "");
    EXPECT_NE(none.err.find("--pnu 999: no parameter request or answer about PNU 999"),
              std::string::npos)
        << none.err;

    test::CommandResult station =
        test::run_dpscope({"decode", "--bus", "fc", "--station", "1", "samples/fc-examples.hex"});
    EXPECT_EQ(station.exit_code, 0) << station.err;
    // Everything but the broadcast goes to or comes from drive 1 (in either address format).
    EXPECT_EQ(test::lines_of(station.out).size(), 16u) << station.out;
    EXPECT_EQ(station.out.find("broadcast"), std::string::npos) << station.out;
}

TEST(FcRendererTest, ProfibusOnlyOptionsOnAnFcCaptureAreNamedAsIgnored) {
    test::CommandResult r = test::run_dpscope(
        {"decode", "-q", "--dialect", "ge", "--pcd-profile", "profidrive", "samples/fc.pcap"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err,
              "dpscope: warning: samples/fc.pcap: --dialect, --pcd-profile apply to PROFIBUS DP; "
              "this capture is the FC protocol (RS-485): ignored\n");
    // Options of the other serial buses are named too.
    test::CommandResult vlt = test::run_dpscope(
        {"decode", "-q", "--fc-pnu-bits", "11", "--strict", "samples/vlt2000-examples.txt"});
    EXPECT_EQ(vlt.exit_code, 0) << vlt.err;
    EXPECT_NE(vlt.err.find("dpscope: warning: samples/vlt2000-examples.txt: --strict applies to "
                           "PROFIBUS DP; this capture is the VLT 2000 telegram: ignored\n"),
              std::string::npos)
        << vlt.err;
    EXPECT_NE(vlt.err.find("--fc-pnu-bits applies to the FC protocol (RS-485); this capture is "
                           "the VLT 2000 telegram: ignored"),
              std::string::npos)
        << vlt.err;
    test::CommandResult fc =
        test::run_dpscope({"decode", "-q", "--vlt2000-checksum", "ignore", "samples/fc.pcap"});
    EXPECT_EQ(fc.err,
              "dpscope: warning: samples/fc.pcap: --vlt2000-checksum applies to the VLT 2000 "
              "telegram; this capture is the FC protocol (RS-485): ignored\n");
    test::CommandResult dp =
        test::run_dpscope({"decode", "-q", "--dialect", "ge", "samples/ge.pcap"});
    EXPECT_EQ(dp.err, "");
}

TEST(FcRendererTest, TextWriteIsNamedByTheIndHighByte) {
    // AK 15 with IND high byte 0x05 writes the text (FC 102 guide: "read/write text").
    const std::string text =
        render(OutputFormat::Text,
               {telegram(0x81, text_block(1, kFcTextWrite, "Deutsch", 0x047F, 0x2000))});
    EXPECT_NE(text.find("AK=15 Write text PNU=1"), std::string::npos) << text;
    const std::string read = render(
        OutputFormat::Text, {telegram(0x81, text_block(1, kFcTextRead, "", 0x047F, 0x2000))});
    EXPECT_NE(read.find("AK=15 Read text PNU=1"), std::string::npos) << read;
}

}  // namespace
}  // namespace dpscope
