// Phrasing a closed object's unknown keys. A misspelt key is the commonest mistake in a scenario,
// so each one is named with "did you mean" and the keys the object allows, gathered from every
// schema node that closes the object rather than from valijson's words.
#include <algorithm>
#include <regex>
#include <set>

#include "scenario/did_you_mean.hpp"
#include "scenario/value_text.hpp"
#include "schema_check_parts.hpp"

namespace rumble::scenario {
namespace {

using nlohmann::json;
using Rule = SchemaIssue::Rule;

}  // namespace

void IssueBuilder::unknown_keys(const std::vector<std::string>& path,
                                const std::string& description, std::vector<SchemaIssue>& out) {
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

bool IssueBuilder::matches_pattern(const json& node, const std::string& key) {
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

SchemaIssue IssueBuilder::unknown_key(const std::vector<std::string>& path, const std::string& key,
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

}  // namespace rumble::scenario
