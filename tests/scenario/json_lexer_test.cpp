// The one JSON lexer behind the position index, the duplicate keys and the syntax messages.
#include "scenario/json_lexer.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace rumble::scenario {
namespace {

/// Each token's kind and text, up to the end.
std::vector<std::pair<TokenKind, std::string>> tokens(std::string_view text) {
  std::vector<std::pair<TokenKind, std::string>> out;
  JsonLexer lex(text);
  for (JsonToken t = lex.next(); t.kind != TokenKind::kEnd; t = lex.next())
    out.emplace_back(t.kind, std::string(text.substr(t.span.begin, t.span.end - t.span.begin)));
  return out;
}

TEST(JsonLexer, SplitsJsonIntoPunctuationStringsAndWords) {
  using K = TokenKind;
  const auto got = tokens("\xEF\xBB\xBF{\"a\\\"b\": [1.5e3, true],\n\"c\":null}");
  const std::vector<std::pair<TokenKind, std::string>> expected = {
      {K::kOpen, "{"},     {K::kString, "\"a\\\"b\""}, {K::kColon, ":"},   {K::kOpen, "["},
      {K::kWord, "1.5e3"}, {K::kComma, ","},           {K::kWord, "true"}, {K::kClose, "]"},
      {K::kComma, ","},    {K::kString, "\"c\""},      {K::kColon, ":"},   {K::kWord, "null"},
      {K::kClose, "}"}};
  EXPECT_EQ(got, expected) << "the byte order mark is skipped, an escaped quote stays inside";
}

TEST(JsonLexer, AnUnclosedStringEndsWhereTheParserGivesUp) {
  const std::string text = "{\"a\": \"abc\n}";
  JsonLexer lex(text);
  lex.next();
  lex.next();
  lex.next();
  const JsonToken s = lex.next();
  EXPECT_EQ(s.kind, TokenKind::kString);
  EXPECT_FALSE(s.closed);
  EXPECT_EQ(s.span.end, text.find('\n')) << "at the raw line break";
  EXPECT_EQ(lex.next().kind, TokenKind::kClose) << "and lexing goes on after it";
  const std::string cut = "[\"abc\\";
  JsonLexer tail(cut);
  tail.next();
  const JsonToken t = tail.next();
  EXPECT_FALSE(t.closed);
  EXPECT_EQ(t.span.end, cut.size()) << "a trailing backslash reads nothing past the end";
  EXPECT_EQ(tail.next().kind, TokenKind::kEnd);
  EXPECT_EQ(tail.next().kind, TokenKind::kEnd);
}

TEST(JsonLexer, DecodesEscapesAndRefusesInvalidOnes) {
  const auto decoded = [](const std::string& text) {
    JsonLexer lex(text);
    return decode_string(text, lex.next());
  };
  EXPECT_EQ(decoded(R"("a\tb\u00e9\/")"), "a\tb\xC3\xA9/");
  EXPECT_EQ(decoded(R"("\ud83d\ude00")"), "\xF0\x9F\x98\x80") << "a surrogate pair";
  EXPECT_FALSE(decoded(R"("\q")").has_value());
  EXPECT_FALSE(decoded(R"("\u12")").has_value());
  EXPECT_FALSE(decoded("\"open").has_value());
  EXPECT_FALSE(decoded("word").has_value());
}

}  // namespace
}  // namespace rumble::scenario
