#include "scenario/json_position.hpp"

#include <algorithm>
#include <cstdint>

namespace rumble::scenario {
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
    char closer;  // '}' for an object, ']' for an array
    std::size_t next_index;
  };
  std::vector<Frame> stack;
  JsonLexer lex(text);
  JsonToken t = lex.next();
  std::string pointer;
  TextSpan key{};
  const auto closes = [&](const Frame& f) {
    return t.kind == TokenKind::kClose && text[t.span.begin] == f.closer;
  };
  // Reads the next member's key (objects) or index (arrays) into `pointer`, leaving `t` at its
  // value's first token; false when the text is malformed here.
  const auto next_member = [&](Frame& frame) {
    if (frame.closer == ']') {
      key = TextSpan{};
      pointer = frame.pointer + "/" + std::to_string(frame.next_index++);
      return true;
    }
    std::optional<std::string> name = decode_string(text, t);
    if (!name) return false;
    key = t.span;
    if (lex.next().kind != TokenKind::kColon) return false;
    pointer = frame.pointer + "/" + escape_pointer_token(*name);
    visit.member(frame.pointer, std::move(*name), key, pointer);
    t = lex.next();
    return true;
  };
  while (true) {
    // `t` starts a value at `pointer`.
    if (t.kind == TokenKind::kOpen) {
      visit.value(pointer, key, TextSpan{t.span.begin, text.size()});
      stack.push_back(Frame{pointer, text[t.span.begin] == '{' ? '}' : ']', 0});
      t = lex.next();
      if (!closes(stack.back())) {
        if (!next_member(stack.back())) return;
        continue;
      }
    } else if (t.kind == TokenKind::kWord || (t.kind == TokenKind::kString && t.closed)) {
      visit.value(pointer, key, t.span);
      t = lex.next();
    } else {
      return;
    }
    // After a value (or at an empty container's closer): close what ends, then the next member.
    bool more = false;
    while (!stack.empty() && !more) {
      if (t.kind == TokenKind::kComma) {
        t = lex.next();
        if (!next_member(stack.back())) return;
        more = true;
      } else if (closes(stack.back())) {
        visit.closed(stack.back().pointer, t.span.end);
        stack.pop_back();
        t = lex.next();
      } else {
        return;
      }
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
  if (!pointer.empty() && pointer[0] != '/') return std::nullopt;  // not a JSON pointer
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

namespace {

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

/// Skips the value that `t` starts, leaving `t` at the token after it; containers by counting
/// brackets, so nesting depth costs nothing. The value's end, or nullopt when the text ends
/// first or `t` starts no value.
std::optional<std::size_t> skip_value(JsonLexer& lex, JsonToken& t) {
  if (t.kind == TokenKind::kWord || (t.kind == TokenKind::kString && t.closed)) {
    const std::size_t end = t.span.end;
    t = lex.next();
    return end;
  }
  if (t.kind != TokenKind::kOpen) return std::nullopt;
  for (std::size_t depth = 0; t.kind != TokenKind::kEnd; t = lex.next()) {
    if (t.kind == TokenKind::kOpen) ++depth;
    if (t.kind == TokenKind::kClose && --depth == 0) {
      const std::size_t end = t.span.end;
      t = lex.next();
      return end;
    }
  }
  return std::nullopt;
}

struct Found {
  TextSpan key;  // empty (begin == end == 0) for the document root and array elements
  TextSpan value;
};

/// Moves `t` from an object's '{' to the value of its last member named `name` (nlohmann keeps
/// the last of a duplicated key), setting `key`; false when it has none.
bool enter_member(JsonLexer& lex, JsonToken& t, const std::string& name, TextSpan& key) {
  std::optional<JsonLexer> at_value;
  std::optional<JsonToken> value_token;
  for (t = lex.next(); t.kind == TokenKind::kString;) {
    const std::optional<std::string> member = decode_string(lex.text(), t);
    const TextSpan member_key = t.span;
    if (!member || lex.next().kind != TokenKind::kColon) break;
    t = lex.next();
    if (*member == name) {
      at_value = lex;  // the lexer is a cursor: a copy resumes here
      value_token = t;
      key = member_key;
    }
    if (!skip_value(lex, t) || t.kind != TokenKind::kComma) break;
    t = lex.next();
  }
  if (!at_value) return false;
  lex = *at_value;
  t = *value_token;
  return true;
}

/// Moves `t` from an array's '[' to its element `index`; false when it has none.
bool enter_element(JsonLexer& lex, JsonToken& t, std::size_t index) {
  t = lex.next();
  for (std::size_t i = 0; i < index; ++i) {
    if (!skip_value(lex, t) || t.kind != TokenKind::kComma) return false;
    t = lex.next();
  }
  return t.kind != TokenKind::kEnd && t.kind != TokenKind::kClose;
}

/// Walks down to the pointer's target without indexing what it passes; nullopt when it is not
/// in the text.
std::optional<Found> walk(std::string_view text, const std::vector<std::string>& tokens) {
  JsonLexer lex(text);
  JsonToken t = lex.next();
  TextSpan key{};
  for (const std::string& token : tokens) {
    if (t.kind != TokenKind::kOpen) return std::nullopt;
    if (text[t.span.begin] == '{') {
      if (!enter_member(lex, t, token, key)) return std::nullopt;
    } else {
      const auto index = parse_index(token);
      if (!index || !enter_element(lex, t, *index)) return std::nullopt;
      key = TextSpan{};
    }
  }
  if (t.kind == TokenKind::kEnd) return std::nullopt;
  const std::size_t begin = t.span.begin;
  return Found{key, TextSpan{begin, skip_value(lex, t).value_or(text.size())}};
}

}  // namespace

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
  JsonLexer lex(text);
  for (JsonToken t = lex.next(); t.kind != TokenKind::kEnd && t.span.begin <= offset;
       t = lex.next()) {
    // An unclosed string also owns the character the parser stopped at, just past its end.
    if (offset < t.span.end || (!t.closed && offset == t.span.end)) return t.span.begin;
  }
  return offset;
}

}  // namespace rumble::scenario
