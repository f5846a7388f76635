#include "scenario/syntax_error.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "scenario/did_you_mean.hpp"
#include "scenario/json_position.hpp"

namespace rumble::scenario {
namespace {

Diagnostic at(std::string_view text, std::size_t offset, std::string message,
              std::string hint = "") {
  Diagnostic d;
  const LineColumn lc = line_column(text, offset);
  d.line = lc.line;
  d.column = lc.column;
  d.message = "syntax error: " + std::move(message);
  d.hint = std::move(hint);
  return d;
}

/// The word (number, literal, garbage) starting at `offset`, at most 40 bytes, printable.
std::string word_at(std::string_view text, std::size_t offset) {
  std::string word;
  for (std::size_t i = offset;
       i < text.size() && !is_json_whitespace(text[i]) && !is_json_structural(text[i]); ++i) {
    if (word.size() >= 40) {
      word += "...";
      break;
    }
    word += text[i];
  }
  return word;
}

std::string hex_byte(unsigned char b) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "0x%02X", static_cast<unsigned>(b));
  return buf;
}

bool printable_ascii(std::string_view s) {
  for (const char c : s) {
    const auto b = static_cast<unsigned char>(c);
    if (b < 0x20 || b >= 0x7F) return false;
  }
  return true;
}

std::size_t previous_non_ws(std::string_view text, std::size_t offset, bool& found) {
  found = false;
  while (offset > 0) {
    --offset;
    if (!is_json_whitespace(text[offset])) {
      found = true;
      return offset;
    }
  }
  return 0;
}

/// Brackets still open at the end of the text, innermost last (offsets of '{' or '[').
std::vector<std::size_t> open_brackets(std::string_view text) {
  std::vector<std::size_t> stack;
  JsonLexer lex(text);
  for (JsonToken t = lex.next(); t.kind != TokenKind::kEnd; t = lex.next()) {
    if (t.kind == TokenKind::kOpen) {
      stack.push_back(t.span.begin);
    } else if (t.kind == TokenKind::kClose && !stack.empty()) {
      stack.pop_back();
    }
  }
  return stack;
}

std::string where(std::string_view text, std::size_t offset) {
  const LineColumn lc = line_column(text, offset);
  return "line " + std::to_string(lc.line) + ", column " + std::to_string(lc.column);
}

/// "syntax error while parsing object key - unexpected '}'; expected string literal" ->
/// context "object key", detail "unexpected '}'; expected string literal".
void split_message(std::string_view what, std::string& context, std::string& detail) {
  std::string_view rest = what;
  if (const auto p = rest.find("syntax error while parsing "); p != std::string_view::npos) {
    rest = rest.substr(p + std::string_view("syntax error while parsing ").size());
    if (const auto dash = rest.find(" - "); dash != std::string_view::npos) {
      context = std::string(rest.substr(0, dash));
      detail = std::string(rest.substr(dash + 3));
      return;
    }
  }
  if (const auto p = rest.find(": "); p != std::string_view::npos) rest = rest.substr(p + 2);
  if (const auto p = rest.find(": "); p != std::string_view::npos) rest = rest.substr(p + 2);
  detail = std::string(rest);
}

std::string after(std::string_view s, std::string_view marker) {
  const auto p = s.find(marker);
  if (p == std::string_view::npos) return "";
  return std::string(s.substr(p + marker.size()));
}

std::string before(std::string_view s, std::string_view marker) {
  return std::string(s.substr(0, s.find(marker)));
}

Diagnostic invalid_literal(std::string_view text, std::size_t tok, const std::string& context,
                           const std::string& detail) {
  const std::string word = word_at(text, tok);
  if (tok < text.size() && text[tok] == '/') {
    return at(text, tok, "comments are not allowed in JSON",
              "remove the comment; free text can go in the \"description\" key");
  }
  if (tok < text.size() && text[tok] == '\'') {
    return at(text, tok, "strings must be in double quotes, not single quotes",
              "replace ' with \"");
  }
  if (detail.find("expected end of input") != std::string::npos) {
    return at(text, tok, "unexpected text after the end of the JSON value",
              "a scenario file holds exactly one JSON object; is there an extra '}' or a "
              "missing '{'?");
  }
  if (word.empty() || !printable_ascii(word.substr(0, 1))) {
    const auto b = tok < text.size() ? static_cast<unsigned char>(text[tok]) : 0;
    return at(text, tok, "unexpected character " + hex_byte(b),
              "is this a JSON text file? (it may be binary, or not saved as UTF-8)");
  }
  if (context == "object key") {
    return at(text, tok, "object key " + word + " must be in double quotes",
              "write \"" + word + "\"");
  }
  for (const char* special : {"NaN", "Infinity", "-Infinity", "+Infinity", "nan", "inf", "-inf"}) {
    if (word == special) {
      return at(text, tok, "'" + word + "' is not a JSON number",
                "JSON has no NaN or Infinity; use a finite number");
    }
  }
  if (word.size() > 1 && word[0] == '+') {
    return at(text, tok, "numbers must not start with '+'", "write " + word.substr(1));
  }
  const std::vector<std::string> literals = {"true", "false", "null"};
  if (const auto m = closest_match(word, literals)) {
    return at(text, tok, "invalid literal '" + word + "'",
              "did you mean " + *m + "? JSON literals are lowercase: true, false, null");
  }
  return at(text, tok, "unquoted text '" + word + "'",
            "strings must be in double quotes: \"" + word + "\"");
}

Diagnostic unexpected_token(std::string_view text, std::size_t tok, const std::string& context,
                            const std::string& detail) {
  const std::string token = before(after(detail, "unexpected "), ";");
  const std::string expected = after(detail, "; expected ");
  bool has_prev = false;
  const std::size_t prev = previous_non_ws(text, tok, has_prev);
  const char c = tok < text.size() ? text[tok] : '\0';

  if ((c == '}' || c == ']') && has_prev && text[prev] == ',') {
    return at(text, prev,
              c == '}' ? "trailing comma after the last member of an object"
                       : "trailing comma after the last element of an array",
              "remove this comma; JSON allows no comma before '" + std::string(1, c) + "'");
  }
  if (expected == "end of input") {
    return at(text, tok, "unexpected text after the end of the JSON value",
              "a scenario file holds exactly one JSON object; is there an extra '}' or a "
              "missing '{'?");
  }
  if (expected == "':'") {
    return at(text, tok, "missing ':' after the object key", "write \"key\": value");
  }
  // nlohmann lexes "01" as the numbers 0 and 1; the second is the "unexpected" one.
  const std::string word = word_at(text, tok);
  const std::size_t digits = (!word.empty() && word[0] == '-') ? 1 : 0;
  if (token.find("number literal") != std::string::npos && word.size() > digits + 1 &&
      word[digits] == '0' && word[digits + 1] >= '0' && word[digits + 1] <= '9') {
    // All zeros ("00", "-000") leave no other digit: the number meant is 0.
    const std::size_t first = word.find_first_not_of("-0");
    const std::string rest = first == std::string::npos ? "0" : word.substr(first);
    return at(text, tok, "numbers must not have leading zeros",
              "write " + word.substr(0, digits) + rest + " (or " + word.substr(0, digits) + "0." +
                  rest + ")");
  }
  if (context == "object" && expected == "'}'") {
    return at(text, tok, "missing ',' between object members",
              "add a comma after the previous value");
  }
  if (context == "array" && expected == "']'") {
    return at(text, tok, "missing ',' between array elements",
              "add a comma after the previous element");
  }
  if (context == "object key") {
    return at(text, tok, "expected a key in double quotes, got " + token,
              "object members are written \"key\": value");
  }
  if (context == "value" && (c == '}' || c == ']' || c == ',' || c == ':')) {
    return at(text, tok, "missing value before '" + std::string(1, c) + "'",
              "write a value: a number, a string in double quotes, true, false, null, an "
              "object or an array");
  }
  return at(text, tok, "unexpected " + token + (expected.empty() ? "" : "; expected " + expected));
}

/// The file ended inside a value: the bracket never closed, when one is open.
Diagnostic end_of_input(std::string_view text) {
  bool has_last = false;
  const std::size_t last = previous_non_ws(text, text.size(), has_last);
  const std::size_t end = has_last ? last + 1 : 0;
  const auto open = open_brackets(text);
  if (!open.empty()) {
    const char opener = text[open.back()];
    const char closer = opener == '{' ? '}' : ']';
    return at(text, end,
              std::string("unexpected end of file: the '") + opener + "' at " +
                  where(text, open.back()) + " is never closed",
              "the file may be truncated; add the missing '" + std::string(1, closer) + "'");
  }
  return at(text, end, "unexpected end of file", "the file may be truncated");
}

/// A character a string may not hold (`e` its byte): control characters and invalid UTF-8;
/// nullopt for another error.
std::optional<Diagnostic> bad_string_character(std::string_view text, std::size_t e,
                                               std::size_t tok, const std::string& detail) {
  if (detail.find("control character U+000A") != std::string::npos ||
      detail.find("control character U+000D") != std::string::npos) {
    return at(text, tok, "line break inside a string",
              "close the string with \" before the end of the line, or write the break as \\n");
  }
  if (detail.find("control character U+0009") != std::string::npos) {
    return at(text, e, "raw tab character inside a string", "write it as \\t");
  }
  if (detail.find("control character") != std::string::npos) {
    const auto b = e < text.size() ? static_cast<unsigned char>(text[e]) : 0;
    char code[16];
    std::snprintf(code, sizeof code, "\\u%04X", static_cast<unsigned>(b));
    return at(text, e, "control character " + hex_byte(b) + " inside a string",
              std::string("write it as ") + code);
  }
  if (detail.find("ill-formed UTF-8") != std::string::npos) {
    const auto b = e < text.size() ? static_cast<unsigned char>(text[e]) : 0;
    return at(text, e, "invalid UTF-8 byte " + hex_byte(b) + " in a string",
              "save the file as UTF-8");
  }
  return std::nullopt;
}

/// A backslash sequence a string may not hold; nullopt for another error.
std::optional<Diagnostic> bad_escape(std::string_view text, std::size_t e, std::size_t tok,
                                     const std::string& detail) {
  if (detail.find("forbidden character after backslash") != std::string::npos) {
    const std::size_t bs = e > 0 ? e - 1 : 0;
    const std::string seq(text.substr(bs, 2));
    return at(text, bs,
              "invalid escape sequence '" + (printable_ascii(seq) ? seq : std::string("\\")) +
                  "' in a string",
              "valid escapes are \\\" \\\\ \\/ \\b \\f \\n \\r \\t \\uXXXX; write a backslash "
              "as \\\\");
  }
  if (detail.find("'\\u'") != std::string::npos || detail.find("surrogate") != std::string::npos) {
    return at(text, tok, "invalid \\u escape in a string",
              "\\u takes 4 hex digits; characters above U+FFFF are written as a surrogate pair");
  }
  return std::nullopt;
}

/// nlohmann stops at the character that breaks the number (`e`); the number starts before it.
Diagnostic invalid_number(std::string_view text, std::size_t e, const std::string& detail) {
  const auto number_char = [](char c) {
    return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.' || c == 'e' || c == 'E';
  };
  std::size_t start = std::min(e, text.size());
  while (start > 0 && number_char(text[start - 1])) --start;
  std::size_t end = start;
  while (end < text.size() && number_char(text[end])) ++end;
  const std::string reason = before(after(detail, "invalid number; "), "; last read");
  return at(text, start,
            "invalid number '" + std::string(text.substr(start, end - start)) + "'" +
                (reason.empty() ? "" : ": " + reason),
            "numbers look like 12, -0.5 or 2.1e11");
}

}  // namespace

Diagnostic describe_parse_error(std::string_view text, std::size_t byte, std::string_view what) {
  std::string context;
  std::string detail;
  split_message(what, context, detail);
  const std::size_t e = byte == 0 ? 0 : std::min(byte - 1, text.size());
  const std::size_t tok = token_start(text, e);

  if (detail.rfind("unexpected end of input", 0) == 0) return end_of_input(text);
  if (detail.find("missing closing quote") != std::string::npos) {
    return at(text, tok, "string is missing its closing quote",
              "end the string with \" on the same line");
  }
  if (auto d = bad_string_character(text, e, tok, detail)) return std::move(*d);
  if (auto d = bad_escape(text, e, tok, detail)) return std::move(*d);
  if (detail.rfind("invalid number", 0) == 0) return invalid_number(text, e, detail);
  if (detail.rfind("invalid literal", 0) == 0) {
    return invalid_literal(text, tok, context, detail);
  }
  if (detail.rfind("unexpected ", 0) == 0) {
    return unexpected_token(text, tok, context, detail);
  }
  return at(text, tok, detail.empty() ? std::string(what) : detail);
}

Diagnostic describe_number_overflow(std::string_view text, std::string_view what) {
  const std::string number = before(after(what, "parsing '"), "'");
  // Find the first number token that does not fit a double: that is the one nlohmann refused.
  std::optional<std::size_t> found;
  JsonLexer lex(text);
  for (JsonToken t = lex.next(); t.kind != TokenKind::kEnd && !found; t = lex.next()) {
    const char c = text[t.span.begin];
    if (t.kind != TokenKind::kWord || !(c == '-' || (c >= '0' && c <= '9'))) continue;
    const std::string token(text.substr(t.span.begin, t.span.end - t.span.begin));
    if (token == number || !std::isfinite(std::strtod(token.c_str(), nullptr)))
      found = t.span.begin;
  }
  Diagnostic d = at(text, found.value_or(0),
                    "number " + (number.empty() ? std::string("") : number + " ") +
                        "is too large (the largest double is about 1.8e308)",
                    "check the exponent");
  if (!found) d.line = d.column = 0;
  d.message = d.message.substr(std::string_view("syntax error: ").size());
  return d;
}

std::optional<std::size_t> find_excess_nesting(std::string_view text, std::size_t max_depth) {
  std::size_t depth = 0;
  JsonLexer lex(text);
  for (JsonToken t = lex.next(); t.kind != TokenKind::kEnd; t = lex.next()) {
    if (t.kind == TokenKind::kOpen) {
      if (++depth > max_depth) return t.span.begin;
    } else if (t.kind == TokenKind::kClose && depth > 0) {
      --depth;
    }
  }
  return std::nullopt;
}

}  // namespace rumble::scenario
