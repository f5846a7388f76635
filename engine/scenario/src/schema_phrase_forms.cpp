// Phrasing the rules on sizes and forms: counts of items, characters and keys, multipleOf,
// patterns, `not`, unique items, dependencies, formats, contains and tuples. A family of its own
// (the rules on the value itself are schema_phrase_values.cpp's), so that the message a user gets
// for each keyword is found in one short place.
#include <algorithm>
#include <cstdint>
#include <cstdlib>

#include "scenario/value_text.hpp"
#include "schema_check_parts.hpp"

namespace rumble::scenario {
namespace {

using nlohmann::json;
using Rule = SchemaIssue::Rule;

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

}  // namespace

bool IssueBuilder::phrase_size_rule(const json& value, const std::string& d,
                                    SchemaIssue& issue) const {
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

bool IssueBuilder::phrase_form_rule(const json& value, const std::string& d,
                                    SchemaIssue& issue) const {
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
    issue.message = "required key " + quote_name(name) + " is missing" + dependency_of(value, name);
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

void IssueBuilder::phrase_pattern(SchemaIssue& issue) const {
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

void IssueBuilder::phrase_not(const json& value, SchemaIssue& issue) const {
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

std::string IssueBuilder::dependency_of(const json& value, const std::string& name) const {
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

std::size_t IssueBuilder::count(const char* name, const std::string& d) const {
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

}  // namespace rumble::scenario
