// Short, printable renderings of JSON values and names for messages.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

namespace rumble::scenario {

/// Shortest text that reads back as the same double ("0.5", "2.1e+11", "1e-09"); integers as is.
std::string format_number(const nlohmann::json& number);
std::string format_number(double value);

/// Compact JSON of any value, cut to about `max_chars` characters with "..." (never inside a
/// UTF-8 sequence); invalid UTF-8 is replaced, so the result is always valid UTF-8.
std::string short_json(const nlohmann::json& value, std::size_t max_chars = 40);

/// Cuts text to about `max_chars` characters, appending "..." when cut.
std::string truncate_text(std::string_view text, std::size_t max_chars);

/// The offset of the first byte of text that does not belong to a well-formed UTF-8 sequence
/// (RFC 3629: no overlong forms, no surrogates, nothing above U+10FFFF), or nullopt.
std::optional<std::size_t> first_invalid_utf8(std::string_view text);

/// A key or name for a message: 'dampng', or with JSON escapes when it holds control characters.
std::string quote_name(std::string_view name);

/// "a number", "an integer", "a string", "true or false", "an object", "an array", "null".
std::string type_phrase(std::string_view json_schema_type);

/// The JSON Schema type name of a value: "integer", "number", "string", "boolean", ...
std::string type_of(const nlohmann::json& value);

}  // namespace rumble::scenario
