#include "scenario/json_position.hpp"

#include <algorithm>
#include <cstdint>

namespace rumble::scenario {
namespace {

constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF";

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

/// A cursor over the text. Every method stops at the end of the text and reports failure
/// instead of reading past it, so truncated or garbled text is handled like any other.
class Scanner {
 public:
  explicit Scanner(std::string_view text) : text_(text) {
    if (text_.substr(0, kUtf8Bom.size()) == kUtf8Bom) pos_ = kUtf8Bom.size();
  }

  std::size_t pos() const { return pos_; }
  void set_pos(std::size_t p) { pos_ = p; }
  bool at_end() const { return pos_ >= text_.size(); }
  char peek() const { return at_end() ? '\0' : text_[pos_]; }
  void advance() { ++pos_; }

  void skip_ws() {
    while (!at_end() && is_json_whitespace(text_[pos_])) ++pos_;
  }

  /// Reads the string starting at the current '"', decoding escapes into *out when given.
  bool read_string(std::string* out) {
    if (peek() != '"') return false;
    ++pos_;
    while (!at_end()) {
      const char c = text_[pos_++];
      if (c == '"') return true;
      if (c != '\\') {
        if (out != nullptr) *out += c;
        continue;
      }
      if (at_end()) return false;
      const char e = text_[pos_++];
      switch (e) {
        case '"':
        case '\\':
        case '/':
          if (out != nullptr) *out += e;
          break;
        case 'b':
          if (out != nullptr) *out += '\b';
          break;
        case 'f':
          if (out != nullptr) *out += '\f';
          break;
        case 'n':
          if (out != nullptr) *out += '\n';
          break;
        case 'r':
          if (out != nullptr) *out += '\r';
          break;
        case 't':
          if (out != nullptr) *out += '\t';
          break;
        case 'u': {
          std::uint32_t cp = 0;
          if (!read_hex4(cp)) return false;
          if (cp >= 0xD800 && cp <= 0xDBFF && text_.substr(pos_, 2) == "\\u") {
            pos_ += 2;
            std::uint32_t low = 0;
            if (!read_hex4(low)) return false;
            cp = 0x10000 + ((cp - 0xD800) << 10) + (low - 0xDC00);
          }
          if (out != nullptr) append_utf8(*out, cp);
          break;
        }
        default:
          return false;
      }
    }
    return false;
  }

  /// Skips one value of any kind. Containers are skipped by counting brackets, never by
  /// recursion, so nesting depth costs nothing.
  bool skip_value() {
    skip_ws();
    if (at_end()) return false;
    const char c = peek();
    if (c == '"') return read_string(nullptr);
    if (c == '{' || c == '[') {
      std::size_t depth = 0;
      while (!at_end()) {
        const char d = peek();
        if (d == '"') {
          if (!read_string(nullptr)) return false;
          continue;
        }
        ++pos_;
        if (d == '{' || d == '[') ++depth;
        if (d == '}' || d == ']') {
          if (--depth == 0) return true;
        }
      }
      return false;
    }
    const std::size_t start = pos_;
    while (!at_end() && !is_json_whitespace(peek()) && !is_json_structural(peek())) ++pos_;
    return pos_ > start;
  }

 private:
  bool read_hex4(std::uint32_t& cp) {
    if (pos_ + 4 > text_.size()) return false;
    cp = 0;
    for (int i = 0; i < 4; ++i) {
      const char h = text_[pos_++];
      cp <<= 4;
      if (h >= '0' && h <= '9') {
        cp |= static_cast<std::uint32_t>(h - '0');
      } else if (h >= 'a' && h <= 'f') {
        cp |= static_cast<std::uint32_t>(h - 'a' + 10);
      } else if (h >= 'A' && h <= 'F') {
        cp |= static_cast<std::uint32_t>(h - 'A' + 10);
      } else {
        return false;
      }
    }
    return true;
  }

  std::string_view text_;
  std::size_t pos_ = 0;
};

std::optional<std::size_t> parse_index(const std::string& token) {
  if (token.empty() || token.size() > 18) return std::nullopt;
  if (token.size() > 1 && token[0] == '0') return std::nullopt;
  std::size_t v = 0;
  for (const char c : token) {
    if (c < '0' || c > '9') return std::nullopt;
    v = v * 10 + static_cast<std::size_t>(c - '0');
  }
  return v;
}

struct Found {
  TextSpan key;  // empty (begin == end == 0) for the document root and array elements
  TextSpan value;
};

/// Walks down to the pointer's target; nullopt when it is not in the text.
std::optional<Found> walk(std::string_view text, const std::vector<std::string>& tokens) {
  Scanner s(text);
  s.skip_ws();
  TextSpan key{};
  for (const std::string& token : tokens) {
    s.skip_ws();
    const char c = s.peek();
    if (c == '{') {
      s.advance();
      std::optional<std::size_t> value_begin;
      // Scan the whole object: with a duplicated key the last occurrence is the one parsed.
      while (true) {
        s.skip_ws();
        if (s.peek() == '}') break;
        const std::size_t key_begin = s.pos();
        std::string name;
        if (!s.read_string(&name)) break;
        const std::size_t key_end = s.pos();
        s.skip_ws();
        if (s.peek() != ':') break;
        s.advance();
        s.skip_ws();
        if (name == token) {
          value_begin = s.pos();
          key = TextSpan{key_begin, key_end};
        }
        if (!s.skip_value()) break;
        s.skip_ws();
        if (s.peek() != ',') break;
        s.advance();
      }
      if (!value_begin) return std::nullopt;
      s.set_pos(*value_begin);
    } else if (c == '[') {
      const auto index = parse_index(token);
      if (!index) return std::nullopt;
      s.advance();
      for (std::size_t i = 0; i < *index; ++i) {
        s.skip_ws();
        if (s.peek() == ']' || !s.skip_value()) return std::nullopt;
        s.skip_ws();
        if (s.peek() != ',') return std::nullopt;
        s.advance();
      }
      s.skip_ws();
      if (s.at_end() || s.peek() == ']') return std::nullopt;
      key = TextSpan{};
    } else {
      return std::nullopt;
    }
  }
  s.skip_ws();
  if (s.at_end()) return std::nullopt;
  const std::size_t begin = s.pos();
  const std::size_t end = s.skip_value() ? s.pos() : text.size();
  return Found{key, TextSpan{begin, end}};
}

}  // namespace

std::optional<std::vector<std::string>> split_pointer(std::string_view pointer) {
  std::vector<std::string> tokens;
  if (pointer.empty()) return tokens;
  if (pointer[0] != '/') return std::nullopt;
  std::string current;
  for (std::size_t i = 1; i <= pointer.size(); ++i) {
    if (i == pointer.size() || pointer[i] == '/') {
      tokens.push_back(current);
      current.clear();
      continue;
    }
    if (pointer[i] == '~') {
      if (i + 1 >= pointer.size()) return std::nullopt;
      const char e = pointer[++i];
      if (e == '0') {
        current += '~';
      } else if (e == '1') {
        current += '/';
      } else {
        return std::nullopt;
      }
      continue;
    }
    current += pointer[i];
  }
  return tokens;
}

std::string escape_pointer_token(std::string_view token) {
  std::string out;
  out.reserve(token.size());
  for (const char c : token) {
    if (c == '~') {
      out += "~0";
    } else if (c == '/') {
      out += "~1";
    } else {
      out += c;
    }
  }
  return out;
}

std::optional<TextSpan> find_value(std::string_view text, std::string_view pointer) {
  const auto tokens = split_pointer(pointer);
  if (!tokens) return std::nullopt;
  const auto found = walk(text, *tokens);
  if (!found) return std::nullopt;
  return found->value;
}

std::optional<TextSpan> find_key(std::string_view text, std::string_view pointer) {
  const auto tokens = split_pointer(pointer);
  if (!tokens || tokens->empty()) return std::nullopt;
  const auto found = walk(text, *tokens);
  if (!found || found->key.end == 0) return std::nullopt;
  return found->key;
}

std::optional<TextSpan> find_nearest(std::string_view text, std::string_view pointer, bool key) {
  auto tokens = split_pointer(pointer);
  if (!tokens) return std::nullopt;
  if (key) {
    if (const auto found = walk(text, *tokens); found && found->key.end != 0) return found->key;
  }
  while (true) {
    if (const auto found = walk(text, *tokens)) return found->value;
    if (tokens->empty()) return std::nullopt;
    tokens->pop_back();
  }
}

namespace {

constexpr std::size_t kCheckpointBytes = 4096;

bool starts_character(char c) {
  return (static_cast<unsigned char>(c) & 0xC0) != 0x80;
}

/// Walks every value of a JSON text in order, with its JSON pointer, telling `visit`:
///   visit.member(container pointer, name, key span, pointer): an object member's key was read;
///   visit.value(pointer, key span (empty in arrays), value span): a value starts (a container's
///     span ends at the text's end until visit.closed);
///   visit.closed(pointer, end): a container closed at `end`.
/// Stops quietly at malformed text (the parser reports it). One walk for every user of the text's
/// structure: the position index, the duplicate keys.
template <class Visit>
void walk_values(std::string_view text, Visit& visit) {
  struct Frame {
    std::string pointer;
    bool object;
    std::size_t next_index;
  };
  std::vector<Frame> stack;
  Scanner s(text);
  std::string pointer;
  TextSpan key{};
  // Reads the next member's key (objects) or index (arrays) into `pointer`; false when the
  // container ends here or the text is malformed.
  const auto next_member = [&](Frame& frame) {
    s.skip_ws();
    if (frame.object) {
      const std::size_t key_begin = s.pos();
      std::string name;
      if (!s.read_string(&name)) return false;
      key = TextSpan{key_begin, s.pos()};
      s.skip_ws();
      if (s.peek() != ':') return false;
      s.advance();
      pointer = frame.pointer + "/" + escape_pointer_token(name);
      visit.member(frame.pointer, std::move(name), key, pointer);
    } else {
      key = TextSpan{};
      pointer = frame.pointer + "/" + std::to_string(frame.next_index++);
    }
    return true;
  };
  while (true) {
    // Read one value at `pointer`.
    s.skip_ws();
    if (s.at_end()) return;
    const std::size_t begin = s.pos();
    const char c = s.peek();
    if (c == '{' || c == '[') {
      visit.value(pointer, key, TextSpan{begin, text.size()});
      s.advance();
      stack.push_back(Frame{pointer, c == '{', 0});
      s.skip_ws();
      if (s.peek() != (c == '{' ? '}' : ']')) {
        if (!next_member(stack.back())) return;
        continue;
      }
    } else {
      if (!s.skip_value()) return;
      visit.value(pointer, key, TextSpan{begin, s.pos()});
    }
    // After a value: close finished containers, then move to the next member.
    bool more = false;
    while (!stack.empty()) {
      s.skip_ws();
      const char d = s.peek();
      if (d == ',') {
        s.advance();
        if (!next_member(stack.back())) return;
        more = true;
        break;
      }
      if (d != (stack.back().object ? '}' : ']')) return;
      s.advance();
      visit.closed(stack.back().pointer, s.pos());
      stack.pop_back();
    }
    if (!more) return;
  }
}

}  // namespace

PositionIndex::PositionIndex(std::string_view text) : text_(text) {
  line_starts_.push_back(0);
  std::size_t chars = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (i % kCheckpointBytes == 0) char_checkpoints_.push_back(chars);
    if (text[i] == '\n') line_starts_.push_back(i + 1);
    if (starts_character(text[i])) ++chars;
  }
  char_checkpoints_.push_back(chars);
  struct Record {
    std::unordered_map<std::string, Entry>& entries;
    void member(const std::string&, std::string&&, TextSpan, const std::string&) {}
    void value(const std::string& pointer, TextSpan key, TextSpan value) {
      entries[pointer] = Entry{key, value};
    }
    void closed(const std::string& pointer, std::size_t end) { entries[pointer].value.end = end; }
  } record{entries_};
  walk_values(text, record);
}

std::optional<TextSpan> PositionIndex::value(const std::string& pointer) const {
  const auto it = entries_.find(pointer);
  if (it == entries_.end()) return std::nullopt;
  return it->second.value;
}

std::optional<TextSpan> PositionIndex::key(const std::string& pointer) const {
  const auto it = entries_.find(pointer);
  if (it == entries_.end() || it->second.key.end == 0) return std::nullopt;
  return it->second.key;
}

std::optional<TextSpan> PositionIndex::nearest(const std::string& pointer, bool at_key) const {
  if (at_key) {
    if (const auto k = key(pointer)) return k;
  }
  std::string p = pointer;
  while (true) {
    if (const auto v = value(p)) return v;
    if (p.empty()) return std::nullopt;
    p.resize(p.rfind('/'));
  }
}

std::size_t PositionIndex::chars_before(std::size_t offset) const {
  const std::size_t block = offset / kCheckpointBytes;
  std::size_t chars = char_checkpoints_[std::min(block, char_checkpoints_.size() - 1)];
  for (std::size_t i = block * kCheckpointBytes; i < offset; ++i)
    chars += starts_character(text_[i]);
  return chars;
}

LineColumn PositionIndex::line_column(std::size_t offset) const {
  if (offset > text_.size()) offset = text_.size();
  const auto next = std::upper_bound(line_starts_.begin(), line_starts_.end(), offset);
  std::size_t line_start = *(next - 1);
  // A byte order mark is invisible in editors, so it takes no column.
  if (line_start == 0 && text_.substr(0, kUtf8Bom.size()) == kUtf8Bom && offset >= 3) {
    line_start = kUtf8Bom.size();
  }
  return LineColumn{static_cast<std::size_t>(next - line_starts_.begin()),
                    chars_before(offset) - chars_before(line_start) + 1};
}

LineColumn line_column(std::string_view text, std::size_t offset) {
  if (offset > text.size()) offset = text.size();
  LineColumn lc{1, 1};
  std::size_t line_start = 0;
  for (std::size_t i = 0; i < offset; ++i) {
    if (text[i] == '\n') {
      ++lc.line;
      line_start = i + 1;
    }
  }
  // A byte order mark is invisible in editors, so it takes no column.
  if (line_start == 0 && text.substr(0, kUtf8Bom.size()) == kUtf8Bom && offset >= 3) {
    line_start = kUtf8Bom.size();
  }
  for (std::size_t i = line_start; i < offset; ++i) {
    const auto byte = static_cast<unsigned char>(text[i]);
    if ((byte & 0xC0) != 0x80) ++lc.column;  // continuation bytes belong to the previous char
  }
  return lc;
}

std::vector<DuplicateKey> find_duplicate_keys(std::string_view text) {
  struct Find {
    std::vector<DuplicateKey> out;
    // Per open object (by pointer): each key's latest position.
    std::unordered_map<std::string, std::unordered_map<std::string, TextSpan>> keys;
    void member(const std::string& object, std::string&& name, TextSpan key,
                const std::string& pointer) {
      auto& seen = keys[object];
      const auto [it, fresh] = seen.emplace(std::move(name), key);
      if (!fresh) {
        out.push_back(DuplicateKey{pointer, it->second, key});
        it->second = key;
      }
    }
    void value(const std::string&, TextSpan, TextSpan) {}
    void closed(const std::string& pointer, std::size_t) { keys.erase(pointer); }
  } find;
  walk_values(text, find);
  return std::move(find.out);
}

std::size_t token_start(std::string_view text, std::size_t offset) {
  std::size_t pos = text.substr(0, kUtf8Bom.size()) == kUtf8Bom ? kUtf8Bom.size() : 0;
  while (pos < text.size()) {
    while (pos < text.size() && is_json_whitespace(text[pos])) ++pos;
    if (pos >= text.size() || pos > offset) break;
    const std::size_t start = pos;
    const char c = text[pos];
    if (c == '"') {
      // A string ends at its closing quote, or where the parser gave up on it: at a raw control
      // character (a line break inside a string) or at the end of the text.
      ++pos;
      bool closed = false;
      while (pos < text.size()) {
        const char d = text[pos];
        if (d == '\\') {
          pos += 2;
          continue;
        }
        if (static_cast<unsigned char>(d) < 0x20) break;
        ++pos;
        if (d == '"') {
          closed = true;
          break;
        }
      }
      if (offset < pos || (!closed && offset == pos)) return start;
    } else if (is_json_structural(c)) {
      ++pos;
      if (offset < pos) return start;
    } else {
      while (pos < text.size() && !is_json_whitespace(text[pos]) && !is_json_structural(text[pos]))
        ++pos;
      if (offset < pos) return start;
    }
  }
  return offset;
}

}  // namespace rumble::scenario
