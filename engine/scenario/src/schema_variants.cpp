// A failed oneOf or anyOf explained through the variant the user meant, the closest one,
// instead of valijson's "failed to match oneOf": the issues of that variant, the key sets of
// variants that differ only in required keys, or the kinds allowed when the value is of none.
#include <algorithm>

#include "scenario/did_you_mean.hpp"
#include "scenario/value_text.hpp"
#include "schema_check_parts.hpp"

namespace rumble::scenario {
namespace {

using nlohmann::json;
using Rule = SchemaIssue::Rule;

// A oneOf inside a oneOf inside ... is explained variant by variant; real schemas nest a few
// levels at most, so deeper ones are summarized instead of explained.
constexpr int kMaxVariantDepth = 4;

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

}  // namespace rumble::scenario
