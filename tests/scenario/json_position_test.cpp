#include "scenario/json_position.hpp"

#include <gtest/gtest.h>

#include <string>

namespace rumble::scenario {
namespace {

// "line:col" of the value (or key) at a pointer, "-" when not found.
std::string at(std::string_view text, std::string_view pointer, bool key = false) {
  const auto span = key ? find_key(text, pointer) : find_value(text, pointer);
  if (!span) return "-";
  const LineColumn lc = line_column(text, span->begin);
  return std::to_string(lc.line) + ":" + std::to_string(lc.column);
}

std::string token(std::string_view text, std::string_view pointer) {
  const auto span = find_value(text, pointer);
  return span ? std::string(text.substr(span->begin, span->end - span->begin)) : "-";
}

TEST(ScenarioJsonPosition, FindsValuesAndKeysInNestedObjectsAndArrays) {
  const std::string text =
      "{\n"
      "  \"a\": {\"b\": [10, {\"c\": -2.5e7}]},\n"
      "  \"d\": \"x\"\n"
      "}\n";
  EXPECT_EQ(at(text, ""), "1:1");
  EXPECT_EQ(at(text, "/a"), "2:8");
  EXPECT_EQ(at(text, "/a", true), "2:3");
  EXPECT_EQ(at(text, "/a/b/0"), "2:15");
  EXPECT_EQ(at(text, "/a/b/1/c"), "2:25");
  EXPECT_EQ(at(text, "/a/b/1/c", true), "2:20");
  EXPECT_EQ(token(text, "/a/b/1/c"), "-2.5e7");
  EXPECT_EQ(token(text, "/a/b"), "[10, {\"c\": -2.5e7}]");
  EXPECT_EQ(at(text, "/d"), "3:8");
}

TEST(ScenarioJsonPosition, MissingTargetsAreNotFound) {
  const std::string text = R"({"a": [1, 2], "b": {}})";
  EXPECT_EQ(at(text, "/a/2"), "-");
  EXPECT_EQ(at(text, "/a/x"), "-");
  EXPECT_EQ(at(text, "/a/01"), "-");
  EXPECT_EQ(at(text, "/b/c"), "-");
  EXPECT_EQ(at(text, "/a/0/deeper"), "-");
  EXPECT_EQ(at(text, "no-slash"), "-");
  EXPECT_EQ(at(text, "", true), "-");  // the root has no key
}

TEST(ScenarioJsonPosition, KeysAreComparedUnescaped) {
  // Pointer escapes (~1 = '/', ~0 = '~') and JSON escapes (\u0062 = 'b', \" ) both decode.
  const std::string text = R"({"a/b": 1, "t~": 2, "\u0062ee": 3, "q\"x": 4, "\ud83d\ude00": 5})";
  EXPECT_EQ(token(text, "/a~1b"), "1");
  EXPECT_EQ(token(text, "/t~0"), "2");
  EXPECT_EQ(token(text, "/bee"), "3");
  EXPECT_EQ(token(text, "/q\"x"), "4");
  EXPECT_EQ(token(text, "/\xF0\x9F\x98\x80"), "5");
}

TEST(ScenarioJsonPosition, DuplicateKeysResolveToTheLastOneLikeTheParser) {
  const std::string text = R"({"a": 1, "a": 2})";
  EXPECT_EQ(token(text, "/a"), "2");
}

TEST(ScenarioJsonPosition, StringsWithBracketsDoNotConfuseTheWalk) {
  const std::string text = R"({"s": "}]{[\"", "t": [ "]", {"u": "{"} ], "v": 7})";
  EXPECT_EQ(token(text, "/v"), "7");
  EXPECT_EQ(token(text, "/t/1/u"), "\"{\"");
}

TEST(ScenarioJsonPosition, ColumnsCountCharactersNotBytesAndSkipTheBom) {
  const std::string text = "\xEF\xBB\xBF{\"\xC3\xA9t\xC3\xA9\": 1}";
  EXPECT_EQ(at(text, ""), "1:1");
  EXPECT_EQ(at(text, "/\xC3\xA9t\xC3\xA9"), "1:9");  // after {"été":
}

TEST(ScenarioJsonPosition, NearestFallsBackToTheClosestAncestorInTheText) {
  const std::string text = "{\n  \"track\": {\n    \"rail\": {}\n  }\n}";
  const auto span = find_nearest(text, "/track/rail/elements_per_bay", false);
  ASSERT_TRUE(span.has_value());
  EXPECT_EQ(line_column(text, span->begin).line, 3u);
  const auto key = find_nearest(text, "/track/rail", true);
  ASSERT_TRUE(key.has_value());
  EXPECT_EQ(text.substr(key->begin, key->end - key->begin), "\"rail\"");
}

TEST(ScenarioJsonPosition, TruncatedAndGarbledTextNeverReadsPastTheEnd) {
  for (const std::string text : {"{\"a\": [1, 2", "{\"a\"", "{\"a\": \"unterminated", "[[[[",
                                 "{\"a\": {\"b\": \\u", "\x01\x02\xFF", "", "{\"a\":}"}) {
    (void)find_value(text, "/a/1");
    (void)find_key(text, "/a");
    (void)find_nearest(text, "/a/b/c", true);
    (void)token_start(text, text.size());
  }
  SUCCEED();
}

TEST(ScenarioJsonPosition, DeepNestingIsSkippedWithoutRecursion) {
  const std::string text =
      "{\"deep\": " + std::string(100000, '[') + std::string(100000, ']') + ", \"after\": true}";
  EXPECT_EQ(token(text, "/after"), "true");
}

TEST(ScenarioJsonPosition, TokenStartFindsTheFirstCharacterOfTheTokenAtAnOffset) {
  const std::string text = R"({"key": "value", "n": -12.5e3})";
  EXPECT_EQ(token_start(text, text.find("alue")), text.find("\"value\""));
  EXPECT_EQ(token_start(text, text.find("2.5")), text.find("-12"));
  EXPECT_EQ(token_start(text, text.find(',')), text.find(','));
  // An unterminated string reaches to the line break that ends it.
  const std::string open = "{\"a\": \"abc\n}";
  EXPECT_EQ(token_start(open, open.find('\n')), open.find("\"abc"));
}

TEST(ScenarioJsonPosition, SplitPointerDecodesAndRejectsMalformedPointers) {
  EXPECT_EQ(split_pointer("/a~1b/~0/0").value(), (std::vector<std::string>{"a/b", "~", "0"}));
  EXPECT_EQ(split_pointer("").value(), std::vector<std::string>{});
  EXPECT_EQ(split_pointer("/").value(), std::vector<std::string>{""});
  EXPECT_FALSE(split_pointer("a").has_value());
  EXPECT_FALSE(split_pointer("/a~2").has_value());
  EXPECT_FALSE(split_pointer("/a~").has_value());
  EXPECT_EQ(escape_pointer_token("a/b~c"), "a~1b~0c");
}

TEST(ScenarioJsonPosition, TheOnePassIndexAgreesWithThePerPointerScan) {
  const std::string text =
      "\xEF\xBB\xBF{\"a\": {\"b\": [10, {\"c\": -2.5e7}, []], \"\xC3\xA9\": {}},\n"
      "  \"d/e\": \"x\", \"a\": {\"z\": [true, null, {\"q~\": 1}]}}";
  const PositionIndex index(text);
  // (The index still knows "/a/b" of the first, overridden "a"; nothing asks for it, as the
  // parsed document has no such value.)
  for (const char* pointer : {"", "/a", "/a/z", "/a/z/0", "/a/z/1", "/a/z/2", "/a/z/2/q~0", "/d~1e",
                              "/missing", "/a/z/3"}) {
    const auto slow = find_value(text, pointer);
    const auto fast = index.value(pointer);
    ASSERT_EQ(slow.has_value(), fast.has_value()) << pointer;
    if (!slow) continue;
    EXPECT_EQ(slow->begin, fast->begin) << pointer;
    EXPECT_EQ(slow->end, fast->end) << pointer;
    const auto slow_key = find_key(text, pointer);
    const auto fast_key = index.key(pointer);
    ASSERT_EQ(slow_key.has_value(), fast_key.has_value()) << pointer;
    if (slow_key) {
      EXPECT_EQ(slow_key->begin, fast_key->begin) << pointer;
    }
    const LineColumn a = line_column(text, slow->begin);
    const LineColumn b = index.line_column(slow->begin);
    EXPECT_EQ(a.line, b.line) << pointer;
    EXPECT_EQ(a.column, b.column) << pointer;
  }
  EXPECT_EQ(index.nearest("/a/z/2/nothing/deeper", false)->begin,
            find_value(text, "/a/z/2")->begin);
}

TEST(ScenarioJsonPosition, IndexColumnsOnAVeryLongLineCountCharacters) {
  std::string text = "[";
  for (int i = 0; i < 5000; ++i) text += "\"\xC3\xA9\xC3\xA9\", ";
  text += "1]";
  const PositionIndex index(text);
  const auto span = index.value("/5000");
  ASSERT_TRUE(span.has_value());
  EXPECT_EQ(index.line_column(span->begin).column, 1u + 5000u * 6u + 1u);
  EXPECT_EQ(line_column(text, span->begin).column, 1u + 5000u * 6u + 1u);
}

TEST(ScenarioJsonPosition, IndexOfTruncatedTextKeepsWhatItSaw) {
  const std::string text = "{\"a\": 1, \"b\": [1, 2";
  const PositionIndex index(text);
  EXPECT_TRUE(index.value("/a").has_value());
  EXPECT_TRUE(index.value("/b/1").has_value());
  EXPECT_FALSE(index.value("/b/2").has_value());
}

}  // namespace
}  // namespace rumble::scenario
