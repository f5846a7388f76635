#include "scenario/value_text.hpp"

#include <charconv>
#include <cmath>

namespace rumble::scenario {

std::string format_number(double value) {
  if (!std::isfinite(value)) return value > 0 ? "inf" : (value < 0 ? "-inf" : "nan");
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, value);
  return std::string(buf, r.ptr);
}

std::string format_number(const nlohmann::json& number) {
  if (number.is_number_float()) return format_number(number.get<double>());
  if (number.is_number()) return number.dump();
  return short_json(number);
}

std::string truncate_text(std::string_view text, std::size_t max_chars) {
  if (text.size() <= max_chars) return std::string(text);
  std::size_t cut = max_chars;
  // Back up to the start of a UTF-8 sequence so that no character is split.
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;
  return std::string(text.substr(0, cut)) + "...";
}

std::string short_json(const nlohmann::json& value, std::size_t max_chars) {
  if (value.is_number()) return format_number(value);
  std::string text;
  try {
    text = value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  } catch (const std::exception&) {
    text = "<value>";
  }
  return truncate_text(text, max_chars);
}

std::optional<std::size_t> first_invalid_utf8(std::string_view text) {
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  std::size_t i = 0;
  while (i < text.size()) {
    const unsigned char b = byte(i);
    const std::size_t n = b < 0x80   ? 1
                          : b < 0xC2 ? 0
                          : b < 0xE0 ? 2
                          : b < 0xF0 ? 3
                          : b < 0xF5 ? 4
                                     : 0;
    if (n == 0 || i + n > text.size()) return i;
    for (std::size_t k = 1; k < n; ++k)
      if ((byte(i + k) & 0xC0) != 0x80) return i;
    // The second byte's range after the leads whose first continuation is restricted
    // (RFC 3629 §4): E0 (overlong), ED (surrogates), F0 (overlong), F4 (beyond U+10FFFF).
    if (n > 2) {
      const unsigned char c = byte(i + 1);
      if ((b == 0xE0 && c < 0xA0) || (b == 0xED && c >= 0xA0) || (b == 0xF0 && c < 0x90) ||
          (b == 0xF4 && c >= 0x90))
        return i;
    }
    i += n;
  }
  return std::nullopt;
}

std::string quote_name(std::string_view name) {
  bool plain = true;
  for (const char c : name) {
    const auto b = static_cast<unsigned char>(c);
    if (b < 0x20 || b == 0x7F || c == '\'') plain = false;
  }
  if (plain) return "'" + truncate_text(name, 80) + "'";
  return short_json(nlohmann::json(std::string(name)), 80);
}

std::string type_phrase(std::string_view t) {
  if (t == "number") return "a number";
  if (t == "integer") return "an integer";
  if (t == "string") return "a string";
  if (t == "boolean") return "true or false";
  if (t == "object") return "an object";
  if (t == "array") return "an array";
  if (t == "null") return "null";
  return "of type " + std::string(t);
}

std::string type_of(const nlohmann::json& value) {
  switch (value.type()) {
    case nlohmann::json::value_t::null:
      return "null";
    case nlohmann::json::value_t::boolean:
      return "boolean";
    case nlohmann::json::value_t::number_integer:
    case nlohmann::json::value_t::number_unsigned:
      return "integer";
    case nlohmann::json::value_t::number_float:
      return "number";
    case nlohmann::json::value_t::string:
      return "string";
    case nlohmann::json::value_t::array:
      return "array";
    case nlohmann::json::value_t::object:
      return "object";
    default:
      return "value";
  }
}

}  // namespace rumble::scenario
