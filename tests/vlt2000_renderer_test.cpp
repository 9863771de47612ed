// Renderers and summary on VLT 2000 telegrams decoded by Vlt2000Decoder from hand-made strings
// (docs/protocol/vlt2000.md; the worked example of protocol.md §7.5 and its reply): text, verbose,
// jsonl and csv, the decode -q summary, and the --pnu / --station filters.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "formats/renderer.hpp"
#include "formats/summary.hpp"
#include "protocols/vlt2000/vlt2000_decoder.hpp"
#include "tests/json_parser.hpp"
#include "tests/test_support.hpp"

namespace dpscope {
namespace {

using test::Json;
using test::parse_json;

constexpr std::int64_t kT0 = 1'704'067'200'000'000'000;  // 2024-01-01T00:00:00Z
constexpr std::int64_t kMs = 1'000'000;

// The 19 characters '<' .. decimal position, then the checksum (the sum of bytes at offsets
// 1..18, its last two decimal digits, computed here independently of the decoder) and '>'.
std::string vlt(std::string_view head) {
    EXPECT_EQ(head.size(), 19u) << head;
    unsigned sum = 0;
    for (std::size_t i = 1; i < head.size(); ++i)
        sum += static_cast<unsigned char>(head[i]);
    std::string telegram(head);
    telegram += static_cast<char>('0' + sum % 100 / 10);
    telegram += static_cast<char>('0' + sum % 10);
    telegram += '>';
    return telegram;
}

// The same with "??" (checksum not checked).
std::string unchecked(std::string_view head) { return std::string(head) + "??" + ">"; }

std::string wrong_checksum(std::string_view head) {
    std::string telegram = vlt(head);
    telegram[20] = telegram[20] == '9' ? '0' : static_cast<char>(telegram[20] + 1);
    return telegram;
}

// A session, one telegram every 10 ms:
//   1/2 the worked example: U 516 = 80 with control word 0x047F, and its reply (status 0x0B87);
//   3/4 R 999 to drive 02 and the failed reply, reason 00; 5/6 U 101 = -23.750 and its reply;
//   7/8 I 621 index 3 and its reply, both with "??"; 9 a C broadcast (0x0400); 10 a wrong
//   checksum (to drive 05: a command wrong only in its checksum may be answered); 11 cut short; 12
//   a letter in the parameter; 13 a failed reply with reason 42 (unknown); 14 a failed reply
//   without a reason code; 15 decimal position 7; 16 groups kept (P) to drive 04; 17 an unknown
//   letter; 18 no address.
std::vector<std::string> session() {
    return {
        vlt("<01UOGD@0516+000800"),
        vlt("<01UGHK@0516+000800"),
        vlt("<02R@@@@0999+000000"),
        vlt("<02R@@@@0999+000009"),
        vlt("<01U@@@@0101-237503"),
        vlt("<01UGHK@0101-237503"),
        unchecked("<03I@@@@0621+000030"),
        unchecked("<03IGHK@0621+000030"),
        vlt("<00C@@D@0000+000000"),
        wrong_checksum("<05R@@@@0516+000000"),
        "<01R@@@@05",
        vlt("<01R@@@@05x6+000000"),
        vlt("<01R@@@@0999+000429"),
        vlt("<01R@@@@0999+000xx9"),
        vlt("<01U@@@@0101+123457"),
        vlt("<04UPPD@0516+000800"),
        vlt("<01X@@@@0516+000000"),
        vlt("<ABR@@@@0516+000000"),
    };
}

Bytes bytes_of(const std::string& s) {
    return Bytes(reinterpret_cast<const std::uint8_t*>(s.data()), s.size());
}

std::string render(OutputFormat format, const std::vector<std::string>& inputs,
                   Vlt2000DecoderOptions options = {}) {
    return test::output_text([&](Output& out) {
        auto renderer = make_renderer(format, out);
        Vlt2000Decoder decoder(options);
        renderer->begin();
        for (std::size_t i = 0; i < inputs.size(); ++i) {
            const DecodedTelegram& t = decoder.decode(
                bytes_of(inputs[i]), kT0 + static_cast<std::int64_t>(i) * 10 * kMs, i + 1);
            renderer->render(t, {});
        }
        renderer->render_end_findings({});
        renderer->end();
    });
}

std::vector<std::string> lines(OutputFormat format) {
    return test::lines_of(render(format, session()));
}

std::vector<Json> jsonl() {
    std::vector<Json> objects;
    for (const std::string& line : lines(OutputFormat::Jsonl)) {
        std::optional<Json> j = parse_json(line);
        EXPECT_TRUE(j) << line;
        if (j) objects.push_back(*j);
    }
    return objects;
}

bool contains(const std::string& text, std::string_view part) {
    return text.find(part) != std::string::npos;
}

TEST(Vlt2000RendererTest, TextOneLinePerTelegram) {
    std::vector<std::string> l = lines(OutputFormat::Text);
    ASSERT_EQ(l.size(), 18u);
    EXPECT_EQ(l[0],
              "     1     0.000000   M → 01  VLT U update       req CTW=0x047F (ON1, ON2, ON3, "
              "coasting possible, ramp (no quick stop), ramp (no hold), start, data valid) "
              "parameter 516 = 80");
    EXPECT_EQ(l[1],
              "     2     0.010000  01 → M   VLT U update       rsp STW=0x0B87 (control ready, VLT "
              "ready, enabled, warning, speed at reference, serial communication control, out "
              "of frequency range, running) parameter 516 = 80");
    // A read command's value is the drive's to fill in: not shown.
    EXPECT_EQ(l[2],
              "     3     0.020000   M → 02  VLT R read         req CTW=0x0000 (data not valid: no "
              "change) "
              "parameter 999");
    EXPECT_EQ(l[3],
              "     4     0.030000  02 → M   VLT R read         rsp STW=0x0000 (control not ready, "
              "VLT not ready, coasting, out of frequency range) "
              "parameter 999 failed: reason 00 (parameter does not exist)");
    EXPECT_TRUE(
        contains(l[4],
                 "M → 01  VLT U update       req CTW=0x0000 (data not valid: no change) parameter "
                 "101 = -23.750"))
        << l[4];
    EXPECT_TRUE(contains(l[5], "01 → M   VLT U update       rsp STW=0x0B87")) << l[5];
    EXPECT_TRUE(contains(l[5], "parameter 101 = -23.750")) << l[5];
    EXPECT_TRUE(
        contains(l[6],
                 "M → 03  VLT I read index   req CTW=0x0000 (data not valid: no change) parameter "
                 "621 index 3 checksum ?? (not checked; computed "))
        << l[6];
    EXPECT_TRUE(contains(l[7], "03 → M   VLT I read index   rsp STW=0x0B87")) << l[7];
    EXPECT_TRUE(contains(
        l[8],
        "  M → all VLT C control      req CTW=0x0400 (OFF1 (ramp stop, relay off), OFF2 (coast, "
        "relay off), OFF3 (quick stop, relay off), coast, quick stop, hold output "
        "frequency, ramp stop, data valid)"))
        << l[8];
    EXPECT_EQ(l[8].find("parameter"), std::string::npos) << l[8];  // ignored with C
    EXPECT_TRUE(contains(l[9], "parameter 516 checksum "));
    EXPECT_TRUE(contains(l[9], " (wrong: computed ")) << l[9];
    EXPECT_TRUE(contains(l[9], ") [vlt2000_checksum_mismatch]")) << l[9];
    EXPECT_TRUE(contains(l[10],
                         "M → 01  VLT R read         req CTW=0x0000 (data not valid: no change) "
                         "[truncated]"))
        << l[10];
    EXPECT_TRUE(
        contains(l[11], "req CTW=0x0000 (data not valid: no change) [vlt2000_field_invalid]"))
        << l[11];
    EXPECT_TRUE(contains(l[12], "parameter 999 failed: reason 42 (unknown reason code)")) << l[12];
    EXPECT_TRUE(contains(l[13], "parameter 999 failed: no reason code given")) << l[13];
    EXPECT_TRUE(
        contains(l[14],
                 "parameter 101 = 12345 (decimal position 7 is out of range (0-5): the digits as "
                 "sent)"))
        << l[14];
    EXPECT_TRUE(contains(l[15],
                         "CTW=0x0400 (bits 0-3 group kept (P), bits 4-7 group kept (P); "
                         "data valid) parameter 516 = 80"))
        << l[15];
    EXPECT_TRUE(contains(l[16], "VLT X unknown      req")) << l[16];
    EXPECT_TRUE(contains(l[16], "[vlt2000_letter_unknown]")) << l[16];
    EXPECT_TRUE(contains(l[17], "  ? → ?   bad -              req \"<ABR@@@@0516+000000")) << l[17];
}

TEST(Vlt2000RendererTest, ValueTextAppliesTheDecimalPoint) {
    auto value_of = [](const std::string& telegram) {
        const std::string text = render(OutputFormat::Text, {telegram});
        const std::size_t at = text.find(" = ");
        return at == std::string::npos ? std::string()
                                       : text.substr(at + 3, text.find('\n') - at - 3);
    };
    EXPECT_EQ(value_of(vlt("<01U@@@@0516+237503")), "23.750");  // the seed's example
    EXPECT_EQ(value_of(vlt("<01U@@@@0516+000800")), "80");
    EXPECT_EQ(value_of(vlt("<01U@@@@0516+000055")), "0.00005");
    EXPECT_EQ(value_of(vlt("<01U@@@@0516-000051")), "-0.5");
    EXPECT_EQ(value_of(vlt("<01U@@@@0516-000002")), "0.00");    // no sign on zero
    EXPECT_EQ(value_of(vlt("<01U@@@@0516 123451")), "1234.5");  // anything but '-' is '+'
    EXPECT_EQ(value_of(vlt("<01U@@@@0516+999996")),
              "99999 (decimal position 6 is out of range (0-5): the digits as sent)");
    // Byte 19 is the decimal position, numbered as the manual numbers it [S004].
    EXPECT_TRUE(value_of(vlt("<01U@@@@0516+12345x"))
                    .starts_with("12345 (no decimal position (byte 19 is not a digit): the digits "
                                 "as sent)"))
        << value_of(vlt("<01U@@@@0516+12345x"));
}

TEST(Vlt2000RendererTest, VerboseFieldsWithTheirByteNumbersAsTheManual) {
    const std::string text =
        render(OutputFormat::Verbose, {vlt("<01UOGD@0516+000800"), vlt("<01UGHK@0516+000800")});
    for (std::string_view expected : {
             "Frame 1: 22 bytes, 2024-01-01T00:00:00.000000000Z\n"
             "    Bytes: 3C 30 31 55 4F 47 44 40 30 35 31 36 2B 30 30 30 38 30 30 30 37 3E\n"
             "VLT 2000 telegram: U update command to drive 01\n"
             "    [1] Start: '<'\n"
             "    [2-3] Address: 01\n"
             "    [4] Control letter: \"U\" (update)\n"
             "    [5-8] Control word: \"OGD@\" = 0x047F (to the drive)\n"
             "        bit  0 = 1: ON1\n",
             "        bit  6 = 1: start\n        bit  7 = 0: no function\n",
             "        bit 10 = 1: data valid\n",
             "        bit 15 = 0: no function\n"
             "    [9-12] Parameter: 516\n"
             "    [13] Sign: \"+\" (positive)\n"
             "    [14-18] Value: 00080 = 80\n"
             "    [19] Decimal position: 0\n"
             "    [20-21] Checksum: 07 (correct)\n"
             "    [22] Stop: '>'\n\n",
             "VLT 2000 telegram: U update reply from drive 01, answers frame 1\n",
             "    [5-8] Status word: \"GHK@\" = 0x0B87 (from the drive)\n"
             "        bit  0 = 1: control ready\n"
             "        bit  1 = 1: VLT ready\n"
             "        bit  2 = 1: enabled\n"
             "        bit  3 = 0: no trip\n",
             "        bit  7 = 1: warning\n"
             "        bit  8 = 1: speed at reference\n"
             "        bit  9 = 1: serial communication control\n"
             "        bit 10 = 0: out of frequency range\n"
             "        bit 11 = 1: running\n",
         })
        EXPECT_TRUE(contains(text, expected)) << expected << "\n---\n" << text;
}

TEST(Vlt2000RendererTest, VerboseFailureIndexKeptGroupsAndDamage) {
    const std::string failed = render(OutputFormat::Verbose, {vlt("<02R@@@@0999+000019")});
    EXPECT_TRUE(contains(failed, "VLT 2000 telegram: R read reply from drive 02\n")) << failed;
    EXPECT_TRUE(contains(failed,
                         "    [14-18] Value: \"00001\" (none: the command failed)\n"
                         "        [17-18] Reason code: 01 = no read/write access\n"
                         "    [19] Decimal position: 9 (unknown parameter or the command "
                         "failed)\n"))
        << failed;

    const std::string index = render(OutputFormat::Verbose, {unchecked("<03I@@@@0621+000030")});
    EXPECT_TRUE(contains(index,
                         "    [13-18] Index: \"+00003\" = 3\n"
                         "    [19] Decimal position: 0\n"
                         "    [20-21] Checksum: ?? (not checked; computed "))
        << index;
    EXPECT_FALSE(contains(index, "Sign")) << index;

    const std::string kept = render(OutputFormat::Verbose, {vlt("<01UPPD@0516+000800")});
    EXPECT_TRUE(contains(kept,
                         "    [5-8] Control word: \"PPD@\" = 0x0400 (to the drive)\n"
                         "        bits 0-3: group kept (P)\n"
                         "        bits 4-7: group kept (P)\n"
                         "        bit  8 = 0: no function\n"))
        << kept;

    const std::string control = render(OutputFormat::Verbose, {vlt("<00C@@D@0000+000000")});
    EXPECT_TRUE(contains(control, "C control command to every drive (broadcast, address 00)"))
        << control;
    EXPECT_TRUE(contains(control, "[9-12] Parameter: 0 (ignored with C)")) << control;

    const std::string cut = render(OutputFormat::Verbose, {"<01R@@@@05"});
    EXPECT_TRUE(contains(cut, "    [5-8] Control word: \"@@@@\" = 0x0000 (to the drive)\n")) << cut;
    EXPECT_FALSE(contains(cut, "[9-12]")) << cut;
    EXPECT_TRUE(contains(cut, "Problems\n    truncated (error)")) << cut;

    const std::string bad = render(OutputFormat::Verbose, {wrong_checksum("<01R@@@@0516+000000")});
    EXPECT_TRUE(contains(bad, "    [20-21] Checksum: ")) << bad;
    EXPECT_TRUE(contains(bad, " (wrong: computed ")) << bad;
    EXPECT_TRUE(contains(bad, "vlt2000_checksum_mismatch (error)")) << bad;

    const std::string letter = render(OutputFormat::Verbose, {vlt("<01R@@@@05x6+000000")});
    EXPECT_TRUE(contains(letter, "    [9-12] Parameter: \"05x6\" (not four digits)\n")) << letter;

    const std::string start = render(OutputFormat::Verbose, {"x01R"});
    EXPECT_TRUE(contains(start, "VLT 2000 telegram\n    [1] Start: \"x\" (not '<')\n")) << start;

    const std::string address = render(OutputFormat::Verbose, {vlt("<ABR@@@@0516+000000")});
    EXPECT_TRUE(contains(address, "    [2-3] Address: \"AB\" (not two digits)\n")) << address;
}

TEST(Vlt2000RendererTest, JsonlCommonKeysAndTheVlt2000Object) {
    std::vector<Json> j = jsonl();
    ASSERT_EQ(j.size(), 18u);
    const Json& command = j[0];
    EXPECT_EQ(command["frame"].integer(), 1);
    EXPECT_EQ(command["len"].integer(), 22);
    EXPECT_EQ(command["direction"].string(), "request");
    EXPECT_EQ(command["master"].integer(), 0);
    EXPECT_EQ(command["slave"].integer(), 1);
    EXPECT_TRUE(command["request_frame"].is_null());
    for (std::string_view dp_key :
         {"sd", "da", "sa", "fc", "fcs_ok", "service", "pcv", "data", "fc_protocol"})
        EXPECT_EQ(command.find(dp_key), nullptr) << dp_key;
    const Json& v = command["vlt2000"];
    EXPECT_TRUE(v["complete"].boolean);
    EXPECT_EQ(v["address"].integer(), 1);
    EXPECT_FALSE(v["broadcast"].boolean);
    EXPECT_EQ(v["letter"].string(), "U");
    EXPECT_EQ(v["letter_name"].string(), "update");
    EXPECT_EQ(v["word_name"].string(), "control");
    EXPECT_EQ(v["word"].integer(), 0x047F);
    ASSERT_EQ(v["word_bits"].items.size(), 16u);
    EXPECT_EQ(v["word_bits"].items[0].string(), "ON1");
    EXPECT_EQ(v["word_bits"].items[10].string(), "data valid");
    EXPECT_EQ(v["word_kept"].items.size(), 0u);
    EXPECT_EQ(v["parameter"].integer(), 516);
    EXPECT_FALSE(v["negative"].boolean);
    EXPECT_EQ(v["digits"].integer(), 80);
    EXPECT_EQ(v["value_text"].string(), "80");
    EXPECT_EQ(v["value"].text, "80");
    EXPECT_TRUE(v["value_note"].is_null());
    EXPECT_EQ(v["decimals"].integer(), 0);
    EXPECT_TRUE(v["index"].is_null());
    EXPECT_TRUE(v["index_number"].is_null());
    EXPECT_FALSE(v["failed"].boolean);
    EXPECT_TRUE(v["reason"].is_null());
    EXPECT_TRUE(v["reason_text"].is_null());
    EXPECT_EQ(v["checksum"].integer(), 7);
    EXPECT_EQ(v["checksum_computed"].integer(), 7);
    EXPECT_FALSE(v["checksum_disabled"].boolean);
    EXPECT_TRUE(v["checksum_ok"].boolean);

    const Json& reply = j[1];
    EXPECT_EQ(reply["direction"].string(), "response");
    EXPECT_EQ(reply["request_frame"].integer(), 1);
    EXPECT_EQ(reply["vlt2000"]["word_name"].string(), "status");
    EXPECT_EQ(reply["vlt2000"]["word"].integer(), 0x0B87);
    EXPECT_EQ(reply["vlt2000"]["word_bits"].items[10].string(), "out of frequency range");
    EXPECT_EQ(reply["vlt2000"]["word_bits"].items[11].string(), "running");

    const Json& failed = j[3]["vlt2000"];
    EXPECT_TRUE(failed["failed"].boolean);
    EXPECT_EQ(failed["decimals"].integer(), 9);
    EXPECT_EQ(failed["reason"].integer(), 0);
    EXPECT_EQ(failed["reason_text"].string(), "parameter does not exist");
    EXPECT_TRUE(failed["value"].is_null());
    EXPECT_TRUE(failed["value_text"].is_null());

    const Json& negative = j[4]["vlt2000"];
    EXPECT_TRUE(negative["negative"].boolean);
    EXPECT_EQ(negative["digits"].integer(), 23750);
    EXPECT_EQ(negative["value_text"].string(), "-23.750");
    EXPECT_EQ(negative["value"].text, "-23.750");
    EXPECT_EQ(negative["decimals"].integer(), 3);

    const Json& index = j[6]["vlt2000"];
    EXPECT_EQ(index["letter"].string(), "I");
    EXPECT_EQ(index["letter_name"].string(), "read index");
    EXPECT_EQ(index["index"].string(), "+00003");
    EXPECT_EQ(index["index_number"].integer(), 3);
    EXPECT_TRUE(index["value"].is_null());
    EXPECT_TRUE(index["checksum"].is_null());
    EXPECT_TRUE(index["checksum_disabled"].boolean);
    EXPECT_TRUE(index["checksum_ok"].is_null());
    EXPECT_FALSE(index["checksum_computed"].is_null());

    const Json& broadcast = j[8];
    EXPECT_EQ(broadcast["slave"].integer(), 0);
    EXPECT_TRUE(broadcast["vlt2000"]["broadcast"].boolean);
    EXPECT_EQ(broadcast["vlt2000"]["letter"].string(), "C");
    EXPECT_EQ(broadcast["vlt2000"]["word"].integer(), 0x0400);

    const Json& wrong = j[9]["vlt2000"];
    EXPECT_FALSE(wrong["checksum_ok"].boolean);
    EXPECT_NE(wrong["checksum"].integer(), wrong["checksum_computed"].integer());
    ASSERT_EQ(j[9]["problems"].items.size(), 1u);
    EXPECT_EQ(j[9]["problems"].items[0]["kind"].string(), "vlt2000_checksum_mismatch");
    EXPECT_EQ(j[9]["problems"].items[0]["offset"].integer(), 19);

    const Json& cut = j[10]["vlt2000"];
    EXPECT_FALSE(cut["complete"].boolean);
    EXPECT_EQ(cut["word"].integer(), 0);
    EXPECT_TRUE(cut["parameter"].is_null());
    EXPECT_TRUE(cut["decimals"].is_null());
    EXPECT_TRUE(cut["failed"].is_null());
    EXPECT_TRUE(cut["checksum"].is_null());
    EXPECT_TRUE(cut["checksum_computed"].is_null());
    EXPECT_TRUE(cut["checksum_disabled"].is_null());

    EXPECT_TRUE(j[11]["vlt2000"]["parameter"].is_null());
    EXPECT_EQ(j[11]["problems"].items[0]["offset"].integer(), 10);

    EXPECT_EQ(j[12]["vlt2000"]["reason"].integer(), 42);
    EXPECT_EQ(j[12]["vlt2000"]["reason_text"].string(), "unknown reason code");
    EXPECT_TRUE(j[13]["vlt2000"]["reason"].is_null());
    EXPECT_EQ(j[13]["vlt2000"]["reason_text"].string(), "no reason code given");

    const Json& seven = j[14]["vlt2000"];
    EXPECT_EQ(seven["decimals"].integer(), 7);
    EXPECT_EQ(seven["value_text"].string(), "12345");
    EXPECT_EQ(seven["value"].text, "12345");
    EXPECT_EQ(seven["value_note"].string(),
              "decimal position 7 is out of range (0-5): the digits as sent");

    const Json& kept = j[15]["vlt2000"];
    ASSERT_EQ(kept["word_kept"].items.size(), 2u);
    EXPECT_EQ(kept["word_kept"].items[0].integer(), 0);
    EXPECT_EQ(kept["word_kept"].items[1].integer(), 1);
    EXPECT_EQ(kept["word_bits"].items[0].string(), "group kept (P)");
    EXPECT_EQ(kept["word_bits"].items[10].string(), "data valid");

    EXPECT_EQ(j[16]["vlt2000"]["letter"].string(), "X");
    EXPECT_EQ(j[16]["vlt2000"]["letter_name"].string(), "unknown");

    const Json& anonymous = j[17];
    EXPECT_TRUE(anonymous["slave"].is_null());
    EXPECT_TRUE(anonymous["vlt2000"]["address"].is_null());
    EXPECT_TRUE(anonymous["vlt2000"]["broadcast"].is_null());
    EXPECT_TRUE(anonymous["vlt2000"]["letter"].is_null());
}

TEST(Vlt2000RendererTest, JsonlEscapesALetterThatIsNotPrintable) {
    std::string telegram = vlt("<01R@@@@0516+000000");
    telegram[3] = '\x07';
    const std::string text = render(OutputFormat::Jsonl, {telegram});
    std::optional<Json> j = parse_json(test::lines_of(text).at(0));
    ASSERT_TRUE(j) << text;
    EXPECT_EQ((*j)["vlt2000"]["letter"].string(), "\\x07");
    EXPECT_EQ((*j)["vlt2000"]["letter_name"].string(), "unknown");
    EXPECT_TRUE(contains(render(OutputFormat::Text, {telegram}), "VLT 0x07 unknown   req"));
}

TEST(Vlt2000RendererTest, AChecksumNotJudgedIsSaidSo) {
    Vlt2000DecoderOptions ignore;
    ignore.check_checksum = false;
    const std::string text =
        render(OutputFormat::Text, {wrong_checksum("<01R@@@@0516+000000")}, ignore);
    EXPECT_TRUE(contains(text, "; not judged, --vlt2000-checksum ignore)")) << text;
    EXPECT_FALSE(contains(text, "[vlt2000_checksum_mismatch]")) << text;
}

TEST(Vlt2000RendererTest, CsvRowsHaveTheHeaderColumns) {
    std::vector<std::string> l = lines(OutputFormat::Csv);
    ASSERT_EQ(l.size(), 19u);
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
    EXPECT_EQ(l[1],
              "1,1704067200.000000000,22,,,,,,,\"U update\",request,0,1,,true,,,,516,,80,"
              "\"update\",,,047F,\"CTW=0x047F (ON1, ON2, ON3, coasting possible, ramp (no quick "
              "stop), ramp (no hold), start, "
              "data valid) parameter 516 = 80\",,,,,");
    EXPECT_TRUE(contains(l[4],
                         ",\"R read\",response,0,2,3,true,,,,999,,,\"read\",0,"
                         "\"parameter does not exist\",0000,"))
        << l[4];
    EXPECT_TRUE(contains(l[5], ",516,,,\"update\"") || contains(l[5], ",101,,-23.750,\"update\","))
        << l[5];
    EXPECT_TRUE(contains(l[7], ",\"I read index\",request,0,3,,true,,,,621,3,,\"read index\",,,"))
        << l[7];
    EXPECT_TRUE(contains(l[9], ",\"C control\",request,0,0,,true,,,,,,,\"control\",,,0400,"))
        << l[9];
    EXPECT_TRUE(contains(l[10], ",false,")) << l[10];
    EXPECT_TRUE(contains(l[10], ",vlt2000_checksum_mismatch@19,")) << l[10];
    EXPECT_TRUE(contains(l[11], ",truncated@10,")) << l[11];
    EXPECT_TRUE(contains(l[14], ",\"read\",,\"no reason code given\",")) << l[14];
}

// Every prefix of a telegram (and the bytes around it damaged) renders in every format without
// reading past the record: each format still writes one record a telegram.
TEST(Vlt2000RendererTest, EveryPrefixAndDamageRendersInEveryFormat) {
    const std::string whole = vlt("<01R@@@@0999+000019");
    std::vector<std::string> inputs;
    for (std::size_t n = 0; n <= whole.size() + 1; ++n)
        inputs.push_back(n <= whole.size() ? whole.substr(0, n) : whole + "x");
    for (std::size_t at = 0; at < whole.size(); ++at) {
        std::string damaged = whole;
        damaged[at] = '\xFF';
        inputs.push_back(damaged);
        damaged[at] = '"';
        inputs.push_back(damaged);
    }
    inputs.push_back(unchecked("<05I@@@@0621\x01,2   0"));  // an index that is no number
    for (OutputFormat format :
         {OutputFormat::Text, OutputFormat::Verbose, OutputFormat::Jsonl, OutputFormat::Csv}) {
        const std::string text = render(format, inputs);
        if (format == OutputFormat::Jsonl) {
            std::vector<std::string> l = test::lines_of(text);
            ASSERT_EQ(l.size(), inputs.size());
            for (const std::string& line : l)
                EXPECT_TRUE(parse_json(line)) << line;
        } else if (format != OutputFormat::Verbose) {
            EXPECT_EQ(test::lines_of(text).size(),
                      inputs.size() + (format == OutputFormat::Csv ? 1 : 0));
        }
    }
    const std::string index = render(OutputFormat::Text, {inputs.back()});
    EXPECT_TRUE(contains(index, "parameter 621 index \"\\x01,2   \"")) << index;
}

std::string summary_text(const Summary& summary) {
    return test::output_text([&](Output& out) {
        BusDecoder decoder;
        summary.render_text(out, InputSummary{"vlt.raw", "raw", 0, false}, decoder);
    });
}

TEST(Vlt2000RendererTest, SummaryCountsLettersFailuresChecksumsAndAddresses) {
    Summary summary;
    Vlt2000Decoder decoder;
    std::vector<std::string> in = session();
    for (std::size_t i = 0; i < in.size(); ++i)
        summary.add(
            decoder.decode(bytes_of(in[i]), kT0 + static_cast<std::int64_t>(i) * 10 * kMs, i + 1));
    EXPECT_EQ(summary.telegrams(), 18u);
    EXPECT_EQ(summary.vlt2000_telegrams(), 18u);
    EXPECT_EQ(summary.vlt2000_commands(Vlt2000Letter::Update), 4u);
    EXPECT_EQ(summary.vlt2000_replies(Vlt2000Letter::Update), 2u);
    EXPECT_EQ(summary.vlt2000_replies(Vlt2000Letter::Read), 3u);
    EXPECT_EQ(summary.vlt2000_broadcasts(), 1u);
    EXPECT_EQ(summary.vlt2000_failed(), 3u);
    EXPECT_EQ(summary.vlt2000_failed_by_reason(0), 1u);
    EXPECT_EQ(summary.vlt2000_failed_by_reason(42), 1u);
    EXPECT_EQ(summary.vlt2000_failed_by_reason(100), 1u);
    EXPECT_EQ(summary.vlt2000_checksum_errors(), 1u);
    EXPECT_EQ(summary.vlt2000_checksum_disabled(), 2u);
    EXPECT_EQ(summary.vlt2000_address(1).failed, 2u);
    std::string text = summary_text(summary);
    EXPECT_EQ(text.find("by frame type"), std::string::npos) << text;
    EXPECT_EQ(text.find("FC protocol"), std::string::npos) << text;
    for (std::string_view expected : {
             "  telegrams: 18, from 2024-01-01T00:00:00.000000000Z",
             "  bus: VLT 2000\n  by direction: 11 commands, 6 replies (1 broadcast)\n",
             "  by letter:\n"
             "    U update                  6  (4 commands, 2 replies)\n"
             "    R read                    7  (4 commands, 3 replies)\n"
             "    C control                 1  (1 command, 0 replies)\n"
             "    I read index              2  (1 command, 1 reply)\n"
             "    unknown letter            1  (1 command, 0 replies)\n",
             "  failed replies (decimal position 9): 3\n"
             "    reason 00 parameter does not exist",
             "    reason 42 unknown reason code",
             "    no reason code given",
             "  checksums: 1 wrong, 2 not checked (\"??\")\n",
             "    vlt2000_checksum_mismatch",
             "  addresses:\n"
             "    00 (broadcast): 1 command, 0 replies\n"
             "    01: 6 commands, 4 replies, 2 failed\n"
             "    02: 1 command, 1 reply, 1 failed\n"
             "    03: 1 command, 1 reply, 2 without checksum (\"??\")\n"
             "    04: 1 command, 0 replies\n"
             "    05: 1 command, 0 replies, 1 checksum error\n",
         })
        EXPECT_TRUE(contains(text, expected)) << expected << "\n---\n" << text;
}

// The CLI end to end on a raw dump: -q, --pnu (a C telegram's parameter is no PNU) and --station
// (0: the broadcasts).
class Vlt2000CliTest : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string all;
        for (const std::string& telegram : session())
            if (telegram.size() == 22 && telegram[1] != 'A') all += telegram;
        path_ = test::temp_path("vlt2000-session.raw");
        test::write_text_file(path_, all);
    }
    test::CommandResult decode(std::vector<std::string> options) {
        std::vector<std::string> args{"decode", "--input-format", "raw", "--bus", "vlt2000"};
        args.insert(args.end(), options.begin(), options.end());
        args.push_back(path_);
        return test::run_dpscope(args);
    }
    std::string path_;
};

TEST_F(Vlt2000CliTest, PnuFilterSelectsTheParameter) {
    test::CommandResult r = decode({"--pnu", "516", "-T", "jsonl"});
    EXPECT_EQ(r.err, "");
    std::vector<std::string> l = test::lines_of(r.out);
    ASSERT_EQ(l.size(), 5u) << r.out;  // 1, 2, the wrong checksum, the kept groups, the X letter
    for (const std::string& line : l)
        EXPECT_TRUE(contains(line, "\"parameter\":516,")) << line;

    test::CommandResult none = decode({"--pnu", "0"});  // only the C broadcast names 0000
    EXPECT_EQ(none.out, "");
    EXPECT_TRUE(contains(none.err, "--pnu 0: no parameter request or answer about PNU 0"))
        << none.err;

    test::CommandResult failed = decode({"--pnu", "999"});
    EXPECT_EQ(failed.err, "");
    EXPECT_EQ(test::lines_of(failed.out).size(), 4u) << failed.out;  // 3, 4 and the two failed
}

TEST_F(Vlt2000CliTest, StationFilterAndBroadcasts) {
    test::CommandResult three = decode({"--station", "3"});
    EXPECT_EQ(three.exit_code, 0) << three.err;
    std::vector<std::string> l = test::lines_of(three.out);
    ASSERT_EQ(l.size(), 2u) << three.out;
    EXPECT_TRUE(contains(l[0], "M → 03")) << l[0];
    EXPECT_TRUE(contains(l[1], "03 → M")) << l[1];

    test::CommandResult broadcasts = decode({"--station", "0"});
    std::vector<std::string> b = test::lines_of(broadcasts.out);
    ASSERT_EQ(b.size(), 1u) << broadcasts.out;
    EXPECT_TRUE(contains(b[0], "M → all VLT C control")) << b[0];

    test::CommandResult quiet = decode({"-q"});
    EXPECT_TRUE(contains(quiet.out, "  bus: VLT 2000\n")) << quiet.out;
    EXPECT_TRUE(contains(quiet.out, "  addresses:\n")) << quiet.out;
}

// A line slower than --baud says, and drives that compute the checksum another way: each is said
// once, with the option that helps.
TEST(Vlt2000CliWarningTest, EarlyRepliesAndAnotherChecksumRuleAreSaid) {
    test::CommandResult slow =
        test::run_dpscope({"report", "--baud", "2400", "-w", test::temp_path("vlt-early.txt"),
                           "samples/vlt2000-examples.txt"});
    EXPECT_TRUE(contains(slow.err,
                         "responses began before their command could have ended at "
                         "2400 baud (10 bits a byte)"))
        << slow.err;
    test::CommandResult fine = test::run_dpscope(
        {"report", "-w", test::temp_path("vlt-fine.txt"), "samples/vlt2000-examples.txt"});
    EXPECT_FALSE(contains(fine.err, "warning")) << fine.err;

    // Every checksum off by 13 from the VLT 3000/3500 rule.
    std::string log;
    for (int i = 0; i < 4; ++i)
        for (std::string telegram : {vlt("<01R@@D@0516+000000"), vlt("<01RGH@@0516+001002")}) {
            const int sum = (telegram[19] - '0') * 10 + (telegram[20] - '0');
            const int other = (sum + 13) % 100;
            telegram[19] = static_cast<char>('0' + other / 10);
            telegram[20] = static_cast<char>('0' + other % 10);
            log += telegram + "\n";
        }
    const std::string path = test::temp_path("vlt-othersum.txt");
    test::write_text_file(path, log);
    test::CommandResult other =
        test::run_dpscope({"report", "-w", test::temp_path("vlt-other.txt"), path});
    EXPECT_EQ(other.exit_code, 1) << other.err;
    EXPECT_TRUE(contains(other.err,
                         "8 of 8 telegrams have a wrong checksum by the VLT 3000/3500 "
                         "rule"))
        << other.err;
    EXPECT_TRUE(contains(other.err, "--vlt2000-checksum ignore decodes them without it"));
    test::CommandResult ignored = test::run_dpscope(
        {"report", "--vlt2000-checksum", "ignore", "-w", test::temp_path("vlt-ignored.txt"), path});
    EXPECT_EQ(ignored.exit_code, 0) << ignored.err;
    EXPECT_FALSE(contains(ignored.err, "wrong checksum")) << ignored.err;
}

}  // namespace
}  // namespace dpscope
