#include "scenario/schema_print.hpp"

#include <algorithm>
#include <array>
#include <nlohmann/json.hpp>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "plugin/registry.hpp"
#include "scenario/did_you_mean.hpp"
#include "scenario/local_ref.hpp"
#include "scenario/value_text.hpp"

namespace rumble::scenario {
namespace {

// Declaration order reads better than alphabetical order, so the schema is read ordered.
using ojson = nlohmann::ordered_json;

constexpr std::size_t kColumns = 6;
using Row = std::array<std::string, kColumns>;

std::string value_text(const ojson& v) {
  if (v.is_number_float()) return format_number(v.get<double>());
  return truncate_text(v.dump(-1, ' ', false, ojson::error_handler_t::replace), 40);
}

const ojson* follow(const ojson& root, const ojson* node) {
  for (int i = 0; i < 32 && node != nullptr; ++i) {
    const std::optional<const ojson*> target = local_ref(root, *node);
    if (!target) return node;
    node = *target;
  }
  return node;
}

std::string type_text(const ojson& node) {
  const auto t = node.find("type");
  if (t != node.end() && t->is_string()) return t->get<std::string>();
  if (t != node.end() && t->is_array()) {
    std::vector<std::string> names;
    for (const auto& x : *t) names.push_back(x.is_string() ? x.get<std::string>() : "?");
    return join(names, "|");
  }
  if (node.contains("enum")) return "enum";
  if (node.contains("const")) return "const";
  if (node.contains("oneOf") || node.contains("anyOf")) return "variants";
  return "any";
}

std::string bound(const ojson& node, const char* exclusive, const char* inclusive, bool& excl) {
  if (const auto it = node.find(exclusive); it != node.end() && it->is_number()) {
    excl = true;
    return value_text(*it);
  }
  if (const auto it = node.find(inclusive); it != node.end() && it->is_number()) {
    excl = false;
    return value_text(*it);
  }
  return "";
}

std::string range_text(const ojson& node) {
  if (const auto e = node.find("enum"); e != node.end() && e->is_array()) {
    std::vector<std::string> values;
    for (const auto& v : *e) values.push_back(v.is_string() ? v.get<std::string>() : value_text(v));
    return "one of: " + join(values);
  }
  if (const auto c = node.find("const"); c != node.end()) return "= " + value_text(*c);
  bool lo_excl = false;
  bool hi_excl = false;
  const std::string lo = bound(node, "exclusiveMinimum", "minimum", lo_excl);
  const std::string hi = bound(node, "exclusiveMaximum", "maximum", hi_excl);
  std::vector<std::string> parts;
  if (!lo.empty() && !hi.empty()) {
    parts.push_back((lo_excl ? "(" : "[") + lo + ", " + hi + (hi_excl ? ")" : "]"));
  } else if (!lo.empty()) {
    parts.push_back((lo_excl ? "> " : ">= ") + lo);
  } else if (!hi.empty()) {
    parts.push_back((hi_excl ? "< " : "<= ") + hi);
  }
  if (const auto n = node.find("minItems"); n != node.end())
    parts.push_back(">= " + value_text(*n) + " items");
  if (const auto n = node.find("maxItems"); n != node.end())
    parts.push_back("<= " + value_text(*n) + " items");
  if (const auto n = node.find("minLength"); n != node.end() && *n == 1)
    parts.push_back("not empty");
  if (const auto p = node.find("pattern"); p != node.end())
    parts.push_back("matches " + value_text(*p));
  return join(parts, ", ");
}

bool numeric(const ojson& node) {
  const auto t = node.find("type");
  return t != node.end() && (*t == "number" || *t == "integer");
}

/// The range of the numbers inside an array or a set of variants, which have no row of their
/// own: "each [-100, 100]" (an array of numbers, nested arrays too), "a number [0, 1e+08]" (a
/// variant that is a number). Every number has a range (docs/scenario.md, "Limits").
std::string inner_range_text(const ojson& root, const ojson& node, int depth = 0) {
  if (depth > 8) return "";
  if (const auto items = node.find("items"); items != node.end()) {
    const ojson* item = follow(root, &*items);
    if (item == nullptr || !item->is_object()) return "";
    if (numeric(*item)) return "each " + range_text(*item);
    return inner_range_text(root, *item, depth + 1);
  }
  std::vector<std::string> parts;
  for (const char* key : {"oneOf", "anyOf"}) {
    const auto variants = node.find(key);
    if (variants == node.end() || !variants->is_array()) continue;
    for (const auto& raw : *variants) {
      const ojson* v = follow(root, &raw);
      if (v == nullptr || !v->is_object()) continue;
      if (numeric(*v)) {
        parts.push_back("a number " + range_text(*v));
      } else if (const std::string inner = inner_range_text(root, *v, depth + 1); !inner.empty()) {
        parts.push_back(inner);
      }
    }
  }
  return join(parts, " or ");
}

void add_rows(const ojson& root, const ojson& object, const std::string& prefix,
              std::vector<Row>& rows, int depth) {
  if (depth > 8) return;
  const auto props = object.find("properties");
  if (props == object.end() || !props->is_object()) return;
  std::vector<std::string> required;
  if (const auto r = object.find("required"); r != object.end() && r->is_array()) {
    for (const auto& x : *r) {
      if (x.is_string()) required.push_back(x.get<std::string>());
    }
  }
  for (const auto& [name, raw] : props->items()) {
    const ojson* node = follow(root, &raw);
    if (node == nullptr || !node->is_object()) {
      rows.push_back({prefix + name, "any", "", "", "", ""});
      continue;
    }
    const bool is_required = std::find(required.begin(), required.end(), name) != required.end();
    const auto d = node->find("default");
    const auto description = node->find("description");
    std::string range = range_text(*node);
    if (const std::string inner = inner_range_text(root, *node); !inner.empty())
      range += (range.empty() ? "" : ", ") + inner;
    rows.push_back({prefix + name, type_text(*node), is_required ? "yes" : "no",
                    d != node->end() ? value_text(*d) : "", range,
                    description != node->end() && description->is_string()
                        ? description->get<std::string>()
                        : ""});
    add_rows(root, *node, prefix + name + ".", rows, depth + 1);
    if (const auto items = node->find("items"); items != node->end()) {
      if (const ojson* item = follow(root, &*items); item != nullptr && item->is_object()) {
        add_rows(root, *item, prefix + name + "[].", rows, depth + 1);
      }
    }
  }
}

}  // namespace

void print_schema(std::ostream& os, const ComponentType& type, bool raw_json) {
  if (raw_json) {  // JSON only, for tools: `rumble schema TYPE --json | jq`
    ojson schema;
    try {
      schema = ojson::parse(type.params_schema);
    } catch (const std::exception& e) {
      throw std::runtime_error("type '" + type.type_name +
                               "': the plugin's params schema is not valid JSON (" + e.what() +
                               "); report this to the plugin's author");
    }
    os << schema.dump(2, ' ', false, ojson::error_handler_t::replace) << '\n';
    return;
  }
  os << type.type_name << " (" << kind_name(type.kind) << " type";
  if (type.library) os << ", plugin " << type.library->path.string();
  os << ")\n";
  if (!type.summary.empty()) os << type.summary << '\n';
  os << '\n';

  ojson schema;
  try {
    schema = ojson::parse(type.params_schema);
  } catch (const std::exception& e) {
    os << "params: the plugin's schema is not valid JSON (" << e.what() << ")\n";
    return;
  }
  std::vector<Row> rows;
  if (schema.is_object()) add_rows(schema, schema, "", rows, 0);
  if (rows.empty()) {
    os << "params: none\n";
  } else {
    rows.insert(rows.begin(), Row{"name", "type", "required", "default", "range", "description"});
    std::array<std::size_t, kColumns> width{};
    for (const Row& r : rows) {
      for (std::size_t c = 0; c < kColumns; ++c) width[c] = std::max(width[c], r[c].size());
    }
    os << "params:\n";
    for (const Row& r : rows) {
      std::string line = " ";
      for (std::size_t c = 0; c < kColumns; ++c) {
        line += ' ';
        line += r[c];
        if (c + 1 < kColumns) line += std::string(width[c] - r[c].size() + 1, ' ');
      }
      while (!line.empty() && line.back() == ' ') line.pop_back();
      os << line << '\n';
    }
  }
}

}  // namespace rumble::scenario
