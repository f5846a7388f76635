// The schema checker's outline: the schema compiled once per subschema, the value validated by
// valijson, and its raw errors made into one issue per real problem (a failed oneOf explained
// through its closest variant, wrappers dropped, shadowed rules dropped). The rule families are
// phrased in files of their own (schema_check_parts.hpp names them), so this one stays the
// algorithm.
#include "scenario/schema_check.hpp"

// VALIJSON_USE_EXCEPTIONS is defined for the whole engine (engine/CMakeLists.txt): without it
// valijson reports a bad schema (or a value it cannot handle) by abort().
#include <algorithm>
#include <set>
#include <string_view>
#include <valijson/adapters/nlohmann_json_adapter.hpp>
#include <valijson/schema.hpp>
#include <valijson/schema_parser.hpp>
#include <valijson/validation_results.hpp>
#include <valijson/validator.hpp>

#include "scenario/json_position.hpp"
#include "schema_check_parts.hpp"

namespace rumble::scenario {
namespace {

using nlohmann::json;
using Rule = SchemaIssue::Rule;

/// valijson's context is {"<root>", "[key]", "[0]", ...}.
std::vector<std::string> path_of(const std::vector<std::string>& context) {
  std::vector<std::string> path;
  for (std::size_t i = 1; i < context.size(); ++i) {
    const std::string& c = context[i];
    path.push_back(c.size() >= 2 ? c.substr(1, c.size() - 2) : c);
  }
  return path;
}

bool has_prefix(const std::vector<std::string>& path, const std::vector<std::string>& prefix) {
  return path.size() >= prefix.size() && std::equal(prefix.begin(), prefix.end(), path.begin());
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

/// Either a raw valijson error still to phrase, or issues already explained (a collapsed
/// oneOf/anyOf) that stand in for all the raw errors under `path`.
struct Entry {
  std::vector<std::string> path;
  std::optional<std::string> description;
  std::vector<SchemaIssue> issues;
};

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

std::optional<SchemaIssue> IssueBuilder::phrase(const std::vector<std::string>& path,
                                                const std::string& d) {
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

}  // namespace rumble::scenario
