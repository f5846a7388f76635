// The one lexer of JSON text behind every scan that nlohmann cannot do for us: where a value or
// key is (json_position), the duplicate keys, the token a parse error points into, the brackets
// left open, the nesting depth, the number too large (syntax_error, document).
//
// nlohmann 3.11 keeps no source positions and stops at the first error, so diagnostics lex the
// text again. The lexer never fails and never reads past the end: on text that is not JSON it
// still returns tokens (a word for anything unquoted), so each caller decides what malformed
// means for it.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace rumble::scenario {

struct TextSpan {
  std::size_t begin = 0;  // byte offset of the first character
  std::size_t end = 0;    // one past the last character
};

/// JSON's insignificant whitespace (RFC 8259): space, tab, line feed, carriage return.
inline bool is_json_whitespace(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}
/// A character that ends a bare JSON word or number: punctuation or a string's opening quote.
inline bool is_json_structural(char c) {
  return c == '{' || c == '}' || c == '[' || c == ']' || c == ',' || c == ':' || c == '"';
}

enum class TokenKind {
  kOpen,    // { or [
  kClose,   // } or ]
  kComma,   // ,
  kColon,   // :
  kString,  // "...", with its quotes
  kWord,    // a number, true/false/null, or any other run of unquoted characters
  kEnd,     // the end of the text
};

struct JsonToken {
  TokenKind kind = TokenKind::kEnd;
  TextSpan span;
  /// kString: its closing quote was found. An unclosed string ends where the parser gives up on
  /// it: at a raw control character (a line break) or at the end of the text.
  bool closed = true;
};

class JsonLexer {
 public:
  /// Starts after a UTF-8 byte order mark, if the text has one.
  explicit JsonLexer(std::string_view text);

  /// The next token, whitespace skipped; kEnd (at the text's end) for ever after.
  JsonToken next();

  std::string_view text() const { return text_; }

 private:
  JsonToken string_token(std::size_t start);

  std::string_view text_;
  std::size_t pos_ = 0;
};

/// The characters of a string token (with its quotes), its escapes decoded; nullopt when the
/// token is not a closed string or holds an invalid escape.
std::optional<std::string> decode_string(std::string_view text, const JsonToken& token);

/// The byte order mark that starts a UTF-8 text written by some editors.
inline constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF";

}  // namespace rumble::scenario
