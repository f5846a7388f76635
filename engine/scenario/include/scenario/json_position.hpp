// Where a JSON pointer's key or value starts in the source text of a JSON document.
//
// nlohmann 3.11 keeps no source positions, so diagnostics find them by lexing the text again
// (json_lexer.hpp): one walk over the tokens records every value's span under its pointer. It
// never recurses (a stack of open containers), so it is safe on any input, valid JSON or not.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "scenario/json_lexer.hpp"

namespace rumble::scenario {

struct LineColumn {
  std::size_t line = 0;    // 1-based
  std::size_t column = 0;  // 1-based, counted in characters (UTF-8 code points), tab = 1
};

/// Splits "/a/b~1c" into {"a", "b/c"}; nullopt when the pointer is malformed.
std::optional<std::vector<std::string>> split_pointer(std::string_view pointer);
/// One token escaped for a pointer ("b/c" -> "b~1c").
std::string escape_pointer_token(std::string_view token);

/// The span of the value at `pointer` ("" = the whole document). For an object member that
/// occurs twice, the last one (which nlohmann keeps) is found. Each call lexes the whole text:
/// for many lookups, build one PositionIndex.
std::optional<TextSpan> find_value(std::string_view text, std::string_view pointer);
/// The span of the key (with its quotes) of the object member at `pointer`.
std::optional<TextSpan> find_key(std::string_view text, std::string_view pointer);
/// Like find_value/find_key, but falls back to the nearest ancestor that exists in the text
/// (a default-filled value or a missing key has no text of its own).
std::optional<TextSpan> find_nearest(std::string_view text, std::string_view pointer, bool key);

/// Every value's position, found in one pass: for many lookups in one document (a scan per
/// lookup would cost the size of the text each time).
class PositionIndex {
 public:
  explicit PositionIndex(std::string_view text);
  std::optional<TextSpan> value(const std::string& pointer) const;
  std::optional<TextSpan> key(const std::string& pointer) const;
  /// As find_nearest().
  std::optional<TextSpan> nearest(const std::string& pointer, bool key) const;
  LineColumn line_column(std::size_t offset) const;

 private:
  struct Entry {
    TextSpan key;  // empty for the root and array elements
    TextSpan value;
  };
  std::size_t chars_before(std::size_t offset) const;

  std::string_view text_;
  std::unordered_map<std::string, Entry> entries_;
  std::vector<std::size_t> line_starts_;
  // Characters (not bytes) before each 4 KiB block, so that a column on a very long line
  // costs one block of counting, not the whole line.
  std::vector<std::size_t> char_checkpoints_;
};

LineColumn line_column(std::string_view text, std::size_t offset);

/// An object key written twice: nlohmann keeps the last value and drops the first silently.
struct DuplicateKey {
  std::string pointer;  // of the member, e.g. "/time/end"
  TextSpan first;       // the earlier key (with its quotes)
  TextSpan second;      // the later one
};
/// Every key that repeats within one object, in text order (three times: two findings). One
/// pass without recursion, like PositionIndex; stops quietly where the text is malformed.
std::vector<DuplicateKey> find_duplicate_keys(std::string_view text);

/// The start of the JSON token containing `offset` (strings, numbers, words, punctuation),
/// found by lexing from the start; used to point parse errors at a token's first character.
std::size_t token_start(std::string_view text, std::size_t offset);

}  // namespace rumble::scenario
