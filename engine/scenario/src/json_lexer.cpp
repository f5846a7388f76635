#include "scenario/json_lexer.hpp"

#include <cstdint>

namespace rumble::scenario {
namespace {

void append_utf8(std::string& out, std::uint32_t cp) {
  if (cp < 0x80) {
    out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    out += static_cast<char>(0xC0 | (cp >> 6));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    out += static_cast<char>(0xE0 | (cp >> 12));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (cp >> 18));
    out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  }
}

/// The 4 hex digits of a \u escape starting at `pos`, or nullopt.
std::optional<std::uint32_t> hex4(std::string_view s, std::size_t pos) {
  if (pos + 4 > s.size()) return std::nullopt;
  std::uint32_t cp = 0;
  for (std::size_t i = pos; i < pos + 4; ++i) {
    const char h = s[i];
    cp <<= 4;
    if (h >= '0' && h <= '9') {
      cp |= static_cast<std::uint32_t>(h - '0');
    } else if (h >= 'a' && h <= 'f') {
      cp |= static_cast<std::uint32_t>(h - 'a' + 10);
    } else if (h >= 'A' && h <= 'F') {
      cp |= static_cast<std::uint32_t>(h - 'A' + 10);
    } else {
      return std::nullopt;
    }
  }
  return cp;
}

/// The character a one-letter escape stands for ('\0' for none).
char simple_escape(char e) {
  switch (e) {
    case '"':
    case '\\':
    case '/':
      return e;
    case 'b':
      return '\b';
    case 'f':
      return '\f';
    case 'n':
      return '\n';
    case 'r':
      return '\r';
    case 't':
      return '\t';
    default:
      return '\0';
  }
}

}  // namespace

JsonLexer::JsonLexer(std::string_view text) : text_(text) {
  if (text_.substr(0, kUtf8Bom.size()) == kUtf8Bom) pos_ = kUtf8Bom.size();
}

JsonToken JsonLexer::next() {
  while (pos_ < text_.size() && is_json_whitespace(text_[pos_])) ++pos_;
  const std::size_t start = pos_;
  if (pos_ >= text_.size()) return JsonToken{TokenKind::kEnd, {start, start}, true};
  const char c = text_[pos_];
  if (c == '"') return string_token(start);
  if (is_json_structural(c)) {
    ++pos_;
    const TokenKind kind = c == '{' || c == '['   ? TokenKind::kOpen
                           : c == '}' || c == ']' ? TokenKind::kClose
                           : c == ','             ? TokenKind::kComma
                                                  : TokenKind::kColon;
    return JsonToken{kind, {start, pos_}, true};
  }
  while (pos_ < text_.size() && !is_json_whitespace(text_[pos_]) &&
         !is_json_structural(text_[pos_]))
    ++pos_;
  return JsonToken{TokenKind::kWord, {start, pos_}, true};
}

JsonToken JsonLexer::string_token(std::size_t start) {
  ++pos_;
  while (pos_ < text_.size()) {
    const char d = text_[pos_];
    if (d == '\\') {
      pos_ = std::min(pos_ + 2, text_.size());
      continue;
    }
    if (static_cast<unsigned char>(d) < 0x20) break;  // the parser gives up here
    ++pos_;
    if (d == '"') return JsonToken{TokenKind::kString, {start, pos_}, true};
  }
  return JsonToken{TokenKind::kString, {start, pos_}, false};
}

std::optional<std::string> decode_string(std::string_view text, const JsonToken& token) {
  if (token.kind != TokenKind::kString || !token.closed) return std::nullopt;
  const std::string_view s =
      text.substr(token.span.begin + 1, token.span.end - token.span.begin - 2);
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '\\') {
      out += s[i];
      continue;
    }
    if (++i >= s.size()) return std::nullopt;
    if (const char plain = simple_escape(s[i]); plain != '\0') {
      out += plain;
      continue;
    }
    if (s[i] != 'u') return std::nullopt;
    auto cp = hex4(s, i + 1);
    if (!cp) return std::nullopt;
    i += 4;
    if (*cp >= 0xD800 && *cp <= 0xDBFF && s.substr(i + 1, 2) == "\\u") {
      const auto low = hex4(s, i + 3);
      if (!low) return std::nullopt;
      cp = 0x10000 + ((*cp - 0xD800) << 10) + (*low - 0xDC00);
      i += 6;
    }
    append_utf8(out, *cp);
  }
  return out;
}

}  // namespace rumble::scenario
