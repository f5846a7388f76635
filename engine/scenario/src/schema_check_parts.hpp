// What the files of the schema checker share: the words they read and write, where a value is,
// which schema node says what, and the IssueBuilder that phrases valijson's raw errors (its rule
// families in files of their own). Private to the scenario room: the interface is
// scenario/schema_check.hpp.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scenario/schema_check.hpp"

namespace rumble::scenario {

// ---------------------------------------------------------------------------------------------
// Words (schema_words.cpp)

bool starts_with(std::string_view s, std::string_view prefix);
/// The text between the first `open` and the last `close` ("" when there is none).
std::string between(std::string_view s, std::string_view open, std::string_view close);
/// A schema's "type", one name or a list, as a list.
std::vector<std::string> type_list(const nlohmann::json& t);
/// An enum's values for a message, the first 20 and how many there are.
std::string enum_list(const nlohmann::json& values);
/// The number at the end of "Expected number greater than 0.000000": the fallback when the
/// schema keyword behind an error cannot be found.
std::string trailing_number(std::string_view d);
/// A schema node's "description" ("" when it has none).
std::string description_of(const nlohmann::json& node);

// ---------------------------------------------------------------------------------------------
// Where a value is, and which schema node declares what (schema_refs.cpp)

/// {"a", "0"} -> "/a/0".
std::string to_pointer(const std::vector<std::string>& path);
/// The value at `path` under `root`, or nullptr.
const nlohmann::json* navigate(const nlohmann::json& root, const std::vector<std::string>& path);
/// Follows local $refs from a property schema to the node that declares its description or
/// default.
const nlohmann::json* declared(const nlohmann::json& root, const nlohmann::json* node,
                               const char* keyword);

// ---------------------------------------------------------------------------------------------
// Phrasing valijson's raw errors

/// Phrases one raw valijson error, looking up the schema keyword behind it for exact bounds,
/// enum values and property descriptions.
class IssueBuilder {
 public:
  IssueBuilder(const SchemaChecker& checker, const std::string& schema_pointer,
               const nlohmann::json& root)
      : checker_(checker), schema_pointer_(schema_pointer), root_(root) {}

  /// A closed object's unknown keys, each with its allowed keys (schema_unknown_keys.cpp).
  void unknown_keys(const std::vector<std::string>& path, const std::string& description,
                    std::vector<SchemaIssue>& out);
  /// The issue of one raw error at `path` (schema_check.cpp); nullopt when no value is there.
  std::optional<SchemaIssue> phrase(const std::vector<std::string>& path, const std::string& d);

 private:
  // The rules on the value itself (schema_phrase_values.cpp).
  /// The rules on the value itself: required, type, range, enum, const; false for another.
  bool phrase_value_rule(const nlohmann::json& value, const std::string& d,
                         SchemaIssue& issue) const;
  void phrase_type(const nlohmann::json& value, SchemaIssue& issue) const;
  void phrase_enum(const nlohmann::json& value, SchemaIssue& issue) const;
  /// "add \"name\": <its description>" for a missing key ("" when it has none).
  std::string required_hint(const std::string& name) const;
  /// The first of the value's schema nodes that has `name`, or nullptr.
  const nlohmann::json* keyword(const char* name) const;
  /// The description of the schema node whose range `value` violates ("" when none says).
  std::string range_reason(const nlohmann::json& value) const;
  std::string range_message(const nlohmann::json& value, const std::string& d) const;

  // The rules on sizes and forms (schema_phrase_forms.cpp).
  /// The rules on sizes: items of an array, characters of a string, keys of an object; false
  /// for another.
  bool phrase_size_rule(const nlohmann::json& value, const std::string& d,
                        SchemaIssue& issue) const;
  /// The rules on a value's form: multiple, pattern, not, unique items, dependencies, formats,
  /// contains, tuples; false for another.
  bool phrase_form_rule(const nlohmann::json& value, const std::string& d,
                        SchemaIssue& issue) const;
  void phrase_pattern(SchemaIssue& issue) const;
  void phrase_not(const nlohmann::json& value, SchemaIssue& issue) const;
  /// " (it must accompany 'key')" for a missing dependency ("" when none says).
  std::string dependency_of(const nlohmann::json& value, const std::string& name) const;
  /// The count a size keyword sets, from the schema or else from valijson's text.
  std::size_t count(const char* name, const std::string& d) const;

  // Unknown keys (schema_unknown_keys.cpp).
  static bool matches_pattern(const nlohmann::json& node, const std::string& key);
  SchemaIssue unknown_key(const std::vector<std::string>& path, const std::string& key,
                          const std::vector<std::string>& allowed) const;

  const SchemaChecker& checker_;
  const std::string& schema_pointer_;
  const nlohmann::json& root_;
  std::vector<SchemaChecker::Ref> refs_;
};

}  // namespace rumble::scenario
