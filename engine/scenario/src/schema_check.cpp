#include "scenario/schema_check.hpp"

// VALIJSON_USE_EXCEPTIONS is defined for the whole engine (engine/CMakeLists.txt): without it
// valijson reports a bad schema (or a value it cannot handle) by abort().
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <regex>
#include <set>
#include <string_view>
#include <valijson/adapters/nlohmann_json_adapter.hpp>
#include <valijson/schema.hpp>
#include <valijson/schema_parser.hpp>
#include <valijson/validation_results.hpp>
#include <valijson/validator.hpp>

#include "scenario/did_you_mean.hpp"
#include "scenario/json_position.hpp"
#include "scenario/local_ref.hpp"
#include "scenario/value_text.hpp"

namespace rumble::scenario {
namespace {

using nlohmann::json;
using Rule = SchemaIssue::Rule;

// A oneOf inside a oneOf inside ... is explained variant by variant; real schemas nest a few
// levels at most, so deeper ones are summarized instead of explained.
constexpr int kMaxVariantDepth = 4;
// $ref chains and allOf nesting are followed this deep (a cyclic $ref stops here too).
constexpr int kMaxClosureDepth = 32;

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

std::string to_pointer(const std::vector<std::string>& path) {
  std::string p;
  for (const std::string& t : path) p += "/" + escape_pointer_token(t);
  return p;
}

bool has_prefix(const std::vector<std::string>& path, const std::vector<std::string>& prefix) {
  return path.size() >= prefix.size() && std::equal(prefix.begin(), prefix.end(), path.begin());
}

std::optional<std::size_t> to_index(const std::string& token) {
  if (token.empty() || token.size() > 18) return std::nullopt;
  std::size_t v = 0;
  for (const char c : token) {
    if (c < '0' || c > '9') return std::nullopt;
    v = v * 10 + static_cast<std::size_t>(c - '0');
  }
  return v;
}

const json* child_of(const json& parent, const std::string& token) {
  if (parent.is_object()) {
    const auto it = parent.find(token);
    return it == parent.end() ? nullptr : &*it;
  }
  if (parent.is_array()) {
    const auto i = to_index(token);
    return (i && *i < parent.size()) ? &parent[*i] : nullptr;
  }
  return nullptr;
}

const json* navigate(const json& root, const std::vector<std::string>& path) {
  const json* v = &root;
  for (const std::string& t : path) {
    v = child_of(*v, t);
    if (v == nullptr) return nullptr;
  }
  return v;
}

/// valijson's context is {"<root>", "[key]", "[0]", ...}.
std::vector<std::string> path_of(const std::vector<std::string>& context) {
  std::vector<std::string> path;
  for (std::size_t i = 1; i < context.size(); ++i) {
    const std::string& c = context[i];
    path.push_back(c.size() >= 2 ? c.substr(1, c.size() - 2) : c);
  }
  return path;
}

bool is_wrapper(std::string_view d) {
  return starts_with(d, "Failed to validate item #") ||
         starts_with(d, "Failed to validate against child schema #") ||
         starts_with(d, "Failed to validate against additional properties schema") ||
         starts_with(d, "Failed to validate against a conditional schema") ||
         starts_with(d, "Failed to validate against schema associated with pattern") ||
         starts_with(d, "Failed to validate against schema associated with property name") ||
         starts_with(d, "Failed to validate against dependent schema");
}

bool is_no_variant_matched(std::string_view d) {
  return starts_with(d, "Failed to validate against any child schemas allowed by oneOf") ||
         starts_with(d, "Failed to validate against any schemas allowed by anyOf");
}

bool is_several_variants_matched(std::string_view d) {
  return starts_with(d, "Failed to validate against exactly one child schema");
}

bool is_unknown_key(std::string_view d) {
  return starts_with(d, "Object contains a property that could not be validated");
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

bool satisfies_type(const json& value, const std::string& t) {
  if (t == "number") return value.is_number();
  if (t == "integer") return value.is_number_integer();
  if (t == "string") return value.is_string();
  if (t == "boolean") return value.is_boolean();
  if (t == "object") return value.is_object();
  if (t == "array") return value.is_array();
  if (t == "null") return value.is_null();
  return true;
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

std::size_t utf8_length(const std::string& s) {
  std::size_t n = 0;
  for (const char c : s) {
    if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) ++n;
  }
  return n;
}

std::string plural(std::size_t n, const std::string& word) {
  return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

/// The number at the end of "Expected number greater than 0.000000": the fallback when the
/// schema keyword behind an error cannot be found.
std::string trailing_number(std::string_view d) {
  const auto p = d.find_last_of(' ');
  if (p == std::string_view::npos) return "";
  const std::string text(d.substr(p + 1));
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  return end == text.c_str() ? text : format_number(v);
}

struct Bound {
  const json* value = nullptr;
  bool exclusive = false;
};

/// "a", "a and b", "a, b and c"
std::string and_list(const std::vector<std::string>& items) {
  if (items.size() <= 1) return join(items);
  return join(std::vector<std::string>(items.begin(), items.end() - 1)) + " and " + items.back();
}

/// Whether the value has any of the keys a variant requires.
bool started_on(const json* variant, const json& value) {
  if (variant == nullptr || !value.is_object() || !variant->is_object()) return false;
  const auto required = variant->find("required");
  if (required == variant->end() || !required->is_array()) return false;
  return std::any_of(required->begin(), required->end(), [&](const json& k) {
    return k.is_string() && value.contains(k.get<std::string>());
  });
}

std::string description_of(const json& node) {
  const auto d = node.is_object() ? node.find("description") : node.end();
  return node.is_object() && d != node.end() && d->is_string() ? d->get<std::string>() : "";
}

struct Range {
  Bound lower;
  Bound upper;
};

Range range_of(const json& node) {
  Range r;
  const auto pick = [&](const char* exclusive, const char* inclusive, Bound& b) {
    if (const auto it = node.find(exclusive); it != node.end() && it->is_number()) {
      b = Bound{&*it, true};
    } else if (const auto jt = node.find(inclusive); jt != node.end() && jt->is_number()) {
      b = Bound{&*jt, false};
    }
  };
  pick("exclusiveMinimum", "minimum", r.lower);
  pick("exclusiveMaximum", "maximum", r.upper);
  return r;
}

std::string range_phrase(const Range& r) {
  if (r.lower.value != nullptr && r.upper.value != nullptr) {
    return std::string("must be in ") + (r.lower.exclusive ? "(" : "[") +
           format_number(*r.lower.value) + ", " + format_number(*r.upper.value) +
           (r.upper.exclusive ? ")" : "]");
  }
  if (r.lower.value != nullptr) {
    return std::string("must be ") + (r.lower.exclusive ? "> " : ">= ") +
           format_number(*r.lower.value);
  }
  if (r.upper.value != nullptr) {
    return std::string("must be ") + (r.upper.exclusive ? "< " : "<= ") +
           format_number(*r.upper.value);
  }
  return "is out of range";
}

bool violates(const Range& r, double v) {
  if (r.lower.value != nullptr) {
    const double lo = r.lower.value->get<double>();
    if (r.lower.exclusive ? !(v > lo) : !(v >= lo)) return true;
  }
  if (r.upper.value != nullptr) {
    const double hi = r.upper.value->get<double>();
    if (r.upper.exclusive ? !(v < hi) : !(v <= hi)) return true;
  }
  return false;
}

/// Follows local $refs from a property schema to the node that declares its description or
/// default.
const json* declared(const json& root, const json* node, const char* keyword) {
  for (int i = 0; node != nullptr && i < kMaxClosureDepth; ++i) {
    if (!node->is_object()) return nullptr;
    if (const auto it = node->find(keyword); it != node->end()) return &*it;
    const std::optional<const json*> target = local_ref(root, *node);
    if (!target) return nullptr;
    node = *target;
  }
  return nullptr;
}

std::string number_hint(const json& value, const std::vector<std::string>& expected) {
  const bool wants_number =
      std::find(expected.begin(), expected.end(), "number") != expected.end() ||
      std::find(expected.begin(), expected.end(), "integer") != expected.end();
  if (wants_number && value.is_string()) {
    const std::string& s = value.get_ref<const std::string&>();
    try {
      const json parsed = json::parse(s);
      if (parsed.is_number()) return "remove the quotes: numbers are written without quotes";
    } catch (const std::exception&) {
    }
  }
  if (std::find(expected.begin(), expected.end(), "integer") != expected.end() &&
      value.is_number_float()) {
    const double d = value.get<double>();
    if (std::isfinite(d) && d == std::floor(d) && std::abs(d) < 1e15) {
      return "write it without a decimal point or exponent: " +
             std::to_string(static_cast<long long>(d));
    }
  }
  const bool wants_bool = std::find(expected.begin(), expected.end(), "boolean") != expected.end();
  if (wants_bool && value.is_string() && (value == "true" || value == "false")) {
    return "remove the quotes: true and false are written without quotes";
  }
  return "";
}

/// Either a raw valijson error still to phrase, or issues already explained (a collapsed
/// oneOf/anyOf) that stand in for all the raw errors under `path`.
struct Entry {
  std::vector<std::string> path;
  std::optional<std::string> description;
  std::vector<SchemaIssue> issues;
};

}  // namespace

/// Phrases one raw valijson error, looking up the schema keyword behind it for exact bounds,
/// enum values and property descriptions.
class IssueBuilder {
 public:
  IssueBuilder(const SchemaChecker& checker, const std::string& schema_pointer, const json& root)
      : checker_(checker), schema_pointer_(schema_pointer), root_(root) {}

  void unknown_keys(const std::vector<std::string>& path, const std::string& description,
                    std::vector<SchemaIssue>& out) {
    const json* value = navigate(root_, path);
    if (value == nullptr || !value->is_object()) return;
    std::set<std::string> reported;
    for (const auto& ref :
         checker_.resolve(schema_pointer_, root_, path, SchemaChecker::Closure::kActive)) {
      const json& node = *ref.node;
      if (!node.is_object()) continue;
      const auto ap = node.find("additionalProperties");
      if (ap == node.end() || !(ap->is_boolean() && !ap->get<bool>())) continue;
      std::vector<std::string> allowed;
      if (const auto props = node.find("properties"); props != node.end() && props->is_object()) {
        for (const auto& [k, v] : props->items()) allowed.push_back(k);
      }
      std::sort(allowed.begin(), allowed.end());
      for (const auto& [key, v] : value->items()) {
        if (std::binary_search(allowed.begin(), allowed.end(), key)) continue;
        if (matches_pattern(node, key) || !reported.insert(key).second) continue;
        out.push_back(unknown_key(path, key, allowed));
      }
    }
    if (reported.empty()) {
      // The schema walk found no closed object here (it should); report valijson's own finding.
      const std::string key = between(description, "constraints: '", "'");
      out.push_back(unknown_key(path, key, {}));
    }
  }

  std::optional<SchemaIssue> phrase(const std::vector<std::string>& path, const std::string& d) {
    const json* value = navigate(root_, path);
    if (value == nullptr) return std::nullopt;
    refs_ = checker_.resolve(schema_pointer_, root_, path, SchemaChecker::Closure::kAll);
    SchemaIssue issue;
    issue.pointer = to_pointer(path);
    if (!phrase_value_rule(*value, d, issue) && !phrase_size_rule(*value, d, issue) &&
        !phrase_form_rule(*value, d, issue))
      issue.message = d;
    return issue;
  }

 private:
  /// The rules on the value itself: required, type, range, enum, const; false for another.
  bool phrase_value_rule(const json& value, const std::string& d, SchemaIssue& issue) const {
    if (starts_with(d, "Missing required property '")) {
      const std::string name = between(d, "property '", "'");
      issue.rule = Rule::kRequired;
      issue.message = "required key " + quote_name(name) + " is missing";
      issue.hint = required_hint(name);
    } else if (starts_with(d, "Value type not permitted")) {
      phrase_type(value, issue);
    } else if (starts_with(d, "Expected number")) {
      issue.rule = Rule::kRange;
      issue.show_value = true;
      issue.message = range_message(value, d);
      // Every number's description says why its range is what it is (docs/scenario.md,
      // "Limits"): the hint a user needs to choose a value.
      issue.hint = range_reason(value);
    } else if (starts_with(d, "Failed to match against any enum values")) {
      phrase_enum(value, issue);
    } else if (starts_with(d, "Failed to match expected value set by 'const'")) {
      issue.rule = Rule::kConst;
      issue.show_value = true;
      issue.message = "has the wrong value";
      if (const json* c = keyword("const"); c != nullptr)
        issue.message = "must be " + short_json(*c);
    } else {
      return false;
    }
    return true;
  }

  void phrase_type(const json& value, SchemaIssue& issue) const {
    issue.rule = Rule::kType;
    issue.show_value = true;
    std::vector<std::string> expected;
    for (const auto& ref : refs_) {
      if (const auto t = ref.node->find("type"); ref.node->is_object() && t != ref.node->end()) {
        const auto types = type_list(*t);
        if (std::none_of(types.begin(), types.end(),
                         [&](const std::string& x) { return satisfies_type(value, x); })) {
          expected = types;
          break;
        }
      }
    }
    std::vector<std::string> phrases;
    for (const std::string& t : expected) phrases.push_back(type_phrase(t));
    issue.message = phrases.empty() ? "has the wrong type" : "must be " + join(phrases, " or ");
    issue.hint = number_hint(value, expected);
  }

  void phrase_enum(const json& value, SchemaIssue& issue) const {
    issue.rule = Rule::kEnum;
    issue.show_value = true;
    issue.message = "is not one of the allowed values";
    for (const auto& ref : refs_) {
      const auto e = ref.node->is_object() ? ref.node->find("enum") : ref.node->end();
      if (!ref.node->is_object() || e == ref.node->end() || !e->is_array()) continue;
      if (std::find(e->begin(), e->end(), value) != e->end()) continue;
      issue.message = "must be one of: " + enum_list(*e);
      if (value.is_string()) {
        std::vector<std::string> names;
        for (const json& x : *e) {
          if (x.is_string()) names.push_back(x.get<std::string>());
        }
        if (const auto m = closest_match(value.get_ref<const std::string&>(), names)) {
          issue.hint = "did you mean \"" + *m + "\"?";
        }
      }
      break;
    }
  }

  /// The rules on sizes: items of an array, characters of a string, keys of an object; false
  /// for another.
  bool phrase_size_rule(const json& value, const std::string& d, SchemaIssue& issue) const {
    if (starts_with(d, "Array should contain no fewer than")) {
      issue.message = "must have at least " + plural(count("minItems", d), "item") + ", got " +
                      std::to_string(value.size());
    } else if (starts_with(d, "Array should contain no more than")) {
      issue.message = "must have at most " + plural(count("maxItems", d), "item") + ", got " +
                      std::to_string(value.size());
    } else if (starts_with(d, "String should be no fewer than")) {
      const std::size_t n = count("minLength", d);
      const std::size_t len = value.is_string() ? utf8_length(value.get<std::string>()) : 0;
      issue.message = (n == 1 && len == 0) ? "must not be empty"
                                           : "must be at least " + plural(n, "character") +
                                                 " long, got " + std::to_string(len);
    } else if (starts_with(d, "String should be no more than")) {
      const std::size_t len = value.is_string() ? utf8_length(value.get<std::string>()) : 0;
      issue.message = "must be at most " + plural(count("maxLength", d), "character") +
                      " long, got " + std::to_string(len);
    } else if (starts_with(d, "Object should have no fewer than")) {
      issue.message = "must have at least " + plural(count("minProperties", d), "key") + ", got " +
                      std::to_string(value.size());
    } else if (starts_with(d, "Object should have no more than")) {
      issue.message = "must have at most " + plural(count("maxProperties", d), "key") + ", got " +
                      std::to_string(value.size());
    } else {
      return false;
    }
    return true;
  }

  /// The rules on a value's form: multiple, pattern, not, unique items, dependencies, formats,
  /// contains, tuples; false for another.
  bool phrase_form_rule(const json& value, const std::string& d, SchemaIssue& issue) const {
    if (starts_with(d, "Value should be a multiple of")) {
      issue.rule = Rule::kRange;
      issue.show_value = true;
      const json* m = keyword("multipleOf");
      issue.message =
          "must be a multiple of " + (m != nullptr ? format_number(*m) : trailing_number(d));
    } else if (starts_with(d, "Failed to match regex specified by 'pattern'")) {
      phrase_pattern(issue);
    } else if (starts_with(d, "Target should not validate against schema specified in 'not'")) {
      phrase_not(value, issue);
    } else if (starts_with(d, "Elements at indexes #")) {
      issue.message = "items must be unique: " + between(d, "indexes ", " violate") + " are equal";
    } else if (starts_with(d, "Missing dependency '")) {
      const std::string name = between(d, "dependency '", "'");
      issue.rule = Rule::kRequired;
      issue.message =
          "required key " + quote_name(name) + " is missing" + dependency_of(value, name);
    } else if (starts_with(d, "String should be a valid ")) {
      issue.show_value = true;
      issue.message = "must be a valid " + d.substr(d.rfind(' ') + 1);
    } else if (starts_with(d, "Failed to any values against subschema in 'contains'")) {
      issue.message = "must contain at least one item of the required form";
    } else if (starts_with(d, "Array contains more items than allowed") ||
               starts_with(d, "Cannot validate item #")) {
      issue.message = "has too many items, got " + std::to_string(value.size());
    } else {
      return false;
    }
    return true;
  }

  void phrase_pattern(SchemaIssue& issue) const {
    issue.show_value = true;
    const json* p = keyword("pattern");
    issue.message = "must match the pattern " +
                    (p != nullptr ? short_json(*p, 60) : std::string("of the schema"));
    // A regular expression is no fix: the description of the value says the rule in words.
    for (const auto& ref : refs_)
      if (ref.node->is_object() && ref.node->contains("pattern")) {
        issue.hint = description_of(*ref.node);
        break;
      }
  }

  void phrase_not(const json& value, SchemaIssue& issue) const {
    issue.show_value = true;
    issue.message = "is a value that is not allowed here";
    // A schema explains its own exclusion through the description of the `not` it violates.
    for (const auto& ref : refs_) {
      const auto n = ref.node->is_object() ? ref.node->find("not") : ref.node->end();
      if (n == ref.node->end() || !n->is_object()) continue;
      const auto why = n->find("description");
      if (why == n->end() || !why->is_string()) continue;
      if (!checker_.matches(ref.pointer + "/not", value)) continue;
      issue.message = why->get<std::string>();
      break;
    }
  }

  static bool matches_pattern(const json& node, const std::string& key) {
    const auto pp = node.find("patternProperties");
    if (pp == node.end() || !pp->is_object()) return false;
    for (const auto& [pattern, s] : pp->items()) {
      try {
        if (std::regex_search(key, std::regex(pattern, std::regex::ECMAScript))) return true;
      } catch (const std::exception&) {
      }
    }
    return false;
  }

  SchemaIssue unknown_key(const std::vector<std::string>& path, const std::string& key,
                          const std::vector<std::string>& allowed) const {
    SchemaIssue issue;
    issue.rule = Rule::kUnknownKey;
    auto key_path = path;
    key_path.push_back(key);
    issue.pointer = to_pointer(key_path);
    issue.at_key = true;
    issue.message = "unknown key " + quote_name(key);
    std::string hint;
    if (const auto m = closest_match(key, allowed)) hint = "did you mean \"" + *m + "\"? ";
    if (allowed.empty()) {
      hint += "this object takes no keys";
    } else {
      hint += "allowed keys: " + join(allowed);
    }
    issue.hint = hint;
    return issue;
  }

  std::string required_hint(const std::string& name) const {
    for (const auto& ref : refs_) {
      if (!ref.node->is_object()) continue;
      const auto props = ref.node->find("properties");
      if (props == ref.node->end() || !props->is_object()) continue;
      const auto prop = props->find(name);
      if (prop == props->end()) continue;
      const json* description = declared(checker_.schema(), &*prop, "description");
      if (description != nullptr && description->is_string()) {
        return "add \"" + name + "\": " + description->get<std::string>();
      }
    }
    return "";
  }

  std::string dependency_of(const json& value, const std::string& name) const {
    for (const auto& ref : refs_) {
      if (!ref.node->is_object()) continue;
      const auto deps = ref.node->find("dependencies");
      if (deps == ref.node->end() || !deps->is_object()) continue;
      for (const auto& [key, list] : deps->items()) {
        if (!value.contains(key) || !list.is_array()) continue;
        if (std::find(list.begin(), list.end(), json(name)) != list.end()) {
          return " (it must accompany " + quote_name(key) + ")";
        }
      }
    }
    return "";
  }

  const json* keyword(const char* name) const {
    for (const auto& ref : refs_) {
      if (!ref.node->is_object()) continue;
      if (const auto it = ref.node->find(name); it != ref.node->end()) return &*it;
    }
    return nullptr;
  }

  std::size_t count(const char* name, const std::string& d) const {
    if (const json* n = keyword(name); n != nullptr && n->is_number_unsigned()) {
      return n->get<std::size_t>();
    }
    if (const json* n = keyword(name); n != nullptr && n->is_number_integer()) {
      return static_cast<std::size_t>(std::max<std::int64_t>(0, n->get<std::int64_t>()));
    }
    // valijson's text: "Array should contain no fewer than 1 elements"
    const auto digits = d.find_first_of("0123456789");
    return digits == std::string::npos ? 0 : std::strtoull(d.c_str() + digits, nullptr, 10);
  }

  /// The description of the schema node whose range `value` violates ("" when none says).
  std::string range_reason(const json& value) const {
    if (!value.is_number()) return "";
    for (const auto& ref : refs_) {
      if (!ref.node->is_object()) continue;
      const Range r = range_of(*ref.node);
      if ((r.lower.value != nullptr || r.upper.value != nullptr) &&
          violates(r, value.get<double>()))
        return description_of(*ref.node);
    }
    return "";
  }

  std::string range_message(const json& value, const std::string& d) const {
    if (value.is_number()) {
      const double v = value.get<double>();
      for (const auto& ref : refs_) {
        if (!ref.node->is_object()) continue;
        const Range r = range_of(*ref.node);
        if ((r.lower.value != nullptr || r.upper.value != nullptr) && violates(r, v)) {
          return range_phrase(r);
        }
      }
    }
    // Fallback: valijson's own words, with its number tidied ("0.000000" -> "0").
    const std::string n = trailing_number(d);
    if (starts_with(d, "Expected number greater than or equal to")) return "must be >= " + n;
    if (starts_with(d, "Expected number greater than")) return "must be > " + n;
    if (starts_with(d, "Expected number less than or equal to")) return "must be <= " + n;
    if (starts_with(d, "Expected number less than")) return "must be < " + n;
    return "is out of range";
  }

  const SchemaChecker& checker_;
  const std::string& schema_pointer_;
  const json& root_;
  std::vector<SchemaChecker::Ref> refs_;
};

namespace {

/// A wrapper with nothing under it is a failure with no inner words (a `false` schema): one
/// issue for each wrapper no issue lies at or below.
void add_bare_wrappers(const std::vector<const Entry*>& wrappers,
                       std::vector<SchemaIssue>& issues) {
  std::vector<std::string> covered_pointers;
  for (const SchemaIssue& i : issues) covered_pointers.push_back(i.pointer);
  std::sort(covered_pointers.begin(), covered_pointers.end());
  const auto covered = [&](const std::string& p) {
    if (std::binary_search(covered_pointers.begin(), covered_pointers.end(), p)) return true;
    const auto below = std::lower_bound(covered_pointers.begin(), covered_pointers.end(), p + "/");
    return below != covered_pointers.end() && starts_with(*below, p + "/");
  };
  for (const Entry* w : wrappers) {
    const std::string p = to_pointer(w->path);
    if (!covered(p)) {
      SchemaIssue issue;
      issue.pointer = p;
      issue.show_value = true;
      issue.message = "is not allowed here";
      issues.push_back(issue);
    }
  }
}

/// The entries' issues: those explained already, and the rest phrased; valijson's wrappers
/// ("Failed to validate item #0") only repeat what their inner errors say.
std::vector<SchemaIssue> phrase_entries(const std::vector<Entry>& entries, IssueBuilder& builder) {
  std::vector<SchemaIssue> issues;
  std::set<std::vector<std::string>> closed_objects_done;
  std::vector<const Entry*> wrappers;
  for (const Entry& entry : entries) {
    if (!entry.description) {
      issues.insert(issues.end(), entry.issues.begin(), entry.issues.end());
    } else if (is_wrapper(*entry.description)) {
      wrappers.push_back(&entry);
    } else if (is_unknown_key(*entry.description)) {
      if (closed_objects_done.insert(entry.path).second) {
        builder.unknown_keys(entry.path, *entry.description, issues);
      }
    } else if (auto issue = builder.phrase(entry.path, *entry.description)) {
      issues.push_back(std::move(*issue));
    }
  }
  add_bare_wrappers(wrappers, issues);
  return issues;
}

/// One message per problem: a wrong type makes enum/const/range checks of the same value
/// noise, and two schemas may report the same thing.
std::vector<SchemaIssue> one_per_problem(std::vector<SchemaIssue>& issues) {
  std::set<std::string> typed;
  for (const SchemaIssue& i : issues) {
    if (i.rule == Rule::kType) typed.insert(i.pointer);
  }
  std::vector<SchemaIssue> unique;
  std::set<std::pair<std::string, std::string>> seen;
  for (SchemaIssue& i : issues) {
    const bool shadowed =
        i.rule != Rule::kType && typed.count(i.pointer) > 0 &&
        (i.rule == Rule::kEnum || i.rule == Rule::kConst || i.rule == Rule::kRange);
    if (shadowed || !seen.emplace(i.pointer, i.message).second) continue;
    unique.push_back(std::move(i));
  }
  return unique;
}

/// How far the value is from a variant, by its issues there: a wrong type or a wrong
/// discriminator (a const/enum key such as "type") weigh far more than a wrong detail.
int variant_distance(const std::vector<SchemaIssue>& issues) {
  int score = 0;
  for (const SchemaIssue& i : issues) {
    const auto level = std::count(i.pointer.begin(), i.pointer.end(), '/');
    const bool kind = i.rule == Rule::kType || i.rule == Rule::kConst || i.rule == Rule::kEnum;
    score += (level == 0 && kind)                                                ? 1000
             : (level == 1 && (i.rule == Rule::kConst || i.rule == Rule::kEnum)) ? 100
                                                                                 : 1;
  }
  return score;
}

}  // namespace

SchemaChecker::SchemaChecker(const std::string& schema_text) {
  try {
    schema_ = json::parse(schema_text);
  } catch (const json::exception& e) {
    throw SchemaError(std::string("the schema is not valid JSON: ") + e.what());
  }
  if (!schema_.is_object() && !schema_.is_boolean()) {
    throw SchemaError("the schema is not a JSON object");
  }
  uses_regex_ = schema_text.find("\"pattern") != std::string::npos;
  try {
    compiled("");
  } catch (const std::exception& e) {
    throw SchemaError(std::string("the schema is not a valid JSON Schema: ") + e.what());
  }
}

SchemaChecker::~SchemaChecker() = default;

const valijson::Schema& SchemaChecker::compiled(const std::string& pointer) const {
  std::lock_guard<std::mutex> lock(mutex_);
  auto& slot = cache_[pointer];
  if (!slot) {
    auto schema = std::make_unique<valijson::Schema>();
    valijson::SchemaParser parser(valijson::SchemaParser::kDraft7);
    if (pointer.empty()) {
      parser.populateSchema(valijson::adapters::NlohmannJsonAdapter(schema_), *schema);
    } else {
      // A subschema is compiled as the whole document with its root replaced by a $ref to it
      // (draft 7 ignores a $ref's siblings), so that its own "#/definitions/..." still resolve.
      json doc = schema_;
      doc["$ref"] = "#" + pointer;
      parser.populateSchema(valijson::adapters::NlohmannJsonAdapter(doc), *schema);
    }
    slot = std::move(schema);
  }
  return *slot;
}

bool SchemaChecker::matches(const std::string& pointer, const json& value) const {
  try {
    valijson::Validator validator(valijson::Validator::kStrongTypes);
    return validator.validate(compiled(pointer), valijson::adapters::NlohmannJsonAdapter(value),
                              nullptr);
  } catch (const std::exception&) {
    return false;
  }
}

const json* SchemaChecker::node_at(const std::string& pointer) const {
  try {
    const json::json_pointer p(pointer);
    return schema_.contains(p) ? &schema_.at(p) : nullptr;
  } catch (const std::exception&) {
    return nullptr;
  }
}

void SchemaChecker::closure(const std::string& pointer, const json& value, Closure mode, int depth,
                            std::vector<Ref>& out) const {
  if (depth > kMaxClosureDepth) return;
  if (std::any_of(out.begin(), out.end(), [&](const Ref& r) { return r.pointer == pointer; })) {
    return;
  }
  const json* node = node_at(pointer);
  if (node == nullptr) return;
  out.push_back(Ref{pointer, node});
  if (!node->is_object()) return;
  if (const auto ref = node->find("$ref"); ref != node->end() && ref->is_string()) {
    const std::string& target = ref->get_ref<const std::string&>();
    if (starts_with(target, "#")) closure(target.substr(1), value, mode, depth + 1, out);
    return;  // draft 7: the siblings of a $ref are ignored
  }
  const auto each = [&](const char* keyword, bool only_matching) {
    const auto list = node->find(keyword);
    if (list == node->end() || !list->is_array()) return;
    for (std::size_t i = 0; i < list->size(); ++i) {
      const std::string p = pointer + "/" + keyword + "/" + std::to_string(i);
      if (!only_matching || matches(p, value)) closure(p, value, mode, depth + 1, out);
    }
  };
  each("allOf", false);
  if (mode != Closure::kActive) {
    each("anyOf", mode == Closure::kMatching);
    each("oneOf", mode == Closure::kMatching);
  }
  if (node->contains("if")) {
    const char* branch = matches(pointer + "/if", value) ? "then" : "else";
    if (node->contains(branch)) closure(pointer + "/" + branch, value, mode, depth + 1, out);
  }
}

std::vector<SchemaChecker::Ref> SchemaChecker::children(const std::vector<Ref>& parents,
                                                        const json& parent_value,
                                                        const std::string& token,
                                                        Closure mode) const {
  std::vector<Ref> out;
  const json* child = child_of(parent_value, token);
  if (child == nullptr) return out;
  for (const Ref& ref : parents) {
    const json& node = *ref.node;
    if (!node.is_object()) continue;
    if (parent_value.is_object()) {
      bool matched = false;
      if (const auto props = node.find("properties");
          props != node.end() && props->is_object() && props->contains(token)) {
        closure(ref.pointer + "/properties/" + escape_pointer_token(token), *child, mode, 0, out);
        matched = true;
      }
      if (const auto pp = node.find("patternProperties"); pp != node.end() && pp->is_object()) {
        for (const auto& [pattern, s] : pp->items()) {
          try {
            if (!std::regex_search(token, std::regex(pattern, std::regex::ECMAScript))) continue;
          } catch (const std::exception&) {
            continue;
          }
          closure(ref.pointer + "/patternProperties/" + escape_pointer_token(pattern), *child, mode,
                  0, out);
          matched = true;
        }
      }
      if (const auto ap = node.find("additionalProperties");
          !matched && ap != node.end() && ap->is_object()) {
        closure(ref.pointer + "/additionalProperties", *child, mode, 0, out);
      }
    } else if (parent_value.is_array()) {
      const auto items = node.find("items");
      if (items == node.end()) continue;
      if (items->is_object() || items->is_boolean()) {
        closure(ref.pointer + "/items", *child, mode, 0, out);
      } else if (items->is_array()) {
        const std::size_t i = to_index(token).value_or(0);
        if (i < items->size()) {
          closure(ref.pointer + "/items/" + token, *child, mode, 0, out);
        } else if (node.contains("additionalItems")) {
          closure(ref.pointer + "/additionalItems", *child, mode, 0, out);
        }
      }
    }
  }
  return out;
}

std::vector<SchemaChecker::Ref> SchemaChecker::resolve(const std::string& pointer,
                                                       const json& value,
                                                       const std::vector<std::string>& path,
                                                       Closure mode) const {
  std::vector<Ref> refs;
  closure(pointer, value, mode, 0, refs);
  const json* v = &value;
  for (const std::string& token : path) {
    refs = children(refs, *v, token, mode);
    v = child_of(*v, token);
    if (v == nullptr) return {};
  }
  return refs;
}

std::optional<std::string> SchemaChecker::too_long_for_regex(const json& value) const {
  if (!uses_regex_) return std::nullopt;
  std::vector<std::pair<const json*, std::string>> stack{{&value, ""}};
  while (!stack.empty()) {
    const auto [v, pointer] = stack.back();
    stack.pop_back();
    if (v->is_string() && v->get_ref<const std::string&>().size() > kMaxPatternInput) {
      return pointer;
    }
    if (v->is_object()) {
      for (const auto& [k, child] : v->items()) {
        const std::string p = pointer + "/" + escape_pointer_token(k);
        if (k.size() > kMaxPatternInput) return p;
        stack.emplace_back(&child, p);
      }
    } else if (v->is_array()) {
      for (std::size_t i = 0; i < v->size(); ++i) {
        stack.emplace_back(&(*v)[i], pointer + "/" + std::to_string(i));
      }
    }
  }
  return std::nullopt;
}

std::vector<SchemaIssue> SchemaChecker::check(const json& value) const {
  if (const auto p = too_long_for_regex(value)) {
    SchemaIssue issue;
    issue.pointer = *p;
    issue.message = "is too long to be checked (more than " + std::to_string(kMaxPatternInput) +
                    " characters where the schema has patterns)";
    return {issue};
  }
  return check_at("", value, 0);
}

std::vector<SchemaIssue> SchemaChecker::check_at(const std::string& pointer, const json& value,
                                                 int depth) const {
  valijson::ValidationResults results;
  try {
    valijson::Validator validator(valijson::Validator::kStrongTypes);
    if (validator.validate(compiled(pointer), valijson::adapters::NlohmannJsonAdapter(value),
                           &results)) {
      return {};
    }
  } catch (const std::exception& e) {
    SchemaIssue issue;
    issue.message = std::string("cannot be checked: the schema failed: ") + e.what();
    return {issue};
  }

  // 1. Replace each failed oneOf/anyOf, and everything valijson reported inside it, by the
  //    issues of the variant closest to the value.
  std::vector<Entry> entries;
  for (const auto& error : results) {
    Entry entry{path_of(error.context), error.description, {}};
    if (is_no_variant_matched(error.description)) {
      while (!entries.empty() && has_prefix(entries.back().path, entry.path)) entries.pop_back();
      entry.description.reset();
      entry.issues = explain_variants(pointer, value, entry.path, depth);
    } else if (is_several_variants_matched(error.description)) {
      entry.description.reset();
      SchemaIssue issue;
      issue.pointer = to_pointer(entry.path);
      issue.message = "fits more than one of the alternatives; exactly one is allowed";
      issue.hint = alternatives_hint(pointer, value, entry.path);
      entry.issues.push_back(issue);
    }
    entries.push_back(std::move(entry));
  }
  // 2. Phrase the rest. 3. One message per problem.
  IssueBuilder builder(*this, pointer, value);
  std::vector<SchemaIssue> issues = phrase_entries(entries, builder);
  return one_per_problem(issues);
}

std::string SchemaChecker::alternatives_hint(const std::string& pointer, const json& value,
                                             const std::vector<std::string>& path) const {
  for (const Ref& ref : resolve(pointer, value, path, Closure::kAll)) {
    if (ref.node->is_object() && ref.node->contains("oneOf")) return description_of(*ref.node);
  }
  return "";
}

std::vector<SchemaIssue> SchemaChecker::explain_variants(const std::string& pointer,
                                                         const json& value,
                                                         const std::vector<std::string>& path,
                                                         int depth) const {
  const json* sub = navigate(value, path);
  const std::string at = to_pointer(path);
  SchemaIssue fallback;
  fallback.pointer = at;
  fallback.show_value = true;
  fallback.message = "does not match any of the allowed forms";
  if (sub == nullptr || depth >= kMaxVariantDepth) return {fallback};

  for (const Ref& ref : resolve(pointer, value, path, Closure::kAll)) {
    if (!ref.node->is_object()) continue;
    for (const char* keyword : {"oneOf", "anyOf"}) {
      const auto list = ref.node->find(keyword);
      if (list == ref.node->end() || !list->is_array() || list->empty()) continue;
      std::vector<std::string> variants;
      for (std::size_t i = 0; i < list->size(); ++i) {
        variants.push_back(ref.pointer + "/" + keyword + "/" + std::to_string(i));
      }
      // Only the alternative list that no variant satisfies is the one that failed.
      if (std::any_of(variants.begin(), variants.end(),
                      [&](const std::string& v) { return matches(v, *sub); })) {
        continue;
      }
      VariantChoice choice = closest_variant(variants, *sub, depth);
      // Alternatives that differ only in which keys are required ({"required": ["k", "c"]} or
      // {"required": ["E", "nu", "rho"]}): the one the value has started on, or else all of
      // them by name rather than a guess.
      if (choice.all_missing_keys && !choice.started.empty()) {
        choice.best = std::move(choice.started);
      } else if (choice.all_missing_keys) {
        return {required_sets_issue(variants, *ref.node, fallback)};
      }
      // The value is of none of the allowed kinds: list the kinds.
      if (choice.best_score >= 1000) return {kinds_issue(variants, fallback)};
      for (SchemaIssue& i : choice.best) i.pointer = at + i.pointer;
      return choice.best;
    }
  }
  return {fallback};
}

SchemaChecker::VariantChoice SchemaChecker::closest_variant(
    const std::vector<std::string>& variants, const json& sub, int depth) const {
  // The closest variant is the one the user meant (variant_distance).
  VariantChoice choice;
  for (const std::string& v : variants) {
    auto issues = check_at(v, sub, depth + 1);
    choice.all_missing_keys &=
        !issues.empty() && std::all_of(issues.begin(), issues.end(), [](const SchemaIssue& i) {
          return i.rule == Rule::kRequired && i.pointer.empty();
        });
    const int score = variant_distance(issues);
    if (started_on(node_at(v), sub) &&
        (choice.started.empty() || issues.size() < choice.started.size())) {
      choice.started = issues;
    }
    if (choice.best_score < 0 || score < choice.best_score) {
      choice.best_score = score;
      choice.best = std::move(issues);
    }
  }
  return choice;
}

SchemaIssue SchemaChecker::required_sets_issue(const std::vector<std::string>& variants,
                                               const json& alternatives,
                                               const SchemaIssue& fallback) const {
  std::vector<std::string> sets;
  for (const std::string& v : variants) {
    const json* node = node_at(v);
    std::vector<std::string> keys;
    if (node != nullptr && node->contains("required") && node->at("required").is_array()) {
      for (const json& k : node->at("required")) {
        if (k.is_string()) keys.push_back(k.get<std::string>());
      }
    }
    sets.push_back(and_list(keys));
  }
  SchemaIssue issue = fallback;
  issue.rule = Rule::kRequired;
  issue.show_value = false;
  issue.message = "needs " + join(sets, ", or ");
  issue.hint = description_of(alternatives);
  return issue;
}

SchemaIssue SchemaChecker::kinds_issue(const std::vector<std::string>& variants,
                                       const SchemaIssue& fallback) const {
  std::vector<std::string> forms;
  for (const std::string& v : variants) {
    const json* node = node_at(v);
    if (const json* c = node ? declared(schema_, node, "const") : nullptr) {
      forms.push_back(short_json(*c));
    } else if (const json* e = node ? declared(schema_, node, "enum") : nullptr;
               e != nullptr && e->is_array()) {
      forms.push_back("one of " + enum_list(*e));
    } else if (const json* t = node ? declared(schema_, node, "type") : nullptr) {
      std::vector<std::string> phrases;
      for (const std::string& x : type_list(*t)) phrases.push_back(type_phrase(x));
      forms.push_back(join(phrases, " or "));
    }
  }
  SchemaIssue issue = fallback;
  issue.rule = Rule::kType;
  if (forms.size() == variants.size()) issue.message = "must be " + join(forms, " or ");
  return issue;
}

void SchemaChecker::fill_defaults(json& value, const std::string& schema_pointer) const {
  if (too_long_for_regex(value)) return;  // invalid anyway, and unsafe to match
  std::vector<Ref> refs;
  closure(schema_pointer, value, Closure::kMatching, 0, refs);
  fill_at(refs, value, 0);
}

void SchemaChecker::fill_at(const std::vector<Ref>& refs, json& value, int depth) const {
  if (depth > 512) return;
  if (value.is_object()) {
    for (const Ref& ref : refs) {
      if (!ref.node->is_object()) continue;
      const auto props = ref.node->find("properties");
      if (props == ref.node->end() || !props->is_object()) continue;
      for (const auto& [key, sub] : props->items()) {
        if (value.contains(key)) continue;
        if (const json* d = declared(schema_, &sub, "default"); d != nullptr) value[key] = *d;
      }
    }
    for (auto& [key, child] : value.items()) {
      const auto child_refs = children(refs, value, key, Closure::kMatching);
      if (!child_refs.empty()) fill_at(child_refs, child, depth + 1);
    }
  } else if (value.is_array()) {
    for (std::size_t i = 0; i < value.size(); ++i) {
      const auto child_refs = children(refs, value, std::to_string(i), Closure::kMatching);
      if (!child_refs.empty()) fill_at(child_refs, value[i], depth + 1);
    }
  }
}

}  // namespace rumble::scenario
