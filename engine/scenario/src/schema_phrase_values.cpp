// Phrasing the rules on a value itself: a missing required key, a wrong type, a number out of
// range, a value not in an enum or not the const. Each message names the exact rule from the
// schema keyword behind it, and a hint where one helps a user fix it (the number's range reason,
// "remove the quotes", "did you mean").
#include <algorithm>
#include <cmath>

#include "scenario/did_you_mean.hpp"
#include "scenario/value_text.hpp"
#include "schema_check_parts.hpp"

namespace rumble::scenario {
namespace {

using nlohmann::json;
using Rule = SchemaIssue::Rule;

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

struct Bound {
  const json* value = nullptr;
  bool exclusive = false;
};

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

}  // namespace

bool IssueBuilder::phrase_value_rule(const json& value, const std::string& d,
                                     SchemaIssue& issue) const {
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
    if (const json* c = keyword("const"); c != nullptr) issue.message = "must be " + short_json(*c);
  } else {
    return false;
  }
  return true;
}

void IssueBuilder::phrase_type(const json& value, SchemaIssue& issue) const {
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

void IssueBuilder::phrase_enum(const json& value, SchemaIssue& issue) const {
  issue.rule = Rule::kEnum;
  issue.show_value = true;
  issue.message = "is not one of the allowed values";
  for (const auto& ref : refs_) {
    const auto e = ref.node->is_object() ? ref.node->find("enum") : ref.node->end();
    if (!ref.node->is_object() || e == ref.node->end() || !e->is_array()) continue;
    if (std::find(e->begin(), e->end(), value) != e->end()) continue;
    issue.message = "must be one of: " + enum_list(*e);
    // A value the schema lists as removed ("x-removed": {value: what replaces it}, docs/
    // plugin-guide.md) is told its replacement, not the nearest spelling of another value.
    const auto removed = ref.node->find("x-removed");
    if (value.is_string() && removed != ref.node->end() && removed->is_object()) {
      const auto fix = removed->find(value.get_ref<const std::string&>());
      if (fix != removed->end() && fix->is_string()) {
        issue.hint = value.dump() + " " + fix->get<std::string>();
        break;
      }
    }
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

std::string IssueBuilder::required_hint(const std::string& name) const {
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

const json* IssueBuilder::keyword(const char* name) const {
  for (const auto& ref : refs_) {
    if (!ref.node->is_object()) continue;
    if (const auto it = ref.node->find(name); it != ref.node->end()) return &*it;
  }
  return nullptr;
}

std::string IssueBuilder::range_reason(const json& value) const {
  if (!value.is_number()) return "";
  for (const auto& ref : refs_) {
    if (!ref.node->is_object()) continue;
    const Range r = range_of(*ref.node);
    if ((r.lower.value != nullptr || r.upper.value != nullptr) && violates(r, value.get<double>()))
      return description_of(*ref.node);
  }
  return "";
}

std::string IssueBuilder::range_message(const json& value, const std::string& d) const {
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

}  // namespace rumble::scenario
