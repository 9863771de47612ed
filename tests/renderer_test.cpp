// Renderers: text, verbose, jsonl and csv on telegrams decoded by BusDecoder. The jsonl lines are
// checked with a strict JSON parser written here (the project has no JSON library).
#include "formats/renderer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "formats/json.hpp"
#include "protocols/profibus/bus_decoder.hpp"
#include "protocols/profibus/telegram_builder.hpp"
#include "simulator/simulator.hpp"
#include "tests/json_parser.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::Json;
using test::JsonParser;
using test::parse_json;

using test::hex;

std::vector<std::string> split_lines(const std::string& text) {
    std::vector<std::string> lines;
    std::size_t start = 0;
    while (start < text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string::npos) {
            ADD_FAILURE() << "last line has no newline";
            end = text.size();
        }
        lines.push_back(text.substr(start, end - start));
        start = end + 1;
    }
    return lines;
}

TEST(RendererTest, JsonCheckerAcceptsValidAndRejectsBrokenJson) {
    std::string error;
    EXPECT_TRUE(JsonParser(R"({"a":[1,-2.5e3,true,null,"x\"\u00e9"],"b":{}})").parse(error));
    auto parsed = JsonParser(R"("\u00e9\n")").parse(error);
    ASSERT_TRUE(parsed);
    EXPECT_EQ(parsed->text, "\xC3\xA9\n");
    for (std::string_view broken :
         {"", "{", R"({"a":1,})", R"({"a" 1})", "[1,]", "01", "1.", "-", R"("a)", "\"\x01\"",
          R"("\x")", R"({"a":1,"a":2})", "{} {}", "nul", "[1 2]", R"({a:1})"}) {
        std::string message;
        EXPECT_FALSE(JsonParser(broken).parse(message)) << broken;
    }
}

// ---- rendering helpers -----------------------------------------------------------------------

constexpr std::int64_t kT0 = 1'704'067'200'000'000'000;  // 2024-01-01T00:00:00Z
constexpr std::uint8_t kMaster = 2;
constexpr std::uint8_t kSlave = 3;

struct Input {
    std::vector<std::uint8_t> bytes;
    std::int64_t time_ns = kNoTime;
    std::vector<Finding> findings;
};

std::string render(OutputFormat format, const std::vector<Input>& inputs,
                   DecoderOptions options = {}, std::span<const Finding> end_findings = {}) {
    return test::output_text([&](Output& out) {
        auto renderer = make_renderer(format, out);
        BusDecoder decoder(options);
        renderer->begin();
        for (std::size_t i = 0; i < inputs.size(); ++i) {
            const Input& input = inputs[i];
            const DecodedTelegram& t =
                decoder.decode(Bytes(input.bytes.data(), input.bytes.size()), input.time_ns, i + 1);
            renderer->render(t, input.findings);
        }
        renderer->render_end_findings(end_findings);
        renderer->end();
    });
}

std::vector<std::uint8_t> request(std::optional<std::uint8_t> dsap, std::vector<std::uint8_t> du,
                                  FdlFunction function = FdlFunction::SrdHigh) {
    return build_telegram({kSlave, kMaster, request_fc(function, true, true), dsap,
                           dsap ? std::optional<std::uint8_t>(62) : std::nullopt, Bytes(du)});
}

std::vector<std::uint8_t> response(std::optional<std::uint8_t> ssap, std::vector<std::uint8_t> du) {
    return build_telegram({kMaster, kSlave, response_fc(FdlStatus::DataLow),
                           ssap ? std::optional<std::uint8_t>(62) : std::nullopt, ssap, Bytes(du)});
}

std::vector<std::uint8_t> pcv_and_pcd(std::uint8_t rc, bool spm, std::uint16_t pnu,
                                      std::uint8_t ind, std::uint32_t pva, std::uint16_t word1,
                                      std::uint16_t word2) {
    std::vector<std::uint8_t> du;
    append_pcv(du, rc, spm, pnu, ind, pva);
    append_u16_be(du, word1);
    append_u16_be(du, word2);
    return du;
}

// Start-up of slave 3 as PPO 1, then a parameter write, a rejected read, a token.
std::vector<Input> session() {
    std::vector<Input> in;
    auto add = [&](std::vector<std::uint8_t> bytes) {
        in.push_back({std::move(bytes), kT0 + static_cast<std::int64_t>(in.size()) * 100'000, {}});
    };
    add(request(61, {0x88, 10, 10, 11, 0x04, 0x02, 0x00}));                          // 1 Set_Prm
    add(hex("E5"));                                                                  // 2 SC
    add(request(62, {0xF3, 0xF1}));                                                  // 3 Chk_Cfg
    add(hex("E5"));                                                                  // 4 SC
    add(request(60, {}));                                                            // 5 Slave_Diag
    add(response(60, {0x00, 0x0C, 0x00, 0x02, 0x04, 0x02}));                         // 6 diag
    add(request(std::nullopt, pcv_and_pcd(2, false, 215, 0, 17, 0x047F, 0x2000)));   // 7 DE
    add(response(std::nullopt, pcv_and_pcd(1, true, 215, 0, 17, 0x0F07, 0x2000)));   // 8 DE
    add(request(std::nullopt, pcv_and_pcd(1, false, 999, 0, 0, 0x047F, 0x2000)));    // 9 DE
    add(response(std::nullopt, pcv_and_pcd(7, false, 999, 0, 17, 0x0F07, 0x2000)));  // 10 RC 7
    add(hex("DC 02 02"));                                                            // 11 token
    add(build_telegram(
        {127, kMaster, request_fc(FdlFunction::SdnHigh), 58, 62, Bytes(hex("08 00"))}));  // 12 GC
    return in;
}

const std::vector<std::string> kJsonKeys = {
    "frame",      "time",     "len",           "sd",
    "da",         "sa",       "dsap",          "ssap",
    "fc",         "fcs_ok",   "service",       "direction",
    "master",     "slave",    "request_frame", "ppo",
    "ppo_source", "dialect",  "pcv",           "pcd",
    "diag",       "prm",      "cfg",           "global_control",
    "data",       "problems", "findings"};

const std::vector<std::string> kPcvKeys = {
    "pca",   "rc",       "spm",          "pnu",  "ind",     "ind_low",    "pva",   "pva_raw",
    "width", "pnu_name", "value_scaled", "unit", "meaning", "code_known", "error", "error_text"};

std::vector<Json> jsonl(const std::vector<Input>& inputs, DecoderOptions options = {}) {
    std::vector<Json> out;
    for (const std::string& line : split_lines(render(OutputFormat::Jsonl, inputs, options))) {
        auto parsed = parse_json(line);
        if (!parsed) continue;
        EXPECT_EQ(parsed->type, Json::Type::Object) << line;
        EXPECT_EQ(parsed->keys(), kJsonKeys) << line;
        out.push_back(std::move(*parsed));
    }
    return out;
}

// ---- jsonl -----------------------------------------------------------------------------------

TEST(RendererTest, JsonlEveryLineIsOneObjectWithTheDocumentedKeys) {
    SimulatorOptions options;
    options.seed = 3;
    options.cycles = 30;
    options.faults = {FaultSpec{FaultKind::Garbage, 0, 5, std::nullopt},
                      FaultSpec{FaultKind::MalformedTelegram, 0, 7, std::nullopt}};
    Simulator simulator(options);
    std::vector<Input> inputs;
    std::vector<std::uint8_t> bytes;
    std::int64_t time_ns = 0;
    while (simulator.next(bytes, time_ns))
        inputs.push_back({bytes, time_ns, {}});
    std::vector<Json> lines = jsonl(inputs);
    ASSERT_EQ(lines.size(), inputs.size());
    for (std::size_t i = 0; i < lines.size(); ++i) {
        EXPECT_EQ(lines[i]["frame"].integer(), static_cast<long long>(i + 1));
        EXPECT_EQ(lines[i]["len"].integer(), static_cast<long long>(inputs[i].bytes.size()));
        const Json& pcv = lines[i]["pcv"];
        if (!pcv.is_null()) {
            EXPECT_EQ(pcv.keys(), kPcvKeys);
        }
    }
}

// The "fc" object of every frame control byte (jsonl copies it from a text made once a byte):
// its bits and names as the FDL layer reads them.
TEST(RendererTest, JsonlFcObjectOfEveryFrameControlByte) {
    std::vector<Input> inputs;
    for (int raw = 0; raw < 256; ++raw) {
        const auto fc = static_cast<std::uint8_t>(raw);
        const auto fcs = static_cast<std::uint8_t>(3 + kMaster + fc);
        inputs.push_back({{0x10, 3, kMaster, fc, fcs, 0x16}, kT0 + raw * 1000, {}});
    }
    std::vector<Json> lines = jsonl(inputs);
    ASSERT_EQ(lines.size(), 256u);
    for (int raw = 0; raw < 256; ++raw) {
        const FrameControl fc{static_cast<std::uint8_t>(raw)};
        const Json& object = lines[static_cast<std::size_t>(raw)]["fc"];
        EXPECT_EQ(object["raw"].integer(), raw);
        EXPECT_EQ(object["request"].boolean, fc.is_request()) << raw;
        if (fc.is_request()) {
            EXPECT_EQ(object.keys(),
                      (std::vector<std::string>{"raw", "request", "fcb", "fcv", "function"}));
            EXPECT_EQ(object["fcb"].boolean, fc.fcb()) << raw;
            EXPECT_EQ(object["fcv"].boolean, fc.fcv()) << raw;
            EXPECT_EQ(object["function"].string(), request_function_name(fc)) << raw;
        } else {
            EXPECT_EQ(object.keys(),
                      (std::vector<std::string>{"raw", "request", "station", "status"}));
            EXPECT_EQ(object["station"].string(), station_type_name(fc.station_type())) << raw;
            EXPECT_EQ(object["status"].string(), response_status_name(fc.function())) << raw;
        }
    }
    // The "service" and "direction" members (copied from texts made once per pair) name what the
    // decoder made of each telegram.
    BusDecoder decoder;
    for (std::size_t i = 0; i < inputs.size(); ++i) {
        const DecodedTelegram& t = decoder.decode(Bytes(inputs[i].bytes), inputs[i].time_ns, i + 1);
        EXPECT_EQ(lines[i]["service"].string(), service_name(t.dp.service)) << i;
        EXPECT_EQ(lines[i]["direction"].string(), direction_name(t.direction)) << i;
    }
}

TEST(RendererTest, JsonlDataExchangeWithPcv) {
    std::vector<Json> lines = jsonl(session());
    ASSERT_EQ(lines.size(), 12u);
    const Json& request = lines[6];
    EXPECT_EQ(request["frame"].integer(), 7);
    EXPECT_EQ(request["time"].text, "1704067200.000600000");
    EXPECT_EQ(request["len"].integer(), 21);
    EXPECT_EQ(request["sd"].string(), "SD2");
    EXPECT_EQ(request["da"].integer(), 3);
    EXPECT_EQ(request["sa"].integer(), 2);
    EXPECT_TRUE(request["dsap"].is_null());
    EXPECT_TRUE(request["ssap"].is_null());
    EXPECT_EQ(request["fc"]["raw"].integer(), 0x7D);
    EXPECT_TRUE(request["fc"]["request"].boolean);
    EXPECT_TRUE(request["fc"]["fcb"].boolean);
    EXPECT_TRUE(request["fc"]["fcv"].boolean);
    EXPECT_EQ(request["fc"]["function"].string(), "SRD high");
    EXPECT_TRUE(request["fcs_ok"].boolean);
    EXPECT_EQ(request["service"].string(), "Data_Exchange");
    EXPECT_EQ(request["direction"].string(), "request");
    EXPECT_EQ(request["master"].integer(), 2);
    EXPECT_EQ(request["slave"].integer(), 3);
    EXPECT_TRUE(request["request_frame"].is_null());
    EXPECT_EQ(request["ppo"].integer(), 1);
    EXPECT_EQ(request["ppo_source"].string(), "chk_cfg");
    EXPECT_EQ(request["dialect"].string(), "vlt");
    const Json& pcv = request["pcv"];
    EXPECT_EQ(pcv.keys(), kPcvKeys);
    EXPECT_EQ(pcv["pca"].integer(), 0x2000 | 215);
    EXPECT_EQ(pcv["rc"].integer(), 2);
    EXPECT_EQ(pcv["spm"].integer(), 0);
    EXPECT_EQ(pcv["pnu"].integer(), 215);
    EXPECT_EQ(pcv["ind"].integer(), 0);
    EXPECT_EQ(pcv["ind_low"].integer(), 0);
    EXPECT_EQ(pcv["pva"].integer(), 17);
    EXPECT_EQ(pcv["pva_raw"].integer(), 17);
    EXPECT_EQ(pcv["width"].string(), "word");
    EXPECT_EQ(pcv["meaning"].string(), "Change parameter value (word)");
    EXPECT_TRUE(pcv["code_known"].boolean);
    EXPECT_TRUE(pcv["error"].is_null());
    EXPECT_TRUE(pcv["error_text"].is_null());
    ASSERT_EQ(request["pcd"].items.size(), 2u);
    EXPECT_EQ(request["pcd"][0].integer(), 0x047F);
    EXPECT_EQ(request["pcd"][1].integer(), 0x2000);
    EXPECT_EQ(request["data"].string(), "20D7000000000011047F2000");
    for (const char* key : {"diag", "prm", "cfg", "global_control"})
        EXPECT_TRUE(request[key].is_null()) << key;
    EXPECT_TRUE(request["problems"].items.empty());
    EXPECT_EQ(request["problems"].type, Json::Type::Array);
    EXPECT_EQ(request["findings"].type, Json::Type::Array);

    const Json& answer = lines[7];
    EXPECT_EQ(answer["direction"].string(), "response");
    EXPECT_EQ(answer["request_frame"].integer(), 7);
    EXPECT_EQ(answer["master"].integer(), 2);
    EXPECT_EQ(answer["slave"].integer(), 3);
    EXPECT_FALSE(answer["fc"]["request"].boolean);
    EXPECT_EQ(answer["fc"]["station"].string(), "slave");
    EXPECT_EQ(answer["fc"]["status"].string(), "DL");
    EXPECT_EQ(answer["fc"].find("fcb"), nullptr);
    EXPECT_EQ(answer["pcv"]["rc"].integer(), 1);
    EXPECT_EQ(answer["pcv"]["spm"].integer(), 1);
    EXPECT_EQ(answer["pcv"]["pca"].integer(), 0x1000 | 0x0800 | 215);
    EXPECT_EQ(answer["pcv"]["meaning"].string(), "Transmit parameter value (word)");
    EXPECT_EQ(answer["pcd"][0].integer(), 0x0F07);
}

TEST(RendererTest, JsonlRejectedRequestCarriesErrorNumberAndText) {
    std::vector<Json> lines = jsonl(session());
    ASSERT_EQ(lines.size(), 12u);
    const Json& pcv = lines[9]["pcv"];
    EXPECT_EQ(pcv["rc"].integer(), 7);
    EXPECT_EQ(pcv["pnu"].integer(), 999);
    EXPECT_EQ(pcv["meaning"].string(), "Request not executable");
    EXPECT_EQ(pcv["error"].integer(), 17);
    EXPECT_EQ(pcv["error_text"].string(), "Request temporarily unexecutable");
    EXPECT_EQ(pcv["pva"].integer(), 17);

    // An error number the dialect does not know: the number, named as unknown.
    std::vector<Input> unknown = session();
    unknown[9].bytes = response(std::nullopt, pcv_and_pcd(7, false, 999, 0, 77, 0x0F07, 0x2000));
    std::vector<Json> again = jsonl(unknown);
    ASSERT_EQ(again.size(), 12u);
    EXPECT_EQ(again[9]["pcv"]["error"].integer(), 77);
    EXPECT_EQ(again[9]["pcv"]["error_text"].string(), "unknown error number");
}

// GE's fault number 131 [S002]: named in the ge dialect, an unknown error number in vlt, the
// same words in every format.
TEST(RendererTest, ErrorNumber131PerDialectInEveryFormat) {
    std::vector<Input> in = session();
    in[9].bytes = response(std::nullopt, pcv_and_pcd(7, false, 999, 0, 131, 0x0F07, 0x2000));
    const std::string ge_text =
        "Data change is not possible because factory setup has been selected";
    DecoderOptions ge;
    ge.dialect = Dialect::Ge;
    DecoderOptions ge_station;
    ge_station.station_dialect[3] = Dialect::Ge;
    for (const DecoderOptions& options : {ge, ge_station}) {
        EXPECT_EQ(jsonl(in, options)[9]["pcv"]["error_text"].string(), ge_text);
        EXPECT_EQ(jsonl(in, options)[9]["dialect"].string(), "ge");
        EXPECT_NE(render(OutputFormat::Text, in, options).find("error 131 (" + ge_text + ")"),
                  std::string::npos);
        EXPECT_NE(render(OutputFormat::Verbose, in, options)
                      .find("Error number: 131 = " + ge_text + "\n"),
                  std::string::npos);
        EXPECT_NE(render(OutputFormat::Csv, in, options).find(",131,\"" + ge_text + "\","),
                  std::string::npos);
    }
    const std::string unknown = "unknown error number";
    EXPECT_EQ(jsonl(in)[9]["pcv"]["error_text"].string(), unknown);
    EXPECT_NE(render(OutputFormat::Text, in).find("error 131 (" + unknown + ")"),
              std::string::npos);
    EXPECT_NE(render(OutputFormat::Verbose, in).find("Error number: 131 = " + unknown + "\n"),
              std::string::npos);
    EXPECT_NE(render(OutputFormat::Csv, in).find(",131,\"" + unknown + "\","), std::string::npos);
}

TEST(RendererTest, JsonlServiceObjects) {
    std::vector<Json> lines = jsonl(session());
    ASSERT_EQ(lines.size(), 12u);
    // Set_Prm request.
    const Json& prm = lines[0]["prm"];
    EXPECT_EQ(prm["ident"].integer(), 0x0402);
    EXPECT_EQ(prm["station_status"].integer(), 0x88);
    ASSERT_EQ(prm["flags"].items.size(), 2u);
    EXPECT_EQ(prm["flags"][0].string(), "WD_On");
    EXPECT_EQ(prm["flags"][1].string(), "Lock_Req");
    EXPECT_EQ(prm["watchdog_ms"].integer(), 1000);
    EXPECT_EQ(prm["min_tsdr"].integer(), 11);
    EXPECT_TRUE(prm["dpv1_status"].is_null());
    EXPECT_EQ(prm["user_prm"].string(), "");
    EXPECT_EQ(lines[0]["dsap"].integer(), 61);
    EXPECT_EQ(lines[0]["ssap"].integer(), 62);
    EXPECT_TRUE(lines[0]["diag"].is_null());
    // Its short acknowledge: no addresses of its own, roles from the request.
    const Json& ack = lines[1];
    EXPECT_EQ(ack["sd"].string(), "SC");
    EXPECT_TRUE(ack["da"].is_null());
    EXPECT_TRUE(ack["fc"].is_null());
    EXPECT_EQ(ack["service"].string(), "Set_Prm");
    EXPECT_EQ(ack["request_frame"].integer(), 1);
    EXPECT_EQ(ack["master"].integer(), 2);
    EXPECT_TRUE(ack["prm"].is_null());
    EXPECT_TRUE(ack["data"].is_null());
    // Chk_Cfg request.
    const Json& cfg = lines[2]["cfg"];
    ASSERT_EQ(cfg["bytes"].items.size(), 2u);
    EXPECT_EQ(cfg["bytes"][0].integer(), 0xF3);
    EXPECT_EQ(cfg["bytes"][1].integer(), 0xF1);
    ASSERT_EQ(cfg["modules"].items.size(), 2u);
    const Json& pcv_module = cfg["modules"][0];
    EXPECT_EQ(pcv_module["identifier"].integer(), 0xF3);
    EXPECT_FALSE(pcv_module["special"].boolean);
    EXPECT_EQ(pcv_module["dir"].string(), "in/out");
    EXPECT_EQ(pcv_module["out_bytes"].integer(), 8);
    EXPECT_EQ(pcv_module["in_bytes"].integer(), 8);
    EXPECT_EQ(pcv_module["unit"].string(), "word");
    EXPECT_TRUE(pcv_module["consistent"].boolean);
    EXPECT_EQ(cfg["modules"][1]["identifier"].integer(), 0xF1);
    EXPECT_EQ(cfg["modules"][1]["out_bytes"].integer(), 4);
    EXPECT_EQ(cfg["ppo"].integer(), 1);
    EXPECT_TRUE(cfg["has_pcv"].boolean);
    EXPECT_EQ(lines[2]["data"].string(), "F3F1");
    // Slave_Diag response.
    const Json& diag = lines[5]["diag"];
    EXPECT_EQ(diag["ident"].integer(), 0x0402);
    EXPECT_EQ(diag["master"].integer(), 2);
    ASSERT_EQ(diag["station_status"].items.size(), 3u);
    EXPECT_EQ(diag["station_status"][1].integer(), 0x0C);
    ASSERT_EQ(diag["flags"].items.size(), 1u);
    EXPECT_EQ(diag["flags"][0].string(), "WD_On");
    EXPECT_TRUE(diag["ext"].is_null());
    EXPECT_TRUE(lines[4]["diag"].is_null());  // the request has none
    // Global_Control broadcast.
    const Json& gc = lines[11]["global_control"];
    EXPECT_EQ(gc["command"].integer(), 8);
    ASSERT_EQ(gc["flags"].items.size(), 1u);
    EXPECT_EQ(gc["flags"][0].string(), "Freeze");
    EXPECT_EQ(gc["group"].integer(), 0);
    EXPECT_EQ(lines[11]["da"].integer(), 127);
}

TEST(RendererTest, JsonlDiagWithoutMasterIsNull) {
    std::vector<Input> in = {{request(60, {}), kT0, {}},
                             {response(60, {0x02, 0x05, 0x00, 0xFF, 0x04, 0x02}), kT0 + 1, {}}};
    std::vector<Json> lines = jsonl(in);
    ASSERT_EQ(lines.size(), 2u);
    EXPECT_TRUE(lines[1]["diag"]["master"].is_null());
    const Json& flags = lines[1]["diag"]["flags"];
    ASSERT_EQ(flags.items.size(), 2u);
    EXPECT_EQ(flags[0].string(), "Station_Not_Ready");
    EXPECT_EQ(flags[1].string(), "Prm_Req");
}

TEST(RendererTest, JsonlNullsWhereAbsent) {
    std::vector<Input> in = {{hex("DC 02 02"), kNoTime, {}}};
    std::vector<Json> lines = jsonl(in);
    ASSERT_EQ(lines.size(), 1u);
    const Json& token = lines[0];
    EXPECT_TRUE(token["time"].is_null());
    EXPECT_EQ(token["sd"].string(), "SD4");
    EXPECT_EQ(token["da"].integer(), 2);
    EXPECT_EQ(token["service"].string(), "Token");
    for (const char* key : {"dsap", "ssap", "fc", "request_frame", "ppo", "ppo_source", "dialect",
                            "pcv", "pcd", "diag", "prm", "cfg", "global_control", "data"})
        EXPECT_TRUE(token[key].is_null()) << key;
    EXPECT_TRUE(token["fcs_ok"].boolean);
}

TEST(RendererTest, JsonlMalformedTelegramsListTheirProblems) {
    std::vector<std::uint8_t> bad_fcs = hex("68 07 07 68 83 82 7D 3E 3E F3 F1 E2 16");
    bad_fcs[11] ^= 0x5A;
    std::vector<Input> in = {{bad_fcs, kT0, {}},
                             {hex("68 07 07 68 83 82 7D 3E 3E F3"), kT0 + 1, {}},
                             {hex("2A 3F 9F"), kT0 + 2, {}}};
    std::vector<Json> lines = jsonl(in);
    ASSERT_EQ(lines.size(), 3u);

    EXPECT_FALSE(lines[0]["fcs_ok"].boolean);
    ASSERT_EQ(lines[0]["problems"].items.size(), 1u);
    const Json& fcs = lines[0]["problems"][0];
    EXPECT_EQ(fcs.keys(), (std::vector<std::string>{"kind", "severity", "offset", "message"}));
    EXPECT_EQ(fcs["kind"].string(), "fcs_mismatch");
    EXPECT_EQ(fcs["severity"].string(), "error");
    EXPECT_EQ(fcs["offset"].integer(), 11);
    EXPECT_EQ(fcs["message"].string(), "byte 11: FCS 0xB8 wrong, checksum of the data is 0xE2");

    ASSERT_EQ(lines[1]["problems"].items.size(), 1u);
    EXPECT_EQ(lines[1]["problems"][0]["kind"].string(), "truncated");
    EXPECT_EQ(lines[1]["problems"][0]["offset"].integer(), 10);
    EXPECT_EQ(lines[1]["problems"][0]["message"].string(),
              "telegram truncated: needs 13 bytes, has 10");

    const Json& junk = lines[2];
    EXPECT_TRUE(junk["sd"].is_null());
    EXPECT_TRUE(junk["da"].is_null());
    EXPECT_TRUE(junk["fc"].is_null());
    EXPECT_TRUE(junk["master"].is_null());
    EXPECT_EQ(junk["service"].string(), "Unknown");
    EXPECT_EQ(junk["len"].integer(), 3);
    ASSERT_EQ(junk["problems"].items.size(), 1u);
    EXPECT_EQ(junk["problems"][0]["kind"].string(), "bad_start_delimiter");
    EXPECT_EQ(junk["problems"][0]["offset"].integer(), 0);
}

TEST(RendererTest, JsonlFindingsAndStringEscaping) {
    Finding finding;
    finding.kind = FindingKind::StackedRequest;
    finding.severity = Severity::Warning;
    finding.frame = 1;
    finding.request_frame = 0;
    finding.time_ns = kT0 + 5;
    finding.master = 2;
    finding.slave = 3;
    finding.pnu = 215;
    finding.message = "quote \" backslash \\ newline \n tab \t cr \r bell \x01 arrow \xE2\x86\x92";
    std::vector<Input> in = {{hex("DC 02 02"), kT0, {finding}}};
    std::string text = render(OutputFormat::Jsonl, in);
    EXPECT_NE(text.find(R"(quote \" backslash \\ newline \n tab \t cr \r bell \u0001 arrow )"),
              std::string::npos)
        << text;
    std::vector<Json> lines = jsonl(in);
    ASSERT_EQ(lines.size(), 1u);
    ASSERT_EQ(lines[0]["findings"].items.size(), 1u);
    const Json& f = lines[0]["findings"][0];
    EXPECT_EQ(f.keys(), (std::vector<std::string>{"kind", "severity", "frame", "request_frame",
                                                  "time", "master", "slave", "pnu", "message"}));
    EXPECT_EQ(f["kind"].string(), "stacked_request");
    EXPECT_EQ(f["severity"].string(), "warning");
    EXPECT_EQ(f["frame"].integer(), 1);
    EXPECT_TRUE(f["request_frame"].is_null());
    EXPECT_EQ(f["time"].text, "1704067200.000000005");
    EXPECT_EQ(f["pnu"].integer(), 215);
    EXPECT_EQ(f["message"].string(), finding.message);
}

TEST(RendererTest, FindingsOpenAtTheEndGetALastLine) {
    Finding timeout;
    timeout.kind = FindingKind::ResponseTimeout;
    timeout.severity = Severity::Error;
    timeout.frame = 1;
    timeout.request_frame = 1;
    timeout.time_ns = kT0 + 1'500'000'000;
    timeout.master = 2;
    timeout.slave = 3;
    timeout.pnu = 520;
    timeout.message = "no answer to request RC 1 PNU 520 from frame 1 within 1000 ms";
    std::vector<Input> in = {{hex("DC 02 02"), kT0, {}}};
    std::vector<Finding> open = {timeout};
    std::vector<std::string> lines = split_lines(render(OutputFormat::Jsonl, in, {}, open));
    ASSERT_EQ(lines.size(), 2u);
    auto last = parse_json(lines[1]);
    ASSERT_TRUE(last);
    EXPECT_EQ(last->keys(), (std::vector<std::string>{"end_of_capture", "findings"}));
    EXPECT_EQ((*last)["end_of_capture"].type, Json::Type::Bool);
    EXPECT_TRUE((*last)["end_of_capture"].boolean);
    ASSERT_EQ((*last)["findings"].items.size(), 1u);
    EXPECT_EQ((*last)["findings"][0]["kind"].string(), "response_timeout");
    EXPECT_EQ((*last)["findings"][0]["request_frame"].integer(), 1);
    std::vector<std::string> text = split_lines(render(OutputFormat::Text, in, {}, open));
    ASSERT_EQ(text.size(), 2u);
    EXPECT_EQ(text[1], "     - end of capture [error response_timeout] " + timeout.message);
    // Nothing open: no last line.
    EXPECT_EQ(split_lines(render(OutputFormat::Jsonl, in)).size(), 1u);
}

TEST(RendererTest, JsonStringHelperEscapesControlCharacters) {
    fmt::memory_buffer buffer;
    json::string(buffer, std::string_view("a\"b\\c\x1f\x7f", 7));
    EXPECT_EQ(std::string(buffer.data(), buffer.size()), "\"a\\\"b\\\\c\\u001f\x7f\"");
}

TEST(RendererTest, TimesBeforeTheEpoch) {
    // 1969-12-31T23:59:58.5Z is -1.5 s since the epoch.
    std::vector<Input> in = {{hex("E5"), -1'500'000'000, {}}};
    std::vector<std::string> verbose = split_lines(render(OutputFormat::Verbose, in));
    ASSERT_FALSE(verbose.empty());
    EXPECT_EQ(verbose[0], "Frame 1: 1 byte, 1969-12-31T23:59:58.500000000Z");
    std::vector<Json> lines = jsonl(in);
    ASSERT_EQ(lines.size(), 1u);
    std::string csv_text = render(OutputFormat::Csv, in);
    std::string csv_time = csv_text.substr(csv_text.find('\n') + 3);
    csv_time = csv_time.substr(0, csv_time.find(','));
    EXPECT_EQ(lines[0]["time"].text, "-1.500000000");
    EXPECT_EQ(csv_time, "-1.500000000");
}

TEST(RendererTest, JsonlDialectFollowsTheOptions) {
    DecoderOptions options;
    options.dialect = Dialect::Profidrive;
    std::vector<Json> lines = jsonl(session(), options);
    ASSERT_EQ(lines.size(), 12u);
    EXPECT_EQ(lines[6]["dialect"].string(), "profidrive");
    EXPECT_EQ(lines[9]["pcv"]["meaning"].string(), "Request cannot be executed");
    EXPECT_EQ(lines[9]["pcv"]["error_text"].string(),
              "Request cannot be executed in the current operating state");
}

// ---- text ------------------------------------------------------------------------------------

TEST(RendererTest, TextOneLinePerTelegram) {
    std::vector<std::string> lines = split_lines(render(OutputFormat::Text, session()));
    ASSERT_EQ(lines.size(), 12u);
    EXPECT_EQ(lines[0],
              "     1     0.000000   2 → 3   SD2 Set_Prm        req ident 0x0402 WD 1000 ms "
              "[WD_On Lock_Req] group 0x00");
    EXPECT_EQ(lines[1], "     2     0.000100   3 → 2   SC  Set_Prm        rsp short acknowledge");
    EXPECT_EQ(lines[2], "     3     0.000200   2 → 3   SD2 Chk_Cfg        req F3 F1 = PPO1");
    EXPECT_EQ(lines[5],
              "     6     0.000500   3 → 2   SD3 Slave_Diag     rsp ident 0x0402 master 2 [WD_On]");
    EXPECT_EQ(lines[6],
              "     7     0.000600   2 → 3   SD2 Data_Exchange  req PPO1 RC=2 Change parameter "
              "value (word) PNU=215 IND=0 PVA=17 | CTW=0x047F MRV=50.00%");
    EXPECT_EQ(lines[7],
              "     8     0.000700   3 → 2   SD2 Data_Exchange  rsp PPO1 RC=1 Transmit parameter "
              "value (word) SPM=1 PNU=215 IND=0 PVA=17 | STW=0x0F07 MAV=50.00%");
    EXPECT_EQ(lines[9],
              "    10     0.000900   3 → 2   SD2 Data_Exchange  rsp PPO1 RC=7 Request not "
              "executable PNU=999 IND=0 error 17 (Request temporarily unexecutable) | "
              "STW=0x0F07 MAV=50.00%");
    EXPECT_EQ(lines[10], "    11     0.001000   2 → 2   SD4 Token          req token");
    EXPECT_EQ(lines[11], "    12     0.001100   2 → 127 SD2 Global_Control req Freeze group 0x00");
}

TEST(RendererTest, TextWithoutTimeProblemsAndFindings) {
    Finding finding;
    finding.kind = FindingKind::FcsError;
    finding.severity = Severity::Error;
    std::vector<std::uint8_t> bad_fcs = hex("10 03 02 49 4F 16");
    std::vector<Input> in = {{hex("2A 3F 9F"), kNoTime, {}},
                             {bad_fcs, kT0 + 2'500'000'000, {finding}},
                             {hex("DC 02 02"), kT0, {}}};
    std::vector<std::string> lines = split_lines(render(OutputFormat::Text, in));
    ASSERT_EQ(lines.size(), 3u);
    EXPECT_EQ(lines[0],
              "     1            -   ? → ?   bad Unknown        req 2A 3F 9F "
              "[bad_start_delimiter]");
    EXPECT_EQ(lines[1],
              "     2     0.000000   2 → 3   SD1 FDL_Status     req FDL status "
              "[fcs_mismatch] [error fcs_error]");
    // Relative to the first telegram that has a time; earlier times are negative.
    EXPECT_EQ(lines[2], "     3    -2.500000   2 → 2   SD4 Token          req token");
}

TEST(RendererTest, TextTimeColumnStaysAlignedPastNinetyNineThousandSeconds) {
    const std::int64_t second = 1'000'000'000;
    std::vector<Input> in = {{hex("DC 02 02"), kT0, {}},
                             {hex("DC 02 02"), kT0 + 99'999 * second + 999'999'999, {}},
                             {hex("DC 02 02"), kT0 + 100'000 * second + 500'000'000, {}},
                             {hex("DC 02 02"), kT0 + 12'345'678'901 * (second / 10), {}},
                             {hex("DC 02 02"), kT0 - 10'000 * second - 250'000'000, {}},
                             {hex("DC 02 02"), kT0 + 7'000'000'000 * second, {}},
                             {hex("DC 02 02"), kT0 - 7'000'000'000 * second, {}}};
    std::vector<std::string> lines = split_lines(render(OutputFormat::Text, in));
    ASSERT_EQ(lines.size(), 7u);
    EXPECT_EQ(lines[0], "     1     0.000000   2 → 2   SD4 Token          req token");
    EXPECT_EQ(lines[1], "     2 99999.999999   2 → 2   SD4 Token          req token");
    EXPECT_EQ(lines[2], "     3 100000.50000   2 → 2   SD4 Token          req token");
    EXPECT_EQ(lines[3], "     4 1234567890.1   2 → 2   SD4 Token          req token");
    EXPECT_EQ(lines[4], "     5 -10000.25000   2 → 2   SD4 Token          req token");
    EXPECT_EQ(lines[5], "     6 7000000000.0   2 → 2   SD4 Token          req token");
    EXPECT_EQ(lines[6], "     7  -7000000000   2 → 2   SD4 Token          req token");
}

TEST(RendererTest, TextDataExchangeResponseWithoutDataNamesItsStatus) {
    // A slave that restarted answers Data_Exchange with RS (SAP not activated) and no inputs.
    std::vector<Input> in = {
        {hex("68 0F 0F 68 03 02 5D 00 00 00 00 00 00 00 00 04 7F 00 00 E5 16"), kT0, {}},
        {hex("10 02 03 03 08 16"), kT0 + 200'000, {}}};
    std::vector<std::string> lines = split_lines(render(OutputFormat::Text, in));
    ASSERT_EQ(lines.size(), 2u);
    EXPECT_EQ(lines[1],
              "     2     0.000200   3 → 2   SD1 Data_Exchange  rsp no data: RS (SAP not "
              "activated)");
}

// ---- csv -------------------------------------------------------------------------------------

const std::string kCsvHeader =
    "frame,time,len,sd,da,sa,dsap,ssap,fc,service,direction,master,slave,request_frame,fcs_ok,"
    "ppo,rc,spm,pnu,ind,pva,meaning,error,error_text,pcd,detail,problems,findings,pnu_name,"
    "value_scaled,unit";

// RFC 4180 rows; fails the test on a stray quote.
std::vector<std::vector<std::string>> parse_csv(const std::string& text) {
    std::vector<std::vector<std::string>> rows;
    std::vector<std::string> row;
    std::string field;
    bool quoted = false, was_quoted = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        char c = text[i];
        if (quoted) {
            if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
                field.push_back('"');
                ++i;
            } else if (c == '"') {
                quoted = false;
            } else {
                field.push_back(c);
            }
            continue;
        }
        if (c == '"') {
            if (!field.empty() || was_quoted) ADD_FAILURE() << "stray quote at " << i;
            quoted = was_quoted = true;
        } else if (c == ',') {
            row.push_back(field);
            field.clear();
            was_quoted = false;
        } else if (c == '\n') {
            row.push_back(field);
            rows.push_back(row);
            row.clear();
            field.clear();
            was_quoted = false;
        } else {
            if (was_quoted) ADD_FAILURE() << "text after a closing quote at " << i;
            field.push_back(c);
        }
    }
    EXPECT_FALSE(quoted) << "unterminated quote";
    EXPECT_TRUE(row.empty() && field.empty()) << "last row has no newline";
    return rows;
}

TEST(RendererTest, CsvHeaderAndRowsWithTheSameColumnCount) {
    std::string text = render(OutputFormat::Csv, session());
    EXPECT_EQ(text.substr(0, text.find('\n')), kCsvHeader);
    std::vector<std::vector<std::string>> rows = parse_csv(text);
    ASSERT_EQ(rows.size(), 13u);
    for (const auto& row : rows)
        EXPECT_EQ(row.size(), 31u);
    const std::vector<std::string>& header = rows[0];
    auto column = [&](std::string_view name) {
        for (std::size_t i = 0; i < header.size(); ++i)
            if (header[i] == name) return i;
        ADD_FAILURE() << "no column " << name;
        return std::size_t{0};
    };
    const auto& de = rows[7];  // frame 7
    EXPECT_EQ(de[column("frame")], "7");
    EXPECT_EQ(de[column("time")], "1704067200.000600000");
    EXPECT_EQ(de[column("len")], "21");
    EXPECT_EQ(de[column("sd")], "SD2");
    EXPECT_EQ(de[column("da")], "3");
    EXPECT_EQ(de[column("sa")], "2");
    EXPECT_EQ(de[column("dsap")], "");
    EXPECT_EQ(de[column("fc")], "0x7D");
    EXPECT_EQ(de[column("service")], "Data_Exchange");
    EXPECT_EQ(de[column("direction")], "request");
    EXPECT_EQ(de[column("master")], "2");
    EXPECT_EQ(de[column("slave")], "3");
    EXPECT_EQ(de[column("request_frame")], "");
    EXPECT_EQ(de[column("fcs_ok")], "true");
    EXPECT_EQ(de[column("ppo")], "1");
    EXPECT_EQ(de[column("rc")], "2");
    EXPECT_EQ(de[column("spm")], "0");
    EXPECT_EQ(de[column("pnu")], "215");
    EXPECT_EQ(de[column("pva")], "17");
    EXPECT_EQ(de[column("meaning")], "Change parameter value (word)");
    EXPECT_EQ(de[column("error")], "");
    EXPECT_EQ(de[column("pcd")], "047F 2000");
    EXPECT_EQ(de[column("detail")],
              "PPO1 RC=2 Change parameter value (word) PNU=215 IND=0 PVA=17 | CTW=0x047F "
              "MRV=50.00%");
    const auto& rejected = rows[10];
    EXPECT_EQ(rejected[column("request_frame")], "9");
    EXPECT_EQ(rejected[column("rc")], "7");
    EXPECT_EQ(rejected[column("error")], "17");
    EXPECT_EQ(rejected[column("error_text")], "Request temporarily unexecutable");
    const auto& token = rows[11];
    EXPECT_EQ(token[column("sd")], "SD4");
    EXPECT_EQ(token[column("fc")], "");
    EXPECT_EQ(token[column("rc")], "");
    EXPECT_EQ(token[column("pcd")], "");
    EXPECT_EQ(token[column("detail")], "token");
}

TEST(RendererTest, CsvQuotesTextFields) {
    std::string text = render(OutputFormat::Csv, session());
    std::vector<std::string> lines = split_lines(text);
    ASSERT_EQ(lines.size(), 13u);
    // meaning, error_text and detail are quoted; an empty error text is still quoted.
    EXPECT_NE(lines[10].find(",\"Request not executable\",17,\"Request temporarily "
                             "unexecutable\",0F07 2000,\"PPO1 RC=7 "),
              std::string::npos)
        << lines[10];
    EXPECT_NE(lines[11].find(",\"token\",,"), std::string::npos) << lines[11];
}

TEST(RendererTest, CsvProblemsAndFindings) {
    Finding finding;
    finding.kind = FindingKind::FcsError;
    std::vector<Input> in = {{hex("10 03 02 49 4F 17"), kNoTime, {finding, finding}},
                             {hex("2A 3F 9F"), kNoTime, {}}};
    std::vector<std::vector<std::string>> rows = parse_csv(render(OutputFormat::Csv, in));
    ASSERT_EQ(rows.size(), 3u);
    for (const auto& row : rows)
        ASSERT_EQ(row.size(), 31u);
    EXPECT_EQ(rows[1][1], "");  // no time
    EXPECT_EQ(rows[1][14], "false");
    EXPECT_EQ(rows[1][26], "fcs_mismatch@4 bad_end_delimiter@5");
    EXPECT_EQ(rows[1][27], "fcs_error fcs_error");
    EXPECT_EQ(rows[2][3], "");  // no frame type
    EXPECT_EQ(rows[2][26], "bad_start_delimiter@0");
    EXPECT_EQ(rows[2][25], "");
}

// ---- verbose ---------------------------------------------------------------------------------

std::vector<std::string> verbose_block(const std::vector<Input>& inputs, std::size_t frame,
                                       DecoderOptions options = {}) {
    std::vector<std::string> lines = split_lines(render(OutputFormat::Verbose, inputs, options));
    std::vector<std::string> block;
    bool inside = false;
    std::string start = "Frame " + std::to_string(frame) + ":";
    for (const std::string& line : lines) {
        if (line.rfind(start, 0) == 0) {
            inside = true;
        } else if (inside && line.empty()) {
            break;
        }
        if (inside) block.push_back(line);
    }
    return block;
}

bool contains(const std::vector<std::string>& lines, std::string_view wanted) {
    for (const std::string& line : lines)
        if (line == wanted) return true;
    return false;
}

// An I/O slave configured with one byte each way (Chk_Cfg 0x30: no PPO, no parameter channel):
// no dialect is named for it (jsonl dialect null, verbose "none"), and one byte is "1 byte".
std::vector<Input> io_slave_session() {
    std::vector<Input> in;
    auto add = [&](std::vector<std::uint8_t> bytes) {
        in.push_back({std::move(bytes), kT0 + static_cast<std::int64_t>(in.size()) * 100'000, {}});
    };
    add(request(62, {0x30}));             // 1 Chk_Cfg: 1 byte in and out
    add(hex("E5"));                       // 2 SC
    add(request(std::nullopt, {0x5A}));   // 3 Data_Exchange: 1 byte out
    add(response(std::nullopt, {0xA5}));  // 4 Data_Exchange: 1 byte in
    return in;
}

TEST(RendererTest, SlaveWithoutAParameterChannelHasNoDialectAndOneByteIsSingular) {
    std::vector<Json> lines = jsonl(io_slave_session());
    ASSERT_EQ(lines.size(), 4u);
    for (std::size_t i : {2u, 3u}) {
        EXPECT_EQ(lines[i]["service"].string(), "Data_Exchange");
        EXPECT_TRUE(lines[i]["pcv"].is_null());
        EXPECT_TRUE(lines[i]["dialect"].is_null()) << i;
        EXPECT_EQ(lines[i]["ppo_source"].string(), "chk_cfg");
    }
    std::vector<std::string> block = verbose_block(io_slave_session(), 3);
    ASSERT_FALSE(block.empty());
    for (std::string_view line : {
             "    Data unit: 1 byte from byte 7",
             "    PPO: no standard PPO (0 PCD words, 1 byte each way) from Chk_Cfg",
             "    Dialect: none (no parameter channel); control/status word profile: fc",
         })
        EXPECT_TRUE(contains(block, line)) << line << "\n" << block[0];
    std::vector<std::string> config = verbose_block(io_slave_session(), 1);
    EXPECT_TRUE(std::any_of(config.begin(), config.end(), [](const std::string& line) {
        return line.find("out 1 byte in 1 byte") != std::string::npos;
    })) << config.size();
    std::vector<std::string> ack = verbose_block(io_slave_session(), 2);
    ASSERT_FALSE(ack.empty());
    EXPECT_EQ(ack[0], "Frame 2: 1 byte, 2024-01-01T00:00:00.000100000Z");
}

TEST(RendererTest, VerboseFieldTreeOfADataExchange) {
    std::vector<std::string> block = verbose_block(session(), 7);
    ASSERT_FALSE(block.empty());
    EXPECT_EQ(block[0], "Frame 7: 21 bytes, 2024-01-01T00:00:00.000600000Z");
    for (std::string_view line : {
             "PROFIBUS FDL",
             "    Start delimiter: SD2 (0x68)",
             "    Length: LE 15, LEr 15",
             "    Destination address: 3",
             "    Source address: 2",
             "    Frame control: 0x7D (request, FCB 1, FCV 1, SRD high)",
             "    Data unit: 12 bytes from byte 7",
             "    End delimiter: 0x16",
             "PROFIBUS DP: Data_Exchange request, master 2 / slave 3",
             "    PPO: PPO 1 (PCV + 2 PCD words, 12 bytes each way) from Chk_Cfg",
             "    Dialect: vlt; control/status word profile: fc",
             "    PCV (parameter channel), bytes 7-14",
             "        PCA: 0x20D7",
             "            RC: 2 = Change parameter value (word)",
             "            SPM: 0",
             "            PNU: 215",
             "        IND: 0 (byte 4: 0x00)",
             "        PVA: 0x00000011, word value 17",
             "    PCD (2 words)",
             "        PCD 1 CTW: 0x047F",
             "        PCD 2 MRV: 0x2000 = 50.00 %",
         })
        EXPECT_TRUE(contains(block, line)) << line;
    std::size_t bit_lines = 0;
    for (const std::string& line : block)
        if (line.rfind("            bit ", 0) == 0) ++bit_lines;
    EXPECT_EQ(bit_lines, 16u);
    EXPECT_TRUE(std::any_of(block.begin(), block.end(), [](const std::string& line) {
        return line.rfind("            bit  0 = 1: ", 0) == 0;
    }));
    EXPECT_TRUE(std::any_of(block.begin(), block.end(), [](const std::string& line) {
        return line.rfind("            bit 15 = 0: ", 0) == 0;
    }));
    EXPECT_TRUE(std::any_of(block.begin(), block.end(), [](const std::string& line) {
        return line.rfind("    FCS: 0x", 0) == 0 && line.find("(correct)") != std::string::npos;
    }));
}

TEST(RendererTest, VerboseRejectedResponseAndServices) {
    std::vector<std::string> rejected = verbose_block(session(), 10);
    EXPECT_TRUE(contains(rejected,
                         "PROFIBUS DP: Data_Exchange response, master 2 / slave 3, "
                         "answers frame 9"));
    EXPECT_TRUE(contains(rejected, "            RC: 7 = Request not executable"));
    EXPECT_TRUE(contains(rejected, "        Error number: 17 = Request temporarily unexecutable"));
    std::vector<std::string> prm = verbose_block(session(), 1);
    EXPECT_TRUE(contains(prm, "    Ident number: 0x0402"));
    EXPECT_TRUE(contains(prm, "    Watchdog: factors 10 x 10 = 1000 ms"));
    std::vector<std::string> cfg = verbose_block(session(), 3);
    EXPECT_TRUE(contains(cfg, "    Identifier bytes: F3 F1"));
    std::vector<std::string> diag = verbose_block(session(), 6);
    EXPECT_TRUE(contains(diag, "    Master address: 2"));
    EXPECT_TRUE(contains(diag, "    Station status 2: 0x0C (always_1 WD_On)"));
}

// The service data the decoder stored, shown where each view has always shown it: a
// data-carrying response to Global_Control or Set_Slave_Add in the request's layout in the text
// and verbose views (not in JSONL); a Chk_Cfg request without data; the data of a Chk_Cfg or
// Set_Prm response as plain data.
std::vector<Input> service_data_corner_cases() {
    return {
        {request(58, {0x08, 0x00}), kNoTime, {}},                  // 1 Global_Control
        {response(58, {0x02, 0x07}), kNoTime, {}},                 // 2 its response
        {request(55, {5, 4, 2, 0}), kNoTime, {}},                  // 3 Set_Slave_Add
        {response(55, {5, 4, 2, 1, 0xEE}), kNoTime, {}},           // 4 its response
        {request(62, {}), kNoTime, {}},                            // 5 Chk_Cfg, no data
        {response(62, {0xF1}), kNoTime, {}},                       // 6 its response
        {request(61, {0x88, 10, 10, 11, 4, 2, 0}), kNoTime, {}},   // 7 Set_Prm
        {response(61, {0x88, 10, 10, 11, 4, 2, 0}), kNoTime, {}},  // 8 its response
    };
}

TEST(RendererTest, ServiceDataCornerCasesInEveryView) {
    std::vector<std::string> lines =
        split_lines(render(OutputFormat::Text, service_data_corner_cases()));
    ASSERT_EQ(lines.size(), 8u);
    EXPECT_EQ(lines[1],
              "     2            -   3 → 2   SD2 Global_Control rsp Clear_Data group 0x07");
    EXPECT_EQ(lines[3],
              "     4            -   3 → 2   SD2 Set_Slave_Add  rsp new address 5 ident 0x0402");
    EXPECT_EQ(lines[4], "     5            -   2 → 3   SD2 Chk_Cfg        req  = 0w");
    EXPECT_EQ(lines[5],
              "     6            -   3 → 2   SD2 Chk_Cfg        rsp DL slave SAP 62->62 data F1");
    EXPECT_EQ(lines[7],
              "     8            -   3 → 2   SD2 Set_Prm        rsp DL slave SAP 61->62 data 88 0A "
              "0A 0B 04 02 00");

    std::vector<std::string> gc = verbose_block(service_data_corner_cases(), 2);
    EXPECT_TRUE(contains(gc, "    Control command: 0x02 (Clear_Data)"));
    EXPECT_TRUE(contains(gc, "    Group select: 0x07"));
    std::vector<std::string> ssa = verbose_block(service_data_corner_cases(), 4);
    EXPECT_TRUE(contains(ssa, "    No_Add_Chg: 1"));
    EXPECT_TRUE(contains(ssa, "    Rem_Slave_Data: EE"));

    std::vector<Json> json = jsonl(service_data_corner_cases());
    ASSERT_EQ(json.size(), 8u);
    EXPECT_EQ(json[0]["global_control"]["command"].integer(), 8);
    EXPECT_TRUE(json[1]["global_control"].is_null());
    EXPECT_TRUE(json[4]["cfg"].is_null());
    EXPECT_TRUE(json[5]["cfg"].is_null());
    EXPECT_EQ(json[6]["prm"]["ident"].integer(), 0x0402);
    EXPECT_TRUE(json[7]["prm"].is_null());
    for (const Json& line : json)
        EXPECT_TRUE(line["problems"].items.empty());
}

TEST(RendererTest, VerboseMalformedTelegram) {
    std::vector<Input> in = {{hex("10 03 02 49 4F 16"), kNoTime, {}}, {hex("2A"), kNoTime, {}}};
    std::vector<std::string> bad_fcs = verbose_block(in, 1);
    ASSERT_FALSE(bad_fcs.empty());
    EXPECT_EQ(bad_fcs[0], "Frame 1: 6 bytes");
    EXPECT_TRUE(contains(bad_fcs, "    Bytes: 10 03 02 49 4F 16"));
    EXPECT_TRUE(contains(bad_fcs, "    FCS: 0x4F (wrong)"));
    EXPECT_TRUE(contains(bad_fcs, "Problems"));
    EXPECT_TRUE(contains(bad_fcs,
                         "    fcs_mismatch (error): byte 4: FCS 0x4F wrong, checksum of "
                         "the data is 0x4E"));
    std::vector<std::string> junk = verbose_block(in, 2);
    EXPECT_TRUE(contains(junk, "    Start delimiter: 0x2A (not a start delimiter)"));
}

// ---- fields checked against the sources (issue #7) --------------------------------------------

std::vector<Input> diag_exchange(std::vector<std::uint8_t> ext,
                                 std::optional<std::vector<std::uint8_t>> set_prm = std::nullopt) {
    std::vector<Input> in;
    if (set_prm) in.push_back({request(61, *set_prm), kNoTime, {}});
    std::vector<std::uint8_t> du = {0x08, 0x0C, 0x00, 0x02, 0x04, 0x02};
    du.insert(du.end(), ext.begin(), ext.end());
    in.push_back({request(60, {}), kNoTime, {}});
    in.push_back({response(60, du), kNoTime, {}});
    return in;
}

TEST(RendererTest, VerboseChannelIoTypeZeroIsReserved) {
    // Module 1; channel byte 0x02 (I/O type 00), 0xC2 (11); type byte 0xA6: word, line break.
    std::vector<std::string> reserved = verbose_block(diag_exchange(hex("81 02 A6")), 2);
    EXPECT_TRUE(contains(reserved,
                         "        channel-related: module 1, channel 2, reserved I/O type, word: "
                         "error 6 (line break)"));
    std::vector<std::string> both = verbose_block(diag_exchange(hex("81 C2 A6")), 2);
    EXPECT_TRUE(contains(both,
                         "        channel-related: module 1, channel 2, input/output, word: "
                         "error 6 (line break)"));
    // Cut after the channel byte: a problem, and no block is shown.
    std::vector<std::string> cut = verbose_block(diag_exchange(hex("81 02")), 2);
    EXPECT_TRUE(std::none_of(cut.begin(), cut.end(), [](const std::string& line) {
        return line.find("channel-related") != std::string::npos;
    }));
    EXPECT_TRUE(std::any_of(cut.begin(), cut.end(), [](const std::string& line) {
        return line.rfind("    diag_block_truncated (error): ", 0) == 0;
    }));
}

TEST(RendererTest, DeviceDiagnosisReadsAsTheSlavesSetPrmSays) {
    // Device-related block of 5 bytes: 0x81 (status message), slot 1, specifier 0, one data byte.
    const auto ext = hex("05 81 01 00 7F");
    const auto dpv1 = hex("88 0A 0A 0B 04 02 00 80 00 00");
    const auto dpv0 = hex("88 0A 0A 0B 04 02 00 81 00 00");  // reserved bit: not DP-V1 status
    std::vector<std::string> unknown = verbose_block(diag_exchange(ext), 2);
    EXPECT_TRUE(contains(unknown,
                         "        device-related: 81 01 00 7F (DP-V1 or manufacturer-specific: "
                         "no Set_Prm seen; as DP-V1: status message, slot 1)"));
    std::vector<std::string> enabled = verbose_block(diag_exchange(ext, dpv1), 3);
    EXPECT_TRUE(
        contains(enabled, "        device-related: 81 01 00 7F (DP-V1: status message, slot 1)"));
    std::vector<std::string> disabled = verbose_block(diag_exchange(ext, dpv0), 3);
    EXPECT_TRUE(contains(disabled,
                         "        device-related: 81 01 00 7F (manufacturer-specific: Set_Prm did "
                         "not enable DP-V1)"));
    // Too short for a DP-V1 alarm or status header.
    std::vector<std::string> short_block = verbose_block(diag_exchange(hex("03 81 01"), dpv1), 3);
    EXPECT_TRUE(contains(short_block,
                         "        device-related: 81 01 (DP-V1, but 2 bytes: too short for an "
                         "alarm or status)"));
    std::vector<std::string> short_unknown = verbose_block(diag_exchange(hex("03 81 01")), 2);
    EXPECT_TRUE(contains(short_unknown,
                         "        device-related: 81 01 (DP-V1 or manufacturer-specific: no "
                         "Set_Prm seen)"));

    EXPECT_TRUE(jsonl(diag_exchange(ext))[1]["diag"]["dpv1"].is_null());
    const Json on = jsonl(diag_exchange(ext, dpv1))[2]["diag"]["dpv1"];
    EXPECT_EQ(on.type, Json::Type::Bool);
    EXPECT_TRUE(on.boolean);
    const Json off = jsonl(diag_exchange(ext, dpv0))[2]["diag"]["dpv1"];
    EXPECT_EQ(off.type, Json::Type::Bool);
    EXPECT_FALSE(off.boolean);
}

TEST(RendererTest, VerboseDpv1Status3ShowsAlarmModeAndPrmCmd) {
    // DPV1_Status_3 0x9B: PrmCmd, IsoM_Req, Prm_Structure, Alarm_Mode 3.
    std::vector<std::string> prm =
        verbose_block({{request(61, hex("88 0A 0A 0B 04 02 00 80 00 9B")), kNoTime, {}}}, 1);
    EXPECT_TRUE(contains(prm,
                         "    DPV1_Status_3: 0x9B (Alarm_Mode 3 = 8 alarms in total; Prm_Structure "
                         "IsoM_Req PrmCmd)"));
    std::vector<std::string> zero =
        verbose_block({{request(61, hex("88 0A 0A 0B 04 02 00 80 00 00")), kNoTime, {}}}, 1);
    EXPECT_TRUE(contains(zero, "    DPV1_Status_3: 0x00 (Alarm_Mode 0 = 1 alarm of each type)"));
    // Reserved bits 5..6 set: the bytes are User_Prm_Data, no DPV1_Status lines.
    std::vector<std::string> reserved =
        verbose_block({{request(61, hex("88 0A 0A 0B 04 02 00 80 00 60")), kNoTime, {}}}, 1);
    EXPECT_TRUE(std::none_of(reserved.begin(), reserved.end(), [](const std::string& line) {
        return line.find("DPV1_Status") != std::string::npos;
    }));
    EXPECT_TRUE(contains(reserved, "    User_Prm_Data: 80 00 60"));
}

TEST(RendererTest, ClockValueAndReservedFrameControl) {
    std::vector<Input> in = {
        {build_telegram({127, kMaster, 0xC0, std::nullopt, std::nullopt, Bytes(hex("01 02"))}),
         kNoTime,
         {}},
        {build_telegram({kSlave, kMaster, 0xCD, 60, 62, Bytes()}), kNoTime, {}},
    };
    std::vector<std::string> clock = verbose_block(in, 1);
    EXPECT_TRUE(contains(clock, "    Frame control: 0xC0 (request, FCB 0, FCV 0, clock value)"));
    EXPECT_TRUE(std::none_of(clock.begin(), clock.end(),
                             [](const std::string& line) { return line == "Problems"; }));
    std::vector<std::string> reserved = verbose_block(in, 2);
    EXPECT_TRUE(contains(reserved, "    Frame control: 0xCD (request, FCB 0, FCV 0, reserved)"));
    EXPECT_TRUE(contains(reserved,
                         "    reserved_frame_control (error): byte 6: frame control 0xCD has the "
                         "reserved bit 7 set (only the clock value request 0xC0 sets it)"));
    std::vector<Json> lines = jsonl(in);
    ASSERT_EQ(lines.size(), 2u);
    EXPECT_EQ(lines[0]["fc"]["function"].string(), "clock value");
    EXPECT_EQ(lines[0]["problems"].items.size(), 0u);
    EXPECT_EQ(lines[1]["fc"]["function"].string(), "reserved");
    ASSERT_EQ(lines[1]["problems"].items.size(), 1u);
    EXPECT_EQ(lines[1]["problems"][0]["kind"].string(), "reserved_frame_control");
    EXPECT_EQ(lines[1]["problems"][0]["offset"].integer(), 6);
    std::vector<std::vector<std::string>> rows = parse_csv(render(OutputFormat::Csv, in));
    ASSERT_EQ(rows.size(), 3u);
    EXPECT_EQ(rows[1][25], "clock value data 01 02");
    EXPECT_EQ(rows[2][26], "reserved_frame_control@6");
}

TEST(RendererTest, WatchdogWithPossibleDpv1StatusShowsBothReadings) {
    // WD_Base_1ms set in bytes that fit the DP-V1 status layout: 5 x 20 = 100 ms or 1000 ms.
    std::vector<Input> ambiguous = {
        {request(61, hex("88 05 14 0B 04 02 00 84 00 00")), kNoTime, {}}};
    EXPECT_TRUE(contains(verbose_block(ambiguous, 1),
                         "    Watchdog: factors 5 x 20 = 100 ms with WD_Base_1ms, or 1000 ms if "
                         "the bytes read as DPV1_Status are User_Prm_Data (10 ms base)"));
    const Json prm = jsonl(ambiguous)[0]["prm"];
    EXPECT_EQ(prm["watchdog_ms"].integer(), 100);
    EXPECT_EQ(prm["watchdog_ms_alt"].integer(), 1000);
    std::vector<std::vector<std::string>> rows = parse_csv(render(OutputFormat::Csv, ambiguous));
    ASSERT_EQ(rows.size(), 2u);
    EXPECT_EQ(rows[1][25],
              "ident 0x0402 WD 100 ms (1 ms base) or 1000 ms (10 ms base) [WD_On Lock_Req] "
              "group 0x00 DP-V1");
    std::string text = render(OutputFormat::Text, ambiguous);
    EXPECT_NE(text.find("WD 100 ms (1 ms base) or 1000 ms (10 ms base)"), std::string::npos)
        << text;
    // DP-V1 status bytes without DPV1_Enable: the slave runs in DP-V0 mode, no "DP-V1" mark.
    std::vector<Input> dpv0 = {{request(61, hex("88 05 14 0B 04 02 00 04 00 00")), kNoTime, {}}};
    std::string dpv0_text = render(OutputFormat::Text, dpv0);
    EXPECT_NE(dpv0_text.find("group 0x00"), std::string::npos) << dpv0_text;
    EXPECT_EQ(dpv0_text.find("DP-V1"), std::string::npos) << dpv0_text;

    // One reading: no WD_Base_1ms, reserved bits set (not DP-V1 status), too few user bytes.
    for (const char* du : {"88 05 14 0B 04 02 00 80 00 00", "88 05 14 0B 04 02 00 85 00 00",
                           "88 05 14 0B 04 02 00 84 00"}) {
        SCOPED_TRACE(du);
        std::vector<Input> single = {{request(61, hex(du)), kNoTime, {}}};
        EXPECT_TRUE(contains(verbose_block(single, 1), "    Watchdog: factors 5 x 20 = 1000 ms"));
        const Json one = jsonl(single)[0]["prm"];
        EXPECT_EQ(one["watchdog_ms"].integer(), 1000);
        EXPECT_TRUE(one["watchdog_ms_alt"].is_null());
    }
    // Watchdog off: neither reading.
    const Json off =
        jsonl({{request(61, hex("80 05 14 0B 04 02 00 84 00 00")), kNoTime, {}}})[0]["prm"];
    EXPECT_TRUE(off["watchdog_ms"].is_null());
    EXPECT_TRUE(off["watchdog_ms_alt"].is_null());
}

TEST(RendererTest, ProfidriveHighBitsAreDeviceSpecificUnlessDanfoss) {
    // PPO 3 (two PCD words); control word with bits 10, 11 and 15 set.
    std::vector<Input> in = {{request(std::nullopt, hex("8C 7F 20 00")), kNoTime, {}}};
    DecoderOptions generic;
    generic.dialect = Dialect::Profidrive;
    std::vector<std::string> block = verbose_block(in, 1, generic);
    // PPO 3 has no parameter channel: no dialect named (it still chooses the PCD words' names).
    EXPECT_TRUE(contains(block,
                         "    Dialect: none (no parameter channel); control/status word profile: "
                         "profidrive"));
    EXPECT_TRUE(contains(block, "            bit 10 = 1: data valid"));
    EXPECT_TRUE(contains(block, "            bit 11 = 1: device-specific bit 11"));
    EXPECT_TRUE(contains(block, "            bit 15 = 1: device-specific bit 15"));

    DecoderOptions danfoss;  // vlt slave in the Danfoss PROFIdrive profile
    danfoss.pcd_profile = PcdProfile::Profidrive;
    block = verbose_block(in, 1, danfoss);
    EXPECT_TRUE(contains(block,
                         "    Dialect: none (no parameter channel); control/status word profile: "
                         "profidrive (Danfoss)"));
    EXPECT_TRUE(contains(block, "            bit 11 = 1: slow down"));
    EXPECT_TRUE(contains(block, "            bit 15 = 1: reverse"));

    DecoderOptions fc;  // profidrive dialect, FC profile
    fc.dialect = Dialect::Profidrive;
    fc.pcd_profile = PcdProfile::Fc;
    block = verbose_block(in, 1, fc);
    EXPECT_TRUE(contains(block, "            bit 11 = 1: relay 01 active"));
}

TEST(RendererTest, OutputFormatNames) {
    for (OutputFormat format :
         {OutputFormat::Text, OutputFormat::Verbose, OutputFormat::Jsonl, OutputFormat::Csv})
        EXPECT_EQ(output_format_from_name(output_format_name(format)), format);
    EXPECT_EQ(output_format_name(OutputFormat::Jsonl), "jsonl");
    EXPECT_FALSE(output_format_from_name("json").has_value());
}

// ---- DP-V1 and PROFIdrive --------------------------------------------------------------------

std::vector<std::uint8_t> msac(bool request, std::vector<std::uint8_t> du,
                               std::uint8_t slave_sap = 51, std::uint8_t master_sap = 51) {
    if (request)
        return build_telegram({kSlave, kMaster, request_fc(FdlFunction::SrdHigh, true, true),
                               slave_sap, master_sap, Bytes(du)});
    return build_telegram(
        {kMaster, kSlave, response_fc(FdlStatus::DataLow), master_sap, slave_sap, Bytes(du)});
}

// Parameter access to slave 3 on slot 0, index 47: a read of PNU 12.4 with two polls answered
// "state conflict", a read of PNU 918 answered negatively, a change of PNU 12.4, and a response
// whose request is not in the capture.
std::vector<Input> dpv1_session() {
    std::vector<Input> in;
    auto add = [&](bool request, std::string_view du) {
        in.push_back(
            {msac(request, hex(du)), kT0 + static_cast<std::int64_t>(in.size()) * 1'000'000, {}});
    };
    add(true, "5F 00 2F 0A 05 01 00 01 10 01 00 0C 00 04");              // 1 write: read PNU 12.4
    add(false, "5F 00 2F 0A");                                           // 2 write response
    add(true, "5E 00 2F F0");                                            // 3 read
    add(false, "DE 80 B5 00");                                           // 4 state conflict
    add(true, "5E 00 2F F0");                                            // 5 read
    add(false, "5E 00 2F 08 05 01 00 01 42 01 00 03");                   // 6 read response: 3
    add(true, "5F 00 2F 0A 06 01 00 01 10 00 03 96 00 00");              // 7 write: read PNU 918
    add(false, "5F 00 2F 0A");                                           // 8
    add(true, "5E 00 2F F0");                                            // 9
    add(false, "5E 00 2F 08 06 81 00 01 44 01 00 00");                   // 10 error 0
    add(true, "5F 00 2F 0E 07 02 00 01 10 01 00 0C 00 04 42 01 00 07");  // 11 change to 7
    add(false, "5F 00 2F 0E");                                           // 12
    add(true, "5E 00 2F F0");                                            // 13
    add(false, "5E 00 2F 04 07 02 00 01");                               // 14 change (+)
    add(true, "5E 00 2F F0");                                            // 15
    add(false, "DF 80 A1 00");                                           // 16 write error
    return in;
}

bool ends_with(const std::string& line, std::string_view tail) {
    return line.size() >= tail.size() &&
           line.compare(line.size() - tail.size(), tail.size(), tail) == 0;
}

TEST(RendererTest, TextDpv1AndProfidriveDetail) {
    std::vector<std::string> lines = split_lines(render(OutputFormat::Text, dpv1_session()));
    ASSERT_EQ(lines.size(), 16u);
    EXPECT_NE(lines[0].find("MSAC_C1"), std::string::npos) << lines[0];
    EXPECT_TRUE(ends_with(lines[0],
                          "req Write slot 0 idx 47 len 10 | PROFIdrive req ref 5 request parameter "
                          "value axis 0, 1 param: PNU 12[4] value"))
        << lines[0];
    EXPECT_TRUE(ends_with(lines[1], "rsp Write slot 0 idx 47 len 10")) << lines[1];
    EXPECT_TRUE(ends_with(lines[2], "req Read slot 0 idx 47 len 240")) << lines[2];
    EXPECT_TRUE(ends_with(lines[3], "rsp Read negative DP-V1 access: state conflict (0xB5)"))
        << lines[3];
    EXPECT_TRUE(ends_with(lines[5],
                          "Read slot 0 idx 47 len 8 | PROFIdrive rsp ref 5 request parameter (+) "
                          "axis 0, 1 param: PNU 12[4] = 3 (Word)"))
        << lines[5];
    EXPECT_TRUE(ends_with(lines[9],
                          "PROFIdrive rsp ref 6 request parameter (-) axis 0, 1 param: PNU 918: "
                          "error 0x00 illegal or unknown parameter number"))
        << lines[9];
    EXPECT_TRUE(ends_with(lines[10],
                          "PROFIdrive req ref 7 change parameter value axis 0, 1 param: PNU 12[4] "
                          "value = 7 (Word)"))
        << lines[10];
    EXPECT_TRUE(ends_with(lines[13],
                          "Read slot 0 idx 47 len 4 | PROFIdrive rsp ref 7 change parameter (+) "
                          "axis 0, 1 param"))
        << lines[13];
    EXPECT_TRUE(ends_with(lines[15], "Write negative DP-V1 application: write error (0xA1)"))
        << lines[15];
}

TEST(RendererTest, TextProfidriveResponseWithoutItsRequestNumbersTheParameters) {
    std::vector<Input> in;
    in.push_back({msac(true, hex("5E 00 2F F0")), kNoTime, {}});
    in.push_back(
        {msac(false, hex("5E 00 2F 0E 09 81 00 02 42 01 00 03 44 02 00 03 00 05")), kNoTime, {}});
    std::vector<std::string> lines = split_lines(render(OutputFormat::Text, in));
    ASSERT_EQ(lines.size(), 2u);
    EXPECT_TRUE(ends_with(lines[1],
                          "2 params: param 1 = 3 (Word), param 2: error 0x03 invalid subindex "
                          "(subindex 5)"))
        << lines[1];
}

TEST(RendererTest, TextProfidriveReservedFormatAndLastSubindex) {
    std::vector<Input> in;
    // An array from subindex 65534 on, 5 elements: the range ends at the last subindex.
    in.push_back({msac(true, hex("5F 00 2F 0A 01 01 00 01 10 05 00 0C FF FE")), kNoTime, {}});
    // A value block of a reserved format with nothing after it, and one with a byte.
    in.push_back({msac(false, hex("5E 00 2F 06 02 01 00 01 50 01")), kNoTime, {}});
    in.push_back({msac(false, hex("5E 00 2F 07 03 01 00 01 50 01 AB")), kNoTime, {}});
    std::vector<std::string> lines = split_lines(render(OutputFormat::Text, in));
    ASSERT_EQ(lines.size(), 3u);
    EXPECT_TRUE(ends_with(lines[0], "1 param: PNU 12[65534..65535] value")) << lines[0];
    EXPECT_NE(lines[1].find("PNU 12[65534..65535] = (no values) (format 0x50, reserved)"),
              std::string::npos)
        << lines[1];
    EXPECT_NE(lines[2].find("param 1 = AB (format 0x50, reserved)"), std::string::npos) << lines[2];
}

TEST(RendererTest, TextDpv1ClassTwoAndOtherPdus) {
    std::vector<Input> in;
    auto add = [&](bool request, std::string_view du, std::uint8_t slave_sap) {
        in.push_back({msac(request, hex(du), slave_sap, 50), kNoTime, {}});
    };
    add(true, "57 00 00 00 00 64 01 00 00 00 12 34 00 02 00 02 02 31 05 30", 49);
    add(false, "57 F0 01 00 00 00 12 34 00 02 00 02 02 31 05 30", 49);
    add(true, "48", 48);
    add(true, "58 00 13", 48);
    add(true, "51 00 10 02 AA BB", 48);
    add(true, "", 48);
    add(true, "5F 00", 48);
    std::vector<std::string> lines = split_lines(render(OutputFormat::Text, in));
    ASSERT_EQ(lines.size(), 7u);
    EXPECT_NE(lines[0].find("MSAC_C2"), std::string::npos) << lines[0];
    EXPECT_TRUE(ends_with(lines[0],
                          "Initiate send timeout 1000 ms features 0x0100 profile features 0x0000 "
                          "profile ident 0x1234 S_Type 0 S_Len 2 D_Type 0 D_Len 2"))
        << lines[0];
    EXPECT_TRUE(ends_with(lines[1],
                          "Initiate max data unit 240 features 0x0100 profile features "
                          "0x0000 profile ident 0x1234 S_Type 0 S_Len 2 D_Type 0 D_Len 2"))
        << lines[1];
    EXPECT_TRUE(ends_with(lines[2], "req Idle")) << lines[2];
    EXPECT_TRUE(ends_with(lines[3], "Abort subnet 0 MSAC_C2: connection timeout (ABT_TO)"))
        << lines[3];
    EXPECT_TRUE(ends_with(lines[4], "Data_Transport slot 0 idx 16 len 2 data AA BB")) << lines[4];
    EXPECT_TRUE(ends_with(lines[5], "no PDU (link-level poll)")) << lines[5];
    EXPECT_TRUE(ends_with(lines[6], "Write (header cut short) [service_data_short]")) << lines[6];
}

TEST(RendererTest, VerboseDpv1AndProfidriveFields) {
    std::string text = render(OutputFormat::Verbose, dpv1_session());
    for (std::string_view expected : {
             "    DP-V1 function: 0x5F (Write)\n",
             "        Slot: 0\n",
             "        Index: 47 (PROFIdrive parameter channel)\n",
             "        Length: 10\n",
             "        Data (10 bytes from byte 13): 05 01 00 01 10 01 00 0C 00 04\n",
             "    PROFIdrive parameter request\n",
             "        Request reference: 5\n",
             "        Request ID: 0x01 (request parameter value)\n",
             "        Axis: 0\n",
             "        Number of parameters: 1\n",
             "        Parameter 1\n",
             "            Attribute: 0x10 (value)\n",
             "            Number of elements: 1\n",
             "            Parameter number: 12\n",
             "            Subindex: 4\n",
             "    DP-V1 function: 0xDE (Read negative), negative response\n",
             "        Error_Decode: 0x80 (DP-V1)\n",
             "        Error_Code_1: 0xB5\n",
             "            Error class: 11 (access)\n",
             "            Error code: 5 (state conflict)\n",
             "        Error_Code_2: 0x00\n",
             "    PROFIdrive parameter response\n",
             "        Response ID: 0x01 (request parameter (+))\n",
             "        Answers the request in frame 1 (ref 5, ID 0x01)\n",
             "            Format: 0x42 (Word)\n",
             "            Number of values: 1\n",
             "            Values: 3\n",
             "            Parameter number: 918\n",
             "            Format: 0x44 (Error)\n",
             "            Error number: 0x00 (illegal or unknown parameter number)\n",
             "        Response ID: 0x02 (change parameter (+))\n",
         })
        EXPECT_NE(text.find(expected), std::string::npos) << expected;
}

TEST(RendererTest, VerboseDpv1InitiateAndAbort) {
    std::vector<Input> in;
    in.push_back(
        {msac(true, hex("57 00 00 00 00 64 01 00 00 00 12 34 00 02 00 02 02 31 05 30"), 49, 50),
         kNoTime,
         {}});
    in.push_back({msac(true, hex("58 01 13"), 48, 50), kNoTime, {}});
    std::string text = render(OutputFormat::Verbose, in);
    for (std::string_view expected : {
             "    DP-V1 function: 0x57 (Initiate)\n",
             "        Send_Timeout: 100 (1000 ms)\n",
             "        Features_Supported: 0x0100\n",
             "        Profile_Ident_Number: 0x1234\n",
             "        S_Type: 0, S_Len: 2\n",
             "        S_Addr: 02 31\n",
             "        D_Addr: 05 30\n",
             "        Subnet: 1\n",
             "        Instance_Reason_Code: 0x13\n",
             "            Instance: 1 (MSAC_C2)\n",
             "            Reason code: 3 (connection timeout (ABT_TO))\n",
         })
        EXPECT_NE(text.find(expected), std::string::npos) << expected << text;
}

TEST(RendererTest, JsonlDpv1AndProfidriveKeys) {
    std::string text = render(OutputFormat::Jsonl, dpv1_session());
    std::vector<Json> lines;
    for (const std::string& line : split_lines(text)) {
        auto parsed = parse_json(line);
        ASSERT_TRUE(parsed) << line;
        std::vector<std::string> keys = kJsonKeys;
        keys.insert(keys.begin() + 24, {"dpv1", "profidrive"});
        EXPECT_EQ(parsed->keys(), keys) << line;
        lines.push_back(std::move(*parsed));
    }
    ASSERT_EQ(lines.size(), 16u);
    const std::vector<std::string> dpv1_keys = {"function",
                                                "function_name",
                                                "negative",
                                                "complete",
                                                "slot",
                                                "index",
                                                "length",
                                                "data_length",
                                                "alarm_type",
                                                "specifier",
                                                "error_decode",
                                                "error_decode_name",
                                                "error_code_1",
                                                "error_class",
                                                "error_class_name",
                                                "error_code",
                                                "error_code_name",
                                                "error_code_2",
                                                "initiate",
                                                "abort"};
    const Json& write = lines[0];
    EXPECT_EQ(write["dpv1"].keys(), dpv1_keys);
    EXPECT_EQ(write["dpv1"]["function"].integer(), 0x5F);
    EXPECT_EQ(write["dpv1"]["function_name"].string(), "Write");
    EXPECT_FALSE(write["dpv1"]["negative"].boolean);
    EXPECT_EQ(write["dpv1"]["slot"].integer(), 0);
    EXPECT_EQ(write["dpv1"]["index"].integer(), 47);
    EXPECT_EQ(write["dpv1"]["length"].integer(), 10);
    EXPECT_EQ(write["dpv1"]["data_length"].integer(), 10);
    EXPECT_TRUE(write["dpv1"]["error_decode"].is_null());
    const Json& request = write["profidrive"];
    EXPECT_FALSE(request["response"].boolean);
    EXPECT_EQ(request["reference"].integer(), 5);
    EXPECT_EQ(request["request_id"].integer(), 1);
    EXPECT_EQ(request["id_name"].string(), "request parameter value");
    EXPECT_EQ(request["axis"].integer(), 0);
    EXPECT_EQ(request["count"].integer(), 1);
    EXPECT_EQ(request.find("request_frame"), nullptr);
    const Json& parameter = request["parameters"][0];
    EXPECT_EQ(parameter.keys(), (std::vector<std::string>{
                                    "attribute", "attribute_name", "elements", "pnu", "subindex",
                                    "format", "format_name", "value_count", "values", "numbers",
                                    "pnu_name", "value_scaled", "unit", "complete", "error"}));
    EXPECT_EQ(parameter["attribute"].integer(), 0x10);
    EXPECT_EQ(parameter["attribute_name"].string(), "value");
    EXPECT_EQ(parameter["elements"].integer(), 1);
    EXPECT_EQ(parameter["pnu"].integer(), 12);
    EXPECT_EQ(parameter["subindex"].integer(), 4);
    EXPECT_TRUE(parameter["format"].is_null());

    const Json& busy = lines[3]["dpv1"];
    EXPECT_TRUE(busy["negative"].boolean);
    EXPECT_EQ(busy["function_name"].string(), "Read negative");
    EXPECT_EQ(busy["error_decode"].integer(), 0x80);
    EXPECT_EQ(busy["error_decode_name"].string(), "DP-V1");
    EXPECT_EQ(busy["error_code_1"].integer(), 0xB5);
    EXPECT_EQ(busy["error_class"].integer(), 11);
    EXPECT_EQ(busy["error_class_name"].string(), "access");
    EXPECT_EQ(busy["error_code"].integer(), 5);
    EXPECT_EQ(busy["error_code_name"].string(), "state conflict");
    EXPECT_EQ(busy["error_code_2"].integer(), 0);
    EXPECT_TRUE(busy["slot"].is_null());
    EXPECT_TRUE(lines[3]["profidrive"].is_null());

    const Json& answer = lines[5]["profidrive"];
    EXPECT_TRUE(answer["response"].boolean);
    EXPECT_EQ(answer["response_id"].integer(), 1);
    EXPECT_EQ(answer["id_name"].string(), "request parameter (+)");
    EXPECT_EQ(answer["request_frame"].integer(), 1);
    const Json& value = answer["parameters"][0];
    EXPECT_EQ(value["pnu"].integer(), 12);
    EXPECT_EQ(value["format"].integer(), 0x42);
    EXPECT_EQ(value["format_name"].string(), "Word");
    EXPECT_EQ(value["value_count"].integer(), 1);
    EXPECT_EQ(value["values"].string(), "3");
    EXPECT_EQ(value["numbers"][0].integer(), 3);
    EXPECT_TRUE(value["complete"].boolean);
    EXPECT_TRUE(value["error"].is_null());

    const Json& negative = lines[9]["profidrive"];
    EXPECT_TRUE(negative["negative"].boolean);
    const Json& error = negative["parameters"][0]["error"];
    EXPECT_EQ(error["number"].integer(), 0);
    EXPECT_EQ(error["text"].string(), "illegal or unknown parameter number");
    EXPECT_TRUE(error["info"].is_null());
    EXPECT_EQ(negative["parameters"][0]["pnu"].integer(), 918);
    EXPECT_TRUE(negative["parameters"][0]["values"].is_null());

    const Json& change = lines[10]["profidrive"]["parameters"][0];
    EXPECT_EQ(change["values"].string(), "7");
    EXPECT_EQ(change["numbers"][0].integer(), 7);
    // A positive change response has no blocks: its parameter is the request's address alone.
    const Json& changed = lines[13]["profidrive"]["parameters"];
    ASSERT_EQ(changed.items.size(), 1u);
    EXPECT_EQ(changed[0]["pnu"].integer(), 12);
    EXPECT_TRUE(changed[0]["format"].is_null());
}

TEST(RendererTest, JsonlProfidriveRealNumbersAndStrings) {
    std::vector<Input> in;
    in.push_back({msac(true, hex("5E 00 2F F0")), kNoTime, {}});
    in.push_back({msac(false, hex("5E 00 2F 12 09 01 00 03 08 01 3F C0 00 00 21 01 20 00 09 02 "
                                  "48 49")),
                  kNoTime,
                  {}});
    std::vector<std::string> text = split_lines(render(OutputFormat::Jsonl, in));
    ASSERT_EQ(text.size(), 2u);
    auto parsed = parse_json(text[1]);
    ASSERT_TRUE(parsed) << text[1];
    const Json& parameters = (*parsed)["profidrive"]["parameters"];
    ASSERT_EQ(parameters.items.size(), 3u);
    EXPECT_EQ(parameters[0]["numbers"][0].text, "1.5");
    EXPECT_EQ(parameters[1]["values"].string(), "50.000 %");
    EXPECT_EQ(parameters[1]["numbers"][0].text, "50");
    EXPECT_EQ(parameters[2]["values"].string(), "\"HI\"");
    EXPECT_TRUE(parameters[2]["numbers"].is_null());
    EXPECT_TRUE(parameters[0]["pnu"].is_null());  // the request is not in the capture
    EXPECT_TRUE((*parsed)["profidrive"]["request_frame"].is_null());
}

TEST(RendererTest, JsonlDpv1InitiateAndAbortObjects) {
    std::vector<Input> in;
    in.push_back(
        {msac(false, hex("57 F0 01 00 00 00 12 34 00 02 00 02 02 31 05 30"), 49, 50), kNoTime, {}});
    in.push_back({msac(true, hex("58 01 13"), 48, 50), kNoTime, {}});
    std::vector<std::string> text = split_lines(render(OutputFormat::Jsonl, in));
    ASSERT_EQ(text.size(), 2u);
    auto initiate = parse_json(text[0]);
    ASSERT_TRUE(initiate);
    const Json& i = (*initiate)["dpv1"]["initiate"];
    EXPECT_TRUE(i["send_timeout"].is_null());
    EXPECT_EQ(i["max_len_data_unit"].integer(), 240);
    EXPECT_EQ(i["features_supported"].integer(), 0x0100);
    EXPECT_EQ(i["profile_ident_number"].integer(), 0x1234);
    EXPECT_EQ(i["s_len"].integer(), 2);
    EXPECT_EQ(i["s_addr"].string(), "0231");
    EXPECT_EQ(i["d_addr"].string(), "0530");
    auto abort = parse_json(text[1]);
    ASSERT_TRUE(abort);
    const Json& a = (*abort)["dpv1"]["abort"];
    EXPECT_EQ(a["subnet"].integer(), 1);
    EXPECT_EQ(a["instance"].integer(), 1);
    EXPECT_EQ(a["instance_name"].string(), "MSAC_C2");
    EXPECT_EQ(a["reason"].integer(), 3);
    EXPECT_EQ(a["reason_name"].string(), "connection timeout (ABT_TO)");
}

TEST(RendererTest, CsvDpv1DetailColumn) {
    std::string text = render(OutputFormat::Csv, dpv1_session());
    EXPECT_NE(text.find("\"Read slot 0 idx 47 len 8 | PROFIdrive rsp ref 5 request parameter (+) "
                        "axis 0, 1 param: PNU 12[4] = 3 (Word)\""),
              std::string::npos)
        << text;
}

}  // namespace
}  // namespace dpscope
