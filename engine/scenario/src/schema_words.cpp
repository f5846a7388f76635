// The words the schema checker's messages are built from: valijson's texts read (prefixes, the
// text between quotes, a trailing number) and a schema's types, enums and descriptions written
// for a user. Shared by the files that phrase the rule families.
#include <cstdlib>

#include "scenario/did_you_mean.hpp"
#include "scenario/value_text.hpp"
#include "schema_check_parts.hpp"

namespace rumble::scenario {
namespace {

using nlohmann::json;

}  // namespace

bool starts_with(std::string_view s, std::string_view prefix) {
  return s.substr(0, prefix.size()) == prefix;
}

std::string between(std::string_view s, std::string_view open, std::string_view close) {
  const auto a = s.find(open);
  if (a == std::string_view::npos) return "";
  const auto b = s.rfind(close);
  if (b == std::string_view::npos || b < a + open.size()) return "";
  return std::string(s.substr(a + open.size(), b - a - open.size()));
}

std::vector<std::string> type_list(const json& t) {
  std::vector<std::string> types;
  if (t.is_string()) types.push_back(t.get<std::string>());
  if (t.is_array()) {
    for (const json& e : t) {
      if (e.is_string()) types.push_back(e.get<std::string>());
    }
  }
  return types;
}

std::string enum_list(const json& values) {
  std::vector<std::string> items;
  for (const json& v : values) {
    items.push_back(v.is_string() ? truncate_text(v.get_ref<const std::string&>(), 40)
                                  : short_json(v));
    if (items.size() == 20 && values.size() > 20) {
      items.push_back("... (" + std::to_string(values.size()) + " values)");
      break;
    }
  }
  return join(items);
}

std::string trailing_number(std::string_view d) {
  const auto p = d.find_last_of(' ');
  if (p == std::string_view::npos) return "";
  const std::string text(d.substr(p + 1));
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  return end == text.c_str() ? text : format_number(v);
}

std::string description_of(const json& node) {
  const auto d = node.is_object() ? node.find("description") : node.end();
  return node.is_object() && d != node.end() && d->is_string() ? d->get<std::string>() : "";
}

}  // namespace rumble::scenario
