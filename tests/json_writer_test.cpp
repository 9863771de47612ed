#include "formats/json_writer.hpp"

#include <gtest/gtest.h>

#include <string>
#include <string_view>
#include <vector>

#include "core/code_tables.hpp"
#include "core/finding.hpp"
#include "core/problem.hpp"
#include "formats/bit_meanings_json.hpp"
#include "protocols/fc/fc_telegram.hpp"
#include "protocols/profibus/dp_service.hpp"
#include "protocols/profibus/dpv1/dpv1.hpp"
#include "protocols/profibus/dpv1/profidrive.hpp"
#include "protocols/profibus/fdl.hpp"
#include "protocols/profibus/pcd.hpp"
#include "protocols/profibus/ppo.hpp"
#include "protocols/vlt2000/vlt2000_codes.hpp"
#include "protocols/vlt2000/vlt2000_describe.hpp"
#include "tests/json_parser.hpp"

namespace dpscope {
namespace {

std::string text(const fmt::memory_buffer& buffer) {
    return std::string(buffer.data(), buffer.size());
}

TEST(JsonWriterTest, PutsCommasBetweenMembersAndItemsOfNestedContainers) {
    fmt::memory_buffer buffer;
    JsonWriter w(buffer);
    w.begin_object();
    w.key("a").integer(1);
    w.key("b").begin_array();
    w.integer(2);
    w.begin_object().key("c").boolean(true).key("d").boolean(false).end_object();
    w.begin_array().integer(3).integer(-4).end_array();
    w.string("e");
    w.end_array();
    w.key("f").begin_object().key("g").begin_object().key("h").null().end_object().end_object();
    w.key("i").integer(5);
    w.end_object();
    EXPECT_EQ(text(buffer),
              R"({"a":1,"b":[2,{"c":true,"d":false},[3,-4],"e"],"f":{"g":{"h":null}},"i":5})");
    EXPECT_EQ(w.depth(), 0u);
}

TEST(JsonWriterTest, KeysFromLiteralsCharArraysAndStringViewsReadTheSame) {
    fmt::memory_buffer buffer;
    JsonWriter w(buffer);
    char shorter[16] = "ab";  // an array longer than the name it holds
    const std::string view = "cd";
    w.begin_object();
    w.key("literal").integer(1);
    w.key(shorter).integer(2);
    w.key(std::string_view(view)).integer(3);
    w.end_object();
    EXPECT_EQ(text(buffer), R"({"literal":1,"ab":2,"cd":3})");
}

TEST(JsonWriterTest, WritesEmptyContainers) {
    fmt::memory_buffer buffer;
    JsonWriter w(buffer);
    w.begin_object();
    w.key("object").begin_object().end_object();
    w.key("array").begin_array().end_array();
    w.key("nested").begin_array().begin_array().end_array().begin_object().end_object().end_array();
    w.end_object();
    EXPECT_EQ(text(buffer), R"({"object":{},"array":[],"nested":[[],{}]})");
}

TEST(JsonWriterTest, WritesAnEmptyObjectAtTheTop) {
    fmt::memory_buffer buffer;
    JsonWriter w(buffer);
    w.begin_object().end_object();
    EXPECT_EQ(text(buffer), "{}");
}

TEST(JsonWriterTest, WritesNullAsAMemberAndAsAnItem) {
    fmt::memory_buffer buffer;
    JsonWriter w(buffer);
    w.begin_object();
    w.key("a").null();
    w.key("b").begin_array().null().null().end_array();
    w.key("c").optional_integer(false, 7);
    w.key("d").optional_integer(true, 7);
    w.end_object();
    EXPECT_EQ(text(buffer), R"({"a":null,"b":[null,null],"c":null,"d":7})");
}

TEST(JsonWriterTest, EscapesQuotesBackslashesAndControlCharacters) {
    fmt::memory_buffer buffer;
    JsonWriter w(buffer);
    w.begin_array();
    w.string("say \"hi\"\\");
    w.string(std::string_view("\n\r\t\b\f\x01\x1f\0", 8));
    w.string("");
    w.end_array();
    EXPECT_EQ(text(buffer), R"(["say \"hi\"\\","\n\r\t\u0008\u000c\u0001\u001f\u0000",""])");
}

// The check for "nothing to escape" takes sixteen bytes a step, then eight, then one: a byte that
// needs an escape (and none of the bytes at the edges of the tests) is found at every position of
// strings up to two sixteen-byte steps, an eight-byte step and a tail long, with plain bytes on
// both sides.
TEST(JsonWriterTest, FindsAByteToEscapeAtEveryPositionOfAWord) {
    struct Special {
        std::string_view bytes;
        std::string_view written;
    };
    const Special specials[] = {{"\"", "\\\""},
                                {"\\", "\\\\"},
                                {std::string_view("\0", 1), "\\u0000"},
                                {"\x1f", "\\u001f"},
                                {"\n", "\\n"},
                                {"\x7f", "\x7f"},
                                {"\xC3\xBC", "\xC3\xBC"},
                                {"\x80", "\xEF\xBF\xBD"},
                                {" ", " "},
                                {"!", "!"},
                                {"~", "~"}};
    for (std::size_t length = 0; length <= 44; ++length) {
        for (std::size_t at = 0; at <= length; ++at) {
            for (const Special& special : specials) {
                std::string input(at, 'a');
                input += special.bytes;
                input.append(length - at, 'b');
                std::string expected = "\"" + std::string(at, 'a');
                expected += special.written;
                expected.append(length - at, 'b');
                expected += '"';
                fmt::memory_buffer buffer;
                json::string(buffer, input);
                ASSERT_EQ(text(buffer), expected) << "length " << length << " at " << at;
            }
        }
    }
}

TEST(JsonWriterTest, CopiesNonAsciiBytesAsTheyAre) {
    fmt::memory_buffer buffer;
    JsonWriter w(buffer);
    // UTF-8 "Grüße µs" and a DEL: nothing to escape.
    w.string(
        "Gr\xC3\xBC\xC3\x9F"
        "e \xC2\xB5s\x7F");
    EXPECT_EQ(text(buffer),
              "\"Gr\xC3\xBC\xC3\x9F"
              "e \xC2\xB5s\x7F\"");
}

TEST(JsonWriterTest, WritesNumberTextAndRawValuesVerbatim) {
    fmt::memory_buffer buffer;
    JsonWriter w(buffer);
    w.begin_object();
    w.key("ms").number_text("0.125000");
    w.key("time").raw_value([](fmt::memory_buffer& b) { b.append(std::string_view("1.5")); });
    w.key("list").begin_array().number_text("1.0").number_text("2.0").end_array();
    w.end_object();
    EXPECT_EQ(text(buffer), R"({"ms":0.125000,"time":1.5,"list":[1.0,2.0]})");
}

TEST(JsonWriterTest, AppendsToWhatTheBufferHolds) {
    fmt::memory_buffer buffer;
    buffer.append(std::string_view("x "));
    JsonWriter w(buffer);
    w.begin_array().integer(1).end_array();
    EXPECT_EQ(text(buffer), "x [1]");
}

TEST(JsonWriterTest, StringsRoundTripThroughAStrictParser) {
    constexpr char kText[] = "quote \" backslash \\ tab \t nul \0 bell \a \xC2\xB5s end";
    const std::string original(kText, sizeof kText - 1);
    fmt::memory_buffer buffer;
    JsonWriter w(buffer);
    w.begin_object().key("s").string(original).key("n").begin_array().end_array().end_object();
    std::optional<test::Json> parsed = test::parse_json(text(buffer));
    ASSERT_TRUE(parsed) << text(buffer);
    EXPECT_EQ((*parsed)["s"].string(), original);
    EXPECT_TRUE((*parsed)["n"].items.empty());
}

}  // namespace
}  // namespace dpscope

namespace dpscope {
namespace {

// The writer writes through a cursor into the buffer's spare room and tells the buffer its size
// at the end of a top-level value, at settle() and before another hand writes: a document far
// larger than the room it takes at a time comes out whole, also when the buffer is emptied in the
// middle (as Output::end_record does) after settle().
TEST(JsonWriterTest, ALongDocumentWrittenInPiecesComesOutWhole) {
    fmt::memory_buffer buffer;
    std::string flushed;
    {
        JsonWriter w(buffer);
        w.begin_array();
        std::string expected = "[";
        for (int i = 0; i < 3000; ++i) {
            w.begin_object().key("n").integer(-i).key("s").string(std::string(i % 50, 'x'));
            w.key("big").string(std::string(i == 1500 ? 10000 : 1, 'y')).end_object();
            if (i % 100 == 99) {  // flushed in the middle of the document
                w.settle();
                flushed.append(buffer.data(), buffer.size());
                buffer.clear();
            }
        }
        w.end_array();
    }
    flushed.append(buffer.data(), buffer.size());
    std::optional<test::Json> parsed = test::parse_json(flushed);
    ASSERT_TRUE(parsed);
    ASSERT_EQ(parsed->items.size(), 3000u);
    EXPECT_EQ(test::number_of((*parsed)[2999]["n"]), -2999);
    EXPECT_EQ((*parsed)[1500]["big"].text.size(), 10000u);
    EXPECT_EQ((*parsed)[49]["s"].text, std::string(49, 'x'));
}

TEST(JsonWriterTest, TheBufferHoldsATopLevelValueAsSoonAsItIsComplete) {
    fmt::memory_buffer buffer;
    JsonWriter w(buffer);
    w.begin_object().key("a").integer(1).end_object();
    buffer.push_back('\n');  // what the jsonl renderer does before the writer ends
    EXPECT_EQ(text(buffer), "{\"a\":1}\n");
}

}  // namespace
}  // namespace dpscope

namespace dpscope {
namespace {

// JsonWriter::name() skips the escape check: the tables it writes from hold nothing to escape.
TEST(JsonWriterTest, TheNamesWrittenWithoutTheEscapeCheckNeedNone) {
    std::vector<std::string_view> names;
    for (PcdProfile profile : {PcdProfile::Profidrive, PcdProfile::Fc})
        for (bool danfoss : {false, true})
            for (const WordBits* bits :
                 {&control_word_bits(profile, danfoss), &status_word_bits(profile, danfoss)})
                for (const WordBit& bit : *bits) {
                    names.push_back(bit.when_0);
                    names.push_back(bit.when_1);
                }
    for (unsigned bit = 0; bit < 16; ++bit)
        for (const Vlt2000Bit* row : {&vlt2000_control_bit(bit), &vlt2000_status_bit(bit)}) {
            names.push_back(row->when_0);
            names.push_back(row->when_1);
        }
    names.push_back("group kept (P)");  // vlt2000_bit_meaning's own
    // The enumerations' names the jsonl lines write with name().
    for (Direction direction : {Direction::Request, Direction::Response}) {
        names.push_back(direction_name(direction));
        names.push_back(vlt2000_word_name(direction));
    }
    for (FcBlock block : {FcBlock::Process, FcBlock::Parameter, FcBlock::Text, FcBlock::Unknown})
        names.push_back(fc_block_name(block));
    for (FcAddressFormat format : {FcAddressFormat::Short, FcAddressFormat::Long})
        names.push_back(fc_address_format_name(format));
    for (int letter = 0; letter <= static_cast<int>(Vlt2000Letter::Unknown); ++letter)
        names.push_back(vlt2000_letter_name(static_cast<Vlt2000Letter>(letter)));
    // PROFIBUS DP's (profibus_jsonl_render.cpp): every value each table can be asked for.
    for (int type = 0; type <= static_cast<int>(FrameType::Invalid); ++type)
        names.push_back(frame_type_name(static_cast<FrameType>(type)));
    for (std::size_t service = 0; service < kServiceCount; ++service)
        names.push_back(service_name(static_cast<Service>(service)));
    for (int source = 0; source <= static_cast<int>(PpoSource::Option); ++source)
        names.push_back(ppo_source_name(static_cast<PpoSource>(source)));
    for (int dialect = 0; dialect <= static_cast<int>(Dialect::Vlt2000); ++dialect) {
        names.push_back(dialect_name(static_cast<Dialect>(dialect)));
        for (unsigned rc = 0; rc < 16; ++rc) {
            names.push_back(
                request_code(static_cast<Dialect>(dialect), static_cast<std::uint8_t>(rc)).meaning);
            names.push_back(
                response_code(static_cast<Dialect>(dialect), static_cast<std::uint8_t>(rc))
                    .meaning);
        }
    }
    for (unsigned byte = 0; byte < 256; ++byte) {
        const auto b = static_cast<std::uint8_t>(byte);
        names.push_back(request_function_name(FrameControl{b}));
        names.push_back(response_status_name(b));
        names.push_back(station_type_name(b & 0x03));
        names.push_back(dpv1_function_name(b));
        names.push_back(profidrive_request_id_name(b));
        names.push_back(profidrive_response_id_name(b));
        names.push_back(profidrive_attribute_name(b));
        names.push_back(profidrive_format_name(b));
    }
    names.push_back("word");
    names.push_back("dword");
    // A finding's kind and severity (json::finding).
    for (std::size_t kind = 0; kind < kFindingKindCount; ++kind)
        names.push_back(finding_kind_name(static_cast<FindingKind>(kind)));
    for (Severity severity : {Severity::Note, Severity::Warning, Severity::Error})
        names.push_back(severity_name(severity));
    for (std::string_view name : names)
        EXPECT_TRUE(json::plain_text(name)) << name;
    fmt::memory_buffer a, b;
    JsonWriter(a).name("start");
    JsonWriter(b).string("start");
    EXPECT_EQ(text(a), text(b));
}

}  // namespace
}  // namespace dpscope

namespace dpscope {
namespace {

// BitMeaningsJson keeps 64 arrays: whatever the order of the words (slots shared, evicted and
// found again), each array is the one the writer writes for that word, and two tables with the
// same word keep apart.
TEST(BitMeaningsJsonTest, EachArrayIsTheWritersOwnWhateverTheOrder) {
    const WordBits& control = control_word_bits(PcdProfile::Fc, true);
    const WordBits& status = status_word_bits(PcdProfile::Fc, true);
    BitMeaningsJson arrays;
    for (int pass = 0; pass < 3; ++pass)
        for (std::uint32_t i = 0; i < 300; ++i) {
            const std::uint16_t word = static_cast<std::uint16_t>((i * 40503u) >> (pass * 2));
            for (const WordBits* bits : {&control, &status}) {
                const auto meaning = [&](unsigned bit) {
                    return (word >> bit) & 1u ? (*bits)[bit].when_1 : (*bits)[bit].when_0;
                };
                fmt::memory_buffer expected;
                {
                    JsonWriter w(expected);
                    w.begin_array();
                    for (unsigned bit = 0; bit < 16; ++bit)
                        w.string(meaning(bit));
                    w.end_array();
                }
                ASSERT_EQ(arrays.array(bits, word, meaning), text(expected))
                    << "word " << word << " pass " << pass;
            }
        }
}

}  // namespace
}  // namespace dpscope
