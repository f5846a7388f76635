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
