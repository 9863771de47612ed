// Text from outside (file names, settings lines) made valid UTF-8 without control characters,
// and the writers that put such text into UTF-8 outputs (JSON, XML/HTML, Markdown).
#include "core/text_encoding.hpp"

#include <gtest/gtest.h>

#include <string>

#include "formats/describe.hpp"
#include "formats/json_writer.hpp"
#include "formats/report_markup.hpp"

namespace dpscope {
namespace {

const std::string kFffd = "\xEF\xBF\xBD";

TEST(TextEncodingTest, ValidSequencesAreMeasured) {
    EXPECT_EQ(utf8_sequence_length("\xC2\xB5", 0), 2u);          // µ
    EXPECT_EQ(utf8_sequence_length("\xE2\x86\x92", 0), 3u);      // →
    EXPECT_EQ(utf8_sequence_length("\xF0\x9F\x98\x80", 0), 4u);  // U+1F600
    EXPECT_EQ(utf8_sequence_length("\xF4\x8F\xBF\xBF", 0), 4u);  // U+10FFFF
    EXPECT_TRUE(is_valid_utf8("Log \xC2\xB5s \xE2\x86\x92 ok"));
}

TEST(TextEncodingTest, InvalidSequencesAreRefused) {
    for (std::string_view bad : {
             std::string_view("\x80"),              // a continuation byte alone
             std::string_view("\xC0\xAF"),          // an overlong '/'
             std::string_view("\xC1\xBF"),          // overlong
             std::string_view("\xE0\x80\xAF"),      // overlong, three bytes
             std::string_view("\xED\xA0\x80"),      // a surrogate (U+D800)
             std::string_view("\xF0\x80\x80\xAF"),  // overlong, four bytes
             std::string_view("\xF4\x90\x80\x80"),  // beyond U+10FFFF
             std::string_view("\xF5\x80\x80\x80"),  // never a first byte
             std::string_view("\xFF"),
             std::string_view("\xE2\x86"),      // cut short by the end
             std::string_view("\xE2\x41\x42"),  // no continuation
         }) {
        EXPECT_EQ(utf8_sequence_length(bad, 0), 0u) << testing::PrintToString(bad);
        EXPECT_FALSE(is_valid_utf8(bad));
    }
}

TEST(TextEncodingTest, DisplayTextReplacesBadBytesAndControls) {
    EXPECT_EQ(display_text("capture.pcap"), "capture.pcap");
    EXPECT_EQ(display_text("Log \xC2\xB5s"), "Log \xC2\xB5s");
    EXPECT_EQ(display_text("cap\xFF\xFE\x01.pcap"), "cap" + kFffd + kFffd + kFffd + ".pcap");
    EXPECT_EQ(display_text("a\tb\nc\x7F"), "a" + kFffd + "b" + kFffd + "c" + kFffd);
    EXPECT_EQ(display_text("\x1B[31mred"), kFffd + "[31mred");  // no terminal escape gets through
}

TEST(TextEncodingTest, ExcerptsAreCutAtACharacterBoundary) {
    EXPECT_EQ(quoted_excerpt("short", 80), "short");
    EXPECT_EQ(quoted_excerpt(std::string(200, 'x'), 10), std::string(10, 'x') + "...");
    // 9 bytes of 'a' then "µ" (2 bytes): a cut at 10 would split the µ.
    EXPECT_EQ(quoted_excerpt(std::string(9, 'a') + "\xC2\xB5" + "zzz", 10),
              std::string(9, 'a') + "...");
}

TEST(TextEncodingTest, JsonStringsAreValidUtf8WhateverTheBytes) {
    fmt::memory_buffer buffer;
    JsonWriter w(buffer);
    w.begin_array();
    w.string("cap\xFF\xFE\x01.pcap");
    w.string("Log \xC2\xB5s \xE2\x86\x92");
    w.string("\xE2\x86");  // cut short
    w.end_array();
    const std::string json(buffer.data(), buffer.size());
    EXPECT_EQ(json, "[\"cap" + kFffd + kFffd + "\\u0001.pcap\",\"Log \xC2\xB5s \xE2\x86\x92\",\"" +
                        kFffd + kFffd + "\"]");
    EXPECT_TRUE(is_valid_utf8(json));
}

TEST(TextEncodingTest, XmlTextIsValidUtf8WithoutForbiddenControls) {
    const std::string text = report::xml("cap\xFF\x01<&>\t\xC2\xB5\x7F");
    EXPECT_EQ(text, "cap" + kFffd + kFffd + "&lt;&amp;&gt;\t\xC2\xB5" + kFffd);
    EXPECT_TRUE(
        is_valid_utf8(report::md_escape("a|\xFF"
                                        "b")));
    EXPECT_EQ(report::md_escape("a|\xFF"
                                "b\xC2\xB5"),
              "a\\|" + kFffd + "b\xC2\xB5");
}

}  // namespace
}  // namespace dpscope
