// SPDX-License-Identifier: MIT
// rumble/params.hpp: reading a component's params (JSON text) in a plugin. Optional header: it
// needs nlohmann-json (find_package(nlohmann_json) is done by the Rumble package config).
//
// A parameter is declared once, in the component's params schema: its name, type, unit, range
// and default. The host validates params against that schema and fills every declared default
// before the plugin sees them; Params given the same schema also falls back to the schema's
// default itself, so that a component created without the host (a unit test, another tool)
// reads the same values and no default is ever written a second time in C++
// (docs/plugin-guide.md, "Each parameter is declared once").
#ifndef RUMBLE_PARAMS_HPP
#define RUMBLE_PARAMS_HPP

#include <initializer_list>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>

namespace rumble {

/// A params schema of these properties (each a `"name": {...}` fragment), closed to any other
/// key: for a component whose properties are assembled from shared fragments.
inline std::string object_schema(std::initializer_list<std::string> properties) {
  std::string s =
      "{\n  \"type\": \"object\",\n  \"additionalProperties\": false,\n  \"properties\": {";
  const char* separator = "\n    ";
  for (const std::string& p : properties) {
    s += separator + p;
    separator = ",\n    ";
  }
  return s + "\n  }\n}";
}

class Params {
 public:
  /// `schema_json`: the component's params schema (its params_schema()); optional, but without
  /// it a key that is absent has no default here. `component`: prefixes every message
  /// ("fem: params/mesh/radius: ..."); "" for none.
  explicit Params(const std::string& json_text, const char* schema_json = nullptr,
                  const std::string& component = "")
      : j_(nlohmann::json::parse(json_text)),
        schema_(std::make_shared<const nlohmann::json>(
            schema_json != nullptr ? nlohmann::json::parse(schema_json) : nlohmann::json())),
        node_(schema_.get()),
        where_(component.empty() ? "params/" : component + ": params/") {}

  /// True when params give `key` (a default does not count: this tells what the user set).
  bool has(const char* key) const { return j_.contains(key) && !j_.at(key).is_null(); }

  /// The value of `key`, else the schema's default for it; throws with the JSON pointer when
  /// neither exists (a plugin bug: a key it reads as required has no default) or when the value
  /// is of the wrong type.
  template <class T>
  T get(const char* key) const {
    const nlohmann::json* value = has(key) ? &j_.at(key) : schema_default(key);
    if (value == nullptr)
      throw std::invalid_argument(where_ + key + ": missing, and the schema gives no default");
    try {
      return value->get<T>();
    } catch (const nlohmann::json::exception& e) {
      throw std::invalid_argument(where_ + key + ": " + e.what());
    }
  }

  /// For a default the schema cannot state because it derives from other values (e.g. a step
  /// from a frequency); a constant default belongs in the schema, read with get().
  template <class T>
  T get_or(const char* key, T fallback) const {
    return has(key) ? get<T>(key) : fallback;
  }

  /// The value of `key`, else the schema's default, else nothing: for a key whose default
  /// derives from other values, which the caller computes where it reads it.
  template <class T>
  std::optional<T> optional(const char* key) const {
    if (!has(key) && schema_default(key) == nullptr) return std::nullopt;
    return get<T>(key);
  }

  /// The message prefix of `key`: "params/mesh/radius: " (with the component's name before it
  /// when given), for a check of the caller's own to name the key as get() does.
  std::string pointer(const char* key) const { return where_ + key + ": "; }

  /// The object `key` (given, else the schema's default, else empty), read against its own
  /// schema: its get() falls back to the defaults declared inside it.
  Params object(const char* key) const {
    Params sub(*this);
    const nlohmann::json* given = has(key) ? &j_.at(key) : schema_default(key);
    sub.j_ = given != nullptr ? *given : nlohmann::json::object();
    if (!sub.j_.is_object())
      throw std::invalid_argument(where_ + key + ": must be an object, got " + sub.j_.dump());
    sub.node_ = property(key);
    sub.where_ = where_ + key + "/";
    return sub;
  }

  const nlohmann::json& json() const { return j_; }

 private:
  static constexpr int kMaxDepth = 32;  // $ref and allOf nesting followed (a cycle stops here)

  // The declaration of `key` in the schema node this reads against (following local $refs and
  // allOf), or nullptr.
  const nlohmann::json* property(const char* key) const {
    return node_ != nullptr ? property_in(*node_, key, 0) : nullptr;
  }

  const nlohmann::json* property_in(const nlohmann::json& node, const char* key, int depth) const {
    return declaration_in(node, key, depth, [](const nlohmann::json&) { return true; });
  }

  // The first declaration of `key` below `node` that `wanted` accepts, looking in properties,
  // then in the parts of allOf, then in the branch of an if/then/else that applies.
  template <class Wanted>
  const nlohmann::json* declaration_in(const nlohmann::json& node, const char* key, int depth,
                                       const Wanted& wanted) const {
    const nlohmann::json* n = resolved(node, depth);
    if (n == nullptr || !n->is_object() || depth > kMaxDepth) return nullptr;
    if (const auto props = n->find("properties"); props != n->end() && props->contains(key))
      if (const nlohmann::json* p = resolved(props->at(key), depth + 1); p && wanted(*p)) return p;
    if (const auto all = n->find("allOf"); all != n->end() && all->is_array())
      for (const nlohmann::json& part : *all)
        if (const nlohmann::json* p = declaration_in(part, key, depth + 1, wanted)) return p;
    if (const nlohmann::json* branch = branch_taken(*n))
      return declaration_in(*branch, key, depth + 1, wanted);
    return nullptr;
  }

  // The "then" or "else" of `node` that applies to the params read here, for an "if" that only
  // requires keys and compares them with "const" (a default that only one choice has: the FEM
  // soil's boundary.pml); nullptr for no if, or one this reader cannot decide.
  const nlohmann::json* branch_taken(const nlohmann::json& node) const {
    const auto test = node.find("if");
    if (test == node.end() || !test->is_object()) return nullptr;
    bool holds = true;
    for (const auto& [keyword, value] : test->items()) {
      if (keyword == "required" && value.is_array()) {
        for (const nlohmann::json& k : value)
          holds = holds && k.is_string() && j_.contains(k.get<std::string>());
      } else if (keyword == "properties" && value.is_object()) {
        for (const auto& [k, rule] : value.items()) {
          if (!rule.is_object() || rule.size() != 1 || !rule.contains("const")) return nullptr;
          holds = holds && (!j_.contains(k) || j_.at(k) == rule.at("const"));
        }
      } else {
        return nullptr;
      }
    }
    const auto branch = node.find(holds ? "then" : "else");
    return branch != node.end() ? &*branch : nullptr;
  }

  // `node` with its local "$ref" ("#/definitions/x") followed; nullptr for a broken one.
  const nlohmann::json* resolved(const nlohmann::json& node, int depth) const {
    const auto ref = node.is_object() ? node.find("$ref") : node.end();
    if (depth > kMaxDepth || ref == node.end() || !ref->is_string()) return &node;
    const std::string target = ref->get<std::string>();
    if (target.empty() || target[0] != '#') return nullptr;
    try {
      const nlohmann::json::json_pointer at(target.substr(1));
      return schema_->contains(at) ? resolved(schema_->at(at), depth + 1) : nullptr;
    } catch (const nlohmann::json::exception&) {
      return nullptr;  // not a JSON pointer
    }
  }

  const nlohmann::json* schema_default(const char* key) const {
    if (node_ == nullptr) return nullptr;
    const nlohmann::json* p = declaration_in(*node_, key, 0, [](const nlohmann::json& d) {
      return d.is_object() && d.contains("default");
    });
    return p != nullptr ? &p->at("default") : nullptr;
  }

  nlohmann::json j_;
  std::shared_ptr<const nlohmann::json> schema_;  // the whole document, for local $refs
  const nlohmann::json* node_ = nullptr;          // the schema of j_, inside *schema_
  std::string where_;  // "params/" or "<component>: params/", then the path of nested objects
};

}  // namespace rumble

#endif  // RUMBLE_PARAMS_HPP
