// Validates a JSON value against a JSON Schema (draft 7) with valijson and turns its raw results
// into messages a user can act on, one per real problem:
//   pointer of the offending value, the rule in plain words ("must be > 0", "must be one of: a,
//   b", "required key 'mass' is missing", "unknown key 'dampng'"), a hint where one helps.
// valijson's wrapper errors ("Failed to validate item #0", "... against child schema #1") are
// dropped, and a failed oneOf/anyOf is reported through the variant closest to the value
// instead of "failed to match oneOf". Also fills the schema's declared defaults into a value.
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace valijson {
class Schema;
}

namespace rumble::scenario {

/// The schema text is not JSON, or not a schema valijson can use.
class SchemaError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct SchemaIssue {
  enum class Rule { kType, kRequired, kUnknownKey, kEnum, kConst, kRange, kOther };
  Rule rule = Rule::kOther;
  std::string pointer;      // relative to the checked value
  bool at_key = false;      // point at the key (unknown keys), not at the value
  std::string message;      // "must be > 0" (without the value)
  bool show_value = false;  // the caller appends ", got <value as written>"
  std::string hint;
};

class SchemaChecker {
 public:
  static constexpr std::size_t kMaxPatternInput = 1000;  // bytes

  /// Throws SchemaError when `schema_text` is not valid JSON or not a usable schema.
  explicit SchemaChecker(const std::string& schema_text);
  ~SchemaChecker();
  SchemaChecker(const SchemaChecker&) = delete;
  SchemaChecker& operator=(const SchemaChecker&) = delete;

  /// Every problem of `value`, in valijson's order (schema order, then document order).
  /// Never throws for any value; a schema that fails while validating (a bad regex) is
  /// reported as an issue at "". When the schema has regular expressions, a string or key
  /// longer than kMaxPatternInput is reported instead of checked: std::regex recurses per
  /// character and would overflow the stack.
  std::vector<SchemaIssue> check(const nlohmann::json& value) const;

  /// Inserts every declared "default" for keys absent from objects, recursively (defaults that
  /// are objects are filled in turn). Variants (oneOf, anyOf, if/then) count only where the
  /// value matches them. `schema_pointer`: the part of the schema `value` is an instance of
  /// ("" = the whole schema; "/properties/track" for a scenario's track).
  void fill_defaults(nlohmann::json& value, const std::string& schema_pointer = "") const;

  const nlohmann::json& schema() const { return schema_; }

 private:
  struct Ref {
    std::string pointer;  // into schema_, e.g. "/properties/time"
    const nlohmann::json* node = nullptr;
  };
  enum class Closure { kActive, kMatching, kAll };

  const valijson::Schema& compiled(const std::string& pointer) const;
  bool matches(const std::string& pointer, const nlohmann::json& value) const;
  const nlohmann::json* node_at(const std::string& pointer) const;
  void closure(const std::string& pointer, const nlohmann::json& value, Closure mode, int depth,
               std::vector<Ref>& out) const;
  std::vector<Ref> children(const std::vector<Ref>& parents, const nlohmann::json& parent_value,
                            const std::string& token, Closure mode) const;
  std::vector<Ref> resolve(const std::string& pointer, const nlohmann::json& value,
                           const std::vector<std::string>& path, Closure mode) const;
  std::vector<SchemaIssue> check_at(const std::string& pointer, const nlohmann::json& value,
                                    int depth) const;
  std::string alternatives_hint(const std::string& pointer, const nlohmann::json& value,
                                const std::vector<std::string>& path) const;
  std::vector<SchemaIssue> explain_variants(const std::string& pointer, const nlohmann::json& value,
                                            const std::vector<std::string>& path, int depth) const;
  // The steps of explain_variants: the variant closest to the value (its issues, and those of
  // the closest one the value has started on), the required key sets of variants that differ
  // only in them, and the kinds of variants the value is of none of.
  struct VariantChoice {
    std::vector<SchemaIssue> best, started;
    int best_score = -1;
    bool all_missing_keys = true;
  };
  VariantChoice closest_variant(const std::vector<std::string>& variants, const nlohmann::json& sub,
                                int depth) const;
  SchemaIssue required_sets_issue(const std::vector<std::string>& variants,
                                  const nlohmann::json& alternatives,
                                  const SchemaIssue& fallback) const;
  SchemaIssue kinds_issue(const std::vector<std::string>& variants,
                          const SchemaIssue& fallback) const;
  void fill_at(const std::vector<Ref>& refs, nlohmann::json& value, int depth) const;

  /// The pointer of the first string or key too long for a regex, when the schema has any.
  std::optional<std::string> too_long_for_regex(const nlohmann::json& value) const;

  nlohmann::json schema_;
  bool uses_regex_ = false;   // "pattern" or "patternProperties" anywhere in the schema
  mutable std::mutex mutex_;  // guards cache_: compiled subschemas, built on first use
  mutable std::map<std::string, std::unique_ptr<valijson::Schema>> cache_;

  friend class IssueBuilder;
};

}  // namespace rumble::scenario
